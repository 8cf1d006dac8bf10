//! `getmatrix`, `coor`, `Rvalue`, `multiply`, `Hermite` (with `coor2`,
//! `coor1`, `Rvalue1`), `initM`, `getdistance`, `getpath`, `delete`,
//! `saving1`, `do34`: unit `paper`, OCR lines 2554–2877, §2.4, §3.2.3
//! (b)–(c).

use super::{contour_box, cubic_range, reparam, Distarray, Mh, PaperPair, Sdirection};
use crate::options::Fidelity;
use crate::shapes::sweep::orientation;
use crate::types::{Coeff, ObjectRecord, SweepShape, MAXSEGMENTS};

/// M_h (§2.4.1), the Hermite basis matrix as `initM` fills `M1`: with
/// T = [t³ t² t 1], T·M_h = (2t³−3t²+1, −2t³+3t², t³−2t²+t, t³−t²), the
/// weights of P(0), P(1), P′(0), P′(1).
pub const MH: Mh = [
    [2.0, -2.0, 1.0, 1.0],
    [-3.0, 3.0, -2.0, -1.0],
    [0.0, 0.0, 1.0, 0.0],
    [1.0, 0.0, 0.0, 0.0],
];

/// M_hᵀ, as `initM` fills `M2`.
pub const MH_T: Mh = [
    [2.0, -3.0, 0.0, 1.0],
    [-2.0, 3.0, 0.0, 0.0],
    [1.0, -2.0, 1.0, 0.0],
    [1.0, -1.0, 0.0, 0.0],
];

/// `getmatrix(p00, p10, p01, p11, path1, path2: coeff; var H: Mh)` (unit
/// `paper`, §2.4.2, §3.2.3 (b), Fig. 3.5, OCR lines 2554–2580): "get the
/// matrix of Hermite Patch" H = M_h·G·M_hᵀ, so that
/// x(s, t) = [s³ s² s 1]·H·[t³ t² t 1]ᵀ ([`patch`]).
///
/// The geometry G: the corners P00 = `coor(p00)` (s = 0, t = 0), P01
/// (s = 0, t = 1), P10 (s = 1, t = 0), P11; the t-tangents from the paths
/// of the two start points, `Rvalue(path1, 0)`, `Rvalue(path1, 1)`,
/// `Rvalue(path2, 0)`, `Rvalue(path2, 1)`; the s-tangents of the four
/// curves at their `first`, `Rvalue(p, p.first)`; the twists 0
/// (§3.2.3 (d)). Returns H (the listing's `var H`). Erratum 18 is in what
/// `goahead` passes.
pub fn getmatrix(p00: &Coeff, p10: &Coeff, p01: &Coeff, p11: &Coeff, path1: &Coeff, path2: &Coeff) -> Mh {
    let mut h: Mh = [[0.0; 4]; 4];
    h[0][0] = coor(p00);
    h[0][1] = coor(p01);
    h[1][0] = coor(p10);
    h[1][1] = coor(p11);
    h[0][2] = Rvalue(path1, 0.0);
    h[0][3] = Rvalue(path1, 1.0);
    h[1][2] = Rvalue(path2, 0.0);
    h[1][3] = Rvalue(path2, 1.0);
    h[2][0] = Rvalue(p00, p00.first);
    h[3][0] = Rvalue(p10, p10.first);
    h[2][1] = Rvalue(p01, p01.first);
    h[3][1] = Rvalue(p11, p11.first);
    // H[3,3], H[3,4], H[4,3], H[4,4] := 0: no twist.
    let (m1, m2) = initM();
    let h = multiply(&m1, &h);
    multiply(&h, &m2)
}

/// `coor(p: coeff): real` (unit `paper`, OCR lines 2582–2586): the point
/// of the segment at its `first`, `d + first*(c + first*(b + a*first))`.
pub fn coor(p: &Coeff) -> f64 {
    p.d + p.first * (p.c + p.first * (p.b + p.a * p.first))
}

/// `Rvalue(p: coeff; t: real): real` (unit `paper`, OCR lines 2588–2592):
/// the derivative dx/dt = `c + t*(2*b + t*3*a)`.
#[allow(non_snake_case)]
pub fn Rvalue(p: &Coeff, t: f64) -> f64 {
    p.c + t * (2.0 * p.b + t * 3.0 * p.a)
}

/// `multiply(m1, m2: Mh): Mh` (unit `paper`, OCR lines 2594–2602): the
/// matrix product m1·m2.
pub fn multiply(m1: &Mh, m2: &Mh) -> Mh {
    let mut k: Mh = [[0.0; 4]; 4];
    for (i, row) in k.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = m1[i][0] * m2[0][j] + m1[i][1] * m2[1][j] + m1[i][2] * m2[2][j] + m1[i][3] * m2[3][j];
        }
    }
    k
}

/// x(s, t) = [s³ s² s 1]·H·[t³ t² t 1]ᵀ: the patch of `getmatrix` (the
/// functions x(s, t), y(s, t) of §3.2.3 (b), a₁₁ s³t³ + … + a₄₄).
pub fn patch(h: &Mh, s: f64, t: f64) -> f64 {
    let sv = [s * s * s, s * s, s, 1.0];
    let tv = [t * t * t, t * t, t, 1.0];
    let mut x = 0.0;
    for (i, row) in h.iter().enumerate() {
        for (j, hij) in row.iter().enumerate() {
            x += sv[i] * hij * tv[j];
        }
    }
    x
}

/// `coor2(u: coeff; co: real): real` (nested in `Hermite`, OCR lines
/// 2613–2621): the point at t = `(first + last)*co`. Only the listing's
/// commented-out debug output calls it.
pub fn coor2(u: &Coeff, co: f64) -> f64 {
    let t = (u.first + u.last) * co;
    u.d + t * (u.c + t * (u.b + u.a * t))
}

/// `coor1(u: coeff): real` (nested in `Hermite`, OCR lines 2623–2627): the
/// point at `last`. Only the commented-out debug output calls it.
pub fn coor1(u: &Coeff) -> f64 {
    u.d + u.last * (u.c + u.last * (u.b + u.a * u.last))
}

/// `Rvalue1(p: coeff; t: real): real` (nested in `Hermite`, OCR lines
/// 2629–2633): the second derivative `2*b + t*6*a`. Not called.
#[allow(non_snake_case)]
pub fn Rvalue1(p: &Coeff, t: f64) -> f64 {
    2.0 * p.b + t * 6.0 * p.a
}

/// Give `obj` the in-between's frame and `snu` segments, reusing its
/// vectors (no allocation once their capacity is 60, [`PaperPair::scratch`]).
fn prepare(int: &PaperPair, obj: &mut SweepShape) -> usize {
    // `snu` ≤ 60 for every pair `goahead` builds; a hand-made one is clamped.
    let snu = int.snu.min(MAXSEGMENTS);
    let f = &int.first_shape;
    obj.orientt = f.orientt;
    obj.curve = f.curve;
    obj.length = f.length;
    obj.scale = f.scale;
    obj.segment = snu;
    // Hermite and do34 write every one of the snu segments, so what the
    // vectors held before need not be cleared (no memset an in-between).
    obj.u.resize(snu, Coeff::default());
    obj.v.resize(snu, Coeff::default());
    snu
}

/// The box of a contour from its segments' `min`, `max`.
fn segments_box(int: &PaperPair, obj: &SweepShape) -> crate::types::BoundingBox {
    let range = |p: &[Coeff]| {
        p.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
            (lo.min(c.min), hi.max(c.max))
        })
    };
    contour_box(int.class, &int.first_shape, range(&obj.u), range(&obj.v))
}

/// `Hermite(int; t: real; var obj)` (unit `paper`, §3.2.3 (c), Fig. 3.9,
/// 3.10, OCR lines 2604–2687): "calculate the in-between figure of every
/// segment of obj" at time `t`: segment i is the patch `Hmx[int,i]`,
/// `Hmy[int,i]` at t, a cubic in s on [0, 1] (`u[i].a` the s³ coefficient
/// `H[1,1]·t³ + H[1,2]·t² + H[1,3]·t + H[1,4]`, …). Erratum 9.
///
/// `int` is the pair's state (the Pascal's index into the globals); `obj`
/// is caller-owned scratch ([`PaperPair::scratch`]): it ends with
/// `segment` = `snu`, `u`, `v` and `bbox` for the sweep intersection, and
/// FIRST's `orientt`, `curve`, `length`, `scale` (`points` are left as
/// they are: the in-between has none).
///
/// Erratum 9 (`Hermite`'s part): the listing bounds segment i by the merged
/// bounds of the key shapes widened by 2, `u[i].max := p1u[int][i].max+2`,
/// which fails when the in-between bulges farther (a fast motion: the path
/// tangents are the motion); the object box is `goahead`'s `tbox`.
/// `Fidelity::Thesis` bounds each segment by its extrema at this t (the
/// "extrema test" of §3.3, [`cubic_range`]) and the box by those bounds.
#[allow(non_snake_case)]
pub fn Hermite(int: &PaperPair, t: f64, obj: &mut SweepShape) {
    let t2 = t * t;
    let t3 = t2 * t;
    let snu = prepare(int, obj);
    let row = |h: &Mh, r: usize| h[r][0] * t3 + h[r][1] * t2 + h[r][2] * t + h[r][3];
    for i in 1..=snu {
        let (hx, hy) = (&int.hmx[i], &int.hmy[i]);
        let mut u = Coeff {
            a: row(hx, 0),
            b: row(hx, 1),
            c: row(hx, 2),
            d: row(hx, 3),
            first: 0.0,
            last: 1.0,
            max: 0.0,
            min: 0.0,
        };
        let mut v = Coeff {
            a: row(hy, 0),
            b: row(hy, 1),
            c: row(hy, 2),
            d: row(hy, 3),
            ..u
        };
        match int.fidelity {
            // Erratum 9, listing: u[i].max := p1u[int][i].max+2;
            // u[i].min := p1u[int][i].min-2; v likewise.
            Fidelity::Listing => {
                u.max = int.p1u[i].max + 2.0;
                u.min = int.p1u[i].min - 2.0;
                v.max = int.p1v[i].max + 2.0;
                v.min = int.p1v[i].min - 2.0;
            }
            // Thesis: the segment's own extrema at t.
            Fidelity::Thesis => {
                (u.min, u.max) = cubic_range(&u);
                (v.min, v.max) = cubic_range(&v);
            }
        }
        obj.u[i - 1] = u;
        obj.v[i - 1] = v;
    }
    obj.bbox = match int.fidelity {
        Fidelity::Listing => int.bbox,
        Fidelity::Thesis => segments_box(int, obj),
    };
    obj.orientation = orientation(&obj.u, &obj.v);
}

/// `initM` (unit `paper`, §2.4.1, OCR lines 2689–2743): "initialize the
/// value of Mh and transpose(Mh)": returns (`M1`, `M2`) = (M_h, M_hᵀ),
/// the listing's globals, element by element as printed.
#[allow(non_snake_case)]
pub fn initM() -> (Mh, Mh) {
    let mut m1: Mh = [[0.0; 4]; 4];
    let mut m2: Mh = [[0.0; 4]; 4];
    m1[0] = [2.0, -2.0, 1.0, 1.0];
    m1[1] = [-3.0, 3.0, -2.0, -1.0];
    m1[2] = [0.0, 0.0, 1.0, 0.0];
    m1[3] = [1.0, 0.0, 0.0, 0.0];
    m2[0] = [2.0, -3.0, 0.0, 1.0];
    m2[1] = [-2.0, 3.0, 0.0, 0.0];
    m2[2] = [1.0, -2.0, 1.0, 0.0];
    m2[3] = [1.0, -1.0, 0.0, 0.0];
    (m1, m2)
}

/// `getdistance(u, v: sdirection; nu; var dist: distarray)` (unit
/// `paper`, §3.2.3 (a), OCR lines 2745–2790): the share of the contour's
/// length at the start of every segment. The length is measured along the
/// chords between consecutive segment start points `(coor(u[i]),
/// coor(v[i]))`, the last chord from segment nu's start back to segment
/// 1's; `dist[i]` is the share up to the start of segment i + 1, `dist[0]
/// = 0`, `dist[nu] = 1`. Erratum 10.
///
/// Erratum 10 (`getdistance`'s part): §3.2.3 prints `dist2[i] :=
/// (distance(p[i-1],p[i]) + dist1[i-1])/length(curve2)`, adding the
/// *first* curve's share to the second's (and dividing the running sum at
/// every step); the listing accumulates each curve's own chords and
/// divides once. Both fidelities follow the listing: the text's line is a
/// misprint that would make the second curve's shares depend on the first.
///
/// `nu` is clamped to 60; a contour whose chords all have length 0 gives
/// NaN shares, as the Pascal would (`goahead` refuses such a contour).
pub fn getdistance(u: &Sdirection, v: &Sdirection, nu: usize, dist: &mut Distarray) {
    let nu = nu.min(MAXSEGMENTS);
    dist[0] = 0.0;
    if nu == 0 {
        return;
    }
    let mut u2 = coor(&u[1]);
    let mut v2 = coor(&v[1]);
    let mut u1 = coor(&u[nu]);
    let mut v1 = coor(&v[nu]);
    let mut sum = ((u2 - u1) * (u2 - u1) + (v2 - v1) * (v2 - v1)).sqrt();
    dist[nu] = sum;
    for i in 2..=nu {
        u2 = coor(&u[i]);
        u1 = coor(&u[i - 1]);
        v2 = coor(&v[i]);
        v1 = coor(&v[i - 1]);
        dist[i - 1] = ((u2 - u1) * (u2 - u1) + (v2 - v1) * (v2 - v1)).sqrt();
        sum += dist[i - 1];
    }
    dist[0] = 0.0;
    for i in 1..=nu {
        dist[i] = dist[i] / sum + dist[i - 1];
    }
}

/// `getpath(n1, n2; H: Mh; dist: distarray; var path: sdirection)` (unit
/// `paper`, §3.2.3 (b), Fig. 3.8, OCR lines 2792–2828): "get the motion
/// path of every starting point of segment" n1 + 1 … n2 − 1 from the
/// large patch H: with s = `dist[i-1] - dist[n1-1]` (the start's share of
/// the contour's length from segment n1's start), `path[i]` is x(s, t) as
/// a cubic in t: `path[i].a := s³·H[1,1] + s²·H[2,1] + s·H[3,1] + H[4,1]`,
/// and `b`, `c`, `d` from the columns 2, 3, 4. Indices past 60 are not
/// visited.
pub fn getpath(n1: usize, n2: usize, h: &Mh, dist: &Distarray, path: &mut Sdirection) {
    if n1 == 0 {
        return;
    }
    for i in n1.saturating_add(1)..=n2.saturating_sub(1).min(MAXSEGMENTS) {
        let s1 = dist[i - 1] - dist[n1 - 1];
        let s2 = s1 * s1;
        let s3 = s2 * s1;
        path[i].a = s3 * h[0][0] + s2 * h[1][0] + s1 * h[2][0] + h[3][0];
        path[i].b = s3 * h[0][1] + s2 * h[1][1] + s1 * h[2][1] + h[3][1];
        path[i].c = s3 * h[0][2] + s2 * h[1][2] + s1 * h[2][2] + h[3][2];
        path[i].d = s3 * h[0][3] + s2 * h[1][3] + s1 * h[2][3] + h[3][3];
    }
}

/// `delete(name: string)` (unit `paper`, OCR lines 2830–2843): takes the
/// object `name` out of the table, closing the gap; `None` where the
/// listing prints `no object by that name exists`. The port's `goahead`
/// does not call it: the deck reader already keeps the later key shapes
/// out of `Scene::objects` (in `KeyframeRecord::rest`).
pub fn delete(name: &str, table: &mut Vec<ObjectRecord>) -> Option<ObjectRecord> {
    let i = table.iter().position(|o| o.name == name)?;
    Some(table.remove(i))
}

/// `saving1(n; u, v: sdirection; var uu, vv: sdirection)` (unit `paper`,
/// OCR lines 2845–2856): "backup the equations of curve": `uu[i] := u[i]`,
/// `vv[i] := v[i]` for i = 1 … n (clamped to 60).
pub fn saving1(n: usize, u: &Sdirection, v: &Sdirection, uu: &mut Sdirection, vv: &mut Sdirection) {
    for i in 1..=n.min(MAXSEGMENTS) {
        uu[i] = u[i];
        vv[i] = v[i];
    }
}

/// `do34(time: real; int; var obj)` (unit `paper`, OCR lines 2858–2877):
/// "if time = 0 then the in-between figure is the curve of object1":
/// `u[i] := p3u[int][i]` when `time = 0`, else LAST's `p4u[int][i]`, the
/// key shapes after expanding, with their merged bounds.
///
/// The expanded key shapes have pieces of segments (`first`, `last` inside
/// [0, 1]). `Fidelity::Listing` copies each record as it stands, as the
/// listing does; `Fidelity::Thesis` writes each piece as the same curve on
/// [0, 1] ([`reparam`], DEVIATIONS D15), the form the port's sweep
/// intersection takes (`PaperChain::inbetween` hands it the listing's
/// pieces the same way). `obj` as in [`Hermite`]; the box is `goahead`'s
/// in `Fidelity::Listing`, from the segments' bounds in `Fidelity::Thesis`
/// (erratum 9).
pub fn do34(time: f64, int: &PaperPair, obj: &mut SweepShape) {
    let snu = prepare(int, obj);
    for i in 1..=snu {
        let (u, v) = if time == 0.0 {
            (&int.p3u[i], &int.p3v[i])
        } else {
            (&int.p4u[i], &int.p4v[i])
        };
        (obj.u[i - 1], obj.v[i - 1]) = match int.fidelity {
            // Listing: u[i] := p3u[int][i] (or p4u), a, b, c, d, first,
            // last as stored.
            Fidelity::Listing => (*u, *v),
            // D15: the same curve on [0, 1].
            Fidelity::Thesis => (reparam(u), reparam(v)),
        };
    }
    obj.bbox = match int.fidelity {
        Fidelity::Listing => int.bbox,
        Fidelity::Thesis => segments_box(int, obj),
    };
    obj.orientation = orientation(&obj.u, &obj.v);
}

/// The in-between contour of pair `int` at `time`, as the `paper = 1`
/// branch of `motionblur` (unit `drt`, OCR lines 2177–2183) chooses it:
/// `if (time=0) or (time=1) then do34(time,int,object) else
/// Hermite(int,time,object)`.
pub fn inbetween(int: &PaperPair, time: f64, obj: &mut SweepShape) {
    if time == 0.0 || time == 1.0 {
        do34(time, int, obj);
    } else {
        Hermite(int, time, obj);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(a: f64, b: f64, cc: f64, d: f64) -> Coeff {
        Coeff {
            a,
            b,
            c: cc,
            d,
            max: 0.0,
            min: 0.0,
            first: 0.0,
            last: 1.0,
        }
    }

    #[test]
    fn coor_rvalue_and_the_nested_functions() {
        // x(t) = t³ + 2t² + 3t + 4.
        let mut p = c(1.0, 2.0, 3.0, 4.0);
        assert_eq!(coor(&p), 4.0);
        assert_eq!(coor1(&p), 10.0);
        assert_eq!(Rvalue(&p, 0.0), 3.0);
        assert_eq!(Rvalue(&p, 1.0), 3.0 + 4.0 + 3.0);
        assert_eq!(Rvalue1(&p, 0.0), 4.0);
        assert_eq!(Rvalue1(&p, 1.0), 10.0);
        // coor2 reads t = (first + last)·co: 0.5 → x(0.5) = 0.125+0.5+1.5+4.
        assert_eq!(coor2(&p, 0.5), 6.125);
        p.first = 0.5;
        p.last = 1.5;
        assert_eq!(coor(&p), 6.125);
        assert_eq!(coor2(&p, 0.5), 10.0);
        assert_eq!(coor1(&p), 1.5f64.powi(3) + 2.0 * 2.25 + 4.5 + 4.0);
    }

    #[test]
    fn getpath_reads_the_patch_at_the_share() {
        // A patch x(s, t) = s·t: only the s·t coefficient H[3,3].
        let mut h = [[0.0; 4]; 4];
        h[2][2] = 1.0;
        let mut dist = [0.0; MAXSEGMENTS + 1];
        dist[..5].copy_from_slice(&[0.0, 0.25, 0.5, 0.75, 1.0]);
        let mut path = Sdirection::default();
        getpath(1, 4, &h, &dist, &mut path);
        // Segments 2 and 3: s = dist[1], dist[2]; path(t) = s·t.
        assert_eq!((path[2].c, path[3].c), (0.25, 0.5));
        assert_eq!(path[4], Coeff::default());
        assert_eq!(path[1], Coeff::default());
        // From segment 3: s measured from dist[2].
        getpath(3, 5, &h, &dist, &mut path);
        assert_eq!(path[4].c, 0.25);
        // Out-of-range counts visit nothing past 60.
        getpath(59, 1000, &h, &dist, &mut path);
        getpath(0, 10, &h, &dist, &mut path);
    }

    #[test]
    fn a_hand_made_pair_past_60_is_clamped() {
        let first = crate::types::SweepShape {
            orientt: crate::types::Axis::Z,
            curve: crate::types::CurveKind::Bspline,
            points: vec![],
            segment: 0,
            u: vec![],
            v: vec![],
            length: 1.0,
            scale: 1.0,
            bbox: Default::default(),
            orientation: 0.0,
        };
        let obj = ObjectRecord {
            name: "x".into(),
            class: crate::types::PrimitiveClass::Translation,
            surface: 0,
            transfm: Default::default(),
            inverse: Default::default(),
            sphereo: Default::default(),
            angle: Default::default(),
            radius: 1.0,
            shape: crate::types::Shape::Sweep(first.clone()),
        };
        let mut pair = PaperPair::empty(1, &obj, &first, crate::scene::Expander::Burtnyk, Fidelity::Thesis);
        pair.snu = 100;
        let mut out = pair.scratch();
        Hermite(&pair, 0.5, &mut out);
        do34(0.0, &pair, &mut out);
        assert_eq!(out.segment, MAXSEGMENTS);
    }
}

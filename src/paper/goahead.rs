//! `expanding`, `more`, `saving`, `merge`, `goahead` (with `difference`):
//! unit `paper`, OCR lines 2270–2552, §3.2.3 (a)–(b), §3.3.

use super::{
    contour_box, coor, expanding2, getdistance, getmatrix, getpath, patch_range, reparam, saving1, PaperError,
    PaperMessage, PaperPair, Sdirection,
};
use crate::options::Fidelity;
use crate::scene::{Expander, Scene};
use crate::types::{Coeff, DVec3, ObjectRecord, PrimitiveClass, Shape, SweepShape, MAXSEGMENTS};

/// What a count of Burtnyk's rule counts (erratum 10).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outline {
    /// The rule as §3.2.3 prints it (after Burtnyk & Wein 1971, who
    /// matched polygons): NS is a number of points of an open polygon, so
    /// there are NS − 1 edges: RT := (NS1−1) div (NS2−1), RS := (NS1−1) mod
    /// (NS2−1).
    Open,
    /// The rule as `expanding` computes it: NS is the number of segments of
    /// a closed curve: RT := NS1 div NS2, RS := NS1 mod NS2.
    Closed,
}

/// Burtnyk's numbers (§3.2.3 (a)) for figures of `ns1` and `ns2`: (RT, RS)
/// with the larger count as NS1 ("the algorithm is the same with NS1 and
/// NS2 interchanged"). "RT points are added to the first RS segments, and
/// the (RT−1) to the others." `None` when the smaller count leaves nothing
/// to divide by (0 segments, or an open polygon of 1 point).
///
/// Erratum 10: the text's rule counts the points of open polygons; for the
/// closed contours of sweep objects it does not give equal counts (10 and
/// 4 segments: RT = 3, RS = 0 adds 2 points to each of the 4 segments,
/// giving 12). `expanding` uses [`Outline::Closed`] in both fidelities.
pub fn burtnyk(ns1: usize, ns2: usize, outline: Outline) -> Option<(usize, usize)> {
    let (big, small) = if ns1 >= ns2 { (ns1, ns2) } else { (ns2, ns1) };
    let (big, small) = match outline {
        Outline::Open => (big.checked_sub(1)?, small.checked_sub(1)?),
        Outline::Closed => (big, small),
    };
    if small == 0 {
        return None;
    }
    Some((big / small, big % small))
}

/// `expanding(int; var obj1, obj2)` (unit `paper`, §3.2.3 (a), OCR lines
/// 2270–2306; ref. Burtnyk & Wein 1971): makes the segment counts of the
/// two key shapes equal by `more` on the one with fewer segments, saving
/// both contours into `p1u`, `p1v` (FIRST) and `p2u`, `p2v` (LAST) of the
/// pair `int`. Errata 8, 10.
///
/// `div1 := NS_big div NS_small; mod1 := NS_big mod NS_small` (the closed
/// count of [`burtnyk`]): `more` splits the first `mod1` segments into
/// `div1 + 1` pieces and the others into `div1`, so the counts always end
/// equal. The listing still checks, printing `***** error *****` or
/// `equal`; `obj1`, `obj2` are the port's working copies (their `segment`
/// changes as the Pascal's did).
pub fn expanding(int: &mut PaperPair, obj1: &mut SweepShape, obj2: &mut SweepShape) -> Result<(), PaperError> {
    if obj1.segment < obj2.segment {
        let (div1, mod1) = burtnyk(obj2.segment, obj1.segment, Outline::Closed).unwrap_or((1, 0));
        more(obj1, div1, mod1, &mut int.p1u, &mut int.p1v);
        saving(obj2, &mut int.p2u, &mut int.p2v);
    } else {
        let (div1, mod1) = burtnyk(obj1.segment, obj2.segment, Outline::Closed).unwrap_or((1, 0));
        saving(obj1, &mut int.p1u, &mut int.p1v);
        more(obj2, div1, mod1, &mut int.p2u, &mut int.p2v);
    }
    if obj1.segment != obj2.segment {
        let message = PaperMessage::ExpandingError {
            segment1: obj1.segment,
            segment2: obj2.segment,
        };
        match int.fidelity {
            // Erratum 8, listing: writeln(' ***** error *****'); writeln(
            // obj1^.segment, obj2^.segment) and go on.
            Fidelity::Listing => int.messages.push(message),
            // Thesis: the counts must be equal for the patches: stop.
            Fidelity::Thesis => return Err(PaperError::Method { int: int.int, message }),
        }
    } else {
        int.messages.push(PaperMessage::Equal);
    }
    Ok(())
}

/// `more(var obj; div1, mod1; var uu, vv: sdirection)` (unit `paper`,
/// §3.2.3 (a), OCR lines 2308–2375; ref. Burtnyk & Wein 1971): "adding
/// control points to the object whose segment is less". Each of the first
/// `mod1` segments becomes `div1 + 1` copies of itself with `first`, `last`
/// cutting [0, 1] into equal parameter ranges (`div1` points added), each
/// other segment `div1` copies; the copies go to `uu`, `vv` and
/// `obj.segment` becomes their number.
///
/// The pieces cut each segment's `[0, 1]` (the listing's `t := 1/(div1+1)`),
/// which is right for the segments `spline` gives (`first` 0, `last` 1).
/// If the result would pass the 60 entries of `sdirection` (the Pascal
/// would write past the array), or `obj` has fewer coefficients than
/// segments, nothing is written and `obj.segment` stays: the caller's
/// count check reports it.
pub fn more(obj: &mut SweepShape, div1: usize, mod1: usize, uu: &mut Sdirection, vv: &mut Sdirection) {
    let segment = obj.segment;
    let total = segment.checked_mul(div1).and_then(|x| x.checked_add(mod1));
    if total.is_none_or(|n| n > MAXSEGMENTS) || mod1 > segment || segment > obj.u.len().min(obj.v.len()) {
        return;
    }
    // `obj^.u[i]` is `obj.u[i - 1]`: the record's arrays are 0-based here.
    let mut j = 1;
    if mod1 > 0 {
        for i in 1..=mod1 {
            uu[j] = obj.u[i - 1];
            vv[j] = obj.v[i - 1];
            j += 1;
            let mut t = 1.0 / (div1 as f64 + 1.0);
            let t1 = t;
            for _k in 1..=div1 {
                uu[j] = obj.u[i - 1];
                vv[j] = obj.v[i - 1];
                uu[j].first = t;
                vv[j].first = t;
                uu[j - 1].last = t;
                vv[j - 1].last = t;
                t += t1;
                j += 1;
            }
        }
    }
    for i in (mod1 + 1)..=segment {
        uu[j] = obj.u[i - 1];
        vv[j] = obj.v[i - 1];
        j += 1;
        let mut t = 1.0 / div1 as f64;
        let t1 = t;
        for _k in 1..div1 {
            uu[j] = obj.u[i - 1];
            vv[j] = obj.v[i - 1];
            uu[j].first = t;
            vv[j].first = t;
            uu[j - 1].last = t;
            vv[j - 1].last = t;
            t += t1;
            j += 1;
        }
    }
    obj.segment = j - 1;
}

/// `saving(obj; var uu, vv: sdirection)` (unit `paper`, OCR lines
/// 2377–2393): "backup the equations of curve of obj": `uu[i] := u[i]`,
/// `vv[i] := v[i]` for every segment (at most 60, and no more than `obj`
/// has coefficients).
pub fn saving(obj: &SweepShape, uu: &mut Sdirection, vv: &mut Sdirection) {
    let n = obj.segment.min(obj.u.len()).min(obj.v.len()).min(MAXSEGMENTS);
    for i in 1..=n {
        uu[i] = obj.u[i - 1];
        vv[i] = obj.v[i - 1];
    }
}

/// `merge(var p1, p2: sdirection; nu)` (unit `paper`, §3.3, OCR lines
/// 2395–2411): "merge the bounding box of the corresponding bounding box":
/// segment i of both contours gets the larger `max` and the smaller `min`
/// of the two (Fig. 3.12). `nu` is clamped to 60.
pub fn merge(p1: &mut Sdirection, p2: &mut Sdirection, nu: usize) {
    for i in 1..=nu.min(MAXSEGMENTS) {
        if p1[i].max < p2[i].max {
            p1[i].max = p2[i].max;
        } else {
            p2[i].max = p1[i].max;
        }
        if p1[i].min > p2[i].min {
            p1[i].min = p2[i].min;
        } else {
            p2[i].min = p1[i].min;
        }
    }
}

/// `difference(po1, po2; var dif)` (nested in `goahead`, OCR lines
/// 2419–2424): `dif := po2 − po1`. Erratum 4: the listing writes
/// `dif.y := po2.x - po1.y` and `dif.z := po2.x - po1.z`.
pub fn difference(po1: DVec3, po2: DVec3, dif: &mut DVec3, fidelity: Fidelity) {
    dif.x = po2.x - po1.x;
    match fidelity {
        // Erratum 4, listing: dif.y := po2.x-po1.y; dif.z := po2.x-po1.z.
        Fidelity::Listing => {
            dif.y = po2.x - po1.y;
            dif.z = po2.x - po1.z;
        }
        // Thesis: dif.y := po2.y-po1.y; dif.z := po2.z-po1.z.
        Fidelity::Thesis => {
            dif.y = po2.y - po1.y;
            dif.z = po2.z - po1.z;
        }
    }
}

/// The sweep record of a key shape, checked for what `goahead` reads.
fn key_shape<'a>(int: usize, obj: &'a ObjectRecord, which: &'static str) -> Result<&'a SweepShape, PaperError> {
    let sweep = match (&obj.shape, obj.class) {
        (Shape::Sweep(s), PrimitiveClass::Translation | PrimitiveClass::Conic | PrimitiveClass::Rotation) => s,
        _ => return Err(PaperError::NotSweep { int, which }),
    };
    if sweep.segment < 2 {
        return Err(PaperError::TooFewSegments {
            int,
            which,
            segment: sweep.segment,
        });
    }
    Ok(sweep)
}

/// The checks of a key shape that need the expanded count to be ≤ 60 first.
fn check_contour(int: usize, obj: &ObjectRecord, sweep: &SweepShape, which: &'static str) -> Result<(), PaperError> {
    let n = sweep.segment;
    if sweep.u.len() < n || sweep.v.len() < n {
        return Err(PaperError::NotPrepared {
            int,
            which,
            segment: n,
            coefficients: sweep.u.len().min(sweep.v.len()),
        });
    }
    let finite = |c: &Coeff| {
        [c.a, c.b, c.c, c.d, c.min, c.max, c.first, c.last]
            .iter()
            .all(|x| x.is_finite())
    };
    if !sweep.u[..n].iter().chain(&sweep.v[..n]).all(finite)
        || !obj.sphereo.is_finite()
        || !obj.angle.is_finite()
        || !sweep.length.is_finite()
        || !sweep.scale.is_finite()
    {
        return Err(PaperError::NotFinite { int, which });
    }
    // getdistance divides by the length of the chords between segment
    // start points: all start points in one place would divide by 0.
    let start = |i: usize| (coor(&sweep.u[i]), coor(&sweep.v[i]));
    let p0 = start(0);
    if (1..n).all(|i| start(i) == p0) {
        return Err(PaperError::Degenerate { int, which });
    }
    Ok(())
}

/// The corner curves of segment i's patch at s = 0 and s = 1 for one key
/// shape's contour `p` (`next` the index of the following segment).
///
/// Erratum 18 (the port's reading): the listing
/// passes `p[i]` and `p[next]`; `getmatrix` takes the position and the
/// s-tangent of each at its `first`, so the tangent at s = 1 is segment
/// i + 1's at its start, and both are derivatives by the original
/// segment's parameter even where `more`/`plus` cut it into pieces. Then
/// the patch at t = 0 is not FIRST's contour (nor at t = 1 LAST's) where a
/// segment was cut or where a Bezier contour has a corner, although §3.2.3
/// (1) takes "the first and last pictures as the curves of the Hermite
/// patch at t = 0 and t = 1" (`do34` hides it at exactly 0 and 1).
/// `Fidelity::Thesis` takes both ends of segment i itself, as a cubic on
/// [0, 1] ([`reparam`]): the patch then reproduces the key shapes exactly.
fn corners(p: &Sdirection, i: usize, next: usize, fidelity: Fidelity) -> (Coeff, Coeff) {
    match fidelity {
        // Listing: getmatrix(p1u[int][i], p1u[int][i+1], …).
        Fidelity::Listing => (p[i], p[next]),
        // Thesis: segment i on [0, 1], read at s = 0 (`first` 0) and at
        // s = 1 (`first` 1).
        Fidelity::Thesis => {
            let r = reparam(&p[i]);
            (r, Coeff { first: 1.0, ..r })
        }
    }
}

/// `goahead`'s `tbox.xmax := tbox.xmax+2; tbox.xmin := tbox.xmin-2;`
/// `tbox.ymax := …+2; tbox.ymin := …-2` (OCR lines 2439–2442), for all the
/// key-frame pairs of `scene` at once (erratum 9). The listing widens the
/// one box of the translation class, which every translation sweep uses
/// (`spline`'s class boxes, `prepare_sweeps`), by 2 in x and y once per
/// pair, whatever the pair's class: `Fidelity::Listing` widens the box of
/// every translation sweep of the scene (later key shapes included) by
/// 2·pairs. `Fidelity::Thesis` leaves each box its own (§3.3). Boxes only
/// cull, so a wider box changes which rays are solved, not the hits.
pub fn widen_tbox(scene: &mut Scene, fidelity: Fidelity) {
    let pairs = scene.keyframes.iter().map(|k| k.rest.len()).sum::<usize>() as f64;
    let by = match fidelity {
        // Listing: 2 for every call of goahead.
        Fidelity::Listing => 2.0 * pairs,
        // Thesis: no widening.
        Fidelity::Thesis => return,
    };
    let Scene { objects, keyframes, .. } = scene;
    for obj in objects
        .iter_mut()
        .chain(keyframes.iter_mut().flat_map(|k| k.rest.iter_mut()))
    {
        if let (PrimitiveClass::Translation, Shape::Sweep(sw)) = (obj.class, &mut obj.shape) {
            if sw.segment > 0 && by > 0.0 {
                sw.bbox.xmax += by;
                sw.bbox.xmin -= by;
                sw.bbox.ymax += by;
                sw.bbox.ymin -= by;
            }
        }
    }
}

/// `goahead(int; var obj1, obj2)` (unit `paper`, §3.2.3, §3.3, OCR lines
/// 2413–2552): "to calculate the in-between figure from obj1 and obj2":
/// everything key-frame pair `int` (from 1) needs before the scanline loop.
/// Errata 4, 8, 9, 18.
///
/// The steps, as printed: `initM`; if the counts differ, `expanding`
/// (`expander` Burtnyk) or `expanding2` (Arclength), else `saving` both;
/// widen `tbox` by 2; `difference` of the positions (`diff`) and the
/// angles (`diffangle`); `snu := obj1^.segment; mid := snu div 2`;
/// `merge` the segment bounds; keep copies for `do34` (`saving1`);
/// `getdistance` of both contours; the paths of the start points of
/// segments 1 and `mid`: `pathx[1] := (0, 0, obj2^.sphereo.x −
/// obj1^.sphereo.x, obj1^.sphereo.x)`, and `pathy` likewise with z (the
/// object's straight motion, §3.2.3 (b) (2), U taking x and V z);
/// `getmatrix` and `getpath` for the two large patches 1 → `mid` and
/// `mid` → 1, which give the path of every other segment start (s being
/// the start's share of the whole contour's length, as §3.2.3 (b) says,
/// so the large patch is read for s up to about ½); then one patch per
/// segment, `Hmx[int,i]`, `Hmy[int,i]`; last `delete(obj2^.name)`.
///
/// Here `obj1` (FIRST) and `obj2` (LAST) are not changed: the deck has
/// already moved LAST out of the scene (its `delete`, see [`delete`](super::delete)) and
/// the expanded count is [`PaperPair::snu`].
///
/// Erratum 9 (`goahead`'s part): the listing widens the class box `tbox`
/// by 2 in x and y, whatever the pair's class ([`widen_tbox`] does it on
/// the scene), and the in-between object uses the box of its class.
/// `Fidelity::Listing` gives [`PaperPair::bbox`] as FIRST's box, which in
/// that fidelity is its class's box (`tbox`, `cbox`, `rbox`, as
/// `prepare_sweeps` and [`widen_tbox`] leave it); `Fidelity::Thesis` the
/// union of the key shapes' boxes and of every segment patch's Bernstein
/// control values ([`patch_range`]), which hold the patch for all s, t in
/// [0, 1].
///
/// Errors: not two sweeps of one class; a shape of fewer than 2 segments;
/// more than 60 segments after expanding; `u`, `v` not filled; a number
/// that is not finite; a contour whose segment starts coincide; and in
/// `Fidelity::Thesis` the method's failures (erratum 8).
pub fn goahead(
    int: usize,
    obj1: &ObjectRecord,
    obj2: &ObjectRecord,
    expander: Expander,
    fidelity: Fidelity,
) -> Result<PaperPair, PaperError> {
    let first = key_shape(int, obj1, "FIRST")?;
    let last = key_shape(int, obj2, "LAST")?;
    if obj1.class != obj2.class {
        return Err(PaperError::ClassMismatch {
            int,
            first: obj1.class,
            last: obj2.class,
        });
    }
    // Both expanders end with the larger count (when they succeed).
    let count = first.segment.max(last.segment);
    if count > MAXSEGMENTS {
        return Err(PaperError::TooManySegments { int, count });
    }
    check_contour(int, obj1, first, "FIRST")?;
    check_contour(int, obj2, last, "LAST")?;

    let mut pair = PaperPair::empty(int, obj1, first, expander, fidelity);
    // The working copies whose `segment` the expanders change (the Pascal
    // changed the objects).
    let mut o1 = first.clone();
    let mut o2 = last.clone();

    // initM: the port's getmatrix reads the constants MH, MH_T.
    if o1.segment != o2.segment {
        match expander {
            Expander::Burtnyk => expanding(&mut pair, &mut o1, &mut o2)?,
            Expander::Arclength => expanding2(&mut pair, &mut o1, &mut o2)?,
        }
    } else {
        saving(&o1, &mut pair.p1u, &mut pair.p1v);
        saving(&o2, &mut pair.p2u, &mut pair.p2v);
    }

    // tbox widening (erratum 9): in the box below.

    difference(obj1.sphereo, obj2.sphereo, &mut pair.diff, fidelity);
    difference(obj1.angle, obj2.angle, &mut pair.diffangle, fidelity);

    // snu ≤ 60: `more` and `more2` write no more than 60 entries, and
    // `expanding2` sets obj1^.segment to the other count (≤ 60).
    let snu = o1.segment.clamp(2, MAXSEGMENTS);
    let mid = snu / 2;
    pair.snu = snu;
    pair.mid = mid;

    merge(&mut pair.p1u, &mut pair.p2u, snu);
    merge(&mut pair.p1v, &mut pair.p2v, snu);
    // saving1 copies from and to the same pair's arrays: copy the sources.
    let (p1u, p1v, p2u, p2v) = (pair.p1u, pair.p1v, pair.p2u, pair.p2v);
    saving1(snu, &p1u, &p1v, &mut pair.p3u, &mut pair.p3v);
    saving1(snu, &p2u, &p2v, &mut pair.p4u, &mut pair.p4v);

    getdistance(&p1u, &p1v, snu, &mut pair.dist1);
    getdistance(&p2u, &p2v, snu, &mut pair.dist2);

    pair.pathx[1] = Coeff {
        a: 0.0,
        b: 0.0,
        c: obj2.sphereo.x - obj1.sphereo.x,
        d: obj1.sphereo.x,
        ..Coeff::default()
    };
    pair.pathx[mid] = pair.pathx[1];
    pair.pathy[1] = Coeff {
        a: 0.0,
        b: 0.0,
        c: obj2.sphereo.z - obj1.sphereo.z,
        d: obj1.sphereo.z,
        ..Coeff::default()
    };
    pair.pathy[mid] = pair.pathy[1];

    let hu = getmatrix(&p1u[1], &p1u[mid], &p2u[1], &p2u[mid], &pair.pathx[1], &pair.pathx[mid]);
    let hv = getmatrix(&p1v[1], &p1v[mid], &p2v[1], &p2v[mid], &pair.pathy[1], &pair.pathy[mid]);
    getpath(1, mid, &hu, &pair.dist1, &mut pair.pathx);
    getpath(1, mid, &hv, &pair.dist1, &mut pair.pathy);

    let hu = getmatrix(&p1u[mid], &p1u[1], &p2u[mid], &p2u[1], &pair.pathx[mid], &pair.pathx[1]);
    let hv = getmatrix(&p1v[mid], &p1v[1], &p2v[mid], &p2v[1], &pair.pathy[mid], &pair.pathy[1]);
    getpath(mid, snu + 1, &hu, &pair.dist1, &mut pair.pathx);
    getpath(mid, snu + 1, &hv, &pair.dist1, &mut pair.pathy);

    for i in 1..snu {
        let ((u00, u10), (u01, u11)) = (corners(&p1u, i, i + 1, fidelity), corners(&p2u, i, i + 1, fidelity));
        let ((v00, v10), (v01, v11)) = (corners(&p1v, i, i + 1, fidelity), corners(&p2v, i, i + 1, fidelity));
        pair.hmx[i] = getmatrix(&u00, &u10, &u01, &u11, &pair.pathx[i], &pair.pathx[i + 1]);
        pair.hmy[i] = getmatrix(&v00, &v10, &v01, &v11, &pair.pathy[i], &pair.pathy[i + 1]);
    }
    let i = snu;
    let ((u00, u10), (u01, u11)) = (corners(&p1u, i, 1, fidelity), corners(&p2u, i, 1, fidelity));
    let ((v00, v10), (v01, v11)) = (corners(&p1v, i, 1, fidelity), corners(&p2v, i, 1, fidelity));
    pair.hmx[i] = getmatrix(&u00, &u10, &u01, &u11, &pair.pathx[i], &pair.pathx[1]);
    pair.hmy[i] = getmatrix(&v00, &v10, &v01, &v11, &pair.pathy[i], &pair.pathy[1]);

    // The merged box of the two key shapes (Fig. 3.11, 3.12): the merged
    // segment bounds hold both contours.
    let range = |p: &Sdirection| {
        (1..=snu).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), i| {
            (lo.min(p[i].min), hi.max(p[i].max))
        })
    };
    let merged = contour_box(obj1.class, first, range(&pair.p1u), range(&pair.p1v));
    pair.bbox = match fidelity {
        // Erratum 9, listing: the box of the class, `tbox` widened by
        // `tbox.xmax := tbox.xmax+2; …` once per pair (widen_tbox).
        Fidelity::Listing => first.bbox,
        // Thesis (§3.3: the merged box, adjusted by the extrema of the
        // in-between curves): every patch's control net holds it for all t.
        Fidelity::Thesis => {
            let (mut u, mut v) = (range(&pair.p1u), range(&pair.p1v));
            for i in 1..=snu {
                let (ulo, uhi) = patch_range(&pair.hmx[i]);
                let (vlo, vhi) = patch_range(&pair.hmy[i]);
                u = (u.0.min(ulo), u.1.max(uhi));
                v = (v.0.min(vlo), v.1.max(vhi));
            }
            merged.union(&contour_box(obj1.class, first, u, v))
        }
    };

    // delete(obj2^.name): the deck keeps LAST out of the scene already.
    Ok(pair)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::BoundingBox;

    fn seg(a: f64) -> Coeff {
        Coeff {
            a,
            b: 2.0 * a,
            c: 3.0,
            d: 4.0,
            max: a + 1.0,
            min: a - 1.0,
            first: 0.0,
            last: 1.0,
        }
    }

    fn shape(n: usize) -> SweepShape {
        SweepShape {
            orientt: crate::types::Axis::Z,
            curve: crate::types::CurveKind::Bspline,
            points: vec![],
            segment: n,
            u: (0..n).map(|i| seg(i as f64)).collect(),
            v: (0..n).map(|i| seg(10.0 + i as f64)).collect(),
            length: 1.0,
            scale: 1.0,
            bbox: BoundingBox::default(),
            orientation: 0.0,
        }
    }

    #[test]
    fn more_cuts_the_first_mod1_segments_into_div1_plus_1() {
        // 3 segments to 8: div1 = 2, mod1 = 2.
        let mut obj = shape(3);
        let (mut uu, mut vv) = (Sdirection::default(), Sdirection::default());
        more(&mut obj, 2, 2, &mut uu, &mut vv);
        assert_eq!(obj.segment, 8);
        let firsts: Vec<f64> = (1..=8).map(|j| uu[j].first).collect();
        let lasts: Vec<f64> = (1..=8).map(|j| uu[j].last).collect();
        let third = 1.0 / 3.0;
        assert_eq!(firsts, [0.0, third, 2.0 * third, 0.0, third, 2.0 * third, 0.0, 0.5]);
        assert_eq!(lasts, [third, 2.0 * third, 1.0, third, 2.0 * third, 1.0, 0.5, 1.0]);
        let from: Vec<f64> = (1..=8).map(|j| uu[j].a).collect();
        assert_eq!(from, [0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0]);
        assert_eq!(vv[8].a, 12.0);
    }

    #[test]
    fn more_refuses_to_pass_60() {
        let mut obj = shape(31);
        let (mut uu, mut vv) = (Sdirection::default(), Sdirection::default());
        more(&mut obj, 2, 0, &mut uu, &mut vv);
        assert_eq!(obj.segment, 31);
        assert_eq!(uu[1], Coeff::default());
    }

    #[test]
    fn saving_and_merge() {
        let obj = shape(3);
        let (mut p1, mut v1) = (Sdirection::default(), Sdirection::default());
        saving(&obj, &mut p1, &mut v1);
        assert_eq!(p1[3], obj.u[2]);
        assert_eq!(p1[4], Coeff::default());
        let mut p2 = p1;
        p2[1].max = 5.0;
        p2[1].min = -7.0;
        p1[2].max = 9.0;
        p1[2].min = -9.0;
        merge(&mut p1, &mut p2, 3);
        // Segment 1: p2's bounds are the wider (the `then` branches).
        assert_eq!((p1[1].max, p1[1].min, p2[1].max, p2[1].min), (5.0, -7.0, 5.0, -7.0));
        // Segment 2: p1's are (the `else` branches copy them to p2).
        assert_eq!((p1[2].max, p2[2].max), (9.0, 9.0));
        assert_eq!((p1[2].min, p2[2].min), (-9.0, -9.0));
        // A count past 60 is clamped.
        merge(&mut p1, &mut p2, 1000);
    }

    /// Erratum 8: `expanding` prints `***** error *****` when `more` leaves
    /// the counts different. `more` always ends equal on shapes `spline`
    /// filled; a shape with fewer coefficients than segments is where it
    /// writes nothing, and the check is reached: listing goes on with the
    /// message, thesis stops.
    #[test]
    fn expanding_error_when_the_counts_stay_different() {
        let first = ObjectRecord {
            name: "a".into(),
            class: PrimitiveClass::Translation,
            surface: 0,
            transfm: crate::types::DMat4::IDENTITY,
            inverse: crate::types::DMat4::IDENTITY,
            sphereo: DVec3::ZERO,
            angle: DVec3::ZERO,
            radius: 1.0,
            shape: Shape::Sweep(shape(3)),
        };
        for fidelity in [Fidelity::Listing, Fidelity::Thesis] {
            let mut pair = PaperPair::empty(1, &first, &shape(3), Expander::Burtnyk, fidelity);
            let mut short = shape(3);
            short.u.pop();
            let mut other = shape(5);
            let got = expanding(&mut pair, &mut short, &mut other);
            let message = PaperMessage::ExpandingError {
                segment1: 3,
                segment2: 5,
            };
            match fidelity {
                Fidelity::Listing => {
                    assert_eq!(got, Ok(()));
                    assert_eq!(pair.messages, [message]);
                    assert_eq!(message.to_string(), " ***** error ***** 3 5");
                }
                Fidelity::Thesis => {
                    assert_eq!(got, Err(PaperError::Method { int: 1, message }));
                }
            }
            // Shapes as spline fills them end equal: ` equal `.
            let mut pair = PaperPair::empty(1, &first, &shape(3), Expander::Burtnyk, fidelity);
            assert_eq!(expanding(&mut pair, &mut shape(3), &mut shape(5)), Ok(()));
            assert_eq!(pair.messages, [PaperMessage::Equal]);
        }
    }

    #[test]
    fn burtnyk_rules() {
        assert_eq!(burtnyk(10, 4, Outline::Open), Some((3, 0)));
        assert_eq!(burtnyk(4, 10, Outline::Open), Some((3, 0)));
        assert_eq!(burtnyk(9, 4, Outline::Open), Some((2, 2)));
        assert_eq!(burtnyk(10, 4, Outline::Closed), Some((2, 2)));
        assert_eq!(burtnyk(5, 1, Outline::Open), None);
        assert_eq!(burtnyk(5, 0, Outline::Closed), None);
    }
}

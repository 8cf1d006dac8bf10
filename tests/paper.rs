//! Unit `paper` (§3.1–3.3): the Hermite matrices, the expanders, the
//! in-between contours, the poses and the boxes of key-frame pairs, in both
//! fidelities (errata 4, 8, 9, 10, 18, 19).

mod common;

use raytrace::options::*;
use raytrace::paper::*;
use raytrace::proc::sweep::spline;
use raytrace::scene::*;
use raytrace::shapes::sweep::Sweep;
use raytrace::types::*;

// ---------------------------------------------------------------- fixtures

/// A sweep with `u`, `v`, `segment`, `bbox` filled by `spline` (unit
/// `proc`) as the sweep module fills them (B-spline: segment i uses points
/// i..i+3 wrapping; Bezier: P[3i..3i+3 mod 3k]), 2 long.
fn sweep(points: &[[f64; 2]], curve: CurveKind) -> SweepShape {
    let n = points.len();
    let segment = match curve {
        CurveKind::Bspline => n,
        CurveKind::Bezier => n / 3,
    };
    let at = |i: usize, k: usize| match curve {
        CurveKind::Bspline => points[(i + k) % n],
        CurveKind::Bezier => points[(3 * i + k) % (3 * segment)],
    };
    let mut bbox = BoundingBox {
        xmin: f64::INFINITY,
        xmax: f64::NEG_INFINITY,
        ymin: f64::INFINITY,
        ymax: f64::NEG_INFINITY,
        zmin: 0.0,
        zmax: 2.0,
    };
    let (mut u, mut v) = (Vec::new(), Vec::new());
    let class = PrimitiveClass::Translation;
    for i in 0..segment {
        let p = [0, 1, 2, 3].map(|k| at(i, k));
        let (mut cu, mut cv) = (Coeff::default(), Coeff::default());
        spline(curve, p[0][0], p[1][0], p[2][0], p[3][0], &mut cu, class, 1, &mut bbox);
        spline(curve, p[0][1], p[1][1], p[2][1], p[3][1], &mut cv, class, 2, &mut bbox);
        u.push(cu);
        v.push(cv);
    }
    SweepShape {
        orientt: Axis::Z,
        curve,
        points: points.to_vec(),
        segment,
        u,
        v,
        length: 2.0,
        scale: 1.0,
        bbox,
        orientation: 0.0,
    }
}

/// A key shape at `at`, turned `turn_z` degrees about z.
fn key(name: &str, class: PrimitiveClass, at: [f64; 3], turn_z: f64, shape: SweepShape) -> ObjectRecord {
    let sphereo = DVec3::from_array(at);
    let r = DMat4::from_rotation_z(turn_z.to_radians());
    ObjectRecord {
        name: name.into(),
        class,
        surface: 0,
        transfm: DMat4::from_translation(sphereo) * r,
        inverse: r.transpose() * DMat4::from_translation(-sphereo),
        sphereo,
        angle: DVec3::new(0.0, 0.0, turn_z),
        radius: 10.0,
        shape: Shape::Sweep(shape),
    }
}

fn translation(name: &str, at: [f64; 3], shape: SweepShape) -> ObjectRecord {
    key(name, PrimitiveClass::Translation, at, 0.0, shape)
}

/// A closed B-spline contour of `n` points about (cx, 0), its radius
/// wobbling with `seed` so that the chords differ.
fn wobbly(n: usize, seed: f64, cx: f64) -> SweepShape {
    let pts: Vec<[f64; 2]> = (0..n)
        .map(|k| {
            let th = std::f64::consts::TAU * k as f64 / n as f64;
            let r = 3.0 + 0.8 * (seed + 2.3 * k as f64).sin();
            [cx + r * th.cos(), r * th.sin()]
        })
        .collect();
    sweep(&pts, CurveKind::Bspline)
}

/// A closed Bezier polygon through `corners` with straight sides.
fn bezier_polygon(corners: &[[f64; 2]]) -> SweepShape {
    let mut pts = Vec::new();
    for i in 0..corners.len() {
        let (p, q) = (corners[i], corners[(i + 1) % corners.len()]);
        for k in 0..3 {
            let f = k as f64 / 3.0;
            pts.push([p[0] + (q[0] - p[0]) * f, p[1] + (q[1] - p[1]) * f]);
        }
    }
    sweep(&pts, CurveKind::Bezier)
}

/// A Bezier contour with bulging sides and corners between them.
fn bezier_flower(n: usize, r: f64) -> SweepShape {
    let mut pts = Vec::new();
    for i in 0..n {
        let th = std::f64::consts::TAU * i as f64 / n as f64;
        let th2 = std::f64::consts::TAU * (i as f64 + 1.0) / n as f64;
        let (p, q) = ([r * th.cos(), r * th.sin()], [r * th2.cos(), r * th2.sin()]);
        let mid = (th + th2) / 2.0;
        let bulge = [1.6 * r * mid.cos(), 1.6 * r * mid.sin()];
        pts.push(p);
        pts.push([(2.0 * bulge[0] + p[0]) / 3.0, (2.0 * bulge[1] + p[1]) / 3.0]);
        pts.push([(2.0 * bulge[0] + q[0]) / 3.0, (2.0 * bulge[1] + q[1]) / 3.0]);
    }
    sweep(&pts, CurveKind::Bezier)
}

fn x(c: &Coeff, s: f64) -> f64 {
    ((c.a * s + c.b) * s + c.c) * s + c.d
}

/// d/ds and d/dt of the patch x(s, t) = S·H·Tᵀ.
fn patch_d(h: &Mh, s: f64, t: f64, ds: bool, dt: bool) -> f64 {
    let sv = if ds {
        [3.0 * s * s, 2.0 * s, 1.0, 0.0]
    } else {
        [s * s * s, s * s, s, 1.0]
    };
    let tv = if dt {
        [3.0 * t * t, 2.0 * t, 1.0, 0.0]
    } else {
        [t * t * t, t * t, t, 1.0]
    };
    (0..4)
        .map(|i| (0..4).map(|j| sv[i] * h[i][j] * tv[j]).sum::<f64>())
        .sum()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

/// Is (u, v) of the contour inside the local box of a sweep of `class`?
fn in_box(class: PrimitiveClass, b: &BoundingBox, u: f64, v: f64) -> bool {
    let tol = 1e-9;
    match class {
        PrimitiveClass::Rotation => u.abs() <= b.xmax + tol && v >= b.zmin - tol && v <= b.zmax + tol,
        _ => u >= b.xmin - tol && u <= b.xmax + tol && v >= b.ymin - tol && v <= b.ymax + tol,
    }
}

// ------------------------------------------------------- matrices (§2.4)

#[test]
fn initm_gives_mh_and_its_transpose() {
    let (m1, m2) = initM();
    let mh = [
        [2.0, -2.0, 1.0, 1.0],
        [-3.0, 3.0, -2.0, -1.0],
        [0.0, 0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0, 0.0],
    ];
    assert_eq!(m1, mh);
    assert_eq!(m1, MH);
    assert_eq!(m2, MH_T);
    for i in 0..4 {
        for j in 0..4 {
            assert_eq!(m2[i][j], mh[j][i]);
        }
    }
}

#[test]
fn multiply_against_hand_products() {
    let a = [
        [1.0, 2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 3.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    let b = [
        [1.0, 0.0, 0.0, 0.0],
        [4.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 2.0, 0.0],
        [0.0, 0.0, 5.0, 1.0],
    ];
    assert_eq!(
        multiply(&a, &b),
        [
            [9.0, 2.0, 0.0, 0.0],
            [4.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 17.0, 3.0],
            [0.0, 0.0, 5.0, 1.0]
        ]
    );
    assert_eq!(
        multiply(&b, &a),
        [
            [1.0, 2.0, 0.0, 0.0],
            [4.0, 9.0, 0.0, 0.0],
            [0.0, 0.0, 2.0, 6.0],
            [0.0, 0.0, 5.0, 16.0]
        ]
    );
    // M_h·M_hᵀ: row 1 by itself, 2·2 + 2·2 + 1 + 1 = 10; rows 1 and 2:
    // 2·(−3) + (−2)·3 + 1·(−2) + 1·(−1) = −15.
    let p = multiply(&MH, &MH_T);
    assert_eq!((p[0][0], p[0][1], p[1][0]), (10.0, -15.0, -15.0));
    let id = [
        [1.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.0],
        [0.0, 0.0, 0.0, 1.0],
    ];
    assert_eq!(multiply(&MH, &id), MH);
    assert_eq!(multiply(&id, &MH_T), MH_T);
}

#[test]
fn hermite_basis_at_0_half_1() {
    // T·M_h = (2t³−3t²+1, −2t³+3t², t³−2t²+t, t³−t²) (§2.4.1).
    let basis = |t: f64| {
        let tv = [t * t * t, t * t, t, 1.0];
        let mut b = [0.0; 4];
        for (j, bj) in b.iter_mut().enumerate() {
            *bj = (0..4).map(|i| tv[i] * MH[i][j]).sum();
        }
        b
    };
    assert_eq!(basis(0.0), [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(basis(0.5), [0.5, 0.5, 0.125, -0.125]);
    assert_eq!(basis(1.0), [0.0, 1.0, 0.0, 0.0]);
    for t in [0.0, 0.25, 0.5, 0.8, 1.0] {
        let f = [
            2.0 * t * t * t - 3.0 * t * t + 1.0,
            -2.0 * t * t * t + 3.0 * t * t,
            t * t * t - 2.0 * t * t + t,
            t * t * t - t * t,
        ];
        assert_eq!(basis(t), f);
    }
}

#[test]
fn a_hermite_patch_reproduces_its_corners_and_corner_tangents() {
    let c = |a, b, cc, d, first| Coeff {
        a,
        b,
        c: cc,
        d,
        max: 0.0,
        min: 0.0,
        first,
        last: 1.0,
    };
    let p00 = c(1.0, -2.0, 0.5, 3.0, 0.0);
    let p10 = c(-0.5, 1.0, 2.0, -1.0, 0.25);
    let p01 = c(2.0, 0.0, -1.5, 4.0, 0.5);
    let p11 = c(0.3, 0.7, -0.2, 1.5, 0.0);
    let path1 = c(0.4, -1.0, 2.0, 7.0, 0.0);
    let path2 = c(-0.6, 0.5, 1.0, -3.0, 0.0);
    let h = getmatrix(&p00, &p10, &p01, &p11, &path1, &path2);
    let tol = 1e-12;
    // Corners: P(s, t) at (0,0), (0,1), (1,0), (1,1).
    assert!(close(patch(&h, 0.0, 0.0), coor(&p00), tol));
    assert!(close(patch(&h, 0.0, 1.0), coor(&p01), tol));
    assert!(close(patch(&h, 1.0, 0.0), coor(&p10), tol));
    assert!(close(patch(&h, 1.0, 1.0), coor(&p11), tol));
    // s-tangents: the curves' derivatives at their `first`.
    assert!(close(patch_d(&h, 0.0, 0.0, true, false), Rvalue(&p00, 0.0), tol));
    assert!(close(patch_d(&h, 1.0, 0.0, true, false), Rvalue(&p10, 0.25), tol));
    assert!(close(patch_d(&h, 0.0, 1.0, true, false), Rvalue(&p01, 0.5), tol));
    assert!(close(patch_d(&h, 1.0, 1.0, true, false), Rvalue(&p11, 0.0), tol));
    // t-tangents: the paths' derivatives at t = 0 and 1.
    assert!(close(patch_d(&h, 0.0, 0.0, false, true), Rvalue(&path1, 0.0), tol));
    assert!(close(patch_d(&h, 0.0, 1.0, false, true), Rvalue(&path1, 1.0), tol));
    assert!(close(patch_d(&h, 1.0, 0.0, false, true), Rvalue(&path2, 0.0), tol));
    assert!(close(patch_d(&h, 1.0, 1.0, false, true), Rvalue(&path2, 1.0), tol));
    // Zero twist at the corners.
    for (s, t) in [(0.0, 0.0), (0.0, 1.0), (1.0, 0.0), (1.0, 1.0)] {
        assert!(patch_d(&h, s, t, true, true).abs() < 1e-12);
    }
    // Inside, at (½, ½), with the Hermite basis (½, ½, ⅛, −⅛) on both
    // sides and no twist: ¼ of the corners (3 − 0.4453125 + 3.5 + 1.5),
    // plus 1/16 of the s-tangents (0.5 − 2.40625 + 0 + 0.2) and of the
    // t-tangents (2 − 1.2 + 1 − 0.2): 2409/1280.
    assert!(
        (patch(&h, 0.5, 0.5) - 2409.0 / 1280.0).abs() < 1e-12,
        "{}",
        patch(&h, 0.5, 0.5)
    );
}

// ------------------------------------------------- the key shapes at 0, 1

/// Hermite at t and do34 at the end agree coefficient by coefficient.
fn max_gap(pair: &PaperPair, t: f64, end: f64) -> f64 {
    let (mut a, mut b) = (pair.scratch(), pair.scratch());
    Hermite(pair, t, &mut a);
    do34(end, pair, &mut b);
    // The same curve on [0, 1] (the listing's do34 keeps a piece's `first`,
    // `last`: D15).
    for c in b.u.iter_mut().chain(b.v.iter_mut()) {
        *c = reparam(c);
    }
    assert_eq!(a.segment, b.segment);
    let mut gap = 0.0f64;
    for (p, q) in a.u.iter().zip(&b.u).chain(a.v.iter().zip(&b.v)) {
        for (x, y) in [
            (p.a, q.a),
            (p.b, q.b),
            (p.c, q.c),
            (p.d, q.d),
            (p.first, q.first),
            (p.last, q.last),
        ] {
            gap = gap.max((x - y).abs());
        }
    }
    gap
}

fn end_pairs(fidelity: Fidelity) -> Vec<(&'static str, PaperPair)> {
    let mk = |a: SweepShape, b: SweepShape, e: Expander| {
        goahead(
            1,
            &translation("first", [0.0, 0.0, 0.0], a),
            &translation("last", [5.0, 1.0, -2.0], b),
            e,
            fidelity,
        )
        .unwrap()
    };
    vec![
        (
            "bspline 9 = 9",
            mk(wobbly(9, 0.3, 0.0), wobbly(9, 1.7, 0.0), Expander::Burtnyk),
        ),
        (
            "bspline 7 → 12 burtnyk",
            mk(wobbly(7, 0.3, 0.0), wobbly(12, 1.7, 0.0), Expander::Burtnyk),
        ),
        (
            "bspline 12 → 7 arclength",
            mk(wobbly(12, 0.3, 0.0), wobbly(7, 1.7, 0.0), Expander::Arclength),
        ),
        (
            "bezier 3 → 5 burtnyk",
            mk(bezier_flower(3, 2.0), bezier_flower(5, 3.0), Expander::Burtnyk),
        ),
        (
            "bezier 5 → 3 arclength",
            mk(bezier_flower(5, 2.0), bezier_flower(3, 3.0), Expander::Arclength),
        ),
    ]
}

#[test]
fn do34_and_hermite_agree_at_the_ends_in_thesis_fidelity() {
    for (name, pair) in end_pairs(Fidelity::Thesis) {
        for (t, end) in [(0.0, 0.0), (1.0, 1.0)] {
            let gap = max_gap(&pair, t, end);
            assert!(gap < 1e-12, "{name}: Hermite({t}) differs from do34 by {gap}");
        }
        // And they join continuously: just inside the shutter.
        assert!(max_gap(&pair, 1e-14, 0.0) < 1e-12, "{name}");
        assert!(max_gap(&pair, 1.0 - 1e-14, 1.0) < 1e-12, "{name}");
    }
}

/// `Hermite` and `do34` keep the in-between contour's orientation with its
/// segments (DEVIATIONS D31): the sign of its signed area, whatever the
/// scratch record held before.
#[test]
fn hermite_and_do34_keep_the_contours_orientation() {
    for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
        for (name, pair) in end_pairs(fidelity) {
            for t in [0.0, 0.3, 1.0] {
                let (mut a, mut b) = (pair.scratch(), pair.scratch());
                (a.orientation, b.orientation) = (0.0, 0.0);
                Hermite(&pair, t, &mut a);
                do34(t, &pair, &mut b);
                for (who, c) in [("Hermite", &a), ("do34", &b)] {
                    let want = raytrace::shapes::sweep::orientation(&c.u, &c.v);
                    assert_eq!(c.orientation, want, "{name} {fidelity:?} {who}({t})");
                }
            }
        }
    }
}

/// Erratum 18: the listing's patches reproduce the key shapes only where
/// no segment was cut and the contour has no corner.
#[test]
fn erratum_18_listing_patches_miss_cut_segments_and_corners() {
    let gaps: Vec<(&str, f64)> = end_pairs(Fidelity::Listing)
        .iter()
        .map(|(name, pair)| (*name, max_gap(pair, 0.0, 0.0).max(max_gap(pair, 1.0, 1.0))))
        .collect();
    // Equal B-spline counts: no cut, no corner: exact.
    assert!(gaps[0].1 < 1e-12, "{gaps:?}");
    // Cut segments or Bezier corners: the t = 0 or t = 1 curve is not the key shape.
    for (name, gap) in &gaps[1..] {
        assert!(*gap > 1e-3, "{name}: {gap}");
    }
}

// ------------------------------------------------------ equalising counts

#[test]
fn burtnyk_worked_numbers_and_erratum_10() {
    // §3.2.3: RT := (NS1-1) div (NS2-1); RS := (NS1-1) mod (NS2-1).
    assert_eq!(burtnyk(10, 4, Outline::Open), Some((3, 0)));
    assert_eq!(burtnyk(9, 4, Outline::Open), Some((2, 2)));
    // For open polygons the rule gives NS1 − 1 edges: RS(RT+1) + (NS2−1−RS)·RT.
    for (ns1, ns2) in [(10usize, 4usize), (9, 4), (60, 7), (13, 5)] {
        let (rt, rs) = burtnyk(ns1, ns2, Outline::Open).unwrap();
        assert_eq!(rs * (rt + 1) + (ns2 - 1 - rs) * rt, ns1 - 1);
    }
    // Erratum 10: read as segment counts of closed curves (NS2 segments each
    // taking its points) the text's numbers do not give NS1: 10 and 4 give 12.
    let (rt, rs) = burtnyk(10, 4, Outline::Open).unwrap();
    assert_eq!(rs * (rt + 1) + (4 - rs) * rt, 12);
    // expanding's closed rule: NS1 div NS2, NS1 mod NS2, which does.
    assert_eq!(burtnyk(10, 4, Outline::Closed), Some((2, 2)));
    let first = translation("a", [0.0; 3], wobbly(4, 0.1, 0.0));
    let last = translation("b", [0.0; 3], wobbly(10, 0.9, 0.0));
    for f in [Fidelity::Listing, Fidelity::Thesis] {
        let pair = goahead(1, &first, &last, Expander::Burtnyk, f).unwrap();
        assert_eq!(pair.snu, 10);
        assert_eq!(pair.messages, [PaperMessage::Equal]);
        // The first RS = 2 segments take RT = 2 points (3 pieces), the others 1.
        let from: Vec<f64> = (1..=10).map(|i| pair.p1u[i].first).collect();
        let third = 1.0 / 3.0;
        assert_eq!(
            from,
            [0.0, third, 2.0 * third, 0.0, third, 2.0 * third, 0.0, 0.5, 0.0, 0.5]
        );
    }
}

/// The expanded contour (pieces `p[1..n]`) traverses the original
/// segments in order, each cut into pieces that tile its [0, 1]: sampled
/// points of every piece lie on the original curve at the same place.
fn same_curve(p: &Sdirection, n: usize, original: &[Coeff]) -> Result<(), String> {
    let mut seg = 0;
    let mut from = 0.0;
    for k in 1..=n {
        let c = &p[k];
        let o = original
            .get(seg)
            .ok_or(format!("piece {k}: past the original's {} segments", original.len()))?;
        if (c.a, c.b, c.c, c.d) != (o.a, o.b, o.c, o.d) {
            return Err(format!("piece {k} is not a piece of segment {}", seg + 1));
        }
        if c.first != from || c.last <= c.first {
            return Err(format!("piece {k}: [{}, {}] after {from}", c.first, c.last));
        }
        for tau in [0.0, 0.3, 0.7, 1.0] {
            let s = c.first + tau * (c.last - c.first);
            let on = x(o, s);
            if (x(c, s) - on).abs() > 1e-12 {
                return Err(format!("piece {k} leaves the curve at {s}"));
            }
        }
        if (c.last - 1.0).abs() < 1e-12 {
            seg += 1;
            from = 0.0;
        } else {
            from = c.last;
        }
    }
    if seg != original.len() {
        return Err(format!("covered {seg} of {} segments", original.len()));
    }
    Ok(())
}

#[test]
fn both_expanders_equalise_every_pair_of_counts_4_to_60() {
    let shapes: Vec<SweepShape> = (0..=60).map(|n| wobbly(n.max(4), n as f64 * 0.37, 0.0)).collect();
    let mut checked = 0;
    for (n1, s1) in shapes.iter().enumerate().skip(4) {
        for n2 in 4..=60 {
            let first = translation("a", [0.0; 3], s1.clone());
            let last = translation("b", [3.0, 0.0, 1.0], wobbly(n2, 1.0 + n2 as f64 * 0.61, 0.5));
            let Shape::Sweep(ls) = &last.shape else { unreachable!() };
            for expander in [Expander::Burtnyk, Expander::Arclength] {
                for f in [Fidelity::Thesis, Fidelity::Listing] {
                    let pair = goahead(1, &first, &last, expander, f)
                        .unwrap_or_else(|e| panic!("{n1} {n2} {expander:?} {f:?}: {e}"));
                    assert_eq!(pair.snu, n1.max(n2), "{n1} {n2} {expander:?} {f:?}");
                    assert!(!pair.failed(), "{n1} {n2} {expander:?} {f:?}: {:?}", pair.messages);
                    let ctx = |e: String| format!("{n1} {n2} {expander:?} {f:?}: {e}");
                    same_curve(&pair.p1u, pair.snu, &s1.u).map_err(ctx).unwrap();
                    same_curve(&pair.p1v, pair.snu, &s1.v).map_err(ctx).unwrap();
                    same_curve(&pair.p2u, pair.snu, &ls.u).map_err(ctx).unwrap();
                    same_curve(&pair.p2v, pair.snu, &ls.v).map_err(ctx).unwrap();
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 57 * 57 * 4);
}

/// FIRST: 5 straight segments whose starts are at the shares 0, ⅛, ¼, ½,
/// ¾; LAST: a unit square and two petals (loops) at its first corner, so
/// that its last two chords have length 0 and its starts are at the shares
/// 0, ¼, ½, ¾, 1, 1.
fn impossible_pair() -> (ObjectRecord, ObjectRecord) {
    let first = bezier_polygon(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
    let mut pts = bezier_polygon(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]).points;
    pts.extend_from_slice(&[
        [0.0, 0.0],
        [-1.0, -0.5],
        [-0.5, -1.0],
        [0.0, 0.0],
        [-1.0, 0.5],
        [-0.5, 1.0],
    ]);
    let last = sweep(&pts, CurveKind::Bezier);
    (
        translation("five", [0.0; 3], first),
        translation("petals", [0.0; 3], last),
    )
}

#[test]
fn erratum_8_more2_it_is_impossible() {
    let (first, last) = impossible_pair();
    let (Shape::Sweep(fs), Shape::Sweep(ls)) = (&first.shape, &last.shape) else {
        unreachable!()
    };
    assert_eq!((fs.segment, ls.segment), (5, 6));

    // more2 itself on the two contours' shares.
    let mut d1 = [0.0; MAXSEGMENTS + 1];
    let mut d2 = [0.0; MAXSEGMENTS + 1];
    let (mut pu, mut pv, mut qu, mut qv) = Default::default();
    saving(fs, &mut pu, &mut pv);
    saving(ls, &mut qu, &mut qv);
    getdistance(&pu, &pv, 5, &mut d1);
    getdistance(&qu, &qv, 6, &mut d2);
    assert_eq!(&d1[..6], &[0.0, 0.125, 0.25, 0.5, 0.75, 1.0]);
    assert_eq!(&d2[..7], &[0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0]);
    let mut log = Vec::new();
    let (mut lu, mut lv) = (pu, pv);
    assert_eq!(
        more2(&d1, &d2, 5, 6, &mut lu, &mut lv, Fidelity::Listing, &mut log),
        Ok(())
    );
    assert_eq!(
        log,
        [
            PaperMessage::Impossible { segment: 2 },
            PaperMessage::PlusError { nu: -1 },
            PaperMessage::More2Unequal { n2: 6, k1: 4 },
        ]
    );
    assert_eq!(log[0].to_string(), "It is impossible (segment 2)");
    let mut log = Vec::new();
    let (mut tu, mut tv) = (pu, pv);
    assert_eq!(
        more2(&d1, &d2, 5, 6, &mut tu, &mut tv, Fidelity::Thesis, &mut log),
        Ok(())
    );
    assert_eq!(log, [PaperMessage::More2Equal]);

    // Listing: goahead goes on with segment 2 dropped, the old segment 5
    // still in entry 5 and a zero entry 6 (the fresh global array).
    let pair = goahead(1, &first, &last, Expander::Arclength, Fidelity::Listing).unwrap();
    assert!(pair.failed());
    assert_eq!(pair.messages.len(), 3);
    assert_eq!(pair.snu, 6);
    let curve = |c: &Coeff| (c.a, c.b, c.c, c.d, c.first, c.last);
    let kept: Vec<_> = (1..=5).map(|i| curve(&pair.p1u[i])).collect();
    let from: Vec<_> = [0, 2, 3, 4, 4].iter().map(|&i| curve(&fs.u[i])).collect();
    assert_eq!(kept, from);
    assert_eq!(curve(&pair.p1u[6]), (0.0, 0.0, 0.0, 0.0, 0.0, 0.0));
    // It still renders something finite.
    let mut out = pair.scratch();
    Hermite(&pair, 0.5, &mut out);
    assert!(out.u.iter().chain(&out.v).all(|c| c.a.is_finite() && c.d.is_finite()));

    // Thesis: the last segment's range is closed at 1, the counts end equal,
    // the tiny segment 2 borrowing the spare point of segment 5.
    let pair = goahead(1, &first, &last, Expander::Arclength, Fidelity::Thesis).unwrap();
    assert!(!pair.failed());
    assert_eq!(pair.messages, [PaperMessage::More2Equal]);
    assert_eq!(pair.snu, 6);
    same_curve(&pair.p1u, 6, &fs.u).unwrap();
    same_curve(&pair.p1v, 6, &fs.v).unwrap();
    assert_eq!(
        (pair.p1u[5].first, pair.p1u[5].last, pair.p1u[6].first),
        (0.0, 0.5, 0.5)
    );
    // Burtnyk has no such failure in either fidelity.
    for f in [Fidelity::Listing, Fidelity::Thesis] {
        let pair = goahead(1, &first, &last, Expander::Burtnyk, f).unwrap();
        assert_eq!(pair.messages, [PaperMessage::Equal]);
    }
}

/// Erratum 8 in `Fidelity::Thesis`: a failure of the method is an error
/// (here forced by giving more2 shares whose starts it cannot place).
#[test]
fn erratum_8_thesis_fidelity_returns_the_failure() {
    let mut d1 = [0.0; MAXSEGMENTS + 1];
    d1[..4].copy_from_slice(&[0.0, 0.2, 0.6, 1.0]);
    // A NaN share: never counted, in either fidelity.
    let mut d2 = [0.0; MAXSEGMENTS + 1];
    d2[..5].copy_from_slice(&[f64::NAN, f64::NAN, 0.5, 0.7, 1.0]);
    let (mut pu, mut pv) = Default::default();
    let mut log = Vec::new();
    let r = more2(&d1, &d2, 3, 4, &mut pu, &mut pv, Fidelity::Thesis, &mut log);
    assert_eq!(r, Err(PaperMessage::Impossible { segment: 1 }));
    let mut log = Vec::new();
    let r = more2(&d1, &d2, 3, 4, &mut pu, &mut pv, Fidelity::Listing, &mut log);
    assert_eq!(r, Ok(()));
    assert!(log.contains(&PaperMessage::Impossible { segment: 1 }));
    assert!(matches!(log.last(), Some(PaperMessage::More2Unequal { n2: 4, .. })));
}

#[test]
fn getdistance_of_a_square_is_in_quarters() {
    for shape in [
        bezier_polygon(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]),
        sweep(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]], CurveKind::Bspline),
    ] {
        let (mut u, mut v) = Default::default();
        saving(&shape, &mut u, &mut v);
        let mut dist = [f64::NAN; MAXSEGMENTS + 1];
        getdistance(&u, &v, 4, &mut dist);
        assert_eq!(&dist[..5], &[0.0, 0.25, 0.5, 0.75, 1.0]);
    }
    // Erratum 10: each contour's shares are its own, in both fidelities. A
    // square to a 1×3 rectangle (chords 1, 3, 1, 3): ⅛, ½, ⅝.
    let square = translation(
        "sq",
        [0.0; 3],
        bezier_polygon(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]),
    );
    let rect = translation(
        "re",
        [0.0; 3],
        bezier_polygon(&[[0.0, 0.0], [1.0, 0.0], [1.0, 3.0], [0.0, 3.0]]),
    );
    for f in [Fidelity::Listing, Fidelity::Thesis] {
        let pair = goahead(1, &square, &rect, Expander::Arclength, f).unwrap();
        assert_eq!(&pair.dist1[..5], &[0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(&pair.dist2[..5], &[0.0, 0.125, 0.5, 0.625, 1.0]);
    }
    // The text's line dist2[i] := (distance(p[i-1],p[i]) + dist1[i-1]) /
    // length(curve2) would give (1 + 0)/8, (3 + ¼)/8, … : not the rectangle's.
    let text: Vec<f64> = [1.0, 3.0, 1.0]
        .iter()
        .zip([0.0, 0.25, 0.5])
        .map(|(c, d1)| (c + d1) / 8.0)
        .collect();
    assert_ne!(text, [0.125, 0.5, 0.625]);
}

#[test]
fn more_than_60_segments_is_an_error() {
    let small = translation("a", [0.0; 3], wobbly(4, 0.0, 0.0));
    let big = translation("b", [0.0; 3], wobbly(61, 0.0, 0.0));
    for e in [Expander::Burtnyk, Expander::Arclength] {
        for f in [Fidelity::Listing, Fidelity::Thesis] {
            assert_eq!(
                goahead(3, &small, &big, e, f).unwrap_err(),
                PaperError::TooManySegments { int: 3, count: 61 }
            );
            assert_eq!(
                goahead(3, &big, &small, e, f).unwrap_err(),
                PaperError::TooManySegments { int: 3, count: 61 }
            );
        }
    }
    let sixty = translation("c", [0.0; 3], wobbly(60, 0.0, 0.0));
    assert_eq!(
        goahead(1, &small, &sixty, Expander::Arclength, Fidelity::Thesis)
            .unwrap()
            .snu,
        60
    );
}

#[test]
fn bad_pairs_are_errors() {
    let good = translation("a", [0.0; 3], wobbly(5, 0.0, 0.0));
    let g = |a: &ObjectRecord, b: &ObjectRecord| goahead(2, a, b, Expander::Arclength, Fidelity::Thesis);
    let mut sphere = good.clone();
    sphere.shape = Shape::Sphere;
    sphere.class = PrimitiveClass::Sphere;
    assert!(matches!(
        g(&sphere, &good),
        Err(PaperError::NotSweep { int: 2, which: "FIRST" })
    ));
    let mut conic = good.clone();
    conic.class = PrimitiveClass::Conic;
    assert!(matches!(g(&good, &conic), Err(PaperError::ClassMismatch { .. })));
    let one = translation("one", [0.0; 3], bezier_polygon(&[[0.0, 0.0], [1.0, 0.0]]));
    let mut one = one;
    if let Shape::Sweep(s) = &mut one.shape {
        s.segment = 1;
    }
    assert!(matches!(
        g(&good, &one),
        Err(PaperError::TooFewSegments { which: "LAST", .. })
    ));
    let mut bare = good.clone();
    if let Shape::Sweep(s) = &mut bare.shape {
        s.u.clear();
    }
    assert!(matches!(g(&good, &bare), Err(PaperError::NotPrepared { .. })));
    let mut nan = good.clone();
    if let Shape::Sweep(s) = &mut nan.shape {
        s.v[2].c = f64::NAN;
    }
    assert!(matches!(g(&nan, &good), Err(PaperError::NotFinite { .. })));
    let mut far = good.clone();
    far.sphereo.y = f64::INFINITY;
    assert!(matches!(g(&good, &far), Err(PaperError::NotFinite { .. })));
    let dot = translation("dot", [0.0; 3], sweep(&[[1.0, 1.0]; 6], CurveKind::Bspline));
    assert!(matches!(
        g(&good, &dot),
        Err(PaperError::Degenerate { which: "LAST", .. })
    ));
    assert_eq!(
        PaperChain::new(&good, &[], Expander::Burtnyk, Fidelity::Thesis).unwrap_err(),
        PaperError::EmptyChain
    );
    // The messages name the pair.
    assert!(g(&good, &dot).unwrap_err().to_string().starts_with("key-frame pair 2:"));
}

// ----------------------------------------------------------------- poses

#[test]
fn erratum_4_difference_in_both_fidelities() {
    let (p1, p2) = (DVec3::new(1.0, 5.0, 7.0), DVec3::new(4.0, 9.0, 2.0));
    let mut d = DVec3::ZERO;
    difference(p1, p2, &mut d, Fidelity::Listing);
    assert_eq!(d, DVec3::new(3.0, 4.0 - 5.0, 4.0 - 7.0));
    difference(p1, p2, &mut d, Fidelity::Thesis);
    assert_eq!(d, DVec3::new(3.0, 4.0, -5.0));

    let first = translation("a", [1.0, 5.0, 7.0], wobbly(6, 0.0, 0.0));
    let last = translation("b", [4.0, 9.0, 2.0], wobbly(6, 1.0, 0.0));
    let thesis = goahead(1, &first, &last, Expander::Burtnyk, Fidelity::Thesis).unwrap();
    let listing = goahead(1, &first, &last, Expander::Burtnyk, Fidelity::Listing).unwrap();
    assert_eq!(thesis.diff, DVec3::new(3.0, 4.0, -5.0));
    assert_eq!(listing.diff, DVec3::new(3.0, -1.0, -3.0));
    // At t = 1 the thesis's object stands where LAST stands; the listing's
    // moves in y and z by the wrong amounts.
    assert_eq!(thesis.pose(1.0).sphereo, last.sphereo);
    assert_eq!(listing.pose(1.0).sphereo, DVec3::new(4.0, 4.0, 4.0));
    assert_eq!(thesis.pose(0.5).sphereo, DVec3::new(2.5, 7.0, 4.5));
    for pair in [&thesis, &listing] {
        let p = pair.pose(0.25);
        assert!(p.transfm.transform_point3(DVec3::ZERO).abs_diff_eq(p.sphereo, 1e-12));
        assert!((p.transfm * p.inverse).abs_diff_eq(DMat4::IDENTITY, 1e-12));
    }
}

/// A key shape at `at`, turned as a deck turns it: `rotate x ax` then
/// `rotate z az` (R ← Rz·Rx, `angle` = (ax, 0, az)).
fn key_turned(name: &str, at: [f64; 3], ax: f64, az: f64, shape: SweepShape) -> ObjectRecord {
    let sphereo = DVec3::from_array(at);
    let r = DMat4::from_rotation_z(az.to_radians()) * DMat4::from_rotation_x(ax.to_radians());
    ObjectRecord {
        transfm: DMat4::from_translation(sphereo) * r,
        inverse: r.transpose() * DMat4::from_translation(-sphereo),
        angle: DVec3::new(ax, 0.0, az),
        ..key(name, PrimitiveClass::Translation, at, 0.0, shape)
    }
}

/// Erratum 19 with a FIRST turned 90° about x (as fig5_10's star stands):
/// the listing's `rotate(name,xaxis,0,0,0,angle.x)` on the restored
/// `temp1` keeps FIRST's rest pose at every time, never a second x turn;
/// the thesis turns by t·`diffangle` onto LAST.
#[test]
fn erratum_19_the_angle_over_the_shutter() {
    let first = key_turned("a", [0.0, 0.0, 1.0], 90.0, 0.0, wobbly(6, 0.0, 0.0));
    let last = key_turned("b", [2.0, 0.0, 1.0], 90.0, 90.0, wobbly(6, 1.0, 0.0));
    let thesis = goahead(1, &first, &last, Expander::Burtnyk, Fidelity::Thesis).unwrap();
    let listing = goahead(1, &first, &last, Expander::Burtnyk, Fidelity::Listing).unwrap();
    assert_eq!(thesis.diffangle, DVec3::new(0.0, 0.0, 90.0));
    // Erratum 4 in `diffangle` too: dif.y := po2.x - po1.y = 90 - 0, and
    // dif.z := po2.x - po1.z = 90 - 0.
    assert_eq!(listing.diffangle, DVec3::new(0.0, 90.0, 90.0));
    // Thesis: angle(t) = θ1 + (θ2 − θ1)t: at 0 FIRST's pose, at 1 LAST's,
    // at ½ the contour's x axis turned 45° about z.
    assert!(thesis.pose(0.0).transfm.abs_diff_eq(first.transfm, 1e-12));
    assert!(thesis.pose(1.0).transfm.abs_diff_eq(last.transfm, 1e-12));
    assert!(thesis.pose(1.0).inverse.abs_diff_eq(last.inverse, 1e-12));
    let half = thesis.pose(0.5).transfm.transform_vector3(DVec3::X);
    let c = std::f64::consts::FRAC_1_SQRT_2;
    assert!(half.abs_diff_eq(DVec3::new(c, c, 0.0), 1e-12));
    // Listing: FIRST's rest rotation at every time, only the position moves
    // (by `diff`): the sweep's axis (local z) points along −y, the contour's
    // V (local y) up, as FIRST's; no second turn about x, no turn by the
    // (erratum 4) `diffangle`.
    for t in [0.0, 0.3, 0.5, 1.0] {
        let p = listing.pose(t);
        let rest = DMat3::from_mat4(first.transfm);
        assert!(DMat3::from_mat4(p.transfm).abs_diff_eq(rest, 1e-12), "t {t}");
        assert!(
            p.transfm.transform_vector3(DVec3::Z).abs_diff_eq(-DVec3::Y, 1e-12),
            "t {t}"
        );
        assert!(
            p.transfm.transform_vector3(DVec3::Y).abs_diff_eq(DVec3::Z, 1e-12),
            "t {t}"
        );
        assert_eq!(p.sphereo, first.sphereo + listing.diff * t);
        assert!((p.transfm * p.inverse).abs_diff_eq(DMat4::IDENTITY, 1e-12));
    }
    assert!(listing.pose(0.0).transfm.abs_diff_eq(first.transfm, 1e-12));
}

// ----------------------------------------------------------------- boxes

fn box_pairs(fidelity: Fidelity, speed: f64) -> Vec<(String, PaperPair)> {
    let mut v = Vec::new();
    for (class, a, b) in [
        (PrimitiveClass::Translation, wobbly(7, 0.2, 0.0), wobbly(13, 2.0, 0.0)),
        (
            PrimitiveClass::Translation,
            bezier_flower(3, 2.0),
            bezier_flower(6, 3.0),
        ),
        (PrimitiveClass::Conic, wobbly(9, 0.5, 0.0), bezier_flower(4, 2.5)),
        (PrimitiveClass::Rotation, wobbly(8, 0.1, 5.0), wobbly(5, 1.1, 6.0)),
    ] {
        for e in [Expander::Burtnyk, Expander::Arclength] {
            let first = key("a", class, [0.0, 0.0, 0.0], 0.0, a.clone());
            let last = key("b", class, [speed, 2.0, -0.6 * speed], 0.0, b.clone());
            let pair = prepared_pair(first, last, e, fidelity);
            v.push((format!("{class:?} {e:?} speed {speed}"), pair));
        }
    }
    v
}

/// The pair as the renderer sets it up: FIRST and LAST in a scene through
/// `prepare`, so that the key shapes' boxes are what the fidelity makes
/// them (listing: the class's box, `tbox` widened by 2 for the one pair).
fn prepared_pair(first: ObjectRecord, last: ObjectRecord, expander: Expander, fidelity: Fidelity) -> PaperPair {
    let mut scene = common::scene();
    scene.objects.push(first);
    scene.keyframes.push(KeyframeRecord {
        pos: Pos::default(),
        first: 0,
        rest: vec![last],
        expander,
    });
    let opts = Options {
        fidelity,
        ..Options::default()
    };
    let prepared = common::prepare(scene, opts);
    let chain = PaperChain::from_keyframe(prepared.scene(), &prepared.scene().keyframes[0], fidelity).unwrap();
    chain.pairs()[0].clone()
}

/// Samples of the in-between contour at 64 times: (t, segment, u, v).
fn samples(pair: &PaperPair, out: &mut SweepShape, mut each: impl FnMut(f64, usize, f64, f64)) {
    for k in 0..64 {
        let t = k as f64 / 63.0;
        inbetween(pair, t, out);
        for i in 0..out.segment {
            for j in 0..=16 {
                let s = j as f64 / 16.0;
                each(t, i, x(&out.u[i], s), x(&out.v[i], s));
            }
        }
    }
}

#[test]
fn erratum_9_every_inbetween_lies_in_the_box_at_64_times() {
    for speed in [1.0, 40.0] {
        for (name, pair) in box_pairs(Fidelity::Thesis, speed) {
            let mut out = pair.scratch();
            let mut n = 0;
            samples(&pair, &mut out.clone(), |t, i, u, v| {
                n += 1;
                assert!(
                    in_box(pair.class, &pair.bbox, u, v),
                    "{name}: t {t} segment {i}: ({u}, {v})"
                );
            });
            // Each call's own bounds hold its contour too.
            for k in 0..64 {
                let t = k as f64 / 63.0;
                inbetween(&pair, t, &mut out);
                for i in 0..out.segment {
                    for j in 0..=16 {
                        let s = j as f64 / 16.0;
                        let (u, v) = (x(&out.u[i], s), x(&out.v[i], s));
                        let (cu, cv) = (&out.u[i], &out.v[i]);
                        assert!(u >= cu.min - 1e-12 && u <= cu.max + 1e-12, "{name}: t {t} seg {i}");
                        assert!(v >= cv.min - 1e-12 && v <= cv.max + 1e-12, "{name}: t {t} seg {i}");
                        assert!(in_box(pair.class, &out.bbox, u, v), "{name}: t {t} seg {i}");
                    }
                }
            }
            assert!(n > 64 * 5 * 17);
        }
    }
}

#[test]
fn erratum_9_listing_widening_of_2_holds_when_slow_and_fails_when_fast() {
    // Slow (LAST 1 away): the class box (`tbox` widened by 2) holds every
    // sample.
    for (name, pair) in box_pairs(Fidelity::Listing, 1.0) {
        let mut out = pair.scratch();
        samples(&pair, &mut out, |t, i, u, v| {
            assert!(
                in_box(pair.class, &pair.bbox, u, v),
                "{name}: t {t} segment {i}: ({u}, {v})"
            );
        });
    }
    // Fast (LAST 40 away in x): the t-tangents of the patches are the motion,
    // the in-between bulges by up to 40·√3/18 ≈ 3.8 > 2 beyond the key
    // shapes, and leaves both the box and Hermite's per-segment bounds.
    let mut escaped = 0;
    let mut worst = 0.0f64;
    for (_, pair) in box_pairs(Fidelity::Listing, 40.0) {
        let mut out = pair.scratch();
        let mut outside = false;
        samples(&pair, &mut out.clone(), |_, _, u, v| {
            if !in_box(pair.class, &pair.bbox, u, v) {
                outside = true;
                let b = &pair.bbox;
                worst = worst.max(b.xmin - u).max(u - b.xmax);
            }
        });
        Hermite(&pair, 0.2, &mut out);
        let seg_escape = (0..out.segment).any(|i| {
            (0..=16).any(|j| {
                let u = x(&out.u[i], j as f64 / 16.0);
                u < out.u[i].min || u > out.u[i].max
            })
        });
        if outside && seg_escape {
            escaped += 1;
        }
    }
    assert!(escaped >= 4, "{escaped} fast pairs escaped");
    assert!(worst > 1.0, "worst overshoot {worst}");
}

// ---------------------------------------------------------------- chains

#[test]
fn chain_time_shares_the_shutter_equally() {
    assert_eq!(chain_time(1, 0.7), (0, 0.7));
    assert_eq!(chain_time(1, 1.5), (0, 1.5));
    assert_eq!(chain_time(2, 0.0), (0, 0.0));
    assert_eq!(chain_time(2, 0.25), (0, 0.5));
    assert_eq!(chain_time(2, 0.5), (1, 0.0));
    assert_eq!(chain_time(2, 0.75), (1, 0.5));
    assert_eq!(chain_time(2, 1.0), (1, 1.0));
    assert_eq!(chain_time(4, 0.6), (2, 0.6 * 4.0 - 2.0));
    // Outside the shutter: the end pairs, extrapolated.
    assert_eq!(chain_time(2, 1.25), (1, 1.5));
    assert_eq!(chain_time(2, -0.25), (0, -0.5));
    assert_eq!(chain_time(2, f64::NAN).0, 0);
}

#[test]
fn a_chain_of_three_key_shapes() {
    let a = translation("n", [0.0, 0.0, 0.0], wobbly(5, 0.0, 0.0));
    let b = translation("e", [2.0, 0.0, 0.0], bezier_flower(4, 2.0));
    let c = translation("c", [4.0, 0.0, 1.0], wobbly(9, 1.0, 0.0));
    let chain = PaperChain::new(&a, &[b.clone(), c.clone()], Expander::Arclength, Fidelity::Thesis).unwrap();
    assert_eq!(chain.pairs().len(), 2);
    assert_eq!((chain.pairs()[0].int, chain.pairs()[1].int), (1, 2));
    assert_eq!((chain.pairs()[0].snu, chain.pairs()[1].snu), (5, 9));
    // Mid-shutter: B, in place.
    assert_eq!(chain.pose(0.5).sphereo, b.sphereo);
    assert_eq!(chain.pose(1.0).sphereo, c.sphereo);
    assert!(chain.pairs()[0]
        .pose(1.0)
        .transfm
        .abs_diff_eq(chain.pairs()[1].pose(0.0).transfm, 1e-12));
    // Both pairs give B's contour at the join: sample it.
    let mut end1 = chain.scratch();
    let mut start2 = chain.scratch();
    inbetween(&chain.pairs()[0], 1.0, &mut end1);
    chain.inbetween(0.5, &mut start2);
    let Shape::Sweep(bs) = &b.shape else { unreachable!() };
    for out in [&end1, &start2] {
        // Every sampled point of the contour lies on B (its 4 Bezier sides).
        for i in 0..out.segment {
            for j in 0..=8 {
                let s = j as f64 / 8.0;
                let p = (x(&out.u[i], s), x(&out.v[i], s));
                let on_b = (0..bs.segment).any(|k| {
                    (0..=2000).any(|m| {
                        let r = m as f64 / 2000.0;
                        (x(&bs.u[k], r) - p.0).hypot(x(&bs.v[k], r) - p.1) < 5e-3
                    })
                });
                assert!(on_b, "({}, {}) is not on B", p.0, p.1);
            }
        }
    }
    let bx = chain.bbox();
    assert!(bx.xmin <= chain.pairs()[1].bbox.xmin && bx.xmax >= chain.pairs()[0].bbox.xmax);

    // From a deck's keyframe record.
    let scene_objects = vec![a.clone()];
    let rec = KeyframeRecord {
        pos: Pos::default(),
        first: 0,
        rest: vec![b, c],
        expander: Expander::Arclength,
    };
    let scene = Scene {
        view: View {
            eyept: DVec3::ZERO,
            lookpt: DVec3::X,
            screensize: 1.0,
            scrndistance: 1.0,
        },
        image: ImageSpec {
            width: 1,
            height: 1,
            masksize: 1,
            aliasing: 0.0,
        },
        backgrnd: DVec3::ZERO,
        lights: vec![],
        surfaces: vec![],
        objects: scene_objects,
        object_pos: vec![Pos::default()],
        motions: vec![],
        keyframes: vec![],
        blur: None,
        pattern: None,
        film: None,
        lens: None,
    };
    assert_eq!(
        PaperChain::from_keyframe(&scene, &rec, Fidelity::Thesis).unwrap(),
        chain
    );
    let bad = KeyframeRecord { first: 7, ..rec };
    assert_eq!(
        PaperChain::from_keyframe(&scene, &bad, Fidelity::Thesis).unwrap_err(),
        PaperError::NoSuchObject { index: 7 }
    );
}

#[test]
fn hermite_and_do34_reuse_the_scratch() {
    let a = translation("a", [0.0; 3], wobbly(12, 0.0, 0.0));
    let b = translation("b", [1.0; 3], wobbly(4, 1.0, 0.0));
    let c = translation("c", [2.0; 3], wobbly(40, 2.0, 0.0));
    let chain = PaperChain::new(&a, &[b, c], Expander::Burtnyk, Fidelity::Thesis).unwrap();
    let mut out = chain.scratch();
    let (pu, pv) = (out.u.as_ptr(), out.v.as_ptr());
    let mut counts = Vec::new();
    for k in 0..=20 {
        chain.inbetween(k as f64 / 20.0, &mut out);
        counts.push(out.segment);
        assert_eq!((out.u.len(), out.v.len()), (out.segment, out.segment));
    }
    assert!(counts.contains(&40) && counts.contains(&12));
    assert_eq!(
        (out.u.as_ptr(), out.v.as_ptr()),
        (pu, pv),
        "a call reallocated the scratch"
    );
}

#[test]
fn delete_takes_the_named_object_out_of_the_table() {
    let mut table = vec![
        translation("one", [0.0; 3], wobbly(4, 0.0, 0.0)),
        translation("two", [0.0; 3], wobbly(4, 0.0, 0.0)),
        translation("three", [0.0; 3], wobbly(4, 0.0, 0.0)),
    ];
    assert_eq!(delete("two", &mut table).map(|o| o.name), Some("two".to_string()));
    assert_eq!(
        table.iter().map(|o| o.name.as_str()).collect::<Vec<_>>(),
        ["one", "three"]
    );
    // "no object by that name exists"
    assert!(delete("two", &mut table).is_none());
    assert_eq!(table.len(), 2);
}

/// Odd contours (repeated points, points in a line, huge and tiny
/// coordinates, zero-length chords) in every mode: an error or a pair,
/// never a panic; the pair's contours are finite wherever its inputs were.
#[test]
fn odd_contours_never_panic() {
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    let mut made = 0;
    for _ in 0..400 {
        let contour = |n: usize, next: &mut dyn FnMut() -> u64| -> SweepShape {
            let scale = [1e-9, 1.0, 1e6][(next() % 3) as usize];
            let pts: Vec<[f64; 2]> = (0..n)
                .map(|_| match next() % 5 {
                    0 => [0.0, 0.0],
                    1 => [1.0, 1.0],
                    2 => [(next() % 7) as f64 * scale, 0.0],
                    _ => [
                        (next() % 1000) as f64 / 100.0 * scale,
                        (next() % 1000) as f64 / 100.0 * scale,
                    ],
                })
                .collect();
            let curve = if next().is_multiple_of(2) {
                CurveKind::Bspline
            } else {
                CurveKind::Bezier
            };
            sweep(&pts, curve)
        };
        let n1 = 6 + (next() % 55) as usize;
        let n2 = 6 + (next() % 55) as usize;
        let (a, b) = (contour(n1, &mut next), contour(n2, &mut next));
        let first = translation("a", [0.0; 3], a);
        let last = translation("b", [(next() % 50) as f64, 1.0, 2.0], b);
        for e in [Expander::Burtnyk, Expander::Arclength] {
            for f in [Fidelity::Listing, Fidelity::Thesis] {
                match goahead(1, &first, &last, e, f) {
                    Ok(pair) => {
                        made += 1;
                        assert!(pair.snu >= 2 && pair.snu <= MAXSEGMENTS);
                        let mut out = pair.scratch();
                        for t in [0.0, 0.3, 1.0, 1.5] {
                            inbetween(&pair, t, &mut out);
                            assert_eq!(out.u.len(), pair.snu);
                        }
                        let _ = pair.pose(0.5);
                    }
                    Err(err) => assert!(!err.to_string().is_empty()),
                }
            }
        }
    }
    assert!(made > 100, "only {made} pairs");
}

/// The first crossing of the 2-D ray (x0, y0) + d·(dx, dy), d > 0, with the
/// contour, by sampling each segment finely and bisecting sign changes.
fn first_crossing(u: &[Coeff], v: &[Coeff], x0: f64, y0: f64, dx: f64, dy: f64) -> Option<f64> {
    let f = |i: usize, s: f64| (x(&u[i], s) - x0) * dy - (x(&v[i], s) - y0) * dx;
    let mut best: Option<f64> = None;
    for i in 0..u.len() {
        const N: usize = 4000;
        for k in 0..N {
            let (mut a, mut b) = (k as f64 / N as f64, (k + 1) as f64 / N as f64);
            let (fa, fb) = (f(i, a), f(i, b));
            if fa == 0.0 || fa * fb >= 0.0 {
                continue;
            }
            for _ in 0..60 {
                let m = 0.5 * (a + b);
                if (f(i, m) < 0.0) == (fa < 0.0) {
                    a = m;
                } else {
                    b = m;
                }
            }
            let s = 0.5 * (a + b);
            let d = (x(&u[i], s) - x0) * dx + (x(&v[i], s) - y0) * dy;
            if d > 1e-9 && best.is_none_or(|b| d < b) {
                best = Some(d);
            }
        }
    }
    best
}

/// The contours `Hermite` and `do34` write are what the sweep intersection
/// needs: rays across the in-between translation sweep (in the plane z = 1,
/// so no cap) hit it where its contour is, at every time, in thesis
/// fidelity. In listing fidelity a fast pair's per-segment bounds (the
/// merged bounds ± 2, erratum 9) cull crossings: holes in the object.
#[test]
fn inbetween_contours_meet_the_sweep_intersection() {
    let opts = Options {
        solver: Solver::Robust,
        ..Options::default()
    };
    let mut rays: Vec<(f64, f64, f64, f64)> = (0..60)
        .map(|k| {
            let th = std::f64::consts::TAU * k as f64 / 60.0 + 0.1;
            let off = (k % 7) as f64 - 3.0;
            // From 30 away toward the contour, offset sideways.
            let (dx, dy) = (-th.cos(), -th.sin());
            (30.0 * th.cos() - off * dy, 30.0 * th.sin() + off * dx, dx, dy)
        })
        .collect();
    // Down the lines x = −12 … 12 and across the lines y = −12 … 12.
    for k in 0..97 {
        let c = -12.0 + 0.25 * k as f64 + 0.01;
        rays.push((c, 30.0, 0.0, -1.0));
        rays.push((-30.0, c, 1.0, 0.0));
    }
    let mut misses = [0usize; 2];
    let mut hits = [0usize; 2];
    for (fi, f) in [Fidelity::Thesis, Fidelity::Listing].into_iter().enumerate() {
        let first = translation("a", [0.0; 3], wobbly(7, 0.2, 0.0));
        let last = translation("b", [40.0, 0.0, -24.0], bezier_flower(5, 3.0));
        let pair = goahead(1, &first, &last, Expander::Arclength, f).unwrap();
        let mut out = pair.scratch();
        for t in [0.0, 0.1, 0.21, 0.5, 0.79, 0.9, 1.0] {
            inbetween(&pair, t, &mut out);
            for &(x0, y0, dx, dy) in &rays {
                let truth = first_crossing(&out.u, &out.v, x0, y0, dx, dy);
                let ray = Ray::new(DVec3::new(x0, y0, 1.0), DVec3::new(dx, dy, 0.0));
                // A contour of the moment: no cache.
                let contour = Sweep {
                    class: PrimitiveClass::Translation,
                    shape: &out,
                    cache: None,
                };
                let got = contour.intersect(&ray, 1e-9, &opts, &mut 0);
                match (truth, got) {
                    (Some(d), Some(h)) if (h.t - d).abs() < 1e-6 => {
                        hits[fi] += 1;
                        assert!((h.point.z - 1.0).abs() < 1e-9 && h.normal.z.abs() < 1e-9);
                    }
                    // The first crossing culled: no hit, or a later one.
                    (Some(d), got) => {
                        assert!(got.is_none_or(|h| h.t > d), "{f:?} t {t}: a hit before the contour");
                        misses[fi] += 1;
                    }
                    (None, got) => assert!(got.is_none(), "{f:?} t {t}: a hit where the contour is not"),
                }
            }
        }
    }
    assert_eq!(misses[0], 0, "thesis fidelity missed crossings");
    assert!(hits[0] > 100);
    assert!(misses[1] > 0, "listing fidelity culled nothing");
}

//! The coefficients and boxes of the sweep objects, from their control
//! points (`spline`), before any ray.

use super::contour::orientation;
use crate::options::Fidelity;
use crate::proc::sweep::spline;
use crate::scene::Scene;
use crate::types::{BoundingBox, Coeff, CurveKind, DVec3, PrimitiveClass, Shape, SweepShape, MAXSEGMENTS};

/// The four control points of segment i: B-spline points i … i+3
/// (wrapping), Bezier `P[3i]` … `P[3i+3 mod 3k]`.
pub fn segment_points(curve: CurveKind, points: &[[f64; 2]], i: usize) -> [[f64; 2]; 4] {
    let n = points.len();
    match curve {
        CurveKind::Bspline => std::array::from_fn(|k| points[(i + k) % n]),
        CurveKind::Bezier => {
            let m = 3 * (n / 3);
            std::array::from_fn(|k| points[(3 * i + k) % m])
        }
    }
}

/// `u`, `v` and `segment` of one sweep from its control points, by
/// `spline`; returns the box `spline` widened (x from U; y, or for a
/// rotation z, from V).
pub fn fill_segments(class: PrimitiveClass, sw: &mut SweepShape) -> BoundingBox {
    let n = sw.points.len();
    let segments = match sw.curve {
        CurveKind::Bspline => n,
        CurveKind::Bezier => n / 3,
    }
    .min(MAXSEGMENTS);
    sw.segment = segments;
    sw.u.clear();
    sw.v.clear();
    let mut sbox = BoundingBox::EMPTY;
    for i in 0..segments {
        let p = segment_points(sw.curve, &sw.points, i);
        let (mut cu, mut cv) = (Coeff::default(), Coeff::default());
        spline(
            sw.curve, p[0][0], p[1][0], p[2][0], p[3][0], &mut cu, class, 1, &mut sbox,
        );
        spline(
            sw.curve, p[0][1], p[1][1], p[2][1], p[3][1], &mut cv, class, 2, &mut sbox,
        );
        sw.u.push(cu);
        sw.v.push(cv);
    }
    sw.orientation = orientation(&sw.u, &sw.v);
    sbox
}

/// The box the listing's class box gets from one sweep: `spline`'s x and
/// y (rotation: x and z) plus what `spline` does not write: the height
/// 0..length of translation and conic sweeps, the conic contour scaled to
/// `scale`; for rotation y copies x (the listing leaves `rbox.y` alone).
pub(super) fn listing_box(class: PrimitiveClass, sw: &SweepShape, sbox: &BoundingBox) -> BoundingBox {
    let mut b = *sbox;
    match class {
        PrimitiveClass::Rotation => {
            b.ymin = b.xmin;
            b.ymax = b.xmax;
        }
        _ => {
            if class == PrimitiveClass::Conic && sw.scale.is_finite() {
                let s = sw.scale;
                let (x0, x1) = (b.xmin * s, b.xmax * s);
                let (y0, y1) = (b.ymin * s, b.ymax * s);
                b.xmin = b.xmin.min(x0).min(x1);
                b.xmax = b.xmax.max(x0).max(x1);
                b.ymin = b.ymin.min(y0).min(y1);
                b.ymax = b.ymax.max(y0).max(y1);
            }
            b.zmin = 0.0f64.min(sw.length);
            b.zmax = 0.0f64.max(sw.length);
        }
    }
    b
}

/// The object's own local box: as [`listing_box`], but a rotation sweep's
/// x and y span ±(largest radius).
pub(super) fn own_box(class: PrimitiveClass, sw: &SweepShape, sbox: &BoundingBox) -> BoundingBox {
    let mut b = listing_box(class, sw, sbox);
    if class == PrimitiveClass::Rotation {
        let r = sbox.xmin.abs().max(sbox.xmax.abs());
        (b.xmin, b.xmax, b.ymin, b.ymax) = (-r, r, -r, r);
    }
    b
}

/// Fills every sweep object's `u`, `v`, `segment` and `bbox` from its
/// control points (`spline`, one `Coeff` per segment and coordinate), and
/// widens the object's bounding-sphere `radius` to hold its own box.
///
/// Reconstructed from the thesis's §2.2–2.3 and §3.3 (`spline` is printed;
/// who calls it is not). B-spline segment i uses points i, i+1, i+2, i+3
/// (wrapping, n points give n segments); Bezier segment i uses `P[3i]`,
/// `P[3i+1]`, `P[3i+2]`, `P[3i+3 mod 3k]` (3k points give k). At most 60.
///
/// Erratum 9: `Thesis` gives each object its own box. `Listing` keeps one
/// box per class as the listing's globals `tbox`, `cbox`, `rbox` do: every
/// sweep of a class gets the union of the class's boxes, with a rotation
/// box's x (and y) the radius range min U … max U as `spline` writes it.
pub fn prepare_sweeps(scene: &mut Scene, fidelity: Fidelity) {
    let classes = [
        PrimitiveClass::Translation,
        PrimitiveClass::Conic,
        PrimitiveClass::Rotation,
    ];
    let mut class_box = [BoundingBox::EMPTY; 3];
    // The later key shapes of a keyframe record stood in the Pascal's table
    // too until `goahead` deleted them: they get coefficients and widen
    // the class's box like every other sweep.
    let Scene { objects, keyframes, .. } = scene;
    for obj in objects
        .iter_mut()
        .chain(keyframes.iter_mut().flat_map(|k| k.rest.iter_mut()))
    {
        let class = obj.class;
        let Some(ci) = classes.iter().position(|&c| c == class) else {
            continue;
        };
        let Shape::Sweep(sw) = &mut obj.shape else {
            continue;
        };
        let sbox = fill_segments(class, sw);
        if sw.segment == 0 {
            sw.bbox = BoundingBox::default();
            continue;
        }
        let own = own_box(class, sw, &sbox);
        class_box[ci] = class_box[ci].union(&listing_box(class, sw, &sbox));
        sw.bbox = own;
        let corner = DVec3::new(
            own.xmin.abs().max(own.xmax.abs()),
            own.ymin.abs().max(own.ymax.abs()),
            own.zmin.abs().max(own.zmax.abs()),
        );
        if corner.is_finite() {
            obj.radius = obj.radius.max(corner.length() * (1.0 + 1e-9));
        }
    }
    match fidelity {
        // Erratum 9, listing: `spline` widens the one global box of the
        // class (`tbox`, `cbox`, `rbox`), which every object of it uses.
        Fidelity::Listing => {
            for obj in objects
                .iter_mut()
                .chain(keyframes.iter_mut().flat_map(|k| k.rest.iter_mut()))
            {
                let Some(ci) = classes.iter().position(|&c| c == obj.class) else {
                    continue;
                };
                if let Shape::Sweep(sw) = &mut obj.shape {
                    if sw.segment > 0 {
                        sw.bbox = class_box[ci];
                    }
                }
            }
        }
        // Thesis (§3.3): "the bounding box of each picture" — each
        // object keeps its own.
        Fidelity::Thesis => {}
    }
}

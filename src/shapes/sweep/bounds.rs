//! What the sweep driver takes from an object's box for every ray, made
//! once per box (DEVIATIONS D33).

use super::box_size;
use crate::types::{BoundingBox, Coeff, DVec3, PrimitiveClass, SweepShape, MAXSEGMENTS};

/// What [`Sweep`](super::Sweep) takes from an object's box for every ray:
/// the size its tolerances are relative to, the padded box a ray must
/// meet, and the sphere about it that [`Near`](crate::shapes::Near)
/// re-bases the ray on. Made once for an object whose box is final
/// ([`SweepCache`](super::SweepCache)) and kept with the box and class it
/// was made from; a ray of an object whose box has changed since, or of a
/// contour of the moment, makes its own (the port's; the same values
/// either way).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct QueryBounds {
    class: PrimitiveClass,
    bbox: BoundingBox,
    pub(super) size: f64,
    pub(super) boxed: bool,
    pub(super) lo: DVec3,
    pub(super) hi: DVec3,
    pub(super) centre: DVec3,
    pub(super) radius2: f64,
}

impl QueryBounds {
    /// The bounds of `sweep` (segments `u`, `v`) as an object of `class`;
    /// `None` for a class that is not a sweep's or a sweep of no size.
    pub(super) fn of(class: PrimitiveClass, sweep: &SweepShape, u: &[Coeff], v: &[Coeff]) -> Option<QueryBounds> {
        let mut size = box_size(&sweep.bbox);
        if !(size > 0.0 && size.is_finite()) {
            size = u
                .iter()
                .chain(v)
                .fold(0.0f64, |m, c| m.max(c.min.abs()).max(c.max.abs()));
            size = size.max(sweep.length.abs());
        }
        if !(size > 0.0 && size.is_finite()) {
            return None;
        }
        let b = &sweep.bbox;
        let pad = 1e-9 * size;
        let boxed = b.xmin < b.xmax && b.zmin < b.zmax;
        let (lo, hi) = match class {
            PrimitiveClass::Translation | PrimitiveClass::Conic => (
                DVec3::new(b.xmin, b.ymin, b.zmin) - pad,
                DVec3::new(b.xmax, b.ymax, b.zmax) + pad,
            ),
            PrimitiveClass::Rotation => {
                let r = b.xmin.abs().max(b.xmax.abs()).max(b.ymin.abs()).max(b.ymax.abs());
                (DVec3::new(-r, -r, b.zmin) - pad, DVec3::new(r, r, b.zmax) + pad)
            }
            _ => return None,
        };
        let (centre, radius2) = if boxed {
            (0.5 * (lo + hi), 0.25 * (hi - lo).length_squared())
        } else {
            (DVec3::ZERO, 4.0 * size * size)
        };
        Some(QueryBounds {
            class,
            bbox: *b,
            size,
            boxed,
            lo,
            hi,
            centre,
            radius2,
        })
    }

    /// The bounds to keep for `sweep` as an object of `class`: those whose
    /// size is its box's, which then depend on the box alone (a sweep
    /// without one takes its size from its segments, which may change
    /// under the same box).
    pub(super) fn kept(class: PrimitiveClass, sweep: &SweepShape) -> Option<QueryBounds> {
        let n = sweep.segment.min(sweep.u.len()).min(sweep.v.len()).min(MAXSEGMENTS);
        QueryBounds::of(class, sweep, &sweep.u[..n], &sweep.v[..n]).filter(|b| b.size == box_size(&b.bbox))
    }

    /// Were these bounds made from this box, for this class? (`==` of
    /// each coordinate, as `BoundingBox`'s, joined by `&`: asked of every
    /// ray, without a branch for each.)
    #[inline(always)]
    pub(super) fn holds(&self, class: PrimitiveClass, bbox: &BoundingBox) -> bool {
        let (a, b) = (&self.bbox, bbox);
        self.class == class
            && (a.xmin == b.xmin)
                & (a.xmax == b.xmax)
                & (a.ymin == b.ymin)
                & (a.ymax == b.ymax)
                & (a.zmin == b.zmin)
                & (a.zmax == b.zmax)
    }
}

#[cfg(test)]
mod tests {
    use super::super::{star_points, translation_sweep, Sweep, SweepCache};
    use super::*;
    use crate::options::Options;
    use crate::types::Ray;

    /// A sweep whose box was never filled (all zeros) takes its size from
    /// its segments and is still met; one with no segments at all is not.
    #[test]
    fn a_sweep_without_a_box_takes_its_size_from_its_segments() {
        let filled = translation_sweep(star_points(8, 1.0, 0.6), crate::types::CurveKind::Bspline, 1.0);
        // The cache made for the filled box: its cap grid holds for the
        // boxless sweep's segments, its bounds not for its box.
        let cache = SweepCache::new(PrimitiveClass::Translation, &filled);
        let boxless = SweepShape {
            bbox: BoundingBox::default(),
            ..filled.clone()
        };
        assert!(cache
            .as_ref()
            .is_some_and(|c| !c.fits(PrimitiveClass::Translation, &boxless)));
        let meet = |shape: &SweepShape, ray: &Ray, opts: &Options| {
            let sweep = Sweep {
                class: PrimitiveClass::Translation,
                shape,
                cache: cache.as_ref(),
            };
            sweep.intersect(ray, 1e-9, opts, &mut 0)
        };
        let b = QueryBounds::of(PrimitiveClass::Translation, &boxless, &boxless.u, &boxless.v).expect("a size");
        assert_eq!(
            b.size, 1.0,
            "the largest |coordinate| of the segments' ranges and the length"
        );
        assert!(!b.boxed);
        assert_eq!(
            QueryBounds::kept(PrimitiveClass::Translation, &boxless),
            None,
            "no box, nothing kept"
        );
        // Segments that are points, swept nowhere: no size, no bounds.
        let point = SweepShape {
            u: vec![Coeff::default(); boxless.u.len()],
            v: vec![Coeff::default(); boxless.v.len()],
            length: 0.0,
            ..boxless.clone()
        };
        assert_eq!(
            QueryBounds::of(PrimitiveClass::Translation, &point, &point.u, &point.v),
            None
        );
        let ray = Ray::new(DVec3::new(0.0, -5.0, 0.5), DVec3::Y);
        let opts = Options::default();
        let hit = meet(&boxless, &ray, &opts).expect("met");
        let want = meet(&filled, &ray, &opts).expect("met");
        assert!((hit.t - want.t).abs() < 1e-9, "{} {}", hit.t, want.t);
        let empty = SweepShape {
            u: vec![],
            v: vec![],
            segment: 0,
            ..boxless
        };
        assert_eq!(meet(&empty, &ray, &opts), None);
    }

    /// What a ray takes from a box, pinned on one box for each kind: the
    /// size, the box padded by 10⁻⁹ of it, the sphere about its centre;
    /// a box flat in x or z is not a box.
    #[test]
    fn query_bounds_of_a_box() {
        let mut sw = translation_sweep(star_points(8, 1.0, 0.6), crate::types::CurveKind::Bspline, 1.0);
        sw.bbox = BoundingBox {
            xmin: -1.0,
            xmax: 2.0,
            ymin: -3.0,
            ymax: 1.0,
            zmin: 0.5,
            zmax: 4.0,
        };
        let (u, v) = (sw.u.clone(), sw.v.clone());
        let pad = 4e-9;
        let t = QueryBounds::of(PrimitiveClass::Translation, &sw, &u, &v).unwrap();
        assert_eq!((t.size, t.boxed), (4.0, true));
        assert_eq!(t.lo, DVec3::new(-1.0, -3.0, 0.5) - pad);
        assert_eq!(t.hi, DVec3::new(2.0, 1.0, 4.0) + pad);
        assert_eq!(t.centre, 0.5 * (t.lo + t.hi));
        assert_eq!(t.radius2, 0.25 * (t.hi - t.lo).length_squared());
        assert!((t.radius2 - 0.25 * (9.0 + 16.0 + 12.25)).abs() < 1e-7);
        let r = QueryBounds::of(PrimitiveClass::Rotation, &sw, &u, &v).unwrap();
        assert_eq!(r.lo, DVec3::new(-3.0, -3.0, 0.5) - pad);
        assert_eq!(r.hi, DVec3::new(3.0, 3.0, 4.0) + pad);
        assert_eq!(QueryBounds::of(PrimitiveClass::Sphere, &sw, &u, &v), None);
        for flat in [(1.0, 1.0, 0.5, 4.0), (-1.0, 2.0, 4.0, 4.0)] {
            let mut f = sw.clone();
            (f.bbox.xmin, f.bbox.xmax, f.bbox.zmin, f.bbox.zmax) = flat;
            let b = QueryBounds::of(PrimitiveClass::Translation, &f, &u, &v).unwrap();
            assert!(!b.boxed, "{flat:?}");
            assert_eq!((b.centre, b.radius2), (DVec3::ZERO, 4.0 * b.size * b.size), "{flat:?}");
        }
    }
}

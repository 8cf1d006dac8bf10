//! Structures over the objects, so that a ray tests the objects near it
//! and not every object of the table: the port's extension. The thesis
//! names both remedies (§2.1.2, OCR lines 210–275): bounding volumes
//! gathered into clusters tested first (Fig. 2.12), here a bounding volume
//! hierarchy ([`Bvh`]), and space subdivision after Glassner 1984 (Fig.
//! 2.15–2.16), here the octree whose node lookup is LISTING 1's `findnode`
//! ([`Octree`]). The original's loop over the table stays the third
//! choice and the default below [`THRESHOLD`] objects (`--accel`).
//!
//! A structure knows boxes, not objects: each object's box over every
//! time a sample can have, and for an object that moves far against its
//! size its box over each segment of those times ([`Bounds`], made by
//! `crate::motion::object_bounds`), by index. What it answers is which
//! objects a ray at a time of one segment may meet, in an order that lets
//! a query stop early ([`Structure::walk`]); the objects themselves are
//! tested by the intersection seam (`crate::intersect`), which keeps the
//! loop's rule of the nearest hit (the lower index of equal distances).

mod bvh;
mod octree;
mod quad;
mod time;

use std::ops::ControlFlow;

pub use bvh::Bvh;
pub use octree::{findnode_digit, Found, Octree, MAX_DEPTH};
pub use time::{Bounds, Hierarchy, Segments, Timed, USE_UNION};

pub use crate::options::{Accel, THRESHOLD};
use crate::types::{BoundingBox, DVec3, Ray};

/// A box as the structures keep it: its least and greatest corners.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub lo: DVec3,
    pub hi: DVec3,
}

impl Aabb {
    /// The box holding nothing.
    pub const EMPTY: Aabb = Aabb {
        lo: DVec3::INFINITY,
        hi: DVec3::NEG_INFINITY,
    };

    /// The box holding everything: what an object whose bounds are not
    /// finite gets, so that every ray tests it, as the loop does.
    pub const ALL: Aabb = Aabb {
        lo: DVec3::NEG_INFINITY,
        hi: DVec3::INFINITY,
    };

    /// The box of `b`; [`Aabb::ALL`] for one with a NaN.
    pub fn of(b: &BoundingBox) -> Aabb {
        let a = Aabb {
            lo: DVec3::new(b.xmin, b.ymin, b.zmin),
            hi: DVec3::new(b.xmax, b.ymax, b.zmax),
        };
        if a.lo.is_nan() || a.hi.is_nan() {
            Aabb::ALL
        } else {
            a
        }
    }

    pub fn union(&self, b: &Aabb) -> Aabb {
        Aabb {
            lo: self.lo.min(b.lo),
            hi: self.hi.max(b.hi),
        }
    }

    pub fn is_empty(&self) -> bool {
        self.lo.x > self.hi.x || self.lo.y > self.hi.y || self.lo.z > self.hi.z
    }

    /// Half the surface area (what the surface area heuristic weighs by);
    /// 0 for an empty box.
    pub fn half_area(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        let d = self.hi - self.lo;
        d.x * d.y + d.y * d.z + d.z * d.x
    }

    pub fn centre(&self) -> DVec3 {
        0.5 * (self.lo + self.hi)
    }

    /// Do the two closed boxes share a point?
    pub fn overlaps(&self, b: &Aabb) -> bool {
        self.lo.cmple(b.hi).all() && b.lo.cmple(self.hi).all()
    }
}

/// A ray made ready for many box tests: its origin and the reciprocals of
/// its direction.
#[derive(Clone, Copy, Debug)]
pub struct BoxRay {
    pub origin: DVec3,
    pub dir: DVec3,
    inv: DVec3,
}

impl BoxRay {
    pub fn new(ray: &Ray) -> BoxRay {
        // −0 as +0: a direction component of 0 then always has the
        // reciprocal +∞ (see [`BoxRay::span`]).
        let dir = ray.dir + DVec3::ZERO;
        BoxRay {
            origin: ray.origin,
            dir: ray.dir,
            inv: dir.recip(),
        }
    }

    /// The slab test: the part `[enter, exit]` of `[t0, t1]` in which the
    /// ray is inside the closed box `b`, or `None`. A direction component
    /// of 0 has the reciprocal +∞, so its slab's quotients are ±∞ (all of
    /// t, or none) or, for an origin on one of its faces (a ray along the
    /// face, which is in the closed box), NaN, which bounds no t: every
    /// comparison with a NaN is false, and each `if` below then keeps what
    /// it had (the usual robust form, as pbrt's `Bounds3::IntersectP`).
    #[inline(always)]
    pub fn span(&self, b: &Aabb, t0: f64, t1: f64) -> Option<(f64, f64)> {
        let (mut enter, mut exit) = (t0, t1);
        for k in 0..3 {
            let ta = (b.lo[k] - self.origin[k]) * self.inv[k];
            let tb = (b.hi[k] - self.origin[k]) * self.inv[k];
            let (near, far) = if ta > tb { (tb, ta) } else { (ta, tb) };
            enter = if near > enter { near } else { enter };
            exit = if far < exit { far } else { exit };
        }
        (enter <= exit).then_some((enter, exit))
    }
}

/// What a query does with an object the ray may meet, given to
/// [`Structure::walk`]: `Continue(limit)` goes on, skipping every object
/// whose box the ray enters only beyond `limit` (the nearest hit so far,
/// or the shadow ray's end); `Break` stops the walk.
pub type Step = ControlFlow<(), f64>;

/// Visits each of `objects` (an index and its box) whose box the ray
/// meets between `tmin` and the limit, the limit updated by each visit:
/// a leaf's or a cell's objects, in a walk.
#[inline(always)]
fn visit_each<'b>(
    ray: &BoxRay,
    tmin: f64,
    limit: &mut f64,
    objects: impl Iterator<Item = (usize, &'b Aabb)>,
    visit: &mut impl FnMut(usize) -> Step,
) -> ControlFlow<()> {
    for (i, b) in objects {
        if ray.span(b, tmin, *limit).is_some() {
            *limit = visit(i)?;
        }
    }
    ControlFlow::Continue(())
}

/// What a walk keeps of the nodes it has still to visit, kept by the
/// walker from one walk to the next (a hierarchy's far children).
#[derive(Clone, Debug, Default)]
pub struct WalkStack(Vec<(u32, f32)>);

/// A structure over the objects' boxes.
#[derive(Clone, Debug, PartialEq)]
pub enum Structure {
    Bvh(Hierarchy),
    Octree(Octree),
}

impl Structure {
    /// The structure `accel` names (after [`Accel::resolve`]) over the
    /// objects' boxes, by index; `None` for the loop. The hierarchy keeps
    /// the boxes over the time segments; the octree, the thesis's, the
    /// boxes over all times.
    pub fn build(accel: Accel, bounds: &Bounds) -> Option<Structure> {
        match accel.resolve(bounds.whole.len()) {
            Accel::Bvh => Some(Structure::Bvh(Hierarchy::build(&Timed::of(bounds), bounds.runs))),
            Accel::Octree => {
                let boxes: Vec<Aabb> = bounds.whole.iter().map(Aabb::of).collect();
                Some(Structure::Octree(Octree::build(&boxes)))
            }
            Accel::None | Accel::Auto => None,
        }
    }

    /// The time segment of film time `time` ([`Segments::of`]), which a
    /// walk of a ray at that time is given.
    #[inline]
    pub fn segment(&self, time: f64) -> usize {
        match self {
            Structure::Bvh(h) => h.segment(time),
            Structure::Octree(_) => 0,
        }
    }

    /// Calls `visit` with each object whose box `ray` meets between `tmin`
    /// and the limit, near boxes before far ones as the structure can, the
    /// limit starting at `limit` and then the last `visit` returned
    /// ([`Step`]). An object may be visited more than once (an octree's
    /// object straddles cells), and one whose box the ray passes within
    /// about a millionth of its distance may be visited too (the
    /// hierarchy's single-precision test, `quad`). Every object whose box
    /// the ray meets at some t in `[tmin, limit]`, the limit as it stands
    /// when the walk reaches that t, is visited: its box over the time
    /// segment `segment` ([`Structure::segment`] of the ray's time) where
    /// it has one.
    pub fn walk(
        &self,
        ray: &Ray,
        tmin: f64,
        limit: f64,
        segment: usize,
        stack: &mut WalkStack,
        visit: impl FnMut(usize) -> Step,
    ) -> ControlFlow<()> {
        match self {
            Structure::Bvh(h) => {
                let (tree, segment) = h.tree(segment);
                tree.walk(&BoxRay::new(ray), tmin, limit, segment, &mut stack.0, visit)
            }
            Structure::Octree(o) => o.walk(&BoxRay::new(ray), tmin, limit, visit),
        }
    }

    /// Every object whose box `ray` meets beyond `tmin` (and any
    /// [`Structure::walk`] visits besides) in time segment `segment`, into
    /// `out`, ascending, each once.
    pub fn candidates(&self, ray: &Ray, tmin: f64, segment: usize, stack: &mut WalkStack, out: &mut Vec<usize>) {
        out.clear();
        let _ = self.walk(ray, tmin, f64::INFINITY, segment, stack, |i| {
            out.push(i);
            ControlFlow::Continue(f64::INFINITY)
        });
        out.sort_unstable();
        out.dedup();
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The cube of half-side `r` about `c`.
    pub(crate) fn cube(c: [f64; 3], r: f64) -> Aabb {
        let c = DVec3::from_array(c);
        Aabb { lo: c - r, hi: c + r }
    }

    /// Degenerate bounds: objects all at one point, of no size, many at
    /// one point with a size, and boxes that are not finite, build in
    /// each structure; each visits every object whose box a ray through
    /// them meets.
    #[test]
    fn degenerate_bounds_build_and_are_walked() {
        let sets = [
            vec![cube([1.0, 2.0, 3.0], 0.0); 100],
            vec![cube([1.0, 2.0, 3.0], 0.5); 50],
            (0..30)
                .map(|i| {
                    if i % 7 == 0 {
                        Aabb::ALL
                    } else {
                        cube([i as f64, 2.0, 3.0], 0.0)
                    }
                })
                .collect(),
            vec![Aabb::ALL; 3],
        ];
        let ray = Ray::new(DVec3::new(-50.0, 2.0, 3.0), DVec3::X);
        for boxes in sets {
            let through: Vec<usize> = (0..boxes.len())
                .filter(|&i| BoxRay::new(&ray).span(&boxes[i], 0.0, f64::INFINITY).is_some())
                .collect();
            assert!(!through.is_empty());
            for s in [
                Structure::Bvh(Hierarchy::of(Bvh::build(&boxes))),
                Structure::Octree(Octree::build(&boxes)),
            ] {
                let mut v = Vec::new();
                s.candidates(&ray, 0.0, 0, &mut WalkStack::default(), &mut v);
                assert_eq!(v, through, "{s:?}");
            }
        }
        assert!(Bvh::build(&[]).is_empty());
        assert!(Octree::build(&[]).is_empty());
    }

    fn unit() -> Aabb {
        Aabb {
            lo: DVec3::ZERO,
            hi: DVec3::ONE,
        }
    }

    #[test]
    fn slabs_of_a_unit_box() {
        let r = |o: [f64; 3], d: [f64; 3]| BoxRay::new(&Ray::new(DVec3::from_array(o), DVec3::from_array(d)));
        let b = unit();
        assert_eq!(
            r([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0]).span(&b, 0.0, 9.0),
            Some((1.0, 2.0))
        );
        // Cut by the interval.
        assert_eq!(
            r([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0]).span(&b, 1.5, 1.75),
            Some((1.5, 1.75))
        );
        assert_eq!(r([-1.0, 0.5, 0.5], [1.0, 0.0, 0.0]).span(&b, 0.0, 0.5), None);
        // Parallel outside, parallel inside, along a face (0 · ∞ = NaN).
        assert_eq!(r([-1.0, 2.0, 0.5], [1.0, 0.0, 0.0]).span(&b, 0.0, 9.0), None);
        assert!(r([-1.0, 1.0, 0.5], [1.0, 0.0, 0.0]).span(&b, 0.0, 9.0).is_some());
        assert!(r([-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]).span(&b, 0.0, 9.0).is_some());
        assert!(r([-1.0, 0.0, 0.0], [1.0, -0.0, 0.0]).span(&b, 0.0, 9.0).is_some());
        assert!(r([-1.0, 1.0, 1.0], [1.0, -0.0, 0.0]).span(&b, 0.0, 9.0).is_some());
        assert!(r([-1.0, 1.0, 0.5], [1.0, -0.0, 0.0]).span(&b, 0.0, 9.0).is_some());
        assert!(r([0.5, 0.5, 1.0], [0.0, 0.0, -1.0]).span(&b, 0.0, 9.0).is_some());
        // Behind.
        assert_eq!(r([2.0, 0.5, 0.5], [1.0, 0.0, 0.0]).span(&b, 0.0, 9.0), None);
        // Everything.
        assert!(r([2.0, 0.5, 0.5], [1.0, 0.0, 0.0]).span(&Aabb::ALL, 0.0, 9.0).is_some());
    }

    #[test]
    fn auto_is_the_loop_below_the_threshold() {
        assert_eq!(Accel::Auto.resolve(THRESHOLD - 1), Accel::None);
        assert_eq!(Accel::Auto.resolve(THRESHOLD), Accel::Bvh);
        assert_eq!(Accel::Octree.resolve(1), Accel::Octree);
        assert_eq!(Accel::None.resolve(1_000_000), Accel::None);
    }

    #[test]
    fn a_nan_box_holds_everything() {
        let mut b = BoundingBox::EMPTY;
        b.xmin = f64::NAN;
        assert_eq!(Aabb::of(&b), Aabb::ALL);
        assert!(unit().overlaps(&Aabb::ALL));
        assert_eq!(Aabb::EMPTY.half_area(), 0.0);
        assert_eq!(unit().half_area(), 3.0);
    }
}

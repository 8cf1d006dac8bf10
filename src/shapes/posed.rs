//! An object as a ray meets it at one instant: the dispatch from the
//! object's shape to its intersection.

use super::blob::query as blob_query;
use super::patch::query as patch_query;
use super::sweep::Sweep;
use super::ShapeCache;
use super::{
    block_blocks, bounding_sphere_hit, intersect_block, intersect_cylinder, intersect_prism, intersect_sphere,
};
use crate::options::Options;
use crate::types::{LocalHit, ObjectRecord, Pose, Ray, Shape, SweepShape};

/// An object as a ray meets it at one instant: its record, the shape it
/// has then (its own, or its contour of the moment when it deforms), the
/// cache made with that shape ([`ShapeCache`]; `None` for a contour of the
/// moment, whose caps are then solved and whose bounds are made per ray;
/// a patch of the moment's pieces made at the instant) and where it
/// stands then.
#[derive(Clone, Copy, Debug)]
pub struct Posed<'a> {
    pub obj: &'a ObjectRecord,
    pub shape: &'a Shape,
    pub cache: Option<&'a ShapeCache>,
    pub pose: &'a Pose,
}

impl Posed<'_> {
    /// Does the ray reach the object's bounding sphere (`sphereo` at the
    /// pose, `radius`) beyond `tmin`? A cheap rejection before any shape's
    /// own test (§2.1.2 (1)(b), the bounding volume).
    pub fn meets_bounding_sphere(&self, ray: &Ray, tmin: f64) -> bool {
        bounding_sphere_hit(self.pose.sphereo, self.obj.radius, ray, tmin)
    }

    /// The hit of a world ray with the shape at the pose, without the
    /// bounding-sphere test: the ray into the local frame, the shape's own
    /// intersection. Returns the local hit (its `t` is the world
    /// parameter). `searched` counts the polynomials a sweep searched
    /// ([`Sweep::intersect`]).
    pub fn intersect(&self, ray: &Ray, tmin: f64, opts: &Options, searched: &mut u64) -> Option<LocalHit> {
        let local = ray.transformed(&self.pose.inverse);
        match self.shape {
            Shape::Sphere => intersect_sphere(self.obj.radius, &local, tmin),
            Shape::Block { lengths } => intersect_block(*lengths, &local, tmin),
            Shape::Cylinder {
                cylradius, top, bottom, ..
            } => intersect_cylinder(*cylradius, *bottom, *top, &local, tmin),
            Shape::Prism { height, vertex, .. } => intersect_prism(vertex, *height, &local, tmin),
            Shape::Sweep(sw) => self.sweep(sw).intersect(&local, tmin, opts, searched),
            Shape::Blob(_) | Shape::Patch(_) => self.of_points(&local, tmin, f64::INFINITY, false, opts, searched),
        }
    }

    /// Does the shape (as in [`Posed::intersect`]) stand on the ray at
    /// some t with `tmin` < t < `tmax`? The shadow ray's question: a sweep
    /// answers it at its first hit before `tmax` ([`Sweep::blocks`]), as
    /// blobs and patches do, a block by its slabs, the other shapes by
    /// their nearest hit. The same
    /// answer as `intersect(..).is_some_and(|h| h.t < tmax)`.
    pub fn blocks(&self, ray: &Ray, tmin: f64, tmax: f64, opts: &Options, searched: &mut u64) -> bool {
        match self.shape {
            Shape::Sweep(sw) => {
                let local = ray.transformed(&self.pose.inverse);
                self.sweep(sw).blocks(&local, tmin, tmax, opts, searched)
            }
            Shape::Block { lengths } => block_blocks(*lengths, &ray.transformed(&self.pose.inverse), tmin, tmax),
            Shape::Blob(_) | Shape::Patch(_) => {
                let local = ray.transformed(&self.pose.inverse);
                self.of_points(&local, tmin, tmax, true, opts, searched)
                    .is_some_and(|h| h.t < tmax)
            }
            _ => self.intersect(ray, tmin, opts, searched).is_some_and(|h| h.t < tmax),
        }
    }

    /// The sweep `sw` (this object's shape) as its driver meets it.
    #[inline]
    fn sweep<'s>(&'s self, sw: &'s SweepShape) -> Sweep<'s> {
        Sweep {
            class: self.obj.class,
            shape: sw,
            cache: self.cache.and_then(ShapeCache::sweep),
        }
    }

    /// A blob's or a patch's hit with the ray `local` in its frame: the
    /// nearest beyond `tmin`, or (`first`) the first found before `tmax`.
    /// Out of line, so that the dispatch of the thesis's shapes stays the
    /// size it was where it is inlined (the shadow rays' loop).
    #[inline(never)]
    fn of_points(
        &self,
        local: &Ray,
        tmin: f64,
        tmax: f64,
        first: bool,
        opts: &Options,
        searched: &mut u64,
    ) -> Option<LocalHit> {
        let (radius, cache) = (self.obj.radius, self.cache);
        match self.shape {
            Shape::Blob(b) => blob_query(
                b,
                cache.and_then(ShapeCache::blob),
                radius,
                local,
                tmin,
                tmax,
                opts,
                searched,
            ),
            Shape::Patch(p) => {
                let cache = cache.and_then(ShapeCache::patch);
                patch_query(p, cache, radius, local, tmin, tmax, first, searched)
            }
            _ => None,
        }
    }
}

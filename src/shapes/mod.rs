//! Reconstructed base: the primitive intersections of the base program
//! `Raytrace` (Ch. 4 (e): sphere, block, cylinder, prism, sweep object);
//! and the port's extension, the objects §6.2 names next ([`blob`],
//! [`patch`]).
//! The thesis does not print them; they follow the usual closed forms
//! (Rogers 1985, the thesis's reference for the static program), in each
//! object's local frame: the ray is carried by the object's `inverse`, the
//! hit back by its `transfm`. Both are rigid, so the ray parameter is the
//! same in both frames.
//!
//! Every function returns the nearest hit with parameter greater than
//! `tmin`, entering or leaving, with the unit OUTWARD normal; the shader
//! decides which side the ray came from.
//!
//! Every function works on the ray [`Near`] the object: a ray that starts
//! outside the object's bounds is re-based at its closest approach to
//! their centre, and the distance is added back to the hit. So no
//! coefficient of a quadratic, cubic or sextic carries the eye's distance
//! (squared, in the constant terms), and an object seen from 10⁶ units
//! away is intersected as exactly as from 10 (the port's extension; the
//! thesis's eye is never far, DEVIATIONS D20).

pub mod blob;
pub mod patch;
mod posed;
pub mod sweep;

pub use blob::{blob_box, blob_reach, BlobCache};
pub use patch::{patch_box, patch_reach, PatchCache};
pub use posed::Posed;
pub use sweep::SweepCache;

use std::sync::Arc;

use crate::scene::Scene;
use crate::types::{BoundingBox, DVec3, LocalHit, ObjectRecord, PrimitiveClass, Ray, Shape};

/// What is prepared for an object's own shape before any ray, owned by
/// the render: a sweep's ([`SweepCache`]), a blob's hierarchy of
/// components ([`BlobCache`]), a patch's pieces ([`PatchCache`]).
#[derive(Clone, Debug, PartialEq)]
pub enum ShapeCache {
    Sweep(SweepCache),
    Blob(BlobCache),
    Patch(PatchCache),
}

impl ShapeCache {
    /// A sweep's cache.
    pub fn sweep(&self) -> Option<&SweepCache> {
        match self {
            ShapeCache::Sweep(c) => Some(c),
            _ => None,
        }
    }

    /// A blob's hierarchy.
    pub fn blob(&self) -> Option<&BlobCache> {
        match self {
            ShapeCache::Blob(c) => Some(c),
            _ => None,
        }
    }

    /// A patch's pieces.
    pub fn patch(&self) -> Option<&PatchCache> {
        match self {
            ShapeCache::Patch(c) => Some(c),
            _ => None,
        }
    }

    /// The cache of a blob or a patch: made for one at rest once, for an
    /// in-between at each instant (a sweep's contour of the moment takes
    /// none).
    pub fn of_moment(shape: &Shape) -> Option<ShapeCache> {
        match shape {
            Shape::Blob(b) => Some(ShapeCache::Blob(BlobCache::new(b))),
            Shape::Patch(p) => Some(ShapeCache::Patch(PatchCache::new(p))),
            _ => None,
        }
    }
}

/// The caches of `scene.objects[i]`, in their order: the sweeps' (made
/// after their boxes are final, `prepare_sweeps` then `widen_tbox`;
/// objects of one contour, box and class share one), the blobs' and
/// patches' ([`ShapeCache::of_moment`]); `None` for the other objects.
pub fn prepare_caches(scene: &Scene) -> Vec<Option<Arc<ShapeCache>>> {
    let sweeps = sweep::prepare_caches(scene);
    scene
        .objects
        .iter()
        .zip(sweeps)
        .map(|(obj, sweep)| sweep.or_else(|| ShapeCache::of_moment(&obj.shape).map(Arc::new)))
        .collect()
}

/// A ray taken near an object: the same line from another origin,
/// `ray.origin = original.at(shift)`, and `tmin` measured from there.
#[derive(Clone, Copy, Debug)]
pub struct Near {
    pub ray: Ray,
    pub tmin: f64,
    pub shift: f64,
}

impl Near {
    /// `ray` re-based at its closest approach to `centre` when it starts
    /// outside the sphere of radius √`radius2` about `centre` and runs
    /// toward it (the square, so that no root is taken per ray);
    /// unchanged (shift 0) when it starts inside, so a ray leaving a
    /// surface keeps its own bits. The closest approach is a well-
    /// conditioned product (no difference of squares), and from it every
    /// point of the object is within `radius` plus the ray's offset.
    #[inline(always)]
    pub fn of(ray: &Ray, tmin: f64, centre: DVec3, radius2: f64) -> Near {
        let oc = ray.origin - centre;
        let unchanged = Near {
            ray: *ray,
            tmin,
            shift: 0.0,
        };
        if oc.length_squared() <= radius2 {
            return unchanged;
        }
        let shift = -oc.dot(ray.dir) / ray.dir.length_squared();
        // Not `is_finite`, which this target compiles to a classification.
        if !(shift > 0.0 && shift < f64::INFINITY) {
            return unchanged;
        }
        Near {
            ray: Ray::new(ray.at(shift), ray.dir),
            tmin: tmin - shift,
            shift,
        }
    }

    /// [`Near::of`] the sphere of radius `reach` about the local origin,
    /// for a ray whose numbers are all finite and whose direction is not
    /// zero (`None` otherwise: such a ray meets nothing): the start of a
    /// blob's and a patch's search.
    pub fn about_origin(ray: &Ray, tmin: f64, reach: f64) -> Option<Near> {
        let fit = ray.origin.is_finite() && ray.dir.is_finite() && ray.dir != DVec3::ZERO && !tmin.is_nan();
        fit.then(|| Near::of(ray, tmin, DVec3::ZERO, reach * reach))
    }

    /// A hit on the re-based ray as a hit on the original: the distance
    /// added back (the point is the same).
    pub fn back(&self, hit: Option<LocalHit>) -> Option<LocalHit> {
        hit.map(|h| LocalHit {
            t: h.t + self.shift,
            ..h
        })
    }
}

/// A sphere of `radius` about the local origin.
///
/// Reconstructed: |o + t d|² = r², a quadratic in t (on the ray [`Near`]
/// the sphere).
pub fn intersect_sphere(radius: f64, ray: &Ray, tmin: f64) -> Option<LocalHit> {
    let near = Near::of(ray, tmin, DVec3::ZERO, radius * radius);
    near.back(sphere_hit(radius, &near.ray, near.tmin))
}

fn sphere_hit(radius: f64, ray: &Ray, tmin: f64) -> Option<LocalHit> {
    let a = ray.dir.length_squared();
    let half_b = ray.origin.dot(ray.dir);
    let c = ray.origin.length_squared() - radius * radius;
    let disc = half_b * half_b - a * c;
    if disc < 0.0 || a == 0.0 {
        return None;
    }
    let sq = disc.sqrt();
    // The numerically stable pair of roots: q = −(b/2 + sign(b/2)·√disc).
    let q = -(half_b + half_b.signum() * sq);
    let (mut t0, mut t1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    if t0 > t1 {
        std::mem::swap(&mut t0, &mut t1);
    }
    let t = if t0 > tmin {
        t0
    } else if t1 > tmin {
        t1
    } else {
        return None;
    };
    let point = ray.at(t);
    Some(LocalHit {
        t,
        point,
        normal: point / radius,
    })
}

/// The hit of a ray with a convex solid given as the intersection of
/// half-spaces n·p ≤ h (n unit, outward): the Cyrus–Beck clip. Blocks and
/// prisms both use it. `plane(i)` is plane i's (n, h), i < `count`.
fn intersect_convex(ray: &Ray, tmin: f64, count: usize, plane: impl Fn(usize) -> (DVec3, f64)) -> Option<LocalHit> {
    let planes = (0..count).map(|i| {
        let (n, h) = plane(i);
        (n.dot(ray.dir), h - n.dot(ray.origin))
    });
    let (t, i) = clip(tmin, planes)?;
    Some(LocalHit {
        t,
        point: ray.at(t),
        normal: plane(i).0,
    })
}

/// The clip of [`intersect_convex`], given each plane's n·d and h − n·o:
/// the t of the hit beyond `tmin` and the index of its plane.
fn clip(tmin: f64, planes: impl Iterator<Item = (f64, f64)>) -> Option<(f64, usize)> {
    let mut c = Clip::new();
    for (i, (denom, dist)) in planes.enumerate() {
        if !c.plane(i, denom, dist) {
            return None;
        }
    }
    c.hit(tmin)
}

/// The state of a Cyrus–Beck clip: the latest entry and the earliest exit
/// so far, and their planes.
struct Clip {
    t_enter: f64,
    t_exit: f64,
    i_enter: usize,
    i_exit: usize,
}

impl Clip {
    fn new() -> Self {
        Clip {
            t_enter: f64::NEG_INFINITY,
            t_exit: f64::INFINITY,
            i_enter: 0,
            i_exit: 0,
        }
    }

    /// Plane `i` with n·d = `denom` and h − n·o = `dist`; false when the
    /// ray runs parallel to it outside its half-space (no hit).
    #[inline(always)]
    fn plane(&mut self, i: usize, denom: f64, dist: f64) -> bool {
        if denom == 0.0 {
            return dist >= 0.0 || dist.is_nan();
        }
        let t = dist / denom;
        if denom < 0.0 {
            if t > self.t_enter {
                self.t_enter = t;
                self.i_enter = i;
            }
        } else if t < self.t_exit {
            self.t_exit = t;
            self.i_exit = i;
        }
        true
    }

    /// The hit beyond `tmin`: the entry, else the exit.
    fn hit(&self, tmin: f64) -> Option<(f64, usize)> {
        if self.t_enter > self.t_exit {
            None
        } else if self.t_enter > tmin {
            Some((self.t_enter, self.i_enter))
        } else if self.t_exit > tmin && self.t_exit.is_finite() {
            Some((self.t_exit, self.i_exit))
        } else {
            None
        }
    }
}

/// The outward normals of a block's faces, in [`intersect_block`]'s order.
const BLOCK_NORMALS: [DVec3; 6] = [DVec3::X, DVec3::NEG_X, DVec3::Y, DVec3::NEG_Y, DVec3::Z, DVec3::NEG_Z];

/// A box centred on the local origin with edge lengths `lengths`.
///
/// Reconstructed: the slab test, as a convex clip of six planes.
///
/// The six planes ±x = h.x, ±y = h.y, ±z = h.z taken in that order, as
/// `intersect_convex` would take them, with its dot products written out:
/// n·d and n·o of an axis normal are ±d_k and ±o_k exactly, so the hits are
/// the same to the bit, without the products by zero. (Taken a pair of
/// faces at a time with an early exit, as [`block_blocks`] is, it took 14 %
/// more instructions on fig5_3: most of these rays hit.)
// Inlined into its caller: the ray it is given was just made there (the
// local frame's), and read back through memory here its halves missed
// the stores' forwarding (18 % of this function's time, measured).
#[inline(always)]
pub fn intersect_block(lengths: DVec3, ray: &Ray, tmin: f64) -> Option<LocalHit> {
    let h = lengths * 0.5;
    let near = Near::of(ray, tmin, DVec3::ZERO, h.length_squared());
    let (ray, tmin) = (&near.ray, near.tmin);
    let (o, d) = (ray.origin, ray.dir);
    // (n·d, h − n·o) of ±x, ±y, ±z.
    let planes = [
        (d.x, h.x - o.x),
        (-d.x, h.x + o.x),
        (d.y, h.y - o.y),
        (-d.y, h.y + o.y),
        (d.z, h.z - o.z),
        (-d.z, h.z + o.z),
    ];
    let (t, i) = clip(tmin, planes.into_iter())?;
    near.back(Some(LocalHit {
        t,
        point: ray.at(t),
        normal: BLOCK_NORMALS[i],
    }))
}

/// What one pair of a block's faces (±k at half-length `hk`) does to a ray
/// with direction component `dk` and origin component `ok`, as
/// [`Clip::plane`] takes the two planes: the +k face with n·d = dk and
/// h − n·o = hk − ok, the −k face with −dk and hk + ok.
enum Slab {
    /// Parallel to both, outside one of them: no hit.
    Outside,
    /// Parallel to both and between them, or a NaN direction (no quotient
    /// compares): no bound.
    Open,
    /// The entry and exit quotients.
    Span(f64, f64),
}

#[inline(always)]
fn slab(dk: f64, ok: f64, hk: f64) -> Slab {
    let (plus, minus) = (hk - ok, hk + ok);
    if dk == 0.0 {
        // `dist >= 0 || dist.is_nan()` for both faces.
        return if plus < 0.0 || minus < 0.0 {
            Slab::Outside
        } else {
            Slab::Open
        };
    }
    let (tp, tm) = (plus / dk, minus / -dk);
    if dk < 0.0 {
        Slab::Span(tp, tm)
    } else if dk > 0.0 {
        Slab::Span(tm, tp)
    } else {
        Slab::Open
    }
}

/// Does the block of [`intersect_block`] stand on the ray at some t with
/// `tmin` < t < `tmax`? The shadow ray's question, answered as
/// `intersect_block(..).is_some_and(|h| h.t < tmax)` is, to the bit: the
/// same re-based ray ([`Near`]), the same quotients of the same planes
/// (`slab`), the same choice of entry or exit and the same
/// `t + shift < tmax`; but no point or normal, and it stops at the first
/// slab after which no hit inside the span can remain. The entry only
/// grows and the exit only shrinks from plane to plane, and their values
/// are a largest and a smallest (NaN quotients skipped, as `Clip::plane`
/// skips them), the same whatever the order the slabs come in; so the
/// thinnest slab goes first, the one a ray leaving a face or crossing a
/// floor is most often decided by.
// Inlined for the reason `intersect_block` is.
#[inline(always)]
pub fn block_blocks(lengths: DVec3, ray: &Ray, tmin: f64, tmax: f64) -> bool {
    let h = lengths * 0.5;
    let near = Near::of(ray, tmin, DVec3::ZERO, h.length_squared());
    let (o, d) = (near.ray.origin, near.ray.dir);
    let (tmin, shift) = (near.tmin, near.shift);
    let (mut enter, mut exit) = (f64::NEG_INFINITY, f64::INFINITY);
    // False when no hit is left: the entry past the exit, the exit behind
    // the start, or an entry (the hit, should it stay one) already at or
    // beyond `tmax`; no hit now is no hit after more planes.
    let mut span = |k: usize| -> bool {
        let (te, tx) = match slab(d[k], o[k], h[k]) {
            Slab::Outside => return false,
            Slab::Open => return true,
            Slab::Span(te, tx) => (te, tx),
        };
        if te > enter {
            enter = te;
        }
        if tx < exit {
            exit = tx;
        }
        // (enter > tmin: the sum is no NaN, and `>=` is `!(<)` for a tmax
        // that is none either; a NaN tmax blocks nothing, either way.)
        !(enter > exit || exit <= tmin || (enter > tmin && enter + shift >= tmax))
    };
    let [a, b, c] = thinnest_first(h);
    if !(span(a) && span(b) && span(c)) {
        return false;
    }
    if enter > tmin {
        enter + shift < tmax
    } else {
        exit > tmin && exit.is_finite() && exit + shift < tmax
    }
}

/// The axes 0, 1, 2 in the order of the half-lengths `h`, smallest first
/// (ties in axis order).
fn thinnest_first(h: DVec3) -> [usize; 3] {
    // Each order spelt out: an index by a variable axis compiled, in some
    // builds, to a branch and a load per block test.
    let (x, y, z) = (h.x, h.y, h.z);
    if y < x {
        if z < y {
            [2, 1, 0]
        } else if z < x {
            [1, 2, 0]
        } else {
            [1, 0, 2]
        }
    } else if z < x {
        [2, 0, 1]
    } else if z < y {
        [0, 2, 1]
    } else {
        [0, 1, 2]
    }
}

/// A right prism over the convex, counter-clockwise polygon `vertex` in the
/// local x–y plane, from z = 0 to `height`.
///
/// Reconstructed: a convex clip of the side planes and the two caps.
pub fn intersect_prism(vertex: &[[f64; 2]], height: f64, ray: &Ray, tmin: f64) -> Option<LocalHit> {
    let n = vertex.len();
    let reach2 = vertex.iter().fold(0.0f64, |m, &[x, y]| m.max(x * x + y * y));
    let near = Near::of(ray, tmin, DVec3::ZERO, reach2 + height * height);
    let (ray, tmin) = (&near.ray, near.tmin);
    let plane = |i: usize| {
        if i == n {
            return (DVec3::Z, height);
        }
        if i > n {
            return (DVec3::NEG_Z, 0.0);
        }
        let [x0, y0] = vertex[i];
        let [x1, y1] = vertex[(i + 1) % n];
        // Outward normal of a counter-clockwise edge: (dy, −dx).
        let normal = DVec3::new(y1 - y0, x0 - x1, 0.0).normalize();
        (normal, normal.x * x0 + normal.y * y0)
    };
    near.back(intersect_convex(ray, tmin, n + 2, plane))
}

/// A cylinder of radius `cylradius` about local z from `bottom` to `top`,
/// closed by two caps.
///
/// Reconstructed: x² + y² = r² for the side, the planes z = bottom, z = top
/// within the radius for the caps.
pub fn intersect_cylinder(cylradius: f64, bottom: f64, top: f64, ray: &Ray, tmin: f64) -> Option<LocalHit> {
    let centre = DVec3::new(0.0, 0.0, 0.5 * (bottom + top));
    let half = 0.5 * (top - bottom);
    let near = Near::of(ray, tmin, centre, cylradius * cylradius + half * half);
    near.back(cylinder_hit(cylradius, bottom, top, &near.ray, near.tmin))
}

fn cylinder_hit(cylradius: f64, bottom: f64, top: f64, ray: &Ray, tmin: f64) -> Option<LocalHit> {
    let (o, d) = (ray.origin, ray.dir);
    let mut best: Option<LocalHit> = None;
    let mut consider = |t: f64, normal: DVec3| {
        if t > tmin && best.is_none_or(|b| t < b.t) {
            best = Some(LocalHit {
                t,
                point: ray.at(t),
                normal,
            });
        }
    };
    let a = d.x * d.x + d.y * d.y;
    if a > 0.0 {
        let half_b = o.x * d.x + o.y * d.y;
        let c = o.x * o.x + o.y * o.y - cylradius * cylradius;
        let disc = half_b * half_b - a * c;
        if disc >= 0.0 {
            let sq = disc.sqrt();
            let q = -(half_b + half_b.signum() * sq);
            if q != 0.0 {
                for t in [q / a, c / q] {
                    let z = o.z + t * d.z;
                    if z >= bottom && z <= top {
                        let p = ray.at(t);
                        consider(t, DVec3::new(p.x, p.y, 0.0) / cylradius);
                    }
                }
            }
        }
    }
    if d.z != 0.0 {
        for (zc, nz) in [(bottom, -1.0), (top, 1.0)] {
            let t = (zc - o.z) / d.z;
            let (x, y) = (o.x + t * d.x, o.y + t * d.y);
            if x * x + y * y <= cylradius * cylradius {
                consider(t, DVec3::new(0.0, 0.0, nz));
            }
        }
    }
    best
}

/// The radius of the sphere the bounding-sphere test takes for an
/// object's `radius`: padded by a part in 10⁶ so no surface hit is lost.
/// Every bound over the object (`crate::motion::object_boxes`) holds it.
#[inline(always)]
pub fn bounding_radius(radius: f64) -> f64 {
    radius * (1.0 + 1e-6) + 1e-9
}

/// The box in the object's local frame that holds its surface, where it
/// is tighter than the bounding sphere: a block's, a cylinder's, a
/// prism's extent; a sweep's from its `bbox` (its own, or in `listing`
/// fidelity its class's, which holds it, erratum 9), for a rotation sweep
/// ±its greatest radius across (the listing's `rbox` keeps the radius
/// range min U … max U in x and y); a blob's from its components' spheres
/// ([`blob_box`]), a patch's from its control points ([`patch_box`]).
/// `None` for a sphere (its sphere is its bound), a sweep without segments
/// and a blob without a component of positive strength.
pub fn local_box(obj: &ObjectRecord) -> Option<BoundingBox> {
    let b = |lo: DVec3, hi: DVec3| BoundingBox {
        xmin: lo.x,
        xmax: hi.x,
        ymin: lo.y,
        ymax: hi.y,
        zmin: lo.z,
        zmax: hi.z,
    };
    match &obj.shape {
        Shape::Sphere => None,
        Shape::Block { lengths } => Some(b(-0.5 * *lengths, 0.5 * *lengths)),
        Shape::Cylinder {
            cylradius, top, bottom, ..
        } => Some(b(
            DVec3::new(-cylradius, -cylradius, bottom.min(*top)),
            DVec3::new(*cylradius, *cylradius, top.max(*bottom)),
        )),
        Shape::Prism { height, vertex, .. } => {
            let around = vertex.iter().fold(BoundingBox::EMPTY, |a, &[x, y]| {
                a.holding(DVec3::new(x, y, 0.0)).holding(DVec3::new(x, y, *height))
            });
            (!vertex.is_empty()).then_some(around)
        }
        Shape::Sweep(sw) if sw.segment == 0 => None,
        Shape::Sweep(sw) if obj.class == PrimitiveClass::Rotation => {
            let r = sw.bbox.xmin.abs().max(sw.bbox.xmax.abs());
            Some(b(DVec3::new(-r, -r, sw.bbox.zmin), DVec3::new(r, r, sw.bbox.zmax)))
        }
        Shape::Sweep(sw) => Some(sw.bbox),
        Shape::Blob(b) => blob_box(b),
        Shape::Patch(p) => Some(patch_box(p)),
    }
}

/// Does the ray meet the sphere of `radius` about `centre` beyond `tmin`?
/// Padded ([`bounding_radius`]) so no surface hit is lost.
pub(crate) fn bounding_sphere_hit(centre: DVec3, radius: f64, ray: &Ray, tmin: f64) -> bool {
    let r = bounding_radius(radius);
    let oc = ray.origin - centre;
    let a = ray.dir.length_squared();
    let half_b = oc.dot(ray.dir);
    let c = oc.length_squared() - r * r;
    if c <= 0.0 {
        return true; // the ray starts inside
    }
    // Outside and moving away, or missing. Else both crossings lie ahead,
    // the far one at t ≥ −half_b/a: beyond tmin without its root when
    // that is twice tmin (the usual case, tmin being a rounding guard).
    half_b < 0.0
        && half_b * half_b - a * c >= 0.0
        && (-half_b > 2.0 * tmin.abs() * a || {
            let far = (-half_b + (half_b * half_b - a * c).sqrt()) / a;
            far > tmin
        })
}

/// Where a pattern or texture is painted: coordinates on the face hit, in
/// object units from the face's lower-left corner as seen from outside,
/// and the face's extent.
///
/// Reconstructed (the thesis prints the pattern procedures, not how the
/// base program chose their arguments): block faces take the two
/// coordinates that span them, upright on the side faces so that a picture
/// pasted on them reads left to right (Fig. 5.3, 5.5); a cylinder's side
/// unrolls by arc length from local +x, counter-clockwise; everything else
/// (caps, spheres, prisms, sweeps) is projected along local z onto the
/// local x–y plane, from −radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceCoords {
    pub s: f64,
    pub t: f64,
    pub width: f64,
    pub height: f64,
}

/// See [`FaceCoords`].
// Inlined for the reason `intersect_block` is: its caller reads the
// coordinates back at once, two at a time.
#[inline(always)]
pub fn face_coords(obj: &ObjectRecord, local: DVec3, local_normal: DVec3) -> FaceCoords {
    match &obj.shape {
        Shape::Block { lengths } => {
            let h = *lengths * 0.5;
            let a = local_normal.abs();
            let (s, t, width, height) = if a.z >= a.x && a.z >= a.y {
                if local_normal.z > 0.0 {
                    (local.x + h.x, local.y + h.y, lengths.x, lengths.y)
                } else {
                    (local.x + h.x, h.y - local.y, lengths.x, lengths.y)
                }
            } else if a.y >= a.x {
                if local_normal.y > 0.0 {
                    (h.x - local.x, local.z + h.z, lengths.x, lengths.z)
                } else {
                    (local.x + h.x, local.z + h.z, lengths.x, lengths.z)
                }
            } else if local_normal.x > 0.0 {
                (local.y + h.y, local.z + h.z, lengths.y, lengths.z)
            } else {
                (h.y - local.y, local.z + h.z, lengths.y, lengths.z)
            };
            FaceCoords { s, t, width, height }
        }
        Shape::Cylinder {
            cylradius, top, bottom, ..
        } if local_normal.z.abs() < 0.5 => {
            let theta = local.y.atan2(local.x).rem_euclid(std::f64::consts::TAU);
            FaceCoords {
                s: theta * cylradius,
                t: local.z - bottom,
                width: std::f64::consts::TAU * cylradius,
                height: top - bottom,
            }
        }
        _ => {
            let r = obj.radius;
            FaceCoords {
                s: local.x + r,
                t: local.y + r,
                width: 2.0 * r,
                height: 2.0 * r,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
        Ray::new(DVec3::from_array(o), DVec3::from_array(d).normalize())
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    /// The bounding-sphere test without its root answers as the test with
    /// it: rays from outside and inside, toward and away, grazing, with
    /// `tmin` from 0 to beyond the sphere.
    #[test]
    fn bounding_sphere_test_as_with_its_root() {
        use crate::hash::hashed_uniform;
        let with_root = |centre: DVec3, radius: f64, ray: &Ray, tmin: f64| {
            let r = radius * (1.0 + 1e-6) + 1e-9;
            let oc = ray.origin - centre;
            let (a, half_b) = (ray.dir.length_squared(), oc.dot(ray.dir));
            let c = oc.length_squared() - r * r;
            c <= 0.0
                || (half_b < 0.0
                    && half_b * half_b - a * c >= 0.0
                    && (-half_b + (half_b * half_b - a * c).sqrt()) / a > tmin)
        };
        let (mut yes, mut no) = (0, 0);
        for k in 0..20_000u64 {
            let r = |j: u64| 2.0 * hashed_uniform(8 * k + j) - 1.0;
            let centre = DVec3::new(r(0), r(1), r(2));
            let radius = 0.5 + r(3).abs();
            let o = DVec3::new(3.0 * r(4), 3.0 * r(5), 3.0 * r(6));
            let d = (centre - o + DVec3::new(r(7), r(8), r(1) * r(2)) * radius).normalize();
            let ray = Ray::new(o, d);
            let tmin = [1e-9, 0.0, (o - centre).length(), 10.0 * r(3).abs()][(k % 4) as usize];
            let got = bounding_sphere_hit(centre, radius, &ray, tmin);
            assert_eq!(got, with_root(centre, radius, &ray, tmin), "ray {k}");
            if got {
                yes += 1;
            } else {
                no += 1;
            }
        }
        assert!(yes > 2000 && no > 2000, "{yes} {no}");
    }

    /// The block's written-out slab test gives the six-plane convex clip's
    /// hits to the bit: rays from inside, outside, along a face and through
    /// edges, exactly axis-parallel ones included.
    #[test]
    fn block_is_the_six_plane_clip_to_the_bit() {
        use crate::hash::hashed_uniform;
        let lengths = DVec3::new(2.0, 3.0, 0.5);
        let h = lengths * 0.5;
        let planes = [
            (DVec3::X, h.x),
            (DVec3::NEG_X, h.x),
            (DVec3::Y, h.y),
            (DVec3::NEG_Y, h.y),
            (DVec3::Z, h.z),
            (DVec3::NEG_Z, h.z),
        ];
        let mut hits = 0;
        for k in 0..4000u64 {
            let r = |j: u64| 2.0 * hashed_uniform(8 * k + j) - 1.0;
            let mut o = DVec3::new(3.0 * r(0), 3.0 * r(1), 2.0 * r(2));
            let mut d = DVec3::new(r(3), r(4), r(5));
            let axis = (k / 8 % 3) as usize;
            match k % 8 {
                1 => d[axis] = 0.0,                           // parallel to a pair of faces
                2 => o.z = h.z,                               // in the top face's plane
                3 => o = DVec3::new(h.x, h.y, 0.0) - d * 4.0, // through an edge
                4 => d[axis] = -0.0,                          // parallel, negative zero
                5 => d[axis] = f64::NAN,
                6 => o[axis] = f64::NAN,
                7 => (o, d) = (DVec3::new(0.5, -1.5, 0.1), DVec3::new(r(3), 1.0, r(5))), // from a face
                _ => {}
            }
            if d == DVec3::ZERO {
                continue;
            }
            let ray = Ray::new(o, d);
            for tmin in [1e-9, 0.0, -1.0] {
                let near = Near::of(&ray, tmin, DVec3::ZERO, h.length_squared());
                let slab = intersect_block(lengths, &ray, tmin);
                if o.is_finite() && d.is_finite() {
                    // (A NaN coordinate spoils every plane's n·o or n·d in
                    // the clip's products, only its own pair in the block's.)
                    let convex = near.back(intersect_convex(&near.ray, near.tmin, 6, |i| planes[i]));
                    let bits = |h: Option<LocalHit>| h.map(|h| (h.t.to_bits(), h.point.to_array().map(f64::to_bits)));
                    assert_eq!(bits(convex), bits(slab), "ray {k}: {o} {d}");
                    assert_eq!(convex, slab, "ray {k}: {o} {d}");
                }
                hits += slab.is_some() as usize;
            }
        }
        assert!(hits > 3000, "the rays meet the block often: {hits}");
    }

    /// The boolean block test answers as the nearest hit before `tmax`
    /// does: random rays from inside and outside (re-based or not), rays
    /// parallel to faces, starting on a face (as shadow rays do), through
    /// edges, far away, with NaN and infinite parts, and `tmax` before,
    /// at and beyond the hits; blocks of every order of thinness.
    #[test]
    fn block_blocks_as_the_nearest_hit_before_tmax() {
        use crate::hash::hashed_uniform;
        let (mut yes, mut no) = (0, 0);
        for k in 0..60_000u64 {
            let r = |j: u64| 2.0 * hashed_uniform(16 * k + j) - 1.0;
            let lengths = DVec3::new(0.2 + 3.0 * r(0).abs(), 0.2 + 3.0 * r(1).abs(), 0.2 + 3.0 * r(2).abs());
            let h = lengths * 0.5;
            let mut o = DVec3::new(3.0 * r(3), 3.0 * r(4), 3.0 * r(5));
            let mut d = DVec3::new(r(6), r(7), r(8));
            let axis = (k / 16 % 3) as usize;
            match k % 16 {
                1 => d[axis] = 0.0,                                                // parallel to a pair of faces
                2 => d[axis] = -0.0,                                               // the same, negative zero
                3 => o[axis] = h[axis],                                            // on a face's plane
                4 => o[axis] = -h[axis],                                           // on the opposite one
                5 => o = DVec3::new(h.x, h.y, 0.0) - d * 4.0,                      // through an edge
                6 => o *= 1e6,                                                     // far away
                7 => (o[axis], d[axis]) = (h[axis] * (1.0 + 1e-7), d[axis].abs()), // leaving a face
                8 => (o[axis], d[axis]) = (-h[axis] * (1.0 + 1e-7), -d[axis].abs()),
                9 => d[axis] = f64::NAN,
                10 => o[axis] = f64::NAN,
                11 => o[axis] = f64::INFINITY,
                12 => (d[axis], d[(axis + 1) % 3]) = (0.0, 0.0), // along an axis
                _ => {}
            }
            let ray = Ray::new(o, d);
            let tmin = if k % 5 == 0 { 0.0 } else { 1e-9 };
            let nearest = intersect_block(lengths, &ray, tmin);
            let at = nearest.map_or(1.0, |h| h.t);
            for tmax in [10.0 * r(9).abs(), 1e9, f64::INFINITY, at, at.next_up(), at.next_down()] {
                let want = nearest.is_some_and(|h| h.t < tmax);
                assert_eq!(block_blocks(lengths, &ray, tmin, tmax), want, "ray {k}: {o} {d} {tmax}");
                (yes, no) = if want { (yes + 1, no) } else { (yes, no + 1) };
            }
        }
        assert!(yes > 20_000 && no > 20_000, "{yes} {no}");
    }

    #[test]
    fn thinnest_axis_first() {
        for (h, want) in [
            ([1.0, 2.0, 3.0], [0, 1, 2]),
            ([3.0, 2.0, 1.0], [2, 1, 0]),
            ([2.0, 1.0, 3.0], [1, 0, 2]),
            ([2.0, 3.0, 1.0], [2, 0, 1]),
            ([20.0, 20.0, 0.5], [2, 0, 1]),
            ([1.0, 1.0, 1.0], [0, 1, 2]),
            ([1.0, 3.0, 2.0], [0, 2, 1]),
            ([3.0, 1.0, 2.0], [1, 2, 0]),
            ([2.0, 1.0, 2.0], [1, 0, 2]),
            ([2.0, 2.0, 1.0], [2, 0, 1]),
            // Ties keep the axis order.
            ([2.0, 1.0, 1.0], [1, 2, 0]),
            ([1.0, 2.0, 1.0], [0, 2, 1]),
            ([1.0, 2.0, 2.0], [0, 1, 2]),
        ] {
            assert_eq!(thinnest_first(DVec3::from_array(h)), want, "{h:?}");
        }
    }

    #[test]
    fn sphere_hit_distance_and_normal() {
        let h = intersect_sphere(2.0, &ray([0.0, -10.0, 0.0], [0.0, 1.0, 0.0]), 1e-9).unwrap();
        assert!((h.t - 8.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::NEG_Y));
        // From inside, the far side.
        let h = intersect_sphere(2.0, &ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]), 1e-9).unwrap();
        assert!((h.t - 2.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::Z));
        // A ray at distance 3 from the centre misses.
        assert!(intersect_sphere(2.0, &ray([3.0, -10.0, 0.0], [0.0, 1.0, 0.0]), 1e-9).is_none());
        // An oblique hit: from (1, −5, 0) along +y meets x² + y² = 4 at y = −√3.
        let h = intersect_sphere(2.0, &ray([1.0, -5.0, 0.0], [0.0, 1.0, 0.0]), 1e-9).unwrap();
        assert!((h.t - (5.0 - 3f64.sqrt())).abs() < 1e-12);
        assert!(close(h.normal, DVec3::new(0.5, -3f64.sqrt() / 2.0, 0.0)));
    }

    #[test]
    fn block_faces() {
        let l = DVec3::new(2.0, 4.0, 6.0);
        let h = intersect_block(l, &ray([-5.0, 0.5, 0.5], [1.0, 0.0, 0.0]), 1e-9).unwrap();
        assert!((h.t - 4.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::NEG_X));
        let h = intersect_block(l, &ray([0.0, 0.0, 10.0], [0.0, 0.0, -1.0]), 1e-9).unwrap();
        assert!((h.t - 7.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::Z));
        // From inside: the exit face.
        let h = intersect_block(l, &ray([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]), 1e-9).unwrap();
        assert!((h.t - 2.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::Y));
        // Parallel to a face, outside its slab.
        assert!(intersect_block(l, &ray([1.5, -9.0, 0.0], [0.0, 1.0, 0.0]), 1e-9).is_none());
        // Diagonal into a corner region that misses.
        assert!(intersect_block(l, &ray([-5.0, -5.0, 0.0], [1.0, -1.0, 0.0]), 1e-9).is_none());
    }

    #[test]
    fn cylinder_side_and_caps() {
        let h = intersect_cylinder(1.0, -1.0, 2.0, &ray([-5.0, 0.0, 0.5], [1.0, 0.0, 0.0]), 1e-9).unwrap();
        assert!((h.t - 4.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::NEG_X));
        let h = intersect_cylinder(1.0, -1.0, 2.0, &ray([0.3, 0.2, 9.0], [0.0, 0.0, -1.0]), 1e-9).unwrap();
        assert!((h.t - 7.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::Z));
        let h = intersect_cylinder(1.0, -1.0, 2.0, &ray([0.3, 0.2, -9.0], [0.0, 0.0, 1.0]), 1e-9).unwrap();
        assert!((h.t - 8.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::NEG_Z));
        // Above the top, aimed sideways: misses.
        assert!(intersect_cylinder(1.0, -1.0, 2.0, &ray([-5.0, 0.0, 2.5], [1.0, 0.0, 0.0]), 1e-9).is_none());
        // Oblique through the side at 45° in x–z: enters x = −1 at z = 0.
        let h = intersect_cylinder(1.0, -1.0, 2.0, &ray([-3.0, 0.0, -2.0], [1.0, 0.0, 1.0]), 1e-9).unwrap();
        assert!((h.t - 2.0 * 2f64.sqrt()).abs() < 1e-12);
        assert!(close(h.point, DVec3::new(-1.0, 0.0, 0.0)));
    }

    #[test]
    fn prism_over_a_triangle() {
        // Right triangle (0,0), (2,0), (0,2), height 1.
        let v = [[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]];
        // Into the hypotenuse x + y = 2 from (3, 3) toward the origin.
        let h = intersect_prism(&v, 1.0, &ray([3.0, 3.0, 0.5], [-1.0, -1.0, 0.0]), 1e-9).unwrap();
        let expect_t = (DVec3::new(3.0, 3.0, 0.0) - DVec3::new(1.0, 1.0, 0.0)).length();
        assert!((h.t - expect_t).abs() < 1e-12);
        assert!(close(h.normal, DVec3::new(1.0, 1.0, 0.0).normalize()));
        // Down onto the top cap.
        let h = intersect_prism(&v, 1.0, &ray([0.5, 0.5, 5.0], [0.0, 0.0, -1.0]), 1e-9).unwrap();
        assert!((h.t - 4.0).abs() < 1e-12);
        assert!(close(h.normal, DVec3::Z));
        // Beside the hypotenuse: misses.
        assert!(intersect_prism(&v, 1.0, &ray([1.5, 1.5, 5.0], [0.0, 0.0, -1.0]), 1e-9).is_none());
    }
}

//! Reconstructed base: `raytrace`, the recursive shading of the base
//! program (not printed in the thesis). It follows §2.1 (the four kinds of
//! surface and their terms, Fig. 2.2–2.6) and Ch. 4 (f), Whitted's model
//!
//! I = Ia + Kd Σ(N·Lj) + Ks Is + Kt It,
//!
//! with the main program's call `raytrace(aray, 1.0, false, acolor, 1)`:
//! a ray, its weight, whether it travels inside an object, and the depth.
//!
//! Choices the thesis leaves open, each written once here:
//! - Ia = ka·Iobject; the diffuse term is kd·(N·L̂)·light colour·colour,
//!   for each light that a shadow ray reaches.
//! - `opaque`: Ia and Id only (§2.1 step 4(a): Is = It = 0). `mirrored`:
//!   adds ks·prcntrfl·Is. `transparent` and `crystal`: add ks·Is and kt·It.
//! - Shadow rays are stopped by every object but those of kind `light` and
//!   `background`, and `crystal`, which lets kt·colour of the light through
//!   (a transparent object casts a full shadow, as Whitted's first images
//!   do).
//! - `light` surfaces return their colour; `background` surfaces return the
//!   background colour.
//! - Recursion stops at depth [`MAXDEPTH`] or when a ray's weight falls
//!   below [`MINWEIGHT`]; total internal reflection sends the transmitted
//!   weight along the reflected direction and is counted (`kfTIRcnt`).

use std::cell::{Cell, Ref, RefCell};

use crate::paper::PaperChain;
use crate::shapes::{face_coords, in_bounding_sphere, intersect_shape, shape_blocks};
use crate::types::{
    DVec3, Intensity, IntersectionRecord, LocalHit, ObjectRecord, Options, PaintKind, Painting, Pose, Ray, Scene,
    Shape, SurfaceAttribute, SurfaceRecord,
};

/// The scene at one instant of the shutter: the read-only scene, where
/// each of its objects stands then (`poses[i]` for `scene.objects[i]`),
/// and the objects whose contour deforms. What `motionblur` wrote into the
/// shared records, the port keeps here.
#[derive(Clone, Copy, Debug)]
pub struct Snapshot<'a> {
    pub scene: &'a Scene,
    pub poses: &'a [Pose],
    pub deforming: &'a [Deforming<'a>],
}

/// An in-between object of a key-frame chain (§3.2): its contour at the
/// snapshot's time. `motionblur` computed it for every ray (`do34` or
/// `Hermite`); here it is computed the first time a ray of the instant
/// reaches the object's bounding sphere, and kept for the instant's other
/// rays, since most rays never come near the object (DEVIATIONS D19).
#[derive(Debug)]
pub struct Deforming<'a> {
    /// Index into `scene.objects`.
    pub object: usize,
    chain: &'a PaperChain,
    time: Cell<f64>,
    ready: Cell<bool>,
    contour: RefCell<Shape>,
}

impl<'a> Deforming<'a> {
    /// Scratch for the in-between object `object` of `chain`.
    pub fn new(object: usize, chain: &'a PaperChain) -> Self {
        Deforming {
            object,
            chain,
            time: Cell::new(0.0),
            ready: Cell::new(false),
            contour: RefCell::new(Shape::Sweep(chain.scratch())),
        }
    }

    /// A new instant: the contour is due again.
    pub fn at(&self, time: f64) {
        self.time.set(time);
        self.ready.set(false);
    }

    /// The contour at the instant: `do34` at time 0 or 1, else `Hermite`
    /// (`PaperChain::inbetween`), on first use.
    pub fn contour(&self) -> Ref<'_, Shape> {
        if !self.ready.get() {
            if let Shape::Sweep(sw) = &mut *self.contour.borrow_mut() {
                self.chain.inbetween(self.time.get(), sw);
            }
            self.ready.set(true);
        }
        self.contour.borrow()
    }
}

impl Snapshot<'_> {
    /// `f` of object `i` as it stands at this instant (its own shape, or
    /// its contour of the moment when it deforms), for a ray that reaches
    /// its bounding sphere; `None` for one that does not.
    fn at_instant<R>(
        &self,
        i: usize,
        ray: &Ray,
        f: impl FnOnce(&ObjectRecord, &Shape, &Pose) -> Option<R>,
    ) -> Option<R> {
        let (obj, pose) = (&self.scene.objects[i], &self.poses[i]);
        if !in_bounding_sphere(obj, pose, ray, TMIN) {
            return None;
        }
        match self.deforming.iter().find(|d| d.object == i) {
            None => f(obj, &obj.shape, pose),
            Some(d) => f(obj, &d.contour(), pose),
        }
    }

    /// Does object `i` as it stands at this instant meet the ray before
    /// `tmax`? ([`Snapshot::hit_object`]'s hit, before `tmax`.)
    fn blocks(&self, i: usize, ray: &Ray, tmax: f64, opts: &Options) -> bool {
        self.at_instant(i, ray, |obj, shape, pose| {
            shape_blocks(obj, shape, pose, ray, TMIN, tmax, opts).then_some(())
        })
        .is_some()
    }

    /// The hit of a ray with object `i` as it stands at this instant.
    fn hit_object(&self, i: usize, ray: &Ray, opts: &Options) -> Option<LocalHit> {
        self.at_instant(i, ray, |obj, shape, pose| {
            intersect_shape(obj, shape, pose, ray, TMIN, opts)
        })
    }
}

/// Every object of `scene` at rest: the poses of a [`Snapshot`] of a
/// scene in which nothing moves.
pub fn rest_poses(scene: &Scene) -> Vec<Pose> {
    scene.objects.iter().map(|o| o.pose()).collect()
}

/// The deepest recursion `raytrace` makes (the main program calls it at
/// depth 1). The base program's limit is not printed; 6 is the port's.
pub const MAXDEPTH: u32 = 6;

/// Rays whose weight would contribute less than this (about half a step of
/// an 8-bit channel) are not traced.
pub const MINWEIGHT: f64 = 0.002;

/// How far the fudged-out and fudged-in points of an intersection stand
/// off the surface, relative to the size of the coordinates.
const FUDGE: f64 = 1e-7;

/// Rays start this far along (relative) so that a ray leaving a fudged
/// point does not meet the surface it left.
const TMIN: f64 = 1e-9;

/// Counts of what a render did: rays of each kind and `kfTIRcnt`, the
/// main program's count of total internal reflections.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraceStats {
    /// Every ray `raytrace` was called with (primary and secondary).
    pub rays: u64,
    /// Shadow rays to the lights.
    pub shadow_rays: u64,
    /// `kfTIRcnt`: total internal reflections.
    pub kftircnt: u64,
}

impl std::ops::AddAssign for TraceStats {
    fn add_assign(&mut self, o: Self) {
        self.rays += o.rays;
        self.shadow_rays += o.shadow_rays;
        self.kftircnt += o.kftircnt;
    }
}

/// The nearest hit of a ray with the scene's objects beyond the ray's
/// origin, as an `intersectionrecord` (Fig. 4.3); `None` is `status =
/// false`. `dir` must be unit length.
pub fn intersect(snap: &Snapshot, ray: &Ray, opts: &Options) -> Option<IntersectionRecord> {
    let mut best: Option<(usize, LocalHit)> = None;
    for i in 0..snap.scene.objects.len() {
        if let Some(h) = snap.hit_object(i, ray, opts) {
            if best.is_none_or(|(_, b)| h.t < b.t) {
                best = Some((i, h));
            }
        }
    }
    let (object, hit) = best?;
    Some(record_of(snap, object, ray, &hit))
}

/// The intersection record of a local hit: world point and normal, and the
/// fudged-out and fudged-in points.
fn record_of(snap: &Snapshot, object: usize, ray: &Ray, hit: &LocalHit) -> IntersectionRecord {
    let obj = &snap.scene.objects[object];
    let point = ray.at(hit.t);
    let normal = snap.poses[object].transfm.transform_vector3(hit.normal).normalize();
    let fudge = FUDGE * (1.0 + point.abs().max_element());
    IntersectionRecord {
        normal,
        p: point + normal * fudge,
        insidep: point - normal * fudge,
        surface: obj.surface,
        parameter: hit.t,
        distance: hit.t * ray.dir.length(),
        object,
        local: hit.point,
        local_normal: hit.normal,
    }
}

/// The colour a surface shows at a hit under diffuse light: its `color`,
/// or its pattern's (`painting` of unit `proc`), or its texture's.
pub fn surface_color(snap: &Snapshot, surf: &SurfaceRecord, hit: &IntersectionRecord, opts: &Options) -> Intensity {
    let obj = &snap.scene.objects[hit.object];
    if let Some(tex) = &surf.texture {
        let f = face_coords(obj, hit.local, hit.local_normal);
        return tex.texel(f.s / f.width, f.t / f.height);
    }
    let Some(paint) = &surf.paint else {
        return surf.color;
    };
    let painting = match paint.kind {
        PaintKind::Floor => {
            let f = face_coords(obj, hit.local, hit.local_normal);
            crate::proc::floortest(f.s, f.t, paint.lengthx, paint.lengthy)
        }
        PaintKind::Floorstar => {
            let f = face_coords(obj, hit.local, hit.local_normal);
            crate::proc::floorstar(f.s, f.t, paint.lengthx, paint.lengthy, opts.fidelity)
        }
        PaintKind::Star => {
            // `startest` with cas = 1 (the x–z plane) on the point scaled to
            // the unit sphere: a star where the object faces ±y.
            let p = hit.local / obj.radius;
            crate::proc::startest(p.x * paint.lengthx, p.y, p.z * paint.lengthy, 1)
        }
    };
    match painting.unwrap_or_default() {
        Painting::Normal1 => surf.color,
        Painting::Floor1 | Painting::Star1 => paint.color,
    }
}

/// `raytrace(aray, weight, inside, acolor, depth)`: the colour seen along
/// a ray. Reconstructed (see the module's comment); `inside` is kept for
/// the reader of the main program, the side is taken from the normal.
pub fn raytrace(
    snap: &Snapshot,
    aray: &Ray,
    weight: f64,
    inside: bool,
    depth: u32,
    opts: &Options,
    stats: &mut TraceStats,
) -> Intensity {
    let _ = inside;
    let scene = snap.scene;
    stats.rays += 1;
    let Some(hit) = intersect(snap, aray, opts) else {
        return scene.backgrnd;
    };
    let surf = &scene.surfaces[hit.surface];
    match surf.surface {
        SurfaceAttribute::Background => return scene.backgrnd,
        SurfaceAttribute::Light => return surf.color,
        _ => {}
    }
    let d = aray.dir;
    // Which side the ray came from: `n` faces the ray, `near` is the fudged
    // point on its side and `far` the one on the other.
    let entering = hit.normal.dot(d) < 0.0;
    let (n, near, far) = if entering {
        (hit.normal, hit.p, hit.insidep)
    } else {
        (-hit.normal, hit.insidep, hit.p)
    };
    let color = surface_color(snap, surf, &hit, opts);
    let ambient_color = if surf.paint.is_some() || surf.texture.is_some() {
        color
    } else {
        surf.iobject
    };
    let mut i = surf.ka * ambient_color;
    i += surf.kd * diffuse(snap, near, n, opts, stats) * color;

    let (ks_weight, kt_weight) = match surf.surface {
        SurfaceAttribute::Opaque => (0.0, 0.0),
        SurfaceAttribute::Mirrored => (surf.ks * surf.prcntrfl, 0.0),
        _ => (surf.ks, surf.kt),
    };
    if depth >= MAXDEPTH {
        return i;
    }
    let reflected = d - 2.0 * d.dot(n) * n;
    if ks_weight > 0.0 && weight * ks_weight >= MINWEIGHT {
        let r = Ray::new(near, reflected.normalize());
        i += ks_weight * raytrace(snap, &r, weight * ks_weight, !entering, depth + 1, opts, stats);
    }
    if kt_weight > 0.0 && weight * kt_weight >= MINWEIGHT {
        let eta = if entering { 1.0 / surf.index } else { surf.index };
        let t = match refract(d, n, eta) {
            Some(t) => Ray::new(far, t),
            None => {
                stats.kftircnt += 1;
                Ray::new(near, reflected.normalize())
            }
        };
        i += kt_weight * raytrace(snap, &t, weight * kt_weight, entering, depth + 1, opts, stats);
    }
    i
}

/// Σ (N·L̂j) · light colour over the lights a shadow ray from `p` reaches,
/// each shadow ray attenuated by the `crystal` objects it passes.
fn diffuse(snap: &Snapshot, p: DVec3, n: DVec3, opts: &Options, stats: &mut TraceStats) -> Intensity {
    let mut sum = Intensity::ZERO;
    for light in &snap.scene.lights {
        let to_light = light.position - p;
        let dist = to_light.length();
        let l = to_light / dist;
        let cos = n.dot(l);
        if cos <= 0.0 {
            continue;
        }
        stats.shadow_rays += 1;
        let transmit = shadow(snap, Ray::new(p, l), dist, opts);
        sum += cos * light.color * transmit;
    }
    sum
}

/// How much light passes along a shadow ray to a light `dist` away.
fn shadow(snap: &Snapshot, ray: Ray, dist: f64, opts: &Options) -> Intensity {
    let mut transmit = Intensity::ONE;
    for (i, obj) in snap.scene.objects.iter().enumerate() {
        let surf = &snap.scene.surfaces[obj.surface];
        if matches!(surf.surface, SurfaceAttribute::Light | SurfaceAttribute::Background) {
            continue;
        }
        if !snap.blocks(i, &ray, dist, opts) {
            continue;
        }
        if surf.surface == SurfaceAttribute::Crystal {
            // Once through each crystal object (its two walls count as one).
            transmit *= surf.kt * surf.color;
        } else {
            return Intensity::ZERO;
        }
    }
    transmit
}

/// Snell's law: the refracted unit direction of unit `d` at a surface whose
/// unit normal `n` faces the incoming ray, with `eta` = n₁/n₂; `None` for
/// total internal reflection.
pub fn refract(d: DVec3, n: DVec3, eta: f64) -> Option<DVec3> {
    let cos_i = -d.dot(n);
    let sin2_t = eta * eta * (1.0 - cos_i * cos_i);
    if sin2_t > 1.0 {
        return None;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    Some((eta * d + (eta * cos_i - cos_t) * n).normalize())
}

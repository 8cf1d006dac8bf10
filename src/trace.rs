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

use crate::distributed::{glossy, toward_light};
use crate::intersect::{for_each_blocker, nearest, Snapshot};
use crate::sampler::Sampler;
use crate::shapes::face_coords;
use crate::types::{
    DVec3, Intensity, IntersectionRecord, LocalHit, PaintKind, Painting, Ray, SurfaceAttribute, SurfaceRecord,
};

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

/// Counts of what a render did: rays of each kind, `kfTIRcnt` (the main
/// program's count of total internal reflections) and the polynomial
/// searches of the sweeps (what makes one ray dearer than another).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraceStats {
    /// Primary rays: the subpixels traced (the listing's extra column
    /// included), or the adaptive sampler's samples.
    pub primary: u64,
    /// Every ray `raytrace` was called with (primary and secondary).
    pub rays: u64,
    /// Shadow rays to the lights.
    pub shadow_rays: u64,
    /// `kfTIRcnt`: total internal reflections.
    pub kftircnt: u64,
    /// Polynomials searched for roots by `laguerre` or the robust solver
    /// (past the pre-tests that settle most of them).
    pub searched: u64,
}

impl std::ops::AddAssign for TraceStats {
    fn add_assign(&mut self, o: Self) {
        self.primary += o.primary;
        self.rays += o.rays;
        self.shadow_rays += o.shadow_rays;
        self.kftircnt += o.kftircnt;
        self.searched += o.searched;
    }
}

/// What one ray tree carries besides the scene: the counts it adds to and
/// the sample it belongs to, whose further dimensions ([`Sampler::get_1d`],
/// [`Sampler::get_2d`]) are where a lens point, a light point or a gloss
/// turn come from. Per thread: the renderer makes one for each primary ray
/// from its worker's scratch.
pub struct Context<'a> {
    pub stats: &'a mut TraceStats,
    pub sampler: &'a mut dyn Sampler,
}

/// The nearest hit of a ray with the scene's objects beyond the ray's
/// origin ([`nearest`]), as an `intersectionrecord` (Fig. 4.3); `None` is
/// `status = false`. `dir` must be unit length. Inlined, so that the
/// record is made where `raytrace` keeps it, not copied there.
#[inline(always)]
pub fn intersect(snap: &Snapshot, ray: &Ray, stats: &mut TraceStats) -> Option<IntersectionRecord> {
    let (object, hit) = nearest(snap, ray, TMIN, &mut stats.searched)?;
    Some(record_of(snap, object, ray, &hit))
}

/// The intersection record of a local hit: world point and normal, and the
/// fudged-out and fudged-in points.
#[inline(always)]
fn record_of(snap: &Snapshot, object: usize, ray: &Ray, hit: &LocalHit) -> IntersectionRecord {
    let obj = &snap.scene.objects[object];
    let point = ray.at(hit.t);
    let normal = snap.pose(object).transfm.transform_vector3(hit.normal).normalize();
    let fudge = FUDGE * (1.0 + point.abs().max_element());
    IntersectionRecord {
        normal,
        p: point + normal * fudge,
        insidep: point - normal * fudge,
        surface: obj.surface,
        parameter: hit.t,
        object,
        local: hit.point,
        local_normal: hit.normal,
    }
}

/// The colour a surface shows at a hit under diffuse light: its `color`,
/// or its pattern's (`painting` of unit `proc`), or its texture's.
pub(crate) fn surface_color(snap: &Snapshot, surf: &SurfaceRecord, hit: &IntersectionRecord) -> Intensity {
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
            crate::proc::floorstar(f.s, f.t, paint.lengthx, paint.lengthy, snap.opts.fidelity)
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
/// a ray. Reconstructed (see the module's comment). The colour is returned
/// rather than written to `acolor`; `inside`, whether the ray travels
/// inside an object, is not kept: the side a ray meets a surface from is
/// taken from the normal at the hit.
pub fn raytrace(snap: &Snapshot, aray: &Ray, weight: f64, depth: u32, ctx: &mut Context) -> Intensity {
    ctx.stats.rays += 1;
    match intersect(snap, aray, ctx.stats) {
        Some(hit) => shade(snap, aray, &hit, weight, depth, ctx),
        None => snap.scene.backgrnd,
    }
}

/// The rest of `raytrace` once `aray` has met the scene first at `hit`:
/// the colour seen along it. Apart so that a caller that looks at the
/// first hit (the features a reconstruction reads,
/// [`crate::reconstruct::Features`]) shades the same hit without
/// searching for it twice.
pub(crate) fn shade(
    snap: &Snapshot,
    aray: &Ray,
    hit: &IntersectionRecord,
    weight: f64,
    depth: u32,
    ctx: &mut Context,
) -> Intensity {
    let scene = snap.scene;
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
    let color = surface_color(snap, surf, hit);
    let ambient_color = if surf.paint.is_some() || surf.texture.is_some() {
        color
    } else {
        surf.iobject
    };
    let mut i = surf.ka * ambient_color;
    i += surf.kd * diffuse(snap, near, n, ctx) * color;

    let (ks_weight, kt_weight) = match surf.surface {
        SurfaceAttribute::Opaque => (0.0, 0.0),
        SurfaceAttribute::Mirrored => (surf.ks * surf.prcntrfl, 0.0),
        _ => (surf.ks, surf.kt),
    };
    if depth >= MAXDEPTH {
        return i;
    }
    // Made only for a ray that is sent (never for an opaque surface's).
    let reflected = || (d - 2.0 * d.dot(n) * n).normalize();
    if ks_weight > 0.0 && weight * ks_weight >= MINWEIGHT {
        let r = Ray::new(near, turn(snap, surf, near, reflected(), n, 1.0, ctx));
        i += ks_weight * raytrace(snap, &r, weight * ks_weight, depth + 1, ctx);
    }
    if kt_weight > 0.0 && weight * kt_weight >= MINWEIGHT {
        let eta = if entering { 1.0 / surf.index } else { surf.index };
        let t = match refract(d, n, eta) {
            Some(t) => Ray::new(far, turn(snap, surf, far, t, n, -1.0, ctx)),
            None => {
                ctx.stats.kftircnt += 1;
                Ray::new(near, turn(snap, surf, near, reflected(), n, 1.0, ctx))
            }
        };
        i += kt_weight * raytrace(snap, &t, weight * kt_weight, depth + 1, ctx);
    }
    i
}

/// The direction `dir` of a secondary ray from `p`, turned as the
/// surface's `gloss` says ([`glossy`], the port's extension); `gloss 0`,
/// the mirror, keeps it and draws nothing.
fn turn(snap: &Snapshot, surf: &SurfaceRecord, p: DVec3, dir: DVec3, n: DVec3, side: f64, ctx: &mut Context) -> DVec3 {
    if surf.gloss > 0.0 {
        glossy(p, dir, n, side, surf.gloss, snap.opts.fidelity, ctx.sampler)
    } else {
        dir
    }
}

/// Σ (N·L̂j) · light colour over the lights a shadow ray from `p` reaches,
/// each shadow ray attenuated by the `crystal` objects it passes. A sphere
/// of light (`radius` > 0) sends each sample's shadow ray to a point of it
/// of the sample's own ([`toward_light`]): the mean over a pixel's samples
/// is Cook 1984's penumbra.
fn diffuse(snap: &Snapshot, p: DVec3, n: DVec3, ctx: &mut Context) -> Intensity {
    let mut sum = Intensity::ZERO;
    for light in &snap.scene.lights {
        // A sphere of light (the port's extension) surrounding `p` lights
        // it fully, as from its centre, with nothing between.
        let Some((l, dist)) = toward_light(light, p, ctx.sampler) else {
            let to = light.position - p;
            let cos = if to == DVec3::ZERO {
                1.0
            } else {
                n.dot(to.normalize()).max(0.0)
            };
            sum += cos * light.color;
            continue;
        };
        let cos = n.dot(l);
        if cos <= 0.0 {
            continue;
        }
        ctx.stats.shadow_rays += 1;
        let transmit = shadow(snap, Ray::new(p, l), dist, ctx.stats);
        sum += cos * light.color * transmit;
    }
    sum
}

/// How much light passes along a shadow ray to a light `dist` away: none
/// past an opaque object; through each `crystal` object once (its two
/// walls count as one), kt·colour of it, taken in the object table's order.
fn shadow(snap: &Snapshot, ray: Ray, dist: f64, stats: &mut TraceStats) -> Intensity {
    let mut transmit = Intensity::ONE;
    let stopped = for_each_blocker(snap, &ray, TMIN, dist, &mut stats.searched, |i| {
        let surf = &snap.scene.surfaces[snap.scene.objects[i].surface];
        transmit *= surf.kt * surf.color;
    });
    if stopped.is_break() {
        Intensity::ZERO
    } else {
        transmit
    }
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

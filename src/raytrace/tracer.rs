//! One worker's scratch: where every object stands at the instant being
//! traced, the in-between contours, and the counts. What the listing's
//! `motionblur` wrote into the shared records for each ray, each worker
//! keeps here (legacy_pascal/README.md, "State").

use super::Prepared;
use crate::intersect::{Deforming, Poses, Scratch, Snapshot};
use crate::reconstruct::{Features, Gathered};
use crate::sampler::Sampler;
use crate::trace::{intersect, raytrace, shade, surface_color, Context, TraceStats};
use crate::types::{Intensity, IntersectionRecord, Ray, SurfaceAttribute};

pub(super) struct Tracer<'p> {
    prepared: &'p Prepared,
    poses: Poses<'p>,
    deforming: Vec<Deforming<'p>>,
    scratch: Scratch,
    /// The time segment of the instant in the prepared structure; `None`
    /// where the loop searches: always without a structure, and with one
    /// for an instant a caller chose outside the render's times
    /// ([`Tracer::at_any`]; a render's are all inside, [`Tracer::at`]).
    segment: Option<usize>,
    pub(super) stats: TraceStats,
}

impl<'p> Tracer<'p> {
    pub(super) fn new(prepared: &'p Prepared) -> Self {
        Tracer {
            prepared,
            poses: prepared.poses(),
            deforming: prepared.deforming(),
            scratch: Scratch::default(),
            segment: prepared.aggregate().structure().map(|_| 0),
            stats: TraceStats::default(),
        }
    }

    /// The scene at film time `time`: `motionblur` poses every moving
    /// object; its `paper = 1` branch moves the in-between object's pose by
    /// `diff`, and the contour (`do34` at time 0 or 1, else `Hermite`) is
    /// made when a ray first needs it. A moving object is posed when a ray
    /// first reaches it ([`Poses`]); objects that do not move keep their
    /// rest pose at no cost. The structure over the objects bounds every
    /// time a sample of the render can have ([`Prepared::time_span`]);
    /// the instant's segment of it is found here, once.
    #[inline(always)]
    pub(super) fn at(&mut self, time: f64) {
        self.poses.at(time);
        for d in &self.deforming {
            d.at(time);
        }
        self.segment = self.prepared.aggregate().structure().map(|s| s.segment(time));
    }

    /// [`Tracer::at`] for a time a caller chose, which may lie outside the
    /// times the render's samples have: the loop searches it there.
    pub(super) fn at_any(&mut self, time: f64) {
        self.at(time);
        self.segment = self.segment.filter(|_| self.prepared.bounds_time(time));
    }

    /// The scene as the last [`Tracer::at`] left it, to shoot primary rays
    /// into until the next instant (made once for all of them).
    pub(super) fn instant(&mut self) -> Instant<'_> {
        Instant {
            snap: snapshot(self.prepared, &self.poses, &self.deforming, &self.scratch, self.segment),
            stats: &mut self.stats,
        }
    }

    /// [`Instant::shoot`] with the scene as the last [`Tracer::at`] left it.
    pub(super) fn shoot(&mut self, aray: &Ray, sampler: &mut dyn Sampler) -> Intensity {
        self.instant().shoot(aray, sampler)
    }

    /// [`Instant::shoot_features`] with the scene as the last
    /// [`Tracer::at`] left it.
    pub(super) fn shoot_features(&mut self, aray: &Ray, sampler: &mut dyn Sampler) -> (Intensity, Features) {
        self.instant().shoot_features(aray, sampler)
    }

    /// The object `ray` meets first with the scene as the last
    /// [`Tracer::at`] left it, and the hit.
    pub(super) fn first_hit(&mut self, ray: &Ray) -> Option<IntersectionRecord> {
        let snap = snapshot(self.prepared, &self.poses, &self.deforming, &self.scratch, self.segment);
        intersect(&snap, ray, &mut self.stats)
    }
}

/// The scene at one instant, where a worker's [`Tracer::at`] left it, and
/// the worker's counts: what the primary rays of that instant's samples
/// are shot into.
pub(super) struct Instant<'t> {
    snap: Snapshot<'t>,
    stats: &'t mut TraceStats,
}

impl Instant<'_> {
    /// The next instant, film time `time`, where a structure's rays ask
    /// for the moving objects' poses ([`Poses::at_asked`]): what
    /// [`Tracer::at`] does, in this snapshot, which then serves the new
    /// instant without being made again. False, and nothing done, for the
    /// loop, which poses every object at once.
    #[inline(always)]
    pub(super) fn at_asked(&mut self, time: f64) -> bool {
        let Some(structure) = self.snap.structure else {
            return false;
        };
        if !self.snap.poses.at_asked(time) {
            return false;
        }
        for d in self.snap.deforming {
            d.at(time);
        }
        self.snap.segment = structure.segment(time);
        true
    }

    /// `raytrace(aray, 1.0, false, acolor, 1)` of the primary ray `aray`
    /// of `sampler`'s sample.
    pub(super) fn shoot(&mut self, aray: &Ray, sampler: &mut dyn Sampler) -> Intensity {
        self.stats.primary += 1;
        let mut ctx = Context {
            stats: self.stats,
            sampler,
        };
        raytrace(&self.snap, aray, 1.0, 1, &mut ctx)
    }

    /// As [`Instant::shoot`], and what the first hit tells besides the
    /// colour, for a reconstruction that reads it: the same colour, from
    /// the same one search for the first hit.
    pub(super) fn shoot_features(&mut self, aray: &Ray, sampler: &mut dyn Sampler) -> (Intensity, Features) {
        let snap = &self.snap;
        self.stats.primary += 1;
        self.stats.rays += 1;
        let Some(hit) = intersect(snap, aray, self.stats) else {
            let background = snap.scene.backgrnd;
            let f = Features {
                albedo: background,
                ..Features::default()
            };
            return (background, f);
        };
        let mut ctx = Context {
            stats: self.stats,
            sampler,
        };
        let colour = shade(snap, aray, &hit, 1.0, 1, &mut ctx);
        let surf = &snap.scene.surfaces[hit.surface];
        let albedo = match surf.surface {
            SurfaceAttribute::Background | SurfaceAttribute::Light => colour,
            _ => surface_color(snap, surf, &hit),
        };
        let normal = if hit.normal.dot(aray.dir) < 0.0 {
            hit.normal
        } else {
            -hit.normal
        };
        let f = Features {
            albedo,
            normal,
            object: Some(hit.object),
        };
        (colour, f)
    }
}

/// How a render loop shoots a sample's primary ray: for its colour alone
/// (`()`, the box of `antialias`) or also gathering its features into
/// the pixel's [`Gathered`], for a reconstruction that reads them.
pub(super) trait Shot: Clone + Default + Send + Sync {
    /// The sample's colour, the ray `aray` shot by `tracer`.
    fn shoot(&mut self, tracer: &mut Tracer, aray: &Ray, sampler: &mut dyn Sampler) -> Intensity;
}

impl Shot for () {
    #[inline]
    fn shoot(&mut self, tracer: &mut Tracer, aray: &Ray, sampler: &mut dyn Sampler) -> Intensity {
        tracer.shoot(aray, sampler)
    }
}

impl Shot for Gathered {
    fn shoot(&mut self, tracer: &mut Tracer, aray: &Ray, sampler: &mut dyn Sampler) -> Intensity {
        let (colour, features) = tracer.shoot_features(aray, sampler);
        self.add(colour, &features);
        colour
    }
}

/// The prepared scene with its objects where `poses` put them and the
/// deforming objects' contours of the instant, searched by the prepared
/// structure in the instant's time `segment`, or by the loop (`None`).
fn snapshot<'a>(
    prepared: &'a Prepared,
    poses: &'a Poses<'a>,
    deforming: &'a [Deforming<'a>],
    scratch: &'a Scratch,
    segment: Option<usize>,
) -> Snapshot<'a> {
    Snapshot {
        scene: prepared.scene(),
        opts: prepared.options(),
        poses,
        all: poses.all(),
        deforming,
        deforming_of: prepared.deforming_of(),
        caches: prepared.caches(),
        aggregate: prepared.aggregate(),
        structure: prepared.aggregate().structure().filter(|_| segment.is_some()),
        segment: segment.unwrap_or(0),
        scratch,
    }
}

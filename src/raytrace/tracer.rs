//! One worker's scratch: where every object stands at the instant being
//! traced, the in-between contours, and the counts. What the listing's
//! `motionblur` wrote into the shared records for each ray, each worker
//! keeps here (legacy_pascal/README.md, "State").

use super::Prepared;
use crate::intersect::{rest_poses, Deforming, Snapshot};
use crate::sampler::Sampler;
use crate::trace::{intersect, raytrace, Context, TraceStats};
use crate::types::{Intensity, IntersectionRecord, Pose, Ray};

pub(super) struct Tracer<'p> {
    prepared: &'p Prepared,
    poses: Vec<Pose>,
    deforming: Vec<Deforming<'p>>,
    pub(super) stats: TraceStats,
}

impl<'p> Tracer<'p> {
    pub(super) fn new(prepared: &'p Prepared) -> Self {
        Tracer {
            prepared,
            poses: rest_poses(prepared.scene()),
            deforming: prepared
                .moving()
                .iter()
                .filter_map(|m| m.chain().map(|chain| Deforming::new(m.object, chain)))
                .collect(),
            stats: TraceStats::default(),
        }
    }

    /// The scene at film time `time`: `motionblur` poses every moving
    /// object; its `paper = 1` branch moves the in-between object's pose by
    /// `diff`, and the contour (`do34` at time 0 or 1, else `Hermite`) is
    /// made when a ray first needs it. Objects that do not move keep their
    /// rest pose at no cost.
    pub(super) fn at(&mut self, time: f64) {
        let prepared = self.prepared;
        let (objects, fidelity) = (&prepared.scene().objects, prepared.options().fidelity);
        for m in prepared.moving() {
            self.poses[m.object] = m.pose(&objects[m.object], time, fidelity);
        }
        for d in &self.deforming {
            d.at(time);
        }
    }

    /// `raytrace(aray, 1.0, false, acolor, 1)` of the primary ray `aray`
    /// of `sampler`'s sample, with the scene as the last [`Tracer::at`]
    /// left it.
    pub(super) fn shoot(&mut self, aray: &Ray, sampler: &mut dyn Sampler) -> Intensity {
        let snap = snapshot(self.prepared, &self.poses, &self.deforming);
        self.stats.primary += 1;
        let mut ctx = Context {
            stats: &mut self.stats,
            sampler,
        };
        raytrace(&snap, aray, 1.0, 1, &mut ctx)
    }

    /// The object `ray` meets first with the scene as the last
    /// [`Tracer::at`] left it, and the hit.
    pub(super) fn first_hit(&mut self, ray: &Ray) -> Option<IntersectionRecord> {
        let snap = snapshot(self.prepared, &self.poses, &self.deforming);
        intersect(&snap, ray, &mut self.stats)
    }
}

/// The prepared scene with its objects where `poses` put them and the
/// deforming objects' contours of the instant.
fn snapshot<'a>(prepared: &'a Prepared, poses: &'a [Pose], deforming: &'a [Deforming<'a>]) -> Snapshot<'a> {
    Snapshot {
        scene: prepared.scene(),
        opts: prepared.options(),
        poses,
        deforming,
        deforming_of: prepared.deforming_of(),
        caches: prepared.caches(),
        aggregate: prepared.aggregate(),
    }
}

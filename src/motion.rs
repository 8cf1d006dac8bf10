//! What moves over the shutter, each kind of motion in one place: where it
//! puts its object at a time ([`Moving::pose`]) and where it can put the
//! object's origin over an interval of time ([`Moving::centre_bounds`]).
//!
//! Two kinds, as the main program has them: an object of the motion table
//! (`motionblur`'s non-key-frame branch: the user's path and law of §3.2.2,
//! or in `listing` fidelity the fixed slide of erratum 3, both in
//! [`crate::drt`]), and the in-between object of a key-frame chain (the
//! `paper = 1` branch: its pose from `goahead`'s `diff` and `diffangle`,
//! [`PaperChain::pose`]; its contour is made where a ray needs it,
//! `crate::intersect::Deforming`); the port's chains of blobs or of
//! patches ([`PointChain`]) are the same kind. The arrangement is the
//! port's: the listing's `motionblur` does both for every ray.

use crate::accel::{Aabb, Bounds, Segments, USE_UNION};
use crate::drt::{motion_bounds, motion_place, motionblur, Isblur};
use crate::options::Fidelity;
use crate::paper::{KeyChain, PaperChain, PointChain};
use crate::scene::{Law, MotionRecord, Scene};
use crate::types::{BoundingBox, DMat3, DVec3, ObjectRecord, Pose};

/// How much wider than the exact bounds [`Moving::centre_bounds`] are,
/// relative to the size of their coordinates: a path's point is a cubic
/// of sums of products, whose rounding is a few units in the last place
/// of its largest term (2⁻⁵² ≈ 2·10⁻¹⁶).
pub const ROUNDING: f64 = 1e-12;

/// How an object moves.
#[derive(Clone, Debug, PartialEq)]
pub enum Motion {
    /// The object's `motion` record (§3.2.2).
    Path(MotionRecord),
    /// The chain of key shapes of `keyframe` record `record` (§3.2): the
    /// object is the chain's in-between object (FIRST's record).
    Chain { record: usize, chain: PaperChain },
    /// The chain of key blobs or key patches of `keyframe` record `record`
    /// (the port's extension, §6.2).
    Points { record: usize, chain: PointChain },
}

/// An object that moves, and how.
#[derive(Clone, Debug, PartialEq)]
pub struct Moving {
    /// Index into `scene.objects`.
    pub object: usize,
    pub motion: Motion,
}

impl Moving {
    /// Where the object stands at film time `time`, from `rest`, its record
    /// as the deck left it: `motionblur` of its path, or its chain's pose.
    pub fn pose(&self, rest: &ObjectRecord, time: f64, fidelity: Fidelity) -> Pose {
        let mut pose = Pose::IDENTITY;
        self.pose_into(rest, time, fidelity, &mut pose);
        pose
    }

    /// [`Moving::pose`] written over `pose`, as `motionblur` writes the
    /// object's record: made where it is kept, not copied there.
    #[inline]
    pub fn pose_into(&self, rest: &ObjectRecord, time: f64, fidelity: Fidelity, pose: &mut Pose) {
        match &self.motion {
            Motion::Path(record) => motionblur(rest, record, time, fidelity, pose),
            Motion::Chain { chain, .. } => *pose = chain.pose(time),
            Motion::Points { chain, .. } => *pose = chain.pose(time),
        }
    }

    /// Where [`Moving::pose`] puts the object's origin (`sphereo`) at film
    /// time `time`, the same to the bit, without the rest of the pose: what
    /// the bounding sphere's test needs.
    #[inline(always)]
    pub fn centre(&self, rest: &ObjectRecord, time: f64, fidelity: Fidelity) -> DVec3 {
        match &self.motion {
            Motion::Path(record) => motion_place(rest, record, time, fidelity).0,
            Motion::Chain { chain, .. } => chain.centre(time),
            Motion::Points { chain, .. } => chain.centre(time),
        }
    }

    /// The box the object's origin (`sphereo`) stays in over the film times
    /// `t0` ≤ t ≤ `t1` (the object itself lies within its `radius` of it):
    /// the motion's own bounds, widened by [`ROUNDING`] of their size so
    /// that they hold the origin as [`Moving::pose`] computes it, rounding
    /// and all.
    pub fn centre_bounds(&self, rest: &ObjectRecord, t0: f64, t1: f64, fidelity: Fidelity) -> BoundingBox {
        let b = match &self.motion {
            Motion::Path(record) => motion_bounds(rest, record, t0, t1, fidelity),
            Motion::Chain { chain, .. } => chain.centre_bounds(t0, t1),
            Motion::Points { chain, .. } => chain.centre_bounds(t0, t1),
        };
        rounded(b)
    }

    /// The box the object's surface stays in over the film times `t0` ≤ t
    /// ≤ `t1`, where the motion knows one tighter than its origin's box
    /// widened by the object's radius: a chain of blobs or patches sweeps
    /// its components' spheres or its control hull
    /// ([`PointChain::world_bounds`]), widened as
    /// [`Moving::centre_bounds`]. `None` for the other motions, and for a
    /// chain with no surface then (its origin's box, widened by its
    /// radius, then bounds it).
    pub fn swept_bounds(&self, t0: f64, t1: f64) -> Option<BoundingBox> {
        match &self.motion {
            Motion::Points { chain, .. } => chain.world_bounds(t0, t1).map(rounded),
            _ => None,
        }
    }

    /// The object's [`Glide`], if it glides: in `thesis` fidelity, a
    /// `motion` record with a straight path (no `via`) and no turn.
    pub fn glide(&self, rest: &ObjectRecord, fidelity: Fidelity) -> Option<Glide> {
        match (&self.motion, fidelity) {
            (Motion::Path(record), Fidelity::Thesis)
                if record.via.is_none() && record.turn.cmpeq(DVec3::ZERO).all() =>
            {
                // `motionblur`'s turn is then turn_xyz(0 · f), the identity,
                // at every time of finite f: its product with the rest
                // rotation is made once.
                let r = DMat3::IDENTITY * DMat3::from_mat4(rest.transfm);
                Some(Glide {
                    from: rest.sphereo,
                    delta: record.to - rest.sphereo,
                    law: record.law,
                    r,
                    rt: r.transpose(),
                })
            }
            _ => None,
        }
    }

    /// The chain, for the in-between object of a key-frame chain of
    /// sweeps.
    pub fn chain(&self) -> Option<&PaperChain> {
        match &self.motion {
            Motion::Chain { chain, .. } => Some(chain),
            _ => None,
        }
    }

    /// The chain of an in-between object, of sweeps or of blobs or patches.
    pub fn key_chain(&self) -> Option<KeyChain<'_>> {
        match &self.motion {
            Motion::Path(_) => None,
            Motion::Chain { chain, .. } => Some(KeyChain::Sweep(chain)),
            Motion::Points { chain, .. } => Some(KeyChain::Points(chain)),
        }
    }
}

/// A motion that only carries its object along a straight line (the
/// most common `motion` record: `to` alone, no `via`, no `turn`), kept
/// ready so that its pose costs what moving it costs: at the fraction f =
/// LAW(law, 1, t) of the way, its origin is `path_point`'s `from + (to −
/// from)·f` and its rotation the rest pose's, the same to the bit as
/// [`crate::drt::motionblur`] makes them for any finite f (the identity's
/// product with the rest rotation, and its transpose, made once). The
/// port's: the listing turned and moved every object for every ray.
#[derive(Clone, Debug, PartialEq)]
pub struct Glide {
    from: DVec3,
    /// `to − from`, as `path_point` takes it.
    delta: DVec3,
    law: Law,
    r: DMat3,
    rt: DMat3,
}

impl Glide {
    /// How far along the path a time is (its LAW).
    pub fn law(&self) -> Law {
        self.law
    }

    /// Where its origin (`sphereo`) stands at the fraction `f` of the way.
    #[inline(always)]
    pub fn centre(&self, f: f64) -> DVec3 {
        self.from + self.delta * f
    }

    /// Its pose at the fraction `f` of the way (finite), written over
    /// `pose`: [`Moving::pose_into`]'s, to the bit.
    #[inline(always)]
    pub fn pose_into(&self, f: f64, pose: &mut Pose) {
        pose.place(&self.r, &self.rt, self.centre(f));
    }

    /// [`Glide::pose_into`] over a pose it wrote before (at any fraction):
    /// the rotation is there, only the place is written.
    #[inline(always)]
    pub fn move_into(&self, f: f64, pose: &mut Pose) {
        pose.move_to(&self.rt, self.centre(f));
    }
}

/// Each moving object's [`Glide`], if it glides ([`Moving::glide`]), by
/// its index among the moving objects, and the laws they follow.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Glides {
    pub each: Vec<Option<Glide>>,
    /// Bit l set for each LAW l some glide follows (`Law as u8`).
    pub laws: u8,
}

impl Glides {
    /// The glides of `moving`, which moves `objects` (at rest).
    pub fn of(moving: &[Moving], objects: &[ObjectRecord], fidelity: Fidelity) -> Glides {
        let each: Vec<Option<Glide>> = moving.iter().map(|m| m.glide(&objects[m.object], fidelity)).collect();
        let laws = each.iter().flatten().fold(0, |b, g| b | 1 << g.law as u8);
        Glides { each, laws }
    }
}

/// `b` widened by [`ROUNDING`] of its size.
fn rounded(b: BoundingBox) -> BoundingBox {
    let size = [b.xmin, b.xmax, b.ymin, b.ymax, b.zmin, b.zmax]
        .iter()
        .fold(1.0f64, |m, v| m.max(v.abs()));
    b.widened(ROUNDING * size)
}

/// The objects of the motion table that move, in the object table's
/// order: the main program's `if not Isblur(tableindex, motionmatrix)`
/// asked once for each object before the scanline loop (not for every
/// ray: the answer does not change), with the motion table made of the
/// deck's `motion` records (`motionmatrix`). Each gets its record.
pub fn paths(scene: &Scene) -> Vec<Moving> {
    let motionmatrix: Vec<usize> = scene.motions.iter().map(|mo| mo.object).collect();
    (0..scene.objects.len())
        .filter(|&i| !Isblur(i, &motionmatrix))
        .filter_map(|i| {
            let record = scene.motions.iter().find(|mo| mo.object == i)?;
            Some(Moving {
                object: i,
                motion: Motion::Path(record.clone()),
            })
        })
        .collect()
}

/// How much wider than the bounding sphere an object's box is, relative to
/// the size of its coordinates: far above the rounding of a ray's box
/// test and of a hit's distance (a few parts in 10¹⁶), so a structure
/// never leaves out an object the loop would find.
pub const BOX_SLACK: f64 = 1e-9;

/// The most time segments a structure's boxes are kept for
/// ([`object_bounds`]).
pub const MAX_SEGMENTS: usize = 16;

/// How far, in its own widths, the farthest mover may go over one time
/// segment ([`object_bounds`]): 1. The runs of segments then hold one
/// segment each where the trees' memory allows, a tree a segment (a split
/// in time, Woop et al. 2017), and a node keeps no boxes over segments
/// within its tree. A quarter of a width, with four segments a run (the
/// nodes keeping their boxes over them), took 1,707 instructions and 5.2
/// first-level misses a sample on 1,000 spheres moving 4.6 radii, where
/// a width takes 1,659 and 4.8, and 5–7 % more CPU time; at two radii
/// (one segment, where a quarter took four) the two are within 1 %
/// (docs/scale.md).
pub const SEGMENT_WIDTHS: f64 = 1.0;

/// An object's box in the world over the film times `t0` ≤ t ≤ `t1`, for
/// `o` moved by `moving` (`None`: it does not move): the one function
/// every kind of object's bounds over time go through, for the whole of
/// the times a render can have and for each segment of them
/// ([`object_bounds`]). The box its origin stays in
/// ([`Moving::centre_bounds`], from each motion's own bounds: the path's
/// in `thesis` fidelity, erratum 3's slide in `listing` fidelity, the
/// key-frame chain's), widened by the bounding sphere the intersection
/// tests first ([`crate::shapes::bounding_radius`] of the object's
/// `radius`, as `prepare` widened it to hold its own box, or its chain's
/// at every time), or for a chain of blobs or patches its surface's own
/// swept box ([`Moving::swept_bounds`]), and by [`BOX_SLACK`]. The object lies within its
/// radius of its origin whichever way it turns, so the box holds it at
/// every time of the interval. An object that does not move is held
/// tighter where its shape's own box ([`crate::shapes::local_box`])
/// turned into the world is smaller. The port's (the thesis bounds
/// objects at rest only).
pub fn object_box(o: &ObjectRecord, moving: Option<&Moving>, t0: f64, t1: f64, fidelity: Fidelity) -> BoundingBox {
    let r = crate::shapes::bounding_radius(o.radius);
    let b = match moving {
        Some(m) => match m.swept_bounds(t0, t1) {
            Some(swept) => swept,
            None => m.centre_bounds(o, t0, t1, fidelity).widened(r),
        },
        None => {
            let sphere = BoundingBox::EMPTY.holding(o.sphereo).widened(r);
            match crate::shapes::local_box(o) {
                Some(local) => intersection(&sphere, &world_box(&local, o).widened(r - o.radius)),
                None => sphere,
            }
        }
    };
    let size = [b.xmin, b.xmax, b.ymin, b.ymax, b.zmin, b.zmax]
        .iter()
        .fold(1.0f64, |m, v| m.max(v.abs()));
    b.widened(BOX_SLACK * size)
}

/// Each object's box over the film times `t0` ≤ t ≤ `t1`
/// ([`object_box`]), by index.
pub fn object_boxes(
    objects: &[ObjectRecord],
    moving: &[Moving],
    t0: f64,
    t1: f64,
    fidelity: Fidelity,
) -> Vec<BoundingBox> {
    let mut by_object: Vec<Option<&Moving>> = vec![None; objects.len()];
    for m in moving {
        by_object[m.object] = Some(m);
    }
    objects
        .iter()
        .zip(by_object)
        .map(|(o, m)| object_box(o, m, t0, t1, fidelity))
        .collect()
}

/// Each object's boxes over the film times `span` a render can have, for
/// a structure over the objects ([`Bounds`]): over all of them, and, for
/// an object that moves far against its size, over each of the segments
/// the times are cut into. How far: an object's box over all the times
/// against its box at one instant, on the axis where the path stretches
/// it most, the path's length in its own widths, w; the times are cut
/// into the power of two of segments (at most [`MAX_SEGMENTS`]) that
/// makes the largest w among the moving objects its width or less a
/// segment ([`SEGMENT_WIDTHS`]), and an object keeps its boxes over them
/// when its box over all the times has more than 1.4 times their mean area
/// (psychopath's rule, as the hierarchy's nodes: `crate::accel`). Nothing
/// moving far: one segment, one box an object.
pub fn object_bounds(objects: &[ObjectRecord], moving: &[Moving], span: (f64, f64), fidelity: Fidelity) -> Bounds {
    let (t0, t1) = span;
    let whole = object_boxes(objects, moving, t0, t1, fidelity);
    let reach = moving.iter().fold(0.0f64, |w, m| {
        let o = &objects[m.object];
        w.max(stretch(&whole[m.object], &object_box(o, Some(m), t0, t0, fidelity)))
    });
    let mut count = 1;
    while count < MAX_SEGMENTS && (count as f64) * SEGMENT_WIDTHS < reach {
        count *= 2;
    }
    let segments = Segments::new(t0, t1, count);
    let mut timed = vec![Vec::new(); objects.len()];
    if count > 1 {
        for m in moving {
            let o = &objects[m.object];
            let boxes: Vec<BoundingBox> = (0..count)
                .map(|k| {
                    let (a, b) = segments.span(k);
                    object_box(o, Some(m), a, b, fidelity)
                })
                .collect();
            let area = |b: &BoundingBox| Aabb::of(b).half_area();
            let mean = boxes.iter().map(area).sum::<f64>() / count as f64;
            if area(&whole[m.object]) > USE_UNION * mean {
                timed[m.object] = boxes;
            }
        }
    }
    // A tree of its own for each run of segments over which the farthest
    // mover goes its width or less (a power of two, as the segments are),
    // while the trees together keep within RUN_OBJECTS objects.
    let mut runs = 1;
    while runs < count && (runs as f64) < reach && 2 * runs * objects.len() <= RUN_OBJECTS {
        runs *= 2;
    }
    Bounds {
        segments,
        whole,
        timed,
        runs,
    }
}

/// The most objects the hierarchy's trees over the runs of time segments
/// hold together ([`object_bounds`]): a bound on their memory.
pub(crate) const RUN_OBJECTS: usize = 4_000_000;

/// How much `whole` outstretches `instant` on the axis where it does most,
/// in widths of `instant` (0 for boxes that are not finite).
fn stretch(whole: &BoundingBox, instant: &BoundingBox) -> f64 {
    let spans = |b: &BoundingBox| [b.xmax - b.xmin, b.ymax - b.ymin, b.zmax - b.zmin];
    let (w, i) = (spans(whole), spans(instant));
    let most = (0..3).map(|k| (w[k] - i[k]) / i[k]).fold(0.0f64, f64::max);
    if most.is_finite() {
        most
    } else {
        0.0
    }
}

/// The world box of the local box `b` of object `o` at rest: its eight
/// corners carried by `transfm`.
fn world_box(b: &BoundingBox, o: &ObjectRecord) -> BoundingBox {
    let mut w = BoundingBox::EMPTY;
    for &x in &[b.xmin, b.xmax] {
        for &y in &[b.ymin, b.ymax] {
            for &z in &[b.zmin, b.zmax] {
                w = w.holding(o.transfm.transform_point3(crate::types::DVec3::new(x, y, z)));
            }
        }
    }
    w
}

/// The box both boxes hold (a NaN in either leaves the other's bound).
fn intersection(a: &BoundingBox, b: &BoundingBox) -> BoundingBox {
    BoundingBox {
        xmin: a.xmin.max(b.xmin),
        xmax: a.xmax.min(b.xmax),
        ymin: a.ymin.max(b.ymin),
        ymax: a.ymax.min(b.ymax),
        zmin: a.zmin.max(b.zmin),
        zmax: a.zmax.min(b.zmax),
    }
}

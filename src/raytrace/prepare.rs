//! The set-up the main program does between `initialize` and the scanline
//! loop, done once into a [`Prepared`] scene that every render reads.

use std::sync::Arc;

use super::{Camera, RenderError};
use crate::accel::{Accel, Structure};
use crate::drt::TimeTable;
use crate::intersect::{rest_poses, Aggregate, Deforming, Poses};
use crate::motion::{object_bounds, paths, Glides, Motion, Moving};
use crate::options::{Fidelity, Options, TimeSampler};
use crate::paper::{PaperChain, PointChain};
use crate::sampler::Tables;
use crate::scene::{KeyframeRecord, Scene};
use crate::shapes::ShapeCache;
use crate::types::{BoundingBox, DVec3, Pose, Shape};

/// A scene ready to render with its options: made once by
/// [`Prepared::new`], then read by every render of it (a still, each
/// frame of a film, each window of rows). Nothing in it is made again by a
/// render, and nothing falls back to a default: what cannot be prepared is
/// an error here.
#[derive(Clone, Debug)]
pub struct Prepared {
    scene: Scene,
    opts: Options,
    camera: Camera,
    /// The lookup tables the samplers read (the subpixel times among them).
    tables: Tables,
    /// What moves over the shutter: the motion table's objects (those
    /// `Isblur` says move), then each key-frame chain's in-between object.
    moving: Vec<Moving>,
    /// For each object, the index in `moving` of its chain if it deforms.
    deforming_of: Vec<Option<usize>>,
    /// For each object, its index in `moving` if it moves.
    moving_of: Vec<Option<usize>>,
    /// For each of `moving`, its glide if it glides ([`Moving::glide`]).
    glides: Glides,
    /// Where the key-frame chains start in `moving` (after the paths).
    first_chain: usize,
    /// Every object at rest.
    rest: Vec<Pose>,
    /// What `shapes` prepared for each object's own shape.
    caches: Vec<Option<Arc<ShapeCache>>>,
    aggregate: Aggregate,
    /// The film times the aggregate's structure bounds the objects over:
    /// every time a sample can have. The structure is searched at every
    /// sample's time, so it must hold them all: a time outside would find
    /// an object where it is not.
    span: (f64, f64),
    /// Whether the samples' times come back (the table's, without
    /// jitter): the loop then keeps each instant's poses for its return.
    repeats: bool,
}

impl Prepared {
    /// The scene `initialize` read, set up for rendering with `opts`: the
    /// subpixel time table (its `pattern` and `blur` records checked); the
    /// sweeps' coefficients and boxes (`spline`, and in `listing` fidelity
    /// `goahead`'s widening of `tbox`); `goahead` for each key-frame pair,
    /// the in-between object's bounding sphere widened to hold its contour
    /// at every time; the motion table; the shapes' caches; the camera;
    /// the structure over the objects `opts.accel` chooses (`--accel`: the
    /// picture is the same whichever it is).
    pub fn new(mut scene: Scene, opts: Options) -> Result<Prepared, RenderError> {
        crate::adaptive::check(&opts).map_err(RenderError::Options)?;
        let fidelity = opts.fidelity;
        let times = time_table(&scene, fidelity)?;
        crate::shapes::sweep::prepare_sweeps(&mut scene, fidelity);
        crate::paper::widen_tbox(&mut scene, fidelity);
        let chains = key_frame_chains(&scene, fidelity)?;
        for (k, chain) in &chains {
            widen_to_hold(&mut scene, *k, &chain.bbox());
        }
        let points = point_chains(&scene, fidelity)?;
        // A chain of blobs or patches over the times the render's samples
        // take.
        let span = film_span(&scene, &times);
        for (k, chain) in &points {
            if let Some(b) = chain.local_bounds(span.0, span.1) {
                widen_to_hold(&mut scene, *k, &b);
            }
        }
        let caches = crate::shapes::prepare_caches(&scene);
        let mut moving = paths(&scene);
        moving.extend(chains.into_iter().map(|(record, chain)| Moving {
            object: scene.keyframes[record].first,
            motion: Motion::Chain { record, chain },
        }));
        moving.extend(points.into_iter().map(|(record, chain)| Moving {
            object: scene.keyframes[record].first,
            motion: Motion::Points { record, chain },
        }));
        Ok(Prepared::assemble(
            scene,
            opts,
            Tables::new(times),
            moving,
            caches,
            opts.accel,
        ))
    }

    /// The parts made into one: what depends on the scene alone (the
    /// camera, the aggregate, who moves and who deforms) made here.
    fn assemble(
        scene: Scene,
        opts: Options,
        tables: Tables,
        moving: Vec<Moving>,
        caches: Vec<Option<Arc<ShapeCache>>>,
        accel: Accel,
    ) -> Prepared {
        let mut deforming_of = vec![None; scene.objects.len()];
        let chains = moving.iter().enumerate().filter(|(_, m)| m.key_chain().is_some());
        for (d, (_, m)) in chains.enumerate() {
            deforming_of[m.object] = Some(d);
        }
        let mut moving_of = vec![None; scene.objects.len()];
        for (k, m) in moving.iter().enumerate() {
            moving_of[m.object] = Some(k);
        }
        let glides = Glides::of(&moving, &scene.objects, opts.fidelity);
        let first_chain = moving.iter().take_while(|m| m.key_chain().is_none()).count();
        let span = film_span(&scene, &tables.times);
        let structure = match accel.resolve(scene.objects.len()) {
            Accel::None => None,
            kind => Structure::build(kind, &object_bounds(&scene.objects, &moving, span, opts.fidelity)),
        };
        let counted = opts.sampler == TimeSampler::Adaptive;
        let repeats = opts.sampler == TimeSampler::Table && tables.times.repeats();
        Prepared {
            camera: Camera::new(&scene, opts.fidelity),
            aggregate: Aggregate::new(&scene, structure, counted),
            rest: rest_poses(&scene),
            scene,
            opts,
            tables,
            moving,
            deforming_of,
            moving_of,
            glides,
            first_chain,
            caches,
            span,
            repeats,
        }
    }

    /// The scene, set up.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The options it was prepared with.
    pub fn options(&self) -> &Options {
        &self.opts
    }

    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    pub fn tables(&self) -> &Tables {
        &self.tables
    }

    /// What moves over the shutter.
    pub fn moving(&self) -> &[Moving] {
        &self.moving
    }

    /// For each object, the index of its chain among the deforming objects
    /// (the chains of [`Prepared::chains`], in order), if it deforms.
    pub fn deforming_of(&self) -> &[Option<usize>] {
        &self.deforming_of
    }

    pub fn caches(&self) -> &[Option<Arc<ShapeCache>>] {
        &self.caches
    }

    pub fn aggregate(&self) -> &Aggregate {
        &self.aggregate
    }

    /// For each object, its index in [`Prepared::moving`] if it moves.
    pub fn moving_of(&self) -> &[Option<usize>] {
        &self.moving_of
    }

    /// Every object at rest, where the deck left it.
    pub fn rest(&self) -> &[Pose] {
        &self.rest
    }

    /// A worker's poses of the objects, at rest until [`Poses::at`]: all
    /// posed at each instant for the loop, each when a ray reaches it for
    /// a structure.
    pub fn poses(&self) -> Poses<'_> {
        let (fidelity, eager) = (self.opts.fidelity, self.aggregate.structure().is_none());
        Poses::new(
            &self.scene.objects,
            &self.rest,
            &self.moving,
            &self.moving_of,
            fidelity,
            eager,
            self.repeats,
        )
        .gliding(&self.glides)
    }

    /// A worker's scratch for the deforming objects' contours, one a chain.
    pub fn deforming(&self) -> Vec<Deforming<'_>> {
        // (The chains follow the paths: a row's worker need not look at
        // every path.)
        self.moving[self.first_chain..]
            .iter()
            .filter_map(|m| m.key_chain().map(|chain| Deforming::new(m.object, chain)))
            .collect()
    }

    /// The least and greatest film time a sample of a render can have:
    /// the times over which the aggregate's structure bounds the objects.
    pub fn time_span(&self) -> (f64, f64) {
        self.span
    }

    /// Does the aggregate's structure hold the objects where they stand at
    /// film time `time` ([`Prepared::time_span`])?
    pub fn bounds_time(&self, time: f64) -> bool {
        time >= self.span.0 && time <= self.span.1
    }

    /// Does anything move or deform (so each sample needs its time)?
    pub fn timed(&self) -> bool {
        !self.moving.is_empty()
    }

    /// Do the table's subpixel times come back at every subpixel of the
    /// same place in the table (`--sampler table` and
    /// [`TimeTable::repeats`](crate::drt::TimeTable::repeats))?
    pub fn repeats(&self) -> bool {
        self.repeats
    }

    /// The key-frame chains, in the order of their `keyframe` records.
    pub fn chains(&self) -> impl Iterator<Item = &PaperChain> {
        self.moving.iter().filter_map(Moving::chain)
    }

    /// The scene as it stands at one film time `time`, still: every moving
    /// object at its pose then (`motionblur`), every key-frame object at its
    /// in-between contour and pose, and nothing left to move. For looking at
    /// in-between shapes without blur (`tools frames`), and for tests.
    pub fn still_at(&self, time: f64) -> Prepared {
        let mut still = self.scene.clone();
        let mut caches = self.caches.clone();
        for m in &self.moving {
            let obj = &mut still.objects[m.object];
            if let Some(chain) = m.key_chain() {
                let mut contour = chain.scratch();
                chain.inbetween(time, &mut contour);
                obj.shape = contour;
                // A contour of the moment: nothing was prepared for it.
                caches[m.object] = None;
            }
            let pose = m.pose(&self.scene.objects[m.object], time, self.opts.fidelity);
            (obj.transfm, obj.inverse, obj.sphereo) = (pose.transfm, pose.inverse, pose.sphereo);
        }
        still.motions.clear();
        still.keyframes.clear();
        let accel = match self.aggregate.structure() {
            None => Accel::None,
            Some(Structure::Bvh(_)) => Accel::Bvh,
            Some(Structure::Octree(_)) => Accel::Octree,
        };
        Prepared::assemble(still, self.opts, self.tables.clone(), Vec::new(), caches, accel)
    }
}

/// The film times a sample of `scene` can have: the subpixel times τ of
/// its table ([`TimeTable::span`]) or of any other sampler (0 to 1), as
/// the first and the last frame of its film map them (`crate::film`).
fn film_span(scene: &Scene, times: &TimeTable) -> (f64, f64) {
    let (a, b) = times.span();
    let (tau0, tau1) = (a.min(0.0), b.max(1.0));
    let Some(film) = &scene.film else {
        return (tau0, tau1);
    };
    let (first, last) = (film.frame(1), film.frame(film.frames));
    let corners = [first.time(tau0), first.time(tau1), last.time(tau0), last.time(tau1)];
    corners.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
        (lo.min(t), hi.max(t))
    })
}

/// The subpixel times of a scene: its `pattern` and `blur` records, or
/// the defaults; a pattern that does not fit the mask is an error at its
/// record.
pub fn time_table(scene: &Scene, fidelity: Fidelity) -> Result<TimeTable, RenderError> {
    let blur = scene.blur.as_ref().map_or(0, |b| b.n);
    TimeTable::new(scene.image.masksize, scene.pattern.as_ref(), blur, fidelity).map_err(|message| {
        let pos = scene.pattern.as_ref().map(|p| p.pos.clone()).unwrap_or_default();
        RenderError::Misfit {
            pos,
            record: "pattern",
            message,
        }
    })
}

/// Is `record` a chain of blobs or of patches (the port's extension)?
fn of_points(scene: &Scene, record: &KeyframeRecord) -> bool {
    scene
        .objects
        .get(record.first)
        .is_some_and(|o| matches!(o.shape, Shape::Blob(_) | Shape::Patch(_)))
}

/// The chains `make` makes of the `keyframe` records of blobs or patches
/// (`points`) or of the others, with each record's index; a record it
/// cannot make is an error at the record.
fn chains<C, E: std::fmt::Display>(
    scene: &Scene,
    points: bool,
    make: impl Fn(&KeyframeRecord) -> Result<C, E>,
) -> Result<Vec<(usize, C)>, RenderError> {
    scene
        .keyframes
        .iter()
        .enumerate()
        .filter(|(_, record)| of_points(scene, record) == points)
        .map(|(k, record)| {
            make(record).map(|chain| (k, chain)).map_err(|e| RenderError::Misfit {
                pos: record.pos.clone(),
                record: "keyframe",
                message: e.to_string(),
            })
        })
        .collect()
}

/// `goahead(i2, …)` for every key-frame pair of the main program
/// (`for i2 := 1 to papernumber`): the chain of each `keyframe` record of
/// sweeps, with the record's index (the chains of blobs and patches are
/// `point_chains`).
pub fn key_frame_chains(scene: &Scene, fidelity: Fidelity) -> Result<Vec<(usize, PaperChain)>, RenderError> {
    chains(scene, false, |record| {
        PaperChain::from_keyframe(scene, record, fidelity)
    })
}

/// The chains of the `keyframe` records of blobs or of patches (the port's
/// extension, §6.2: `PointChain`), with each record's index.
pub(crate) fn point_chains(scene: &Scene, fidelity: Fidelity) -> Result<Vec<(usize, PointChain)>, RenderError> {
    chains(scene, true, |record| PointChain::from_keyframe(scene, record, fidelity))
}

/// The bounding-sphere `radius` of keyframe record `k`'s in-between object
/// widened to hold its local box `b` at every time (a sweep chain's
/// `bbox`, a blob or patch chain's box over the render's times).
fn widen_to_hold(scene: &mut Scene, k: usize, b: &BoundingBox) {
    let corner = DVec3::new(
        b.xmin.abs().max(b.xmax.abs()),
        b.ymin.abs().max(b.ymax.abs()),
        b.zmin.abs().max(b.zmax.abs()),
    );
    let first = scene.keyframes[k].first;
    if corner.is_finite() {
        scene.objects[first].radius = scene.objects[first].radius.max(corner.length() * (1.0 + 1e-9));
    }
}

//! Which object a ray meets: the one seam every way of finding it plugs
//! into. [`nearest`] for the rays `raytrace` shades, [`for_each_blocker`]
//! for the shadow rays (a `crystal` object lets light through, so a plain
//! yes or no is not enough). The backend is the original's loop over the
//! object table ([`Aggregate`] without a structure, `--accel none`); structures over the objects are
//! the port's and go beside it.
//!
//! What every backend answers as the loop does, written down: of two hits
//! at the same t, the object earlier in the table (the lower index) is the
//! nearest ([`closer`]); a shadow ray is stopped by any opaque object on
//! it, whichever is found first, and otherwise passes each `crystal`
//! object on it, taken in the table's order (the product of their
//! transmittances is then the same to the bit).

use std::cell::{Cell, Ref, RefCell};
use std::ops::ControlFlow;
use std::sync::Arc;

use crate::accel::{Structure, WalkStack};
use crate::options::Options;
use crate::paper::{KeyChain, PaperChain};
use crate::scene::Scene;
use crate::shapes::{Posed, ShapeCache};
use crate::types::{LocalHit, ObjectRecord, Pose, Ray, Shape, SurfaceAttribute};

mod poses;
pub use poses::{PoseRef, Poses};

/// The scene at one instant of the shutter: the read-only scene and what
/// was prepared for it, where each of its objects stands then
/// ([`Poses`]), and the contours of the objects that deform. What
/// `motionblur` wrote into the shared records, the port keeps here.
#[derive(Clone, Copy, Debug)]
pub struct Snapshot<'a> {
    pub scene: &'a Scene,
    pub opts: &'a Options,
    pub poses: &'a Poses<'a>,
    /// `poses.all()`, at hand: the loop reads every object's pose here.
    pub all: &'a [Pose],
    /// The in-between objects' contours of the instant.
    pub deforming: &'a [Deforming<'a>],
    /// For each object, its index in `deforming` if it deforms.
    pub deforming_of: &'a [Option<usize>],
    /// What `shapes` prepared for each object's own shape.
    pub caches: &'a [Option<Arc<ShapeCache>>],
    pub aggregate: &'a Aggregate,
    /// The structure to search, or `None` for the loop.
    pub structure: Option<&'a Structure>,
    /// The instant's time segment in the structure
    /// ([`Structure::segment`]; 0 for the loop).
    pub segment: usize,
    /// The queries' scratch.
    pub scratch: &'a Scratch,
}

/// What a query keeps between its steps, made once a worker.
#[derive(Debug, Default)]
pub struct Scratch {
    /// The objects a ray may meet ([`Structure::candidates`]).
    candidates: RefCell<Vec<usize>>,
    /// The `crystal` objects on a shadow ray.
    crystals: RefCell<Vec<usize>>,
    /// A walk's nodes to come.
    stack: RefCell<WalkStack>,
    /// The opaque object that stopped the last shadow ray stopped by one:
    /// the next shadow ray, from a point near the last, asks it first.
    blocker: Cell<Option<usize>>,
}

/// An in-between object of a key-frame chain (§3.2): its contour at the
/// snapshot's time (or its blob or patch, the port's extension). `motionblur` computed it for every ray (`do34` or
/// `Hermite`); here it is computed the first time a ray of the instant
/// reaches the object's bounding sphere, and kept for the instant's other
/// rays, since most rays never come near the object (DEVIATIONS D19).
#[derive(Debug)]
pub struct Deforming<'a> {
    /// Index into `scene.objects`.
    pub object: usize,
    chain: KeyChain<'a>,
    time: Cell<f64>,
    ready: Cell<bool>,
    contour: RefCell<Shape>,
    /// What is made for the contour of the instant (a blob's hierarchy, a
    /// patch's pieces).
    cache: RefCell<Option<ShapeCache>>,
}

impl<'a> From<&'a PaperChain> for KeyChain<'a> {
    fn from(chain: &'a PaperChain) -> Self {
        KeyChain::Sweep(chain)
    }
}

impl<'a> Deforming<'a> {
    /// Scratch for the in-between object `object` of `chain` (a
    /// [`PaperChain`] of sweeps, or any [`KeyChain`]).
    pub fn new(object: usize, chain: impl Into<KeyChain<'a>>) -> Self {
        let chain = chain.into();
        Deforming {
            object,
            chain,
            time: Cell::new(0.0),
            ready: Cell::new(false),
            contour: RefCell::new(chain.scratch()),
            cache: RefCell::new(None),
        }
    }

    /// A new instant: the contour is due again.
    pub fn at(&self, time: f64) {
        self.time.set(time);
        self.ready.set(false);
    }

    /// The contour at the instant: `do34` at time 0 or 1, else `Hermite`
    /// (`PaperChain::inbetween`, or `PointChain::inbetween`), on first use.
    pub fn contour(&self) -> Ref<'_, Shape> {
        self.shape().0
    }

    /// The contour at the instant ([`Deforming::contour`]) and what is
    /// made for it then ([`ShapeCache::of_moment`]: a blob's hierarchy, a
    /// patch's pieces).
    pub fn shape(&self) -> (Ref<'_, Shape>, Ref<'_, Option<ShapeCache>>) {
        if !self.ready.get() {
            self.make();
        }
        (self.contour.borrow(), self.cache.borrow())
    }

    /// The contour of the instant made, and its cache: out of line, once an
    /// instant (the loop over the objects inlines [`Deforming::shape`]).
    #[inline(never)]
    fn make(&self) {
        let mut contour = self.contour.borrow_mut();
        self.chain.inbetween(self.time.get(), &mut contour);
        *self.cache.borrow_mut() = ShapeCache::of_moment(&contour);
        self.ready.set(true);
    }
}

impl Snapshot<'_> {
    /// Where object `i` stands at this instant ([`Poses::get`]).
    #[inline(always)]
    pub fn pose(&self, i: usize) -> PoseRef<'_> {
        match self.all.get(i) {
            Some(p) => PoseRef::Kept(p),
            None => self.poses.get(i),
        }
    }

    /// `f` of object `i` as it stands at this instant (its own shape and
    /// what was prepared for it, or its contour of the moment when it
    /// deforms), for a ray that reaches its bounding sphere beyond `tmin`;
    /// `None` for one that does not. A moving object is posed only then.
    #[inline(always)]
    fn posed<R>(&self, i: usize, ray: &Ray, tmin: f64, f: impl FnOnce(&Posed) -> Option<R>) -> Option<R> {
        let cache = || self.caches[i].as_deref();
        let obj = &self.scene.objects[i];
        let meets = |centre| crate::shapes::bounding_sphere_hit(centre, obj.radius, ray, tmin);
        let kept = match self.all.get(i) {
            Some(pose) => Some(pose),
            None => self.poses.asked(i).is_none().then(|| &self.poses.rest[i]),
        };
        if let Some(pose) = kept {
            return if meets(pose.sphereo) {
                self.shaped(i, obj, pose, cache, f)
            } else {
                None
            };
        }
        let (m, time) = self.poses.asked(i)?;
        if !meets(self.poses.centre(m, time)) {
            return None;
        }
        let pose = self.poses.posed(m, time);
        self.shaped(i, obj, &pose, cache, f)
    }

    /// The objects the structure `s` gives `ray` beyond `tmin` at the
    /// instant's segment ([`Structure::candidates`]), in the scratch.
    fn candidates(&self, s: &Structure, ray: &Ray, tmin: f64) -> std::cell::RefMut<'_, Vec<usize>> {
        let mut out = self.scratch.candidates.borrow_mut();
        s.candidates(ray, tmin, self.segment, &mut self.scratch.stack.borrow_mut(), &mut out);
        out
    }

    /// `f` of object `i` at `pose`, its cache given by `cache` (asked for
    /// a sweep only), a ray having met its bounding sphere
    /// ([`Snapshot::posed`]; the loop walks the tables side by side and
    /// calls it with each object's record and pose at hand).
    #[inline(always)]
    fn shaped<'s, R>(
        &'s self,
        i: usize,
        obj: &'s ObjectRecord,
        pose: &'s Pose,
        cache: impl FnOnce() -> Option<&'s ShapeCache>,
        f: impl FnOnce(&Posed) -> Option<R>,
    ) -> Option<R> {
        let mut at_rest = Posed {
            obj,
            shape: &obj.shape,
            cache: None,
            pose,
        };
        // Only a sweep, a blob or a patch has a cache: the others need not
        // look.
        if matches!(obj.shape, Shape::Sweep(_) | Shape::Blob(_) | Shape::Patch(_)) {
            at_rest.cache = cache();
        }
        // A scene with nothing deforming need not look (most of them).
        let deforms = if self.deforming.is_empty() {
            None
        } else {
            self.deforming_of[i]
        };
        match deforms {
            None => f(&at_rest),
            Some(d) => {
                let (contour, cache) = self.deforming[d].shape();
                f(&Posed {
                    shape: &contour,
                    cache: cache.as_ref(),
                    ..at_rest
                })
            }
        }
    }
}

/// What an object does to a shadow ray that meets it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shadow {
    /// Stops it (every surface but the three below).
    Opaque,
    /// Lets kt·colour of the light through (`crystal`).
    Crystal,
    /// Casts no shadow (`light` and `background` surfaces).
    None,
}

impl Shadow {
    /// What the objects of `scene` do to shadow rays, by their surfaces (an
    /// object without a surface record, as in a test's scene, is opaque).
    pub fn of(scene: &Scene) -> Vec<Shadow> {
        let kind = |surface: usize| match scene.surfaces.get(surface).map(|s| s.surface) {
            Some(SurfaceAttribute::Light | SurfaceAttribute::Background) => Shadow::None,
            Some(SurfaceAttribute::Crystal) => Shadow::Crystal,
            _ => Shadow::Opaque,
        };
        scene.objects.iter().map(|o| kind(o.surface)).collect()
    }
}

/// How the objects a ray may meet are found: the original's loop over
/// the object table, every object in turn behind its bounding sphere, or
/// a structure over the objects (`crate::accel`) that gives the same
/// answers.
#[derive(Clone, Debug, PartialEq)]
pub struct Aggregate {
    /// What each object does to a shadow ray.
    shadow: Vec<Shadow>,
    /// The objects a shadow ray can be stopped or dimmed by, in order,
    /// with what they do to it: the loop's.
    casters: Vec<(usize, Shadow)>,
    structure: Option<Structure>,
    /// Whether a ray makes the searches the loop makes, no fewer: a
    /// sampler that reads them (`--sampler adaptive` deals rays by what a
    /// pixel's searches cost) must see the same counts whatever finds the
    /// objects, or the images would differ. A structure then gives each
    /// query every object whose box the ray meets, in the table's order,
    /// and the loop runs over those: the same searches, as the others are
    /// those whose bounding sphere the ray misses.
    counted: bool,
}

impl Aggregate {
    /// The loop over `scene`'s objects.
    pub fn linear(scene: &Scene) -> Aggregate {
        Aggregate::new(scene, None, false)
    }

    /// `structure` over `scene`'s objects (the loop for `None`); `counted`
    /// as `Aggregate::counted` says.
    pub fn new(scene: &Scene, structure: Option<Structure>, counted: bool) -> Aggregate {
        let shadow = Shadow::of(scene);
        let casters = shadow
            .iter()
            .copied()
            .enumerate()
            .filter(|&(_, s)| s != Shadow::None)
            .collect();
        Aggregate {
            shadow,
            casters,
            structure,
            counted,
        }
    }

    /// The structure, `None` for the loop.
    pub fn structure(&self) -> Option<&Structure> {
        self.structure.as_ref()
    }
}

/// Is hit `a` (its t, its object's index) nearer than hit `b`? The lesser
/// t; of equal t, the lower index, as the original's loop keeps the first
/// it met.
pub fn closer(a: (f64, usize), b: (f64, usize)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

/// The nearest hit of `ray` beyond `tmin` with the snapshot's objects, and
/// the object's index ([`closer`]). `searched` counts the polynomial
/// searches the sweeps made.
#[inline]
pub fn nearest(snap: &Snapshot, ray: &Ray, tmin: f64, searched: &mut u64) -> Option<(usize, LocalHit)> {
    let Some(s) = snap.structure else {
        // The loop, kept apart from the structures' walks so that it stays
        // as small as the original's where it is inlined; with every pose
        // at hand (the instant's, or at rest), the objects, their poses and
        // caches walked side by side.
        let mut best: Option<(usize, LocalHit)> = None;
        let objects = &snap.scene.objects;
        if snap.all.len() == objects.len() && snap.caches.len() == objects.len() {
            let tables = objects.iter().zip(snap.all).zip(snap.caches);
            for (i, ((obj, pose), cache)) in tables.enumerate() {
                if crate::shapes::bounding_sphere_hit(pose.sphereo, obj.radius, ray, tmin) {
                    let hit = snap.shaped(
                        i,
                        obj,
                        pose,
                        || cache.as_deref(),
                        |p| p.intersect(ray, tmin, snap.opts, searched),
                    );
                    keep(hit, i, &mut best);
                }
            }
        } else {
            for i in 0..objects.len() {
                consider(snap, i, ray, tmin, searched, &mut best);
            }
        }
        return best;
    };
    nearest_in(snap, s, ray, tmin, searched)
}

/// [`nearest`] with a structure.
#[inline(never)]
fn nearest_in(snap: &Snapshot, s: &Structure, ray: &Ray, tmin: f64, searched: &mut u64) -> Option<(usize, LocalHit)> {
    let mut best: Option<(usize, LocalHit)> = None;
    if snap.aggregate.counted {
        let candidates = snap.candidates(s, ray, tmin);
        for &i in candidates.iter() {
            consider(snap, i, ray, tmin, searched, &mut best);
        }
        return best;
    }
    // Front to back; an object whose box the ray enters beyond the nearest
    // hit so far cannot be nearer (nor, entered at its t, tie it: such a
    // box is still visited).
    let _ = s.walk(
        ray,
        tmin,
        f64::INFINITY,
        snap.segment,
        &mut snap.scratch.stack.borrow_mut(),
        |i| {
            consider(snap, i, ray, tmin, searched, &mut best);
            ControlFlow::Continue(best.map_or(f64::INFINITY, |(_, h)| h.t))
        },
    );
    best
}

/// Object `i`'s hit with `ray` beyond `tmin`, kept in `best` if it is
/// nearer ([`closer`]): the loop's body, wherever the objects come from.
/// Inlined in each of its three callers: a call for every object of every
/// ray was a tenth of the chapter-5 decks' instructions.
#[inline(always)]
fn consider(snap: &Snapshot, i: usize, ray: &Ray, tmin: f64, searched: &mut u64, best: &mut Option<(usize, LocalHit)>) {
    let hit = snap.posed(i, ray, tmin, |p| p.intersect(ray, tmin, snap.opts, searched));
    keep(hit, i, best);
}

/// Object `i`'s `hit`, kept in `best` if it is nearer ([`closer`]).
#[inline(always)]
fn keep(hit: Option<LocalHit>, i: usize, best: &mut Option<(usize, LocalHit)>) {
    // The hit read where it was written, its t first, and copied only if
    // it is kept.
    if let Some(h) = &hit {
        if best.is_none_or(|(j, b)| closer((h.t, i), (b.t, j))) {
            *best = Some((i, *h));
        }
    }
}

/// Does object `i` stand on the shadow ray between `tmin` and `tmax`?
// Inlined in the shadow rays' loops: with the blobs' and patches' arms in
// the dispatch the compiler stopped inlining it, a call for every object
// of every shadow ray (1 % more instructions on fig5_1, cachegrind).
#[inline(always)]
fn blocks(snap: &Snapshot, i: usize, ray: &Ray, tmin: f64, tmax: f64, searched: &mut u64) -> bool {
    snap.posed(i, ray, tmin, |p| {
        p.blocks(ray, tmin, tmax, snap.opts, searched).then_some(())
    })
    .is_some()
}

/// What stands on a shadow ray between `tmin` and `tmax`: `Break` if an
/// opaque object does (no light passes); else `f` is called with the index
/// of every `crystal` object on it, in the object table's order, and the
/// answer is `Continue`.
#[inline]
pub fn for_each_blocker(
    snap: &Snapshot,
    ray: &Ray,
    tmin: f64,
    tmax: f64,
    searched: &mut u64,
    mut f: impl FnMut(usize),
) -> ControlFlow<()> {
    let agg = snap.aggregate;
    let Some(s) = snap.structure else {
        // The loop: every caster in the table's order.
        for &(i, shadow) in &agg.casters {
            match (blocks(snap, i, ray, tmin, tmax, searched), shadow) {
                (false, _) | (_, Shadow::None) => {}
                (true, Shadow::Crystal) => f(i),
                (true, Shadow::Opaque) => return ControlFlow::Break(()),
            }
        }
        return ControlFlow::Continue(());
    };
    blockers_in(snap, s, ray, tmin, tmax, searched, &mut f)
}

/// [`for_each_blocker`] with a structure.
#[inline(never)]
fn blockers_in(
    snap: &Snapshot,
    s: &Structure,
    ray: &Ray,
    tmin: f64,
    tmax: f64,
    searched: &mut u64,
    f: &mut dyn FnMut(usize),
) -> ControlFlow<()> {
    let agg = snap.aggregate;
    let mut blocks = |i: usize| blocks(snap, i, ray, tmin, tmax, searched);
    if agg.counted {
        let candidates = snap.candidates(s, ray, tmin);
        for &i in candidates.iter() {
            match agg.shadow[i] {
                Shadow::None => {}
                Shadow::Crystal if blocks(i) => f(i),
                Shadow::Opaque if blocks(i) => return ControlFlow::Break(()),
                _ => {}
            }
        }
        return ControlFlow::Continue(());
    }
    // Any opaque object stops the ray, whichever is found first (the last
    // one that stopped a shadow ray is asked first, and not again in the
    // walk when it does not); the crystals it passes are taken in the
    // table's order.
    let last = &snap.scratch.blocker;
    let asked = last.get();
    if asked.is_some_and(&mut blocks) {
        return ControlFlow::Break(());
    }
    let mut crystals = snap.scratch.crystals.borrow_mut();
    crystals.clear();
    s.walk(
        ray,
        tmin,
        tmax,
        snap.segment,
        &mut snap.scratch.stack.borrow_mut(),
        |i| match agg.shadow[i] {
            Shadow::None => ControlFlow::Continue(tmax),
            Shadow::Crystal => {
                if blocks(i) {
                    crystals.push(i);
                }
                ControlFlow::Continue(tmax)
            }
            Shadow::Opaque if Some(i) != asked && blocks(i) => {
                last.set(Some(i));
                ControlFlow::Break(())
            }
            Shadow::Opaque => ControlFlow::Continue(tmax),
        },
    )?;
    crystals.sort_unstable();
    crystals.dedup();
    for &i in crystals.iter() {
        f(i);
    }
    ControlFlow::Continue(())
}

/// Every object of `scene` at rest: the poses of a [`Snapshot`] of a
/// scene in which nothing moves.
pub(crate) fn rest_poses(scene: &Scene) -> Vec<Pose> {
    scene.objects.iter().map(|o| o.pose()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Moving;
    use crate::options::Fidelity;
    use crate::types::DVec3;

    /// fig5_1's scene, its objects at rest, its motions, and each object's
    /// motion by index.
    fn fig5_1() -> (Scene, Vec<Pose>, Vec<Moving>, Vec<Option<usize>>) {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/decks");
        let src = std::fs::read_to_string(dir.join("fig5_1.deck")).unwrap();
        let scene = crate::deck::initialize(&src, "fig5_1.deck", &dir, Fidelity::Thesis).unwrap();
        let (rest, moving, moving_of) = moved(&scene);
        (scene, rest, moving, moving_of)
    }

    /// A scene's objects at rest, its motions, and each object's motion by
    /// index.
    fn moved(scene: &Scene) -> (Vec<Pose>, Vec<Moving>, Vec<Option<usize>>) {
        let rest = rest_poses(scene);
        let moving = crate::motion::paths(scene);
        let mut moving_of = vec![None; scene.objects.len()];
        for (k, m) in moving.iter().enumerate() {
            moving_of[m.object] = Some(k);
        }
        (rest, moving, moving_of)
    }

    /// The loop over poses made when asked (a structure's, at an instant
    /// outside the times it bounds) meets the objects where the poses made
    /// all at once put them: the same nearest hit for rays at the moving
    /// ball and at the floor.
    #[test]
    fn the_loop_meets_lazy_poses_as_eager_ones() {
        let (scene, rest, moving, moving_of) = fig5_1();
        let caches = crate::shapes::prepare_caches(&scene);
        let (opts, aggregate) = (Options::default(), Aggregate::linear(&scene));
        let nearest_with = |eager: bool, ray: &Ray| {
            let mut poses = Poses::new(
                &scene.objects,
                &rest,
                &moving,
                &moving_of,
                Fidelity::Thesis,
                eager,
                false,
            );
            poses.at(0.3);
            let snap = Snapshot {
                scene: &scene,
                opts: &opts,
                poses: &poses,
                all: poses.all(),
                deforming: &[],
                deforming_of: &vec![None; scene.objects.len()],
                caches: &caches,
                aggregate: &aggregate,
                structure: None,
                segment: 0,
                scratch: &Scratch::default(),
            };
            assert_eq!(snap.all.len(), if eager { scene.objects.len() } else { 0 });
            nearest(&snap, ray, 1e-9, &mut 0).map(|(i, h)| (i, h.t))
        };
        let eye = scene.view.eyept;
        let (objects, moved) = (&scene.objects, &moving_of);
        let mut ball = Poses::new(objects, &rest, &moving, moved, Fidelity::Thesis, true, false);
        ball.at(0.3);
        let centre = ball.get(moving[0].object).sphereo;
        for target in [centre, DVec3::new(0.0, 0.0, -0.5)] {
            let ray = Ray::new(eye, (target - eye).normalize());
            let hit = nearest_with(true, &ray);
            assert!(hit.is_some());
            assert_eq!(nearest_with(false, &ray), hit);
        }
        // The ball is met where it stands at 0.3, not at rest.
        let ray = Ray::new(eye, (centre - eye).normalize());
        assert_eq!(nearest_with(false, &ray).map(|(i, _)| i), Some(moving[0].object));
    }

    /// The loop's poses kept for instants whose times come back are those
    /// made afresh: over times that return in every order (and more of
    /// them than there are places, so that instants take each other's),
    /// every object where it stands then, to the bit.
    #[test]
    fn kept_poses_are_the_instants_own() {
        let (scene, rest, moving, moving_of) = fig5_1();
        let (objects, moved) = (&scene.objects, &moving_of);
        let new = |repeats| Poses::new(objects, &rest, &moving, moved, Fidelity::Thesis, true, repeats);
        let (mut kept, mut fresh) = (new(true), new(false));
        let times: Vec<f64> = (0..40).map(|k| ((k * 7) % 23) as f64 / 23.0).collect();
        for (n, &t) in times.iter().chain(times.iter().rev()).enumerate() {
            kept.at(t);
            fresh.at(t);
            for i in 0..scene.objects.len() {
                let (a, b) = (kept.get(i), fresh.get(i));
                let bits = |p: &Pose| p.transfm.to_cols_array().map(f64::to_bits);
                assert_eq!(bits(&a), bits(&b), "instant {n}, time {t}, object {i}");
                assert_eq!(a.sphereo, b.sphereo);
            }
        }
    }

    /// A scene of moving objects: straight glides under each law (one
    /// turned at rest about two axes, one whose turn is of zeros, −0
    /// among them), and two that do not glide: turning, and on a curve.
    fn glides_scene() -> Scene {
        scene_of(GLIDES_DECK)
    }

    /// The same scene with no glide of the first law (LAW's constant
    /// speed): `Movers::at` must then find the other laws' fractions alone.
    fn glides_scene_without_the_first_law() -> Scene {
        scene_of(
            &GLIDES_DECK
                .replace(
                    "motion a to 1.3 0.1 -0.2\n",
                    "motion a to 1.3 0.1 -0.2 law accelerate\n",
                )
                .replace("turn 0 -0 0\n", "turn 0 -0 0 law smooth\n"),
        )
    }

    /// The same scene with every glide that follows a law following `law`
    /// (`""` for the first, constant speed): `Movers::at` must then find
    /// that law's fraction alone.
    fn glides_scene_at_one_law(law: &str) -> Scene {
        let mut deck = GLIDES_DECK.to_string();
        for other in [" law accelerate\n", " law decelerate\n", " law smooth\n"] {
            deck = deck.replace(other, &format!("{law}\n"));
        }
        // The two glides at constant speed.
        for constant in ["motion a to 1.3 0.1 -0.2", "turn 0 -0 0"] {
            deck = deck.replace(&format!("{constant}\n"), &format!("{constant}{law}\n"));
        }
        scene_of(&deck)
    }

    fn scene_of(deck: &str) -> Scene {
        crate::deck::initialize(deck, "glides.deck", std::path::Path::new("."), Fidelity::Thesis).unwrap()
    }

    const GLIDES_DECK: &str = "view eye 0 -10 0 look 0 0 0 screen 4 distance 5\n\
            image 8 8 mask 1\n\
            surface s opaque color 1 1 1 ka 0.1 kd 0.8 ks 0.1 kt 0\n\
            sphere a s at 0.3 0.1 -0.2 radius 0.5\n\
            block b s at -1 0.2 0.4 size 1 2 0.5\n\
            rotate b x 90\n\
            rotate b z -90\n\
            sphere c s at 1 1 1 radius 0.2\n\
            sphere d s at 2 -1 0 radius 0.2\n\
            sphere e s at -2 -1 0 radius 0.2\n\
            sphere f s at 0 2 0 radius 0.2\n\
            sphere g s at 0 -2 1 radius 0.2\n\
            motion a to 1.3 0.1 -0.2\n\
            motion b to -1 1.7 0.4 law accelerate\n\
            motion c to 1 0 1 law decelerate\n\
            motion d to 2 -1 3 law smooth\n\
            motion e to -2 0 0 turn 0 0 30\n\
            motion f to 1 2 0 via 0 3 0 1 3 0\n\
            motion g to 0 -2 2 turn 0 -0 0\n\
            blur 1\n";

    /// Bits of a pose, to compare them exactly.
    fn pose_bits(p: &Pose) -> Vec<u64> {
        let (t, i) = (p.transfm.to_cols_array(), p.inverse.to_cols_array());
        let s = p.sphereo.to_array();
        t.iter().chain(&i).chain(&s).map(|v| v.to_bits()).collect()
    }

    /// A glide poses its object and places its origin as `motionblur`
    /// does, to the bit, under each law, at times in and past the shutter;
    /// what turns, curves, or is read in listing fidelity does not glide.
    #[test]
    fn a_glide_is_posed_as_motionblur_poses_it() {
        let scene = glides_scene();
        let moving = crate::motion::paths(&scene);
        assert_eq!(moving.len(), 7);
        let glides = crate::motion::Glides::of(&moving, &scene.objects, Fidelity::Thesis);
        let gliding: Vec<bool> = glides.each.iter().map(Option::is_some).collect();
        assert_eq!(gliding, [true, true, true, true, false, false, true]);
        assert_eq!(glides.laws, 0b1111);
        let listing = crate::motion::Glides::of(&moving, &scene.objects, Fidelity::Listing);
        assert!(listing.each.iter().all(Option::is_none) && listing.laws == 0);
        for (m, g) in moving.iter().zip(&glides.each) {
            let Some(g) = g else { continue };
            let rest = &scene.objects[m.object];
            for k in 0..=30 {
                let time = k as f64 / 20.0;
                let f = crate::drt::LAW(g.law(), 1.0, time);
                let want = m.pose(rest, time, Fidelity::Thesis);
                let mut got = Pose::IDENTITY;
                g.pose_into(f, &mut got);
                assert_eq!(pose_bits(&got), pose_bits(&want), "object {} at {time}", m.object);
                assert_eq!(
                    g.centre(f).to_array().map(f64::to_bits),
                    want.sphereo.to_array().map(f64::to_bits)
                );
                assert_eq!(want.sphereo, m.centre(rest, time, Fidelity::Thesis));
            }
        }
    }

    /// Poses given the glides ([`Poses::gliding`]) put every object, and
    /// every moving object's origin, where poses made by the motions
    /// alone put them, to the bit: at times in and past the shutter, for
    /// the loop (all at once) and for a structure (each when asked,
    /// origins first), the laws of every glide found for each instant
    /// (all four laws, all but the first, each alone).
    #[test]
    fn gliding_poses_are_the_motions_own() {
        let (all, without_first) = (glides_scene(), glides_scene_without_the_first_law());
        for (scene, laws) in [(&all, 0b1111), (&without_first, 0b1110)] {
            gliding_poses_match(scene, laws);
        }
        for (law, bit) in ["", " law accelerate", " law decelerate", " law smooth"]
            .into_iter()
            .zip(0..)
        {
            gliding_poses_match(&glides_scene_at_one_law(law), 1 << bit);
        }
    }

    fn gliding_poses_match(scene: &Scene, laws: u8) {
        let (rest, moving, moving_of) = moved(scene);
        let glides = crate::motion::Glides::of(&moving, &scene.objects, Fidelity::Thesis);
        assert!(glides.each.iter().filter(|g| g.is_some()).count() >= 4);
        assert_eq!(glides.laws, laws);
        let (objects, moved) = (&scene.objects, &moving_of);
        for eager in [true, false] {
            let new = || Poses::new(objects, &rest, &moving, moved, Fidelity::Thesis, eager, false);
            let (mut gliding, mut plain) = (new().gliding(&glides), new());
            for k in 0..=30 {
                let t = k as f64 / 20.0;
                gliding.at(t);
                plain.at(t);
                for (m, mover) in moving.iter().enumerate() {
                    if !eager {
                        let (a, b) = (gliding.centre(m, t), plain.centre(m, t));
                        assert_eq!(a.to_array().map(f64::to_bits), b.to_array().map(f64::to_bits));
                    }
                    let want = mover.pose(&scene.objects[mover.object], t, Fidelity::Thesis);
                    assert_eq!(
                        pose_bits(&gliding.get(mover.object)),
                        pose_bits(&want),
                        "{eager} {t} {m}"
                    );
                    assert_eq!(pose_bits(&plain.get(mover.object)), pose_bits(&want));
                }
            }
        }
    }

    /// An object that deforms is met as its contour of the moment, without
    /// a cache (its caps solved, its bounds made per ray), though its key
    /// shape has one; the same object at rest is met with its cache.
    #[test]
    fn a_deforming_object_is_met_without_a_cache() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/decks");
        let src = std::fs::read_to_string(dir.join("fig5_10.deck")).unwrap();
        let mut scene = crate::deck::initialize(&src, "fig5_10.deck", &dir, Fidelity::Thesis).unwrap();
        crate::shapes::sweep::prepare_sweeps(&mut scene, Fidelity::Thesis);
        let caches = crate::shapes::prepare_caches(&scene);
        let record = &scene.keyframes[0];
        let chain = PaperChain::from_keyframe(&scene, record, Fidelity::Thesis).unwrap();
        let first = record.first;
        assert!(caches[first].is_some(), "the key shape has a cache");
        let rest = rest_poses(&scene);
        let no_moving = vec![None; scene.objects.len()];
        let poses = Poses::new(&scene.objects, &rest, &[], &no_moving, Fidelity::Thesis, true, false);
        let deforming = [Deforming::new(first, &chain)];
        deforming[0].at(0.5);
        let mut deforming_of = vec![None; scene.objects.len()];
        deforming_of[first] = Some(0);
        let opts = Options::default();
        let aggregate = Aggregate::linear(&scene);
        let snap = Snapshot {
            scene: &scene,
            opts: &opts,
            poses: &poses,
            all: poses.all(),
            deforming: &deforming,
            deforming_of: &deforming_of,
            caches: &caches,
            aggregate: &aggregate,
            structure: None,
            segment: 0,
            scratch: &Scratch::default(),
        };
        let eye = scene.view.eyept;
        let toward = Ray::new(eye, (rest[first].sphereo - eye).normalize());
        let cached = |snap: &Snapshot| snap.posed(first, &toward, 1e-9, |p| Some(p.cache.is_some()));
        assert_eq!(cached(&snap), Some(false));
        let at_rest = vec![None; scene.objects.len()];
        assert_eq!(
            cached(&Snapshot {
                deforming_of: &at_rest,
                ..snap
            }),
            Some(true)
        );
    }
}

//! Where each object stands at one instant ([`Poses`]): the poses the loop
//! keeps for instants whose times come back (D71), and those a structure's
//! rays ask for, each made the first time it is asked (D70).

use std::cell::{Cell, Ref, RefCell};

use crate::drt::LAW;
use crate::motion::{Glide, Glides, Moving};
use crate::scene::Law;
use crate::types::{DVec3, ObjectRecord, Pose};

/// Where each object stands at one instant: an object at rest where the
/// deck left it, a moving one where its motion puts it then. With the
/// loop, which meets every object, every moving object is posed when the
/// instant begins, as `motionblur` did for every ray; with a structure
/// over the objects, a moving object is posed the first time a ray of the
/// instant reaches its bounding sphere (its origin alone found before,
/// `Poses::centre`), and those no ray comes near cost nothing.
#[derive(Debug)]
pub struct Poses<'a> {
    /// Every object at rest, shared by the workers.
    pub(super) rest: &'a [Pose],
    /// For each object, its index in `moving` if it moves.
    moving_of: &'a [Option<usize>],
    movers: Movers<'a>,
    /// The instant; `None` (every object at rest) before the first.
    time: Cell<Option<f64>>,
    now: Now,
}

/// The moving objects and how each is posed at the instant.
#[derive(Debug)]
struct Movers<'a> {
    objects: &'a [ObjectRecord],
    moving: &'a [Moving],
    /// For each moving object, its [`Glide`] if it glides (none given:
    /// each is posed by its motion).
    glides: &'a [Option<Glide>],
    /// Bit l set for each LAW l some glide follows.
    laws: u8,
    /// LAW(l, 1, t) of the instant's t, for each law of `laws`: the
    /// fraction of the way every glide of that law has come, found once
    /// an instant.
    along: [Cell<f64>; 4],
    fidelity: crate::options::Fidelity,
}

/// The laws, in the order of their bits in [`Movers::laws`].
const LAWS: [Law; 4] = [Law::Constant, Law::Accelerate, Law::Decelerate, Law::Smooth];

impl Movers<'_> {
    /// The instant's fractions of the way, for time `time`.
    #[inline(always)]
    fn at(&self, time: f64) {
        if self.laws & 1 != 0 {
            self.along[0].set(LAW(Law::Constant, 1.0, time));
        }
        if self.laws & !1 != 0 {
            self.at_other_laws(time);
        }
    }

    /// [`Movers::at`] for the laws but the first: apart, so that their
    /// sines and cosines are not computed where no glide follows them.
    #[inline(never)]
    fn at_other_laws(&self, time: f64) {
        for (l, law) in LAWS.into_iter().enumerate().skip(1) {
            if self.laws & (1 << l) != 0 {
                self.along[l].set(LAW(law, 1.0, time));
            }
        }
    }

    /// Moving object `m`'s glide and the fraction of its way at the
    /// instant, if it glides and the fraction is finite.
    #[inline(always)]
    fn glide(&self, m: usize) -> Option<(&Glide, f64)> {
        let g = self.glides.get(m)?.as_ref()?;
        let f = self.along[g.law() as usize].get();
        f.is_finite().then_some((g, f))
    }

    /// Every moving object's pose at `time`, the instant, in its place
    /// among `slots` (found from the time's bits: [`Now::All`]) unless it
    /// holds them already; returns the place. Apart from [`Poses::at`],
    /// so that a structure's instant, which poses nothing, costs little.
    #[inline(never)]
    fn pose_all(&self, slots: &mut [(Option<u64>, Vec<Pose>)], time: f64) -> usize {
        let bits = time.to_bits();
        // A multiplicative hash's top bits: the times of a table land in
        // different places.
        let k = match slots.len() {
            1 => 0,
            n => (bits.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - n.trailing_zeros())) as usize,
        };
        let (at, all) = &mut slots[k];
        if *at != Some(bits) {
            for (m, moving) in self.moving.iter().enumerate() {
                self.pose_into(m, time, &mut all[moving.object], false);
            }
            *at = Some(bits);
        }
        k
    }

    /// Moving object `m`'s pose at `time`, the instant, written over
    /// `pose`, which holds `m`'s pose at another instant if `again`.
    #[inline(always)]
    fn pose_into(&self, m: usize, time: f64, pose: &mut Pose, again: bool) {
        match self.glide(m) {
            Some((g, f)) if again => g.move_into(f, pose),
            Some((g, f)) => g.pose_into(f, pose),
            None => {
                let moving = &self.moving[m];
                moving.pose_into(&self.objects[moving.object], time, self.fidelity, pose);
            }
        }
    }
}

/// The poses of the instant, as [`Poses`] keeps them.
#[derive(Debug)]
enum Now {
    /// For the loop: every object's, in [`SLOTS`] places (one where that
    /// many copies of the table would be large), each holding the poses
    /// of one instant and its time (its bits), an instant's place found
    /// from its time: an instant whose time comes back (the table's times
    /// without jitter, fig5_1's) is posed once, and another in its place
    /// is posed over it. `current` is the instant's place.
    All {
        slots: Vec<(Option<u64>, Vec<Pose>)>,
        current: usize,
    },
    /// For a structure: the poses of the moving objects asked at the
    /// instant, in the order they were asked, each written where it is
    /// kept beside the moving object it was last written for (the list
    /// is kept from one instant to the next and written over: it grows
    /// only while more are asked than ever before; the next instant's
    /// rays mostly ask for the same objects in the same order, and a
    /// glide written over its own pose writes its place alone); how
    /// many are the instant's; and for each moving object the instant it
    /// was last posed at and its place in the list (instants counted from
    /// 1: nothing to clear at the next).
    Lazy {
        posed: RefCell<Vec<(u32, Pose)>>,
        made: Cell<usize>,
        slot: Vec<Cell<(u64, u32)>>,
        instant: Cell<u64>,
    },
}

/// How many instants' poses the loop keeps ([`Now::All`]): a power of two,
/// as many as a 4×4 table has times.
const SLOTS: usize = 16;

/// The most poses the loop keeps in its places for instants: beyond, one
/// place.
const SLOT_POSES: usize = 1024;

/// A pose as [`Poses::get`] gives it: one kept for the instant, or a
/// moving object's written at it.
#[derive(Debug)]
pub enum PoseRef<'p> {
    Kept(&'p Pose),
    Written(Ref<'p, Pose>),
}

impl std::ops::Deref for PoseRef<'_> {
    type Target = Pose;

    #[inline(always)]
    fn deref(&self) -> &Pose {
        match self {
            PoseRef::Kept(p) => p,
            PoseRef::Written(p) => p,
        }
    }
}

impl<'a> Poses<'a> {
    /// Every object at rest: `rest[i]` for `objects[i]`, which `moving`
    /// (`moving_of[i]` its index there) moves from [`Poses::at`] on, all
    /// of them at once if `eager` (for the loop), else each when first
    /// asked. Eager poses of instants whose times come back (`repeats`)
    /// are kept for them (`Now::All`).
    pub fn new(
        objects: &'a [ObjectRecord],
        rest: &'a [Pose],
        moving: &'a [Moving],
        moving_of: &'a [Option<usize>],
        fidelity: crate::options::Fidelity,
        eager: bool,
        repeats: bool,
    ) -> Poses<'a> {
        let now = if eager {
            let count = if repeats && rest.len() * SLOTS <= SLOT_POSES {
                SLOTS
            } else {
                1
            };
            Now::All {
                slots: vec![(None, rest.to_vec()); count],
                current: 0,
            }
        } else {
            Now::Lazy {
                posed: RefCell::new(Vec::new()),
                made: Cell::new(0),
                slot: vec![Cell::new((0, 0)); moving.len()],
                instant: Cell::new(0),
            }
        };
        Poses {
            rest,
            moving_of,
            movers: Movers {
                objects,
                moving,
                glides: &[],
                laws: 0,
                along: Default::default(),
                fidelity,
            },
            time: Cell::new(None),
            now,
        }
    }

    /// These poses with the moving objects' glides, `glides.each[k]` for
    /// `moving[k]` ([`Moving::glide`]): a glide is posed from what was
    /// made ready for it, to the same bits.
    pub fn gliding(mut self, glides: &'a Glides) -> Poses<'a> {
        self.movers.glides = &glides.each;
        self.movers.laws = glides.laws;
        self
    }

    /// A new instant, film time `time`: every moving object's pose is due.
    #[inline]
    pub fn at(&mut self, time: f64) {
        if !self.at_asked(time) {
            self.time.set(Some(time));
            self.movers.at(time);
            if let Now::All { slots, current } = &mut self.now {
                *current = self.movers.pose_all(slots, time);
            }
        }
    }

    /// [`Poses::at`] where each moving object is posed when asked (a
    /// structure's rays ask), which needs no more than a shared
    /// reference: a snapshot of the scene made once serves its instants
    /// one after another. False, and nothing done, where all are posed at
    /// once (the loop's).
    #[inline]
    pub fn at_asked(&self, time: f64) -> bool {
        let Now::Lazy { instant, made, .. } = &self.now else {
            return false;
        };
        self.time.set(Some(time));
        self.movers.at(time);
        instant.set(instant.get() + 1);
        made.set(0);
        true
    }

    /// Where object `i` stands at the instant (its rest pose until the
    /// first [`Poses::at`]).
    #[inline(always)]
    pub fn get(&self, i: usize) -> PoseRef<'_> {
        match (&self.now, self.moving_of[i], self.time.get()) {
            (Now::All { slots, current }, ..) => PoseRef::Kept(&slots[*current].1[i]),
            (Now::Lazy { .. }, Some(m), Some(time)) => PoseRef::Written(self.posed(m, time)),
            _ => PoseRef::Kept(&self.rest[i]),
        }
    }

    /// Every object's pose of the instant when all are posed at once (for
    /// the loop); empty when each is posed when asked.
    pub fn all(&self) -> &[Pose] {
        match &self.now {
            Now::All { slots, current } => &slots[*current].1,
            Now::Lazy { .. } => &[],
        }
    }

    /// For object `i`, when it is posed when asked ([`Poses::all`] empty):
    /// its index among the moving objects if it moves, once the instant is
    /// set.
    #[inline(always)]
    pub(super) fn asked(&self, i: usize) -> Option<(usize, f64)> {
        Some((self.moving_of[i]?, self.time.get()?))
    }

    /// Where moving object `m`'s origin (`sphereo`) stands at `time`, the
    /// instant, as [`Poses::get`] puts it, to the bit: without posing it
    /// when it is not posed yet.
    #[inline(always)]
    pub(super) fn centre(&self, m: usize, time: f64) -> DVec3 {
        if let Now::Lazy {
            posed, slot, instant, ..
        } = &self.now
        {
            // A glide's origin costs less than looking for its pose.
            if let Some((g, f)) = self.movers.glide(m) {
                return g.centre(f);
            }
            let (when, k) = slot[m].get();
            if when == instant.get() {
                return posed.borrow()[k as usize].1.sphereo;
            }
        }
        let moving = &self.movers.moving[m];
        moving.centre(&self.movers.objects[moving.object], time, self.movers.fidelity)
    }

    /// Moving object `m`'s pose at `time`, the instant, posed on first use
    /// at the instant and written where it is kept (the poses are made
    /// when asked). Inlined: most asks find the pose made ([`Poses::pose`]
    /// makes it).
    #[inline(always)]
    pub(super) fn posed(&self, m: usize, time: f64) -> Ref<'_, Pose> {
        let Now::Lazy {
            posed, slot, instant, ..
        } = &self.now
        else {
            unreachable!("the loop's poses are all made at once");
        };
        let (when, k) = slot[m].get();
        let k = if when == instant.get() { k } else { self.pose(m, time) };
        Ref::map(posed.borrow(), |list| &list[k as usize].1)
    }

    /// Moving object `m`'s pose at `time`, the instant, made and written
    /// where it is kept; returns its place in the list.
    #[inline(never)]
    fn pose(&self, m: usize, time: f64) -> u32 {
        let Now::Lazy {
            posed,
            made,
            slot,
            instant,
        } = &self.now
        else {
            unreachable!("the loop's poses are all made at once");
        };
        // A pose is lent only while one object is tested or shaded, never
        // while another is posed: the list is free to write.
        let mut list = posed.borrow_mut();
        let k = made.get() as u32;
        made.set(k as usize + 1);
        if k as usize == list.len() {
            list.push((u32::MAX, Pose::IDENTITY));
        }
        let (owner, pose) = &mut list[k as usize];
        self.movers.pose_into(m, time, pose, *owner == m as u32);
        *owner = m as u32;
        slot[m].set((instant.get(), k));
        k
    }
}

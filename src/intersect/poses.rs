//! Where each object stands at one instant ([`Poses`]): the poses the loop
//! keeps for instants whose times come back (D71), and those a structure's
//! rays ask for, each made the first time it is asked (D70).

use std::cell::{Cell, Ref, RefCell};

use crate::motion::Moving;
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
    objects: &'a [ObjectRecord],
    /// Every object at rest, shared by the workers.
    pub(super) rest: &'a [Pose],
    moving: &'a [Moving],
    /// For each object, its index in `moving` if it moves.
    moving_of: &'a [Option<usize>],
    fidelity: crate::options::Fidelity,
    /// The instant; `None` (every object at rest) before the first.
    time: Option<f64>,
    now: Now,
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
    /// kept (the list is kept from one instant to the next and written
    /// over: it grows only while more are asked than ever before); how
    /// many are the instant's; and for each moving object the instant it
    /// was last posed at and its place in the list (instants counted from
    /// 1: nothing to clear at the next).
    Lazy {
        posed: RefCell<Vec<Pose>>,
        made: Cell<usize>,
        slot: Vec<Cell<(u64, u32)>>,
        instant: u64,
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
                instant: 0,
            }
        };
        Poses {
            objects,
            rest,
            moving,
            moving_of,
            fidelity,
            time: None,
            now,
        }
    }

    /// A new instant, film time `time`: every moving object's pose is due.
    #[inline]
    pub fn at(&mut self, time: f64) {
        self.time = Some(time);
        match &mut self.now {
            Now::All { slots, current } => {
                let bits = time.to_bits();
                // A multiplicative hash's top bits: the times of a table
                // land in different places.
                let k = match slots.len() {
                    1 => 0,
                    n => (bits.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - n.trailing_zeros())) as usize,
                };
                *current = k;
                let (at, all) = &mut slots[k];
                if *at != Some(bits) {
                    for m in self.moving {
                        m.pose_into(&self.objects[m.object], time, self.fidelity, &mut all[m.object]);
                    }
                    *at = Some(bits);
                }
            }
            Now::Lazy { instant, made, .. } => {
                *instant += 1;
                made.set(0);
            }
        }
    }

    /// Where object `i` stands at the instant (its rest pose until the
    /// first [`Poses::at`]).
    #[inline(always)]
    pub fn get(&self, i: usize) -> PoseRef<'_> {
        match (&self.now, self.moving_of[i], self.time) {
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
        Some((self.moving_of[i]?, self.time?))
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
            let (when, k) = slot[m].get();
            if when == *instant {
                return posed.borrow()[k as usize].sphereo;
            }
        }
        let moving = &self.moving[m];
        moving.centre(&self.objects[moving.object], time, self.fidelity)
    }

    /// Moving object `m`'s pose at `time`, the instant, posed on first use
    /// at the instant and written where it is kept (the poses are made
    /// when asked).
    #[inline(never)]
    pub(super) fn posed(&self, m: usize, time: f64) -> Ref<'_, Pose> {
        let Now::Lazy {
            posed,
            made,
            slot,
            instant,
        } = &self.now
        else {
            unreachable!("the loop's poses are all made at once");
        };
        let (when, mut k) = slot[m].get();
        if when != *instant {
            // A pose is lent only while one object is tested or shaded,
            // never while another is posed: the list is free to write.
            let mut list = posed.borrow_mut();
            k = made.get() as u32;
            made.set(k as usize + 1);
            if k as usize == list.len() {
                list.push(Pose::IDENTITY);
            }
            let moving = &self.moving[m];
            moving.pose_into(&self.objects[moving.object], time, self.fidelity, &mut list[k as usize]);
            slot[m].set((*instant, k));
        }
        Ref::map(posed.borrow(), |list| &list[k as usize])
    }
}

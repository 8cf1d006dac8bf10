//! Bounds in time: the film times a render's samples can have, cut into
//! segments ([`Segments`]); each object's boxes over all of them and over
//! each segment ([`Bounds`], [`Timed`]); and the hierarchy over objects
//! that move far against their size ([`Hierarchy`]): a tree of its own
//! for each run of segments, each node keeping its boxes over the
//! segments where psychopath's rule says so ([`Bvh`]). The port's.

use super::{Aabb, Bvh};
use crate::types::BoundingBox;

/// The film times a structure serves, cut into segments of equal length:
/// a ray at time t tests the boxes of t's segment ([`Segments::of`]), each
/// of which holds its object at every time of the segment. One segment
/// where nothing moves far.
#[derive(Clone, Debug, PartialEq)]
pub struct Segments {
    /// The segments' ends, ascending: segment k runs from `ends[k]` to
    /// `ends[k + 1]`.
    ends: Vec<f64>,
    /// Segments a unit of time: n/(t1 − t0) (0 for one segment).
    per_time: f64,
}

impl Segments {
    /// `count` (at least one) segments of equal length from `t0` to `t1`.
    pub fn new(t0: f64, t1: f64, count: usize) -> Segments {
        let n = count.max(1);
        let ends = (0..=n).map(|k| t0 + (t1 - t0) * (k as f64 / n as f64)).collect();
        let per_time = if n > 1 { n as f64 / (t1 - t0) } else { 0.0 };
        Segments { ends, per_time }
    }

    /// One segment over all of `t0` to `t1`.
    pub fn whole(t0: f64, t1: f64) -> Segments {
        Segments::new(t0, t1, 1)
    }

    /// The number of segments.
    pub fn len(&self) -> usize {
        self.ends.len() - 1
    }

    /// Is it one segment only?
    pub fn is_whole(&self) -> bool {
        self.len() == 1
    }

    /// The `count` segments from segment `first` on.
    fn run(&self, first: usize, count: usize) -> Segments {
        let ends = self.ends[first..=first + count].to_vec();
        let per_time = if count > 1 { self.per_time } else { 0.0 };
        Segments { ends, per_time }
    }

    /// Segment `k`'s first and last time.
    pub fn span(&self, k: usize) -> (f64, f64) {
        (self.ends[k], self.ends[k + 1])
    }

    /// The segment that holds `time`: the k with `ends[k]` ≤ time ≤
    /// `ends[k + 1]` as the ends are kept (the product's rounding put
    /// right), the first or the last for a time before or after them all.
    #[inline]
    pub fn of(&self, time: f64) -> usize {
        let n = self.len();
        if n == 1 {
            return 0;
        }
        // `as usize` saturates: a time before t0, or NaN, gives 0.
        let mut k = ((time - self.ends[0]) * self.per_time) as usize;
        k = k.min(n - 1);
        if k > 0 && time < self.ends[k] {
            k -= 1;
        } else if k + 1 < n && time > self.ends[k + 1] {
            k += 1;
        }
        k
    }
}

/// Each object's boxes over the times a structure serves, by index: over
/// all of them (`whole`), and for an object that moves far against its
/// size over each of the segments (`timed[i]`, one box a segment; empty
/// for the others); and into how many runs of equal length the segments
/// fall for the hierarchy, a tree each (`runs`, dividing the number of
/// segments: [`Hierarchy`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Bounds {
    pub segments: Segments,
    pub whole: Vec<BoundingBox>,
    pub timed: Vec<Vec<BoundingBox>>,
    pub runs: usize,
}

impl Bounds {
    /// Boxes over one segment only: `whole`.
    pub fn still(whole: Vec<BoundingBox>) -> Bounds {
        Bounds {
            segments: Segments::whole(0.0, 1.0),
            timed: vec![Vec::new(); whole.len()],
            whole,
            runs: 1,
        }
    }
}

/// No boxes over time segments: of a node, a leaf's object, or an object
/// that does not move far.
pub(super) const UNTIMED: u32 = u32::MAX;

/// [`Bounds`] as the structures read them: the boxes as [`Aabb`]s, and the
/// boxes over the segments of every object that has them in one table
/// (object i's from `first[i]`, or [`UNTIMED`]).
#[derive(Clone, Debug)]
pub struct Timed {
    pub(super) segments: Segments,
    pub(super) whole: Vec<Aabb>,
    pub(super) per: Vec<Aabb>,
    pub(super) first: Vec<u32>,
}

impl Timed {
    pub fn of(b: &Bounds) -> Timed {
        let count = b.segments.len();
        let mut per = Vec::new();
        let first = (0..b.whole.len())
            .map(|i| match b.timed.get(i) {
                Some(t) if count > 1 && t.len() == count => {
                    per.extend(t.iter().map(Aabb::of));
                    (per.len() - count) as u32
                }
                _ => UNTIMED,
            })
            .collect();
        Timed {
            segments: b.segments.clone(),
            whole: b.whole.iter().map(Aabb::of).collect(),
            per,
            first,
        }
    }

    /// The boxes over the `count` segments from segment `first` on, as
    /// boxes over segments of their own: an object's box over all of them
    /// the union of its boxes over them.
    fn run(&self, first: usize, count: usize) -> Timed {
        let mut per = Vec::new();
        let mut whole = self.whole.clone();
        let first_of = self
            .first
            .iter()
            .zip(&mut whole)
            .map(|(&at, w)| match at {
                UNTIMED => UNTIMED,
                at => {
                    let boxes = &self.per[at as usize + first..][..count];
                    *w = boxes.iter().fold(Aabb::EMPTY, |u, b| u.union(b));
                    per.extend_from_slice(boxes);
                    (per.len() - count) as u32
                }
            })
            .collect();
        Timed {
            segments: self.segments.run(first, count),
            whole,
            per,
            first: first_of,
        }
    }

    /// One box an object over all times.
    pub fn still(whole: Vec<Aabb>) -> Timed {
        Timed {
            segments: Segments::whole(0.0, 1.0),
            first: vec![UNTIMED; whole.len()],
            per: Vec::new(),
            whole,
        }
    }
}

/// The bounding volume hierarchy over the objects' boxes in time: where
/// objects move far against their size, a split in time at the root (as
/// Embree's spatio-temporal hierarchy splits in time, Woop et al. 2017):
/// the segments fall into runs of equal length, and each run has a tree
/// of its own ([`Bvh`]), built on the objects' boxes over that run, its
/// nodes keeping boxes over each of the run's segments where they pay. A
/// ray at a time of segment k walks the tree of k's run, in k's place
/// among the run's segments. One run, one tree, where nothing moves far.
#[derive(Clone, Debug, PartialEq)]
pub struct Hierarchy {
    segments: Segments,
    /// Segments a run: 2 to this power.
    shift: u32,
    trees: Vec<Bvh>,
}

impl Hierarchy {
    /// The trees over `boxes`, in `runs` runs of its segments (powers of
    /// two both, the runs no more than the segments; else one run).
    pub fn build(boxes: &Timed, runs: usize) -> Hierarchy {
        let n = boxes.segments.len();
        let fits = runs.is_power_of_two() && n.is_power_of_two() && runs <= n;
        let runs = if fits { runs } else { 1 };
        let per_run = n / runs;
        let trees = match runs {
            1 => vec![Bvh::build_timed(boxes)],
            _ => (0..runs)
                .map(|r| Bvh::build_timed(&boxes.run(r * per_run, per_run)))
                .collect(),
        };
        Hierarchy {
            segments: boxes.segments.clone(),
            shift: per_run.trailing_zeros(),
            trees,
        }
    }

    /// One tree over `bvh`'s boxes, at every time.
    pub fn of(bvh: Bvh) -> Hierarchy {
        Hierarchy {
            segments: bvh.segments().clone(),
            shift: 0,
            trees: vec![bvh],
        }
    }

    /// The time segment of `time` ([`Segments::of`]).
    pub fn segment(&self, time: f64) -> usize {
        self.segments.of(time)
    }

    /// The tree a ray at a time of segment `segment` walks, and the
    /// segment's place among its run's.
    #[inline(always)]
    pub fn tree(&self, segment: usize) -> (&Bvh, usize) {
        match &self.trees[..] {
            [one] => (one, segment),
            trees => {
                let run = (segment >> self.shift).min(trees.len() - 1);
                (&trees[run], segment - (run << self.shift))
            }
        }
    }

    /// The trees, one a run of segments.
    pub fn trees(&self) -> &[Bvh] {
        &self.trees
    }
}

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

    /// The number of segments (one at least).
    pub fn count(&self) -> usize {
        self.ends.len() - 1
    }

    /// Is it one segment only?
    pub fn is_whole(&self) -> bool {
        self.count() == 1
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
        let n = self.count();
        if n == 1 {
            return 0;
        }
        // `as u32` saturates: a time before t0, or NaN, gives 0 (and it
        // costs less than `as usize`, whose range a double exceeds).
        let mut k = (((time - self.ends[0]) * self.per_time) as u32 as usize).min(n - 1);
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

/// A node, or an object, keeps boxes over each time segment when its box
/// over all the times has more than this many times their mean half-area
/// (psychopath's `USE_UNION_FACTOR`, in its src/accel/bvh_base.rs).
pub const USE_UNION: f64 = 1.4;

/// No boxes over time segments: of a node, a leaf's object, or an object
/// that does not move far.
pub(super) const UNTIMED: u32 = u32::MAX;

/// [`Bounds`] as the structures read them: the boxes as [`Aabb`]s, and the
/// boxes over the segments of every object that has them in one table
/// (object i's from `first[i]`, or `UNTIMED`).
#[derive(Clone, Debug)]
pub struct Timed {
    pub(super) segments: Segments,
    pub(super) whole: Vec<Aabb>,
    pub(super) per: Vec<Aabb>,
    pub(super) first: Vec<u32>,
}

impl Timed {
    pub fn of(b: &Bounds) -> Timed {
        let count = b.segments.count();
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
        let n = boxes.segments.count();
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
    #[inline]
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::{BoxRay, Structure, WalkStack};
    use crate::hash::hashed_uniform;
    use crate::types::{DVec3, Ray};

    /// Every time of the span lies in the segment `of` gives, to the bit of
    /// the kept ends; times before and after go to the first and last.
    #[test]
    fn a_time_lies_in_its_segment() {
        for (t0, t1, n) in [(0.0, 1.0, 16), (0.0, 1.5, 8), (-0.25, 3.0, 4), (0.1, 0.3, 2)] {
            let s = Segments::new(t0, t1, n);
            assert_eq!(s.count(), n);
            for i in 0..=10_000 {
                let t = t0 + (t1 - t0) * i as f64 / 10_000.0;
                let k = s.of(t);
                let (a, b) = s.span(k);
                assert!(a <= t && t <= b, "{t} in segment {k}: {a}..{b}");
            }
            for k in 0..n {
                let (a, b) = s.span(k);
                assert!(s.of(a) == k || s.of(a) + 1 == k, "{a}");
                assert!(s.of(b) == k || s.of(b) == k + 1, "{b}");
            }
            assert_eq!((s.of(t0 - 1.0), s.of(t1 + 1.0), s.of(f64::NAN)), (0, n - 1, 0));
        }
        assert_eq!(Segments::whole(0.0, 1.0).of(0.7), 0);
        assert!(Segments::whole(0.0, 1.0).is_whole() && !Segments::new(0.0, 1.0, 2).is_whole());
    }

    /// `n` cubes of half-side `r` moving `travel` of their widths along x
    /// over `count` segments of [0, 1]: each object's box over each segment
    /// (those moving), and over all.
    fn moving_cubes(n: usize, r: f64, travel: f64, count: usize, runs: usize) -> Bounds {
        let segments = Segments::new(0.0, 1.0, count);
        let (mut whole, mut timed) = (Vec::new(), Vec::new());
        for i in 0..n {
            let u = |j: u64| hashed_uniform(8 * i as u64 + j);
            let c = DVec3::new(10.0 * u(0), 10.0 * u(1), 10.0 * u(2));
            let moving = i % 4 != 0;
            let at = |t: f64| c + DVec3::X * (if moving { 2.0 * r * travel * t } else { 0.0 });
            let over = |a: f64, b: f64| BoundingBox::EMPTY.holding(at(a) - r).holding(at(b) + r);
            whole.push(over(0.0, 1.0));
            timed.push(match moving {
                true => (0..count)
                    .map(|k| over(segments.span(k).0, segments.span(k).1))
                    .collect(),
                false => Vec::new(),
            });
        }
        Bounds {
            segments,
            whole,
            timed,
            runs,
        }
    }

    /// A ray at a time of segment k visits every object whose box over k
    /// it meets, and none whose box over all the times it passes farther
    /// than the nodes' single-precision slack; in one tree or in a tree a
    /// run of segments.
    #[test]
    fn a_ray_meets_the_boxes_of_its_segment() {
        for runs in [1, 2, 4] {
            let bounds = moving_cubes(300, 0.2, 3.0, 8, runs);
            let Some(Structure::Bvh(h)) = Structure::build(crate::accel::Accel::Bvh, &bounds) else {
                panic!("a hierarchy");
            };
            assert_eq!(h.trees().len(), runs);
            // Over the whole shutter the fast movers' nodes keep boxes in
            // time; over a quarter of it, the rule may find one box enough.
            assert!(
                runs > 1 || h.trees()[0].timed_len() > 0,
                "fast movers keep boxes in time"
            );
            let structure = Structure::Bvh(h);
            // The same objects with their boxes over all the times only.
            let still = Structure::build(crate::accel::Accel::Bvh, &Bounds::still(bounds.whole.clone())).unwrap();
            let (mut visits, mut stack, mut still_visits) = (0, WalkStack::default(), 0);
            for k in 0..500u64 {
                let u = |j: u64| hashed_uniform(1_000_000 + 8 * k + j);
                let o = DVec3::new(-5.0, 10.0 * u(0), 10.0 * u(1));
                let ray = Ray::new(o, (DVec3::new(15.0, 10.0 * u(2), 10.0 * u(3)) - o).normalize());
                let time = u(4);
                let segment = structure.segment(time);
                let mut got = Vec::new();
                structure.candidates(&ray, 0.0, segment, &mut stack, &mut got);
                let boxray = BoxRay::new(&ray);
                let at = |i: usize| Aabb::of(bounds.timed[i].get(segment).unwrap_or(&bounds.whole[i]));
                let whole = |i: usize| {
                    let b = Aabb::of(&bounds.whole[i]);
                    boxray
                        .span(
                            &Aabb {
                                lo: b.lo - 1e-4,
                                hi: b.hi + 1e-4,
                            },
                            0.0,
                            f64::INFINITY,
                        )
                        .is_some()
                };
                for i in 0..bounds.whole.len() {
                    if boxray.span(&at(i), 0.0, f64::INFINITY).is_some() {
                        assert!(got.contains(&i), "ray {k}: object {i} in segment {segment}");
                    } else if !whole(i) {
                        // (A node that keeps one box tests its objects'
                        // boxes over all the times: more visits, never fewer.)
                        assert!(!got.contains(&i), "ray {k}: object {i} is off the ray");
                    }
                }
                visits += got.len();
                still.candidates(&ray, 0.0, 0, &mut stack, &mut got);
                still_visits += got.len();
            }
            assert!(visits > 200, "{visits}");
            assert!(
                4 * visits < 3 * still_visits,
                "boxes in time: {visits} visits against {still_visits}"
            );
        }
    }

    /// Slow movers keep one box: the rule finds their boxes over the
    /// segments as large as over all of them.
    #[test]
    fn slow_movers_keep_one_box() {
        let bounds = moving_cubes(100, 0.5, 0.01, 4, 1);
        let Some(Structure::Bvh(h)) = Structure::build(crate::accel::Accel::Bvh, &bounds) else {
            panic!("a hierarchy");
        };
        assert_eq!(h.trees()[0].timed_len(), 0);
        let fast = moving_cubes(100, 0.5, 3.0, 4, 1);
        let Some(Structure::Bvh(h)) = Structure::build(crate::accel::Accel::Bvh, &fast) else {
            panic!("a hierarchy");
        };
        assert!(h.trees()[0].timed_len() > 0);
    }
}

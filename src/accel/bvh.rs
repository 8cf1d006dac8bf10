//! The bounding volume hierarchy: the thesis's clusters of bounding
//! volumes tested before the volumes in them (§2.1.2 (1)(b), Fig. 2.12),
//! built as pbrt-v4 builds its BVH (`BVHAggregate::buildRecursive`,
//! src/pbrt/cpu/aggregates.cpp: the surface area heuristic over twelve
//! buckets of the boxes' centres on the widest axis, a node's test costing
//! half an object's), kept flat (a node's first child follows it), and
//! walked front to back. The port's; the thesis prints no code for it.
//!
//! One choice beyond pbrt's: the object with the largest box may be made
//! a child of its own, when the heuristic prices that lower than the
//! buckets' best. A floor under a crowd of small objects has its centre
//! among theirs and would fall into one bucket's box with them, making
//! that box as large as the floor; alone, it costs one test.

use std::ops::ControlFlow;

use super::{visit_each, Aabb, BoxRay, Step};
use crate::types::DVec3;

/// Buckets of the heuristic (pbrt-v4's).
const BUCKETS: usize = 12;

/// A node holds at most this many objects unless splitting costs more.
const MAX_LEAF: usize = 4;

/// No node deeper (a chain of nested boxes would otherwise make a node a
/// level), so that the build's recursion stays shallow.
const MAX_DEPTH: usize = 60;

/// What a node's box test costs against an object's test (pbrt-v4's ½).
const TRAVERSAL_COST: f64 = 0.5;

/// A node: for a leaf (`count` > 0), its objects `items[offset..offset +
/// count]`; for an inner node (`count` = 0), its second child at `offset`
/// (the first is the next node) and the boxes of the two, side by side
/// (`children.lo[axis][c]` of child c): a step of the walk tests both at
/// once, from one place in memory. A node's own box is in its parent, the
/// root's in [`Bvh`].
#[derive(Clone, Debug, PartialEq)]
struct Node {
    children: Pair,
    offset: u32,
    count: u32,
}

/// Two boxes, axis by axis: `lo[k][c]` and `hi[k][c]` bound box c on axis k.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Pair {
    lo: [[f64; 2]; 3],
    hi: [[f64; 2]; 3],
}

impl Pair {
    /// Boxes `a` and `b`.
    pub(super) fn of(a: &Aabb, b: &Aabb) -> Pair {
        let lane = |u: DVec3, v: DVec3| [[u.x, v.x], [u.y, v.y], [u.z, v.z]];
        Pair {
            lo: lane(a.lo, b.lo),
            hi: lane(a.hi, b.hi),
        }
    }

    /// The lower and upper corners, axis by axis, box by box.
    pub(super) fn lanes(&self) -> super::Lanes<'_> {
        (&self.lo, &self.hi)
    }

    /// Box `c` (0 or 1).
    #[cfg(test)]
    fn get(&self, c: usize) -> Aabb {
        let at = |v: &[[f64; 2]; 3]| DVec3::new(v[0][c], v[1][c], v[2][c]);
        Aabb {
            lo: at(&self.lo),
            hi: at(&self.hi),
        }
    }
}

/// See the module doc. Built by [`Bvh::build`], walked by [`Bvh::walk`].
#[derive(Clone, Debug, PartialEq)]
pub struct Bvh {
    /// The root's box.
    bounds: Aabb,
    nodes: Vec<Node>,
    items: Vec<Item>,
}

/// An object of a leaf: its box and index.
#[derive(Clone, Debug, PartialEq)]
struct Item {
    bounds: Aabb,
    object: u32,
}

/// An object while building: its box, the box's centre (0 on an axis
/// where the box is not finite), its index.
#[derive(Clone, Copy)]
struct Prim {
    bounds: Aabb,
    centre: [f64; 3],
    object: u32,
}

/// The fraction of the rays through a box of half-area `total` that also
/// cross one of half-area `part` inside it: infinite boxes (objects whose
/// bounds are not finite) take every ray, and in a box without area every
/// ray meets everything.
fn fraction(part: f64, total: f64) -> f64 {
    if total == f64::INFINITY {
        if part == f64::INFINITY {
            1.0
        } else {
            0.0
        }
    } else if total > 0.0 {
        part / total
    } else {
        1.0
    }
}

impl Bvh {
    /// The hierarchy over `boxes`, object i's box at index i.
    pub fn build(boxes: &[Aabb]) -> Bvh {
        let mut prims: Vec<Prim> = boxes
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let c = b.centre();
                Prim {
                    bounds: *b,
                    centre: c.to_array().map(|v| if v.is_finite() { v } else { 0.0 }),
                    object: i as u32,
                }
            })
            .collect();
        let mut bvh = Bvh {
            bounds: Aabb::EMPTY,
            nodes: Vec::with_capacity(2 * boxes.len()),
            items: Vec::with_capacity(boxes.len()),
        };
        if !prims.is_empty() {
            bvh.bounds = bvh.node(&mut prims, 0).1;
        }
        bvh
    }

    /// The node over `prims` and all below it; returns its index and box.
    fn node(&mut self, prims: &mut [Prim], depth: usize) -> (usize, Aabb) {
        // A leaf of one object has that object's box itself, so that the
        // test of it in its parent is the object's own test.
        let bounds = match prims {
            [one] => one.bounds,
            _ => prims.iter().fold(Aabb::EMPTY, |b, p| b.union(&p.bounds)),
        };
        let index = self.nodes.len();
        self.nodes.push(Node {
            children: Pair::of(&Aabb::EMPTY, &Aabb::EMPTY),
            offset: 0,
            count: 0,
        });
        match split(prims, &bounds, depth) {
            None => {
                prims.sort_unstable_by_key(|p| p.object);
                self.nodes[index].offset = self.items.len() as u32;
                self.nodes[index].count = prims.len() as u32;
                self.items.extend(prims.iter().map(|p| Item {
                    bounds: p.bounds,
                    object: p.object,
                }));
            }
            Some(mid) => {
                let (near, far) = prims.split_at_mut(mid);
                let (_, a) = self.node(near, depth + 1);
                let (second, b) = self.node(far, depth + 1);
                self.nodes[index].offset = second as u32;
                self.nodes[index].children = Pair::of(&a, &b);
            }
        }
        (index, bounds)
    }

    /// The walk of [`super::Structure::walk`]: a node's children in the
    /// order the ray enters them, each skipped when the ray enters it
    /// beyond the limit as it stands then; a leaf's objects each behind
    /// its own box.
    pub fn walk(
        &self,
        ray: &BoxRay,
        tmin: f64,
        mut limit: f64,
        stack: &mut Vec<(u32, f64)>,
        mut visit: impl FnMut(usize) -> Step,
    ) -> ControlFlow<()> {
        if self.nodes.is_empty() {
            return ControlFlow::Continue(());
        }
        let Some((mut enter, _)) = ray.span(&self.bounds, tmin, limit) else {
            return ControlFlow::Continue(());
        };
        stack.clear();
        let mut n = 0u32;
        loop {
            if enter <= limit {
                let node = &self.nodes[n as usize];
                if node.count > 0 {
                    let start = node.offset as usize;
                    let items = &self.items[start..start + node.count as usize];
                    if let [one] = items {
                        // Its box is the leaf's, which the ray enters at
                        // `enter`, within the limit: tested already.
                        limit = visit(one.object as usize)?;
                    } else {
                        let objects = items.iter().map(|item| (item.object as usize, &item.bounds));
                        visit_each(ray, tmin, &mut limit, objects, &mut visit)?;
                    }
                } else {
                    let (a, b) = (n + 1, node.offset);
                    let [ea, eb] = ray.span_pair(node.children.lanes(), tmin, limit);
                    // The near child next, the far one kept for after.
                    (n, enter) = match (ea, eb) {
                        (Some((ta, _)), Some((tb, _))) if tb < ta => {
                            stack.push((a, ta));
                            (b, tb)
                        }
                        (Some((ta, _)), Some((tb, _))) => {
                            stack.push((b, tb));
                            (a, ta)
                        }
                        (Some((ta, _)), None) => (a, ta),
                        (None, Some((tb, _))) => (b, tb),
                        (None, None) => (0, f64::INFINITY),
                    };
                    if enter < f64::INFINITY {
                        continue;
                    }
                }
            }
            match stack.pop() {
                Some(next) => (n, enter) = next,
                None => return ControlFlow::Continue(()),
            }
        }
    }

    /// The deepest leaf's depth (the root's is 0).
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = vec![(0usize, 0usize)];
        while let Some((n, d)) = stack.pop() {
            deepest = deepest.max(d);
            if self.nodes.get(n).is_some_and(|node| node.count == 0) {
                stack.push((n + 1, d + 1));
                stack.push((self.nodes[n].offset as usize, d + 1));
            }
        }
        deepest
    }

    /// The number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}

/// Where to split `prims` (those before the index go to the first child),
/// with their box `bounds`; `None` for a leaf.
fn split(prims: &mut [Prim], bounds: &Aabb, depth: usize) -> Option<usize> {
    let n = prims.len();
    if n <= 1 || depth >= MAX_DEPTH {
        return None;
    }
    let area = bounds.half_area();
    let buckets = bucket_split(prims, area);
    let alone = largest_alone(prims, area);
    let best = match (buckets, alone) {
        (Some(b), Some(a)) if a.0 < b.0 => Split::Alone(a.1),
        (Some(b), _) => Split::Bucket(b.1, b.2),
        (None, Some(a)) => Split::Alone(a.1),
        (None, None) => return None,
    };
    let cost = match best {
        Split::Alone(_) => alone.map_or(f64::INFINITY, |a| a.0),
        Split::Bucket(..) => buckets.map_or(f64::INFINITY, |b| b.0),
    };
    // pbrt-v4: a leaf when it holds few enough and splitting does not pay.
    if n <= MAX_LEAF && (cost >= n as f64 || cost.is_nan()) {
        return None;
    }
    match best {
        Split::Alone(i) => {
            prims.swap(0, i);
            Some(1)
        }
        Split::Bucket(axis, last) => {
            let (lo, scale) = centre_scale(prims, axis)?;
            let mid = partition(prims, |p| bucket(p.centre[axis], lo, scale) <= last);
            (mid > 0 && mid < n).then_some(mid)
        }
    }
}

enum Split {
    /// The object at this index alone, the rest in the other child.
    Alone(usize),
    /// Buckets 0..=last on the axis in the first child.
    Bucket(usize, usize),
}

/// The least and the scale of the centres on `axis`: bucket b holds the
/// centres c with ⌊(c − least)·scale⌋ = b. `None` when they are all one.
fn centre_scale(prims: &[Prim], axis: usize) -> Option<(f64, f64)> {
    let (lo, hi) = prims.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p.centre[axis]), b.max(p.centre[axis]))
    });
    let scale = BUCKETS as f64 / (hi - lo);
    (hi > lo && scale.is_finite()).then_some((lo, scale))
}

fn bucket(c: f64, lo: f64, scale: f64) -> usize {
    (((c - lo) * scale) as usize).min(BUCKETS - 1)
}

/// The heuristic's best bucket split on the axis where the centres spread
/// widest: (cost, axis, last bucket of the first child).
fn bucket_split(prims: &[Prim], area: f64) -> Option<(f64, usize, usize)> {
    let scales = [0, 1, 2].map(|axis| centre_scale(prims, axis));
    let spread = |axis: usize| scales[axis].map_or(0.0, |(_, s)| BUCKETS as f64 / s);
    let axis = (0..3).max_by(|&a, &b| spread(a).total_cmp(&spread(b)))?;
    let (lo, scale) = scales[axis]?;
    let mut counts = [0usize; BUCKETS];
    let mut boxes = [Aabb::EMPTY; BUCKETS];
    for p in prims {
        let b = bucket(p.centre[axis], lo, scale);
        counts[b] += 1;
        boxes[b] = boxes[b].union(&p.bounds);
    }
    // The cost of each split after bucket `last`, from a sweep each way.
    let mut below = [(0usize, Aabb::EMPTY); BUCKETS];
    let mut acc = (0usize, Aabb::EMPTY);
    for b in 0..BUCKETS {
        acc = (acc.0 + counts[b], acc.1.union(&boxes[b]));
        below[b] = acc;
    }
    let mut best: Option<(f64, usize, usize)> = None;
    let mut above = (0usize, Aabb::EMPTY);
    for last in (0..BUCKETS - 1).rev() {
        above = (above.0 + counts[last + 1], above.1.union(&boxes[last + 1]));
        let (nb, bb) = below[last];
        if nb == 0 || above.0 == 0 {
            continue;
        }
        let cost = TRAVERSAL_COST
            + nb as f64 * fraction(bb.half_area(), area)
            + above.0 as f64 * fraction(above.1.half_area(), area);
        if best.is_none_or(|(c, ..)| cost < c) {
            best = Some((cost, axis, last));
        }
    }
    best
}

/// The object with the largest box alone in a child: (cost, its index in
/// `prims`).
fn largest_alone(prims: &[Prim], area: f64) -> Option<(f64, usize)> {
    let (big, _) = prims
        .iter()
        .enumerate()
        .max_by(|(_, a), (_, b)| a.bounds.half_area().total_cmp(&b.bounds.half_area()))?;
    let rest = prims
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != big)
        .fold(Aabb::EMPTY, |b, (_, p)| b.union(&p.bounds));
    let cost = TRAVERSAL_COST
        + fraction(prims[big].bounds.half_area(), area)
        + (prims.len() - 1) as f64 * fraction(rest.half_area(), area);
    Some((cost, big))
}

/// Moves the prims for which `first` holds to the front; returns how many.
fn partition(prims: &mut [Prim], first: impl Fn(&Prim) -> bool) -> usize {
    let mut mid = 0;
    for i in 0..prims.len() {
        if first(&prims[i]) {
            prims.swap(i, mid);
            mid += 1;
        }
    }
    mid
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::tests::cube;
    use crate::types::Ray;

    fn visited(bvh: &Bvh, ray: &Ray, limit: f64) -> Vec<usize> {
        let mut v = Vec::new();
        let _ = bvh.walk(&BoxRay::new(ray), 0.0, limit, &mut Vec::new(), |i| {
            v.push(i);
            ControlFlow::Continue(limit)
        });
        v
    }

    /// A row of boxes along x: a ray along the row visits them nearest
    /// first, a ray beside it none, and a limit stops the walk there.
    #[test]
    fn a_row_is_walked_front_to_back() {
        let boxes: Vec<Aabb> = (0..40).map(|i| cube([i as f64 * 3.0, 0.0, 0.0], 1.0)).collect();
        let bvh = Bvh::build(&boxes);
        assert!(bvh.len() > 10, "{}", bvh.len());
        let along = Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X);
        let v = visited(&bvh, &along, f64::INFINITY);
        assert_eq!(v, (0..40).collect::<Vec<_>>());
        let back = Ray::new(DVec3::new(200.0, 0.0, 0.0), DVec3::NEG_X);
        assert_eq!(visited(&bvh, &back, f64::INFINITY), (0..40).rev().collect::<Vec<_>>());
        let beside = Ray::new(DVec3::new(-5.0, 3.0, 0.0), DVec3::X);
        assert!(visited(&bvh, &beside, f64::INFINITY).is_empty());
        // Boxes entered beyond t = 20 (x = 15) are not visited; one
        // entered at the limit is.
        assert_eq!(visited(&bvh, &along, 20.0), (0..=5).collect::<Vec<_>>());
        assert_eq!(visited(&bvh, &along, 22.0), (0..=6).collect::<Vec<_>>());
    }

    /// A floor under a crowd: the floor is a child of its own.
    #[test]
    fn the_largest_box_may_stand_alone() {
        let mut boxes = vec![Aabb {
            lo: DVec3::new(-100.0, -100.0, -1.0),
            hi: DVec3::new(100.0, 100.0, 0.0),
        }];
        boxes.extend((0..64).map(|i| cube([(i % 8) as f64, (i / 8) as f64, 1.0], 0.2)));
        let bvh = Bvh::build(&boxes);
        let root = &bvh.nodes[0];
        let (a, b) = (&bvh.nodes[1], &bvh.nodes[root.offset as usize]);
        let alone = |n: &Node| n.count == 1 && bvh.items[n.offset as usize].object == 0;
        assert!(alone(a) || alone(b));
        // The root holds its children's boxes: the floor's own is one.
        let floor = |c: usize| root.children.get(c) == boxes[0];
        assert_eq!(floor(0), alone(a));
        assert_eq!(floor(1), alone(b));
    }

    #[test]
    fn nested_boxes_stay_within_the_depth() {
        let boxes: Vec<Aabb> = (0..500).map(|i| cube([0.0; 3], 1.01f64.powi(i))).collect();
        let bvh = Bvh::build(&boxes);
        assert!(bvh.depth() <= MAX_DEPTH, "{}", bvh.depth());
        let ray = Ray::new(DVec3::new(0.0, 0.0, -1e100), DVec3::Z);
        assert_eq!(visited(&bvh, &ray, f64::INFINITY).len(), 500);
    }
}

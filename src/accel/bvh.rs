//! The bounding volume hierarchy: the thesis's clusters of bounding
//! volumes tested before the volumes in them (§2.1.2 (1)(b), Fig. 2.12),
//! built as pbrt-v4 builds its BVH (`BVHAggregate::buildRecursive`,
//! src/pbrt/cpu/aggregates.cpp: the surface area heuristic over twelve
//! buckets of the boxes' centres on the widest axis, a node's test costing
//! half an object's), and walked front to back. The port's; the thesis
//! prints no code for it.
//!
//! One choice beyond pbrt's: the object with the largest box may be made
//! a child of its own, when the heuristic prices that lower than the
//! buckets' best. A floor under a crowd of small objects has its centre
//! among theirs and would fall into one bucket's box with them, making
//! that box as large as the floor; alone, it costs one test.
//!
//! The walk does not step through the binary tree the heuristic builds:
//! each of its nodes takes its children's children in their places (up
//! to four; a leaf stays), as Embree's four-wide nodes do, and the four
//! boxes are tested at once in single precision ([`super::quad`]), a
//! test that may let in a box the ray passes very near but never keeps
//! out one it meets. A ray then steps through half as many levels, each
//! step one test of four boxes where it was two of two.
//!
//! Bounds in time: where objects move far against their size, a node
//! keeps its children's boxes over each segment of the times the render
//! can have ([`super::Segments`]), and a ray tests those of its own
//! time's segment. Which nodes keep them is psychopath's rule
//! (its `src/accel/bvh_base.rs`: one box where the union of the boxes over
//! time is at most 1.4 times their average area): a node whose box over
//! the whole time is not much larger than its boxes over the segments
//! keeps the one box, as every node of a scene at rest does.

use std::ops::ControlFlow;

use super::quad::{Quad, QuadRay};
use super::time::UNTIMED;
use in_time::InTime;

mod in_time;
use super::{visit_each, Aabb, BoxRay, Segments, Step, Timed, USE_UNION};

/// Buckets of the heuristic (pbrt-v4's).
const BUCKETS: usize = 12;

/// A node holds at most this many objects unless splitting costs more.
const MAX_LEAF: usize = 4;

/// No node deeper (a chain of nested boxes would otherwise make a node a
/// level), so that the build's recursion stays shallow.
const MAX_DEPTH: usize = 60;

/// What a node's box test costs against an object's test (pbrt-v4's ½).
const TRAVERSAL_COST: f64 = 0.5;

/// A node: the boxes of its two to four children side by side (one
/// [`Quad`], tested at once) and what each child is: a node (its index), a
/// leaf (`LEAF` and its index in `leaves`), or none ([`NO_CHILD`]). It is
/// a node of the binary hierarchy the heuristic builds with its children
/// raised to take their own children's places ([`Bvh::wide`]), so that a
/// ray steps through half as many levels.
///
/// Aligned to a cache line (128 bytes, two lines): the boxes' 16-byte
/// rows are then never split across lines.
#[derive(Clone, Debug, PartialEq)]
#[repr(C, align(64))]
struct Node {
    boxes: Quad,
    child: [u32; 4],
    /// Bit c set for each lane c with a child.
    lanes: u32,
    /// [`UNTIMED`], or where the node's boxes over each time segment
    /// start in the build's `Scratch::quads` (one [`Quad`] a segment, in
    /// their order).
    timed: u32,
}

/// A child that is a leaf: its index in `leaves`, with this bit.
const LEAF: u32 = 1 << 31;

/// A leaf of one object: the object's index itself with this bit and
/// [`LEAF`], so that the walk reaches the object without looking up the
/// leaf and its item (two loads, one after the other); below it, an
/// object that fits.
const ONE: u32 = 1 << 30;

/// A lane without a child.
const NO_CHILD: u32 = u32::MAX;

/// See the module doc. Built by [`Bvh::build`], walked by [`Bvh::walk`].
#[derive(Clone, Debug, PartialEq)]
pub struct Bvh {
    /// The root's box, and the root (a node, or a leaf).
    bounds: Aabb,
    root: u32,
    nodes: Vec<Node>,
    /// A leaf's objects: `items[offset..offset + count]`.
    leaves: Vec<(u32, u32)>,
    items: Vec<Item>,
    /// The time segments the boxes over time are for.
    segments: Segments,
    /// The root's box over each segment (none when it keeps one box).
    root_at: Vec<Aabb>,
    /// The nodes as a walk at one time reads them ([`InTime`]), where
    /// there is more than one segment.
    in_time: InTime,
    /// The boxes over each segment of the objects that have them
    /// ([`Item::at`]).
    object_at: Vec<Aabb>,
}

/// An object of a leaf: its box, its index, and where its boxes over the
/// segments start in `Bvh::object_at` ([`UNTIMED`] if it has none).
#[derive(Clone, Debug, PartialEq)]
struct Item {
    bounds: Aabb,
    object: u32,
    at: u32,
}

/// An object while building: its box, the box's centre (0 on an axis
/// where the box is not finite), its index, and where its boxes over the
/// segments start ([`Item::at`]).
#[derive(Clone, Copy)]
struct Prim {
    bounds: Aabb,
    centre: [f64; 3],
    object: u32,
    at: u32,
}

/// A node of the binary hierarchy while building: its box, and its two
/// children or (a leaf) its objects' place in `items`; where its boxes
/// over the segments start in the build's table ([`UNTIMED`] when
/// nothing in it has any), and whether it keeps them ([`USE_UNION`]).
struct Binary {
    bounds: Aabb,
    kids: Option<[usize; 2]>,
    items: (u32, u32),
    at: u32,
    keep: bool,
}

/// What the build keeps beside the binary nodes: their boxes over the
/// segments, `count` a node.
struct Scratch {
    binary: Vec<Binary>,
    at: Vec<Aabb>,
    count: usize,
    /// The timed nodes' boxes, a [`Quad`] a segment ([`Node::timed`]),
    /// until [`InTime`] lays them out in the nodes.
    quads: Vec<Quad>,
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
    /// The hierarchy over `boxes`, object i's box at index i, one box an
    /// object over all times.
    pub fn build(boxes: &[Aabb]) -> Bvh {
        Bvh::build_timed(&Timed::still(boxes.to_vec()))
    }

    /// The hierarchy over `boxes`: object i's box over all times, and
    /// over each time segment where it has them. The tree is built on the
    /// boxes over all times; what a node keeps over the segments is the
    /// union of its children's.
    pub fn build_timed(boxes: &Timed) -> Bvh {
        let count = boxes.segments.count();
        let mut prims: Vec<Prim> = boxes
            .whole
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let c = b.centre();
                Prim {
                    bounds: *b,
                    centre: c.to_array().map(|v| if v.is_finite() { v } else { 0.0 }),
                    object: i as u32,
                    at: boxes.first[i],
                }
            })
            .collect();
        let n = boxes.whole.len();
        let mut bvh = Bvh {
            bounds: Aabb::EMPTY,
            root: NO_CHILD,
            nodes: Vec::with_capacity(n / 2),
            leaves: Vec::with_capacity(n),
            items: Vec::with_capacity(n),
            segments: boxes.segments.clone(),
            root_at: Vec::new(),
            in_time: InTime::default(),
            object_at: boxes.per.clone(),
        };
        if !prims.is_empty() {
            let mut scratch = Scratch {
                binary: Vec::with_capacity(2 * n),
                at: Vec::new(),
                count,
                quads: Vec::new(),
            };
            let top = bvh.node(&mut scratch, &mut prims, 0);
            let root = &scratch.binary[top];
            bvh.bounds = root.bounds;
            if root.keep {
                bvh.root_at = scratch.at[root.at as usize..][..count].to_vec();
            }
            bvh.root = bvh.wide(&mut scratch, top);
            // The walk reads the boxes over the segments from the nodes
            // made for it; the table they were gathered in goes with the
            // scratch.
            if count > 1 {
                bvh.in_time = InTime::of(&bvh.nodes, &scratch.quads, bvh.root, count);
            }
        }
        bvh
    }

    /// The binary node over `prims` and all below it, into `scratch`;
    /// returns its index.
    fn node(&mut self, scratch: &mut Scratch, prims: &mut [Prim], depth: usize) -> usize {
        // A leaf of one object has that object's box itself, so that the
        // test of it in its parent is the object's own test.
        let bounds = match prims {
            [one] => one.bounds,
            _ => prims.iter().fold(Aabb::EMPTY, |b, p| b.union(&p.bounds)),
        };
        let index = scratch.binary.len();
        scratch.binary.push(Binary {
            bounds,
            kids: None,
            items: (0, 0),
            at: UNTIMED,
            keep: false,
        });
        let at = match split(prims, &bounds, depth) {
            None => {
                prims.sort_unstable_by_key(|p| p.object);
                scratch.binary[index].items = (self.items.len() as u32, prims.len() as u32);
                self.items.extend(prims.iter().map(|p| Item {
                    bounds: p.bounds,
                    object: p.object,
                    at: p.at,
                }));
                let parts = prims.iter().map(|p| (p.bounds, p.at));
                union_over_segments(&mut scratch.at, Some(&self.object_at), scratch.count, parts)
            }
            Some(mid) => {
                let (near, far) = prims.split_at_mut(mid);
                let a = self.node(scratch, near, depth + 1);
                let b = self.node(scratch, far, depth + 1);
                scratch.binary[index].kids = Some([a, b]);
                let parts = [a, b].map(|k| (scratch.binary[k].bounds, scratch.binary[k].at));
                union_over_segments(&mut scratch.at, None, scratch.count, parts.into_iter())
            }
        };
        let keep = at != UNTIMED && {
            let boxes = &scratch.at[at as usize..][..scratch.count];
            let mean = boxes.iter().map(Aabb::half_area).sum::<f64>() / scratch.count as f64;
            bounds.half_area() > USE_UNION * mean
        };
        scratch.binary[index].at = at;
        scratch.binary[index].keep = keep;
        index
    }

    /// The walked node of binary node `b` (a leaf stays a leaf): its
    /// children, each child that is not a leaf replaced by its own two;
    /// returns the child reference. The node keeps its lanes' boxes over
    /// the segments when one of them keeps its own.
    fn wide(&mut self, scratch: &mut Scratch, b: usize) -> u32 {
        let binary = &scratch.binary;
        let Some(two) = binary[b].kids else {
            let (start, count) = binary[b].items;
            if count == 1 {
                let object = self.items[start as usize].object;
                // (`ONE - 1` too would make the leaf `NO_CHILD`.)
                if object < ONE - 1 {
                    return LEAF | ONE | object;
                }
            }
            self.leaves.push(binary[b].items);
            debug_assert!(self.leaves.len() <= ONE as usize);
            return LEAF | (self.leaves.len() - 1) as u32;
        };
        let (mut kids, mut n) = ([0usize; 4], 0);
        for k in two {
            match binary[k].kids {
                Some(grand) => {
                    kids[n..n + 2].copy_from_slice(&grand);
                    n += 2;
                }
                None => {
                    kids[n] = k;
                    n += 1;
                }
            }
        }
        let index = self.nodes.len();
        let mut boxes = [Aabb::EMPTY; 4];
        for (b, &k) in boxes.iter_mut().zip(&kids[..n]) {
            *b = binary[k].bounds;
        }
        let mut timed = UNTIMED;
        if kids[..n].iter().any(|&k| binary[k].keep) {
            timed = scratch.quads.len() as u32;
            for seg in 0..scratch.count {
                let mut at = boxes;
                for (a, &k) in at.iter_mut().zip(&kids[..n]) {
                    if binary[k].at != UNTIMED {
                        *a = scratch.at[binary[k].at as usize + seg];
                    }
                }
                scratch.quads.push(Quad::of(&at[..n]));
            }
        }
        self.nodes.push(Node {
            boxes: Quad::of(&boxes[..n]),
            child: [NO_CHILD; 4],
            lanes: (1 << n) - 1,
            timed,
        });
        for (c, &k) in kids[..n].iter().enumerate() {
            let child = self.wide(scratch, k);
            self.nodes[index].child[c] = child;
        }
        index as u32
    }

    /// The walk of [`super::Structure::walk`]: a node's children in the
    /// order the ray enters them, each skipped when the ray enters it
    /// beyond the limit as it stands then; a leaf's objects each behind
    /// its own box (a leaf of one object behind its lane of the parent's
    /// test, which is its box). The nodes' tests are `QuadRay::span`'s,
    /// which may let in a box the ray only passes near, never keep out one
    /// it meets. Where a node, or an object of a leaf, has boxes over the
    /// time segments, those of `segment` are tested: the ray's time must
    /// lie in it ([`Segments::of`]).
    pub fn walk(
        &self,
        ray: &BoxRay,
        tmin: f64,
        limit: f64,
        segment: usize,
        stack: &mut Vec<(u32, f32)>,
        visit: impl FnMut(usize) -> Step,
    ) -> ControlFlow<()> {
        // A tree with no boxes over time (every scene at rest) is walked
        // without asking each node for them.
        if self.segments.is_whole() {
            self.walk_in::<false>(ray, tmin, limit, 0, stack, visit)
        } else {
            let segment = segment.min(self.segments.count() - 1);
            self.walk_in::<true>(ray, tmin, limit, segment, stack, visit)
        }
    }

    /// [`Bvh::walk`], asking each node and leaf for its boxes over the
    /// time segments if `TIMED`.
    #[inline(always)]
    fn walk_in<const TIMED: bool>(
        &self,
        ray: &BoxRay,
        tmin: f64,
        mut limit: f64,
        segment: usize,
        stack: &mut Vec<(u32, f32)>,
        mut visit: impl FnMut(usize) -> Step,
    ) -> ControlFlow<()> {
        if self.is_empty() {
            return ControlFlow::Continue(());
        }
        let root = match TIMED {
            true => self.root_at.get(segment).unwrap_or(&self.bounds),
            false => &self.bounds,
        };
        if ray.span(root, tmin, limit).is_none() {
            return ControlFlow::Continue(());
        }
        let (nodes, offset, root) = match TIMED {
            true => (&self.in_time.nodes[..], self.in_time.offset(segment), self.in_time.root),
            false => (&self.nodes[..], 0, self.root),
        };
        let quad = QuadRay::new(ray, tmin);
        let mut t1 = quad.limit(limit);
        stack.clear();
        // The root is met (its entry is within the limit).
        let (mut at, mut enter) = (root, quad.start());
        loop {
            if enter <= t1 {
                // (A node's reference may carry `ONE`'s bit as `InTime`'s
                // mark, never with `LEAF`.)
                if at & (LEAF | ONE) == LEAF | ONE {
                    limit = visit((at & !(LEAF | ONE)) as usize)?;
                    t1 = quad.limit(limit);
                } else if at & LEAF != 0 {
                    let (start, count) = self.leaves[(at & !LEAF) as usize];
                    // (A leaf of one object is one of these only past
                    // `ONE`'s objects: its box is then tested again.)
                    let items = &self.items[start as usize..(start + count) as usize];
                    let objects = items.iter().map(|item| {
                        let b = match item.at {
                            at if TIMED && at != UNTIMED => &self.object_at[at as usize + segment],
                            _ => &item.bounds,
                        };
                        (item.object as usize, b)
                    });
                    visit_each(ray, tmin, &mut limit, objects, &mut visit)?;
                    t1 = quad.limit(limit);
                } else {
                    let node = &nodes[InTime::index(at, offset)];
                    let (enters, bits) = quad.span(&node.boxes, t1);
                    let lane = |c: usize| (node.child[c], enters[c]);
                    // The nearer of two next, the other kept for after.
                    let mut two = |x: (u32, f32), y: (u32, f32)| {
                        let (near, far) = if y.1 < x.1 { (y, x) } else { (x, y) };
                        stack.push(far);
                        near
                    };
                    // Each case its own branch (not the lane computed from
                    // the bits): the processor goes on to the predicted
                    // child before the test is done.
                    let next = match bits & node.lanes {
                        0 => None,
                        0b0001 => Some(lane(0)),
                        0b0010 => Some(lane(1)),
                        0b0100 => Some(lane(2)),
                        0b1000 => Some(lane(3)),
                        0b0011 => Some(two(lane(0), lane(1))),
                        0b0101 => Some(two(lane(0), lane(2))),
                        0b1001 => Some(two(lane(0), lane(3))),
                        0b0110 => Some(two(lane(1), lane(2))),
                        0b1010 => Some(two(lane(1), lane(3))),
                        0b1100 => Some(two(lane(2), lane(3))),
                        more => {
                            let a = more.trailing_zeros() as usize;
                            let rest = more & (more - 1);
                            let b = rest.trailing_zeros() as usize;
                            Some(nearest_of(stack, node, &enters, lane(a), lane(b), rest & (rest - 1)))
                        }
                    };
                    if let Some(next) = next {
                        (at, enter) = next;
                        continue;
                    }
                }
            }
            match stack.pop() {
                Some(next) => (at, enter) = next,
                None => return ControlFlow::Continue(()),
            }
        }
    }

    /// The deepest leaf's depth in the walked tree (the root's is 0).
    pub fn depth(&self) -> usize {
        let mut deepest = 0;
        let mut stack = vec![(self.root, 0usize)];
        while let Some((n, d)) = stack.pop() {
            deepest = deepest.max(d);
            // (A lane without a child, and the empty tree's root, carry
            // the leaf bit too.)
            if n & LEAF == 0 {
                for &c in &self.nodes[n as usize].child {
                    if c != NO_CHILD {
                        stack.push((c, d + 1));
                    }
                }
            }
        }
        deepest
    }

    /// The number of nodes (leaves apart).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.root == NO_CHILD
    }

    /// The time segments its boxes are kept for.
    pub fn segments(&self) -> &Segments {
        &self.segments
    }

    /// The number of nodes that keep boxes over the time segments.
    pub fn timed_len(&self) -> usize {
        self.nodes.iter().filter(|n| n.timed != UNTIMED).count()
    }
}

/// The union of `parts` over each of `count` segments, pushed on `out`;
/// returns where it starts there, or [`UNTIMED`] when no part has boxes
/// over the segments. A part is its box over all times and where its
/// boxes over the segments start, in `from` (`None`: in `out` itself), or
/// [`UNTIMED`] (its one box in every segment).
fn union_over_segments(
    out: &mut Vec<Aabb>,
    from: Option<&[Aabb]>,
    count: usize,
    parts: impl Iterator<Item = (Aabb, u32)>,
) -> u32 {
    if count == 1 {
        return UNTIMED;
    }
    let start = out.len();
    out.resize(start + count, Aabb::EMPTY);
    let mut any = false;
    for (whole, at) in parts {
        any |= at != UNTIMED;
        for k in 0..count {
            let b = match (at, from) {
                (UNTIMED, _) => whole,
                (at, Some(from)) => from[at as usize + k],
                (at, None) => out[at as usize + k],
            };
            out[start + k] = out[start + k].union(&b);
        }
    }
    if !any {
        out.truncate(start);
        return UNTIMED;
    }
    start as u32
}

/// Of three or four children met (`first`, `second` and the lanes of
/// `rest`), the nearest, the others pushed on `stack` the nearer last.
#[inline(never)]
fn nearest_of(
    stack: &mut Vec<(u32, f32)>,
    node: &Node,
    enters: &[f32; 4],
    first: (u32, f32),
    second: (u32, f32),
    mut rest: u32,
) -> (u32, f32) {
    // A lane without a child sorts farthest and is not pushed.
    let none = (NO_CHILD, f32::INFINITY);
    let mut met = [first, second, none, none];
    for m in met.iter_mut().skip(2) {
        let c = rest.trailing_zeros() as usize;
        if c < 4 {
            *m = (node.child[c], enters[c]);
        }
        rest &= rest.wrapping_sub(1);
    }
    // Farthest first: a sorting network of four.
    for (i, j) in [(0, 1), (2, 3), (0, 2), (1, 3), (1, 2)] {
        if met[i].1 < met[j].1 {
            met.swap(i, j);
        }
    }
    for &m in &met[..3] {
        if m.0 != NO_CHILD {
            stack.push(m);
        }
    }
    met[3]
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
    use crate::types::{DVec3, Ray};

    fn visited(bvh: &Bvh, ray: &Ray, limit: f64) -> Vec<usize> {
        let mut v = Vec::new();
        let _ = bvh.walk(&BoxRay::new(ray), 0.0, limit, 0, &mut Vec::new(), |i| {
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
        // The root's children, and whether each is a leaf of the floor.
        let root = &bvh.nodes[bvh.root as usize];
        let alone = |c: usize| root.child[c] == LEAF | ONE;
        assert_eq!((0..4).filter(|&c| alone(c)).count(), 1);
        // The root holds its children's boxes: the floor's own is one.
        let floor = Quad::of(&[boxes[0]; 4]);
        for c in 0..4 {
            assert_eq!(root.boxes.lane(c) == floor.lane(c), alone(c), "{c}");
        }
    }

    /// The walked tree's levels: a lone object is the root leaf; two or
    /// four objects hang from one node; 64 in a row take three levels of
    /// four-wide nodes at least, and no more than the binary tree's six
    /// levels would halve to, give or take the heuristic's uneven splits.
    #[test]
    fn depth_counts_the_walked_levels() {
        let row = |n: usize| -> Vec<Aabb> { (0..n).map(|i| cube([i as f64 * 3.0, 0.0, 0.0], 1.0)).collect() };
        assert_eq!(Bvh::build(&row(1)).depth(), 0);
        assert!(!Bvh::build(&row(1)).is_empty() && Bvh::build(&[]).is_empty());
        assert_eq!(Bvh::build(&row(2)).depth(), 1);
        assert_eq!(Bvh::build(&row(4)).depth(), 1);
        let d = Bvh::build(&row(64)).depth();
        assert!((3..=5).contains(&d), "{d}");
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

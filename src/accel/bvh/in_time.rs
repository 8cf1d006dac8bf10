//! The nodes of a [`Bvh`](super::Bvh) with boxes over time segments, laid
//! out for a walk at one time ([`InTime`]). The port's.

use super::{Node, Quad, LEAF, NO_CHILD};
use crate::accel::time::UNTIMED;

/// The nodes of a tree with boxes over time segments as a walk at one
/// time reads them: one node a step, its boxes of the ray's segment in it,
/// as at rest (not the node and then its boxes over the segment from a
/// table apart). A node that keeps no boxes over the segments is kept
/// once, `nodes[i]`; one that keeps them (a tree's upper nodes seldom
/// do) once a segment after those, `nodes[untimed + segment · timed + j]`,
/// and its parent refers to it as [`IN_SEGMENT`] | j.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct InTime {
    pub(super) nodes: Vec<Node>,
    pub(super) root: u32,
    untimed: u32,
    timed: u32,
}

/// The mark of a reference to a node kept once a segment ([`InTime`]):
/// below [`LEAF`], above any index of a node.
const IN_SEGMENT: u32 = 1 << 30;

impl InTime {
    /// A tree's `nodes` (its root `root`) and their boxes over its
    /// `count` segments (a timed node's from `quads[node.timed]` on).
    pub(super) fn of(nodes: &[Node], quads: &[Quad], root: u32, count: usize) -> InTime {
        debug_assert!(nodes.len() < IN_SEGMENT as usize);
        // Each node's reference here: the untimed and the timed counted
        // apart, each in the tree's order.
        let (mut untimed, mut timed) = (0u32, 0u32);
        let new_ref: Vec<u32> = nodes
            .iter()
            .map(|n| {
                let (counter, mark) = match n.timed {
                    UNTIMED => (&mut untimed, 0),
                    _ => (&mut timed, IN_SEGMENT),
                };
                *counter += 1;
                mark | (*counter - 1)
            })
            .collect();
        let child = |c: u32| match c {
            c if c == NO_CHILD || c & LEAF != 0 => c,
            c => new_ref[c as usize],
        };
        let remapped = |n: &Node, boxes: Quad| Node {
            boxes,
            child: n.child.map(child),
            lanes: n.lanes,
            timed: n.timed,
        };
        let mut walked: Vec<Node> = nodes
            .iter()
            .filter(|n| n.timed == UNTIMED)
            .map(|n| remapped(n, n.boxes))
            .collect();
        for seg in 0..count {
            let timed_nodes = nodes.iter().filter(|n| n.timed != UNTIMED);
            walked.extend(timed_nodes.map(|n| remapped(n, quads[n.timed as usize + seg])));
        }
        InTime {
            nodes: walked,
            root: child(root),
            untimed,
            timed,
        }
    }

    /// What [`InTime::index`] adds to the index of a node kept once a
    /// segment, for segment `segment`.
    #[inline(always)]
    pub(super) fn offset(&self, segment: usize) -> usize {
        (self.untimed + segment as u32 * self.timed) as usize
    }

    /// Where the node `at` refers to stands in `nodes` for the segment
    /// whose [`InTime::offset`] is `offset`: without a branch, which the
    /// mix of the two kinds along a walk would make hard to foresee.
    #[inline(always)]
    pub(super) fn index(at: u32, offset: usize) -> usize {
        let in_segment = (at >> 30) as usize & 1;
        (at & !IN_SEGMENT) as usize + (offset & in_segment.wrapping_neg())
    }
}

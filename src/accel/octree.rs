//! The thesis's space subdivision (§2.1.2 (2)(b), OCR lines 239–275,
//! after Glassner 1984): space cut into cells (Fig. 2.15), each keeping the
//! objects in it; a ray tests the objects of the nearest cell first and
//! goes on to the next cell only if it found no hit before leaving it
//! ("若有交點, 便可忽略其他的子空間, 否則再對下一個子空間作交點的測試").
//! The cell a point lies in is found by LISTING 1, `findnode(x,y,z)`
//! (Fig. 2.16, OCR lines 244–271), ported as printed: from node 1, while
//! the node is subdivided, compare the point with the node's centre (`>`)
//! and go to child `node*10 + 1..8`.
//!
//! What the listing does not print, the port's (DEVIATIONS D34): the
//! build (the scene's box, halved on every axis while a cell holds more
//! than [`MAX_IN_CELL`] objects, to [`MAX_DEPTH`] levels, and while the
//! references stay within a budget), that an object straddling cells is
//! kept in each cell its box meets, how a ray steps from a cell to the
//! next (a point just past the face it leaves, looked up by `findnode`),
//! and where the nodes are kept: in a flat table, each with its listing
//! number, rather than at the number itself.

use std::collections::VecDeque;
use std::ops::ControlFlow;

use super::{visit_each, Aabb, BoxRay, Step};
use crate::types::DVec3;

/// A cell holding more objects than this is subdivided (if it may be).
pub(crate) const MAX_IN_CELL: usize = 8;

/// The deepest level: node numbers stay below 10^(MAX_DEPTH + 1), well
/// within a u64.
pub const MAX_DEPTH: u32 = 12;

/// The most references to objects the cells may hold, per object.
const BUDGET: usize = 12;

/// A node of the octree: a cell, its listing number, its box and centre,
/// its children (`children..children + 8`, in the order of Listing 1's
/// branches 1..8; 0 for a leaf), its objects (`refs[start..start + count]`).
#[derive(Clone, Debug, PartialEq)]
struct Node {
    number: u64,
    bounds: Aabb,
    centre: DVec3,
    children: u32,
    start: u32,
    count: u32,
}

/// The leaf `findnode` found: its number as Listing 1 counts (1 the root,
/// `node*10 + k` its children), and its place in the port's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Found {
    pub node: u64,
    pub index: usize,
}

/// See the module doc. Built by [`Octree::build`], searched by
/// [`Octree::findnode`], walked by [`Octree::walk`].
#[derive(Clone, Debug, PartialEq)]
pub struct Octree {
    nodes: Vec<Node>,
    refs: Vec<u32>,
    /// Every object's box, by index.
    boxes: Vec<Aabb>,
    /// The objects whose box is not finite: no cell holds them, every ray
    /// visits them.
    everywhere: Vec<u32>,
}

/// The branch Listing 1 takes at a node whose centre is (`cx`, `cy`, `cz`):
/// the last digit of the child's number, as printed.
#[allow(clippy::collapsible_else_if)] // The listing's nest of IFs, as printed.
fn branch(x: f64, y: f64, z: f64, cx: f64, cy: f64, cz: f64) -> u64 {
    if x > cx {
        if y > cy {
            if z > cz {
                6
            } else {
                2
            }
        } else {
            if z > cz {
                8
            } else {
                4
            }
        }
    } else {
        if y > cy {
            if z > cz {
                5
            } else {
                1
            }
        } else {
            if z > cz {
                7
            } else {
                3
            }
        }
    }
}

/// Which side of the centre each axis of child `k` (1..8) lies on, `true`
/// for above: the inverse of `branch`.
pub fn findnode_digit(k: u64) -> [bool; 3] {
    match k {
        6 => [true, true, true],
        2 => [true, true, false],
        8 => [true, false, true],
        4 => [true, false, false],
        5 => [false, true, true],
        1 => [false, true, false],
        7 => [false, false, true],
        _ => [false, false, false],
    }
}

/// The box of child `k` of a cell: above the centre on an axis, from the
/// centre to the cell's top (the centre itself belongs below, `>`).
fn child_box(cell: &Aabb, centre: DVec3, k: u64) -> Aabb {
    let above = findnode_digit(k);
    let mut b = *cell;
    for axis in 0..3 {
        if above[axis] {
            b.lo[axis] = centre[axis];
        } else {
            b.hi[axis] = centre[axis];
        }
    }
    b
}

/// May a cell be halved: its centre strictly inside it on every axis, and
/// its sides well above the rounding of its coordinates.
fn divisible(b: &Aabb) -> bool {
    let size = b.lo.abs().max(b.hi.abs()).max_element().max(1.0);
    let c = b.centre();
    (0..3).all(|k| b.hi[k] - b.lo[k] > 1e-9 * size && c[k] > b.lo[k] && c[k] < b.hi[k])
}

impl Octree {
    /// The octree over `boxes`, object i's box at index i: the box of the
    /// finite ones, halved breadth first (see the module doc).
    pub fn build(boxes: &[Aabb]) -> Octree {
        let finite = |b: &Aabb| b.lo.is_finite() && b.hi.is_finite();
        let everywhere: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| !finite(&boxes[i as usize]))
            .collect();
        let inside: Vec<u32> = (0..boxes.len() as u32)
            .filter(|&i| finite(&boxes[i as usize]))
            .collect();
        let mut tree = Octree {
            nodes: Vec::new(),
            refs: Vec::new(),
            boxes: boxes.to_vec(),
            everywhere,
        };
        if inside.is_empty() {
            return tree;
        }
        let root = inside.iter().fold(Aabb::EMPTY, |b, &i| b.union(&boxes[i as usize]));
        let budget = BUDGET * inside.len() + 1024;
        let mut held = inside.len();
        let mut lists: Vec<Vec<u32>> = vec![inside];
        tree.nodes.push(Node {
            number: 1,
            bounds: root,
            centre: root.centre(),
            children: 0,
            start: 0,
            count: 0,
        });
        let mut queue = VecDeque::from([(0usize, 0u32)]);
        while let Some((n, depth)) = queue.pop_front() {
            let (cell, centre, number) = (tree.nodes[n].bounds, tree.nodes[n].centre, tree.nodes[n].number);
            let list = &lists[n];
            if list.len() <= MAX_IN_CELL || depth >= MAX_DEPTH || !divisible(&cell) {
                continue;
            }
            let parts: Vec<(Aabb, Vec<u32>)> = (1..=8)
                .map(|k| {
                    let b = child_box(&cell, centre, k);
                    (
                        b,
                        list.iter()
                            .copied()
                            .filter(|&i| boxes[i as usize].overlaps(&b))
                            .collect(),
                    )
                })
                .collect();
            let more: usize = parts.iter().map(|(_, l)| l.len()).sum::<usize>();
            // No child holds fewer than the cell: halving gains nothing.
            if parts.iter().all(|(_, l)| l.len() == list.len()) || held + more > budget {
                continue;
            }
            held += more;
            tree.nodes[n].children = tree.nodes.len() as u32;
            for (k, (b, l)) in (1..=8).zip(parts) {
                queue.push_back((tree.nodes.len(), depth + 1));
                tree.nodes.push(Node {
                    number: number * 10 + k,
                    bounds: b,
                    centre: b.centre(),
                    children: 0,
                    start: 0,
                    count: 0,
                });
                lists.push(l);
            }
        }
        // The leaves' lists into one table.
        for (node, list) in tree.nodes.iter_mut().zip(lists) {
            if node.children == 0 {
                node.start = tree.refs.len() as u32;
                node.count = list.len() as u32;
                tree.refs.extend(list);
            }
        }
        tree
    }

    /// `findnode(x,y,z)` of LISTING 1 (OCR lines 248–271): from node 1,
    /// while the node is subdivided, the child on the point's side of its
    /// centre in each axis (`>`: a point on a centre plane goes below),
    /// numbered `node*10 + k`. Returns the leaf, its number as the listing
    /// counts and its place in the port's table. The octree must have
    /// cells (an octree of no finite box has none).
    pub fn findnode(&self, x: f64, y: f64, z: f64) -> Found {
        let mut node = 1u64;
        let mut index = 0usize;
        while self.nodes[index].children != 0 {
            let c = self.nodes[index].centre;
            let k = branch(x, y, z, c.x, c.y, c.z);
            node = node * 10 + k;
            index = self.nodes[index].children as usize + (k - 1) as usize;
        }
        Found { node, index }
    }

    /// The walk of [`super::Structure::walk`], as §2.1.2 (2)(b) says: the
    /// objects of the cell the ray starts in (or enters the scene's box
    /// by), then of each next cell, until the limit (the nearest hit so
    /// far, or the shadow ray's end) lies before the cell's far side.
    /// Each object behind its own box; an object in several cells may be
    /// visited in each.
    pub fn walk<'t>(
        &'t self,
        ray: &BoxRay,
        tmin: f64,
        mut limit: f64,
        mut visit: impl FnMut(usize) -> Step,
    ) -> ControlFlow<()> {
        let of = |refs: &'t [u32]| refs.iter().map(|&i| (i as usize, &self.boxes[i as usize]));
        visit_each(ray, tmin, &mut limit, of(&self.everywhere), &mut visit)?;
        let Some(root) = self.nodes.first() else {
            return ControlFlow::Continue(());
        };
        let Some((enter, _)) = ray.span(&root.bounds, tmin, limit) else {
            return ControlFlow::Continue(());
        };
        let root_box = root.bounds;
        let mut p = (ray.origin + ray.dir * enter).clamp(root_box.lo, root_box.hi);
        // A ray crosses each leaf once at most: more steps would be a
        // fault of the stepping; the rest is then visited without order.
        for _ in 0..self.nodes.len() {
            let found = self.findnode(p.x, p.y, p.z);
            let leaf = &self.nodes[found.index];
            let start = leaf.start as usize;
            visit_each(
                ray,
                tmin,
                &mut limit,
                of(&self.refs[start..start + leaf.count as usize]),
                &mut visit,
            )?;
            let (exit, next) = step(ray, &leaf.bounds, &root_box);
            match next {
                Some(q) if limit >= exit || limit.is_nan() => p = q,
                _ => return ControlFlow::Continue(()),
            }
        }
        visit_each(ray, tmin, &mut limit, self.boxes.iter().enumerate(), &mut visit)
    }

    /// The number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The listing numbers of the leaves, for tests and tools.
    pub fn leaves(&self) -> impl Iterator<Item = u64> + '_ {
        self.nodes.iter().filter(|n| n.children == 0).map(|n| n.number)
    }
}

/// Where the ray leaves `cell`: its t there, and a point just inside the
/// next cell, `None` when it leaves the scene's box `root`. On each axis
/// whose face the ray leaves by, the point is on the next cell's side of
/// the face as `findnode`'s `>` takes it (the face's coordinate itself
/// going down, the next number above it going up); on the other axes the
/// ray's coordinate there, kept within the cell.
fn step(ray: &BoxRay, cell: &Aabb, root: &Aabb) -> (f64, Option<DVec3>) {
    let mut exit = f64::INFINITY;
    let mut far = [f64::INFINITY; 3];
    for (k, far) in far.iter_mut().enumerate() {
        let d = ray.dir[k];
        let face = if d > 0.0 {
            cell.hi[k]
        } else if d < 0.0 {
            cell.lo[k]
        } else {
            continue;
        };
        *far = (face - ray.origin[k]) / d;
        exit = exit.min(*far);
    }
    if !exit.is_finite() {
        return (exit, None);
    }
    let mut p = ray.origin + ray.dir * exit;
    for k in 0..3 {
        if far[k] == exit {
            if ray.dir[k] > 0.0 {
                if cell.hi[k] >= root.hi[k] {
                    return (exit, None);
                }
                p[k] = cell.hi[k].next_up();
            } else {
                if cell.lo[k] <= root.lo[k] {
                    return (exit, None);
                }
                p[k] = cell.lo[k];
            }
        } else {
            let lo = if cell.lo[k] <= root.lo[k] {
                cell.lo[k]
            } else {
                cell.lo[k].next_up()
            };
            p[k] = p[k].clamp(lo, cell.hi[k]);
        }
    }
    (exit, Some(p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::tests::cube;
    use crate::types::Ray;

    /// LISTING 1 as printed, on its own centres: `node_center` of each
    /// node given, `node_subdivided` true to `depth` levels.
    fn listing_findnode(x: f64, y: f64, z: f64, centre: impl Fn(u64) -> [f64; 3], depth: u32) -> u64 {
        let mut node: u64 = 1;
        let mut level = 0;
        while level < depth {
            let [cx, cy, cz] = centre(node);
            // The IFs of Fig. 2.16, line by line.
            node = if x > cx {
                if y > cy {
                    if z > cz {
                        (node * 10) + 6
                    } else {
                        (node * 10) + 2
                    }
                } else if z > cz {
                    (node * 10) + 8
                } else {
                    (node * 10) + 4
                }
            } else if y > cy {
                if z > cz {
                    (node * 10) + 5
                } else {
                    (node * 10) + 1
                }
            } else if z > cz {
                (node * 10) + 7
            } else {
                (node * 10) + 3
            };
            level += 1;
        }
        node
    }

    /// The object whose box is the whole cube of [`two_levels`].
    const BIG: usize = 64 * 9;

    /// A full octree of two levels over the cube [0, 8]³: nine objects
    /// about the centre of each cell of the second level (object i in
    /// cell i mod 64), which no halving of it separates, and one object
    /// as large as the cube ([`BIG`]).
    fn two_levels() -> Octree {
        let boxes: Vec<Aabb> = (0..BIG)
            .map(|i| {
                let c = i % 64;
                let (x, y, z) = ((c % 4) as f64, (c / 4 % 4) as f64, (c / 16) as f64);
                cube([2.0 * x + 1.0, 2.0 * y + 1.0, 2.0 * z + 1.0], 0.25)
            })
            .chain([cube([4.0; 3], 4.0)])
            .collect();
        Octree::build(&boxes)
    }

    /// The cells' objects a walk visits (the large one left out), with
    /// `limit` as every visit's answer.
    fn walked(tree: &Octree, ray: &Ray, limit: f64) -> Vec<usize> {
        let mut v = Vec::new();
        let _ = tree.walk(&BoxRay::new(ray), 0.0, f64::INFINITY, |i| {
            if i != BIG {
                v.push(i % 64);
            }
            ControlFlow::Continue(limit)
        });
        v.dedup();
        v
    }

    /// The node's centre, from its number: the cube [0, 8]³ halved along
    /// the digits' branches.
    fn centre_of(number: u64) -> [f64; 3] {
        let digits: Vec<u64> = number
            .to_string()
            .bytes()
            .skip(1)
            .map(|b| u64::from(b - b'0'))
            .collect();
        let (mut lo, mut size) = ([0.0; 3], 8.0);
        for k in digits {
            size /= 2.0;
            let above = findnode_digit(k);
            for a in 0..3 {
                if above[a] {
                    lo[a] += size;
                }
            }
        }
        lo.map(|l| l + size / 2.0)
    }

    /// `findnode` against the listing on points in every octant of both
    /// levels, and on the cell boundaries (a point on a centre plane goes
    /// to the lower side, the listing's `>`).
    #[test]
    fn findnode_is_listing_1() {
        let tree = two_levels();
        assert_eq!(tree.leaves().count(), 64);
        let mut seen = std::collections::BTreeSet::new();
        let coords = [
            0.0,
            0.5,
            1.0,
            1.5,
            2.0,
            2.5,
            3.0,
            4.0,
            4.0f64.next_up(),
            5.0,
            6.0,
            7.5,
            8.0,
        ];
        for &x in &coords {
            for &y in &coords {
                for &z in &coords {
                    let got = tree.findnode(x, y, z);
                    let want = listing_findnode(x, y, z, centre_of, 2);
                    assert_eq!(got.node, want, "({x}, {y}, {z})");
                    assert_eq!(tree.nodes[got.index].number, want);
                    seen.insert(want);
                }
            }
        }
        assert_eq!(seen.len(), 64, "every leaf reached");
        // The printed digits: the centre 4, 4, 4 itself goes to 3
        // (x ≤, y ≤, z ≤), just above it on every axis to 6.
        assert_eq!(tree.findnode(4.0, 4.0, 4.0).node / 10, 13);
        let up = 4.0f64.next_up();
        assert_eq!(tree.findnode(up, up, up).node / 10, 16);
        for (x, y, z, k) in [
            (5.0, 5.0, 5.0, 6),
            (5.0, 5.0, 3.0, 2),
            (5.0, 3.0, 5.0, 8),
            (5.0, 3.0, 3.0, 4),
            (3.0, 5.0, 5.0, 5),
            (3.0, 5.0, 3.0, 1),
            (3.0, 3.0, 5.0, 7),
            (3.0, 3.0, 3.0, 3),
        ] {
            assert_eq!(tree.findnode(x, y, z).node / 10, 10 + k, "octant {k}");
        }
    }

    /// A ray through the cells visits the objects of each cell it passes,
    /// in the order of the cells along it; a limit stops the walk at the
    /// cell where it falls.
    #[test]
    fn a_ray_steps_from_cell_to_cell() {
        let tree = two_levels();
        let ray = Ray::new(DVec3::new(-1.0, 1.0, 1.0), DVec3::X);
        assert_eq!(walked(&tree, &ray, f64::INFINITY), vec![0, 1, 2, 3]);
        assert_eq!(walked(&tree, &ray, 2.5), vec![0], "the first cell ends at t = 3");
        assert_eq!(walked(&tree, &ray, 3.0), vec![0]);
        assert_eq!(
            walked(&tree, &ray, 3.75),
            vec![0, 1],
            "a box entered at the limit is visited"
        );
        let back = Ray::new(DVec3::new(9.0, 7.0, 3.0), DVec3::NEG_X);
        assert_eq!(walked(&tree, &back, f64::INFINITY), vec![31, 30, 29, 28]);
        // Diagonally through the centre and along the edges of cells.
        let diagonal = Ray::new(DVec3::splat(-1.0), DVec3::ONE);
        assert_eq!(walked(&tree, &diagonal, f64::INFINITY), vec![0, 21, 42, 63]);
        let on_edge = Ray::new(DVec3::new(4.0, 4.0, -1.0), DVec3::Z);
        assert!(walked(&tree, &on_edge, f64::INFINITY).is_empty());
    }

    #[test]
    fn straddling_objects_stop_the_halving() {
        let boxes = vec![cube([0.0; 3], 1.0); 1000];
        let tree = Octree::build(&boxes);
        assert_eq!(tree.len(), 1);
        let mut boxes: Vec<Aabb> = (0..1000).map(|i| cube([i as f64 * 0.01, 0.0, 0.0], 0.3)).collect();
        boxes.push(cube([5.0, 0.0, 0.0], 100.0));
        let tree = Octree::build(&boxes);
        assert!(tree.refs.len() <= BUDGET * boxes.len() + 1024);
    }
}

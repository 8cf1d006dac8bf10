//! Key shapes given by points: the blobs and patches of §6.2 deformed by
//! the §3.2 machinery (the port's extension). The thesis deforms sweep
//! contours and ends (§6.2, OCR lines ~1212–1216) on the objects that
//! would come next, "parametric surfaces and soft objects", whose
//! in-betweens are feasible "once the bottleneck of their motion paths is
//! overcome". Here their points take the paths §3.2.3 gives a contour's
//! segment starts:
//!
//! 1. the counts made equal: two blobs of different counts are matched
//!    component by component in order, the fewer given components of
//!    strength 0 at the other's centres and radii, which fade in (or out)
//!    over the pair (DEVIATIONS D57); a patch always has 16 points;
//! 2. the paths of the points (§3.2.3 (b), Fig. 3.8): each point's
//!    coordinates (x, y, z, and a blob component's radius and strength)
//!    are the contour's U and V of the sweeps, one at a time. The first
//!    point and the middle one (`mid := count div 2`) are the reference
//!    points; two large Hermite patches from the first to the middle and
//!    back (`getmatrix`), read at each point's share of the length of the
//!    closed polygon through the points ([`point_shares`], `getdistance`'s
//!    chords in space), give every other point's path (`getpath`);
//! 3. each point's in-between (§3.2.3 (c)): the patch of `getmatrix`
//!    whose two corners at t = 0 are the point in FIRST and at t = 1 in
//!    LAST (a segment of no length), t-tangents from the point's path; its
//!    edge is the Hermite cubic in t the point follows; at t = 0 and 1 the
//!    key shapes themselves (`do34`);
//! 4. the pose (`motionblur`'s `paper = 1` branch, [`keyed_pose`]): from
//!    FIRST's to LAST's, `diff` and `diffangle` by `difference`
//!    (errata 4, 19 as for the sweeps).
//!
//! One reading differs from the sweeps' (DEVIATIONS D56): the reference
//! points' paths are their own straight lines from FIRST to LAST in the
//! object's frame, not the object's motion. The sweeps' `goahead` gives
//! the contour's start and middle the motion's x and z as t-tangents, so
//! a sweep pair of one shape at two places bulges by up to 0.096 of the
//! distance between them (erratum 9's row); with the points' own lines,
//! key shapes that are one shape give every path a tangent of exactly 0,
//! and the in-between is that shape, to the bit, moving from pose to pose.

use super::{
    chain_pairs, cubic_range, difference, getmatrix, getpath, keyed_centre, keyed_pose, keyframe_first, reparam, Chain,
    Distarray, KeyPair, PaperError, Sdirection,
};
use crate::options::Fidelity;
use crate::scene::{KeyframeRecord, Scene};
use crate::types::{
    BlobComponent, BlobShape, BoundingBox, Coeff, DMat3, DVec3, ObjectRecord, PatchShape, Pose, PrimitiveClass, Shape,
    MAXCOMPONENTS, MAXSEGMENTS,
};

/// The coordinates of a point: x, y, z, and a blob component's radius and
/// strength (a patch's points use the first three).
pub const DIMS: usize = 5;

/// A key shape's points, its threshold (a blob's; 0 for a patch) and its
/// class; `None` for a shape that is not a blob or a patch.
fn points_of(obj: &ObjectRecord) -> Option<(Vec<[f64; DIMS]>, f64)> {
    match &obj.shape {
        Shape::Blob(b) => Some((
            b.components
                .iter()
                .map(|c| [c.centre.x, c.centre.y, c.centre.z, c.radius, c.strength])
                .collect(),
            b.threshold,
        )),
        Shape::Patch(p) => Some((p.points.iter().map(|q| [q.x, q.y, q.z, 0.0, 0.0]).collect(), 0.0)),
        _ => None,
    }
}

/// `getdistance` (unit `paper`, OCR lines 2745–2790) for points in space:
/// the share of the closed polygon through `points` (their x, y, z) from
/// the first point to point i + 1 in `dist[i]`, `dist[0] = 0` and
/// `dist[n] = 1`; the chords summed and divided once, as the listing
/// does. Points that all coincide (one component, or concentric ones)
/// have no length: their shares are then i/n (the port's; the sweeps
/// refuse such a contour, `PaperError::Degenerate`).
pub fn point_shares(points: &[[f64; DIMS]], dist: &mut Distarray) {
    let nu = points.len().min(MAXSEGMENTS);
    dist[0] = 0.0;
    if nu == 0 {
        return;
    }
    let at = |i: usize| DVec3::new(points[i - 1][0], points[i - 1][1], points[i - 1][2]);
    let mut sum = (at(1) - at(nu)).length();
    dist[nu] = sum;
    for i in 2..=nu {
        dist[i - 1] = (at(i) - at(i - 1)).length();
        sum += dist[i - 1];
    }
    for i in 1..=nu {
        dist[i] = if sum > 0.0 && sum.is_finite() {
            dist[i] / sum + dist[i - 1]
        } else {
            i as f64 / nu as f64
        };
    }
}

/// What `goahead` computes for a pair of key blobs or patches ([`PointPair::new`]).
#[derive(Clone, Debug, PartialEq)]
pub struct PointPair {
    /// The pair's number in its chain, from 1.
    pub int: usize,
    pub fidelity: Fidelity,
    /// `PrimitiveClass::Blob` or `PrimitiveClass::Patch`.
    pub class: PrimitiveClass,
    /// The points of the pair after matching (`snu` of the sweeps).
    pub count: usize,
    /// `mid := count div 2`: the middle reference point (0 for one point).
    pub mid: usize,
    /// FIRST's shares ([`point_shares`]).
    pub dist: Distarray,
    /// `path[k][i]`: the path of coordinate k of point i (1-based), a
    /// cubic in t (`getpath`).
    pub paths: Vec<Sdirection>,
    /// `curves[k][i - 1]`: coordinate k of point i over the pair, the
    /// Hermite cubic in t of point i's patch (`getmatrix`).
    pub curves: Vec<Vec<Coeff>>,
    /// FIRST's and LAST's points after matching (`p3`, `p4` of `do34`).
    pub first: Vec<[f64; DIMS]>,
    pub last: Vec<[f64; DIMS]>,
    /// FIRST's and LAST's thresholds (blobs), taken linearly between.
    pub threshold: (f64, f64),
    /// `diff[int]`, `diffangle[int]`: by `difference` (erratum 4).
    pub diff: DVec3,
    pub diffangle: DVec3,
    /// FIRST's pose at rest.
    pub first_pose: Pose,
}

impl PointPair {
    /// `goahead` for key shapes `obj1` (FIRST) and `obj2` (LAST), two blobs
    /// or two patches (see the module doc). Errors: not two of one kind, a
    /// number that is not finite.
    pub fn new(
        int: usize,
        obj1: &ObjectRecord,
        obj2: &ObjectRecord,
        fidelity: Fidelity,
    ) -> Result<PointPair, PaperError> {
        let (mut first, t1) = points_of(obj1).ok_or(PaperError::NotPoints { int, which: "FIRST" })?;
        let (mut last, t2) = points_of(obj2).ok_or(PaperError::NotPoints { int, which: "LAST" })?;
        if obj1.class != obj2.class {
            return Err(PaperError::ClassMismatch {
                int,
                first: obj1.class,
                last: obj2.class,
            });
        }
        let finite = |p: &[[f64; DIMS]], obj: &ObjectRecord| {
            p.iter().flatten().all(|x| x.is_finite()) && obj.sphereo.is_finite() && obj.angle.is_finite()
        };
        if !finite(&first, obj1) || !t1.is_finite() {
            return Err(PaperError::NotFinite { int, which: "FIRST" });
        }
        if !finite(&last, obj2) || !t2.is_finite() {
            return Err(PaperError::NotFinite { int, which: "LAST" });
        }
        // 1. The fewer points gain the other's, of strength 0.
        let count = first.len().max(last.len()).min(MAXCOMPONENTS);
        let faded = |long: &[[f64; DIMS]], i: usize| {
            let mut p = long[i];
            p[4] = 0.0;
            p
        };
        while first.len() < count {
            first.push(faded(&last, first.len()));
        }
        while last.len() < count {
            last.push(faded(&first, last.len()));
        }
        first.truncate(count);
        last.truncate(count);
        let mut pair = PointPair {
            int,
            fidelity,
            class: obj1.class,
            count,
            mid: count / 2,
            dist: [0.0; MAXSEGMENTS + 1],
            paths: Vec::new(),
            curves: Vec::new(),
            first,
            last,
            threshold: (t1, t2),
            diff: DVec3::ZERO,
            diffangle: DVec3::ZERO,
            first_pose: obj1.pose(),
        };
        difference(obj1.sphereo, obj2.sphereo, &mut pair.diff, fidelity);
        difference(obj1.angle, obj2.angle, &mut pair.diffangle, fidelity);
        point_shares(&pair.first, &mut pair.dist);
        let dims = if pair.class == PrimitiveClass::Blob { DIMS } else { 3 };
        for k in 0..dims {
            let path = pair.path_of(k);
            pair.curves
                .push((1..=count).map(|i| pair.curve_of(k, i, &path)).collect());
            pair.paths.push(path);
        }
        Ok(pair)
    }

    /// Coordinate k of point i (1-based) in FIRST and in LAST, as the
    /// constant curves `getmatrix` reads (`coor` the value, `Rvalue` 0:
    /// points have no s-tangent; with zero twist the paths' t-tangents do
    /// not depend on it).
    fn ends(&self, k: usize, i: usize) -> (Coeff, Coeff) {
        let c = |v: f64| Coeff {
            d: v,
            ..Coeff::default()
        };
        (c(self.first[i - 1][k]), c(self.last[i - 1][k]))
    }

    /// The paths of coordinate k of every point (§3.2.3 (b)): the
    /// reference points' own straight lines (D56), the others `getpath`'s
    /// from the two large patches.
    fn path_of(&self, k: usize) -> Sdirection {
        let mut path = Sdirection::default();
        if self.count == 0 {
            return path;
        }
        let line = |i: usize| {
            let (a, b) = self.ends(k, i);
            Coeff {
                c: b.d - a.d,
                d: a.d,
                ..Coeff::default()
            }
        };
        path[1] = line(1);
        if self.mid == 0 {
            return path;
        }
        let mid = self.mid;
        path[mid] = line(mid);
        let ((a1, b1), (am, bm)) = (self.ends(k, 1), self.ends(k, mid));
        let h = getmatrix(&a1, &am, &b1, &bm, &path[1], &path[mid]);
        getpath(1, mid, &h, &self.dist, &mut path);
        let h = getmatrix(&am, &a1, &bm, &b1, &path[mid], &path[1]);
        getpath(mid, self.count + 1, &h, &self.dist, &mut path);
        path
    }

    /// Coordinate k of point i (1-based) over the pair (§3.2.3 (c)): the
    /// edge s = 0 of `getmatrix`'s patch with both corners at the point,
    /// `[s³ s² s 1]·H·[t³ t² t 1]ᵀ` at s = 0, H's last row.
    fn curve_of(&self, k: usize, i: usize, path: &Sdirection) -> Coeff {
        let (a, b) = self.ends(k, i);
        let h = getmatrix(&a, &a, &b, &b, &path[i], &path[i]);
        Coeff {
            a: h[3][0],
            b: h[3][1],
            c: h[3][2],
            d: h[3][3],
            first: 0.0,
            last: 1.0,
            ..Coeff::default()
        }
    }

    /// Coordinate k of point i (0-based) at `time`: FIRST's or LAST's own
    /// at 0 and 1 (`do34`), else its curve (`Hermite`).
    fn value(&self, k: usize, i: usize, time: f64) -> f64 {
        if time == 0.0 {
            self.first[i][k]
        } else if time == 1.0 {
            self.last[i][k]
        } else {
            self.curves[k][i].value(time)
        }
    }

    /// The in-between shape at `time` (0 to 1 over the pair), written
    /// into `out` (its vectors reused): a blob's components and threshold,
    /// or a patch's points. A shape of the other kind is replaced.
    pub fn inbetween(&self, time: f64, out: &mut Shape) {
        match (self.class, &mut *out) {
            (PrimitiveClass::Blob, Shape::Blob(b)) => {
                let (t1, t2) = self.threshold;
                b.threshold = if time == 1.0 { t2 } else { t1 + (t2 - t1) * time };
                b.components.clear();
                b.components.extend((0..self.count).map(|i| BlobComponent {
                    centre: DVec3::new(self.value(0, i, time), self.value(1, i, time), self.value(2, i, time)),
                    radius: self.value(3, i, time),
                    strength: self.value(4, i, time),
                }));
            }
            (PrimitiveClass::Patch, Shape::Patch(p)) => {
                for (i, q) in p.points.iter_mut().enumerate().take(self.count) {
                    *q = DVec3::new(self.value(0, i, time), self.value(1, i, time), self.value(2, i, time));
                }
            }
            _ => {
                *out = self.scratch();
                self.inbetween(time, out);
            }
        }
    }

    /// Scratch for [`PointPair::inbetween`]: a shape of the pair's kind
    /// with room for its points.
    pub fn scratch(&self) -> Shape {
        match self.class {
            PrimitiveClass::Blob => Shape::Blob(BlobShape {
                threshold: self.threshold.0,
                components: Vec::with_capacity(MAXCOMPONENTS),
            }),
            _ => Shape::Patch(Box::new(PatchShape {
                points: [DVec3::ZERO; 16],
            })),
        }
    }

    /// The range of coordinate k of point i (0-based) over the pair's
    /// times `l0` ≤ t ≤ `l1`: the cubic's extrema there (§3.3's "extrema
    /// test", [`cubic_range`]), and the key shapes' own values at 0 and 1.
    fn range(&self, k: usize, i: usize, l0: f64, l1: f64) -> (f64, f64) {
        let piece = Coeff {
            first: l0,
            last: l1,
            ..self.curves[k][i]
        };
        let (mut lo, mut hi) = cubic_range(&reparam(&piece));
        for (at, v) in [(0.0, self.first[i][k]), (1.0, self.last[i][k])] {
            if (l0..=l1).contains(&at) {
                (lo, hi) = (lo.min(v), hi.max(v));
            }
        }
        (lo, hi)
    }

    /// The box, in the object's local frame, that holds the in-between's
    /// surface over the pair's times `l0` ≤ t ≤ `l1`: a blob's components'
    /// spheres swept (those whose strength can be positive then), a
    /// patch's control points swept (the control hull holds the patch at
    /// each time). `None` where no component can raise the field.
    pub fn local_bounds(&self, l0: f64, l1: f64) -> Option<BoundingBox> {
        let mut b = BoundingBox::EMPTY;
        for i in 0..self.count {
            let r = |k: usize| self.range(k, i, l0, l1);
            let (x, y, z) = (r(0), r(1), r(2));
            let reach = if self.class == PrimitiveClass::Blob {
                let (radius, strength) = (r(3).1, r(4).1);
                if !(radius > 0.0 && strength > 0.0) {
                    continue;
                }
                radius
            } else {
                0.0
            };
            b = b
                .holding(DVec3::new(x.0, y.0, z.0) - DVec3::splat(reach))
                .holding(DVec3::new(x.1, y.1, z.1) + DVec3::splat(reach));
        }
        (b.xmin <= b.xmax).then_some(b)
    }

    /// The pose at `time` (0 to 1 over the pair).
    pub fn pose(&self, time: f64) -> Pose {
        keyed_pose(&self.first_pose, self.diff, self.diffangle, self.fidelity, time)
    }

    /// The origin of [`PointPair::pose`] at `time`, the same to the bit.
    #[inline]
    pub fn centre(&self, time: f64) -> DVec3 {
        keyed_centre(&self.first_pose, self.diff, time)
    }
}

impl KeyPair for PointPair {
    fn pose(&self, local: f64) -> Pose {
        PointPair::pose(self, local)
    }
    #[inline]
    fn centre(&self, local: f64) -> DVec3 {
        PointPair::centre(self, local)
    }
}

/// The chain of a `keyframe` record of blobs or of patches: pair k from
/// the k-th shape to the next (as [`super::PaperChain`] for sweeps).
pub type PointChain = Chain<PointPair>;

impl Chain<PointPair> {
    /// `goahead` for every consecutive couple of `first, rest[0], …`.
    pub fn new(first: &ObjectRecord, rest: &[ObjectRecord], fidelity: Fidelity) -> Result<PointChain, PaperError> {
        let pairs = chain_pairs(first, rest, |int, from, to| PointPair::new(int, from, to, fidelity))?;
        Ok(Chain { pairs })
    }

    /// The chain of a deck's `keyframe` record of blobs or patches.
    pub fn from_keyframe(scene: &Scene, record: &KeyframeRecord, fidelity: Fidelity) -> Result<PointChain, PaperError> {
        PointChain::new(keyframe_first(scene, record)?, &record.rest, fidelity)
    }

    /// The in-between shape at shutter time `time`, into `out`.
    pub fn inbetween(&self, time: f64, out: &mut Shape) {
        let (pair, local) = self.locate(time);
        pair.inbetween(local, out);
    }

    /// Scratch big enough for every pair.
    pub fn scratch(&self) -> Shape {
        self.pairs[0].scratch()
    }

    /// Each pair the shutter times `t0` ≤ t ≤ `t1` reach, with the part of
    /// them in the pair's own time (as [`super::chain_time`] maps them: times
    /// before the first pair or past the last extrapolate it) and in
    /// shutter time.
    fn pieces(&self, t0: f64, t1: f64) -> impl Iterator<Item = (&PointPair, (f64, f64), (f64, f64))> + '_ {
        let n = self.pairs.len();
        let (a, b) = (t0.min(t1), t0.max(t1));
        self.pairs.iter().enumerate().filter_map(move |(k, pair)| {
            let lo = if k == 0 { f64::NEG_INFINITY } else { k as f64 / n as f64 };
            let hi = if k + 1 == n {
                f64::INFINITY
            } else {
                (k + 1) as f64 / n as f64
            };
            let (c0, c1) = (a.max(lo), b.min(hi));
            let local = |t: f64| if n == 1 { t } else { t * n as f64 - k as f64 };
            (c0 <= c1).then(|| (pair, (local(c0), local(c1)), (c0, c1)))
        })
    }

    /// The box, in the object's local frame, holding the in-between's
    /// surface over the shutter times `t0` ≤ t ≤ `t1`
    /// ([`PointPair::local_bounds`] of each pair they reach).
    pub fn local_bounds(&self, t0: f64, t1: f64) -> Option<BoundingBox> {
        self.pieces(t0, t1)
            .filter_map(|(pair, (l0, l1), _)| pair.local_bounds(l0, l1))
            .reduce(|a, b| a.union(&b))
    }

    /// The box in the world holding the in-between's surface over the
    /// shutter times `t0` ≤ t ≤ `t1`: for each pair they reach, its local
    /// box turned as the pose turns it and moved along the origin's line
    /// (the centre box plus the turned box); a pair whose pose turns
    /// (`diffangle` not 0) by the sphere about the origin's line that
    /// holds the local box in every turn. `None` where nothing can be hit.
    pub fn world_bounds(&self, t0: f64, t1: f64) -> Option<BoundingBox> {
        self.pieces(t0, t1)
            .filter_map(|(pair, (l0, l1), (c0, c1))| {
                let local = pair.local_bounds(l0, l1)?;
                let centre = self.centre_bounds(c0, c1);
                let corners = (0..8).map(|c| {
                    DVec3::new(
                        if c & 1 == 0 { local.xmin } else { local.xmax },
                        if c & 2 == 0 { local.ymin } else { local.ymax },
                        if c & 4 == 0 { local.zmin } else { local.zmax },
                    )
                });
                if pair.diffangle == DVec3::ZERO {
                    let turn = DMat3::from_mat4(pair.first_pose.transfm);
                    let t = corners.fold(BoundingBox::EMPTY, |b, p| b.holding(turn * p));
                    Some(BoundingBox {
                        xmin: centre.xmin + t.xmin,
                        xmax: centre.xmax + t.xmax,
                        ymin: centre.ymin + t.ymin,
                        ymax: centre.ymax + t.ymax,
                        zmin: centre.zmin + t.zmin,
                        zmax: centre.zmax + t.zmax,
                    })
                } else {
                    let reach = corners.fold(0.0f64, |m, p| m.max(p.length()));
                    Some(centre.widened(reach))
                }
            })
            .reduce(|a, b| a.union(&b))
    }
}

/// The chain of a key-frame record, of sweeps ([`super::PaperChain`]) or of
/// blobs or patches ([`PointChain`]): what an in-between object's shape
/// is made by at each instant.
#[derive(Clone, Copy, Debug)]
pub enum KeyChain<'a> {
    Sweep(&'a super::PaperChain),
    Points(&'a PointChain),
}

impl KeyChain<'_> {
    /// Scratch for [`KeyChain::inbetween`].
    pub fn scratch(&self) -> Shape {
        match self {
            KeyChain::Sweep(c) => Shape::Sweep(c.scratch()),
            KeyChain::Points(c) => c.scratch(),
        }
    }

    /// The in-between shape at shutter time `time`, into `out` (made by
    /// [`KeyChain::scratch`]).
    pub fn inbetween(&self, time: f64, out: &mut Shape) {
        match (self, out) {
            (KeyChain::Sweep(c), Shape::Sweep(sw)) => c.inbetween(time, sw),
            (KeyChain::Sweep(c), out) => {
                let mut sw = c.scratch();
                c.inbetween(time, &mut sw);
                *out = Shape::Sweep(sw);
            }
            (KeyChain::Points(c), out) => c.inbetween(time, out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shapes::{blob_box, patch_box};
    use crate::types::{DMat4, PatchShape};

    fn object(name: &str, at: DVec3, shape: Shape) -> ObjectRecord {
        ObjectRecord {
            name: name.into(),
            class: match shape {
                Shape::Blob(_) => PrimitiveClass::Blob,
                _ => PrimitiveClass::Patch,
            },
            surface: 0,
            transfm: DMat4::from_translation(at),
            inverse: DMat4::from_translation(-at),
            sphereo: at,
            angle: DVec3::ZERO,
            radius: 3.0,
            shape,
        }
    }

    fn blob(components: &[(f64, f64, f64, f64, f64)], threshold: f64) -> Shape {
        Shape::Blob(BlobShape {
            threshold,
            components: components
                .iter()
                .map(|&(x, y, z, radius, strength)| BlobComponent {
                    centre: DVec3::new(x, y, z),
                    radius,
                    strength,
                })
                .collect(),
        })
    }

    fn patch(bend: f64) -> Shape {
        Shape::Patch(Box::new(PatchShape {
            points: std::array::from_fn(|k| {
                let (r, c) = ((k / 4) as f64, (k % 4) as f64);
                DVec3::new(
                    c - 1.5,
                    r - 1.5,
                    bend * (1.5 - (c - 1.5).abs()) * (1.5 - (r - 1.5).abs()),
                )
            }),
        }))
    }

    /// FIRST's two components meet LAST's four: FIRST gains LAST's third
    /// and fourth at strength 0, and the in-between is FIRST so padded at
    /// t = 0 and LAST at t = 1 (`do34`); the threshold goes linearly.
    #[test]
    fn the_fewer_components_fade_in() {
        let a = object(
            "a",
            DVec3::ZERO,
            blob(&[(0.0, 0.0, 0.0, 1.0, 1.0), (1.0, 0.0, 0.0, 1.0, 1.0)], 0.5),
        );
        let b = object(
            "b",
            DVec3::X,
            blob(
                &[
                    (0.0, 0.5, 0.0, 0.8, 1.0),
                    (1.0, 0.5, 0.0, 0.8, 2.0),
                    (2.0, 0.0, 1.0, 0.7, 1.5),
                    (0.0, 0.0, 2.0, 0.6, -1.0),
                ],
                0.7,
            ),
        );
        let pair = PointPair::new(1, &a, &b, Fidelity::Thesis).unwrap();
        assert_eq!((pair.count, pair.mid), (4, 2));
        assert_eq!(pair.first[2], [2.0, 0.0, 1.0, 0.7, 0.0]);
        assert_eq!(pair.first[3], [0.0, 0.0, 2.0, 0.6, 0.0]);
        let mut out = pair.scratch();
        pair.inbetween(0.0, &mut out);
        let Shape::Blob(at0) = &out else { panic!() };
        assert_eq!(at0.components.len(), 4);
        assert_eq!(at0.components[3].strength, 0.0);
        assert_eq!(at0.threshold, 0.5);
        pair.inbetween(1.0, &mut out);
        assert!(out == b.shape, "LAST at t = 1");
        pair.inbetween(0.5, &mut out);
        let Shape::Blob(half) = &out else { panic!() };
        assert!((half.threshold - 0.6).abs() < 1e-15);
        // The same the other way: LAST the fewer.
        let back = PointPair::new(1, &b, &a, Fidelity::Thesis).unwrap();
        assert_eq!(back.last[2], [2.0, 0.0, 1.0, 0.7, 0.0]);
    }

    /// Key shapes that are one shape give every point a path of tangent 0
    /// (`getpath` from reference lines of length 0): each curve is its
    /// point, a, b, c exactly 0, wherever the two stand.
    #[test]
    fn one_shape_twice_stands_still() {
        for shape in [
            blob(
                &[
                    (0.0, 0.0, 0.0, 1.0, 1.0),
                    (1.0, 2.0, 0.0, 0.5, -1.0),
                    (2.0, 1.0, 1.0, 0.7, 2.0),
                ],
                0.4,
            ),
            patch(1.0),
        ] {
            let a = object("a", DVec3::ZERO, shape.clone());
            let b = object("b", DVec3::new(3.0, -1.0, 2.0), shape);
            let pair = PointPair::new(1, &a, &b, Fidelity::Thesis).unwrap();
            for curve in pair.curves.iter().flatten() {
                assert_eq!((curve.a, curve.b, curve.c), (0.0, 0.0, 0.0));
            }
            let mut out = pair.scratch();
            pair.inbetween(0.3, &mut out);
            assert!(out == a.shape);
        }
    }

    /// The first point's path is its own straight line (the reference of
    /// §3.2.3 (b), D56): Hermite with both tangents B − A is A + (B − A)t;
    /// the others take `getpath`'s tangents and end at their key places.
    #[test]
    fn the_reference_point_goes_straight_and_all_reach_last() {
        let a = object("a", DVec3::ZERO, patch(0.0));
        let b = object("b", DVec3::ZERO, patch(2.0));
        let pair = PointPair::new(1, &a, &b, Fidelity::Thesis).unwrap();
        for k in 0..3 {
            for t in [0.25, 0.5, 0.8] {
                let (p, q) = (pair.first[0][k], pair.last[0][k]);
                assert!((pair.curves[k][0].value(t) - (p + (q - p) * t)).abs() < 1e-14);
            }
            for i in 0..16 {
                assert!((pair.curves[k][i].value(1.0) - pair.last[i][k]).abs() < 1e-14);
                assert_eq!(pair.curves[k][i].value(0.0), pair.first[i][k]);
            }
        }
        // An inner point rises on the path of the reference points' tangents
        // (0 here: the corners stay), not a straight line: (3t² − 2t³)·Δ.
        let z = pair.curves[2][5].value(0.25);
        assert!(
            (z - (3.0 * 0.0625 - 2.0 * 0.015625) * pair.last[5][2]).abs() < 1e-14,
            "{z}"
        );
    }

    /// The bounds over an interval of the shutter hold the in-between at
    /// every time in it (the local box its components' spheres or control
    /// points; in the world, the surface's points carried by the pose), and
    /// the bounds of a part of the shutter lie within the whole's: a chain
    /// of three blobs and one of three patches, turning and not.
    #[test]
    fn the_bounds_hold_the_inbetween_over_each_interval() {
        let blobs = [
            blob(&[(0.0, 0.0, 0.0, 1.0, 1.0), (1.0, 0.0, 0.0, 1.0, 1.0)], 0.5),
            blob(
                &[
                    (0.0, 1.0, 0.0, 0.8, 1.0),
                    (2.0, 0.0, 0.5, 1.2, 1.0),
                    (0.0, 0.0, 2.0, 0.5, 1.0),
                ],
                0.5,
            ),
            blob(&[(-1.0, 0.0, 0.0, 1.0, 2.0)], 0.9),
        ];
        let patches = [patch(0.0), patch(3.0), patch(-1.0)];
        for (shapes, turn) in [(blobs, 0.0), (patches.clone(), 0.0), (patches, 40.0)] {
            let at = [DVec3::ZERO, DVec3::new(2.0, 1.0, -1.0), DVec3::new(-3.0, 0.5, 2.0)];
            let mut objects: Vec<ObjectRecord> =
                shapes.iter().zip(at).map(|(s, p)| object("k", p, s.clone())).collect();
            objects[2].angle = DVec3::new(turn, 0.0, 0.0);
            let chain = PointChain::new(&objects[0], &objects[1..], Fidelity::Thesis).unwrap();
            let whole = chain.world_bounds(0.0, 1.0).unwrap();
            for (t0, t1) in [(0.0, 1.0), (0.0, 0.3), (0.2, 0.7), (0.5, 0.5), (0.9, 1.0)] {
                let local = chain.local_bounds(t0, t1).unwrap();
                let world = chain.world_bounds(t0, t1).unwrap();
                let inside = |b: &BoundingBox, p: DVec3| b.widened(1e-9).holds(p);
                for c in [
                    DVec3::new(world.xmin, world.ymin, world.zmin),
                    DVec3::new(world.xmax, world.ymax, world.zmax),
                ] {
                    assert!(inside(&whole, c), "[{t0}, {t1}] within the whole shutter's");
                }
                let mut out = chain.scratch();
                for j in 0..=20 {
                    let t = t0 + (t1 - t0) * j as f64 / 20.0;
                    chain.inbetween(t, &mut out);
                    let pose = chain.pose(t);
                    let b = match &out {
                        Shape::Blob(b) => blob_box(b).unwrap(),
                        Shape::Patch(p) => patch_box(p),
                        _ => unreachable!(),
                    };
                    for c in 0..8 {
                        let p = DVec3::new(
                            if c & 1 == 0 { b.xmin } else { b.xmax },
                            if c & 2 == 0 { b.ymin } else { b.ymax },
                            if c & 4 == 0 { b.zmin } else { b.zmax },
                        );
                        assert!(inside(&local, p), "local at {t}");
                        // The box's corners are not the surface, but a box
                        // turned with the pose lies within the turned hull.
                        assert!(inside(&world, pose.transfm.transform_point3(p)), "world at {t}");
                    }
                }
            }
        }
    }
}

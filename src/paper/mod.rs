//! Unit `paper` of the thesis (listing in the OCR text, lines 2264–3011):
//! key-frame deformation of sweep objects (§3.1–3.3, Fig. 3.5–3.12).
//!
//! A first and a last shape (two sweep objects of one class, the key
//! frames) are joined by a surface made of bicubic Hermite patches with
//! zero twist (§2.4.2, Fig. 3.5, 3.9): one patch per segment of the
//! contour, s along the segment and t the time. The curve of all patches at
//! a time t is the in-between contour (Fig. 3.10). The steps, each a
//! procedure of the listing:
//!
//! 1. make the segment counts equal (§3.2.3 (a)): Burtnyk & Wein 1971
//!    (`expanding`, `more`) or the thesis's arc-length method
//!    (`expanding2`, `more2`, `plus`);
//! 2. the paths of the segment start points (§3.2.3 (b), Fig. 3.8): two
//!    large patches from the start point of the contour to its middle
//!    point and back, whose t-tangents are the object's motion
//!    (`getmatrix`, `getpath`, `getdistance`);
//! 3. one patch per segment (`getmatrix`), evaluated at t (`Hermite`);
//!    at t = 0 and 1 the key shapes themselves (`do34`);
//! 4. the bounding box (§3.3, Fig. 3.11–3.12): the first and last shapes'
//!    boxes merged (`merge`).
//!
//! The procedures are here in the listing's order, in three files by
//! line range: [`goahead`](self::goahead()) and what it calls first (OCR
//! 2270–2552), the Hermite patches (2554–2877), the arc-length method
//! (2879–3011). All are re-exported from this module. A fourth file,
//! `points`, is the port's: the key-frame chains of blobs and patches
//! (§6.2), whose points take the same procedures ([`PointChain`]).

//!
//! # State
//! The Pascal kept each pair's state in global arrays indexed by the pair
//! number `int` (`p1u[int]`, `Hmx[int,i]`, `diff[int]`, …) and changed the
//! key objects' `segment` in place. The port gathers what `goahead`
//! computes for pair `int` into a [`PaperPair`], built once per pair before
//! the scanline loop and read-only while rendering; [`Hermite`] and
//! [`do34`] write the in-between contour into caller-owned scratch (a
//! [`SweepShape`], see [`PaperPair::scratch`]), so rendering allocates
//! nothing per ray. [`goahead`](self::goahead()) does not change the key
//! objects: the segment count after expanding is [`PaperPair::snu`].
//! Where a listing parameter named the pair by its number (`int` in
//! `Hermite`, `do34`, `expanding`), it is the [`PaperPair`] itself here.
//!
//! Pascal arrays keep their indices: `sdirection = array [1..60] of coeff`
//! is [`Sdirection`] (1-based), `distarray` is [`Distarray`] (0..60), and
//! `Hmx[int,1..60]` is [`HermiteMatrices`] (1-based). A [`SweepShape`]'s
//! own `u`, `v` are 0-based vectors: `obj^.u[i]` is `obj.u[i - 1]`.
//!
//! # Failures (erratum 8)
//! `expanding` prints `***** error *****` and `more2` prints `It is
//! impossible` (and `plus`, `more2` their own error lines) where the methods
//! fail, then go on. Every line the listing prints is kept as a
//! [`PaperMessage`] in [`PaperPair::messages`]. `Fidelity::Listing` goes on
//! as the listing does; `Fidelity::Thesis` returns
//! [`PaperError::Method`] instead (and its `more2` does not fail: see
//! [`more2`]).
//!
//! # Key-frame chains
//! The deck's `keyframe A B C …` is a chain of key shapes. [`PaperChain`]
//! holds one pair per consecutive couple (A→B is pair 1, B→C pair 2, …)
//! and maps shutter time onto them with [`chain_time`]: n pairs share the
//! shutter equally (two pairs: one half each). The printed program knows
//! only pairs (`papermatrix[i2].start`, `.ending`); chains are the port's.

mod arclength;
mod goahead;
mod hermite;
mod points;

pub use arclength::{expanding2, more2, plus};
pub use goahead::{burtnyk, difference, expanding, goahead, merge, more, saving, widen_tbox, Outline};
pub use hermite::{
    coor, coor1, coor2, delete, do34, getdistance, getmatrix, getpath, inbetween, initM, multiply, patch, saving1,
    Hermite, Rvalue, Rvalue1, MH, MH_T,
};
pub use points::{point_shares, KeyChain, PointChain, PointPair};

use std::ops::{Index, IndexMut};

use crate::types::{BoundingBox, Coeff, DVec3, ObjectRecord, Pose, PrimitiveClass, SweepShape, MAXSEGMENTS};

use crate::scene::{Expander, KeyframeRecord, Scene};

use crate::options::Fidelity;

/// `Mh`: a 4×4 matrix, `H[i,j]` is `h[i - 1][j - 1]` (row i, column j).
pub type Mh = [[f64; 4]; 4];

/// A Pascal `array [1..N] of T`: indexed from 1, as the listing indexes it.
/// Index 0 or past N is a bug of the port (the procedures that take a count
/// from their caller clamp it to N first).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OneBased<T, const N: usize>(pub [T; N]);

impl<T: Copy + Default, const N: usize> Default for OneBased<T, N> {
    /// Every entry zero: the state of a Pascal global array nothing has
    /// written yet (Sun Pascal's globals are static, zero-filled storage).
    fn default() -> Self {
        OneBased([T::default(); N])
    }
}

impl<T, const N: usize> Index<usize> for OneBased<T, N> {
    type Output = T;
    fn index(&self, i: usize) -> &T {
        &self.0[i - 1]
    }
}

impl<T, const N: usize> IndexMut<usize> for OneBased<T, N> {
    fn index_mut(&mut self, i: usize) -> &mut T {
        &mut self.0[i - 1]
    }
}

/// `sdirection = array [1..60] of coeff`: one coordinate (U or V) of every
/// segment of a contour, or the paths of the segment start points.
pub type Sdirection = OneBased<Coeff, MAXSEGMENTS>;

/// `Hmx[int, 1..60]`, `Hmy[int, 1..60]`: the Hermite matrix of every
/// segment's patch.
pub type HermiteMatrices = OneBased<Mh, MAXSEGMENTS>;

/// `distarray`: `dist[0..60]`, `dist[i]` the share of the contour's length
/// (measured along the chords between segment start points) from the start
/// of segment 1 to the start of segment i + 1; `dist[0] = 0`, `dist[nu] = 1`.
pub type Distarray = [f64; MAXSEGMENTS + 1];

/// A line the listing prints while it equalises segment counts (erratum 8).
/// `Display` gives the printed text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PaperMessage {
    /// `expanding`: `' equal '`.
    Equal,
    /// `expanding`: `' ***** error *****'` and the two counts: `more` left
    /// the counts different.
    ExpandingError { segment1: usize, segment2: usize },
    /// `more2`: `'It is impossible '`: segment `segment` of the contour
    /// with fewer segments got no start point of the other contour and no
    /// other segment had one to spare.
    Impossible { segment: usize },
    /// `plus`: `' error : plus. nu:'`: a segment asked for a negative
    /// number of added points (it is then dropped).
    PlusError { nu: i64 },
    /// `more2`: `' error : more2. n2 <> (k-1) '`: the counts still differ.
    More2Unequal { n2: usize, k1: usize },
    /// `more2`: `' o.k : equal '`.
    More2Equal,
}

impl std::fmt::Display for PaperMessage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PaperMessage::Equal => write!(f, " equal "),
            PaperMessage::ExpandingError { segment1, segment2 } => {
                write!(f, " ***** error ***** {segment1} {segment2}")
            }
            PaperMessage::Impossible { segment } => write!(f, "It is impossible (segment {segment})"),
            PaperMessage::PlusError { nu } => write!(f, " error : plus. nu:{nu}"),
            PaperMessage::More2Unequal { n2, k1 } => write!(f, " error : more2. n2 <> (k-1) {n2} {k1}"),
            PaperMessage::More2Equal => write!(f, " o.k : equal "),
        }
    }
}

/// Why a key-frame pair cannot be set up.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PaperError {
    #[error("key-frame pair {int}: {which} is not a sweep object")]
    NotSweep { int: usize, which: &'static str },
    #[error("key-frame pair {int}: {which} is not a blob or a patch")]
    NotPoints { int: usize, which: &'static str },
    #[error("key-frame pair {int}: FIRST is a {first:?} sweep and LAST a {last:?} sweep; a pair must be of one class")]
    ClassMismatch {
        int: usize,
        first: PrimitiveClass,
        last: PrimitiveClass,
    },
    #[error("key-frame pair {int}: {which} has {segment} segments; a key shape needs at least 2")]
    TooFewSegments {
        int: usize,
        which: &'static str,
        segment: usize,
    },
    #[error(
        "key-frame pair {int}: {count} segments after expanding, more than the 60 of `sdirection = array [1..60] of coeff`"
    )]
    TooManySegments { int: usize, count: usize },
    #[error(
        "key-frame pair {int}: {which} has {segment} segments but {coefficients} u/v coefficients: fill them with `spline` first"
    )]
    NotPrepared {
        int: usize,
        which: &'static str,
        segment: usize,
        coefficients: usize,
    },
    #[error("key-frame pair {int}: {which} has a coefficient or a position that is not a finite number")]
    NotFinite { int: usize, which: &'static str },
    #[error(
        "key-frame pair {int}: the segment start points of {which} all coincide: its contour has no length (getdistance would divide by 0)"
    )]
    Degenerate { int: usize, which: &'static str },
    /// The method failed where the listing prints a message and goes on
    /// (erratum 8); `Fidelity::Thesis` stops here.
    #[error("key-frame pair {int}: {message}")]
    Method { int: usize, message: PaperMessage },
    #[error("key-frame record: object index {index} is not in the scene")]
    NoSuchObject { index: usize },
    #[error("a key-frame chain needs at least one shape after FIRST")]
    EmptyChain,
}

/// What `goahead` computes for key-frame pair `int`: the Pascal's global
/// arrays at index `int`, and the pose and box of the in-between object.
///
/// The in-between object is FIRST's record (its surface, class, `orientt`,
/// `length`, `scale`) with the contour of [`Hermite`] / [`do34`] and the
/// pose of [`PaperPair::pose`].
#[derive(Clone, Debug, PartialEq)]
pub struct PaperPair {
    /// `int`: the pair's number, from 1 (`i2` of the main program's
    /// `for i2 := 1 to papernumber do goahead(i2, …)`).
    pub int: usize,
    pub fidelity: Fidelity,
    pub expander: Expander,
    /// Every line the listing prints while it equalises the counts.
    pub messages: Vec<PaperMessage>,
    pub class: PrimitiveClass,
    /// `snu`: the in-between's segment count (`obj1^.segment` after
    /// expanding).
    pub snu: usize,
    /// `mid := snu div 2`: the segment whose start point is the contour's
    /// "middle point" (§3.2.3 (b)).
    pub mid: usize,
    /// `p1u[int]`, `p1v[int]`: FIRST's segments after expanding, with the
    /// bounds merged with LAST's (`merge`).
    pub p1u: Sdirection,
    pub p1v: Sdirection,
    /// `p2u[int]`, `p2v[int]`: LAST's, likewise.
    pub p2u: Sdirection,
    pub p2v: Sdirection,
    /// `p3u[int]`, `p3v[int]`: copies of `p1u`, `p1v` (`saving1`), which
    /// `do34` hands out at t = 0.
    pub p3u: Sdirection,
    pub p3v: Sdirection,
    /// `p4u[int]`, `p4v[int]`: copies of `p2u`, `p2v`, for t = 1.
    pub p4u: Sdirection,
    pub p4v: Sdirection,
    /// `dist1`, `dist2`: `getdistance` of the expanded FIRST and LAST.
    pub dist1: Distarray,
    pub dist2: Distarray,
    /// `pathx`, `pathy`: the path over time of the start point of every
    /// segment, U and V (x(t) = a t³ + b t² + c t + d).
    pub pathx: Sdirection,
    pub pathy: Sdirection,
    /// `Hmx[int,i]`, `Hmy[int,i]`: the patch of segment i for U and V.
    pub hmx: HermiteMatrices,
    pub hmy: HermiteMatrices,
    /// `diff[int]`: LAST's `sphereo` minus FIRST's (erratum 4).
    pub diff: DVec3,
    /// `diffangle[int]`: LAST's `angle` minus FIRST's (erratum 4).
    pub diffangle: DVec3,
    /// FIRST's pose at rest (the main program's `temp1`, `temp2`).
    pub first_pose: Pose,
    /// FIRST's `angle`.
    pub first_angle: DVec3,
    /// FIRST's sweep record before expanding: what the in-between keeps of
    /// it (`orientt`, `curve`, `length`, `scale`, `points`).
    pub first_shape: SweepShape,
    /// The local box of the in-between object over the shutter (§3.3,
    /// erratum 9): in `Fidelity::Listing` the box of its class as the
    /// listing shares it (FIRST's box: `tbox` widened by 2 per pair, or
    /// `cbox`, `rbox`); in `Fidelity::Thesis` a box that holds the contour
    /// at every t in [0, 1].
    pub bbox: BoundingBox,
}

impl PaperPair {
    /// A pair with nothing computed yet: every array zero (the Pascal's
    /// globals before `goahead`).
    pub(crate) fn empty(
        int: usize,
        first: &ObjectRecord,
        first_shape: &SweepShape,
        expander: Expander,
        fidelity: Fidelity,
    ) -> PaperPair {
        PaperPair {
            int,
            fidelity,
            expander,
            messages: Vec::new(),
            class: first.class,
            snu: 0,
            mid: 0,
            p1u: Sdirection::default(),
            p1v: Sdirection::default(),
            p2u: Sdirection::default(),
            p2v: Sdirection::default(),
            p3u: Sdirection::default(),
            p3v: Sdirection::default(),
            p4u: Sdirection::default(),
            p4v: Sdirection::default(),
            dist1: [0.0; MAXSEGMENTS + 1],
            dist2: [0.0; MAXSEGMENTS + 1],
            pathx: Sdirection::default(),
            pathy: Sdirection::default(),
            hmx: HermiteMatrices::default(),
            hmy: HermiteMatrices::default(),
            diff: DVec3::ZERO,
            diffangle: DVec3::ZERO,
            first_pose: first.pose(),
            first_angle: first.angle,
            first_shape: first_shape.clone(),
            bbox: BoundingBox::default(),
        }
    }

    /// Scratch for [`Hermite`] and [`do34`]: FIRST's sweep record with room
    /// for 60 segments, so that no later call allocates. One per thread.
    pub fn scratch(&self) -> SweepShape {
        let mut s = self.first_shape.clone();
        s.u = Vec::with_capacity(MAXSEGMENTS);
        s.v = Vec::with_capacity(MAXSEGMENTS);
        s.segment = 0;
        s
    }

    /// Did the listing report a failure while it equalised the counts
    /// (only possible in `Fidelity::Listing`, which goes on)?
    pub fn failed(&self) -> bool {
        self.messages
            .iter()
            .any(|m| !matches!(m, PaperMessage::Equal | PaperMessage::More2Equal))
    }

    /// The lines the listing writes while `goahead` sets this pair up, in
    /// its order: `expanding` or `expanding2` (to `debugf`, OCR lines 2283,
    /// 2990) when the counts differed, the expanders' messages (erratum 8;
    /// the listing wrote them to standard output), and `path : a b c d`
    /// of every segment start's path in U (`debugf`, OCR lines 2520–2522,
    /// `a:3:3`: three decimals). For the `--debug` log.
    pub fn debug_lines(&self) -> Vec<String> {
        let mut lines = Vec::new();
        // Each expander ends with a message (`equal`, `o.k : equal` or the
        // error), so there are messages exactly when one ran.
        if !self.messages.is_empty() {
            lines.push(
                match self.expander {
                    Expander::Burtnyk => "expanding",
                    Expander::Arclength => "expanding2",
                }
                .to_string(),
            );
        }
        lines.extend(self.messages.iter().map(|m| m.to_string()));
        for i in 1..=self.snu {
            let p = &self.pathx[i];
            lines.push(format!("path : {:.3} {:.3} {:.3} {:.3}", p.a, p.b, p.c, p.d));
        }
        lines
    }

    /// The pose of the in-between object at `time`: the `paper = 1` branch
    /// of `motionblur` (unit `drt`, OCR lines 2139–2159):
    /// `sphereo := temp1.sphereo + time*diff[int]` (FIRST's position plus
    /// `time` times `diff`, erratum 4 in `diff`), then the turn.
    ///
    /// Erratum 19: the listing restores `transfm` from `temp1` (FIRST's
    /// rest pose, its x angle included) and calls
    /// `rotate(name,xaxis,0,0,0,angle.x)` with FIRST's own x angle; the y
    /// and z turns by `diffangle` are commented out, so `diffangle` is
    /// computed and never read. The port reads that call as re-imposing the
    /// angle the restored pose already holds (DEVIATIONS, erratum 19, gives
    /// the listing's evidence): `Fidelity::Listing` keeps FIRST's rest
    /// rotation at every time. `Fidelity::Thesis` follows §3.2.2,
    /// angle(t) = θ₁ + (θ₂ − θ₁)·t: the turn t·`diffangle` about x, then
    /// y, then z through the object's origin, composed on FIRST's rest
    /// pose (D8's convention), so that at t = 1 the object stands where
    /// LAST stands whenever LAST's extra turn is about one axis (or the
    /// deck turned it about x, then y, then z).
    pub fn pose(&self, time: f64) -> Pose {
        keyed_pose(&self.first_pose, self.diff, self.diffangle, self.fidelity, time)
    }

    /// The in-between object's origin at local time `time`, as
    /// [`PaperPair::pose`] puts it: FIRST's place plus `time`·`diff`.
    #[inline]
    pub fn centre(&self, time: f64) -> DVec3 {
        keyed_centre(&self.first_pose, self.diff, time)
    }
}

/// Where [`keyed_pose`] puts the in-between object's origin at `time`:
/// FIRST's place plus `time`·`diff`, the same to the bit; what the
/// bounding sphere's test needs without the rest of the pose.
#[inline]
pub fn keyed_centre(first_pose: &Pose, diff: DVec3, time: f64) -> DVec3 {
    first_pose.sphereo + diff * time
}

/// The pose at `time` of an in-between object whose first key shape stands
/// at `first_pose`, with `goahead`'s `diff` and `diffangle`: the
/// `paper = 1` branch of `motionblur` ([`PaperPair::pose`], erratum 19),
/// for the sweeps' pairs and for the blobs' and patches' ([`PointPair`]).
pub fn keyed_pose(first_pose: &Pose, diff: DVec3, diffangle: DVec3, fidelity: Fidelity, time: f64) -> Pose {
    let sphereo = keyed_centre(first_pose, diff, time);
    let turn = match fidelity {
        // Listing: rotate(name,xaxis,0,0,0,angle.x) on the restored
        // temp1, which holds angle.x already: no further turn. The y
        // and z lines `angle.y+diffangle[int].y*time` are commented out.
        Fidelity::Listing => crate::types::DMat3::IDENTITY,
        // Thesis: the turn θ(t) − θ₁ = t·(θ₂ − θ₁) about x, y, z.
        Fidelity::Thesis => crate::drt::turn_xyz(diffangle * time),
    };
    first_pose.turned(turn, sphereo)
}

/// Which pair of a chain of `pairs` pairs shutter time `time` falls in, and
/// the time within that pair: the pairs share the shutter equally (pair k,
/// from 0, covers [k/n, (k+1)/n); two pairs take one half each), and the
/// local time runs 0 → 1 over a pair's share. `time` = 1 is the last pair
/// at local time 1. Times outside [0, 1] (the listing's times reach 1.5,
/// erratum 2) go to the first or last pair and extrapolate it, so that a
/// chain of one pair is the identity, as the listing's single pair.
///
/// Reconstructed: the thesis motivates chains (§1.2) but its program has
/// pairs only.
pub fn chain_time(pairs: usize, time: f64) -> (usize, f64) {
    if pairs <= 1 {
        return (0, time);
    }
    let n = pairs as f64;
    let scaled = time * n;
    // `as usize` saturates: negative times and NaN go to pair 0.
    let k = (scaled.floor().max(0.0) as usize).min(pairs - 1);
    (k, scaled - k as f64)
}

/// The pair of a chain's `pairs` (never empty) at shutter time `time`,
/// and the time within it ([`chain_time`]): for the chains of sweeps and
/// of blobs or patches alike.
pub fn pair_at<P>(pairs: &[P], time: f64) -> (&P, f64) {
    let (k, local) = chain_time(pairs.len(), time);
    (&pairs[k.min(pairs.len() - 1)], local)
}

/// A pair of key shapes as a chain walks it: where the in-between object
/// stands at the pair's own time (0 to 1 over the pair). The sweeps'
/// [`PaperPair`] and the blobs' and patches' [`PointPair`] alike.
pub trait KeyPair {
    /// The pose at the pair's own time `local`.
    fn pose(&self, local: f64) -> Pose;
    /// The origin of [`KeyPair::pose`] at `local`, the same to the bit.
    fn centre(&self, local: f64) -> DVec3;
}

impl KeyPair for PaperPair {
    fn pose(&self, local: f64) -> Pose {
        PaperPair::pose(self, local)
    }
    #[inline]
    fn centre(&self, local: f64) -> DVec3 {
        PaperPair::centre(self, local)
    }
}

/// The pairs of a key-frame chain `keyframe A B C …` (§1.2): pair k,
/// numbered from 1, goes from the k-th shape to the next. The in-between
/// object is A's record; each pair's pose goes from its first shape's pose
/// to its last's. Of sweeps, [`PaperChain`]; of blobs or patches,
/// [`PointChain`].
#[derive(Clone, Debug, PartialEq)]
pub struct Chain<P> {
    /// At least one pair (the constructors refuse an empty chain).
    pairs: Vec<P>,
}

/// The chain of a `keyframe` record of sweeps: `goahead`'s pairs.
pub type PaperChain = Chain<PaperPair>;

impl<P: KeyPair> Chain<P> {
    /// The pairs, pair k (from 1) at index k − 1.
    pub fn pairs(&self) -> &[P] {
        &self.pairs
    }

    /// The pair and local time of shutter time `time` ([`pair_at`]).
    pub fn locate(&self, time: f64) -> (&P, f64) {
        pair_at(&self.pairs, time)
    }

    /// The in-between object's pose at shutter time `time`.
    pub fn pose(&self, time: f64) -> Pose {
        let (pair, local) = self.locate(time);
        pair.pose(local)
    }

    /// The in-between object's origin at shutter time `time`, as
    /// [`Chain::pose`] puts it.
    pub fn centre(&self, time: f64) -> DVec3 {
        let (pair, local) = self.locate(time);
        pair.centre(local)
    }

    /// The box the in-between object's origin (`sphereo`) stays in over
    /// the shutter times `t0` ≤ t ≤ `t1`: the port's, for bounds over the
    /// shutter. Within a pair the origin moves along a straight line
    /// ([`keyed_pose`]: FIRST's place plus t·`diff`), so the box of
    /// its places at `t0`, `t1` and at both sides of each pair boundary
    /// between holds every place (times past the ends extrapolate the
    /// first or last pair, as [`chain_time`] does).
    pub fn centre_bounds(&self, t0: f64, t1: f64) -> BoundingBox {
        chain_centre_bounds(self.pairs.len(), |k, local| self.pairs[k].pose(local), t0, t1)
    }
}

impl Chain<PaperPair> {
    /// `goahead` for every consecutive couple of `first, rest[0], rest[1], …`.
    pub fn new(
        first: &ObjectRecord,
        rest: &[ObjectRecord],
        expander: Expander,
        fidelity: Fidelity,
    ) -> Result<PaperChain, PaperError> {
        let pairs = chain_pairs(first, rest, |int, from, to| goahead(int, from, to, expander, fidelity))?;
        Ok(Chain { pairs })
    }

    /// The chain of a deck's `keyframe` record: FIRST from `scene.objects`,
    /// the later shapes from the record.
    pub fn from_keyframe(scene: &Scene, record: &KeyframeRecord, fidelity: Fidelity) -> Result<PaperChain, PaperError> {
        PaperChain::new(keyframe_first(scene, record)?, &record.rest, record.expander, fidelity)
    }

    /// The in-between contour at shutter time `time`, into `obj`
    /// ([`inbetween`]), every segment on [0, 1] as the port's sweep
    /// intersection takes it: the listing's `do34` leaves pieces of cut
    /// segments on their `first` … `last`, and [`reparam`] writes each as
    /// the same curve on [0, 1] (DEVIATIONS D15; exact for a segment on
    /// [0, 1] already).
    pub fn inbetween(&self, time: f64, obj: &mut SweepShape) {
        let (pair, local) = self.locate(time);
        inbetween(pair, local, obj);
        for c in obj.u.iter_mut().chain(obj.v.iter_mut()) {
            *c = reparam(c);
        }
    }

    /// Scratch big enough for every pair ([`PaperPair::scratch`]).
    pub fn scratch(&self) -> SweepShape {
        self.pairs[0].scratch()
    }

    /// The union of the pairs' boxes (each in its own pair's local frame;
    /// the frames agree when the key shapes share `orientt`).
    pub fn bbox(&self) -> BoundingBox {
        self.pairs
            .iter()
            .skip(1)
            .fold(self.pairs[0].bbox, |b, p| b.union(&p.bbox))
    }
}

/// `goahead` (`make`) for pair k (from 1) of every consecutive couple of
/// `first, rest[0], rest[1], …`: a chain's pairs, at least one.
pub(crate) fn chain_pairs<P>(
    first: &ObjectRecord,
    rest: &[ObjectRecord],
    make: impl Fn(usize, &ObjectRecord, &ObjectRecord) -> Result<P, PaperError>,
) -> Result<Vec<P>, PaperError> {
    if rest.is_empty() {
        return Err(PaperError::EmptyChain);
    }
    let mut pairs = Vec::with_capacity(rest.len());
    let mut from = first;
    for (k, to) in rest.iter().enumerate() {
        pairs.push(make(k + 1, from, to)?);
        from = to;
    }
    Ok(pairs)
}

/// FIRST of a deck's `keyframe` record, from `scene.objects`.
pub(crate) fn keyframe_first<'a>(scene: &'a Scene, record: &KeyframeRecord) -> Result<&'a ObjectRecord, PaperError> {
    scene
        .objects
        .get(record.first)
        .ok_or(PaperError::NoSuchObject { index: record.first })
}

/// The box the in-between object's origin stays in over the shutter times
/// `t0` ≤ t ≤ `t1` of a chain of `pairs` pairs whose pair k (from 0) puts
/// it at `pose(k, local)` ([`PaperChain::centre_bounds`], for the sweeps'
/// chains and the blobs' and patches'): its places at `t0`, `t1` and at
/// both sides of each pair boundary between, the origin moving along a
/// straight line within a pair.
pub(crate) fn chain_centre_bounds(pairs: usize, pose: impl Fn(usize, f64) -> Pose, t0: f64, t1: f64) -> BoundingBox {
    let (a, b) = (t0.min(t1), t0.max(t1));
    let at = |time: f64| {
        let (k, local) = chain_time(pairs, time);
        pose(k.min(pairs - 1), local).sphereo
    };
    let mut bounds = BoundingBox::EMPTY.holding(at(a)).holding(at(b));
    for k in 1..pairs {
        let boundary = k as f64 / pairs as f64;
        if boundary > a && boundary < b {
            bounds = bounds.holding(pose(k - 1, 1.0).sphereo).holding(pose(k, 0.0).sphereo);
        }
    }
    bounds
}

/// The local box of a sweep whose contour has U in `u` = (min, max) and V
/// in `v`: translation and conic sweeps put U on x and V on y and run from
/// z = 0 to `length` (a conic contour scaled by `scale` at the far end); a
/// rotation sweep revolves the radius U about z (x and y within ±max |U|)
/// with V the height z. The same box the sweep module gives a key shape
/// of its own (erratum 9, thesis), from the contour's range.
pub(crate) fn contour_box(class: PrimitiveClass, sweep: &SweepShape, u: (f64, f64), v: (f64, f64)) -> BoundingBox {
    match class {
        PrimitiveClass::Rotation => {
            let r = u.0.abs().max(u.1.abs());
            BoundingBox {
                xmin: -r,
                xmax: r,
                ymin: -r,
                ymax: r,
                zmin: v.0,
                zmax: v.1,
            }
        }
        _ => {
            let mut b = BoundingBox {
                xmin: u.0,
                xmax: u.1,
                ymin: v.0,
                ymax: v.1,
                zmin: 0.0f64.min(sweep.length),
                zmax: 0.0f64.max(sweep.length),
            };
            if class == PrimitiveClass::Conic && sweep.scale.is_finite() {
                let s = sweep.scale;
                b.xmin = b.xmin.min(u.0 * s).min(u.1 * s);
                b.xmax = b.xmax.max(u.0 * s).max(u.1 * s);
                b.ymin = b.ymin.min(v.0 * s).min(v.1 * s);
                b.ymax = b.ymax.max(v.0 * s).max(v.1 * s);
            }
            b
        }
    }
}

/// The segment x(first + s·(last − first)), s in [0, 1], as a cubic in s
/// on [0, 1] (`first` 0, `last` 1; `min`, `max` kept): the same curve.
pub fn reparam(p: &Coeff) -> Coeff {
    let (f, w) = (p.first, p.last - p.first);
    Coeff {
        a: p.a * w * w * w,
        b: (3.0 * p.a * f + p.b) * w * w,
        c: ((3.0 * p.a * f + 2.0 * p.b) * f + p.c) * w,
        d: ((p.a * f + p.b) * f + p.c) * f + p.d,
        first: 0.0,
        last: 1.0,
        ..*p
    }
}

/// The least and greatest value of the cubic x(s) = a s³ + b s² + c s + d
/// for s in [0, 1]: the ends and the zeros of x′ inside (the "extrema test"
/// of §3.3), widened by a rounding margin.
pub fn cubic_range(p: &Coeff) -> (f64, f64) {
    let x = |s: f64| ((p.a * s + p.b) * s + p.c) * s + p.d;
    let (mut lo, mut hi) = {
        let (x0, x1) = (x(0.0), x(1.0));
        (x0.min(x1), x0.max(x1))
    };
    let pad = 1e-12 * (p.a.abs() + p.b.abs() + p.c.abs() + p.d.abs());
    // The inner Bernstein control values b1 = d + c/3, b2 = d + 2c/3 + b/3:
    // the cubic lies in the hull of b0 = x(0), b1, b2, b3 = x(1), so when
    // both inner ones lie between the ends the ends are the range, and the
    // extrema need no solving (the same answer, for most segments cheaper).
    let b1 = p.d + p.c / 3.0;
    let b2 = p.d + (2.0 * p.c + p.b) / 3.0;
    if b1 >= lo && b1 <= hi && b2 >= lo && b2 <= hi {
        return (lo - pad, hi + pad);
    }
    let mut visit = |s: f64| {
        if s > 0.0 && s < 1.0 {
            let y = x(s);
            lo = lo.min(y);
            hi = hi.max(y);
        }
    };
    // x′(s) = 3a s² + 2b s + c.
    let (qa, qb, qc) = (3.0 * p.a, 2.0 * p.b, p.c);
    let scale = qa.abs().max(qb.abs()).max(qc.abs());
    if qa.abs() <= 1e-14 * scale {
        if qb != 0.0 {
            visit(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let r = disc.sqrt();
            // The root of larger magnitude first, then the other from the
            // product of the roots (no cancellation).
            let q = -0.5 * (qb + qb.signum() * r);
            if q != 0.0 {
                visit(q / qa);
                visit(qc / q);
            } else {
                visit(0.0);
            }
        }
    }
    (lo - pad, hi + pad)
}

/// The Bernstein (Bezier) control values of the patch x(s, t) = S·H·Tᵀ on
/// [0, 1]²: their least and greatest hold the patch (convex hull), so the
/// segment of [`Hermite`] at every t in [0, 1] lies within them.
pub fn patch_range(h: &Mh) -> (f64, f64) {
    // Power coefficients (s³, s², s, 1) → Bezier control values:
    // P0 = d, P1 = d + c/3, P2 = d + 2c/3 + b/3, P3 = a + b + c + d.
    const K: Mh = [
        [0.0, 0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0 / 3.0, 1.0],
        [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0],
        [1.0, 1.0, 1.0, 1.0],
    ];
    let mut kt = [[0.0; 4]; 4];
    for (i, row) in kt.iter_mut().enumerate() {
        for (j, x) in row.iter_mut().enumerate() {
            *x = K[j][i];
        }
    }
    let net = multiply(&multiply(&K, h), &kt);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut size = 0.0f64;
    for x in net.iter().flatten() {
        lo = lo.min(*x);
        hi = hi.max(*x);
        size = size.max(x.abs());
    }
    let pad = 1e-12 * size;
    (lo - pad, hi + pad)
}

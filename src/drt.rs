//! Unit `drt` of the thesis (listing in the OCR text, lines 2021–2262):
//! distributed ray tracing for motion blur (§2.6, §3.4, after Cook 1984
//! and 1986), in the listing's order: `motionblur` (with its nested
//! `boundvolume`), `depthoffield`, `jittering`, `Isblur`. Beside them the
//! lookup tables `initialize` builds (Ch. 4 (a)(3): "建立lookup table以做為
//! 產生blur時所需之統計數據"), the pattern tables of Fig. 2.33, and `LAW`
//! of Fig. 3.2 (§3.2.2).
//!
//! # Subpixel times and the temporal filter
//! Every subpixel of a pixel gets a time from the M×M pattern table (M =
//! `masksize`, §2.6.3–2.6.4):
//! - `listing` fidelity: `time := pattern[row,col]*0.1` (errata 1, 2): times
//!   0, 0.1, …, so a 4×4 table reaches 1.5 and a 2×2 table 0.3; no jitter.
//!   Over the pixel the shutter is sampled at M² fixed instants: the
//!   temporal filter is a comb of M² equal spikes.
//! - `thesis` fidelity: `time := (pattern[row,col] + x̄) / M²`, where x̄ is
//!   the mean of the `blur` N uniforms of the CLT table (§2.6.5: the sum of
//!   N uniforms, mean N/2, variance N/12, so x̄ has mean ½ and variance
//!   1/(12N)); `blur 0` takes x̄ = ½, the centre of each stratum. So the
//!   table picks one of M² strata of the shutter and x̄ a place in it: with
//!   N = 1 the times are stratified uniform and the filter is a box over
//!   [0, 1); with larger N each stratum's samples gather at its centre
//!   (the box convolved with the Irwin–Hall density of x̄), tending to the
//!   comb of `blur 0` — §3.4 (c): "n decides the normal distribution".

use crate::types::{Axis, BoundingBox, DMat3, DVec3, ObjectRecord, Pose, Ray};

use crate::options::Fidelity;

use crate::scene::{Law, MotionRecord, PatternRecord};

/// `maxindex`: the length of the lookup tables the cursors `aindex`,
/// `dindex` and `mindex` run through (wrapping to 1 past it). Not printed;
/// the port's choice.
pub const MAXINDEX: usize = 1000;

/// Park & Miller's "minimal standard" generator (CACM 31(10), 1988),
/// x ← 16807·x mod (2³¹ − 1): contemporary with the thesis, whose own
/// generator is not printed. Returns uniforms in (0, 1).
#[derive(Clone, Debug)]
pub struct MinimalStandard(u64);

impl MinimalStandard {
    const MODULUS: u64 = 2_147_483_647;

    /// A generator from a seed in 1..2³¹−1 (0 is taken as 1).
    pub fn new(seed: u64) -> Self {
        let s = seed % Self::MODULUS;
        MinimalStandard(if s == 0 { 1 } else { s })
    }

    /// The next uniform in (0, 1).
    pub fn next_uniform(&mut self) -> f64 {
        self.0 = (self.0 * 16807) % Self::MODULUS;
        self.0 as f64 / Self::MODULUS as f64
    }
}

/// `noise2[1..maxindex]`: the pixel-jitter table of `initialize`
/// (Reconstructed: not printed). Uniform on (−½, ½), so that
/// `noise2[aindex]*aliasing` moves a subpixel sample by at most
/// `aliasing`/2 of a subpixel either way. Index 0 here is the Pascal's 1.
pub fn noise2_table() -> Vec<f64> {
    let mut rng = MinimalStandard::new(2);
    (0..MAXINDEX).map(|_| rng.next_uniform() - 0.5).collect()
}

/// `noise[1..maxindex]`: the table `depthoffield` reads (Reconstructed:
/// not printed). Uniform on (−½, ½), so `fradius*noise[dindex]*2` moves the
/// eye by at most `fradius`.
pub fn noise_table() -> Vec<f64> {
    let mut rng = MinimalStandard::new(3);
    (0..MAXINDEX).map(|_| rng.next_uniform() - 0.5).collect()
}

/// The CLT table of §2.6.5 for `blur n`: entry k is the sum of n uniforms
/// on (0, 1), before centring (mean n/2, variance n/12). Reconstructed:
/// the thesis gives the theorem, not the table. Empty for n = 0.
pub fn clt_table(n: u32) -> Vec<f64> {
    if n == 0 {
        return Vec::new();
    }
    let mut rng = MinimalStandard::new(5);
    (0..MAXINDEX)
        .map(|_| (0..n).map(|_| rng.next_uniform()).sum())
        .collect()
}

/// Fig. 2.33, the 4×4 sampling pattern as printed (erratum 1: 10 appears
/// twice, 9 never).
pub const FIG_2_33: [[u32; 4]; 4] = [[7, 11, 3, 14], [4, 15, 13, 0], [10, 1, 8, 12], [6, 10, 5, 2]];

/// Fig. 2.33 for a fidelity. Erratum 1: `listing` keeps the printed table;
/// `thesis` makes it the permutation of 0..15 it was meant to be by
/// writing 9 for the 10 in row 3, column 1. Of the two 10s that one is
/// chosen because it has fewer neighbours (diagonals included) with a
/// consecutive time: beside (3,1) only 10 at (4,2); beside (4,2) both 8
/// and 10 (a 9 at (4,2) would stand next to 8 and 10).
pub fn fig_2_33(fidelity: Fidelity) -> [[u32; 4]; 4] {
    let mut t = FIG_2_33;
    match fidelity {
        // Listing: the table as printed.
        Fidelity::Listing => {}
        // Thesis: 9 for the 10 of row 3, column 1.
        Fidelity::Thesis => t[2][0] = 9,
    }
    t
}

/// The port's table for `masksize` 2 in `thesis` fidelity (DEVIATIONS D9):
/// a permutation of 0..3, as the thesis's time (pattern + x̄)/M² needs one,
/// with consecutive times on the diagonals apart, as Fig. 2.33 keeps
/// consecutive times apart.
pub const PATTERN_2: [[u32; 2]; 2] = [[0, 2], [3, 1]];

/// The pattern table for a subpixel mask of `m`×`m` when the deck has no
/// `pattern` record (DEVIATIONS D9).
///
/// `listing`: the one table the thesis prints is Fig. 2.33, and
/// `motionblur` reads it at `row := (scancol mod masksize)+1`, `col :=
/// (scanline mod masksize)+1` (OCR lines 2122–2124), so a mask of m ≤ 4
/// reads its top-left m×m corner as printed: with 2×2 subpixels (the
/// experiments of Ch. 5) 7, 11 over 4, 15, times 0.7, 1.1, 0.4, 1.5.
/// `thesis`: 1×1 is `[0]`, 2×2 is [`PATTERN_2`] (a corner of Fig. 2.33 is
/// no permutation of 0..3), 4×4 is Fig. 2.33 with erratum 1 fixed. Other
/// sizes, in both, a fixed shuffle of 0..m²−1 (the port's: the listing's
/// table has 16 entries).
pub fn default_pattern(m: usize, fidelity: Fidelity) -> Vec<Vec<u32>> {
    match (fidelity, m) {
        // Listing: the corner of the printed table the mask's indices reach.
        (Fidelity::Listing, 1..=4) => FIG_2_33[..m].iter().map(|r| r[..m].to_vec()).collect(),
        // Thesis: tables whose values are the strata 0..m²−1.
        (Fidelity::Thesis, 1) => vec![vec![0]],
        (Fidelity::Thesis, 2) => PATTERN_2.iter().map(|r| r.to_vec()).collect(),
        (Fidelity::Thesis, 4) => fig_2_33(fidelity).iter().map(|r| r.to_vec()).collect(),
        _ => {
            let mut v: Vec<u32> = (0..(m * m) as u32).collect();
            let mut rng = MinimalStandard::new(7);
            for i in (1..v.len()).rev() {
                let j = (rng.next_uniform() * (i + 1) as f64) as usize;
                v.swap(i, j.min(i));
            }
            v.chunks(m.max(1)).map(|r| r.to_vec()).collect()
        }
    }
}

/// The subpixel times of a render: the pattern table, the CLT table of
/// `blur`, and the fidelity that reads them.
#[derive(Clone, Debug)]
pub struct TimeTable {
    /// `masksize`.
    m: usize,
    /// `pattern[row][col]`, 0-based here, at `row`·m + `col`, as a number
    /// (each read as one for every subpixel).
    pattern: Vec<f64>,
    /// `blur` N (0: no jitter), and as a number.
    n: u32,
    n_real: f64,
    /// M², as a number.
    cells: f64,
    clt: Vec<f64>,
    fidelity: Fidelity,
}

impl TimeTable {
    /// The table for `masksize`, the deck's `pattern` and `blur` N.
    ///
    /// `motionblur` reads `pattern[row,col]` with row and col in
    /// 1..masksize. A deck table smaller than the mask is refused in both
    /// fidelities (the listing would read entries its table does not
    /// have). A larger one: `listing` reads its top-left masksize×masksize
    /// corner, as the listing's indices do; `thesis` refuses it, since the
    /// corner is no permutation of the mask's strata 0..M²−1.
    pub fn new(
        masksize: usize,
        pattern: Option<&PatternRecord>,
        blur: u32,
        fidelity: Fidelity,
    ) -> Result<TimeTable, String> {
        let Some(p) = pattern else {
            return Ok(Self::with_default_pattern(masksize, blur, fidelity));
        };
        let fits = match fidelity {
            // Listing: any table the mask's indices stay inside.
            Fidelity::Listing => p.m >= masksize,
            // Thesis: one stratum a subpixel.
            Fidelity::Thesis => p.m == masksize,
        };
        if !fits {
            return Err(format!(
                "the pattern table is {}×{} but the image's mask is {}×{}: the listing indexes it by scanline and scancol mod masksize{}",
                p.m,
                p.m,
                masksize,
                masksize,
                if p.m > masksize { " (the listing fidelity reads its top-left corner)" } else { "" }
            ));
        }
        let m = masksize.max(1);
        let corner = p
            .values
            .iter()
            .take(m)
            .map(|r| r.iter().take(m).copied().collect())
            .collect();
        Ok(Self::of(m, corner, blur, fidelity))
    }

    /// The table for `masksize` with [`default_pattern`].
    pub fn with_default_pattern(masksize: usize, blur: u32, fidelity: Fidelity) -> TimeTable {
        let m = masksize.max(1);
        Self::of(m, default_pattern(m, fidelity), blur, fidelity)
    }

    /// The table of an `m`×`m` `pattern` (its rows) and `blur` N.
    fn of(m: usize, pattern: Vec<Vec<u32>>, blur: u32, fidelity: Fidelity) -> TimeTable {
        TimeTable {
            m,
            pattern: pattern.iter().flatten().map(|&v| f64::from(v)).collect(),
            n: blur,
            n_real: f64::from(blur),
            cells: (m * m) as f64,
            clt: clt_table(blur),
            fidelity,
        }
    }

    /// The least and the greatest time [`TimeTable::time`] gives: in
    /// `listing` fidelity a tenth of the table's least and greatest entry
    /// (erratum 2: 1.5 for Fig. 2.33, more for a larger mask's table); in
    /// `thesis` fidelity the shutter, 0 to 1.
    pub fn span(&self) -> (f64, f64) {
        match self.fidelity {
            Fidelity::Listing => {
                let values = self.pattern.iter().map(|&v| v * 0.1);
                values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), t| (a.min(t), b.max(t)))
            }
            Fidelity::Thesis => (0.0, 1.0),
        }
    }

    /// Does a subpixel's time come back at every subpixel of the same place
    /// in the table (no jitter by the subpixel's index: `blur 0`, or the
    /// listing, which never reads `mindex`)? Asked of the times
    /// themselves, one place's over the CLT table's length.
    pub fn repeats(&self) -> bool {
        let first = self.time(1, 1, 0);
        (1..MAXINDEX).all(|k| self.time(1, 1, k).to_bits() == first.to_bits())
    }

    /// The time of subpixel (`scanline`, `scancol`), 1-based, the `k`-th
    /// subpixel of the scan order (0-based): the first lines of
    /// `motionblur`. Errata 1 and 2.
    #[inline]
    pub fn time(&self, scanline: usize, scancol: usize, k: usize) -> f64 {
        match self.fidelity {
            // Erratum 2, listing: `col := (scanline mod masksize)+1;
            // row := (scancol mod masksize)+1; time := pattern[row,col]*0.1`
            // and `mindex` is advanced but never read.
            Fidelity::Listing => {
                let (row, col) = (scancol % self.m, scanline % self.m);
                self.pattern[row * self.m + col] * 0.1
            }
            // Thesis: row from the scanline, column from the scancol; the
            // table picks a stratum of [0,1), the CLT mean x̄ (entry `mindex`
            // = k mod maxindex) a place in it (§2.6.4–2.6.5).
            Fidelity::Thesis => {
                let (row, col) = (scanline % self.m, scancol % self.m);
                let xbar = if self.n == 0 {
                    0.5
                } else {
                    self.clt[k % MAXINDEX] / self.n_real
                };
                (self.pattern[row * self.m + col] + xbar) / self.cells
            }
        }
    }
}

/// `LAW(OP, MAXVAL, FRACT)` of Fig. 3.2 (§3.2.2, OCR lines 720–733): how
/// far along a path a key frame is at the fraction FRACT of the time.
#[allow(non_snake_case)]
pub fn LAW(op: Law, maxval: f64, fract: f64) -> f64 {
    use std::f64::consts::PI;
    match op {
        // 1: constant velocity
        Law::Constant => maxval * fract,
        // 2: acceleration
        Law::Accelerate => maxval * (1.0 - (PI * fract / 2.0).cos()),
        // 3: deceleration
        Law::Decelerate => maxval * (PI * fract / 2.0).sin(),
        // 4: acceleration then deceleration
        Law::Smooth => maxval * (1.0 - (PI * fract).cos()) / 2.0,
    }
}

/// The rotation about a world axis by `degrees`.
#[inline]
fn rotation(axis: Axis, degrees: f64) -> DMat3 {
    // Most motions turn about one axis or none: skip the others' sin and cos.
    if degrees == 0.0 {
        return DMat3::IDENTITY;
    }
    let a = degrees.to_radians();
    match axis {
        Axis::X => DMat3::from_rotation_x(a),
        Axis::Y => DMat3::from_rotation_y(a),
        Axis::Z => DMat3::from_rotation_z(a),
    }
}

/// A turn by `degrees` about x, then y, then z (through the object's own
/// origin): the convention of every turn in the port's motions (`turn` of
/// a `motion` record, the key-frame angle; DEVIATIONS D8).
#[inline(always)]
pub fn turn_xyz(degrees: DVec3) -> DMat3 {
    // A turn about one axis or none, as most motions make: the product
    // with the identities is that rotation (or the identity) to the bit.
    // An entry of A·I or I·A is the entry plus products by 0, which change
    // it only if it is −0 or a product is not finite; the rotation by a
    // finite angle that is not 0 in radians has neither.
    let still = |d: f64| d == 0.0;
    let plain = |d: f64| {
        let a = d.to_radians();
        a != 0.0 && a.is_finite()
    };
    match (still(degrees.x), still(degrees.y), still(degrees.z)) {
        (true, true, true) => DMat3::IDENTITY,
        (false, true, true) if plain(degrees.x) => rotation(Axis::X, degrees.x),
        (true, false, true) if plain(degrees.y) => rotation(Axis::Y, degrees.y),
        (true, true, false) if plain(degrees.z) => rotation(Axis::Z, degrees.z),
        _ => rotation(Axis::Z, degrees.z) * rotation(Axis::Y, degrees.y) * rotation(Axis::X, degrees.x),
    }
}

/// The point of a motion path at the fraction `f` of the way (§3.2.2):
/// the straight line from `from` to `to`, or the cubic Bezier with the
/// two `via` points as its inner control points.
pub fn path_point(from: DVec3, motion: &MotionRecord, f: f64) -> DVec3 {
    match motion.via {
        None => from + (motion.to - from) * f,
        Some([p1, p2]) => {
            let g = 1.0 - f;
            from * (g * g * g) + p1 * (3.0 * g * g * f) + p2 * (3.0 * g * f * f) + motion.to * (f * f * f)
        }
    }
}

/// `motionblur(r, int, temp1, temp2, object, msc)` (unit `drt`, OCR lines
/// 2036–2186), for an object that moves but does not deform: from the
/// rest pose (the listing restores `transfm`, `inverse` and `sphereo` from
/// `temp1`, `temp2`), the pose at `time`, written into `pose` as the
/// listing writes it into the object's record: its `rotate` and
/// `translate` ([`motion_place`]) made one rigid pose. The time itself
/// comes from [`TimeTable::time`]; the key-frame branch (`paper = 1`)
/// comes with the `paper` unit. Erratum 3.
pub fn motionblur(object: &ObjectRecord, motion: &MotionRecord, time: f64, fidelity: Fidelity, pose: &mut Pose) {
    let (sphereo, turn) = motion_place(object, motion, time, fidelity);
    pose.turn_from(&object.transfm, turn, sphereo);
}

/// Where [`motionblur`] puts the object at `time`: its origin `sphereo`
/// and the turn about it. Apart so that the origin alone can be asked
/// (inlined, what goes unused is not computed): a structure tests the
/// bounding sphere before it poses the object. Erratum 3.
#[inline(always)]
pub fn motion_place(object: &ObjectRecord, motion: &MotionRecord, time: f64, fidelity: Fidelity) -> (DVec3, DMat3) {
    match fidelity {
        // Erratum 3, listing: `sphereo.x := sphereo.x+time*6;
        // rotate(name,xaxis,0,0,0,270*time*50); translate(name,sphereo…)`:
        // every moving object slides 6 along x while it spins about x,
        // whatever its motion record says.
        Fidelity::Listing => (
            object.sphereo + DVec3::new(6.0 * time, 0.0, 0.0),
            rotation(Axis::X, 270.0 * time * 50.0),
        ),
        // Thesis (§3.2.2): the user's path, the turn interpolated linearly,
        // both at LAW(law, 1, time); turns about x, then y, then z.
        Fidelity::Thesis => {
            let f = LAW(motion.law, 1.0, time);
            (path_point(object.sphereo, motion, f), turn_xyz(motion.turn * f))
        }
    }
}

/// Where `motionblur` can put the object's origin (`sphereo`) over the
/// times `t0` ≤ t ≤ `t1`: the smallest box that holds it (the port's, for
/// bounds over the shutter; the thesis bounds objects at rest only).
/// Erratum 3, as in [`motionblur`]: `listing` slides the origin 6·t along x
/// whatever the motion record says; `thesis` follows the user's path at
/// LAW(law, 1, t). Times outside [0, 1] (the listing's reach 1.5) are
/// bounded as well: each formula holds for any t.
pub fn motion_bounds(
    object: &ObjectRecord,
    motion: &MotionRecord,
    t0: f64,
    t1: f64,
    fidelity: Fidelity,
) -> BoundingBox {
    let s = object.sphereo;
    match fidelity {
        // Listing: sphereo.x := sphereo.x + time*6, linear in time.
        Fidelity::Listing => BoundingBox::EMPTY
            .holding(s + DVec3::new(6.0 * t0, 0.0, 0.0))
            .holding(s + DVec3::new(6.0 * t1, 0.0, 0.0)),
        // Thesis: the path at the fraction LAW(law, 1, t) of the way.
        Fidelity::Thesis => {
            let (f0, f1) = law_range(motion.law, t0, t1);
            path_bounds(s, motion, f0, f1)
        }
    }
}

/// The least and greatest LAW(op, 1, t) over `t0` ≤ t ≤ `t1`: the values
/// at the ends and where the law turns (its derivative's zeros: at even t
/// for LAW 2, odd t for LAW 3, whole t for LAW 4).
pub fn law_range(op: Law, t0: f64, t1: f64) -> (f64, f64) {
    let (a, b) = (t0.min(t1), t0.max(t1));
    let mut lo = LAW(op, 1.0, a).min(LAW(op, 1.0, b));
    let mut hi = LAW(op, 1.0, a).max(LAW(op, 1.0, b));
    let (step, offset) = match op {
        Law::Constant => return (lo, hi),
        Law::Accelerate => (2.0, 0.0),
        Law::Decelerate => (2.0, 1.0),
        Law::Smooth => (1.0, 0.0),
    };
    // The turning points step·n + offset strictly inside (a, b); only the
    // first few matter (the law is periodic), so at most three are taken.
    let first = ((a - offset) / step).floor() + 1.0;
    for n in 0..3 {
        let t = (first + n as f64) * step + offset;
        if t >= b || !t.is_finite() {
            break;
        }
        let f = LAW(op, 1.0, t);
        (lo, hi) = (lo.min(f), hi.max(f));
    }
    (lo, hi)
}

/// The box of [`path_point`] over the fractions `f0` ≤ f ≤ `f1`: a line's
/// two ends, or a Bezier path's ends and, on each axis, its turning points
/// (the roots of the derivative, a quadratic) between them.
pub fn path_bounds(from: DVec3, motion: &MotionRecord, f0: f64, f1: f64) -> BoundingBox {
    let mut b = BoundingBox::EMPTY
        .holding(path_point(from, motion, f0))
        .holding(path_point(from, motion, f1));
    let Some([p1, p2]) = motion.via else {
        return b;
    };
    // B(f) = from (1−f)³ + 3 p1 (1−f)² f + 3 p2 (1−f) f² + to f³; B′(f)/3 =
    // a f² + 2 b f + c per axis, a = −from + 3 p1 − 3 p2 + to,
    // b = from − 2 p1 + p2, c = p1 − from.
    let a = -from + 3.0 * p1 - 3.0 * p2 + motion.to;
    let bq = from - 2.0 * p1 + p2;
    let c = p1 - from;
    for axis in 0..3 {
        let (qa, qb, qc) = (a[axis], bq[axis], c[axis]);
        // The roots as q/a and c/q, q = −(b + sign(b)·√disc): the pair
        // that does not cancel (with a path whose a is a rounding of 0,
        // (−b ± √disc)/a lost the root, c/q keeps it).
        let disc = qb * qb - qa * qc;
        let roots: [Option<f64>; 2] = if disc < 0.0 {
            [None, None]
        } else {
            let q = -(qb + qb.signum() * disc.sqrt());
            [(qa != 0.0).then(|| q / qa), (q != 0.0).then(|| qc / q)]
        };
        for f in roots.into_iter().flatten() {
            if f > f0.min(f1) && f < f0.max(f1) {
                b = b.holding(path_point(from, motion, f));
            }
        }
    }
    b
}

/// `boundvolume(r, class)` (nested in `motionblur`, OCR lines 2044–2110):
/// does the line of the ray meet the box? It compares the line with the
/// box's corners in projections. Erratum 12: the listing tests only the
/// x–y and x–z projections (and its call is commented out); `thesis`
/// fidelity adds the y–z projection, which makes the test exact for a
/// line (the three projections are the separating axes d × eᵢ). Like the
/// listing, it takes the ray as a whole line, both ways.
pub fn boundvolume(r: &Ray, bx: &BoundingBox, fidelity: Fidelity) -> bool {
    let (x0, y0, z0) = (r.origin.x, r.origin.y, r.origin.z);
    let (vx, vy, vz) = (r.dir.x, r.dir.y, r.dir.z);
    // The line (p0 + s·v) projected along the third axis crosses the
    // rectangle [amin,amax]×[bmin,bmax] iff the two corners on the
    // rectangle's diagonal that the line's slope picks lie on both sides.
    let crosses = |va: f64, vb: f64, a0: f64, b0: f64, amin: f64, amax: f64, bmin: f64, bmax: f64| {
        let tail = vb * a0 - va * b0;
        let (t1, t2) = if va * vb >= 0.0 {
            (vb * amin - va * bmax - tail, vb * amax - va * bmin - tail)
        } else {
            (vb * amax - va * bmax - tail, vb * amin - va * bmin - tail)
        };
        t1 * t2 <= 0.0
    };
    let xy = crosses(vx, vy, x0, y0, bx.xmin, bx.xmax, bx.ymin, bx.ymax);
    let xz = crosses(vx, vz, x0, z0, bx.xmin, bx.xmax, bx.zmin, bx.zmax);
    match fidelity {
        Fidelity::Listing => xy && xz,
        Fidelity::Thesis => xy && xz && crosses(vy, vz, y0, z0, bx.ymin, bx.ymax, bx.zmin, bx.zmax),
    }
}

/// `depthoffield(x0, y0, var z0, x1, y1, z1)` (unit `drt`, OCR lines
/// 2191–2202), which the thesis calls "not completed" and no deck record
/// reaches: moves the ray's second point onto the focal plane
/// y = `focuslength`, then the eye by `fradius*noise[dindex]*2` in z only
/// (a lens one-dimensional). `dindex` is 0-based here.
#[allow(clippy::too_many_arguments)]
pub fn depthoffield(
    x0: f64,
    y0: f64,
    z0: &mut f64,
    x1: &mut f64,
    y1: &mut f64,
    z1: &mut f64,
    focuslength: f64,
    fradius: f64,
    noise: &[f64],
    dindex: usize,
) {
    let t = (focuslength - y0) / (*y1 - y0);
    *x1 = x0 + (*x1 - x0) * t;
    *y1 = y0 + (*y1 - y0) * t;
    *z1 = *z0 + (*z1 - *z0) * t;
    *z0 += fradius * noise[dindex % noise.len()] * 2.0;
}

/// `jittering(x0, y0, z0, r, var a, b, c)` (unit `drt`, OCR lines
/// 2204–2238): the point 5 along the direction (a, b, c) from
/// (x0, y0, z0), moved by `r` across the direction. Erratum 16 (the port's
/// reading): the listing's first branch writes `a := xi-(b+c)*r/a`
/// without the factor t, and the second and third read `a` (and `b`)
/// after overwriting them, so the offset is neither across the direction
/// nor of length r; `thesis` fidelity uses t and the old components,
/// (−(b+c)·r·t/a, r·t, r·t) and its two siblings, which is perpendicular
/// to (a, b, c) and of length r.
#[allow(clippy::too_many_arguments)]
pub fn jittering(x0: f64, y0: f64, z0: f64, r: f64, a: &mut f64, b: &mut f64, c: &mut f64, fidelity: Fidelity) {
    let len = (*a * *a + *b * *b + *c * *c).sqrt();
    *a /= len;
    *b /= len;
    *c /= len;
    let (xi, yi, zi) = (x0 + *a * 5.0, y0 + *b * 5.0, z0 + *c * 5.0);
    let (oa, ob, oc) = (*a, *b, *c);
    if oa != 0.0 {
        let t = (oa * oa / (2.0 * oa * oa + (ob + oc) * (ob + oc))).sqrt();
        *a = match fidelity {
            Fidelity::Listing => xi - (ob + oc) * r / oa,
            Fidelity::Thesis => xi - (ob + oc) * r * t / oa,
        };
        *b = yi + r * t;
        *c = zi + r * t;
    } else if ob != 0.0 {
        let t = (ob * ob / (2.0 * ob * ob + (oa + oc) * (oa + oc))).sqrt();
        *a = xi + r * t;
        *b = match fidelity {
            // `b := yi-(a+c)*r/b` after `a := xi+r*t`.
            Fidelity::Listing => yi - (*a + oc) * r / ob,
            Fidelity::Thesis => yi - (oa + oc) * r * t / ob,
        };
        *c = zi + r * t;
    } else if oc != 0.0 {
        let t = (oc * oc / (2.0 * oc * oc + (ob + oa) * (ob + oa))).sqrt();
        *a = xi + r * t;
        *b = yi + r * t;
        *c = match fidelity {
            // `c := zi-(a+b)*r/c` after `a` and `b` were overwritten.
            Fidelity::Listing => zi - (*a + *b) * r / oc,
            Fidelity::Thesis => zi - (oa + ob) * r * t / oc,
        };
    }
}

/// `Isblur` (unit `drt`, OCR lines 2240–2262): is the object
/// `tableindex` absent from the motion table `motionmatrix`? True means it
/// does not move, so it needs no per-ray work.
#[allow(non_snake_case)]
pub fn Isblur(tableindex: usize, motionmatrix: &[usize]) -> bool {
    !motionmatrix.contains(&tableindex)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn minimal_standard_known_value() {
        // Park & Miller's check: from seed 1, the 10 000th value is 1043618065.
        let mut g = MinimalStandard::new(1);
        for _ in 0..10_000 {
            g.next_uniform();
        }
        assert_eq!(g.0, 1_043_618_065);
    }

    /// The bits of a matrix's entries, column by column (any NaN as one:
    /// Rust leaves a NaN's sign and payload open).
    fn bits(m: DMat3) -> Vec<u64> {
        let bits = |v: &f64| if v.is_nan() { f64::NAN.to_bits() } else { v.to_bits() };
        m.to_cols_array().iter().map(bits).collect()
    }

    /// `turn_xyz`'s short cut for a turn about one axis or none gives the
    /// product of the three rotations to the bit, −0 and all; where the
    /// rotation alone would not (an angle that is 0 once in radians, or
    /// not finite), it makes the product.
    #[test]
    fn a_turn_about_one_axis_is_the_product_to_the_bit() {
        let product = |d: DVec3| rotation(Axis::Z, d.z) * rotation(Axis::Y, d.y) * rotation(Axis::X, d.x);
        let mut rng = MinimalStandard::new(7);
        let mut angles = vec![
            0.0, -0.0, 25.0, -12.0, 90.0, 180.0, -270.0, 360.0, 1e-300, 5e-324, -5e-324, 1e300,
        ];
        angles.extend([f64::INFINITY, f64::NAN]);
        angles.extend((0..50).map(|_| (rng.next_uniform() - 0.5) * 1440.0));
        for &a in &angles {
            for axis in 0..3 {
                let mut d = DVec3::ZERO;
                d[axis] = a;
                assert_eq!(bits(turn_xyz(d)), bits(product(d)), "{a}° about axis {axis}");
            }
        }
        // The cases the short cut must leave to the product: the rotation
        // alone differs from it there.
        let tiny = DVec3::new(5e-324, 0.0, 0.0);
        assert_ne!(bits(rotation(Axis::X, tiny.x)), bits(product(tiny)));
        // Two axes, three: the product.
        for d in [DVec3::new(30.0, 0.0, 45.0), DVec3::new(30.0, 20.0, 45.0)] {
            assert_eq!(bits(turn_xyz(d)), bits(product(d)), "{d}");
        }
    }

    /// A subpixel's time comes back without jitter: always in the listing
    /// (which never reads `mindex`), with `blur 0` in the thesis; not with
    /// `blur` N > 0, whose CLT mean moves it.
    #[test]
    fn times_repeat_without_jitter() {
        for m in [1, 2, 3, 4] {
            let table = |blur, fidelity| TimeTable::with_default_pattern(m, blur, fidelity);
            assert!(table(0, Fidelity::Listing).repeats() && table(3, Fidelity::Listing).repeats());
            assert!(table(0, Fidelity::Thesis).repeats(), "{m}");
            assert!(!table(1, Fidelity::Thesis).repeats() && !table(2, Fidelity::Thesis).repeats());
        }
    }

    #[test]
    fn noise2_is_centred_and_bounded() {
        let t = noise2_table();
        assert_eq!(t.len(), MAXINDEX);
        assert!(t.iter().all(|v| (-0.5..0.5).contains(v)));
        let mean = t.iter().sum::<f64>() / t.len() as f64;
        // Uniform(−½,½) has σ = 1/√12; the mean of 1000 has σ ≈ 0.0091.
        assert!(mean.abs() < 0.04, "mean {mean}");
    }
}

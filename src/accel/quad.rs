//! Four boxes tested against a ray at once, in single precision: the
//! test of a node of the hierarchy ([`super::Bvh`]). The port's, as the
//! hierarchy is.
//!
//! Four lanes of `f32` are what one SSE register holds, so the compiler
//! makes the four slab tests one (`subps`/`mulps`/`minps`/`maxps`), where
//! `f64` took two registers for two boxes. The test is *conservative*: it
//! answers "meets" for every box the exact test ([`super::BoxRay::span`])
//! says the ray meets, and may say so of a box the ray passes within a
//! millionth of its distance. A box the walk enters wrongly costs one
//! object test, which decides alone (in `f64`, as the loop): the image
//! does not change. How each rounding is kept on the safe side:
//!
//! - the boxes are rounded outward to `f32` ([`down`], [`up`]);
//! - every t the test compares is 0 or more, so that a relative error of
//!   it moves it one known way: the walk's interval starts at `tmin` ≥ 0
//!   (as every render's does), or else t is counted from `tmin`, the
//!   origin moved there (`o + tmin·d`, in `f64`);
//! - the origin is rounded up for the lower faces and down for the upper
//!   ones, so that each face's distance from it, `lo − o` and `hi − o`,
//!   can only grow outward (whatever the direction's sign);
//! - what rounding is left (the difference, the reciprocal of the
//!   direction, the product: three roundings of 2⁻²⁴ each) is a relative
//!   error of t under 2⁻²²: a box is met when its entry is at most its
//!   exit times 1 + 2⁻²⁰ ([`SLACK`]), plus [`TINY`] (for t so small that its
//!   rounding is not relative), and the walk's limit is taken as much
//!   above itself ([`QuadRay::limit`]);
//! - a direction component whose reciprocal does not fit an `f32` (one of
//!   less than about 10⁻³⁸, not 0) gives its slab a NaN, which bounds no
//!   t: that slab is left out of the test (a wider answer, never a
//!   narrower one). A component of 0 keeps its reciprocal +∞, as in `f64`.
//!
//! Coordinates and t up to about 10³⁷ only: beyond, an `f32` overflows; a
//! limit there is taken as no limit.

use super::{Aabb, BoxRay};

/// The relative widening of an exit: 2⁻²⁰, above the 2⁻²² that three
/// `f32` roundings of an entry and an exit may take together, with room
/// for its own.
const SLACK: f32 = 1.0 / 1_048_576.0;

/// The absolute widening, for t whose rounding is not relative (below
/// `f32::MIN_POSITIVE`, in the subnormals).
const TINY: f32 = f32::MIN_POSITIVE;

/// 2⁻²²: an `f32` rounded to nearest is within 2⁻²⁴ of itself of the
/// `f64` it came from; moved by this much of itself it is past it.
const ULP: f32 = 1.0 / 4_194_304.0;

/// The reciprocals an `f32` holds with its relative precision: normal
/// and finite once rounded.
const MIN_INV: f64 = f32::MIN_POSITIVE as f64 * 2.0;
const MAX_INV: f64 = f32::MAX as f64 / 2.0;

/// Beyond this an `f32` t is near overflowing: a limit there is none.
const FAR: f64 = 1e37;

/// `x` in `f32`, moved past itself by `rel` of itself and `TINY`, up or
/// (`sign` −1) down: a few instructions, where [`up`] and [`down`] branch.
/// With `rel` = `ULP` it is past `x` itself.
#[inline(always)]
fn past(x: f64, rel: f32, sign: f32) -> f32 {
    let y = x as f32;
    y + sign * (y.abs() * rel + TINY)
}

/// The greatest `f32` not above `x` (NaN stays NaN).
fn down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) > x {
        y.next_down()
    } else {
        y
    }
}

/// The least `f32` not below `x` (NaN stays NaN).
fn up(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) < x {
        y.next_up()
    } else {
        y
    }
}

/// Four boxes, axis by axis: `lo[k][c]`, `hi[k][c]` bound box c on axis k,
/// rounded outward to `f32`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Quad {
    lo: [[f32; 4]; 3],
    hi: [[f32; 4]; 3],
}

impl Quad {
    /// Up to four boxes; the lanes after them hold nothing the walk reads
    /// (it does not look at a lane without a child).
    pub(super) fn of(boxes: &[Aabb]) -> Quad {
        let mut q = Quad {
            lo: [[f32::INFINITY; 4]; 3],
            hi: [[f32::NEG_INFINITY; 4]; 3],
        };
        for (c, b) in boxes.iter().enumerate().take(4) {
            for k in 0..3 {
                q.lo[k][c] = down(b.lo[k]);
                q.hi[k][c] = up(b.hi[k]);
            }
        }
        q
    }

    /// Box `c`'s corners, as kept.
    #[cfg(test)]
    pub(super) fn lane(&self, c: usize) -> [[f32; 3]; 2] {
        [self.lo, self.hi].map(|v| [v[0][c], v[1][c], v[2][c]])
    }
}

/// A ray made ready for [`Quad`]s, its t counted from `tmin`: see the
/// module doc.
#[derive(Clone, Copy, Debug)]
pub(super) struct QuadRay {
    /// The origin at `base`, rounded up (for the lower faces) and down
    /// (the upper).
    o_up: [f32; 3],
    o_down: [f32; 3],
    inv: [f32; 3],
    /// Where t is counted from: 0, or `tmin` when that is below 0.
    base: f64,
    /// `tmin`, counted so, in `f32`.
    t0: f32,
}

impl QuadRay {
    #[inline(always)]
    pub(super) fn new(ray: &BoxRay, tmin: f64) -> QuadRay {
        let inv = ray.inv.to_array().map(|r| {
            // A reciprocal that does not fit (overflows, or falls into the
            // subnormals and loses its relative precision): no slab. ±∞
            // (a direction component of 0) stays.
            let a = r.abs();
            if (MIN_INV..=MAX_INV).contains(&a) || a == f64::INFINITY {
                r as f32
            } else {
                f32::NAN
            }
        });
        let (mut o_up, mut o_down) = ([0.0; 3], [0.0; 3]);
        // t counted from 0, or from tmin when that is below 0.
        let base = tmin.min(0.0);
        for k in 0..3 {
            let mut o = ray.origin[k];
            if base < 0.0 {
                // The moved origin, and a bound on its rounding (not
                // relative to it when the move cancels the origin).
                let step = base * ray.dir[k];
                let err = (o.abs() + step.abs()) * f64::EPSILON;
                o += step;
                o_up[k] = past(o + err, ULP, 1.0);
                o_down[k] = past(o - err, ULP, -1.0);
            } else {
                o_up[k] = past(o, ULP, 1.0);
                o_down[k] = past(o, ULP, -1.0);
            }
        }
        // The interval's start, down; 0 or more.
        let t0 = past(tmin - base, ULP, -1.0).max(0.0);
        QuadRay {
            o_up,
            o_down,
            inv,
            base,
            t0,
        }
    }

    /// The walk's `limit` as [`QuadRay::span`] takes it: in `f32`, above
    /// itself by the slack the entries may need (the module doc); +∞ for
    /// one near overflowing.
    #[inline(always)]
    pub(super) fn limit(&self, limit: f64) -> f32 {
        let t = limit - self.base;
        let t = t + (limit.abs() + self.base.abs()) * f64::EPSILON;
        if t < FAR {
            past(t, 4.0 * SLACK, 1.0)
        } else {
            f32::INFINITY
        }
    }

    /// Where the walk's interval starts, as [`QuadRay::span`] counts t.
    pub(super) fn start(&self) -> f32 {
        self.t0
    }

    /// For each box c of `q`: bit c set when the ray may meet it between
    /// `tmin` and the limit `t1` (from [`QuadRay::limit`]), and the t at
    /// which it may enter it (counted from 0, or from `tmin` below 0).
    /// Conservative (the module doc): every box the ray meets there has
    /// its bit, and an entry of at most `t1` when the exact entry is at
    /// most the limit.
    #[inline(always)]
    pub(super) fn span(&self, q: &Quad, t1: f32) -> ([f32; 4], u32) {
        let (mut enter, mut exit) = ([self.t0; 4], [t1; 4]);
        for k in 0..3 {
            for c in 0..4 {
                let ta = (q.lo[k][c] - self.o_up[k]) * self.inv[k];
                let tb = (q.hi[k][c] - self.o_down[k]) * self.inv[k];
                let (near, far) = if ta > tb { (tb, ta) } else { (ta, tb) };
                enter[c] = if near > enter[c] { near } else { enter[c] };
                exit[c] = if far < exit[c] { far } else { exit[c] };
            }
        }
        let mut bits = 0;
        for c in 0..4 {
            // The entry is 0 or more: a negative exit is a miss however
            // widened.
            let met = enter[c] <= exit[c] * (1.0 + SLACK) + TINY;
            bits |= u32::from(met) << c;
        }
        (enter, bits)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::tests::cube;
    use crate::types::{DVec3, Ray};

    #[test]
    fn rounding_outward() {
        for x in [0.1, -0.1, 1.0, 1e-40, -1e-40, 3e38, 1e39, -1e39, f64::INFINITY, 5e-324] {
            assert!(f64::from(down(x)) <= x && f64::from(up(x)) >= x, "{x}");
            if x.is_finite() {
                assert!(f64::from(down(x).next_up()) > x || down(x) == f32::MAX, "{x}");
                assert!(f64::from(up(x).next_down()) < x, "{x}");
            }
        }
        assert!(down(f64::NAN).is_nan() && up(f64::NAN).is_nan());
        assert_eq!((down(1.0), up(1.0)), (1.0, 1.0));
        for x in [10.0, 0.1, 1e-9, 0.0, -3.0, 1e-40, 9.99e36, -1e30] {
            let (hi, lo) = (past(x, ULP, 1.0), past(x, ULP, -1.0));
            assert!(
                f64::from(hi) >= x && f64::from(hi) <= x + x.abs() * 1e-6 + 1e-37,
                "{x} {hi}"
            );
            assert!(
                f64::from(lo) <= x && f64::from(lo) >= x - x.abs() * 1e-6 - 1e-37,
                "{x} {lo}"
            );
        }
        let ray = QuadRay::new(&BoxRay::new(&Ray::new(DVec3::ZERO, DVec3::X)), 2.0);
        assert_eq!(ray.limit(f64::INFINITY), f32::INFINITY);
        assert_eq!(ray.limit(1e38), f32::INFINITY);
        let t = ray.limit(10.0);
        assert!((10.0..10.0001).contains(&t), "{t}");
        assert!(ray.start() <= 2.0 && ray.start() > 1.9999);
        let back = QuadRay::new(&BoxRay::new(&Ray::new(DVec3::ZERO, DVec3::X)), -2.0);
        let t = back.limit(10.0);
        assert!((12.0..12.0001).contains(&t), "{t}");
        assert_eq!(back.start(), 0.0);
    }

    /// Uniform numbers in [a, b), one a call, from `key` on.
    fn uniforms(mut key: u64) -> impl FnMut(f64, f64) -> f64 {
        move |a, b| {
            key += 1;
            a + (b - a) * crate::hash::hashed_uniform(key)
        }
    }

    /// The exact test's answer for one box; whether the quad's, for it in
    /// lane `c` (the others empty), lets the walk in (its bit, and an
    /// entry within the limit); whether the quad's entry is within a limit
    /// at the exact entry (so that a box met at the nearest hit so far is
    /// still walked into).
    fn both(ray: &Ray, b: &Aabb, c: usize, t0: f64, t1: f64) -> (Option<(f64, f64)>, bool, bool) {
        let exact = BoxRay::new(ray).span(b, t0, t1);
        let mut boxes = [Aabb::EMPTY; 4];
        boxes[c] = *b;
        let quad = QuadRay::new(&BoxRay::new(ray), t0);
        let (enter, bits) = quad.span(&Quad::of(&boxes), quad.limit(t1));
        let within = enter[c] <= quad.limit(t1);
        let entry = exact.is_none_or(|(e, _)| enter[c] <= quad.limit(e));
        (exact, bits & 1 << c != 0 && within, entry)
    }

    /// Every box the exact test meets, the quad meets, entering no later
    /// (as the walk compares entries); a box the exact test misses by more
    /// than the slack, the quad misses. Random boxes and rays, and the hard ones: rays grazing a
    /// face or an edge, along a face, from a corner, with a direction
    /// component of 0, of 1e-40 (its slab left out), far and tiny
    /// coordinates, limits at the entry.
    #[test]
    fn the_quad_meets_every_box_the_exact_test_meets() {
        let mut u = uniforms(0u64);
        let (mut met, mut missed) = (0, 0);
        for case in 0..20_000 {
            let scale = [1.0, 1e-30, 1e30, 1e-3][case % 4];
            let c = [u(-3.0, 3.0), u(-3.0, 3.0), u(-3.0, 3.0)].map(|v| v * scale);
            let mut b = cube(c, u(0.0, 2.0) * scale);
            if case % 7 == 0 {
                b.hi.x = b.lo.x;
            }
            if case % 11 == 0 {
                b.hi.y = f64::INFINITY;
            }
            let mut dir = DVec3::new(u(-1.0, 1.0), u(-1.0, 1.0), u(-1.0, 1.0));
            let mut origin = DVec3::new(u(-6.0, 6.0), u(-6.0, 6.0), u(-6.0, 6.0)) * scale;
            if case % 19 < 3 {
                // At 0, its rounding gives no room: the slack must.
                origin = DVec3::ZERO;
            }
            // Aim at a corner, an edge's point or a face's point.
            let target = DVec3::new(
                if case % 3 == 0 { b.lo.x } else { u(b.lo.x, b.hi.x) },
                if case % 5 < 2 {
                    b.hi.y.min(b.lo.y + 1e300)
                } else {
                    u(b.lo.y, b.lo.y + 1e-9)
                },
                if case % 2 == 0 { b.lo.z } else { b.hi.z },
            );
            if case % 13 < 6 && target.is_finite() {
                dir = target - origin;
            }
            match case % 17 {
                0 => {
                    dir.x = 0.0;
                    origin.x = b.lo.x;
                }
                1 => dir.y = 1e-40,
                2 => dir.z = -0.0,
                _ => {}
            }
            let ray = Ray::new(origin, dir);
            let exact_all = BoxRay::new(&ray).span(&b, 0.0, f64::INFINITY);
            // t of the order of the distance to the box, in lengths of dir.
            let span = (origin - b.centre()).length() / dir.length();
            let span = if span.is_finite() { span } else { scale / dir.length() };
            let t0 = if case % 9 == 0 { 0.0 } else { u(-1.0, 1.0) * span };
            // A limit at the exact entry, now and then.
            let t1 = match (case % 3, exact_all) {
                (0, _) => f64::INFINITY,
                (1, Some((enter, _))) if enter > t0 => enter,
                _ => u(0.0, 10.0) * span,
            };
            let (exact, hit, entry) = both(&ray, &b, case % 4, t0, t1);
            if exact.is_some() {
                met += 1;
                assert!(hit && entry, "case {case}: {ray:?} {b:?} [{t0}, {t1}] {exact:?}");
            }
            // A clear miss: the box grown by a ten-thousandth of the
            // scene's extent (what the slack may reach, with room) and the
            // interval by as much of itself are missed by the exact test,
            // and the direction has no tiny component: the quad misses it.
            let extent = origin
                .abs()
                .max_element()
                .max(c.map(f64::abs).into_iter().fold(0.0, f64::max));
            let grown = Aabb {
                lo: b.lo - 1e-4 * extent,
                hi: b.hi + 1e-4 * extent,
            };
            // (A component whose reciprocal an f32 does not hold: its slab
            // is left out, a wider answer.)
            let tiny = dir
                .to_array()
                .iter()
                .any(|d| *d != 0.0 && !(1e-37..1e36).contains(&d.abs()));
            let wide = BoxRay::new(&ray).span(&grown, t0 - 1e-4 * t0.abs(), t1 + 1e-4 * t1.abs());
            if wide.is_none() && !tiny {
                assert!(!hit, "case {case}: {ray:?} {b:?} [{t0}, {t1}]");
                missed += 1;
            }
        }
        assert!(met > 5_000 && missed > 5_000, "{met} {missed}");
    }

    /// A walk that starts below 0 moves the origin to its start; where
    /// that move all but cancels the origin, the rounding of what is left
    /// is not relative to it, and its bound must keep a box the ray leaves
    /// just there met (the exact test says so of about half of these).
    #[test]
    fn an_origin_moved_to_the_start_keeps_its_rounding() {
        let mut u = uniforms(7u64);
        let mut met = 0;
        for i in 0..4000 {
            // Half of them mirrored in x: the lower face, the origin
            // rounded up.
            let m = if i % 2 == 0 { 1.0 } else { -1.0 };
            let dir = DVec3::new(m * u(0.1, 1.0), u(-1.0, 1.0), u(-1.0, 1.0));
            let origin = DVec3::new(m * u(1.0, 10.0), u(-1.0, 1.0), u(-1.0, 1.0));
            // The ray leaves the box at x = 0 at about tmin.
            let tmin = -origin.x / dir.x;
            let (lo, hi) = if m > 0.0 { (-1.0, 0.0) } else { (0.0, 1.0) };
            let b = Aabb {
                lo: DVec3::new(lo, -1e3, -1e3),
                hi: DVec3::new(hi, 1e3, 1e3),
            };
            let ray = Ray::new(origin, dir);
            let (exact, hit, _) = both(&ray, &b, 0, tmin, f64::INFINITY);
            if exact.is_some() {
                met += 1;
                assert!(hit, "{ray:?} {tmin}");
            }
        }
        assert!(met > 200, "{met}");
    }

    /// Lanes answer each for its own box, the lanes apart: four cubes on a
    /// row, a ray along it enters them in order.
    #[test]
    fn four_lanes_four_boxes() {
        let boxes: Vec<Aabb> = (0..4).map(|i| cube([i as f64 * 3.0, 0.0, 0.0], 1.0)).collect();
        let quad = |o: DVec3| QuadRay::new(&BoxRay::new(&Ray::new(o, DVec3::X)), -1.0);
        let along = quad(DVec3::new(-5.0, 0.0, 0.0));
        let (enter, bits) = along.span(&Quad::of(&boxes), along.limit(f64::INFINITY));
        assert_eq!(bits, 0b1111);
        for (i, e) in enter.iter().enumerate() {
            // From t = −1.
            let exact = 5.0 + 3.0 * i as f32;
            assert!(*e <= exact && *e > exact * 0.9999, "{i} {e}");
        }
        let (_, bits) = along.span(&Quad::of(&boxes), along.limit(7.0));
        assert_eq!(bits, 0b0011);
        let beside = quad(DVec3::new(-5.0, 3.0, 0.0));
        let (_, bits) = beside.span(&Quad::of(&boxes[..3]), beside.limit(f64::INFINITY));
        // (A lane without a box answers what it will: the walk masks it.)
        assert_eq!(bits & 0b0111, 0);
    }
}

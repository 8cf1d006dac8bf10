//! Unit `proc` of the thesis (listing in the OCR text, lines 1437–2035):
//! `rotatetest`, `floortest`, `startest`, `floorstar` here, in the
//! listing's order; `laguerre`, `sorting`, `spline`, `outrectp` and
//! `roottesting` in [`sweep`]. The port's second root solver, not the
//! thesis's, stands beside the unit ([`crate::robust`]).
//!
//! The pattern procedures of the listing set the global `painting`; here
//! they return the [`Painting`] they would set, or `None` where the listing
//! leaves `painting` as it was. The listing reads the pattern scale from the
//! globals `lengthx`, `lengthy`; here they are arguments.

pub mod sweep;

use crate::options::Fidelity;

use crate::types::{Painting, Ray};

/// `3.141592654`, the listing's value of π in `rotatetest`, kept as printed.
#[allow(clippy::approx_constant)]
const LISTING_PI: f64 = 3.141592654;

/// `rotatetest(var rae: ray; angle: real)` (unit `proc`, OCR lines
/// 1437–1452): turns the ray's second point (x1, z1) about the y axis by
/// `angle` degrees. Erratum 5.
///
/// The listing is not called by the printed main program; it is kept for a
/// reader who compares the units.
pub fn rotatetest(rae: &mut Ray, angle: f64, fidelity: Fidelity) {
    let (s, c) = (angle * LISTING_PI / 180.0).sin_cos();
    let p1 = rae.origin + rae.dir;
    let (x1, z1) = (p1.x, p1.z);
    let new_x1 = x1 * c - z1 * s;
    let new_z1 = match fidelity {
        // Erratum 5, listing: `z1 := x1*sin(..) + z1*cos(..)` runs after
        // `x1` was overwritten, so it reads the rotated x1.
        Fidelity::Listing => new_x1 * s + z1 * c,
        // Thesis: a rotation, z1' = x1 sin θ + z1 cos θ with the old x1.
        Fidelity::Thesis => x1 * s + z1 * c,
    };
    let p1 = crate::types::DVec3::new(new_x1, p1.y, new_z1);
    rae.dir = p1 - rae.origin;
}

/// Pascal's `round(x) mod 2` for the patterns: `round` is half away from
/// zero (as Rust's `f64::round`); `mod` follows ISO 7185, whose result is
/// never negative (Sun Pascal's own `mod` on negative operands is not
/// documented in the thesis; the port's pattern coordinates are measured
/// from a face's corner, so they are not negative anyway).
fn round_mod2(x: f64) -> i64 {
    pascal_round(x).rem_euclid(2)
}

/// Pascal's `round`, `x.round() as i64` to the bit, without the library
/// call `f64::round` is on this target (it shows in the profile of every
/// checker floor): below 2⁵² the whole part and the fraction are exact,
/// and the fraction decides; above it every value is whole (or infinite,
/// or NaN, which the conversion saturates, or makes 0, alike).
fn pascal_round(x: f64) -> i64 {
    // One comparison for both: a NaN is not below 2⁵².
    if x.abs() < 4_503_599_627_370_496.0 {
        let whole = x as i64; // toward zero
        let fraction = x - whole as f64;
        if fraction >= 0.5 {
            whole + 1
        } else if fraction <= -0.5 {
            whole - 1
        } else {
            whole
        }
    } else {
        x as i64
    }
}

/// `floortest(x, y: real)` (unit `proc`, OCR lines 1455–1476): paints the
/// checker floor on a block. The point (x, y) is scaled by `lengthx`,
/// `lengthy`; where `round(tx) mod 2 + round(ty) mod 2` is 0 or 2 the
/// listing sets `painting := floor1`.
pub fn floortest(x: f64, y: f64, lengthx: f64, lengthy: f64) -> Option<Painting> {
    let tx = round_mod2(x * lengthx);
    let ty = round_mod2(y * lengthy);
    let tz = tx + ty;
    (tz == 0 || tz == 2).then_some(Painting::Floor1)
}

/// `startest(x, y, z: real; cas: integer)` (unit `proc`, OCR lines
/// 1479–1515): is the point in the star (two triangles of a hexagram,
/// √3/9 from the centre to an edge)? `cas = 1` tests the x–z plane,
/// `cas = 2` the x–y plane; other values paint nothing, as in the listing.
pub fn startest(x: f64, y: f64, z: f64, cas: i32) -> Option<Painting> {
    let t = 3f64.sqrt();
    let second = match cas {
        1 => z,
        2 => y,
        _ => return None,
    };
    let w = second;
    let down = (w - t / 9.0 < 0.0) && (t * x + w + 2.0 * t / 9.0 > 0.0) && (t * x - w - 2.0 * t / 9.0 < 0.0);
    let up = (w + t / 9.0 > 0.0) && (t * x + w - 2.0 * t / 9.0 < 0.0) && (t * x - w + 2.0 * t / 9.0 > 0.0);
    (down || up).then_some(Painting::Star1)
}

/// `floorstar(x, y: real)` (unit `proc`, OCR lines 1519–1560): stars on a
/// block. The plane is cut into 3×3 tiles (of the scaled coordinates); in
/// the tiles whose indices sum to an odd number, two triangles make a star.
/// Erratum 6.
// The two triangles are the listing's two branches; they stay two.
#[allow(clippy::if_same_then_else)]
pub fn floorstar(x: f64, y: f64, lengthx: f64, lengthy: f64, fidelity: Fidelity) -> Option<Painting> {
    let mut tx = x * lengthx;
    let mut ty = y * lengthy;
    let (mut xx, mut yy) = (0i64, 0i64);
    while tx > 3.0 {
        tx -= 3.0;
        xx += 1;
    }
    while ty > 3.0 {
        ty -= 3.0;
        yy += 1;
    }
    if (xx + yy) % 2 == 0 {
        return None;
    }
    if (tx * 15.0 + ty * 10.0 - 27.5) >= 0.0 && ty <= 2.0 && (tx * 1.5 - ty - 1.75) <= 0.0 {
        Some(Painting::Star1)
    } else if (tx * 15.0 + ty * 10.0 - 47.5) <= 0.0 && ty >= 1.0 && (tx * 1.5 - ty + 0.25) >= 0.0 {
        Some(Painting::Star1)
    } else {
        match fidelity {
            // Erratum 6, listing: `else painting := star1`, so the whole odd
            // tile is painted and the star cannot be seen.
            Fidelity::Listing => Some(Painting::Star1),
            // Thesis: "stars on a block"; outside the two triangles the
            // surface keeps its own colour.
            Fidelity::Thesis => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::DVec3;

    /// `pascal_round` is `f64::round` (half away from zero) to the bit:
    /// at the halves and their neighbours, at 2⁵² and past the range of
    /// i64, and on hashed values of every magnitude.
    #[test]
    fn pascal_round_is_round() {
        let mut xs = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            -2.5,
            0.49999999999999994,
            -0.49999999999999994,
            4_503_599_627_370_495.5,
            -4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            9.3e18,
            -9.3e18,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
        ];
        for k in 0..4000u64 {
            let u = crate::hash::hashed_uniform(k) - 0.5;
            let scale = 10f64.powi((k % 20) as i32 - 3);
            xs.push(u * scale);
            xs.push((u * 64.0).round() / 2.0); // the halves themselves
            let half = (u * 64.0).round() / 2.0 + 0.5;
            xs.push(f64::from_bits(half.to_bits() + 1));
            xs.push(f64::from_bits(half.to_bits().saturating_sub(1)));
        }
        for x in xs {
            assert_eq!(pascal_round(x), x.round() as i64, "{x:e}");
        }
    }

    #[test]
    fn floortest_paints_the_even_squares() {
        // round(0.4)=0, round(0.4)=0: 0+0 = 0, painted.
        assert_eq!(floortest(0.4, 0.4, 1.0, 1.0), Some(Painting::Floor1));
        // round(0.6)=1, round(0.4)=0: odd, not painted.
        assert_eq!(floortest(0.6, 0.4, 1.0, 1.0), None);
        // 1 + 1 = 2: painted.
        assert_eq!(floortest(1.2, 0.7, 1.0, 1.0), Some(Painting::Floor1));
        // lengthx scales: x = 0.3 at 2 per unit is 0.6 → 1.
        assert_eq!(floortest(0.3, 0.0, 2.0, 1.0), None);
        // Half away from zero: round(0.5) = 1.
        assert_eq!(floortest(0.5, 0.0, 1.0, 1.0), None);
    }

    #[test]
    fn startest_centre_and_tips() {
        let t = 3f64.sqrt();
        assert_eq!(startest(0.0, 0.0, 0.0, 1), Some(Painting::Star1));
        assert_eq!(startest(0.0, 0.0, 0.0, 2), Some(Painting::Star1));
        // Just inside the upward tip at z = 2√3/9, just outside beyond it.
        assert_eq!(startest(0.0, 0.0, 2.0 * t / 9.0 - 1e-3, 1), Some(Painting::Star1));
        assert_eq!(startest(0.0, 0.0, 2.0 * t / 9.0 + 1e-3, 1), None);
        // cas 2 reads y, not z.
        assert_eq!(startest(0.0, 0.0, 0.5, 2), Some(Painting::Star1));
        assert_eq!(startest(0.0, 0.5, 0.0, 2), None);
        // Between two tips (on the hexagram's concave notch) is outside.
        assert_eq!(startest(0.3, 0.0, 0.0, 1), None);
        assert_eq!(startest(0.0, 0.0, 0.0, 3), None);
    }

    #[test]
    fn floorstar_in_both_fidelities() {
        // Tile (0,0): even, never painted.
        assert_eq!(floorstar(1.5, 1.5, 1.0, 1.0, Fidelity::Listing), None);
        // Tile (1,0) is odd: local (tx, ty) = (1.5, 1.5) is in the first
        // triangle: 22.5 + 15 − 27.5 ≥ 0, ty ≤ 2, 2.25 − 1.5 − 1.75 ≤ 0.
        for f in [Fidelity::Listing, Fidelity::Thesis] {
            assert_eq!(floorstar(4.5, 1.5, 1.0, 1.0, f), Some(Painting::Star1));
        }
        // Local (0.2, 0.2) of an odd tile is in neither triangle:
        // the listing paints it anyway (erratum 6), the thesis does not.
        assert_eq!(floorstar(3.2, 0.2, 1.0, 1.0, Fidelity::Listing), Some(Painting::Star1));
        assert_eq!(floorstar(3.2, 0.2, 1.0, 1.0, Fidelity::Thesis), None);
    }

    #[test]
    fn rotatetest_erratum_5() {
        let ray = Ray::new(DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0));
        let mut thesis = ray;
        rotatetest(&mut thesis, 90.0, Fidelity::Thesis);
        // A true rotation of (1,0,0) by 90°: x = cos, z = sin → (0, 0, 1).
        assert!((thesis.dir - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-8);
        let mut listing = ray;
        rotatetest(&mut listing, 90.0, Fidelity::Listing);
        // The listing's z1 reads the new x1 ≈ 0: z1 ≈ 0·1 + 0·0.
        assert!(listing.dir.z.abs() < 1e-8);
        assert!((listing.dir.length() - 1.0).abs() > 0.5);
    }
}

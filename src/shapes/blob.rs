//! Soft objects (§6.2's "soft object"): the port's extension. A blob is the
//! surface where the sum of its components' fields equals its threshold
//! T > 0, each component contributing S·(1 − r²/R²)² at a distance r < R
//! from its centre and 0 beyond (POV-Ray's field, so that the two
//! renderers can be compared; Wyvill, McPheeters & Wyvill 1986 use a
//! sextic of the same support).
//!
//! The intersection is exact. Along a ray p(t) = o + t·d each component's
//! (1 − |p − c|²/R²) is a quadratic in t, its field a quartic, and it is 0
//! outside the ray's chord through the component's sphere. Between the
//! ends of the chords the sum is one quartic: the chords' ends, sorted,
//! cut the ray into intervals, and on each the quartic less T is written
//! over s ∈ [0, 1] and solved by the solver of the sweeps (`laguerre`
//! behind its Bernstein pre-test, or `--solver robust`: the sweep module's
//! [`solve`]); the first root beyond `tmin` is the hit. An interval where
//! no component of positive strength is active holds no surface (the field
//! is ≤ 0 < T there) and is skipped. The normal is the field's gradient,
//! exact: −∇F = 4 Σ S·(1 − r²/R²)·(p − c)/R² over the components whose
//! sphere holds the hit.
//!
//! Each component is bounded by its sphere, tested first; a blob has at
//! most [`MAXCOMPONENTS`] (60), so the chords fit fixed arrays and
//! nothing is allocated per ray. The field is C¹ where a chord ends (the
//! component's value and slope are 0 there), so a root a hair past an
//! interval's end (the solvers' slack, 10⁻⁹ of the interval) is the next
//! interval's root too.
//!
//! Where it fails (docs/STABILITY.md): `laguerre`'s misses of the quartic
//! (four fixed starts, four iterations) leave holes, worst where the ray
//! grazes the surface (a double root) and where two roots of one interval
//! lie close; the robust solver reports a tangency as a double root.

use super::sweep::{polish, solve, JOINT_SLACK, RESIDUAL_TOL};
use super::Near;
use crate::options::Options;
use crate::types::{BlobComponent, BlobShape, BoundingBox, DVec3, LocalHit, Ray, MAXCOMPONENTS};

/// A component adds to the field only where it has a sphere and a
/// strength.
fn counts(c: &BlobComponent) -> bool {
    c.radius > 0.0 && c.strength != 0.0
}

/// The components that can raise the field: their spheres hold the
/// surface (outside them the field is ≤ 0 < T).
fn raises(c: &BlobComponent) -> bool {
    c.radius > 0.0 && c.strength > 0.0
}

/// The box, in the blob's local frame, of the spheres of its components
/// of positive strength, which hold its surface; `None` when there are
/// none (the blob has no surface).
pub fn blob_box(shape: &BlobShape) -> Option<BoundingBox> {
    let b = shape
        .components
        .iter()
        .filter(|c| raises(c))
        .fold(BoundingBox::EMPTY, |b, c| {
            b.holding(c.centre - DVec3::splat(c.radius))
                .holding(c.centre + DVec3::splat(c.radius))
        });
    (b.xmin <= b.xmax).then_some(b)
}

/// The radius of a sphere about the local origin that holds the blob's
/// surface: the farthest reach of a component of positive strength (0
/// for a blob without surface).
pub fn blob_reach(shape: &BlobShape) -> f64 {
    shape
        .components
        .iter()
        .filter(|c| raises(c))
        .fold(0.0f64, |m, c| m.max(c.centre.length() + c.radius))
}

/// The field at `p` less the threshold, and its gradient.
pub fn field(shape: &BlobShape, p: DVec3) -> (f64, DVec3) {
    let (mut f, mut grad) = (-shape.threshold, DVec3::ZERO);
    for c in shape.components.iter().filter(|c| counts(c)) {
        let w = p - c.centre;
        let r2 = c.radius * c.radius;
        let q = 1.0 - w.length_squared() / r2;
        if q > 0.0 {
            f += c.strength * q * q;
            grad -= 4.0 * c.strength * q / r2 * w;
        }
    }
    (f, grad)
}

/// A component's chord: where the ray enters and leaves its sphere, and
/// which component it is.
#[derive(Clone, Copy, Default)]
struct Chord {
    enter: f64,
    leave: f64,
    k: u8,
}

// A component's index fits the byte its chord keeps it in.
const _: () = assert!(MAXCOMPONENTS <= u8::MAX as usize + 1);

/// The nearest hit of a ray with the blob beyond `tmin`, in its local
/// frame (see the module doc); `reach` is the radius of a sphere about the
/// local origin holding it ([`blob_reach`], or the object's `radius`),
/// about which the ray is taken [`Near`] the blob. `searched` counts the
/// quartics the solvers searched past their pre-tests.
pub fn intersect_blob(
    shape: &BlobShape,
    reach: f64,
    ray: &Ray,
    tmin: f64,
    opts: &Options,
    searched: &mut u64,
) -> Option<LocalHit> {
    query(shape, reach, ray, tmin, f64::INFINITY, opts, searched)
}

/// Does the blob stand on the ray at some t with `tmin` < t < `tmax`?
/// The shadow ray's question: the answer of [`intersect_blob`] (its
/// nearest hit lies before `tmax`), its intervals searched no further
/// than `tmax`.
pub fn blob_blocks(
    shape: &BlobShape,
    reach: f64,
    ray: &Ray,
    tmin: f64,
    tmax: f64,
    opts: &Options,
    searched: &mut u64,
) -> bool {
    query(shape, reach, ray, tmin, tmax, opts, searched).is_some_and(|h| h.t < tmax)
}

/// The first hit beyond `tmin`, its intervals searched while they begin
/// before `tmax` (the caller's t).
fn query(
    shape: &BlobShape,
    reach: f64,
    ray: &Ray,
    tmin: f64,
    tmax: f64,
    opts: &Options,
    searched: &mut u64,
) -> Option<LocalHit> {
    if !ray.origin.is_finite() || !ray.dir.is_finite() || ray.dir == DVec3::ZERO || tmin.is_nan() {
        return None;
    }
    let near = Near::of(ray, tmin, DVec3::ZERO, reach * reach);
    let (o, d, tmin) = (near.ray.origin, near.ray.dir, near.tmin);
    let limit = tmax - near.shift;
    let (chords, count) = chords(shape, o, d, tmin)?;
    let chords = &chords[..count];
    // The intervals' ends: every chord's ends, sorted.
    let mut ends = [0.0f64; 2 * MAXCOMPONENTS];
    for (k, c) in chords.iter().enumerate() {
        ends[2 * k] = c.enter;
        ends[2 * k + 1] = c.leave;
    }
    let ends = &mut ends[..2 * count];
    ends.sort_unstable_by(f64::total_cmp);
    for w in ends.windows(2) {
        let (a, b) = (w[0].max(tmin), w[1]);
        if a >= limit {
            break;
        }
        if !(b > a) {
            continue;
        }
        // The components whose chords span the interval.
        let active = chords.iter().filter(|c| c.enter <= w[0] && c.leave >= b);
        let mut raised = false;
        let mut poly = [0.0f64; 7];
        poly[0] = -shape.threshold;
        let (start, step) = (o + a * d, d * (b - a));
        let dd = step.length_squared();
        for c in active {
            let comp = &shape.components[c.k as usize];
            raised |= comp.strength > 0.0;
            let inv = 1.0 / (comp.radius * comp.radius);
            let w = start - comp.centre;
            // q(s) = 1 − |w + s·step|²/R² = γ + β s + α s².
            let (g, be, al) = (1.0 - w.length_squared() * inv, -2.0 * w.dot(step) * inv, -dd * inv);
            let st = comp.strength;
            poly[0] += st * g * g;
            poly[1] += st * 2.0 * g * be;
            poly[2] += st * (be * be + 2.0 * al * g);
            poly[3] += st * 2.0 * al * be;
            poly[4] += st * al * al;
        }
        if !raised {
            continue;
        }
        if let Some(s) = first_root(&poly, opts, searched) {
            let t = a + s * (b - a);
            if t > tmin {
                let point = o + t * d;
                return near.back(Some(LocalHit {
                    t,
                    point,
                    normal: outward(shape, point, d),
                }));
            }
        }
    }
    None
}

/// The chords of the components that count ([`counts`]) and that the ray
/// meets beyond `tmin`; `None` when none of them raises the field.
fn chords(shape: &BlobShape, o: DVec3, d: DVec3, tmin: f64) -> Option<([Chord; MAXCOMPONENTS], usize)> {
    let a = d.length_squared();
    let mut out = [Chord::default(); MAXCOMPONENTS];
    let (mut count, mut raised) = (0, false);
    for (k, c) in shape.components.iter().enumerate().take(MAXCOMPONENTS) {
        if !counts(c) {
            continue;
        }
        let oc = o - c.centre;
        let half_b = oc.dot(d);
        let cc = oc.length_squared() - c.radius * c.radius;
        let disc = half_b * half_b - a * cc;
        if !(disc > 0.0) {
            continue;
        }
        // The numerically stable pair of roots (as the sphere's).
        let q = -(half_b + half_b.signum() * disc.sqrt());
        if q == 0.0 {
            continue;
        }
        let (t0, t1) = (q / a, cc / q);
        let (enter, leave) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
        if leave <= tmin {
            continue;
        }
        raised |= c.strength > 0.0;
        out[count] = Chord {
            enter,
            leave,
            k: k as u8,
        };
        count += 1;
    }
    raised.then_some((out, count))
}

/// The least root in [−δ, 1 + δ] (δ the solvers' slack) of the quartic
/// `poly` (ascending) that is a root: polished, and |p(s)| within
/// [`RESIDUAL_TOL`] of the size of its terms (a spurious root of
/// `laguerre`, erratum 7, is not).
fn first_root(poly: &[f64; 7], opts: &Options, searched: &mut u64) -> Option<f64> {
    let found = solve(4, poly, opts, searched);
    let scale: f64 = poly[..5].iter().map(|c| c.abs()).sum();
    let mut best: Option<f64> = None;
    for &s in &found.s[..found.count] {
        let s = polish(4, poly, s);
        let f = (((poly[4] * s + poly[3]) * s + poly[2]) * s + poly[1]) * s + poly[0];
        let inside = (-JOINT_SLACK..=1.0 + JOINT_SLACK).contains(&s);
        if inside && f.abs() <= RESIDUAL_TOL * scale && best.is_none_or(|b| s < b) {
            best = Some(s);
        }
    }
    best
}

/// The unit outward normal at `p` on the surface: −∇F, normalised; where
/// the gradient vanishes (a point of the surface where it has no tangent
/// plane, as where two equal components just touch), the ray's reverse.
fn outward(shape: &BlobShape, p: DVec3, d: DVec3) -> DVec3 {
    let (_, grad) = field(shape, p);
    let n = -grad;
    let len = n.length();
    if len > 0.0 && len.is_finite() {
        n / len
    } else {
        -d.normalize()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Solver;

    fn one(radius: f64, strength: f64, threshold: f64) -> BlobShape {
        BlobShape {
            threshold,
            components: vec![BlobComponent {
                centre: DVec3::ZERO,
                radius,
                strength,
            }],
        }
    }

    fn opts(solver: Solver) -> Options {
        Options {
            solver,
            ..Options::default()
        }
    }

    /// One component is a sphere: S(1 − r²/R²)² = T at r = R·√(1 − √(T/S)).
    #[test]
    fn one_component_is_a_sphere() {
        let b = one(2.0, 1.0, 0.25);
        let r = 2.0 * (1.0f64 - 0.5).sqrt();
        for solver in [Solver::Laguerre, Solver::Robust] {
            let ray = Ray::new(DVec3::new(0.0, -10.0, 0.0), DVec3::Y);
            let h = intersect_blob(&b, blob_reach(&b), &ray, 1e-9, &opts(solver), &mut 0).unwrap();
            assert!((h.t - (10.0 - r)).abs() < 1e-9, "{solver:?}: {}", h.t);
            assert!((h.normal - DVec3::NEG_Y).length() < 1e-9);
            // From inside: the far side, the normal outward.
            let ray = Ray::new(DVec3::ZERO, DVec3::Z);
            let h = intersect_blob(&b, blob_reach(&b), &ray, 1e-9, &opts(solver), &mut 0).unwrap();
            assert!((h.t - r).abs() < 1e-9, "{solver:?}: {}", h.t);
            assert!((h.normal - DVec3::Z).length() < 1e-9);
            // Passing outside the surface but through the sphere: a miss.
            let ray = Ray::new(DVec3::new(1.6, -10.0, 0.0), DVec3::Y);
            assert!(intersect_blob(&b, blob_reach(&b), &ray, 1e-9, &opts(solver), &mut 0).is_none());
        }
        // A component weaker than the threshold has no surface.
        let weak = one(2.0, 0.2, 0.25);
        let ray = Ray::new(DVec3::new(0.0, -10.0, 0.0), DVec3::Y);
        assert!(intersect_blob(&weak, 2.0, &ray, 1e-9, &opts(Solver::Robust), &mut 0).is_none());
    }

    /// Two components: the surface between them bridges (the field is the
    /// sum), and a negative component carves a hole.
    #[test]
    fn components_sum_and_carve() {
        let c = |x: f64, strength: f64| BlobComponent {
            centre: DVec3::new(x, 0.0, 0.0),
            radius: 1.0,
            strength,
        };
        let pair = BlobShape {
            threshold: 0.5,
            components: vec![c(-0.6, 1.0), c(0.6, 1.0)],
        };
        // Down through the middle: each alone gives (1 − 0.36)² = 0.41 < T
        // at x = 0, the two 0.82 > T: a hit.
        let down = Ray::new(DVec3::new(0.0, 0.0, 5.0), DVec3::NEG_Z);
        for solver in [Solver::Laguerre, Solver::Robust] {
            let h = intersect_blob(&pair, blob_reach(&pair), &down, 1e-9, &opts(solver), &mut 0).unwrap();
            let (f, _) = field(&pair, h.point);
            assert!(f.abs() < 1e-9, "{solver:?}: {f}");
            assert!((h.normal - DVec3::Z).length() < 1e-9, "{}", h.normal);
        }
        let carved = BlobShape {
            threshold: 0.5,
            components: vec![c(-0.6, 1.0), c(0.6, 1.0), c(0.0, -2.0)],
        };
        assert!(intersect_blob(&carved, 2.0, &down, 1e-9, &opts(Solver::Robust), &mut 0).is_none());
    }

    /// The shadow question answers as the nearest hit before `tmax`.
    #[test]
    fn blocks_as_the_nearest_hit_before_tmax() {
        let b = one(2.0, 1.0, 0.25);
        let ray = Ray::new(DVec3::new(0.0, -10.0, 0.0), DVec3::Y);
        let o = opts(Solver::Robust);
        let at = intersect_blob(&b, 2.0, &ray, 1e-9, &o, &mut 0).unwrap().t;
        for tmax in [at - 1e-6, at + 1e-6, 5.0, 20.0, f64::INFINITY] {
            assert_eq!(blob_blocks(&b, 2.0, &ray, 1e-9, tmax, &o, &mut 0), at < tmax, "{tmax}");
        }
    }

    #[test]
    fn box_and_reach_of_the_raising_components() {
        let b = BlobShape {
            threshold: 1.0,
            components: vec![
                BlobComponent {
                    centre: DVec3::new(1.0, 0.0, 0.0),
                    radius: 0.5,
                    strength: 1.0,
                },
                BlobComponent {
                    centre: DVec3::new(-9.0, 0.0, 0.0),
                    radius: 3.0,
                    strength: -1.0,
                },
            ],
        };
        let bx = blob_box(&b).unwrap();
        assert_eq!((bx.xmin, bx.xmax, bx.ymin, bx.ymax), (0.5, 1.5, -0.5, 0.5));
        assert_eq!(blob_reach(&b), 1.5);
        assert!(blob_box(&one(1.0, -1.0, 1.0)).is_none());
    }
}

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
//! `solve`); the first root beyond `tmin` is the hit. An interval where
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
use crate::accel::{Aabb, BoxRay};
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
/// its field along the ray: q(t) = 1 − |p(t) − c|²/R² = `peak_q` −
/// `curve`·(t − `peak_t`)², the component adding `strength`·q² where q > 0.
#[derive(Clone, Copy, Default)]
struct Chord {
    enter: f64,
    leave: f64,
    peak_t: f64,
    peak_q: f64,
    curve: f64,
    strength: f64,
    /// The component's index in the blob.
    k: u8,
}

impl Chord {
    /// The most q reaches on [a, b] (within the chord).
    fn most(&self, a: f64, b: f64) -> f64 {
        let e = self.peak_t.clamp(a, b) - self.peak_t;
        self.peak_q - self.curve * e * e
    }
}

/// An end of a chord: where, which chord, and whether it begins there.
#[derive(Clone, Copy, Default)]
struct End {
    t: f64,
    chord: u8,
    enter: bool,
}

// A component's index fits the byte its chord's end keeps it in.
const _: () = assert!(MAXCOMPONENTS <= u8::MAX as usize + 1);
// A component's index is a bit of the `u64` [`chords_of`] gathers a
// [`BlobCache`]'s components in.
const _: () = assert!(MAXCOMPONENTS <= u64::BITS as usize);

/// The nearest hit of a ray with the blob beyond `tmin`, in its local
/// frame (see the module doc); `reach` is the radius of a sphere about the
/// local origin holding it ([`blob_reach`], or the object's `radius`),
/// about which the ray is taken [`Near`] the blob. `searched` counts the
/// quartics the solvers searched past their pre-tests.
pub fn intersect_blob(
    shape: &BlobShape,
    cache: Option<&BlobCache>,
    reach: f64,
    ray: &Ray,
    tmin: f64,
    opts: &Options,
    searched: &mut u64,
) -> Option<LocalHit> {
    query(shape, cache, reach, ray, tmin, f64::INFINITY, opts, searched)
}

/// The first hit beyond `tmin`, its intervals searched while they begin
/// before `tmax` (the caller's t): the shadow ray's question, whose answer
/// is whether that hit lies before `tmax` ([`intersect_blob`] asks with
/// `tmax` infinite). The chords' ends are taken in order,
/// the components whose chords span the interval up to the next end kept
/// as they come and go; an interval on which no component of positive
/// strength is active, or on which those cannot reach T even at their
/// most, is passed without a polynomial.
#[allow(clippy::too_many_arguments)]
pub fn query(
    shape: &BlobShape,
    cache: Option<&BlobCache>,
    reach: f64,
    ray: &Ray,
    tmin: f64,
    tmax: f64,
    opts: &Options,
    searched: &mut u64,
) -> Option<LocalHit> {
    let near = Near::about_origin(ray, tmin, reach)?;
    let (o, d, tmin) = (near.ray.origin, near.ray.dir, near.tmin);
    // An interval from t on holds no hit before `tmax` once t, the shift
    // added back, is past it (as the caller will compare the hit).
    let limit = (tmax, near.shift);
    // Most rays cross few components: their arrays are made that small,
    // and made again full size for a ray that crosses more.
    let found = match search::<SOME, { 2 * SOME }>(shape, cache, o, d, tmin, limit, opts, searched) {
        Ok(found) => found,
        Err(Crowded) => search::<MAXCOMPONENTS, { 2 * MAXCOMPONENTS }>(shape, cache, o, d, tmin, limit, opts, searched)
            .unwrap_or(None),
    };
    near.back(found)
}

/// The chords a ray's first arrays hold ([`search`]).
const SOME: usize = 12;

/// More chords than the arrays hold.
struct Crowded;

/// [`query`]'s search, on the ray `o + t·d` near the blob, with room for
/// `N` chords and `E` = 2·`N` ends: the hit, or `Crowded` if the ray
/// crosses more than `N` components.
#[allow(clippy::too_many_arguments)]
fn search<const N: usize, const E: usize>(
    shape: &BlobShape,
    cache: Option<&BlobCache>,
    o: DVec3,
    d: DVec3,
    tmin: f64,
    limit: (f64, f64),
    opts: &Options,
    searched: &mut u64,
) -> Result<Option<LocalHit>, Crowded> {
    let mut chords = [Chord::default(); N];
    let Some(count) = chords_of(shape, cache, o, d, tmin, &mut chords)? else {
        return Ok(None);
    };
    let chords = &chords[..count];
    let mut ends = [End::default(); E];
    for (k, c) in chords.iter().enumerate() {
        ends[2 * k] = End {
            t: c.enter,
            chord: k as u8,
            enter: true,
        };
        ends[2 * k + 1] = End {
            t: c.leave,
            chord: k as u8,
            enter: false,
        };
    }
    let ends = &mut ends[..2 * count];
    ends.sort_unstable_by(|x, y| x.t.total_cmp(&y.t));
    let mut active = [0u8; N];
    let mut live = 0;
    for w in ends.windows(2) {
        let end = w[0];
        if end.enter {
            active[live] = end.chord;
            live += 1;
        } else if let Some(i) = active[..live].iter().position(|&c| c == end.chord) {
            live -= 1;
            active[i] = active[live];
        }
        let (a, b) = (end.t.max(tmin), w[1].t);
        if a + limit.1 >= limit.0 {
            break;
        }
        if b <= a {
            continue;
        }
        let on = || active[..live].iter().map(|&c| &chords[c as usize]);
        let most: f64 = on()
            .filter(|c| c.strength > 0.0)
            .map(|c| {
                let q = c.most(a, b).max(0.0);
                c.strength * q * q
            })
            .sum();
        if most < shape.threshold || most.is_nan() {
            continue;
        }
        // The quartic in s ∈ [0, 1], t = a + s·(b − a): each component's
        // q = γ + β s + α s², squared and weighed.
        let len = b - a;
        let mut poly = [0.0f64; 7];
        poly[0] = -shape.threshold;
        for c in on() {
            let e = a - c.peak_t;
            let (g, be, al) = (
                c.peak_q - c.curve * e * e,
                -2.0 * c.curve * e * len,
                -c.curve * len * len,
            );
            let st = c.strength;
            poly[0] += st * g * g;
            poly[1] += st * 2.0 * g * be;
            poly[2] += st * (be * be + 2.0 * al * g);
            poly[3] += st * 2.0 * al * be;
            poly[4] += st * al * al;
        }
        // The least root beyond `tmin`: a ray that leaves the surface
        // finds the root it leaves at s ≈ 0, and may meet another in the
        // same interval.
        if let Some(s) = first_root(&poly, |s| a + s * len > tmin, opts, searched) {
            let t = a + s * len;
            let point = o + t * d;
            return Ok(Some(LocalHit {
                t,
                point,
                normal: outward(shape, chords, point, d),
            }));
        }
    }
    Ok(None)
}

/// The chords, into `out`, of the components that count ([`counts`]) and
/// that the ray meets beyond `tmin`, and how many; `None` when none of
/// them raises the field; `Crowded` when `out` cannot hold them. The components are those of the leaves of
/// `cache` whose boxes the ray meets, or (without one) all of them.
fn chords_of(
    shape: &BlobShape,
    cache: Option<&BlobCache>,
    o: DVec3,
    d: DVec3,
    tmin: f64,
    out: &mut [Chord],
) -> Result<Option<usize>, Crowded> {
    let a = d.length_squared();
    let inv_a = 1.0 / a;
    let (mut count, mut raised, mut crowded) = (0, false, false);
    let mut chord = |k: usize| {
        let c = &shape.components[k];
        let oc = o - c.centre;
        let half_b = oc.dot(d);
        let r2 = c.radius * c.radius;
        let cc = oc.length_squared() - r2;
        let disc = half_b * half_b - a * cc;
        if disc <= 0.0 || disc.is_nan() {
            return;
        }
        // The numerically stable pair of roots (as the sphere's).
        let q = -(half_b + half_b.signum() * disc.sqrt());
        if q == 0.0 {
            return;
        }
        let (t0, t1) = (q * inv_a, cc / q);
        let (enter, leave) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
        if leave <= tmin {
            return;
        }
        if count == out.len() {
            crowded = true;
            return;
        }
        raised |= c.strength > 0.0;
        out[count] = Chord {
            enter,
            leave,
            peak_t: -half_b * inv_a,
            peak_q: disc * inv_a / r2,
            curve: a / r2,
            strength: c.strength,
            k: k as u8,
        };
        count += 1;
    };
    match cache {
        Some(cache) => {
            // The leaves' components gathered as bits, then taken in the
            // components' order, as the loop over all finds them: the sums
            // below are then the same to the bit (and no chords sorted).
            let mut met = 0u64;
            cache.visit(&Ray::new(o, d), tmin, &mut |k| met |= 1 << k);
            while met != 0 {
                chord(met.trailing_zeros() as usize);
                met &= met - 1;
            }
        }
        None => (0..shape.components.len().min(MAXCOMPONENTS))
            .filter(|&k| counts(&shape.components[k]))
            .for_each(chord),
    }
    if crowded {
        return Err(Crowded);
    }
    Ok(raised.then_some(count))
}

/// The most components a leaf of a [`BlobCache`] holds.
const LEAF: usize = 4;

/// The nodes a walk of a [`BlobCache`] keeps waiting: one a level and the
/// one it takes, and a node over more than `LEAF` components is halved,
/// so that a tree of `LEAF`·2ᵏ components is k + 1 levels deep.
const STACK: usize = 16;
const _: () = assert!(MAXCOMPONENTS <= LEAF << (STACK - 2));

/// A node of a [`BlobCache`]: its box, and its components (a leaf: `len`
/// of them from `start` in the cache's order) or its children (the next
/// node and node `right`).
#[derive(Clone, Debug, PartialEq)]
struct BlobNode {
    bounds: Aabb,
    right: u32,
    start: u8,
    len: u8,
}

/// What is prepared for a blob before any ray: its components gathered in
/// a hierarchy of boxes (§2.1.2's clusters of bounding volumes, Fig.
/// 2.12, within one object), so that a ray tests the spheres of the
/// components near it and not all 60: halved at the median of their
/// centres along the widest axis down to leaves of at most four (`LEAF`); each
/// node's box holds its components' spheres. Made for a blob at rest
/// once, for a deforming one at each instant a ray first reaches it.
#[derive(Clone, Debug, PartialEq)]
pub struct BlobCache {
    nodes: Vec<BlobNode>,
    /// The components that count ([`counts`]), in the leaves' order.
    order: Vec<u8>,
}

impl BlobCache {
    /// The hierarchy of `shape`'s components (see the type's doc).
    pub fn new(shape: &BlobShape) -> BlobCache {
        let mut order: Vec<u8> = (0..shape.components.len().min(MAXCOMPONENTS))
            .filter(|&k| counts(&shape.components[k]))
            .map(|k| k as u8)
            .collect();
        let mut nodes = Vec::new();
        let len = order.len();
        build(shape, &mut order, 0, len, &mut nodes);
        BlobCache { nodes, order }
    }

    /// Calls `f` with each component in a leaf whose box the ray meets
    /// beyond `tmin`.
    fn visit(&self, ray: &Ray, tmin: f64, f: &mut impl FnMut(usize)) {
        let boxes = BoxRay::new(ray);
        // A node's right child waits while its left is taken: one a level.
        let mut stack = [0u32; STACK];
        let mut len = usize::from(!self.nodes.is_empty());
        while len > 0 {
            len -= 1;
            let at = stack[len] as usize;
            let node = &self.nodes[at];
            if boxes.span(&node.bounds, tmin, f64::INFINITY).is_none() {
                continue;
            }
            if node.len > 0 {
                let (start, end) = (node.start as usize, node.start as usize + node.len as usize);
                self.order[start..end].iter().for_each(|&k| f(k as usize));
            } else {
                stack[len] = node.right;
                stack[len + 1] = at as u32 + 1;
                len += 2;
            }
        }
    }
}

/// The node over `order[start..end]` and those under it, into `nodes`.
fn build(shape: &BlobShape, order: &mut [u8], start: usize, end: usize, nodes: &mut Vec<BlobNode>) {
    let c = |k: u8| &shape.components[k as usize];
    let bounds = order[start..end].iter().fold(Aabb::EMPTY, |b, &k| {
        let r = DVec3::splat(c(k).radius);
        b.union(&Aabb {
            lo: c(k).centre - r,
            hi: c(k).centre + r,
        })
    });
    let at = nodes.len();
    nodes.push(BlobNode {
        bounds,
        right: 0,
        start: start as u8,
        len: (end - start) as u8,
    });
    if end - start <= LEAF {
        return;
    }
    let centres = order[start..end].iter().fold(Aabb::EMPTY, |b, &k| {
        b.union(&Aabb {
            lo: c(k).centre,
            hi: c(k).centre,
        })
    });
    let extent = centres.hi - centres.lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    order[start..end].sort_unstable_by(|&a, &b| c(a).centre[axis].total_cmp(&c(b).centre[axis]));
    let mid = (start + end) / 2;
    nodes[at].len = 0;
    build(shape, order, start, mid, nodes);
    nodes[at].right = nodes.len() as u32;
    build(shape, order, mid, end, nodes);
}

/// The least root in [−δ, 1 + δ] (δ the solvers' slack) of the quartic
/// `poly` (ascending) that is a root, polished, and |p(s)| within
/// [`RESIDUAL_TOL`] of the size of its terms (a spurious root of
/// `laguerre`, erratum 7, is not), and that `beyond` keeps.
fn first_root(poly: &[f64; 7], beyond: impl Fn(f64) -> bool, opts: &Options, searched: &mut u64) -> Option<f64> {
    let found = solve(4, poly, opts, searched);
    let scale: f64 = poly[..5].iter().map(|c| c.abs()).sum();
    let mut best: Option<f64> = None;
    for &s in &found.s[..found.count] {
        let s = polish(4, poly, s);
        let f = (((poly[4] * s + poly[3]) * s + poly[2]) * s + poly[1]) * s + poly[0];
        let inside = (-JOINT_SLACK..=1.0 + JOINT_SLACK).contains(&s);
        if inside && f.abs() <= RESIDUAL_TOL * scale && beyond(s) && best.is_none_or(|b| s < b) {
            best = Some(s);
        }
    }
    best
}

/// The unit outward normal at `p` on the surface: −∇F over the components
/// of `chords` (those the ray meets, which hold every one whose sphere
/// holds `p`), normalised; where the gradient vanishes (a point of the
/// surface where it has no tangent plane, as where two equal components
/// just touch), the ray's reverse.
fn outward(shape: &BlobShape, chords: &[Chord], p: DVec3, d: DVec3) -> DVec3 {
    let mut n = DVec3::ZERO;
    for ch in chords {
        let c = &shape.components[ch.k as usize];
        let w = p - c.centre;
        let r2 = c.radius * c.radius;
        let q = 1.0 - w.length_squared() / r2;
        if q > 0.0 {
            n += 4.0 * c.strength * q / r2 * w;
        }
    }
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

    /// `field` is POV-Ray's sum, each component s·(1 − r²/R²)² inside its
    /// sphere, less T, and its gradient −4·s·q/R²·(p − c): values worked by
    /// hand at a point two components reach and a third does not (the
    /// other tests read `field` as their oracle, so it is pinned here).
    #[test]
    fn field_is_the_sum_of_the_components_less_the_threshold() {
        let c = |centre: DVec3, radius: f64, strength: f64| BlobComponent {
            centre,
            radius,
            strength,
        };
        let shape = BlobShape {
            threshold: 0.3,
            components: vec![
                c(DVec3::X, 2.0, 1.5),
                c(DVec3::Y, 1.0, -0.5),
                c(DVec3::new(5.0, 0.0, 0.0), 1.0, 2.0),
            ],
        };
        // q = 0.875 and 0.5: 1.5·0.875² − 0.5·0.5² − 0.3; the gradients
        // −1.3125·(−0.5, 0.5, 0) and 1.0·(0.5, −0.5, 0).
        let (f, grad) = field(&shape, DVec3::new(0.5, 0.5, 0.0));
        assert!((f - 0.7234375).abs() < 1e-15, "{f}");
        assert!((grad - DVec3::new(1.15625, -1.15625, 0.0)).length() < 1e-15, "{grad}");
        // Outside every sphere the field is −T and flat.
        assert_eq!(field(&shape, DVec3::new(0.0, -3.0, 0.0)), (-0.3, DVec3::ZERO));
    }

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
            let h = intersect_blob(&b, None, blob_reach(&b), &ray, 1e-9, &opts(solver), &mut 0).unwrap();
            assert!((h.t - (10.0 - r)).abs() < 1e-9, "{solver:?}: {}", h.t);
            assert!((h.normal - DVec3::NEG_Y).length() < 1e-9);
            // From inside: the far side, the normal outward.
            let ray = Ray::new(DVec3::ZERO, DVec3::Z);
            let h = intersect_blob(&b, None, blob_reach(&b), &ray, 1e-9, &opts(solver), &mut 0).unwrap();
            assert!((h.t - r).abs() < 1e-9, "{solver:?}: {}", h.t);
            assert!((h.normal - DVec3::Z).length() < 1e-9);
            // Passing outside the surface but through the sphere: a miss.
            let ray = Ray::new(DVec3::new(1.6, -10.0, 0.0), DVec3::Y);
            assert!(intersect_blob(&b, None, blob_reach(&b), &ray, 1e-9, &opts(solver), &mut 0).is_none());
        }
        // A component weaker than the threshold has no surface.
        let weak = one(2.0, 0.2, 0.25);
        let ray = Ray::new(DVec3::new(0.0, -10.0, 0.0), DVec3::Y);
        assert!(intersect_blob(&weak, None, 2.0, &ray, 1e-9, &opts(Solver::Robust), &mut 0).is_none());
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
            let h = intersect_blob(&pair, None, blob_reach(&pair), &down, 1e-9, &opts(solver), &mut 0).unwrap();
            let (f, _) = field(&pair, h.point);
            assert!(f.abs() < 1e-9, "{solver:?}: {f}");
            assert!((h.normal - DVec3::Z).length() < 1e-9, "{}", h.normal);
        }
        let carved = BlobShape {
            threshold: 0.5,
            components: vec![c(-0.6, 1.0), c(0.6, 1.0), c(0.0, -2.0)],
        };
        assert!(intersect_blob(&carved, None, 2.0, &down, 1e-9, &opts(Solver::Robust), &mut 0).is_none());
    }

    /// A ray that leaves the surface (its `tmin` a hair past a root) meets
    /// the next root of the same interval: two lobes, their components'
    /// spheres overlapping over the gap between them, so that one quartic
    /// holds both the root the ray leaves and the one it meets next.
    #[test]
    fn a_ray_leaving_the_surface_meets_the_next_root_of_its_interval() {
        let c = |x: f64| BlobComponent {
            centre: DVec3::new(x, 0.0, 0.0),
            radius: 2.5,
            strength: 1.0,
        };
        // The field on the x axis crosses 0.9 at ±2.066 and ±0.923.
        let b = BlobShape {
            threshold: 0.9,
            components: vec![c(-1.5), c(1.5)],
        };
        let ray = Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X);
        for solver in [Solver::Laguerre, Solver::Robust] {
            let o = opts(solver);
            // From inside lobe A (x = −1.5): its far side, in the gap.
            let inside = intersect_blob(&b, None, 4.0, &ray, 3.5, &o, &mut 0).unwrap();
            assert!(
                inside.point.x < -0.5 && inside.point.x > -1.0,
                "{solver:?}: {}",
                inside.point.x
            );
            // From a hair past that root: lobe B's near side, mirrored.
            let next = intersect_blob(&b, None, 4.0, &ray, inside.t + 1e-12, &o, &mut 0).unwrap();
            assert!(
                (next.point.x + inside.point.x).abs() < 1e-9,
                "{solver:?}: {}",
                next.point.x
            );
        }
    }

    /// The shadow question answers as the nearest hit before `tmax`.
    #[test]
    fn blocks_as_the_nearest_hit_before_tmax() {
        let b = one(2.0, 1.0, 0.25);
        let ray = Ray::new(DVec3::new(0.0, -10.0, 0.0), DVec3::Y);
        let o = opts(Solver::Robust);
        let at = intersect_blob(&b, None, 2.0, &ray, 1e-9, &o, &mut 0).unwrap().t;
        for tmax in [at - 1e-6, at + 1e-6, 5.0, 20.0, f64::INFINITY] {
            assert_eq!(
                query(&b, None, 2.0, &ray, 1e-9, tmax, &o, &mut 0).is_some_and(|h| h.t < tmax),
                at < tmax,
                "{tmax}"
            );
        }
    }

    /// The hierarchy of components finds the hits the loop over all of
    /// them finds, to the bit: a blob of 60 components on a ring, one in
    /// four of negative strength, rays from all around.
    #[test]
    fn the_hierarchy_meets_what_the_loop_meets() {
        let b = BlobShape {
            threshold: 0.4,
            components: (0..60)
                .map(|k| {
                    let a = k as f64 * std::f64::consts::TAU / 60.0;
                    BlobComponent {
                        centre: DVec3::new(2.0 * a.cos(), 2.0 * a.sin(), 0.3 * (3.0 * a).sin()),
                        radius: 0.5 + 0.1 * (k % 3) as f64,
                        strength: if k % 4 == 3 { -0.5 } else { 1.0 },
                    }
                })
                .collect(),
        };
        let cache = BlobCache::new(&b);
        let o = opts(Solver::Robust);
        let mut hits = 0;
        for k in 0..3000u64 {
            let r = |j: u64| 2.0 * crate::hash::hashed_uniform(4 * k + j) - 1.0;
            let from = DVec3::new(r(0), r(1), r(2)).normalize() * 6.0;
            let to = DVec3::new(2.5 * r(3), 2.5 * r(1) * r(2), 0.5 * r(0));
            let ray = Ray::new(from, (to - from).normalize());
            let loose = intersect_blob(&b, None, blob_reach(&b), &ray, 1e-9, &o, &mut 0);
            let kept = intersect_blob(&b, Some(&cache), blob_reach(&b), &ray, 1e-9, &o, &mut 0);
            assert_eq!(loose, kept, "ray {k}");
            hits += kept.is_some() as usize;
        }
        assert!(hits > 500, "{hits}");
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

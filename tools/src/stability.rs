//! `tools stability`: the root solvers on hard cases, docs/STABILITY.md.
//!
//! Two kinds of family, every case built from a fixed seed:
//! - root families: constructed polynomials with known roots, solved on
//!   [0, 1] by `laguerre` (listing and thesis fidelity) and by
//!   `real_roots` (the robust solver);
//! - geometric families: constructed rays against constructed sweeps,
//!   intersected by `intersect_sweep` with each solver, where the true
//!   first hit is known by construction (a ray tangent to, or aimed from
//!   outside at a point of, a convex sweep; a cap or an apex) or
//!   analytically (rotation sweeps of straight segments, which are exact
//!   cylinders and cones).
//!
//! Counted per family and method: the cases, the true roots (hits),
//! those missed, the spurious ones, the worst error of those found, and
//! the time of one solve.

use std::fmt::Write;
use std::path::Path;
use std::time::Instant;

use raytrace::proc::robust::real_roots;
use raytrace::proc::sweep::{laguerre, Root, LAGUERRE_ROOTS};
use raytrace::shapes::sweep::intersect_sweep;
use raytrace::types::{Coeff, DVec3, Fidelity, Options, PrimitiveClass, Ray, Shape, Solver, SweepShape};

use crate::measure::median;

/// A root counts as found within this distance of the true root.
pub const ROOT_TOL: f64 = 1e-6;
/// A found root that is not within [`ROOT_TOL`] of a true root but within
/// this is rough (found, inaccurately); farther, spurious.
pub const ROUGH_TOL: f64 = 1e-3;
/// A hit counts as the true one within this distance, relative to the
/// object's size.
pub const HIT_TOL: f64 = 1e-6;
/// How far inside the tangent the grazing rays pass, relative to the size.
pub const GRAZE: f64 = 1e-13;

/// The three methods compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    LaguerreListing,
    LaguerreThesis,
    Robust,
}

pub const METHODS: [Method; 3] = [Method::LaguerreListing, Method::LaguerreThesis, Method::Robust];

impl Method {
    pub fn label(self) -> &'static str {
        match self {
            Method::LaguerreListing => "laguerre, listing",
            Method::LaguerreThesis => "laguerre, thesis",
            Method::Robust => "robust",
        }
    }

    pub fn options(self) -> Options {
        let (fidelity, solver) = match self {
            Method::LaguerreListing => (Fidelity::Listing, Solver::Laguerre),
            Method::LaguerreThesis => (Fidelity::Thesis, Solver::Laguerre),
            Method::Robust => (Fidelity::Thesis, Solver::Robust),
        };
        Options {
            fidelity,
            solver,
            ..Options::default()
        }
    }
}

/// xorshift64*: fixed seeds, so every run builds the same cases.
pub struct Rng(pub u64);

impl Rng {
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.uniform()
    }
    pub fn sign(&mut self) -> f64 {
        if self.uniform() < 0.5 {
            -1.0
        } else {
            1.0
        }
    }
}

pub use raytrace::proc::robust::poly_from_roots as poly;

// ---------------------------------------------------------------------------
// Root families

/// A polynomial of degree `n` and its distinct roots in [0, 1].
#[derive(Clone, Debug)]
pub struct PolyCase {
    pub n: usize,
    pub a: [f64; 7],
    pub roots: Vec<f64>,
}

impl PolyCase {
    /// The polynomial with these roots (a repeated value is a multiple
    /// root, listed once among the true roots).
    pub fn new(all_roots: &[f64]) -> PolyCase {
        let mut roots: Vec<f64> = all_roots.iter().copied().filter(|x| (0.0..=1.0).contains(x)).collect();
        roots.sort_by(f64::total_cmp);
        roots.dedup();
        PolyCase {
            n: all_roots.len(),
            a: poly(all_roots, 1.0),
            roots,
        }
    }
}

/// A family of constructed polynomials.
pub struct PolyFamily {
    pub name: String,
    pub cases: Vec<PolyCase>,
}

/// `count` roots outside [0, 1], in [−1, −0.05] ∪ [1.05, 2].
fn outside(rng: &mut Rng, count: usize) -> Vec<f64> {
    (0..count)
        .map(|_| {
            if rng.uniform() < 0.5 {
                rng.range(-1.0, -0.05)
            } else {
                rng.range(1.05, 2.0)
            }
        })
        .collect()
}

/// Values in [lo, hi] at least `gap` from each other and from `taken`.
fn spread(rng: &mut Rng, count: usize, lo: f64, hi: f64, gap: f64, taken: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(count);
    while out.len() < count {
        let x = rng.range(lo, hi);
        if out.iter().chain(taken).all(|y| (x - y).abs() >= gap) {
            out.push(x);
        }
    }
    out
}

/// The root families, `per` polynomials each, for degrees 3 and 6.
pub fn poly_families(per: usize) -> Vec<PolyFamily> {
    let mut fams = Vec::new();
    for n in [3usize, 6] {
        let deg = if n == 3 { "cubic" } else { "sextic" };
        // For comparison: every root in [0, 1], at least 0.1 apart.
        let mut rng = Rng(0x5EED_0001 + n as u64);
        fams.push(PolyFamily {
            name: format!("separated roots, {deg} (for comparison)"),
            cases: (0..per)
                .map(|_| PolyCase::new(&spread(&mut rng, n, 0.05, 0.98, 0.1, &[])))
                .collect(),
        });
        // Double roots (a grazing ray): d twice in [0.05, 0.95], the others
        // at least 0.05 from it, half of them inside.
        let mut rng = Rng(0x5EED_0002 + n as u64);
        fams.push(PolyFamily {
            name: format!("double roots, {deg}"),
            cases: (0..per)
                .map(|_| {
                    let d = rng.range(0.05, 0.95);
                    let inside = (n - 2) / 2;
                    let mut r = vec![d, d];
                    r.extend(spread(&mut rng, inside, 0.0, 1.0, 0.05, &[d]));
                    r.extend(outside(&mut rng, n - 2 - inside));
                    PolyCase::new(&r)
                })
                .collect(),
        });
        // Near-double roots: d and d + δ, δ of one decade.
        for gap in [1e-3f64, 1e-5, 1e-7] {
            let mut rng = Rng(0x5EED_0003 + n as u64 + (gap.log10().abs() as u64) * 16);
            fams.push(PolyFamily {
                name: format!("near-double roots {gap:.0e} apart, {deg}"),
                cases: (0..per)
                    .map(|_| {
                        let d = rng.range(0.05, 0.9);
                        let delta = gap * rng.range(1.0, 10.0);
                        let mut r = vec![d, d + delta];
                        r.extend(spread(&mut rng, n - 2, 0.0, 1.0, 0.05, &[d, d + delta]));
                        PolyCase::new(&r)
                    })
                    .collect(),
            });
        }
        // Clustered roots: three within 0.002 (spacing 0.0003–0.001), the
        // others apart from the cluster.
        let mut rng = Rng(0x5EED_0004 + n as u64);
        fams.push(PolyFamily {
            name: format!("clustered roots (3 within 0.002), {deg}"),
            cases: (0..per)
                .map(|_| {
                    let c = rng.range(0.1, 0.9);
                    let c2 = c + rng.range(3e-4, 1e-3);
                    let c3 = c2 + rng.range(3e-4, 1e-3);
                    let mut r = vec![c, c2, c3];
                    r.extend(spread(&mut rng, n - 3, 0.0, 1.0, 0.05, &[c, c3]));
                    PolyCase::new(&r)
                })
                .collect(),
        });
    }
    fams
}

/// The roots a method finds on [0, 1], each with its multiplicity (1 for
/// `laguerre`, which has none).
pub fn solve(method: Method, case: &PolyCase) -> Vec<(f64, u8)> {
    match method {
        Method::LaguerreListing | Method::LaguerreThesis => {
            let mut root = [Root::default(); LAGUERRE_ROOTS];
            let total = laguerre(case.n, &case.a, 1.0, 0.0, &mut root, method.options().fidelity);
            root[..total].iter().map(|r| (r.a, 1)).collect()
        }
        Method::Robust => {
            let r = real_roots(case.n, &case.a, 0.0, 1.0);
            (0..r.count).map(|i| (r.x[i], r.multiplicity[i])).collect()
        }
    }
}

/// How found roots match the true ones: (missed, rough, spurious, worst
/// error). Closest pairs within `tol` are matched first; a true root takes
/// one found root, a found root takes as many true roots as its
/// multiplicity (the robust solver reports two roots closer than rounding
/// can part as one double root). An unmatched found root within `rough`
/// of a true root is rough, farther from every true root spurious.
pub fn match_roots(truth: &[f64], found: &[(f64, u8)], tol: f64, rough: f64) -> (usize, usize, usize, f64) {
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, t) in truth.iter().enumerate() {
        for (j, f) in found.iter().enumerate() {
            let e = (t - f.0).abs();
            if e <= tol {
                pairs.push((e, i, j));
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut true_used = vec![false; truth.len()];
    let mut room: Vec<u8> = found.iter().map(|f| f.1.max(1)).collect();
    let mut matched_found = vec![false; found.len()];
    let mut worst = 0.0f64;
    for (e, i, j) in pairs {
        if !true_used[i] && room[j] > 0 {
            true_used[i] = true;
            room[j] -= 1;
            matched_found[j] = true;
            worst = worst.max(e);
        }
    }
    let missed = true_used.iter().filter(|u| !**u).count();
    let (mut n_rough, mut spurious) = (0, 0);
    for (j, f) in found.iter().enumerate() {
        if !matched_found[j] {
            if truth.iter().any(|t| (t - f.0).abs() <= rough) {
                n_rough += 1;
            } else {
                spurious += 1;
            }
        }
    }
    (missed, n_rough, spurious, worst)
}

// ---------------------------------------------------------------------------
// Geometric families

/// A sweep for the geometric families, prepared as a renderer would.
#[derive(Clone, Debug)]
pub struct TestSweep {
    pub name: String,
    pub class: PrimitiveClass,
    pub sweep: SweepShape,
    /// The largest coordinate of its box: the scale of the hit tolerance.
    pub size: f64,
}

/// A sweep from a deck record: `class` and `curve` as the deck spells
/// them, the control points, length and scale; at the origin, axis z.
pub fn test_sweep(
    name: &'static str,
    class: &str,
    curve: &str,
    points: &[[f64; 2]],
    length: f64,
    scale: f64,
) -> TestSweep {
    let mut deck = String::from(
        "view eye 0 -10 0 look 0 0 0 screen 4 distance 5\nimage 8 8 mask 1\n\
         surface s opaque color 1 1 1 ka 0 kd 1 ks 0 kt 0\n",
    );
    let _ = write!(deck, "sweep obj s {class} {curve} at 0 0 0");
    if class != "rotation" {
        let _ = write!(deck, " length {length:.17}");
    }
    if class == "conic" {
        let _ = write!(deck, " scale {scale:.17}");
    }
    deck.push('\n');
    for p in points {
        let _ = writeln!(deck, "{:.17} {:.17}", p[0], p[1]);
    }
    deck.push_str("end\n");
    let mut scene = crate::decks::load_source(&deck, name, Path::new("."), Fidelity::Thesis)
        .unwrap_or_else(|e| panic!("the constructed sweep {name} is a valid deck: {e}"));
    raytrace::raytrace::prepare(&mut scene, &Options::default())
        .unwrap_or_else(|e| panic!("the constructed sweep {name} prepares: {e}"));
    let obj = scene.objects.pop().expect("one object");
    let Shape::Sweep(sweep) = obj.shape else {
        panic!("{name} is a sweep")
    };
    let size = box_size(&sweep);
    TestSweep {
        name: name.to_string(),
        class: obj.class,
        sweep,
        size,
    }
}

/// The largest coordinate of a sweep's box.
fn box_size(sweep: &SweepShape) -> f64 {
    let b = &sweep.bbox;
    [b.xmin, b.xmax, b.ymin, b.ymax, b.zmin, b.zmax]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// 12 B-spline points whose curve passes through radius `r` at the
/// joints (a joint is (P_i + 4P_{i+1} + P_{i+2})/6): a circle within
/// 0.2 % of r between them, convex.
pub fn circle_points(r: f64) -> Vec<[f64; 2]> {
    let theta = std::f64::consts::TAU / 12.0;
    let rho = r * 6.0 / (4.0 + 2.0 * theta.cos());
    (0..12)
        .map(|j| {
            let a = theta * j as f64;
            [rho * a.cos(), rho * a.sin()]
        })
        .collect()
}

/// A unit sphere as a rotation sweep: two Bezier quarter arcs from pole to
/// pole, then down the axis. Convex; the poles and the equator are joints.
pub fn sphere_points() -> Vec<[f64; 2]> {
    let k = 4.0 / 3.0 * (2f64.sqrt() - 1.0);
    vec![
        [0.0, -1.0],
        [k, -1.0],
        [1.0, -k],
        [1.0, 0.0],
        [1.0, k],
        [k, 1.0],
        [0.0, 1.0],
        [0.0, 1.0 / 3.0],
        [0.0, -1.0 / 3.0],
    ]
}

/// A closed polygon as a Bezier contour of straight segments (the inner
/// control points at the thirds of each side).
pub fn straight_bezier(corners: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut out = Vec::new();
    for (i, p) in corners.iter().enumerate() {
        let q = corners[(i + 1) % corners.len()];
        for k in 0..3 {
            let f = k as f64 / 3.0;
            out.push([p[0] + (q[0] - p[0]) * f, p[1] + (q[1] - p[1]) * f]);
        }
    }
    out
}

/// The sweeps of the geometric families.
pub struct Sweeps {
    /// Translation of the B-spline circle, radius 1, length 2.
    pub circle: TestSweep,
    /// Conic of the same circle, length 2, scale 0.5 (apex at z = 4).
    pub frustum: TestSweep,
    /// Conic of the same circle, length 2, scale 0 (apex at z = 2).
    pub cone: TestSweep,
    /// Rotation of two Bezier quarter arcs: a unit sphere.
    pub sphere: TestSweep,
    /// Translation of a straight-sided square, side 2, length 2: exact.
    pub square: TestSweep,
    /// Rotation of a rectangle: an exact cylinder, radius 1, 0 ≤ z ≤ 2.
    pub cylinder_r: TestSweep,
    /// Rotation of a triangle: an exact cone, radius 1 − z/2, 0 ≤ z ≤ 2.
    pub cone_r: TestSweep,
}

impl Sweeps {
    pub fn new() -> Sweeps {
        Sweeps {
            circle: test_sweep("circle", "translation", "bspline", &circle_points(1.0), 2.0, 1.0),
            frustum: test_sweep("frustum", "conic", "bspline", &circle_points(1.0), 2.0, 0.5),
            cone: test_sweep("cone", "conic", "bspline", &circle_points(1.0), 2.0, 0.0),
            sphere: test_sweep("sphere", "rotation", "bezier", &sphere_points(), 0.0, 1.0),
            square: test_sweep(
                "square",
                "translation",
                "bezier",
                &straight_bezier(&[[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]),
                2.0,
                1.0,
            ),
            cylinder_r: test_sweep(
                "cylinder",
                "rotation",
                "bezier",
                &straight_bezier(&[[0.0, 0.0], [1.0, 0.0], [1.0, 2.0], [0.0, 2.0]]),
                0.0,
                1.0,
            ),
            cone_r: test_sweep(
                "cone-r",
                "rotation",
                "bezier",
                &straight_bezier(&[[0.0, 0.0], [1.0, 0.0], [0.0, 2.0]]),
                0.0,
                1.0,
            ),
        }
    }
}

impl Default for Sweeps {
    fn default() -> Self {
        Self::new()
    }
}

fn ev(c: &Coeff, s: f64) -> f64 {
    ((c.a * s + c.b) * s + c.c) * s + c.d
}
fn ev1(c: &Coeff, s: f64) -> f64 {
    (3.0 * c.a * s + 2.0 * c.b) * s + c.c
}

/// A ray against a sweep, and its true first hit (the ray parameter t,
/// the ray's direction being unit), if any.
#[derive(Clone, Debug)]
pub struct RayCase<'a> {
    pub sweep: &'a TestSweep,
    pub ray: Ray,
    pub truth: Option<f64>,
}

/// A family of constructed rays.
pub struct RayFamily<'a> {
    pub name: String,
    /// How the true hit is known.
    pub truth: &'static str,
    pub cases: Vec<RayCase<'a>>,
}

/// The analytic capped cylinder x² + y² ≤ r², 0 ≤ z ≤ len: the first t > 0.
pub fn cylinder_truth(r: f64, len: f64, ray: &Ray) -> Option<f64> {
    let (o, d) = (ray.origin, ray.dir);
    let mut best: Option<f64> = None;
    let mut take = |t: f64| {
        if t > 1e-9 && best.is_none_or(|b| t < b) {
            best = Some(t);
        }
    };
    let a = d.x * d.x + d.y * d.y;
    let b = 2.0 * (o.x * d.x + o.y * d.y);
    let c = o.x * o.x + o.y * o.y - r * r;
    let disc = b * b - 4.0 * a * c;
    if a > 0.0 && disc >= 0.0 {
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        for t in [q / a, if q != 0.0 { c / q } else { f64::NAN }] {
            if (0.0..=len).contains(&ray.at(t).z) {
                take(t);
            }
        }
    }
    if d.z != 0.0 {
        for zc in [0.0, len] {
            let t = (zc - o.z) / d.z;
            let p = ray.at(t);
            if p.x * p.x + p.y * p.y <= r * r {
                take(t);
            }
        }
    }
    best
}

/// The analytic cone x² + y² = (1 − z/2)², 0 ≤ z ≤ 2, with its base disc.
pub fn cone_truth(ray: &Ray) -> Option<f64> {
    let (o, d) = (ray.origin, ray.dir);
    let mut best: Option<f64> = None;
    let mut take = |t: f64| {
        if t > 1e-9 && best.is_none_or(|b| t < b) {
            best = Some(t);
        }
    };
    // x² + y² − (1 − z/2)² = 0 along o + t d.
    let (k0, k1) = (1.0 - o.z / 2.0, -d.z / 2.0);
    let a = d.x * d.x + d.y * d.y - k1 * k1;
    let b = 2.0 * (o.x * d.x + o.y * d.y - k0 * k1);
    let c = o.x * o.x + o.y * o.y - k0 * k0;
    if a.abs() > 1e-300 {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            for t in [q / a, if q != 0.0 { c / q } else { f64::NAN }] {
                if (0.0..=2.0).contains(&ray.at(t).z) {
                    take(t);
                }
            }
        }
    } else if b != 0.0 {
        let t = -c / b;
        if (0.0..=2.0).contains(&ray.at(t).z) {
            take(t);
        }
    }
    if d.z != 0.0 {
        let t = -o.z / d.z;
        let p = ray.at(t);
        if p.x * p.x + p.y * p.y <= 1.0 {
            take(t);
        }
    }
    best
}

/// The radius of the sphere sweep's contour at height z, by bisection on
/// its arcs (V rises monotonically along each), independent of the
/// driver.
fn sphere_radius_at(sw: &SweepShape, z: f64) -> f64 {
    for i in 0..2 {
        let (u, v) = (&sw.u[i], &sw.v[i]);
        let (v0, v1) = (ev(v, 0.0), ev(v, 1.0));
        if (v0..=v1).contains(&z) {
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if ev(v, mid) < z {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return ev(u, 0.5 * (lo + hi));
        }
    }
    0.0
}

/// A tilt as the tables print it.
fn tilt_label(tilt: f64) -> String {
    if tilt == 0.0 {
        "0 (exactly)".into()
    } else {
        format!("{tilt:.0e}")
    }
}

/// A unit ray from `origin` along `dir`.
fn ray(origin: DVec3, dir: DVec3) -> Ray {
    Ray::new(origin, dir.normalize())
}

/// The geometric families, `per` rays (about) each.
pub fn ray_families(sw: &Sweeps, per: usize) -> Vec<RayFamily<'_>> {
    let mut fams = Vec::new();
    let perpendicular = |u: f64, v: f64| DVec3::new(v, -u, 0.0);

    // Grazing rays: tangent to a convex sweep at a point P, reaching it at
    // t = 5, moved GRAZE of the size inward so that they surely enter
    // (a ray exactly tangent may pass outside by rounding): two roots about
    // √(2ρ·GRAZE) apart, the entry within 5e-7 of t = 5.
    let mut rng = Rng(0x6EA2_0001);
    let mut cases = Vec::new();
    for k in 0..per {
        let (ts, p, d, outward) = match k % 3 {
            0 | 1 => {
                let ts = if k % 3 == 0 { &sw.circle } else { &sw.frustum };
                let s = &ts.sweep;
                let i = (rng.uniform() * s.segment as f64) as usize % s.segment;
                let s0 = rng.range(0.05, 0.95);
                let z = rng.range(0.3, 1.7);
                let kappa = (s.scale - 1.0) / s.length;
                let kz = 1.0 + kappa * z;
                let (u, v) = (ev(&s.u[i], s0), ev(&s.v[i], s0));
                let p = DVec3::new(kz * u, kz * v, z);
                let ts_dir = DVec3::new(ev1(&s.u[i], s0), ev1(&s.v[i], s0), 0.0).normalize();
                let tz_dir = DVec3::new(kappa * u, kappa * v, 1.0).normalize();
                let d = (ts_dir * rng.sign() + tz_dir * rng.range(-0.5, 0.5)).normalize();
                (ts, p, d, ts_dir.cross(tz_dir))
            }
            _ => {
                let s = &sw.sphere.sweep;
                let i = k / 3 % 2;
                let s0 = rng.range(0.1, 0.9);
                let phi = rng.range(0.0, std::f64::consts::TAU);
                let (u, v) = (ev(&s.u[i], s0), ev(&s.v[i], s0));
                let (du, dv) = (ev1(&s.u[i], s0), ev1(&s.v[i], s0));
                let (c, sn) = (phi.cos(), phi.sin());
                let p = DVec3::new(u * c, u * sn, v);
                let t_phi = DVec3::new(-sn, c, 0.0);
                let t_m = DVec3::new(du * c, du * sn, dv).normalize();
                let d = (t_phi * rng.sign() + t_m * rng.sign() * rng.range(0.1, 0.5)).normalize();
                (&sw.sphere, p, d, t_phi.cross(t_m))
            }
        };
        // The outward normal: the solids are convex about the z axis.
        let mut n = outward.normalize();
        if n.dot(DVec3::new(p.x, p.y, 0.0)) < 0.0 {
            n = -n;
        }
        let p = p - n * (GRAZE * ts.size);
        cases.push(RayCase {
            sweep: ts,
            ray: Ray::new(p - d * 5.0, d),
            truth: Some(5.0),
        });
    }
    fams.push(RayFamily {
        name: format!("grazing rays (double roots), {GRAZE:.0e} inside the tangent"),
        truth: "by construction: tangent at a point of a convex sweep (B-spline circle translation and frustum, Bezier sphere), moved inward by 1e-13 of the size",
        cases,
    });

    // Rays through segment joints: from outside a convex sweep toward a
    // joint, entering there.
    let mut rng = Rng(0x6EA2_0002);
    let mut cases = Vec::new();
    for k in 0..per {
        let (ts, p, n) = match k % 4 {
            0 | 1 => {
                let ts = if k % 4 == 0 { &sw.circle } else { &sw.frustum };
                let s = &ts.sweep;
                let i = (rng.uniform() * s.segment as f64) as usize % s.segment;
                let z = rng.range(0.2, 1.8);
                let kz = 1.0 + (s.scale - 1.0) / s.length * z;
                let (u, v) = (s.u[i].d, s.v[i].d);
                let n = perpendicular(s.u[i].c, s.v[i].c).normalize();
                (ts, DVec3::new(kz * u, kz * v, z), n)
            }
            2 => {
                // The square prism's corners, entering between its two faces.
                let s = &sw.square.sweep;
                let i = (rng.uniform() * s.segment as f64) as usize % s.segment;
                let (u, v) = (s.u[i].d, s.v[i].d);
                (
                    &sw.square,
                    DVec3::new(u, v, rng.range(0.2, 1.8)),
                    DVec3::new(u, v, 0.0).normalize(),
                )
            }
            _ => {
                // The sphere's equator, where its two arcs join.
                let phi = rng.range(0.0, std::f64::consts::TAU);
                let n = DVec3::new(phi.cos(), phi.sin(), 0.0);
                (&sw.sphere, n, n)
            }
        };
        let side = n.cross(DVec3::Z).normalize_or_zero();
        let o = p + (n + side * rng.range(-0.6, 0.6) + DVec3::Z * rng.range(-0.3, 0.3)) * 4.0;
        let d = (p - o).normalize();
        cases.push(RayCase {
            sweep: ts,
            ray: Ray::new(o, d),
            truth: Some((p - o).length()),
        });
    }
    fams.push(RayFamily {
        name: "rays through segment joints".into(),
        truth: "by construction: aimed from outside at a joint of a convex sweep (circle, frustum, straight-sided square, sphere's equator)",
        cases,
    });

    // Rays parallel to a translation sweep's axis, exactly and nearly.
    let mut rng = Rng(0x6EA2_0003);
    let mut cases = Vec::new();
    let tilts = [0.0, 1e-13, 1e-9, 1e-6];
    for k in 0..per {
        let tilt = tilts[k % tilts.len()];
        let inside = k / tilts.len() % 2 == 0;
        let r = if inside {
            rng.range(0.0, 0.8)
        } else {
            rng.range(1.2, 2.0)
        };
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let up = rng.uniform() < 0.5;
        let (z0, dz) = if up { (-3.0, 1.0) } else { (5.0, -1.0) };
        let o = DVec3::new(r * phi.cos(), r * phi.sin(), z0);
        let d = DVec3::new(tilt, 0.0, dz).normalize();
        let cap = if up { 0.0 } else { 2.0 };
        cases.push(RayCase {
            sweep: &sw.circle,
            ray: Ray::new(o, d),
            truth: inside.then(|| (cap - z0) / d.z),
        });
    }
    fams.push(RayFamily {
        name: "rays parallel to the sweep axis (tilt 0, 1e-13, 1e-9, 1e-6)".into(),
        truth: "by construction: well inside (r ≤ 0.8) the circle meets a cap, well outside (r ≥ 1.2) nothing",
        cases,
    });

    // Rays perpendicular to a rotation axis, exactly and nearly: one
    // family a tilt.
    let mut rng = Rng(0x6EA2_0004);
    for tilt in [0.0, 1e-9, 1e-6, 1e-3] {
        let mut cases = Vec::new();
        for k in 0..per / 4 {
            let y = rng.range(-1.3, 1.3);
            let z = rng.range(0.05, 1.95);
            let r = ray(DVec3::new(-5.0, y, z), DVec3::new(1.0, 0.0, tilt));
            match k % 3 {
                0 => cases.push(RayCase {
                    sweep: &sw.cylinder_r,
                    truth: cylinder_truth(1.0, 2.0, &r),
                    ray: r,
                }),
                1 => cases.push(RayCase {
                    sweep: &sw.cone_r,
                    truth: cone_truth(&r),
                    ray: r,
                }),
                _ if tilt == 0.0 => {
                    // The sphere, horizontal rays: the slice at z is a circle
                    // of the contour's radius there.
                    let z = rng.range(-0.95, 0.95);
                    let y = rng.range(-1.1, 1.1);
                    let rad = sphere_radius_at(&sw.sphere.sweep, z);
                    let truth = (y.abs() <= rad).then(|| 5.0 - (rad * rad - y * y).sqrt());
                    cases.push(RayCase {
                        sweep: &sw.sphere,
                        ray: Ray::new(DVec3::new(-5.0, y, z), DVec3::X),
                        truth,
                    });
                }
                _ => cases.push(RayCase {
                    sweep: &sw.cylinder_r,
                    truth: cylinder_truth(1.0, 2.0, &r),
                    ray: r,
                }),
            }
        }
        fams.push(RayFamily {
            name: format!("rays perpendicular to the rotation axis, tilt {}", tilt_label(tilt)),
            truth: "analytic: rotation sweeps of straight segments are an exact cylinder and cone; the sphere (horizontal rays only) by bisection on its contour",
            cases,
        });
    }

    // Rays along a rotation axis, on it and off it, exactly and nearly
    // parallel: one family a tilt.
    let mut rng = Rng(0x6EA2_0005);
    for tilt in [0.0, 1e-13, 1e-9] {
        let mut cases = Vec::new();
        for k in 0..per / 3 {
            let on_axis = k / 3 % 4 == 0;
            let r = if on_axis { 0.0 } else { rng.range(0.0, 1.3) };
            let phi = rng.range(0.0, std::f64::consts::TAU);
            let up = rng.uniform() < 0.5;
            let (z0, dz) = if up { (-3.0, 1.0) } else { (5.0, -1.0) };
            let o = DVec3::new(r * phi.cos(), r * phi.sin(), z0);
            let rr = ray(o, DVec3::new(tilt, 0.0, dz));
            match k % 3 {
                0 => cases.push(RayCase {
                    sweep: &sw.cylinder_r,
                    truth: cylinder_truth(1.0, 2.0, &rr),
                    ray: rr,
                }),
                1 => cases.push(RayCase {
                    sweep: &sw.cone_r,
                    truth: cone_truth(&rr),
                    ray: rr,
                }),
                _ => {
                    // The sphere on its axis: the poles, which are control
                    // points, reached exactly (tilted, the same to 1e-9).
                    let rr = ray(DVec3::new(0.0, 0.0, z0), DVec3::new(tilt, 0.0, dz));
                    let want = if up { -1.0 - z0 } else { z0 - 1.0 };
                    cases.push(RayCase {
                        sweep: &sw.sphere,
                        truth: Some(want / rr.dir.z.abs()),
                        ray: rr,
                    });
                }
            }
        }
        fams.push(RayFamily {
            name: format!("rays along the rotation axis, tilt {}", tilt_label(tilt)),
            truth: "analytic: exact cylinder and cone; the sphere's poles (control points)",
            cases,
        });
    }

    // Rays through a conic apex.
    let mut rng = Rng(0x6EA2_0006);
    let mut cases = Vec::new();
    for k in 0..per {
        let inside = k % 2 == 0;
        let rho = if inside {
            rng.range(0.0, 0.8)
        } else {
            rng.range(1.2, 2.0)
        };
        let phi = rng.range(0.0, std::f64::consts::TAU);
        let q = DVec3::new(rho * phi.cos(), rho * phi.sin(), 0.0);
        match k / 2 % 4 {
            0 => {
                // The cone (apex at z = 2), from above through the apex:
                // the apex first, inside or out.
                let a = DVec3::new(0.0, 0.0, 2.0);
                let e = (q - a).normalize();
                cases.push(RayCase {
                    sweep: &sw.cone,
                    ray: Ray::new(a - e * 3.0, e),
                    truth: Some(3.0),
                });
            }
            1 => {
                // The cone from below: the base inside, else the apex.
                let a = DVec3::new(0.0, 0.0, 2.0);
                let e = (a - q).normalize();
                let o = q - e;
                cases.push(RayCase {
                    sweep: &sw.cone,
                    ray: Ray::new(o, e),
                    truth: Some(if inside { 1.0 } else { 1.0 + (a - q).length() }),
                });
            }
            2 => {
                // The cone in the plane of its apex: touches the apex.
                let a = DVec3::new(0.0, 0.0, 2.0);
                let h = DVec3::new(phi.cos(), phi.sin(), 0.0);
                cases.push(RayCase {
                    sweep: &sw.cone,
                    ray: Ray::new(a - h * 3.0, h),
                    truth: Some(3.0),
                });
            }
            _ => {
                // The frustum (apex at z = 4, outside the solid), from
                // above through the apex: the top cap inside, else nothing.
                let a = DVec3::new(0.0, 0.0, 4.0);
                let e = (q - a).normalize();
                cases.push(RayCase {
                    sweep: &sw.frustum,
                    ray: Ray::new(a - e * 3.0, e),
                    truth: inside.then(|| 3.0 + 2.0 / -e.z),
                });
            }
        }
    }
    fams.push(RayFamily {
        name: "rays through a conic apex".into(),
        truth: "by construction: through the apex of a circle cone (scale 0) and a frustum (scale 0.5), aimed well inside or outside the base",
        cases,
    });
    fams
}

/// What a method did on one family.
#[derive(Clone, Debug, Default)]
pub struct Tally {
    pub cases: usize,
    /// True roots (root families) or true hits (geometric families).
    pub truths: usize,
    pub missed: usize,
    /// Found roots off a true root by more than [`ROOT_TOL`] but not more
    /// than [`ROUGH_TOL`] (root families only; counted among the missed).
    pub rough: usize,
    pub spurious: usize,
    /// Of the roots (hits) found, the largest error (relative to the
    /// object's size for hits).
    pub worst: f64,
    /// Nanoseconds a solve (median of the timing runs).
    pub ns: f64,
    /// Root families: the largest rounding bound ε·Σ|aₖ|wᵏ/|p′(w)| of a
    /// true root w with no found root within [`ROOT_TOL`] (how far the
    /// rounding of the coefficients alone can move it); 0 when none.
    pub worst_bound_missed: f64,
    /// Root families: the largest distance from a missed true root to the
    /// nearest found root within [`ROUGH_TOL`]; 0 when none.
    pub worst_rough: f64,
}

/// How far rounding the coefficients of `a` (degree `n`) can move its
/// simple root `w`: ε·Σ|aₖ|wᵏ/|p′(w)| (infinite at a multiple root).
pub fn rounding_bound(n: usize, a: &[f64; 7], w: f64) -> f64 {
    let sum: f64 = (0..=n).map(|k| a[k].abs() * w.powi(k as i32)).sum();
    let dp: f64 = (1..=n).map(|k| k as f64 * a[k] * w.powi(k as i32 - 1)).sum();
    f64::EPSILON * sum / dp.abs()
}

/// Times `f` over all cases, repeated until each run takes 50 ms; the
/// median of 7 runs, in ns a case.
fn time_per_case(cases: usize, mut f: impl FnMut()) -> f64 {
    let mut reps = 1usize;
    loop {
        let t = Instant::now();
        for _ in 0..reps {
            f();
        }
        if t.elapsed().as_secs_f64() > 0.05 || reps > 1 << 20 {
            break;
        }
        reps *= 2;
    }
    let runs: Vec<f64> = (0..7)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                f();
            }
            t.elapsed().as_secs_f64() * 1e9 / (reps * cases.max(1)) as f64
        })
        .collect();
    median(&runs)
}

pub fn tally_poly(method: Method, fam: &PolyFamily) -> Tally {
    let mut t = Tally {
        cases: fam.cases.len(),
        ..Tally::default()
    };
    for case in &fam.cases {
        let found = solve(method, case);
        let (missed, rough, spurious, worst) = match_roots(&case.roots, &found, ROOT_TOL, ROUGH_TOL);
        t.truths += case.roots.len();
        t.missed += missed;
        t.rough += rough;
        for &w in &case.roots {
            let nearest = found.iter().map(|f| (f.0 - w).abs()).fold(f64::INFINITY, f64::min);
            if nearest > ROOT_TOL {
                t.worst_bound_missed = t.worst_bound_missed.max(rounding_bound(case.n, &case.a, w));
                if nearest <= ROUGH_TOL {
                    t.worst_rough = t.worst_rough.max(nearest);
                }
            }
        }
        t.spurious += spurious;
        t.worst = t.worst.max(worst);
    }
    t.ns = time_per_case(fam.cases.len(), || {
        for case in &fam.cases {
            std::hint::black_box(solve(method, std::hint::black_box(case)));
        }
    });
    t
}

pub fn tally_rays(method: Method, fam: &RayFamily) -> Tally {
    let opts = method.options();
    let mut t = Tally {
        cases: fam.cases.len(),
        ..Tally::default()
    };
    for case in &fam.cases {
        let got = intersect_sweep(case.sweep.class, &case.sweep.sweep, &case.ray, 1e-9, &opts).map(|h| h.t);
        let tol = HIT_TOL * case.sweep.size;
        if case.truth.is_some() {
            t.truths += 1;
        }
        match (case.truth, got) {
            (Some(want), Some(g)) if (g - want).abs() <= tol => {
                t.worst = t.worst.max((g - want).abs() / case.sweep.size)
            }
            // A farther hit: the true surface was missed.
            (Some(want), Some(g)) if g > want => t.missed += 1,
            (Some(_), Some(_)) => t.spurious += 1,
            (Some(_), None) => t.missed += 1,
            (None, Some(_)) => t.spurious += 1,
            (None, None) => {}
        }
    }
    t.ns = time_per_case(fam.cases.len(), || {
        for case in &fam.cases {
            std::hint::black_box(intersect_sweep(
                case.sweep.class,
                &case.sweep.sweep,
                std::hint::black_box(&case.ray),
                1e-9,
                &opts,
            ));
        }
    });
    t
}

/// The key-frame decks whose in-between shapes the key-frame families
/// take, and how each matches its key shapes.
pub const KEYFRAME_DECKS: [(&str, &str); 3] = [
    ("fig5_10", "`expanding`/`more` (Burtnyk & Wein), translation"),
    ("fig5_11", "`expanding2`/`more2` (arc length), translation"),
    ("fig5_12", "`expanding2`/`more2` (arc length), rotation"),
];

/// The in-between shapes of each key-frame deck at 8 instants of the
/// shutter ((j + ½)/8), as the renderer builds them (`goahead`, then
/// `inbetween` per instant), in the key shapes' local frame.
pub fn keyframe_shapes() -> Result<Vec<(String, Vec<TestSweep>)>, String> {
    let mut out = Vec::new();
    for (deck, how) in KEYFRAME_DECKS {
        let scene = crate::decks::prepared(deck, &Options::default(), None)?;
        let chains = raytrace::raytrace::key_frame_chains(&scene, Fidelity::Thesis).map_err(|e| e.to_string())?;
        let mut shapes = Vec::new();
        for (k, chain) in &chains {
            let class = scene.objects[scene.keyframes[*k].first].class;
            for j in 0..8 {
                let t = (j as f64 + 0.5) / 8.0;
                let mut sweep = chain.scratch();
                chain.inbetween(t, &mut sweep);
                let size = box_size(&sweep);
                shapes.push(TestSweep {
                    name: format!("{deck} at t = {t}"),
                    class,
                    sweep,
                    size,
                });
            }
        }
        out.push((format!("in-between shapes of {deck}: {how}"), shapes));
    }
    Ok(out)
}

/// A random ray from a sphere of radius 8 about the centre of a sweep's
/// box, aimed at a random point of the box (for rotation, the box of
/// the solid of revolution).
fn random_ray(rng: &mut Rng, ts: &TestSweep) -> Ray {
    let b = &ts.sweep.bbox;
    let (lo, hi) = match ts.class {
        PrimitiveClass::Rotation => {
            let r = b.xmax.abs().max(b.xmin.abs());
            (DVec3::new(-r, -r, b.zmin), DVec3::new(r, r, b.zmax))
        }
        _ => (DVec3::new(b.xmin, b.ymin, b.zmin), DVec3::new(b.xmax, b.ymax, b.zmax)),
    };
    let centre = (lo + hi) * 0.5;
    let dir = loop {
        let v = DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        let l = v.length();
        if l > 0.1 && l <= 1.0 {
            break v / l;
        }
    };
    let origin = centre + dir * 8.0;
    let target = DVec3::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y), rng.range(lo.z, hi.z));
    Ray::new(origin, (target - origin).normalize())
}

/// The key-frame families: `per` random rays against the in-between
/// shapes of each key-frame deck. No analytic truth exists for an
/// in-between contour: the true hit is the robust solver's (whose hits
/// lie on the surface within 1e-9 of the size, D12, and which finds every
/// root of the constructed families above), so its own row is the
/// reference and counts nothing.
pub fn keyframe_families(shapes: &[(String, Vec<TestSweep>)], per: usize) -> Vec<RayFamily<'_>> {
    let robust = Method::Robust.options();
    let mut rng = Rng(0x6EA2_0007);
    shapes
        .iter()
        .map(|(name, list)| {
            let cases = (0..per)
                .map(|k| {
                    let ts = &list[k % list.len()];
                    let ray = random_ray(&mut rng, ts);
                    let truth = intersect_sweep(ts.class, &ts.sweep, &ray, 1e-9, &robust).map(|h| h.t);
                    RayCase { sweep: ts, ray, truth }
                })
                .collect();
            RayFamily {
                name: name.clone(),
                truth: "the robust solver's hit (the reference: its own row counts nothing)",
                cases,
            }
        })
        .collect()
}

type Summary = [(String, Vec<(Method, Tally)>)];

/// A method's tally on the family whose name starts with `prefix`.
fn find<'a>(rows: &'a Summary, prefix: &str, m: Method) -> &'a Tally {
    rows.iter()
        .find(|(n, _)| n.starts_with(prefix))
        .and_then(|(_, t)| t.iter().find(|(k, _)| *k == m))
        .map(|(_, t)| t)
        .unwrap_or_else(|| panic!("the family {prefix} is measured"))
}

/// Sums over the families whose names start with `prefix`.
fn total(rows: &Summary, prefix: &str, m: Method) -> Tally {
    let mut sum = Tally::default();
    for (_, ts) in rows.iter().filter(|(n, _)| n.starts_with(prefix)) {
        for (k, t) in ts {
            if *k == m {
                sum.cases += t.cases;
                sum.truths += t.truths;
                sum.missed += t.missed;
                sum.rough += t.rough;
                sum.spurious += t.spurious;
                sum.worst = sum.worst.max(t.worst);
                sum.worst_bound_missed = sum.worst_bound_missed.max(t.worst_bound_missed);
            }
        }
    }
    sum
}

fn pct(a: usize, b: usize) -> f64 {
    100.0 * a as f64 / b.max(1) as f64
}

/// What the tables show, in numbers taken from them.
fn summary(poly: &Summary, rays: &Summary) -> String {
    use Method::*;
    let mut s = String::from("\n## What the tables show\n\n");
    let same = poly
        .iter()
        .chain(rays)
        .all(|(_, t)| (t[0].1.missed, t[0].1.spurious) == (t[1].1.missed, t[1].1.spurious));
    let sep3 = find(poly, "separated roots, cubic", LaguerreThesis);
    let sep6 = find(poly, "separated roots, sextic", LaguerreThesis);
    let dbl3 = find(poly, "double roots, cubic", LaguerreThesis);
    let nd = total(poly, "near-double", LaguerreThesis);
    let cl = total(poly, "clustered", LaguerreThesis);
    let _ = writeln!(
        s,
        "- `laguerre`{}: even with its roots at least 0.1 apart it misses {:.0} % of the cubics' roots \
         and {:.0} % of the sextics' (those below its first start 0.98/n and those its four steps \
         do not settle on); it finds no double root of a cubic to {ROOT_TOL:.0e} ({} of {} only \
         roughly, within {ROUGH_TOL:.0e}: convergence there is linear); it misses {:.0} % of \
         near-double roots and {:.0} % of clustered ones (its 0.001 de-duplication merges them). \
         It never returned a spurious root.",
        if same {
            " (listing and thesis fidelity alike: erratum 7 moves no count here)"
        } else {
            ""
        },
        pct(sep3.missed, sep3.truths),
        pct(sep6.missed, sep6.truths),
        dbl3.rough,
        dbl3.truths,
        pct(nd.missed, nd.truths),
        pct(cl.missed, cl.truths),
    );
    let rob = total(poly, "", Robust);
    let rob_fams: Vec<&str> = poly
        .iter()
        .filter(|(_, t)| t[2].1.missed > 0)
        .map(|(n, _)| n.as_str())
        .collect();
    let _ = writeln!(
        s,
        "- The robust solver finds {} of {} roots to {ROOT_TOL:.0e}, none spurious.{}",
        rob.truths - rob.missed,
        rob.truths,
        if rob_fams.is_empty() {
            String::new()
        } else {
            format!(
                " The {} it misses are in the families {}: it reports two close roots as one double \
                 root between them, at most {:.0e} from each. Rounding the coefficients alone moves \
                 those roots by up to {:.0e} (ε·Σ|aₖ|wᵏ/|p′(w)|, the largest over the missed roots of \
                 each family in turn: {}), so where that exceeds {ROOT_TOL:.0e} no f64 solver can \
                 promise them; where it does not, the solver's test for a double root (about √ε of the \
                 polynomial's scale) is what merges the pair. An error of that size in a contour \
                 parameter is far below a pixel at the decks' scales.",
                rob.missed,
                rob_fams
                    .iter()
                    .map(|n| format!("\"{n}\""))
                    .collect::<Vec<_>>()
                    .join(" and "),
                poly.iter().map(|(_, t)| t[2].1.worst_rough).fold(0.0, f64::max),
                rob.worst_bound_missed,
                poly.iter()
                    .filter(|(_, t)| t[2].1.missed > 0)
                    .map(|(_, t)| format!("{:.0e}", t[2].1.worst_bound_missed))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    );
    let graze = find(rays, "grazing", LaguerreThesis);
    let graze_r = find(rays, "grazing", Robust);
    let perp = total(rays, "rays perpendicular to the rotation axis, tilt 1", LaguerreThesis);
    let along = total(rays, "rays along the rotation axis, tilt 1e-9", LaguerreThesis);
    let spur: usize = METHODS.iter().map(|&m| total(rays, "", m).spurious).sum();
    let rob_rays = total(rays, "", Robust);
    let mut easy = Tally::default();
    for prefix in [
        "rays through segment joints",
        "rays parallel",
        "rays perpendicular to the rotation axis, tilt 0",
        "rays along the rotation axis, tilt 0",
        "rays along the rotation axis, tilt 1e-13",
        "rays through a conic apex",
    ] {
        let t = total(rays, prefix, LaguerreThesis);
        easy.truths += t.truths;
        easy.missed += t.missed;
    }
    let _ = writeln!(
        s,
        "- In the sweep driver every root is polished and checked on the surface: {spur} spurious hits \
         over all families and methods. With `laguerre` the driver loses {} of {} grazing rays (the \
         robust solver {}), {} of {} rays tilted 1e-9 to 1e-3 from perpendicular to a rotation axis \
         (front and back of a ring at nearly one height: a near-double root), and {} of {} rays 1e-9 \
         off a rotation axis. Rays parallel to a translation sweep's axis (tilted up to 1e-6), exactly \
         along or across a rotation axis (or within 1e-13 of it, where the driver takes the same \
         special path), through joints and through a conic apex: `laguerre` misses {} of their {} \
         true hits. The robust solver misses {} of {} true hits in all.",
        graze.missed,
        graze.truths,
        graze_r.missed,
        perp.missed,
        perp.truths,
        along.missed,
        along.truths,
        easy.missed,
        easy.truths,
        rob_rays.missed,
        rob_rays.truths,
    );
    let c3l = find(poly, "separated roots, cubic", LaguerreThesis).ns;
    let c3r = find(poly, "separated roots, cubic", Robust).ns;
    let c6l = find(poly, "separated roots, sextic", LaguerreThesis).ns;
    let c6r = find(poly, "separated roots, sextic", Robust).ns;
    let ratios: Vec<f64> = rays.iter().map(|(_, t)| t[2].1.ns / t[1].1.ns).collect();
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), r| (lo.min(*r), hi.max(*r)));
    let _ = writeln!(
        s,
        "- Cost: on separated roots `laguerre` takes {c3l:.0} ns a cubic and {c6l:.0} ns a sextic, the \
         robust solver {c3r:.0} and {c6r:.0} ns ({:.1}× and {:.1}×). In the driver, where a ray \
         solves one polynomial a segment its box lets through and polishes what it finds, the robust \
         solver takes {lo:.1} to {hi:.1} times as long as `laguerre` (thesis) per family here (the \
         last column of the second table; the chart in docs/speed_accuracy.md has the cost a ray in \
         whole renders).",
        c3r / c3l,
        c6r / c6l
    );
    s
}

/// The report's table rows of one family.
fn rows(out: &mut String, family: &str, tallies: &[(Method, Tally)]) {
    for (k, (m, t)) in tallies.iter().enumerate() {
        let worst = if t.truths > t.missed {
            format!("{:.1e}", t.worst)
        } else {
            "—".into()
        };
        let missed = if t.rough > 0 {
            format!("{} ({} rough)", t.missed, t.rough)
        } else {
            t.missed.to_string()
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {:.0} |",
            if k == 0 { family } else { "" },
            m.label(),
            t.cases,
            t.truths,
            missed,
            t.spurious,
            worst,
            t.ns
        );
    }
}

/// Measures every family and writes the report to `out`.
pub fn run(out: &Path) -> Result<(), String> {
    let per_poly = 1000;
    let per_ray = 1200;
    let mut report = String::new();
    report.push_str(HEADER);
    let _ = writeln!(
        report,
        "\n## Constructed polynomials\n\n{per_poly} polynomials a family (fixed seeds), solved on [0, 1]; a root \
         counts as found within {ROOT_TOL:.0e} of a true root (each true root matched once, the nearest \
         first; a root the robust solver reports as double may match two). A found root that matches \
         none but lies within {ROUGH_TOL:.0e} of a true root is \"rough\" (its true root is counted \
         missed); farther from every true root it is spurious. Worst error: the largest \
         |found − true| of the matched roots. Time: one solve, median of 7 timing runs, release build.\n"
    );
    report.push_str(TABLE_HEAD);
    let mut poly_summary = Vec::new();
    for fam in poly_families(per_poly) {
        let tallies: Vec<(Method, Tally)> = METHODS.iter().map(|&m| (m, tally_poly(m, &fam))).collect();
        eprintln!(
            "{}: {:?}",
            fam.name,
            tallies.iter().map(|(_, t)| (t.missed, t.spurious)).collect::<Vec<_>>()
        );
        rows(&mut report, &fam.name, &tallies);
        poly_summary.push((fam.name.clone(), tallies));
    }
    let sweeps = Sweeps::new();
    let _ = writeln!(
        report,
        "\n## Constructed rays against constructed sweeps\n\n{per_ray} rays a kind of ray (fixed seeds; where \
         each tilt is a family of its own, shared evenly among the tilts), each intersected by `shapes::sweep::intersect_sweep` with the method's solver. A hit is the true one \
         within {HIT_TOL:.0e} of the object's size (its largest box coordinate); \"missed\" counts no hit \
         or a farther one (a hole, or the surface behind), \"spurious\" a hit where there is none or a \
         nearer one. Worst error: the largest |t − t_true| of the hits found, relative to the size. \
         Time: one call of `intersect_sweep` (every segment's polynomial, the polish and the checks).\n"
    );
    report.push_str(TABLE_HEAD);
    let mut truths = String::new();
    let mut ray_summary = Vec::new();
    for fam in ray_families(&sweeps, per_ray) {
        let tallies: Vec<(Method, Tally)> = METHODS.iter().map(|&m| (m, tally_rays(m, &fam))).collect();
        eprintln!(
            "{}: {:?}",
            fam.name,
            tallies.iter().map(|(_, t)| (t.missed, t.spurious)).collect::<Vec<_>>()
        );
        rows(&mut report, &fam.name, &tallies);
        // One line a kind of ray (the tilts of one kind share it).
        let kind = fam.name.split(", tilt").next().unwrap_or(&fam.name);
        if !truths.contains(&format!("- {kind}:")) {
            let _ = writeln!(truths, "- {kind}: {}.", fam.truth);
        }
        ray_summary.push((fam.name.clone(), tallies));
    }
    let _ = write!(report, "\nWhere each true hit comes from:\n\n{truths}");
    report.push_str(&summary(&poly_summary, &ray_summary));
    let shapes = keyframe_shapes()?;
    let _ = writeln!(
        report,
        "\n## Key-frame inputs\n\nRays against the in-between sweeps of key-frame deformation (§3.1–3.3): \
         for each key-frame deck, its in-between contour at 8 instants of the shutter ((j + ½)/8) as the \
         renderer builds it (`goahead`, then the Hermite in-between per instant), and {per_ray} random rays \
         from a sphere of radius 8 about the shape's box, aimed into the box. No analytic truth exists for \
         an in-between contour: the true hit is the robust solver's, so its row is the reference and \
         counts nothing; the `laguerre` rows count where it differs (tolerance as above).\n"
    );
    report.push_str(TABLE_HEAD);
    for fam in keyframe_families(&shapes, per_ray) {
        let tallies: Vec<(Method, Tally)> = METHODS.iter().map(|&m| (m, tally_rays(m, &fam))).collect();
        eprintln!(
            "{}: {:?}",
            fam.name,
            tallies.iter().map(|(_, t)| (t.missed, t.spurious)).collect::<Vec<_>>()
        );
        rows(&mut report, &fam.name, &tallies);
    }
    report.push_str(&star_section()?);
    report.push_str(ROOTTESTING);
    std::fs::write(out, &report).map_err(|e| format!("{}: {e}", out.display()))?;
    println!("{report}");
    println!("wrote {}", out.display());
    Ok(())
}

/// `laguerre`'s missed roots in a whole picture: fig5_6's star at 256².
fn star_section() -> Result<String, String> {
    let size = 256;
    let m = crate::deck_misses::deck_misses("fig5_6", size)?;
    Ok(format!(
        "\n## A deck: fig5_6's star\n\nOne ray a pixel centre of fig5_6 at {size}², against its translation \
         sweep (the eight-pointed star), with each solver (`tools::deck_misses`). Of the {} pixels whose ray \
         the robust solver finds on the star, `laguerre` misses {} ({:.1} %): no hit, or the far side of a \
         lobe where the ray grazes the near side (the grazing ray's double root, which its four steps from \
         fixed starts do not find). That is the thesis's method (§2.5) and the port keeps it as the default; \
         `--solver robust` is right there. `laguerre` found a nearer hit than the robust solver's on {} pixels.\n",
        m.object_pixels,
        m.missed,
        100.0 * m.missed as f64 / m.object_pixels.max(1) as f64,
        m.nearer
    ))
}

const TABLE_HEAD: &str =
    "| family | method | cases | true roots (hits) | missed | spurious | worst error | ns a solve |\n\
                          |---|---|---|---|---|---|---|---|\n";

const HEADER: &str = "# Stability of the root solvers\n\n\
Written by `cargo run -p tools --release -- stability` (tools/src/stability.rs); every case comes from a \
fixed seed, so the counts are the same on every run; the times are not (medians on a shared 2-core \
machine). Three methods: `laguerre` as printed (§2.5, 4 steps from the fixed starts 0.98/n, …) in \
listing and thesis fidelity (erratum 7 parts them: the derivative stored and the zero-denominator \
guards), and the robust solver (`proc::robust::real_roots`, `--solver robust`). \
docs/laguerre_misses.md has laguerre's miss rates on random polynomials and random rays; this report \
takes the hard cases one family at a time.\n";

const ROOTTESTING: &str = "\n`roottesting`'s odd root counts are not measured in this report: the sweep driver \
decides the caps by `point_in_contour`, not by the parity of the side roots, so it never calls \
`roottesting` and no odd count reaches it (DEVIATIONS D10; `proc::sweep::roottesting` is ported and \
tested on its own).\n";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poly_has_the_roots() {
        let a = poly(&[0.2, 0.5, 0.5], 2.0);
        for x in [0.2f64, 0.5] {
            let y: f64 = (0..7).map(|k| a[k] * x.powi(k as i32)).sum();
            assert!(y.abs() < 1e-15);
        }
        assert_eq!(PolyCase::new(&[0.2, 0.5, 0.5, 1.5]).roots, vec![0.2, 0.5]);
    }

    /// Matching: nearest first, one true root a found root unless the
    /// found root is double; the unmatched found roots are spurious.
    #[test]
    fn matching_counts_missed_and_spurious() {
        let truth = [0.2, 0.4, 0.4 + 1e-8];
        assert_eq!(match_roots(&truth, &[(0.2, 1), (0.4, 1)], 1e-6, 1e-3).0, 1);
        let (m, r, s, w) = match_roots(&truth, &[(0.2, 1), (0.4, 2), (0.9, 1)], 1e-6, 1e-3);
        assert_eq!((m, r, s), (0, 0, 1));
        assert!((w - 1e-8).abs() < 1e-12);
        assert_eq!(match_roots(&truth, &[], 1e-6, 1e-3), (3, 0, 0, 0.0));
        // 1e-5 off: rough, and the true root missed.
        let (m, r, s, _) = match_roots(&[0.5], &[(0.50001, 1)], 1e-6, 1e-3);
        assert_eq!((m, r, s), (1, 1, 0));
    }

    /// The constructed truths: rays at the analytic cylinder and cone.
    #[test]
    fn analytic_truths() {
        let r = Ray::new(DVec3::new(-5.0, 0.0, 1.0), DVec3::X);
        assert!((cylinder_truth(1.0, 2.0, &r).unwrap() - 4.0).abs() < 1e-12);
        assert!((cone_truth(&r).unwrap() - 4.5).abs() < 1e-12);
        let down = Ray::new(DVec3::new(0.5, 0.0, 5.0), DVec3::NEG_Z);
        assert!((cylinder_truth(1.0, 2.0, &down).unwrap() - 3.0).abs() < 1e-12);
        assert!((cone_truth(&down).unwrap() - 4.0).abs() < 1e-12);
        let miss = Ray::new(DVec3::new(-5.0, 1.5, 1.0), DVec3::X);
        assert!(cylinder_truth(1.0, 2.0, &miss).is_none() && cone_truth(&miss).is_none());
    }

    /// The robust solver finds the constructed hits of the easy rays, so the
    /// constructions are what they say.
    #[test]
    fn robust_finds_the_constructed_joint_and_apex_hits() {
        let sweeps = Sweeps::new();
        let fams = ray_families(&sweeps, 40);
        assert!(fams.iter().all(|f| !f.cases.is_empty()));
        for name in ["rays through segment joints", "rays through a conic apex"] {
            let fam = fams.iter().find(|f| f.name == name).unwrap();
            let t = tally_rays(Method::Robust, fam);
            assert_eq!((t.missed, t.spurious), (0, 0), "{name}");
        }
    }

    /// Every key-frame deck gives 8 in-between shapes, each with segments
    /// and a box, and rays that hit some of them.
    #[test]
    fn keyframe_shapes_are_built() {
        let shapes = keyframe_shapes().unwrap();
        assert_eq!(shapes.len(), KEYFRAME_DECKS.len());
        for (name, list) in &shapes {
            assert_eq!(list.len(), 8, "{name}");
            assert!(list.iter().all(|s| s.sweep.segment > 0 && s.size > 0.0), "{name}");
        }
        let fams = keyframe_families(&shapes, 50);
        for f in &fams {
            assert!(f.cases.iter().any(|c| c.truth.is_some()), "{}", f.name);
        }
    }

    #[test]
    fn straight_bezier_has_thirds() {
        let p = straight_bezier(&[[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]]);
        assert_eq!(p.len(), 9);
        assert_eq!(p[1], [1.0, 0.0]);
        assert_eq!(p[5], [1.0, 2.0]);
    }
}

//! The sweeps, rays and answers the sweep tests share (tests/sweep.rs,
//! tests/sweep_driver.rs, tests/sweep_cases.rs).

use raytrace::options::*;
use raytrace::proc::sweep::{laguerre, Root, LAGUERRE_ROOTS};
use raytrace::scene::*;
use raytrace::shapes::sweep::{prepare_sweeps, Sweep, SweepCache};
use raytrace::types::*;
use std::f64::consts::{PI, TAU};

// ---------------------------------------------------------------------------
// Helpers

/// xorshift64*: a fixed-seed generator, so every run sees the same cases.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
    pub fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(self.range(-1.0, 1.0), self.range(-1.0, 1.0), self.range(-1.0, 1.0));
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
}

pub fn laguerre_roots(n: usize, a: &[f64; 7], fid: Fidelity) -> Vec<f64> {
    let mut root = [Root::default(); LAGUERRE_ROOTS];
    let total = laguerre(n, a, 1.0, 0.0, &mut root, fid);
    root[..total].iter().map(|r| r.a).collect()
}

pub const OPTS: [Options; 4] = [
    Options {
        fidelity: Fidelity::Thesis,
        solver: Solver::Laguerre,
        sampler: TimeSampler::Table,
        accel: Accel::Auto,
    },
    Options {
        fidelity: Fidelity::Listing,
        solver: Solver::Laguerre,
        sampler: TimeSampler::Table,
        accel: Accel::Auto,
    },
    Options {
        fidelity: Fidelity::Thesis,
        solver: Solver::Robust,
        sampler: TimeSampler::Table,
        accel: Accel::Auto,
    },
    Options {
        fidelity: Fidelity::Listing,
        solver: Solver::Robust,
        sampler: TimeSampler::Table,
        accel: Accel::Auto,
    },
];

pub const ROBUST: Options = Options {
    fidelity: Fidelity::Thesis,
    solver: Solver::Robust,
    sampler: TimeSampler::Table,
    accel: Accel::Auto,
};
pub const LAGUERRE: Options = Options {
    fidelity: Fidelity::Thesis,
    solver: Solver::Laguerre,
    sampler: TimeSampler::Table,
    accel: Accel::Auto,
};

pub fn scene_with(objects: Vec<ObjectRecord>) -> Scene {
    let mut scene = super::scene();
    scene.object_pos = vec![Pos::default(); objects.len()];
    scene.objects = objects;
    scene
}

pub fn object(class: PrimitiveClass, sw: SweepShape) -> ObjectRecord {
    ObjectRecord {
        name: "sw".into(),
        class,
        surface: 0,
        transfm: DMat4::IDENTITY,
        inverse: DMat4::IDENTITY,
        sphereo: DVec3::ZERO,
        angle: DVec3::ZERO,
        radius: 0.0,
        shape: Shape::Sweep(sw),
    }
}

pub fn raw(curve: CurveKind, points: Vec<[f64; 2]>, length: f64, scale: f64) -> SweepShape {
    SweepShape {
        orientt: Axis::Z,
        curve,
        points,
        segment: 0,
        u: vec![],
        v: vec![],
        length,
        scale,
        bbox: BoundingBox::default(),
        orientation: 0.0,
    }
}

/// A prepared sweep (Thesis boxes).
pub fn sweep(class: PrimitiveClass, curve: CurveKind, points: Vec<[f64; 2]>, length: f64, scale: f64) -> SweepShape {
    let mut scene = scene_with(vec![object(class, raw(curve, points, length, scale))]);
    prepare_sweeps(&mut scene, Fidelity::Thesis);
    match scene.objects.pop().unwrap().shape {
        Shape::Sweep(sw) => sw,
        _ => unreachable!(),
    }
}

/// Control points on a circle of radius ρ.
pub fn ring(n: usize, rho: f64, cx: f64, cy: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|j| {
            let a = TAU * j as f64 / n as f64;
            [cx + rho * a.cos(), cy + rho * a.sin()]
        })
        .collect()
}

/// 12 B-spline points whose curve passes through radius R at the joints:
/// a joint is (P_i + 4P_{i+1} + P_{i+2})/6, of radius ρ(4 + 2cos θ)/6.
pub fn circle_points(r: f64) -> Vec<[f64; 2]> {
    let theta = TAU / 12.0;
    ring(12, r * 6.0 / (4.0 + 2.0 * theta.cos()), 0.0, 0.0)
}

/// The nearest point of the contour to q: (distance, segment, s).
pub fn nearest(sw: &SweepShape, q: [f64; 2]) -> (f64, usize, f64) {
    let mut best = (f64::INFINITY, 0, 0.0);
    for i in 0..sw.segment {
        let (u, v) = (&sw.u[i], &sw.v[i]);
        for j in 0..=200 {
            let mut s = j as f64 / 200.0;
            // Newton on (c(s) − q)·c′(s) = 0.
            for _ in 0..30 {
                let (x, y, dx, dy, ddx, ddy) = (
                    u.value(s),
                    v.value(s),
                    u.slope(s),
                    v.slope(s),
                    u.curvature(s),
                    v.curvature(s),
                );
                let g = (x - q[0]) * dx + (y - q[1]) * dy;
                let dg = dx * dx + dy * dy + (x - q[0]) * ddx + (y - q[1]) * ddy;
                if dg <= 0.0 {
                    break;
                }
                s = (s - g / dg).clamp(0.0, 1.0);
            }
            let dist = (u.value(s) - q[0]).hypot(v.value(s) - q[1]);
            if dist < best.0 {
                best = (dist, i, s);
            }
        }
    }
    best
}

/// Even–odd test against a dense polygon of the contour (independent of
/// the driver's own test).
pub fn inside_polygon(sw: &SweepShape, q: [f64; 2]) -> bool {
    let mut pts = vec![];
    for i in 0..sw.segment {
        for j in 0..400 {
            let s = j as f64 / 400.0;
            pts.push([sw.u[i].value(s), sw.v[i].value(s)]);
        }
    }
    let mut inside = false;
    let n = pts.len();
    for i in 0..n {
        let (a, b) = (pts[i], pts[(i + 1) % n]);
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let x = a[0] + (q[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if x > q[0] {
                inside = !inside;
            }
        }
    }
    inside
}

pub fn size_of(sw: &SweepShape) -> f64 {
    let b = &sw.bbox;
    [b.xmin, b.xmax, b.ymin, b.ymax, b.zmin, b.zmax]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// Independent check of one hit: the relative distance from the surface
/// and, for a side hit, the normal against the surface tangents. Returns
/// (relative residual, |n·tangents| worst, |n| − 1).
pub fn check_hit(class: PrimitiveClass, sw: &SweepShape, hit: &LocalHit) -> (f64, f64, f64) {
    let size = size_of(sw);
    let p = hit.point;
    let n = hit.normal;
    let unit = (n.length() - 1.0).abs();
    match class {
        PrimitiveClass::Rotation => {
            let r = p.x.hypot(p.y);
            let (dist, i, s) = nearest(sw, [r, p.z]);
            let (u, v) = (&sw.u[i], &sw.v[i]);
            let er = if r > 1e-9 {
                DVec3::new(p.x / r, p.y / r, 0.0)
            } else {
                DVec3::X
            };
            let t1 = (er * u.slope(s) + DVec3::Z * v.slope(s)).normalize_or_zero();
            let t2 = DVec3::new(-er.y, er.x, 0.0);
            (dist / size, n.dot(t1).abs().max(n.dot(t2).abs()), unit)
        }
        _ => {
            let kappa = kappa(class, sw);
            let k = 1.0 + kappa * p.z;
            let mut side = f64::INFINITY;
            let mut perp = 0.0f64;
            if p.z >= -1e-9 && p.z <= sw.length + 1e-9 && k.abs() > 1e-12 {
                let (dist, i, s) = nearest(sw, [p.x / k, p.y / k]);
                side = dist * k.abs();
                let (u, v) = (&sw.u[i], &sw.v[i]);
                let t1 = DVec3::new(u.slope(s), v.slope(s), 0.0).normalize_or_zero();
                let t2 = DVec3::new(kappa * u.value(s), kappa * v.value(s), 1.0).normalize();
                perp = n.dot(t1).abs().max(n.dot(t2).abs());
            }
            let kc = 1.0 + kappa * sw.length;
            let cap0 = if inside_polygon(sw, [p.x, p.y]) {
                p.z.abs()
            } else {
                f64::INFINITY
            };
            let cap1 = if kc != 0.0 && inside_polygon(sw, [p.x / kc, p.y / kc]) {
                (p.z - sw.length).abs()
            } else {
                f64::INFINITY
            };
            let cap = cap0.min(cap1);
            if cap < side {
                let want = if (p.z - sw.length).abs() < p.z.abs() { 1.0 } else { -1.0 };
                (cap / size, (n - DVec3::new(0.0, 0.0, want)).length(), unit)
            } else {
                (side / size, perp, unit)
            }
        }
    }
}

pub fn star_points(n: usize, r1: f64, r2: f64) -> Vec<[f64; 2]> {
    (0..2 * n)
        .map(|j| {
            let a = PI * j as f64 / n as f64;
            let r = if j % 2 == 0 { r1 } else { r2 };
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

/// A sphere of radius r as a rotation sweep: two Bezier quarter arcs from
/// the south pole to the north pole, then straight down the axis.
pub fn sphere_points(r: f64) -> Vec<[f64; 2]> {
    let k = 4.0 / 3.0 * (2f64.sqrt() - 1.0) * r;
    vec![
        [0.0, -r],
        [k, -r],
        [r, -k],
        [r, 0.0],
        [r, k],
        [k, r],
        [0.0, r],
        [0.0, r / 3.0],
        [0.0, -r / 3.0],
    ]
}

/// The test shapes: (name, class, sweep).
pub fn shapes() -> Vec<(&'static str, PrimitiveClass, SweepShape)> {
    use CurveKind::*;
    use PrimitiveClass::*;
    vec![
        (
            "circle",
            Translation,
            sweep(Translation, Bspline, circle_points(1.0), 2.0, 1.0),
        ),
        (
            "star",
            Translation,
            sweep(Translation, Bspline, star_points(8, 1.2, 0.6), 1.5, 1.0),
        ),
        (
            "bezier-blob",
            Translation,
            sweep(
                Translation,
                Bezier,
                vec![
                    [-1.0, -1.0],
                    [0.0, -1.5],
                    [1.0, -1.0],
                    [1.5, -0.5],
                    [1.5, 0.5],
                    [1.0, 1.0],
                    [0.5, 1.5],
                    [-0.5, 1.5],
                    [-1.0, 1.0],
                    [-1.0, 0.3],
                    [-1.0, -0.3],
                    [-1.0, -0.6],
                ],
                1.0,
                1.0,
            ),
        ),
        ("frustum", Conic, sweep(Conic, Bspline, circle_points(1.0), 2.0, 0.5)),
        (
            "star-cone",
            Conic,
            sweep(Conic, Bspline, star_points(5, 1.2, 0.7), 2.0, 0.0),
        ),
        (
            "flare",
            Conic,
            sweep(
                Conic,
                Bezier,
                sphere_points(1.0).into_iter().take(6).collect(),
                1.0,
                1.8,
            ),
        ),
        (
            "star-cw",
            Translation,
            sweep(
                Translation,
                Bspline,
                star_points(8, 1.2, 0.6).into_iter().rev().collect(),
                1.5,
                1.0,
            ),
        ),
        (
            "torus",
            Rotation,
            sweep(Rotation, Bspline, ring(12, 0.55, 2.0, 0.0), 0.0, 1.0),
        ),
        (
            "sphere",
            Rotation,
            sweep(Rotation, Bezier, sphere_points(1.0), 0.0, 1.0),
        ),
        ("vase", Rotation, sweep(Rotation, Bspline, vase_points(), 0.0, 1.0)),
        (
            "sphere-cw",
            Rotation,
            sweep(Rotation, Bezier, reversed_bezier(sphere_points(1.0)), 0.0, 1.0),
        ),
    ]
}

/// The same composite Bezier contour run the other way.
pub fn reversed_bezier(mut p: Vec<[f64; 2]>) -> Vec<[f64; 2]> {
    p[1..].reverse();
    p
}

/// A vase wall (B-spline, closed, clear of the axis).
pub fn vase_points() -> Vec<[f64; 2]> {
    vec![
        [0.4, 0.0],
        [1.0, 0.0],
        [1.2, 0.6],
        [0.6, 1.4],
        [0.7, 2.2],
        [0.9, 2.5],
        [0.8, 2.6],
        [0.55, 2.2],
        [0.45, 1.4],
        [0.9, 0.7],
        [0.7, 0.2],
        [0.4, 0.15],
    ]
}

/// A random ray from a sphere of radius 8 about the box centre, aimed at a
/// random point of the box.
pub fn random_ray(rng: &mut Rng, sw: &SweepShape, class: PrimitiveClass) -> Ray {
    let (lo, hi) = super::sweep_box(class, sw);
    let centre = (lo + hi) * 0.5;
    let origin = centre + rng.unit() * 8.0;
    let target = DVec3::new(rng.range(lo.x, hi.x), rng.range(lo.y, hi.y), rng.range(lo.z, hi.z));
    Ray::new(origin, (target - origin).normalize())
}

/// κ of a sweep's contour scale k(z) = 1 + κz: (scale − 1)/length for a
/// conic sweep, 0 for a translation.
pub fn kappa(class: PrimitiveClass, sw: &SweepShape) -> f64 {
    if class == PrimitiveClass::Conic {
        (sw.scale - 1.0) / sw.length
    } else {
        0.0
    }
}

/// Both solvers, robust first.
pub fn both() -> [Options; 2] {
    [ROBUST, LAGUERRE]
}

/// The hit of the ray from `o` along `d` (normalized), with the cache a
/// render makes for the sweep.
pub fn hit(class: PrimitiveClass, sw: &SweepShape, o: [f64; 3], d: [f64; 3], opts: &Options) -> Option<LocalHit> {
    let ray = Ray::new(DVec3::from_array(o), DVec3::from_array(d).normalize());
    let cache = SweepCache::new(class, sw);
    let obj = Sweep {
        class,
        shape: sw,
        cache: cache.as_ref(),
    };
    obj.intersect(&ray, 1e-9, opts, &mut 0)
}

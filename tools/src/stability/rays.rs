//! The geometric families: constructed rays against constructed sweeps,
//! with the true first hit known by construction or analytically.

use std::fmt::Write;
use std::path::Path;

use raytrace::shapes::sweep::{Sweep, SweepCache};
use raytrace::types::{Coeff, DVec3, PrimitiveClass, Ray, Shape, SweepShape};

use raytrace::options::{Fidelity, Options};

use super::{Rng, GRAZE};

/// A sweep for the geometric families, prepared as a renderer would.
#[derive(Clone, Debug)]
pub struct TestSweep {
    pub name: String,
    pub class: PrimitiveClass,
    pub sweep: SweepShape,
    /// The cache a render makes for it (`None` for a contour of the
    /// moment).
    pub cache: Option<SweepCache>,
    /// The largest coordinate of its box: the scale of the hit tolerance.
    pub size: f64,
}

impl TestSweep {
    /// The sweep as its driver meets it, with its cache.
    pub fn object(&self) -> Sweep<'_> {
        Sweep {
            class: self.class,
            shape: &self.sweep,
            cache: self.cache.as_ref(),
        }
    }
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
    let scene = crate::decks::load_source(&deck, name, Path::new("."), Fidelity::Thesis)
        .unwrap_or_else(|e| panic!("the constructed sweep {name} is a valid deck: {e}"));
    let mut scene = crate::decks::prepare(scene, &Options::default())
        .unwrap_or_else(|e| panic!("the constructed sweep {name} prepares: {e}"))
        .scene()
        .clone();
    let obj = scene.objects.pop().expect("one object");
    let Shape::Sweep(sweep) = obj.shape else {
        panic!("{name} is a sweep")
    };
    let size = box_size(&sweep);
    TestSweep {
        name: name.to_string(),
        class: obj.class,
        cache: SweepCache::new(obj.class, &sweep),
        sweep,
        size,
    }
}

/// The largest coordinate of a sweep's box.
pub(super) fn box_size(sweep: &SweepShape) -> f64 {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stability::{tally_rays, Method};

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

    #[test]
    fn straight_bezier_has_thirds() {
        let p = straight_bezier(&[[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]]);
        assert_eq!(p.len(), 9);
        assert_eq!(p[1], [1.0, 0.0]);
        assert_eq!(p[5], [1.0, 2.0]);
    }
}

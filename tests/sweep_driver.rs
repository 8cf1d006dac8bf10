//! The reconstructed sweep intersection driver (§2.3, §3.3) on random
//! rays: hits on the surface with true normals, against quadrics, and
//! laguerre against the robust solver.

mod common;
use common::sweeps::*;
use raytrace::shapes::sweep::{Sweep, SweepCache};
use raytrace::types::*;

// ---------------------------------------------------------------------------
// The intersection driver

/// Every hit lies on the surface (relative residual < 1e-9); its normal is
/// unit and perpendicular to both surface tangents; for every solver and
/// fidelity; and each way in is at least as near as the robust solver's.
#[test]
fn hits_lie_on_the_surface_with_true_normals() {
    let mut rng = Rng(7);
    for (name, class, sw) in shapes() {
        let cache = SweepCache::new(class, &sw);
        let obj = Sweep {
            class,
            shape: &sw,
            cache: cache.as_ref(),
        };
        let mut hits = 0;
        for _ in 0..300 {
            let ray = random_ray(&mut rng, &sw, class);
            for opts in OPTS {
                if let Some(h) = obj.intersect(&ray, 1e-9, &opts, &mut 0) {
                    hits += 1;
                    let (res, perp, unit) = check_hit(class, &sw, &h);
                    assert!(res < 1e-9, "{name} {opts:?}: residual {res:e} at {h:?}");
                    assert!(unit < 1e-12, "{name}: |n| − 1 = {unit:e}");
                    assert!(perp < 1e-7, "{name} {opts:?}: n·tangent {perp:e} at {h:?}");
                    assert!((ray.at(h.t) - h.point).length() < 1e-12);
                }
            }
        }
        assert!(hits > 300, "{name}: only {hits} hits");
    }
}

/// Normals point out: a step along the normal leaves the solid, a step
/// against it enters (away from rims and cusps).
#[test]
fn normals_point_outward() {
    let mut rng = Rng(11);
    for (name, class, sw) in shapes() {
        let size = size_of(&sw);
        let eps = 1e-4 * size;
        let cache = SweepCache::new(class, &sw);
        let obj = Sweep {
            class,
            shape: &sw,
            cache: cache.as_ref(),
        };
        let mut checked = 0;
        for _ in 0..300 {
            let ray = random_ray(&mut rng, &sw, class);
            let Some(h) = obj.intersect(&ray, 1e-9, &ROBUST, &mut 0) else {
                continue;
            };
            let out = h.point + h.normal * eps;
            let inn = h.point - h.normal * eps;
            let (Some(a), Some(b)) = (
                solid_inside(class, &sw, out, 0.5 * eps),
                solid_inside(class, &sw, inn, 0.5 * eps),
            ) else {
                continue;
            };
            assert!(!a && b, "{name}: normal {:?} at {:?}", h.normal, h.point);
            checked += 1;
        }
        assert!(checked > 100, "{name}: {checked}");
    }
}

/// Inside the solid? `None` within `margin` of a rim or the contour.
fn solid_inside(class: PrimitiveClass, sw: &SweepShape, p: DVec3, margin: f64) -> Option<bool> {
    match class {
        PrimitiveClass::Rotation => {
            let q = [p.x.hypot(p.y), p.z];
            if nearest(sw, q).0 < margin {
                return None;
            }
            Some(inside_polygon(sw, q))
        }
        _ => {
            let kappa = kappa(class, sw);
            let k = 1.0 + kappa * p.z;
            if p.z.abs() < margin || (p.z - sw.length).abs() < margin || k.abs() < 1e-3 {
                return None;
            }
            if p.z < 0.0 || p.z > sw.length {
                return Some(false);
            }
            let q = [p.x / k, p.y / k];
            if nearest(sw, q).0 * k.abs() < margin {
                return None;
            }
            Some(inside_polygon(sw, q))
        }
    }
}

/// The translation sweep of a 12-point B-spline circle matches a cylinder
/// of radius R: each hit's distance differs from the cylinder's by no more
/// than the contour's own measured deviation from the circle allows.
#[test]
fn circle_sweep_matches_a_cylinder() {
    let (r, len) = (1.0, 2.0);
    let sw = sweep(
        PrimitiveClass::Translation,
        CurveKind::Bspline,
        circle_points(r),
        len,
        1.0,
    );
    // The contour's deviation from radius R, measured densely.
    let mut dev = 0.0f64;
    for i in 0..sw.segment {
        for j in 0..=1000 {
            let s = j as f64 / 1000.0;
            dev = dev.max((sw.u[i].value(s).hypot(sw.v[i].value(s)) - r).abs());
        }
    }
    assert!(dev > 1e-4 && dev < 2e-2, "deviation {dev}");
    let cache = SweepCache::new(PrimitiveClass::Translation, &sw);
    let obj = Sweep {
        class: PrimitiveClass::Translation,
        shape: &sw,
        cache: cache.as_ref(),
    };
    let mut rng = Rng(3);
    let mut sides = 0;
    let mut caps = 0;
    for _ in 0..2000 {
        let ray = random_ray(&mut rng, &sw, PrimitiveClass::Translation);
        let cyl = cylinder_hit(r, len, &ray);
        for opts in [ROBUST, LAGUERRE] {
            let got = obj.intersect(&ray, 1e-9, &opts, &mut 0);
            match (cyl, got) {
                (Some((tc, nc)), Some(h)) => {
                    if nc.z.abs() > 0.5 {
                        // A cap: the same plane; near the rim the sweep's
                        // side may come first, within the deviation.
                        if (h.normal - nc).length() < 1e-12 {
                            assert!((h.t - tc).abs() < 1e-9);
                            caps += 1;
                        } else {
                            assert!((h.t - tc).abs() < dev * 50.0, "rim: {} vs {tc}", h.t);
                        }
                    } else {
                        let cos = ray.dir.dot(nc).abs();
                        if cos > 0.3 {
                            let rr = h.point.x.hypot(h.point.y);
                            assert!((rr - r).abs() <= dev + 1e-12, "radius {rr}");
                            // First order in the deviation; 1.5 for the curvature.
                            assert!((h.t - tc).abs() <= 1.5 * dev / cos, "t {} vs {tc}, cos {cos}", h.t);
                            assert!(h.normal.dot(nc) > 0.95);
                            sides += 1;
                        }
                    }
                }
                (None, None) => {}
                // A grazing ray may meet one and miss the other: check
                // that the cylinder's hit is within the deviation of its
                // rim or silhouette.
                (Some((tc, _)), None) => {
                    let p = ray.at(tc);
                    let near_rim = (p.x.hypot(p.y) - r).abs() < 2.0 * dev;
                    let grazing = ray_min_radius(&ray) > r - 2.0 * dev;
                    assert!(near_rim || grazing, "{opts:?}: missed the sweep at t = {tc}");
                }
                (None, Some(h)) => {
                    assert!(
                        ray_min_radius(&ray) > r - 2.0 * dev || {
                            let p = h.point;
                            (p.x.hypot(p.y) - r).abs() < 2.0 * dev
                        }
                    );
                }
            }
        }
    }
    assert!(sides > 500 && caps > 200, "sides {sides}, caps {caps}");
}

/// The least distance of the ray's line from the z axis.
fn ray_min_radius(ray: &Ray) -> f64 {
    let (o, d) = (ray.origin, ray.dir);
    let a = d.x * d.x + d.y * d.y;
    if a == 0.0 {
        return o.x.hypot(o.y);
    }
    let t = -(o.x * d.x + o.y * d.y) / a;
    (o.x + t * d.x).hypot(o.y + t * d.y)
}

/// The analytic capped cylinder x² + y² ≤ r², 0 ≤ z ≤ len: (t, normal).
fn cylinder_hit(r: f64, len: f64, ray: &Ray) -> Option<(f64, DVec3)> {
    let (o, d) = (ray.origin, ray.dir);
    let mut best: Option<(f64, DVec3)> = None;
    let mut take = |t: f64, n: DVec3| {
        if t > 1e-9 && best.is_none_or(|b| t < b.0) {
            best = Some((t, n));
        }
    };
    let a = d.x * d.x + d.y * d.y;
    let b = 2.0 * (o.x * d.x + o.y * d.y);
    let c = o.x * o.x + o.y * o.y - r * r;
    let disc = b * b - 4.0 * a * c;
    if a > 0.0 && disc >= 0.0 {
        for t in [(-b - disc.sqrt()) / (2.0 * a), (-b + disc.sqrt()) / (2.0 * a)] {
            let p = ray.at(t);
            if (0.0..=len).contains(&p.z) {
                take(t, DVec3::new(p.x, p.y, 0.0) / r);
            }
        }
    }
    if d.z != 0.0 {
        for (zc, nz) in [(0.0, -1.0), (len, 1.0)] {
            let t = (zc - o.z) / d.z;
            let p = ray.at(t);
            if p.x * p.x + p.y * p.y <= r * r {
                take(t, DVec3::new(0.0, 0.0, nz));
            }
        }
    }
    best
}

/// How often laguerre's nearest hit is not the robust solver's, per shape,
/// on 2000 random rays (fixed seed): (shape, rays hitting by robust, laguerre
/// missing the hit, laguerre hitting farther, laguerre hitting nearer).
fn solver_disagreements() -> Vec<(&'static str, usize, usize, usize, usize)> {
    let mut rng = Rng(0xD15A);
    let mut out = vec![];
    for (name, class, sw) in shapes() {
        let (mut hits, mut missed, mut farther, mut nearer) = (0, 0, 0, 0);
        let cache = SweepCache::new(class, &sw);
        let obj = Sweep {
            class,
            shape: &sw,
            cache: cache.as_ref(),
        };
        for _ in 0..2000 {
            let ray = random_ray(&mut rng, &sw, class);
            let r = obj.intersect(&ray, 1e-9, &ROBUST, &mut 0);
            let l = obj.intersect(&ray, 1e-9, &LAGUERRE, &mut 0);
            match (r, l) {
                (Some(r), Some(l)) => {
                    hits += 1;
                    if l.t > r.t + 1e-7 {
                        farther += 1;
                    } else if l.t < r.t - 1e-7 {
                        nearer += 1;
                    }
                }
                (Some(_), None) => {
                    hits += 1;
                    missed += 1;
                }
                (None, Some(_)) => nearer += 1,
                (None, None) => {}
            }
        }
        out.push((name, hits, missed, farther, nearer));
    }
    out
}

/// Laguerre's nearest hit against the robust solver's on 2000 random rays
/// a shape (fixed seed), measured and pinned (docs/laguerre_misses.md).
/// Laguerre never hits nearer: a root it misses leaves a hole or shows
/// the surface behind, never a false surface.
#[test]
fn laguerre_against_robust_on_random_rays() {
    let got = solver_disagreements();
    println!("{got:#?}");
    assert_eq!(got, EXPECTED_DISAGREEMENTS.to_vec());
    assert!(got.iter().all(|r| r.4 == 0));
}

/// (shape, rays the robust solver hits, laguerre misses the object,
/// laguerre's hit farther, laguerre's hit nearer).
const EXPECTED_DISAGREEMENTS: [(&str, usize, usize, usize, usize); 11] = [
    ("circle", 1794, 0, 0, 0),
    ("star", 1469, 0, 1, 0),
    ("bezier-blob", 1755, 0, 8, 0),
    ("frustum", 1428, 0, 0, 0),
    ("star-cone", 895, 0, 2, 0),
    ("flare", 1100, 1, 14, 0),
    ("star-cw", 1477, 0, 2, 0),
    ("torus", 1420, 0, 1, 0),
    ("sphere", 1553, 11, 3, 0),
    ("vase", 1420, 1, 0, 0),
    ("sphere-cw", 1550, 6, 12, 0),
];

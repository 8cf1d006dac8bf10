//! The blobs' and patches' families (§6.2, the port's extension):
//! constructed rays against constructed blobs and patches, where each
//! method fails. A blob's hit is a root of a quartic a chord interval,
//! found by the method's solver (`shapes::blob`); a patch has one method,
//! its pieces' certified Newton steps and Bezier clipping
//! (`shapes::patch`), the same for every solver.

use raytrace::options::Options;
use raytrace::shapes::blob::intersect_blob;
use raytrace::shapes::patch::{intersect_patch, patch_point};
use raytrace::shapes::{blob_box, blob_reach, patch_box, patch_reach, ShapeCache};
use raytrace::types::{BlobComponent, BlobShape, BoundingBox, DVec3, PatchShape, Ray, Shape};

use super::{time_per_case, Rng, Tally, HIT_TOL};

/// A blob or a patch with what the render prepares for it.
pub struct SoftShape {
    pub shape: Shape,
    pub cache: Option<ShapeCache>,
    /// The radius of a sphere about the local origin that holds it.
    pub reach: f64,
    /// Its box's largest coordinate: the scale of the hit tolerance.
    pub size: f64,
}

impl SoftShape {
    pub fn new(shape: Shape) -> SoftShape {
        let (reach, b) = match &shape {
            Shape::Blob(b) => (blob_reach(b), blob_box(b).unwrap_or_default()),
            Shape::Patch(p) => (patch_reach(p), patch_box(p)),
            _ => (0.0, BoundingBox::default()),
        };
        let size = [b.xmin, b.xmax, b.ymin, b.ymax, b.zmin, b.zmax]
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()));
        SoftShape {
            cache: ShapeCache::of_moment(&shape),
            shape,
            reach,
            size,
        }
    }

    /// The first hit's t beyond 1e-9 with `opts`' solver.
    pub fn hit(&self, ray: &Ray, opts: &Options) -> Option<f64> {
        let cache = self.cache.as_ref();
        match &self.shape {
            Shape::Blob(b) => intersect_blob(b, cache.and_then(ShapeCache::blob), self.reach, ray, 1e-9, opts, &mut 0),
            Shape::Patch(p) => intersect_patch(p, cache.and_then(ShapeCache::patch), self.reach, ray, 1e-9, &mut 0),
            _ => None,
        }
        .map(|h| h.t)
    }
}

/// Constructed rays against blobs or patches, each with its true first
/// hit (or none).
pub struct SoftFamily {
    pub name: String,
    /// How the true hit is known.
    pub truth: &'static str,
    /// Blobs (every solver) or patches (one method).
    pub patches: bool,
    pub shapes: Vec<SoftShape>,
    /// (shape, ray, true hit).
    pub cases: Vec<(usize, Ray, Option<f64>)>,
}

/// What a method does on a family (as [`super::tally_rays`] for sweeps).
pub fn tally_soft(opts: &Options, fam: &SoftFamily) -> Tally {
    let mut t = Tally {
        cases: fam.cases.len(),
        ..Tally::default()
    };
    for (k, ray, truth) in &fam.cases {
        let shape = &fam.shapes[*k];
        let got = shape.hit(ray, opts);
        t.truths += truth.is_some() as usize;
        match (*truth, got) {
            (Some(want), Some(g)) if (g - want).abs() <= HIT_TOL * shape.size => {
                t.worst = t.worst.max((g - want).abs() / shape.size)
            }
            (Some(want), Some(g)) if g > want => t.missed += 1,
            (Some(_), Some(_)) | (None, Some(_)) => t.spurious += 1,
            (Some(_), None) => t.missed += 1,
            (None, None) => {}
        }
    }
    t.ns = time_per_case(fam.cases.len(), || {
        for (k, ray, _) in &fam.cases {
            std::hint::black_box(fam.shapes[*k].hit(std::hint::black_box(ray), opts));
        }
    });
    t
}

/// A blob of the given components (centre, radius, strength).
fn blob(threshold: f64, parts: &[(DVec3, f64, f64)]) -> Shape {
    Shape::Blob(BlobShape {
        threshold,
        components: parts
            .iter()
            .map(|&(centre, radius, strength)| BlobComponent {
                centre,
                radius,
                strength,
            })
            .collect(),
    })
}

/// A random unit vector.
fn unit(rng: &mut Rng) -> DVec3 {
    loop {
        let v = DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        let l = v.length();
        if l > 0.1 && l <= 1.0 {
            break v / l;
        }
    }
}

/// The first t > 1e-9 where the ray meets the sphere of radius `r` about
/// `c`.
fn sphere_truth(c: DVec3, r: f64, ray: &Ray) -> Option<f64> {
    let oc = ray.origin - c;
    let (a, b, cc) = (ray.dir.length_squared(), oc.dot(ray.dir), oc.length_squared() - r * r);
    let disc = b * b - a * cc;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    [(-b - s) / a, (-b + s) / a].into_iter().find(|&t| t > 1e-9)
}

/// The radius of one component's surface: S(1 − ρ²/R²)² = T.
fn surface_radius(radius: f64, strength: f64, threshold: f64) -> f64 {
    radius * (1.0 - (threshold / strength).sqrt()).sqrt()
}

/// The first t at which the field along the ray reaches the threshold,
/// by stepping 4000 times over the ray's span through the blob's sphere
/// and halving the first step that crosses, to rounding: a reference that
/// misses only a root pair closer than a step (a ray grazing the surface).
fn field_truth(shape: &Shape, ray: &Ray) -> Option<f64> {
    let Shape::Blob(b) = shape else { return None };
    let f = |t: f64| raytrace::shapes::blob::field(b, ray.at(t)).0;
    let (t0, t1) = (1e-9, (ray.origin.length() + blob_reach(b)) / ray.dir.length());
    let steps = 4000;
    let mut prev = (t0, f(t0));
    for i in 1..=steps {
        let t = t0 + (t1 - t0) * i as f64 / steps as f64;
        let v = f(t);
        if (v >= 0.0) != (prev.1 >= 0.0) {
            let (mut lo, mut hi) = (prev.0, t);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if (f(mid) >= 0.0) == (prev.1 >= 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
        prev = (t, v);
    }
    None
}

/// A ray from 6 sizes away from `at`, aimed at it along `dir` (unit).
fn toward(at: DVec3, dir: DVec3, size: f64) -> Ray {
    Ray::new(at - dir * 6.0 * size, dir)
}

/// A family of `per` cases, each a blob (or patch), a ray and its true
/// hit from `make`.
fn family(
    name: String,
    truth: &'static str,
    per: usize,
    rng: &mut Rng,
    mut make: impl FnMut(&mut Rng) -> (Shape, Ray, Option<f64>),
) -> SoftFamily {
    let (mut shapes, mut cases) = (Vec::new(), Vec::new());
    for k in 0..per {
        let (shape, ray, hit) = make(rng);
        shapes.push(SoftShape::new(shape));
        cases.push((k, ray, hit));
    }
    SoftFamily {
        name,
        truth,
        patches: false,
        shapes,
        cases,
    }
}

/// The blob families (see the module doc).
pub fn blob_families(per: usize) -> Vec<SoftFamily> {
    let mut rng = Rng(0xB10B_0001);
    // One component: a sphere of known radius (R, S, T, and the surface's).
    let one = |rng: &mut Rng| {
        let (r, s, t) = (rng.range(0.5, 2.0), rng.range(0.5, 3.0), rng.range(0.05, 0.4));
        let s = s.max(t * 1.5);
        (r, s, t, surface_radius(r, s, t))
    };
    let mut fams = vec![family(
        "one component, rays into its surface's sphere".into(),
        "analytic: one component's surface is the sphere of radius R·√(1 − √(T/S))",
        per,
        &mut rng,
        |rng| {
            let (r, s, t, rho) = one(rng);
            let target = unit(rng) * rho * rng.range(0.0, 0.999);
            let ray = toward(target, unit(rng), r);
            (
                blob(t, &[(DVec3::ZERO, r, s)]),
                ray,
                sphere_truth(DVec3::ZERO, rho, &ray),
            )
        },
    )];
    fams.push(family(
        format!(
            "one component, grazing rays (double roots), {:.0e} inside the tangent",
            super::GRAZE
        ),
        "analytic: the surface's sphere, the ray tangent to it moved inward",
        per,
        &mut rng,
        |rng| {
            let (r, s, t, rho) = one(rng);
            // Tangent at a point of the surface, moved inward by 1e-13 of the size.
            let n = unit(rng);
            let ray = toward(n * (rho - super::GRAZE * r), n.cross(unit(rng)).normalize(), r);
            (
                blob(t, &[(DVec3::ZERO, r, s)]),
                ray,
                sphere_truth(DVec3::ZERO, rho, &ray),
            )
        },
    ));
    // Two components whose spheres touch: their fields never meet, each
    // surface is its own sphere; rays aimed near the point they touch.
    fams.push(family(
        "two components whose spheres touch, rays near the touching point".into(),
        "analytic: the two fields never overlap, each surface its own sphere",
        per,
        &mut rng,
        |rng| {
            let (r1, s1, t, rho1) = one(rng);
            let (r2, s2) = (rng.range(0.5, 2.0), rng.range(t * 1.5, 3.0));
            let axis = unit(rng);
            let c2 = axis * (r1 + r2);
            let near_touch = axis * r1 + unit(rng) * rng.range(0.0, 0.3) * r1.min(r2);
            let ray = toward(near_touch, unit(rng), r1 + r2);
            let truth = [
                sphere_truth(DVec3::ZERO, rho1, &ray),
                sphere_truth(c2, surface_radius(r2, s2, t), &ray),
            ]
            .into_iter()
            .flatten()
            .reduce(f64::min);
            (blob(t, &[(DVec3::ZERO, r1, s1), (c2, r2, s2)]), ray, truth)
        },
    ));
    // Overlapping components, one of them carving: the field's own
    // crossing by steps and halving.
    for (name, carve) in [
        ("overlapping components", false),
        ("overlapping components, one carving", true),
    ] {
        fams.push(family(
            format!("{name}, random rays"),
            "the field's first crossing along the ray: 4000 steps, then halving to rounding",
            per,
            &mut rng,
            |rng| {
                let parts: Vec<(DVec3, f64, f64)> = (0..5)
                    .map(|j| {
                        let s = if carve && j == 4 {
                            -rng.range(0.5, 1.5)
                        } else {
                            rng.range(0.6, 1.5)
                        };
                        (unit(rng) * rng.range(0.0, 1.0), rng.range(0.6, 1.2), s)
                    })
                    .collect();
                let shape = blob(0.4, &parts);
                let ray = toward(unit(rng) * rng.range(0.0, 1.2), unit(rng), 2.5);
                let truth = field_truth(&shape, &ray);
                (shape, ray, truth)
            },
        ));
    }
    fams
}

/// A concave cap z = 2 − x² − y² over [−1, 1]² (exact as a bicubic: each
/// parabola's Bezier points 0, 4/3, 4/3, 0), the first row collapsed to
/// its middle point when `collapsed` (a near-degenerate patch: no tangent
/// plane along that edge).
fn cap(collapsed: bool) -> PatchShape {
    let z = [0.0, 4.0 / 3.0, 4.0 / 3.0, 0.0];
    let x = [-1.0, -1.0 / 3.0, 1.0 / 3.0, 1.0];
    PatchShape {
        points: std::array::from_fn(|k| {
            let (r, c) = (k / 4, k % 4);
            if collapsed && r == 0 {
                DVec3::new(0.0, -1.0, 2.0 * z[1] - 2.0)
            } else {
                DVec3::new(x[c], x[r], z[c] + z[r])
            }
        }),
    }
}

/// The patch families (see the module doc): rays aimed from above the
/// tangent plane at a point of the concave cap (the cap lies below every
/// tangent plane, so that point is the first hit), grazing rays in the
/// tangent plane, rays at the edges, vertical rays on a patch with a
/// collapsed edge (a height field: the point straight below is the hit)
/// and rays just past its edges (no hit).
pub fn patch_families(per: usize) -> Vec<SoftFamily> {
    let mut rng = Rng(0x9A7C_0001);
    let shapes = || vec![SoftShape::new(Shape::Patch(Box::new(cap(false))))];
    let on = |p: &PatchShape, u: f64, v: f64| {
        let (q, n) = patch_point(p, u, v);
        let n = n.unwrap_or(DVec3::Z);
        (q, if n.z < 0.0 { -n } else { n })
    };
    let t_at = |ray: &Ray, q: DVec3| (q - ray.origin).dot(ray.dir) / ray.dir.length_squared();
    let mut fams = Vec::new();
    let c = cap(false);
    let mut family = |name: &str,
                      truth: &'static str,
                      shapes: Vec<SoftShape>,
                      make: &mut dyn FnMut(&mut Rng) -> (Ray, Option<f64>)| {
        let cases = (0..per).map(|_| {
            let (ray, truth) = make(&mut rng);
            (0, ray, truth)
        });
        fams.push(SoftFamily {
            name: name.into(),
            truth,
            patches: true,
            shapes,
            cases: cases.collect(),
        });
    };
    family(
        "a concave cap, rays from above its tangent plane",
        "by construction: the cap lies below each tangent plane",
        shapes(),
        &mut |rng| {
            let (q, n) = on(&c, rng.uniform(), rng.uniform());
            let dir = (-n + unit(rng) * rng.range(0.0, 0.9)).normalize();
            let dir = if dir.dot(n) < -0.05 { dir } else { -n };
            let ray = toward(q, dir, 2.0);
            (ray, Some(t_at(&ray, q)))
        },
    );
    family(
        &format!(
            "a concave cap, grazing rays (double roots), {:.0e} inside the tangent",
            super::GRAZE
        ),
        "by construction: the tangent point, the two roots beside it within the tolerance",
        shapes(),
        &mut |rng| {
            let (q, n) = on(&c, rng.range(0.1, 0.9), rng.range(0.1, 0.9));
            let dir = n.cross(unit(rng)).normalize();
            let ray = toward(q - n * super::GRAZE * 2.0, dir, 2.0);
            (ray, Some(t_at(&ray, q)))
        },
    );
    family(
        "a concave cap, rays at its edges (within 1e-9 of u or v = 0 or 1)",
        "by construction: the cap lies below each tangent plane",
        shapes(),
        &mut |rng| {
            let edge = if rng.uniform() < 0.5 { 1e-9 } else { 1.0 - 1e-9 };
            let (u, v) = if rng.uniform() < 0.5 {
                (edge, rng.uniform())
            } else {
                (rng.uniform(), edge)
            };
            let (q, n) = on(&c, u, v);
            let ray = toward(q, -n, 2.0);
            (ray, Some(t_at(&ray, q)))
        },
    );
    let folded = cap(true);
    family(
        "a patch with a collapsed edge, vertical rays",
        "by construction: a height field, the point straight below",
        vec![SoftShape::new(Shape::Patch(Box::new(folded.clone())))],
        &mut |rng| {
            let (q, _) = on(&folded, rng.range(0.0, 1.0), rng.range(0.0, 1.0).powi(3));
            let ray = Ray::new(q + DVec3::Z * 10.0, DVec3::NEG_Z);
            (ray, Some(t_at(&ray, q)))
        },
    );
    family(
        "a concave cap, vertical rays 1e-9 past its edges",
        "by construction: outside the cap's shadow on the plane, no hit",
        shapes(),
        &mut |rng| {
            let s = rng.range(-1.0, 1.0);
            let past = 1.0 + 1e-9;
            let (x, y) = match (rng.uniform() * 4.0) as u32 {
                0 => (past, s),
                1 => (-past, s),
                2 => (s, past),
                _ => (s, -past),
            };
            (Ray::new(DVec3::new(x, y, 10.0), DVec3::NEG_Z), None)
        },
    );
    fams
}

/// The in-between blobs of sec6_2.deck at 8 instants of the shutter, and
/// random rays at them: the robust solver's hit the reference (as the
/// key-frame sweeps' families).
pub fn inbetween_blobs(per: usize) -> Result<SoftFamily, String> {
    let prepared = crate::decks::prepared("sec6_2", &Options::default(), None)?;
    let robust = super::Method::Robust.options();
    let mut shapes = Vec::new();
    for j in 0..8 {
        let still = prepared.still_at((j as f64 + 0.5) / 8.0);
        for obj in &still.scene().objects {
            if let Shape::Blob(_) = obj.shape {
                shapes.push(SoftShape::new(obj.shape.clone()));
            }
        }
    }
    let mut rng = Rng(0x6EA2_0062);
    let cases = (0..per)
        .map(|k| {
            let i = k % shapes.len();
            let ray = toward(
                unit(&mut rng) * rng.range(0.0, 0.8) * shapes[i].size,
                unit(&mut rng),
                shapes[i].size,
            );
            let truth = shapes[i].hit(&ray, &robust);
            (i, ray, truth)
        })
        .collect();
    Ok(SoftFamily {
        name: "in-between blobs of sec6_2.deck".into(),
        truth: "the robust solver's hit (the reference: its own row counts nothing)",
        patches: false,
        shapes,
        cases,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every family has cases with true hits, the robust solver finds the
    /// one-component blob's hits, and the patch's rays from above find the
    /// cap where it was aimed.
    #[test]
    fn the_families_are_built() {
        let robust = super::super::Method::Robust.options();
        for fam in blob_families(40).iter().chain(&patch_families(40)) {
            let truths = fam.cases.iter().filter(|c| c.2.is_some()).count();
            assert!(truths > 0 || fam.name.contains("past"), "{}", fam.name);
            if fam.name.starts_with("one component, rays") || fam.name.starts_with("a concave cap, rays from") {
                assert_eq!(tally_soft(&robust, fam).missed, 0, "{}", fam.name);
            }
        }
    }
}

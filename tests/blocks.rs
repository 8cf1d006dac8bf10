//! The shadow ray's yes/no questions against the nearest hits they stand
//! for ([`Posed::blocks`], [`block_blocks`]), and the ray re-based near an
//! object ([`Near::of`]), on rays whose arithmetic is exact, so that the
//! ties a boundary comparison decides (an entry at the exit, an entry at
//! `tmin`, a ray in a face's plane, a hit at `tmax`) happen exactly.
//!
//! What cargo-mutants changes in these functions and no test here sees
//! changes no answer: `block_blocks`' early exit on `exit <= tmin` or on
//! an entry at or past `tmax` (weakened, or fired only where the answer is
//! no) is repeated by its final test, which the exit makes true at the
//! entry and at `exit > tmin`; `>=` for `>` in keeping the largest entry
//! (and `<=` for `<`, the smallest exit) assigns an equal value; `slab`'s
//! `dk < 0` and `dk > 0` follow `dk == 0`; `Posed::blocks`' block and
//! sweep arms give the answer of the nearest hit they stand in for.

mod common;

use common::sweeps::{circle_points, sweep, Rng, ROBUST};
use raytrace::shapes::{blob_reach, block_blocks, intersect_block, patch_reach, Near, Posed, ShapeCache, SweepCache};
use raytrace::types::*;

/// The nearest hit's answer: a hit with t in (`tmin`, `tmax`).
fn nearest_before(hit: Option<LocalHit>, tmax: f64) -> bool {
    hit.is_some_and(|h| h.t < tmax)
}

/// The `tmax`es that decide a ray: at, just before and just after its
/// nearest hit, and ones with nothing to do with it.
fn tmaxes(hit: Option<LocalHit>, tmin: f64) -> Vec<f64> {
    let mut v = vec![0.0, tmin, 0.5, 1.0, 3.0, 1e9, f64::INFINITY, f64::NAN];
    if let Some(h) = hit {
        v.extend([h.t, h.t.next_up(), h.t.next_down(), 2.0 * h.t]);
    }
    v
}

/// Dyadic blocks, origins and directions: the slabs' quotients and the
/// re-basing shift (axis-parallel or |d|² a power of two) are exact, so
/// rays run exactly in a face's plane, through an edge or a corner (the
/// entry at the exit), start exactly on a face (the entry at `tmin` = 0),
/// start outside with `tmin` past the entry (the hit is the exit), and
/// their hits fall exactly at the `tmax` given. `block_blocks` answers
/// as the nearest hit of `intersect_block` before `tmax` on all of them.
#[test]
fn block_blocks_as_the_nearest_hit_on_exact_rays() {
    let steps = [-4.0, -2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0, 4.0];
    let comps = [-1.0, -0.5, -0.0, 0.0, 0.5, 1.0];
    let (mut yes, mut no, mut ties, mut in_plane, mut on_face) = (0, 0, 0, 0, 0);
    for lengths in [DVec3::new(2.0, 1.0, 4.0), DVec3::ONE, DVec3::new(0.5, 2.0, 2.0)] {
        let h = lengths * 0.5;
        for &sx in &steps {
            for &sy in &steps {
                for &sz in &steps {
                    let o = DVec3::new(sx, sy, sz) * h;
                    for &dx in &comps {
                        for &dy in &comps {
                            for &dz in &comps {
                                let d = DVec3::new(dx, dy, dz);
                                if d == DVec3::ZERO {
                                    continue;
                                }
                                let ray = Ray::new(o, d);
                                let on = (0..3).filter(|&k| o[k].abs() == h[k]).count();
                                if (0..3).any(|k| d[k] == 0.0 && o[k].abs() == h[k]) {
                                    in_plane += 1;
                                }
                                // Past the entry of a ray from afar too: the exit is the hit.
                                for tmin in [0.0, 1e-9, -1.0, 2.5, 4.5] {
                                    let nearest = intersect_block(lengths, &ray, tmin);
                                    if on >= 2 && nearest.is_some() {
                                        ties += 1; // from an edge or a corner
                                    }
                                    if on == 1 && tmin == 0.0 && nearest.is_some() {
                                        on_face += 1;
                                    }
                                    for tmax in tmaxes(nearest, tmin) {
                                        let want = nearest_before(nearest, tmax);
                                        let got = block_blocks(lengths, &ray, tmin, tmax);
                                        assert_eq!(got, want, "block {lengths} ray {o} {d} tmin {tmin} tmax {tmax}");
                                        (yes, no) = if want { (yes + 1, no) } else { (yes, no + 1) };
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    assert!(yes > 100_000 && no > 100_000, "{yes} {no}");
    assert!(
        ties > 1000 && in_plane > 1000 && on_face > 1000,
        "{ties} {in_plane} {on_face}"
    );
}

/// Exact ties, one at a time, with what the nearest hit says of them.
#[test]
fn block_blocks_at_its_ties() {
    let lengths = DVec3::new(2.0, 2.0, 2.0);
    // Re-based to the edge x = y = 1 (shift 1): the entry (−0 after the
    // y slab) equals the exit (0 after the x slab), a hit at t = 1.
    let edge = Ray::new(DVec3::new(0.0, 2.0, 0.25), DVec3::new(1.0, -1.0, 0.0));
    assert_eq!(intersect_block(lengths, &edge, 1e-9).map(|h| h.t), Some(1.0));
    assert!(block_blocks(lengths, &edge, 1e-9, 1.5));
    assert!(block_blocks(lengths, &edge, 1e-9, 1.0f64.next_up()));
    assert!(!block_blocks(lengths, &edge, 1e-9, 1.0));
    // In the plane of the top face (d.z = 0, o.z = h.z): on the block from
    // x = −1 to x = 1.
    let along = Ray::new(DVec3::new(-3.0, 0.0, 1.0), DVec3::X);
    assert_eq!(intersect_block(lengths, &along, 1e-9).map(|h| h.t), Some(2.0));
    assert!(block_blocks(lengths, &along, 1e-9, 2.5));
    assert!(!block_blocks(lengths, &along, 1e-9, 2.0));
    // Just above it: nothing.
    let above = Ray::new(DVec3::new(-3.0, 0.0, 1.0f64.next_up()), DVec3::X);
    assert!(intersect_block(lengths, &above, 1e-9).is_none());
    assert!(!block_blocks(lengths, &above, 1e-9, f64::INFINITY));
    // Starting on the −x face into the block with tmin 0: the entry is at
    // tmin, so the hit is the exit at t = 2, not the entry.
    let from_face = Ray::new(DVec3::new(-1.0, 0.5, 0.5), DVec3::X);
    assert_eq!(intersect_block(lengths, &from_face, 0.0).map(|h| h.t), Some(2.0));
    assert!(!block_blocks(lengths, &from_face, 0.0, 1.0));
    assert!(!block_blocks(lengths, &from_face, 0.0, 2.0));
    assert!(block_blocks(lengths, &from_face, 0.0, 2.0f64.next_up()));
    // From afar (shift 8): the entry at t = 9, the exit at t = 11.
    let far = Ray::new(DVec3::new(-10.0, 0.5, 0.5), DVec3::X);
    assert_eq!(intersect_block(lengths, &far, 1e-9).map(|h| h.t), Some(9.0));
    assert!(!block_blocks(lengths, &far, 1e-9, 9.0));
    assert!(block_blocks(lengths, &far, 1e-9, 9.0f64.next_up()));
}

/// A sphere, a block, a cylinder off its centre, a prism, a sweep, a blob
/// and a patch, each turned and moved: `Posed::blocks` answers as `Posed::intersect`'s
/// nearest hit before `tmax`, with `tmax` exactly at the hit among others.
#[test]
fn posed_blocks_as_the_nearest_hit_for_every_shape() {
    let mut cylinder = common::object(
        "cyl",
        0,
        [0.0; 3],
        Shape::Cylinder {
            cylradius: 0.75,
            orient: Axis::Z,
            top: 2.0,
            bottom: 0.5,
        },
        2.2,
    );
    cylinder.radius = 2.2;
    let prism = common::object(
        "prism",
        0,
        [0.0; 3],
        Shape::Prism {
            orientp: Axis::Z,
            height: 1.5,
            vertex: vec![[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]],
        },
        2.6,
    );
    let sw = sweep(
        PrimitiveClass::Translation,
        CurveKind::Bspline,
        circle_points(1.0),
        1.5,
        1.0,
    );
    let sweep_obj = common::sweeps::object(PrimitiveClass::Translation, sw);
    // A blob of three components, one carving; a patch bent into a dome.
    let component = |x: f64, z: f64, radius: f64, strength: f64| BlobComponent {
        centre: DVec3::new(x, 0.0, z),
        radius,
        strength,
    };
    let blob_shape = BlobShape {
        threshold: 0.4,
        components: vec![
            component(-0.5, 0.0, 1.0, 1.0),
            component(0.5, 0.2, 0.9, 1.0),
            component(0.0, 0.5, 0.5, -0.7),
        ],
    };
    let blob = common::object(
        "blob",
        0,
        [0.0; 3],
        Shape::Blob(blob_shape.clone()),
        blob_reach(&blob_shape),
    );
    let dome = PatchShape {
        points: std::array::from_fn(|k| {
            let (r, c) = ((k / 4) as f64, (k % 4) as f64);
            let inner = (1.0..=2.0).contains(&r) && (1.0..=2.0).contains(&c);
            DVec3::new(c / 1.5 - 1.0, r / 1.5 - 1.0, if inner { 1.2 } else { 0.0 })
        }),
    };
    let patch = common::object(
        "patch",
        0,
        [0.0; 3],
        Shape::Patch(Box::new(dome.clone())),
        patch_reach(&dome),
    );
    let objects = [
        common::sphere("ball", 0, [0.0; 3], 1.25),
        common::block("box", 0, [0.0; 3], [2.0, 1.0, 0.5]),
        cylinder,
        prism,
        sweep_obj,
        blob,
        patch,
    ];
    let mut rng = Rng(0x5eed_b10c);
    let turn = DMat3::from_rotation_x(0.3) * DMat3::from_rotation_y(-0.7) * DMat3::from_rotation_z(1.1);
    for obj in &objects {
        let pose = obj.pose().turned(turn, DVec3::new(1.0, -2.0, 0.5));
        let cache = match &obj.shape {
            Shape::Sweep(sw) => SweepCache::new(obj.class, sw).map(ShapeCache::Sweep),
            shape => ShapeCache::of_moment(shape),
        };
        let posed = Posed {
            obj,
            shape: &obj.shape,
            cache: cache.as_ref(),
            pose: &pose,
        };
        let (mut yes, mut no, mut at_hit) = (0, 0, 0);
        for k in 0..3000 {
            // From all around the object toward a point near it; from its
            // surface (a shadow ray's start) every fourth.
            let target = pose.sphereo + rng.unit() * rng.range(0.0, 1.5);
            let mut o = pose.sphereo + rng.unit() * rng.range(0.5, 6.0);
            if k % 4 == 0 {
                let probe = Ray::new(o, target - o);
                if let Some(h) = posed.intersect(&probe, 1e-9, &ROBUST, &mut 0) {
                    o = probe.at(h.t);
                }
            }
            let ray = Ray::new(o, (target - o).normalize_or(DVec3::Z));
            for tmin in [1e-9, 0.0] {
                let nearest = posed.intersect(&ray, tmin, &ROBUST, &mut 0);
                for tmax in tmaxes(nearest, tmin) {
                    let want = nearest_before(nearest, tmax);
                    let got = posed.blocks(&ray, tmin, tmax, &ROBUST, &mut 0);
                    assert_eq!(got, want, "{} ray {k}: {o} tmin {tmin} tmax {tmax}", obj.name);
                    (yes, no) = if want { (yes + 1, no) } else { (yes, no + 1) };
                    at_hit += nearest.is_some_and(|h| h.t == tmax) as usize;
                }
            }
        }
        assert!(
            yes > 3000 && no > 3000 && at_hit > 1000,
            "{}: {yes} {no} {at_hit}",
            obj.name
        );
    }
}

/// The bits of a [`Near`], to compare without `==`'s −0 = 0.
fn bits(n: &Near) -> ([u64; 3], [u64; 3], u64, u64) {
    let b = |v: DVec3| v.to_array().map(f64::to_bits);
    (b(n.ray.origin), b(n.ray.dir), n.tmin.to_bits(), n.shift.to_bits())
}

/// [`Near::of`]'s contract: a ray that starts inside the sphere (its
/// boundary included), runs away from or across its centre's closest
/// point, or has no finite positive shift (a zero or underflowing
/// direction, NaN) comes back with its own bits and shift +0; a ray from
/// outside running toward the centre is the same line from its closest
/// approach to `centre` (no farther from it than the start), `tmin` and
/// the hit's t measured from there.
#[test]
fn near_of_rebases_only_rays_from_outside_toward_the_centre() {
    let unchanged = |ray: &Ray, tmin: f64, centre: DVec3, r2: f64| {
        let n = Near::of(ray, tmin, centre, r2);
        let same = Near {
            ray: *ray,
            tmin,
            shift: 0.0,
        };
        assert_eq!(bits(&n), bits(&same), "{ray:?} {centre} {r2}");
    };
    let c = DVec3::new(100.0, -50.0, 3.0);
    // Inside, and exactly on the sphere (|oc|² = 9 = r²), toward the centre.
    unchanged(&Ray::new(c + DVec3::new(1.0, 0.5, 0.0), DVec3::NEG_X), 1e-9, c, 9.0);
    unchanged(&Ray::new(c + DVec3::new(3.0, 0.0, 0.0), DVec3::NEG_X), 1e-9, c, 9.0);
    // Outside, away from the centre, and across it (oc·d = ±0).
    unchanged(&Ray::new(c + DVec3::new(4.0, 0.0, 0.0), DVec3::X), 1e-9, c, 9.0);
    unchanged(&Ray::new(DVec3::new(-0.0, 5.0, 0.0), DVec3::X), 1e-9, DVec3::ZERO, 1.0);
    unchanged(
        &Ray::new(DVec3::new(5.0, 0.0, -0.0), DVec3::new(0.0, 1.0, -1.0)),
        1e-9,
        DVec3::ZERO,
        1.0,
    );
    // A direction so short its square underflows (shift +∞), and NaN.
    unchanged(
        &Ray::new(DVec3::new(5.0, 0.0, 0.0), DVec3::new(-1e-200, 0.0, 0.0)),
        1e-9,
        DVec3::ZERO,
        1.0,
    );
    unchanged(
        &Ray::new(DVec3::new(5.0, 0.0, 0.0), DVec3::new(f64::NAN, 0.0, 0.0)),
        1e-9,
        DVec3::ZERO,
        1.0,
    );

    // Exact cases: the closest approach itself, with d not of unit length.
    let ray = Ray::new(c + DVec3::new(10.0, 2.0, 0.0), DVec3::new(-2.0, 0.0, 0.0));
    let n = Near::of(&ray, 1e-9, c, 9.0);
    assert_eq!(n.shift, 5.0);
    assert_eq!(n.ray.origin, c + DVec3::new(0.0, 2.0, 0.0));
    assert_eq!(n.ray.dir, ray.dir);
    assert_eq!(n.tmin, 1e-9 - 5.0);

    let mut rng = Rng(0xc105e);
    for k in 0..20_000 {
        let centre = DVec3::new(rng.range(-1e3, 1e3), rng.range(-1e3, 1e3), rng.range(-10.0, 10.0));
        let r2 = rng.range(0.01, 25.0);
        let o = centre + rng.unit() * rng.range(0.0, 20.0);
        let d = (centre + rng.unit() * rng.range(0.0, 10.0) - o) * rng.range(0.1, 10.0);
        let ray = Ray::new(o, d);
        let tmin = [1e-9, 0.0, -1.0][k % 3];
        let oc = o - centre;
        if oc.length_squared() <= r2 || oc.dot(d) >= 0.0 {
            unchanged(&ray, tmin, centre, r2);
            continue;
        }
        let n = Near::of(&ray, tmin, centre, r2);
        assert!(n.shift > 0.0 && n.shift.is_finite(), "ray {k}");
        assert_eq!(bits(&n).0, ray.at(n.shift).to_array().map(f64::to_bits), "ray {k}");
        assert_eq!(n.ray.dir, d, "ray {k}");
        assert_eq!(n.tmin, tmin - n.shift, "ray {k}");
        let near = n.ray.origin - centre;
        // The closest approach: perpendicular to the ray, and nearer.
        let scale = oc.length() * d.length();
        assert!(near.dot(d).abs() <= 1e-12 * scale, "ray {k}: {}", near.dot(d) / scale);
        assert!(near.length_squared() <= oc.length_squared(), "ray {k}");
        // And the shift is the distance along the ray in units of d.
        let along = -oc.dot(d) / d.length_squared();
        assert!((n.shift - along).abs() <= 1e-12 * along, "ray {k}");
        // A hit on the re-based ray, carried back, is the same point.
        let back = n.back(Some(LocalHit {
            t: 0.25,
            point: n.ray.at(0.25),
            normal: DVec3::Z,
        }));
        assert_eq!(back.map(|h| h.t), Some(0.25 + n.shift), "ray {k}");
    }
}

/// From 10⁸ units along each axis, either way, with directions of three
/// lengths, a sphere and a cylinder (off its centre, met from the side)
/// are met where they stand, to a part in 10⁹ of their size: the ray
/// re-based near them carries no eye distance into their quadratics. (A
/// ray taken where it starts rounds |o|² ≈ 10¹⁶ to units, more than r².)
#[test]
fn far_rays_meet_the_quadrics_where_they_stand() {
    for axis in 0..3 {
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        for sign in [1.0, -1.0] {
            for m in [1.0, 0.5, 3.0] {
                let mut o = DVec3::ZERO;
                o[axis] = -sign * 1e8;
                let mut d = DVec3::ZERO;
                d[axis] = sign * m;
                // The sphere of radius 1, passed (0.5, 0.25) from its centre.
                let (mut from, mut at) = (o, DVec3::ZERO);
                (from[a], from[b]) = (0.5, 0.25);
                (at[a], at[b]) = (0.5, 0.25);
                at[axis] = -sign * 0.6875f64.sqrt();
                let s = raytrace::shapes::intersect_sphere(1.0, &Ray::new(from, d), 1e-9).expect("sphere");
                let t = (1e8 - 0.6875f64.sqrt()) / m;
                assert!((s.t - t).abs() <= 1e-7, "sphere {axis} {sign} {m}: {}", s.t - t);
                assert!(
                    (s.point - at).length() <= 1e-9,
                    "sphere {axis} {sign} {m}: {}",
                    s.point - at
                );
            }
        }
    }
    // A cylinder of radius 1 about z from 40 to 42 (its centre at z = 41),
    // met from the side from 10⁸ away, 0.25 off its axis.
    for (dir, m) in [(DVec3::X, 1.0), (DVec3::NEG_Y, 0.5), (DVec3::X, 3.0)] {
        let perp = DVec3::new(dir.y, -dir.x, 0.0) * 0.25;
        let ray = Ray::new(-dir * 1e8 + perp + DVec3::new(0.0, 0.0, 41.5), dir * m);
        let c = raytrace::shapes::intersect_cylinder(1.0, 40.0, 42.0, &ray, 1e-9).expect("cylinder");
        let t = (1e8 - 0.9375f64.sqrt()) / m;
        let at = -dir * 0.9375f64.sqrt() + perp + DVec3::new(0.0, 0.0, 41.5);
        assert!((c.t - t).abs() <= 1e-7, "cylinder {dir} {m}: {}", c.t - t);
        assert!((c.point - at).length() <= 1e-9, "cylinder {dir} {m}: {}", c.point - at);
    }
}

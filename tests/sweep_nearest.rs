//! The sweep driver tries a ray's segments nearest first and stops past
//! the nearest hit, and answers a shadow ray at its first hit before the
//! light: checked here against the answers that need neither, on the
//! sweeps of Chapter 5 (fig5_6's star, fig5_7's obelisk, fig5_8's goblet).

mod common;
use raytrace::hash::hashed_uniform;
use raytrace::options::*;
use raytrace::shapes::sweep::{point_in_contour, Sweep, SweepCache};
use raytrace::types::*;

const SOLVERS: [Solver; 2] = [Solver::Laguerre, Solver::Robust];

fn opts(solver: Solver) -> Options {
    Options {
        solver,
        ..Options::default()
    }
}

/// Segment `i` alone, with the whole contour's box (so the ray is taken
/// near the object in the same way and each segment's polynomial is the
/// same to the bit).
fn single(sw: &SweepShape, i: usize) -> SweepShape {
    SweepShape {
        segment: 1,
        u: vec![sw.u[i]],
        v: vec![sw.v[i]],
        ..sw.clone()
    }
}

/// Ray `k`: from 6 units off the box's centre toward a point of the box,
/// or (every other ray) toward a joint of the contour, where two segments'
/// hits compete at nearly one t; horizontal (local z fixed) when `flat`.
fn ray(class: PrimitiveClass, sw: &SweepShape, k: u64, flat: bool) -> Ray {
    let (lo, hi) = common::sweep_box(class, sw);
    let r = |j: u64| hashed_uniform(16 * k + j);
    let mut target = lo + (hi - lo) * DVec3::new(r(0), r(1), r(2));
    if k % 2 == 1 {
        let j = (r(5) * sw.segment as f64) as usize % sw.segment;
        let (ju, jv) = (sw.u[j].d, sw.v[j].d);
        target = match class {
            PrimitiveClass::Rotation => {
                let phi = std::f64::consts::TAU * r(6);
                DVec3::new(ju * phi.cos(), ju * phi.sin(), jv)
            }
            _ => {
                let z = sw.length * r(2);
                let scale = 1.0 + (sw.scale - 1.0) * z / sw.length;
                DVec3::new(scale * ju, scale * jv, z)
            }
        };
    }
    let a = std::f64::consts::TAU * r(3);
    let mut origin = 0.5 * (lo + hi) + 6.0 * DVec3::new(a.cos(), a.sin(), r(4) - 0.5);
    if flat {
        origin.z = target.z;
    }
    Ray::new(origin, (target - origin).normalize())
}

/// The options of `solver` with the sweeps' bounds and order in force
/// (the table sampler's), and without them (`--sampler adaptive`, which
/// weighs every segment's search).
fn with_and_without_bounds(solver: Solver) -> (Options, Options) {
    let with = opts(solver);
    let without = Options {
        sampler: TimeSampler::Adaptive,
        ..with
    };
    (with, without)
}

/// `sweep`'s nearest hit of `ray` and its shadow answers (to half, once
/// and one and a half times the hit, and far) with a bound in force
/// (`bounded`) are those of every segment tried (`every`), to the bit;
/// returns the hit. `what` names the ray; `searched` counts each side's
/// searches.
fn same_answers(
    sweep: &Sweep,
    ray: &Ray,
    (bounded, every): (&Options, &Options),
    searched: (&mut u64, &mut u64),
    what: &str,
) -> Option<LocalHit> {
    let a = sweep.intersect(ray, 1e-9, bounded, searched.0);
    assert_eq!(a, sweep.intersect(ray, 1e-9, every, searched.1), "{what}");
    let tmaxes = [0.5, 1.0, 1.5].map(|f| a.map_or(1e9, |h| h.t * f));
    for tmax in tmaxes.into_iter().chain([1e9]) {
        assert_eq!(
            sweep.blocks(ray, 1e-9, tmax, bounded, &mut 0),
            sweep.blocks(ray, 1e-9, tmax, every, &mut 0),
            "shadow of {what} to {tmax}"
        );
    }
    a
}

/// The nearest hit of the whole contour is the nearest of its segments'
/// own, to the bit: culling by the segments' bounds never skips the one
/// that holds it. Translation rays are horizontal, so no cap is met and a
/// segment alone answers for its side.
#[test]
fn nearest_first_finds_the_nearest_segment_hit() {
    for (deck, flat) in [("fig5_6", true), ("fig5_7", true), ("fig5_8", false)] {
        let (class, sw) = common::deck_sweep(&format!("{deck}.deck"));
        let cache = SweepCache::new(class, &sw);
        let singles: Vec<SweepShape> = (0..sw.segment).map(|i| single(&sw, i)).collect();
        // Each with the whole contour's cache, as each kept it before
        // the caches left the records (horizontal rays meet no cap).
        let [whole, each] = [&sw, &singles[0]].map(|shape| Sweep {
            class,
            shape,
            cache: cache.as_ref(),
        });
        for solver in SOLVERS {
            let o = opts(solver);
            let mut hits = 0;
            for k in 0..1500 {
                let ray = ray(class, &sw, k, flat);
                let whole = whole.intersect(&ray, 1e-9, &o, &mut 0).map(|h| h.t);
                let each = singles
                    .iter()
                    .filter_map(|s| {
                        Sweep { shape: s, ..each }
                            .intersect(&ray, 1e-9, &o, &mut 0)
                            .map(|h| h.t)
                    })
                    .fold(None, |m: Option<f64>, t| Some(m.map_or(t, |m| m.min(t))));
                assert_eq!(whole, each, "{deck} {solver:?} ray {k}");
                hits += whole.is_some() as usize;
            }
            assert!(hits > 300, "{deck} {solver:?}: the rays meet the sweep ({hits})");
        }
    }
}

/// A ray that enters the slab between the caps' planes through the near
/// cap's plane, inside the contour there, hits that cap: the cap tried
/// first is kept, and no side beyond it is taken for the hit. (A side hit
/// at the rim may stand a hair before it.) Caps that the ray enters
/// outside the contour are passed, and the hit is farther.
#[test]
fn the_near_cap_first_is_the_hit_where_it_is_inside() {
    for deck in ["fig5_6", "fig5_7"] {
        let (class, sw) = common::deck_sweep(&format!("{deck}.deck"));
        let cache = SweepCache::new(class, &sw);
        let obj = Sweep {
            class,
            shape: &sw,
            cache: cache.as_ref(),
        };
        for solver in SOLVERS {
            let o = opts(solver);
            let (mut inside, mut outside) = (0, 0);
            for k in 0..1500 {
                let ray = ray(class, &sw, k, false);
                let (p, d) = (ray.origin, ray.dir);
                let (zc, nz) = if d.z < 0.0 { (sw.length, 1.0) } else { (0.0, -1.0) };
                let t_cap = (zc - p.z) / d.z;
                if t_cap.is_nan() || t_cap <= 0.0 {
                    continue;
                }
                let at = ray.at(t_cap);
                let scale = 1.0 + (sw.scale - 1.0) * zc / sw.length;
                let hit = obj.intersect(&ray, 1e-9, &o, &mut 0);
                if point_in_contour(&sw.u, &sw.v, at.x / scale, at.y / scale) {
                    let h = hit.expect("the near cap is hit");
                    assert!(
                        (h.t - t_cap).abs() <= 1e-9 * t_cap,
                        "{deck} {solver:?} ray {k}: {} vs {t_cap}",
                        h.t
                    );
                    if h.t == t_cap {
                        assert_eq!(h.normal, DVec3::new(0.0, 0.0, nz));
                    }
                    inside += 1;
                } else {
                    assert!(hit.is_none_or(|h| h.t > t_cap), "{deck} {solver:?} ray {k}");
                    outside += 1;
                }
            }
            assert!(
                inside > 20 && outside > 100,
                "{deck} {solver:?}: {inside} in, {outside} out"
            );
        }
    }
}

/// `Sweep::blocks` answers what the nearest hit answers, before lights at
/// every distance: in front of the sweep, inside it, behind it.
#[test]
fn shadow_query_is_the_nearest_hit_before_the_light() {
    for deck in ["fig5_6", "fig5_7", "fig5_8"] {
        let (class, sw) = common::deck_sweep(&format!("{deck}.deck"));
        let cache = SweepCache::new(class, &sw);
        let obj = Sweep {
            class,
            shape: &sw,
            cache: cache.as_ref(),
        };
        for solver in SOLVERS {
            let o = opts(solver);
            let (mut blocked, mut free) = (0, 0);
            for k in 0..1500 {
                let ray = ray(class, &sw, k, false);
                let nearest = obj.intersect(&ray, 1e-9, &o, &mut 0).map(|h| h.t);
                let tmax = 3.0 + 6.0 * hashed_uniform(7_000_000 + k);
                let want = nearest.is_some_and(|t| t < tmax);
                assert_eq!(
                    obj.blocks(&ray, 1e-9, tmax, &o, &mut 0),
                    want,
                    "{deck} {solver:?} ray {k}"
                );
                if let Some(t) = nearest {
                    // Just before and just after the nearest hit.
                    assert!(!obj.blocks(&ray, 1e-9, t, &o, &mut 0), "{deck} ray {k}: at t");
                    assert!(obj.blocks(&ray, 1e-9, t * (1.0 + 1e-12), &o, &mut 0));
                }
                if want {
                    blocked += 1;
                } else {
                    free += 1;
                }
            }
            assert!(
                blocked > 200 && free > 200,
                "{deck} {solver:?}: {blocked} blocked, {free} free"
            );
        }
    }
}

/// Thesis fidelity skips a translation sweep's segments whose hits lie
/// before tmin or where the ray is not between the caps (their boxes bound
/// the hits' t); listing fidelity, whose boxes need not hold their
/// segments, tries them all. The robust solver is the same in both, so the
/// hits must be the same to the bit: for slanted rays from afar, and for
/// rays that start inside the box (as a shadow ray leaves a surface), where
/// the segments behind the start are skipped.
#[test]
fn skipping_segments_outside_the_rays_span_keeps_every_hit() {
    let (class, sw) = common::deck_sweep("fig5_6.deck");
    let thesis = opts(Solver::Robust);
    let listing = Options {
        fidelity: Fidelity::Listing,
        ..thesis
    };
    let (lo, hi) = common::sweep_box(class, &sw);
    let cache = SweepCache::new(class, &sw);
    let obj = Sweep {
        class,
        shape: &sw,
        cache: cache.as_ref(),
    };
    let (mut hits, mut sides, mut inside_starts) = (0, 0, 0);
    for k in 0..3000 {
        let mut ray = ray(class, &sw, k, false);
        let r = |j: u64| hashed_uniform(9_000_000 + 8 * k + j);
        if k % 3 == 0 {
            // Started at a point of the box, toward the same target.
            let start = lo + (hi - lo) * DVec3::new(r(0), r(1), r(2));
            ray = Ray::new(start, ray.dir);
            inside_starts += 1;
        } else if k % 3 == 1 {
            // Toward a point of a side a hair from a cap's plane, where the
            // span between the caps' planes ends.
            let i = (r(0) * sw.segment as f64) as usize % sw.segment;
            let s = r(1);
            let z = if r(2) < 0.5 {
                1e-7 * r(3)
            } else {
                sw.length * (1.0 - 1e-7 * r(3))
            };
            let target = DVec3::new(sw.u[i].value(s), sw.v[i].value(s), z);
            ray = Ray::new(ray.origin, (target - ray.origin).normalize());
        }
        let a = obj.intersect(&ray, 1e-9, &thesis, &mut 0);
        let b = obj.intersect(&ray, 1e-9, &listing, &mut 0);
        assert_eq!(a, b, "ray {k}");
        hits += a.is_some() as usize;
        sides += a.is_some_and(|h| h.normal.z == 0.0) as usize;
    }
    // Most on the sides, which a test that skipped every segment would lose.
    assert!(
        hits > 600 && sides > 500 && inside_starts == 1000,
        "{hits} hits, {sides} on the sides"
    );
}

/// A segment whose box does not hold it (as the listing's in-between boxes
/// need not, erratum 9) is still solved in listing fidelity: its box only
/// orders the segments there. Here the star's first segment, alone, keeps
/// a box behind the ray's start, which thesis fidelity would take as the
/// bound of the segment's hits and skip.
#[test]
fn listing_boxes_only_order_the_segments() {
    let (class, sw) = common::deck_sweep("fig5_6.deck");
    // With the whole contour's cache, as the segment kept it before the
    // caches left the records (a horizontal ray meets no cap).
    let cache = SweepCache::new(class, &sw);
    let sw = single(&sw, 0);
    let segment = Sweep {
        class,
        shape: &sw,
        cache: cache.as_ref(),
    };
    let listing = Options {
        fidelity: Fidelity::Listing,
        ..opts(Solver::Robust)
    };
    // A horizontal ray at mid height through the middle of the segment.
    let (cu, cv) = (sw.u[0], sw.v[0]);
    let target = DVec3::new(cu.value(0.5), cv.value(0.5), 0.5 * sw.length);
    let origin = target - DVec3::new(4.0, 0.3, 0.0);
    let ray = Ray::new(origin, (target - origin).normalize());
    let want = segment
        .intersect(&ray, 1e-9, &listing, &mut 0)
        .expect("the ray meets the segment");
    // Its box moved to just behind the ray's start, still across its line.
    let mut moved = sw.clone();
    let back = origin - ray.dir * 0.5;
    (moved.u[0].min, moved.u[0].max) = (back.x - 0.1, back.x + 0.1);
    (moved.v[0].min, moved.v[0].max) = (back.y - 0.1, back.y + 0.1);
    let moved = Sweep {
        shape: &moved,
        ..segment
    };
    let got = moved.intersect(&ray, 1e-9, &listing, &mut 0);
    assert_eq!(got.map(|h| h.t), Some(want.t));
    // Thesis fidelity trusts the box, which holds no hit.
    assert_eq!(moved.intersect(&ray, 1e-9, &opts(Solver::Robust), &mut 0), None);
}

/// The bounds a sweep's cache keeps (`SweepCache`) give every ray the hit
/// it gets when they are made for the ray, to the bit, for each kind of
/// sweep; and bounds kept for another box are not used: with the box
/// shrunk to its bottom after they were kept, a ray through the middle of
/// the object misses, as the new box says.
#[test]
fn kept_bounds_answer_as_bounds_made_per_ray_and_only_for_their_box() {
    for deck in ["fig5_6", "fig5_7", "fig5_8"] {
        let (class, sw) = common::deck_sweep(&format!("{deck}.deck"));
        // The box shrunk to its bottom.
        let mut shrunk = sw.clone();
        let b = &mut shrunk.bbox;
        b.zmax = b.zmin + 0.01 * (b.zmax - b.zmin);
        let cache = SweepCache::new(class, &sw).expect("a cache");
        assert!(cache.fits(class, &sw), "{deck}: the cache keeps the bounds");
        // Made for the shrunk box: its bounds are not taken for `sw`'s
        // (its cap grid, made with the same segments, is).
        let unkept = SweepCache::new(class, &shrunk).expect("a cache");
        assert!(!unkept.fits(class, &sw), "{deck}");
        let kept = Sweep {
            class,
            shape: &sw,
            cache: Some(&cache),
        };
        let made = Sweep {
            cache: Some(&unkept),
            ..kept
        };
        for solver in SOLVERS {
            let o = opts(solver);
            let mut hits = 0;
            for k in 0..1000 {
                let ray = ray(class, &sw, k, false);
                let hit = kept.intersect(&ray, 1e-9, &o, &mut 0);
                assert_eq!(hit, made.intersect(&ray, 1e-9, &o, &mut 0), "{deck} {solver:?} ray {k}");
                let tmax = hit.map_or(1e9, |h| h.t * 1.5);
                assert_eq!(
                    kept.blocks(&ray, 1e-9, tmax, &o, &mut 0),
                    made.blocks(&ray, 1e-9, tmax, &o, &mut 0),
                    "{deck} {solver:?} shadow ray {k}"
                );
                hits += hit.is_some() as usize;
            }
            assert!(hits > 200, "{deck} {solver:?}: the rays meet the sweep ({hits})");
        }
        // The shrunk box with the bounds kept for the whole one.
        let (lo, hi) = common::sweep_box(class, &sw);
        let middle = 0.5 * (lo + hi);
        let through = Ray::new(middle - DVec3::new(0.0, 10.0, 0.0), DVec3::Y);
        let robust = opts(Solver::Robust);
        assert!(kept.intersect(&through, 1e-9, &robust, &mut 0).is_some());
        assert_eq!(
            Sweep { shape: &shrunk, ..kept }.intersect(&through, 1e-9, &robust, &mut 0),
            None,
            "{deck}: the new box is asked, not the kept bounds"
        );
    }
}

/// A conic sweep's segment whose box keeps away from the ray's central
/// projection between the caps is not searched in thesis fidelity (D69):
/// fig5_7's rays find the same hits, to the bit, as when every segment is
/// tried (as it is for `--sampler adaptive`, which weighs the searches),
/// with fewer searches of `laguerre`.
#[test]
fn a_conic_sweep_skips_the_segments_off_the_rays_projection() {
    let (class, sw) = common::deck_sweep("fig5_7.deck");
    assert_eq!(class, PrimitiveClass::Conic);
    let cache = SweepCache::new(class, &sw);
    let conic = Sweep {
        class,
        shape: &sw,
        cache: cache.as_ref(),
    };
    for solver in SOLVERS {
        let every = Options {
            sampler: TimeSampler::Adaptive,
            ..opts(solver)
        };
        let (mut culled, mut all, mut hits) = (0, 0, 0);
        for k in 0..2000 {
            let ray = ray(class, &sw, k, k % 3 == 0);
            let a = conic.intersect(&ray, 1e-9, &opts(solver), &mut culled);
            let b = conic.intersect(&ray, 1e-9, &every, &mut all);
            assert_eq!(a, b, "{solver:?} ray {k}");
            hits += a.is_some() as usize;
        }
        assert!(hits > 500, "{hits}");
        // (The robust solver settles most skipped cubics by their count,
        // which is no search: `laguerre`'s pre-test is.)
        match solver {
            Solver::Laguerre => assert!(culled < all, "{culled} searches against {all}"),
            Solver::Robust => assert!(culled <= all, "{culled} searches against {all}"),
        }
    }
}

/// Segment i's point of greatest radius, of 65 along it.
fn widest(sw: &SweepShape, i: usize) -> (f64, f64) {
    (0..=64)
        .map(|j| j as f64 / 64.0)
        .map(|s| (sw.u[i].value(s), sw.v[i].value(s)))
        .fold((f64::NEG_INFINITY, 0.0), |m, p| if p.0 > m.0 { p } else { m })
}

/// A rotation sweep's segment is bounded in t by its greatest radius as
/// well as its heights, and skipped where the ray leaves either by tmin
/// (D90): fig5_8's rays find the same hits and shadow answers, to the bit,
/// as when neither bound is used (as under `--sampler adaptive`, which
/// weighs the searches), with fewer searches. At the bounds' edges too:
/// rays that pass a segment's widest point a hair inside or outside its
/// radius (the radius bound's edge), and rays that start on a hit (the
/// edge of tmin).
#[test]
fn a_rotation_sweep_bounds_its_segments_by_their_radius() {
    let (class, sw) = common::deck_sweep("fig5_8.deck");
    assert_eq!(class, PrimitiveClass::Rotation);
    let (lo, hi) = common::sweep_box(class, &sw);
    let cache = SweepCache::new(class, &sw);
    let goblet = Sweep {
        class,
        shape: &sw,
        cache: cache.as_ref(),
    };
    for solver in SOLVERS {
        let (bounded, every) = with_and_without_bounds(solver);
        let (mut culled, mut all, mut hits, mut grazed, mut restarts) = (0, 0, 0, 0, 0);
        for k in 0..3000 {
            let mut ray = ray(class, &sw, k, false);
            let r = |j: u64| hashed_uniform(7_000_000 + 8 * k + j);
            match k % 4 {
                0 => ray = Ray::new(lo + (hi - lo) * DVec3::new(r(0), r(1), r(2)), ray.dir),
                1 => {
                    // Past the widest point of a segment, tangent to its
                    // circle, at its radius less or more a hair.
                    let i = (r(0) * sw.segment as f64) as usize % sw.segment;
                    let (u, v) = widest(&sw, i);
                    let phi = std::f64::consts::TAU * r(1);
                    let hair = [-1e-7, -1e-10, 0.0, 1e-10, 1e-7][(r(2) * 5.0) as usize % 5];
                    let at = DVec3::new(phi.cos(), phi.sin(), 0.0) * u * (1.0 + hair) + DVec3::Z * v;
                    let dir = DVec3::new(-phi.sin(), phi.cos(), 0.4 * (r(3) - 0.5)).normalize();
                    ray = Ray::new(at - 3.0 * dir, dir);
                    grazed += 1;
                }
                _ => {}
            }
            let both = (&bounded, &every);
            let a = same_answers(
                &goblet,
                &ray,
                both,
                (&mut culled, &mut all),
                &format!("{solver:?} ray {k}"),
            );
            if let Some(h) = a {
                hits += 1;
                // On from the hit, as a ray leaving the surface.
                let on = Ray::new(h.point, ray.dir);
                let what = format!("{solver:?} ray {k} on from its hit");
                let c = same_answers(&goblet, &on, both, (&mut culled, &mut all), &what);
                restarts += c.is_some() as usize;
            }
        }
        assert!(
            hits > 800 && grazed == 750 && restarts > 300,
            "{hits} hits, {restarts} on"
        );
        assert!(culled < all, "{culled} searches against {all}");
    }
}

/// A conic sweep's segments are tried along the ray's central projection,
/// by the least λ = w·X over each box, and the rest skipped once that
/// passes λ at the nearest hit (D91): fig5_7's rays find the same hits
/// and shadow answers, to the bit, as when every segment is tried (as
/// under `--sampler adaptive`), and so do rays that start on a hit (the
/// edge of tmin). A ray through the axis crosses two sides, the far one
/// after the near: of `laguerre`'s searches (each side's cubic, one
/// crossing), the far side's is skipped.
#[test]
fn a_conic_sweep_tries_its_segments_along_the_rays_projection() {
    let (class, sw) = common::deck_sweep("fig5_7.deck");
    let cache = SweepCache::new(class, &sw);
    let conic = Sweep {
        class,
        shape: &sw,
        cache: cache.as_ref(),
    };
    for solver in SOLVERS {
        let (ordered, every) = with_and_without_bounds(solver);
        let (mut hits, mut restarts) = (0, 0);
        for k in 0..3000 {
            let ray = ray(class, &sw, k, k % 3 == 0);
            let both = (&ordered, &every);
            let a = same_answers(&conic, &ray, both, (&mut 0, &mut 0), &format!("{solver:?} ray {k}"));
            if let Some(h) = a {
                hits += 1;
                // On from the hit, and back out toward where it came from.
                for dir in [ray.dir, -ray.dir] {
                    let on = Ray::new(h.point, dir);
                    let what = format!("{solver:?} ray {k} from its hit");
                    let c = same_answers(&conic, &on, both, (&mut 0, &mut 0), &what);
                    restarts += c.is_some() as usize;
                }
            }
        }
        assert!(hits > 1000 && restarts > 300, "{hits} hits, {restarts} on");
    }
    // Rays through the axis between the caps, nearly level (a level ray
    // has no span between the caps' planes, and no order), from every
    // side: one search each (the near side's; two at a joint), where every
    // segment tried takes two.
    let (mut ordered, mut all, mut rays) = (0, 0, 0);
    for k in 0..200 {
        let r = |j: u64| hashed_uniform(9_000_000 + 4 * k + j);
        let z = sw.length * (0.2 + 0.6 * r(0));
        let a = std::f64::consts::TAU * r(1);
        let dir = DVec3::new(a.cos(), a.sin(), 0.1 * (r(2) - 0.5)).normalize();
        let ray = Ray::new(DVec3::new(0.0, 0.0, z) - 6.0 * dir, dir);
        let (with, every) = with_and_without_bounds(Solver::Laguerre);
        let hit = conic.intersect(&ray, 1e-9, &with, &mut ordered);
        assert!(hit.is_some(), "ray {k}");
        assert_eq!(hit, conic.intersect(&ray, 1e-9, &every, &mut all), "ray {k}");
        rays += 1;
    }
    assert!(all >= 2 * rays, "{all} searches of every segment for {rays} rays");
    assert!(2 * ordered < 3 * rays, "{ordered} searches in order for {rays} rays");
}

//! The structures over the objects (`--accel bvh`, `--accel octree`)
//! answer every query as the original's loop does (`--accel none`), to
//! the bit: the nearest hit (object, distance, point, normal; of equal
//! distances the lower index) and what stands on a shadow ray (stopped,
//! or the `crystal` objects passed, in the table's order). On random
//! scenes of every primitive and all three sweep kinds, objects moving,
//! turning and deforming, in both fidelities, with random rays at random
//! times of the shutter; and on every deck.

use std::ops::ControlFlow;
use std::path::Path;

use raytrace::accel::{Accel, Structure};
use raytrace::deck::initialize;
use raytrace::hash::hashed_uniform;
use raytrace::intersect::{for_each_blocker, nearest, Deforming, Poses, Scratch, Snapshot};
use raytrace::motion::Motion;
use raytrace::options::{Fidelity, Options, TimeSampler};
use raytrace::raytrace::Prepared;
use raytrace::scene::Scene;
use raytrace::types::{DVec3, LocalHit, Ray};

/// A prepared scene posed at one instant, as a worker holds it.
struct Probe<'p> {
    prepared: &'p Prepared,
    poses: Poses<'p>,
    deforming: Vec<Deforming<'p>>,
    scratch: Scratch,
    /// The instant's time segment in the structure.
    segment: usize,
}

impl<'p> Probe<'p> {
    fn new(prepared: &'p Prepared) -> Self {
        Probe {
            prepared,
            poses: prepared.poses(),
            deforming: prepared.deforming(),
            scratch: Scratch::default(),
            segment: 0,
        }
    }

    fn at(&mut self, time: f64) {
        assert!(self.prepared.bounds_time(time), "time {time} outside the bounds");
        self.poses.at(time);
        for d in &self.deforming {
            d.at(time);
        }
        self.segment = self.prepared.aggregate().structure().map_or(0, |s| s.segment(time));
    }

    fn snap(&self) -> Snapshot<'_> {
        let p = self.prepared;
        Snapshot {
            scene: p.scene(),
            opts: p.options(),
            poses: &self.poses,
            all: self.poses.all(),
            deforming: &self.deforming,
            deforming_of: p.deforming_of(),
            caches: p.caches(),
            aggregate: p.aggregate(),
            structure: p.aggregate().structure(),
            segment: self.segment,
            scratch: &self.scratch,
        }
    }

    /// The nearest hit's object and bits, and the searches it took.
    fn nearest(&self, ray: &Ray) -> (Option<(usize, [u64; 7])>, u64) {
        let mut searched = 0;
        let hit = nearest(&self.snap(), ray, 1e-9, &mut searched);
        (hit.map(|(i, h)| (i, bits(&h))), searched)
    }

    /// What stands on the shadow ray to `tmax`: `None` if stopped, else
    /// the crystals passed, in order; and the searches.
    fn shadow(&self, ray: &Ray, tmax: f64) -> (Option<Vec<usize>>, u64) {
        let (mut searched, mut crystals) = (0, Vec::new());
        let flow = for_each_blocker(&self.snap(), ray, 1e-9, tmax, &mut searched, |i| crystals.push(i));
        ((flow == ControlFlow::Continue(())).then_some(crystals), searched)
    }
}

fn bits(h: &LocalHit) -> [u64; 7] {
    let [a, b, c] = h.point.to_array().map(f64::to_bits);
    let [d, e, f] = h.normal.to_array().map(f64::to_bits);
    [h.t.to_bits(), a, b, c, d, e, f]
}

/// The scene prepared with each `--accel`; the loop's first.
fn each_accel(scene: &Scene, opts: Options) -> Vec<Prepared> {
    [Accel::None, Accel::Bvh, Accel::Octree]
        .into_iter()
        .map(|accel| Prepared::new(scene.clone(), Options { accel, ..opts }).unwrap_or_else(|e| panic!("{e}")))
        .collect()
}

/// A uniform on [0, 1) from the test's key.
fn u(key: &mut u64) -> f64 {
    *key += 1;
    hashed_uniform(*key)
}

/// Compares the structures' answers with the loop's for `rays` rays of
/// `scene`: from the eye and from points about the scene toward its
/// objects or anywhere, at random times; shadow rays from each hit to each
/// light and to random points. Returns (hits, shadow rays stopped).
fn compare(scene: &Scene, opts: Options, rays: usize, key: u64) -> (usize, usize) {
    let prepared = each_accel(scene, opts);
    let counted = opts.sampler == TimeSampler::Adaptive;
    assert!(prepared[0].aggregate().structure().is_none());
    assert!(matches!(prepared[1].aggregate().structure(), Some(Structure::Bvh(_))));
    assert!(matches!(
        prepared[2].aggregate().structure(),
        Some(Structure::Octree(_))
    ));
    let mut probes: Vec<Probe> = prepared.iter().map(Probe::new).collect();
    let timed = prepared[0].timed();
    let (mut k, mut hits, mut stopped) = (key << 32, 0, 0);
    for r in 0..rays {
        if timed && r % 8 == 0 {
            // Times over the whole span (the listing's reaches past 1),
            // its ends too.
            let (t0, t1) = prepared[0].time_span();
            let t = match r % 64 {
                0 => [t0, t1][r / 64 % 2],
                _ => t0 + (t1 - t0) * u(&mut k),
            };
            for p in &mut probes {
                p.at(t);
            }
        }
        let v = |k: &mut u64| DVec3::new(u(k), u(k), u(k)) * 2.0 - 1.0;
        let origin = match r % 3 {
            0 => scene.view.eyept,
            _ => v(&mut k) * 8.0,
        };
        // Toward an object where it stands at the instant.
        let aim = (u(&mut k) * centres_len(&prepared[0]) as f64) as usize;
        let toward = probes[0].poses.get(aim).sphereo + v(&mut k) * 0.7;
        let dir = if r % 5 == 4 { v(&mut k) } else { toward - origin };
        if dir.length_squared() == 0.0 {
            continue;
        }
        let ray = Ray::new(origin, dir.normalize());
        let answers: Vec<_> = probes.iter().map(|p| p.nearest(&ray)).collect();
        for (a, p) in answers.iter().zip(&prepared).skip(1) {
            assert_eq!(
                a.0,
                answers[0].0,
                "ray {r} {ray:?}: nearest with {:?}",
                p.aggregate().structure().map(kind)
            );
            if counted {
                assert_eq!(a.1, answers[0].1, "ray {r}: searches");
            }
        }
        let Some((_, b)) = answers[0].0 else { continue };
        hits += 1;
        let at = ray.at(f64::from_bits(b[0]));
        let mut targets: Vec<DVec3> = scene.lights.iter().map(|l| l.position).collect();
        targets.push(v(&mut k) * 8.0);
        for target in targets {
            let to = target - at;
            let dist = to.length();
            let shadow_ray = Ray::new(at, to / dist);
            let answers: Vec<_> = probes.iter().map(|p| p.shadow(&shadow_ray, dist)).collect();
            for a in &answers[1..] {
                assert_eq!(a.0, answers[0].0, "ray {r}: shadow ray {shadow_ray:?} to {dist}");
                if counted {
                    assert_eq!(a.1, answers[0].1, "ray {r}: shadow searches");
                }
            }
            stopped += answers[0].0.is_none() as usize;
        }
    }
    (hits, stopped)
}

fn centres_len(p: &Prepared) -> usize {
    p.scene().objects.len()
}

fn kind(s: &Structure) -> &'static str {
    match s {
        Structure::Bvh(_) => "bvh",
        Structure::Octree(_) => "octree",
    }
}

/// A random deck of `n` objects: spheres, blocks, cylinders, prisms and
/// sweeps of all three kinds, some turned, some moving (straight, along a
/// Bezier, turning, under each law), a key-frame pair or chain, surfaces
/// opaque, crystal, light and background, a floor.
fn random_deck(n: usize, key: u64) -> String {
    let mut k = key << 40;
    let mut d = String::from(
        "view eye 1 -14 6 look 0 0 0.5 screen 6 distance 5\nimage 16 16 mask 2\nbackground 0.1 0.1 0.2\n\
         light sun 5 -6 10 1 1 1\nlight fill -6 2 3 0.5 0.5 0.5\n\
         surface op opaque color 0.8 0.2 0.1 ka 0.2 kd 0.8 ks 0 kt 0\n\
         surface cr crystal color 0.9 0.9 0.9 ka 0.1 kd 0.1 ks 0.3 kt 0.7\n\
         surface li light color 1 1 1 ka 1 kd 0 ks 0 kt 0\n\
         surface bg background color 0 0 0 ka 0 kd 0 ks 0 kt 0\n\
         block floor op at 0 0 -0.5 size 30 30 1\n",
    );
    let star = "sweep {N} {S} translation bspline at {P} length {L}\n 1 0\n 0.3 0.3\n 0 1\n -0.3 0.3\n -1 0\n -0.3 -0.3\n 0 -1\n 0.3 -0.3\nend\n";
    let cone = "sweep {N} {S} conic bspline at {P} length {L} scale 0.4\n 0.8 0\n 0 0.8\n -0.8 0\n 0 -0.8\nend\n";
    let square =
        "sweep {N} {S} translation bspline at {P} length {L}\n 0.7 0.7\n -0.7 0.7\n -0.7 -0.7\n 0.7 -0.7\nend\n";
    let goblet = "sweep {N} {S} rotation bezier at {P}\n 0 0\n 0.3 0\n 0.6 0\n 0.6 0.1\n 0.2 0.3\n 0.15 0.6\n 0.4 0.9\n 0.5 1.2\n 0.45 1.3\n 0 1.3\n 0 0.9\n 0 0.4\nend\n";
    let mut names = Vec::new();
    for i in 0..n {
        let name = format!("o{i}");
        let at = format!(
            "{:.3} {:.3} {:.3}",
            8.0 * u(&mut k) - 4.0,
            8.0 * u(&mut k) - 4.0,
            3.0 * u(&mut k)
        );
        let surf = ["op", "op", "op", "cr", "li", "bg"][(u(&mut k) * 6.0) as usize];
        let size = 0.2 + 0.8 * u(&mut k);
        let fill = |t: &str| {
            t.replace("{N}", &name)
                .replace("{S}", surf)
                .replace("{P}", &at)
                .replace("{L}", &format!("{size:.3}"))
        };
        let line = match (u(&mut k) * 8.0) as usize {
            0 => format!("sphere {name} {surf} at {at} radius {size:.3}\n"),
            1 => format!("block {name} {surf} at {at} size {size:.3} {:.3} 0.3\n", 2.0 * size),
            2 => format!(
                "cylinder {name} {surf} at {at} radius {:.3} bottom 0 top {size:.3} axis y\n",
                size / 2.0
            ),
            3 => format!("prism {name} {surf} at {at} height {size:.3}\n 0 0\n 1 0\n 0.5 0.8\nend\n"),
            4 => fill(star),
            5 => fill(cone),
            6 => fill(goblet),
            _ => fill(square),
        };
        d.push_str(&line);
        if u(&mut k) < 0.4 {
            d.push_str(&format!(
                "rotate {name} {} {:.1}\n",
                ["x", "y", "z"][i % 3],
                360.0 * u(&mut k)
            ));
        }
        names.push(name);
    }
    // Moving objects: every third, by each kind of path and law.
    for (i, name) in names.iter().enumerate().filter(|(i, _)| i % 3 == 1) {
        let to = format!(
            "{:.3} {:.3} {:.3}",
            8.0 * u(&mut k) - 4.0,
            8.0 * u(&mut k) - 4.0,
            3.0 * u(&mut k)
        );
        let law = ["constant", "accelerate", "decelerate", "smooth"][i % 4];
        let extra = match i % 3 {
            0 => format!(" turn {:.0} {:.0} {:.0}", 90.0 * u(&mut k), 0.0, 180.0 * u(&mut k)),
            1 => format!(" via {to} {:.3} 0 2", 6.0 * u(&mut k) - 3.0),
            _ => String::new(),
        };
        d.push_str(&format!("motion {name} to {to}{extra} law {law}\n"));
    }
    // A key-frame chain of three translation sweeps.
    for (j, (shape, at)) in [(star, "-2 1 0.5"), (square, "1 2 1"), (star, "3 -1 0.2")]
        .iter()
        .enumerate()
    {
        let fill = shape
            .replace("{N}", &format!("key{j}"))
            .replace("{S}", "op")
            .replace("{P}", at)
            .replace("{L}", "0.6");
        d.push_str(&fill);
    }
    d.push_str("rotate key1 z 40\nkeyframe key0 key1 key2\nblur 1\n");
    d
}

/// Degenerate placements the random decks do not make: objects of no
/// size at one point, a motion far outside the rest.
fn degenerate_deck(key: u64) -> String {
    let mut d = String::from(
        "view eye 0 -10 3 look 0 0 0 screen 4 distance 5\nimage 16 16 mask 2\n\
         light sun 5 -6 10 1 1 1\nsurface op opaque color 0.8 0.2 0.1 ka 0.2 kd 0.8 ks 0 kt 0\n\
         surface cr crystal color 0.9 0.9 0.9 ka 0.1 kd 0.1 ks 0.3 kt 0.7\n",
    );
    for i in 0..40 {
        let surf = if i % 3 == 0 { "cr" } else { "op" };
        d.push_str(&format!("sphere p{i} {surf} at 0.5 0.5 0.5 radius 0.0000001\n"));
        d.push_str(&format!("sphere q{i} {surf} at 0 0 0 radius 1\n"));
    }
    d.push_str(&format!(
        "sphere far op at 0 0 0 radius 0.5\nmotion far to {} 9000 3 law smooth\n",
        1e6 + key as f64
    ));
    d.push_str("sphere still op at 1 0 0 radius 0.5\nmotion still to 1 0 0\n");
    d
}

fn scene_of(deck: &str, fidelity: Fidelity) -> Scene {
    initialize(deck.as_bytes(), "random.deck", Path::new("."), fidelity).unwrap_or_else(|e| panic!("{e}\n{deck}"))
}

#[test]
fn structures_answer_as_the_loop_on_random_scenes() {
    let (mut hits, mut stopped) = (0, 0);
    for seed in 0..24u64 {
        let n = [3, 12, 40, 90][seed as usize % 4];
        let deck = random_deck(n, seed);
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            let scene = scene_of(&deck, fidelity);
            let opts = Options {
                fidelity,
                ..Options::default()
            };
            let (h, s) = compare(&scene, opts, 600, seed);
            (hits, stopped) = (hits + h, stopped + s);
        }
    }
    assert!(
        hits > 5000 && stopped > 1000,
        "the rays meet things: {hits} hits, {stopped} stopped"
    );
}

/// Under `--sampler adaptive`, which reads them, the searches are the
/// loop's too.
#[test]
fn structures_search_as_the_loop_for_the_adaptive_sampler() {
    for seed in 100..106u64 {
        let deck = random_deck(30, seed);
        let scene = scene_of(&deck, Fidelity::Thesis);
        let opts = Options {
            sampler: TimeSampler::Adaptive,
            ..Options::default()
        };
        compare(&scene, opts, 400, seed);
    }
}

#[test]
fn degenerate_bounds_answer_as_the_loop() {
    for seed in 0..3 {
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            let scene = scene_of(&degenerate_deck(seed), fidelity);
            let opts = Options {
                fidelity,
                ..Options::default()
            };
            let (hits, _) = compare(&scene, opts, 400, seed);
            assert!(hits > 50, "{hits}");
        }
    }
}

#[test]
fn structures_answer_as_the_loop_on_every_deck() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/decks");
    let mut decks: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "deck"))
        .collect();
    decks.sort();
    assert!(decks.len() >= 12);
    for (n, path) in decks.iter().enumerate() {
        let src = std::fs::read(path).unwrap();
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            let scene = initialize(&src, &path.display().to_string(), &dir, fidelity).unwrap();
            for sampler in [TimeSampler::Table, TimeSampler::Adaptive] {
                if sampler == TimeSampler::Adaptive && fidelity == Fidelity::Listing {
                    continue;
                }
                let opts = Options {
                    fidelity,
                    sampler,
                    ..Options::default()
                };
                compare(&scene, opts, 300, n as u64);
            }
        }
    }
}

/// Objects with the same contour (and box and class) share the prepared
/// data of their sweep: one cap grid for many copies of a star, another
/// for a star of another size.
#[test]
fn copies_of_one_contour_share_their_cache() {
    let star = "sweep {N} op translation bspline at {P} length 0.5\n 1 0\n 0.3 0.3\n 0 1\n -0.3 0.3\n -1 0\n -0.3 -0.3\n 0 -1\n 0.3 -0.3\nend\n";
    let mut deck = String::from(
        "view eye 0 -10 3 look 0 0 0 screen 4 distance 5\nimage 16 16 mask 1\n\
         surface op opaque color 0.8 0.2 0.1 ka 0.2 kd 0.8 ks 0 kt 0\n",
    );
    for (i, at) in ["0 0 0", "2 0 0", "0 3 1"].iter().enumerate() {
        deck.push_str(&star.replace("{N}", &format!("s{i}")).replace("{P}", at));
    }
    deck.push_str(
        &star
            .replace("{N}", "big")
            .replace("{P}", "1 1 1")
            .replace(" 1 0\n", " 2 0\n"),
    );
    deck.push_str("rotate s2 x 30\n");
    let p = Prepared::new(scene_of(&deck, Fidelity::Thesis), Options::default()).unwrap();
    let c = p.caches();
    let same = |a: usize, b: usize| std::sync::Arc::ptr_eq(c[a].as_ref().unwrap(), c[b].as_ref().unwrap());
    assert!(same(0, 1) && same(0, 2), "placed and turned copies share");
    assert!(!same(0, 3), "another contour has its own");
    assert_eq!(c[3], raytrace::shapes::prepare_caches(p.scene())[3]);
}

/// Erratum 2 pinned through the structures: in `listing` fidelity the
/// table's times reach 1.5 (`pattern[row,col]*0.1` of Fig. 2.33) and every
/// moving object slides 6·t along x (erratum 3), so past the shutter's end
/// it goes on from x + 6 to x + 9. The structures bound the objects over
/// every time the table gives (`TimeTable::span`), not the shutter alone:
/// the image is the loop's, byte for byte, with each. Bounded over (0, 1)
/// only, the rays of the last third of the times would pass the objects
/// where they are then.
#[test]
fn listing_times_past_the_shutter_render_as_the_loop() {
    let mut deck = String::from(
        "view eye 0 -20 0 look 0 0 0 screen 10 distance 10\nimage 48 16 mask 4\nbackground 0.1 0.1 0.2\n\
         light sun 5 -10 10 1 1 1\nsurface op opaque color 0.8 0.2 0.1 ka 0.2 kd 0.8 ks 0 kt 0\n",
    );
    for i in 0..12 {
        let (x, z) = (-8.0 + (i % 4) as f64, -1.5 + (i / 4) as f64 * 1.5);
        deck.push_str(&format!(
            "sphere s{i} op at {x} 0 {z} radius 0.4\nmotion s{i} to {x} 0 {z}\n"
        ));
    }
    let scene = scene_of(&deck, Fidelity::Listing);
    let opts = Options {
        fidelity: Fidelity::Listing,
        ..Options::default()
    };
    let prepared = each_accel(&scene, opts);
    let images: Vec<Vec<[u8; 3]>> = prepared
        .iter()
        .map(|p| {
            let r = raytrace::raytrace::render(p, &raytrace::raytrace::Request::STILL).unwrap();
            r.raster.pixels
        })
        .collect();
    // The spheres are seen where the times past 1 put them (x from 1 to
    // 4.4, right of the middle), not only where the shutter does.
    let background = images[0][0];
    let right = (0..16 * 48).filter(|i| (29..40).contains(&(i % 48)));
    assert!(
        right.clone().any(|i| images[0][i] != background),
        "the spheres past t = 1"
    );
    assert_eq!(images[1], images[0], "bvh");
    assert_eq!(images[2], images[0], "octree");
    assert_eq!(prepared[1].time_span(), (0.0, 1.5), "the table's times");
}

/// The boxes over time of `motion::object_bounds`: as many segments as
/// make the farthest mover go its width or less in each (a power of two,
/// at most 16), and as many runs, a segment a tree;
/// each moving object's box over a segment holds its bounding sphere at
/// every time of the segment, and it keeps boxes over the segments only
/// where they are much smaller than its box over all the times. A
/// deforming sweep (a key-frame chain that moves as it deforms) too.
#[test]
fn bounds_in_time_hold_the_movers_and_are_cut_by_their_reach() {
    for (travel, count, runs) in [
        (0.0, 1, 1),
        (0.05, 1, 1),
        (0.5, 1, 1),
        (2.0, 1, 1),
        (2.4, 2, 2),
        (4.6, 4, 4),
        (40.0, 16, 16),
    ] {
        let mut deck = String::from(
            "view eye 0 -20 0 look 0 0 0 screen 10 distance 10\nimage 8 8 mask 1\n\
             surface op opaque color 0.8 0.2 0.1 ka 0.2 kd 0.8 ks 0 kt 0\nblur 1\n",
        );
        for i in 0..6 {
            let x = i as f64 * 3.0;
            deck.push_str(&format!("sphere s{i} op at {x} 0 0 radius 0.5\n"));
            if travel > 0.0 && i % 2 == 0 {
                deck.push_str(&format!(
                    "motion s{i} to {} 0 {} law smooth\n",
                    x + travel * 0.5,
                    travel * 0.25
                ));
            }
        }
        // A star that turns into another while it moves as far in its
        // widths as the spheres go in theirs.
        for (k, x) in [(0, 0.0), (1, travel * 0.5)] {
            deck.push_str(&format!(
                "sweep k{k} op translation bspline at {x} 9 0 length 0.5\n 0 0.5\n -0.5 0\n 0 -0.5\n 0.5 0\nend\n"
            ));
        }
        deck.push_str("rotate k1 z 30\nkeyframe k0 k1\n");
        let scene = scene_of(&deck, Fidelity::Thesis);
        let prepared = Prepared::new(scene, Options::default()).unwrap();
        let moving = prepared.moving();
        let span = prepared.time_span();
        let b = raytrace::motion::object_bounds(&prepared.scene().objects, moving, span, Fidelity::Thesis);
        assert_eq!((b.segments.count(), b.runs), (count, runs), "travel {travel}");
        let chains = moving
            .iter()
            .filter(|m| matches!(m.motion, Motion::Chain { .. }))
            .count();
        assert_eq!(chains, 1, "the deforming star moves");
        for m in moving {
            let timed = &b.timed[m.object];
            // (The star, wider than a sphere, goes fewer of its widths: up
            // to 4.6 radii its boxes over the segments, cut for the spheres,
            // are not small enough.)
            let far = matches!(m.motion, Motion::Path(_)) || travel > 4.6;
            assert_eq!(
                !timed.is_empty(),
                count > 1 && far,
                "travel {travel}: boxes in time of {:?}",
                m.motion
            );
            for (k, bx) in timed.iter().enumerate() {
                let (t0, t1) = b.segments.span(k);
                for j in 0..=20 {
                    let t = t0 + (t1 - t0) * j as f64 / 20.0;
                    let rest = &prepared.scene().objects[m.object];
                    let c = m.pose(rest, t, Fidelity::Thesis).sphereo;
                    let r = rest.radius;
                    let inside = bx.holds(c - r) && bx.holds(c + r);
                    assert!(inside, "travel {travel}, segment {k}, t {t}: {c} in {bx:?}");
                }
            }
        }
    }
}

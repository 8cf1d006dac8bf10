//! Each kind of motion's bounds over an interval of time (`motion.rs`,
//! `drt::motion_bounds`, `PaperChain::centre_bounds`): every place the
//! object's origin takes in the interval lies in them, and they are no
//! larger than those places need. Times reach past [0, 1] as the
//! listing's do (erratum 2: to 1.5) and a key-frame chain's extrapolate.

mod common;

use raytrace::drt::{law_range, motion_bounds, LAW};
use raytrace::hash::hashed_uniform;
use raytrace::motion::{paths, Motion};
use raytrace::options::*;
use raytrace::scene::*;
use raytrace::types::*;

const LAWS: [Law; 4] = [Law::Constant, Law::Accelerate, Law::Decelerate, Law::Smooth];

/// The box of the places `place(t)` takes at `n` + 1 times across [t0, t1].
fn sampled(t0: f64, t1: f64, n: usize, place: impl Fn(f64) -> DVec3) -> BoundingBox {
    (0..=n).fold(BoundingBox::EMPTY, |b, k| {
        b.holding(place(t0 + (t1 - t0) * k as f64 / n as f64))
    })
}

/// Every sampled place is within `rounding` of `bounds`, and `bounds`
/// reaches no further than the sampled places by more than `slack`.
fn holds_tightly(bounds: &BoundingBox, seen: &BoundingBox, rounding: f64, slack: f64, what: &str) {
    let lo = |b: &BoundingBox| DVec3::new(b.xmin, b.ymin, b.zmin);
    let hi = |b: &BoundingBox| DVec3::new(b.xmax, b.ymax, b.zmax);
    assert!(
        (lo(bounds) - rounding).cmple(lo(seen)).all() && (hi(bounds) + rounding).cmpge(hi(seen)).all(),
        "{what}: {bounds:?} does not hold {seen:?}"
    );
    assert!(
        (lo(seen) - lo(bounds)).max_element() <= slack && (hi(bounds) - hi(seen)).max_element() <= slack,
        "{what}: {bounds:?} is larger than {seen:?}"
    );
}

/// LAW's range over an interval: the values at the ends and at its turns,
/// for intervals inside, across and beyond [0, 1].
#[test]
fn law_range_is_the_laws_least_and_greatest_value() {
    let intervals = [
        (0.0, 1.0),
        (0.2, 0.3),
        (0.0, 1.5),
        (0.9, 1.5),
        (-0.7, 0.4),
        (1.5, 4.5),
        (-3.0, 3.0),
        (2.0, 2.0),
    ];
    for law in LAWS {
        for (t0, t1) in intervals {
            let (lo, hi) = law_range(law, t0, t1);
            let mut seen = (f64::INFINITY, f64::NEG_INFINITY);
            for k in 0..=4000 {
                let f = LAW(law, 1.0, t0 + (t1 - t0) * k as f64 / 4000.0);
                seen = (seen.0.min(f), seen.1.max(f));
            }
            assert!(
                lo <= seen.0 + 1e-15 && hi >= seen.1 - 1e-15,
                "{law:?} [{t0}, {t1}]: {lo} {hi} {seen:?}"
            );
            assert!(
                seen.0 - lo < 1e-6 && hi - seen.1 < 1e-6,
                "{law:?} [{t0}, {t1}]: {lo} {hi} {seen:?}"
            );
        }
    }
}

/// A `motion` record of every kind (a line or a Bezier path, every law, a
/// turn or none) at random, as `motionblur` moves it in each fidelity:
/// listing's slide of 6·t along x (erratum 3), the thesis's path.
#[test]
fn a_paths_bounds_hold_its_places_and_no_more() {
    let mut s = common::scene();
    s.surfaces
        .push(common::surface(SurfaceAttribute::Opaque, [1.0; 3], 0.2, 0.8, 0.0, 0.0));
    s.objects.push(common::sphere("ball", 0, [0.5, -1.0, 2.0], 0.3));
    let r = |k: u64| 8.0 * hashed_uniform(k) - 4.0;
    for case in 0..200u64 {
        let via = (case % 2 == 1).then(|| {
            let k = 100 * case;
            [
                DVec3::new(r(k), r(k + 1), r(k + 2)),
                DVec3::new(r(k + 3), r(k + 4), r(k + 5)),
            ]
        });
        let record = MotionRecord {
            pos: Pos::default(),
            object: 0,
            to: DVec3::new(r(100 * case + 6), r(100 * case + 7), r(100 * case + 8)),
            turn: DVec3::new(0.0, 90.0 * (case % 3) as f64, 0.0),
            via,
            law: LAWS[(case / 2 % 4) as usize],
        };
        let (a, b) = (
            1.6 * hashed_uniform(100 * case + 9) - 0.1,
            1.6 * hashed_uniform(100 * case + 10) - 0.1,
        );
        let (t0, t1) = (a.min(b), a.max(b));
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            let obj = &s.objects[0];
            let bounds = motion_bounds(obj, &record, t0, t1, fidelity);
            let seen = sampled(t0, t1, 2000, |t| {
                common::motionblur_pose(obj, &record, t, fidelity).sphereo
            });
            // The exact bounds, to rounding (the paths' coordinates are below 10).
            holds_tightly(
                &bounds,
                &seen,
                1e-13,
                1e-3,
                &format!("case {case} {fidelity:?} [{t0}, {t1}]"),
            );
        }
    }
}

/// The motion table's objects and each key-frame chain: `Moving`'s bounds
/// hold the origin of `Moving::pose` over every interval, on the decks
/// that move (a chain's times extrapolate past [0, 1]). fig5_1's path
/// rises and falls symmetrically in z: its cubic term is a rounding of 0,
/// and the turning point was lost by the root formula that divides by it.
#[test]
fn every_moving_objects_bounds_hold_its_poses() {
    for deck in [
        "fig5_1.deck",
        "fig5_2.deck",
        "fig5_9.deck",
        "fig5_10.deck",
        "fig5_12.deck",
        "nec_morph.deck",
    ] {
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            let p = common::prepare(
                common::load_deck(deck, fidelity),
                Options {
                    fidelity,
                    ..Options::default()
                },
            );
            assert!(!p.moving().is_empty(), "{deck}");
            for m in p.moving() {
                let rest = &p.scene().objects[m.object];
                for (t0, t1) in [(0.0, 1.0), (0.0, 0.25), (0.4, 0.6), (0.3, 1.5), (-0.2, 0.1)] {
                    let bounds = m.centre_bounds(rest, t0, t1, fidelity);
                    let seen = sampled(t0, t1, 1000, |t| m.pose(rest, t, fidelity).sphereo);
                    // Widened for rounding: they hold every place computed.
                    holds_tightly(&bounds, &seen, 0.0, 1e-3, &format!("{deck} {fidelity:?} [{t0}, {t1}]"));
                }
            }
        }
    }
}

/// The motion table is asked of `Isblur` once an object: the objects with
/// a `motion` record, in the object table's order, each with its record;
/// the others (which `Isblur` says do not move) are not in it.
#[test]
fn the_motion_table_holds_the_objects_with_a_motion() {
    let s = common::load_deck("fig5_9.deck", Fidelity::Thesis);
    let moving = paths(&s);
    let mut with_motion: Vec<usize> = s.motions.iter().map(|m| m.object).collect();
    with_motion.sort_unstable();
    assert_eq!(moving.iter().map(|m| m.object).collect::<Vec<_>>(), with_motion);
    for m in &moving {
        let Motion::Path(record) = &m.motion else {
            panic!("a path")
        };
        assert_eq!(record.object, m.object);
    }
    assert!(moving.len() < s.objects.len(), "the floor does not move");
}

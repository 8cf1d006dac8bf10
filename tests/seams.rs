//! The seams every addition plugs into: one prepared scene, one render
//! request (a frame and a window of rows), and the intersection seam's tie
//! rule.

mod common;

use common::{load_deck, prepare};
use raytrace::film::Frame;
use raytrace::options::*;
use raytrace::raytrace::{debug_log, first_hit, render, trace_ray, Prepared, RenderError, Request};
use raytrace::scene::*;
use raytrace::types::*;

fn options(fidelity: Fidelity, sampler: TimeSampler) -> Options {
    Options {
        fidelity,
        sampler,
        ..Options::default()
    }
}

/// A deck that moves and deforms (fig5_10), small.
fn small(fidelity: Fidelity) -> Scene {
    let mut s = load_deck("fig5_10.deck", fidelity);
    s.resize(20, 13, 2);
    s
}

/// Every window of rows renders as those rows of the whole image, byte for
/// byte, with every sampler of the subpixel grid, in both fidelities and
/// for a film frame: the samplers' values depend on the subpixel alone.
/// The windows' primary rays add up to the whole image's.
#[test]
fn a_window_is_those_rows_of_the_whole() {
    for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
        for sampler in [TimeSampler::Table, TimeSampler::Random, TimeSampler::Stratified] {
            let p = prepare(small(fidelity), options(fidelity, sampler));
            for frame in [
                Frame::STILL,
                Frame {
                    number: 2,
                    frames: 3,
                    shutter: 0.5,
                },
            ] {
                let whole = render(&p, &Request::frame(frame)).unwrap();
                let mut primary = 0;
                for rows in [0..1, 1..5, 5..12, 12..13] {
                    let part = render(&p, &Request::frame(frame).rows(rows.clone())).unwrap();
                    assert_eq!(part.rows, rows);
                    assert_eq!(part.raster.height, rows.len());
                    let want = &whole.raster.pixels[rows.start * 20..rows.end * 20];
                    assert_eq!(part.raster.pixels, want, "{fidelity:?} {sampler:?} {rows:?}");
                    let colours = &whole.colours[rows.start * 20..rows.end * 20];
                    assert!(part
                        .colours
                        .iter()
                        .zip(colours)
                        .all(|(a, b)| a.to_array() == b.to_array()));
                    primary += part.stats.primary;
                }
                assert_eq!(primary, whole.stats.primary, "{fidelity:?} {sampler:?}");
            }
        }
    }
}

/// A window outside the image, or empty, is refused; so is a window of the
/// adaptive sampler, which deals its rays over the whole image (its whole
/// image renders).
#[test]
fn windows_that_cannot_be_rendered_are_refused() {
    let p = prepare(small(Fidelity::Thesis), Options::default());
    for rows in [3..3, 0..14, 13..14] {
        let e = render(&p, &Request::STILL.rows(rows.clone())).unwrap_err();
        assert!(matches!(e, RenderError::Window(_)), "{rows:?}: {e}");
        assert!(e.to_string().contains("13 rows"), "{e}");
    }
    let adaptive = prepare(
        small(Fidelity::Thesis),
        options(Fidelity::Thesis, TimeSampler::Adaptive),
    );
    let e = render(&adaptive, &Request::STILL.rows(0..5)).unwrap_err();
    assert!(e.to_string().contains("--sampler adaptive"), "{e}");
    assert_eq!(
        render(&adaptive, &Request::STILL.rows(0..13)).unwrap().raster.height,
        13
    );
}

/// What cannot be prepared is an error of `Prepared::new`, never a default
/// taken later: a pattern that does not fit the mask (at its record), and
/// the adaptive sampler with the listing's times.
#[test]
fn what_cannot_be_prepared_is_an_error() {
    let mut s = small(Fidelity::Thesis);
    s.pattern = Some(PatternRecord {
        pos: Pos {
            file: "t.deck".into(),
            line: 7,
            column: 3,
        },
        m: 3,
        values: vec![vec![0, 1, 2], vec![3, 4, 5], vec![6, 7, 8]],
    });
    let e = Prepared::new(s, Options::default()).unwrap_err();
    assert!(matches!(e, RenderError::Misfit { record: "pattern", .. }), "{e}");
    assert!(e.to_string().starts_with("t.deck:7:3: pattern:"), "{e}");
    let e = Prepared::new(
        small(Fidelity::Listing),
        options(Fidelity::Listing, TimeSampler::Adaptive),
    )
    .unwrap_err();
    assert!(matches!(e, RenderError::Options(_)), "{e}");
}

/// The debug log of a window has that window's scanlines only.
#[test]
fn the_debug_log_follows_the_window() {
    let p = prepare(small(Fidelity::Listing), options(Fidelity::Listing, TimeSampler::Table));
    let r = render(&p, &Request::STILL.rows(4..6)).unwrap();
    let log = debug_log(&p, &r);
    let lines: Vec<&str> = log.lines().filter(|l| l.starts_with(" scanline=")).collect();
    assert_eq!(
        lines,
        [
            " scanline=    9",
            " scanline=   10",
            " scanline=   11",
            " scanline=   12"
        ]
    );
    assert!(log.contains(&format!("kfTIRcnt={:9}", r.stats.kftircnt)));
}

/// Two objects the same in every way but their surface: of two hits at the
/// same t the object earlier in the table is the nearest, whichever it is.
#[test]
fn of_two_hits_at_one_t_the_earlier_object_is_the_nearest() {
    let ray = Ray::new(DVec3::new(0.0, -5.0, 0.0), DVec3::Y);
    let (red, blue) = ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    for (first, second) in [(red, blue), (blue, red)] {
        let mut s = common::scene();
        for colour in [first, second] {
            let k = s.surfaces.len();
            s.surfaces
                .push(common::surface(SurfaceAttribute::Light, colour, 0.0, 0.0, 0.0, 0.0));
            s.objects.push(common::sphere("ball", k, [0.0, 0.0, 0.0], 1.0));
        }
        let p = prepare(s, Options::default());
        assert_eq!(trace_ray(&p, &ray, 0.0).0, DVec3::from_array(first));
        assert_eq!(first_hit(&p, &ray, None).map(|h| h.object), Some(0));
    }
}

/// `first_hit` sees the scene at the time asked: a block that slides along
/// x is met where it stands then, and at rest where the deck put it.
#[test]
fn first_hit_sees_the_scene_at_its_time() {
    let p = prepare(common::moving_block(2, 4, 20.0), Options::default());
    let at = |x: f64| Ray::new(DVec3::new(x, -50.0, 0.0), DVec3::Y);
    assert!(first_hit(&p, &at(-5.0), None).is_some());
    assert!(first_hit(&p, &at(-5.0), Some(1.0)).is_none());
    assert!(first_hit(&p, &at(5.0), Some(1.0)).is_some());
    assert!(first_hit(&p, &at(0.0), Some(0.5)).is_some());
}

/// A prepared scene renders the same every time, and its still at a time
/// has nothing left that moves.
#[test]
fn still_at_has_nothing_that_moves() {
    let p = prepare(load_deck("nec_morph.deck", Fidelity::Thesis), Options::default());
    assert!(p.timed());
    assert_eq!(p.chains().count(), 1);
    let still = p.still_at(0.25);
    assert!(!still.timed());
    assert_eq!(still.chains().count(), 0);
    assert!(still.scene().keyframes.is_empty() && still.scene().motions.is_empty());
}

/// A shadow ray through two `crystal` objects takes kt·colour of each, in
/// the object table's order (the product to the bit); an opaque object on
/// it anywhere in the table stops it.
#[test]
fn a_shadow_ray_passes_each_crystal_in_the_tables_order() {
    let mut s = common::scene();
    s.surfaces
        .push(common::surface(SurfaceAttribute::Opaque, [1.0; 3], 0.0, 1.0, 0.0, 0.0));
    s.objects
        .push(common::block("floor", 0, [0.0, 0.0, -0.5], [20.0, 20.0, 1.0]));
    s.lights.push(common::light([0.0, 0.0, 10.0], [1.0, 1.0, 1.0]));
    let glass = [([0.3, 0.7, 0.9], 0.7), ([0.9, 0.11, 0.6], 0.45)];
    for (k, (colour, kt)) in glass.iter().enumerate() {
        s.surfaces
            .push(common::surface(SurfaceAttribute::Crystal, *colour, 0.0, 0.0, 0.0, *kt));
        s.objects
            .push(common::sphere("gem", k + 1, [0.0, 0.0, 3.0 + 3.0 * k as f64], 1.0));
    }
    let ray = Ray::new(DVec3::new(0.0, 0.0, 1.5), DVec3::NEG_Z);
    let mut want = Intensity::ONE;
    for (colour, kt) in glass {
        want *= kt * DVec3::from_array(colour);
    }
    assert_eq!(trace_ray(&prepare(s.clone(), Options::default()), &ray, 0.0).0, want);
    for at in [1, 3] {
        let mut shaded = s.clone();
        shaded
            .objects
            .insert(at, common::sphere("stone", 0, [0.0, 0.0, 8.5], 0.5));
        let got = trace_ray(&prepare(shaded, Options::default()), &ray, 0.0).0;
        assert_eq!(got, Intensity::ZERO, "the stone at {at}");
    }
}

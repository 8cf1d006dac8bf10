//! `raytrace --show` and `--watch` without a window: the image rendered in
//! bands of rows is the image rendered whole (raster, colours, counts,
//! statistics), for a still, a deforming blurred object, the listing's
//! fidelity, a film's frame and the adaptive sampler; a stopped render
//! gives nothing; the picture so far fills band by band.

use std::path::Path;

use raytrace::film::Frame;
use raytrace::options::{Fidelity, Options, TimeSampler};
use raytrace::raytrace::{render, Prepared, Request};
use raytrace::run::DeckInput;
use raytrace::show::{render_in_bands, Progressive, BAND_ROWS};

fn prepared(deck: &str, opts: Options, size: usize) -> Prepared {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("legacy_pascal/decks")
        .join(deck);
    let mut scene = DeckInput::read(&path).unwrap().initialize(opts.fidelity).unwrap();
    let mask = scene.image.masksize;
    scene.resize(size, size - 3, mask);
    Prepared::new(scene, opts).unwrap()
}

#[test]
fn the_bands_joined_are_the_whole_render() {
    let listing = Options {
        fidelity: Fidelity::Listing,
        ..Options::default()
    };
    let adaptive = Options {
        sampler: TimeSampler::Adaptive,
        ..Options::default()
    };
    for (deck, opts, frame) in [
        ("fig5_8.deck", Options::default(), Frame::STILL),
        ("fig5_10.deck", Options::default(), Frame::STILL),
        ("fig5_10.deck", listing, Frame::STILL),
        ("fig5_9.deck", adaptive, Frame::STILL),
        (
            "nec_commercial.deck",
            Options::default(),
            Frame {
                number: 7,
                frames: 36,
                shutter: 0.5,
            },
        ),
    ] {
        let p = prepared(deck, opts, 30);
        let request = Request::frame(frame);
        let whole = render(&p, &request).unwrap();
        let mut seen = Vec::new();
        let mut picture = Progressive::new(30, 27);
        let joined = render_in_bands(&p, &request, |band| {
            seen.push(band.rows.clone());
            picture.band(band);
            true
        })
        .unwrap()
        .unwrap();
        assert_eq!(joined.raster, whole.raster, "{deck}");
        assert_eq!(joined.colours, whole.colours, "{deck}");
        assert_eq!(joined.counts, whole.counts, "{deck}");
        assert_eq!(joined.stats, whole.stats, "{deck}");
        assert_eq!(joined.rows, 0..27);
        assert_eq!(
            picture.raster, whole.raster,
            "{deck}: the picture so far is the whole at the end"
        );
        let bands = if opts.sampler == TimeSampler::Adaptive {
            1
        } else {
            27usize.div_ceil(BAND_ROWS)
        };
        assert_eq!(seen.len(), bands, "{deck}");
    }
}

#[test]
fn a_stopped_render_gives_nothing_and_leaves_the_rest_black() {
    let p = prepared("fig5_8.deck", Options::default(), 30);
    let mut picture = Progressive::new(30, 27);
    let mut calls = 0;
    let r = render_in_bands(&p, &Request::STILL, |band| {
        calls += 1;
        picture.band(band);
        false
    })
    .unwrap();
    assert!(r.is_none());
    assert_eq!(calls, 1);
    assert!(picture.raster.pixels[..30 * BAND_ROWS].iter().any(|&p| p != [0, 0, 0]));
    assert!(picture.raster.pixels[30 * BAND_ROWS..].iter().all(|&p| p == [0, 0, 0]));
}

#[test]
fn without_a_display_show_and_watch_say_so_and_render_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let deck = Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/decks/fig5_8.deck");
    for flag in ["--show", "--watch"] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_raytrace"))
            .arg(&deck)
            .args([flag, "-o", "x.ras"])
            .current_dir(dir.path())
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        let e = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{flag}: {e}");
        assert!(e.contains("cannot open a window (DISPLAY is not set)"), "{e}");
        assert!(e.contains("xvfb-run") && e.contains("psout FILE"), "{e}");
        assert!(!dir.path().join("x.ras").exists());
    }
}

#[test]
fn watch_needs_a_deck_file() {
    for args in [&["-", "--watch"][..], &["--watch"][..]] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_raytrace"))
            .args(args)
            .output()
            .unwrap();
        let e = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {e}");
        assert!(e.contains("--watch renders a deck file again"), "{e}");
    }
}

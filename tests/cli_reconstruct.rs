//! The `raytrace` command's `--denoise`, `--coherence N` and `--sampler
//! sobol`: what they write and say, and the inputs they refuse (exit
//! status 2, nothing written).

use std::process::Command;

mod common;
use common::{decks, raytrace_command};

/// `raytrace fig5_3.deck --size 24x16 ARGS -o OUT`: its exit status and
/// what it wrote to standard error.
fn run(args: &[&str], out: &std::path::Path) -> (Option<i32>, String) {
    let o = raytrace_command()
        .arg(decks().join("fig5_3.deck"))
        .args(["--size", "24x16"])
        .args(args)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned())
}

/// Each flag renders, and the summary line says how the pixels were made.
#[test]
fn the_summary_line_names_the_reconstruction() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.ras");
    for (args, says) in [
        (&["--denoise"][..], "(24×16, 2×2 subpixels, denoised,"),
        (
            &["--denoise", "--sampler", "adaptive"],
            "(24×16, 4 rays a pixel on average, adaptive, denoised,",
        ),
        (
            &["--coherence", "4"],
            "(24×16, 2×2 subpixels in the pixels coherence 4 traced,",
        ),
        (&["--sampler", "sobol", "--mask", "4"], "(24×16, 4×4 subpixels,"),
    ] {
        let (status, err) = run(args, &out);
        assert_eq!(status, Some(0), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        let r = raytrace::raster::read_raster_file(&out).unwrap();
        assert_eq!((r.width, r.height), (24, 16));
        std::fs::remove_file(&out).unwrap();
    }
}

/// `--coherence 0`, above 64 or not a number, `--denoise` twice, the two
/// together, coherence with the adaptive sampler: a usage error, exit 2,
/// nothing written.
#[test]
fn bad_reconstruction_flags_are_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o.ras");
    for (args, says) in [
        (&["--coherence", "0"][..], "0 is not in 1..=64"),
        (&["--coherence", "65"], "65 is not in 1..=64"),
        (&["--coherence", "two"], "invalid value"),
        (&["--denoise", "--denoise"], "cannot be used multiple times"),
        (&["--denoise", "--coherence", "2"], "cannot be used with"),
        (
            &["--coherence", "2", "--sampler", "adaptive"],
            "--sampler adaptive deals its rays",
        ),
    ] {
        let (status, err) = run(args, &out);
        assert_eq!(status, Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "{args:?} left a file"
        );
    }
}

/// A film with `--denoise`: each frame written, as the same frame
/// rendered alone writes it.
#[test]
fn a_film_denoised_frame_by_frame() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("f.ras");
    let film = |frames: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_raytrace"))
            .arg(decks().join("nec_commercial.deck"))
            .args(["--size", "20x16", "--denoise", "-q", "--frames", frames, "-o"])
            .arg(&stem)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    film("1..3");
    let second = std::fs::read(dir.path().join("f.0002.ras")).unwrap();
    std::fs::remove_file(dir.path().join("f.0002.ras")).unwrap();
    film("2");
    assert_eq!(std::fs::read(dir.path().join("f.0002.ras")).unwrap(), second);
    assert_ne!(std::fs::read(dir.path().join("f.0001.ras")).unwrap(), second);
}

//! The `raytrace` command's `--sampler adaptive`, `--mask` and `--size`:
//! what they write, what the summary line says, and the inputs they refuse
//! (exit status 2, nothing written).

use std::process::Command;

fn raytrace() -> Command {
    Command::new(env!("CARGO_BIN_EXE_raytrace"))
}

/// A folder holding `moving.deck` (`MOVING`), and the deck's path.
fn moving_deck() -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("moving.deck");
    std::fs::write(&deck, MOVING).unwrap();
    (dir, deck)
}

const MOVING: &str = "\
view  eye 0 -10 3  look 0 0 0  screen 4  distance 5
image 16 12  mask 2
light sun 5 -5 10  1 1 1
surface red opaque color 1 0 0 ka 0.2 kd 0.8 ks 0 kt 0
sphere ball red at -1 0 0 radius 1
motion ball to 1 0 0
blur 1
";

/// `--size` and `--mask` take the place of the deck's `image` record for
/// the run: the raster has the size asked for, and the summary line names
/// it and the rays a pixel.
#[test]
fn size_and_mask_override_the_deck() {
    let (dir, deck) = moving_deck();
    let out = dir.path().join("moving.ras");
    let run = raytrace()
        .args([
            "--size",
            "20x10",
            "--mask",
            "3",
            "--sampler",
            "adaptive",
            "--threads",
            "2",
        ])
        .arg(&deck)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let r = raytrace::raster::read_raster_file(&out).unwrap();
    assert_eq!((r.width, r.height), (20, 10));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("(20×10, 9 rays a pixel on average, adaptive,"), "{err}");

    let run = raytrace()
        .args(["--size", "8x6", "--mask", "32"])
        .arg(&deck)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("(8×6, 32×32 subpixels,"), "{err}");
    let r = raytrace::raster::read_raster_file(&out).unwrap();
    assert_eq!((r.width, r.height), (8, 6));
}

/// The adaptive image is the same for 1 and 2 threads, byte for byte.
#[test]
fn adaptive_is_the_same_for_any_threads() {
    let (dir, deck) = moving_deck();
    let mut rasters = Vec::new();
    for threads in ["1", "2"] {
        let out = dir.path().join(format!("t{threads}.ras"));
        let run = raytrace()
            .args(["-q", "--sampler", "adaptive", "--mask", "4", "--threads", threads])
            .arg(&deck)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        rasters.push(std::fs::read(&out).unwrap());
    }
    assert_eq!(rasters[0], rasters[1]);
}

/// Each refused input: exit status 2, a message naming the flag (and for
/// the listing's fidelity, both flags), and no file written.
#[test]
fn bad_input_exits_2_and_writes_nothing() {
    let (dir, deck) = moving_deck();
    let out = dir.path().join("out.ras");
    let cases: [(&[&str], &[&str]); 6] = [
        (
            &["--sampler", "adaptive", "--fidelity", "listing"],
            &["--sampler adaptive", "--fidelity listing"],
        ),
        (&["--mask", "0"], &["--mask", "1..=32"]),
        (&["--mask", "33"], &["--mask", "1..=32"]),
        (&["--size", "0x10"], &["--size", "width '0'"]),
        (&["--size", "9000x10"], &["--size", "width '9000'", "8192"]),
        (&["--size", "64"], &["--size", "WxH"]),
    ];
    for (args, words) in cases {
        let run = raytrace()
            .args(args)
            .arg(&deck)
            .arg("-o")
            .arg(&out)
            .arg("--png")
            .arg(dir.path().join("out.png"))
            .output()
            .unwrap();
        assert_eq!(run.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&run.stderr);
        for w in words {
            assert!(err.contains(w), "{args:?}: no '{w}' in {err}");
        }
        // Only the deck is in the folder.
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1, "{args:?}");
    }
}

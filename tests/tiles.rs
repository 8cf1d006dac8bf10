//! A farm's tasks as a user runs them (issue 25): `raytrace --tile K/N`
//! bands that join into the one-process render byte for byte, `--resume`
//! that keeps complete outputs and renders incomplete ones again, and the
//! bad inputs of `--tile`, each exit 2 with nothing written.

use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use raytrace::raster::encode_raster;
use raytrace::tile::join;

mod common;
use common::{decks, file_names, raytrace_command};

fn run(cmd: &mut Command) -> Output {
    cmd.output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `raytrace DECK -q ARGS`, which must succeed.
fn render(deck: &str, args: &[&str]) {
    let o = run(raytrace_command().arg(decks().join(deck)).arg("-q").args(args));
    assert!(o.status.success(), "{deck} {args:?}: {}", stderr(&o));
}

/// The bands 1..n of `deck` rendered one process each with `flags` (`-o
/// DIR/partK.ras`), and the whole image rendered by one process (`-o
/// DIR/whole.ras`): the bands joined are its bytes. `file` gives the file
/// an `-o DIR/NAME.ras` writes (a film's frame is `NAME.FRAME.ras`).
fn bands_join_to_the_whole(dir: &Path, deck: &str, n: u32, flags: &[&str], file: &dyn Fn(&str) -> PathBuf) {
    let o = |name: &str| dir.join(format!("{name}.ras")).to_str().unwrap().to_string();
    let mut whole_args = flags.to_vec();
    let whole = o("whole");
    whole_args.extend(["-o", &whole, "--threads", "2"]);
    render(deck, &whole_args);
    let mut parts = Vec::new();
    for k in 1..=n {
        let tile = format!("{k}/{n}");
        let name = o(&format!("part{k}"));
        let mut args = flags.to_vec();
        // Another thread count for each band: the bytes depend on neither.
        let threads = (k % 3 + 1).to_string();
        args.extend(["--tile", &tile, "-o", &name, "--threads", &threads]);
        render(deck, &args);
        parts.push(file(&format!("part{k}")));
    }
    let joined = join(&parts).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        encode_raster(&joined),
        std::fs::read(file("whole")).unwrap(),
        "{deck} {flags:?}: the bands joined differ from the whole"
    );
}

/// The bands of a still that moves and deforms (fig5_10), joined, are the
/// one-process render byte for byte with the table, random and stratified
/// samplers in both fidelities; 30 rows in 4 bands split unevenly (7, 8,
/// 7, 8), so bands start inside no block of the listing but between them.
#[test]
fn joined_bands_are_the_one_process_render_for_every_grid_sampler_and_fidelity() {
    for fidelity in ["thesis", "listing"] {
        for sampler in ["table", "random", "stratified"] {
            let dir = tempfile::tempdir().unwrap();
            let flags = [
                "--size",
                "40x30",
                "--mask",
                "2",
                "--fidelity",
                fidelity,
                "--sampler",
                sampler,
            ];
            let file = |name: &str| dir.path().join(format!("{name}.ras"));
            bands_join_to_the_whole(dir.path(), "fig5_10.deck", 4, &flags, &file);
        }
    }
}

/// With `--denoise` (the filter's reach rendered in each band and cut)
/// and with `--coherence N` (the cells a band crosses worked out whole),
/// the bands joined are still the one-process render byte for byte, and
/// `--sampler sobol` bands join as the other grid samplers' do.
#[test]
fn joined_bands_are_the_one_process_render_with_the_reconstructions() {
    for extra in [
        &["--denoise"][..],
        &["--denoise", "--sampler", "sobol"],
        &["--coherence", "4"],
        &["--coherence", "3", "--fidelity", "listing"],
        &["--sampler", "sobol"],
    ] {
        let dir = tempfile::tempdir().unwrap();
        let mut flags = vec!["--size", "40x30", "--mask", "2"];
        flags.extend(extra);
        let file = |name: &str| dir.path().join(format!("{name}.ras"));
        bands_join_to_the_whole(dir.path(), "fig5_10.deck", 4, &flags, &file);
    }
}

/// A film's frame in bands: each band file is named as the frame, and the
/// bands joined are the frame one process renders.
#[test]
fn the_bands_of_a_film_frame_join_to_the_frame() {
    let dir = tempfile::tempdir().unwrap();
    let flags = ["--size", "24x21", "--frames", "7"];
    let file = |name: &str| dir.path().join(format!("{name}.0007.ras"));
    bands_join_to_the_whole(dir.path(), "nec_commercial.deck", 3, &flags, &file);
}

/// A band written alone is a raster of its rows any raster reader reads
/// (the line naming the band comes after the pixels).
#[test]
fn a_band_is_a_raster_of_its_rows() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b.ras");
    render(
        "fig5_8.deck",
        &["--size", "20x10", "--tile", "2/3", "-o", out.to_str().unwrap()],
    );
    let r = raytrace::raster::read_raster_file(&out).unwrap();
    assert_eq!((r.width, r.height), (20, 3));
    let bytes = std::fs::read(&out).unwrap();
    assert!(bytes.ends_with(b"raytrace tile 2/3: rows 3..6 of 10\n"));
}

/// `--resume`: the frames already there and complete are kept (the very
/// same files), a truncated one and a missing one are rendered again, to
/// the bytes the first run wrote; run once more, nothing is rendered.
#[test]
fn resume_keeps_complete_frames_and_renders_the_rest_again() {
    let dir = tempfile::tempdir().unwrap();
    let stem = dir.path().join("f.ras");
    let args = ["--size", "20x16", "--frames", "1..4", "-o", stem.to_str().unwrap()];
    render("nec_commercial.deck", &args);
    let frame = |k: u32| dir.path().join(format!("f.{k:04}.ras"));
    let first: Vec<Vec<u8>> = (1..=4).map(|k| std::fs::read(frame(k)).unwrap()).collect();
    let inode = |k: u32| std::fs::metadata(frame(k)).unwrap().ino();
    let kept = [(1, inode(1)), (4, inode(4))];
    std::fs::write(frame(2), &first[1][..first[1].len() - 1]).unwrap();
    std::fs::remove_file(frame(3)).unwrap();
    let mut resume = args.to_vec();
    resume.push("--resume");
    let o = run(raytrace_command()
        .arg(decks().join("nec_commercial.deck"))
        .args(&resume));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("f.0002.ras: not complete"), "{}", stderr(&o));
    // A missing frame is not "not complete": it is simply rendered.
    assert!(!stderr(&o).contains("f.0003.ras"), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("2 complete already (--resume) kept"),
        "{}",
        stderr(&o)
    );
    for (k, ino) in kept {
        assert_eq!(inode(k), ino, "frame {k} was written again");
    }
    for k in 1..=4 {
        assert_eq!(std::fs::read(frame(k)).unwrap(), first[k as usize - 1], "frame {k}");
    }
    let o = run(raytrace_command()
        .arg(decks().join("nec_commercial.deck"))
        .args(&resume));
    assert!(stderr(&o).contains("nothing rendered"), "{}", stderr(&o));
    assert!(stderr(&o).contains(" 0 rays"), "{}", stderr(&o));
    // Quiet, a frame cut short is rendered again without a word.
    std::fs::write(frame(2), &first[1][..10]).unwrap();
    let mut quiet = resume.clone();
    quiet.push("-q");
    let o = run(raytrace_command().arg(decks().join("nec_commercial.deck")).args(&quiet));
    assert!(o.status.success() && o.stderr.is_empty(), "{}", stderr(&o));
    assert_eq!(std::fs::read(frame(2)).unwrap(), first[1]);
}

/// `--resume --apng`: the frames kept are read back, so the animated PNG
/// holds every frame, the same bytes as a run that rendered them all.
#[test]
fn resume_with_apng_animates_the_kept_frames_too() {
    let dir = tempfile::tempdir().unwrap();
    let path = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let (stem, all, resumed) = (path("f.ras"), path("all.png"), path("resumed.png"));
    render(
        "nec_commercial.deck",
        &["--size", "16x12", "--frames", "1..3", "-o", &stem, "--apng", &all],
    );
    std::fs::remove_file(dir.path().join("f.0002.ras")).unwrap();
    render(
        "nec_commercial.deck",
        &[
            "--size", "16x12", "--frames", "1..3", "-o", &stem, "--apng", &resumed, "--resume",
        ],
    );
    assert_eq!(std::fs::read(&resumed).unwrap(), std::fs::read(&all).unwrap());
}

/// `--resume` of a band: kept when it is that band whole, rendered again
/// when it is cut short or is another band of the same file name.
#[test]
fn resume_checks_a_band_for_its_own_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b.ras");
    let o_ = out.to_str().unwrap();
    let band = |tile: &str| {
        let o = run(raytrace_command()
            .arg(decks().join("fig5_8.deck"))
            .args(["--size", "20x11", "--resume", "--tile", tile, "-o", o_]));
        assert!(o.status.success(), "{}", stderr(&o));
        stderr(&o)
    };
    assert!(!band("1/2").contains("nothing rendered"));
    let written = std::fs::read(&out).unwrap();
    assert!(band("1/2").contains("nothing rendered"));
    std::fs::write(&out, &written[..written.len() - 1]).unwrap();
    assert!(band("1/2").contains("not complete"));
    assert_eq!(std::fs::read(&out).unwrap(), written);
    // Band 2 of 2 is 6 rows, band 1 5: the file is not it.
    let e = band("2/2");
    assert!(e.contains("not complete") && !e.contains("nothing rendered"), "{e}");
}

/// Every bad input of `--tile` (and `--resume`) is exit 2 with a message
/// that says what is wrong, and nothing is written: not the output, not
/// the default folder raster/.
#[test]
fn bad_tiles_are_usage_errors_and_write_nothing() {
    let cases: &[(&[&str], &str)] = &[
        (&["--tile", "0/3"], "K must be one of the bands 1..=3"),
        (&["--tile", "4/3"], "K must be one of the bands 1..=3"),
        (&["--tile", "1/0"], "N, the number of bands, must be"),
        (&["--tile", "x/2"], "K 'x' is not a whole number"),
        (&["--tile", "1/13"], "13 bands of an image of 12 rows"),
        (&["--tile", "1/2", "-o", "-"], "-o -: --tile 1/2 writes a band"),
        (&["--tile", "1/2", "-o", "/dev/null"], "-o /dev/null: --tile 1/2"),
        (&["--tile", "1/2", "-o", "x.png"], "name it with -o NAME.ras"),
        (&["--tile", "1/2", "--png", "x.png"], "--png with --tile 1/2"),
        (
            &["--tile", "1/2", "--sampler", "adaptive"],
            "--sampler adaptive deals its rays over the whole image",
        ),
        (&["--resume", "-o", "-"], "-o -: --resume checks Sun raster files"),
        (&["--resume", "-o", "x.png"], "name it with -o NAME.ras"),
    ];
    for (args, says) in cases {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("small.deck"), common::SMALL_DECK).unwrap();
        let o = run(raytrace_command().current_dir(dir.path()).arg("small.deck").args(*args));
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
        assert!(o.stdout.is_empty(), "{args:?} wrote to standard output");
        assert_eq!(file_names(dir.path()), ["small.deck"], "{args:?}");
    }
    // A film's --apng needs whole frames.
    let dir = tempfile::tempdir().unwrap();
    let o = run(raytrace_command()
        .current_dir(dir.path())
        .arg(decks().join("nec_commercial.deck"))
        .args(["--tile", "1/2", "--apng", "a.png", "-o", "f.ras"]));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--apng with --tile 1/2"), "{}", stderr(&o));
    assert!(file_names(dir.path()).is_empty());
}

/// Without -o, a band goes to raster/<deck>.K-of-N.ras, beside the whole
/// image's raster/<deck>.ras and not over it.
#[test]
fn a_band_without_o_is_named_by_its_band() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("small.deck"), common::SMALL_DECK).unwrap();
    let o = run(raytrace_command()
        .current_dir(dir.path())
        .args(["small.deck", "-q", "--tile", "2/3"]));
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(file_names(&dir.path().join("raster")), ["small.2-of-3.ras"]);
}

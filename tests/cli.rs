//! The `raytrace` command as a user meets it: exit codes, what it writes
//! and what it refuses to write.

mod common;
use common::{decks, raytrace_command, SMALL_DECK};

/// A deck with an error: exit status 2, the error as FILE:LINE:COLUMN,
/// and no raster, no PNG, no debug log written (and an old raster left
/// as it was).
#[test]
fn deck_error_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("bad.deck");
    std::fs::write(&deck, SMALL_DECK.replace("radius 1", "radius lots")).unwrap();
    let out = dir.path().join("bad.ras");
    std::fs::write(&out, b"the last good raster").unwrap();
    let png = dir.path().join("bad.png");
    let debug = dir.path().join("bad.log");
    let run = raytrace_command()
        .arg(&deck)
        .arg("-o")
        .arg(&out)
        .arg("--png")
        .arg(&png)
        .arg("--debug")
        .arg(&debug)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("bad.deck:5:"), "{err}");
    assert!(err.contains("sphere 'ball'"), "{err}");
    assert_eq!(std::fs::read(&out).unwrap(), b"the last good raster");
    assert!(!png.exists() && !debug.exists());
    // Only the two files the test made are in the folder.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
}

/// A deck that cannot be read at all, and a texture that is not a raster.
#[test]
fn unreadable_inputs_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let run = raytrace_command()
        .arg(dir.path().join("missing.deck"))
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("missing.deck"));

    std::fs::write(dir.path().join("junk.ras"), b"not a raster at all, not even close").unwrap();
    let deck = dir.path().join("tex.deck");
    std::fs::write(&deck, format!("{SMALL_DECK}texture red junk.ras\n")).unwrap();
    let out = dir.path().join("tex.ras");
    let run = raytrace_command().arg(&deck).arg("-o").arg(&out).output().unwrap();
    assert_eq!(run.status.code(), Some(2), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(String::from_utf8_lossy(&run.stderr).contains("tex.deck:6:"));
    assert!(!out.exists());
}

/// A good deck: exit 0, a raster the reader reads back at the deck's
/// size, a PNG, and the listing's debug log.
#[test]
fn good_deck_writes_raster_png_and_debug_log() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("small.deck");
    std::fs::write(&deck, SMALL_DECK).unwrap();
    std::fs::create_dir(dir.path().join("nested")).unwrap();
    let out = dir.path().join("nested/small.ras");
    let png = dir.path().join("small.png");
    let debug = dir.path().join("small.log");
    let run = raytrace_command()
        .args(["--quiet", "--threads", "2"])
        .arg(&deck)
        .arg("-o")
        .arg(&out)
        .arg("--png")
        .arg(&png)
        .arg("--debug")
        .arg(&debug)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(
        run.stderr.is_empty(),
        "--quiet: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    let r = raytrace::raster::read_raster_file(&out).unwrap();
    assert_eq!((r.width, r.height), (16, 12));
    assert!(
        r.pixels.iter().any(|p| p[0] > 100 && p[1] < 30),
        "the red ball is in the picture"
    );
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    let log = std::fs::read_to_string(&debug).unwrap();
    assert_eq!(log.lines().filter(|l| l.starts_with(" scanline=")).count(), 12);
    assert!(log.contains(" scanline=    1\n") && log.contains("FRAME NUMBER   1---DONE"));
}

/// The two fidelities are accepted, and a bad flag is a usage error.
#[test]
fn flags() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("small.deck");
    std::fs::write(&deck, SMALL_DECK).unwrap();
    for f in ["listing", "thesis"] {
        let out = dir.path().join(format!("{f}.ras"));
        let run = raytrace_command()
            .args(["-q", "--fidelity", f])
            .arg(&deck)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        assert!(run.status.success());
        assert!(out.exists());
    }
    let run = raytrace_command()
        .args(["--fidelity", "pascal"])
        .arg(&deck)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let help = raytrace_command().arg("--help").output().unwrap();
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(text.contains("--fidelity") && text.contains("Exit status"));
}

/// Every deck in legacy_pascal/decks renders at a small size with no NaN
/// or infinite colour reaching the raster (checked on the float image
/// before `rgbtochars`, which would hide a NaN as black).
#[test]
fn every_legacy_deck_renders_without_nan() {
    use raytrace::options::{Fidelity, Options};
    let mut names = vec![];
    for entry in std::fs::read_dir(decks()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "deck") {
            names.push(path);
        }
    }
    names.sort();
    assert!(names.len() >= 6, "{names:?}");
    for path in names {
        let src = std::fs::read_to_string(&path).unwrap();
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            let name = path.display().to_string();
            let mut scene = raytrace::deck::initialize(&src, &name, decks(), fidelity)
                .unwrap_or_else(|e| panic!("{name} ({fidelity:?}): {e}"));
            let opts = Options {
                fidelity,
                ..Options::default()
            };
            scene.image.width = 48;
            scene.image.height = 48;
            let prepared = match raytrace::raytrace::Prepared::new(scene, opts) {
                Ok(p) => p,
                Err(e) => {
                    // Key frames come with the paper unit.
                    assert!(e.to_string().contains("keyframe"), "{name}: {e}");
                    continue;
                }
            };
            let colours = raytrace::raytrace::render(&prepared, &raytrace::raytrace::Request::STILL)
                .unwrap()
                .colours;
            assert!(
                colours.iter().all(|c| c.is_finite()),
                "{name} ({fidelity:?}): a NaN or infinite colour"
            );
        }
    }
}

/// With no deck, the embedded default (nec_morph.deck) is rendered to
/// raster/default.ras and raster/default.png under the working folder.
#[test]
fn no_deck_renders_the_embedded_default() {
    let dir = tempfile::tempdir().unwrap();
    let run = raytrace_command().arg("-q").current_dir(dir.path()).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let r = raytrace::raster::read_raster_file(&dir.path().join("raster/default.ras")).unwrap();
    assert_eq!((r.width, r.height), (256, 256));
    let png = std::fs::read(dir.path().join("raster/default.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG"));
    // The blue letters are in the picture.
    let blue = |p: &&[u8; 3]| p[2] as i32 > p[0] as i32 + 60 && p[2] as i32 > p[1] as i32 + 40;
    assert!(r.pixels.iter().filter(blue).count() > 200);
    // The deck it embeds (include_str! of this file) is the key-frame chain.
    let file = decks().join("nec_morph.deck");
    let scene = raytrace::deck::initialize(
        &std::fs::read_to_string(file).unwrap(),
        "nec_morph.deck",
        decks(),
        raytrace::options::Fidelity::Thesis,
    )
    .unwrap();
    assert_eq!(scene.keyframes.len(), 1);
}

/// `raytrace -` reads the deck from standard input: the same raster as
/// from the file, errors named `<stdin>:LINE:COLUMN`, texture files
/// relative to the current folder, and the default output raster/stdin.ras.
#[test]
fn a_deck_from_standard_input() {
    use std::io::Write;
    use std::process::Stdio;
    let piped = |deck: &str, dir: &std::path::Path, args: &[&str]| {
        let mut child = raytrace_command()
            .arg("-")
            .args(args)
            .current_dir(dir)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        child.stdin.take().unwrap().write_all(deck.as_bytes()).unwrap();
        child.wait_with_output().unwrap()
    };
    let (dir, file) = small_deck();
    let from_file = raytrace_command()
        .arg("-q")
        .arg(&file)
        .args(["-o", "-"])
        .output()
        .unwrap();
    let from_stdin = piped(SMALL_DECK, dir.path(), &["-q", "-o", "-"]);
    assert!(
        from_stdin.status.success(),
        "{}",
        String::from_utf8_lossy(&from_stdin.stderr)
    );
    assert_eq!(from_stdin.stdout, from_file.stdout);

    let bad = piped(&SMALL_DECK.replace("radius 1", "radius lots"), dir.path(), &["-q"]);
    assert_eq!(bad.status.code(), Some(2));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.starts_with("raytrace: <stdin>:5:"), "{err}");

    // A texture named relative to the current folder; the default output.
    let tex = raytrace::raster::Raster {
        width: 2,
        height: 2,
        pixels: vec![[0, 255, 0]; 4],
    };
    raytrace::raster::outputframe(&dir.path().join("green.ras"), &tex).unwrap();
    let textured = format!("{SMALL_DECK}texture red green.ras\n");
    let run = piped(&textured, dir.path(), &["-q"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let r = raytrace::raster::read_raster_file(&dir.path().join("raster/stdin.ras")).unwrap();
    assert!(
        r.pixels.iter().any(|p| p[1] > 100 && p[0] < 30),
        "the green texture is on the ball"
    );
    help_says("or - to read it from standard input");
}

/// `--threads` takes 0 (one per core) to 256; more is refused at once as
/// a usage error, never a render starting thousands of threads.
#[test]
fn threads_are_bounded() {
    let (_dir, deck) = small_deck();
    let out = deck.with_extension("ras");
    let with = |n: &str| run_small(&deck, &out, &["--threads", n]);
    for n in ["10000", "257"] {
        let (code, err) = with(n);
        assert_eq!(code, Some(2), "--threads {n}");
        assert!(err.contains("--threads <N>"), "--threads {n}: {err}");
        assert!(!out.exists());
    }
    let mut rasters = Vec::new();
    for n in ["0", "1", "256"] {
        let (code, err) = with(n);
        assert_eq!(code, Some(0), "--threads {n}: {err}");
        rasters.push(std::fs::read(&out).unwrap());
    }
    assert!(
        rasters.iter().all(|r| r == &rasters[0]),
        "the same image for any number"
    );
    help_says("1..256, or 0 for one per core");
}

/// `--accel` takes auto, none, bvh or octree, each giving the same image;
/// another word is a usage error naming them, and nothing is written.
#[test]
fn accel_takes_four_words_and_gives_one_image() {
    let (_dir, deck) = small_deck();
    let out = deck.with_extension("ras");
    let with = |word: &str| run_small(&deck, &out, &["--accel", word]);
    let (code, err) = with("kdtree");
    assert_eq!(code, Some(2), "{err}");
    assert!(
        ["auto", "none", "bvh", "octree"].iter().all(|w| err.contains(w)),
        "{err}"
    );
    assert!(!out.exists());
    let mut rasters = Vec::new();
    for word in ["auto", "none", "bvh", "octree"] {
        let (code, err) = with(word);
        assert_eq!(code, Some(0), "--accel {word}: {err}");
        rasters.push(std::fs::read(&out).unwrap());
    }
    assert!(rasters.iter().all(|r| r == &rasters[0]));
}

/// The summary line (without --quiet) names the deck, what was written,
/// the size and sampling, and the rays traced: a film's are the sum of
/// its frames'.
#[test]
fn the_summary_line_counts_the_rays() {
    let (dir, deck) = small_deck();
    let film = dir.path().join("film.deck");
    std::fs::write(&film, format!("{SMALL_DECK}motion ball to 1 0 0\nfilm 2\n")).unwrap();
    let summary = |deck: &std::path::Path, args: &[&str]| {
        let run = raytrace_command()
            .arg(deck)
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        String::from_utf8(run.stderr).unwrap()
    };
    let still = summary(&deck, &["-o", "s.ras"]);
    assert!(
        still.contains("small.deck → s.ras (16×12, 1×1 subpixels, 192 rays, "),
        "{still}"
    );
    let rays = |line: &str| -> u64 {
        let before = &line[..line.find(" rays").unwrap()];
        before[before.rfind(' ').unwrap() + 1..].parse().unwrap()
    };
    let both = summary(&film, &["-o", "f.ras"]);
    assert!(
        both.contains("film.deck → f.0001.ras … f.0002.ras (frames 1..2 of 2, 16×12"),
        "{both}"
    );
    let one = summary(&film, &["-o", "f.ras", "--frames", "1"]);
    let two = summary(&film, &["-o", "f.ras", "--frames", "2"]);
    assert!(rays(&one) > 0);
    assert_eq!(rays(&both), rays(&one) + rays(&two));
}

/// A temporary folder with small.deck (SMALL_DECK) in it.
fn small_deck() -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("small.deck");
    std::fs::write(&deck, SMALL_DECK).unwrap();
    (dir, deck)
}

/// `raytrace DECK -q ARGS -o OUT`: its exit status and standard error.
fn run_small(deck: &std::path::Path, out: &std::path::Path, args: &[&str]) -> (Option<i32>, String) {
    let mut command = raytrace_command();
    command.arg(deck).arg("-q").args(args).arg("-o").arg(out);
    let run = command.output().unwrap();
    (run.status.code(), String::from_utf8_lossy(&run.stderr).into_owned())
}

/// `raytrace --help` says `words`.
fn help_says(words: &str) {
    let help = String::from_utf8(raytrace_command().arg("--help").output().unwrap().stdout).unwrap();
    assert!(help.contains(words), "{help}");
}

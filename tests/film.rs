//! The film (the port's extension, docs/film.md): the `film` record, the
//! frame times through the render loop, one raster per frame, `--frames`
//! and `--apng`, and the split-and-join path.

use std::path::{Path, PathBuf};
use std::process::Command;

use raytrace::film::{frame_path, read_sequence, FrameRange};

use raytrace::options::{Fidelity, Options};
use raytrace::raster::read_raster_file;
use raytrace::raytrace::{render, Prepared, Request};
use raytrace::scene::FilmRecord;
use raytrace::scene::Scene;

fn raytrace() -> Command {
    Command::new(env!("CARGO_BIN_EXE_raytrace"))
}

/// A small scene that moves and deforms: a sphere with a motion and a
/// key-frame pair of two translation sweeps, 24×16 with 2×2 subpixels.
const MOVING: &str = "\
view  eye 0 -10 3  look 0 0 0  screen 4  distance 5
image 24 16  mask 2
light sun 5 -5 10  1 1 1
surface red opaque color 1 0 0 ka 0.2 kd 0.8 ks 0 kt 0
surface blue opaque color 0.1 0.3 0.9 ka 0.2 kd 0.8 ks 0 kt 0
sphere ball red at -1.5 0 0 radius 0.5
motion ball to 1.5 0 0.5
sweep A blue translation bspline at -0.5 0 -1 length 0.3
  -0.4 -0.4
   0.4 -0.4
   0.4  0.4
  -0.4  0.4
end
sweep B blue translation bspline at 0.5 0 -1 length 0.3
  -0.2 -0.6
   0.6 -0.2
   0.2  0.6
  -0.6  0.2
end
keyframe A B
blur 1
";

/// The deck as `initialize` reads it.
fn scene(deck: &str, fidelity: Fidelity) -> Result<Scene, String> {
    raytrace::deck::initialize(deck, "t.deck", Path::new("."), fidelity).map_err(|e| e.to_string())
}

/// The still of `scene` rendered with `opts`.
fn render_still(scene: &Scene, opts: &Options) -> raytrace::raytrace::Render {
    render_request(&Prepared::new(scene.clone(), *opts).unwrap(), &Request::STILL)
}

/// Film frame `frame` of `scene` rendered with `opts`.
fn render_frame(scene: &Scene, opts: &Options, frame: raytrace::film::Frame) -> raytrace::raytrace::Render {
    render_request(&Prepared::new(scene.clone(), *opts).unwrap(), &Request::frame(frame))
}

fn render_request(prepared: &Prepared, request: &Request) -> raytrace::raytrace::Render {
    render(prepared, request).unwrap()
}

fn opts(fidelity: Fidelity) -> Options {
    Options {
        fidelity,
        ..Options::default()
    }
}

#[test]
fn the_film_record_reads_its_fields_and_defaults() {
    let s = scene(&format!("{MOVING}film 36\n"), Fidelity::Thesis).unwrap();
    let film = s.film.clone().unwrap();
    assert_eq!((film.frames, film.shutter, film.rate), (36, 0.5, 12));
    assert_eq!((film.pos.line, film.pos.column), (22, 1));
    let s = scene(&format!("{MOVING}FILM 10000 rate 60 shutter 1\n"), Fidelity::Thesis).unwrap();
    let film = s.film.clone().unwrap();
    assert_eq!((film.frames, film.shutter, film.rate), (10000, 1.0, 60));
    assert!(scene(MOVING, Fidelity::Thesis).unwrap().film.is_none());
}

#[test]
fn bad_film_records_are_errors_at_line_and_column() {
    for (record, at, words) in [
        ("film 0", "t.deck:22:6:", "1..10000"),
        ("film 10001", "t.deck:22:6:", "1..10000"),
        ("film 2.5", "t.deck:22:6:", "integer"),
        ("film", "t.deck:22:5:", "FRAMES"),
        ("film 12 shutter 0", "t.deck:22:17:", "(0, 1]"),
        ("film 12 shutter 1.5", "t.deck:22:17:", "(0, 1]"),
        ("film 12 shutter -0.5", "t.deck:22:17:", "(0, 1]"),
        ("film 12 rate 0", "t.deck:22:14:", "1..60"),
        ("film 12 rate 61", "t.deck:22:14:", "1..60"),
        ("film 12 rate 12 rate 12", "t.deck:22:17:", "twice"),
        ("film 12 speed 3", "t.deck:22:9:", "'shutter', 'rate'"),
        (
            "film 12\nfilm 12",
            "t.deck:23:1:",
            "second 'film' record (the first is on line 22)",
        ),
    ] {
        let err = scene(&format!("{MOVING}{record}\n"), Fidelity::Thesis).unwrap_err();
        assert!(err.starts_with(at), "{record}: {err}");
        assert!(err.contains("film"), "{record}: {err}");
        assert!(err.contains(words), "{record}: {err}");
    }
}

/// `film 1 shutter 1` is the thesis's one shutter over all of film time:
/// the same bytes as the deck without it, in both fidelities and with
/// every sampler.
#[test]
fn film_1_shutter_1_is_the_still_bit_for_bit() {
    use raytrace::options::TimeSampler;
    for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
        let still = scene(MOVING, fidelity).unwrap();
        let film = scene(&format!("{MOVING}film 1 shutter 1\n"), fidelity).unwrap();
        for sampler in [TimeSampler::Table, TimeSampler::Random, TimeSampler::Stratified] {
            let o = Options {
                sampler,
                ..opts(fidelity)
            };
            let a = render_still(&still, &o).raster;
            let f = film.film.clone().unwrap();
            let b = render_frame(&film, &o, f.frame(1)).raster;
            assert_eq!(a, b, "{fidelity:?} {sampler:?}");
        }
    }
}

/// The frames of a film are different instants: each differs from the
/// others and from the still smeared over all of film time, in both
/// fidelities (in `listing` the listing's own times, erratum 2, map the
/// same way). And frame k of F with shutter 1 over τ is the still of the
/// scene over t ∈ [(k−1)/F, k/F]: frame 1 of 1 is the still, so the
/// frames must be the still's pieces.
#[test]
fn frames_are_different_instants_in_both_fidelities() {
    for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
        let s = scene(&format!("{MOVING}film 4 shutter 0.5\n"), fidelity).unwrap();
        let film = s.film.clone().unwrap();
        let still = render_still(&s, &opts(fidelity)).raster;
        let frames: Vec<_> = (1..=4)
            .map(|k| render_frame(&s, &opts(fidelity), film.frame(k)).raster)
            .collect();
        for (i, a) in frames.iter().enumerate() {
            assert_ne!(a, &still, "{fidelity:?} frame {}", i + 1);
            for b in &frames[i + 1..] {
                assert_ne!(a, b, "{fidelity:?}");
            }
        }
    }
}

/// The hook maps every subpixel time. With one subpixel a pixel and no
/// `blur`, the thesis's table gives every subpixel τ = (0 + ½)/1 = ½; so
/// frame k of F with shutter S must show the scene still at
/// t = (k−1+S/2)/F, and the listing's table (erratum 2: the entry 7 of
/// Fig. 2.33's top-left corner, D9, times 0.1) at t = (k−1+0.7·S)/F.
/// Checked against `still_at`, which poses without the loop.
#[test]
fn the_render_loop_uses_frame_time_for_every_sample() {
    let one_instant = MOVING.replace("mask 2", "mask 1").replace("blur 1\n", "");
    for (fidelity, tau) in [(Fidelity::Thesis, 0.5), (Fidelity::Listing, 0.7)] {
        let s = scene(&format!("{one_instant}film 5 shutter 0.8\n"), fidelity).unwrap();
        let o = opts(fidelity);
        let prepared = Prepared::new(s.clone(), o).unwrap();
        for k in [1u32, 3, 5] {
            let t = (f64::from(k - 1) + 0.8 * tau) / 5.0;
            let want = render_request(&prepared.still_at(t), &Request::STILL).raster;
            let got = render_frame(&s, &o, s.film.as_ref().unwrap().frame(k)).raster;
            assert_eq!(got, want, "{fidelity:?} frame {k}");
        }
    }
}

fn write_deck(dir: &Path, body: &str) -> PathBuf {
    let deck = dir.join("walk.deck");
    std::fs::write(&deck, body).unwrap();
    deck
}

fn run_ok(cmd: &mut Command) -> String {
    let out = cmd.output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn frame_files(stem: &Path, range: std::ops::RangeInclusive<u32>, frames: u32) -> Vec<PathBuf> {
    range.map(|k| frame_path(stem, k, frames)).collect()
}

/// The split-and-join path of docs/film.md: frames 1..6 in one process
/// equal frames 1..3 and 4..6 rendered in two others with other thread
/// counts, byte for byte; the two halves joined (`tools join` is
/// `read_sequence` + `write_apng`) give the one process's `--apng` byte for
/// byte.
#[cfg(feature = "png")]
#[test]
fn frames_split_over_processes_equal_one_process_and_join_to_the_same_apng() {
    let dir = tempfile::tempdir().unwrap();
    let deck = write_deck(dir.path(), &format!("{MOVING}film 6 shutter 0.5 rate 8\n"));
    for folder in ["one", "split", "task"] {
        std::fs::create_dir(dir.path().join(folder)).unwrap();
    }
    let one = dir.path().join("one/walk.ras");
    let apng = dir.path().join("one/walk.png");
    let msg = run_ok(
        raytrace()
            .arg(&deck)
            .arg("-o")
            .arg(&one)
            .arg("--apng")
            .arg(&apng)
            .args(["--threads", "2"]),
    );
    assert!(msg.contains("frames 1..6 of 6"), "{msg}");
    let split = dir.path().join("split/walk");
    run_ok(raytrace().arg(&deck).arg("-o").arg(split.with_extension("ras")).args([
        "--frames",
        "1..3",
        "--threads",
        "1",
        "--quiet",
    ]));
    run_ok(raytrace().arg(&deck).arg("-o").arg(split.with_extension("ras")).args([
        "--frames",
        "4..6",
        "--threads",
        "3",
        "--quiet",
    ]));
    let a = frame_files(&dir.path().join("one/walk"), 1..=6, 6);
    let b = frame_files(&split, 1..=6, 6);
    for (a, b) in a.iter().zip(&b) {
        assert_eq!(std::fs::read(a).unwrap(), std::fs::read(b).unwrap(), "{}", b.display());
    }
    // Only the six frames in the split folder.
    assert_eq!(std::fs::read_dir(dir.path().join("split")).unwrap().count(), 6);
    // One frame at a time, as a Slurm array task renders it.
    let task = dir.path().join("task/walk");
    run_ok(
        raytrace()
            .arg(&deck)
            .arg("-o")
            .arg(task.with_extension("ras"))
            .args(["--frames", "5", "--quiet"]),
    );
    assert_eq!(
        std::fs::read(frame_path(&task, 5, 6)).unwrap(),
        std::fs::read(&b[4]).unwrap()
    );

    // Join.
    let joined = dir.path().join("joined.png");
    raytrace::film::write_apng(&joined, &read_sequence(&b).unwrap(), 8).unwrap();
    assert_eq!(std::fs::read(&joined).unwrap(), std::fs::read(&apng).unwrap());

    // The APNG: six frames, each 1/8 s, the rasters' pixels.
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(&apng).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let actl = reader.info().animation_control.unwrap();
    assert_eq!(actl.num_frames, 6);
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    for path in &a {
        reader.next_frame(&mut buf).unwrap();
        let fc = reader.info().frame_control.unwrap();
        assert_eq!((fc.delay_num, fc.delay_den), (1, 8));
        let r = read_raster_file(path).unwrap();
        let flat: Vec<u8> = r.pixels.iter().flatten().copied().collect();
        assert_eq!(&buf[..flat.len()], &flat[..], "{}", path.display());
    }
}

/// Without `-o` the frames are raster/<deck name>.0001.ras …, relative to
/// the working directory.
#[test]
fn without_o_frames_land_in_raster() {
    let dir = tempfile::tempdir().unwrap();
    let deck = write_deck(dir.path(), &format!("{MOVING}film 3\n"));
    run_ok(
        raytrace()
            .current_dir(dir.path())
            .arg(&deck)
            .args(["--frames", "2..3", "-q"]),
    );
    let mut names: Vec<String> = std::fs::read_dir(dir.path().join("raster"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["walk.0002.ras", "walk.0003.ras"]);
}

/// Flags that do not fit the deck: exit 2, a clear message, nothing written.
#[test]
fn bad_film_flags_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let film = write_deck(dir.path(), &format!("{MOVING}film 6\n"));
    let still = dir.path().join("still.deck");
    std::fs::write(&still, MOVING).unwrap();
    let out = dir.path().join("out/x.ras");
    let cases: Vec<(&Path, Vec<&str>, &str)> = vec![
        (
            &film,
            vec!["--frames", "0..2"],
            "frame 0 is outside the film's frames 1..6",
        ),
        (
            &film,
            vec!["--frames", "7"],
            "frame 7 is outside the film's frames 1..6",
        ),
        (&film, vec!["--frames", "5..7"], "frame 7 is outside"),
        (&film, vec!["--frames", "4..2"], "reversed"),
        (&film, vec!["--frames", "two"], "expected K or A..B"),
        (&film, vec!["--png", "x.png"], "--apng"),
        (&still, vec!["--frames", "1"], "--frames is for a film"),
        (&still, vec!["--apng", "x.png"], "--apng is for a film"),
    ];
    for (deck, flags, words) in cases {
        let run = raytrace()
            .current_dir(dir.path())
            .arg(deck)
            .arg("-o")
            .arg(&out)
            .args(&flags)
            .output()
            .unwrap();
        assert_eq!(run.status.code(), Some(2), "{flags:?}");
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(err.contains(words), "{flags:?}: {err}");
        assert!(!dir.path().join("out").exists(), "{flags:?} wrote something");
        assert!(!dir.path().join("x.png").exists(), "{flags:?} wrote x.png");
    }
    // A deck error in the film record: FILE:LINE:COL, exit 2.
    let bad = dir.path().join("bad.deck");
    std::fs::write(&bad, format!("{MOVING}film 12 shutter 0\n")).unwrap();
    let run = raytrace().arg(&bad).arg("-o").arg(&out).output().unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("bad.deck:22:17: film"));
    assert!(!dir.path().join("out").exists());
}

/// docs/film.md's `-o DIR/NAME`: a film named without an extension writes
/// DIR/NAME.0001.ras …, the bytes of `-o DIR/NAME.ras`; a device is no
/// stem for frames (exit 2), and `--apng` must name a PNG.
#[test]
fn a_film_named_without_an_extension_writes_name_0001_ras() {
    let dir = tempfile::tempdir().unwrap();
    let deck = write_deck(dir.path(), &format!("{MOVING}film 3\n"));
    for folder in ["bare", "ras"] {
        std::fs::create_dir(dir.path().join(folder)).unwrap();
        let name = if folder == "bare" { "bare/walk" } else { "ras/walk.ras" };
        run_ok(
            raytrace()
                .current_dir(dir.path())
                .arg(&deck)
                .args(["-q", "--frames", "2..3", "-o", name]),
        );
    }
    let bare = frame_files(&dir.path().join("bare/walk"), 2..=3, 3);
    let ras = frame_files(&dir.path().join("ras/walk"), 2..=3, 3);
    for (a, b) in bare.iter().zip(&ras) {
        assert_eq!(std::fs::read(a).unwrap(), std::fs::read(b).unwrap(), "{}", a.display());
    }
    assert_eq!(std::fs::read_dir(dir.path().join("bare")).unwrap().count(), 2);

    for (flags, words) in [
        (
            &["-o", "/dev/null"][..],
            "-o /dev/null: a film writes one file per frame",
        ),
        (
            &["--apng", "film.gif"],
            "--apng 'film.gif': --apng writes an animated PNG",
        ),
    ] {
        let run = raytrace()
            .current_dir(dir.path())
            .arg(&deck)
            .args(flags)
            .output()
            .unwrap();
        assert_eq!(run.status.code(), Some(2), "{flags:?}");
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(err.contains(words), "{flags:?}: {err}");
        assert!(!dir.path().join("raster").exists() && !dir.path().join("film.gif").exists());
    }
}

#[test]
fn every_frame_of_a_film_is_numbered_in_range() {
    let film = FilmRecord {
        pos: Default::default(),
        frames: 36,
        shutter: 0.5,
        rate: 12,
    };
    assert_eq!(film.all(), FrameRange { first: 1, last: 36 });
    // The shutters of consecutive frames do not overlap and stay in [0, 1].
    for k in 1..36 {
        assert!(film.frame(k).time(1.0) < film.frame(k + 1).time(0.0));
    }
    assert_eq!(film.frame(1).time(0.0), 0.0);
    assert!(film.frame(36).time(1.0) <= 1.0);
}

/// `-o DIR/NAME.png` (or `.ppm`) on a film writes a file a frame in that
/// format, `NAME.0001.png` …, each the frame's Sun raster's pixels.
#[cfg(feature = "png")]
#[test]
fn a_film_named_png_or_ppm_writes_frames_in_that_format() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let deck = write_deck(dir, &format!("{MOVING}film 3 shutter 0.5\n"));
    run_ok(raytrace().arg(&deck).arg("-o").arg(dir.join("ras")).arg("-q"));
    for ext in ["png", "ppm"] {
        std::fs::create_dir(dir.join(ext)).unwrap();
        let out = dir.join(ext).join(format!("walk.{ext}"));
        run_ok(raytrace().arg(&deck).arg("-o").arg(&out).arg("-q"));
        let mut names: Vec<String> = std::fs::read_dir(dir.join(ext))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(names, [1, 2, 3].map(|k| format!("walk.000{k}.{ext}")));
        for k in 1..=3 {
            let frame = raytrace::image_file::read_image_file(&dir.join(ext).join(&names[k - 1])).unwrap();
            let raster = read_raster_file(&frame_path(&dir.join("ras"), k as u32, 3)).unwrap();
            assert_eq!(frame, raster, "{ext} frame {k}");
        }
    }
}

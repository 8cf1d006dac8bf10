//! The run in-process (`raytrace::run`): a film's frames written and
//! resumed, a still's band, and the usage errors before anything is
//! written, without starting the program.

use std::path::{Path, PathBuf};

use raytrace::exit::Kind;
use raytrace::options::Options;
use raytrace::raster::read_raster_file;
use raytrace::raytrace::Prepared;
use raytrace::run::{DeckInput, Ended, Hooks, Outputs, Quiet, Run, Summary};
use raytrace::tile::Tile;

/// A sphere moving across a 12×8 picture, 2×2 subpixels, as a film of
/// `frames` frames.
fn deck(frames: u32) -> DeckInput {
    let text = format!(
        "view eye 0 -10 3 look 0 0 0 screen 4 distance 5\n\
         image 12 8 mask 2\n\
         light sun 5 -5 10 1 1 1\n\
         surface red opaque color 1 0 0 ka 0.2 kd 0.8 ks 0 kt 0\n\
         sphere ball red at -1.5 0 0 radius 0.5\n\
         motion ball to 1.5 0 0.5\n\
         blur 1\n{}",
        if frames > 0 {
            format!("film {frames}\n")
        } else {
            String::new()
        }
    );
    DeckInput::from_reader(text.as_bytes(), "t.deck", Path::new("."), "t").unwrap()
}

/// What the hooks were told.
#[derive(Default)]
struct Told {
    incomplete: Vec<PathBuf>,
    started: Vec<String>,
    written: Vec<u32>,
}

impl Hooks for Told {
    fn incomplete(&mut self, path: &Path, _why: &str) {
        self.incomplete.push(path.to_path_buf());
    }
    fn frame_started(&mut self, what: &str) {
        self.started.push(what.to_string());
    }
    fn frame_written(&mut self, number: u32, _path: PathBuf) {
        self.written.push(number);
    }
}

/// Runs `deck` with `outputs` on one thread; the summary and what was told.
fn run(deck: &DeckInput, outputs: &Outputs) -> (Summary, Told) {
    let (summary, told, _) = run_film(deck, outputs);
    (summary, told)
}

/// As [`run`], and the film's first and last frame the run planned.
fn run_film(deck: &DeckInput, outputs: &Outputs) -> (Summary, Told, Option<(u32, u32)>) {
    let scene = deck.initialize(Options::default().fidelity).unwrap();
    let prepared = Prepared::new(scene, Options::default()).unwrap();
    let mut told = Told::default();
    let run = Run::start(&prepared, deck, outputs, Default::default(), &mut told).unwrap();
    let (rows, film) = (run.rows_to_render(), run.film());
    let counted = std::sync::atomic::AtomicU64::new(0);
    let progress = || {
        counted.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    let Ok(Ended::Done(summary)) = run.render(&pool, &progress, &mut told) else {
        panic!("the run ends done");
    };
    assert_eq!(counted.into_inner(), rows, "progress once a row rendered");
    (summary, told, film)
}

#[test]
fn a_films_frames_are_written_then_resumed() {
    let dir = tempfile::tempdir().unwrap();
    let deck = deck(3);
    let outputs = Outputs {
        output: Some(dir.path().join("f.ras")),
        ..Outputs::default()
    };
    let (summary, told, film) = run_film(&deck, &outputs);
    assert_eq!(film, Some((1, 3)));
    assert_eq!((summary.rendered, summary.kept), (3, 0));
    assert!(summary.rays >= 3 * 12 * 8 * 4, "{} rays", summary.rays);
    assert_eq!(told.written, [1, 2, 3]);
    assert_eq!(
        told.started,
        [
            "tracing t.deck frame 1/3",
            "tracing t.deck frame 2/3",
            "tracing t.deck frame 3/3"
        ]
    );
    let frame = |k: u32| dir.path().join(format!("f.000{k}.ras"));
    let first: Vec<_> = (1..=3).map(|k| std::fs::read(frame(k)).unwrap()).collect();
    assert_ne!(first[0], first[2], "the sphere moves from frame to frame");
    assert_eq!(read_raster_file(&frame(2)).unwrap().width, 12);
    let line = summary.to_string();
    assert!(line.starts_with("t.deck → "), "{line}");
    assert!(line.contains("frames 1..3 of 3, 12×8, 2×2 subpixels"), "{line}");

    // Resumed: frame 2 cut short is rendered again, the others kept.
    std::fs::write(frame(2), &first[1][..40]).unwrap();
    let resume = Outputs {
        resume: true,
        ..outputs.clone()
    };
    let (summary, told) = run(&deck, &resume);
    assert_eq!((summary.rendered, summary.kept), (1, 2));
    assert_eq!(told.incomplete, [frame(2)]);
    assert_eq!(told.started, ["tracing t.deck frame 2/3"]);
    assert_eq!(told.written, [1, 2, 3], "a stop keeps the kept frames too");
    for k in 1..=3 {
        assert_eq!(std::fs::read(frame(k)).unwrap(), first[k as usize - 1], "frame {k}");
    }
    assert!(summary.to_string().contains(", 2 complete already (--resume) kept"));

    // All complete: nothing rendered.
    let (summary, told) = run(&deck, &resume);
    assert_eq!((summary.rendered, summary.kept, summary.rays), (0, 3, 0));
    assert!(told.started.is_empty() && told.incomplete.is_empty());
    assert!(summary
        .to_string()
        .contains("all complete already (--resume): nothing rendered"));
}

#[test]
fn a_stills_band_is_its_rows() {
    let dir = tempfile::tempdir().unwrap();
    let deck = deck(0);
    let whole = dir.path().join("whole.ras");
    run(
        &deck,
        &Outputs {
            output: Some(whole.clone()),
            ..Outputs::default()
        },
    );
    let band = dir.path().join("band.ras");
    let tile = Tile::parse("2/2").unwrap();
    let (summary, told, film) = run_film(
        &deck,
        &Outputs {
            output: Some(band.clone()),
            tile: Some(tile),
            ..Outputs::default()
        },
    );
    assert!(told.written.is_empty(), "a still is no film's frame");
    assert_eq!(film, None);
    assert_eq!(summary.band.as_ref().map(|(_, rows)| rows.clone()), Some(4..8));
    let (whole, band) = (read_raster_file(&whole).unwrap(), read_raster_file(&band).unwrap());
    assert_eq!(band.pixels, whole.pixels[4 * 12..]);
}

#[test]
fn bad_outputs_are_usage_errors_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let scene = deck(0).initialize(Options::default().fidelity).unwrap();
    let prepared = Prepared::new(scene, Options::default()).unwrap();
    let still = dir.path().join("s.ras");
    let still_and = |edit: &dyn Fn(&mut Outputs)| {
        let mut outputs = Outputs {
            output: Some(still.clone()),
            ..Outputs::default()
        };
        edit(&mut outputs);
        outputs
    };
    let dash = || Some(PathBuf::from("-"));
    for (outputs, says) in [
        (
            still_and(&|o| o.apng = Some(dir.path().join("a.png"))),
            "--apng is for a film",
        ),
        (still_and(&|o| o.png = Some(dir.path().join("p.ras"))), "--png"),
        (
            still_and(&|o| (o.output, o.debug) = (dash(), dash())),
            "only one output",
        ),
        (
            still_and(&|o| o.apng = Some(dir.path().join("a.gif"))),
            "--apng writes an animated PNG, so the name must end in .png",
        ),
        (
            still_and(&|o| (o.output, o.resume) = (Some(dir.path().join("s.png")), true)),
            "--resume",
        ),
    ] {
        let e = Run::start(&prepared, &deck(0), &outputs, Default::default(), &mut Quiet)
            .err()
            .unwrap();
        assert_eq!(e.kind, Kind::Usage, "{e}");
        assert!(e.message.contains(says), "{e}");
    }
    // A stop says `--resume` goes on only where the outputs are the Sun rasters it checks.
    let png = Outputs {
        output: Some(dir.path().join("s.png")),
        ..Outputs::default()
    };
    assert!(!png.resumable());
    assert!(Outputs {
        output: Some(still),
        ..png
    }
    .resumable());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "nothing written");
}

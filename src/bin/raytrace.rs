//! `raytrace`: renders a scene deck to a raster file, as the thesis's
//! program did (its main program is `raytrace::raytrace`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::Parser;

use raytrace::cli::exit_code;
use raytrace::cli::{FarmArgs, RenderArgs};
use raytrace::exit::Failure;
use raytrace::film::{Frame, FrameFiles, FrameRange};
use raytrace::options::{Options, TimeSampler};
use raytrace::output::{is_stream, write_atomically, OutputError, PendingFile, STDOUT};
use raytrace::raster::{read_raster_file, Format, FormatError, Raster};
use raytrace::raytrace::{Prepared, Render, Request};
use raytrace::reconstruct::Reconstruction;
use raytrace::run::DeckInput;
use raytrace::scene::{FilmRecord, Scene};
use raytrace::tile::{check_written, write_tile, Tile};

/// The scene rendered when no deck is named: legacy_pascal/decks/nec_morph.deck,
/// the thesis's own motivating example (§1.2).
const DEFAULT_DECK: &str = include_str!("../../legacy_pascal/decks/nec_morph.deck");

const AFTER_HELP: &str = "\
With no DECK, renders the embedded default deck (legacy_pascal/decks/nec_morph.deck:
'N' deforming into 'E' and then 'C' while it moves, blurred)
to raster/default.ras and raster/default.png.

The format of -o follows its extension: .ras a Sun rasterfile (24-bit
RT_STANDARD, the format the thesis sent to the PS 390 through psout; look at it
with `psout FILE`), .png a PNG, .ppm or .pnm a netpbm pixmap. `-o -` writes the
Sun raster to standard output (e.g. `raytrace DECK -o - | rasttopnm`), and so
does a device or FIFO named without an extension (-o /dev/null, -o /dev/stdout).
A film writes a file a frame: -o NAME or -o NAME.ras writes NAME.0001.ras …,
-o NAME.png (.ppm, .pnm, .exr) NAME.0001.png …. .exr is OpenEXR: the render's
linear radiance as 32-bit floats, before the clamp and rounding of the raster.
Only the default folder raster/ is created; every output is checked before
rendering. --tile K/N writes band K of N as a Sun raster of its rows (default
raster/<deck name>.K-of-N.ras); `tools join --tiles` stacks the bands into the
whole image (docs/farm.md). When the reader of standard output stops early (`-o - | head -c 10`),
the rest is dropped quietly and the status is that of the render, 0 when it
succeeded: the reader has what it wanted, as with any Unix filter.

Exit status: 0 on success; 2 for a usage error (a bad flag or output file name)
or an error in the deck or an input file (reported as FILE:LINE:COLUMN); 1 for
anything else (e.g. an output file that cannot be written, or a missing
folder); 130 or 143 when stopped by SIGINT or SIGTERM. Nothing is written when
the deck has an error, and no temporary file is left behind.";

#[derive(Parser, Clone, Debug)]
#[command(
    name = "raytrace",
    version,
    about = "Render a scene deck of TR-88-036 (motion-blurred deforming sweep objects) to a raster file",
    after_help = AFTER_HELP
)]
struct Cli {
    /// The scene deck (format: legacy_pascal/DECK.md), or - to read it from standard input
    /// (named <stdin> in errors, its texture files relative to the current folder, its
    /// default output raster/stdin.ras). Omit it for the embedded default deck.
    deck: Option<PathBuf>,

    /// The image file to write, its format by its extension (.ras, .png, .ppm, .pnm),
    /// or - for standard output [default: raster/<deck name>.ras].
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,

    /// Also write the image as PNG to FILE, a name ending in .png or - (the default deck always
    /// gets raster/default.png).
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,

    #[command(flatten)]
    render: RenderArgs,

    #[command(flatten)]
    farm: FarmArgs,

    /// No progress bar and no summary line.
    #[arg(short, long)]
    quiet: bool,

    /// Render only frames A..B (or frame K) of a deck with a `film` record; the other
    /// frames are not touched. A frame's bytes do not depend on which process renders it.
    #[arg(long, value_name = "A..B|K")]
    frames: Option<String>,

    /// With a `film` record, also write the frames rendered as one animated PNG (APNG) to
    /// FILE, a name ending in .png or -, each frame shown for 1/rate s.
    #[arg(long, value_name = "FILE")]
    apng: Option<PathBuf>,

    /// Write the listing's debug log (the Pascal `debugf`: a line per scanline, kfTIRcnt) to FILE.
    #[arg(long, value_name = "FILE")]
    debug: Option<PathBuf>,

    /// Show the picture on psout's 1024×864 screen in a window as its rows finish, and keep
    /// the window until a key is pressed (needs an X display).
    #[arg(long)]
    show: bool,

    /// Show the picture as --show does, and render again (a quick pass first) whenever the
    /// deck file changes, until q or Esc; each render writes the outputs again.
    #[arg(long)]
    watch: bool,
}

#[path = "raytrace/progress.rs"]
mod progress;
#[path = "raytrace/show.rs"]
mod show;
#[path = "raytrace/stopped.rs"]
mod stopped;

fn main() -> ExitCode {
    let cli = Cli::parse();
    exit_code("raytrace", run(&cli))
}

/// The folder the default outputs go to, created when they are used.
const DEFAULT_FOLDER: &str = "raster";

/// Reads the deck, checks and reserves every output, renders the still or
/// the film's frames (each written as soon as it is done), and prints the
/// summary; with `--show` in a window as the rows finish, with `--watch`
/// again each time the deck changes.
fn run(cli: &Cli) -> Result<(), Failure> {
    raytrace::cli::remove_temp_files_on_signals()?;
    let opts = cli.render.options.options()?;
    cli.render.reconstruction()?;
    // Usage errors of the output names come first, before the deck is read.
    let _ = check_output_names(cli)?;
    let watched = match (&cli.deck, cli.watch) {
        (Some(path), true) if path.as_os_str() != raytrace::run::STDIN => Some(path.clone()),
        (_, true) => {
            return Err(Failure::usage(
                "--watch renders a deck file again when it changes: name one (not - or the default deck)",
            ))
        }
        _ => None,
    };
    if cli.show || cli.watch {
        if let Some(reason) = raytrace::psout::display_missing() {
            return Err(show::no_display(reason));
        }
    }
    let deck = read_deck(cli)?;
    let prepared = cli.render.scene(&deck, &opts)?;
    if !(cli.show || cli.watch) {
        return render_deck(cli, &opts, &deck, &prepared, None).map(|_| ());
    }
    let mut screen = show::Screen::open(&deck.name, watched.clone())?;
    match render_deck(cli, &opts, &deck, &prepared, Some(&mut screen))? {
        Outcome::Quit if watched.is_none() => {
            return Err(Failure::other("stopped in the window: nothing more was written"))
        }
        Outcome::Quit => return Ok(()),
        Outcome::Done | Outcome::Changed => {}
    }
    let Some(path) = watched else {
        screen.hold();
        return Ok(());
    };
    loop {
        if !screen.wait_for_change() {
            return Ok(());
        }
        let again = DeckInput::read(&path).and_then(|deck| {
            let prepared = cli.render.scene(&deck, &opts)?;
            let img = &prepared.scene().image;
            screen.quick(&show::quick(&cli.render, &deck, &opts)?, (img.width, img.height));
            render_deck(cli, &opts, &deck, &prepared, Some(&mut screen))
        });
        match again {
            Ok(Outcome::Quit) => return Ok(()),
            Ok(_) => {}
            // The last picture stays, the error over it and in the title;
            // the next change is rendered again.
            Err(e) => {
                eprintln!("raytrace: {e}");
                screen.failed(&e.to_string());
            }
        }
    }
}

/// The deck the command line names, or the embedded default deck.
fn read_deck(cli: &Cli) -> Result<DeckInput, Failure> {
    match &cli.deck {
        Some(path) => DeckInput::read(path),
        None => Ok(DeckInput {
            source: DEFAULT_DECK.as_bytes().to_vec(),
            name: "nec_morph.deck".to_string(),
            dir: PathBuf::from("legacy_pascal/decks"),
            stem: "default".to_string(),
        }),
    }
}

/// How a render in the window ended.
enum Outcome {
    Done,
    /// q or Esc (or the window closed under --watch): stop.
    Quit,
    /// The watched deck changed during the render: render it again.
    Changed,
}

/// Reserves the outputs of the prepared deck, renders its still or frames
/// (in the window when `screen` is given) and writes them, and prints the
/// summary line.
fn render_deck(
    cli: &Cli,
    opts: &Options,
    deck: &DeckInput,
    prepared: &Prepared,
    mut screen: Option<&mut show::Screen>,
) -> Result<Outcome, Failure> {
    let output_format = check_output_names(cli)?;
    let scene = prepared.scene();
    let rows = cli.farm.rows(prepared)?;
    let mut job = Job::reserve(cli, scene, deck, output_format)?;

    let pool = cli.render.thread_pool()?;
    let (written, film) = job.summary();
    // Each frame with whether its file is complete already (`--resume`).
    let plan: Vec<(Frame, bool)> = job
        .frames()
        .into_iter()
        .map(|f| (f, cli.farm.resume && job.complete(f, &scene.image, cli.quiet)))
        .collect();
    let kept = plan.iter().filter(|&&(_, complete)| complete).count();
    let rendered = plan.len() - kept;
    stopped::start(stopped::Kept {
        args: std::env::args().collect(),
        resumable: resumable(cli),
        film: job.range().map(|r| (r.first, r.last)),
        done: Vec::new(),
    });
    let bar = progress::bar(cli.quiet, rows.len() as u64 * rendered as u64)?;
    let started = Instant::now();
    let mut rays = 0;
    // In frame order, so that the animated PNG has them in order.
    for &(frame, complete) in &plan {
        if complete {
            job.keep(frame)?;
            job.done(frame);
            continue;
        }
        bar.set_message(job.tracing(&deck.name, frame));
        let progress = || bar.inc(1);
        let request = Request::frame(frame)
            .rows(rows.clone())
            .reconstruction(cli.render.reconstruction()?)
            .progress(&progress);
        let result = match screen.as_deref_mut() {
            Some(s) => match s.render(prepared, &request, &pool, &job.tracing(&deck.name, frame)) {
                show::Shown::Done(r) => r,
                show::Shown::Quit => return Ok(Outcome::Quit),
                show::Shown::Changed => return Ok(Outcome::Changed),
            },
            None => pool.install(|| raytrace::raytrace::render(prepared, &request)),
        };
        let render = result
            .and_then(|r| r.check_finite().map(|()| r))
            .map_err(|e| Failure::other(format!("{}: {e}", job.what(&deck.name, frame))))?;
        rays += render.stats.rays;
        job.write(frame, render, prepared)?;
        job.done(frame);
    }
    let elapsed = started.elapsed().as_secs_f64();
    bar.finish_and_clear();
    job.finish()?;
    if !cli.quiet {
        let img = &scene.image;
        let band = cli
            .farm
            .tile
            .map(|t| format!("band {t} (rows {}..{}) of ", rows.start, rows.end))
            .unwrap_or_default();
        let kept = match (kept, rendered) {
            (0, _) => String::new(),
            (_, 0) => ", all complete already (--resume): nothing rendered".into(),
            (n, _) => format!(", {n} complete already (--resume) kept"),
        };
        eprintln!(
            "raytrace: {} → {written} ({}{band}{}×{}, {}, {rays} rays, {elapsed:.2} s{}{kept})",
            deck.name,
            film.as_ref().map(|f| format!("{f}, ")).unwrap_or_default(),
            img.width,
            img.height,
            sampling(opts, img, cli.render.reconstruction()?),
            film.filter(|_| rendered > 0)
                .map(|_| format!(", {:.2} s a frame", elapsed / rendered as f64))
                .unwrap_or_default()
        );
    }
    Ok(Outcome::Done)
}

/// What a run writes, reserved before the render: one still (its image, a
/// PNG beside it, the listing's debug log), or the frames of a film (a Sun
/// raster each, and an animated PNG of them at the end).
enum Job {
    Still {
        /// Taken when written.
        output: Option<PendingFile>,
        /// Its path, which stays when `output` is taken.
        path: PathBuf,
        format: Format,
        png: Option<PendingFile>,
        debug: Option<PendingFile>,
        tile: Option<Tile>,
    },
    Film {
        film: FilmRecord,
        range: FrameRange,
        files: FrameFiles,
        format: Format,
        apng: Option<PendingFile>,
        /// The frames, rendered or read back (`--resume`), in order, for the
        /// animated PNG.
        rasters: Vec<Raster>,
        tile: Option<Tile>,
    },
}

/// What the deck makes: a still in a format, or the frames of a film.
enum Made {
    Still(Format),
    Film(FilmRecord, FrameRange, Format),
}

/// A file that cannot be written: exit 1, named.
fn not_written(path: &Path, e: impl std::fmt::Display) -> Failure {
    Failure::other(format!("{}: {e}", path.display()))
}

impl Job {
    /// Checks the flags against the deck (film or still) and reserves every
    /// output, so a usage error (exit 2) comes first and writes nothing,
    /// and a long render never ends on a file it cannot write.
    /// `format` is the one of `-o`, or the error for a still named without
    /// an extension (a film's frames may be).
    fn reserve(cli: &Cli, scene: &Scene, deck: &DeckInput, format: Result<Format, Failure>) -> Result<Job, Failure> {
        let band = cli
            .farm
            .tile
            .map(|t| format!(".{}-of-{}", t.k, t.n))
            .unwrap_or_default();
        let output = cli
            .output
            .clone()
            .unwrap_or_else(|| Path::new(DEFAULT_FOLDER).join(format!("{}{band}.ras", deck.stem)));
        let png = cli.png.clone().or_else(|| {
            cli.deck
                .is_none()
                .then(|| Path::new(DEFAULT_FOLDER).join("default.png"))
        });
        let what = match &scene.film {
            // A film's frames named without an extension are Sun rasters.
            Some(film) => Made::Film(
                film.clone(),
                check_film(cli, film, &deck.name, &output)?,
                format.unwrap_or(Format::SunRaster),
            ),
            None => {
                if let Some(flag) = [(cli.frames.is_some(), "--frames"), (cli.apng.is_some(), "--apng")]
                    .iter()
                    .find_map(|&(given, flag)| given.then_some(flag))
                {
                    return Err(Failure::usage(format!(
                        "{flag} is for a film, and {} has no 'film' record (legacy_pascal/DECK.md, 'film')",
                        deck.name
                    )));
                }
                Made::Still(format?)
            }
        };
        if cli.output.is_none() || (cli.png.is_none() && png.is_some()) {
            std::fs::create_dir_all(DEFAULT_FOLDER).map_err(|e| not_written(Path::new(DEFAULT_FOLDER), e))?;
        }
        let reserve = |path: &Path| PendingFile::create(path).map_err(|e| not_written(path, e));
        let output = reserve(&output)?;
        Ok(match what {
            Made::Film(film, range, format) => Job::Film {
                film,
                range,
                // The frames go beside `output`, whose folder reserving it
                // has checked (it is not written itself); the APNG is
                // reserved now, so a bad name fails before the first frame.
                files: FrameFiles::of(output.path()),
                format,
                apng: cli.apng.as_deref().map(reserve).transpose()?,
                rasters: Vec::new(),
                tile: cli.farm.tile,
            },
            Made::Still(format) => Job::Still {
                path: output.path().to_path_buf(),
                output: Some(output),
                format,
                png: png.as_deref().map(reserve).transpose()?,
                debug: cli.debug.as_deref().map(reserve).transpose()?,
                tile: cli.farm.tile,
            },
        })
    }

    /// A film's frames to render.
    fn range(&self) -> Option<FrameRange> {
        match self {
            Job::Still { .. } => None,
            Job::Film { range, .. } => Some(*range),
        }
    }

    /// Tells what a signal's stop would keep: a film's `frame` is written
    /// whole.
    fn done(&self, frame: Frame) {
        if let Job::Film { .. } = self {
            stopped::frame_done(frame.number, self.file_of(frame).0);
        }
    }

    /// The frames to render, in order.
    fn frames(&self) -> Vec<Frame> {
        match self {
            Job::Still { .. } => vec![Frame::STILL],
            Job::Film { film, range, .. } => range.numbers().map(|k| film.frame(k)).collect(),
        }
    }

    /// The file `frame` is written to, and the band it holds.
    fn file_of(&self, frame: Frame) -> (PathBuf, Option<Tile>) {
        match self {
            Job::Still { path, tile, .. } => (path.clone(), *tile),
            Job::Film { film, files, tile, .. } => (files.path(frame.number, film.frames), *tile),
        }
    }

    /// Whether `frame`'s file is there and complete (`--resume`): its
    /// header and length as this run would write them. One that is there
    /// and not complete is said (unless `quiet`), and rendered again.
    fn complete(&self, frame: Frame, img: &raytrace::scene::ImageSpec, quiet: bool) -> bool {
        let (path, tile) = self.file_of(frame);
        match check_written(&path, tile, img.width, img.height) {
            Ok(()) => true,
            Err(why) => {
                if !quiet && path.exists() {
                    eprintln!("raytrace: {}: not complete ({why}): rendering it again", path.display());
                }
                false
            }
        }
    }

    /// Keeps `frame`'s complete file (`--resume`): a film's frame is read
    /// back for the animated PNG.
    fn keep(&mut self, frame: Frame) -> Result<(), Failure> {
        let (path, _) = self.file_of(frame);
        if let Job::Film {
            apng: Some(_), rasters, ..
        } = self
        {
            rasters.push(read_raster_file(&path).map_err(|e| Failure::input(format!("{}: {e}", path.display())))?);
        }
        Ok(())
    }

    /// The progress bar's message while `frame` is traced.
    fn tracing(&self, deck: &str, frame: Frame) -> String {
        match self {
            Job::Still { .. } => format!("tracing {deck}"),
            Job::Film { film, .. } => format!("tracing {deck} frame {}/{}", frame.number, film.frames),
        }
    }

    /// What an error about `frame`'s pixels names.
    fn what(&self, deck: &str, frame: Frame) -> String {
        match self {
            Job::Still { .. } => deck.to_string(),
            Job::Film { .. } => format!("{deck}: frame {}", frame.number),
        }
    }

    /// Writes what `frame`'s render makes: the still's files, or the
    /// frame's raster (atomically, at once) kept for the animated PNG.
    fn write(&mut self, frame: Frame, render: Render, prepared: &Prepared) -> Result<(), Failure> {
        match self {
            Job::Still {
                output,
                format,
                png,
                debug,
                tile,
                ..
            } => {
                let (format, height) = (*format, prepared.scene().image.height);
                commit(output, |w| write_frame(&render, format, *tile, height, w))?;
                commit(png, |w| Format::Png.write(&render.raster, w))?;
                if debug.is_some() {
                    let log = raytrace::raytrace::debug_log(prepared, &render);
                    commit(debug, |w| w.write_all(log.as_bytes()).map_err(OutputError::from))?;
                }
            }
            Job::Film {
                film,
                files,
                format,
                apng,
                rasters,
                tile,
                ..
            } => {
                let path = files.path(frame.number, film.frames);
                let height = prepared.scene().image.height;
                match (*tile, *format) {
                    // The thesis's `outputframe`, a frame's raster file.
                    (None, Format::SunRaster) => raytrace::raster::outputframe(&path, &render.raster),
                    _ => write_atomically(&path, |w| write_frame(&render, *format, *tile, height, w)),
                }
                .map_err(|e| not_written(&path, e))?;
                if apng.is_some() {
                    rasters.push(render.raster);
                }
            }
        }
        Ok(())
    }

    /// For the summary line: what is written, and for a film which frames.
    fn summary(&self) -> (String, Option<String>) {
        let and = |file: &Option<PendingFile>| {
            file.as_ref()
                .map(|f| format!(" and {}", f.path().display()))
                .unwrap_or_default()
        };
        match self {
            Job::Still { output, png, .. } => {
                let first = output.as_ref().map(|f| f.path().display().to_string());
                (format!("{}{}", first.unwrap_or_default(), and(png)), None)
            }
            Job::Film {
                film,
                range,
                files,
                apng,
                ..
            } => (
                format!(
                    "{} … {}{}",
                    files.path(range.first, film.frames).display(),
                    files.path(range.last, film.frames).display(),
                    and(apng)
                ),
                Some(format!("frames {}..{} of {}", range.first, range.last, film.frames)),
            ),
        }
    }

    /// Writes the animated PNG of a film.
    fn finish(self) -> Result<(), Failure> {
        match self {
            Job::Film {
                film,
                apng: Some(file),
                rasters,
                ..
            } => write_apng(file, &rasters, film.rate),
            _ => Ok(()),
        }
    }
}

/// Writes a frame's render (a still's, or a film's frame) in `format`, or
/// with `tile` its band as `tools join --tiles` reads it: an image of
/// `height` rows in all.
fn write_frame(
    render: &Render,
    format: Format,
    tile: Option<Tile>,
    height: usize,
    w: &mut dyn std::io::Write,
) -> Result<(), raytrace::raster::RasterError> {
    match tile {
        Some(t) => write_tile(&render.raster, t, height, w),
        None => format.write_render(&render.raster, &render.colours, w),
    }
}

/// Writes a reserved file through `write`; an error names the file.
fn commit<E: From<OutputError> + std::fmt::Display>(
    file: &mut Option<PendingFile>,
    write: impl FnOnce(&mut dyn std::io::Write) -> Result<(), E>,
) -> Result<(), Failure> {
    match file.take() {
        Some(f) => {
            let path = f.path().to_path_buf();
            f.commit(write).map_err(|e| not_written(&path, e))
        }
        None => Ok(()),
    }
}

#[cfg(feature = "png")]
fn write_apng(file: PendingFile, rasters: &[Raster], rate: u32) -> Result<(), Failure> {
    let path = file.path().to_path_buf();
    let bytes = raytrace::film::encode_apng(rasters, rate).map_err(|e| not_written(&path, e))?;
    file.commit(|w| w.write_all(&bytes).map_err(OutputError::from))
        .map_err(|e| not_written(&path, e))
}

#[cfg(not(feature = "png"))]
fn write_apng(_file: PendingFile, _rasters: &[Raster], _rate: u32) -> Result<(), Failure> {
    Ok(())
}

/// The flags of a film checked against its `film` record before any output
/// is reserved: the frames to render.
fn check_film(cli: &Cli, film: &FilmRecord, file_name: &str, output: &Path) -> Result<FrameRange, Failure> {
    let range = match &cli.frames {
        Some(text) => FrameRange::parse(text, film.frames).map_err(Failure::usage)?,
        None => film.all(),
    };
    let known = output.extension().is_none() || Format::of(output).is_ok();
    if output.as_os_str() == STDOUT || is_stream(output) || !known {
        return Err(Failure::usage(format!(
            "-o {}: a film writes one file per frame, STEM.0001.ras …; name them with -o STEM.ras \
             (or STEM.png, .ppm, .pnm, .exr)",
            output.display()
        )));
    }
    for (given, flag, instead) in [
        (
            cli.png.is_some(),
            "--png",
            "--apng FILE for an animated PNG of the frames",
        ),
        (
            cli.debug.is_some(),
            "--debug",
            "a deck without 'film' for the listing's log of one frame",
        ),
    ] {
        if given {
            return Err(Failure::usage(format!(
                "{flag} writes one still, and {file_name} is a film: use {instead}"
            )));
        }
    }
    #[cfg(not(feature = "png"))]
    if cli.apng.is_some() {
        return Err(Failure::usage(
            "--apng: this build has no PNG export (the `png` feature is off)",
        ));
    }
    Ok(range)
}

/// Checks the output file names before anything is read or written
/// (usage errors, exit 2): a name with an extension that names no format,
/// a `--png` or `--apng` not ending in `.png`, more than one output to
/// standard output. (An empty name is refused by the flag parser, also
/// with exit 2.) Gives the format of `-o`, or the error for a name without
/// an extension, raised once the deck is read and found to be a still (a
/// film's frames may be named so).
fn check_output_names(cli: &Cli) -> Result<Result<Format, Failure>, Failure> {
    let usage = |flag: &str, path: &Path, e: &dyn std::fmt::Display| {
        Failure::usage(format!("{flag} '{}': {e}", path.display()))
    };
    let stdout = [&cli.output, &cli.png, &cli.debug, &cli.apng]
        .iter()
        .filter(|p| p.as_deref().is_some_and(|p| p.as_os_str() == STDOUT))
        .count();
    if stdout > 1 {
        return Err(Failure::usage("only one output can go to standard output (-)"));
    }
    check_farm_names(cli)?;
    if let Some(png) = cli.png.as_deref().filter(|p| p.as_os_str() != STDOUT) {
        match Format::of(png) {
            Ok(Format::Png) => {}
            Ok(_) | Err(FormatError::UnknownFormat(_)) => {
                return Err(usage(
                    "--png",
                    png,
                    &"--png writes a PNG, so the name must end in .png (-o writes .ras, .ppm or .pnm)",
                ));
            }
            Err(e) => return Err(usage("--png", png, &e)),
        }
    }
    if let Some(apng) = cli.apng.as_deref().filter(|p| p.as_os_str() != STDOUT) {
        if !apng.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
            return Err(usage(
                "--apng",
                apng,
                &"--apng writes an animated PNG, so the name must end in .png",
            ));
        }
    }
    Ok(match cli.output.as_deref() {
        None => Ok(Format::SunRaster),
        Some(out) => match Format::of_output(out) {
            Err(e @ FormatError::UnknownFormat(None)) => Err(usage("-o", out, &e)),
            Err(e) => return Err(usage("-o", out, &e)),
            Ok(format) => Ok(format),
        },
    })
}

/// Checks the outputs of `--tile` and `--resume` (usage errors): each
/// writes or checks Sun raster files, so neither goes with standard
/// output, a device, another format, or the files of one whole still
/// (`--png`, `--debug`); a band has no `--apng` of whole frames.
fn check_farm_names(cli: &Cli) -> Result<(), Failure> {
    let farm = &cli.farm;
    let flag = match (farm.tile, farm.resume) {
        (Some(t), _) => format!("--tile {t}"),
        (None, true) => "--resume".into(),
        (None, false) => return Ok(()),
    };
    let what = match farm.tile {
        Some(_) => "writes a band as a Sun raster file that `tools join --tiles` reads",
        None => "checks Sun raster files that are there",
    };
    if let Some(out) = &cli.output {
        let other = out.extension().is_some_and(|e| !e.eq_ignore_ascii_case("ras"));
        if out.as_os_str() == STDOUT || is_stream(out) || other {
            return Err(Failure::usage(format!(
                "-o {}: {flag} {what}: name it with -o NAME.ras",
                out.display()
            )));
        }
    }
    let whole = [
        (cli.png.is_some(), "--png"),
        (cli.debug.is_some(), "--debug"),
        (cli.apng.is_some() && farm.tile.is_some(), "--apng"),
    ];
    if let Some((_, other)) = whole.iter().find(|(given, _)| *given) {
        return Err(Failure::usage(format!(
            "{other} with {flag}: {other} writes the whole picture, and {flag} {what}; \
             join the bands or frames first (tools join, docs/farm.md)"
        )));
    }
    Ok(())
}

/// Whether `--resume` could go on from a run of these flags: its outputs
/// are the Sun rasters it checks ([`check_farm_names`] with it).
fn resumable(cli: &Cli) -> bool {
    let mut with_resume = cli.clone();
    with_resume.farm.resume = true;
    check_farm_names(&with_resume).is_ok()
}

/// The summary line's words for the rays a pixel: M×M subpixels, or the
/// adaptive sampler's average; and how the pixels were made, when not by
/// `antialias`'s box.
fn sampling(opts: &Options, img: &raytrace::scene::ImageSpec, reconstruction: Reconstruction) -> String {
    let rays = match opts.sampler {
        TimeSampler::Adaptive => format!("{} rays a pixel on average, adaptive", img.masksize * img.masksize),
        _ => format!("{}×{} subpixels", img.masksize, img.masksize),
    };
    match reconstruction {
        Reconstruction::Box => rays,
        Reconstruction::Denoise => format!("{rays}, denoised"),
        Reconstruction::Coherence(n) => format!("{rays} in the pixels coherence {n} traced"),
    }
}

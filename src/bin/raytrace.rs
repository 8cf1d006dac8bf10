//! `raytrace`: renders a scene deck to a raster file, as the thesis's
//! program did (its main program is `raytrace::raytrace`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use raytrace::output::{Format, OutputError, PendingFile, STDOUT};
use raytrace::types::{Fidelity, Options, Solver, TimeSampler};

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
Sun raster to standard output (e.g. `raytrace DECK -o - | rasttopnm`). Only the
default folder raster/ is created; every output is checked before rendering.

Exit status: 0 on success; 2 for a usage error (a bad flag or output file name)
or an error in the deck or an input file (reported as FILE:LINE:COLUMN); 1 for
anything else (e.g. an output file that cannot be written, or a missing
folder); 130 or 143 when stopped by SIGINT or SIGTERM. Nothing is written when
the deck has an error, and no temporary file is left behind.";

#[derive(Parser, Debug)]
#[command(
    name = "raytrace",
    version,
    about = "Render a scene deck of TR-88-036 (motion-blurred deforming sweep objects) to a raster file",
    after_help = AFTER_HELP
)]
struct Cli {
    /// The scene deck (format: legacy_pascal/DECK.md). Omit it for the embedded default deck.
    deck: Option<PathBuf>,

    /// The image file to write, its format by its extension (.ras, .png, .ppm, .pnm),
    /// or - for standard output [default: raster/<deck name>.ras].
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,

    /// Also write the image as PNG to FILE, a name ending in .png or - (the default deck always
    /// gets raster/default.png).
    #[arg(long, value_name = "FILE")]
    png: Option<PathBuf>,

    /// Follow the printed listings quirks included (listing) or the thesis text (thesis);
    /// legacy_pascal/DEVIATIONS.md lists every difference.
    #[arg(long, value_enum, default_value_t = FidelityArg::Thesis)]
    fidelity: FidelityArg,

    /// Root solver for sweep objects: the thesis's laguerre, or a robust one that finds every root.
    #[arg(long, value_enum, default_value_t = SolverArg::Laguerre)]
    solver: SolverArg,

    /// How each subpixel's time is chosen: the thesis's pattern table with its CLT jitter
    /// (table), an independent uniform time (random), or one time in each stratum of the
    /// shutter in a per-pixel order (stratified). adaptive spends the same M² rays a pixel
    /// on average where each pixel needs them (places and times in pixel and shutter from a
    /// scrambled Sobol sequence). Only table is the thesis's.
    #[arg(long, value_enum, default_value_t = SamplerArg::Table)]
    sampler: SamplerArg,

    /// M×M subpixels a pixel (M² rays a pixel on average for --sampler adaptive), 1..32,
    /// in place of the deck's `mask` for this run [default: the deck's].
    #[arg(long, value_name = "M", value_parser = clap::value_parser!(u16).range(1..=MAX_MASK))]
    mask: Option<u16>,

    /// The image's width and height in pixels, WxH (each 1..8192), in place of the deck's
    /// `image` record for this run; the view stays, so the picture is the same at another size.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(usize, usize)>,

    /// Worker threads [default: one per core]; the image is the same for any number.
    #[arg(long, value_name = "N")]
    threads: Option<usize>,

    /// No progress bar and no summary line.
    #[arg(short, long)]
    quiet: bool,

    /// Render only frames A..B (or frame K) of a deck with a `film` record; the other
    /// frames are not touched. A frame's bytes do not depend on which process renders it.
    #[arg(long, value_name = "A..B|K")]
    frames: Option<String>,

    /// With a `film` record, also write the frames rendered as one animated PNG (APNG) to
    /// FILE, each shown for 1/rate s.
    #[arg(long, value_name = "FILE")]
    apng: Option<PathBuf>,

    /// Write the listing's debug log (the Pascal `debugf`: a line per scanline, kfTIRcnt) to FILE.
    #[arg(long, value_name = "FILE")]
    debug: Option<PathBuf>,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum FidelityArg {
    Listing,
    Thesis,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum SamplerArg {
    Table,
    Random,
    Stratified,
    Adaptive,
}

/// The largest `--mask`: 32×32 = 1024 rays a pixel, the chart's reference.
const MAX_MASK: i64 = 32;

/// The largest side `--size` takes, the deck's `image` limit.
const MAX_SIDE: usize = 8192;

/// `--size WxH`: two whole numbers in 1..=[`MAX_SIDE`].
fn parse_size(text: &str) -> Result<(usize, usize), String> {
    let (w, h) = text
        .split_once(['x', 'X', '×'])
        .ok_or_else(|| format!("'{text}' is not WxH (e.g. 256x256)"))?;
    let side = |v: &str, what: &str| match v.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_SIDE).contains(&n) => Ok(n),
        _ => Err(format!("the {what} '{v}' is not a whole number in 1..={MAX_SIDE}")),
    };
    Ok((side(w, "width")?, side(h, "height")?))
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum SolverArg {
    Laguerre,
    Robust,
}

/// An error and the exit status it ends with.
struct Failure {
    code: u8,
    message: String,
}

/// A usage error (exit 2, as clap's own), or an input error: a deck or file
/// that cannot be used.
fn input_error(message: impl ToString) -> Failure {
    Failure {
        code: 2,
        message: message.to_string(),
    }
}

fn other_error(message: impl ToString) -> Failure {
    Failure {
        code: 1,
        message: message.to_string(),
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Err(e) = raytrace::output::remove_temp_files_on_signals() {
        eprintln!("raytrace: cannot watch for SIGINT and SIGTERM: {e}");
        return ExitCode::from(1);
    }
    match run(&cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("raytrace: {}", f.message);
            ExitCode::from(f.code)
        }
    }
}

fn run(cli: &Cli) -> Result<(), Failure> {
    let opts = Options {
        fidelity: match cli.fidelity {
            FidelityArg::Listing => Fidelity::Listing,
            FidelityArg::Thesis => Fidelity::Thesis,
        },
        solver: match cli.solver {
            SolverArg::Laguerre => Solver::Laguerre,
            SolverArg::Robust => Solver::Robust,
        },
        sampler: match cli.sampler {
            SamplerArg::Table => TimeSampler::Table,
            SamplerArg::Random => TimeSampler::Random,
            SamplerArg::Stratified => TimeSampler::Stratified,
            SamplerArg::Adaptive => TimeSampler::Adaptive,
        },
    };
    raytrace::adaptive::check(&opts).map_err(input_error)?;

    let output_format = check_output_names(cli)?;

    // The deck: text, the name its errors carry, the folder its files are relative to.
    let (source, file_name, deck_dir, stem) = match &cli.deck {
        Some(path) => {
            let source =
                raytrace::deck::read_deck_file(path).map_err(|e| input_error(format!("{}: {e}", path.display())))?;
            let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
            let stem = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or("out".into());
            (source, path.display().to_string(), dir, stem)
        }
        None => (
            DEFAULT_DECK.as_bytes().to_vec(),
            "nec_morph.deck".to_string(),
            PathBuf::from("legacy_pascal/decks"),
            "default".to_string(),
        ),
    };
    let output = cli
        .output
        .clone()
        .unwrap_or_else(|| Path::new(DEFAULT_FOLDER).join(format!("{stem}.ras")));
    let png = cli.png.clone().or_else(|| {
        cli.deck
            .is_none()
            .then(|| Path::new(DEFAULT_FOLDER).join("default.png"))
    });

    let mut scene = raytrace::deck::initialize(&source, &file_name, &deck_dir, opts.fidelity).map_err(input_error)?;
    if cli.mask.is_some() || cli.size.is_some() {
        let (w, h) = cli.size.unwrap_or((scene.image.width, scene.image.height));
        let m = cli.mask.map_or(scene.image.masksize, usize::from);
        scene.resize(w, h, m);
    }
    raytrace::raytrace::prepare(&mut scene, &opts).map_err(|e| input_error(format!("{file_name}:{e}")))?;

    // Every output is checked and reserved before the render, so a long
    // render never ends on a file it cannot write.
    let film_range = match scene.film {
        Some(film) => Some(check_film(cli, film, &file_name, &output)?),
        None => {
            if let Some(flag) = [(cli.frames.is_some(), "--frames"), (cli.apng.is_some(), "--apng")]
                .iter()
                .find_map(|&(given, flag)| given.then_some(flag))
            {
                return Err(input_error(format!(
                    "{flag} is for a film, and {file_name} has no 'film' record (legacy_pascal/DECK.md, 'film')"
                )));
            }
            None
        }
    };
    if cli.output.is_none() || (cli.png.is_none() && png.is_some()) {
        std::fs::create_dir_all(DEFAULT_FOLDER).map_err(|e| other_error(format!("{DEFAULT_FOLDER}: {e}")))?;
    }
    let reserve = |path: &Path| PendingFile::create(path).map_err(|e| other_error(format!("{}: {e}", path.display())));
    let raster_file = reserve(&output)?;
    let png_file = png.as_deref().map(reserve).transpose()?;
    let debug_file = cli.debug.as_deref().map(reserve).transpose()?;

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cli.threads.unwrap_or(0))
        .build()
        .map_err(other_error)?;
    if let (Some(film), Some(range)) = (scene.film, film_range) {
        return run_film(cli, &scene, &opts, &pool, (film, range), &file_name, &output);
    }
    let bar = progress_bar(cli.quiet, scene.image.height as u64)?;
    bar.set_message(format!("tracing {file_name}"));
    let started = Instant::now();
    let render = pool.install(|| raytrace::raytrace::render(&scene, &opts, &|| bar.inc(1)));
    let elapsed = started.elapsed();
    bar.finish_and_clear();
    render
        .check_finite()
        .map_err(|e| other_error(format!("{file_name}: {e}")))?;

    raster_file
        .commit(|w| output_format.write(&render.raster, w))
        .map_err(|e| other_error(format!("{}: {e}", output.display())))?;
    if let (Some(file), Some(path)) = (png_file, &png) {
        file.commit(|w| Format::Png.write(&render.raster, w))
            .map_err(|e| other_error(format!("{}: {e}", path.display())))?;
    }
    if let (Some(file), Some(path)) = (debug_file, &cli.debug) {
        let log = raytrace::raytrace::debug_log(&scene, &render, opts.fidelity);
        file.commit(|w| w.write_all(log.as_bytes()).map_err(OutputError::from))
            .map_err(|e| other_error(format!("{}: {e}", path.display())))?;
    }
    if !cli.quiet {
        let img = &scene.image;
        eprintln!(
            "raytrace: {} → {}{} ({}×{}, {}, {} rays, {:.2} s)",
            file_name,
            output.display(),
            png.as_ref()
                .map(|p| format!(" and {}", p.display()))
                .unwrap_or_default(),
            img.width,
            img.height,
            sampling(&opts, img),
            render.stats.rays,
            elapsed.as_secs_f64()
        );
    }
    Ok(())
}

/// The folder the default outputs go to, created when they are used.
const DEFAULT_FOLDER: &str = "raster";
/// The progress bar over `rows` rows of pixels (hidden with `--quiet`).
fn progress_bar(quiet: bool, rows: u64) -> Result<ProgressBar, Failure> {
    if quiet {
        return Ok(ProgressBar::hidden());
    }
    let bar = ProgressBar::with_draw_target(Some(rows), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} rows, {elapsed} (eta {eta})")
            .map_err(other_error)?
            .progress_chars("=> "),
    );
    Ok(bar)
}

/// The flags of a film checked against its `film` record before any output
/// is reserved, so a usage error (exit 2) comes first and writes nothing:
/// the frames to render.
fn check_film(
    cli: &Cli,
    film: raytrace::film::FilmRecord,
    file_name: &str,
    output: &Path,
) -> Result<raytrace::film::FrameRange, Failure> {
    use raytrace::film::FrameRange;
    let range = match &cli.frames {
        Some(text) => FrameRange::parse(text, film.frames).map_err(input_error)?,
        None => film.all(),
    };
    if output.as_os_str() == STDOUT || output.extension().is_some_and(|e| !e.eq_ignore_ascii_case("ras")) {
        return Err(input_error(format!(
            "-o {}: a film writes one Sun raster per frame, STEM.0001.ras …; name them with -o STEM.ras",
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
            return Err(input_error(format!(
                "{flag} writes one still, and {file_name} is a film: use {instead}"
            )));
        }
    }
    #[cfg(not(feature = "png"))]
    if cli.apng.is_some() {
        return Err(input_error(
            "--apng: this build has no PNG export (the `png` feature is off)",
        ));
    }
    Ok(range)
}

/// Renders the frames of a deck with a `film` record: one raster per
/// frame, `STEM.0001.ras` …, each written (atomically) as soon as it is
/// done, and with `--apng` one animated PNG of them at the end. Every flag
/// is checked before the first frame, so a bad one writes nothing.
fn run_film(
    cli: &Cli,
    scene: &raytrace::types::Scene,
    opts: &Options,
    pool: &rayon::ThreadPool,
    (film, range): (raytrace::film::FilmRecord, raytrace::film::FrameRange),
    file_name: &str,
    output: &Path,
) -> Result<(), Failure> {
    use raytrace::film::{frame_path, frame_stem};
    let stem = frame_stem(output);
    // The frames go beside `output`, whose folder `run` has checked; the
    // APNG is reserved now, so a bad name fails before the first frame.
    let apng_file = cli
        .apng
        .as_deref()
        .map(|p| PendingFile::create(p).map_err(|e| other_error(format!("{}: {e}", p.display()))))
        .transpose()?;

    // One bar over every frame's rows; its message names the frame.
    let bar = progress_bar(cli.quiet, scene.image.height as u64 * u64::from(range.len()))?;
    let started = Instant::now();
    let mut rays = 0;
    let mut rasters = Vec::new();
    for k in range.numbers() {
        bar.set_message(format!("tracing {file_name} frame {k}/{}", film.frames));
        let render = pool.install(|| raytrace::raytrace::render_frame(scene, opts, film.frame(k), &|| bar.inc(1)));
        render
            .check_finite()
            .map_err(|e| other_error(format!("{file_name}: frame {k}: {e}")))?;
        let path = frame_path(&stem, k, film.frames);
        raytrace::raster::outputframe(&path, &render.raster)
            .map_err(|e| other_error(format!("{}: {e}", path.display())))?;
        rays += render.stats.rays;
        if cli.apng.is_some() {
            rasters.push(render.raster);
        }
    }
    let elapsed = started.elapsed();
    bar.finish_and_clear();
    #[cfg(feature = "png")]
    if let (Some(file), Some(apng)) = (apng_file, &cli.apng) {
        let bytes = raytrace::film::encode_apng(&rasters, film.rate)
            .map_err(|e| other_error(format!("{}: {e}", apng.display())))?;
        file.commit(|w| w.write_all(&bytes).map_err(OutputError::from))
            .map_err(|e| other_error(format!("{}: {e}", apng.display())))?;
    }
    #[cfg(not(feature = "png"))]
    drop(apng_file);
    if !cli.quiet {
        let img = &scene.image;
        eprintln!(
            "raytrace: {} → {} … {}{} (frames {}..{} of {}, {}×{}, {}, {} rays, {:.2} s, {:.2} s a frame)",
            file_name,
            frame_path(&stem, range.first, film.frames).display(),
            frame_path(&stem, range.last, film.frames).display(),
            cli.apng
                .as_ref()
                .map(|p| format!(" and {}", p.display()))
                .unwrap_or_default(),
            range.first,
            range.last,
            film.frames,
            img.width,
            img.height,
            sampling(opts, img),
            rays,
            elapsed.as_secs_f64(),
            elapsed.as_secs_f64() / f64::from(range.len())
        );
    }
    Ok(())
}

/// Checks the output file names before anything is read or written, and
/// gives the format of `-o`: a usage error (exit 2) when a name has an
/// extension that names no format or (`--png`) is not a `.png`, or when
/// more than one output goes to standard output. (An empty name is
/// refused by the flag parser, also with exit 2.)
fn check_output_names(cli: &Cli) -> Result<Format, Failure> {
    let usage =
        |flag: &str, path: &Path, e: &dyn std::fmt::Display| input_error(format!("{flag} '{}': {e}", path.display()));
    let stdout = [&cli.output, &cli.png, &cli.debug]
        .iter()
        .filter(|p| p.as_deref().is_some_and(|p| p.as_os_str() == STDOUT))
        .count();
    if stdout > 1 {
        return Err(input_error("only one output can go to standard output (-)"));
    }
    if let Some(png) = cli.png.as_deref().filter(|p| p.as_os_str() != STDOUT) {
        match Format::of(png) {
            Ok(Format::Png) => {}
            Ok(_) | Err(OutputError::UnknownFormat(_)) => {
                return Err(usage(
                    "--png",
                    png,
                    &"--png writes a PNG, so the name must end in .png (-o writes .ras, .ppm or .pnm)",
                ));
            }
            Err(e) => return Err(usage("--png", png, &e)),
        }
    }
    match cli.output.as_deref() {
        None => Ok(Format::SunRaster),
        Some(out) if out.as_os_str() == STDOUT => Ok(Format::SunRaster),
        Some(out) => Format::of(out).map_err(|e| usage("-o", out, &e)),
    }
}

/// The summary line's words for the rays a pixel: M×M subpixels, or the
/// adaptive sampler's average.
fn sampling(opts: &Options, img: &raytrace::types::ImageSpec) -> String {
    match opts.sampler {
        TimeSampler::Adaptive => format!("{} rays a pixel on average, adaptive", img.masksize * img.masksize),
        _ => format!("{}×{} subpixels", img.masksize, img.masksize),
    }
}

//! `raytrace`: renders a scene deck to a raster file, as the thesis's
//! program did (its main program is `raytrace::raytrace`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use raytrace::types::{Fidelity, Options, Solver, TimeSampler};

/// The scene rendered when no deck is named: legacy_pascal/decks/nec_morph.deck,
/// the thesis's own motivating example (§1.2).
const DEFAULT_DECK: &str = include_str!("../../legacy_pascal/decks/nec_morph.deck");

const AFTER_HELP: &str = "\
With no DECK, renders the embedded default deck (legacy_pascal/decks/nec_morph.deck:
'N' deforming into 'E' and then 'C' while it moves, blurred)
to raster/default.ras and raster/default.png.

The raster file is a Sun rasterfile (24-bit RT_STANDARD), the format the thesis
sent to the PS 390 through psout; look at it with `psout FILE`.

Exit status: 0 on success, 2 for an error in the deck or an input file
(reported as FILE:LINE:COLUMN), 1 for anything else (e.g. an output file that
cannot be written). Nothing is written when the deck has an error.";

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

    /// The raster file to write [default: raster/<deck name>.ras].
    #[arg(short, long, value_name = "FILE")]
    output: Option<PathBuf>,

    /// Also write the image as PNG to FILE (the default deck always gets raster/default.png).
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

    // The deck: text, the name its errors carry, the folder its files are relative to.
    let (source, file_name, deck_dir, stem) = match &cli.deck {
        Some(path) => {
            let source = std::fs::read_to_string(path).map_err(|e| input_error(format!("{}: {e}", path.display())))?;
            let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
            let stem = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or("out".into());
            (source, path.display().to_string(), dir, stem)
        }
        None => (
            DEFAULT_DECK.to_string(),
            "nec_morph.deck".to_string(),
            PathBuf::from("legacy_pascal/decks"),
            "default".to_string(),
        ),
    };
    let output = cli
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("raster/{stem}.ras")));
    let png = cli
        .png
        .clone()
        .or_else(|| cli.deck.is_none().then(|| PathBuf::from("raster/default.png")));

    let mut scene = raytrace::deck::initialize(&source, &file_name, &deck_dir, opts.fidelity).map_err(input_error)?;
    if cli.mask.is_some() || cli.size.is_some() {
        let (w, h) = cli.size.unwrap_or((scene.image.width, scene.image.height));
        let m = cli.mask.map_or(scene.image.masksize, usize::from);
        scene.resize(w, h, m);
    }
    raytrace::raytrace::prepare(&mut scene, &opts).map_err(|e| input_error(format!("{file_name}:{e}")))?;

    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(cli.threads.unwrap_or(0))
        .build()
        .map_err(other_error)?;
    if let Some(film) = scene.film {
        return run_film(cli, &scene, &opts, &pool, film, &file_name, &output);
    }
    if let Some(flag) = [(cli.frames.is_some(), "--frames"), (cli.apng.is_some(), "--apng")]
        .iter()
        .find_map(|&(given, flag)| given.then_some(flag))
    {
        return Err(input_error(format!(
            "{flag} is for a film, and {file_name} has no 'film' record (legacy_pascal/DECK.md, 'film')"
        )));
    }
    let bar = progress_bar(cli.quiet, scene.image.height as u64)?;
    bar.set_message(format!("tracing {file_name}"));
    let started = Instant::now();
    let render = pool.install(|| raytrace::raytrace::render(&scene, &opts, &|| bar.inc(1)));
    let elapsed = started.elapsed();
    bar.finish_and_clear();

    make_folders(std::iter::once(&output).chain(png.iter()).chain(cli.debug.iter()))?;
    raytrace::raster::outputframe(&output, &render.raster)
        .map_err(|e| other_error(format!("{}: {e}", output.display())))?;
    if let Some(png) = &png {
        write_png(png, &render.raster)?;
    }
    if let Some(debug) = &cli.debug {
        std::fs::write(debug, raytrace::raytrace::debug_log(&scene, &render))
            .map_err(|e| other_error(format!("{}: {e}", debug.display())))?;
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

/// Creates the folders the output files go in.
fn make_folders<'a>(paths: impl Iterator<Item = &'a PathBuf>) -> Result<(), Failure> {
    for path in paths {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| other_error(format!("{}: {e}", dir.display())))?;
        }
    }
    Ok(())
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
    film: raytrace::film::FilmRecord,
    file_name: &str,
    output: &Path,
) -> Result<(), Failure> {
    use raytrace::film::{frame_path, frame_stem, FrameRange};
    let range = match &cli.frames {
        Some(text) => FrameRange::parse(text, film.frames).map_err(input_error)?,
        None => film.all(),
    };
    if output.extension().is_some_and(|e| !e.eq_ignore_ascii_case("ras")) {
        return Err(input_error(format!(
            "-o {}: a film writes one Sun raster per frame, STEM.0001.ras …; name them with -o STEM.ras or -o STEM",
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
    let stem = frame_stem(output);
    make_folders(std::iter::once(&stem.with_extension("ras")).chain(cli.apng.iter()))?;

    // One bar over every frame's rows; its message names the frame.
    let bar = progress_bar(cli.quiet, scene.image.height as u64 * u64::from(range.len()))?;
    let started = Instant::now();
    let mut rays = 0;
    let mut rasters = Vec::new();
    for k in range.numbers() {
        bar.set_message(format!("tracing {file_name} frame {k}/{}", film.frames));
        let render = pool.install(|| raytrace::raytrace::render_frame(scene, opts, film.frame(k), &|| bar.inc(1)));
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
    if let Some(apng) = &cli.apng {
        raytrace::film::write_apng(apng, &rasters, film.rate)
            .map_err(|e| other_error(format!("{}: {e}", apng.display())))?;
    }
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

#[cfg(feature = "png")]
fn write_png(path: &Path, raster: &raytrace::raster::Raster) -> Result<(), Failure> {
    raytrace::raster::write_png(path, raster).map_err(|e| other_error(format!("{}: {e}", path.display())))
}

#[cfg(not(feature = "png"))]
fn write_png(path: &Path, _raster: &raytrace::raster::Raster) -> Result<(), Failure> {
    Err(input_error(format!(
        "{}: this build has no PNG export (the `png` feature is off)",
        path.display()
    )))
}

/// The summary line's words for the rays a pixel: M×M subpixels, or the
/// adaptive sampler's average.
fn sampling(opts: &Options, img: &raytrace::types::ImageSpec) -> String {
    match opts.sampler {
        TimeSampler::Adaptive => format!("{} rays a pixel on average, adaptive", img.masksize * img.masksize),
        _ => format!("{}×{} subpixels", img.masksize, img.masksize),
    }
}

//! The command line's words for a render, defined once for every program
//! that renders (`raytrace`, the tools, the binaries to come): the choices
//! of [`Options`] (`--fidelity`, `--solver`, `--sampler`, the library's own
//! enums), the image's size and the threads (`--mask`, `--size`,
//! `--threads`), how pixels are made from samples (`--denoise`,
//! `--coherence`), a task of a farm (`--tile`, `--resume`). Each flattens
//! into a program's `clap` parser; what goes wrong is a [`Failure`] whose
//! kind gives the exit status. Also what only a program does: print its
//! failure and end with its status ([`exit_code`]), and end on SIGINT and
//! SIGTERM ([`remove_temp_files_on_signals`]). The port's; behind the
//! feature `cli`, so the library alone parses no flags, prints nothing and
//! never ends the process.

use std::path::Path;
use std::process::ExitCode;
use std::sync::{Mutex, Once, PoisonError};

use clap::Args;

use crate::accel::Accel;
use crate::coherence::MAX_STEP;
use crate::exit::Failure;
use crate::options::{Fidelity, Options, Solver, TimeSampler};
use crate::raytrace::Prepared;
use crate::reconstruct::Reconstruction;
use crate::run::DeckInput;
use crate::tile::Tile;

/// `--fidelity`: the listing or the thesis.
#[derive(Args, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FidelityArg {
    /// Where the printed listings and the thesis text disagree, which to follow
    /// (legacy_pascal/DEVIATIONS.md lists every difference).
    #[arg(long, value_enum, default_value_t)]
    pub fidelity: Fidelity,
}

/// `--fidelity`, `--solver`, `--sampler`, `--accel`: the [`Options`] of a
/// render.
#[derive(Args, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OptionArgs {
    #[command(flatten)]
    pub fidelity: FidelityArg,

    /// The root solver of the sweep objects.
    #[arg(long, value_enum, default_value_t)]
    pub solver: Solver,

    /// How each subpixel's time (and with adaptive, its place) is chosen; only
    /// table is the thesis's.
    #[arg(long, value_enum, default_value_t)]
    pub sampler: TimeSampler,

    /// How the objects a ray may meet are found; the image is the same with each
    /// (docs/scale.md).
    #[arg(long, value_enum, default_value_t)]
    pub accel: Accel,
}

impl OptionArgs {
    /// The options, or a usage error for a pair that does not go together
    /// ([`crate::adaptive::check`]).
    pub fn options(&self) -> Result<Options, Failure> {
        let opts = Options {
            fidelity: self.fidelity.fidelity,
            solver: self.solver,
            sampler: self.sampler,
            accel: self.accel,
        };
        crate::adaptive::check(&opts).map_err(Failure::usage)?;
        Ok(opts)
    }
}

/// The largest `--mask`: 32×32 = 1024 rays a pixel, the chart's reference.
pub const MAX_MASK: u16 = 32;

/// The largest side `--size` takes, the deck's `image` limit.
pub const MAX_SIDE: usize = 8192;

/// The most `--threads`: more than the cores of any machine the port has
/// met (rows are the work shared out, so threads past the cores only add
/// start-up time), and few enough that a slip such as `--threads 10000` is
/// refused at once rather than starting ten thousand threads.
pub const MAX_THREADS: u16 = 256;

/// The flags of a render: its [`Options`], the image's size and mask in
/// place of the deck's, and the worker threads.
#[derive(Args, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RenderArgs {
    #[command(flatten)]
    pub options: OptionArgs,

    /// M×M subpixels a pixel (M² rays a pixel on average for --sampler adaptive), 1..32,
    /// in place of the deck's `mask` for this run [default: the deck's].
    #[arg(long, value_name = "M", value_parser = parse_mask)]
    pub mask: Option<u16>,

    /// The image's width and height in pixels, WxH (each 1..8192), in place of the deck's
    /// `image` record for this run; the view stays, so the picture is the same at another size.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(usize, usize)>,

    /// Worker threads, 1..256, or 0 for one per core [default: one per core]. The image
    /// is the same for any number; rows are shared out, so more threads than cores only
    /// cost start-up time, and more than 256 is refused as a slip.
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub threads: Option<u16>,

    /// Make each pixel from its own and its neighbours' samples, weighted by how alike their
    /// colours, surface colours and normals are: a smooth picture from few rays (e.g.
    /// --sampler adaptive --mask 2). Not the thesis's (docs/reconstruction.md).
    #[arg(long, conflicts_with = "coherence")]
    pub denoise: bool,

    /// The thesis's coherence (§2.1.2): trace every N-th pixel in each direction (N in
    /// 1..64) and interpolate the rest, tracing a pixel after all where its traced neighbours
    /// disagree. Fast on plain scenes, wrong on busy ones (docs/reconstruction.md). Not with
    /// --sampler adaptive.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_STEP)))]
    pub coherence: Option<u32>,
}

/// `--size WxH`: two whole numbers in 1..=[`MAX_SIDE`]. Every program
/// that takes a size reads it with this.
pub fn parse_size(text: &str) -> Result<(usize, usize), String> {
    let (w, h) = text
        .split_once(['x', 'X', '×'])
        .ok_or_else(|| format!("'{text}' is not WxH (e.g. 256x256)"))?;
    let side = |v: &str, what: &str| match v.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_SIDE).contains(&n) => Ok(n),
        _ => Err(format!("the {what} '{v}' is not a whole number in 1..={MAX_SIDE}")),
    };
    Ok((side(w, "width")?, side(h, "height")?))
}

/// A whole number in `range`, or the message every flag of the kind gives.
fn whole_in(text: &str, range: std::ops::RangeInclusive<u16>) -> Result<u16, String> {
    match text.trim().parse::<u16>() {
        Ok(n) if range.contains(&n) => Ok(n),
        _ => Err(format!(
            "'{text}' is not a whole number in {}..={}",
            range.start(),
            range.end()
        )),
    }
}

/// `--mask M`: M×M subpixels a pixel, M in 1..=[`MAX_MASK`]; outside it
/// refused, never clamped. Every program that takes a mask reads it with
/// this.
pub fn parse_mask(text: &str) -> Result<u16, String> {
    whole_in(text, 1..=MAX_MASK)
}

/// `--threads N`: N in 0..=[`MAX_THREADS`], 0 for one per core; outside
/// it refused. Every program that takes threads reads them with this.
pub fn parse_threads(text: &str) -> Result<u16, String> {
    whole_in(text, 0..=MAX_THREADS)
}

/// The pool of `threads` workers, 0 for one per core.
pub fn thread_pool(threads: u16) -> Result<rayon::ThreadPool, Failure> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(usize::from(threads))
        .build()
        .map_err(Failure::other)
}

/// `--screenshot OUT.png` (psout, contour): a usage error (exit 2) unless
/// `out` is standard output (`-`) or names a PNG; the format follows the
/// extension, as for `raytrace -o`.
pub fn check_screenshot_name(out: &Path) -> Result<(), Failure> {
    use crate::output::STDOUT;
    use crate::raster::{Format, FormatError};
    let problem = match Format::of(out) {
        _ if out.as_os_str() == STDOUT => return Ok(()),
        Ok(Format::Png) => return Ok(()),
        Ok(_) | Err(FormatError::UnknownFormat(_)) => "a screenshot is a PNG, so the name must end in .png".to_string(),
        Err(e) => e.to_string(),
    };
    Err(Failure::usage(format!("--screenshot '{}': {problem}", out.display())))
}

/// Writes `screen` as a PNG to `--screenshot`'s `out` (a file, or `-` for
/// standard output) for `program`.
pub fn write_screenshot(program: &str, out: &Path, screen: &crate::psout::Framebuffer) -> Result<(), Failure> {
    #[cfg(feature = "png")]
    {
        let _ = program;
        crate::raster::write_png(out, &screen.to_raster())
            .map_err(|e| Failure::other(format!("cannot write {}: {e}", out.display())))
    }
    #[cfg(not(feature = "png"))]
    {
        let _ = (out, screen);
        Err(Failure::other(format!(
            "this {program} was built without the `png` feature, so --screenshot is not available"
        )))
    }
}

impl RenderArgs {
    /// The scene of `deck` as these flags render it: read with their
    /// fidelity, resized by `--size` and `--mask`, and prepared. Its
    /// errors are input errors (exit 2), each naming its FILE:LINE:COLUMN.
    pub fn scene(&self, deck: &DeckInput, opts: &Options) -> Result<Prepared, Failure> {
        let mut scene = deck.initialize(opts.fidelity)?;
        if self.mask.is_some() || self.size.is_some() {
            let (w, h) = self.size.unwrap_or((scene.image.width, scene.image.height));
            let m = self.mask.map_or(scene.image.masksize, usize::from);
            scene.resize(w, h, m);
        }
        Prepared::new(scene, *opts).map_err(Failure::input)
    }

    /// How the pixels are made from their samples (`--denoise`,
    /// `--coherence N`, or `antialias`'s box), or a usage error for
    /// coherence with the adaptive sampler.
    pub fn reconstruction(&self) -> Result<Reconstruction, Failure> {
        Ok(match (self.denoise, self.coherence) {
            (_, Some(n)) if self.options.sampler == TimeSampler::Adaptive => {
                return Err(Failure::usage(format!(
                    "--coherence {n} traces some pixels whole and interpolates the rest, and --sampler \
                     adaptive deals its rays over every pixel by need: use one or the other"
                )))
            }
            (_, Some(n)) => Reconstruction::Coherence(n),
            (true, None) => Reconstruction::Denoise,
            (false, None) => Reconstruction::Box,
        })
    }

    /// The pool of `--threads` workers (one per core without it, or with 0).
    pub fn thread_pool(&self) -> Result<rayon::ThreadPool, Failure> {
        thread_pool(self.threads.unwrap_or(0))
    }
}

/// `--tile K/N`, `--resume`: what a task of a farm renders of a deck
/// (docs/farm.md). The port's extension.
#[derive(Args, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FarmArgs {
    /// Render band K of N of the image's rows (whole rows, split as evenly as they allow; N at
    /// most the rows) and write it as a Sun raster of those rows for `tools join --tiles`;
    /// the bands joined are the whole image byte for byte. Not with --sampler adaptive.
    #[arg(long, value_name = "K/N", value_parser = Tile::parse)]
    pub tile: Option<Tile>,

    /// Skip each output (a film's frame, the still or its tile) that is already there and
    /// complete (its header and length checked, not just present), and render again one that
    /// is not, so a task run again renders only what is missing.
    #[arg(long)]
    pub resume: bool,
}

/// The end of a program's `main`: success, or the failure's message
/// printed to stderr as `PROGRAM: MESSAGE` and its kind's status
/// ([`crate::exit`]).
pub fn exit_code(program: &str, result: Result<(), Failure>) -> ExitCode {
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("{program}: {}", f.message);
            ExitCode::from(f.kind.status())
        }
    }
}

/// What the program does last when a signal stops it, after the temporary
/// files are removed and before it exits: [`on_signal`].
type LastWord = Box<dyn Fn(i32) + Send>;

static LAST_WORD: Mutex<Option<LastWord>> = Mutex::new(None);

/// Sets what the program does last when SIGINT or SIGTERM stops it (after
/// [`remove_temp_files_on_signals`] has removed the temporary files, before
/// the exit): `raytrace` says what was kept and the command that goes on.
/// The call gets the signal. A later call replaces an earlier one.
pub fn on_signal(last_word: impl Fn(i32) + Send + 'static) {
    *LAST_WORD.lock().unwrap_or_else(PoisonError::into_inner) = Some(Box::new(last_word));
}

/// Makes SIGINT and SIGTERM remove this process's temporary files
/// ([`crate::output::remove_temp_files`]), say the program's last word
/// ([`on_signal`]) and exit with 128 + the signal (130, 143). For the
/// programs' `main`; a second call does nothing.
///
/// The signals are taken by `signal-hook`'s iterator on a thread of its
/// own, so the removal runs as ordinary code, not inside a signal handler.
pub fn remove_temp_files_on_signals() -> Result<(), Failure> {
    static INSTALLED: Once = Once::new();
    let mut result = Ok(());
    INSTALLED.call_once(|| {
        result = (|| {
            use signal_hook::consts::{SIGINT, SIGTERM};
            let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])?;
            std::thread::Builder::new()
                .name("output-signals".into())
                .spawn(move || {
                    if let Some(signal) = signals.forever().next() {
                        // Held until exit: no temporary file is made or
                        // renamed after this.
                        let _removed = crate::output::remove_temp_files();
                        if let Some(last_word) = LAST_WORD.lock().unwrap_or_else(PoisonError::into_inner).as_ref() {
                            last_word(signal);
                        }
                        std::process::exit(i32::from(crate::exit::Kind::Signal(signal).status()));
                    }
                })?;
            Ok(())
        })();
    });
    result.map_err(|e: std::io::Error| Failure::other(format!("cannot watch for SIGINT and SIGTERM: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use std::path::PathBuf;

    #[derive(Parser, Debug)]
    struct Cli {
        #[command(flatten)]
        render: RenderArgs,
    }

    fn parse(args: &[&str]) -> Result<RenderArgs, clap::Error> {
        Cli::try_parse_from(std::iter::once("t").chain(args.iter().copied())).map(|c| c.render)
    }

    #[test]
    fn no_flags_are_the_defaults() {
        let args = parse(&[]).unwrap();
        assert_eq!(args, RenderArgs::default());
        assert_eq!(args.options.options().unwrap(), Options::default());
    }

    #[test]
    fn the_library_enums_are_the_values() {
        let args = parse(&["--fidelity", "listing", "--solver", "robust", "--sampler", "stratified"]).unwrap();
        let opts = args.options.options().unwrap();
        assert_eq!(
            (opts.fidelity, opts.solver, opts.sampler),
            (Fidelity::Listing, Solver::Robust, TimeSampler::Stratified)
        );
        let sobol = parse(&["--sampler", "sobol"]).unwrap().options.options().unwrap();
        assert_eq!(sobol.sampler, TimeSampler::Sobol);
        assert!(parse(&["--sampler", "halton"]).is_err());
        let octree = parse(&["--accel", "octree"]).unwrap().options.options().unwrap();
        assert_eq!(octree.accel, Accel::Octree);
        assert_eq!(parse(&[]).unwrap().options.options().unwrap().accel, Accel::Auto);
    }

    #[test]
    fn adaptive_with_the_listing_is_a_usage_error() {
        let args = parse(&["--fidelity", "listing", "--sampler", "adaptive"]).unwrap();
        let e = args.options.options().unwrap_err();
        assert_eq!(e.kind, crate::exit::Kind::Usage);
        assert!(e.message.contains("--sampler adaptive"), "{e}");
    }

    /// `--denoise` and `--coherence N` (1..=64) make the reconstruction;
    /// both together, either twice, a step out of range, or coherence
    /// with the adaptive sampler are usage errors.
    #[test]
    fn the_reconstruction_flags() {
        let r = |args: &[&str]| parse(args).unwrap().reconstruction().unwrap();
        assert_eq!(r(&[]), Reconstruction::Box);
        assert_eq!(r(&["--denoise"]), Reconstruction::Denoise);
        assert_eq!(r(&["--coherence", "1"]), Reconstruction::Coherence(1));
        assert_eq!(r(&["--coherence", "64"]), Reconstruction::Coherence(64));
        assert_eq!(r(&["--denoise", "--sampler", "adaptive"]), Reconstruction::Denoise);
        for bad in [
            &["--coherence", "0"][..],
            &["--coherence", "65"],
            &["--coherence", "x"],
            &["--denoise", "--denoise"],
            &["--coherence", "2", "--coherence", "3"],
            &["--denoise", "--coherence", "2"],
        ] {
            let e = parse(bad).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{bad:?}");
        }
        let e = parse(&["--coherence", "4", "--sampler", "adaptive"])
            .unwrap()
            .reconstruction()
            .unwrap_err();
        assert_eq!(e.kind, crate::exit::Kind::Usage);
        assert!(e.message.contains("--coherence 4"), "{e}");
    }

    #[test]
    fn threads_are_bounded_and_zero_is_one_per_core() {
        assert_eq!(parse(&["--threads", "256"]).unwrap().threads, Some(256));
        assert_eq!(parse(&["--threads", "0"]).unwrap().threads, Some(0));
        assert!(parse(&["--threads", "257"]).is_err());
        assert!(parse(&["--threads", "10000"]).is_err());
        let cores = rayon::ThreadPoolBuilder::new().build().unwrap().current_num_threads();
        let pool = parse(&["--threads", "0"]).unwrap().thread_pool().unwrap();
        assert_eq!(pool.current_num_threads(), cores);
        let pool = parse(&["--threads", "3"]).unwrap().thread_pool().unwrap();
        assert_eq!(pool.current_num_threads(), 3);
    }

    #[test]
    fn mask_and_size_are_checked() {
        let args = parse(&["--mask", "32", "--size", "64x48"]).unwrap();
        assert_eq!((args.mask, args.size), (Some(32), Some((64, 48))));
        for bad in [
            ["--mask", "0"],
            ["--mask", "33"],
            ["--size", "64"],
            ["--size", "0x4"],
            ["--size", "4x8193"],
        ] {
            assert!(parse(&bad).is_err(), "{bad:?}");
        }
        assert_eq!(parse_size("8192×1"), Ok((8192, 1)));
        assert_eq!(parse_size("2X3"), Ok((2, 3)));
    }

    /// A deck whose `pattern` (2×2) does not fit its mask (1): the error
    /// `prepare` raises names the file from the record's position, with
    /// no prefix added by the caller.
    #[test]
    fn a_render_error_names_file_line_and_column() {
        let deck = DeckInput {
            source: b"view eye 0 -10 3 look 0 0 0 screen 4 distance 5\nimage 4 4 mask 1\npattern 2\n 0 3\n 2 1\nend\n"
                .to_vec(),
            name: "dir/t.deck".into(),
            dir: PathBuf::from("dir"),
            stem: "t".into(),
        };
        let args = parse(&[]).unwrap();
        let e = args.scene(&deck, &Options::default()).unwrap_err();
        assert_eq!(e.kind, crate::exit::Kind::Input);
        assert!(
            e.message
                .starts_with("dir/t.deck:3:1: pattern: the pattern table is 2×2"),
            "{e}"
        );
        // --mask 2 makes it fit.
        let args = parse(&["--mask", "2"]).unwrap();
        assert!(args.scene(&deck, &Options::default()).is_ok());
    }
}

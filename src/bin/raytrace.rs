//! `raytrace`: renders a scene deck to a raster file, as the thesis's
//! program did (its main program is `raytrace::raytrace`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;

use raytrace::cli::{exit_code, FarmArgs, RenderArgs};
use raytrace::exit::Failure;
use raytrace::raytrace::{Prepared, Request};
use raytrace::run::{DeckInput, Ended, Hooks, Outputs, Rendered, Run};

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

/// Reads the deck, checks and reserves every output, renders the still or
/// the film's frames (each written as soon as it is done), and prints the
/// summary; with `--show` in a window as the rows finish, with `--watch`
/// again each time the deck changes.
fn run(cli: &Cli) -> Result<(), Failure> {
    raytrace::cli::remove_temp_files_on_signals()?;
    let opts = cli.render.options.options()?;
    cli.render.reconstruction()?;
    // Usage errors of the output names come first, before the deck is read.
    let _ = outputs(cli).check_names()?;
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
        return render_deck(cli, &deck, &prepared, None).map(|_| ());
    }
    let mut screen = show::Screen::open(&deck.name, watched.clone())?;
    match render_deck(cli, &deck, &prepared, Some(&mut screen))? {
        Ended::Quit if watched.is_none() => {
            return Err(Failure::other("stopped in the window: nothing more was written"))
        }
        Ended::Quit => return Ok(()),
        Ended::Done(_) | Ended::Changed => {}
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
            render_deck(cli, &deck, &prepared, Some(&mut screen))
        });
        match again {
            Ok(Ended::Quit) => return Ok(()),
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

/// What the program adds to a run: the progress bar's message, the
/// account a stop prints, the window, and what `--quiet` keeps quiet.
struct Program<'a> {
    /// The bar, once the rows to render are known.
    bar: Option<&'a indicatif::ProgressBar>,
    quiet: bool,
    screen: Option<&'a mut show::Screen>,
}

impl Hooks for Program<'_> {
    fn incomplete(&mut self, path: &Path, why: &str) {
        if !self.quiet {
            eprintln!("raytrace: {}: not complete ({why}): rendering it again", path.display());
        }
    }

    fn frame_started(&mut self, what: &str) {
        if let Some(bar) = self.bar {
            bar.set_message(what.to_string());
        }
    }

    fn frame_written(&mut self, number: u32, path: PathBuf) {
        stopped::frame_done(number, path);
    }

    fn render(&mut self, prepared: &Prepared, request: &Request, pool: &rayon::ThreadPool, what: &str) -> Rendered {
        match self.screen.as_deref_mut() {
            Some(s) => s.render(prepared, request, pool, what),
            None => Rendered::Done(pool.install(|| raytrace::raytrace::render(prepared, request))),
        }
    }
}

/// The outputs the flags name.
fn outputs(cli: &Cli) -> Outputs {
    Outputs {
        output: cli.output.clone(),
        png: cli.png.clone(),
        default_png: cli.deck.is_none(),
        apng: cli.apng.clone(),
        debug: cli.debug.clone(),
        frames: cli.frames.clone(),
        tile: cli.farm.tile,
        resume: cli.farm.resume,
    }
}

/// Reserves the outputs of the prepared deck, renders its still or frames
/// (in the window when `screen` is given) and writes them, and prints the
/// summary line.
fn render_deck(
    cli: &Cli,
    deck: &DeckInput,
    prepared: &Prepared,
    screen: Option<&mut show::Screen>,
) -> Result<Ended, Failure> {
    let outputs = outputs(cli);
    let mut hooks = Program {
        bar: None,
        quiet: cli.quiet,
        screen,
    };
    let run = Run::start(prepared, deck, &outputs, cli.render.reconstruction()?, &mut hooks)?;
    let pool = cli.render.thread_pool()?;
    stopped::start(stopped::Kept {
        args: std::env::args().collect(),
        resumable: outputs.resumable(),
        film: run.film(),
        done: Vec::new(),
    });
    let bar = progress::bar(cli.quiet, run.rows_to_render())?;
    hooks.bar = Some(&bar);
    let ended = run.render(&pool, &|| bar.inc(1), &mut hooks)?;
    bar.finish_and_clear();
    if let (Ended::Done(summary), false) = (&ended, cli.quiet) {
        eprintln!("raytrace: {summary}");
    }
    Ok(ended)
}

//! `contour DECK NAME`: the contour editor (the port's extension; the
//! thesis's interactive input of §3.2.1). Opens the sweep NAME of a deck in
//! a window on the PS 390's 1024×864 screen: the (U, V) plane with the
//! control points and the curve, beside the object rendered with the
//! deck's view, lights and surfaces; the mouse and keys edit, `s` saves the
//! record back into the deck. Without a window: `--script EDITS -o
//! NEW.deck` applies edits, `--screenshot OUT.png` writes the screen.
//! Everything but the window is `raytrace::editor`; docs/editor.md.
//!
//! Exit codes: 0 done; 1 no window could be opened, or an output could
//! not be written; 2 a bad command line, a deck with an error, a NAME
//! that is no sweep, a script with an error or a contour refused by the
//! save; 130 or 143 stopped by SIGINT or SIGTERM.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;
use raytrace::cli::exit_code;
use raytrace::cli::FidelityArg;
use raytrace::editor::document::Document;
use raytrace::editor::screen;
use raytrace::editor::session::{Editor, KEYS_HELP};
use raytrace::exit::Failure;
use raytrace::output::{write_atomically, OutputError};
use raytrace::psout;
use raytrace::run::DeckInput;

/// Edit a sweep of a scene deck: its control points, curve and sweep kind,
/// seen at once as the curve and as the rendered object.
#[derive(Parser, Debug)]
#[command(name = "contour", version, after_help = KEYS_HELP)]
struct Args {
    /// The scene deck (format: legacy_pascal/DECK.md); with --new, the new deck to write.
    #[arg(value_name = "DECK")]
    deck: PathBuf,

    /// The sweep to edit (a `sweep` record's name, or a key shape's).
    #[arg(value_name = "NAME", required_unless_present = "new")]
    name: Option<String>,

    /// Begin a new deck DECK (it must not exist) with one sweep, `shape`, to edit; the
    /// save writes DECK.
    #[arg(long, conflicts_with = "name")]
    new: bool,

    /// Apply the edits of EDITS, one a line (move K DU DV, insert K U V, delete K,
    /// curve bspline|bezier, sweep translation|conic|rotation; points from 1), or - for
    /// standard input.
    #[arg(long, value_name = "EDITS")]
    script: Option<PathBuf>,

    /// Write the deck with the edited sweep to NEW.deck (DECK itself to save in place),
    /// without a window; a contour the save refuses writes nothing (exit 2).
    #[arg(short, long, value_name = "NEW.deck")]
    output: Option<PathBuf>,

    /// Write the editor's 1024×864 screen (with the finer preview) to OUT.png (or - for
    /// standard output) and exit, without a window.
    #[arg(long, value_name = "OUT.png")]
    screenshot: Option<PathBuf>,

    /// Print the control points, one a line: number, U, V, and the column and row of
    /// the point on the screen (after a line `# … (S pixels a unit)`); then exit, without
    /// a window.
    #[arg(long)]
    list: bool,

    /// A key shape of a key-frame chain: where the time slider starts, 0..1 [default: the
    /// key shape's own time].
    #[arg(long, value_name = "T", value_parser = parse_time)]
    time: Option<f64>,

    #[command(flatten)]
    fidelity: FidelityArg,
}

/// `--time T`: a number in 0..1.
fn parse_time(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(t) if (0.0..=1.0).contains(&t) => Ok(t),
        _ => Err(format!("'{text}' is not a time in 0..1")),
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    exit_code("contour", run(&args))
}

fn run(args: &Args) -> Result<(), Failure> {
    raytrace::cli::remove_temp_files_on_signals()?;
    let headless = args.output.is_some() || args.screenshot.is_some() || args.list;
    if args.script.is_some() && !headless {
        return Err(Failure::usage(
            "--script makes edits without a window: name what to write with -o NEW.deck or --screenshot OUT.png",
        ));
    }
    if let Some(out) = &args.screenshot {
        raytrace::cli::check_screenshot_name(out)?;
    }
    let mut editor = Editor::new(open(args)?);
    if editor.chain.is_some() {
        editor.time = args.time.unwrap_or(editor.time);
    }
    if let Some(path) = &args.script {
        let (text, file) = read_script(path)?;
        editor.run_script(&text, &file).map_err(Failure::input)?;
    }
    if !headless {
        return window(editor, &args.deck);
    }
    if let Some(out) = &args.output {
        let bytes = editor
            .doc
            .save(&editor.contour)
            .map_err(|r| Failure::input(format!("{}: not saved: {r}", out.display())))?;
        write_atomically(out, |w| w.write_all(&bytes).map_err(OutputError::from))
            .map_err(|e| Failure::other(format!("{}: {e}", out.display())))?;
    }
    if args.list {
        list(&editor)?;
    }
    if let Some(out) = &args.screenshot {
        let screen = screen::screenshot(&editor);
        raytrace::cli::write_screenshot("contour", out, &screen)?;
    }
    Ok(())
}

/// `--list`: the points on standard output; a reader that stops early
/// (`| head`) ends the list quietly, as with any Unix filter.
fn list(editor: &Editor) -> Result<(), Failure> {
    use std::io::Write;
    let mut text = format!("# K\tU\tV\tX\tY ({} pixels a unit)\n", editor.plane.scale);
    for (k, p) in editor.contour.points.iter().enumerate() {
        let (x, y) = editor.plane.to_screen([p.u, p.v]);
        text.push_str(&format!("{}\t{}\t{}\t{}\t{}\n", k + 1, p.u, p.v, x.round(), y.round()));
    }
    match std::io::stdout().lock().write_all(text.as_bytes()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(Failure::other(format!("standard output: {e}"))),
        _ => Ok(()),
    }
}

/// The document the command line names: DECK at NAME, or a new deck.
fn open(args: &Args) -> Result<Document, Failure> {
    let fidelity = args.fidelity.fidelity;
    if args.new {
        if args.deck.exists() {
            return Err(Failure::usage(format!(
                "--new {}: the file exists; open a sweep of it with `contour {} NAME`",
                args.deck.display(),
                args.deck.display()
            )));
        }
        return Document::new_deck(&args.deck, fidelity);
    }
    let deck = DeckInput::read(&args.deck)?;
    Document::open(deck, args.name.as_deref().unwrap_or_default(), fidelity)
}

/// The script's text and the name its errors give, read to its limit
/// (`raytrace::editor::script::read`); an error is an input error (exit 2).
fn read_script(path: &Path) -> Result<(String, String), Failure> {
    let read = |reader: &mut dyn std::io::Read, file: String| {
        raytrace::editor::script::read(reader, &file)
            .map(|text| (text, file))
            .map_err(Failure::input)
    };
    if path.as_os_str() == "-" {
        return read(&mut std::io::stdin().lock(), "<stdin>".to_string());
    }
    let file = path.display().to_string();
    let mut f = std::fs::File::open(path).map_err(|e| Failure::input(format!("{file}: {e}")))?;
    read(&mut f, file)
}

/// The error when no window can be opened.
fn no_display(reason: &str) -> Failure {
    Failure::other(psout::no_display_message(
        "contour",
        reason,
        "edit without a window: `contour DECK NAME --script EDITS -o NEW.deck`, `--screenshot OUT.png`",
    ))
}

#[cfg(not(feature = "window"))]
fn window(_editor: Editor, _deck: &Path) -> Result<(), Failure> {
    Err(no_display(psout::display_missing().unwrap_or("no window feature")))
}

#[cfg(feature = "window")]
#[path = "contour/window.rs"]
mod window;

#[cfg(feature = "window")]
fn window(editor: Editor, deck: &Path) -> Result<(), Failure> {
    if let Some(reason) = psout::display_missing() {
        return Err(no_display(reason));
    }
    window::run(editor, deck).map_err(|e| match e {
        window::Error::Open(reason) => no_display(&reason),
        window::Error::Failed(reason) => Failure::other(format!("the window failed: {reason}")),
    })
}

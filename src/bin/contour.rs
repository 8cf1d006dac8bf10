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

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;
use raytrace::cli::{DeckInput, FidelityArg};
use raytrace::editor::document::Document;
use raytrace::editor::script;
use raytrace::exit::{exit_code, Failure};

/// Edit a sweep of a scene deck: its control points, curve and sweep kind,
/// seen at once as the curve and as the rendered object.
#[derive(Parser, Debug)]
#[command(name = "contour", version)]
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

    #[command(flatten)]
    fidelity: FidelityArg,
}

fn main() -> ExitCode {
    let args = Args::parse();
    exit_code("contour", run(&args))
}

fn run(args: &Args) -> Result<(), Failure> {
    raytrace::output::remove_temp_files_on_signals()
        .map_err(|e| Failure::other(format!("cannot watch for SIGINT and SIGTERM: {e}")))?;
    if args.script.is_some() && args.output.is_none() {
        return Err(Failure::usage(
            "--script makes edits without a window: name what to write with -o NEW.deck",
        ));
    }
    let doc = open(args)?;
    let mut contour = doc.original.clone();
    if let Some(path) = &args.script {
        let (text, file) = read_script(path)?;
        let edits = script::parse(&text, &file).map_err(Failure::input)?;
        script::apply(&mut contour, &edits, &file).map_err(Failure::input)?;
    }
    match &args.output {
        Some(out) => {
            let bytes = doc
                .save(&contour)
                .map_err(|r| Failure::input(format!("{}: not saved: {r}", out.display())))?;
            raytrace::output::write_atomically(out, |w| {
                w.write_all(&bytes).map_err(raytrace::output::OutputError::from)
            })
            .map_err(|e| Failure::other(format!("{}: {e}", out.display())))
        }
        None => Err(Failure::other("the window is not built yet")),
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

/// The script's text and the name its errors give.
fn read_script(path: &Path) -> Result<(String, String), Failure> {
    let mut text = String::new();
    let file = if path.as_os_str() == "-" {
        std::io::stdin()
            .read_to_string(&mut text)
            .map_err(|e| Failure::input(format!("<stdin>: {e}")))?;
        "<stdin>".to_string()
    } else {
        text = std::fs::read_to_string(path).map_err(|e| Failure::input(format!("{}: {e}", path.display())))?;
        path.display().to_string()
    };
    Ok((text, file))
}

// A program that embeds the renderer (`cargo run --release --example render
// -- DECK OUT.png`): reads a deck, renders it with the thesis's reading of the
// errata and Sobol sample times, writes a PNG. A deck that cannot be used is
// refused with the library's own error (FILE:LINE:COLUMN), exit 2, as raytrace.

use std::path::Path;
use std::process::ExitCode;

use raytrace::{initialize, read_deck_file, render, write_png, Fidelity, Options, Prepared, Request, TimeSampler};

/// Renders `deck` into `out`; an error is its exit status and message.
fn run(deck: &Path, out: &Path) -> Result<(), (u8, String)> {
    let opts = Options {
        fidelity: Fidelity::Thesis,
        sampler: TimeSampler::Sobol,
        ..Options::default()
    };
    let text = read_deck_file(deck).map_err(|e| (2, format!("{}: {e}", deck.display())))?;
    let dir = deck.parent().unwrap_or(Path::new(""));
    let scene = initialize(&text, &deck.display().to_string(), dir, opts.fidelity).map_err(|e| (2, e.to_string()))?;
    let prepared = Prepared::new(scene, opts).map_err(|e| (2, e.to_string()))?;
    let image = render(&prepared, &Request::STILL).map_err(|e| (1, e.to_string()))?;
    image.check_finite().map_err(|e| (1, e.to_string()))?;
    write_png(out, &image.raster).map_err(|e| (1, e.to_string()))
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [deck, out] = &args[..] else {
        eprintln!("usage: render DECK OUT.png");
        return ExitCode::from(2);
    };
    match run(Path::new(deck), Path::new(out)) {
        Ok(()) => ExitCode::SUCCESS,
        Err((status, message)) => {
            eprintln!("render: {message}");
            ExitCode::from(status)
        }
    }
}

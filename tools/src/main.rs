//! Tools of the port: `texture` makes the texture raster the decks use;
//! `bench` times the renderer on a deck (medians, never asserted in tests).

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Parser, Subcommand};
use raytrace::raster::{outputframe, Raster};
use raytrace::types::{Fidelity, Options, Solver};

#[derive(Parser)]
#[command(name = "tools", about = "Tools of the TR-88-036 port")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Write the test-card texture raster the decks paste on blocks and cylinders.
    Texture {
        /// Where to write it.
        #[arg(default_value = "raster/card.tex.ras")]
        out: PathBuf,
    },
    /// Time renders of a deck: N runs, then the median, fastest and slowest.
    Bench {
        /// The deck [default: legacy_pascal/decks/default.deck].
        #[arg(default_value = "legacy_pascal/decks/default.deck")]
        deck: PathBuf,
        /// How many timed runs (after one untimed warm-up).
        #[arg(long, default_value_t = 11)]
        runs: usize,
        /// Worker threads [default: one per core].
        #[arg(long)]
        threads: Option<usize>,
        /// Use the robust root solver instead of laguerre.
        #[arg(long)]
        robust: bool,
        /// Follow the listings instead of the thesis.
        #[arg(long)]
        listing: bool,
    },
}

fn main() -> Result<(), String> {
    match Cli::parse().command {
        Command::Texture { out } => {
            let card = test_card(64, 64);
            if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
                std::fs::create_dir_all(dir).map_err(|e| e.to_string())?;
            }
            outputframe(&out, &card).map_err(|e| format!("{}: {e}", out.display()))?;
            println!("wrote {} ({}×{})", out.display(), card.width, card.height);
            Ok(())
        }
        Command::Bench { deck, runs, threads, robust, listing } => {
            let opts = Options {
                fidelity: if listing { Fidelity::Listing } else { Fidelity::Thesis },
                solver: if robust { Solver::Robust } else { Solver::Laguerre },
            };
            bench(&deck, runs.max(1), threads, &opts)
        }
    }
}

/// A 64×64 test card: eight colour bars over the top half, a grey ramp,
/// and a black frame with a white diagonal, so that a pasted picture shows
/// its orientation (which way is up, which is left) at a glance.
fn test_card(width: usize, height: usize) -> Raster {
    const BARS: [[u8; 3]; 8] = [
        [255, 255, 255],
        [255, 255, 0],
        [0, 255, 255],
        [0, 255, 0],
        [255, 0, 255],
        [255, 0, 0],
        [0, 0, 255],
        [0, 0, 0],
    ];
    let mut pixels = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let frame = x < 2 || y < 2 || x >= width - 2 || y >= height - 2;
            let diagonal = y >= height / 2 && (x as i64 - (y - height / 2) as i64 * 2).abs() <= 1;
            let px = if frame {
                [0, 0, 0]
            } else if diagonal {
                [255, 255, 255]
            } else if y < height / 2 {
                BARS[x * BARS.len() / width]
            } else {
                let g = (x * 255 / (width - 1)) as u8;
                [g, g, g / 2]
            };
            pixels.push(px);
        }
    }
    Raster { width, height, pixels }
}

fn bench(deck: &Path, runs: usize, threads: Option<usize>, opts: &Options) -> Result<(), String> {
    let source = std::fs::read_to_string(deck).map_err(|e| format!("{}: {e}", deck.display()))?;
    let dir = deck.parent().unwrap_or(Path::new("."));
    let name = deck.display().to_string();
    let mut scene = raytrace::deck::initialize(&source, &name, dir, opts.fidelity).map_err(|e| e.to_string())?;
    raytrace::raytrace::prepare(&mut scene, opts).map_err(|e| e.to_string())?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .map_err(|e| e.to_string())?;
    let warm = pool.install(|| raytrace::raytrace::render(&scene, opts, &|| {}));
    let mut secs = Vec::with_capacity(runs);
    for _ in 0..runs {
        let t = Instant::now();
        let r = pool.install(|| raytrace::raytrace::render(&scene, opts, &|| {}));
        secs.push(t.elapsed().as_secs_f64());
        if r.raster != warm.raster {
            return Err("a render differs from the warm-up: the renderer is not deterministic".into());
        }
    }
    secs.sort_by(f64::total_cmp);
    let median = secs[secs.len() / 2];
    let img = &scene.image;
    println!(
        "{name}: {}×{}, {}×{} subpixels, {} threads, {:?} {:?}: median {:.4} s, fastest {:.4} s, slowest {:.4} s over {} runs; {} rays a render, {:.0} rays/s",
        img.width,
        img.height,
        img.masksize,
        img.masksize,
        pool.current_num_threads(),
        opts.fidelity,
        opts.solver,
        median,
        secs[0],
        secs[secs.len() - 1],
        runs,
        warm.stats.rays,
        warm.stats.rays as f64 / median
    );
    Ok(())
}

//! Tools of the port: `texture` makes the texture raster the decks use;
//! `frames` draws a key-frame deck's filmstrip; `bench` times the renderer
//! on a deck; `chart` draws the speed/accuracy
//! chart; `heatmap` shows where the adaptive sampler spends its rays;
//! `stability` writes the root solvers' stability report. Timings
//! are measured and printed, never asserted in tests; `join` makes a
//! film's animated PNG from its frame rasters.

use std::path::PathBuf;

use clap::{Parser, Subcommand};
use raytrace::raster::outputframe;
use raytrace::types::{Fidelity, Options, Solver, TimeSampler};
use tools::textures::{nec_card, test_card};

#[derive(Parser)]
#[command(name = "tools", about = "Tools of the TR-88-036 port")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Write the texture rasters the decks paste on blocks and cylinders:
    /// card.tex.ras (a test card) and nec.tex.ras (the letters NEC).
    Texture {
        /// The folder to write them in.
        #[arg(default_value = "raster")]
        dir: PathBuf,
    },
    /// A filmstrip of a deck with key frames: the scene at fixed instants of the
    /// shutter (no blur), side by side in one PNG, to see the in-between shapes.
    Frames {
        /// The deck.
        deck: PathBuf,
        /// The PNG to write.
        #[arg(long, default_value = "frames.png")]
        out: PathBuf,
        /// The instants, in [0, 1].
        #[arg(long, value_delimiter = ',', default_value = "0,0.25,0.5,0.75,1")]
        times: Vec<f64>,
        /// Width and height of each frame, in pixels.
        #[arg(long, default_value_t = 160)]
        size: usize,
        /// Follow the listings instead of the thesis.
        #[arg(long)]
        listing: bool,
    },
    /// Time renders of a deck: N runs, then the median, fastest and slowest.
    Bench {
        /// The deck.
        #[arg(default_value = "legacy_pascal/decks/still_life.deck")]
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
        /// How subpixel times are chosen: table (the thesis's), random, stratified, adaptive.
        #[arg(long, default_value = "table")]
        sampler: String,
        /// Render at this mask (M×M subpixels a pixel) instead of the deck's.
        #[arg(long)]
        mask: Option<usize>,
        /// Render at this width and height instead of the deck's.
        #[arg(long, num_args = 2, value_names = ["WIDTH", "HEIGHT"])]
        size: Option<Vec<usize>>,
    },
    /// Draw the speed/accuracy chart: time samplers (error against render
    /// time) and root solvers (silhouette pixels wrong against time per ray).
    Chart {
        /// Where to write speed_accuracy.png and speed_accuracy.svg.
        #[arg(long, default_value = "docs")]
        dir: PathBuf,
        /// The width and height of every render of the chart, in pixels.
        #[arg(long, default_value_t = 96)]
        size: usize,
        /// Timed renders a point (the median is plotted).
        #[arg(long, default_value_t = 5)]
        runs: usize,
    },
    /// Where `--sampler adaptive` spends its rays: the image beside a heat map
    /// of the rays each pixel got, one PNG.
    Heatmap {
        /// The deck (a shipped deck's name, e.g. fig5_10, or a path).
        deck: PathBuf,
        /// The PNG to write.
        #[arg(long, default_value = "docs/img/adaptive_heatmap.png")]
        out: PathBuf,
        /// Width and height of the image, in pixels.
        #[arg(long, default_value_t = 256)]
        size: usize,
        /// The budget: mask² rays a pixel on average.
        #[arg(long, default_value_t = 4)]
        mask: usize,
    },
    /// Join a film's frame rasters (in the order given, e.g. raster/nec.*.ras) into one
    /// animated PNG; with --strip also a still strip of every Nth frame (docs/film.md).
    Join {
        /// The frame rasters, in order.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// The animated PNG to write.
        #[arg(long, short)]
        out: PathBuf,
        /// Frames a second (the deck's `film … rate FPS`).
        #[arg(long, default_value_t = 12, value_parser = clap::value_parser!(u32).range(1..=60))]
        rate: u32,
        /// Also write a PNG of frames 1, 1+N, 1+2N, … side by side (N from --every).
        #[arg(long)]
        strip: Option<PathBuf>,
        /// The step between the frames of --strip.
        #[arg(long, default_value_t = 6, value_parser = clap::value_parser!(u64).range(1..))]
        every: u64,
    },
    /// Write the stability report of the root solvers on hard cases.
    Stability {
        /// The report to write.
        #[arg(long, default_value = "docs/STABILITY.md")]
        out: PathBuf,
    },
}

fn main() -> Result<(), String> {
    match Cli::parse().command {
        Command::Texture { dir } => {
            std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            for (name, raster) in [("card.tex.ras", test_card(64, 64)), ("nec.tex.ras", nec_card())] {
                let out = dir.join(name);
                outputframe(&out, &raster).map_err(|e| format!("{}: {e}", out.display()))?;
                println!("wrote {} ({}×{})", out.display(), raster.width, raster.height);
            }
            Ok(())
        }
        Command::Frames {
            deck,
            out,
            times,
            size,
            listing,
        } => {
            let fidelity = if listing { Fidelity::Listing } else { Fidelity::Thesis };
            tools::frames::frames(&deck, &out, &times, size.clamp(8, 1024), fidelity)
        }
        Command::Bench {
            deck,
            runs,
            threads,
            robust,
            listing,
            sampler,
            mask,
            size,
        } => {
            let sampler = match sampler.as_str() {
                "table" => TimeSampler::Table,
                "random" => TimeSampler::Random,
                "stratified" => TimeSampler::Stratified,
                "adaptive" => TimeSampler::Adaptive,
                other => {
                    return Err(format!(
                        "--sampler {other}: expected table, random, stratified or adaptive"
                    ))
                }
            };
            let opts = Options {
                fidelity: if listing { Fidelity::Listing } else { Fidelity::Thesis },
                solver: if robust { Solver::Robust } else { Solver::Laguerre },
                sampler,
            };
            raytrace::adaptive::check(&opts)?;
            let size = size.map(|s| (s[0].clamp(1, 8192), s[1].clamp(1, 8192)));
            tools::bench::bench(&deck, runs.max(1), threads, &opts, size, mask.map(|m| m.clamp(1, 64)))
        }
        Command::Chart { dir, size, runs } => tools::chart::run(&dir, size.max(8), runs.max(1)),
        Command::Heatmap { deck, out, size, mask } => {
            tools::heatmap::run(&deck, &out, size.clamp(8, 2048), mask.clamp(1, 32))
        }
        Command::Stability { out } => tools::stability::run(&out),
        Command::Join {
            files,
            out,
            rate,
            strip,
            every,
        } => tools::join::join(&files, &out, rate, strip.as_deref().map(|s| (s, every as usize))),
    }
}

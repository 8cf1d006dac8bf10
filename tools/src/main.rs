//! Tools of the port: `texture` makes the texture raster the decks use;
//! `frames` draws a key-frame deck's filmstrip; `gallery` draws every
//! picture of the docs again from its deck; `bench` times the renderer
//! on a deck; `preview` times the contour editor's first preview; `chart` draws the speed/accuracy
//! chart; `goal` measures the adaptive sampler's goal (its
//! error and CPU time over the table's); `heatmap` shows where the
//! adaptive sampler spends its rays; `scale` times the structures over
//! the objects (`--accel`) and POV-Ray on scenes of up to 100,000 objects;
//! `stability` writes the root solvers' stability report; `pov` exports a
//! deck to POV-Ray and `vs-povray` compares the two renderers. Timings are
//! measured and printed, never asserted in tests; `join` makes a film's
//! animated PNG from its frame rasters.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use raytrace::cli::{exit_code, parse_mask, parse_size, parse_threads, FidelityArg, RenderArgs};
use raytrace::exit::Failure;
use raytrace::run::DeckInput;

#[derive(Parser)]
#[command(name = "tools", version, about = "Tools of the TR-88-036 port")]
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
        /// The PNG to write [default: raster/<deck name>_frames.png].
        #[arg(long)]
        out: Option<PathBuf>,
        /// The instants, in [0, 1].
        #[arg(long, value_delimiter = ',', default_value = "0,0.25,0.5,0.75,1")]
        times: Vec<f64>,
        /// Width and height of each frame in pixels, WxH (each 1..8192).
        #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "160x160")]
        size: (usize, usize),
        #[command(flatten)]
        fidelity: FidelityArg,
    },
    /// Draw every picture of the docs again from its deck, with the options
    /// it was made with (the table is tools/src/gallery.rs).
    Gallery {
        /// Only the pictures whose path contains one of these (e.g. fig5_8).
        only: Vec<String>,
        /// Compare with the files (and the texture rasters) in memory,
        /// writing nothing; fail naming the stale ones.
        #[arg(long)]
        check: bool,
        /// List the pictures, their decks and the commands that draw them.
        #[arg(long)]
        list: bool,
    },
    /// Time renders of a deck: N runs, then the median, fastest and slowest. The render
    /// flags are raytrace's.
    Bench {
        /// The deck (- for standard input).
        #[arg(default_value = "legacy_pascal/decks/still_life.deck")]
        deck: PathBuf,
        /// How many timed runs (after one untimed warm-up).
        #[arg(long, default_value_t = 11)]
        runs: usize,
        #[command(flatten)]
        render: RenderArgs,
    },
    /// Time the contour editor from an edit to the first preview on its screen (the quick
    /// pass, 128×128 at one ray a pixel): a point moved, then the scene prepared, rendered
    /// and drawn; N edits, the median.
    Preview {
        /// The deck.
        #[arg(default_value = "legacy_pascal/decks/fig5_8.deck")]
        deck: PathBuf,
        /// The sweep to edit.
        #[arg(default_value = "goblet")]
        name: String,
        /// The point moved (from 1).
        #[arg(long, default_value_t = 11)]
        point: usize,
        /// Timed edits (after one untimed).
        #[arg(long, default_value_t = 21)]
        runs: usize,
        /// Render threads, 1..256, or 0 for one per core (the goal is for one core).
        #[arg(long, value_name = "N", value_parser = parse_threads, default_value = "1")]
        threads: u16,
    },
    /// Draw the speed/accuracy chart: time samplers (error against render
    /// time) and root solvers (silhouette pixels wrong against time per ray).
    Chart {
        /// Where to write speed_accuracy.png and speed_accuracy.svg.
        #[arg(long, default_value = "docs")]
        dir: PathBuf,
        /// The width and height of every render of the chart in pixels, WxH (each 1..8192).
        #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "96x96")]
        size: (usize, usize),
        /// Timed renders a point (the median is plotted).
        #[arg(long, default_value_t = 5)]
        runs: usize,
        /// A folder to keep the references in between runs (as `tools goal`'s).
        #[arg(long)]
        cache: Option<PathBuf>,
    },
    /// The adaptive sampler's goal: RMSE and one-thread CPU time of `--sampler adaptive`
    /// over the thesis table's, at 16 and 64 rays a pixel, on the chart's blur decks.
    Goal {
        /// The width and height of every render in pixels, WxH (each 1..8192).
        #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "96x96")]
        size: (usize, usize),
        /// Timed rounds (the medians are compared).
        #[arg(long, default_value_t = 5)]
        runs: usize,
        /// A folder to keep the references in between runs.
        #[arg(long)]
        cache: Option<PathBuf>,
    },
    /// The reconstructions' goals: RMSE against a 1024-ray reference and one-thread CPU time
    /// of `--denoise`, `--sampler sobol` and `--coherence N` on motion scenes, each over the
    /// best 16-ray render before them (`--sampler adaptive --mask 4`).
    Frontier {
        /// The decks (shipped names, `spheres`, `ball`, or paths) [default: fig5_3, fig5_10,
        /// spheres, ball].
        decks: Vec<String>,
        /// The width and height of every render in pixels, WxH (each 1..8192).
        #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "128x128")]
        size: (usize, usize),
        /// Timed rounds (the medians are compared); 0 for the errors alone.
        #[arg(long, default_value_t = 5)]
        runs: usize,
        /// A folder to keep the references in between runs.
        #[arg(long)]
        cache: Option<PathBuf>,
    },
    /// Where `--sampler adaptive` spends its rays: the image beside a heat map
    /// of the rays each pixel got, one PNG.
    Heatmap {
        /// The deck (a shipped deck's name, e.g. fig5_10, or a path).
        deck: PathBuf,
        /// The PNG to write.
        #[arg(long, default_value = "docs/img/adaptive_heatmap.png")]
        out: PathBuf,
        /// Width and height of the image in pixels, WxH (each 1..8192).
        #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "256x256")]
        size: (usize, usize),
        /// The budget: M² rays a pixel on average, M in 1..32.
        #[arg(long, value_name = "M", value_parser = parse_mask, default_value = "4")]
        mask: u16,
    },
    /// Join a film's frame rasters (in the order given, e.g. raster/nec.*.ras) into one
    /// animated PNG; with --strip also a still strip of every Nth frame (docs/film.md).
    /// With --tiles, stack the bands of `raytrace --tile K/N` into the whole image
    /// (docs/farm.md).
    Join {
        /// The frame rasters, in order (with --tiles, the bands 1..N, in order).
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// The animated PNG to write (with --tiles, the whole image: .ras, .png, .ppm).
        #[arg(long, short)]
        out: PathBuf,
        /// The files are the bands of one still (`raytrace --tile K/N`): check that they are
        /// bands 1..N of one image, in order, none missing, and write the whole image.
        #[arg(long, conflicts_with_all = ["strip"])]
        tiles: bool,
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
    /// Export a deck's scene to POV-Ray 3.7 SDL: camera, lights, primitives,
    /// sweeps, blobs and patches ((x, y, z) becomes <x, z, y>; sweeps become
    /// prism and lathe, blobs blob, patches bicubic_patch; the objects at
    /// rest, key frames as their first shape), paints as POV-Ray patterns
    /// and textures as image maps.
    Pov {
        /// The deck (a path, or a shipped deck's name such as fig5_8).
        deck: String,
        /// The SDL file to write; each texture's picture goes beside it as
        /// NAME.SURFACE.png (run povray in that folder).
        #[arg(short, long)]
        out: PathBuf,
        // The listing's window is taller: the fidelity matters to the export.
        #[command(flatten)]
        fidelity: FidelityArg,
    },
    /// Render decks with ours and with POV-Ray (the Debian package `povray`),
    /// one thread each, interleaved, at equal samples: CPU ratio and
    /// silhouette agreement.
    VsPovray {
        /// The decks (paths or shipped names).
        #[arg(default_values_t = ["fig5_6".to_string(), "fig5_7".to_string(), "fig5_8".to_string()])]
        decks: Vec<String>,
        /// Width and height in pixels, WxH (each 1..8192).
        #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "256x256")]
        size: (usize, usize),
        /// M×M samples a pixel on both sides, M in 1..32 (POV-Ray's antialiasing depth
        /// goes to 9).
        #[arg(long, value_name = "M", value_parser = parse_mask, default_value = "4")]
        mask: u16,
        /// Timed rounds (the medians are printed).
        #[arg(long, default_value_t = 5)]
        runs: usize,
        /// Instead of the decks: the depth-of-field scene (cook.deck, lens
        /// only), CPU at equal RMSE against each renderer's own 1024-ray
        /// reference.
        #[arg(long)]
        depth_of_field: bool,
        /// With --depth-of-field: our samplers to measure, interleaved
        /// (repeat or separate by commas; the deck default, table, if none).
        #[arg(long, value_enum, value_delimiter = ',')]
        sampler: Vec<raytrace::options::TimeSampler>,
        /// Instead of the decks: the scenes of blobs and patches in
        /// tools/decks (a blob, a vase and floor of patches, and the
        /// speed goal's one blob of 60 components with 20 patches).
        #[arg(long, conflicts_with = "depth_of_field")]
        shapes: bool,
    },
    /// Time a sample against the number of objects: N spheres, fig5_6 stars and fig5_8
    /// goblets at random in a box, with each --accel and with POV-Ray when installed, one
    /// thread each; writes scale.png and scale.svg and prints the figures (docs/scale.md).
    Scale {
        /// Where to write scale.png and scale.svg.
        #[arg(long, default_value = "docs")]
        dir: PathBuf,
        /// A run small enough for a test: 24×24 at one sample a pixel, N = 1, 10, 100
        /// spheres and 1, 10 sweeps, one round (the flags below still apply).
        #[arg(long)]
        quick: bool,
        /// Width and height of every render in pixels, WxH (each 1..8192) [default: 256x256].
        #[arg(long, value_name = "WxH", value_parser = parse_size)]
        size: Option<(usize, usize)>,
        /// M×M samples a pixel on both sides, M in 1..32 (POV-Ray's antialiasing depth goes
        /// to 9) [default: 2].
        #[arg(long, value_name = "M", value_parser = parse_mask)]
        mask: Option<u16>,
        /// Timed rounds, after one untimed (the medians are plotted) [default: 5].
        #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
        runs: Option<u16>,
        /// The most objects a scene has (fewer points, a shorter run).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=100_000))]
        max: Option<u32>,
        /// The loop (--accel none) only on scenes of at most this many objects
        /// [default: 10000; beyond, a render of the loop takes minutes].
        #[arg(long)]
        loop_max: Option<usize>,
        /// Leave POV-Ray out even when it is installed.
        #[arg(long)]
        no_povray: bool,
        /// Also count the instructions a sample with valgrind (cachegrind): minutes more.
        #[arg(long)]
        instructions: bool,
        /// Write the scenes' decks (sphere100.deck, …) to this folder instead of measuring.
        #[arg(long, value_name = "DIR")]
        decks: Option<PathBuf>,
    },
    /// Write the stability report of the root solvers on hard cases.
    Stability {
        /// The report to write.
        #[arg(long, default_value = "docs/STABILITY.md")]
        out: PathBuf,
    },
    /// Fuzz the deck reader or the raster reader with mutations of the
    /// repository's decks and rasters; findings are written to OUT.
    Fuzz {
        /// What to fuzz: deck or raster.
        #[arg(value_parser = ["deck", "raster"])]
        target: String,
        /// The random seed: the same seed and input count try the same inputs.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Stop after this many inputs.
        #[arg(long, default_value_t = 100_000)]
        inputs: u64,
        /// Stop after this many seconds.
        #[arg(long)]
        seconds: Option<f64>,
        /// Where findings are written.
        #[arg(long, default_value = "raster/fuzz")]
        out: PathBuf,
    },
}

fn main() -> ExitCode {
    exit_code("tools", run(Cli::parse().command))
}

/// `tools bench`: the render flags and the deck as raytrace reads them
/// (their errors exit 2), then the timed renders.
fn bench(deck: &std::path::Path, runs: usize, render: &RenderArgs) -> Result<(), Failure> {
    let opts = render.options.options()?;
    let reconstruction = render.reconstruction()?;
    let deck = DeckInput::read(deck)?;
    let scene = render.scene(&deck, &opts)?;
    let pool = render.thread_pool()?;
    tools::bench::bench(&deck.name, &scene, reconstruction, runs.max(1), &pool).map_err(Failure::other)
}

/// A deck a tool reads (a path, or a shipped deck's name), read first so
/// that a bad one is an input error (exit 2), as in every program, before
/// the tool's own work.
fn readable(deck: &std::path::Path, fidelity: raytrace::options::Fidelity) -> Result<(), Failure> {
    let path = tools::decks::deck_path(&deck.to_string_lossy());
    DeckInput::read(&path)?.initialize(fidelity).map(drop)
}

/// Runs a command: the render flags' and the decks' errors are the
/// library's kinds; the tools' own are messages (exit 1).
fn run(command: Command) -> Result<(), Failure> {
    let done = match command {
        Command::Bench { deck, runs, render } => return bench(&deck, runs, &render),
        Command::Pov { deck, out, fidelity } => {
            let fidelity = fidelity.fidelity;
            let scene = tools::decks::load(&deck, fidelity).map_err(Failure::input)?;
            return tools::pov::write(&scene, fidelity, &out);
        }
        Command::Texture { dir } => tools::textures::write_textures(&dir),
        Command::Frames {
            deck,
            out,
            times,
            size,
            fidelity,
        } => {
            readable(&deck, fidelity.fidelity)?;
            tools::frames::frames(&deck, out.as_deref(), &times, size, fidelity.fidelity)
        }
        Command::Gallery { only, check, list } => {
            if list {
                for p in tools::gallery::GALLERY {
                    println!("{}\t{}\t{}", p.image, p.deck, p.command());
                }
                return Ok(());
            }
            tools::gallery::run(&tools::gallery::checkout(), &only, check)
        }
        Command::Chart { dir, size, runs, cache } => tools::chart::run(&dir, size, runs.max(1), cache.as_deref()),
        Command::Goal { size, runs, cache } => tools::goal::run(size, runs, cache.as_deref()),
        Command::Frontier {
            decks,
            size,
            runs,
            cache,
        } => tools::frontier::run(&decks, size, runs, cache.as_deref()),
        Command::Heatmap { deck, out, size, mask } => {
            readable(&deck, Default::default())?;
            tools::heatmap::run(&deck, &out, size, usize::from(mask))
        }
        Command::Stability { out } => tools::stability::run(&out),
        Command::Scale {
            dir,
            quick,
            size,
            mask,
            runs,
            max,
            loop_max,
            no_povray,
            instructions,
            decks,
        } => {
            let mut set = if quick {
                tools::scale::Settings::quick()
            } else {
                tools::scale::Settings::full()
            };
            set.size = size.unwrap_or(set.size);
            set.mask = mask.map_or(set.mask, usize::from);
            set.runs = runs.map_or(set.runs, usize::from);
            set.loop_max = loop_max.unwrap_or(set.loop_max);
            set.povray &= !no_povray;
            set.instructions = instructions;
            if let Some(max) = max {
                set.keep_at_most(max as usize);
            }
            match decks {
                Some(to) => tools::scale::write_decks(&set, &to),
                None => tools::scale::run(&mut set, &dir),
            }
        }
        Command::Preview {
            deck,
            name,
            point,
            runs,
            threads,
        } => {
            readable(&deck, Default::default())?;
            tools::preview::run(&deck, &name, point, runs.max(1), threads)
        }
        Command::Fuzz {
            target,
            seed,
            inputs,
            seconds,
            out,
        } => tools::fuzz::main(&target, seed, inputs, seconds, &out),
        Command::Join {
            files,
            out,
            tiles: true,
            ..
        } => return tools::join::join_tiles(&files, &out),
        Command::Join {
            files,
            out,
            rate,
            strip,
            every,
            ..
        } => return tools::join::join(&files, &out, rate, strip.as_deref().map(|s| (s, every as usize))),
        Command::VsPovray {
            decks,
            size,
            mask,
            runs,
            depth_of_field,
            sampler,
            shapes,
        } => {
            let set = tools::vs_povray::Settings {
                size,
                mask: usize::from(mask),
                runs: runs.max(1),
            };
            if depth_of_field {
                let samplers = if sampler.is_empty() {
                    vec![raytrace::options::Options::default().sampler]
                } else {
                    sampler
                };
                return tools::vs_povray::depth_of_field(&set, &samplers).map_err(Failure::other);
            }
            let decks: Vec<PathBuf> = if shapes {
                tools::decks::SHAPE_DECKS
                    .iter()
                    .map(|d| tools::decks::tools_deck(d))
                    .collect()
            } else {
                decks.iter().map(PathBuf::from).collect()
            };
            tools::vs_povray::run(&decks, &set)
        }
    };
    done.map_err(Failure::other)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `tools --version` prints the version (clap's `version` attribute).
    #[test]
    fn version_is_an_option() {
        let err = Cli::try_parse_from(["tools", "--version"])
            .err()
            .expect("--version stops the parse");
        assert_eq!(err.kind(), clap::error::ErrorKind::DisplayVersion);
        assert!(err.to_string().contains(env!("CARGO_PKG_VERSION")));
    }

    /// `tools frames DECK` without --out leaves the file to the frames module.
    #[test]
    fn frames_has_no_default_file_in_the_checkout() {
        let Command::Frames { out, .. } = Cli::try_parse_from(["tools", "frames", "x.deck"]).unwrap().command else {
            panic!("frames parses as frames");
        };
        assert_eq!(out, None);
    }
}

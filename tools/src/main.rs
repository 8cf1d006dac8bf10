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
        /// The deck [default: legacy_pascal/decks/still_life.deck].
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
            frames(&deck, &out, &times, size.clamp(8, 1024), fidelity)
        }
        Command::Bench {
            deck,
            runs,
            threads,
            robust,
            listing,
        } => {
            let opts = Options {
                fidelity: if listing { Fidelity::Listing } else { Fidelity::Thesis },
                solver: if robust { Solver::Robust } else { Solver::Laguerre },
                ..Options::default()
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

/// The letters N, E, C in blue on white, 96×48, for the advertising cube
/// of Fig. 5.5. Each letter is drawn from strokes on a 5×7 grid.
fn nec_card() -> Raster {
    const GLYPHS: [[&str; 7]; 3] = [
        ["X...X", "XX..X", "XX..X", "X.X.X", "X..XX", "X..XX", "X...X"],
        ["XXXXX", "X....", "X....", "XXXX.", "X....", "X....", "XXXXX"],
        [".XXXX", "X....", "X....", "X....", "X....", "X....", ".XXXX"],
    ];
    let (cell, width, height) = (4usize, 96usize, 48usize);
    let (left, top) = (6usize, 10usize);
    let mut pixels = vec![[255u8, 255, 255]; width * height];
    for (g, glyph) in GLYPHS.iter().enumerate() {
        for (row, line) in glyph.iter().enumerate() {
            for (col, ch) in line.bytes().enumerate() {
                if ch != b'X' {
                    continue;
                }
                let x0 = left + g * (6 * cell + 4) + col * cell;
                let y0 = top + row * cell;
                for y in y0..y0 + cell {
                    for x in x0..x0 + cell {
                        pixels[y * width + x] = [20, 40, 170];
                    }
                }
            }
        }
    }
    Raster { width, height, pixels }
}

/// The scene of `deck` at each instant of `times`: every moving object at
/// its pose then, every key-frame object at its in-between shape and pose,
/// rendered still and laid side by side.
fn frames(deck: &Path, out: &Path, times: &[f64], size: usize, fidelity: Fidelity) -> Result<(), String> {
    use raytrace::types::Shape;
    let source = std::fs::read_to_string(deck).map_err(|e| format!("{}: {e}", deck.display()))?;
    let dir = deck.parent().unwrap_or(Path::new("."));
    let opts = Options {
        fidelity,
        ..Options::default()
    };
    let mut scene =
        raytrace::deck::initialize(&source, &deck.display().to_string(), dir, fidelity).map_err(|e| e.to_string())?;
    raytrace::raytrace::prepare(&mut scene, &opts).map_err(|e| e.to_string())?;
    let chains = raytrace::raytrace::key_frame_chains(&scene, fidelity).map_err(|e| e.to_string())?;
    scene.image.width = size;
    scene.image.height = size;
    let mut strip = Raster {
        width: size * times.len().max(1),
        height: size,
        pixels: vec![[0; 3]; size * size * times.len().max(1)],
    };
    for (i, &t) in times.iter().enumerate() {
        let mut still = scene.clone();
        for mo in &scene.motions {
            let pose = raytrace::drt::motionblur(&scene.objects[mo.object], mo, t, fidelity);
            let obj = &mut still.objects[mo.object];
            (obj.transfm, obj.inverse, obj.sphereo) = (pose.transfm, pose.inverse, pose.sphereo);
        }
        for (k, chain) in &chains {
            let obj = &mut still.objects[scene.keyframes[*k].first];
            let mut contour = chain.scratch();
            chain.inbetween(t, &mut contour);
            obj.shape = Shape::Sweep(contour);
            let pose = chain.pose(t);
            (obj.transfm, obj.inverse, obj.sphereo) = (pose.transfm, pose.inverse, pose.sphereo);
        }
        still.motions.clear();
        still.keyframes.clear();
        let r = raytrace::raytrace::render(&still, &opts, &|| {}).raster;
        for y in 0..size {
            let row = y * strip.width + i * size;
            strip.pixels[row..row + size].copy_from_slice(&r.pixels[y * size..(y + 1) * size]);
        }
    }
    raytrace::raster::write_png(out, &strip).map_err(|e| format!("{}: {e}", out.display()))?;
    println!("wrote {} ({} frames at t = {:?})", out.display(), times.len(), times);
    Ok(())
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The texture rasters in raster/ are what `tools texture` writes.
    #[test]
    fn shipped_textures_are_the_tools_output() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../raster");
        for (name, raster) in [("card.tex.ras", test_card(64, 64)), ("nec.tex.ras", nec_card())] {
            let shipped = std::fs::read(dir.join(name)).expect("the shipped texture is readable");
            assert_eq!(
                shipped,
                raytrace::raster::encode_raster(&raster),
                "{name}: run `cargo run -p tools -- texture`"
            );
        }
    }
}

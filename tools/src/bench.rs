//! `tools bench DECK`: a quick timing of a deck's render (medians, never
//! asserted in tests).

use std::path::Path;
use std::time::Instant;

use raytrace::types::Options;

/// Renders `deck` once untimed, then `runs` times, and prints the median,
/// fastest and slowest time and the rays per second; fails if a render
/// differs from the first. `size` and `mask` override the deck's image.
pub fn bench(
    deck: &Path,
    runs: usize,
    threads: Option<usize>,
    opts: &Options,
    size: Option<(usize, usize)>,
    mask: Option<usize>,
) -> Result<(), String> {
    let source = std::fs::read_to_string(deck).map_err(|e| format!("{}: {e}", deck.display()))?;
    let dir = deck.parent().unwrap_or(Path::new("."));
    let name = deck.display().to_string();
    let mut scene = raytrace::deck::initialize(&source, &name, dir, opts.fidelity).map_err(|e| e.to_string())?;
    if size.is_some() || mask.is_some() {
        let (w, h) = size.unwrap_or((scene.image.width, scene.image.height));
        let m = mask.unwrap_or(scene.image.masksize);
        scene.resize(w, h, m);
    }
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
        "{name}: {}×{}, {}×{} subpixels, {} threads, {:?} {:?} {:?}: median {:.4} s, fastest {:.4} s, slowest {:.4} s over {} runs; {} rays a render, {:.0} rays/s",
        img.width,
        img.height,
        img.masksize,
        img.masksize,
        pool.current_num_threads(),
        opts.fidelity,
        opts.solver,
        opts.sampler,
        median,
        secs[0],
        secs[secs.len() - 1],
        runs,
        warm.stats.rays,
        warm.stats.rays as f64 / median
    );
    Ok(())
}

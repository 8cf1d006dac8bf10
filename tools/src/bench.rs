//! `tools bench DECK`: a quick timing of a deck's render (medians, never
//! asserted in tests).

use std::time::Instant;

use raytrace::raytrace::{render, Prepared, Request};
use raytrace::reconstruct::Reconstruction;

/// Renders the prepared `scene` of the deck `name` once untimed, then
/// `runs` times on `pool`, its pixels made by `reconstruction`, and prints
/// the median, fastest and slowest time and the rays per second; fails if
/// a render differs from the first.
pub fn bench(
    name: &str,
    prepared: &Prepared,
    reconstruction: Reconstruction,
    runs: usize,
    pool: &rayon::ThreadPool,
) -> Result<(), String> {
    let (scene, opts) = (prepared.scene(), prepared.options());
    let request = Request::STILL.reconstruction(reconstruction);
    let render = || pool.install(|| render(prepared, &request)).map_err(|e| e.to_string());
    let warm = render()?;
    let mut secs = Vec::with_capacity(runs);
    for _ in 0..runs {
        let t = Instant::now();
        let r = render()?;
        secs.push(t.elapsed().as_secs_f64());
        if r.raster != warm.raster {
            return Err("a render differs from the warm-up: the renderer is not deterministic".into());
        }
    }
    secs.sort_by(f64::total_cmp);
    let median = secs[secs.len() / 2];
    let img = &scene.image;
    println!(
        "{name}: {}×{}, {}×{} subpixels, {} threads, {:?} {:?} {:?} {:?}: median {:.4} s, fastest {:.4} s, slowest {:.4} s over {} runs; {} rays a render, {:.0} rays/s",
        img.width,
        img.height,
        img.masksize,
        img.masksize,
        pool.current_num_threads(),
        opts.fidelity,
        opts.solver,
        opts.sampler,
        reconstruction,
        median,
        secs[0],
        secs[secs.len() - 1],
        runs,
        warm.stats.rays,
        warm.stats.rays as f64 / median
    );
    Ok(())
}

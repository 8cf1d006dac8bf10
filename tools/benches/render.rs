//! The renderer's benches (`cargo bench -p tools`), with criterion:
//! - `chapter5/DECK`: each deck of Chapter 5 as it is (256×256, 2×2);
//! - `rays/DECK/SOLVER`: rays a second on the three sweep kinds (fig5_6
//!   translation, fig5_7 conic, fig5_8 rotation) for each root solver;
//! - `resolution/W×H`: fig5_9 at 128², 256², 512² and 1024×864, 2×2
//!   (pixels a second: flat means time linear in pixels);
//! - `segments/N`: a translation sweep of a B-spline circle of N = 4, 8,
//!   15, 30, 60 points at 256×256, 2×2.
//!
//! Sample counts are modest (10 samples, 3 s) so that the whole run takes a
//! few minutes on two cores. Renders use every core (rayon's global pool).
//! Nothing here is asserted: the targets are read off the report.

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use raytrace::raytrace::{prepare, render};
use raytrace::types::{Fidelity, Options, Scene, Solver};
use tools::decks::{circle_sweep_deck, load_source, prepared, CHAPTER5, SWEEP_KINDS};

fn modest<M: criterion::measurement::Measurement>(g: &mut BenchmarkGroup<'_, M>) {
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
}

fn scene(name: &str, opts: &Options, size: Option<(usize, usize, usize)>) -> Scene {
    prepared(name, opts, size).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Primary and secondary rays of one render.
fn rays_of(scene: &Scene, opts: &Options) -> u64 {
    render(scene, opts, &|| {}).stats.rays
}

fn chapter5(c: &mut Criterion) {
    let mut g = c.benchmark_group("chapter5");
    modest(&mut g);
    let opts = Options::default();
    for &name in CHAPTER5 {
        let s = scene(name, &opts, None);
        g.bench_function(name, |b| b.iter(|| render(black_box(&s), &opts, &|| {})));
    }
    g.finish();
}

fn rays(c: &mut Criterion) {
    let mut g = c.benchmark_group("rays");
    modest(&mut g);
    for &name in SWEEP_KINDS {
        for solver in [Solver::Laguerre, Solver::Robust] {
            let opts = Options {
                solver,
                ..Options::default()
            };
            let s = scene(name, &opts, None);
            g.throughput(Throughput::Elements(rays_of(&s, &opts)));
            let id = format!(
                "{name}/{}",
                if solver == Solver::Laguerre {
                    "laguerre"
                } else {
                    "robust"
                }
            );
            g.bench_function(id, |b| b.iter(|| render(black_box(&s), &opts, &|| {})));
        }
    }
    g.finish();
}

fn resolution(c: &mut Criterion) {
    let mut g = c.benchmark_group("resolution");
    modest(&mut g);
    let opts = Options::default();
    for (w, h) in [(128, 128), (256, 256), (512, 512), (1024, 864)] {
        let s = scene("fig5_9", &opts, Some((w, h, 2)));
        g.throughput(Throughput::Elements((w * h) as u64));
        g.bench_function(format!("fig5_9/{w}x{h}"), |b| {
            b.iter(|| render(black_box(&s), &opts, &|| {}))
        });
    }
    g.finish();
}

fn segments(c: &mut Criterion) {
    let mut g = c.benchmark_group("segments");
    modest(&mut g);
    let opts = Options::default();
    for n in [4, 8, 15, 30, 60] {
        let text = circle_sweep_deck(n, 256, 256, 2);
        let mut s = load_source(&text, &format!("circle{n}"), Path::new("."), Fidelity::Thesis)
            .unwrap_or_else(|e| panic!("circle {n}: {e}"));
        prepare(&mut s, &opts).unwrap_or_else(|e| panic!("circle {n}: {e}"));
        g.bench_function(format!("circle/{n}"), |b| {
            b.iter(|| render(black_box(&s), &opts, &|| {}))
        });
    }
    g.finish();
}

criterion_group!(benches, chapter5, rays, resolution, segments);
criterion_main!(benches);

//! The renderer's benches (`cargo bench -p tools-bench`), with criterion:
//! - `chapter5/DECK`: each deck of Chapter 5 as it is (256×256, 2×2);
//! - `rays/DECK/SOLVER`: rays a second on the three sweep kinds (fig5_6
//!   translation, fig5_7 conic, fig5_8 rotation) for each root solver;
//! - `resolution/W×H`: fig5_9 at 128², 256², 512² and 1024×864, 2×2
//!   (pixels a second: flat means time linear in pixels);
//! - `segments/N`: a translation sweep of a B-spline circle of N = 4, 8,
//!   15, 30, 60 points at 256×256, 2×2;
//! - `solver/DEGREE/SOLVER`: one solve of a cubic and of a sextic with
//!   separated roots in [0, 1], by `laguerre` and by the robust solver;
//! - `sweep/KIND/SOLVER`: one `Sweep::intersect` call a ray, on the sweep of
//!   fig5_6, fig5_7 and fig5_8 with rays aimed into its box;
//! - `scale/KIND/N`: N = 10, 100, 1000, 10000 spheres, fig5_6 stars or
//!   fig5_8 goblets at random in a 6×6×3 box (`tools scale`'s scenes),
//!   256×256, 2×2, `--accel auto` (samples a second: flat means time
//!   independent of N).
//!
//! Sample counts are modest (10 samples, 3 s) so that the whole run takes a
//! few minutes on two cores. Renders use every core (rayon's global pool).
//! Nothing here is asserted: the targets are read off the report.

use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use raytrace::options::{Fidelity, Options, Solver};
use raytrace::proc::sweep::{laguerre, Root, LAGUERRE_ROOTS};
use raytrace::raytrace::Prepared;
use raytrace::robust::{poly_from_roots, real_roots};
use raytrace::shapes::sweep::{Sweep, SweepCache};
use raytrace::types::{DVec3, Ray, Shape};
use tools::decks::{circle_sweep_deck, load_source, prepare, prepared, still, CHAPTER5, SWEEP_KINDS};
use tools::scale::scenes::{deck, Frame, Kind};

fn modest<M: criterion::measurement::Measurement>(g: &mut BenchmarkGroup<'_, M>) {
    g.sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
}

fn scene(name: &str, opts: &Options, size: Option<(usize, usize, usize)>) -> Prepared {
    prepared(name, opts, size).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Primary and secondary rays of one render.
fn rays_of(scene: &Prepared) -> u64 {
    still(scene).stats.rays
}

fn chapter5(c: &mut Criterion) {
    let mut g = c.benchmark_group("chapter5");
    modest(&mut g);
    let opts = Options::default();
    for &name in CHAPTER5 {
        let s = scene(name, &opts, None);
        g.bench_function(name, |b| b.iter(|| still(black_box(&s))));
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
            g.throughput(Throughput::Elements(rays_of(&s)));
            let id = format!(
                "{name}/{}",
                if solver == Solver::Laguerre {
                    "laguerre"
                } else {
                    "robust"
                }
            );
            g.bench_function(id, |b| b.iter(|| still(black_box(&s))));
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
        g.bench_function(format!("fig5_9/{w}x{h}"), |b| b.iter(|| still(black_box(&s))));
    }
    g.finish();
}

fn segments(c: &mut Criterion) {
    let mut g = c.benchmark_group("segments");
    modest(&mut g);
    let opts = Options::default();
    for n in [4, 8, 15, 30, 60] {
        let text = circle_sweep_deck(n, 256, 256, 2);
        let s = load_source(&text, &format!("circle{n}"), Path::new("."), Fidelity::Thesis)
            .and_then(|s| prepare(s, &opts))
            .unwrap_or_else(|e| panic!("circle {n}: {e}"));
        g.bench_function(format!("circle/{n}"), |b| b.iter(|| still(black_box(&s))));
    }
    g.finish();
}

const SOLVERS: [(Solver, &str); 2] = [(Solver::Laguerre, "laguerre"), (Solver::Robust, "robust")];

fn solver(c: &mut Criterion) {
    let mut g = c.benchmark_group("solver");
    modest(&mut g);
    let cubic = poly_from_roots(&[0.15, 0.5, 0.85], 1.0);
    let sextic = poly_from_roots(&[0.1, 0.25, 0.4, 0.55, 0.7, 0.9], 1.0);
    for (n, p) in [(3, cubic), (6, sextic)] {
        g.bench_function(format!("degree{n}/laguerre"), |b| {
            b.iter(|| {
                let mut root = [Root::default(); LAGUERRE_ROOTS];
                laguerre(n, black_box(&p), 1.0, 0.0, &mut root, Fidelity::Thesis)
            })
        });
        g.bench_function(format!("degree{n}/robust"), |b| {
            b.iter(|| real_roots(n, black_box(&p), 0.0, 1.0).count)
        });
    }
    g.finish();
}

fn sweep(c: &mut Criterion) {
    let mut g = c.benchmark_group("sweep");
    modest(&mut g);
    for (&name, kind) in SWEEP_KINDS.iter().zip(["translation", "conic", "rotation"]) {
        let s = scene(name, &Options::default(), None);
        let Some(obj) = s.scene().objects.iter().find(|o| matches!(o.shape, Shape::Sweep(_))) else {
            continue;
        };
        let Shape::Sweep(sw) = &obj.shape else { continue };
        let cache = SweepCache::new(obj.class, sw);
        let sweep = Sweep {
            class: obj.class,
            shape: sw,
            cache: cache.as_ref(),
        };
        // 64 rays from 8 units off the box's centre, aimed across the box.
        let b = &sw.bbox;
        let (lo, hi) = (DVec3::new(b.xmin, b.ymin, b.zmin), DVec3::new(b.xmax, b.ymax, b.zmax));
        let centre = (lo + hi) * 0.5;
        let rays: Vec<Ray> = (0..64)
            .map(|k| {
                let a = k as f64 * 0.7;
                let origin = centre + DVec3::new(8.0 * a.cos(), 8.0 * a.sin(), 2.0 * (k as f64 * 0.3).sin());
                let target = lo + (hi - lo) * DVec3::new((k % 8) as f64 / 7.0, 0.5, (k / 8) as f64 / 7.0);
                Ray::new(origin, (target - origin).normalize())
            })
            .collect();
        g.throughput(Throughput::Elements(rays.len() as u64));
        for (solver, sname) in SOLVERS {
            let opts = Options {
                solver,
                ..Options::default()
            };
            g.bench_function(format!("{kind}/{sname}"), |bch| {
                bch.iter(|| {
                    rays.iter()
                        .filter(|r| sweep.intersect(black_box(r), 1e-9, &opts, &mut 0).is_some())
                        .count()
                })
            });
        }
    }
    g.finish();
}

fn scale(c: &mut Criterion) {
    let mut g = c.benchmark_group("scale");
    modest(&mut g);
    let frame = Frame {
        size: (256, 256),
        mask: 2,
        travel: 0.0,
    };
    g.throughput(Throughput::Elements(256 * 256 * 4));
    for kind in Kind::ALL {
        for n in [10, 100, 1000, 10000] {
            let s = deck(kind, n, frame)
                .and_then(|text| load_source(&text, kind.name(), Path::new("."), Fidelity::Thesis))
                .and_then(|s| prepare(s, &Options::default()))
                .unwrap_or_else(|e| panic!("{} {n}: {e}", kind.name()));
            g.bench_function(format!("{}/{n}", kind.name()), |b| b.iter(|| still(black_box(&s))));
        }
    }
    g.finish();
}

criterion_group!(benches, chapter5, rays, resolution, segments, solver, sweep, scale);
criterion_main!(benches);

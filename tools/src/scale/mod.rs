//! `tools scale`: time per sample against the number of objects, for each
//! `--accel` and for POV-Ray, on scenes of N spheres, fig5_6 stars and
//! fig5_8 goblets ([`scenes`]); docs/scale.png and docs/scale.svg, and
//! the figures as Markdown tables (issue 24, item 5). Not the thesis's: a
//! measurement of the port's structures over the objects.
//!
//! For each scene kind and each N, every method renders the same scene,
//! one thread each, in interleaved rounds after an untimed one, and the
//! median CPU time over the image's samples (width·height·mask², the same
//! for every method) is plotted. Ours is the render alone (the thread's
//! CPU time, the scene prepared before); POV-Ray's is the trace time it
//! reports (`+A0.0 +AM1 +RM -J +WT1`, M×M samples a pixel), without its
//! parse and bounding, which the table gives as set-up beside our
//! preparation. The untimed round also checks that every `--accel` gives
//! the same raster, byte for byte, and fails naming the one that does not.
//!
//! Then 1,000 spheres each moving two radii, and each moving 4.6 radii,
//! with `blur 1` against the same spheres at rest (ours, `--accel auto`),
//! and with `--instructions` the instructions a sample, counted by
//! valgrind ([`instructions`]).
//! Timings are printed, never asserted in tests.

pub mod instructions;
mod plot;
pub mod scenes;

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::ValueEnum;
use raytrace::accel::Accel;
use raytrace::options::{Fidelity, Options};
use raytrace::raytrace::Prepared;
use raytrace::scene::Scene;

use crate::measure::{interleaved_medians_of, timed_still};
use scenes::{Frame, Kind};

/// What one `tools scale` run measures.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Width and height of every render, in pixels.
    pub size: (usize, usize),
    /// M: M×M samples a pixel on both sides.
    pub mask: usize,
    /// Timed rounds (after one untimed).
    pub runs: usize,
    /// The N of the sphere scenes, and of the star and goblet scenes.
    pub sphere_ns: Vec<usize>,
    pub sweep_ns: Vec<usize>,
    /// The loop (`--accel none`) renders scenes of at most this many
    /// objects: beyond, one render takes minutes.
    pub loop_max: usize,
    /// The N of the moving spheres against the same at rest.
    pub moving_n: usize,
    /// How far they move, in their radii: one scene each.
    pub travels: Vec<f64>,
    /// Whether POV-Ray races too (when it is installed).
    pub povray: bool,
    /// Whether valgrind counts the instructions a sample.
    pub instructions: bool,
}

impl Settings {
    /// The measurement: 256×256, 4 samples a pixel, 1…100,000
    /// spheres and 1…10,000 sweeps at three points a decade.
    pub fn full() -> Settings {
        let decades = |top: usize| -> Vec<usize> {
            let mut n = vec![1];
            while *n.last().unwrap() < top {
                let last = *n.last().unwrap();
                n.push(if n.len() % 2 == 1 { last * 3 } else { last * 10 / 3 });
            }
            n
        };
        Settings {
            size: (256, 256),
            mask: 2,
            runs: 5,
            sphere_ns: decades(100_000),
            sweep_ns: decades(10_000),
            loop_max: 10_000,
            moving_n: 1_000,
            travels: TRAVELS.to_vec(),
            povray: true,
            instructions: false,
        }
    }

    /// A run small enough for a test: 24×24 at one sample a pixel, a few N.
    pub fn quick() -> Settings {
        Settings {
            size: (24, 24),
            mask: 1,
            runs: 1,
            sphere_ns: vec![1, 10, 100],
            sweep_ns: vec![1, 10],
            loop_max: 100,
            moving_n: 10,
            ..Settings::full()
        }
    }

    /// Leaves out the scenes of more than `max` objects (the moving
    /// spheres too: at most `max` of them).
    pub fn keep_at_most(&mut self, max: usize) {
        self.sphere_ns.retain(|&n| n <= max);
        self.sweep_ns.retain(|&n| n <= max);
        self.moving_n = self.moving_n.min(max);
    }

    /// The N of a kind's scenes.
    pub fn ns(&self, kind: Kind) -> &[usize] {
        match kind {
            Kind::Sphere => &self.sphere_ns,
            Kind::Star | Kind::Goblet => &self.sweep_ns,
        }
    }

    fn frame(&self, travel: f64) -> Frame {
        Frame {
            size: self.size,
            mask: self.mask,
            travel,
        }
    }

    /// Samples an image: width·height·mask².
    pub fn samples(&self) -> f64 {
        (self.size.0 * self.size.1 * self.mask * self.mask) as f64
    }
}

/// A way of finding what a ray meets: one of ours, or POV-Ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Ours(Accel),
    Povray,
}

/// Every method, in the order of the table's columns and the rounds.
pub const METHODS: [Method; 5] = [
    Method::Ours(Accel::None),
    Method::Ours(Accel::Bvh),
    Method::Ours(Accel::Octree),
    Method::Ours(Accel::Auto),
    Method::Povray,
];

impl Method {
    pub fn label(self) -> String {
        match self {
            Method::Ours(a) => format!(
                "--accel {}",
                a.to_possible_value()
                    .map(|v| v.get_name().to_string())
                    .unwrap_or_default()
            ),
            Method::Povray => "POV-Ray 3.7".into(),
        }
    }
}

/// One method on one scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    pub kind: Kind,
    pub n: usize,
    pub method: Method,
    /// Median CPU seconds a sample.
    pub per_sample: f64,
    /// Seconds to the first ray: our `Prepared` (wall clock, once), or
    /// POV-Ray's parse and bounding (CPU, median); NaN when not known.
    pub setup: f64,
}

/// Everything one run measured.
#[derive(Clone, Debug, Default)]
pub struct Measured {
    pub points: Vec<Point>,
    /// Median CPU seconds of the spheres' render at rest, and moving each
    /// of the travels (in radii, and the seconds).
    pub moving: Option<(f64, Vec<(f64, f64)>)>,
    pub instructions: Vec<instructions::Row>,
}

impl Measured {
    pub fn point(&self, kind: Kind, n: usize, method: Method) -> Option<&Point> {
        self.points
            .iter()
            .find(|p| p.kind == kind && p.n == n && p.method == method)
    }
}

/// A scene's deck read as `raytrace` reads it.
fn scene(kind: Kind, n: usize, frame: Frame) -> Result<Scene, String> {
    let text = scenes::deck(kind, n, frame)?;
    crate::decks::load_source(&text, &format!("{}{n}", kind.name()), Path::new("."), Fidelity::Thesis)
}

/// The methods that render a scene of `n` objects.
fn methods(set: &Settings, n: usize) -> Vec<Method> {
    METHODS
        .into_iter()
        .filter(|m| match m {
            Method::Ours(Accel::None) => n <= set.loop_max,
            Method::Ours(_) => true,
            Method::Povray => set.povray,
        })
        .collect()
}

/// Every method on the scene of `n` objects of `kind`: see the module doc.
fn measure_scene(
    set: &Settings,
    pool: &rayon::ThreadPool,
    tmp: &Path,
    kind: Kind,
    n: usize,
) -> Result<Vec<Point>, String> {
    let base = scene(kind, n, set.frame(0.0))?;
    let methods = methods(set, n);
    let mut prepared = Vec::new();
    let mut setup = Vec::new();
    for m in &methods {
        if let Method::Ours(accel) = *m {
            let t = Instant::now();
            let p = Prepared::new(
                base.clone(),
                Options {
                    accel,
                    ..Options::default()
                },
            )
            .map_err(|e| e.to_string())?;
            setup.push(t.elapsed().as_secs_f64());
            prepared.push((accel, p));
        }
    }
    let pov = tmp.join(format!("{}{n}.pov", kind.name()));
    let ppm = tmp.join("pov.ppm");
    if set.povray {
        std::fs::write(&pov, crate::pov::scene_sdl(&base, Fidelity::Thesis))
            .map_err(|e| format!("{}: {e}", pov.display()))?;
    }
    // The untimed round's rasters, to hold every --accel to the first.
    let rasters: RefCell<Vec<(Accel, Vec<[u8; 3]>)>> = RefCell::new(Vec::new());
    let mut pov_setup = Vec::new();
    let mut jobs: Vec<Box<dyn FnMut() -> Result<f64, String> + '_>> = Vec::new();
    let ours_count = prepared.len();
    for (accel, p) in &prepared {
        let rasters = &rasters;
        jobs.push(Box::new(move || {
            let (secs, raster) = timed_still(pool, p);
            let mut rasters = rasters.borrow_mut();
            if rasters.len() < ours_count {
                rasters.push((*accel, raster));
            }
            Ok(secs)
        }));
    }
    if set.povray {
        let (pov, ppm, pov_setup) = (&pov, &ppm, &mut pov_setup);
        jobs.push(Box::new(move || {
            let run = crate::vs_povray::povray(pov, ppm, set.size, set.mask)?;
            pov_setup.push(run.setup.unwrap_or(f64::NAN));
            Ok(run.trace.unwrap_or(run.process))
        }));
    }
    let mut refs: Vec<&mut dyn FnMut() -> Result<f64, String>> = jobs.iter_mut().map(|j| j.as_mut() as _).collect();
    let secs = interleaved_medians_of(&mut refs, set.runs)?;
    drop(jobs);
    let rasters = rasters.into_inner();
    if let Some((first, reference)) = rasters.first() {
        if let Some((other, _)) = rasters.iter().find(|(_, r)| r != reference) {
            return Err(format!(
                "{} {}s: --accel {other:?} renders another image than --accel {first:?}",
                n,
                kind.name()
            ));
        }
    }
    let setup = setup.into_iter().chain([crate::measure::median(&pov_setup)]);
    let points: Vec<Point> = methods
        .into_iter()
        .zip(secs)
        .zip(setup)
        .map(|((method, s), setup)| Point {
            kind,
            n,
            method,
            per_sample: s / set.samples(),
            setup,
        })
        .collect();
    let line: Vec<String> = points
        .iter()
        .map(|p| format!("{} {:.3} µs", p.method.label(), p.per_sample * 1e6))
        .collect();
    eprintln!("{n} {}s: {}", kind.name(), line.join(", "));
    Ok(points)
}

/// The moving spheres against the same at rest: median CPU seconds of
/// each render, interleaved (at rest, then each travel).
fn measure_moving(set: &Settings, pool: &rayon::ThreadPool) -> Result<(f64, Vec<(f64, f64)>), String> {
    let prep = |travel| {
        scene(Kind::Sphere, set.moving_n, set.frame(travel))
            .and_then(|s| Prepared::new(s, Options::default()).map_err(|e| e.to_string()))
    };
    let scenes = std::iter::once(0.0)
        .chain(set.travels.iter().copied())
        .map(prep)
        .collect::<Result<Vec<_>, _>>()?;
    let mut jobs: Vec<Box<dyn FnMut() -> Result<f64, String> + '_>> = scenes
        .iter()
        .map(|p| Box::new(move || Ok(timed_still(pool, p).0)) as Box<dyn FnMut() -> Result<f64, String>>)
        .collect();
    let mut refs: Vec<&mut dyn FnMut() -> Result<f64, String>> = jobs.iter_mut().map(|j| j.as_mut() as _).collect();
    let m = interleaved_medians_of(&mut refs, set.runs)?;
    let moving: Vec<(f64, f64)> = set.travels.iter().copied().zip(m[1..].iter().copied()).collect();
    for &(travel, secs) in &moving {
        eprintln!(
            "{} spheres: at rest {:.4} s, each moving {travel} radii with blur 1 {secs:.4} s ({:.2}×)",
            set.moving_n,
            m[0],
            secs / m[0]
        );
    }
    Ok((m[0], moving))
}

/// How far the moving spheres move, in their radii: two (the scene of
/// issue 24) and 4.6 (issue 38's, as Blender Cycles was timed on).
pub const TRAVELS: [f64; 2] = [2.0, 4.6];

/// Measures everything `set` asks for.
pub fn measure(set: &Settings) -> Result<Measured, String> {
    let pool = crate::measure::one_thread()?;
    let tmp = crate::measure::scratch_dir("scale")?;
    let result = (|| {
        let mut out = Measured::default();
        for kind in Kind::ALL {
            for &n in set.ns(kind) {
                out.points.extend(measure_scene(set, &pool, &tmp, kind, n)?);
            }
        }
        out.moving = Some(measure_moving(set, &pool)?);
        if set.instructions {
            out.instructions = instructions::measure(set, &tmp)?;
        }
        Ok(out)
    })();
    let _ = std::fs::remove_dir_all(&tmp);
    result
}

/// `tools scale`: measures, prints the tables, writes `dir`/scale.png and
/// scale.svg.
pub fn run(set: &mut Settings, dir: &Path) -> Result<(), String> {
    crate::fonts::register()?;
    if set.povray {
        if let Err(e) = crate::vs_povray::check_povray() {
            eprintln!("{e}; measuring without it");
            set.povray = false;
        }
    }
    if set.instructions {
        instructions::check_valgrind()?;
    }
    let measured = measure(set)?;
    print!("{}", tables(&measured, set));
    let (png, svg): (PathBuf, PathBuf) = (dir.join("scale.png"), dir.join("scale.svg"));
    plot::write(&measured, set, &png, &svg)?;
    println!("\nwrote {} and {}", png.display(), svg.display());
    Ok(())
}

/// `tools scale --decks DIR`: every scene of the run as a deck,
/// DIR/KINDN.deck, at the run's size and mask; and the moving spheres as
/// DIR/sphereN_movingT.deck, T the radii they move.
pub fn write_decks(set: &Settings, dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut files = Vec::new();
    for kind in Kind::ALL {
        for &n in set.ns(kind) {
            files.push((
                format!("{}{n}.deck", kind.name()),
                scenes::deck(kind, n, set.frame(0.0))?,
            ));
        }
    }
    for &travel in &set.travels {
        let moving = scenes::deck(Kind::Sphere, set.moving_n, set.frame(travel))?;
        files.push((format!("sphere{}_moving{travel}.deck", set.moving_n), moving));
    }
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| format!("{}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The goal's scenes: (kind, N) where ours is held to POV-Ray.
pub const GOAL: [(Kind, usize); 3] = [(Kind::Sphere, 10_000), (Kind::Star, 1_000), (Kind::Goblet, 1_000)];

/// A number of objects as the tables write it (10,000).
fn count(n: usize) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// The figures as Markdown tables: time a sample for every scene and
/// method, the goal's ratios, the moving spheres, the instructions.
pub fn tables(m: &Measured, set: &Settings) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let methods: Vec<Method> = METHODS
        .into_iter()
        .filter(|&x| m.points.iter().any(|p| p.method == x))
        .collect();
    let _ = writeln!(
        s,
        "\nµs a sample (CPU, one thread, median of {} interleaved rounds), {}×{}, {} samples a pixel\n",
        set.runs,
        set.size.0,
        set.size.1,
        set.mask * set.mask
    );
    let head: Vec<String> = methods.iter().map(|x| x.label()).collect();
    let _ = writeln!(s, "| scene | N | {} | set-up, ours / POV (ms) |", head.join(" | "));
    let _ = writeln!(s, "|---|---|{}---|", "---|".repeat(methods.len()));
    for kind in Kind::ALL {
        for &n in set.ns(kind) {
            let cell = |x: Method| {
                m.point(kind, n, x)
                    .map_or("–".into(), |p| format!("{:.3}", p.per_sample * 1e6))
            };
            let cells: Vec<String> = methods.iter().map(|&x| cell(x)).collect();
            let setup = |x: Method| {
                m.point(kind, n, x)
                    .map_or("–".into(), |p| format!("{:.1}", p.setup * 1e3))
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} / {} |",
                kind.name(),
                count(n),
                cells.join(" | "),
                setup(Method::Ours(Accel::Auto)),
                setup(Method::Povray)
            );
        }
    }
    let _ = writeln!(
        s,
        "\n| goal scene | ours (auto), µs | POV-Ray, µs | ours/POV |\n|---|---|---|---|"
    );
    for (kind, n) in GOAL {
        let (a, b) = (
            m.point(kind, n, Method::Ours(Accel::Auto)),
            m.point(kind, n, Method::Povray),
        );
        if let (Some(a), Some(b)) = (a, b) {
            let _ = writeln!(
                s,
                "| {} {}s | {:.3} | {:.3} | {:.2} |",
                count(n),
                kind.name(),
                a.per_sample * 1e6,
                b.per_sample * 1e6,
                a.per_sample / b.per_sample
            );
        }
    }
    if let Some((rest, moving)) = &m.moving {
        let _ = writeln!(
            s,
            "\n| {} spheres, --accel auto, blur 1 | CPU s (median) | against at rest |\n|---|---|---|\n| at rest | {rest:.4} | 1 |",
            count(set.moving_n),
        );
        for (travel, secs) in moving {
            let _ = writeln!(s, "| each moving {travel} radii | {secs:.4} | {:.2} |", secs / rest);
        }
    }
    s.push_str(&instructions::table(&m.instructions));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_with_thousands_separated() {
        assert_eq!(count(1), "1");
        assert_eq!(count(1000), "1,000");
        assert_eq!(count(100_000), "100,000");
    }

    /// Three points a decade from 1 to the top, the top included.
    #[test]
    fn the_full_run_has_three_points_a_decade() {
        let set = Settings::full();
        assert_eq!(set.sweep_ns, [1, 3, 10, 30, 100, 300, 1000, 3000, 10000]);
        assert_eq!(set.sphere_ns.len(), 11);
        assert_eq!(set.sphere_ns.last(), Some(&100_000));
        for (kind, n) in GOAL {
            assert!(set.ns(kind).contains(&n), "{kind:?} {n}");
        }
    }

    /// The loop stops at `loop_max`; POV-Ray only when asked.
    #[test]
    fn methods_by_n() {
        let mut set = Settings::quick();
        assert_eq!(methods(&set, 100).len(), 5);
        assert!(!methods(&set, 101).contains(&Method::Ours(Accel::None)));
        set.povray = false;
        assert!(!methods(&set, 1).contains(&Method::Povray));
        set.keep_at_most(5);
        assert_eq!(
            (set.sphere_ns.as_slice(), set.sweep_ns.as_slice(), set.moving_n),
            (&[1][..], &[1][..], 5)
        );
        assert_eq!(Method::Ours(Accel::Octree).label(), "--accel octree");
    }
}

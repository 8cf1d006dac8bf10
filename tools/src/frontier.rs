//! `tools frontier`: the reconstructions and the Sobol sampler against
//! their goals, measured in one run on each deck of [`FRONTIER_DECKS`]
//! (or those named): every way of [`WAYS`] rendered at `size`², its RMSE
//! against the chart's reference (1024 stratified rays a pixel, `--mask
//! 32 --sampler stratified`) and its CPU time (one thread, the thread's
//! own CPU time, every way of a deck interleaved, the median of `runs`
//! rounds), each over the best 16-ray render of the port before them
//! (`--sampler adaptive --mask 4`). The goals it prints:
//!
//! - `--denoise`: the RMSE of that best render or less, in at most 0.35
//!   × its CPU time: [`DENOISED`], 4 rays a pixel, and the fewest rays
//!   (4, 9 or 16) at which the adaptive sampler and `--denoise` reach
//!   that RMSE, and at what CPU time;
//! - `--sampler sobol` at 16 rays a pixel: RMSE at most 0.85 ×
//!   `--sampler stratified`'s.
//!
//! `--coherence N` has no goal but its point on the chart: its rows say
//! what the thesis's coherence buys and costs on the same decks.
//!
//! The references take most of the run; `cache` keeps them between runs
//! (as `tools goal`'s, [`crate::goal::reference`]).

use std::fmt::Write as _;
use std::path::Path;

use raytrace::options::TimeSampler;
use raytrace::raytrace::{render, Prepared, Request};
use raytrace::reconstruct::Reconstruction;
use raytrace::types::Intensity;

use crate::decks::{prepared, FRONTIER_DECKS};
use crate::goal::{opts, reference};
use crate::measure::{interleaved_medians_of, rmse, thread_cpu_timed};

/// One way of rendering: a sampler at a mask, and how pixels are made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Way {
    pub label: &'static str,
    pub sampler: TimeSampler,
    pub mask: usize,
    pub reconstruction: Reconstruction,
}

const fn way(label: &'static str, sampler: TimeSampler, mask: usize, reconstruction: Reconstruction) -> Way {
    Way {
        label,
        sampler,
        mask,
        reconstruction,
    }
}

/// The best 16-ray render before the reconstructions: the goals' yardstick.
pub const BEST: Way = way("adaptive", TimeSampler::Adaptive, 4, Reconstruction::Box);

/// `--sampler stratified` and `sobol` at 16 rays: the Sobol goal's pair.
pub const STRATIFIED16: Way = way("stratified", TimeSampler::Stratified, 4, Reconstruction::Box);
pub const SOBOL16: Way = way("sobol", TimeSampler::Sobol, 4, Reconstruction::Box);

/// The `--denoise` way of the goal: the adaptive sampler at 4 rays a
/// pixel (the rays where the spread is), then the filter.
pub const DENOISED: Way = way("adaptive + denoise", TimeSampler::Adaptive, 2, Reconstruction::Denoise);

/// Every way measured, [`BEST`] first.
pub const WAYS: &[Way] = &[
    BEST,
    STRATIFIED16,
    SOBOL16,
    DENOISED,
    way("sobol + denoise", TimeSampler::Sobol, 2, Reconstruction::Denoise),
    way("adaptive + denoise", TimeSampler::Adaptive, 3, Reconstruction::Denoise),
    way("adaptive + denoise", TimeSampler::Adaptive, 4, Reconstruction::Denoise),
    way("adaptive", TimeSampler::Adaptive, 2, Reconstruction::Box),
    way("adaptive", TimeSampler::Adaptive, 3, Reconstruction::Box),
    way("table", TimeSampler::Table, 4, Reconstruction::Box),
    way(
        "table + coherence 2",
        TimeSampler::Table,
        4,
        Reconstruction::Coherence(2),
    ),
    way(
        "table + coherence 4",
        TimeSampler::Table,
        4,
        Reconstruction::Coherence(4),
    ),
    way(
        "table + coherence 8",
        TimeSampler::Table,
        4,
        Reconstruction::Coherence(8),
    ),
];

/// One way's figures on one deck.
#[derive(Clone, Debug)]
pub struct Point {
    pub deck: String,
    pub way: Way,
    pub rmse: f64,
    /// Median CPU seconds on one thread (NaN when not timed).
    pub secs: f64,
}

/// The render of `way` of a prepared scene.
fn still(scene: &Prepared, way: &Way) -> Vec<Intensity> {
    let request = Request::STILL.reconstruction(way.reconstruction);
    render(scene, &request)
        .unwrap_or_else(|e| panic!("a whole image: {e}"))
        .colours
}

/// Measures `ways` on each of `decks` at `size`² with `runs` timed rounds.
pub fn measure(
    decks: &[String],
    ways: &[Way],
    size: (usize, usize),
    runs: usize,
    cache: Option<&Path>,
) -> Result<Vec<Point>, String> {
    let one = crate::measure::one_thread()?;
    let mut points = Vec::new();
    for deck in decks {
        let reference = reference(deck, size, cache)?;
        let scenes: Vec<Prepared> = ways
            .iter()
            .map(|w| prepared(deck, &opts(w.sampler), Some((size.0, size.1, w.mask))))
            .collect::<Result<_, _>>()?;
        let errors: Vec<f64> = scenes
            .iter()
            .zip(ways)
            .map(|(s, w)| rmse(&still(s, w), &reference))
            .collect();
        let secs = if runs == 0 {
            vec![f64::NAN; ways.len()]
        } else {
            let mut jobs: Vec<Box<dyn FnMut() -> Result<f64, String>>> = scenes
                .iter()
                .zip(ways)
                .map(|(s, w)| {
                    let pool = &one;
                    Box::new(
                        move || Ok(pool.install(|| thread_cpu_timed(|| drop(std::hint::black_box(still(s, w)))).0)),
                    ) as Box<dyn FnMut() -> Result<f64, String>>
                })
                .collect();
            let mut refs: Vec<&mut dyn FnMut() -> Result<f64, String>> =
                jobs.iter_mut().map(|j| j.as_mut() as _).collect();
            interleaved_medians_of(&mut refs, runs)?
        };
        for ((way, rmse), secs) in ways.iter().zip(errors).zip(secs) {
            let p = Point {
                deck: deck.clone(),
                way: *way,
                rmse,
                secs,
            };
            eprintln!("{}", line(&p, &points_best(&points, deck).unwrap_or(p.clone())));
            points.push(p);
        }
    }
    Ok(points)
}

/// The [`BEST`] point of `deck` among `points`.
fn points_best(points: &[Point], deck: &str) -> Option<Point> {
    points.iter().find(|p| p.deck == deck && p.way == BEST).cloned()
}

/// A row of the table: the point, and its ratios to `best`'s.
pub fn line(p: &Point, best: &Point) -> String {
    format!(
        "| {} | {} | {} | {:.5} | {:.3} | {:.4} | {:.3} |",
        p.deck,
        p.way.label,
        p.way.mask * p.way.mask,
        p.rmse,
        p.rmse / best.rmse,
        p.secs,
        p.secs / best.secs
    )
}

/// The table of every point, then the goals' lines.
pub fn report(points: &[Point]) -> String {
    let mut s = String::from(
        "| deck | way | rays a pixel | RMSE | RMSE / adaptive 16 | CPU s | CPU / adaptive 16 |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for p in points {
        if let Some(best) = points_best(points, &p.deck) {
            let _ = writeln!(s, "{}", line(p, &best));
        }
    }
    s.push('\n');
    let find = |deck: &str, way: &Way| points.iter().find(|p| p.deck == deck && p.way == *way);
    let mut decks: Vec<&str> = points.iter().map(|p| p.deck.as_str()).collect();
    decks.dedup();
    for deck in decks {
        if let (Some(best), Some(d)) = (find(deck, &BEST), find(deck, &DENOISED)) {
            let (e, t) = (d.rmse / best.rmse, d.secs / best.secs);
            let met = e <= 1.0 && t <= 0.35;
            let _ = writeln!(
                s,
                "{deck}: --denoise (adaptive, 4 rays) RMSE {e:.3} × and CPU {t:.3} × adaptive 16's: goal (≤ 1, ≤ 0.35) {}",
                if met { "met" } else { "not met" }
            );
        }
        let reached = points
            .iter()
            .filter(|p| p.deck == deck && p.way.label == DENOISED.label)
            .filter(|p| find(deck, &BEST).is_some_and(|b| p.rmse <= b.rmse))
            .min_by_key(|p| p.way.mask);
        if let (Some(best), Some(r)) = (find(deck, &BEST), reached) {
            let _ = writeln!(
                s,
                "{deck}: adaptive + --denoise reaches adaptive 16's RMSE at {} rays a pixel, CPU {:.3} ×",
                r.way.mask * r.way.mask,
                r.secs / best.secs
            );
        }
        if let (Some(st), Some(so)) = (find(deck, &STRATIFIED16), find(deck, &SOBOL16)) {
            let r = so.rmse / st.rmse;
            let _ = writeln!(
                s,
                "{deck}: --sampler sobol at 16 rays RMSE {r:.3} × stratified's: goal (≤ 0.85) {}",
                if r <= 0.85 { "met" } else { "not met" }
            );
        }
    }
    s
}

/// `tools frontier`: measures and prints the table and the goals.
pub fn run(decks: &[String], size: (usize, usize), runs: usize, cache: Option<&Path>) -> Result<(), String> {
    let decks: Vec<String> = if decks.is_empty() {
        FRONTIER_DECKS.iter().map(|d| d.to_string()).collect()
    } else {
        decks.to_vec()
    };
    let points = measure(&decks, WAYS, size, runs, cache)?;
    print!("{}", report(&points));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(way: Way, rmse: f64, secs: f64) -> Point {
        Point {
            deck: "fig5_3".into(),
            way,
            rmse,
            secs,
        }
    }

    /// The ratios are over the adaptive 16-ray render's, and the goals'
    /// lines say met or not by the goals' bounds.
    #[test]
    fn the_report_gives_the_ratios_and_the_goals() {
        let points = [
            point(BEST, 0.01, 1.0),
            point(STRATIFIED16, 0.02, 0.8),
            point(SOBOL16, 0.0168, 0.8),
            point(DENOISED, 0.009, 0.3),
        ];
        let r = report(&points);
        assert!(
            r.contains("| fig5_3 | adaptive + denoise | 4 | 0.00900 | 0.900 | 0.3000 | 0.300 |"),
            "{r}"
        );
        assert!(
            r.contains("RMSE 0.900 × and CPU 0.300 × adaptive 16's: goal (≤ 1, ≤ 0.35) met"),
            "{r}"
        );
        assert!(r.contains("RMSE 0.840 × stratified's: goal (≤ 0.85) met"), "{r}");
        let worse = [point(BEST, 0.01, 1.0), point(DENOISED, 0.011, 0.3)];
        assert!(report(&worse).contains("not met"));
        assert!(!report(&worse).contains("reaches"));
        let sixteen = Way { mask: 4, ..DENOISED };
        let reached = [
            point(BEST, 0.01, 1.0),
            point(DENOISED, 0.011, 0.3),
            point(sixteen, 0.0099, 1.2),
        ];
        assert!(
            report(&reached).contains("reaches adaptive 16's RMSE at 16 rays a pixel, CPU 1.200 ×"),
            "{}",
            report(&reached)
        );
        assert_eq!(WAYS[0], BEST);
    }
}

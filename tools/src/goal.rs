//! `tools goal`: the adaptive sampler's goal (half the table's error in at
//! most 1.1 times its time), measured in one run: on each deck of
//! [`BLUR_DECKS`] at 16 and 64 rays a pixel (masks 4 and 8), the RMSE of
//! the adaptive image over the thesis table's, both against the chart's
//! reference (1024 stratified time samples a pixel), and the CPU time of
//! the adaptive render over the table's (one thread, the two interleaved,
//! median of `runs` rounds; the thread's own CPU time, [`thread_cpu_timed`],
//! so that other work on the machine counts less). The goal is an RMSE
//! ratio ≤ 0.5 and a time ratio ≤ 1.1.
//!
//! The references take most of the run; `cache` keeps them in a folder
//! (one file per deck and size, the colours as little-endian f64s), for
//! runs on the same code of the renderer.

use std::path::Path;

use raytrace::options::{Fidelity, Options, Solver, TimeSampler};
use raytrace::raytrace::Prepared;
use raytrace::types::Intensity;

use crate::chart::BLUR_REFERENCE_MASK;
use crate::decks::{prepared, still, BLUR_DECKS};
use crate::measure::{interleaved_medians_of, rmse, thread_cpu_timed};

/// The masks of the goal: 16 and 64 rays a pixel.
pub const GOAL_MASKS: [usize; 2] = [4, 8];

/// One row of the goal's table.
#[derive(Clone, Debug)]
pub struct GoalRow {
    pub deck: &'static str,
    pub mask: usize,
    pub rmse_table: f64,
    pub rmse_adaptive: f64,
    pub secs_table: f64,
    pub secs_adaptive: f64,
}

/// Thesis fidelity, `laguerre`, and `sampler`: the goals' options.
pub fn opts(sampler: TimeSampler) -> Options {
    Options {
        fidelity: Fidelity::Thesis,
        solver: Solver::Laguerre,
        sampler,
        accel: Default::default(),
    }
}

/// The chart's reference of `deck` at `size`², read from `cache` when it
/// holds one, else rendered (and written there).
pub fn reference(deck: &str, size: (usize, usize), cache: Option<&Path>) -> Result<Vec<Intensity>, String> {
    let (w, h) = size;
    let file = cache.map(|d| d.join(format!("{deck}_{w}x{h}_{BLUR_REFERENCE_MASK}.f64")));
    if let Some(bytes) = file.as_ref().and_then(|f| std::fs::read(f).ok()) {
        if bytes.len() == w * h * 24 {
            let f: Vec<f64> = bytes
                .chunks_exact(8)
                .map(|b| f64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
                .collect();
            return Ok(f.chunks_exact(3).map(|c| Intensity::new(c[0], c[1], c[2])).collect());
        }
    }
    let o = opts(TimeSampler::Stratified);
    let scene = prepared(deck, &o, Some((size.0, size.1, BLUR_REFERENCE_MASK)))?;
    eprintln!("{deck}: reference, {BLUR_REFERENCE_MASK}×{BLUR_REFERENCE_MASK} stratified");
    let colours = still(&scene).colours;
    if let Some(f) = &file {
        let bytes: Vec<u8> = colours
            .iter()
            .flat_map(|c| c.to_array())
            .flat_map(f64::to_le_bytes)
            .collect();
        if let Some(dir) = f.parent() {
            std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
        }
        std::fs::write(f, bytes).map_err(|e| format!("{}: {e}", f.display()))?;
    }
    Ok(colours)
}

/// Measures the goal's table at `size`² with `runs` timed rounds.
pub fn measure(size: (usize, usize), runs: usize, cache: Option<&Path>) -> Result<Vec<GoalRow>, String> {
    let one = crate::measure::one_thread()?;
    let (table, adaptive) = (opts(TimeSampler::Table), opts(TimeSampler::Adaptive));
    let mut rows = Vec::new();
    for &deck in BLUR_DECKS {
        let reference = reference(deck, size, cache)?;
        for mask in GOAL_MASKS {
            let t_scene = prepared(deck, &table, Some((size.0, size.1, mask)))?;
            let a_scene = prepared(deck, &adaptive, Some((size.0, size.1, mask)))?;
            let rmse_table = rmse(&still(&t_scene).colours, &reference);
            let rmse_adaptive = rmse(&still(&a_scene).colours, &reference);
            let secs = cpu_medians(&one, &[&t_scene, &a_scene], runs);
            let row = GoalRow {
                deck,
                mask,
                rmse_table,
                rmse_adaptive,
                secs_table: secs[0],
                secs_adaptive: secs[1],
            };
            eprintln!("{}", line(&row));
            rows.push(row);
        }
    }
    Ok(rows)
}

/// The median CPU seconds of each render on the one thread of `pool`,
/// `runs` rounds of all of them in turn after an untimed one (NaN for
/// `runs` 0).
fn cpu_medians(pool: &rayon::ThreadPool, jobs: &[&Prepared], runs: usize) -> Vec<f64> {
    if runs == 0 {
        return vec![f64::NAN; jobs.len()];
    }
    let mut timed: Vec<Box<dyn FnMut() -> Result<f64, String>>> = jobs
        .iter()
        .map(|&scene| {
            Box::new(move || Ok(pool.install(|| thread_cpu_timed(|| drop(std::hint::black_box(still(scene)))).0)))
                as Box<dyn FnMut() -> Result<f64, String>>
        })
        .collect();
    let mut refs: Vec<&mut dyn FnMut() -> Result<f64, String>> = timed.iter_mut().map(|j| j.as_mut() as _).collect();
    interleaved_medians_of(&mut refs, runs).unwrap_or_else(|e| unreachable!("a render never fails: {e}"))
}

/// A row of the goal's Markdown table.
pub fn line(r: &GoalRow) -> String {
    format!(
        "| {} | {} | {:.5} | {:.5} | {:.3} | {:.3} | {:.3} | {:.3} |",
        r.deck,
        r.mask * r.mask,
        r.rmse_table,
        r.rmse_adaptive,
        r.rmse_adaptive / r.rmse_table,
        r.secs_table,
        r.secs_adaptive,
        r.secs_adaptive / r.secs_table
    )
}

/// The goal's Markdown table.
pub fn table(rows: &[GoalRow]) -> String {
    let mut s = String::from(
        "| deck | rays a pixel | RMSE, table | RMSE, adaptive | ratio | CPU s, table | CPU s, adaptive | ratio |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        s.push_str(&line(r));
        s.push('\n');
    }
    s
}

/// `tools goal`: measures and prints the table.
pub fn run(size: (usize, usize), runs: usize, cache: Option<&Path>) -> Result<(), String> {
    let rows = measure(size, runs, cache)?;
    print!("{}", table(&rows));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ratios are adaptive over table, in the columns the header names.
    #[test]
    fn rows_print_the_ratios() {
        let r = GoalRow {
            deck: "fig5_3",
            mask: 4,
            rmse_table: 0.02,
            rmse_adaptive: 0.01,
            secs_table: 2.0,
            secs_adaptive: 2.2,
        };
        assert_eq!(
            line(&r),
            "| fig5_3 | 16 | 0.02000 | 0.01000 | 0.500 | 2.000 | 2.200 | 1.100 |"
        );
        assert!(table(&[r]).starts_with("| deck | rays a pixel |"));
    }
}

//! The speed/accuracy chart's lower panels (`tools chart`): the ways of
//! making pixels from fewer rays (`--sampler sobol`, `--denoise`,
//! `--coherence 4`, the port's extensions) beside the adaptive sampler,
//! on the chart's blur decks and the Cook deck: RMSE against the chart's
//! 1024-ray reference, against one thread's CPU time (the median of
//! interleaved rounds, [`crate::frontier::measure`]) and against the rays
//! a pixel, at 1, 4, 16 and 64 rays a pixel.

use std::fmt::Write as _;
use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use raytrace::options::TimeSampler;
use raytrace::reconstruct::Reconstruction;

use crate::chart::{panel, Series, BLUR_MASKS, SAMPLING_COLOURS};
use crate::decks::BLUR_DECKS;
use crate::frontier::{measure, Point, Way};

/// The decks of the lower panels: the blur decks ([`BLUR_DECKS`]) and
/// Cook's effects (depth of field, soft shadows, gloss).
pub fn decks() -> Vec<&'static str> {
    let mut d = BLUR_DECKS.to_vec();
    d.push("cook");
    d
}

/// The ways of the lower panels, each at the masks of [`BLUR_MASKS`].
pub const WAYS: [Way; 5] = [
    Way {
        label: "adaptive",
        sampler: TimeSampler::Adaptive,
        mask: 1,
        reconstruction: Reconstruction::Box,
    },
    Way {
        label: "sobol",
        sampler: TimeSampler::Sobol,
        mask: 1,
        reconstruction: Reconstruction::Box,
    },
    Way {
        label: "adaptive + denoise",
        sampler: TimeSampler::Adaptive,
        mask: 1,
        reconstruction: Reconstruction::Denoise,
    },
    Way {
        label: "sobol + denoise",
        sampler: TimeSampler::Sobol,
        mask: 1,
        reconstruction: Reconstruction::Denoise,
    },
    Way {
        label: "table + coherence 4",
        sampler: TimeSampler::Table,
        mask: 1,
        reconstruction: Reconstruction::Coherence(4),
    },
];

/// Each way's colour: the upper panels' for the adaptive and the Sobol
/// samplers, the listing table's red and the random sampler's orange
/// (neither is drawn below) for their denoised lines, grey for coherence.
const COLOURS: [RGBColor; 5] = [
    SAMPLING_COLOURS[5],
    SAMPLING_COLOURS[4],
    SAMPLING_COLOURS[0],
    SAMPLING_COLOURS[2],
    RGBColor(90, 90, 90),
];

/// Every way of [`WAYS`] at every mask, on every deck of [`decks`].
pub fn measure_reconstructions(size: (usize, usize), runs: usize, cache: Option<&Path>) -> Result<Vec<Point>, String> {
    let ways: Vec<Way> = WAYS
        .iter()
        .flat_map(|w| BLUR_MASKS.map(|mask| Way { mask, ..*w }))
        .collect();
    let decks: Vec<String> = decks().iter().map(|d| d.to_string()).collect();
    measure(&decks, &ways, size, runs, cache)
}

/// The series of the lower panels, x by `x`: colour by way, marker by deck,
/// the ways named once (on the first deck's lines).
fn series(points: &[Point], x: &dyn Fn(&Point) -> f64) -> Vec<Series> {
    let mut out = Vec::new();
    for (di, deck) in decks().iter().enumerate() {
        for (wi, way) in WAYS.iter().enumerate() {
            let same = |p: &&Point| p.deck == *deck && p.way.label == way.label;
            out.push(Series {
                label: if di == 0 { way.label.to_string() } else { String::new() },
                colour: COLOURS[wi],
                marker: di,
                points: points.iter().filter(same).map(|p| (x(p), p.rmse)).collect(),
            });
        }
    }
    out
}

/// The two lower panels on `area`.
pub fn draw_reconstructions<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    points: &[Point],
    size: (usize, usize),
) -> Result<(), String> {
    let (w, h) = size;
    let (left, right) = area.split_horizontally(area.dim_in_pixel().0 / 2);
    let markers = "markers by deck: circle fig5_3, triangle fig5_9, cross fig5_10, square fig5_12, ring cook";
    panel(
        &left,
        "Fewer rays, reconstructed: error against CPU time",
        "CPU time, s (median, one thread)",
        "RMSE against 1024 samples a pixel",
        &series(points, &|p| p.secs),
        None,
        &format!("{w}×{h}; left to right on each line: 1, 4, 16, 64 rays a pixel; {markers}"),
        Some(SeriesLabelPosition::LowerLeft),
        1.0,
    )?;
    panel(
        &right,
        "Fewer rays, reconstructed: error against rays",
        "primary rays a pixel (adaptive: on average; coherence: of the pixels traced)",
        "RMSE against 1024 samples a pixel",
        &series(points, &|p| (p.way.mask * p.way.mask) as f64),
        None,
        markers,
        None,
        1.0,
    )
}

/// The lower panels' measurements as a Markdown table.
pub fn recon_table(points: &[Point], size: (usize, usize)) -> String {
    let (w, h) = size;
    let mut s = format!(
        "\nReconstructions, {w}×{h} (CPU: median, one thread)\n\n\
         | deck | way | rays a pixel | CPU s | RMSE |\n|---|---|---|---|---|\n"
    );
    for p in points {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.4} | {:.4} |",
            p.deck,
            p.way.label,
            p.way.mask * p.way.mask,
            p.secs,
            p.rmse
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each deck and way is a line of four points, named once; the table
    /// has a row a point.
    #[test]
    fn series_and_table_of_points() {
        let points: Vec<Point> = decks()
            .into_iter()
            .flat_map(|d| {
                WAYS.iter().flat_map(move |w| {
                    BLUR_MASKS.map(|mask| Point {
                        deck: d.to_string(),
                        way: Way { mask, ..*w },
                        rmse: 0.1 / mask as f64,
                        secs: 0.01 * (mask * mask) as f64,
                    })
                })
            })
            .collect();
        let s = series(&points, &|p| p.secs);
        assert_eq!(s.len(), decks().len() * WAYS.len());
        assert!(s.iter().all(|l| l.points.len() == BLUR_MASKS.len()));
        assert_eq!(s.iter().filter(|l| !l.label.is_empty()).count(), WAYS.len());
        assert_eq!(
            recon_table(&points, (96, 96))
                .lines()
                .filter(|l| l.starts_with("| cook"))
                .count(),
            20
        );
    }
}

//! `tools chart`: the speed/accuracy chart, docs/speed_accuracy.png and .svg.
//!
//! Panels 1 and 2, time samplers: for each motion-blurred deck of
//! [`BLUR_DECKS`] and each way of choosing the
//! subpixel times, the RMSE of the float image (`Render::colours`) against
//! a reference of 1024 stratified time samples a pixel (mask 32), against
//! the median render time (all threads; panel 1) and against the rays a
//! pixel (panel 2), at 1, 4, 16 and 64 samples a pixel (mask 1, 2, 4, 8;
//! for `--sampler adaptive`, the same numbers on average).
//!
//! Panel 3, root solvers: for each sweep deck of
//! [`SOLVER_DECKS`] and each solver, the share
//! of silhouette pixels whose colour differs (by more than
//! [`DIFFER`] in a channel) from a reference rendered with the robust
//! solver at mask 16, at masks 1, 2, 4 and 8, against the time per ray
//! (one thread, timed at mask 4: a ray's cost does not depend on the mask).
//!
//! Every render of the chart is `size`×`size` pixels (96 by default), so
//! the whole chart takes a few minutes on two cores.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use raytrace::options::{Fidelity, Options, Solver, TimeSampler};
use raytrace::raytrace::Prepared;
use raytrace::scene::Scene;

use crate::chart_reconstructions::{draw_reconstructions, measure_reconstructions, recon_table};
use crate::decks::{prepared, still, BLUR_DECKS, SOLVER_DECKS};
use crate::frontier::Point;
use crate::measure::{differing, interleaved_medians, is_sweep, probe_objects, rmse, silhouette};

/// One way of choosing the subpixel times.
#[derive(Clone, Copy, Debug)]
pub struct Sampling {
    pub label: &'static str,
    pub fidelity: Fidelity,
    pub sampler: TimeSampler,
}

/// The six samplers of panels 1 and 2: the listing's table (times
/// `pattern·0.1`, up to 6.3 at mask 8: erratum 2, so its error is large by
/// design), the thesis's table with the CLT jitter of the deck's `blur`,
/// plain random times, stratified times, scrambled Sobol points and the
/// adaptive sampler (the last two the port's extensions,
/// `raytrace::sampler`, `raytrace::adaptive`).
pub const SAMPLINGS: [Sampling; 6] = [
    Sampling {
        label: "listing table",
        fidelity: Fidelity::Listing,
        sampler: TimeSampler::Table,
    },
    Sampling {
        label: "thesis table + CLT",
        fidelity: Fidelity::Thesis,
        sampler: TimeSampler::Table,
    },
    Sampling {
        label: "random",
        fidelity: Fidelity::Thesis,
        sampler: TimeSampler::Random,
    },
    Sampling {
        label: "stratified",
        fidelity: Fidelity::Thesis,
        sampler: TimeSampler::Stratified,
    },
    Sampling {
        label: "sobol",
        fidelity: Fidelity::Thesis,
        sampler: TimeSampler::Sobol,
    },
    Sampling {
        label: "adaptive",
        fidelity: Fidelity::Thesis,
        sampler: TimeSampler::Adaptive,
    },
];

/// The masks of panels 1 and 2: 1, 4, 16 and 64 samples a pixel.
pub const BLUR_MASKS: [usize; 4] = [1, 2, 4, 8];
/// Panels 1 and 2's reference: 32×32 = 1024 stratified time samples a pixel.
pub const BLUR_REFERENCE_MASK: usize = 32;
/// The masks of panel 3.
pub const SOLVER_MASKS: [usize; 4] = [1, 2, 4, 8];
/// The mask of panel 3's timing renders.
pub const TIMING_MASK: usize = 4;
/// Panel 3's reference: the robust solver at 16×16 rays a pixel.
pub const SOLVER_REFERENCE_MASK: usize = 16;
/// The probe rays a pixel (k×k) that decide which pixels are silhouette.
pub const PROBE: usize = 8;
/// A pixel differs when some channel is off by more than this (about 13
/// steps of an 8-bit channel: well above the noise of the shading, well
/// below a coverage change of one subpixel in four on a silhouette).
pub const DIFFER: f64 = 0.05;

/// A point of panels 1 and 2.
#[derive(Clone, Debug)]
pub struct BlurPoint {
    pub deck: &'static str,
    pub sampling: usize,
    pub mask: usize,
    pub secs: f64,
    pub rmse: f64,
}

/// A point of panel 3.
#[derive(Clone, Debug)]
pub struct SolverPoint {
    pub deck: &'static str,
    pub solver: Solver,
    pub mask: usize,
    /// Median render time over all rays traced, one thread.
    pub secs_per_ray: f64,
    pub silhouette: usize,
    /// Silhouette pixels differing from the reference.
    pub differ_silhouette: usize,
    /// All pixels differing from the reference.
    pub differ_all: usize,
    /// Silhouette pixels differing from the robust solver's image at the
    /// same mask (the same rays): the solver's own share.
    pub differ_same_rays: usize,
}

fn opts(fidelity: Fidelity, solver: Solver, sampler: TimeSampler) -> Options {
    Options {
        fidelity,
        solver,
        sampler,
        accel: Default::default(),
    }
}

/// Panels 1 and 2's measurements: the error of each render, then the times,
/// `runs` interleaved rounds over every render.
pub fn measure_blur(size: (usize, usize), runs: usize, cache: Option<&Path>) -> Result<Vec<BlurPoint>, String> {
    let mut out = Vec::new();
    let mut jobs: Vec<Prepared> = Vec::new();
    for &deck in BLUR_DECKS {
        let reference = crate::goal::reference(deck, size, cache)?;
        for (si, s) in SAMPLINGS.iter().enumerate() {
            let o = opts(s.fidelity, Solver::Laguerre, s.sampler);
            for mask in BLUR_MASKS {
                let scene = prepared(deck, &o, Some((size.0, size.1, mask)))?;
                let e = rmse(&still(&scene).colours, &reference);
                out.push(BlurPoint {
                    deck,
                    sampling: si,
                    mask,
                    secs: f64::NAN,
                    rmse: e,
                });
                jobs.push(scene);
            }
        }
    }
    eprintln!("timing {} renders, {runs} rounds", jobs.len());
    let mut closures: Vec<Box<dyn FnMut()>> = jobs
        .iter()
        .map(|scene| Box::new(move || drop(std::hint::black_box(still(scene)))) as Box<dyn FnMut()>)
        .collect();
    let mut refs: Vec<&mut dyn FnMut()> = closures.iter_mut().map(|c| c.as_mut() as &mut dyn FnMut()).collect();
    let secs = interleaved_medians(&mut refs, runs);
    for (p, t) in out.iter_mut().zip(secs) {
        p.secs = t;
        eprintln!(
            "{}: {:<20} {:>3} spp: {t:.4} s, RMSE {:.5}",
            p.deck,
            SAMPLINGS[p.sampling].label,
            p.mask * p.mask,
            p.rmse
        );
    }
    Ok(out)
}

/// The indices of a scene's sweep objects.
fn sweeps_of(scene: &Scene) -> Vec<usize> {
    (0..scene.objects.len())
        .filter(|&i| is_sweep(scene.objects[i].class))
        .collect()
}

/// Panel 3's measurements.
pub fn measure_solvers(size: (usize, usize), runs: usize) -> Result<Vec<SolverPoint>, String> {
    let one = crate::measure::one_thread()?;
    let mut out = Vec::new();
    for &deck in SOLVER_DECKS {
        let robust = opts(Fidelity::Thesis, Solver::Robust, TimeSampler::Table);
        let ref_scene = prepared(deck, &robust, Some((size.0, size.1, SOLVER_REFERENCE_MASK)))?;
        eprintln!("{deck}: reference, robust at {SOLVER_REFERENCE_MASK}×{SOLVER_REFERENCE_MASK}");
        let reference = still(&ref_scene).colours;
        let sweeps = sweeps_of(ref_scene.scene());
        let seen = probe_objects(&ref_scene, PROBE);
        let sil = silhouette(&seen, |o| sweeps.contains(&o));
        let count = |v: &[bool], only_sil: bool| v.iter().zip(&sil).filter(|(d, s)| **d && (**s || !only_sil)).count();
        let n_sil = sil.iter().filter(|s| **s).count();
        // The cost of a ray is the solver's and the deck's, not the mask's:
        // one timing a solver, on renders at TIMING_MASK, the two solvers
        // interleaved.
        let solver_opts = [Solver::Laguerre, Solver::Robust].map(|s| opts(Fidelity::Thesis, s, TimeSampler::Table));
        let (lag, rob) = (
            prepared(deck, &solver_opts[0], Some((size.0, size.1, TIMING_MASK)))?,
            prepared(deck, &solver_opts[1], Some((size.0, size.1, TIMING_MASK)))?,
        );
        let rays = [&lag, &rob].map(|p| still(p).stats.rays.max(1));
        let secs = one.install(|| {
            interleaved_medians(
                &mut [&mut || drop(std::hint::black_box(still(&lag))), &mut || {
                    drop(std::hint::black_box(still(&rob)))
                }],
                runs,
            )
        });
        let per_ray = [secs[0] / rays[0] as f64, secs[1] / rays[1] as f64];
        for mask in SOLVER_MASKS {
            let robust_img = still(&prepared(deck, &robust, Some((size.0, size.1, mask)))?).colours;
            for (k, solver) in [Solver::Laguerre, Solver::Robust].into_iter().enumerate() {
                let o = opts(Fidelity::Thesis, solver, TimeSampler::Table);
                let img = still(&prepared(deck, &o, Some((size.0, size.1, mask)))?).colours;
                let d_ref = differing(&img, &reference, DIFFER);
                let d_same = differing(&img, &robust_img, DIFFER);
                let p = SolverPoint {
                    deck,
                    solver,
                    mask,
                    secs_per_ray: per_ray[k],
                    silhouette: n_sil,
                    differ_silhouette: count(&d_ref, true),
                    differ_all: count(&d_ref, false),
                    differ_same_rays: count(&d_same, true),
                };
                eprintln!(
                    "{deck}: {solver:?} mask {mask}: {:.3} µs/ray, {}/{} silhouette px differ ({} same rays), {} px in all",
                    p.secs_per_ray * 1e6,
                    p.differ_silhouette,
                    p.silhouette,
                    p.differ_same_rays,
                    p.differ_all
                );
                out.push(p);
            }
        }
    }
    Ok(out)
}

/// The chart's size in pixels.
const WIDTH: u32 = 2100;
const HEIGHT: u32 = 1400;

/// Each sampler's colour, by its place in [`SAMPLINGS`].
pub(crate) const SAMPLING_COLOURS: [RGBColor; 6] = [
    RGBColor(200, 40, 40),
    RGBColor(40, 90, 200),
    RGBColor(230, 140, 20),
    RGBColor(30, 150, 60),
    RGBColor(0, 170, 190),
    RGBColor(140, 50, 170),
];
const SOLVER_COLOURS: [RGBColor; 2] = [RGBColor(200, 40, 40), RGBColor(40, 90, 200)];

/// A log range holding every value with a margin; 0 and below are left out.
fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !(lo.is_finite() && hi > 0.0) {
        return (1e-3, 1.0);
    }
    (lo / 1.6, hi * 1.6)
}

/// A log axis's tick label: 1, 2 and 5 times a power of ten, in as few
/// digits as they need; the other ticks stay unlabelled.
fn tick(v: f64) -> String {
    if !(v > 0.0 && v.is_finite()) {
        return String::new();
    }
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    let lead = [1.0, 2.0, 5.0].into_iter().find(|d| (m - d).abs() < 1e-6 * d);
    match lead {
        Some(d) => {
            let decimals = if e < 0.0 { (-e) as usize } else { 0 };
            format!("{:.*}", decimals, d * 10f64.powf(e))
        }
        None => String::new(),
    }
}

/// One series of a panel: its label, colour, marker and points.
pub(crate) struct Series {
    pub(crate) label: String,
    pub(crate) colour: RGBColor,
    pub(crate) marker: usize,
    pub(crate) points: Vec<(f64, f64)>,
}

/// A log-log panel of `series` on `area`: `floor` is where a value of 0
/// is drawn, `note` the line under it, `legend` where the series are
/// named (none: not named), `x_room` how far the x axis reaches past the
/// last point (room for a legend). `tools scale` draws its panels so too.
#[allow(clippy::too_many_arguments)]
pub(crate) fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    series: &[Series],
    floor: Option<f64>,
    note: &str,
    legend: Option<SeriesLabelPosition>,
    x_room: f64,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| format!("{e:?}");
    let (area, strip) = area.split_vertically(area.dim_in_pixel().1 - 28);
    let area = &area;
    let (x0, x1) = log_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.0)));
    let x1 = x1 * x_room;
    let (mut y0, y1) = log_range(series.iter().flat_map(|s| s.points.iter().map(|p| p.1)));
    if let Some(f) = floor {
        y0 = y0.min(f / 1.6);
    }
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(70)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .label_style(("sans-serif", 14))
        .bold_line_style(BLACK.mix(0.2))
        // No light lines: on a log axis plotters draws them every tenth of
        // a decade, a grey band near the decade's top.
        .light_line_style(WHITE.mix(0.0))
        .axis_desc_style(("sans-serif", 15))
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .draw()
        .map_err(err)?;
    for s in series {
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .map(|&(x, y)| (x, if y > 0.0 { y } else { floor.unwrap_or(y0) }))
            .collect();
        let (colour, m) = (s.colour, s.marker);
        let line = chart
            .draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))
            .map_err(err)?;
        // Only a panel with a legend labels its series, and only those
        // with a label.
        if legend.is_some() && !s.label.is_empty() {
            line.label(s.label.clone()).legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(-6, 0), (14, 0)], colour.stroke_width(2))
                    + Circle::new((4, 0), if m == 0 { 4 } else { 0 }, colour.filled())
                    + TriangleMarker::new((4, 0), if m == 1 { 6 } else { 0 }, colour.filled())
                    + Cross::new((4, 0), if m == 2 { 5 } else { 0 }, colour.stroke_width(2))
                    + Circle::new((4, 0), if m == 4 { 4 } else { 0 }, colour.stroke_width(2))
                    + Rectangle::new(
                        [(0, -4), (8, 4)],
                        if m == 3 {
                            colour.filled()
                        } else {
                            colour.mix(0.0).filled()
                        },
                    )
            });
        }
        // The markers: filled circle, triangle, cross, square, ring, by deck.
        let fill = colour.filled();
        let at = pts.iter().copied();
        match m % 5 {
            0 => chart.draw_series(at.map(|p| Circle::new(p, 5, fill))).map(|_| ()),
            1 => chart
                .draw_series(at.map(|p| TriangleMarker::new(p, 7, fill)))
                .map(|_| ()),
            2 => chart
                .draw_series(at.map(|p| Cross::new(p, 6, colour.stroke_width(2))))
                .map(|_| ()),
            3 => chart
                .draw_series(at.map(|p| EmptyElement::at(p) + Rectangle::new([(-5, -5), (5, 5)], fill)))
                .map(|_| ()),
            _ => chart
                .draw_series(at.map(|p| Circle::new(p, 6, colour.stroke_width(2))))
                .map(|_| ()),
        }
        .map_err(err)?;
    }
    if let Some(legend) = legend {
        chart
            .configure_series_labels()
            .position(legend)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.4))
            .label_font(("sans-serif", 12))
            .draw()
            .map_err(err)?;
    }
    strip
        .draw(&Text::new(
            note.to_string(),
            (24, 4),
            ("sans-serif", 13).into_font().color(&BLACK.mix(0.75)),
        ))
        .map_err(err)?;
    Ok(())
}

/// Draws the five panels on `root`: the time samplers and the root
/// solvers above, the reconstructions below.
pub fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    blur: &[BlurPoint],
    solvers: &[SolverPoint],
    recon: &[Point],
    size: (usize, usize),
) -> Result<(), String> {
    let (w, h) = size;
    root.fill(&WHITE).map_err(|e| format!("{e:?}"))?;
    let (top, bottom) = root.split_vertically(HEIGHT / 2);
    draw_reconstructions(&bottom, recon, size)?;
    let (left, rest) = top.split_horizontally(WIDTH / 3);
    let (middle, right) = rest.split_horizontally(WIDTH / 3);
    let blur_series = |x: &dyn Fn(&BlurPoint) -> f64| {
        let mut series = Vec::new();
        for (di, &deck) in BLUR_DECKS.iter().enumerate() {
            for (si, s) in SAMPLINGS.iter().enumerate() {
                let points: Vec<(f64, f64)> = blur
                    .iter()
                    .filter(|p| p.deck == deck && p.sampling == si)
                    .map(|p| (x(p), p.rmse))
                    .collect();
                series.push(Series {
                    label: format!("{deck} · {}", s.label),
                    colour: SAMPLING_COLOURS[si],
                    marker: di,
                    points,
                });
            }
        }
        series
    };
    panel(
        &left,
        "Time samplers: error against render time",
        "render time, s (median, 2 threads)",
        "RMSE against 1024 samples a pixel",
        &blur_series(&|p| p.secs),
        None,
        &format!("{w}×{h} pixels; left to right on each line: 1, 4, 16, 64 samples a pixel"),
        Some(SeriesLabelPosition::LowerLeft),
        1.0,
    )?;
    panel(
        &middle,
        "Time samplers: error against rays",
        "primary rays a pixel (adaptive: on average)",
        "RMSE against 1024 samples a pixel",
        &blur_series(&|p| (p.mask * p.mask) as f64),
        None,
        "markers by deck as in the left panel: circle fig5_3, triangle fig5_9, cross fig5_10, square fig5_12",
        None,
        1.0,
    )?;
    let mut s2 = Vec::new();
    for (di, &deck) in SOLVER_DECKS.iter().enumerate() {
        for (ki, solver) in [Solver::Laguerre, Solver::Robust].into_iter().enumerate() {
            let points: Vec<(f64, f64)> = solvers
                .iter()
                .filter(|p| p.deck == deck && p.solver == solver)
                .map(|p| {
                    (
                        p.secs_per_ray * 1e6,
                        100.0 * p.differ_silhouette as f64 / p.silhouette.max(1) as f64,
                    )
                })
                .collect();
            s2.push(Series {
                label: format!(
                    "{deck} · {}",
                    if solver == Solver::Laguerre {
                        "laguerre"
                    } else {
                        "robust"
                    }
                ),
                colour: SOLVER_COLOURS[ki],
                marker: di,
                points,
            });
        }
    }
    let floor = s2
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .filter(|v| *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    panel(
        &right,
        "Root solvers: silhouette errors against cost",
        "time per ray, µs (median, one thread)",
        "silhouette pixels differing from the reference, %",
        &s2,
        floor.is_finite().then_some(floor / 2.0),
        &format!(
            "{w}×{h}; top to bottom on each line: 1, 4, 16, 64 rays a pixel; reference: robust, 256 rays a pixel; 0 drawn at the bottom"
        ),
        Some(SeriesLabelPosition::UpperRight),
        3.0,
    )?;
    root.present().map_err(|e| format!("{e:?}"))
}

/// Measures, prints the figures, and writes `dir`/speed_accuracy.png and
/// .svg; `cache` keeps the blur decks' references between runs.
pub fn run(dir: &Path, size: (usize, usize), runs: usize, cache: Option<&Path>) -> Result<(), String> {
    crate::fonts::register()?;
    let blur = measure_blur(size, runs, cache)?;
    let solvers = measure_solvers(size, runs)?;
    let recon = measure_reconstructions(size, runs, cache)?;
    print!("{}", tables(&blur, &solvers, size));
    print!("{}", recon_table(&recon, size));
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let png = dir.join("speed_accuracy.png");
    let mut buf = vec![0u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        draw(&root, &blur, &solvers, &recon, size)?;
    }
    image::save_buffer(&png, &buf, WIDTH, HEIGHT, image::ExtendedColorType::Rgb8)
        .map_err(|e| format!("{}: {e}", png.display()))?;
    let svg = dir.join("speed_accuracy.svg");
    {
        let root = SVGBackend::new(&svg, (WIDTH, HEIGHT)).into_drawing_area();
        draw(&root, &blur, &solvers, &recon, size)?;
    }
    println!("wrote {} and {}", png.display(), svg.display());
    Ok(())
}

/// The measurements as Markdown tables.
pub fn tables(blur: &[BlurPoint], solvers: &[SolverPoint], size: (usize, usize)) -> String {
    let (w, h) = size;
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "\nTime samplers, {w}×{h} (render time: median, all threads)\n");
    let _ = writeln!(s, "| deck | sampler | samples a pixel | render time (s) | RMSE |");
    let _ = writeln!(s, "|---|---|---|---|---|");
    for p in blur {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.4} | {:.4} |",
            p.deck,
            SAMPLINGS[p.sampling].label,
            p.mask * p.mask,
            p.secs,
            p.rmse
        );
    }
    let _ = writeln!(s, "\nRoot solvers, {w}×{h} (time per ray: median, one thread)\n");
    let _ = writeln!(
        s,
        "| deck | solver | mask | µs a ray | silhouette pixels | differ from reference | same rays as robust: differ | all pixels differing |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    for p in solvers {
        let _ = writeln!(
            s,
            "| {} | {:?} | {} | {:.3} | {} | {} ({:.1} %) | {} | {} |",
            p.deck,
            p.solver,
            p.mask,
            p.secs_per_ray * 1e6,
            p.silhouette,
            p.differ_silhouette,
            100.0 * p.differ_silhouette as f64 / p.silhouette.max(1) as f64,
            p.differ_same_rays,
            p.differ_all
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_label_1_2_5() {
        assert_eq!(tick(0.01), "0.01");
        assert_eq!(tick(0.05), "0.05");
        assert_eq!(tick(2.0), "2");
        assert_eq!(tick(100.0), "100");
        assert_eq!(tick(0.03), "");
        assert_eq!(tick(0.0), "");
    }

    #[test]
    fn log_range_brackets_the_positive_values() {
        let (lo, hi) = log_range([0.0, 0.01, 2.0, f64::NAN].into_iter());
        assert!(lo < 0.01 && lo > 0.001 && hi > 2.0 && hi < 4.0);
        assert_eq!(log_range([0.0].into_iter()), (1e-3, 1.0));
    }

    /// The chart draws from made-up points without error, into a buffer.
    #[test]
    fn draws_from_points() {
        crate::fonts::register().unwrap();
        let blur: Vec<BlurPoint> = (0..SAMPLINGS.len())
            .flat_map(|s| {
                BLUR_MASKS.map(|m| BlurPoint {
                    deck: BLUR_DECKS[0],
                    sampling: s,
                    mask: m,
                    secs: 0.001 * (m * m) as f64,
                    rmse: 0.1 / m as f64,
                })
            })
            .collect();
        let solvers: Vec<SolverPoint> = SOLVER_MASKS
            .iter()
            .map(|&m| SolverPoint {
                deck: SOLVER_DECKS[0],
                solver: Solver::Laguerre,
                mask: m,
                secs_per_ray: 1e-6,
                silhouette: 100,
                differ_silhouette: 10 / m,
                differ_all: 12,
                differ_same_rays: 1,
            })
            .collect();
        let mut buf = vec![0u8; (WIDTH * HEIGHT * 3) as usize];
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        let recon: Vec<Point> = BLUR_MASKS
            .map(|mask| Point {
                deck: "cook".into(),
                way: crate::frontier::Way {
                    mask,
                    ..crate::chart_reconstructions::WAYS[2]
                },
                rmse: 0.05 / mask as f64,
                secs: 0.002 * (mask * mask) as f64,
            })
            .to_vec();
        draw(&root, &blur, &solvers, &recon, (96, 96)).unwrap();
        drop(root);
        // Something other than white was drawn: the axes, text, lines.
        assert!(buf.iter().any(|&b| b < 128));
    }
}

//! The scanline loop of the main program (OCR lines 3100–3215) for the
//! samplers of the subpixel grid: every subpixel of a block of `masksize`
//! scanlines traced in the listing's order, then `antialias` of the block
//! into a row of final pixels.

use std::ops::Range;

use rayon::prelude::*;

use super::tracer::{Instant, Tracer};
use super::{Camera, Prepared, Traced};
use crate::film::Frame;
use crate::options::Fidelity;
use crate::reconstruct::Gathered;
use crate::sampler::{GridKind, GridSampler, Sampler};
use crate::trace::TraceStats;
use crate::types::{Intensity, Ray};

/// The rows `rows` of final pixels, each from its `masksize` scanlines of
/// subpixels ([`scan_row`]). `progress` is called once per finished row
/// (from worker threads).
pub(super) fn render_grid(
    prepared: &Prepared,
    kind: GridKind,
    frame: Frame,
    rows: Range<usize>,
    progress: &(dyn Fn() + Sync),
) -> Traced {
    let img = &prepared.scene().image;
    let (w, m) = (img.width, img.masksize);
    let mut pixels = vec![Intensity::ZERO; w * rows.len()];
    let stats = by_rows(prepared, &mut pixels, w, rows, |tracer, line, out, row| {
        // Each pixel's sum over its m subpixel columns of one scanline,
        // the scanlines in turn: the sums `antialias` reads.
        let mut virtual_rows = Vec::with_capacity(m * w);
        let shoot = |instant: &mut Instant, aray: &Ray, sampler: &mut GridSampler| instant.shoot(aray, sampler);
        scan_row(prepared, tracer, line, kind, frame, row, shoot, |columns| {
            let sums = columns
                .chunks_exact(m)
                .map(|pixel| pixel.iter().fold(Intensity::ZERO, |s, &c| s + c));
            virtual_rows.extend(sums);
        });
        antialias(&virtual_rows, m, out);
        progress();
    });
    Traced {
        counts: vec![(m * m) as u32; pixels.len()],
        colours: pixels,
        stats,
    }
}

/// As [`render_grid`], each pixel's samples gathered with their features
/// ([`Gathered`]) for a reconstruction that reads them, not averaged.
/// `progress` is called for each finished row in `told`.
pub(super) fn gather_grid(
    prepared: &Prepared,
    kind: GridKind,
    frame: Frame,
    rows: Range<usize>,
    told: Range<usize>,
    progress: &(dyn Fn() + Sync),
) -> (Vec<Gathered>, TraceStats) {
    let img = &prepared.scene().image;
    let (w, m) = (img.width, img.masksize);
    let mut pixels = vec![Gathered::default(); w * rows.len()];
    let stats = by_rows(prepared, &mut pixels, w, rows, |tracer, line, out, row| {
        let shoot =
            |instant: &mut Instant, aray: &Ray, sampler: &mut GridSampler| instant.shoot_features(aray, sampler);
        scan_row(prepared, tracer, line, kind, frame, row, shoot, |columns| {
            for (pixel, samples) in out.iter_mut().zip(columns.chunks_exact(m)) {
                for (colour, features) in samples {
                    pixel.add(*colour, features);
                }
            }
        });
        if told.contains(&row) {
            progress();
        }
    });
    (pixels, stats)
}

/// `row` for each row of `rows` (its `width` pixels in `pixels`, which
/// holds the rows in order), the rows in parallel, each worker tracing
/// its rows with one [`Tracer`] (the poses it keeps are the instants',
/// whichever row asks) and one line of samples ([`scan_row`]); the rows'
/// counts summed.
fn by_rows<T: Send, S: Send>(
    prepared: &Prepared,
    pixels: &mut [T],
    width: usize,
    rows: Range<usize>,
    row: impl Fn(&mut Tracer, &mut Vec<S>, &mut [T], usize) + Sync,
) -> TraceStats {
    let per_row: Vec<TraceStats> = pixels
        .par_chunks_mut(width)
        .zip(rows)
        .map_init(
            || (Tracer::new(prepared), Vec::new()),
            |(tracer, line), (out, r)| {
                row(tracer, line, out, r);
                std::mem::take(&mut tracer.stats)
            },
        )
        .collect();
    let mut stats = TraceStats::default();
    for s in per_row {
        stats += s;
    }
    stats
}

/// Traces the subpixels of row `row` of final pixels with `tracer` (its
/// counts added to), laid by the grid sampler `kind`, posing the scene
/// at each one's time: `shoot` traces each primary ray, and `take` is
/// given each of the row's `masksize` scanlines in turn, its samples in
/// `line` in the order of their columns from 1 (erratum 13's column 0,
/// traced, is not given).
///
/// The listing traces a scanline's subpixels in turn, each at its own
/// instant. Where they share few instants, each instant's subpixels are
/// traced together, the scene posed and its snapshot made once an
/// instant: with nothing that moves, all at one; with the table's times
/// repeating ([`Prepared::repeats`]: `blur 0`, or the listing, erratum
/// 2), a subpixel's time is the table's at its column mod `masksize`,
/// so at `masksize` instants a scanline. A sample depends on its
/// subpixel alone, never on the order they are traced in, and `take`
/// sees them in the listing's order.
///
/// Erratum 13: the listing's column loop runs `for scancol := quickx to
/// quickx2` with `quickx = 0`, tracing one column more than the raster
/// has; `listing` fidelity traces it (and `antialias` never reads it),
/// `thesis` fidelity starts at 1.
#[allow(clippy::too_many_arguments)]
fn scan_row<S: Copy + Default>(
    prepared: &Prepared,
    tracer: &mut Tracer,
    line: &mut Vec<S>,
    kind: GridKind,
    frame: Frame,
    row: usize,
    mut shoot: impl FnMut(&mut Instant, &Ray, &mut GridSampler) -> S,
    mut take: impl FnMut(&[S]),
) {
    let opts = prepared.options();
    let img = &prepared.scene().image;
    let (w, m) = (img.width, img.masksize);
    let camera = prepared.camera();
    let first_col = match opts.fidelity {
        Fidelity::Listing => 0,
        Fidelity::Thesis => 1,
    };
    let last_col = w * m;
    let timed = prepared.timed();
    // The instants a scanline's subpixels share, if few.
    let instants = if !timed {
        Some(1)
    } else if kind == GridKind::Table && prepared.repeats() {
        Some(m)
    } else {
        None
    };
    let mut sampler = GridSampler::new(prepared.tables(), kind, opts.fidelity, w, m, img.aliasing);
    sampler.start_row(row);
    line.resize(last_col + 1 - first_col, S::default());
    for sub in 0..m {
        let scanline = row * m + sub + 1;
        let Some(n) = instants else {
            for scancol in first_col..=last_col {
                let aray = primary_ray(camera, &mut sampler, scanline, scancol);
                tracer.at(frame.time(sampler.time()));
                line[scancol - first_col] = shoot(&mut tracer.instant(), &aray, &mut sampler);
            }
            take(&line[1 - first_col..]);
            continue;
        };
        // The columns of each instant: first_col + i, first_col + i + n, …
        for i in 0..n {
            let first = first_col + i;
            if timed {
                sampler.start(scanline, first);
                tracer.at(frame.time(sampler.time()));
            }
            let mut instant = tracer.instant();
            // (`step_by` takes three times the instructions a column.)
            let mut scancol = first;
            while scancol <= last_col {
                let aray = primary_ray(camera, &mut sampler, scanline, scancol);
                line[scancol - first_col] = shoot(&mut instant, &aray, &mut sampler);
                scancol += n;
            }
        }
        take(&line[1 - first_col..]);
    }
}

/// The primary ray of subpixel (`scanline`, `scancol`), its sample
/// started in `sampler`.
#[inline(always)]
fn primary_ray(camera: &Camera, sampler: &mut GridSampler, scanline: usize, scancol: usize) -> Ray {
    sampler.start(scanline, scancol);
    camera.ray_of(sampler.camera(), sampler)
}

/// `antialias(1, i4, acthighx, i4)`: one row of final pixels from the
/// `masksize` scanlines of subpixels above it. Reconstructed: the box
/// filter, the mean of the masksize × masksize subpixels of each pixel
/// (§2.1.3 (2), supersampling). `sums` holds, for each of the `m` subpixel
/// rows, each pixel's sum over its `m` subpixel columns.
fn antialias(sums: &[Intensity], m: usize, out: &mut [Intensity]) {
    let width = out.len();
    for (x, px) in out.iter_mut().enumerate() {
        let total: Intensity = (0..m).map(|sub| sums[sub * width + x]).sum();
        *px = total / (m * m) as f64;
    }
}

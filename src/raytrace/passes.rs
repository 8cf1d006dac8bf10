//! The scanline loop of `--sampler adaptive` (the port's extension, see
//! [`crate::adaptive`]): a first pass of a few rays a pixel, then the
//! passes that deal out the rest of the deck's budget of `masksize`² rays a
//! pixel by need.

use rayon::prelude::*;

use super::tracer::{Shot, Tracer};
use super::{Prepared, Traced};
use crate::adaptive::{self, PixelSum};
use crate::film::Frame;
use crate::reconstruct::Gathered;
use crate::sampler::{PixelSampler, PixelSamples, Sampler};
use crate::trace::TraceStats;

/// Each sample is a place in the pixel and a time from the pixel's
/// [`PixelSamples`]; a row is traced instant by instant (the times its
/// pixels share), the scene posed once an instant ([`Tracer::at`]) and
/// each due pixel's ray shot at it ([`Tracer::shoot`]); a pixel is the mean
/// of its samples (the box filter of `antialias`). `progress` is called for
/// each row of the last pass.
pub(super) fn render_adaptive(prepared: &Prepared, frame: Frame, progress: &(dyn Fn() + Sync)) -> Traced {
    passes::<()>(prepared, frame, progress).0
}

/// As [`render_adaptive`], each pixel's samples also gathered with their
/// features ([`Gathered`]) for a reconstruction that reads them.
pub(super) fn gather_adaptive(
    prepared: &Prepared,
    frame: Frame,
    progress: &(dyn Fn() + Sync),
) -> (Vec<Gathered>, Traced) {
    let (traced, gathered) = passes::<Gathered>(prepared, frame, progress);
    (gathered, traced)
}

/// The passes of [`render_adaptive`], each sample shot by `S` (into a
/// pixel's `S` beside its sum).
fn passes<S: Shot>(prepared: &Prepared, frame: Frame, progress: &(dyn Fn() + Sync)) -> (Traced, Vec<S>) {
    let img = &prepared.scene().image;
    let (w, m) = (img.width, img.masksize);
    let budget = (m * m) as u32;
    let first = adaptive::first_pass(m);
    let mut sums = vec![PixelSum::default(); w * img.height];
    // Each pixel's samples before the pass and due by its end.
    let mut start = vec![0; sums.len()];
    let mut counts = vec![first; sums.len()];
    // The first pass, then the passes that have rays to deal out (none
    // for a budget of one ray).
    let mut passes = vec![0];
    passes.extend(
        adaptive::later_passes(sums.len(), budget, first)
            .into_iter()
            .filter(|&e| e > 0),
    );
    let samples: Vec<_> = (0..sums.len()).map(|i| PixelSamples::new(i, w)).collect();
    let mut allocation = adaptive::Allocation::new(w);
    let mut shots = vec![S::default(); sums.len()];
    let mut stats = TraceStats::default();
    for (pass, &extra) in passes.iter().enumerate() {
        if pass > 0 {
            let next = allocation.allocate(&sums, budget, extra, adaptive::quantum(budget));
            start = std::mem::replace(&mut counts, next);
        }
        let last = pass + 1 == passes.len();
        let rows: Vec<TraceStats> = sums
            .par_chunks_mut(w)
            .zip(shots.par_chunks_mut(w))
            .zip(start.par_chunks(w).zip(counts.par_chunks(w)))
            .zip(samples.par_chunks(w))
            .enumerate()
            .map_init(
                adaptive::DueByInstant::default,
                |due, (row, (((sums, shots), (start, counts)), samples))| {
                    let pixels = Pixels {
                        sums,
                        shots,
                        start,
                        counts,
                        samples,
                    };
                    let stats = trace_row(prepared, frame, row, pixels, due);
                    if last {
                        progress();
                    }
                    stats
                },
            )
            .collect();
        for s in rows {
            stats += s;
        }
    }
    let traced = Traced {
        colours: sums.iter().map(PixelSum::mean).collect(),
        counts,
        stats,
    };
    (traced, shots)
}

/// A row's pixels in a pass: their sums, what `S` keeps of their
/// samples, their counts before the pass and due by its end, and their
/// samples.
struct Pixels<'a, S> {
    sums: &'a mut [PixelSum],
    shots: &'a mut [S],
    start: &'a [u32],
    counts: &'a [u32],
    samples: &'a [PixelSamples],
}

/// One pass over row `row`: its due samples instant by instant, the
/// scene posed once an instant ([`adaptive::DueByInstant`]). Each
/// pixel's sum gets its samples' colours and the polynomial searches they
/// made (their cost). `due` holds the sort's buffers, kept from row to
/// row.
fn trace_row<S: Shot>(
    prepared: &Prepared,
    frame: Frame,
    row: usize,
    pixels: Pixels<S>,
    due: &mut adaptive::DueByInstant,
) -> TraceStats {
    let Pixels {
        sums,
        shots,
        start,
        counts,
        samples,
    } = pixels;
    let img = &prepared.scene().image;
    let camera = prepared.camera();
    let timed = prepared.timed();
    let mut tracer = Tracer::new(prepared);
    let mut sampler = PixelSampler::new(samples, row, img.width, img.masksize);
    for instant in due.sort(samples, start, counts) {
        if timed {
            // The scene posed once an instant, at its time, which its
            // samples share.
            let (x, j) = instant[0];
            sampler.start(x as usize, j);
            tracer.at(frame.time(sampler.time()));
        }
        for &(x, j) in instant {
            let x = x as usize;
            sampler.start(x, j);
            let c = sampler.camera();
            let aray = camera.ray_of(c, &mut sampler);
            let before = tracer.stats.searched;
            sums[x].add(shots[x].shoot(&mut tracer, &aray, &mut sampler));
            sums[x].add_searched(tracer.stats.searched - before);
        }
    }
    tracer.stats
}

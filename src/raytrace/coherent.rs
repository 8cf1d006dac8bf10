//! `--coherence N`: the scanline loop's pixels traced only where the
//! thesis's coherence ([`crate::coherence`], §2.1.2 (2)(a), Badt 88) asks,
//! each traced pixel exactly as the scanline loop traces it (its
//! `masksize`² subpixels with the grid sampler, `antialias`'s mean), the
//! rest interpolated.

use std::ops::Range;

use rayon::prelude::*;

use super::tracer::Tracer;
use super::{Prepared, RenderError, Traced};
use crate::coherence::{reconstruct, Lattice, Value};
use crate::film::Frame;
use crate::reconstruct::Gathered;
use crate::sampler::{GridKind, GridSampler, Layout, Sampler};
use crate::trace::TraceStats;
use crate::types::Intensity;

/// The rows `rows` of frame `frame` with every `step`-th pixel traced
/// and the rest as coherence says; the cells the rows cross are worked
/// out whole ([`Lattice::rows`]), so a band is the whole picture's band.
/// `progress` is called once for each row at the end. Not for
/// `--sampler adaptive`, which deals its rays over the whole image.
pub(super) fn render(
    prepared: &Prepared,
    frame: Frame,
    rows: Range<usize>,
    step: u32,
    progress: &(dyn Fn() + Sync),
) -> Result<Traced, RenderError> {
    let Layout::Grid(kind) = Layout::of(prepared.options().sampler) else {
        return Err(RenderError::Options(
            "--coherence traces some pixels whole and interpolates the rest; --sampler adaptive deals its rays over every pixel by need: use one or the other".into(),
        ));
    };
    if !(1..=crate::coherence::MAX_STEP).contains(&step) {
        return Err(RenderError::Options(format!(
            "--coherence {step}: the step is 1..={}",
            crate::coherence::MAX_STEP
        )));
    }
    let img = &prepared.scene().image;
    let lattice = Lattice {
        width: img.width,
        height: img.height,
        step: step as usize,
    };
    let window = lattice.rows(&rows);
    let mut stats = TraceStats::default();
    let values = reconstruct(&lattice, window.clone(), |at| {
        let (values, s) = trace_pixels(prepared, kind, frame, window.start, at);
        stats += s;
        values
    });
    let cut = (rows.start - window.start) * img.width..(rows.end - window.start) * img.width;
    let m = img.masksize as u32;
    let kept = &values[cut];
    for _ in rows {
        progress();
    }
    Ok(Traced {
        colours: kept.iter().map(|v| v.colour).collect(),
        counts: kept.iter().map(|v| if v.traced { m * m } else { 0 }).collect(),
        stats,
    })
}

/// The pixels `at` ((column, row) pairs, the rows counted from `first`),
/// each traced whole by the grid sampler `kind`: row by row in parallel,
/// each row's pixels in turn.
fn trace_pixels(
    prepared: &Prepared,
    kind: GridKind,
    frame: Frame,
    first: usize,
    at: &[(usize, usize)],
) -> (Vec<Value>, TraceStats) {
    let mut order: Vec<usize> = (0..at.len()).collect();
    order.sort_by_key(|&k| (at[k].1, at[k].0));
    let rows: Vec<&[usize]> = order.chunk_by(|&a, &b| at[a].1 == at[b].1).collect();
    let traced: Vec<(Vec<Value>, TraceStats)> = rows
        .par_iter()
        .map(|ks| {
            let row = first + at[ks[0]].1;
            let mut pixel = PixelTracer::new(prepared, kind, frame, row);
            let values = ks.iter().map(|&k| pixel.trace(at[k].0)).collect();
            (values, pixel.tracer.stats)
        })
        .collect();
    let mut out = vec![Value::default(); at.len()];
    let mut stats = TraceStats::default();
    for (ks, (values, s)) in rows.iter().zip(traced) {
        for (&k, v) in ks.iter().zip(values) {
            out[k] = v;
        }
        stats += s;
    }
    (out, stats)
}

/// A worker tracing whole pixels of one row.
struct PixelTracer<'p> {
    prepared: &'p Prepared,
    frame: Frame,
    row: usize,
    tracer: Tracer<'p>,
    sampler: GridSampler<'p>,
}

impl<'p> PixelTracer<'p> {
    fn new(prepared: &'p Prepared, kind: GridKind, frame: Frame, row: usize) -> Self {
        let opts = prepared.options();
        let img = &prepared.scene().image;
        let mut sampler = GridSampler::new(
            prepared.tables(),
            kind,
            opts.fidelity,
            img.width,
            img.masksize,
            img.aliasing,
        );
        sampler.start_row(row);
        PixelTracer {
            prepared,
            frame,
            row,
            tracer: Tracer::new(prepared),
            sampler,
        }
    }

    /// Pixel `x` of the row: its subpixels as the scanline loop traces
    /// them, summed in `antialias`'s order (so its colour is the scanline
    /// loop's to the bit), and the objects they met first.
    fn trace(&mut self, x: usize) -> Value {
        let m = self.prepared.scene().image.masksize;
        let camera = self.prepared.camera();
        let timed = self.prepared.timed();
        let mut total = Intensity::ZERO;
        let mut objects = Gathered::default();
        for sub in 0..m {
            let scanline = self.row * m + sub + 1;
            let mut row_sum = Intensity::ZERO;
            for c in 0..m {
                self.sampler.start(scanline, x * m + c + 1);
                let cam = self.sampler.camera();
                let aray = camera.ray_of(cam, &mut self.sampler);
                if timed {
                    self.tracer.at(self.frame.time(self.sampler.time()));
                }
                let (colour, features) = self.tracer.shoot_features(&aray, &mut self.sampler);
                objects.add(colour, &features);
                row_sum += colour;
            }
            total += row_sum;
        }
        Value {
            colour: total / (m * m) as f64,
            objects: objects.objects,
            traced: true,
        }
    }
}

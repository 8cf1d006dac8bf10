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
/// The column loop starts at [`first_column`].
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
    let first_col = first_column(opts.fidelity);
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
            // Each subpixel its own instant. A structure's snapshot of the
            // scene is made once and moved on from instant to instant.
            sampler.start(scanline, first_col);
            tracer.at(frame.time(sampler.time()));
            let mut instant = tracer.instant();
            for scancol in first_col..=last_col {
                let aray = primary_ray(camera, &mut sampler, scanline, scancol);
                let time = frame.time(sampler.time());
                if !instant.at_asked(time) {
                    tracer.at(time);
                    instant = tracer.instant();
                }
                line[scancol - first_col] = shoot(&mut instant, &aray, &mut sampler);
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

/// The first subpixel column the scanline loop traces.
///
/// Erratum 13: the listing's column loop runs `for scancol := quickx to
/// quickx2` with `quickx = 0`, tracing one column more than the raster
/// has; `listing` fidelity traces it (and `antialias` never reads it),
/// `thesis` fidelity starts at 1.
fn first_column(fidelity: Fidelity) -> usize {
    match fidelity {
        Fidelity::Listing => 0,
        Fidelity::Thesis => 1,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::Accel;
    use crate::options::{Options, TimeSampler};
    use crate::sampler::Layout;
    use std::path::Path;

    /// A ball on a path over a checker floor, `blur N`, its objects found
    /// by `accel`.
    fn prepared(blur: u32, fidelity: Fidelity, sampler: TimeSampler, accel: Accel) -> Prepared {
        let deck = format!(
            "view eye 0 -12 5 look 0 0 0.5 screen 5 distance 5
             image 9 7 mask 3
             light sun 5 -8 12 1 1 1
             surface f opaque color 0.3 0.3 0.35 ka 0.2 kd 0.8 ks 0 kt 0
             paint f floor scale 1 1 color 0.85 0.85 0.8
             surface red opaque color 0.9 0.15 0.1 ka 0.15 kd 0.8 ks 0 kt 0
             block floor f at 0 0 -0.5 size 40 40 1
             sphere ball red at -3.5 0 0.7 radius 2.5
             motion ball to 3.5 0 0.7 via -1.5 -3 3.5 1.5 3 3.5
             blur {blur}"
        );
        let opts = Options {
            fidelity,
            sampler,
            accel,
            ..Options::default()
        };
        let scene = crate::deck::initialize(&deck, "ball.deck", Path::new(""), fidelity).unwrap();
        Prepared::new(scene, opts).unwrap()
    }

    /// The listing's loop: every subpixel in turn at its own instant, the
    /// scanline's sums and `antialias` as the listing takes them.
    fn one_by_one(prepared: &Prepared, kind: GridKind) -> Vec<Intensity> {
        let img = &prepared.scene().image;
        let (w, m) = (img.width, img.masksize);
        let first_col = first_column(prepared.options().fidelity);
        let mut tracer = Tracer::new(prepared);
        let mut pixels = Vec::new();
        for row in 0..img.height {
            let mut sampler =
                GridSampler::new(prepared.tables(), kind, prepared.options().fidelity, w, m, img.aliasing);
            sampler.start_row(row);
            let mut virtual_rows = vec![Intensity::ZERO; m * w];
            for sub in 0..m {
                for scancol in first_col..=w * m {
                    let aray = primary_ray(prepared.camera(), &mut sampler, row * m + sub + 1, scancol);
                    tracer.at(Frame::STILL.time(sampler.time()));
                    let acolor = tracer.shoot(&aray, &mut sampler);
                    if scancol >= 1 {
                        virtual_rows[sub * w + (scancol - 1) / m] += acolor;
                    }
                }
            }
            let mut out = vec![Intensity::ZERO; w];
            antialias(&virtual_rows, m, &mut out);
            pixels.extend(out);
        }
        pixels
    }

    /// Tracing a scanline's subpixels by their instants (the table's
    /// times repeating: `blur 0`, or the listing) or one by one gives
    /// each pixel the bits the listing's order gives, and with the times
    /// jittered (`blur 3`) and another sampler too; with the loop and
    /// with a hierarchy, whose snapshot of the scene is moved on from one
    /// subpixel's instant to the next.
    #[test]
    fn subpixels_taken_by_instant_as_one_by_one() {
        let cases = [
            (0, Fidelity::Thesis, TimeSampler::Table, true),
            (3, Fidelity::Listing, TimeSampler::Table, true),
            (3, Fidelity::Thesis, TimeSampler::Table, false),
            (0, Fidelity::Thesis, TimeSampler::Stratified, false),
        ];
        let with_each = cases
            .into_iter()
            .flat_map(|(b, f, s, r)| [Accel::None, Accel::Bvh].map(|a| (b, f, s, r, a)));
        for (blur, fidelity, sampler, repeats, accel) in with_each {
            let p = prepared(blur, fidelity, sampler, accel);
            assert_eq!(p.aggregate().structure().is_some(), accel == Accel::Bvh);
            assert_eq!(p.repeats(), repeats, "{blur} {fidelity:?} {sampler:?} {accel:?}");
            let Layout::Grid(kind) = Layout::of(sampler) else {
                unreachable!()
            };
            let traced = render_grid(&p, kind, Frame::STILL, 0..p.scene().image.height, &|| {});
            let want = one_by_one(&p, kind);
            let bits = |v: &[Intensity]| {
                v.iter()
                    .flat_map(|c| c.to_array().map(f64::to_bits))
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                bits(&traced.colours),
                bits(&want),
                "{blur} {fidelity:?} {sampler:?} {accel:?}"
            );
        }
    }
}

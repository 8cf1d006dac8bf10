//! Coherence, the thesis's own speed-up that it did not build (§2.1.2
//! (2)(a), OCR lines 227–229, Figs. 2.13–2.14): "neighbouring pixels
//! often have ray paths alike, so to save rays, intersect the rays with
//! the objects only every n (n ≥ 2) pixels, and find the rgb of the pixels
//! between by interpolation. It saves much time, but suits mostly
//! 'monotonous' scenes; on a scene of complex colour it often backfires,
//! so it must be used with care [Badt 88]." (Badt 1988, *Two algorithms
//! for taking advantage of temporal coherence in ray tracing*, The Visual
//! Computer 4, reuses a frame's pixels in the next; the thesis takes the
//! idea within one picture.) `--coherence N`, the port's reading:
//!
//! - The pixels of every N-th row and column (and the last of each) are
//!   the lattice; every lattice crossing is traced.
//! - Along each lattice line, between two traced pixels: where the two
//!   agree ([`agree`]), the pixels between are interpolated; where they do
//!   not, the pixel halfway is traced and each half is looked at again.
//! - Each cell of the lattice: where its four corners agree, its inside
//!   is interpolated (bilinearly); where they do not, its centre is traced,
//!   the two lines through the centre are looked at as the lattice lines
//!   were, and each quarter is a cell again. So a skipped pixel is traced
//!   after all where its traced neighbours disagree, and a busy part of
//!   the picture is traced pixel by pixel.
//! - Two pixels agree when their rays met the same objects first and no
//!   channel of their colours differs by more than [`THRESHOLD`].
//!
//! What fails is what the thesis warns of: a thing thinner than N pixels
//! that falls between the traced pixels of a cell whose corners agree is
//! not seen at all (docs/reconstruction.md, "Where they fail").
//!
//! Every decision depends on the pixels of its line or cell alone, never
//! on the order the work is done in: the picture is the same for any
//! number of threads, and a band of rows is the whole picture's band
//! when the cells it crosses are worked out whole ([`Lattice::rows`]).

use std::ops::Range;

use crate::types::Intensity;

/// The largest step N of `--coherence`.
pub const MAX_STEP: u32 = 64;

/// Two traced pixels whose colours differ by more than this in some
/// channel do not agree, and the pixels between them are traced: 0.02,
/// about 5 steps of an 8-bit channel. Measured with `tools frontier`'s
/// decks at 128² and 16 rays a pixel of the table, N = 4 (RMSE against
/// the 1024-ray reference; the share of pixels traced): 0.005 gave
/// 0.0093–0.0175 and 41–48 %, 0.01 0.0093–0.0195 and 32–46 %, 0.02
/// 0.0093–0.0238 and 29–44 %, 0.05 0.0098–0.0296 and 23–44 %, 0.1
/// 0.0109–0.0365 and 17–43 %, 0.2 0.0119–0.0513 and 14–43 %. The larger thresholds lose the checker
/// floor's squares between two traced pixels on squares of one colour
/// (fig5_10, the ball); the smaller ones trace the noise of a plain
/// floor. 0.02 serves the scenes the thesis meant coherence for: on
/// fig5_3's plain floor it is 0.43 of the plain render's CPU time at the
/// same error, where 0.01 is 0.47 and 0.005 0.58; on the checker floors
/// 0.01 would take a fifth off the error (1.75 → 1.43 × the plain
/// render's on the ball) for 3–7 % more time, and coherence is the wrong
/// tool there at either.
pub const THRESHOLD: f64 = 0.02;

/// What is known of a pixel: its colour and the objects its rays met first
/// (a bit each, [`crate::reconstruct::Gathered::objects`]), and whether it
/// was traced or interpolated.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Value {
    pub colour: Intensity,
    pub objects: u64,
    pub traced: bool,
}

/// Whether two pixels agree: the same objects met first, and colours
/// within [`THRESHOLD`] in every channel.
pub fn agree(a: &Value, b: &Value) -> bool {
    a.objects == b.objects && (a.colour - b.colour).abs().max_element() <= THRESHOLD
}

/// The lattice of an image `width`×`height` with step `step`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Lattice {
    pub width: usize,
    pub height: usize,
    pub step: usize,
}

impl Lattice {
    /// The lattice line at or before `i` along a side of `n` pixels.
    fn line_before(&self, i: usize) -> usize {
        i / self.step * self.step
    }

    /// The lattice line after `i` (the last pixel of the side if no
    /// multiple of the step comes first).
    fn line_after(&self, i: usize, n: usize) -> usize {
        (i / self.step * self.step + self.step).min(n - 1)
    }

    /// The rows to work out for a band of `rows`: from the lattice row at
    /// or above its first to the one at or below its last, so that every
    /// cell the band crosses is whole.
    pub fn rows(&self, rows: &Range<usize>) -> Range<usize> {
        let first = self.line_before(rows.start);
        let last = match rows.end - 1 {
            r if r % self.step == 0 => r,
            r => self.line_after(r, self.height),
        };
        first..last + 1
    }

    /// The lattice lines along a side of `n` pixels within `span`: every
    /// multiple of the step and the last pixel.
    fn lines(&self, span: Range<usize>, n: usize) -> Vec<usize> {
        let mut v: Vec<usize> = span.clone().filter(|i| i % self.step == 0 || *i == n - 1).collect();
        v.dedup();
        v
    }
}

/// A run of pixels along a row or a column between two whose values are
/// known, the ends `a` and `b` (pixel indices in the window).
#[derive(Clone, Copy, Debug)]
struct Segment {
    a: usize,
    b: usize,
    /// The index step from one pixel to the next: 1 along a row, the
    /// window's width along a column.
    stride: usize,
}

/// A cell: its corners' columns and rows in the window.
#[derive(Clone, Copy, Debug)]
struct Cell {
    x0: usize,
    x1: usize,
    y0: usize,
    y1: usize,
}

/// The pixels of `window` rows of a `lattice`'s image, each traced by
/// `trace` (which takes (column, row in the window) pairs and returns
/// their values, in order) or interpolated as the module says. `trace`
/// is called once for each round of pixels, never with a pixel twice.
pub fn reconstruct(
    lattice: &Lattice,
    window: Range<usize>,
    mut trace: impl FnMut(&[(usize, usize)]) -> Vec<Value>,
) -> Vec<Value> {
    let w = lattice.width;
    let h = window.len();
    let mut values = vec![Value::default(); w * h];
    let xs = lattice.lines(0..w, w);
    let ys: Vec<usize> = lattice
        .lines(window.clone(), lattice.height)
        .into_iter()
        .map(|y| y - window.start)
        .collect();
    let corners: Vec<(usize, usize)> = ys.iter().flat_map(|&y| xs.iter().map(move |&x| (x, y))).collect();
    let mut run = |values: &mut Vec<Value>, at: Vec<(usize, usize)>| {
        for (&(x, y), v) in at.iter().zip(trace(&at)) {
            values[y * w + x] = Value { traced: true, ..v };
        }
    };
    run(&mut values, corners);
    let mut segments = Vec::new();
    for &y in &ys {
        for pair in xs.windows(2) {
            segments.push(Segment {
                a: y * w + pair[0],
                b: y * w + pair[1],
                stride: 1,
            });
        }
    }
    for &x in &xs {
        for pair in ys.windows(2) {
            segments.push(Segment {
                a: pair[0] * w + x,
                b: pair[1] * w + x,
                stride: w,
            });
        }
    }
    let mut cells: Vec<Cell> = ys
        .windows(2)
        .flat_map(|r| {
            xs.windows(2).map(move |c| Cell {
                x0: c[0],
                x1: c[1],
                y0: r[0],
                y1: r[1],
            })
        })
        .collect();
    loop {
        // The lines first, round by round, so that every cell's sides are
        // known before it is looked at.
        while !segments.is_empty() {
            let mut midpoints = Vec::new();
            let mut next = Vec::new();
            for s in segments.drain(..) {
                let n = (s.b - s.a) / s.stride;
                if n <= 1 {
                    continue;
                }
                let (va, vb) = (values[s.a], values[s.b]);
                if agree(&va, &vb) {
                    for k in 1..n {
                        let t = k as f64 / n as f64;
                        values[s.a + k * s.stride] = Value {
                            colour: between(va.colour, vb.colour, t),
                            objects: va.objects,
                            traced: false,
                        };
                    }
                    continue;
                }
                let m = s.a + n / 2 * s.stride;
                midpoints.push((m % w, m / w));
                next.push(Segment { b: m, ..s });
                next.push(Segment { a: m, ..s });
            }
            run(&mut values, midpoints);
            segments = next;
        }
        if cells.is_empty() {
            break;
        }
        let mut centres = Vec::new();
        let mut split = Vec::new();
        for c in cells.drain(..) {
            if c.x1 - c.x0 <= 1 || c.y1 - c.y0 <= 1 {
                continue;
            }
            let at = |x: usize, y: usize| values[y * w + x];
            let corner = [at(c.x0, c.y0), at(c.x1, c.y0), at(c.x0, c.y1), at(c.x1, c.y1)];
            let all_agree = (0..4).all(|i| (i + 1..4).all(|j| agree(&corner[i], &corner[j])));
            if all_agree {
                bilinear(&mut values, w, &c, &corner);
                continue;
            }
            let (mx, my) = ((c.x0 + c.x1) / 2, (c.y0 + c.y1) / 2);
            centres.push((mx, my));
            split.push(c);
        }
        run(&mut values, centres);
        for c in split {
            let (mx, my) = ((c.x0 + c.x1) / 2, (c.y0 + c.y1) / 2);
            let centre = my * w + mx;
            segments.extend([
                Segment {
                    a: c.y0 * w + mx,
                    b: centre,
                    stride: w,
                },
                Segment {
                    a: centre,
                    b: c.y1 * w + mx,
                    stride: w,
                },
                Segment {
                    a: my * w + c.x0,
                    b: centre,
                    stride: 1,
                },
                Segment {
                    a: centre,
                    b: my * w + c.x1,
                    stride: 1,
                },
            ]);
            cells.extend([
                Cell { x1: mx, y1: my, ..c },
                Cell { x0: mx, y1: my, ..c },
                Cell { x1: mx, y0: my, ..c },
                Cell { x0: mx, y0: my, ..c },
            ]);
        }
    }
    values
}

/// The inside of cell `c` from its four corners (top left, top right,
/// bottom left, bottom right), which agree.
fn bilinear(values: &mut [Value], w: usize, c: &Cell, corner: &[Value; 4]) {
    let (dx, dy) = ((c.x1 - c.x0) as f64, (c.y1 - c.y0) as f64);
    for y in c.y0 + 1..c.y1 {
        let t = (y - c.y0) as f64 / dy;
        for x in c.x0 + 1..c.x1 {
            let s = (x - c.x0) as f64 / dx;
            let top = between(corner[0].colour, corner[1].colour, s);
            let bottom = between(corner[2].colour, corner[3].colour, s);
            values[y * w + x] = Value {
                colour: between(top, bottom, t),
                objects: corner[0].objects,
                traced: false,
            };
        }
    }
}

/// The colour a fraction `t` of the way from `a` to `b`: `a` + (`b` −
/// `a`)·t, which is `a` itself between two equal colours.
fn between(a: Intensity, b: Intensity, t: f64) -> Intensity {
    a + (b - a) * t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A picture given by a function of the pixel: what `trace` returns,
    /// and a count of the pixels traced.
    fn picture<'a>(
        f: impl Fn(usize, usize) -> (f64, u64) + 'a,
        traced: &'a mut Vec<(usize, usize)>,
        first_row: usize,
    ) -> impl FnMut(&[(usize, usize)]) -> Vec<Value> + 'a {
        move |at: &[(usize, usize)]| {
            at.iter()
                .map(|&(x, y)| {
                    traced.push((x, y + first_row));
                    let (c, objects) = f(x, y + first_row);
                    Value {
                        colour: Intensity::splat(c),
                        objects,
                        traced: false,
                    }
                })
                .collect()
        }
    }

    /// A smooth ramp is traced only on the lattice and interpolated exactly
    /// elsewhere; step 1 traces every pixel once.
    #[test]
    fn a_ramp_is_interpolated_from_the_lattice() {
        let lattice = Lattice {
            width: 17,
            height: 9,
            step: 4,
        };
        let ramp = |x: usize, y: usize| (0.003 * x as f64 + 0.001 * y as f64, 1);
        let mut traced = Vec::new();
        let v = reconstruct(&lattice, 0..9, picture(ramp, &mut traced, 0));
        // Columns 0, 4, 8, 12, 16 and rows 0, 4, 8.
        assert_eq!(traced.len(), 15);
        for (i, p) in v.iter().enumerate() {
            let (x, y) = (i % 17, i / 17);
            assert!((p.colour.x - ramp(x, y).0).abs() < 1e-12, "({x}, {y})");
            assert_eq!(p.traced, x % 4 == 0 && y % 4 == 0, "({x}, {y})");
        }
        let mut traced = Vec::new();
        let lattice = Lattice { step: 1, ..lattice };
        let v = reconstruct(&lattice, 0..9, picture(ramp, &mut traced, 0));
        assert!(v.iter().all(|p| p.traced));
        traced.sort_unstable();
        traced.dedup();
        assert_eq!(traced.len(), 17 * 9);
    }

    /// A disc of another object: every pixel whose colour or object
    /// differs from a neighbour's is traced, so the picture is exact; far
    /// fewer than all pixels are traced. A pixel is never traced twice.
    #[test]
    fn an_edge_is_traced_and_the_rest_interpolated() {
        let (w, h) = (40, 33);
        let disc = |x: usize, y: usize| {
            let (dx, dy) = (x as f64 - 20.0, y as f64 - 15.0);
            if dx * dx + dy * dy < 100.0 {
                (0.8, 2)
            } else {
                (0.2, 1)
            }
        };
        for step in [2, 3, 4, 8] {
            let lattice = Lattice {
                width: w,
                height: h,
                step,
            };
            let mut traced = Vec::new();
            let v = reconstruct(&lattice, 0..h, picture(disc, &mut traced, 0));
            for (i, p) in v.iter().enumerate() {
                let (x, y) = (i % w, i / w);
                assert_eq!(p.colour.x, disc(x, y).0, "step {step} ({x}, {y})");
            }
            let n = traced.len();
            traced.sort_unstable();
            traced.dedup();
            assert_eq!(traced.len(), n, "step {step}: a pixel traced twice");
            assert!(n < w * h / 2, "step {step}: {n} traced");
        }
    }

    /// What the thesis warns of: a line one pixel wide between the
    /// lattice's columns, in cells whose corners agree, is not seen.
    #[test]
    fn a_thin_line_between_traced_pixels_is_missed() {
        let line = |x: usize, _: usize| if x == 6 { (1.0, 2) } else { (0.0, 1) };
        let lattice = Lattice {
            width: 16,
            height: 16,
            step: 4,
        };
        let mut traced = Vec::new();
        let v = reconstruct(&lattice, 0..16, picture(line, &mut traced, 0));
        assert!(v.iter().all(|p| p.colour.x == 0.0));
        let lattice = Lattice { step: 2, ..lattice };
        let v = reconstruct(&lattice, 0..16, picture(line, &mut traced, 0));
        assert!(v.iter().enumerate().all(|(i, p)| p.colour.x == line(i % 16, 0).0));
    }

    /// Agreement: objects alike and every channel within the threshold.
    #[test]
    fn agreement_by_objects_and_threshold() {
        let v = |c: f64, objects| Value {
            colour: Intensity::new(0.5, c, 0.5),
            objects,
            traced: true,
        };
        assert!(agree(&v(0.5, 1), &v(0.5 + THRESHOLD * 0.99, 1)));
        assert!(!agree(&v(0.5, 1), &v(0.5 + THRESHOLD * 1.01, 1)));
        assert!(!agree(&v(0.5, 1), &v(0.5, 2)));
    }

    /// Bands of rows worked out with the cells they cross are the whole
    /// picture's rows.
    #[test]
    fn a_band_is_the_whole_pictures_band() {
        let (w, h) = (23, 29);
        let f = |x: usize, y: usize| {
            let r = ((x * 7 + y * 13) % 11) as f64 / 10.0;
            (
                if (x / 5 + y / 3).is_multiple_of(2) { r } else { 0.3 },
                ((x / 7) % 2) as u64,
            )
        };
        for step in [1, 2, 3, 5, 8] {
            let lattice = Lattice {
                width: w,
                height: h,
                step,
            };
            let mut t = Vec::new();
            let whole = reconstruct(&lattice, 0..h, picture(f, &mut t, 0));
            for band in [0..1, 0..7, 3..4, 5..17, 20..29, 28..29] {
                let window = lattice.rows(&band);
                // The cells the band crosses, and no more: from the multiple
                // of the step at or above its first row to the lattice row
                // (a multiple, or the last row) at or below its last.
                let first = band.start / step * step;
                let last = (0..h).find(|&y| y + 1 >= band.end && (y % step == 0 || y == h - 1));
                assert_eq!(
                    Some(window.clone()),
                    last.map(|b| first..b + 1),
                    "step {step} band {band:?}"
                );
                let mut t = Vec::new();
                let part = reconstruct(&lattice, window.clone(), picture(f, &mut t, window.start));
                let cut = (band.start - window.start) * w..(band.end - window.start) * w;
                assert_eq!(
                    &part[cut],
                    &whole[band.start * w..band.end * w],
                    "step {step} band {band:?}"
                );
            }
        }
    }
}

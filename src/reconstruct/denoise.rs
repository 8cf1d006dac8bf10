//! `--denoise`: each pixel from its own samples and its neighbours', the
//! port's extension (the thesis's pixel is the mean of its own subpixels,
//! `antialias`).
//!
//! Non-local means over the pixels' mean colours, guided by their mean
//! features, with the filter chosen pixel by pixel from the data (after
//! Rousselle, Knaus & Zwicker 2012, *Adaptive rendering with non-local
//! means filtering*, and Rousselle, Manzi & Zwicker 2013, *Robust
//! denoising using feature and color information*; the choice by Stein's
//! unbiased risk estimate as in Li, Wu & Chuang 2012, *SURE-based
//! optimization for adaptive sampling and reconstruction*):
//!
//! - A neighbour j within [`RADIUS`] counts toward pixel i by how alike
//!   the two are. Colour: the squared difference of the 3×3 patches
//!   around them, less what the noise of the two means accounts for (the
//!   variance of each mean, from the spread of its samples), over that
//!   noise. Features (the surface's own colour, the normal): the squared
//!   difference less the features' own noise, over the larger of their
//!   noise, their change from pixel to pixel, and a floor. A checker
//!   square's edge, a letter's outline, a texture's edge: the features
//!   differ where the noise does not reach, and the filter stops; a
//!   blurred streak, whose features spread as its samples do, does not
//!   stop it.
//! - Three candidates: the pixel's own mean; the filter of colours and
//!   features; the filter of colours alone (for what the features do not
//!   see: a shadow's edge, a reflection). Each pixel takes the one whose
//!   error the risk estimate says is least, the estimates averaged over
//!   the 3×3 pixels around it.
//!
//! Every output pixel depends on the pixels within [`REACH`] of it and on
//! nothing else (no statistic of the whole image), so a band of rows
//! rendered with [`REACH`] rows more on each side and cut is the whole
//! image's band to the bit, and the result is the same for any number of
//! threads. The arithmetic is in `f32`, a plane (a `Vec`) a quantity,
//! the loops running along a row's pixels.

use rayon::prelude::*;

use super::{Gathered, PixelMeans};
use crate::types::Intensity;

/// The filter's window reaches this many pixels each way: 2 (5×5).
/// Measured on fig5_10 and fig5_3 at 4 rays a pixel (`tools frontier`'s
/// way): 3 gave the same error on fig5_10 and 8 % more on fig5_3, 1 gave
/// 2–7 % more, 5 more still (with Rousselle's k_f, 2 % and 11 % over 3):
/// the wider the window, the more it blurs what it should not, which the
/// risk estimate does not always see.
pub const RADIUS: usize = 2;

/// How far an output pixel's inputs lie: the window, the 3×3 patches,
/// the 3×3 pooling of the colour variance and the features' change, and
/// the 3×3 smoothing of the risk estimates.
pub const REACH: usize = RADIUS + 3;

/// The colour distance's scale (Rousselle 2013's k_c): a neighbour whose
/// patch differs by what the noise explains plus `COLOUR_K`² times the
/// noise weighs about e⁻¹ (0.3 and 0.6 measured within 2 %).
const COLOUR_K: f32 = 0.45;

/// The features' scale (Rousselle 2013's k_f): 2. Rousselle's 0.6
/// stopped the filter at every feature edge of the motion-blurred
/// streaks, whose features are as noisy as their colours (fig5_10 at 4
/// rays a pixel: RMSE 0.0136 against 0.0124 at 2; 4 and 8 measured as 2).
const FEATURE_K: f32 = 2.0;

/// The features' floor (Rousselle 2013's τ): a feature that neither
/// spreads nor changes still lets differences below about √τ through.
const FEATURE_FLOOR: f32 = 1e-3;

/// Below this noise (the variance of the mean colour summed over the
/// channels: a quarter of an 8-bit step in each channel) a pixel's own
/// mean is kept.
const QUIET: f32 = 3.0 * (0.25 / 255.0) * (0.25 / 255.0);

/// The candidates: the pixel's own mean, colours and features, colours.
const CANDIDATES: usize = 3;

/// Rows of pixels a worker filters at a time.
const BAND: usize = 16;

/// The denoised colours of an image `width` pixels wide whose pixels
/// gathered `pixels` (row by row).
pub fn denoise(pixels: &[Gathered], width: usize) -> Vec<Intensity> {
    if pixels.is_empty() || width == 0 {
        return Vec::new();
    }
    let planes = Planes::new(pixels, width);
    let sums = planes.filter();
    let risks = planes.risks(&sums);
    // The risks summed over the 3×3 pixels around each: a candidate's
    // own risk is too noisy to choose by alone.
    let smoothed = risks.each_ref().map(|r| {
        let clamped: Vec<f32> = r.iter().map(|v| v.min(1e30)).collect();
        box_sums(&clamped, width)
    });
    (0..pixels.len())
        .into_par_iter()
        .map(|i| {
            let own = pixels[i].mean();
            let best = (1..CANDIDATES).fold(0, |best, c| {
                match smoothed[c][i] < smoothed[best][i] && risks[c][i].is_finite() {
                    true => c,
                    false => best,
                }
            });
            if best == 0 {
                return own;
            }
            let s = &sums[best - 1];
            let f = Intensity::new(
                f64::from(s.colour[0][i]),
                f64::from(s.colour[1][i]),
                f64::from(s.colour[2][i]),
            ) / f64::from(s.weight[i]);
            if f.is_finite() {
                f
            } else {
                own
            }
        })
        .collect()
}

/// The pixels' means as planes of `f32`, what the filter reads.
struct Planes {
    width: usize,
    height: usize,
    colour: [Vec<f32>; 3],
    /// The variance of each mean colour, channel by channel, pooled.
    var: [Vec<f32>; 3],
    /// The sum of the channels' variances: the noise of the pixel.
    noise: Vec<f32>,
    albedo: [Vec<f32>; 3],
    normal: [Vec<f32>; 3],
    /// Each feature's variance of the mean.
    albedo_var: Vec<f32>,
    normal_var: Vec<f32>,
    /// 1 / (k_f² · max(τ, variance, change²)) for each feature.
    albedo_scale: Vec<f32>,
    normal_scale: Vec<f32>,
    /// Each row's runs of pixels that are not quiet (columns a..b): only
    /// their sums are made.
    active: Vec<Vec<(usize, usize)>>,
}

/// A candidate filter's sums: the weighted colours and the weights.
struct Sums {
    colour: [Vec<f32>; 3],
    weight: Vec<f32>,
}

impl Sums {
    fn new(n: usize) -> Sums {
        Sums {
            colour: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            weight: vec![0.0; n],
        }
    }
}

impl Planes {
    fn new(pixels: &[Gathered], width: usize) -> Planes {
        let n = pixels.len();
        let zeros = || [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]];
        let (mut colour, mut own_var, mut albedo, mut normal) = (zeros(), zeros(), zeros(), zeros());
        let height = n / width;
        let (mut albedo_var, mut normal_var) = (vec![0.0f32; n], vec![0.0f32; n]);
        // Whether the pixel has a variance of its own (two samples or more).
        let mut has_var = vec![false; n];
        for (i, g) in pixels.iter().enumerate() {
            let m: PixelMeans = g.means();
            for ch in 0..3 {
                colour[ch][i] = m.colour[ch] as f32;
                albedo[ch][i] = m.albedo[ch] as f32;
                normal[ch][i] = m.normal[ch] as f32;
                own_var[ch][i] = m.colour_var.map_or(0.0, |v| v[ch] as f32);
            }
            has_var[i] = m.colour_var.is_some();
            albedo_var[i] = m.albedo_var as f32;
            normal_var[i] = m.normal_var as f32;
        }
        // A mean of few samples has a very noisy variance: each pixel's is
        // the average over the 3×3 pixels around it that have one; for
        // pixels of one sample, the variance of the 3×3 means.
        let with_var: Vec<f32> = has_var.iter().map(|&h| f32::from(u8::from(h))).collect();
        let k = box_sums(&with_var, width);
        let m = box_sums(&vec![1.0; n], width);
        let var = [0, 1, 2].map(|ch| {
            let own: Vec<f32> = own_var[ch].iter().zip(&with_var).map(|(v, h)| v * h).collect();
            let sum = box_sums(&own, width);
            let c = box_sums(&colour[ch], width);
            let squares: Vec<f32> = colour[ch].iter().map(|c| c * c).collect();
            let c2 = box_sums(&squares, width);
            (0..n)
                .map(|i| match k[i] > 0.0 {
                    true => sum[i] / k[i],
                    false => ((c2[i] - c[i] * c[i] / m[i]) / m[i]).max(0.0),
                })
                .collect::<Vec<f32>>()
        });
        let noise: Vec<f32> = (0..n).map(|i| var[0][i] + var[1][i] + var[2][i]).collect();
        let active = noise
            .chunks_exact(width)
            .map(|row| {
                let mut runs: Vec<(usize, usize)> = Vec::new();
                for (x, _) in row.iter().enumerate().filter(|(_, &v)| v > QUIET) {
                    match runs.last_mut() {
                        Some(r) if r.1 == x => r.1 = x + 1,
                        _ => runs.push((x, x + 1)),
                    }
                }
                runs
            })
            .collect();
        let albedo_scale = scales(&albedo, &albedo_var, width);
        let normal_scale = scales(&normal, &normal_var, width);
        Planes {
            width,
            height,
            colour,
            var,
            noise,
            albedo,
            normal,
            albedo_var,
            normal_var,
            albedo_scale,
            normal_scale,
            active,
        }
    }

    /// The sums of the two filters over the window: band by band of rows
    /// in parallel, and in each band offset by offset ([`Band::offset`]).
    fn filter(&self) -> [Sums; 2] {
        let h = self.height;
        let bands: Vec<[Sums; 2]> = (0..h.div_ceil(BAND))
            .into_par_iter()
            .map(|b| {
                let mut band = Band::new(self, b * BAND..((b + 1) * BAND).min(h));
                let r = RADIUS as isize;
                for dy in -r..=r {
                    for dx in -r..=r {
                        if (dx, dy) != (0, 0) {
                            band.offset(dx, dy);
                        }
                    }
                }
                band.sums
            })
            .collect();
        let mut sums = [Sums::new(0), Sums::new(0)];
        for band in bands {
            for (all, part) in sums.iter_mut().zip(band) {
                for ch in 0..3 {
                    all.colour[ch].extend(part.colour[ch].iter());
                }
                all.weight.extend(part.weight);
            }
        }
        sums
    }

    /// Each candidate's risk at each pixel: the pixel's noise for its own
    /// mean; for a filter F, SURE's ‖F(y) − y‖² + 2 σ² ∂F/∂y − σ², with
    /// ∂F/∂y the pixel's own weight over the whole (the weights' own
    /// change with y left out, as Li et al. do).
    fn risks(&self, sums: &[Sums; 2]) -> [Vec<f32>; CANDIDATES] {
        let n = self.noise.len();
        let mut out = [self.noise.clone(), vec![f32::INFINITY; n], vec![f32::INFINITY; n]];
        for (c, s) in sums.iter().enumerate() {
            for (i, risk) in out[c + 1].iter_mut().enumerate() {
                let noise = self.noise[i];
                if noise <= QUIET {
                    continue;
                }
                let weight = s.weight[i];
                let mut d2 = 0.0;
                for ch in 0..3 {
                    let d = s.colour[ch][i] / weight - self.colour[ch][i];
                    d2 += d * d;
                }
                let r = d2 + 2.0 * noise / weight - noise;
                if r.is_finite() {
                    *risk = r;
                }
            }
        }
        out
    }
}

/// The columns x of a row whose neighbour x + `dx` lies in a row of `w`.
fn span(dx: isize, w: usize) -> (usize, usize) {
    let x0 = (-dx).max(0) as usize;
    let x1 = (w as isize - dx.max(0)).max(0) as usize;
    (x0.min(w), x1.max(x0.min(w)))
}

/// Each pixel's feature scale, 1 / (k_f² · max(τ, variance, change²)),
/// the change the largest squared difference to a 3×3 neighbour, halved
/// (a central difference).
fn scales(f: &[Vec<f32>; 3], var: &[f32], width: usize) -> Vec<f32> {
    let n = var.len();
    // The squared differences to the pixel to the right, below, below
    // right and below left (0 where there is none).
    let step = |di: usize, keep: fn(usize, usize) -> bool| -> Vec<f32> {
        let mut d = vec![0.0; n];
        for (i, d) in d.iter_mut().enumerate().take(n.saturating_sub(di)) {
            if keep(i % width, width) {
                let j = i + di;
                let (a, b, c) = (f[0][i] - f[0][j], f[1][i] - f[1][j], f[2][i] - f[2][j]);
                *d = a * a + b * b + c * c;
            }
        }
        d
    };
    let right = step(1, |x, w| x + 1 < w);
    let below = step(width, |_, _| true);
    let below_right = step(width + 1, |x, w| x + 1 < w);
    let below_left = step(width - 1, |x, _| x > 0);
    (0..n)
        .map(|i| {
            let back = |d: &[f32], di: usize| if i >= di { d[i - di] } else { 0.0 };
            // A pair out of the image has 0 here, so no test is needed.
            let change = right[i]
                .max(below[i])
                .max(below_right[i])
                .max(below_left[i])
                .max(back(&right, 1))
                .max(back(&below, width))
                .max(back(&below_right, width + 1))
                .max(back(&below_left, width - 1))
                * 0.25;
            1.0 / (FEATURE_K * FEATURE_K * FEATURE_FLOOR.max(var[i]).max(change))
        })
        .collect()
}

/// The sums of `values` over the 3×3 pixels around each pixel (fewer at
/// the image's edges), an image `width` pixels wide: along the rows, then
/// down the columns.
fn box_sums(values: &[f32], width: usize) -> Vec<f32> {
    let n = values.len();
    let mut across = vec![0.0; n];
    for (row, out) in values.chunks_exact(width).zip(across.chunks_exact_mut(width)) {
        for x in 0..width {
            let left = if x > 0 { row[x - 1] } else { 0.0 };
            let right = if x + 1 < width { row[x + 1] } else { 0.0 };
            out[x] = left + row[x] + right;
        }
    }
    (0..n)
        .map(|i| {
            let up = if i >= width { across[i - width] } else { 0.0 };
            let down = if i + width < n { across[i + width] } else { 0.0 };
            up + across[i] + down
        })
        .collect()
}

/// The filter's weight for a distance: e^−d in shape, exactly 0 past 4
/// (a few multiplications where an exponential is a library call).
#[inline]
fn kernel(d: f32) -> f32 {
    let t = (1.0 - 0.25 * d).max(0.0);
    let t2 = t * t;
    t2 * t2
}

/// A band of rows being filtered: the two filters' sums of its pixels,
/// and the scratch of the colour distances to one offset.
struct Band<'a> {
    planes: &'a Planes,
    rows: std::ops::Range<usize>,
    sums: [Sums; 2],
    /// The pixel distances of the band's rows and one more above and
    /// below (0 where the pair leaves the image), and their sums along
    /// rows of three.
    distance: Vec<f32>,
    across: Vec<f32>,
    /// Rows of scratch: 1 / the patch's columns, the features' distance,
    /// the two filters' weights.
    cols: Vec<f32>,
    features: Vec<f32>,
    kb: Vec<f32>,
    kc: Vec<f32>,
}

impl<'a> Band<'a> {
    /// The band of `rows`, each pixel weighing 1 in its own sums.
    fn new(planes: &'a Planes, rows: std::ops::Range<usize>) -> Self {
        let w = planes.width;
        let own = rows.start * w..rows.end * w;
        let sums = [0, 1].map(|_| Sums {
            colour: [0, 1, 2].map(|ch| planes.colour[ch][own.clone()].to_vec()),
            weight: vec![1.0; own.len()],
        });
        let scratch = (rows.len() + 2) * w;
        Band {
            planes,
            rows,
            sums,
            distance: vec![0.0; scratch],
            across: vec![0.0; scratch],
            cols: vec![0.0; w],
            features: vec![0.0; w],
            kb: vec![0.0; w],
            kc: vec![0.0; w],
        }
    }

    /// Adds the neighbour at (`dx`, `dy`) of each of the band's pixels to
    /// its sums: the colour distance of each pixel to its neighbour
    /// (the squared difference less the noise of the two means, over the
    /// noise: Rousselle 2012), averaged over the 3×3 patch around it;
    /// the features' distances; the weights.
    fn offset(&mut self, dx: isize, dy: isize) {
        let p = self.planes;
        let (w, h) = (p.width, p.height);
        // The pairs in the image: columns x0..x1, rows y0..y1.
        let (x0, x1) = span(dx, w);
        let (y0, y1) = span(dy, h);
        let first = self.rows.start as isize - 1;
        // The distances of rows first..first + len (the band and a row
        // above and below).
        for (k, (d, across)) in self
            .distance
            .chunks_exact_mut(w)
            .zip(self.across.chunks_exact_mut(w))
            .enumerate()
        {
            d.fill(0.0);
            across.fill(0.0);
            let y = first + k as isize;
            if y < y0 as isize || y >= y1 as isize || x0 >= x1 {
                continue;
            }
            let i = y as usize * w + x0..y as usize * w + x1;
            let j = ((y + dy) as usize * w + x0).wrapping_add_signed(dx)
                ..((y + dy) as usize * w + x1).wrapping_add_signed(dx);
            let out = &mut d[x0..x1];
            for ch in 0..3 {
                let (ci, cj) = (&p.colour[ch][i.clone()], &p.colour[ch][j.clone()]);
                let (vi, vj) = (&p.var[ch][i.clone()], &p.var[ch][j.clone()]);
                for ((((o, &ci), &cj), &vi), &vj) in out.iter_mut().zip(ci).zip(cj).zip(vi).zip(vj) {
                    let diff = ci - cj;
                    *o += (diff * diff - (vi + vi.min(vj))) / (1e-10 + COLOUR_K * COLOUR_K * (vi + vj));
                }
            }
            // Sums along the row of three (outside the pairs, 0).
            for x in x0..x1 {
                let left = if x > x0 { d[x - 1] } else { 0.0 };
                let right = if x + 1 < x1 { d[x + 1] } else { 0.0 };
                across[x] = left + d[x] + right;
            }
        }
        // 1 / the patch's columns within the pairs' (3, or 2 at an end).
        let cols = &mut self.cols[x0..x1];
        cols.fill(1.0 / 3.0);
        if let Some(c) = cols.first_mut() {
            *c = 0.5;
        }
        if let Some(c) = cols.last_mut() {
            *c = if x1 - x0 == 1 { 1.0 } else { 0.5 };
        }
        let [both, colours] = &mut self.sums;
        for (k, y) in self.rows.clone().enumerate() {
            if y < y0 || y >= y1 || x0 >= x1 {
                continue;
            }
            // 1 / 3 channels / the patch's rows within the pairs'.
            let rows_in = 1 + usize::from(y > y0) + usize::from(y + 1 < y1);
            let per_row = 1.0 / (3 * rows_in) as f32;
            // Only the pixels the filter may change (not quiet).
            for &(a, b) in &p.active[y] {
                let (xa, xb) = (a.max(x0), b.min(x1));
                if xa >= xb {
                    continue;
                }
                let up = &self.across[k * w + xa..k * w + xb];
                let mid = &self.across[(k + 1) * w + xa..(k + 1) * w + xb];
                let down = &self.across[(k + 2) * w + xa..(k + 2) * w + xb];
                let i = y * w + xa..y * w + xb;
                let jy = (y as isize + dy) as usize * w;
                let j = (jy + xa).wrapping_add_signed(dx)..(jy + xb).wrapping_add_signed(dx);
                // The larger of the features' distances.
                let df = &mut self.features[xa..xb];
                feature_distances(&p.albedo, &p.albedo_var, &p.albedo_scale, &i, &j, df, false);
                feature_distances(&p.normal, &p.normal_var, &p.normal_scale, &i, &j, df, true);
                let (kb, kc) = (&mut self.kb[xa..xb], &mut self.kc[xa..xb]);
                for (((((kb, kc), df), cols), up), (mid, down)) in kb
                    .iter_mut()
                    .zip(kc.iter_mut())
                    .zip(df.iter())
                    .zip(cols.iter())
                    .zip(up)
                    .zip(mid.iter().zip(down))
                {
                    let dc = ((up + mid + down) * per_row * cols).max(0.0);
                    *kc = kernel(dc);
                    *kb = kernel(dc.max(*df));
                }
                let o = k * w + xa..k * w + xb;
                for ch in 0..3 {
                    let c = &p.colour[ch][j.clone()];
                    for ((b, cc), ((kb, kc), c)) in both.colour[ch][o.clone()]
                        .iter_mut()
                        .zip(colours.colour[ch][o.clone()].iter_mut())
                        .zip(kb.iter().zip(kc.iter()).zip(c))
                    {
                        *b += kb * c;
                        *cc += kc * c;
                    }
                }
                for ((b, cc), (kb, kc)) in both.weight[o.clone()]
                    .iter_mut()
                    .zip(colours.weight[o].iter_mut())
                    .zip(kb.iter().zip(kc.iter()))
                {
                    *b += kb;
                    *cc += kc;
                }
            }
        }
    }
}

/// A feature's distances between the pixels `i` and `j` (runs of a row),
/// into `out` (or the larger of it and them, with `max`): the squared
/// difference less the noise of the two means, times i's scale, at
/// least 0 (Rousselle 2013).
fn feature_distances(
    f: &[Vec<f32>; 3],
    var: &[f32],
    scale: &[f32],
    i: &std::ops::Range<usize>,
    j: &std::ops::Range<usize>,
    out: &mut [f32],
    max: bool,
) {
    let (vi, vj, si) = (&var[i.clone()], &var[j.clone()], &scale[i.clone()]);
    let [a, b, c] = f.each_ref().map(|p| (&p[i.clone()], &p[j.clone()]));
    let pairs = a.0.iter().zip(a.1).zip(b.0.iter().zip(b.1)).zip(c.0.iter().zip(c.1));
    for ((((o, vi), vj), si), (((ai, aj), (bi, bj)), (ci, cj))) in out.iter_mut().zip(vi).zip(vj).zip(si).zip(pairs) {
        let (x, y, z) = (ai - aj, bi - bj, ci - cj);
        let d = ((x * x + y * y + z * z - (vi + vi.min(*vj))) * si).max(0.0);
        *o = if max { o.max(d) } else { d };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reconstruct::Features;
    use crate::types::DVec3;

    /// A reproducible uniform in [−1, 1) for sample `k` (a 64-bit mix).
    fn noise(k: u64) -> f64 {
        let mut z = k.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    /// An image `w` pixels wide and `h` high of 4 samples a pixel: a pixel
    /// of column x has the true colour and surface colour `truth(x)`, each
    /// sample's colour off by up to `spread` (the surface colour and the
    /// normal exact).
    fn image(w: usize, h: usize, spread: f64, truth: impl Fn(usize) -> (f64, f64)) -> Vec<Gathered> {
        (0..w * h)
            .map(|i| {
                let (colour, albedo) = truth(i % w);
                let f = Features {
                    albedo: Intensity::splat(albedo),
                    normal: DVec3::Z,
                    object: Some(0),
                };
                let mut g = Gathered::default();
                for s in 0..4 {
                    g.add(Intensity::splat(colour + spread * noise((i * 4 + s) as u64)), &f);
                }
                g
            })
            .collect()
    }

    /// The mean squared error of the red channel over the columns `xs` of
    /// an image `w` wide.
    fn mse(c: &[Intensity], w: usize, xs: std::ops::Range<usize>, truth: impl Fn(usize) -> f64) -> f64 {
        let at: Vec<usize> = (0..c.len()).filter(|i| xs.contains(&(i % w))).collect();
        at.iter().map(|&i| (c[i].x - truth(i % w)).powi(2)).sum::<f64>() / at.len() as f64
    }

    /// The mean of the red channel down column `x` of an image `w` wide.
    fn column(c: &[Intensity], w: usize, x: usize) -> f64 {
        let h = c.len() / w;
        (0..h).map(|y| c[y * w + x].x).sum::<f64>() / h as f64
    }

    /// Noise over a plain surface is smoothed: a quarter of the box's
    /// error or less (a fifth, measured).
    #[test]
    fn noise_on_a_plain_surface_is_smoothed() {
        let w = 32;
        let pixels = image(w, w, 0.3, |_| (0.5, 0.5));
        let boxed: Vec<Intensity> = pixels.iter().map(Gathered::mean).collect();
        let out = denoise(&pixels, w);
        let (before, after) = (mse(&boxed, w, 0..w, |_| 0.5), mse(&out, w, 0..w, |_| 0.5));
        assert!(after < before / 4.0, "{before} → {after}");
    }

    /// An edge (colours 0.3 and 0.7, surface colours 0.2 and 0.8) under
    /// noise of ±0.6 a sample: the two columns each side of it keep their
    /// own colour (their means within 0.04 of it, 0.03 measured; a 3×3
    /// box would put them 0.13 off) and are smoothed (0.4 of the box's
    /// error or less, 0.35 measured).
    #[test]
    fn an_edge_is_kept_and_each_side_smoothed() {
        let (w, h) = (16, 256);
        let truth = |x: usize| if x < w / 2 { (0.3, 0.2) } else { (0.7, 0.8) };
        let pixels = image(w, h, 0.6, truth);
        let boxed: Vec<Intensity> = pixels.iter().map(Gathered::mean).collect();
        let out = denoise(&pixels, w);
        let edge = w / 2 - 2..w / 2 + 2;
        for x in edge.clone() {
            let m = column(&out, w, x);
            assert!((m - truth(x).0).abs() < 0.04, "column {x}: {m}");
        }
        let (before, after) = (
            mse(&boxed, w, edge.clone(), |x| truth(x).0),
            mse(&out, w, edge, |x| truth(x).0),
        );
        assert!(after < before * 0.4, "{before} → {after}");
    }

    /// Nothing to filter: no pixels, or an image no pixels wide.
    #[test]
    fn an_empty_image() {
        assert!(denoise(&[], 4).is_empty());
        assert!(denoise(&[Gathered::default(); 3], 0).is_empty());
    }
}

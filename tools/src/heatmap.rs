//! `tools heatmap DECK`: where `--sampler adaptive` spent its rays. The
//! image and, beside it, a heat map of the primary rays each pixel got
//! (black: the fewest, through red and yellow to white: the most), with a
//! scale strip below the map.

use std::path::Path;

use raytrace::options::{Fidelity, Options, TimeSampler};
use raytrace::raster::{rgbtochars, Raster};

/// Black → red → yellow → white for `f` in [0, 1].
pub fn heat(f: f64) -> [u8; 3] {
    let f = f.clamp(0.0, 1.0) * 3.0;
    let c = |x: f64| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    [c(f), c(f - 1.0), c(f - 2.0)]
}

/// The picture: the image, a gap of 4 pixels, the heat map of `counts`
/// (each count over the largest), and under the map a strip 8 pixels high
/// of the scale from 0 to the largest count.
pub fn side_by_side(image: &Raster, counts: &[u32]) -> Raster {
    let (w, h) = (image.width, image.height);
    let gap = 4;
    let strip = 8;
    let width = 2 * w + gap;
    let height = h + gap + strip;
    let mut pixels = vec![[255u8; 3]; width * height];
    let top = counts.iter().copied().max().unwrap_or(1).max(1) as f64;
    for y in 0..h {
        for x in 0..w {
            pixels[y * width + x] = image.pixels[y * w + x];
            pixels[y * width + w + gap + x] = heat(counts[y * w + x] as f64 / top);
        }
    }
    for y in h + gap..height {
        for x in 0..w {
            pixels[y * width + w + gap + x] = heat(x as f64 / (w - 1).max(1) as f64);
        }
    }
    Raster { width, height, pixels }
}

/// Renders `deck` with `--sampler adaptive` at `size` (W×H) pixels and a
/// budget of `mask`² rays a pixel: the image beside its heat map, and the
/// rays each pixel got.
pub fn draw(deck: &Path, (width, height): (usize, usize), mask: usize) -> Result<(Raster, Vec<u32>), String> {
    let opts = Options {
        fidelity: Fidelity::Thesis,
        sampler: TimeSampler::Adaptive,
        ..Options::default()
    };
    let name = deck.to_string_lossy();
    let scene = crate::decks::prepared(&name, &opts, Some((width, height, mask)))?;
    let render = crate::decks::still(&scene);
    let (colours, counts) = (render.colours, render.counts);
    let image = Raster {
        width,
        height,
        pixels: colours.iter().map(|&c| rgbtochars(c)).collect(),
    };
    Ok((side_by_side(&image, &counts), counts))
}

/// [`draw`], written to `out` (PNG). Prints the counts' range.
pub fn run(deck: &Path, out: &Path, size: (usize, usize), mask: usize) -> Result<(), String> {
    let (picture, counts) = draw(deck, size, mask)?;
    raytrace::raster::write_png(out, &picture).map_err(|e| format!("{}: {e}", out.display()))?;
    let (lo, hi) = (
        counts.iter().copied().min().unwrap_or(0),
        counts.iter().copied().max().unwrap_or(0),
    );
    let at_first = counts.iter().filter(|&&n| n == lo).count();
    println!(
        "wrote {}: {}×{}, {} rays a pixel on average, {lo} to {hi} a pixel ({:.0} % of the pixels at {lo})",
        out.display(),
        size.0,
        size.1,
        mask * mask,
        100.0 * at_first as f64 / counts.len() as f64
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heat_runs_black_red_yellow_white() {
        assert_eq!(heat(0.0), [0, 0, 0]);
        assert_eq!(heat(1.0 / 3.0), [255, 0, 0]);
        assert_eq!(heat(2.0 / 3.0), [255, 255, 0]);
        assert_eq!(heat(1.0), [255, 255, 255]);
    }

    /// The image on the left, the map on the right (the most rays white,
    /// the fewest black), the scale below the map.
    #[test]
    fn lays_out_image_and_map() {
        let image = Raster {
            width: 2,
            height: 1,
            pixels: vec![[10, 20, 30], [40, 50, 60]],
        };
        let p = side_by_side(&image, &[4, 16]);
        assert_eq!((p.width, p.height), (8, 13));
        assert_eq!(&p.pixels[0..2], &image.pixels[..]);
        assert_eq!(p.pixels[6], heat(0.25));
        assert_eq!(p.pixels[7], [255, 255, 255]);
        assert_eq!(p.pixels[5 * 8 + 6], [0, 0, 0]);
        assert_eq!(p.pixels[5 * 8 + 7], [255, 255, 255]);
    }
}

//! A picture as it renders (`raytrace --show`, `--watch`): the port's
//! extension (the thesis's program wrote its raster and psout showed it
//! afterwards; POV-Ray draws its picture as it goes). The window-free
//! part: the image rendered in bands of rows through the one
//! `render(&Prepared, &Request)` (each band a window of the request, so
//! the bands make the very image a whole render makes), the picture so far
//! with the rows not yet rendered black, the quick pass `--watch` shows
//! first, and the deck file's stamp that tells it changed. The window is
//! `src/bin/raytrace/show.rs`.

use std::ops::Range;
use std::path::Path;
use std::time::SystemTime;

use crate::raster::Raster;
use crate::raytrace::{render, Prepared, Render, RenderError, Request};
use crate::reconstruct::Reconstruction;

/// Rows of final pixels a band: small enough that the picture fills in
/// steps a person sees, large enough that each band keeps the threads busy.
pub const BAND_ROWS: usize = 8;

/// The bands of `height` rows, `rows` rows each (the last may be shorter).
pub fn bands(height: usize, rows: usize) -> Vec<Range<usize>> {
    let rows = rows.max(1);
    (0..height).step_by(rows).map(|r| r..(r + rows).min(height)).collect()
}

/// Renders `request` (its rows, or the whole image) band by band, calling
/// `on_band` with each finished band (its rows and pixels) in order; it
/// returns `false` to stop, and then the result is `None`. The bands
/// joined are the render of the whole request: the same raster, colours,
/// counts and statistics. `--sampler adaptive` deals its rays over the
/// whole image, and `--denoise` and `--coherence` would render the rows
/// their filter or cells reach again for every band: these render in one
/// band.
pub fn render_in_bands(
    prepared: &Prepared,
    request: &Request,
    mut on_band: impl FnMut(&Render) -> bool,
) -> Result<Option<Render>, RenderError> {
    let height = prepared.scene().image.height;
    let whole = request.rows.clone().unwrap_or(0..height);
    if !prepared.options().sampler.renders_windows() || request.reconstruction != Reconstruction::Box {
        let r = render(prepared, request)?;
        return Ok(on_band(&r).then_some(r));
    }
    let mut joined: Option<Render> = None;
    for band in bands(whole.len(), BAND_ROWS) {
        let rows = whole.start + band.start..whole.start + band.end;
        let part = render(prepared, &request.clone().rows(rows))?;
        if !on_band(&part) {
            return Ok(None);
        }
        joined = Some(match joined {
            None => part,
            Some(mut j) => {
                j.rows.end = part.rows.end;
                j.colours.extend(part.colours);
                j.raster.height += part.raster.height;
                j.raster.pixels.extend(part.raster.pixels);
                j.counts.extend(part.counts);
                j.stats += part.stats;
                j.nonfinite += part.nonfinite;
                j
            }
        });
    }
    match joined {
        Some(r) => Ok(Some(r)),
        None => render(prepared, request).map(Some),
    }
}

/// The picture so far: the image's size, black where no band has come.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Progressive {
    pub raster: Raster,
}

impl Progressive {
    /// A black picture of `width`×`height`.
    pub fn new(width: usize, height: usize) -> Progressive {
        Progressive {
            raster: Raster {
                width,
                height,
                pixels: vec![[0, 0, 0]; width * height],
            },
        }
    }

    /// Puts a finished band in its rows.
    pub fn band(&mut self, part: &Render) {
        let w = self.raster.width;
        let at = part.rows.start * w;
        let n = part
            .raster
            .pixels
            .len()
            .min(self.raster.pixels.len().saturating_sub(at));
        self.raster.pixels[at..at + n].copy_from_slice(&part.raster.pixels[..n]);
    }

    /// Fills the whole picture with `small` enlarged by pixel replication
    /// (the quick pass, shown until the bands replace it).
    pub fn fill_from(&mut self, small: &Raster) {
        let (w, h) = (self.raster.width, self.raster.height);
        if small.width == 0 || small.height == 0 {
            return;
        }
        for y in 0..h {
            let sy = y * small.height / h;
            for x in 0..w {
                let sx = x * small.width / w;
                self.raster.pixels[y * w + x] = small.pixels[sy * small.width + sx];
            }
        }
    }
}

/// The quick pass's size: a quarter of the image's on each side (at least
/// one pixel), one ray a pixel.
pub fn quick_size(width: usize, height: usize) -> (usize, usize, usize) {
    ((width / 4).max(1), (height / 4).max(1), 1)
}

/// What tells that a file changed: its modification time and length, or
/// `None` while it cannot be read (an editor replacing it).
pub fn stamp(path: &Path) -> Option<(SystemTime, u64)> {
    let m = std::fs::metadata(path).ok()?;
    Some((m.modified().ok()?, m.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_cover_the_rows_in_order() {
        assert_eq!(bands(20, 8), vec![0..8, 8..16, 16..20]);
        assert_eq!(bands(3, 8), vec![0..3]);
        assert!(bands(0, 8).is_empty());
    }

    #[test]
    fn a_quick_pass_fills_the_picture_enlarged() {
        let mut p = Progressive::new(4, 2);
        let small = Raster {
            width: 2,
            height: 1,
            pixels: vec![[1, 1, 1], [2, 2, 2]],
        };
        p.fill_from(&small);
        assert_eq!(p.raster.pixels[..4], [[1, 1, 1], [1, 1, 1], [2, 2, 2], [2, 2, 2]]);
        assert_eq!(p.raster.pixels[4..], p.raster.pixels[..4]);
        assert_eq!(quick_size(256, 3), (64, 1, 1));
    }

    #[test]
    fn a_file_changed_has_another_stamp() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("d");
        assert_eq!(stamp(&f), None);
        std::fs::write(&f, "a").unwrap();
        let first = stamp(&f).unwrap();
        std::fs::write(&f, "ab").unwrap();
        assert_ne!(stamp(&f), Some(first));
    }
}

//! The rendered object beside the plane: the deck's scene with the edited
//! contour, prepared ([`Prepared`]) at a small size and rendered by the one
//! `render(&Prepared, &Request)`, still (no blur: the scene at one time).
//! A quick pass comes first, at once after an edit; a finer one when the
//! editor is idle, in windows of rows so that a newer edit can stop it.

use super::document::Document;
use super::model::Contour;
use crate::options::Options;
use crate::raster::Raster;
use crate::raytrace::{render, Prepared, Request};
use crate::scene::Scene;

/// A preview's size and rays a pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pass {
    /// Pixels along the image's longer side (the deck's aspect kept).
    pub long_side: usize,
    /// M×M rays a pixel; `None` for the deck's mask.
    pub mask: Option<usize>,
}

/// The pass after an edit: 128 pixels a side, one ray a pixel.
pub const QUICK: Pass = Pass {
    long_side: 128,
    mask: Some(1),
};

/// The pass when idle: 384 pixels a side (the preview's box, one screen
/// pixel a pixel), the deck's subpixels.
pub const FINE: Pass = Pass {
    long_side: 384,
    mask: None,
};

/// The rows a window of the fine pass renders before it looks for a
/// newer edit.
pub(crate) const ROWS_A_WINDOW: usize = 16;

/// What to render: the scene with the contour, and the time it is shown at.
#[derive(Clone, Debug)]
pub struct Job {
    pub scene: Scene,
    pub opts: Options,
    /// The shutter time the scene stands still at (a key-frame chain's
    /// slider; 0 otherwise: every object where the deck puts it).
    pub time: f64,
}

impl Job {
    /// The job of `doc` with `contour`, at `time`.
    pub fn new(doc: &Document, contour: &Contour, time: f64) -> Job {
        Job {
            scene: doc.scene_with(contour),
            opts: Options {
                fidelity: doc.fidelity,
                ..Options::default()
            },
            time,
        }
    }

    /// The rays a pixel of `pass` (M of M×M).
    pub fn mask(&self, pass: Pass) -> usize {
        pass.mask.unwrap_or(self.scene.image.masksize)
    }

    /// The scene prepared for `pass`: resized (the view kept), then, if
    /// anything moves or deforms, stood still at the job's time.
    pub fn prepare(&self, pass: Pass) -> Result<Prepared, String> {
        let mut scene = self.scene.clone();
        let (w, h) = size(scene.image.width, scene.image.height, pass.long_side);
        scene.resize(w, h, self.mask(pass));
        let prepared = Prepared::new(scene, self.opts).map_err(|e| e.to_string())?;
        Ok(match prepared.timed() {
            true => prepared.still_at(self.time),
            false => prepared,
        })
    }
}

/// The width and height with `long` pixels on the longer side and the
/// aspect of `width`×`height`.
pub fn size(width: usize, height: usize, long: usize) -> (usize, usize) {
    let short = |a: usize, b: usize| ((long * a + b / 2) / b).max(1);
    match width >= height {
        true => (long, short(height, width)),
        false => (short(width, height), long),
    }
}

/// The rows `rows` of a prepared preview as a raster.
pub fn render_rows(prepared: &Prepared, rows: std::ops::Range<usize>) -> Result<Raster, String> {
    let r = render(prepared, &Request::STILL.rows(rows)).map_err(|e| e.to_string())?;
    r.check_finite().map_err(|e| e.to_string())?;
    Ok(r.raster)
}

/// The whole of a pass at once.
pub(crate) fn render_pass(job: &Job, pass: Pass) -> Result<Raster, String> {
    let prepared = job.prepare(pass)?;
    let height = prepared.scene().image.height;
    render_rows(&prepared, 0..height)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_longer_side_gets_the_size_and_the_aspect_stays() {
        assert_eq!(size(256, 256, 128), (128, 128));
        assert_eq!(size(320, 200, 128), (128, 80));
        assert_eq!(size(200, 320, 384), (240, 384));
        assert_eq!(size(1000, 1, 128), (128, 1));
    }
}

//! The main program `raytrace` (OCR text, lines 3013–3229): `initialize`,
//! `getangle`, `goahead` for each key-frame pair, the motion table, the
//! scanline loop with `translookpt`, `motionblur` and `raytrace` for every
//! subpixel, `antialias` of each block of `masksize` scanlines, and
//! `outputframe`.
//!
//! The steps keep the listing's order, in two parts:
//! - [`Prepared::new`]: everything between `initialize` and the scanline
//!   loop, done once (the sweeps' `spline`, `goahead` for every key-frame
//!   pair, the motion table asked of `Isblur`, the lookup tables, the
//!   camera of `getangle`); it fails on a scene that cannot be drawn.
//! - [`render`]: the scanline loop over a window of the image's rows for
//!   one frame ([`Request`]), returning the colours, the raster and the
//!   counts ([`Render`]).
//!
//! What changes is the sharing (legacy_pascal/README.md, "State"): the prepared scene is
//! read-only while rendering, rows of pixels are traced in parallel, each
//! worker poses the scene in its own scratch, and every lookup-table
//! cursor is a function of the subpixel (`crate::sampler`), so an image is
//! the same for any number of threads and equal to the listing's
//! sequential order.
//!
//! Reconstructed here, as the thesis does not print them: `getangle`,
//! `translookpt` (`camera`), `antialias`, and where on the screen a
//! subpixel lies. The port's beside them: the pixels made from their
//! samples otherwise ([`Request::reconstruction`]: `--denoise`, and the
//! thesis's coherence of §2.1.2, `--coherence N`, which it describes and
//! does not build).

mod camera;
mod coherent;
mod lens;
mod passes;
mod prepare;
mod scanline;
mod tracer;

use std::ops::Range;

pub use camera::{getangle, translookpt, Camera};
pub use lens::Lens;
pub use prepare::{key_frame_chains, time_table, Prepared};

use crate::film::Frame;
use crate::raster::{rgbtochars, Raster};
use crate::reconstruct::{denoise, Reconstruction};
use crate::sampler::{GridKind, GridSampler, Layout};
use crate::scene::Pos;
use crate::trace::TraceStats;
use crate::types::{Intensity, IntersectionRecord, Ray};

/// A scene or a request the renderer cannot draw.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// A record that does not fit the rest of the scene.
    #[error("{pos}: {record}: {message}")]
    Misfit {
        pos: Pos,
        record: &'static str,
        message: String,
    },
    /// Options that cannot be used together, or with this scene.
    #[error("{0}")]
    Options(String),
    /// A window of rows that is not part of the image, or that the sampler
    /// cannot render alone.
    #[error("{0}")]
    Window(String),
    /// Pixels whose colour came out NaN or infinite (the port's extension:
    /// the listing wrote them as black). The deck reader's ranges keep every
    /// deck in range from this; it is the last guard, so that such an image
    /// is refused rather than written.
    #[error("{pixels} of {total} pixels have a colour that is not finite (NaN or infinite): the scene's numbers overflowed; nothing was written")]
    NonFinite { pixels: usize, total: usize },
}

/// What to render of a prepared scene: which frame, which rows, how its
/// pixels are made from their samples, and whom to tell as rows finish.
#[derive(Clone)]
pub struct Request<'a> {
    /// The film frame the sampler's times τ fall in ([`Frame::STILL`]
    /// outside a film).
    pub frame: Frame,
    /// The rows of final pixels to render, row 0 at the top; `None` for
    /// the whole image.
    pub rows: Option<Range<usize>>,
    /// How the pixels are made from their samples: `antialias`'s box
    /// (the default), `--denoise`, `--coherence N`.
    pub reconstruction: Reconstruction,
    /// Called once for each finished row of final pixels (from worker
    /// threads), for a progress bar.
    pub progress: Option<&'a (dyn Fn() + Sync)>,
}

impl Default for Request<'_> {
    fn default() -> Self {
        Request::STILL
    }
}

impl<'a> Request<'a> {
    /// The whole still.
    pub const STILL: Request<'static> = Request {
        frame: Frame::STILL,
        rows: None,
        reconstruction: Reconstruction::Box,
        progress: None,
    };

    /// The whole of film frame `frame`.
    pub fn frame(frame: Frame) -> Request<'static> {
        Request {
            frame,
            ..Request::STILL
        }
    }

    /// This request for the rows `rows` only.
    pub fn rows(self, rows: Range<usize>) -> Self {
        Request {
            rows: Some(rows),
            ..self
        }
    }

    /// This request, its pixels made by `reconstruction`.
    pub fn reconstruction(self, reconstruction: Reconstruction) -> Self {
        Request { reconstruction, ..self }
    }

    /// This request, calling `progress` as rows finish.
    pub fn progress(self, progress: &'a (dyn Fn() + Sync)) -> Request<'a> {
        Request {
            progress: Some(progress),
            ..self
        }
    }
}

/// What a render returns: the window's pixels as colours and as a raster,
/// the rays each pixel got, and the counts.
#[derive(Clone, Debug)]
pub struct Render {
    /// The rows rendered, row 0 at the top of the image.
    pub rows: Range<usize>,
    /// Each pixel's colour before `rgbtochars` clamps and rounds it (row by
    /// row from the window's first), for checks that must see a NaN or a
    /// colour above 1.
    pub colours: Vec<Intensity>,
    /// The raster `outputframe` writes: the window's rows.
    pub raster: Raster,
    /// The primary rays each pixel got: `masksize`² for the samplers of
    /// the subpixel grid, the pixel's share for `--sampler adaptive`; with
    /// `--coherence`, 0 for a pixel interpolated.
    pub counts: Vec<u32>,
    pub stats: TraceStats,
    /// Pixels whose colour was NaN or infinite before `rgbtochars` (which
    /// would write them black); see [`Render::check_finite`].
    pub nonfinite: usize,
}

impl Render {
    /// An error if any pixel's colour was not finite: such a raster must
    /// not be written.
    pub fn check_finite(&self) -> Result<(), RenderError> {
        match self.nonfinite {
            0 => Ok(()),
            pixels => Err(RenderError::NonFinite {
                pixels,
                total: self.raster.pixels.len(),
            }),
        }
    }
}

/// What a scanline loop gives: each pixel's colour and primary rays, and
/// the counts.
struct Traced {
    colours: Vec<Intensity>,
    counts: Vec<u32>,
    stats: TraceStats,
}

/// The scanline loop of the main program over the request's rows of a
/// prepared scene, for the request's frame: each subpixel's time τ from
/// the sampler becomes the film time [`Frame::time`] before `motionblur`
/// and the key-frame chains see it. `--sampler adaptive` deals its rays
/// over the whole image, so it renders no window but the whole.
pub fn render(prepared: &Prepared, request: &Request) -> Result<Render, RenderError> {
    let img = &prepared.scene().image;
    let rows = request.rows.clone().unwrap_or(0..img.height);
    if rows.is_empty() || rows.end > img.height {
        return Err(RenderError::Window(format!(
            "rows {}..{} are not a window of the image's {} rows",
            rows.start, rows.end, img.height
        )));
    }
    let progress = request.progress.unwrap_or(&|| {});
    let sampler = prepared.options().sampler;
    if !sampler.renders_windows() && rows != (0..img.height) {
        return Err(RenderError::Window(
            "--sampler adaptive deals its rays over the whole image, so a window of it would be another picture: render the whole image".into(),
        ));
    }
    let layout = Layout::of(sampler);
    let traced = match (request.reconstruction, layout) {
        (Reconstruction::Box, Layout::Adaptive) => passes::render_adaptive(prepared, request.frame, progress),
        (Reconstruction::Box, Layout::Grid(kind)) => {
            scanline::render_grid(prepared, kind, request.frame, rows.clone(), progress)
        }
        (Reconstruction::Denoise, _) => denoised(prepared, layout, request.frame, rows.clone(), progress),
        (Reconstruction::Coherence(step), _) => {
            coherent::render(prepared, request.frame, rows.clone(), step, progress)?
        }
    };
    let nonfinite = traced.colours.iter().filter(|c| !c.is_finite()).count();
    let raster = Raster {
        width: img.width,
        height: rows.len(),
        pixels: traced.colours.iter().map(|&c| rgbtochars(c)).collect(),
    };
    Ok(Render {
        rows,
        colours: traced.colours,
        raster,
        counts: traced.counts,
        stats: traced.stats,
        nonfinite,
    })
}

/// The rows `rows` of frame `frame`, each pixel from its own samples and
/// its neighbours' ([`denoise`]): the rows within the filter's reach
/// ([`denoise::REACH`]) above and below are rendered too and cut, so a
/// band is the whole image's band.
fn denoised(
    prepared: &Prepared,
    layout: Layout,
    frame: Frame,
    rows: Range<usize>,
    progress: &(dyn Fn() + Sync),
) -> Traced {
    let img = &prepared.scene().image;
    let w = img.width;
    let (gathered, stats, window) = match layout {
        Layout::Adaptive => {
            let (gathered, traced) = passes::gather_adaptive(prepared, frame, progress);
            (gathered, traced.stats, 0..img.height)
        }
        Layout::Grid(kind) => {
            let reach = denoise::REACH;
            let window = rows.start.saturating_sub(reach)..(rows.end + reach).min(img.height);
            let (gathered, stats) =
                scanline::gather_grid(prepared, kind, frame, window.clone(), rows.clone(), progress);
            (gathered, stats, window)
        }
    };
    let cut = (rows.start - window.start) * w..(rows.end - window.start) * w;
    let colours = denoise::denoise(&gathered, w);
    Traced {
        colours: colours[cut.clone()].to_vec(),
        counts: gathered[cut].iter().map(|g| g.n).collect(),
        stats,
    }
}

/// `raytrace` of one primary ray `aray` with the scene at film time `time`
/// (at rest when nothing moves), as the scanline loop traces a subpixel's
/// ray; its further dimensions are those of the image's first subpixel.
/// For tests and tools that look at single rays. The adaptive sampler
/// lays no grid: its single ray takes the thesis's table's.
pub fn trace_ray(prepared: &Prepared, aray: &Ray, time: f64) -> (Intensity, TraceStats) {
    let img = &prepared.scene().image;
    let kind = match Layout::of(prepared.options().sampler) {
        Layout::Grid(kind) => kind,
        Layout::Adaptive => GridKind::Table,
    };
    let mut sampler = GridSampler::new(
        prepared.tables(),
        kind,
        prepared.options().fidelity,
        img.width,
        img.masksize,
        img.aliasing,
    );
    sampler.start(1, 1);
    let mut tracer = tracer::Tracer::new(prepared);
    if prepared.timed() {
        tracer.at_any(time);
    }
    let colour = tracer.shoot(aray, &mut sampler);
    (colour, tracer.stats)
}

/// The object `ray` meets first, and the hit, with the scene at film time
/// `time`, or with every object at rest (where the deck puts it, a
/// key-frame object in its shape of time 0) for `None`: for tools that look
/// at what rays see (the solvers' misses, the silhouettes).
pub fn first_hit(prepared: &Prepared, ray: &Ray, time: Option<f64>) -> Option<IntersectionRecord> {
    let mut tracer = tracer::Tracer::new(prepared);
    if let Some(time) = time.filter(|_| prepared.timed()) {
        tracer.at_any(time);
    }
    tracer.first_hit(ray)
}

/// The lines the listing writes to `debugf` for a frame: first what
/// `goahead` writes for each key-frame pair ([`crate::paper::PaperChain`]'s
/// pairs in order, `PaperPair::debug_lines`, with the expanders' messages,
/// which the listing wrote to standard output), then one line per scanline
/// of the subpixel raster the render traced, `kfTIRcnt`, and the frame's
/// end.
pub fn debug_log(prepared: &Prepared, render: &Render) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    for chain in prepared.chains() {
        for pair in chain.pairs() {
            for line in pair.debug_lines() {
                let _ = writeln!(s, "{line}");
            }
        }
    }
    let m = prepared.scene().image.masksize;
    for scanline in render.rows.start * m + 1..=render.rows.end * m {
        let _ = writeln!(s, " scanline={scanline:5}");
    }
    let _ = writeln!(s, "kfTIRcnt={:9}", render.stats.kftircnt);
    let _ = writeln!(s);
    let _ = writeln!(s, "FRAME NUMBER{:4}---DONE", 1);
    s
}

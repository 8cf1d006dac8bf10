//! Where and when each sample of a pixel falls: one sampler interface for
//! every way of choosing them (the port's; the thesis's own choice, the
//! pattern table of Fig. 2.33 with the lookup-table cursors of the main
//! program and `motionblur`, is one of them).
//!
//! In the spirit of pbrt-v4's samplers: a sample is started for a pixel
//! and an index in it, then asked for what it needs.
//! - **Time** is a call of its own ([`Sampler::time`]): the renderer poses
//!   the scene for it, and the adaptive sampler lets a row's pixels share
//!   instants, so the scene is posed once an instant.
//! - **The place in the pixel** ([`Sampler::camera`]): where the primary
//!   ray crosses the screen.
//! - **Further dimensions** come by a counter, one value
//!   ([`Sampler::get_1d`]) or a pair ([`Sampler::get_2d`]) at a time, each
//!   from its own dimension, so that no dimension decides another (Cook
//!   1984: a ray's time must not decide its lens position). The renderer
//!   hands the sample to shading ([`crate::trace::Context`]), where a lens
//!   point, a light point or a gloss turn would draw them.
//!
//! Two families, by how samples are laid out:
//! - [`GridSampler`] (`--sampler table|random|stratified|sobol`): one sample a
//!   subpixel of the listing's scanline loop, `masksize`² a pixel. Its
//!   place is the listing's `noise2[aindex]` jitter of the subpixel; its
//!   time the thesis's table (`mindex`), an independent uniform, or one
//!   time in each stratum of the shutter; its further dimensions the
//!   table's own cursors (`dindex` into `noise`, as `depthoffield` reads
//!   it), independent uniforms, or strata. `sobol` takes place, time and
//!   further dimensions from one point of the pixel's Sobol sequence.
//! - [`PixelSampler`] (`--sampler adaptive`): sample j of a pixel, any
//!   number a pixel, from a scrambled Sobol sequence ([`sobol`]); the
//!   grid's `--sampler sobol` takes a pixel's first M² points of such a
//!   sequence for its M² subpixels.
//!
//! Every value depends on the sample's pixel and index only, never on the
//! thread or the order samples are taken in: an image is the same for any
//! number of threads and for any window of rows rendered alone.

mod array;
mod grid;
mod keys;
mod pixel;
pub mod sobol;
mod warp;

pub use grid::{GridKind, GridSampler, Layout, Tables, TABLE_DIMENSIONS};
pub use keys::{random_time, strata, stratified_time};
pub use pixel::{further_dimension, sample, PixelSampler, PixelSamples, Sample, SHIFT_BLOCK};
pub use warp::{concentric_disk, uniform_cone};

/// Where a primary ray crosses the screen, in the units the camera takes
/// ([`crate::raytrace::Camera::ray`]): the subpixel (`scancol`, `scanline`,
/// 1-based as in the listing, scanline 1 at the top) and the jitter (`jx`,
/// `jz`) it is moved by, in subpixels. Kept apart, not summed, because the
/// listing's screen formula adds them where the camera does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSample {
    pub scancol: f64,
    pub scanline: f64,
    pub jx: f64,
    pub jz: f64,
}

/// A column, row or count of the screen (`scancol`, a pixel's x,
/// `masksize`) as a float for [`CameraSample`]: through `i64`, a single
/// instruction on x86-64 where an unsigned conversion takes several; the
/// same value, such numbers being far below 2⁶³.
#[inline(always)]
pub(crate) fn screen_f64(n: usize) -> f64 {
    n as i64 as f64
}

/// The sample being traced: its time, its place in the pixel, and as many
/// further dimensions as shading asks for (module documentation). Started
/// by the family's own `start` ([`GridSampler::start`],
/// [`PixelSampler::start`]); every call after that reads the same sample.
pub trait Sampler {
    /// τ, the sample's time in the shutter: in [0, 1) but for the listing's
    /// table, whose times reach 1.5 (erratum 2).
    fn time(&mut self) -> f64;

    /// Where the primary ray crosses the screen.
    fn camera(&self) -> CameraSample;

    /// The next further dimension, in [0, 1).
    fn get_1d(&mut self) -> f64;

    /// The next two further dimensions, in [0, 1)².
    fn get_2d(&mut self) -> [f64; 2] {
        let a = self.get_1d();
        [a, self.get_1d()]
    }
}

/// A sampler for tests: time 0, the first subpixel's place, and its
/// further dimensions from a list, in turn (`Listed(values, 0)`).
#[cfg(test)]
pub(crate) struct Listed(pub Vec<f64>, pub usize);

#[cfg(test)]
impl Sampler for Listed {
    fn time(&mut self) -> f64 {
        0.0
    }
    fn camera(&self) -> CameraSample {
        CameraSample {
            scancol: 1.0,
            scanline: 1.0,
            jx: 0.0,
            jz: 0.0,
        }
    }
    fn get_1d(&mut self) -> f64 {
        let v = self.0[self.1 % self.0.len()];
        self.1 += 1;
        v
    }
}

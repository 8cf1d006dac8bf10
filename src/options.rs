//! How to render: the choices that are not part of the scene (the
//! command line's `--fidelity`, `--solver`, `--sampler`, `--accel`). The port's;
//! every unit of the thesis reads its fidelity from here.
//!
//! The command line (feature `cli`) takes these enums as they are
//! (`clap::ValueEnum`): a value's name is the variant's in lower case, and
//! the first paragraph of its doc comment is its line in `--help`.

/// Which of two behaviours to follow where the printed listings and the
/// thesis text disagree (legacy_pascal/DEVIATIONS.md lists every place).
///
/// Only the code of an erratum branches on this; each branch quotes both
/// formulas.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Fidelity {
    /// Reproduce the printed listings, quirks included.
    Listing,
    /// Follow the thesis text where the listing disagrees.
    #[default]
    Thesis,
}

/// The root solver of the sweep intersection (`--solver`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Solver {
    /// `laguerre` as printed (§2.5): the thesis's method and the default.
    #[default]
    Laguerre,
    /// Every real root in the interval, isolated and polished; not the
    /// thesis's method.
    Robust,
}

/// How each subpixel's time is chosen (`--sampler`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum TimeSampler {
    /// The pattern lookup table of §2.6.4 (Fig. 2.33) with the CLT jitter
    /// of §2.6.5, as the fidelity reads them: the thesis's method and the
    /// default.
    #[default]
    Table,
    /// An independent uniform time for every subpixel; not the thesis's.
    Random,
    /// One uniform time in each of the M² strata of the shutter, the strata
    /// dealt to the subpixels by a permutation of the pixel's own, as
    /// renderers later came to do; not the thesis's.
    Stratified,
    /// M² rays a pixel, the first M² points of an Owen-scrambled Sobol
    /// sequence over the place in the pixel, the time and every further
    /// dimension (lens, light, gloss) together, scrambled pixel by pixel;
    /// not the thesis's.
    Sobol,
    /// M² rays a pixel on average, dealt out by each pixel's need, at
    /// scrambled Sobol places and times; not the thesis's.
    ///
    /// See [`crate::adaptive`].
    Adaptive,
}

impl TimeSampler {
    /// Whether a window of the image's rows (a band of `--tile`, of the
    /// `--show` window, of a farm) renders as those rows of the whole
    /// image. Every sampler of the subpixel grid does; the adaptive sampler
    /// deals its rays over the whole image by need, so a window of it would
    /// be another picture.
    pub fn renders_windows(self) -> bool {
        match self {
            TimeSampler::Table | TimeSampler::Random | TimeSampler::Stratified | TimeSampler::Sobol => true,
            TimeSampler::Adaptive => false,
        }
    }
}

/// `--accel`: how the objects a ray may meet are found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Accel {
    /// The loop below 9 objects, the bounding volume hierarchy from there (as
    /// POV-Ray's Bounding_Threshold).
    #[default]
    Auto,
    /// The original's loop: every object in turn, behind its bounding sphere.
    None,
    /// A bounding volume hierarchy: the thesis's clusters (Fig. 2.12); not the
    /// thesis's code.
    Bvh,
    /// The thesis's space subdivision (Fig. 2.15), an octree searched by
    /// LISTING 1's `findnode`.
    Octree,
}

/// From this many objects `auto` takes the hierarchy; below, the loop.
/// Measured (docs/scale.md): on random spheres and on fig5_6's stars over
/// a floor, the loop is faster up to 7 objects, the two are even at 8, and
/// the hierarchy is faster from 9 (by 20 % at 13).
pub const THRESHOLD: usize = 9;

impl Accel {
    /// What `auto` means for a scene of `objects` objects; the others as
    /// they are.
    pub fn resolve(self, objects: usize) -> Accel {
        match self {
            Accel::Auto if objects < THRESHOLD => Accel::None,
            Accel::Auto => Accel::Bvh,
            other => other,
        }
    }
}

/// How to render: the choices that are not part of the scene, in one
/// place. The worker threads are not among them (the image is the same for
/// any number): they are the pool a program renders in (`--threads`,
/// `cli::RenderArgs::thread_pool`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Options {
    pub fidelity: Fidelity,
    pub solver: Solver,
    pub sampler: TimeSampler,
    /// How the objects a ray may meet are found ([`crate::accel`]).
    pub accel: Accel,
}

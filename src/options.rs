//! How to render: the choices that are not part of the scene (the
//! command line's `--fidelity`, `--solver`, `--sampler`). The port's;
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

/// How to render: the choices that are not part of the scene.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Options {
    pub fidelity: Fidelity,
    pub solver: Solver,
    pub sampler: TimeSampler,
}

//! Reconstruction: how a pixel's colour is made from its samples. The
//! port's part beside the sampler, as pbrt-v4 keeps its film and filter
//! apart from its samplers: the sampler says where and when a sample
//! falls ([`crate::sampler`]), the tracer returns its colour and, when
//! asked, its [`Features`], and the reconstruction turns samples into
//! pixels.
//!
//! - [`Reconstruction::Box`], the default for both fidelities: each pixel
//!   the mean of its own samples, the listing's `antialias` (§2.1.3 (2),
//!   supersampling).
//! - [`Reconstruction::Denoise`] (`--denoise`, the port's extension): each
//!   pixel from its own and its neighbours' samples, weighted by how alike
//!   their colours and features are, the filter's reach chosen pixel by
//!   pixel from the data ([`denoise`]).
//! - [`Reconstruction::Coherence`] (`--coherence N`): the thesis's
//!   coherence, §2.1.2 (2)(a): every N-th pixel traced, the rest
//!   interpolated where their traced neighbours agree
//!   ([`crate::coherence`]).

pub mod denoise;

use crate::types::{DVec3, Intensity};

/// How the pixels of a render are made from its samples (module
/// documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Reconstruction {
    /// Each pixel the mean of its samples (`antialias`).
    #[default]
    Box,
    /// `--denoise`: a feature-guided filter over the samples of the pixel
    /// and its neighbours ([`denoise`]).
    Denoise,
    /// `--coherence N`: every N-th pixel traced in each direction, the
    /// rest interpolated where the traced ones agree; N in
    /// 1..=[`crate::coherence::MAX_STEP`].
    Coherence(u32),
}

/// What a primary sample's first hit tells besides its colour, for a
/// reconstruction that looks at more than colours. Made only when a
/// render asks for it ([`Reconstruction::Denoise`], `Coherence`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Features {
    /// The colour of the surface itself at the first hit, before light:
    /// its `color`, its pattern's or its texture's; for a light surface
    /// and for the background, the colour the ray returns.
    pub albedo: Intensity,
    /// The unit normal at the first hit, turned to face the ray; zero for
    /// a ray that meets nothing.
    pub normal: DVec3,
    /// The object first met, if any.
    pub object: Option<usize>,
}

/// The sums of a pixel's samples: their colours and features, and the
/// squares that give their spreads.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Gathered {
    /// Samples added.
    pub n: u32,
    colour: Intensity,
    colour_sq: Intensity,
    albedo: Intensity,
    albedo_sq: f64,
    normal: DVec3,
    normal_sq: f64,
    /// A bit for each object its samples met first (object k sets bit k
    /// mod 63), bit 63 for a sample that met nothing.
    pub objects: u64,
}

/// A pixel's means and the variances of those means (the spread of its
/// samples over their number: how far the mean may be from the pixel's
/// true value), what [`denoise`] reads.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelMeans {
    pub colour: Intensity,
    /// The variance of the mean colour, channel by channel; `None` for a
    /// pixel of fewer than two samples.
    pub colour_var: Option<Intensity>,
    pub albedo: Intensity,
    pub albedo_var: f64,
    pub normal: DVec3,
    pub normal_var: f64,
}

impl Gathered {
    /// One more sample, of colour `colour` and features `f`.
    pub fn add(&mut self, colour: Intensity, f: &Features) {
        self.n += 1;
        self.colour += colour;
        self.colour_sq += colour * colour;
        self.albedo += f.albedo;
        self.albedo_sq += f.albedo.length_squared();
        self.normal += f.normal;
        self.normal_sq += f.normal.length_squared();
        self.objects |= 1 << f.object.map_or(63, |k| k % 63);
    }

    /// The mean colour of the pixel's samples (black without any).
    pub fn mean(&self) -> Intensity {
        match self.n {
            0 => Intensity::ZERO,
            n => self.colour / f64::from(n),
        }
    }

    /// The pixel's means and their variances; zeros for a pixel without
    /// samples.
    pub fn means(&self) -> PixelMeans {
        if self.n == 0 {
            return PixelMeans::default();
        }
        let n = f64::from(self.n);
        // The variance of a mean of n samples: (Σx² − (Σx)²/n) / (n − 1) / n,
        // never below 0 (rounding).
        let spread = |sum_sq: f64, sum_len_sq: f64| match self.n {
            1 => 0.0,
            _ => ((sum_sq - sum_len_sq / n) / ((n - 1.0) * n)).max(0.0),
        };
        let colour_var = (self.n > 1)
            .then(|| ((self.colour_sq - self.colour * self.colour / n) / ((n - 1.0) * n)).max(Intensity::ZERO));
        PixelMeans {
            colour: self.colour / n,
            colour_var,
            albedo: self.albedo / n,
            albedo_var: spread(self.albedo_sq, self.albedo.length_squared()),
            normal: self.normal / n,
            normal_var: spread(self.normal_sq, self.normal.length_squared()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn features(albedo: f64, object: Option<usize>) -> Features {
        Features {
            albedo: Intensity::splat(albedo),
            normal: DVec3::Z,
            object,
        }
    }

    /// The means of known samples, and the variances of those means as a
    /// textbook computes them; one sample has no colour variance.
    #[test]
    fn means_and_their_variances() {
        let mut g = Gathered::default();
        assert_eq!(g.means(), PixelMeans::default());
        g.add(Intensity::new(1.0, 0.0, 0.5), &features(0.2, Some(2)));
        assert_eq!(g.means().colour_var, None);
        assert_eq!(g.means().albedo_var, 0.0);
        g.add(Intensity::new(0.0, 0.0, 0.5), &features(0.4, None));
        let m = g.means();
        assert_eq!(m.colour, Intensity::new(0.5, 0.0, 0.5));
        // Red 1, 0: sample variance 0.5, of the mean 0.25.
        let var = m.colour_var.unwrap();
        assert!(
            (var - Intensity::new(0.25, 0.0, 0.0)).abs().max_element() < 1e-15,
            "{var}"
        );
        // Albedo 0.2 and 0.4 in each of 3 channels: Σ|a − ā|² = 3·0.02 = 0.06, /1 /2.
        assert!((m.albedo_var - 0.03).abs() < 1e-15, "{}", m.albedo_var);
        assert_eq!(m.normal, DVec3::Z);
        assert_eq!(m.normal_var, 0.0);
        assert_eq!(g.objects, 1 << 2 | 1 << 63);
        assert_eq!(g.n, 2);
    }

    /// The normals' spread: two samples facing opposite ways have a mean
    /// of zero and a variance of the mean of 1 (Σ|n|² = 2, over 1 × 2).
    #[test]
    fn the_normals_spread() {
        let mut g = Gathered::default();
        for normal in [DVec3::X, -DVec3::X] {
            let f = Features {
                normal,
                ..features(0.5, Some(0))
            };
            g.add(Intensity::splat(0.5), &f);
        }
        let m = g.means();
        assert_eq!(m.normal, DVec3::ZERO);
        assert!((m.normal_var - 1.0).abs() < 1e-15, "{}", m.normal_var);
        assert_eq!(m.albedo_var, 0.0);
    }

    /// Objects share a bit only 63 apart.
    #[test]
    fn object_bits() {
        let mut g = Gathered::default();
        g.add(Intensity::ZERO, &features(0.0, Some(64)));
        assert_eq!(g.objects, 1 << 1);
        g.add(Intensity::ZERO, &features(0.0, Some(1)));
        assert_eq!(g.objects, 1 << 1);
    }
}

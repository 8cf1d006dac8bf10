//! `tools stability`: the root solvers on hard cases, docs/STABILITY.md.
//!
//! Two kinds of family, every case built from a fixed seed:
//! - root families: constructed polynomials with known roots, solved on
//!   [0, 1] by `laguerre` (listing and thesis fidelity) and by
//!   `real_roots` (the robust solver);
//! - geometric families: constructed rays against constructed sweeps,
//!   intersected by `Sweep::intersect` with each solver, where the true
//!   first hit is known by construction (a ray tangent to, or aimed from
//!   outside at a point of, a convex sweep; a cap or an apex) or
//!   analytically (rotation sweeps of straight segments, which are exact
//!   cylinders and cones).
//!
//! Counted per family and method: the cases, the true roots (hits),
//! those missed, the spurious ones, the worst error of those found, and
//! the time of one solve.
//!
//! One file a part: `roots` and `rays` build the families,
//! `keyframe` the key-frame ones, `soft` the blobs' and patches' (§6.2,
//! the port's extension), `tally` counts what each method does on them,
//! `report` writes the tables.

use raytrace::options::{Fidelity, Options, Solver};

mod keyframe;
mod rays;
mod report;
mod roots;
mod soft;
mod tally;

pub use keyframe::*;
pub use rays::*;
pub use report::run;
pub use roots::*;
pub use soft::*;
pub use tally::*;

/// A root counts as found within this distance of the true root.
pub const ROOT_TOL: f64 = 1e-6;
/// A found root that is not within [`ROOT_TOL`] of a true root but within
/// this is rough (found, inaccurately); farther, spurious.
pub const ROUGH_TOL: f64 = 1e-3;
/// A hit counts as the true one within this distance, relative to the
/// object's size.
pub const HIT_TOL: f64 = 1e-6;
/// How far inside the tangent the grazing rays pass, relative to the size.
pub const GRAZE: f64 = 1e-13;

/// The three methods compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    LaguerreListing,
    LaguerreThesis,
    Robust,
}

pub const METHODS: [Method; 3] = [Method::LaguerreListing, Method::LaguerreThesis, Method::Robust];

impl Method {
    pub fn label(self) -> &'static str {
        match self {
            Method::LaguerreListing => "laguerre, listing",
            Method::LaguerreThesis => "laguerre, thesis",
            Method::Robust => "robust",
        }
    }

    pub fn options(self) -> Options {
        let (fidelity, solver) = match self {
            Method::LaguerreListing => (Fidelity::Listing, Solver::Laguerre),
            Method::LaguerreThesis => (Fidelity::Thesis, Solver::Laguerre),
            Method::Robust => (Fidelity::Thesis, Solver::Robust),
        };
        Options {
            fidelity,
            solver,
            ..Options::default()
        }
    }
}

/// xorshift64*: fixed seeds, so every run builds the same cases.
pub struct Rng(pub u64);

impl Rng {
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.uniform()
    }
    pub fn sign(&mut self) -> f64 {
        if self.uniform() < 0.5 {
            -1.0
        } else {
            1.0
        }
    }
}

pub use raytrace::robust::poly_from_roots as poly;

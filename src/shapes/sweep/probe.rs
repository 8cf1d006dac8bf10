//! One ray's search of one sweep object, shared by the kinds
//! ([`extrusion`](super::extrusion()), [`revolve`](super::revolve())): what
//! the ray and the object give every phase, the segments the ray may meet
//! ([`Candidates`]), the nearest hit so far ([`Best`]), the step from a
//! segment's polynomial to its polished roots ([`Probe::roots`]) and the
//! hit finished ([`Probe::finish`]).

use super::contour::orientation_of;
use super::{negligible, polish, solve, CapGrid};
use crate::options::{Fidelity, Options, TimeSampler};
use crate::types::{Coeff, DVec3, LocalHit, Ray, SweepShape, MAXSEGMENTS};

/// The "segment" of a cap hit: after every side segment, so a side hit at
/// the same t stays the nearest, as when the caps were tried last.
pub(super) const CAP: usize = usize::MAX;

/// What a caller asks of the sweep driver.
#[derive(Clone, Copy)]
pub(super) enum Want {
    /// The nearest hit.
    Nearest,
    /// Whether a hit lies before this t of the caller's ray (a shadow ray's
    /// light): the first hit found before it is returned, else the nearest
    /// (or none); the normal is not turned by the orientation.
    Before(f64),
}

/// The question of [`Want`] in the frame of the ray
/// [`Near`](crate::shapes::Near) the object, whose t is the caller's less
/// `shift`.
#[derive(Clone, Copy)]
pub(super) struct Query {
    pub(super) want: Want,
    pub(super) shift: f64,
}

impl Query {
    /// Is a hit at t (near frame) an answer at once? Before the caller's
    /// `tmax`, compared as the caller would compare the hit it gets back.
    pub(super) fn done(&self, t: f64) -> bool {
        matches!(self.want, Want::Before(tmax) if t + self.shift < tmax)
    }

    /// Can no hit at t ≥ `t_lo` (near frame) matter? Beyond the nearest hit
    /// so far, or beyond the caller's `tmax`.
    pub(super) fn past(&self, t_lo: f64, best: &Option<Best>) -> bool {
        best.is_some_and(|b| t_lo > b.t) || matches!(self.want, Want::Before(tmax) if t_lo + self.shift >= tmax)
    }
}

/// The nearest hit so far, and the segment it is on.
#[derive(Clone, Copy)]
pub(super) struct Best {
    pub(super) t: f64,
    pub(super) normal: DVec3,
    pub(super) segment: usize,
}

/// Is a hit at t on `segment` the new nearest? Of two hits at one t, the
/// one on the lower segment: the answer of trying the segments in their
/// order, whatever order they are tried in.
pub(super) fn closer(best: &Option<Best>, t: f64, tmin: f64, segment: usize) -> bool {
    t > tmin && best.is_none_or(|b| t < b.t || (t == b.t && segment < b.segment))
}

// A segment's index fits the byte `Candidates` keeps it in.
const _: () = assert!(MAXSEGMENTS <= u8::MAX as usize + 1);

/// Segments a ray may meet, tried nearest first: each with a lower bound
/// on the t of its hits (−∞ where none is known).
pub(super) struct Candidates {
    len: usize,
    t_lo: [f64; MAXSEGMENTS],
    segment: [u8; MAXSEGMENTS],
}

impl Candidates {
    pub(super) fn new() -> Self {
        Candidates {
            len: 0,
            t_lo: [0.0; MAXSEGMENTS],
            segment: [0; MAXSEGMENTS],
        }
    }

    /// Adds `segment`, whose hits lie at t ≥ `t_lo`, keeping the list in
    /// ascending `t_lo` (ties in segment order): insertion into a list of a
    /// few entries.
    pub(super) fn push(&mut self, t_lo: f64, segment: usize) {
        if self.len == MAXSEGMENTS {
            return;
        }
        let mut k = self.len;
        while k > 0 && self.t_lo[k - 1] > t_lo {
            self.t_lo[k] = self.t_lo[k - 1];
            self.segment[k] = self.segment[k - 1];
            k -= 1;
        }
        self.t_lo[k] = t_lo;
        self.segment[k] = segment as u8; // < MAXSEGMENTS = 60
        self.len += 1;
    }

    pub(super) fn iter(&self) -> impl Iterator<Item = (f64, usize)> + '_ {
        (0..self.len).map(|k| (self.t_lo[k], self.segment[k] as usize))
    }
}

/// One ray's search of one sweep object, in the frame of the ray
/// [`Near`](crate::shapes::Near) the object: what the ray and the object
/// give every phase of the search, and the nearest hit so far. Made by
/// [`Sweep`](super::Sweep) once a ray; its phases are the kinds'
/// (`Extrusion`, `Revolve`).
pub(super) struct Probe<'a> {
    pub(super) sweep: &'a SweepShape,
    /// The segments the driver takes from `sweep`.
    pub(super) u: &'a [Coeff],
    pub(super) v: &'a [Coeff],
    /// The cap test's grid, made with all of `sweep`'s segments.
    pub(super) grid: Option<&'a CapGrid>,
    /// The object's size, which the tolerances are relative to.
    pub(super) size: f64,
    pub(super) ray: Ray,
    pub(super) tmin: f64,
    pub(super) opts: &'a Options,
    pub(super) query: Query,
    pub(super) best: Option<Best>,
    /// The polynomials searched ([`solve`]).
    pub(super) searched: &'a mut u64,
}

impl Probe<'_> {
    /// Is a hit at t on `segment` the new nearest? ([`closer`])
    #[inline(always)]
    pub(super) fn closer(&self, t: f64, segment: usize) -> bool {
        closer(&self.best, t, self.tmin, segment)
    }

    /// Do the segments' boxes hold their segments, so that they bound the
    /// hits (D32, D90)?
    #[inline(always)]
    pub(super) fn boxes_hold(&self) -> bool {
        match self.opts.fidelity {
            // Listing (erratum 9): an in-between segment's box is the first
            // key's widened by 2, which the segment can leave: the boxes
            // only order the segments, as before D32.
            Fidelity::Listing => false,
            // Thesis: each segment's box is its extrema.
            Fidelity::Thesis => true,
        }
    }

    /// Are the polynomials searched counted for the adaptive sampler, which
    /// weighs a pixel by its rays' searches ([`Probe::searched`])? The
    /// culls that came after that sampler (D69, D90) skip segments it would
    /// have counted, so under it they skip nothing and its pictures stay
    /// as they were.
    #[inline(always)]
    pub(super) fn counted(&self) -> bool {
        self.opts.sampler == TimeSampler::Adaptive
    }

    /// Can no hit at t ≥ `t_lo` matter? ([`Query::past`])
    #[inline(always)]
    pub(super) fn past(&self, t_lo: f64) -> bool {
        self.query.past(t_lo, &self.best)
    }

    /// The hit at t on `segment` becomes the nearest; true when it is an
    /// answer at once ([`Query::done`]).
    #[inline(always)]
    pub(super) fn keep(&mut self, t: f64, normal: DVec3, segment: usize) -> bool {
        self.best = Some(Best { t, normal, segment });
        self.query.done(t)
    }

    /// The roots in [−δ, 1 + δ] of a segment's polynomial `p` of degree
    /// `n` ([`solve`]), each polished ([`polish`]) and given to `consider`
    /// until it says a hit is an answer at once (then true). A polynomial
    /// negligible beside `scale` (a segment along the ray's projection, or
    /// one that vanishes everywhere) gives none: grazing.
    #[inline(always)]
    pub(super) fn roots(
        &mut self,
        n: usize,
        p: &[f64; 7],
        scale: f64,
        mut consider: impl FnMut(&mut Self, f64) -> bool,
    ) -> bool {
        if negligible(p, scale) {
            return false;
        }
        let found = solve(n, p, self.opts, self.searched);
        for &s in &found.s[..found.count] {
            if consider(self, polish(n, p, s)) {
                return true;
            }
        }
        false
    }

    /// The hit kept, as the caller wants it: as it stands when the caller
    /// asked only whether one lies before its `tmax` (it needs only its t),
    /// else with the normal of a side turned out by the contour's
    /// orientation (once, for the hit kept) and made unit.
    pub(super) fn finish(self) -> Option<LocalHit> {
        let b = self.best?;
        let hit = |normal| LocalHit {
            t: b.t,
            point: self.ray.at(b.t),
            normal,
        };
        if matches!(self.query.want, Want::Before(_)) {
            return Some(hit(b.normal));
        }
        let normal = if b.segment == CAP {
            b.normal
        } else {
            b.normal * orientation_of(self.sweep, self.u, self.v)
        };
        Some(hit(normal.try_normalize()?))
    }
}

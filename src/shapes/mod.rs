//! Reconstructed base: the primitive intersections (being written).
pub mod sweep;

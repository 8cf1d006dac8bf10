//! Unit `proc` (being written).
pub mod sweep;

//! Unit `proc` (being written).
pub mod robust;
pub mod sweep;

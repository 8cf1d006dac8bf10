//! Unit `proc` (being written).

//! The sweep intersection driver (being written).

//! The tools of the port, as a library so that the benches
//! (tools/bench/) share the deck helpers with the command line.

pub mod bench;
pub mod chart;
pub mod chart_reconstructions;
pub mod compare;
pub mod deck_misses;
pub mod decks;
pub mod fonts;
pub mod frames;
pub mod frontier;
pub mod fuzz;
pub mod gallery;
pub mod goal;
pub mod heatmap;
pub mod join;
pub mod measure;
pub mod pov;
pub mod preview;
pub mod scale;
pub mod stability;
pub mod textures;
pub mod vs_povray;

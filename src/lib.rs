//! A Rust port of the ray tracer of TR-88-036 (Institute of Information
//! Science, Academia Sinica, 1989), *Generating motion-blurred images of
//! deforming objects*: sweep objects after van Wijk 1984, motion blur by
//! Cook's distributed ray tracing, and key-frame deformation with bicubic
//! Hermite patches.
//!
//! One module per unit of the original: [`raytrace`] (the main program),
//! [`proc`], and (with later work) `drt` and `paper`; beside them the
//! reconstructed base program ([`trace`], [`shapes`], [`deck`], [`raster`])
//! and the PS 390 display emulation [`psout`]; [`output`], the port's own,
//! writes every output file; [`cli`] and [`exit`], the port's too, are the
//! command line's words for a render and the exit statuses, shared by every
//! program; [`image_file`] reads the pictures psout
//! shows (Sun raster, PNG, PPM); [`film`] and [`tile`], the port's, are a
//! film's frames and a still's bands, each rendered by any process.

pub mod accel;
pub mod adaptive;
#[cfg(feature = "cli")]
pub mod cli;
pub mod coherence;
pub mod deck;
pub mod distributed;
pub mod drt;
#[cfg(feature = "editor")]
pub mod editor;
pub mod exit;
pub mod film;
pub mod hash;
pub mod image_file;
pub mod intersect;
pub mod motion;
pub mod options;
pub mod output;
pub mod paper;
pub mod proc;
pub mod psout;
pub mod raster;
pub mod raytrace;
pub mod reconstruct;
pub mod robust;
pub mod run;
pub mod sampler;
pub mod scene;
pub mod shapes;
pub mod show;
pub mod tile;
pub mod trace;
pub mod types;

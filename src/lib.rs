//! A Rust port of the ray tracer of TR-88-036 (Institute of Information
//! Science, Academia Sinica, 1989), *Generating motion-blurred images of
//! deforming objects*: sweep objects after van Wijk 1984, motion blur by
//! Cook's distributed ray tracing, and key-frame deformation with bicubic
//! Hermite patches.
//!
//! # Rendering a deck
//!
//! The crate's root holds what a program that renders needs: the deck
//! reader ([`initialize`], [`read_deck_file`]), the choices of a render
//! ([`Options`]: [`Fidelity`], [`Solver`], [`TimeSampler`]), the prepared
//! scene and the render ([`Prepared`] with an [`Accel`], [`render`], a
//! [`Request`] of a film's [`Frame`] and a [`Reconstruction`]), and the
//! raster's files ([`outputframe`], the Sun raster the original wrote, and
//! `write_png`). A deck's error names its FILE:LINE:COLUMN.
//!
//! ```
//! use raytrace::{initialize, render, Options, Prepared, Request};
//! use std::path::Path;
//!
//! let deck = "view eye 0 -8 4 look 0 0 0.8 screen 4.5 distance 5
//!             image 8 6 mask 2
//!             light sun 5 -8 12 1 1 1
//!             surface red opaque color 0.9 0.15 0.1 ka 0.15 kd 0.8 ks 0.2 kt 0
//!             sphere ball red at 0 0 0.8 radius 0.8";
//! let opts = Options::default();
//! let scene = initialize(deck, "ball.deck", Path::new(""), opts.fidelity)?;
//! let image = render(&Prepared::new(scene, opts)?, &Request::STILL)?;
//! assert_eq!((image.raster.width, image.raster.height), (8, 6));
//! let [r, g, _] = image.raster.pixels[3 * 8 + 4]; // the red ball, mid-picture
//! assert!(r > 2 * g, "{r} {g}");
//!
//! let bad = initialize("image 8 6 mask 2\nsphere", "bad.deck", Path::new(""), opts.fidelity);
//! assert!(bad.unwrap_err().to_string().starts_with("bad.deck:2:"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! `examples/render.rs`, whole, is such a program: it reads the deck a
//! command line names, renders it with the thesis's fidelity and Sobol
//! times, writes a PNG, and refuses a deck it cannot use as `raytrace`
//! does, exit 2 (`cargo run --release --example render -- DECK OUT.png`,
//! docs/usage.md "Embedding"):
//!
#![cfg_attr(
    feature = "png",
    doc = concat!("```no_run\n", include_str!("../examples/render.rs"), "```\n")
)]
//!
//! # The thesis's units and the port's modules
//!
//! One module per unit of the original, the procedures under their Pascal
//! names in the listing's order (legacy_pascal/README.md, CONCORDANCE.md a
//! row per printed procedure):
//!
//! | the thesis | module |
//! |---|---|
//! | `raytrace`, the main program (OCR lines 3013–3229) | [`raytrace`] (`translookpt`, the scanline loop, `antialias`) |
//! | unit `proc` (rotatetest, floortest, …, laguerre, spline, roottesting) | [`proc`] |
//! | unit `drt` (motionblur, depthoffield, jittering, Isblur), `LAW` of §3.2.2 | [`drt`] |
//! | unit `paper` (expanding, goahead, Hermite, …: the key-frame in-betweens) | [`paper`] |
//! | the records of Fig. 4.3 (`objectrecord`, `ray`, `intersectionrecord`, …) | [`types`] |
//! | not printed, reconstructed: `initialize`, the scene reader | [`deck`], its records [`scene`] |
//! | not printed, reconstructed: `raytrace` the shading (Whitted's model) | [`trace`] |
//! | not printed, reconstructed: the primitives' intersections | [`shapes`] |
//! | not printed, reconstructed: `rgbtochars`, `outputframe` | [`raster`] |
//! | `psout`, the PS 390 of Fig. 4.1 | [`psout`] |
//!
//! Beside them the port's additions, one job a module:
//!
//! | module | what it is |
//! |---|---|
//! | [`options`] | the choices of a render: fidelity (the errata), root solver, sampler |
//! | [`sampler`], [`motion`] | where and when each sample falls; what moves over the shutter |
//! | [`adaptive`] | how many samples a pixel gets (`--sampler adaptive`) |
//! | [`intersect`], [`accel`] | which object a ray meets; the structures over the objects' boxes (`--accel`) |
//! | [`reconstruct`], [`coherence`] | how pixels are made from samples (`--denoise`); the thesis's coherence of §2.1.2 (`--coherence N`) |
//! | [`distributed`] | Cook's soft shadows and blurred reflection |
//! | [`robust`], [`hash`] | the second root solver; the uniform from a key |
//! | [`film`], [`tile`] | a film's frames, a still's bands of rows, each rendered by any process |
//! | [`run`] | a render's jobs, called in-process by every program: the deck read, a film's frames or a still's files reserved, kept (`--resume`), written, summed up |
//! | [`output`], [`image_file`] | writing every output file (a temporary file renamed); reading the pictures psout shows |
//! | [`cli`], [`exit`] | the command line's words for a render and the exit statuses, shared by every program |
//! | [`show`], [`editor`] | the picture as it renders (`--show`); the contour editor behind `contour` |
//!
//! A module uses only the layers below it (legacy_pascal/README.md, "Where
//! each part of the port sits"; `tests/layers.rs`).

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

pub use accel::Accel;
pub use deck::{initialize, read_deck_file, DeckError};
pub use film::Frame;
pub use options::{Fidelity, Options, Solver, TimeSampler};
#[cfg(feature = "png")]
pub use raster::write_png;
pub use raster::{outputframe, Raster, RasterError};
pub use raytrace::{render, Prepared, Render, RenderError, Request};
pub use reconstruct::Reconstruction;
pub use scene::Scene;

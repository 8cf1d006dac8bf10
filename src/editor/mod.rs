//! The contour editor behind the `contour` program: the port's extension.
//! The thesis's user entered a sweep's control points interactively, on
//! the PS 300's tablet or with a PC program of the author's, "and the
//! computer draws the curve of the chosen formula (Bezier or B-spline) at
//! once" (§3.2.1; §2.3 item 2); neither program is printed. This module
//! is the port's such program, over the deck: it opens one `sweep` record,
//! edits its control points, curve and sweep kind, draws the closed curve
//! with the port's own `spline`, renders the object with the deck's view,
//! lights and surfaces, and saves the record back into the deck.
//!
//! Everything but the window is here and runs without one: the contour
//! and its edits ([`model`]), the record in the deck's text and the save
//! ([`record`]), the scripted edits ([`script`]). The window
//! (`src/bin/contour.rs`) only turns mouse and key events into calls.

pub mod curve;
pub mod document;
pub mod draw;
pub mod keyshapes;
pub mod layout;
pub mod model;
pub mod plane;
pub mod preview;
pub mod record;
pub mod screen;
pub mod script;
pub mod session;
pub mod worker;

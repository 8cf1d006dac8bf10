//! The scene `initialize` builds from a deck: the records the deck gives
//! besides those of Fig. 4.3 ([`crate::types`]): the view, the image, the
//! lights, the motions and key frames, the subpixel-time tables, the film.
//! Reconstructed from Ch. 4 and the main program (the thesis prints none
//! of them), except where a record says it is the port's.

use std::fmt;
use std::sync::Arc;

use crate::types::{DVec3, Intensity, ObjectRecord, SurfaceRecord};

/// A point light (the base program's, not printed): deck `light`; with
/// `radius` > 0 a sphere of light (the port's extension, Cook 1984's soft
/// shadows: each sample's shadow ray aims at its own point of it).
#[derive(Clone, Debug, PartialEq)]
pub struct LightRecord {
    pub name: String,
    pub position: DVec3,
    pub color: Intensity,
    /// The sphere's radius; 0 is the point light of the base program.
    pub radius: f64,
}

/// Deck `lens APERTURE FOCUS` (the port's extension where the thesis
/// stops: its `depthoffield` is "not completed" and never called): the
/// lens's radius and the distance that is sharp.
#[derive(Clone, Debug, PartialEq)]
pub struct LensRecord {
    pub pos: Pos,
    /// The aperture's radius (`fradius` of `depthoffield`); 0 is the
    /// pinhole of the thesis.
    pub aperture: f64,
    /// How far from the eye the sharp plane stands: along the line of
    /// sight (`thesis`), or the world plane y = FOCUS as `depthoffield`
    /// reads `focuslength` (`listing`).
    pub focus: f64,
}

/// The view (deck `view`; the Pascal read it from the file `fview`).
/// Reconstructed from the main program: `eyept`, the look point, and
/// `screensize`, `scrndistance` of the screen window.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    pub eyept: DVec3,
    pub lookpt: DVec3,
    /// `screensize`: the width of the window on the screen plane.
    pub screensize: f64,
    /// `scrndistance`: the distance of the screen plane from the eye.
    pub scrndistance: f64,
}

/// The image (deck `image`): the final raster size, `masksize`×`masksize`
/// subpixels a pixel, and the `aliasing` jitter amplitude (0–1 of a subpixel).
#[derive(Clone, Debug, PartialEq)]
pub struct ImageSpec {
    pub width: usize,
    pub height: usize,
    /// `masksize`: each pixel is traced as masksize × masksize subpixels.
    pub masksize: usize,
    /// `aliasing`: scales the `noise2` jitter of each subpixel's position.
    pub aliasing: f64,
}

/// Where a deck's word stands: the file (its name as the user gave it,
/// shared by every position in it), the 1-based line and column (columns
/// counting characters). Every error about a place in a deck prints it as
/// `FILE:LINE:COLUMN` ([`fmt::Display`]), so that an error in a file the
/// deck takes in names that file.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub struct Pos {
    pub file: Arc<str>,
    pub line: u32,
    pub column: u32,
}

impl fmt::Display for Pos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.column)
    }
}

/// LAW 1–4 of Fig. 3.2: how the fraction of the shutter maps onto the path.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Law {
    /// LAW 1: constant speed, f.
    #[default]
    Constant,
    /// LAW 2: accelerate, 1 − cos(πf/2).
    Accelerate,
    /// LAW 3: decelerate, sin(πf/2).
    Decelerate,
    /// LAW 4: accelerate then decelerate, (1 − cos πf)/2.
    Smooth,
}

/// Deck `motion` (§3.2.2): the object's path over the shutter.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionRecord {
    pub pos: Pos,
    /// Index into [`Scene::objects`].
    pub object: usize,
    /// Where `sphereo` stands at t = 1.
    pub to: DVec3,
    /// Degrees added about x, y, z over the shutter.
    pub turn: DVec3,
    /// The inner control points of a cubic Bezier path, if any.
    pub via: Option<[DVec3; 2]>,
    pub law: Law,
}

/// How the segment counts of two key shapes are made equal (§3.2.3).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Expander {
    /// `expanding`/`more`: Burtnyk & Wein 1971.
    Burtnyk,
    /// `expanding2`/`more2`/`plus`: the thesis's arc-length method.
    #[default]
    Arclength,
}

/// Deck `keyframe` (§3.1–3.3): a chain of key shapes. FIRST stays in the
/// scene as the in-between object; the later key shapes are removed from the
/// scene (`delete` in `goahead`) and kept here.
#[derive(Clone, Debug, PartialEq)]
pub struct KeyframeRecord {
    pub pos: Pos,
    /// FIRST: index into [`Scene::objects`].
    pub first: usize,
    /// The later key shapes, in order (LAST alone for a pair).
    pub rest: Vec<ObjectRecord>,
    pub expander: Expander,
}

/// Deck `pattern` (Fig. 2.33): the M×M table of subpixel times, values
/// 0..M²−1, `pattern[row][col]`.
#[derive(Clone, Debug, PartialEq)]
pub struct PatternRecord {
    pub pos: Pos,
    pub m: usize,
    pub values: Vec<Vec<u32>>,
}

/// Deck `blur N` (§2.6.5): the CLT normal is the sum of N uniforms.
#[derive(Clone, Debug, PartialEq)]
pub struct BlurRecord {
    pub pos: Pos,
    pub n: u32,
}

/// The scene `initialize` builds from a deck, read-only while rendering.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    pub view: View,
    pub image: ImageSpec,
    /// `backgrnd`: the background colour.
    pub backgrnd: Intensity,
    pub lights: Vec<LightRecord>,
    pub surfaces: Vec<SurfaceRecord>,
    /// `table`: the objects still in the scene, in deck order.
    pub objects: Vec<ObjectRecord>,
    /// Where each object's defining record stands (same indices as `objects`).
    pub object_pos: Vec<Pos>,
    pub motions: Vec<MotionRecord>,
    pub keyframes: Vec<KeyframeRecord>,
    pub blur: Option<BlurRecord>,
    pub pattern: Option<PatternRecord>,
    /// The `lens` record (the port's extension); `None` is the pinhole.
    pub lens: Option<LensRecord>,
    /// The `film` record (the port's extension, [`crate::film`]); `None`
    /// renders one still, as the thesis does.
    pub film: Option<FilmRecord>,
}

impl Scene {
    /// Sets the image to `width`×`height` pixels of `mask`×`mask`
    /// subpixels in place of the deck's `image` record (`--size`,
    /// `--mask`); the view (the window on the screen plane) stays, so the
    /// picture is the same at another resolution. A deck's `pattern`
    /// record fits one mask only, so it is dropped when the mask changes
    /// (the default table of that mask is used).
    pub fn resize(&mut self, width: usize, height: usize, mask: usize) {
        if self.image.masksize != mask {
            self.pattern = None;
        }
        self.image.width = width;
        self.image.height = height;
        self.image.masksize = mask;
    }
}

/// The most frames a film may have.
pub const MAX_FRAMES: u32 = 10_000;
/// The highest frame rate, frames per second.
pub const MAX_RATE: u32 = 60;
/// The shutter when the record names none: open half of each frame's
/// interval (a 180° shutter, the usual one of film cameras).
pub(crate) const DEFAULT_SHUTTER: f64 = 0.5;
/// The frame rate when the record names none.
pub(crate) const DEFAULT_RATE: u32 = 12;

/// The deck's `film FRAMES [shutter S] [rate FPS]` record.
#[derive(Clone, Debug, PartialEq)]
pub struct FilmRecord {
    pub pos: Pos,
    /// F: the number of frames, 1..=[`MAX_FRAMES`].
    pub frames: u32,
    /// S: the fraction of a frame's interval the shutter is open, in (0, 1].
    pub shutter: f64,
    /// Frames per second when played, 1..=[`MAX_RATE`].
    pub rate: u32,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_position_prints_file_line_and_column() {
        let pos = Pos {
            file: "decks/a.deck".into(),
            line: 12,
            column: 3,
        };
        assert_eq!(pos.to_string(), "decks/a.deck:12:3");
    }
}

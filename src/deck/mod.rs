//! `initialize`: reading the scene deck (DECK.md) into a [`Scene`].
//!
//! Reconstructed: the thesis does not print `initialize`. The main program
//! (OCR lines ~3013–3046) calls it first and names the text files it read
//! (`fview`, `filmdata`, `filmdata2`, `translationf`, …); Ch. 4 (a)–(b) says
//! it sets up the variables and lets the user "create the scene" in the
//! records of Fig. 4.3. The port reads all of that from one deck file whose
//! format, legacy_pascal/DECK.md, is the users' contract. This comment is the
//! user's reference for everything DECK.md leaves open; where a choice was
//! open the stricter reading was taken, because an error can be relaxed
//! later without breaking a deck, while an accepted deck must keep rendering
//! the same way.
//!
//! # Lexical rules
//! - Comments are `{ … }` and `(* … *)`. They do not nest; `{` is closed
//!   only by `}` and `(*` only by `*)`. A comment separates words like a
//!   space; the line ends inside a comment do not end a record. A comment
//!   left open at the end of the deck is an error at its opening bracket.
//!   An error between the end of a comment that held its own opener and a
//!   stray closer after it (`{ a { b } c }`) is reported as a comment inside
//!   a comment, at the inner opener.
//! - A word is a run of characters other than white space and comment
//!   openers. Keywords and field names are case-insensitive.
//! - Outside comments a deck is ASCII: a byte that is not is an error at its
//!   line and column. Inside comments any bytes may stand (Big5, Latin-1).
//!   Columns count characters: a UTF-8 character, or a byte that is not
//!   part of one, is one column.
//! - A deck longer than [`MAX_DECK_BYTES`] (64 MiB) is an error at the first
//!   byte past the limit; [`read_deck_file`] reads no more than that. A
//!   deck of more than [`MAX_OBJECTS`] object records (1,000,000) is an
//!   error at the first name past the limit.
//! - Names (surfaces, lights, objects) are case-sensitive, 1–10 characters
//!   of `[A-Za-z0-9_]`; a word that is a number is never a name (`5` where a
//!   name is expected is an error), but `2nd` is a name.
//! - Numbers: `[+|-] (digits [. [digits]] | . digits) [(e|E) [+|-] digits]`,
//!   so `2`, `-0.5`, `1.5E-3`, `.5` and `5.` are numbers. Every real number
//!   lies in −[`MAX_MAGNITUDE`]..[`MAX_MAGNITUDE`] (1e7), every size (`> 0`
//!   below: radii, edges, heights, lengths, `screen`, `distance`, a paint's
//!   `scale`, `index`) in [`MIN_SIZE`]..[`MAX_MAGNITUDE`] (1e-7..1e7), and
//!   a `translate` may not carry `sphereo` out of the range: the port's
//!   extension, so that no product or square the renderer forms overflows
//!   (a radius of 1e155 made every pixel NaN). Where DECK.md says integer (WIDTH,
//!   HEIGHT, mask, blur, pattern), only `[+|-] digits` is accepted (`2.` is
//!   not an integer).
//! - A file name (`texture`) is one word: it cannot hold spaces or braces.
//!
//! # Records and lines
//! - A record is one line. `prism`, `sweep` and `pattern` end their first
//!   line after their fields; then each following line holds one point
//!   `U V` (one row of M integers for `pattern`), and the list ends with a
//!   line holding `end` alone. Empty and comment-only lines are skipped,
//!   between records and inside lists.
//! - Fields come in DECK.md's order ("Field order", [`FIELDS`]): the
//!   required ones in order, then the optional ones (those in brackets) in
//!   any order, each at most once; a field given twice, a word that is no
//!   field of the record, or any extra token is an error.
//! - Records are read top to bottom and may name only what stands above
//!   them; an included file's records stand where its `include` does.
//!   Surfaces, lights, objects and paths are four kinds of name: a surface
//!   and an object may share a name, two surfaces (two lights, two objects
//!   in the scene, two paths) may not. After `delete NAME` the name is free
//!   again; referring to the deleted object is an error ("unknown object").
//!
//! # Values
//! - `view`: exactly once. `screen` and `distance` > 0. The eye may not be
//!   straight above or below `look` (eye = look, or the horizontal part of
//!   eye − look under 1e-9 of its length): world z is up in the image.
//! - `image`: exactly once. WIDTH, HEIGHT integers 1..8192; `mask` M an
//!   integer 1..8 (required); `aliasing` A in 0..1, default 0.
//! - `background`: at most once; R G B in 0..1; default black.
//! - `light`: R G B in 0..1 (a point light's intensity, as Fig. 4.3's
//!   `intensity` comment says).
//! - `surface`: KIND is `opaque`, `mirrored`, `transparent`, `crystal`,
//!   `light` or `background`. `ka kd ks kt` and `reflect` in 0..1. `color`
//!   and `ambient` components in 0..1, except on a `light` surface, which
//!   emits: there any component ≥ 0 is allowed. `ambient` (`Iobject`)
//!   defaults to `color`; `reflect` (`prcntrfl`) defaults to 1 for
//!   `mirrored` and 0 otherwise; `index` defaults to 1.0 and must be > 0.
//!   `reflect` and `index` are accepted on every kind; the tracer uses them
//!   where DECK.md says.
//! - `paint`: `scale` LX LY > 0, default 1 1; `color` in 0..1, default
//!   white. `texture`: FILE is relative to the deck's folder (`deck_dir`;
//!   an absolute path stays absolute), read with
//!   `raster::read_raster_file_within` as a raster file of at most
//!   [`MAX_TEXELS`] texels (texel = byte / 255, kept as bytes); an
//!   empty raster is an error. A
//!   surface gets at most one `paint` or `texture`, not both.
//!
//! # Objects
//! - `at` gives `sphereo`. `transfm` = T(`sphereo`) · R · A(axis) and
//!   `inverse` = A(axis)ᵀ · Rᵀ · T(−`sphereo`), inverted exactly (both
//!   rotation parts are orthogonal). A(axis) maps local z onto the named
//!   world axis: `x` is +90° about y, `y` is −90° about x, `z` the
//!   identity. `rotate NAME x|y|z DEG` sets R ← R_axis(DEG) · R (turning
//!   the object about that world axis through its `sphereo`) and adds DEG to
//!   `angle`; angles that are whole multiples of 90° use exact sines and
//!   cosines. `translate NAME X Y Z` adds to `sphereo`.
//! - `sphere`: radius > 0. `block`: a box centred on `sphereo`, edges LX LY
//!   LZ > 0. `cylinder`: radius > 0, bottom < top, along local z. `prism`:
//!   height > 0 and at least 3 vertices of a strictly convex polygon: a
//!   vertex in line with its neighbours (or repeated), a reflex vertex, or a
//!   polygon winding more than once is an error; a clockwise list is stored
//!   counter-clockwise.
//! - `radius` of a non-sphere is that of a sphere about `sphereo` holding
//!   the whole object: half the block's diagonal; for a cylinder
//!   √(r² + max(bottom², top²)); for a prism √(max(U²+V²) + H²); for sweeps
//!   the control points bound the contour (convex hull property):
//!   translation √(max(U²+V²) + L²), conic the same with the contour scaled
//!   by max(1, S), rotation max √(U²+V²).
//!
//! # Sweeps
//! - `sweep NAME SURFACE CLASS CURVE at X Y Z`, then `length`, `scale`,
//!   `axis` in any order. `length` L > 0 is required for `translation` and
//!   `conic` and an error on `rotation`. `scale` S ≥ 0 is required for
//!   `conic` (S = 0 is a cone's apex; a conic sweep without a scale would be
//!   a translation sweep) and an error on the other classes.
//! - `bspline`: n ≥ 4 points give n segments. `bezier`: 3k points with
//!   k ≥ 2 give k segments (a single closed cubic, k = 1, starts and ends at
//!   one point with a corner there; two segments can draw any such shape).
//!   More than 60 segments (`MAXSEGMENTS`) is an error at the first point
//!   too many. A `rotation` contour with U < 0 is an error at that U.
//! - The port fills `points`, `curve`, `segment`, `length` (0 for
//!   rotation), `scale` (1 for translation and rotation) and `orientt`;
//!   `u`, `v` and `bbox` are left empty for the sweep module (`spline`).
//!
//! # Blobs and patches (the port's extension, src/deck/blob_patch.rs)
//! - `blob NAME SURFACE at X Y Z threshold T`, then one component
//!   `X Y Z RADIUS STRENGTH` a line (1 to [`MAXCOMPONENTS`], 60), then
//!   `end`: T and RADIUS sizes, STRENGTH any number of the range. Its
//!   `radius` is the farthest reach |centre| + RADIUS of a component of
//!   positive strength (0 without one: the blob has no surface).
//! - `patch NAME SURFACE at X Y Z`, then 16 control points `X Y Z`, whole
//!   points on a line (several a line allowed), then `end`; its `radius`
//!   the farthest control point's distance.
//! - Both take no `axis` (their points are in three dimensions).
//!
//! [`MAXCOMPONENTS`]: crate::types::MAXCOMPONENTS
//!
//! # Motion and key frames
//! - `motion NAME to X Y Z [turn AX AY AZ] [via X1 Y1 Z1 X2 Y2 Z2]
//!   [law constant|accelerate|decelerate|smooth]`: one per object; `turn`
//!   defaults to 0 0 0 and `law` to constant.
//! - `keyframe A B [C …] [expander burtnyk|arclength]`: two or more distinct
//!   sweep objects of one class, or blobs, or patches (the word `expander`,
//!   in any case, ends the list of names; blobs and patches take none). A shape may be in one `keyframe` record only. The
//!   later shapes are removed from `objects` into `KeyframeRecord::rest`
//!   after the whole deck is read; every index (`objects`, `object_pos`,
//!   `MotionRecord::object`, `KeyframeRecord::first`) refers to the final
//!   `objects`. `expander` defaults to `arclength`.
//! - Once an object has a `motion` or is a key shape its pose is fixed: a
//!   later `rotate`, `translate` or `delete` of it is an error, and a key
//!   shape may not have a `motion` (its path is from FIRST's pose to the
//!   next shape's pose).
//! - `blur N`: an integer 0..1000, at most once. `pattern M`: M an integer
//!   1..16, then M rows of M integers in 0..M²−1, then `end`; at most once.
//!   In `Fidelity::Thesis` the values must be a permutation of 0..M²−1 (an
//!   error at the first repeated value); `Fidelity::Listing` accepts
//!   repeats, as the printed table of Fig. 2.33 has them (erratum 1). M
//!   is checked against `image`'s mask when the scene is prepared
//!   (`drt::TimeTable::new`): equal in `Fidelity::Thesis`; at least the
//!   mask in `Fidelity::Listing`, which reads the top-left corner
//!   (DEVIATIONS D9).
//!
//! # The path library (the port's extension, src/deck/library.rs)
//! - `path NAME by DX DY DZ [turn AX AY AZ] [via DX1 DY1 DZ1 DX2 DY2 DZ2]
//!   [law …]`: `by` and the `via` points are offsets from the place of the
//!   object that takes the path; `motion OBJ path NAME` is the motion
//!   record with `to` = `sphereo` + `by` and each `via` point `sphereo` +
//!   its offset (sums of reals), which must lie in the deck's range; nothing
//!   follows NAME. A motion naming a path that no record above defines is
//!   an error at the name, raised when the path is defined below it ("used
//!   before it is defined"), at another error, or at the end of the deck
//!   ("unknown path").
//! - `include FILE`: FILE (one word, relative to the folder of the file
//!   naming it) is read in place of the record, named in errors as joined
//!   to that folder. It may hold only [`LIBRARY_RECORDS`]. The deck and all
//!   it includes hold at most [`MAX_DECK_BYTES`] together (a file counted
//!   each time it is included; the error at the first byte past the limit,
//!   in the file where it falls), at most [`MAX_INCLUDES`] includes are
//!   read, files nest at most [`MAX_INCLUDE_DEPTH`] deep, and a file that
//!   includes itself, directly or not (the same file by its device and
//!   inode, so a hard link too), is an error at the `include` that closes
//!   the cycle.
//!
//! # Film
//! - `film FRAMES [shutter S] [rate FPS]` (the port's extension,
//!   [`crate::film`]): FRAMES an integer 1..10000, S a number in (0, 1]
//!   (default 0.5), FPS an integer 1..60 (default 12); at most once.
//!
//! # Errors
//! [`DeckError`] reads `FILE:LINE:COL: RECORD 'NAME': MESSAGE`, or
//! `FILE:LINE:COL: RECORD: MESSAGE` before the record's name is known.
//! RECORD is the record's keyword in lower case, or `deck` outside any
//! record (an unknown record keyword, a comment left open between records).
//! NAME is the declared name once it is a valid name, or the named surface
//! or object of a referring record once it has been found. The position is
//! that of the offending token; a missing token is reported where it was
//! expected: at the next token, the end of the line or the end of the deck.
//! An unknown record, field, keyword choice, surface or object ends with
//! ` — did you mean 'NAME'?` when a valid name is within a third of its
//! letters (case-insensitive edit distance); a field of the record out of
//! its place ends with ` — 'KA' comes before 'KD'` or ` — the field 'F' is
//! given twice`. A `texture` file that cannot be read is named as written,
//! then as joined to `deck_dir` when that differs. A word echoed in a
//! message is cut after 40 characters, its control characters escaped.
//! A missing `view` or `image` is reported at the end of the deck.

mod blob_patch;
mod film;
mod lens;
mod lex;
mod library;
mod objects;
mod parse;
mod records;
pub mod words;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::DMat3;

use crate::scene::{
    BlurRecord, Expander, ImageSpec, KeyframeRecord, LightRecord, MotionRecord, PatternRecord, Pos, Scene, View,
};

use crate::options::Fidelity;

use crate::types::{Intensity, ObjectRecord, SurfaceRecord};
pub use lex::MAX_DECK_BYTES;
pub use library::{LIBRARY_RECORDS, MAX_INCLUDES, MAX_INCLUDE_DEPTH};
use parse::Parser;
pub use parse::{MAX_MAGNITUDE, MIN_SIZE};

/// The most texels a deck texture may have: 4096 × 4096 (48 MiB), a
/// sixteenth of a raster's [`crate::raster::MAX_PIXELS`], since a deck may
/// paste several. The port's bound: the thesis's textures are 256×256.
pub const MAX_TEXELS: usize = 4096 * 4096;

/// The most object records a deck may have (key shapes and deleted
/// objects count): the port's limit. A 64 MiB deck can hold some two
/// million short ones, and reading and preparing an object takes about
/// 1.5 kB, so the limit keeps the largest deck within about 1.5 GB.
pub const MAX_OBJECTS: usize = 1_000_000;

/// The reading limit of a deck texture ([`MAX_TEXELS`]).
pub(crate) const TEXTURE_LIMIT: crate::raster::PixelLimit = crate::raster::PixelLimit {
    pixels: MAX_TEXELS,
    what: "deck texture",
};

/// Reads a deck file's bytes for [`initialize`]: at most one byte more than
/// [`MAX_DECK_BYTES`], so that a file without end (`/dev/zero`, a pipe)
/// ends with `initialize`'s error for a deck too large, not with all memory
/// taken.
pub fn read_deck_file(path: &Path) -> std::io::Result<Vec<u8>> {
    read_deck(std::fs::File::open(path)?)
}

/// Reads a deck's bytes from `reader` (standard input, `raytrace -`) as
/// [`read_deck_file`] does: at most one byte more than [`MAX_DECK_BYTES`].
pub fn read_deck(reader: impl std::io::Read) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let mut bytes = Vec::new();
    reader.take(MAX_DECK_BYTES as u64 + 1).read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// The record keywords, for the suggestion after an unknown one; every
/// keyword that `Builder::record` reads is here (a test holds them equal
/// to DECK.md's list).
pub const RECORDS: &[&str] = &[
    "view",
    "image",
    "background",
    "light",
    "surface",
    "paint",
    "texture",
    "sphere",
    "block",
    "cylinder",
    "prism",
    "sweep",
    "blob",
    "patch",
    "rotate",
    "translate",
    "delete",
    "motion",
    "keyframe",
    "blur",
    "pattern",
    "film",
    "path",
    "include",
    "lens",
];

/// Each record's field names in DECK.md's order, the required ones first
/// then the optional ones (a test holds them equal to DECK.md's list): how
/// a misplaced field is told where it belongs ("'ka' comes before 'kd'")
/// and a misspelt one its nearest field. A record of two forms has an entry
/// for each (`motion … to …`, `motion … path …`), the first the one whose
/// order is told.
pub const FIELDS: &[(&str, &[&str])] = &[
    ("view", &["eye", "look", "screen", "distance"]),
    ("image", &["mask", "aliasing"]),
    ("light", &["radius"]),
    (
        "surface",
        &["color", "ka", "kd", "ks", "kt", "ambient", "reflect", "index", "gloss"],
    ),
    ("paint", &["scale", "color"]),
    ("sphere", &["at", "radius"]),
    ("block", &["at", "size"]),
    ("cylinder", &["at", "radius", "bottom", "top", "axis"]),
    ("prism", &["at", "height", "axis"]),
    ("sweep", &["at", "length", "scale", "axis"]),
    ("blob", &["at", "threshold"]),
    ("patch", &["at"]),
    ("motion", &["to", "turn", "via", "law"]),
    ("motion", &["path"]),
    ("keyframe", &["expander"]),
    ("film", &["shutter", "rate"]),
    ("path", &["by", "turn", "via", "law"]),
];

/// A deck error: where (file, 1-based line and column, the column counting
/// characters), in which record, and what was wrong.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}:{column}: {record}{}: {message}", name_part(.name))]
pub struct DeckError {
    /// The deck's file name as given to [`initialize`].
    pub file: String,
    pub line: u32,
    pub column: u32,
    /// The record's keyword (`sweep`), or `deck` outside any record.
    pub record: String,
    /// The record's name, when known.
    pub name: Option<String>,
    pub message: String,
}

fn name_part(name: &Option<String>) -> String {
    name.as_ref().map(|n| format!(" '{n}'")).unwrap_or_default()
}

impl DeckError {
    /// An error at `pos`, in the file it names, in `record` (named `name`).
    pub fn at(pos: Pos, record: &str, name: Option<String>, message: impl Into<String>) -> DeckError {
        DeckError {
            file: pos.file.to_string(),
            line: pos.line,
            column: pos.column,
            record: record.to_string(),
            name,
            message: message.into(),
        }
    }
}

/// Reads a deck into a [`Scene`].
///
/// Reconstructed: `initialize` of the main program `raytrace` (not printed;
/// see the module comment). `source` is the deck's text, `file_name` names
/// it in errors, `deck_dir` is the folder `texture` files are relative to,
/// and `fidelity` decides whether a `pattern` must be a permutation
/// (erratum 1).
///
/// `source` is bytes: outside comments a deck must be ASCII (a byte that is
/// not is an error at its line and column), inside them any bytes may stand.
/// A deck longer than [`MAX_DECK_BYTES`] is an error at the first byte past
/// the limit.
pub fn initialize(
    source: &(impl AsRef<[u8]> + ?Sized),
    file_name: &str,
    deck_dir: &Path,
    fidelity: Fidelity,
) -> Result<Scene, DeckError> {
    let source = source.as_ref();
    if source.len() > MAX_DECK_BYTES {
        let pos = lex::Cursor::new(source, file_name.into()).pos_at(MAX_DECK_BYTES);
        return Err(DeckError::at(
            pos,
            "deck",
            None,
            format!(
                "the deck is larger than {} MiB, the most the reader takes",
                MAX_DECK_BYTES >> 20
            ),
        ));
    }
    let mut b = Builder {
        p: Parser::new(source, file_name),
        deck_dir: deck_dir.to_path_buf(),
        lib: library::Library::new(source.len(), file_name, deck_dir),
        fidelity,
        view: None,
        image: None,
        background: None,
        lights: Vec::new(),
        light_index: HashMap::new(),
        surfaces: Vec::new(),
        surface_info: Vec::new(),
        surface_index: HashMap::new(),
        entries: Vec::new(),
        object_index: HashMap::new(),
        motions: Vec::new(),
        keyframes: Vec::new(),
        blur: None,
        pattern: None,
        film: None,
        lens: None,
    };
    // A motion that named a path not defined above it stands before any
    // later error: its error is reported first.
    b.records().map_err(|e| b.unknown_path_error().unwrap_or(e))?;
    if let Some(e) = b.unknown_path_error() {
        return Err(e);
    }
    b.finish()
}

/// What the builder keeps about a surface besides its record.
struct SurfaceInfo {
    pos: Pos,
    /// The line and keyword of its `paint` or `texture` record, if any.
    decoration: Option<(Pos, &'static str)>,
}

/// An object as read so far.
struct ObjEntry {
    record: ObjectRecord,
    pos: Pos,
    /// R: the product of the object's `rotate` records.
    rot: DMat3,
    /// A(axis): local z onto the named world axis.
    axis: DMat3,
    /// Removed by `delete`.
    deleted: bool,
    /// The line of its `motion` record.
    motion_line: Option<u32>,
    /// The line of the `keyframe` record it is a key shape of.
    keyframe_line: Option<u32>,
    /// A later key shape: moved into `KeyframeRecord::rest` at the end.
    key_rest: bool,
}

/// A keyframe record before the final object indices are known.
struct PendingKeyframe {
    pos: Pos,
    first: usize,
    rest: Vec<usize>,
    expander: Expander,
}

/// A motion record before the final object indices are known.
struct PendingMotion {
    record: MotionRecord,
    entry: usize,
}

struct Builder<'a> {
    p: Parser<'a>,
    /// The folder of the file being read: the files it names are relative
    /// to it.
    deck_dir: PathBuf,
    /// The path library and the included files (the port's extension).
    lib: library::Library<'a>,
    fidelity: Fidelity,
    view: Option<(View, Pos)>,
    image: Option<(ImageSpec, Pos)>,
    background: Option<(Intensity, Pos)>,
    lights: Vec<LightRecord>,
    /// Light name → (index, where).
    light_index: HashMap<String, (usize, Pos)>,
    surfaces: Vec<SurfaceRecord>,
    surface_info: Vec<SurfaceInfo>,
    surface_index: HashMap<String, usize>,
    entries: Vec<ObjEntry>,
    /// Names of the objects in the scene (not deleted) → index in `entries`.
    object_index: HashMap<String, usize>,
    motions: Vec<PendingMotion>,
    keyframes: Vec<PendingKeyframe>,
    blur: Option<BlurRecord>,
    pattern: Option<PatternRecord>,
    film: Option<crate::scene::FilmRecord>,
    lens: Option<crate::scene::LensRecord>,
}

impl Builder<'_> {
    /// Reads every record, of the deck and of the files it includes.
    fn records(&mut self) -> Result<(), DeckError> {
        loop {
            self.p.begin("deck");
            self.p.skip_blank_lines()?;
            if self.p.at_eof()? {
                if self.end_of_file() {
                    continue;
                }
                return Ok(());
            }
            self.record()?;
        }
    }

    /// Reads one record, its first word being the next token.
    fn record(&mut self) -> Result<(), DeckError> {
        let (word, pos) = self.p.word("a record")?;
        let keyword = word.to_ascii_lowercase();
        if RECORDS.contains(&keyword.as_str()) {
            self.may_stand_here(&keyword, pos.clone())?;
        }
        match keyword.as_str() {
            "view" => self.view(pos),
            "image" => self.image(pos),
            "background" => self.background(pos),
            "light" => self.light(),
            "surface" => self.surface(pos),
            "paint" => self.paint(pos),
            "texture" => self.texture(pos),
            "sphere" => self.sphere(pos),
            "block" => self.block(pos),
            "cylinder" => self.cylinder(pos),
            "prism" => self.prism(pos),
            "sweep" => self.sweep(pos),
            "blob" => self.blob(pos),
            "patch" => self.patch(pos),
            "rotate" => self.rotate(),
            "translate" => self.translate(),
            "delete" => self.delete(),
            "motion" => self.motion(pos),
            "keyframe" => self.keyframe(pos),
            "blur" => self.blur(pos),
            "pattern" => self.pattern(pos),
            "film" => self.film(pos),
            "path" => self.path(),
            "include" => self.include(),
            "lens" => self.lens(pos),
            _ => Err(self.p.error_at(
                pos,
                format!(
                    "unknown record {}{}",
                    parse::shown(&word),
                    parse::did_you_mean(&word, RECORDS)
                ),
            )),
        }
    }

    /// Builds the scene once every record is read: checks that `view` and
    /// `image` were given, computes the transforms, removes deleted objects
    /// and later key shapes, and resolves the object indices.
    fn finish(mut self) -> Result<Scene, DeckError> {
        let end = self.p.pos();
        let Some((view, _)) = self.view.take() else {
            self.p.begin("view");
            return Err(self.p.error_at(end, "the deck has no 'view' record"));
        };
        let Some((image, _)) = self.image.take() else {
            self.p.begin("image");
            return Err(self.p.error_at(end, "the deck has no 'image' record"));
        };
        for e in &mut self.entries {
            let (transfm, inverse) = objects::transforms(e.record.sphereo, e.rot, e.axis);
            e.record.transfm = transfm;
            e.record.inverse = inverse;
        }
        let mut final_index = vec![None; self.entries.len()];
        let mut objects = Vec::new();
        let mut object_pos = Vec::new();
        for (i, e) in self.entries.iter().enumerate() {
            if !e.deleted && !e.key_rest {
                final_index[i] = Some(objects.len());
                objects.push(e.record.clone());
                object_pos.push(e.pos.clone());
            }
        }
        // The checks of `delete`, `motion` and `keyframe` keep every entry
        // named below in the scene; a failure here is a bug of this module,
        // reported as a deck error rather than a panic.
        let lost = |p: &Parser, pos: Pos| p.error_at(pos, "internal error: the object left the scene");
        let mut motions = Vec::new();
        for m in self.motions {
            let mut record = m.record;
            record.object = final_index[m.entry].ok_or_else(|| lost(&self.p, record.pos.clone()))?;
            motions.push(record);
        }
        let mut keyframes = Vec::new();
        for k in self.keyframes {
            let first = final_index[k.first].ok_or_else(|| lost(&self.p, k.pos.clone()))?;
            let rest = k.rest.iter().map(|&i| self.entries[i].record.clone()).collect();
            keyframes.push(KeyframeRecord {
                pos: k.pos,
                first,
                rest,
                expander: k.expander,
            });
        }
        Ok(Scene {
            view,
            image,
            backgrnd: self.background.map(|(c, _)| c).unwrap_or_default(),
            lights: self.lights,
            surfaces: self.surfaces,
            objects,
            object_pos,
            motions,
            keyframes,
            blur: self.blur,
            pattern: self.pattern,
            film: self.film,
            lens: self.lens,
        })
    }
}

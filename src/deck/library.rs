//! The path library: the `path` record, `motion NAME path PATH`, and the
//! `include FILE` record that reads a file of such records. The port's
//! extension (DECK.md, "The path library").
//!
//! §3.2.2 (OCR line 714): a path "has a data structure of its own, which
//! the key shapes can choose; common paths can be kept in files, forming a
//! path library, for the user to choose from". The thesis prints neither
//! the structure nor the files. Here a library path is a motion record
//! without its object: its end and inner Bezier points are offsets from
//! the place of the object that takes it, so one path serves any object;
//! `motion NAME path PATH` makes of it the motion record the same path
//! written inline would be (`to` = the object's `sphereo` + `by`, each
//! `via` point the same), so the two render the same bytes.
//!
//! An included file is read where its `include` record stands, as if its
//! records were written there, with its own name in errors and its own
//! folder for the files it names. It holds library records only
//! ([`LIBRARY_RECORDS`]). The limits of one deck hold for the deck and all
//! it includes together: at most [`MAX_DECK_BYTES`] read in all (a file
//! included twice counts twice), [`MAX_INCLUDES`] files, [`MAX_INCLUDE_DEPTH`]
//! deep, and no file includes itself, directly or not.

use std::collections::HashMap;
use std::io::Read;
use std::path::PathBuf;
use std::sync::Arc;

use glam::DVec3;

use super::lex::{Bytes, Cursor};
use super::parse::{did_you_mean, shown, Parser};
use super::{Builder, DeckError, MAX_DECK_BYTES, MAX_MAGNITUDE};
use crate::scene::{Law, Pos};

/// The most files a deck may include, counting every `include` read (a
/// library is a few files; the bound keeps a deck of includes from opening
/// files without end).
pub const MAX_INCLUDES: usize = 10_000;

/// How deep includes may nest: the deck includes a file that includes a
/// file … at most this many levels.
pub const MAX_INCLUDE_DEPTH: usize = 16;

/// The records an included file may hold: the library's (paths, and the
/// surfaces and lights a scene may share). Objects, the view and the
/// shutter belong to the deck itself.
pub const LIBRARY_RECORDS: &[&str] = &["path", "surface", "paint", "texture", "light", "include"];

/// A path: where it ends, the degrees it turns, its inner Bezier points and
/// its law. In a `motion … to` record `end` and `via` are points of the
/// world; in a `path` record they are offsets from the object's place.
#[derive(Clone, Debug)]
pub(super) struct PathFields {
    pub end: DVec3,
    pub turn: DVec3,
    pub via: Option<[DVec3; 2]>,
    pub law: Law,
}

/// A `path` record: where it stands and what it holds.
struct LibraryPath {
    pos: Pos,
    path: PathFields,
}

/// A file that includes the one being read, waiting for it to end.
struct Includer<'a> {
    p: Parser<'a>,
    dir: PathBuf,
}

/// The first motion that named a path not defined above it: its error is
/// raised once the reader knows whether the path is defined later.
struct UnknownPath {
    name: String,
    /// The error at the path's name in the motion record, its message
    /// still to be written.
    at: DeckError,
}

/// What the reader keeps for the path library and the included files.
pub(super) struct Library<'a> {
    paths: HashMap<String, LibraryPath>,
    unknown: Option<UnknownPath>,
    /// The files that include the one being read, the deck first.
    outer: Vec<Includer<'a>>,
    /// The deck and the files being read, the deck first: each one's
    /// identity (when it is a file) and its name.
    open: Vec<(Option<FileId>, Arc<str>)>,
    /// The bytes the included files may still take.
    bytes_left: usize,
    /// The `include` records read so far.
    files_read: usize,
}

impl Library<'_> {
    /// The library of a deck of `deck_bytes` bytes named `file_name` in
    /// `deck_dir` (the deck's own path, for include cycles, is the name's
    /// last part in that folder).
    pub fn new(deck_bytes: usize, file_name: &str, deck_dir: &std::path::Path) -> Self {
        let own = std::path::Path::new(file_name)
            .file_name()
            .and_then(|n| FileId::of(&deck_dir.join(n)));
        Library {
            paths: HashMap::new(),
            unknown: None,
            outer: Vec::new(),
            open: vec![(own, file_name.into())],
            bytes_left: MAX_DECK_BYTES.saturating_sub(deck_bytes),
            files_read: 0,
        }
    }
}

/// A file as the system knows it: its device and inode, so that a hard
/// link (another name of the same file) is the file it links, and its path
/// resolved (symbolic links and `..` followed), which tells a hard link
/// from a name of the same path.
#[derive(Clone, Debug, PartialEq, Eq)]
struct FileId {
    device: u64,
    inode: u64,
    resolved: PathBuf,
}

impl FileId {
    /// The file at `path`, if there is one.
    fn of(path: &std::path::Path) -> Option<FileId> {
        use std::os::unix::fs::MetadataExt;
        let m = std::fs::metadata(path).ok()?;
        Some(FileId {
            device: m.dev(),
            inode: m.ino(),
            resolved: std::fs::canonicalize(path).ok()?,
        })
    }

    /// Whether both are one file, under one name or two.
    fn same_file(&self, other: &FileId) -> bool {
        (self.device, self.inode) == (other.device, other.inode)
    }
}

/// Where `other` stands, for a message about the file `here`: `line N`
/// in it, `line N of FILE` in another.
fn line_in(other: &Pos, here: &str) -> String {
    if *other.file == *here {
        format!("line {}", other.line)
    } else {
        format!("line {} of {}", other.line, other.file)
    }
}

impl Builder<'_> {
    /// Where an earlier record stands, for "… is already used on …":
    /// `line N` in the file being read, `line N of FILE` in another.
    pub(super) fn line_of(&self, earlier: &Pos) -> String {
        line_in(earlier, &self.p.pos().file)
    }

    /// Refuses a record that an included file may not hold.
    pub(super) fn may_stand_here(&self, keyword: &str, pos: Pos) -> Result<(), DeckError> {
        if self.lib.outer.is_empty() || LIBRARY_RECORDS.contains(&keyword) {
            return Ok(());
        }
        Err(self.p.error_at(
            pos,
            format!(
                "a '{keyword}' record cannot stand in an included file, which holds {} records only",
                LIBRARY_RECORDS.join(", ")
            ),
        ))
    }

    /// `path NAME by DX DY DZ [turn AX AY AZ] [via DX1 DY1 DZ1 DX2 DY2 DZ2]
    /// [law constant|accelerate|decelerate|smooth]`.
    pub(super) fn path(&mut self) -> Result<(), DeckError> {
        self.p.begin("path");
        let (name, pos) = self.p.name("a path name")?;
        self.p.name = Some(name.clone());
        if let Some(first) = self.lib.paths.get(&name) {
            let line = self.line_of(&first.pos);
            return Err(self
                .p
                .error_at(pos, format!("the path name '{name}' is already used on {line}")));
        }
        if self.lib.unknown.as_ref().is_some_and(|u| u.name == name) {
            // Taken: this is the error the motion's becomes.
            let mut e = self
                .lib
                .unknown
                .take()
                .map_or_else(|| self.p.error_at(pos.clone(), ""), |u| u.at);
            e.message = format!(
                "the path '{name}' is used before it is defined (on {}): a record may name only what stands above it",
                line_in(&pos, &e.file)
            );
            return Err(e);
        }
        self.p.keyword("by")?;
        let by = self.p.vec3("after 'by'")?;
        let path = self.path_fields(by)?;
        self.p.end_of_line()?;
        self.lib.paths.insert(name, LibraryPath { pos, path });
        Ok(())
    }

    /// The rest of `motion NAME path PATH`, for the object `entries[i]`:
    /// the library's path PATH made the object's motion (ends and inner
    /// points offset by its `sphereo`), or `None` when no path PATH stands
    /// above (the error waits for [`Builder::unknown_path_error`]).
    pub(super) fn library_path(&mut self, i: usize) -> Result<Option<PathFields>, DeckError> {
        let (name, pos) = self.p.name("a path name")?;
        if let Some((w, _)) = self.p.peek_word()? {
            let mut e = self.p.expected("end of line");
            if ["to", "turn", "via", "law"].iter().any(|f| w.eq_ignore_ascii_case(f)) {
                e.message.push_str(&format!(
                    " — a motion from the library takes its end, turn, via and law from the path '{name}'"
                ));
            }
            return Err(e);
        }
        let Some(lp) = self.lib.paths.get(&name) else {
            if self.lib.unknown.is_none() {
                let at = self.p.error_at(pos, String::new());
                self.lib.unknown = Some(UnknownPath { name, at });
            }
            return Ok(None);
        };
        let o = self.entries[i].record.sphereo;
        let path = PathFields {
            end: o + lp.path.end,
            via: lp.path.via.map(|[a, b]| [o + a, o + b]),
            ..lp.path.clone()
        };
        let points = std::iter::once(path.end).chain(path.via.into_iter().flatten());
        if let Some(p) = points.into_iter().find(|p| p.abs().max_element() > MAX_MAGNITUDE) {
            return Err(self.p.error_at(
                pos,
                format!(
                    "the path '{name}' takes the object to ({}, {}, {}), out of the deck's range -{MAX_MAGNITUDE:e}..{MAX_MAGNITUDE:e}",
                    p.x, p.y, p.z
                ),
            ));
        }
        Ok(Some(path))
    }

    /// The error of the first motion that named a path no record above it
    /// defines, if one did: "unknown path", with the nearest path's name.
    pub(super) fn unknown_path_error(&self) -> Option<DeckError> {
        let u = self.lib.unknown.as_ref()?;
        let mut known: Vec<&str> = self.lib.paths.keys().map(String::as_str).collect();
        known.sort_unstable();
        let mut e = u.at.clone();
        e.message = format!("unknown path '{}'{}", u.name, did_you_mean(&u.name, &known));
        Some(e)
    }

    /// `include FILE`: FILE, relative to the folder of the file that names
    /// it, is read from here on, then the rest of this file.
    pub(super) fn include(&mut self) -> Result<(), DeckError> {
        self.p.begin("include");
        let (file, file_pos) = self.p.word("a file name")?;
        self.p.end_of_line()?;
        let path = self.deck_dir.join(&file);
        let name: Arc<str> = path.to_string_lossy().into();
        if self.lib.outer.len() >= MAX_INCLUDE_DEPTH {
            return Err(self.p.error_at(
                file_pos,
                format!("files may include files at most {MAX_INCLUDE_DEPTH} deep; this would be one deeper"),
            ));
        }
        if self.lib.files_read >= MAX_INCLUDES {
            return Err(self.p.error_at(
                file_pos,
                format!("a deck may include at most {MAX_INCLUDES} files in all, counting each include"),
            ));
        }
        let resolved = FileId::of(&path);
        if let Some((k, id)) = resolved.as_ref().and_then(|r| {
            self.lib
                .open
                .iter()
                .position(|(o, _)| o.as_ref().is_some_and(|o| o.same_file(r)))
                .map(|k| (k, r))
        }) {
            return Err(self.p.error_at(file_pos, self.cycle(k, id, &name)));
        }
        let mut bytes = Vec::new();
        std::fs::File::open(&path)
            .and_then(|f| f.take(self.lib.bytes_left as u64 + 1).read_to_end(&mut bytes))
            .map_err(|e| self.unreadable(file_pos, "included file", &file, &path, e))?;
        if bytes.len() > self.lib.bytes_left {
            let pos = Cursor::new(&bytes, name).pos_at(self.lib.bytes_left);
            return Err(DeckError::at(
                pos,
                "deck",
                None,
                format!(
                    "the deck and the files it includes are larger than {} MiB, the most the reader takes",
                    MAX_DECK_BYTES >> 20
                ),
            ));
        }
        self.lib.bytes_left -= bytes.len();
        self.lib.files_read += 1;
        let dir = path.parent().map(PathBuf::from).unwrap_or_default();
        let inner = Parser::over(Bytes::Shared(bytes.into()), &name);
        let p = std::mem::replace(&mut self.p, inner);
        let dir = std::mem::replace(&mut self.deck_dir, dir);
        self.lib.outer.push(Includer { p, dir });
        self.lib.open.push((resolved, name));
        Ok(())
    }

    /// The error of an include of `name` (the file `id`) that closes a
    /// cycle: the files round it from `open[k]`, which `name` is; a hard
    /// link, another path to the same file, is said to be one.
    fn cycle(&self, k: usize, id: &FileId, name: &str) -> String {
        let (first, first_name) = &self.lib.open[k];
        let chain: Vec<String> = self.lib.open[k..]
            .iter()
            .map(|(_, n)| shown(n))
            .chain(std::iter::once(shown(name)))
            .collect();
        let link = match first {
            Some(f) if f.resolved != id.resolved => {
                format!(", which is {} under another name (a hard link)", shown(first_name))
            }
            _ => String::new(),
        };
        format!(
            "an include cycle: {}{link} (a file may not include itself)",
            chain.join(" includes ")
        )
    }

    /// At the end of an included file: back to the file that included it,
    /// after its `include` record. False at the end of the deck itself.
    pub(super) fn end_of_file(&mut self) -> bool {
        let Some(outer) = self.lib.outer.pop() else {
            return false;
        };
        self.p = outer.p;
        self.deck_dir = outer.dir;
        self.lib.open.pop();
        true
    }
}

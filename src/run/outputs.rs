//! What a run writes, as the flags name it ([`Outputs`]), and the checks of
//! those names before anything is read or written: usage errors (exit 2)
//! first, so a long render never ends on a name it cannot use.

use std::path::{Path, PathBuf};

use crate::exit::Failure;
use crate::output::{is_stream, STDOUT};
use crate::raster::{Format, FormatError};
use crate::tile::Tile;

/// The folder the default outputs go to, created when they are used.
pub const DEFAULT_FOLDER: &str = "raster";

/// The files a run writes and which of them it renders, as `raytrace`'s
/// flags name them (`-o`, `--png`, `--apng`, `--debug`, `--frames`,
/// `--tile`, `--resume`).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Outputs {
    /// The image file, its format by its extension, `-` for standard
    /// output; a film's frames are named after it. `None`:
    /// `raster/<deck stem>.ras` (`raster/<stem>.K-of-N.ras` for a band).
    pub output: Option<PathBuf>,
    /// The image also as a PNG (a still).
    pub png: Option<PathBuf>,
    /// A PNG beside the image when `png` is not given: the default deck's
    /// raster/default.png.
    pub default_png: bool,
    /// A film's frames also as one animated PNG.
    pub apng: Option<PathBuf>,
    /// The listing's debug log (a still).
    pub debug: Option<PathBuf>,
    /// A film's frames to render, `A..B` or `K` (all without it).
    pub frames: Option<String>,
    /// Band K of N of the image's rows, written as a Sun raster of its rows.
    pub tile: Option<Tile>,
    /// Skip each output that is there and complete.
    pub resume: bool,
}

impl Outputs {
    /// Checks the output file names before anything is read or written
    /// (usage errors, exit 2): a name with an extension that names no
    /// format, a `--png` or `--apng` not ending in `.png`, more than one
    /// output to standard output. Gives the format of `-o`, or the error
    /// for a name without an extension, raised once the deck is read and
    /// found to be a still (a film's frames may be named so).
    pub fn check_names(&self) -> Result<Result<Format, Failure>, Failure> {
        let usage = |flag: &str, path: &Path, e: &dyn std::fmt::Display| {
            Failure::usage(format!("{flag} '{}': {e}", path.display()))
        };
        let stdout = [&self.output, &self.png, &self.debug, &self.apng]
            .iter()
            .filter(|p| p.as_deref().is_some_and(|p| p.as_os_str() == STDOUT))
            .count();
        if stdout > 1 {
            return Err(Failure::usage("only one output can go to standard output (-)"));
        }
        self.check_farm_names()?;
        if let Some(png) = self.png.as_deref().filter(|p| p.as_os_str() != STDOUT) {
            match Format::of(png) {
                Ok(Format::Png) => {}
                Ok(_) | Err(FormatError::UnknownFormat(_)) => {
                    return Err(usage(
                        "--png",
                        png,
                        &"--png writes a PNG, so the name must end in .png (-o writes .ras, .ppm or .pnm)",
                    ));
                }
                Err(e) => return Err(usage("--png", png, &e)),
            }
        }
        if let Some(apng) = self.apng.as_deref().filter(|p| p.as_os_str() != STDOUT) {
            if !apng.extension().is_some_and(|e| e.eq_ignore_ascii_case("png")) {
                return Err(usage(
                    "--apng",
                    apng,
                    &"--apng writes an animated PNG, so the name must end in .png",
                ));
            }
        }
        Ok(match self.output.as_deref() {
            None => Ok(Format::SunRaster),
            Some(out) => match Format::of_output(out) {
                Err(e @ FormatError::UnknownFormat(None)) => Err(usage("-o", out, &e)),
                Err(e) => return Err(usage("-o", out, &e)),
                Ok(format) => Ok(format),
            },
        })
    }

    /// Checks the outputs of `--tile` and `--resume` (usage errors): each
    /// writes or checks Sun raster files, so neither goes with standard
    /// output, a device, another format, or the files of one whole still
    /// (`--png`, `--debug`); a band has no `--apng` of whole frames.
    fn check_farm_names(&self) -> Result<(), Failure> {
        let flag = match (self.tile, self.resume) {
            (Some(t), _) => format!("--tile {t}"),
            (None, true) => "--resume".into(),
            (None, false) => return Ok(()),
        };
        let what = match self.tile {
            Some(_) => "writes a band as a Sun raster file that `tools join --tiles` reads",
            None => "checks Sun raster files that are there",
        };
        if let Some(out) = &self.output {
            let other = out.extension().is_some_and(|e| !e.eq_ignore_ascii_case("ras"));
            if out.as_os_str() == STDOUT || is_stream(out) || other {
                return Err(Failure::usage(format!(
                    "-o {}: {flag} {what}: name it with -o NAME.ras",
                    out.display()
                )));
            }
        }
        let whole = [
            (self.png.is_some(), "--png"),
            (self.debug.is_some(), "--debug"),
            (self.apng.is_some() && self.tile.is_some(), "--apng"),
        ];
        if let Some((_, other)) = whole.iter().find(|(given, _)| *given) {
            return Err(Failure::usage(format!(
                "{other} with {flag}: {other} writes the whole picture, and {flag} {what}; \
                 join the bands or frames first (tools join, docs/farm.md)"
            )));
        }
        Ok(())
    }

    /// Whether `--resume` could go on from a run of these outputs: they
    /// are the Sun rasters it checks.
    pub fn resumable(&self) -> bool {
        Outputs {
            resume: true,
            ..self.clone()
        }
        .check_farm_names()
        .is_ok()
    }
}

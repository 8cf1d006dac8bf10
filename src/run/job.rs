//! A run's files ([`Job`]): one still (its image, a PNG beside it, the
//! listing's debug log) or the frames of a film (a file each, and an
//! animated PNG of them at the end), reserved before the render, kept
//! (`--resume`) or written as each frame is done.

use std::path::{Path, PathBuf};

use super::outputs::{Outputs, DEFAULT_FOLDER};
use super::DeckInput;
use crate::exit::Failure;
use crate::film::{Frame, FrameFiles, FrameRange};
use crate::output::{is_stream, write_atomically, OutputError, PendingFile, STDOUT};
use crate::raster::{read_raster_file, Format, Raster};
use crate::raytrace::{Prepared, Render};
use crate::scene::{FilmRecord, ImageSpec, Scene};
use crate::tile::{check_written, write_tile, Tile};

/// What a run writes, reserved before the render: one still (its image, a
/// PNG beside it, the listing's debug log), or the frames of a film (a file
/// each, and an animated PNG of them at the end).
pub enum Job {
    Still {
        /// Taken when written.
        output: Option<PendingFile>,
        /// Its path, which stays when `output` is taken.
        path: PathBuf,
        format: Format,
        png: Option<PendingFile>,
        debug: Option<PendingFile>,
        tile: Option<Tile>,
    },
    Film {
        film: FilmRecord,
        range: FrameRange,
        files: FrameFiles,
        format: Format,
        apng: Option<PendingFile>,
        /// The frames, rendered or read back (`--resume`), in order, for the
        /// animated PNG.
        rasters: Vec<Raster>,
        tile: Option<Tile>,
    },
}

/// What the deck makes: a still in a format, or the frames of a film.
enum Made {
    Still(Format),
    Film(FilmRecord, FrameRange, Format),
}

/// A file that cannot be written: exit 1, named.
fn not_written(path: &Path, e: impl std::fmt::Display) -> Failure {
    Failure::other(format!("{}: {e}", path.display()))
}

impl Job {
    /// Checks `outputs` against the deck (film or still) and reserves every
    /// output, so a usage error (exit 2) comes first and writes nothing,
    /// and a long render never ends on a file it cannot write.
    /// `format` is the one of `-o` ([`Outputs::check_names`]), or the error
    /// for a still named without an extension (a film's frames may be).
    pub fn reserve(
        outputs: &Outputs,
        scene: &Scene,
        deck: &DeckInput,
        format: Result<Format, Failure>,
    ) -> Result<Job, Failure> {
        let band = outputs.tile.map(|t| format!(".{}-of-{}", t.k, t.n)).unwrap_or_default();
        let output = outputs
            .output
            .clone()
            .unwrap_or_else(|| Path::new(DEFAULT_FOLDER).join(format!("{}{band}.ras", deck.stem)));
        let png = outputs.png.clone().or_else(|| {
            outputs
                .default_png
                .then(|| Path::new(DEFAULT_FOLDER).join("default.png"))
        });
        let what = match &scene.film {
            // A film's frames named without an extension are Sun rasters.
            Some(film) => Made::Film(
                film.clone(),
                check_film(outputs, film, &deck.name, &output)?,
                format.unwrap_or(Format::SunRaster),
            ),
            None => {
                if let Some(flag) = [
                    (outputs.frames.is_some(), "--frames"),
                    (outputs.apng.is_some(), "--apng"),
                ]
                .iter()
                .find_map(|&(given, flag)| given.then_some(flag))
                {
                    return Err(Failure::usage(format!(
                        "{flag} is for a film, and {} has no 'film' record (legacy_pascal/DECK.md, 'film')",
                        deck.name
                    )));
                }
                Made::Still(format?)
            }
        };
        if outputs.output.is_none() || (outputs.png.is_none() && png.is_some()) {
            std::fs::create_dir_all(DEFAULT_FOLDER).map_err(|e| not_written(Path::new(DEFAULT_FOLDER), e))?;
        }
        let reserve = |path: &Path| PendingFile::create(path).map_err(|e| not_written(path, e));
        let output = reserve(&output)?;
        Ok(match what {
            Made::Film(film, range, format) => Job::Film {
                film,
                range,
                // The frames go beside `output`, whose folder reserving it
                // has checked (it is not written itself); the APNG is
                // reserved now, so a bad name fails before the first frame.
                files: FrameFiles::of(output.path()),
                format,
                apng: outputs.apng.as_deref().map(reserve).transpose()?,
                rasters: Vec::new(),
                tile: outputs.tile,
            },
            Made::Still(format) => Job::Still {
                path: output.path().to_path_buf(),
                output: Some(output),
                format,
                png: png.as_deref().map(reserve).transpose()?,
                debug: outputs.debug.as_deref().map(reserve).transpose()?,
                tile: outputs.tile,
            },
        })
    }

    /// A film's frames to render.
    pub fn range(&self) -> Option<FrameRange> {
        match self {
            Job::Still { .. } => None,
            Job::Film { range, .. } => Some(*range),
        }
    }

    /// The frames to render, in order.
    pub fn frames(&self) -> Vec<Frame> {
        match self {
            Job::Still { .. } => vec![Frame::STILL],
            Job::Film { film, range, .. } => range.numbers().map(|k| film.frame(k)).collect(),
        }
    }

    /// The file `frame` is written to, and the band it holds.
    pub fn file_of(&self, frame: Frame) -> (PathBuf, Option<Tile>) {
        match self {
            Job::Still { path, tile, .. } => (path.clone(), *tile),
            Job::Film { film, files, tile, .. } => (files.path(frame.number, film.frames), *tile),
        }
    }

    /// A film's frame's file, which a stop keeps once it is written whole;
    /// `None` for a still (written whole at its end).
    pub fn frame_file(&self, frame: Frame) -> Option<PathBuf> {
        match self {
            Job::Still { .. } => None,
            Job::Film { .. } => Some(self.file_of(frame).0),
        }
    }

    /// Whether `frame`'s file is there and complete (`--resume`): its
    /// header and length as this run would write them. Else why not, for a
    /// file that is there (it is rendered again); `None` for one that is
    /// not.
    pub fn complete(&self, frame: Frame, img: &ImageSpec) -> Result<(), Option<(PathBuf, String)>> {
        let (path, tile) = self.file_of(frame);
        check_written(&path, tile, img.width, img.height).map_err(|why| path.exists().then(|| (path, why.to_string())))
    }

    /// Keeps `frame`'s complete file (`--resume`): a film's frame is read
    /// back for the animated PNG.
    pub fn keep(&mut self, frame: Frame) -> Result<(), Failure> {
        let (path, _) = self.file_of(frame);
        if let Job::Film {
            apng: Some(_), rasters, ..
        } = self
        {
            rasters.push(read_raster_file(&path).map_err(|e| Failure::input(format!("{}: {e}", path.display())))?);
        }
        Ok(())
    }

    /// The progress bar's message while `frame` is traced.
    pub fn tracing(&self, deck: &str, frame: Frame) -> String {
        match self {
            Job::Still { .. } => format!("tracing {deck}"),
            Job::Film { film, .. } => format!("tracing {deck} frame {}/{}", frame.number, film.frames),
        }
    }

    /// What an error about `frame`'s pixels names.
    pub fn what(&self, deck: &str, frame: Frame) -> String {
        match self {
            Job::Still { .. } => deck.to_string(),
            Job::Film { .. } => format!("{deck}: frame {}", frame.number),
        }
    }

    /// Writes what `frame`'s render makes: the still's files, or the
    /// frame's raster (atomically, at once) kept for the animated PNG.
    pub fn write(&mut self, frame: Frame, render: Render, prepared: &Prepared) -> Result<(), Failure> {
        match self {
            Job::Still {
                output,
                format,
                png,
                debug,
                tile,
                ..
            } => {
                let (format, height) = (*format, prepared.scene().image.height);
                commit(output, |w| write_frame(&render, format, *tile, height, w))?;
                commit(png, |w| Format::Png.write(&render.raster, w))?;
                if debug.is_some() {
                    let log = crate::raytrace::debug_log(prepared, &render);
                    commit(debug, |w| w.write_all(log.as_bytes()).map_err(OutputError::from))?;
                }
            }
            Job::Film {
                film,
                files,
                format,
                apng,
                rasters,
                tile,
                ..
            } => {
                let path = files.path(frame.number, film.frames);
                let height = prepared.scene().image.height;
                match (*tile, *format) {
                    // The thesis's `outputframe`, a frame's raster file.
                    (None, Format::SunRaster) => crate::raster::outputframe(&path, &render.raster),
                    _ => write_atomically(&path, |w| write_frame(&render, *format, *tile, height, w)),
                }
                .map_err(|e| not_written(&path, e))?;
                if apng.is_some() {
                    rasters.push(render.raster);
                }
            }
        }
        Ok(())
    }

    /// For the summary line: what is written, and for a film which frames.
    pub fn summary(&self) -> (String, Option<String>) {
        let and = |file: &Option<PendingFile>| {
            file.as_ref()
                .map(|f| format!(" and {}", f.path().display()))
                .unwrap_or_default()
        };
        match self {
            Job::Still { output, png, .. } => {
                let first = output.as_ref().map(|f| f.path().display().to_string());
                (format!("{}{}", first.unwrap_or_default(), and(png)), None)
            }
            Job::Film {
                film,
                range,
                files,
                apng,
                ..
            } => (
                format!(
                    "{} … {}{}",
                    files.path(range.first, film.frames).display(),
                    files.path(range.last, film.frames).display(),
                    and(apng)
                ),
                Some(format!("frames {}..{} of {}", range.first, range.last, film.frames)),
            ),
        }
    }

    /// Writes the animated PNG of a film.
    pub fn finish(self) -> Result<(), Failure> {
        match self {
            Job::Film {
                film,
                apng: Some(file),
                rasters,
                ..
            } => write_apng(file, &rasters, film.rate),
            _ => Ok(()),
        }
    }
}

/// Writes a frame's render (a still's, or a film's frame) in `format`, or
/// with `tile` its band as `tools join --tiles` reads it: an image of
/// `height` rows in all.
fn write_frame(
    render: &Render,
    format: Format,
    tile: Option<Tile>,
    height: usize,
    w: &mut dyn std::io::Write,
) -> Result<(), crate::raster::RasterError> {
    match tile {
        Some(t) => write_tile(&render.raster, t, height, w),
        None => format.write_render(&render.raster, &render.colours, w),
    }
}

/// Writes a reserved file through `write`; an error names the file.
fn commit<E: From<OutputError> + std::fmt::Display>(
    file: &mut Option<PendingFile>,
    write: impl FnOnce(&mut dyn std::io::Write) -> Result<(), E>,
) -> Result<(), Failure> {
    match file.take() {
        Some(f) => {
            let path = f.path().to_path_buf();
            f.commit(write).map_err(|e| not_written(&path, e))
        }
        None => Ok(()),
    }
}

#[cfg(feature = "png")]
fn write_apng(file: PendingFile, rasters: &[Raster], rate: u32) -> Result<(), Failure> {
    let path = file.path().to_path_buf();
    let bytes = crate::film::encode_apng(rasters, rate).map_err(|e| not_written(&path, e))?;
    file.commit(|w| w.write_all(&bytes).map_err(OutputError::from))
        .map_err(|e| not_written(&path, e))
}

#[cfg(not(feature = "png"))]
fn write_apng(_file: PendingFile, _rasters: &[Raster], _rate: u32) -> Result<(), Failure> {
    Ok(())
}

/// The flags of a film checked against its `film` record before any output
/// is reserved: the frames to render.
fn check_film(outputs: &Outputs, film: &FilmRecord, file_name: &str, output: &Path) -> Result<FrameRange, Failure> {
    let range = match &outputs.frames {
        Some(text) => FrameRange::parse(text, film.frames).map_err(Failure::usage)?,
        None => film.all(),
    };
    let known = output.extension().is_none() || Format::of(output).is_ok();
    if output.as_os_str() == STDOUT || is_stream(output) || !known {
        return Err(Failure::usage(format!(
            "-o {}: a film writes one file per frame, STEM.0001.ras …; name them with -o STEM.ras \
             (or STEM.png, .ppm, .pnm, .exr)",
            output.display()
        )));
    }
    for (given, flag, instead) in [
        (
            outputs.png.is_some(),
            "--png",
            "--apng FILE for an animated PNG of the frames",
        ),
        (
            outputs.debug.is_some(),
            "--debug",
            "a deck without 'film' for the listing's log of one frame",
        ),
    ] {
        if given {
            return Err(Failure::usage(format!(
                "{flag} writes one still, and {file_name} is a film: use {instead}"
            )));
        }
    }
    #[cfg(not(feature = "png"))]
    if outputs.apng.is_some() {
        return Err(Failure::usage(
            "--apng: this build has no PNG export (the `png` feature is off)",
        ));
    }
    Ok(range)
}

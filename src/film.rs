//! The film: a scene rendered as a sequence of frames, each blurred over
//! its own shutter. The port's extension: the thesis renders one still
//! whose shutter spans the whole motion, though it is written for animation
//! (§1.2, the TV commercial in which 'N' deforms into 'E' and then 'C'
//! while it moves; §6, the films this work prepares). docs/film.md is the
//! users' guide.
//!
//! One job: frame times ([`Frame::time`]), frame numbers and names
//! ([`FrameRange`], [`frame_path`]), reading a film's rasters back
//! ([`read_sequence`]), and the animated PNG ([`write_apng`]).
//! The deck's `film FRAMES [shutter S] [rate FPS]` record is read into a
//! [`FilmRecord`] (a record of the scene, [`crate::scene`]) by the deck
//! reader; its frames are made here.
//!
//! # Film time
//! The scene's motions and key-frame chains run over film time t ∈ [0, 1],
//! the time the thesis's single shutter spans. Frame k (1-based) of F opens
//! its shutter at (k−1)/F and closes it at (k−1+S)/F, and the subpixel time
//! τ ∈ [0, 1] that a sampler gives (the thesis's pattern table and CLT
//! jitter, §2.6.4–2.6.5, or `--sampler`) maps to t = (k−1+S·τ)/F. Without
//! a `film` record the one frame is [`Frame::STILL`], k = F = S = 1, which
//! maps every τ to itself exactly; so does `film 1 shutter 1`.

use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};

use crate::image_file::read_image_file;
use crate::raster::{Raster, RasterError};
use crate::scene::FilmRecord;

impl FilmRecord {
    /// Frame `number` (1-based) of the film.
    pub fn frame(&self, number: u32) -> Frame {
        Frame {
            number,
            frames: self.frames,
            shutter: self.shutter,
        }
    }

    /// Every frame number of the film.
    pub fn all(&self) -> FrameRange {
        FrameRange {
            first: 1,
            last: self.frames,
        }
    }
}

/// One frame's shutter over film time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// k: the frame's number, 1-based.
    pub number: u32,
    /// F: the film's number of frames.
    pub frames: u32,
    /// S: the open fraction of the frame's interval.
    pub shutter: f64,
}

impl Frame {
    /// The one frame of a deck without `film`: the shutter spans all of
    /// film time, as in the thesis.
    pub const STILL: Frame = Frame {
        number: 1,
        frames: 1,
        shutter: 1.0,
    };

    /// The film time t = (k−1+S·τ)/F of the subpixel time `tau` (0 when
    /// the shutter opens, 1 when it closes). Every sample time of the
    /// render loop passes through here. For [`Frame::STILL`] it is `tau`
    /// itself, bit for bit: (0 + 1·τ)/1 rounds to τ.
    pub fn time(&self, tau: f64) -> f64 {
        (f64::from(self.number.saturating_sub(1)) + self.shutter * tau) / f64::from(self.frames)
    }
}

/// Frames `first..=last` of a film (`--frames A..B` or `--frames K`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    pub first: u32,
    pub last: u32,
}

/// A `--frames` value that does not fit the film.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FrameRangeError {
    #[error("--frames '{0}': expected K or A..B with whole numbers, e.g. 1..12")]
    Syntax(String),
    #[error("--frames {first}..{last} is reversed (the first frame comes after the last)")]
    Reversed { first: u32, last: u32 },
    #[error("--frames: frame {frame} is outside the film's frames 1..{frames}")]
    Outside { frame: u32, frames: u32 },
}

impl FrameRange {
    /// Reads `K` or `A..B` and checks it against a film of `frames` frames.
    pub fn parse(text: &str, frames: u32) -> Result<FrameRange, FrameRangeError> {
        let number = |s: &str| {
            let s = s.trim();
            if s.is_empty() || !s.bytes().all(|b| b.is_ascii_digit()) {
                return Err(FrameRangeError::Syntax(text.to_string()));
            }
            // Digits only, so the one failure left is a value past u32:
            // outside any film.
            s.parse::<u32>().map_err(|_| FrameRangeError::Outside {
                frame: u32::MAX,
                frames,
            })
        };
        let (first, last) = match text.split_once("..") {
            Some((a, b)) => (number(a)?, number(b)?),
            None => {
                let k = number(text)?;
                (k, k)
            }
        };
        if first > last {
            return Err(FrameRangeError::Reversed { first, last });
        }
        for frame in [first, last] {
            if frame == 0 || frame > frames {
                return Err(FrameRangeError::Outside { frame, frames });
            }
        }
        Ok(FrameRange { first, last })
    }

    /// The frame numbers, in order.
    pub fn numbers(&self) -> RangeInclusive<u32> {
        self.first..=self.last
    }

    /// How many frames the range holds.
    pub fn len(&self) -> u32 {
        self.last - self.first + 1
    }

    /// Never true: a range holds at least one frame.
    pub fn is_empty(&self) -> bool {
        false
    }
}

/// Frame `number`'s raster file: `STEM.0001.ras`, the number with at least
/// four digits (five for a film of 10000 frames), so the files sort in
/// frame order by name.
pub fn frame_path(stem: &Path, number: u32, frames: u32) -> PathBuf {
    FrameFiles {
        stem: stem.to_path_buf(),
        extension: "ras".into(),
    }
    .path(number, frames)
}

/// Where a film's frames are written: `STEM.0001.EXT` …, in the format of
/// the extension (`crate::raster::Format`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FrameFiles {
    pub stem: PathBuf,
    /// As the output was named (`ras`, `png`, `PPM` …).
    pub extension: String,
}

impl FrameFiles {
    /// The frames of an output path: `NAME.ras`, `NAME.png`, `NAME.ppm`,
    /// `NAME.pnm` or `NAME.exr` gives the stem `NAME` and that extension;
    /// a name without an extension is the stem of Sun rasters
    /// (`NAME.0001.ras`). Another extension is kept in the stem (the
    /// caller refuses it first).
    pub fn of(output: &Path) -> FrameFiles {
        let known = output.extension().filter(|_| crate::raster::Format::of(output).is_ok());
        match known {
            Some(e) => FrameFiles {
                stem: output.with_extension(""),
                extension: e.to_string_lossy().into_owned(),
            },
            None => FrameFiles {
                stem: output.to_path_buf(),
                extension: "ras".into(),
            },
        }
    }

    /// Frame `number`'s file: the number with at least four digits (five
    /// for a film of 10000 frames), so the files sort in frame order.
    pub fn path(&self, number: u32, frames: u32) -> PathBuf {
        let digits = frames.to_string().len().max(4);
        let mut name = self.stem.as_os_str().to_owned();
        name.push(format!(".{number:0digits$}.{}", self.extension));
        PathBuf::from(name)
    }
}

/// Why an animated PNG could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ApngError {
    #[error("no frames to write")]
    NoFrames,
    #[error("frame {index} is {width}×{height}, the first is {first_width}×{first_height}")]
    SizeDiffers {
        /// 1-based position in the list.
        index: usize,
        width: usize,
        height: usize,
        first_width: usize,
        first_height: usize,
    },
    #[error(transparent)]
    Raster(#[from] RasterError),
    #[cfg(feature = "png")]
    #[error("PNG encoder: {0}")]
    Png(#[from] png::EncodingError),
}

/// The frames as one animated PNG (APNG), 8-bit RGB, each shown for
/// 1/`rate` s, looping forever. A viewer that does not animate APNG shows
/// the first frame.
#[cfg(feature = "png")]
pub fn encode_apng(frames: &[Raster], rate: u32) -> Result<Vec<u8>, ApngError> {
    let first = frames.first().ok_or(ApngError::NoFrames)?;
    for (i, f) in frames.iter().enumerate() {
        f.check()?;
        if (f.width, f.height) != (first.width, first.height) {
            return Err(ApngError::SizeDiffers {
                index: i + 1,
                width: f.width,
                height: f.height,
                first_width: first.width,
                first_height: first.height,
            });
        }
    }
    let mut bytes = Vec::new();
    {
        // `check` bounds both sides by 16384: the casts are exact.
        let mut encoder = png::Encoder::new(&mut bytes, first.width as u32, first.height as u32);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        // A film is written once and loaded often (the README's APNG).
        encoder.set_compression(png::Compression::High);
        encoder.set_animated(frames.len() as u32, 0)?;
        // 1/rate s; a rate of 0 would be an infinite delay, so it is 1.
        encoder.set_frame_delay(1, rate.clamp(1, u16::MAX as u32) as u16)?;
        let mut writer = encoder.write_header()?;
        for f in frames {
            let flat: Vec<u8> = f.pixels.iter().flatten().copied().collect();
            writer.write_image_data(&flat)?;
        }
        writer.finish()?;
    }
    Ok(bytes)
}

/// [`encode_apng`] written to `path` atomically, as rasters are.
#[cfg(feature = "png")]
pub fn write_apng(path: &Path, frames: &[Raster], rate: u32) -> Result<(), ApngError> {
    let bytes = encode_apng(frames, rate)?;
    crate::output::write_atomically(path, |w| w.write_all(&bytes).map_err(RasterError::from))?;
    Ok(())
}

/// A sequence of rasters that cannot be a film.
#[derive(Debug, thiserror::Error)]
pub enum SequenceError {
    #[error("{}: {source}", .path.display())]
    Read { path: PathBuf, source: RasterError },
    #[error(
        "{}: {width}×{height}, but {} is {first_width}×{first_height}: the frames of a film have one size",
        .path.display(), .first.display()
    )]
    SizeDiffers {
        path: PathBuf,
        width: usize,
        height: usize,
        first: PathBuf,
        first_width: usize,
        first_height: usize,
    },
}

/// Reads the frames of a film, in the order given: Sun rasters, or PNG or
/// PPM files ([`crate::image_file`]); the first that cannot be read, or
/// whose size differs from the first's, is named in the error.
pub fn read_sequence(paths: &[PathBuf]) -> Result<Vec<Raster>, SequenceError> {
    let mut frames: Vec<Raster> = Vec::with_capacity(paths.len());
    for path in paths {
        let r = read_image_file(path).map_err(|source| SequenceError::Read {
            path: path.clone(),
            source,
        })?;
        if let Some(first) = frames.first() {
            if (r.width, r.height) != (first.width, first.height) {
                return Err(SequenceError::SizeDiffers {
                    path: path.clone(),
                    width: r.width,
                    height: r.height,
                    first: paths[0].clone(),
                    first_width: first.width,
                    first_height: first.height,
                });
            }
        }
        frames.push(r);
    }
    Ok(frames)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Pos;

    #[test]
    fn still_maps_every_time_to_itself() {
        for tau in [0.0, 1e-300, 0.1, 1.0 / 3.0, 0.5, 0.999_999_999, 1.0, 1.5] {
            assert_eq!(Frame::STILL.time(tau).to_bits(), tau.to_bits());
        }
    }

    #[test]
    fn frame_k_opens_and_closes_its_shutter() {
        let film = FilmRecord {
            pos: Pos::default(),
            frames: 4,
            shutter: 0.5,
            rate: 12,
        };
        assert_eq!(film.frame(1).time(0.0), 0.0);
        assert_eq!(film.frame(1).time(1.0), 0.125);
        assert_eq!(film.frame(3).time(0.0), 0.5);
        assert_eq!(film.frame(3).time(1.0), 0.625);
        assert_eq!(film.frame(4).time(0.5), 0.8125);
    }

    #[test]
    fn frame_ranges_parse_and_refuse() {
        assert_eq!(FrameRange::parse("3", 6), Ok(FrameRange { first: 3, last: 3 }));
        assert_eq!(FrameRange::parse("2..5", 6), Ok(FrameRange { first: 2, last: 5 }));
        assert_eq!(
            FrameRange::parse("5..2", 6),
            Err(FrameRangeError::Reversed { first: 5, last: 2 })
        );
        assert_eq!(
            FrameRange::parse("0..2", 6),
            Err(FrameRangeError::Outside { frame: 0, frames: 6 })
        );
        assert_eq!(
            FrameRange::parse("7", 6),
            Err(FrameRangeError::Outside { frame: 7, frames: 6 })
        );
        for bad in ["", "a", "1..", "..3", "1...3", "-1", "1.5", "1..2..3"] {
            assert!(
                matches!(FrameRange::parse(bad, 6), Err(FrameRangeError::Syntax(_))),
                "{bad}"
            );
        }
        assert_eq!(FrameRange { first: 2, last: 5 }.len(), 4);
    }

    #[test]
    fn frame_files_sort_by_number() {
        assert_eq!(
            frame_path(Path::new("raster/nec"), 7, 36),
            PathBuf::from("raster/nec.0007.ras")
        );
        assert_eq!(frame_path(Path::new("x"), 12, 10000), PathBuf::from("x.00012.ras"));
        let files = |out: &str| FrameFiles::of(Path::new(out));
        assert_eq!(files("out/film.ras").path(3, 36), PathBuf::from("out/film.0003.ras"));
        assert_eq!(files("out/film.RAS").path(3, 36), PathBuf::from("out/film.0003.RAS"));
        assert_eq!(files("out/film").path(3, 36), PathBuf::from("out/film.0003.ras"));
        assert_eq!(files("out/film.png").path(12, 36), PathBuf::from("out/film.0012.png"));
        assert_eq!(files("film.ppm").path(1, 2), PathBuf::from("film.0001.ppm"));
        assert_eq!(files("film.pnm").path(1, 2), PathBuf::from("film.0001.pnm"));
        assert_eq!(files("a.b").path(1, 2), PathBuf::from("a.b.0001.ras"));
    }
}

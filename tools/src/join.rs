//! `tools join`: a film's frame rasters, rendered anywhere (one process,
//! a Slurm job array, GNU parallel over hosts), joined into one animated
//! PNG, and optionally a still strip of every Nth frame for viewers that do
//! not animate APNG; with `--tiles`, the bands of a still (`raytrace --tile
//! K/N`) stacked into the whole image. The port's extension (docs/film.md,
//! docs/farm.md).

use std::path::{Path, PathBuf};

use raytrace::exit::Failure;
use raytrace::film::{read_sequence, write_apng};
use raytrace::raster::{write_image, write_png, Format, Raster};

/// The gap between the frames of a strip, in pixels (black).
const STRIP_GAP: usize = 4;

/// Reads `files` in order (all one size), writes them to `out` as an APNG
/// at `rate` frames a second and, with `strip`, frames 1, 1+N, 1+2N, …
/// side by side to a PNG. As in every program: a name that is not a PNG
/// is a usage error, found before any frame is read, and a frame that
/// cannot be read an input error (both exit 2); a file that cannot be
/// written is exit 1.
pub fn join(files: &[PathBuf], out: &Path, rate: u32, strip: Option<(&Path, usize)>) -> Result<(), Failure> {
    for (flag, path) in std::iter::once(("-o", out)).chain(strip.map(|(p, _)| ("--strip", p))) {
        if Format::of(path).ok() != Some(Format::Png) {
            return Err(Failure::usage(format!(
                "{flag} '{}': an animated PNG or a strip is a PNG, so the name must end in .png",
                path.display()
            )));
        }
    }
    let frames = read_sequence(files).map_err(Failure::input)?;
    let not_written = |path: &Path, e: &dyn std::fmt::Display| Failure::other(format!("{}: {e}", path.display()));
    write_apng(out, &frames, rate).map_err(|e| not_written(out, &e))?;
    let size = std::fs::metadata(out).map(|m| m.len()).unwrap_or(0);
    println!(
        "wrote {} ({} frames, {} fps, {} bytes)",
        out.display(),
        frames.len(),
        rate,
        size
    );
    if let Some((path, every)) = strip {
        let picked: Vec<&Raster> = frames.iter().step_by(every.max(1)).collect();
        let s = strip_of(&picked);
        write_png(path, &s).map_err(|e| not_written(path, &e))?;
        println!(
            "wrote {} ({} frames, every {})",
            path.display(),
            picked.len(),
            every.max(1)
        );
    }
    Ok(())
}

/// `tools join --tiles`: reads the bands in the order given, checks that
/// they are bands 1..N of one image ([`raytrace::tile::join`]; a part that
/// does not fit, or a band missing, is an input error naming the file,
/// exit 2) and writes the whole image to `out`, its format by its
/// extension. A bad `out` name is a usage error, found before any band is
/// read.
pub fn join_tiles(files: &[PathBuf], out: &Path) -> Result<(), Failure> {
    let format = Format::of(out).map_err(|e| Failure::usage(format!("-o '{}': {e}", out.display())))?;
    let whole = raytrace::tile::join(files).map_err(Failure::input)?;
    write_image(out, &whole, format).map_err(|e| Failure::other(format!("{}: {e}", out.display())))?;
    println!(
        "wrote {} ({}×{}, {} bands)",
        out.display(),
        whole.width,
        whole.height,
        files.len()
    );
    Ok(())
}

/// The frames side by side, left to right, `STRIP_GAP` black pixels apart
/// (all frames one size, as [`read_sequence`] ensures).
pub fn strip_of(frames: &[&Raster]) -> Raster {
    let (w, h) = frames.first().map_or((0, 0), |f| (f.width, f.height));
    let n = frames.len();
    let width = (n * w + n.saturating_sub(1) * STRIP_GAP).max(1);
    let mut pixels = vec![[0u8; 3]; width * h.max(1)];
    for (i, f) in frames.iter().enumerate() {
        let left = i * (w + STRIP_GAP);
        for y in 0..h {
            pixels[y * width + left..][..w].copy_from_slice(&f.pixels[y * w..][..w]);
        }
    }
    Raster {
        width,
        height: h.max(1),
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_strip_puts_frames_side_by_side_with_gaps() {
        let a = Raster {
            width: 2,
            height: 1,
            pixels: vec![[1, 1, 1], [2, 2, 2]],
        };
        let b = Raster {
            width: 2,
            height: 1,
            pixels: vec![[3, 3, 3], [4, 4, 4]],
        };
        let s = strip_of(&[&a, &b]);
        assert_eq!((s.width, s.height), (2 + STRIP_GAP + 2, 1));
        assert_eq!(s.pixels[0], [1, 1, 1]);
        assert_eq!(s.pixels[1], [2, 2, 2]);
        assert_eq!(s.pixels[2], [0, 0, 0]);
        assert_eq!(s.pixels[2 + STRIP_GAP], [3, 3, 3]);
        assert_eq!(s.pixels[3 + STRIP_GAP], [4, 4, 4]);
    }
}

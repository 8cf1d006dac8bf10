//! Tiles of a still: band K of N of an image's rows, rendered by one
//! process (`raytrace --tile K/N`), written as a raster of those rows, and
//! stacked again into the whole image (`tools join --tiles`). The port's
//! extension (docs/farm.md): the thesis looks to multiprocessor ray tracing,
//! the image cut into sub-images each traced by its own processor and put
//! back together (§2.1.2 (1)(a), Fig. 2.7, after Nishimura 1983; §6.2), but
//! its program renders one image in one process.
//!
//! How bands meet the listing's blocks: the main program's scanline loop
//! (OCR lines 3100–3215) traces `masksize` scanlines of subpixels into
//! `virtual[scancol, scanline mod masksize + 1]` and, when `scanline mod
//! masksize = 0`, calls `antialias(1, i4, acthighx, i4)` with `i4 =
//! scanline div masksize`: block i4 of scanlines (i4−1)·masksize+1 …
//! i4·masksize becomes row i4 of final pixels, and nothing else carries
//! from one block to the next (the listing's one cursor that did, `aindex`,
//! is commented out; the port's samplers take every value from the
//! subpixel, `crate::sampler`). A band is whole rows, so whole blocks: band
//! rows a..b (0-based, b excluded) are the scanlines a·masksize+1 …
//! b·masksize, traced with the samples the whole image gives them, and the
//! bands stacked are the whole image byte for byte (tests/tiles.rs).
//!
//! The split: band K of N of H rows is rows ⌊(K−1)·H/N⌋ … ⌊K·H/N⌋, so the
//! bands differ by at most one row and none is empty while N ≤ H.
//!
//! The file of a tile is the Sun raster of its rows (any raster reader
//! shows the band) followed by one line that says which band it is,
//! `raytrace tile K/N: rows A..B of H`, which raster readers skip (bytes
//! after the image are no part of it). That line is how `tools join
//! --tiles` knows the parts fit one image (one width, one N, one H, bands
//! 1..N in order, none missing), and, being last, how `--resume` knows a
//! tile was written to its end.

use std::fmt;
use std::io::Write;
use std::ops::Range;
use std::path::{Path, PathBuf};

use crate::raster::{
    check_complete, open_sized, read_bounded, read_raster, read_raster_bytes, sun_raster_len, write_sun_raster,
    PixelLimit, Raster, RasterError,
};

/// The most tiles: the most rows an image may have (`--size`'s and the
/// deck's limit of 8192 a side), since a band is at least one row.
pub const MAX_TILES: u32 = 8192;

/// Band `k` of `n` (1 ≤ k ≤ n): `--tile K/N`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    pub k: u32,
    pub n: u32,
}

impl fmt::Display for Tile {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.k, self.n)
    }
}

impl Tile {
    /// `K/N`: two whole numbers, 1 ≤ K ≤ N ≤ [`MAX_TILES`].
    pub fn parse(text: &str) -> Result<Tile, String> {
        let (k, n) = text
            .split_once('/')
            .ok_or_else(|| format!("'{text}' is not K/N (band K of N, e.g. 2/4)"))?;
        let number = |v: &str, what: &str| {
            v.trim()
                .parse::<u32>()
                .map_err(|_| format!("'{text}': {what} '{v}' is not a whole number"))
        };
        let (k, n) = (number(k, "K")?, number(n, "N")?);
        if !(1..=MAX_TILES).contains(&n) {
            return Err(format!("'{text}': N, the number of bands, must be 1..={MAX_TILES}"));
        }
        if !(1..=n).contains(&k) {
            return Err(format!("'{text}': K must be one of the bands 1..={n}"));
        }
        Ok(Tile { k, n })
    }

    /// The rows of band K of N of an image `height` rows high; an error
    /// when there are more bands than rows (a band would be empty).
    pub fn band(self, height: usize) -> Result<Range<usize>, String> {
        if self.n as usize > height {
            return Err(format!(
                "--tile {self}: {} bands of an image of {height} rows would leave some empty; at most {height}",
                self.n
            ));
        }
        let at = |k: u32| (u64::from(k) * height as u64 / u64::from(self.n)) as usize;
        Ok(at(self.k - 1)..at(self.k))
    }

    /// The line after a tile's pixels: `raytrace tile K/N: rows A..B of H`.
    fn trailer(self, rows: &Range<usize>, height: usize) -> Vec<u8> {
        format!("raytrace tile {self}: rows {}..{} of {height}\n", rows.start, rows.end).into_bytes()
    }

    /// The tile a trailer names, and the whole image's height; `None` for
    /// bytes that are not one, or a band that is not this split's.
    fn of_trailer(bytes: &[u8]) -> Option<(Tile, usize)> {
        let text = std::str::from_utf8(bytes).ok()?;
        let rest = text.strip_prefix("raytrace tile ")?.strip_suffix('\n')?;
        let (tile, rest) = rest.split_once(": rows ")?;
        let (_, height) = rest.split_once(" of ")?;
        let tile = Tile::parse(tile).ok()?;
        let height = height.parse().ok()?;
        let rows = tile.band(height).ok()?;
        (tile.trailer(&rows, height) == bytes).then_some((tile, height))
    }
}

/// Writes band `tile` of an image `height` rows high, `raster` its rows:
/// the Sun raster, then the line that names the band.
pub fn write_tile(raster: &Raster, tile: Tile, height: usize, w: &mut dyn Write) -> Result<(), RasterError> {
    let rows = tile.band(height).map_err(RasterError::Inconsistent)?;
    if rows.len() != raster.height {
        return Err(RasterError::Inconsistent(format!(
            "band {tile} of {height} rows is {} rows, the raster {}",
            rows.len(),
            raster.height
        )));
    }
    write_sun_raster(raster, w)?;
    w.write_all(&tile.trailer(&rows, height))?;
    Ok(())
}

/// Checks that `path` holds band `tile` of a `width`×`height` image, whole
/// ([`check_complete`] with its line), or without `tile` the whole
/// image's raster: what `--resume` skips.
pub fn check_written(path: &Path, tile: Option<Tile>, width: usize, height: usize) -> Result<(), String> {
    match tile {
        None => check_complete(path, width, height, b""),
        Some(tile) => {
            let rows = tile.band(height)?;
            check_complete(path, width, rows.len(), &tile.trailer(&rows, height))
        }
    }
}

/// A tile read back: which band of how high an image, and its rows.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Part {
    pub tile: Tile,
    /// The whole image's height.
    pub height: usize,
    pub raster: Raster,
}

/// An error about one part of a join, naming its file.
#[derive(Debug, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct JoinError {
    pub path: PathBuf,
    pub message: String,
}

impl JoinError {
    fn new(path: &Path, message: impl fmt::Display) -> JoinError {
        JoinError {
            path: path.to_path_buf(),
            message: message.to_string(),
        }
    }
}

/// The longest line a tile ends with: `raytrace tile 8192/8192: rows
/// 8191..8192 of 8192` and its newline are 49 bytes; no line is longer
/// than this.
const MAX_TRAILER: usize = 64;

/// Reads a tile `raytrace --tile` wrote: opened once and read front to
/// back (a pipe reads as a file does), no further than its header and its
/// line need, so a file without end (`/dev/zero`) is refused, not read.
pub fn read_tile(path: &Path) -> Result<Part, JoinError> {
    let (mut file, length) = open_sized(path).map_err(|e| JoinError::new(path, e))?;
    let mut bytes = read_raster_bytes(&mut file, PixelLimit::RASTER, length).map_err(|e| JoinError::new(path, e))?;
    // A longer tail than any line is no tile's: `of_trailer` refuses it.
    read_bounded(&mut file, &mut bytes, MAX_TRAILER, length).map_err(|e| JoinError::new(path, e))?;
    let raster = read_raster(&bytes).map_err(|e| JoinError::new(path, e))?;
    let end = sun_raster_len(raster.width, raster.height).min(bytes.len());
    let (tile, height) = Tile::of_trailer(&bytes[end..]).ok_or_else(|| {
        JoinError::new(
            path,
            "not a tile of `raytrace --tile K/N`: no line 'raytrace tile K/N: rows A..B of H' after its pixels",
        )
    })?;
    let rows = tile.band(height).map_err(|e| JoinError::new(path, e))?;
    if rows.len() != raster.height {
        return Err(JoinError::new(
            path,
            format!(
                "band {tile} of {height} rows is {} rows, and it holds {}",
                rows.len(),
                raster.height
            ),
        ));
    }
    Ok(Part { tile, height, raster })
}

/// Reads the tiles `paths`, checks that they are bands 1..N of one image in
/// order (one width, one N, one height, none missing or repeated), and
/// stacks them. An error names the file that does not fit (for a band
/// missing at the end, the last file given).
pub fn join(paths: &[PathBuf]) -> Result<Raster, JoinError> {
    let mut whole: Option<(Part, &Path)> = None;
    let mut pixels = Vec::new();
    for (i, path) in paths.iter().enumerate() {
        let part = read_tile(path)?;
        let misfit = |m: String| Err(JoinError::new(path, m));
        let of = |p: &Part| format!("tile {} of a {}×{} image", p.tile, p.raster.width, p.height);
        let (first, first_path) = whole.get_or_insert((part.clone(), path));
        let fits = (part.raster.width, part.height, part.tile.n) == (first.raster.width, first.height, first.tile.n);
        if !fits {
            return misfit(format!(
                "{}, and {} is {}: they are not bands of one image",
                of(&part),
                first_path.display(),
                of(first)
            ));
        }
        let (expected, n) = (i as u32 + 1, first.tile.n);
        if part.tile.k > expected {
            return misfit(format!(
                "is tile {}, but tile {expected}/{n} is missing before it",
                part.tile
            ));
        }
        if part.tile.k < expected {
            return misfit(format!(
                "is tile {} again or out of order: give tiles 1..{n} of {n} in order",
                part.tile
            ));
        }
        pixels.extend_from_slice(&part.raster.pixels);
    }
    let Some((first, first_path)) = whole else {
        return Err(JoinError::new(Path::new("--tiles"), "no tiles given"));
    };
    let given = paths.len() as u32;
    if given < first.tile.n {
        return Err(JoinError::new(
            paths.last().map_or(first_path, PathBuf::as_path),
            match first.tile.n - given {
                1 => format!(
                    "the last tile given is {given}/{n}: tile {n}/{n} is missing",
                    n = first.tile.n
                ),
                _ => format!(
                    "the last tile given is {given}/{n}: tiles {}..{n} of {n} are missing",
                    given + 1,
                    n = first.tile.n
                ),
            },
        ));
    }
    Ok(Raster {
        width: first.raster.width,
        height: first.height,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_cover_the_rows_in_order_as_evenly_as_they_split() {
        for height in [1usize, 2, 7, 64, 255, 256, 8192] {
            for n in [1u32, 2, 3, 4, 7, 64].into_iter().filter(|&n| n as usize <= height) {
                let bands: Vec<_> = (1..=n).map(|k| Tile { k, n }.band(height).unwrap()).collect();
                assert_eq!(bands[0].start, 0);
                assert_eq!(bands.last().unwrap().end, height);
                for pair in bands.windows(2) {
                    assert_eq!(pair[0].end, pair[1].start);
                }
                let (min, max) = (
                    bands.iter().map(|b| b.len()).min().unwrap(),
                    bands.iter().map(|b| b.len()).max().unwrap(),
                );
                assert!(min >= 1 && max - min <= 1, "{height}/{n}: {bands:?}");
            }
        }
        assert_eq!(Tile { k: 2, n: 3 }.band(10).unwrap(), 3..6);
        assert!(Tile { k: 1, n: 11 }.band(10).unwrap_err().contains("at most 10"));
    }

    #[test]
    fn k_of_n_is_parsed_and_bad_ones_are_said() {
        assert_eq!(Tile::parse("2/4"), Ok(Tile { k: 2, n: 4 }));
        assert_eq!(Tile::parse("1/1"), Ok(Tile { k: 1, n: 1 }));
        for (bad, says) in [
            ("0/3", "K must be one of the bands 1..=3"),
            ("4/3", "K must be one of the bands 1..=3"),
            ("1/0", "N, the number of bands, must be 1..=8192"),
            ("1/8193", "must be 1..=8192"),
            ("x/2", "K 'x' is not a whole number"),
            ("2/y", "N 'y' is not a whole number"),
            ("-1/2", "K '-1'"),
            ("3", "is not K/N"),
        ] {
            let e = Tile::parse(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn a_trailer_reads_back_only_as_written() {
        let tile = Tile { k: 2, n: 3 };
        let line = tile.trailer(&tile.band(10).unwrap(), 10);
        assert_eq!(line, b"raytrace tile 2/3: rows 3..6 of 10\n");
        assert_eq!(Tile::of_trailer(&line), Some((tile, 10)));
        for bad in [
            &b"raytrace tile 2/3: rows 3..7 of 10\n"[..],
            b"raytrace tile 2/3: rows 3..6 of 10",
            b"raytrace tile 2/3: rows 3..6 of 11\n",
            b"raytrace tile 4/3: rows 3..6 of 10\n",
            b"",
        ] {
            assert_eq!(Tile::of_trailer(bad), None, "{}", String::from_utf8_lossy(bad));
        }
    }
}

//! The raster file: a Sun rasterfile, the format the thesis's `Raytrace`
//! wrote on the Sun 3 and sent through `psout` to the PS 390 (Ch. 4 (二),
//! Fig. 4.1; Ch. 4.1 (g) "Output raster file").
//!
//! The thesis does not print the raster procedures; the main program only
//! calls them (OCR lines 3073 and 3165 `rgbtochars`, 3217–3223
//! `outputframe`). What is here is reconstructed from those calls and from
//! the Sun rasterfile layout (`<rasterfile.h>`): a 32-byte big-endian header
//! — magic 0x59a66a95, width, height, depth, length, type, maptype,
//! maplength — then the colour map, then the image, each row padded to a
//! multiple of 16 bits.
//!
//! Reading accepts RT_OLD (0) and RT_STANDARD (1) (BGR order), RT_BYTE_ENCODED
//! (2) and RT_FORMAT_RGB (3) (RGB order), at depth 8 (grey, or indices into an
//! RMT_EQUAL_RGB colour map), 24 and 32 (XBGR, or XRGB for type 3; the first
//! byte of each 32-bit pixel is ignored). Depth 1, RMT_RAW maps and colour
//! maps at depth 24/32 are refused with an error. Any byte string is either
//! a raster or an error, never a panic.
//!
//! Memory: reading costs the bytes of the file it needs plus 3 bytes a
//! pixel, and a raster has at most [`MAX_PIXELS`] pixels (192 MiB; deck
//! textures have a smaller limit, `types::MAX_TEXELS`). Both are checked on
//! the header before anything is allocated. A byte-encoded image is decoded
//! a row at a time straight into its pixels, and its header must declare a
//! size its encoded bytes can hold (at most 86 decoded bytes for each
//! encoded one, the densest run), so a small file cannot claim a large
//! allocation.
//!
//! Writing produces RT_STANDARD, 24-bit, BGR, no colour map, through the
//! writer of [`crate::output`] (a temporary file beside the target renamed
//! over it).

use std::fs::File;
use std::io::{Read, Write};
use std::path::Path;

use byteorder::{BigEndian, ByteOrder};

use crate::types::Intensity;

mod complete;
mod format;
pub use complete::{check_complete, sun_raster_len};
pub use format::{write_exr_to, write_image, write_png_to, write_ppm_to, Format, FormatError, EXTENSIONS};

/// `RAS_MAGIC`: the first four bytes of every Sun raster file.
pub(crate) const RAS_MAGIC: u32 = 0x59a6_6a95;
/// `RT_OLD`: the layout of RT_STANDARD; old writers left `ras_length` 0.
pub(crate) const RT_OLD: u32 = 0;
/// `RT_STANDARD`: raw pixels, 24/32-bit in BGR order.
pub const RT_STANDARD: u32 = 1;
/// `RT_BYTE_ENCODED`: RT_STANDARD data run-length encoded with escape 0x80.
pub const RT_BYTE_ENCODED: u32 = 2;
/// `RT_FORMAT_RGB`: raw pixels, 24/32-bit in RGB order.
pub(crate) const RT_FORMAT_RGB: u32 = 3;
/// `RMT_NONE`: no colour map (`ras_maplength` 0).
pub(crate) const RMT_NONE: u32 = 0;
/// `RMT_EQUAL_RGB`: a map of three planes (red, green, blue) of
/// `ras_maplength / 3` bytes each.
pub(crate) const RMT_EQUAL_RGB: u32 = 1;
/// The largest width and height read or written (a sanity cap, far above
/// the thesis's 256×256 and the PS 390's 1024×864).
pub const MAX_SIDE: usize = 16384;
/// The most pixels a raster read or written may have: 8192 × 8192 (2^26),
/// the largest image a deck can ask for; 192 MiB as pixels. The port's
/// bound, so that a header cannot make the reader allocate gigabytes.
pub const MAX_PIXELS: usize = 8192 * 8192;

/// The length of the header in bytes.
const HEADER_LEN: usize = 32;
/// The largest colour map: 256 entries of three bytes.
const MAX_MAP_LENGTH: usize = 768;
/// The RLE escape byte of RT_BYTE_ENCODED.
const ESCAPE: u8 = 0x80;

/// A 24-bit image, row 0 at the top, `pixels` row-major as [r, g, b].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Raster {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<[u8; 3]>,
}

impl Raster {
    /// Checks that the raster can be written and read back: `pixels` holds
    /// `width × height` entries, both sides are in 1..=[`MAX_SIDE`] and
    /// there are at most [`MAX_PIXELS`] pixels.
    pub fn check(&self) -> Result<(), RasterError> {
        if !(1..=MAX_SIDE).contains(&self.width) || !(1..=MAX_SIDE).contains(&self.height) {
            return Err(RasterError::Inconsistent(format!(
                "size {}×{} is outside 1..={MAX_SIDE} per side",
                self.width, self.height
            )));
        }
        if self.width * self.height > MAX_PIXELS {
            return Err(RasterError::Inconsistent(format!(
                "size {}×{} is more than {MAX_PIXELS} pixels",
                self.width, self.height
            )));
        }
        if self.pixels.len() != self.width * self.height {
            return Err(RasterError::Inconsistent(format!(
                "{} pixels for a {}×{} raster",
                self.pixels.len(),
                self.width,
                self.height
            )));
        }
        Ok(())
    }
}

/// What can go wrong reading or writing a raster file. The messages do not
/// name the file; callers that know it prefix it.
#[derive(Debug, thiserror::Error)]
pub enum RasterError {
    #[error("not a Sun raster file (magic number {0:#010x}, expected 0x59a66a95)")]
    BadMagic(u32),
    #[error("truncated raster file: the {part} needs {needed} bytes, only {found} are present")]
    Truncated {
        part: &'static str,
        needed: usize,
        found: usize,
    },
    #[error("raster size {width}×{height} is outside 1..=16384 per side")]
    BadSize { width: u32, height: u32 },
    #[error(
        "raster size {width}×{height} is {} pixels, more than the {limit} a {what} may have",
        *width as u64 * *height as u64
    )]
    TooLarge {
        width: u32,
        height: u32,
        limit: usize,
        what: &'static str,
    },
    #[error("unsupported raster type {0} (known: 0 old, 1 standard, 2 byte-encoded, 3 RGB)")]
    UnsupportedType(u32),
    #[error("unsupported raster depth {0} (supported: 8, 24, 32 bits)")]
    UnsupportedDepth(u32),
    #[error("unsupported colour map type {0} (supported: 0 none, 1 equal RGB)")]
    UnsupportedMapType(u32),
    #[error("bad colour map: {0}")]
    BadMap(String),
    #[error("header length {header} does not match the image data size {expected}")]
    LengthMismatch { header: u32, expected: usize },
    #[error("pixel ({x}, {y}) has colour index {index}, but the colour map has {entries} entries")]
    ColourIndex {
        x: usize,
        y: usize,
        index: u8,
        entries: usize,
    },
    #[error("byte-encoded data: {0}")]
    Rle(String),
    #[error("raster cannot be written: {0}")]
    Inconsistent(String),
    #[error(transparent)]
    Io(#[from] std::io::Error),
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    #[error(transparent)]
    Format(#[from] FormatError),
    #[cfg(feature = "png")]
    #[error("PNG: {0}")]
    Png(#[from] image::ImageError),
    #[cfg(feature = "png")]
    #[error("PNG: {0}")]
    PngRead(#[from] png::DecodingError),
    #[cfg(not(feature = "png"))]
    #[error("a PNG file, and this build reads none (it is without the `png` feature)")]
    PngNotBuilt,
    #[error("PPM: {0}")]
    Ppm(String),
    #[error("not a Sun raster, PNG or PPM file (it starts with {0:#010x})")]
    UnknownKind(u32),
}

/// The header fields, as stored.
#[derive(Clone, Copy, Debug)]
struct Header {
    width: u32,
    height: u32,
    depth: u32,
    length: u32,
    ras_type: u32,
    maptype: u32,
    maplength: u32,
}

/// What the header says about the layout, once checked.
#[derive(Clone, Copy, Debug)]
struct Layout {
    width: usize,
    height: usize,
    /// Bytes per pixel: 1, 3 or 4.
    bytes_per_pixel: usize,
    /// Bytes per row with the 16-bit padding.
    row_bytes: usize,
    /// `row_bytes × height`: the (decoded) image data.
    data_bytes: usize,
    /// Where the image data starts: after the header and the colour map.
    data_start: usize,
}

fn parse_header(bytes: &[u8]) -> Result<Header, RasterError> {
    if bytes.len() < HEADER_LEN {
        // A short file that does not even start with the magic is not a
        // raster at all; say so rather than "truncated".
        if bytes.len() >= 4 && BigEndian::read_u32(bytes) != RAS_MAGIC {
            return Err(RasterError::BadMagic(BigEndian::read_u32(bytes)));
        }
        return Err(RasterError::Truncated {
            part: "header",
            needed: HEADER_LEN,
            found: bytes.len(),
        });
    }
    let field = |i: usize| BigEndian::read_u32(&bytes[4 * i..4 * i + 4]);
    if field(0) != RAS_MAGIC {
        return Err(RasterError::BadMagic(field(0)));
    }
    Ok(Header {
        width: field(1),
        height: field(2),
        depth: field(3),
        length: field(4),
        ras_type: field(5),
        maptype: field(6),
        maplength: field(7),
    })
}

/// How many pixels a reading may give, and what for (named in the error).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelLimit {
    pub pixels: usize,
    pub what: &'static str,
}

impl PixelLimit {
    /// Any raster: [`MAX_PIXELS`].
    pub const RASTER: PixelLimit = PixelLimit {
        pixels: MAX_PIXELS,
        what: "raster",
    };
}

/// Checks everything the header alone can tell, before any allocation.
fn layout(h: &Header, limit: PixelLimit) -> Result<Layout, RasterError> {
    if !matches!(h.ras_type, RT_OLD | RT_STANDARD | RT_BYTE_ENCODED | RT_FORMAT_RGB) {
        return Err(RasterError::UnsupportedType(h.ras_type));
    }
    let bytes_per_pixel = match h.depth {
        8 => 1,
        24 => 3,
        32 => 4,
        d => return Err(RasterError::UnsupportedDepth(d)),
    };
    let (width, height) = (h.width as usize, h.height as usize);
    if !(1..=MAX_SIDE).contains(&width) || !(1..=MAX_SIDE).contains(&height) {
        return Err(RasterError::BadSize {
            width: h.width,
            height: h.height,
        });
    }
    if width * height > limit.pixels {
        return Err(RasterError::TooLarge {
            width: h.width,
            height: h.height,
            limit: limit.pixels,
            what: limit.what,
        });
    }
    let maplength = h.maplength as usize;
    match h.maptype {
        RMT_NONE => {
            if maplength != 0 {
                return Err(RasterError::BadMap(format!(
                    "map type 0 (none) with map length {maplength}"
                )));
            }
        }
        RMT_EQUAL_RGB => {
            if h.depth != 8 {
                return Err(RasterError::BadMap(format!(
                    "a colour map with depth {} is not supported",
                    h.depth
                )));
            }
            if maplength == 0 || maplength > MAX_MAP_LENGTH || !maplength.is_multiple_of(3) {
                return Err(RasterError::BadMap(format!(
                    "map length {maplength} is not a multiple of 3 in 3..={MAX_MAP_LENGTH}"
                )));
            }
        }
        t => return Err(RasterError::UnsupportedMapType(t)),
    }
    // Both factors are capped, so this cannot overflow: at most 16384 × 4
    // bytes a row, 2^30 bytes in all.
    let row_bytes = (width * bytes_per_pixel).div_ceil(2) * 2;
    let data_bytes = row_bytes * height;
    let length = h.length as usize;
    if h.ras_type == RT_BYTE_ENCODED {
        // Each decoded byte costs at most two encoded bytes (`80 00`), so a
        // longer encoding cannot be exact.
        if length > 2 * data_bytes {
            return Err(RasterError::LengthMismatch {
                header: h.length,
                expected: data_bytes,
            });
        }
    } else if length != 0 && length != data_bytes {
        // RT_OLD files, and some old writers of type 1, leave the length 0.
        return Err(RasterError::LengthMismatch {
            header: h.length,
            expected: data_bytes,
        });
    }
    Ok(Layout {
        width,
        height,
        bytes_per_pixel,
        row_bytes,
        data_bytes,
        data_start: HEADER_LEN + maplength,
    })
}

/// The most bytes of a file [`read_raster`] can look at, given its header.
fn bytes_needed(h: &Header, lay: &Layout) -> usize {
    let data = if h.ras_type != RT_BYTE_ENCODED {
        lay.data_bytes
    } else if h.length != 0 {
        h.length as usize
    } else {
        2 * lay.data_bytes
    };
    lay.data_start + data
}

/// Decodes RT_BYTE_ENCODED data a piece at a time: `80 00` is one 0x80
/// byte, `80 n v` (n ≥ 1) is n + 1 copies of v, any other byte is itself.
/// The encoding runs over the whole padded image, so a run may cross a row
/// end: the decoder keeps what is left of it for the next piece.
struct RunDecoder<'a> {
    src: &'a [u8],
    /// The next encoded byte.
    at: usize,
    /// Bytes decoded so far.
    done: usize,
    /// The decoded size of the whole image.
    expected: usize,
    /// Copies of `value` still owed from the last run.
    left: usize,
    value: u8,
}

impl<'a> RunDecoder<'a> {
    /// A decoder of `src` into `expected` bytes; refuses at once a size the
    /// encoding cannot hold (the densest encoding, `80 ff v`, gives 256
    /// bytes for 3), so nothing is allocated for a header that lies.
    fn new(src: &'a [u8], expected: usize) -> Result<Self, RasterError> {
        if expected > src.len().saturating_mul(86) {
            return Err(RasterError::Rle(format!(
                "{} encoded bytes cannot hold {expected} image bytes",
                src.len()
            )));
        }
        Ok(RunDecoder {
            src,
            at: 0,
            done: 0,
            expected,
            left: 0,
            value: 0,
        })
    }

    /// Fills `out` with the next decoded bytes.
    fn fill(&mut self, out: &mut [u8]) -> Result<(), RasterError> {
        let mut k = 0;
        while k < out.len() {
            if self.left > 0 {
                let n = self.left.min(out.len() - k);
                out[k..k + n].fill(self.value);
                self.left -= n;
                k += n;
                continue;
            }
            let i = self.at;
            let Some(&b) = self.src.get(i) else {
                return Err(RasterError::Truncated {
                    part: "byte-encoded image",
                    needed: self.expected,
                    found: self.done + k,
                });
            };
            if b != ESCAPE {
                out[k] = b;
                k += 1;
                self.at += 1;
                continue;
            }
            let n = *self
                .src
                .get(i + 1)
                .ok_or_else(|| RasterError::Rle(format!("escape at encoded byte {i} is cut off")))?;
            if n == 0 {
                out[k] = ESCAPE;
                k += 1;
                self.at += 2;
                continue;
            }
            let value = *self
                .src
                .get(i + 2)
                .ok_or_else(|| RasterError::Rle(format!("run at encoded byte {i} is cut off")))?;
            let count = n as usize + 1;
            let before = self.done + k;
            if before + count > self.expected {
                return Err(RasterError::Rle(format!(
                    "run of {count} at encoded byte {i} runs past the end of the image \
                     ({before} of {} bytes already decoded)",
                    self.expected
                )));
            }
            (self.left, self.value) = (count, value);
            self.at += 3;
        }
        self.done += out.len();
        Ok(())
    }

    /// With `exact` (the header gave the encoded length), every encoded
    /// byte must have been used; otherwise the rest is ignored.
    fn finish(&self, exact: bool) -> Result<(), RasterError> {
        if exact && self.at < self.src.len() {
            return Err(RasterError::Rle(format!(
                "data continues past the end of the image at encoded byte {}",
                self.at
            )));
        }
        Ok(())
    }
}

/// The image data of a file: raw, present in full, or byte-encoded and
/// decoded a padded row at a time into `row`.
enum ImageData<'a> {
    Raw(&'a [u8]),
    Encoded {
        decoder: RunDecoder<'a>,
        exact: bool,
        row: Vec<u8>,
    },
}

/// Reads a raster file from its bytes, up to [`MAX_PIXELS`] pixels.
///
/// Reconstructed: the Sun rasterfile layout (module doc). Bytes after the
/// image are ignored; everything else that does not fit the layout is an
/// error. 8-bit pixels without a map are grey.
pub fn read_raster(bytes: &[u8]) -> Result<Raster, RasterError> {
    read_raster_within(bytes, PixelLimit::RASTER)
}

/// [`read_raster`] with another pixel limit: a raster with more pixels is
/// refused from its header, before anything is allocated.
pub fn read_raster_within(bytes: &[u8], limit: PixelLimit) -> Result<Raster, RasterError> {
    let h = parse_header(bytes)?;
    let lay = layout(&h, limit)?;

    let map = if h.maptype == RMT_EQUAL_RGB {
        let end = lay.data_start;
        let planes = bytes.get(HEADER_LEN..end).ok_or(RasterError::Truncated {
            part: "colour map",
            needed: end,
            found: bytes.len(),
        })?;
        Some(planes)
    } else {
        None
    };

    let rest = &bytes[lay.data_start.min(bytes.len())..];
    let mut source = if h.ras_type == RT_BYTE_ENCODED {
        let (src, exact) = if h.length != 0 {
            let length = h.length as usize;
            let src = rest.get(..length).ok_or(RasterError::Truncated {
                part: "byte-encoded image",
                needed: lay.data_start + length,
                found: bytes.len(),
            })?;
            (src, true)
        } else {
            (rest, false)
        };
        ImageData::Encoded {
            decoder: RunDecoder::new(src, lay.data_bytes)?,
            exact,
            row: vec![0; lay.row_bytes],
        }
    } else {
        ImageData::Raw(rest.get(..lay.data_bytes).ok_or(RasterError::Truncated {
            part: "image",
            needed: lay.data_start + lay.data_bytes,
            found: bytes.len(),
        })?)
    };

    // Raw data is present in full, and encoded data can hold the image
    // (`RunDecoder::new`), so this is no larger than the input allows.
    let mut pixels = Vec::with_capacity(lay.width * lay.height);
    let rgb_order = h.ras_type == RT_FORMAT_RGB;
    let entries = map.map_or(0, |m| m.len() / 3);
    for y in 0..lay.height {
        let row = match &mut source {
            ImageData::Raw(data) => &data[y * lay.row_bytes..(y + 1) * lay.row_bytes],
            ImageData::Encoded { decoder, row, .. } => {
                decoder.fill(row)?;
                &row[..]
            }
        };
        let row = &row[..lay.width * lay.bytes_per_pixel];
        match lay.bytes_per_pixel {
            1 => {
                for (x, &index) in row.iter().enumerate() {
                    pixels.push(match map {
                        None => [index; 3],
                        Some(m) => {
                            let i = index as usize;
                            if i >= entries {
                                return Err(RasterError::ColourIndex { x, y, index, entries });
                            }
                            [m[i], m[entries + i], m[2 * entries + i]]
                        }
                    });
                }
            }
            n => {
                // 24-bit: B G R (type 3: R G B); 32-bit: X B G R (X R G B).
                for p in row.chunks_exact(n) {
                    let [a, b, c] = [p[n - 3], p[n - 2], p[n - 1]];
                    pixels.push(if rgb_order { [a, b, c] } else { [c, b, a] });
                }
            }
        }
    }
    if let ImageData::Encoded { decoder, exact, .. } = &source {
        decoder.finish(*exact)?;
    }
    Ok(Raster {
        width: lay.width,
        height: lay.height,
        pixels,
    })
}

/// Reads a raster file, up to [`MAX_PIXELS`] pixels.
///
/// Reconstructed (as [`read_raster`]). Only the bytes the header can need
/// are read, so a huge file costs no more memory than its raster.
pub fn read_raster_file(path: &Path) -> Result<Raster, RasterError> {
    read_raster_file_within(path, PixelLimit::RASTER)
}

/// [`read_raster_file`] with another pixel limit ([`read_raster_within`]).
pub fn read_raster_file_within(path: &Path, limit: PixelLimit) -> Result<Raster, RasterError> {
    let (mut file, length) = open_sized(path)?;
    read_raster_within(&read_raster_bytes(&mut file, limit, length)?, limit)
}

/// A file opened for reading, and its length when it is a regular file
/// (not a pipe or a device, whose length says nothing).
pub fn open_sized(path: &Path) -> std::io::Result<(File, Option<u64>)> {
    let file = File::open(path)?;
    let meta = file.metadata()?;
    let length = meta.is_file().then_some(meta.len());
    Ok((file, length))
}

/// Reads at most `most` more bytes of `reader` onto `bytes`, its room made
/// once for what `length` (the reader's bytes from its start, when known)
/// says is there: a buffer grown by doubling as it fills would hold up to
/// twice the file while it is read.
pub(crate) fn read_bounded(
    reader: &mut impl Read,
    bytes: &mut Vec<u8>,
    most: usize,
    length: Option<u64>,
) -> std::io::Result<()> {
    let there = length.map_or(0, |l| {
        usize::try_from(l).unwrap_or(usize::MAX).saturating_sub(bytes.len())
    });
    bytes.reserve_exact(most.min(there));
    reader.take(most as u64).read_to_end(bytes)?;
    Ok(())
}

/// The bytes of the raster that starts at `reader`'s position: its header
/// and then no more than the header says the raster needs (all there is,
/// if less), so a writer that sends a valid header and then bytes without
/// end (a pipe, `/dev/zero`) is read no further than the raster, and
/// `reader` is left just past it (where a tile's line follows). The file
/// is read once, front to back: a pipe reads as a file does. A header
/// [`read_raster_within`] refuses is refused here before more is read.
/// `length` is the reader's bytes from its start, when known (a regular
/// file's length: [`open_sized`]), so that the bytes are held once.
pub fn read_raster_bytes(
    reader: &mut impl Read,
    limit: PixelLimit,
    length: Option<u64>,
) -> Result<Vec<u8>, RasterError> {
    let mut bytes = Vec::with_capacity(HEADER_LEN);
    reader.take(HEADER_LEN as u64).read_to_end(&mut bytes)?;
    let needed = match parse_header(&bytes) {
        Ok(h) => bytes_needed(&h, &layout(&h, limit)?),
        // Let read_raster report the short header.
        Err(_) => HEADER_LEN,
    };
    let rest = needed - bytes.len().min(needed);
    read_bounded(reader, &mut bytes, rest, length)?;
    Ok(bytes)
}

/// `rgbtochars(acolor, threechars)`: a colour of the renderer (each channel
/// nominally 0–1) to the three bytes of a raster pixel.
///
/// Reconstructed: the main program calls it for the background
/// (`rgbtochars(backgrnd,back)`, OCR line 3073) and for each traced pixel
/// (line 3165); its body is not printed. Each channel is clamped to [0, 1]
/// and rounded to the nearest of 0..=255. A NaN channel (a failed shading
/// computation) gives 0, so a bad sample shows black rather than stopping
/// the render.
pub fn rgbtochars(acolor: Intensity) -> [u8; 3] {
    let byte = |c: f64| {
        if c.is_nan() {
            0
        } else {
            (c.clamp(0.0, 1.0) * 255.0).round() as u8
        }
    };
    [byte(acolor.x), byte(acolor.y), byte(acolor.z)]
}

/// The bytes of a raster file: RT_STANDARD, 24-bit, BGR, rows padded to 16
/// bits, `ras_length` = padded row bytes × height, no colour map.
///
/// # Panics
/// If the raster fails [`Raster::check`] (a bug of the caller:
/// [`outputframe`] checks first and returns an error instead).
pub fn encode_raster(raster: &Raster) -> Vec<u8> {
    if let Err(e) = raster.check() {
        panic!("encode_raster: {e}");
    }
    let mut out = Vec::with_capacity(sun_raster_len(raster.width, raster.height));
    match write_sun_raster(raster, &mut out) {
        Ok(()) => out,
        Err(e) => panic!("encode_raster: {e}"),
    }
}

/// Writes the raster file of [`encode_raster`] to `w`, a row at a time (so
/// a large raster is not copied whole first).
///
/// The raster must pass [`Raster::check`]; one that does not is refused.
pub fn write_sun_raster(raster: &Raster, w: &mut dyn Write) -> Result<(), RasterError> {
    raster.check()?;
    let row_bytes = (raster.width * 3).div_ceil(2) * 2;
    let data_bytes = sun_raster_len(raster.width, raster.height) - HEADER_LEN;
    let mut header = [0; HEADER_LEN];
    // The sizes are capped by `check`, so they fit in u32.
    BigEndian::write_u32_into(
        &[
            RAS_MAGIC,
            raster.width as u32,
            raster.height as u32,
            24,
            data_bytes as u32,
            RT_STANDARD,
            RMT_NONE,
            0,
        ],
        &mut header,
    );
    w.write_all(&header)?;
    // The padding byte of an odd width stays 0.
    let mut line = vec![0; row_bytes];
    for row in raster.pixels.chunks_exact(raster.width) {
        for (out, &[r, g, b]) in line.chunks_exact_mut(3).zip(row) {
            out.copy_from_slice(&[b, g, r]);
        }
        w.write_all(&line)?;
    }
    Ok(())
}

/// `outputframe`: writes the finished frame as a raster file.
///
/// Reconstructed: the main program calls `outputframe` once per frame (OCR
/// lines 3217–3223, after `expandframe` when the image is scaled up); its
/// body is not printed. The file goes through [`crate::output`]'s writer:
/// to a temporary file beside `path` renamed over it, so an interrupted
/// write never leaves a truncated file or clobbers the last good one (a
/// device or FIFO is written into).
pub fn outputframe(path: &Path, raster: &Raster) -> Result<(), RasterError> {
    raster.check()?;
    crate::output::write_atomically(path, |w| write_sun_raster(raster, w))
}

/// Writes the raster as an 8-bit RGB PNG through [`crate::output`]'s writer,
/// as [`outputframe`] does.
#[cfg(feature = "png")]
pub fn write_png(path: &Path, raster: &Raster) -> Result<(), RasterError> {
    raster.check()?;
    crate::output::write_atomically(path, |w| write_png_to(raster, w))
}

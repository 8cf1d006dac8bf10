//! The picture files `psout` shows: a Sun raster ([`crate::raster`]), a PNG
//! or a netpbm PPM, the three kinds `raytrace -o` writes
//! ([`crate::output`]). The port's addition: the thesis's psout showed only
//! the Sun rasters of its renderer.
//!
//! The kind is told by the file's first bytes, not by its name, so a PPM
//! named `.pnm` or a raster written to `frame.out` reads all the same. A
//! file that is neither PNG nor netpbm goes to the Sun raster reader, whose
//! errors (truncated header, bad magic number …) it keeps. Every size is
//! checked from the header before the pixels are allocated: the limits of
//! any raster ([`MAX_SIDE`] a side, [`MAX_PIXELS`] in all).

use std::io::{BufRead, BufReader, Read};
use std::ops::RangeInclusive;
use std::path::Path;

use crate::raster::{
    open_sized, read_bounded, read_raster, read_raster_bytes, PixelLimit, Raster, RasterError, MAX_PIXELS, MAX_SIDE,
};

/// The kinds of picture file [`read_image_file`] reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    SunRaster,
    Png,
    /// A netpbm file: `P1` … `P7`; only `P6` and `P3` (PPM) are read.
    Netpbm(u8),
}

/// The PNG signature.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// The kind of a file from its first bytes (at least 8 for a PNG, 3 for a
/// netpbm file); anything else is taken for a Sun raster.
pub(crate) fn kind_of(head: &[u8]) -> Kind {
    match head {
        _ if head.starts_with(PNG_SIGNATURE) => Kind::Png,
        [b'P', n @ b'1'..=b'7', next, ..] if next.is_ascii_whitespace() => Kind::Netpbm(*n),
        _ => Kind::SunRaster,
    }
}

/// Reads a Sun raster, PNG or PPM file (P6, or P3 as text) into a 24-bit
/// raster, up to [`MAX_PIXELS`] pixels ([`read_image`]). The file is
/// opened once and read front to back, so a pipe (`/dev/stdin`, a shell's
/// `<(…)`) reads as a file does. The errors do not name the file; the
/// caller does.
pub fn read_image_file(path: &Path) -> Result<Raster, RasterError> {
    let (file, length) = open_sized(path)?;
    read_image(file, length)
}

/// Reads a Sun raster, PNG or PPM picture from `reader`, read once from
/// its start and no further than the header says the picture needs. A
/// PNG's alpha is dropped, 16-bit samples and a PPM's maxval are scaled to
/// 0..255. `length` is the reader's bytes, when known (a regular file's
/// length), so that a Sun raster's or a PPM's bytes are held once. Memory:
/// the raster's 3 bytes a pixel, and besides them the Sun raster's or the
/// PPM's bytes, or a PNG's rows in flight and its inflater's window.
pub fn read_image(reader: impl Read, length: Option<u64>) -> Result<Raster, RasterError> {
    let mut reader = reader;
    let mut head = Vec::with_capacity(PNG_SIGNATURE.len());
    (&mut reader).take(PNG_SIGNATURE.len() as u64).read_to_end(&mut head)?;
    let kind = kind_of(&head);
    // The bytes read to tell the kind, then the rest.
    let mut whole = std::io::Cursor::new(head).chain(reader);
    match kind {
        Kind::SunRaster => {
            let bytes = read_raster_bytes(&mut whole, PixelLimit::RASTER, length)?;
            read_raster(&bytes).map_err(|e| match e {
                RasterError::BadMagic(m) => RasterError::UnknownKind(m),
                e => e,
            })
        }
        Kind::Png => read_png(BufReader::new(whole)),
        Kind::Netpbm(b'6') => read_ppm(&mut BufReader::new(whole), false, length),
        Kind::Netpbm(b'3') => read_ppm(&mut BufReader::new(whole), true, length),
        Kind::Netpbm(n) => Err(RasterError::Ppm(format!(
            "a netpbm P{} file ({}); the PPM kinds P6 and P3 are read",
            char::from(n),
            match n {
                b'1' | b'4' => "PBM, black and white",
                b'2' | b'5' => "PGM, grey",
                _ => "PAM",
            }
        ))),
    }
}

/// Checks a picture's size from its header: [`MAX_SIDE`] a side, at most
/// [`MAX_PIXELS`] pixels.
fn check_size(width: u32, height: u32) -> Result<(usize, usize), RasterError> {
    let side = 1..=MAX_SIDE;
    let (w, h) = (width as usize, height as usize);
    if !side.contains(&w) || !side.contains(&h) {
        return Err(RasterError::BadSize { width, height });
    }
    if w * h > MAX_PIXELS {
        return Err(RasterError::TooLarge {
            width,
            height,
            limit: MAX_PIXELS,
            what: "raster",
        });
    }
    Ok((w, h))
}

/// A PNG, in a build without the `png` feature: refused as such.
#[cfg(not(feature = "png"))]
fn read_png(_reader: impl BufRead) -> Result<Raster, RasterError> {
    Err(RasterError::PngNotBuilt)
}

/// A reader that cannot seek, for the PNG decoder, which asks for `Seek`
/// and does not use it: so a PNG reads from a pipe.
#[cfg(feature = "png")]
struct Forward<R>(R);

#[cfg(feature = "png")]
impl<R: Read> Read for Forward<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        self.0.read(buf)
    }
}

#[cfg(feature = "png")]
impl<R: BufRead> BufRead for Forward<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        self.0.fill_buf()
    }
    fn consume(&mut self, amount: usize) {
        self.0.consume(amount);
    }
}

#[cfg(feature = "png")]
impl<R> std::io::Seek for Forward<R> {
    fn seek(&mut self, _: std::io::SeekFrom) -> std::io::Result<u64> {
        Err(std::io::ErrorKind::Unsupported.into())
    }
}

/// A PNG decoded a row at a time straight into 8-bit RGB pixels: 16-bit
/// samples cut to their high byte (`STRIP_16`), fewer than 8 bits, a
/// palette and transparency expanded (`EXPAND`), grey repeated into
/// R, G and B, alpha dropped. Besides the raster's 3 bytes a pixel it
/// holds a row or two of the file's widest pixels (8 bytes each) and the
/// inflater's window, so the documented bound (the file's bytes plus 3
/// bytes a pixel) holds for every PNG (`tests/png_memory.rs` measures it).
/// An interlaced (Adam7) PNG's passes are placed pixel by pixel.
#[cfg(feature = "png")]
fn read_png(reader: impl BufRead) -> Result<Raster, RasterError> {
    use png::{ColorType, Transformations};
    let mut decoder = png::Decoder::new(Forward(reader));
    decoder.set_transformations(Transformations::STRIP_16 | Transformations::EXPAND);
    let mut png = decoder.read_info()?;
    let (width, height) = check_size(png.info().width, png.info().height)?;
    let channels = match png.output_color_type().0 {
        ColorType::Grayscale => 1,
        ColorType::GrayscaleAlpha => 2,
        ColorType::Rgb => 3,
        ColorType::Rgba => 4,
        // EXPAND turns a palette into RGB.
        ColorType::Indexed => return Err(RasterError::Inconsistent("a PNG palette not expanded".into())),
    };
    let mut pixels = vec![[0u8; 3]; width * height];
    let mut rgb = Vec::with_capacity(width * 3);
    let mut next = 0;
    while let Some(row) = png.next_interlaced_row()? {
        rgb.clear();
        rgb.extend(row.data().chunks_exact(channels).flat_map(|p| match *p {
            [v] | [v, _] => [v; 3],
            [r, g, b, ..] => [r, g, b],
            [] => [0; 3],
        }));
        let flat = pixels.as_flattened_mut();
        match row.interlace() {
            png::InterlaceInfo::Null(_) => {
                if let Some(line) = flat.get_mut(next * width * 3..(next + 1) * width * 3) {
                    line.iter_mut().zip(&rgb).for_each(|(to, &from)| *to = from);
                }
                next += 1;
            }
            png::InterlaceInfo::Adam7(pass) => png::expand_interlaced_row(flat, width * 3, &rgb, pass, 24),
        }
    }
    Ok(Raster { width, height, pixels })
}

/// The next header field of a netpbm file: a run of bytes other than white
/// space, after white space and `#` comments (to the end of the line);
/// `None` at the end of the file.
fn pnm_token(r: &mut impl BufRead) -> Result<Option<String>, RasterError> {
    let mut token = Vec::new();
    let mut comment = false;
    while let Some(&b) = r.fill_buf()?.first() {
        match b {
            b'\n' | b'\r' if comment => comment = false,
            _ if comment => {}
            b'#' if token.is_empty() => comment = true,
            _ if b.is_ascii_whitespace() && token.is_empty() => {}
            _ if b.is_ascii_whitespace() || b == b'#' => break,
            // No field is this long: a file that is not netpbm after all.
            _ if token.len() == 20 => return Err(RasterError::Ppm("a header field longer than 20 bytes".into())),
            _ => token.push(b),
        }
        r.consume(1);
    }
    Ok((!token.is_empty()).then(|| String::from_utf8_lossy(&token).into_owned()))
}

/// The next field as a number in `range`; `what` names it.
fn pnm_number(r: &mut impl BufRead, what: &str, range: RangeInclusive<u64>) -> Result<u64, RasterError> {
    number_in(pnm_token(r)?, || what.to_string(), range)
}

/// A field read, as a number in `range`; `what` names it in an error.
fn number_in(token: Option<String>, what: impl Fn() -> String, range: RangeInclusive<u64>) -> Result<u64, RasterError> {
    let token = token.ok_or_else(|| RasterError::Ppm(format!("the file ends before the {}", what())))?;
    match token.parse::<u64>() {
        Ok(v) if range.contains(&v) => Ok(v),
        Ok(v) => Err(RasterError::Ppm(format!(
            "the {} {v} is outside {}..={}",
            what(),
            range.start(),
            range.end()
        ))),
        Err(_) => Err(RasterError::Ppm(format!(
            "the {} '{}' is not a number",
            what(),
            token.escape_debug()
        ))),
    }
}

/// A PPM after its magic number: `P6` (`plain` false: binary samples, one
/// byte each below maxval 256, else two, most significant first) or `P3`
/// (`plain`: decimal samples). Bytes after the first image are ignored.
fn read_ppm(r: &mut impl BufRead, plain: bool, length: Option<u64>) -> Result<Raster, RasterError> {
    pnm_token(r)?;
    let side = 1..=MAX_SIDE as u64;
    let width = pnm_number(r, "width", side.clone())?;
    let height = pnm_number(r, "height", side)?;
    let (width, height) = check_size(width as u32, height as u32)?;
    let maxval = pnm_number(r, "maxval", 1..=65535)?;
    let scale = |v: u64| -> Result<u8, RasterError> {
        if v > maxval {
            return Err(RasterError::Ppm(format!(
                "a sample {v} is more than the maxval {maxval}"
            )));
        }
        Ok(((v * 255 + maxval / 2) / maxval) as u8)
    };
    let samples = width * height * 3;
    // Grown as the samples come: a short file claiming a large picture
    // costs what it holds. Each sample goes straight into its pixel.
    let mut pixels: Vec<[u8; 3]> = Vec::new();
    let push = |pixels: &mut Vec<[u8; 3]>, k: usize, v: u64| -> Result<(), RasterError> {
        let v = scale(v)?;
        match k % 3 {
            0 => pixels.push([v, 0, 0]),
            c => {
                if let Some(p) = pixels.last_mut() {
                    p[c] = v;
                }
            }
        }
        Ok(())
    };
    if plain {
        for k in 0..samples {
            let what = || format!("sample {}", k + 1);
            push(&mut pixels, k, number_in(pnm_token(r)?, what, 0..=u16::MAX.into())?)?;
        }
    } else {
        // The one white-space byte that ends the header (pnm_token stopped
        // before it).
        if !r.fill_buf()?.is_empty() {
            r.consume(1);
        }
        let wide = maxval > 255;
        let needed = samples * if wide { 2 } else { 1 };
        let mut data = Vec::new();
        read_bounded(r, &mut data, needed, length)?;
        if data.len() < needed {
            return Err(RasterError::Truncated {
                part: "PPM pixel data",
                needed,
                found: data.len(),
            });
        }
        // All there: the pixels are allocated once, at their size.
        pixels.reserve_exact(width * height);
        for (k, s) in data.chunks_exact(if wide { 2 } else { 1 }).enumerate() {
            push(&mut pixels, k, s.iter().fold(0, |v, &b| v << 8 | u64::from(b)))?;
        }
    }
    Ok(Raster { width, height, pixels })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::write_ppm_to;
    #[cfg(feature = "png")]
    use crate::raster::{write_image, Format};

    /// A raster of many colours, the same for a seed.
    fn test_raster(width: usize, height: usize, seed: u64) -> Raster {
        let mut s = seed | 1;
        let pixels = (0..width * height)
            .map(|_| {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                [s as u8, (s >> 8) as u8, (s >> 16) as u8]
            })
            .collect();
        Raster { width, height, pixels }
    }

    /// `raster` as a plain PPM (P3) at maxval 15, with comments, and the raster
    /// it reads as (each sample v scaled to (v·255 + 7) / 15).
    fn plain_ppm(raster: &Raster) -> (Vec<u8>, Raster) {
        let mut text = format!("P3 # plain\n{} {}\n# maxval next\n15\n", raster.width, raster.height);
        let mut pixels = Vec::new();
        for p in &raster.pixels {
            let v = p.map(|c| c / 17);
            text.push_str(&format!("{} {} {}\n", v[0], v[1], v[2]));
            pixels.push(v.map(|c| ((u32::from(c) * 255 + 7) / 15) as u8));
        }
        (
            text.into_bytes(),
            Raster {
                pixels,
                ..raster.clone()
            },
        )
    }

    #[test]
    fn ppm_files_read_as_their_pixels() {
        let dir = tempfile::tempdir().unwrap();
        let raster = test_raster(7, 5, 3);
        let read = |name: &str, bytes: &[u8]| {
            let path = dir.path().join(name);
            std::fs::write(&path, bytes).unwrap();
            read_image_file(&path).unwrap()
        };
        let mut p6 = Vec::new();
        write_ppm_to(&raster, &mut p6).unwrap();
        assert_eq!(read("a.ppm", &p6), raster);
        // Told by content, not name; bytes after the image are ignored.
        p6.extend_from_slice(b"P6 1 1 255\n\0\0\0");
        assert_eq!(read("a.out", &p6), raster);
        let (p3, expected) = plain_ppm(&raster);
        assert_eq!(read("plain.pnm", &p3), expected);
        // 16-bit samples, most significant byte first: v·257 at maxval 65535.
        let mut wide = format!("P6\n{} {}\n65535\n", raster.width, raster.height).into_bytes();
        wide.extend(
            raster
                .pixels
                .iter()
                .flatten()
                .flat_map(|&c| (u16::from(c) * 257).to_be_bytes()),
        );
        assert_eq!(read("wide.ppm", &wide), raster);
    }

    #[cfg(feature = "png")]
    #[test]
    fn png_files_read_as_their_pixels_alpha_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let raster = test_raster(6, 4, 5);
        let path = dir.path().join("a.png");
        write_image(&path, &raster, Format::Png).unwrap();
        assert_eq!(read_image_file(&path).unwrap(), raster);
        let rgba = image::RgbaImage::from_fn(6, 4, |x, y| {
            let [r, g, b] = raster.pixels[(y * 6 + x) as usize];
            image::Rgba([r, g, b, (x * 40) as u8])
        });
        rgba.save(dir.path().join("rgba.png")).unwrap();
        assert_eq!(read_image_file(&dir.path().join("rgba.png")).unwrap(), raster);
        let grey = image::GrayImage::from_fn(3, 2, |x, y| image::Luma([(x * 50 + y) as u8]));
        grey.save(dir.path().join("grey.png")).unwrap();
        let got = read_image_file(&dir.path().join("grey.png")).unwrap();
        assert_eq!(got.pixels, [0, 50, 100, 1, 51, 101].map(|v| [v; 3]));
    }

    /// An interlaced (Adam7) PNG, as netpbm's `pnmtopng -interlace` writes
    /// it, reads as its pixels: each pass's pixels put in their places.
    /// Without netpbm this is skipped, except under CI, which installs it.
    #[cfg(feature = "png")]
    #[test]
    fn an_interlaced_png_reads_as_its_pixels() {
        let dir = tempfile::tempdir().unwrap();
        let raster = test_raster(13, 11, 7);
        let ppm = dir.path().join("a.ppm");
        let mut bytes = Vec::new();
        write_ppm_to(&raster, &mut bytes).unwrap();
        std::fs::write(&ppm, bytes).unwrap();
        let out = std::process::Command::new("pnmtopng")
            .arg("-interlace")
            .arg(&ppm)
            .stderr(std::process::Stdio::null())
            .output();
        let Some(out) = out.ok().filter(|o| o.status.success()) else {
            assert!(std::env::var_os("CI").is_none(), "CI installs netpbm (pnmtopng)");
            eprintln!("skipped: no pnmtopng (netpbm)");
            return;
        };
        // Byte 28 of a PNG is IHDR's interlace method: 1 is Adam7.
        assert_eq!(out.stdout[28], 1);
        let png = dir.path().join("a.png");
        std::fs::write(&png, &out.stdout).unwrap();
        assert_eq!(read_image_file(&png).unwrap(), raster);
    }

    #[test]
    fn mutated_png_and_ppm_files_give_a_picture_or_an_error_never_a_panic() {
        let dir = tempfile::tempdir().unwrap();
        let raster = test_raster(9, 7, 4);
        let mut seeds = vec![Vec::new(), plain_ppm(&raster).0];
        write_ppm_to(&raster, &mut seeds[0]).unwrap();
        #[cfg(feature = "png")]
        {
            let mut png = Vec::new();
            crate::raster::write_png_to(&raster, &mut png).unwrap();
            seeds.push(png);
        }
        let path = dir.path().join("m");
        let mut s = 0x2545_f491_4f6c_dd1d_u64;
        let (mut ok, mut err) = (0, 0);
        for k in 0..3000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let mut bytes = seeds[k % seeds.len()].clone();
            for j in 0..1 + s % 4 {
                let at = (s >> (8 + 16 * j)) as usize % bytes.len();
                bytes[at] = (s >> (4 * j)) as u8;
            }
            bytes.truncate(bytes.len() - (s >> 40) as usize % 3 * (s as usize % 7));
            std::fs::write(&path, &bytes).unwrap();
            match read_image_file(&path) {
                Ok(r) => {
                    assert_eq!(r.pixels.len(), r.width * r.height);
                    ok += 1;
                }
                Err(_) => err += 1,
            }
        }
        // Both outcomes occur, so the mutations reach past the headers.
        assert!(ok > 100 && err > 100, "ok {ok}, err {err}");
    }
}

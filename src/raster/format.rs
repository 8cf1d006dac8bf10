//! The formats a raster is written in, by the output file's extension:
//! `.ras` Sun raster, `.png` PNG, `.ppm` or `.pnm` netpbm (binary P6), and
//! `.exr` OpenEXR, which holds the render's linear radiance, not the
//! raster (32-bit floats, before `rgbtochars` clamps and rounds them: for
//! compositing). Anything else is an error that names the extensions. The
//! port's extension beside `outputframe`, which writes the Sun raster only.

use std::io::Write;
use std::path::Path;

use super::{write_sun_raster, Raster, RasterError};
use crate::output::write_atomically;
use crate::types::Intensity;

/// The extensions an image output may have, as the errors list them.
pub const EXTENSIONS: &str =
    ".ras (Sun raster), .png (PNG), .ppm or .pnm (netpbm), .exr (OpenEXR, a render's radiance)";

/// A name that gives no format.
#[derive(Debug, thiserror::Error)]
pub enum FormatError {
    #[error("the file name is empty")]
    Empty,
    #[error("{}: the format follows the extension, one of {EXTENSIONS}",
        .0.as_ref().map_or("no extension".to_string(), |e| format!("unknown extension '.{e}'")))]
    UnknownFormat(Option<String>),
    #[error("this build has no PNG export (the `png` feature is off)")]
    NoPng,
    #[error("it is a folder: name a file in it (e.g. FOLDER/NAME.ras)")]
    IsAFolder,
    #[error("this build has no OpenEXR export (the `exr` feature is off)")]
    NoExr,
    #[error(
        "an OpenEXR file holds a render's radiance, and this is a raster of bytes: write .ras, .png, .ppm or .pnm"
    )]
    NoRadiance,
}

/// The format of an image output file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// A Sun rasterfile, 24-bit RT_STANDARD ([`crate::raster`]).
    SunRaster,
    /// An 8-bit RGB PNG.
    Png,
    /// A binary netpbm pixmap (P6, maxval 255).
    Netpbm,
    /// OpenEXR: a render's radiance, R, G and B as 32-bit floats.
    Exr,
}

impl Format {
    /// The format `path`'s extension names (in any case); [`STDOUT`](crate::output::STDOUT) has
    /// none, so its format is the caller's choice.
    pub fn of(path: &Path) -> Result<Format, FormatError> {
        if path.as_os_str().is_empty() {
            return Err(FormatError::Empty);
        }
        let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
        match extension.as_deref() {
            Some("ras") => Ok(Format::SunRaster),
            Some("png") if cfg!(feature = "png") => Ok(Format::Png),
            Some("png") => Err(FormatError::NoPng),
            Some("ppm" | "pnm") => Ok(Format::Netpbm),
            Some("exr") if cfg!(feature = "exr") => Ok(Format::Exr),
            Some("exr") => Err(FormatError::NoExr),
            _ => Err(FormatError::UnknownFormat(extension)),
        }
    }

    /// The format of an output file: [`STDOUT`](crate::output::STDOUT),
    /// and a name without an extension that is a device or a FIFO
    /// ([`crate::output::is_stream`]: `/dev/null`, `/dev/stdout`), get the
    /// Sun raster, the original's format; an existing folder is no file
    /// (`-o DIR/`); any other name its extension's ([`Format::of`]).
    pub fn of_output(path: &Path) -> Result<Format, FormatError> {
        let stream = path.extension().is_none() && crate::output::is_stream(path);
        if path.as_os_str() == crate::output::STDOUT || stream {
            return Ok(Format::SunRaster);
        }
        if path.is_dir() {
            return Err(FormatError::IsAFolder);
        }
        Format::of(path)
    }

    /// Writes `raster` to `w` in this format; OpenEXR, which wants the
    /// radiance ([`Format::write_render`]), is an error.
    pub fn write(self, raster: &Raster, w: &mut dyn Write) -> Result<(), RasterError> {
        match self {
            Format::SunRaster => write_sun_raster(raster, w),
            Format::Png => write_png_to(raster, w),
            Format::Netpbm => write_ppm_to(raster, w),
            Format::Exr => Err(FormatError::NoRadiance.into()),
        }
    }

    /// Writes a render to `w` in this format: OpenEXR its `colours` (the
    /// raster's size, row by row), the others its `raster`.
    pub fn write_render(self, raster: &Raster, colours: &[Intensity], w: &mut dyn Write) -> Result<(), RasterError> {
        match self {
            Format::Exr => write_exr_to(raster.width, raster.height, colours, w),
            _ => self.write(raster, w),
        }
    }
}

/// Writes `colours`, `width`×`height` of them row by row from the top, as
/// an OpenEXR image of one layer, channels R, G and B as 32-bit floats
/// (OpenEXR's "linear" radiance: the renderer's colours as they are, above
/// 1 and below 0 kept). The encoder seeks, so the file is made in memory
/// first (12 bytes a pixel) and then written.
#[cfg(feature = "exr")]
pub fn write_exr_to(width: usize, height: usize, colours: &[Intensity], w: &mut dyn Write) -> Result<(), RasterError> {
    use exr::prelude::{Image, SpecificChannels, Vec2, WritableImage};
    if colours.len() != width * height {
        return Err(RasterError::Inconsistent(format!(
            "{} colours for a {width}×{height} image",
            colours.len()
        )));
    }
    let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
        let c = colours[y * width + x];
        (c.x as f32, c.y as f32, c.z as f32)
    });
    let mut bytes = std::io::Cursor::new(Vec::new());
    Image::from_channels((width, height), channels)
        .write()
        .to_buffered(&mut bytes)
        .map_err(|e| RasterError::Inconsistent(format!("OpenEXR: {e}")))?;
    w.write_all(bytes.get_ref())?;
    Ok(())
}

#[cfg(not(feature = "exr"))]
pub fn write_exr_to(
    _width: usize,
    _height: usize,
    _colours: &[Intensity],
    _w: &mut dyn Write,
) -> Result<(), RasterError> {
    Err(FormatError::NoExr.into())
}

/// Writes `raster` as an 8-bit RGB PNG to `w`.
#[cfg(feature = "png")]
pub fn write_png_to(raster: &Raster, w: &mut dyn Write) -> Result<(), RasterError> {
    use image::ImageEncoder;
    raster.check()?;
    image::codecs::png::PngEncoder::new(w).write_image(
        raster.pixels.as_flattened(),
        raster.width as u32,
        raster.height as u32,
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(())
}

#[cfg(not(feature = "png"))]
pub fn write_png_to(_raster: &Raster, _w: &mut dyn Write) -> Result<(), RasterError> {
    Err(FormatError::NoPng.into())
}

/// Writes `raster` as a binary netpbm pixmap (P6, maxval 255) to `w`.
pub fn write_ppm_to(raster: &Raster, w: &mut dyn Write) -> Result<(), RasterError> {
    raster.check()?;
    write!(w, "P6\n{} {}\n255\n", raster.width, raster.height)?;
    for row in raster.pixels.chunks_exact(raster.width) {
        w.write_all(row.as_flattened())?;
    }
    Ok(())
}

/// Writes `raster` to `path` in `format` ([`write_atomically`]).
pub fn write_image(path: &Path, raster: &Raster, format: Format) -> Result<(), RasterError> {
    write_atomically(path, |w| format.write(raster, w))
}

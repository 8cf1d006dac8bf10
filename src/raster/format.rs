//! The formats a raster is written in, by the output file's extension:
//! `.ras` Sun raster, `.png` PNG, `.ppm` or `.pnm` netpbm (binary P6).
//! Anything else is an error that names the extensions. The port's
//! extension beside `outputframe`, which writes the Sun raster only.

use std::io::Write;
use std::path::Path;

use super::{write_sun_raster, Raster, RasterError};
use crate::output::write_atomically;

/// The extensions an image output may have, as the errors list them.
pub const EXTENSIONS: &str = ".ras (Sun raster), .png (PNG), .ppm or .pnm (netpbm)";

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
            _ => Err(FormatError::UnknownFormat(extension)),
        }
    }

    /// The format of an output file: [`STDOUT`](crate::output::STDOUT),
    /// and a name without an extension that is a device or a FIFO
    /// ([`crate::output::is_stream`]: `/dev/null`, `/dev/stdout`), get the
    /// Sun raster, the original's format; any other name its extension's
    /// ([`Format::of`]).
    pub fn of_output(path: &Path) -> Result<Format, FormatError> {
        let stream = path.extension().is_none() && crate::output::is_stream(path);
        if path.as_os_str() == crate::output::STDOUT || stream {
            return Ok(Format::SunRaster);
        }
        Format::of(path)
    }

    /// Writes `raster` to `w` in this format.
    pub fn write(self, raster: &Raster, w: &mut dyn Write) -> Result<(), RasterError> {
        match self {
            Format::SunRaster => write_sun_raster(raster, w),
            Format::Png => write_png_to(raster, w),
            Format::Netpbm => write_ppm_to(raster, w),
        }
    }
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

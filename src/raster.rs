//! The raster file: a Sun rasterfile (being written; the interface below is
//! the one the rest of the port uses).

use std::path::Path;

/// A 24-bit image, row 0 at the top, `pixels` row-major as [r, g, b].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Raster {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<[u8; 3]>,
}

/// What can go wrong reading or writing a raster file.
#[derive(Debug, thiserror::Error)]
pub enum RasterError {
    #[error("{0}")]
    Format(String),
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

/// Reads a raster file.
pub fn read_raster_file(path: &Path) -> Result<Raster, RasterError> {
    Err(RasterError::Format(format!("{}: raster reading is not built yet", path.display())))
}

/// Stand-in until the raster branch lands.
pub fn rgbtochars(acolor: crate::types::Intensity) -> [u8; 3] {
    let c = |v: f64| if v.is_nan() { 0 } else { (v.clamp(0.0, 1.0) * 255.0).round() as u8 };
    [c(acolor.x), c(acolor.y), c(acolor.z)]
}

/// Stand-in until the raster branch lands.
pub fn outputframe(path: &Path, _raster: &Raster) -> Result<(), RasterError> {
    Err(RasterError::Format(format!("{}: raster writing is not built yet", path.display())))
}

/// Stand-in until the raster branch lands.
#[cfg(feature = "png")]
pub fn write_png(path: &Path, _raster: &Raster) -> Result<(), RasterError> {
    Err(RasterError::Format(format!("{}: PNG writing is not built yet", path.display())))
}

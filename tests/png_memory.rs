//! What reading a picture costs, measured: the peak of the heap while
//! `read_image_file` decodes it, counted by a global allocator that keeps
//! the most bytes live at once (`peakmem-alloc`; this test binary only).
//! The bound docs/usage.md states: 3 bytes a pixel (the raster) plus the
//! file's bytes for a Sun raster or a PPM; a PNG is decoded a row at a
//! time, so its file is not held, and its rows in flight, the inflater's
//! window and the reader's buffer stay under [`PNG_BUFFERS`].
//!
//! The worst PNG for the old decoder (the whole image decoded at its own
//! depth, then converted): 8192×8192 16-bit RGBA, 8 bytes a pixel, half a
//! megabyte of file. One test at a time: the counter is the process's.

#![cfg(feature = "png")]

use std::io::Write;
use std::path::Path;
use std::sync::Mutex;

use peakmem_alloc::{PeakMemAlloc, PeakMemAllocTrait, INSTRUMENTED_SYSTEM};
use raytrace::image_file::read_image_file;
use raytrace::raster::MAX_PIXELS;

#[global_allocator]
static HEAP: &PeakMemAlloc<std::alloc::System> = &INSTRUMENTED_SYSTEM;

/// One measurement at a time.
static ONE: Mutex<()> = Mutex::new(());

/// The most a PNG's decoding holds besides its raster: 1 MiB.
const PNG_BUFFERS: usize = 1 << 20;

/// The peak of the heap above what was live when `read` started, and what
/// it returned.
fn peak_of<T>(read: impl FnOnce() -> T) -> (usize, T) {
    let _one = ONE.lock().unwrap_or_else(|e| e.into_inner());
    HEAP.reset_peak_memory();
    let out = read();
    (HEAP.get_peak_memory(), out)
}

/// Writes a `side`×`side` PNG of `color` and `depth` to `path`, a row at a
/// time; `row(y)` gives row y's bytes.
fn write_png(path: &Path, side: u32, color: png::ColorType, depth: png::BitDepth, row: impl Fn(u32) -> Vec<u8>) {
    let file = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    let mut encoder = png::Encoder::new(file, side, side);
    encoder.set_color(color);
    encoder.set_depth(depth);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().unwrap();
    let mut stream = writer.stream_writer().unwrap();
    for y in 0..side {
        stream.write_all(&row(y)).unwrap();
    }
    stream.finish().unwrap();
}

#[test]
fn the_largest_pngs_decode_within_3_bytes_a_pixel_and_their_rows() {
    let dir = tempfile::tempdir().unwrap();
    let side = 8192u32;
    let pixels = side as usize * side as usize;
    assert_eq!(pixels, MAX_PIXELS);
    // 16-bit RGBA: each row zeros but for its first pixel, whose red is
    // the row's number (high byte first) and whose alpha is opaque.
    let wide = dir.path().join("rgba16.png");
    write_png(&wide, side, png::ColorType::Rgba, png::BitDepth::Sixteen, |y| {
        let mut row = vec![0u8; side as usize * 8];
        row[..2].copy_from_slice(&((y % 256) as u16 * 257).to_be_bytes());
        row[6..8].copy_from_slice(&[255, 255]);
        row
    });
    // 1-bit grey: a pixel set every 8 rows at the start.
    let bits = dir.path().join("grey1.png");
    write_png(&bits, side, png::ColorType::Grayscale, png::BitDepth::One, |y| {
        let mut row = vec![0u8; side as usize / 8];
        row[0] = if y.is_multiple_of(8) { 0x80 } else { 0 };
        row
    });
    for (path, first) in [
        (
            &wide,
            &(|y: usize| [(y % 256) as u8, 0, 0]) as &dyn Fn(usize) -> [u8; 3],
        ),
        (&bits, &|y: usize| [if y.is_multiple_of(8) { 255 } else { 0 }; 3]),
    ] {
        let file = std::fs::metadata(path).unwrap().len() as usize;
        let (peak, raster) = peak_of(|| read_image_file(path).unwrap());
        eprintln!(
            "{}: file {file} bytes; peak {peak} bytes = 3 a pixel + {}",
            path.display(),
            peak as i64 - 3 * pixels as i64
        );
        assert!(peak <= 3 * pixels + PNG_BUFFERS, "{}: peak {peak}", path.display());
        assert_eq!((raster.width, raster.height), (8192, 8192));
        for y in [0, 1, 8, 255, 256, 8191] {
            assert_eq!(raster.pixels[y * 8192], first(y), "{} row {y}", path.display());
            assert_eq!(raster.pixels[y * 8192 + 1], [0; 3]);
        }
    }
}

/// A Sun raster and a binary PPM hold their file's bytes while the pixels
/// are made: the file's bytes plus 3 bytes a pixel, and a little.
#[test]
fn a_sun_raster_and_a_ppm_decode_within_their_bytes_and_3_bytes_a_pixel() {
    let dir = tempfile::tempdir().unwrap();
    // Not a power of two: a buffer grown by doubling would overshoot it.
    let (width, height) = (2000, 1500);
    let raster = raytrace::raster::Raster {
        width,
        height,
        pixels: (0..width * height)
            .map(|i| [i as u8, (i >> 8) as u8, (i >> 16) as u8])
            .collect(),
    };
    let ras = dir.path().join("a.ras");
    let ppm = dir.path().join("a.ppm");
    raytrace::raster::outputframe(&ras, &raster).unwrap();
    raytrace::raster::write_image(&ppm, &raster, raytrace::raster::Format::Netpbm).unwrap();
    for path in [&ras, &ppm] {
        let file = std::fs::metadata(path).unwrap().len() as usize;
        let (peak, read) = peak_of(|| read_image_file(path).unwrap());
        eprintln!("{}: file {file} bytes; peak {peak} bytes", path.display());
        assert!(
            peak <= file + 3 * width * height + (64 << 10),
            "{}: peak {peak}",
            path.display()
        );
        assert_eq!(read, raster);
    }
}

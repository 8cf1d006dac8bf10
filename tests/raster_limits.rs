//! The raster reader's bounds: a pixel limit for every raster and a smaller
//! one for deck textures, both checked on the header before anything is
//! allocated, and textures kept as bytes.

use raytrace::deck::MAX_TEXELS;
use raytrace::options::Fidelity;
use raytrace::raster::{
    read_raster, read_raster_file_within, read_raster_within, PixelLimit, Raster, RasterError, MAX_PIXELS,
};
use raytrace::types::Texture;

mod common;
use common::sun_raster_file;

/// An 8-bit grey RT_BYTE_ENCODED file of `width × height`, all `value`,
/// in runs of 256 (`80 ff v`): about 3 bytes for 256 pixels.
fn flat_encoded(width: u32, height: u32, value: u8) -> Vec<u8> {
    let row = (width as usize).div_ceil(2) * 2;
    let total = row * height as usize;
    let mut data = [0x80, 0xff, value].repeat(total / 256);
    data.extend(std::iter::repeat_n(value, total % 256));
    sun_raster_file(width, height, 8, data.len() as u32, 2, 0, &[], &data)
}

#[test]
fn a_raster_over_the_limit_is_refused_from_its_header() {
    let five = flat_encoded(5, 5, 9);
    let limit = |pixels| PixelLimit { pixels, what: "test" };
    assert_eq!(read_raster_within(&five, limit(25)).unwrap().pixels, vec![[9; 3]; 25]);
    let e = read_raster_within(&five, limit(24)).unwrap_err();
    assert!(
        matches!(
            e,
            RasterError::TooLarge {
                width: 5,
                height: 5,
                limit: 24,
                what: "test"
            }
        ),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        "raster size 5×5 is 25 pixels, more than the 24 a test may have"
    );
    // The largest image a deck can ask for is a raster; one row more is not,
    // whatever the data: the header alone decides, before any allocation.
    assert_eq!(MAX_PIXELS, 8192 * 8192);
    for (w, h) in [(8193, 8192), (16384, 4097), (16384, 16384)] {
        let header_only = sun_raster_file(w, h, 32, 0, 2, 0, &[], &[0x80, 0xff, 0]);
        assert!(
            matches!(read_raster(&header_only), Err(RasterError::TooLarge { .. })),
            "{w}×{h}"
        );
    }
}

/// A byte-encoded image at the limit decodes straight into its pixels: a
/// 16384×4096 grey image from 787 KB of runs.
#[test]
fn a_byte_encoded_raster_at_the_limit_reads() {
    let bytes = flat_encoded(16384, 4096, 200);
    assert!(bytes.len() < 800_000, "{}", bytes.len());
    let r = read_raster(&bytes).unwrap();
    assert_eq!((r.width, r.height, r.pixels.len()), (16384, 4096, MAX_PIXELS));
    assert!(r.pixels.iter().all(|&p| p == [200; 3]));
}

#[test]
fn the_writer_refuses_what_the_reader_would() {
    // Checked on the sizes before the pixels, so no pixels are needed.
    let too_many = Raster {
        width: 8193,
        height: 8192,
        pixels: vec![],
    };
    let e = too_many.check().unwrap_err();
    assert!(e.to_string().contains("more than 67108864 pixels"), "{e}");
}

const DECK: &str = "\
view  eye 0 -10 3  look 0 0 0  screen 4  distance 5
image 8 8  mask 1
surface pic opaque color 1 1 1 ka 0.2 kd 0.8 ks 0 kt 0
texture pic big.ras
sphere ball pic at 0 0 0 radius 1
";

/// A deck texture may have [`MAX_TEXELS`] texels, a sixteenth of a
/// raster's; one more is refused with the deck's line and column, naming
/// the limit.
#[test]
fn a_texture_over_its_limit_is_a_deck_error() {
    assert_eq!(MAX_TEXELS, 4096 * 4096);
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("big.ras"), flat_encoded(4097, 4096, 7)).unwrap();
    let e = raytrace::deck::initialize(DECK, "t.deck", dir.path(), Fidelity::Thesis).unwrap_err();
    let message = e.to_string();
    assert!(message.starts_with("t.deck:4:13:"), "{message}");
    assert!(
        message.contains("4097×4096 is 16781312 pixels, more than the 16777216 a deck texture may have"),
        "{message}"
    );
    // The same file is a raster all the same.
    assert!(read_raster_file_within(&dir.path().join("big.ras"), PixelLimit::RASTER).is_ok());

    std::fs::write(dir.path().join("big.ras"), flat_encoded(4096, 4096, 7)).unwrap();
    let scene = raytrace::deck::initialize(DECK, "t.deck", dir.path(), Fidelity::Thesis).unwrap();
    let texture = scene.surfaces[0].texture.as_ref().unwrap();
    assert_eq!(texture.texels.len(), MAX_TEXELS);
}

/// Texels are the raster's bytes; a lookup gives byte / 255.
#[test]
fn texels_are_bytes_and_lookups_are_colours() {
    let texture = Texture {
        width: 2,
        height: 2,
        texels: vec![[255, 0, 51], [1, 2, 3], [10, 20, 30], [0, 0, 0]],
    };
    assert_eq!(std::mem::size_of_val(&texture.texels[0]), 3);
    // Row 0 is the top: t near 1 is row 0, t near 0 row 1.
    let top_left = texture.texel(0.1, 0.9);
    assert_eq!(top_left.to_array(), [1.0, 0.0, 51.0 / 255.0]);
    let bottom_left = texture.texel(0.1, 0.1);
    assert_eq!(bottom_left.to_array(), [10.0 / 255.0, 20.0 / 255.0, 30.0 / 255.0]);
}

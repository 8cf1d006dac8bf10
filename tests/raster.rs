//! The raster file: round trips, hand-made Sun rasterfiles of every
//! supported kind, every malformed case, truncation and mutation fuzzing,
//! and cross-checks against Pillow and netpbm.

use std::ffi::OsString;
use std::io::Write;
use std::process::{Command, Stdio};

use raytrace::raster::{
    encode_raster, outputframe, read_raster, read_raster_file, rgbtochars, Raster, RasterError, MAX_SIDE,
};
use raytrace::types::Intensity;

mod common;
use common::sun_raster_file as file;

/// A deterministic pseudo-random sequence (xorshift64*), so every run
/// tests the same bytes.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

fn test_raster(width: usize, height: usize, seed: u64) -> Raster {
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    let pixels = (0..width * height)
        .map(|_| {
            let v = rng.next();
            [v as u8, (v >> 8) as u8, (v >> 16) as u8]
        })
        .collect();
    Raster { width, height, pixels }
}

fn grey(v: u8) -> [u8; 3] {
    [v, v, v]
}

#[test]
fn write_then_read_round_trips_at_odd_and_even_widths() {
    for (i, &(w, h)) in [(1, 1), (3, 2), (4, 3), (255, 1), (2, 5), (256, 2), (17, 17), (1, 9)]
        .iter()
        .enumerate()
    {
        let raster = test_raster(w, h, i as u64);
        let bytes = encode_raster(&raster);
        let row_bytes = (3 * w).div_ceil(2) * 2;
        assert_eq!(bytes.len(), 32 + row_bytes * h, "{w}×{h}");
        let field = |k: usize| u32::from_be_bytes(bytes[4 * k..4 * k + 4].try_into().unwrap());
        assert_eq!(
            (0..8).map(field).collect::<Vec<_>>(),
            [0x59a6_6a95, w as u32, h as u32, 24, (row_bytes * h) as u32, 1, 0, 0],
            "{w}×{h} header"
        );
        // The first pixel is stored B G R.
        let [r, g, b] = raster.pixels[0];
        assert_eq!(&bytes[32..35], &[b, g, r]);
        // Padding bytes of odd widths are zero.
        if w % 2 == 1 {
            for y in 0..h {
                assert_eq!(bytes[32 + y * row_bytes + row_bytes - 1], 0);
            }
        }
        assert_eq!(read_raster(&bytes).unwrap(), raster, "{w}×{h}");
    }
}

#[test]
fn outputframe_writes_a_file_that_reads_back_and_leaves_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("frame.ras");
    let first = test_raster(5, 3, 1);
    let second = test_raster(4, 4, 2);
    outputframe(&path, &first).unwrap();
    assert_eq!(read_raster_file(&path).unwrap(), first);
    outputframe(&path, &second).unwrap();
    assert_eq!(read_raster_file(&path).unwrap(), second);
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, ["frame.ras"]);
}

#[test]
fn outputframe_refuses_an_inconsistent_raster_and_keeps_the_last_good_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("frame.ras");
    let good = test_raster(3, 3, 3);
    outputframe(&path, &good).unwrap();
    let short = Raster {
        width: 3,
        height: 3,
        pixels: vec![[0; 3]; 8],
    };
    let empty = Raster {
        width: 0,
        height: 0,
        pixels: vec![],
    };
    let wide = Raster {
        width: MAX_SIDE + 1,
        height: 1,
        pixels: vec![[0; 3]; MAX_SIDE + 1],
    };
    for bad in [short, empty, wide] {
        assert!(matches!(outputframe(&path, &bad), Err(RasterError::Inconsistent(_))));
    }
    assert_eq!(read_raster_file(&path).unwrap(), good);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn outputframe_into_a_missing_folder_names_the_folder_and_makes_none() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no such folder").join("frame.ras");
    let e = outputframe(&path, &test_raster(2, 2, 0)).unwrap_err();
    assert!(
        matches!(&e, RasterError::Output(raytrace::output::OutputError::MissingFolder(_))),
        "{e:?}"
    );
    assert!(e.to_string().contains("no such folder does not exist"), "{e}");
    assert!(!dir.path().join("no such folder").exists());
}

#[cfg(feature = "png")]
#[test]
fn write_png_reads_back_with_the_image_crate() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("frame.png");
    let raster = test_raster(7, 5, 9);
    raytrace::raster::write_png(&path, &raster).unwrap();
    let img = image::open(&path).unwrap().to_rgb8();
    assert_eq!((img.width(), img.height()), (7, 5));
    let pixels: Vec<[u8; 3]> = img.pixels().map(|p| p.0).collect();
    assert_eq!(pixels, raster.pixels);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

#[test]
fn rgbtochars_clamps_rounds_and_maps_nan_to_zero() {
    let cases = [
        (0.0, 0),
        (1.0, 255),
        (0.5, 128), // 127.5 rounds half away from zero
        (1.0 / 255.0, 1),
        (0.998, 254),
        (-0.25, 0),
        (7.0, 255),
        (f64::INFINITY, 255),
        (f64::NEG_INFINITY, 0),
        (f64::NAN, 0),
    ];
    for (c, byte) in cases {
        assert_eq!(rgbtochars(Intensity::new(c, 0.0, 1.0)), [byte, 0, 255], "{c}");
        assert_eq!(rgbtochars(Intensity::new(1.0, c, 0.0)), [255, byte, 0], "{c}");
        assert_eq!(rgbtochars(Intensity::new(0.0, 1.0, c)), [0, 255, byte], "{c}");
    }
}

#[test]
fn eight_bit_without_a_map_is_grey_and_with_a_map_looks_up_its_planes() {
    // 3×2 grey: rows padded to 4 bytes.
    let bytes = file(3, 2, 8, 8, 1, 0, &[], &[10, 20, 30, 99, 40, 50, 60, 99]);
    let r = read_raster(&bytes).unwrap();
    assert_eq!(
        r.pixels,
        [10, 20, 30, 40, 50, 60].map(grey).to_vec(),
        "padding bytes are skipped"
    );
    // Three entries: planes red, green, blue.
    let map = [1, 2, 3, 11, 12, 13, 21, 22, 23];
    let bytes = file(2, 1, 8, 2, 1, 1, &map, &[2, 0]);
    let r = read_raster(&bytes).unwrap();
    assert_eq!(r.pixels, [[3, 13, 23], [1, 11, 21]]);
}

#[test]
fn twenty_four_and_thirty_two_bit_orders_follow_the_type() {
    // 1×1: B G R + pad for type 1, R G B + pad for type 3.
    let std24 = read_raster(&file(1, 1, 24, 4, 1, 0, &[], &[1, 2, 3, 0])).unwrap();
    assert_eq!(std24.pixels, [[3, 2, 1]]);
    let rgb24 = read_raster(&file(1, 1, 24, 4, 3, 0, &[], &[1, 2, 3, 0])).unwrap();
    assert_eq!(rgb24.pixels, [[1, 2, 3]]);
    // 32-bit: X B G R (type 1), X R G B (type 3); no padding needed.
    let data = [0xee, 1, 2, 3, 0xff, 4, 5, 6];
    let std32 = read_raster(&file(2, 1, 32, 8, 1, 0, &[], &data)).unwrap();
    assert_eq!(std32.pixels, [[3, 2, 1], [6, 5, 4]]);
    let rgb32 = read_raster(&file(2, 1, 32, 8, 3, 0, &[], &data)).unwrap();
    assert_eq!(rgb32.pixels, [[1, 2, 3], [4, 5, 6]]);
}

#[test]
fn a_zero_length_is_computed_for_old_and_standard_files_and_trailing_bytes_are_ignored() {
    let data = [1, 2, 3, 0, 4, 5, 6, 0];
    for ras_type in [0, 1] {
        let r = read_raster(&file(1, 2, 24, 0, ras_type, 0, &[], &data)).unwrap();
        assert_eq!(r.pixels, [[3, 2, 1], [6, 5, 4]], "type {ras_type}");
    }
    let mut bytes = file(1, 2, 24, 8, 1, 0, &[], &data);
    bytes.extend_from_slice(&[7; 100]);
    assert_eq!(read_raster(&bytes).unwrap().pixels, [[3, 2, 1], [6, 5, 4]]);
}

#[test]
fn byte_encoded_escape_pair_is_one_0x80() {
    let r = read_raster(&file(2, 1, 8, 3, 2, 0, &[], &[0x80, 0x00, 0x05])).unwrap();
    assert_eq!(r.pixels, [grey(0x80), grey(5)]);
}

#[test]
fn byte_encoded_run_is_n_plus_one_copies() {
    let r = read_raster(&file(4, 1, 8, 3, 2, 0, &[], &[0x80, 0x03, 0x07])).unwrap();
    assert_eq!(r.pixels, [grey(7); 4]);
    // A run of the escape byte itself.
    let r = read_raster(&file(4, 1, 8, 3, 2, 0, &[], &[0x80, 0x03, 0x80])).unwrap();
    assert_eq!(r.pixels, [grey(0x80); 4]);
}

#[test]
fn byte_encoded_runs_cross_the_padded_row_end() {
    // 3×2 at 8 bits: rows of 4 bytes, decoded [1 2 2 p | 2 2 3 p].
    let encoded = [0x01, 0x80, 0x04, 0x02, 0x03, 0x00];
    let r = read_raster(&file(3, 2, 8, 6, 2, 0, &[], &encoded)).unwrap();
    assert_eq!(r.pixels, [1, 2, 2, 2, 2, 3].map(grey).to_vec());
}

#[test]
fn byte_encoded_twenty_four_bit_with_declared_and_zero_length() {
    // 1×2 at 24 bits: decoded [10 10 80 00 | 10 10 80 00].
    let encoded = [0x80, 0x01, 0x10, 0x80, 0x00, 0x00, 0x80, 0x01, 0x10, 0x80, 0x00, 0x00];
    for length in [encoded.len() as u32, 0] {
        let r = read_raster(&file(1, 2, 24, length, 2, 0, &[], &encoded)).unwrap();
        assert_eq!(r.pixels, [[0x80, 0x10, 0x10]; 2], "length {length}");
    }
}

#[test]
fn byte_encoded_thirty_two_bit() {
    // 2×1 XBGR: decoded [0 1 1 1 | 0 2 3 4].
    let encoded = [0x00, 0x80, 0x02, 0x01, 0x00, 0x02, 0x03, 0x04];
    let r = read_raster(&file(2, 1, 32, 8, 2, 0, &[], &encoded)).unwrap();
    assert_eq!(r.pixels, [[1, 1, 1], [4, 3, 2]]);
}

#[test]
fn byte_encoded_eight_bit_with_a_colour_map() {
    // Two entries (black, orange); 5×1, row of 6 bytes: [1 1 1 0 1 p].
    let map = [0, 255, 0, 128, 0, 0];
    let encoded = [0x80, 0x02, 0x01, 0x00, 0x01, 0x00];
    let r = read_raster(&file(5, 1, 8, 6, 2, 1, &map, &encoded)).unwrap();
    let orange = [255, 128, 0];
    assert_eq!(r.pixels, [orange, orange, orange, [0, 0, 0], orange]);
}

/// Checks `read_raster` fails with an error of which `expected` is true.
fn assert_error(bytes: &[u8], what: &str, expected: impl Fn(&RasterError) -> bool) {
    match read_raster(bytes) {
        Ok(r) => panic!("{what}: read a {}×{} raster", r.width, r.height),
        Err(e) => assert!(expected(&e), "{what}: unexpected error {e:?}"),
    }
}

#[test]
fn every_malformed_header_is_an_error() {
    use RasterError::*;
    let data = [0u8; 8];
    let mut bad_magic = file(1, 2, 24, 8, 1, 0, &[], &data);
    bad_magic[0] = 0x58;
    assert_error(&bad_magic, "bad magic", |e| matches!(e, BadMagic(0x58a6_6a95)));
    assert_error(b"P6\n1 1\n255\n\0\0\0", "a PPM", |e| matches!(e, BadMagic(_)));
    for n in [0, 1, 4, 31] {
        let bytes = &file(1, 2, 24, 8, 1, 0, &[], &data)[..n];
        assert_error(bytes, "short header", |e| matches!(e, Truncated { .. }));
    }
    let size = |e: &RasterError| matches!(e, BadSize { .. });
    assert_error(&file(0, 2, 24, 0, 1, 0, &[], &data), "zero width", size);
    assert_error(&file(1, 0, 24, 0, 1, 0, &[], &data), "zero height", size);
    assert_error(&file(16385, 1, 8, 0, 1, 0, &[], &data), "wide", size);
    assert_error(&file(1, 1 << 31, 8, 0, 1, 0, &[], &data), "tall", size);
    assert_error(&file(u32::MAX, u32::MAX, 32, 0, 2, 0, &[], &data), "huge", size);
    for t in [4, 5, 0xffff, u32::MAX] {
        assert_error(
            &file(1, 2, 24, 8, t, 0, &[], &data),
            "type",
            |e| matches!(e, UnsupportedType(x) if *x == t),
        );
    }
    for d in [0, 1, 4, 16, 64] {
        assert_error(
            &file(1, 2, d, 0, 1, 0, &[], &data),
            "depth",
            |e| matches!(e, UnsupportedDepth(x) if *x == d),
        );
    }
    assert_error(&file(1, 2, 8, 4, 1, 2, &[0; 3], &data), "RMT_RAW", |e| {
        matches!(e, UnsupportedMapType(2))
    });
    let map = |e: &RasterError| matches!(e, BadMap(_));
    assert_error(&file(1, 2, 8, 4, 1, 1, &[0; 4], &data), "map not ×3", map);
    assert_error(&file(1, 2, 8, 4, 1, 1, &[], &data), "empty map", map);
    assert_error(&file(1, 2, 8, 4, 1, 1, &[0; 771], &data), "map > 768", map);
    assert_error(&file(1, 2, 24, 8, 1, 1, &[0; 3], &data), "map at 24", map);
    assert_error(&file(1, 2, 8, 4, 1, 0, &[0; 3], &data), "map, type 0", map);
    let length = |e: &RasterError| matches!(e, LengthMismatch { .. });
    assert_error(&file(1, 2, 24, 7, 1, 0, &[], &data), "length 7", length);
    assert_error(&file(1, 2, 24, 9, 3, 0, &[], &data), "length 9", length);
    assert_error(&file(1, 2, 24, 17, 2, 0, &[], &data), "RLE > 2×", length);
}

#[test]
fn every_malformed_body_is_an_error() {
    use RasterError::*;
    let trunc = |e: &RasterError| matches!(e, Truncated { .. });
    // Map: declares 6 bytes, has 4.
    let mut short_map = file(2, 1, 8, 2, 1, 1, &[0; 6], &[0, 1]);
    short_map.truncate(32 + 4);
    assert_error(&short_map, "short map", trunc);
    assert_error(&file(1, 2, 24, 8, 1, 0, &[], &[0; 7]), "short data", trunc);
    assert_error(&file(1, 2, 24, 0, 0, 0, &[], &[0; 7]), "short old", trunc);
    assert_error(
        &file(2, 1, 8, 2, 1, 1, &[1, 2, 3, 4, 5, 6], &[1, 2]),
        "index 2 of 2",
        |e| {
            matches!(
                e,
                ColourIndex {
                    x: 1,
                    y: 0,
                    index: 2,
                    entries: 2
                }
            )
        },
    );
    let rle = |e: &RasterError| matches!(e, Rle(_));
    // 4×1 at 8 bits: 4 decoded bytes.
    let rle_file = |enc: &[u8], length: u32| file(4, 1, 8, length, 2, 0, &[], enc);
    assert_error(&rle_file(&[0x80, 0x04, 1], 3), "run past end", rle);
    assert_error(&rle_file(&[0x80, 0x04, 1], 0), "run past end, no length", rle);
    assert_error(&rle_file(&[1, 0x80, 0x03, 1], 4), "run past end by 1", rle);
    assert_error(&rle_file(&[1, 2, 3, 4, 5], 5), "literal past end", rle);
    assert_error(&rle_file(&[1, 2, 3, 0x80], 4), "cut escape", rle);
    assert_error(&rle_file(&[1, 2, 0x80, 1], 4), "cut run", rle);
    assert_error(&rle_file(&[1, 2, 0x80, 1], 0), "cut run, no length", rle);
    assert_error(&rle_file(&[1, 2, 3], 3), "short decode", trunc);
    assert_error(&rle_file(&[1, 2, 3, 4], 6), "length past file", trunc);
    assert_error(&rle_file(&[], 0), "empty encoding", |e| {
        matches!(e, Rle(_) | Truncated { .. })
    });
    // A 16384×16384 32-bit header on 40 bytes of runs: refused from its
    // header, past the pixel limit; within the limit, for what 40 bytes
    // of runs cannot hold.
    let huge = file(16384, 16384, 32, 0, 2, 0, &[], &[0x80, 0xff, 0x00].repeat(13));
    assert_error(&huge, "huge RLE", |e| matches!(e, TooLarge { .. }));
    let big = file(8192, 8192, 32, 0, 2, 0, &[], &[0x80, 0xff, 0x00].repeat(13));
    assert_error(&big, "big RLE on little data", rle);
    let huge = file(8192, 8192, 32, 0, 1, 0, &[], &[0; 100]);
    assert_error(&huge, "huge raw", trunc);
}

/// Valid files of every kind, for truncation and mutation.
fn valid_files() -> Vec<Vec<u8>> {
    let map = [0, 255, 0, 128, 0, 0];
    vec![
        encode_raster(&test_raster(5, 3, 7)),
        file(5, 1, 8, 6, 2, 1, &map, &[0x80, 0x02, 0x01, 0x00, 0x01, 0x00]),
        file(3, 2, 8, 6, 2, 0, &[], &[0x01, 0x80, 0x04, 0x02, 0x03, 0x00]),
        file(2, 1, 32, 8, 3, 0, &[], &[0xee, 1, 2, 3, 0xff, 4, 5, 6]),
        file(3, 2, 8, 8, 1, 1, &[1, 2, 3, 4, 5, 6], &[0, 1, 1, 0, 1, 0, 0, 0]),
        file(1, 2, 24, 0, 0, 0, &[], &[1, 2, 3, 0, 4, 5, 6, 0]),
    ]
}

#[test]
fn every_truncation_of_a_valid_file_is_an_error() {
    for (k, bytes) in valid_files().iter().enumerate() {
        read_raster(bytes).unwrap_or_else(|e| panic!("file {k} is not valid: {e}"));
        for n in 0..bytes.len() {
            assert!(
                read_raster(&bytes[..n]).is_err(),
                "file {k} cut to {n} of {} bytes was read",
                bytes.len()
            );
        }
    }
}

#[test]
fn thousands_of_mutated_files_give_a_raster_or_an_error_never_a_panic() {
    let mut rng = Rng(0x5eed_1989);
    let (mut ok, mut err) = (0, 0);
    for bytes in valid_files() {
        for _ in 0..1000 {
            let mut m = bytes.clone();
            for _ in 0..1 + rng.below(4) {
                // Half the mutations hit the header, where they matter most.
                let at = if rng.below(2) == 0 {
                    rng.below(32)
                } else {
                    rng.below(m.len())
                };
                m[at] = match rng.below(4) {
                    0 => 0,
                    1 => 0xff,
                    2 => 0x80,
                    _ => rng.next() as u8,
                };
            }
            if rng.below(8) == 0 {
                let n = rng.below(m.len());
                m.truncate(n);
            } else if rng.below(8) == 0 {
                m.extend_from_slice(&[0x80, 0xff, 0x01]);
            }
            match read_raster(&m) {
                Ok(r) => {
                    assert!((1..=MAX_SIDE).contains(&r.width));
                    assert!((1..=MAX_SIDE).contains(&r.height));
                    assert_eq!(r.pixels.len(), r.width * r.height);
                    ok += 1;
                }
                Err(_) => err += 1,
            }
        }
    }
    // Both outcomes occur, so the mutations reach past the header checks.
    assert!(ok > 100 && err > 100, "ok {ok}, err {err}");
}

#[test]
fn read_raster_file_reads_only_what_the_header_needs() {
    let dir = tempfile::tempdir().unwrap();
    let raster = test_raster(3, 2, 4);
    let mut bytes = encode_raster(&raster);
    bytes.extend(vec![0xab; 1 << 20]);
    let path = dir.path().join("padded.ras");
    std::fs::write(&path, &bytes).unwrap();
    assert_eq!(read_raster_file(&path).unwrap(), raster);
    let path = dir.path().join("short.ras");
    std::fs::write(&path, &bytes[..20]).unwrap();
    assert!(matches!(read_raster_file(&path), Err(RasterError::Truncated { .. })));
    assert!(matches!(
        read_raster_file(&dir.path().join("missing.ras")),
        Err(RasterError::Io(_))
    ));
}

/// Whether a probe command runs and succeeds, its output discarded.
fn succeeds(probe: &mut Command) -> bool {
    probe
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// A cross-check's tool is missing: says what was looked for and how to
/// enable it (the test then passes), or fails the test when CI is set.
fn missing(tool: &str, looked_for: &str, enable: &str) {
    if std::env::var_os("CI").is_some() {
        panic!("{tool} is missing ({looked_for}) and CI is set; {enable} would enable it");
    }
    println!("skipping the {tool} cross-check ({looked_for}); {enable} would enable it");
}

/// Whether a cross-check may run: false (after saying how to enable it) when
/// the tool is missing and CI is not set; a failing test when CI is set.
fn tool_available(probe: &mut Command, tool: &str, install: &str) -> bool {
    let found = succeeds(probe);
    if !found {
        missing(tool, "not found", &format!("`{install}`"));
    }
    found
}

fn cross_check_rasters() -> Vec<Raster> {
    vec![
        test_raster(1, 1, 11),
        test_raster(3, 2, 12),
        test_raster(4, 3, 13),
        test_raster(255, 1, 14),
        test_raster(33, 17, 15),
    ]
}

/// The Python the Pillow cross-check runs: the first of `$PYTHON`, `python3`
/// on PATH and Debian's `/usr/bin/python3` that imports Pillow (a pyenv or
/// venv `python3` first on PATH may lack it while Debian's has it).
fn python_with_pillow() -> Result<OsString, String> {
    let named = std::env::var_os("PYTHON").map(|p| (format!("$PYTHON={}", p.to_string_lossy()), p));
    let usual = ["python3", "/usr/bin/python3"].map(|p| (p.to_owned(), OsString::from(p)));
    first_with_pillow(named.into_iter().chain(usual))
}

/// The first of the (label, program) candidates that imports PIL.Image;
/// else the labels of those tried, for the skip message.
fn first_with_pillow(candidates: impl IntoIterator<Item = (String, OsString)>) -> Result<OsString, String> {
    let mut tried = Vec::new();
    for (label, python) in candidates {
        if succeeds(Command::new(&python).args(["-c", "import PIL.Image"])) {
            return Ok(python);
        }
        tried.push(label);
    }
    Err(format!("tried {}: none imports PIL.Image", tried.join(", ")))
}

#[test]
fn the_pillow_python_is_the_first_candidate_that_imports_it() {
    // Stand-ins: /bin/true for a Python with Pillow (its probe succeeds),
    // /bin/false for one without, and a program that does not exist.
    let candidate = |label: &str, program: &str| (label.to_owned(), OsString::from(program));
    let absent = "/nonexistent/python3";
    assert_eq!(
        first_with_pillow([
            candidate("$PYTHON=absent", absent),
            candidate("false", "/bin/false"),
            candidate("true", "/bin/true"),
            candidate("false again", "/bin/false"),
        ]),
        Ok(OsString::from("/bin/true"))
    );
    assert_eq!(
        first_with_pillow([
            candidate("$PYTHON=absent", absent),
            candidate("/bin/false", "/bin/false")
        ]),
        Err("tried $PYTHON=absent, /bin/false: none imports PIL.Image".to_owned())
    );
}

#[test]
fn pillow_reads_the_rasters_the_project_writes() {
    let python = match python_with_pillow() {
        Ok(python) => python,
        Err(tried) => {
            let enable = "`apt-get install -y python3-pil` (for /usr/bin/python3) or `PYTHON=/path/to/python3` \
                          naming one with Pillow";
            missing("Python Pillow", &tried, enable);
            return;
        }
    };
    let dir = tempfile::tempdir().unwrap();
    for (k, raster) in cross_check_rasters().iter().enumerate() {
        let path = dir.path().join(format!("r{k}.ras"));
        outputframe(&path, raster).unwrap();
        // Pillow's Sun reader by name: left to guess, Debian's Pillow 9.4
        // takes a raster 1 or 2 pixels wide for a GIMP brush (its test reads
        // the magic number as a header size and the width as a version).
        let out = Command::new(&python)
            .args([
                "-c",
                "import sys; from PIL import Image\n\
                 im = Image.open(sys.argv[1], formats=['SUN'])\n\
                 print(im.format, im.mode, im.size[0], im.size[1])\n\
                 print(im.convert('RGB').tobytes().hex())",
            ])
            .arg(&path)
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let text = String::from_utf8(out.stdout).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next().unwrap(),
            format!("SUN RGB {} {}", raster.width, raster.height)
        );
        let hex = lines.next().unwrap();
        let expected: String = raster.pixels.iter().flatten().map(|b| format!("{b:02x}")).collect();
        assert_eq!(hex, expected, "raster {k}");
    }
}

/// Parses a binary PPM (P6, maxval 255) as netpbm writes it.
fn parse_ppm(bytes: &[u8]) -> Raster {
    let mut fields = Vec::new();
    let mut i = 0;
    while fields.len() < 4 {
        match bytes[i] {
            b'#' => {
                while bytes[i] != b'\n' {
                    i += 1;
                }
            }
            c if c.is_ascii_whitespace() => i += 1,
            _ => {
                let start = i;
                while !bytes[i].is_ascii_whitespace() {
                    i += 1;
                }
                fields.push(std::str::from_utf8(&bytes[start..i]).unwrap().to_owned());
            }
        }
    }
    assert_eq!(fields[0], "P6");
    assert_eq!(fields[3], "255");
    let width: usize = fields[1].parse().unwrap();
    let height: usize = fields[2].parse().unwrap();
    let data = &bytes[i + 1..];
    assert_eq!(data.len(), width * height * 3);
    Raster {
        width,
        height,
        pixels: data.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect(),
    }
}

fn encode_ppm(raster: &Raster) -> Vec<u8> {
    let mut out = format!("P6\n{} {}\n255\n", raster.width, raster.height).into_bytes();
    out.extend(raster.pixels.iter().flatten());
    out
}

fn run(cmd: &mut Command, input: &[u8]) -> Vec<u8> {
    let mut child = cmd
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let input = input.to_vec();
    let writer = std::thread::spawn(move || stdin.write_all(&input));
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap().unwrap();
    assert!(
        out.status.success(),
        "{:?}: {}",
        cmd,
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

#[test]
fn netpbm_reads_the_rasters_the_project_writes_and_writes_ones_the_project_reads() {
    if !tool_available(
        Command::new("sh").args(["-c", "command -v rasttopnm && command -v pnmtorast"]),
        "netpbm rasttopnm",
        "apt-get install -y netpbm",
    ) {
        return;
    }
    for (k, raster) in cross_check_rasters().iter().enumerate() {
        let ppm = run(&mut Command::new("rasttopnm"), &encode_raster(raster));
        assert_eq!(&parse_ppm(&ppm), raster, "rasttopnm, raster {k}");
    }
    // The other way: pnmtorast's standard and byte-encoded output, 24-bit
    // for many colours and 8-bit with a colour map for few, read here.
    let few = Raster {
        width: 9,
        height: 5,
        pixels: (0..45)
            .map(|i| [[200, 10, 10], [0, 0, 0], [0x80, 0x80, 0x80]][(i / 4) % 3])
            .collect(),
    };
    for raster in cross_check_rasters().iter().chain([&few]) {
        for flag in ["-standard", "-rle"] {
            let ras = run(Command::new("pnmtorast").arg(flag), &encode_ppm(raster));
            // pnmtorast -rle falls back to standard when the encoding would
            // be longer (random pixels).
            let ras_type = u32::from_be_bytes(ras[20..24].try_into().unwrap());
            assert!(ras_type == 1 || (flag == "-rle" && ras_type == 2), "type {ras_type}");
            assert_eq!(
                &read_raster(&ras).unwrap(),
                raster,
                "pnmtorast {flag} {}×{}",
                raster.width,
                raster.height
            );
        }
    }
    let few_ras = run(Command::new("pnmtorast").arg("-rle"), &encode_ppm(&few));
    let depth = u32::from_be_bytes(few_ras[12..16].try_into().unwrap());
    let maptype = u32::from_be_bytes(few_ras[24..28].try_into().unwrap());
    let ras_type = u32::from_be_bytes(few_ras[20..24].try_into().unwrap());
    assert_eq!(
        (depth, ras_type, maptype),
        (8, 2, 1),
        "few colours give a byte-encoded, colour-mapped raster"
    );
}

#[test]
fn the_test_helpers_parse_what_they_encode() {
    // Guards the cross-checks' own PPM code.
    let r = test_raster(3, 2, 5);
    assert_eq!(parse_ppm(&encode_ppm(&r)), r);
}

/// `read_raster_bytes` reads the header and no more than the raster the
/// header declares: the reader is left just past it (a tile's line, or a
/// pipe's next bytes, stay unread), with or without the length known.
#[test]
fn reading_a_raster_stops_at_its_end() {
    use std::io::Read;
    let raster = test_raster(5, 3, 9);
    let bytes = encode_raster(&raster);
    let mut sent = bytes.clone();
    sent.extend_from_slice(b"the next bytes");
    for length in [None, Some(sent.len() as u64)] {
        let mut reader = std::io::Cursor::new(&sent);
        let read =
            raytrace::raster::read_raster_bytes(&mut reader, raytrace::raster::PixelLimit::RASTER, length).unwrap();
        assert_eq!(read, bytes);
        let mut rest = String::new();
        reader.read_to_string(&mut rest).unwrap();
        assert_eq!(rest, "the next bytes");
    }
}

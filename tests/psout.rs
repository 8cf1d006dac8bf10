//! psout: framebuffer composition, the lookup-table quantiser, the folder
//! listing, the command line, the committed check raster used by
//! .ci/psout_xvfb.sh, and the PNG and PPM files it reads besides rasters.

use std::path::{Path, PathBuf};
use std::process::Command;

use raytrace::psout::{
    compose, default_zoom, distance2, neighbour, pack_rgb, placement, rasters_in_folder, screenshot_path, title,
    Framebuffer, Lut, SCREEN_HEIGHT, SCREEN_WIDTH,
};
use raytrace::raster::{encode_raster, outputframe, read_raster, Raster};
#[cfg(feature = "png")]
use raytrace::raster::{write_image, Format};

/// A colour that encodes its own coordinates (unique below 4096×4096), so
/// a screen pixel tells which raster pixel it shows.
fn coord_colour(x: usize, y: usize) -> [u8; 3] {
    [x as u8, y as u8, ((x >> 8) | ((y >> 8) << 4)) as u8]
}

fn coord_raster(width: usize, height: usize) -> Raster {
    Raster {
        width,
        height,
        pixels: (0..height)
            .flat_map(|y| (0..width).map(move |x| coord_colour(x, y)))
            .collect(),
    }
}

/// Checks every screen pixel against the definition: black outside the
/// raster, else the raster pixel at ((sx − left) / zoom, (sy − top) / zoom).
fn assert_screen(fb: &Framebuffer, raster: &Raster, left: i64, top: i64, zoom: i64) {
    assert_eq!((fb.width, fb.height), (1024, 864));
    assert_eq!(fb.pixels.len(), 1024 * 864);
    for sy in 0..864i64 {
        for sx in 0..1024i64 {
            let (dx, dy) = (sx - left, sy - top);
            let inside = dx >= 0 && dy >= 0 && dx < raster.width as i64 * zoom && dy < raster.height as i64 * zoom;
            let expected = if inside {
                let (rx, ry) = ((dx / zoom) as usize, (dy / zoom) as usize);
                pack_rgb(raster.pixels[ry * raster.width + rx])
            } else {
                0
            };
            assert_eq!(
                fb.pixel(sx as usize, sy as usize),
                expected,
                "screen ({sx}, {sy}), raster at ({left}, {top}) ×{zoom}"
            );
        }
    }
}

#[test]
fn a_two_by_two_raster_lands_in_the_centre_at_zooms_one_to_three() {
    let (a, b, c, d) = ([255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 255]);
    let raster = Raster {
        width: 2,
        height: 2,
        pixels: vec![a, b, c, d],
    };
    // Zoom 1: (1024 − 2) / 2 = 511, (864 − 2) / 2 = 431.
    let fb = compose(&raster, Some(1), (0, 0));
    assert_eq!(fb.pixel(511, 431), 0xff0000);
    assert_eq!(fb.pixel(512, 431), 0x00ff00);
    assert_eq!(fb.pixel(511, 432), 0x0000ff);
    assert_eq!(fb.pixel(512, 432), 0xffffff);
    assert_eq!(fb.pixels.iter().filter(|&&p| p != 0).count(), 4);
    assert_screen(&fb, &raster, 511, 431, 1);
    // Zoom 2: a 4×4 block from (510, 430).
    let fb = compose(&raster, Some(2), (0, 0));
    assert_eq!(fb.pixel(510, 430), 0xff0000);
    assert_eq!(fb.pixel(511, 431), 0xff0000);
    assert_eq!(fb.pixel(512, 430), 0x00ff00);
    assert_eq!(fb.pixel(513, 433), 0xffffff);
    assert_eq!(fb.pixels.iter().filter(|&&p| p != 0).count(), 16);
    assert_screen(&fb, &raster, 510, 430, 2);
    // Zoom 3 (also the default for 2×2): a 6×6 block from (509, 429).
    for fb in [compose(&raster, Some(3), (0, 0)), compose(&raster, None, (0, 0))] {
        assert_eq!(fb.pixel(509, 429), 0xff0000);
        assert_eq!(fb.pixel(511, 431), 0xff0000);
        assert_eq!(fb.pixel(512, 431), 0x00ff00);
        assert_eq!(fb.pixel(514, 434), 0xffffff);
        assert_eq!(fb.pixel(515, 434), 0);
        assert_eq!(fb.pixels.iter().filter(|&&p| p != 0).count(), 36);
        assert_screen(&fb, &raster, 509, 429, 3);
    }
}

#[test]
fn the_default_zoom_is_the_largest_that_fits() {
    assert_eq!(default_zoom(256, 256), 3); // the thesis's images: 768×768
    assert_eq!(default_zoom(341, 288), 3);
    assert_eq!(default_zoom(342, 288), 2);
    assert_eq!(default_zoom(341, 289), 2);
    assert_eq!(default_zoom(300, 300), 2);
    assert_eq!(default_zoom(512, 432), 2);
    assert_eq!(default_zoom(513, 10), 1);
    assert_eq!(default_zoom(1024, 864), 1);
    assert_eq!(default_zoom(2000, 1000), 1);
    let p = placement(256, 256, None, (0, 0));
    assert_eq!((p.zoom, p.left, p.top), (3, 128, 48));
}

#[test]
fn odd_sizes_centre_with_the_odd_pixel_to_the_right_and_bottom() {
    let raster = coord_raster(255, 3);
    let fb = compose(&raster, None, (0, 0));
    // 255×3 at ×3 is 765×9: (1024 − 765) / 2 = 129.5 → 129, (864 − 9) / 2 → 427.
    assert_eq!(placement(255, 3, None, (0, 0)).zoom, 3);
    assert_eq!(fb.pixel(129, 427), pack_rgb(coord_colour(0, 0)));
    assert_eq!(fb.pixel(128, 427), 0);
    assert_eq!(fb.pixel(129 + 764, 427 + 8), pack_rgb(coord_colour(254, 2)));
    assert_eq!(fb.pixel(129 + 765, 427 + 8), 0);
    assert_screen(&fb, &raster, 129, 427, 3);
    let raster = coord_raster(7, 5);
    assert_screen(&compose(&raster, Some(2), (0, 0)), &raster, 505, 427, 2);
}

#[test]
fn a_raster_larger_than_the_screen_is_centred_and_clipped() {
    let raster = coord_raster(2000, 1000);
    let fb = compose(&raster, None, (0, 0));
    // (1024 − 2000) / 2 = −488, (864 − 1000) / 2 = −68.
    assert_eq!(fb.pixel(0, 0), pack_rgb(coord_colour(488, 68)));
    assert_eq!(fb.pixel(1023, 863), pack_rgb(coord_colour(1511, 931)));
    assert_screen(&fb, &raster, -488, -68, 1);
    // Zoomed ×2 it is clipped more: (1024 − 4000) / 2 = −1488.
    let fb = compose(&raster, Some(2), (0, 0));
    assert_eq!(fb.pixel(0, 0), pack_rgb(coord_colour(744, 284)));
    assert_screen(&fb, &raster, -1488, -568, 2);
}

#[test]
fn pan_moves_only_a_raster_larger_than_the_screen_and_is_clamped_to_it() {
    let raster = coord_raster(2000, 1000);
    let fb = compose(&raster, None, (100, 20));
    assert_eq!(fb.pixel(0, 0), pack_rgb(coord_colour(588, 88)));
    assert_screen(&fb, &raster, -588, -88, 1);
    // Far past the edge: the raster's right and top edges meet the screen's.
    let p = placement(2000, 1000, None, (10_000, -10_000));
    assert_eq!(p.pan, (488, -68));
    assert_eq!((p.left, p.top), (-976, 0));
    let fb = compose(&raster, None, (10_000, -10_000));
    assert_eq!(fb.pixel(1023, 0), pack_rgb(coord_colour(1999, 0)));
    assert_screen(&fb, &raster, -976, 0, 1);
    let p = placement(2000, 1000, None, (i64::MIN, i64::MAX));
    assert_eq!((p.left, p.top), (0, -136));

    // A raster that fits does not pan, zoomed or not: there is nothing
    // hidden to pan to (issue 14, item 7).
    let small = coord_raster(256, 256);
    for pan in [(1000, 1000), (-1000, -1000), (32, 0)] {
        let p = placement(256, 256, None, pan);
        assert_eq!((p.zoom, p.left, p.top, p.pan), (3, 128, 48, (0, 0)));
        assert_screen(&compose(&small, None, pan), &small, 128, 48, 3);
    }
    let p = placement(256, 256, Some(1), (50, 50));
    assert_eq!((p.left, p.top, p.pan), (384, 304, (0, 0)));
    // Along the axis it overflows a raster pans, along the other it does not.
    let p = placement(700, 10, Some(2), (1000, 1000));
    assert_eq!(p.pan, (188, 0));
    assert_eq!((p.left, p.top), (-376, 422));

    // Whatever the pan, some of the raster is on screen.
    for (w, h, z) in [(2000, 1000, None), (10, 10, Some(3)), (700, 10, Some(2))] {
        for pan in [(i64::MIN, 0), (0, i64::MAX), (12345, -777), (-3, 3)] {
            let p = placement(w, h, z, pan);
            let zoom = p.zoom as i64;
            assert!(p.left < 1024 && p.left + w as i64 * zoom > 0, "{w}×{h} {pan:?}");
            assert!(p.top < 864 && p.top + h as i64 * zoom > 0, "{w}×{h} {pan:?}");
        }
    }
}

/// Big-endian header fields of a raster file.
fn header(w: u32, h: u32, depth: u32, length: u32, ras_type: u32, maptype: u32, maplength: u32) -> Vec<u8> {
    [0x59a6_6a95, w, h, depth, length, ras_type, maptype, maplength]
        .iter()
        .flat_map(|v| v.to_be_bytes())
        .collect()
}

#[test]
fn colour_mapped_and_byte_encoded_files_compose_through_read_raster() {
    // 3×1, 8-bit, map of two entries (red, cyan), RLE [1 1 0 pad].
    let mut bytes = header(3, 1, 8, 5, 2, 1, 6);
    bytes.extend_from_slice(&[255, 0, 0, 255, 0, 255]);
    bytes.extend_from_slice(&[0x80, 0x01, 0x01, 0x00, 0x00]);
    let raster = read_raster(&bytes).unwrap();
    assert_eq!(raster.pixels, [[0, 255, 255], [0, 255, 255], [255, 0, 0]]);
    let fb = compose(&raster, None, (0, 0));
    // 9×3 from ((1024 − 9) / 2, (864 − 3) / 2) = (507, 430).
    assert_eq!(fb.pixel(507, 430), 0x00ffff);
    assert_eq!(fb.pixel(513, 432), 0xff0000);
    assert_screen(&fb, &raster, 507, 430, 3);
}

fn pseudo_random_raster(width: usize, height: usize, seed: u64) -> Raster {
    let mut s = seed | 1;
    let mut pixels = Vec::with_capacity(width * height);
    for i in 0..width * height {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        // Half smooth gradient, half noise: many colours, uneven counts.
        pixels.push(if i % 2 == 0 {
            [(i % width) as u8, (i / width) as u8, 90]
        } else {
            [s as u8, (s >> 8) as u8, (s >> 16) as u8]
        });
    }
    Raster { width, height, pixels }
}

#[test]
fn the_lut_has_at_most_n_entries_and_maps_each_colour_to_its_nearest() {
    let raster = pseudo_random_raster(64, 48, 7);
    for n in [2, 3, 7, 16, 100, 255, 256] {
        let lut = Lut::median_cut(&raster.pixels, n);
        assert!(
            !lut.entries.is_empty() && lut.entries.len() <= n,
            "{n}: {}",
            lut.entries.len()
        );
        let mapped = lut.apply(&raster);
        for (&c, &m) in raster.pixels.iter().zip(&mapped.pixels) {
            let brute = lut.entries.iter().map(|&e| distance2(c, e)).min().unwrap();
            assert_eq!(distance2(c, m), brute, "N = {n}, colour {c:?}");
            assert!(lut.entries.contains(&m));
            // nearest() picks the first entry at the least distance.
            let first = lut.entries.iter().position(|&e| distance2(c, e) == brute).unwrap();
            assert_eq!(lut.nearest(c), first);
        }
        let error: u64 = raster
            .pixels
            .iter()
            .zip(&mapped.pixels)
            .map(|(&a, &b)| distance2(a, b) as u64)
            .sum();
        assert!(error > 0, "N = {n}: 3072 colours cannot all be kept");
    }
    // The quantiser only ever improves as N grows on this image.
    let err = |n| {
        let m = Lut::median_cut(&raster.pixels, n).apply(&raster);
        raster
            .pixels
            .iter()
            .zip(&m.pixels)
            .map(|(&a, &b)| distance2(a, b) as u64)
            .sum::<u64>()
    };
    assert!(err(256) < err(16) && err(16) < err(2));
    // Out-of-range N is clamped to 2..=256.
    assert_eq!(Lut::median_cut(&raster.pixels, 0).entries.len(), 2);
    assert_eq!(Lut::median_cut(&raster.pixels, 10_000).entries.len(), 256);
}

#[test]
fn an_image_with_few_colours_keeps_them_exactly_and_the_lut_is_deterministic() {
    let colours = [[1, 2, 3], [200, 0, 0], [0, 0, 0], [255, 255, 255]];
    let raster = Raster {
        width: 8,
        height: 2,
        pixels: (0..16).map(|i| colours[i * 7 % 4]).collect(),
    };
    let lut = Lut::median_cut(&raster.pixels, 4);
    assert_eq!(lut.entries.len(), 4);
    assert_eq!(lut.apply(&raster), raster);
    let big = pseudo_random_raster(40, 40, 3);
    assert_eq!(Lut::median_cut(&big.pixels, 16), Lut::median_cut(&big.pixels, 16));
    // The split is at the pixel-weighted median: two blacks against a
    // white and a near-white give black and their mean.
    let bw = Lut::median_cut(&[[0, 0, 0], [255, 255, 255], [0, 0, 0], [250, 250, 250]], 2);
    assert_eq!(bw.entries, [[0, 0, 0], [253, 253, 253]]);
    assert_eq!(
        bw.nearest([10, 10, 10]),
        bw.entries.iter().position(|&e| e == [0, 0, 0]).unwrap()
    );
}

#[test]
fn the_title_names_file_size_and_zoom() {
    assert_eq!(
        title(Path::new("raster/fig5_6.ras"), 256, 256, 3, None),
        "psout — fig5_6.ras 256×256 ×3"
    );
    assert_eq!(
        title(Path::new("x.ras"), 2000, 1000, 1, Some(16)),
        "psout — x.ras 2000×1000 ×1 LUT 16"
    );
}

#[test]
fn the_folder_listing_steps_through_ras_files_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in ["b.ras", "a.ras", "c.txt", "D.RAS", "e.ras.png"] {
        std::fs::write(d.join(name), b"").unwrap();
    }
    std::fs::create_dir(d.join("f.ras")).unwrap();
    let names = |v: Vec<PathBuf>| -> Vec<String> {
        v.iter()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .collect()
    };
    assert_eq!(
        names(rasters_in_folder(&d.join("a.ras")).unwrap()),
        ["D.RAS", "a.ras", "b.ras"]
    );
    let step = |name: &str, forward| {
        neighbour(&d.join(name), forward)
            .unwrap()
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
    };
    assert_eq!(step("a.ras", true).as_deref(), Some("b.ras"));
    assert_eq!(step("b.ras", true).as_deref(), Some("D.RAS"), "wraps");
    assert_eq!(step("a.ras", false).as_deref(), Some("D.RAS"));
    assert_eq!(step("D.RAS", false).as_deref(), Some("b.ras"), "wraps");
    assert_eq!(step("c.txt", false).as_deref(), Some("b.ras"));
    assert_eq!(step("aa.txt", true).as_deref(), Some("b.ras"));
    let lone = tempfile::tempdir().unwrap();
    std::fs::write(lone.path().join("only.ras"), b"").unwrap();
    assert_eq!(neighbour(&lone.path().join("only.ras"), true).unwrap(), None);
    assert_eq!(screenshot_path(&d.join("fig5_6.ras")), d.join("fig5_6.psout.png"));
    assert_eq!(screenshot_path(Path::new("fig5_6.ras")), Path::new("fig5_6.psout.png"));
}

fn psout() -> Command {
    Command::new(env!("CARGO_BIN_EXE_psout"))
}

#[cfg(feature = "png")]
#[test]
fn screenshot_writes_the_exact_framebuffer_as_a_1024_by_864_png() {
    let dir = tempfile::tempdir().unwrap();
    let ras = dir.path().join("odd.ras");
    let raster = pseudo_random_raster(255, 3, 11);
    outputframe(&ras, &raster).unwrap();
    let cases: [(&[&str], Raster, Option<u32>); 3] = [
        (&[], raster.clone(), None),
        (&["--zoom", "1"], raster.clone(), Some(1)),
        (
            &["--zoom", "2", "--lut", "8"],
            Lut::median_cut(&raster.pixels, 8).apply(&raster),
            Some(2),
        ),
    ];
    for (k, (flags, shown, zoom)) in cases.into_iter().enumerate() {
        let png = dir.path().join(format!("shot{k}.png"));
        let out = psout()
            .args(flags)
            .arg("--screenshot")
            .arg(&png)
            .arg(&ras)
            .env_remove("DISPLAY")
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{flags:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let img = image::open(&png).unwrap().to_rgb8();
        assert_eq!((img.width(), img.height()), (1024, 864));
        let expected = compose(&shown, zoom, (0, 0));
        let got: Vec<u32> = img.pixels().map(|p| pack_rgb(p.0)).collect();
        assert!(got == expected.pixels, "{flags:?}: pixels differ");
        assert!(got.iter().any(|&p| p != 0));
    }
}

#[test]
fn bad_raster_files_exit_with_code_2_and_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let good = encode_raster(&pseudo_random_raster(4, 4, 1));
    let mut bad_magic = good.clone();
    bad_magic[3] ^= 1;
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("truncated.ras", good[..good.len() - 5].to_vec()),
        ("short-header.ras", good[..12].to_vec()),
        ("bad-magic.ras", bad_magic),
        ("zero-size.ras", header(0, 4, 24, 0, 1, 0, 0)),
        ("gigantic.ras", header(u32::MAX, u32::MAX, 32, 0, 1, 0, 0)),
        ("gigantic-rle.ras", {
            let mut b = header(16384, 16384, 32, 0, 2, 0, 0);
            b.extend_from_slice(&[0x80, 0xff, 0x00]);
            b
        }),
        ("empty.ras", vec![]),
    ];
    for (name, bytes) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        for screenshot in [true, false] {
            let mut cmd = psout();
            if screenshot {
                cmd.arg("--screenshot").arg(dir.path().join("never.png"));
            }
            let out = cmd.arg(&path).env_remove("DISPLAY").output().unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
            assert!(stderr.contains(name), "{name}: {stderr}");
            assert!(!stderr.contains("panicked"), "{name}: {stderr}");
        }
    }
    let out = psout().arg(dir.path().join("missing.ras")).output().unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("missing.ras"));
    assert!(!dir.path().join("never.png").exists());
}

#[test]
fn without_a_display_or_screenshot_the_error_names_both_fixes() {
    let dir = tempfile::tempdir().unwrap();
    let ras = dir.path().join("ok.ras");
    outputframe(&ras, &pseudo_random_raster(3, 3, 2)).unwrap();
    for display in [None, Some("")] {
        let mut cmd = psout();
        cmd.arg(&ras).env_remove("WAYLAND_DISPLAY");
        match display {
            None => cmd.env_remove("DISPLAY"),
            Some(v) => cmd.env("DISPLAY", v),
        };
        let out = cmd.output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{stderr}");
        assert!(stderr.contains("xvfb-run"), "{stderr}");
        assert!(stderr.contains("--screenshot OUT.png"), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

// The check raster: tests/data/psout_check.ras, shown in a real window by
// .ci/psout_xvfb.sh. Odd-sized (255×241, shown ×3), 8-bit with a colour map
// and byte-encoded, so the window path reads the least common layout.

const CHECK_W: usize = 255;
const CHECK_H: usize = 241;

/// The check image as colour indices, and its colour map.
fn check_image() -> (Vec<u8>, Vec<[u8; 3]>) {
    let mut map = Vec::new();
    // 0..32: a sky from dark to light blue.
    for i in 0..32u32 {
        map.push([(20 + 3 * i) as u8, (40 + 4 * i) as u8, (110 + 4 * i) as u8]);
    }
    // 32..96: an orange ball, 64 shades.
    for i in 0..64u32 {
        map.push([(40 + 3 * i) as u8, (15 + 2 * i) as u8, (5 + i / 2) as u8]);
    }
    // 96, 97: the checker floor; 98: a white frame; 99: the ball's shadow.
    map.extend_from_slice(&[[230, 230, 210], [60, 60, 70], [255, 255, 255], [25, 25, 35]]);
    let mut idx = Vec::with_capacity(CHECK_W * CHECK_H);
    for y in 0..CHECK_H {
        for x in 0..CHECK_W {
            let (fx, fy) = (x as f64, y as f64);
            let (dx, dy) = ((fx - 127.0) / 70.0, (fy - 100.0) / 70.0);
            let r2 = dx * dx + dy * dy;
            let v = if x == 0 || y == 0 || x == CHECK_W - 1 || y == CHECK_H - 1 {
                98
            } else if r2 < 1.0 {
                // Lambert shading with the light up and to the left.
                let dz = (1.0 - r2).sqrt();
                let lambert = (-0.5 * dx - 0.6 * dy + 0.62 * dz).max(0.0);
                32 + ((lambert * 63.0).round() as u8).min(63)
            } else if y >= 180 {
                let (sx, sy) = ((fx - 127.0) / 75.0, (fy - 192.0) / 12.0);
                if sx * sx + sy * sy < 1.0 {
                    99
                } else {
                    // A floor in perspective: squares widen toward the viewer.
                    let depth = (fy - 170.0) / 10.0;
                    let u = ((fx - 127.0) / (4.0 * depth)).floor() as i64;
                    let w = (depth * 2.0).ln().floor() as i64;
                    if (u + w).rem_euclid(2) == 0 {
                        96
                    } else {
                        97
                    }
                }
            } else {
                (y * 32 / 180) as u8
            };
            idx.push(v);
        }
    }
    (idx, map)
}

/// RT_BYTE_ENCODED: runs of three or more (and any 0x80) as `80 n v`, a
/// single 0x80 as `80 00`, else literal bytes.
fn byte_encode(data: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < data.len() {
        let v = data[i];
        let mut run = 1;
        while i + run < data.len() && data[i + run] == v && run < 256 {
            run += 1;
        }
        if v == 0x80 && run == 1 {
            out.extend_from_slice(&[0x80, 0x00]);
        } else if run >= 3 || v == 0x80 {
            out.extend_from_slice(&[0x80, (run - 1) as u8, v]);
        } else {
            out.extend(std::iter::repeat_n(v, run));
        }
        i += run;
    }
    out
}

fn check_file() -> (Vec<u8>, Raster) {
    let (idx, map) = check_image();
    let row_bytes = CHECK_W.div_ceil(2) * 2;
    let mut data = Vec::with_capacity(row_bytes * CHECK_H);
    for row in idx.chunks_exact(CHECK_W) {
        data.extend_from_slice(row);
        data.resize(data.len() + row_bytes - CHECK_W, 0);
    }
    let encoded = byte_encode(&data);
    let mut bytes = header(
        CHECK_W as u32,
        CHECK_H as u32,
        8,
        encoded.len() as u32,
        2,
        1,
        3 * map.len() as u32,
    );
    for ch in 0..3 {
        bytes.extend(map.iter().map(|c| c[ch]));
    }
    bytes.extend_from_slice(&encoded);
    let raster = Raster {
        width: CHECK_W,
        height: CHECK_H,
        pixels: idx.iter().map(|&i| map[i as usize]).collect(),
    };
    (bytes, raster)
}

#[test]
fn the_byte_encoder_of_these_tests_round_trips_through_read_raster() {
    for data in [
        vec![0x80],
        vec![0x80, 0x80],
        vec![1, 1, 1, 0x80, 2, 2],
        vec![7; 600],
        (0..=255).collect::<Vec<u8>>(),
    ] {
        let mut data = data;
        if data.len() % 2 == 1 {
            data.push(0);
        }
        let width = data.len() as u32;
        let enc = byte_encode(&data);
        let mut bytes = header(width, 1, 8, enc.len() as u32, 2, 0, 0);
        bytes.extend_from_slice(&enc);
        let r = read_raster(&bytes).unwrap();
        assert_eq!(r.pixels, data.iter().map(|&v| [v; 3]).collect::<Vec<_>>());
    }
}

/// Regenerates tests/data/psout_check.ras when it is missing or stale
/// (outside CI; in CI a stale file fails), and checks it reads back as the
/// intended image.
#[test]
fn the_committed_check_raster_is_current() {
    let (bytes, raster) = check_file();
    assert_eq!(read_raster(&bytes).unwrap(), raster);
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/psout_check.ras");
    let on_disk = std::fs::read(&path).ok();
    if on_disk.as_deref() != Some(&bytes[..]) {
        assert!(
            std::env::var_os("CI").is_none(),
            "{} is stale; run `cargo test --test psout` outside CI and commit it",
            path.display()
        );
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        write_replacing(&path, &bytes);
        println!("regenerated {}", path.display());
    }
    assert_eq!(std::fs::read(&path).unwrap(), bytes);
    // Shown at ×3: 765×723 from (129, 70).
    let fb = compose(&raster, None, (0, 0));
    assert_eq!(placement(CHECK_W, CHECK_H, None, (0, 0)).left, 129);
    assert_screen(&fb, &raster, 129, 70, 3);
}

fn write_replacing(path: &Path, bytes: &[u8]) {
    let tmp = path.with_extension("ras.tmp");
    std::fs::write(&tmp, bytes).unwrap();
    std::fs::rename(&tmp, path).unwrap();
}

#[test]
fn the_screen_is_exactly_1024_by_864() {
    assert_eq!((SCREEN_WIDTH, SCREEN_HEIGHT), (1024, 864));
    let fb = compose(&coord_raster(1, 1), None, (0, 0));
    assert_eq!(fb.to_raster().pixels.len(), 1024 * 864);
    assert_eq!(fb.to_raster().pixels[430 * 1024 + 511], [0, 0, 0]);
    // 1×1 at ×3 from (510, 430): coord_colour(0, 0) is black too, so use a
    // coloured one.
    let one = Raster {
        width: 1,
        height: 1,
        pixels: vec![[9, 8, 7]],
    };
    let fb = compose(&one, None, (0, 0));
    assert_eq!(fb.to_raster().pixels[430 * 1024 + 510], [9, 8, 7]);
    assert_eq!(fb.pixel(512, 432), 0x090807);
    assert_eq!(fb.pixel(513, 432), 0);
}

// PNG and PPM: the other files `raytrace -o` writes.

#[cfg(feature = "png")]
#[test]
fn a_png_or_a_ppm_shows_as_its_raster_does() {
    let dir = tempfile::tempdir().unwrap();
    let raster = pseudo_random_raster(255, 3, 11);
    let shot = |file: &Path| {
        let png = file.with_extension("shot.png");
        let out = psout().arg("--screenshot").arg(&png).arg(file).output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        image::open(&png).unwrap().to_rgb8().into_raw()
    };
    let ras = dir.path().join("r.ras");
    outputframe(&ras, &raster).unwrap();
    let expected = shot(&ras);
    for (name, format) in [("r.png", Format::Png), ("r.ppm", Format::Netpbm)] {
        let path = dir.path().join(name);
        write_image(&path, &raster, format).unwrap();
        assert!(shot(&path) == expected, "{name}: the screen differs");
    }
    // A film of PNG frames is read like one of rasters.
    let frames = [dir.path().join("r.png"), dir.path().join("r.ppm")];
    let out = psout()
        .args(["--screenshot", "-", "--frame", "2"])
        .args(frames)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

#[test]
fn bad_png_and_ppm_files_exit_with_code_2_and_say_what_is_wrong() {
    let dir = tempfile::tempdir().unwrap();
    let mut png = Vec::new();
    #[cfg(feature = "png")]
    raytrace::raster::write_png_to(&pseudo_random_raster(4, 4, 1), &mut png).unwrap();
    #[cfg(not(feature = "png"))]
    png.extend_from_slice(b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR");
    let mut bad_crc = png.clone();
    bad_crc[20] ^= 1;
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("truncated.png", png[..png.len() / 2].to_vec(), "PNG"),
        ("bad-crc.png", bad_crc, "PNG"),
        ("signature-only.png", png[..8].to_vec(), "PNG"),
        (
            "truncated.ppm",
            b"P6 4 4 255\n\x01\x02\x03".to_vec(),
            "PPM pixel data needs 48 bytes, only 3",
        ),
        (
            "no-height.ppm",
            b"P6 4".to_vec(),
            "PPM: the file ends before the height",
        ),
        (
            "word.ppm",
            b"P6 four 4 255\n".to_vec(),
            "PPM: the width 'four' is not a number",
        ),
        (
            "zero.ppm",
            b"P6 0 4 255\n".to_vec(),
            "PPM: the width 0 is outside 1..=16384",
        ),
        (
            "huge.ppm",
            b"P6 2 99999999999 255\n".to_vec(),
            "PPM: the height 99999999999 is outside",
        ),
        (
            "too-many.ppm",
            b"P6 16384 4097 255\n".to_vec(),
            "16384×4097 is 67125248 pixels, more than the 67108864",
        ),
        (
            "maxval.ppm",
            b"P6 1 1 70000\n\0\0\0\0\0\0".to_vec(),
            "PPM: the maxval 70000 is outside 1..=65535",
        ),
        (
            "sample.ppm",
            b"P3 1 1 15\n1 2 16\n".to_vec(),
            "PPM: a sample 16 is more than the maxval 15",
        ),
        (
            "short.ppm",
            b"P3 1 1 15\n1 2".to_vec(),
            "PPM: the file ends before the sample 3",
        ),
        (
            "grey.pgm",
            b"P5 1 1 255\n\0".to_vec(),
            "P5 file (PGM, grey); the PPM kinds P6 and P3 are read",
        ),
        ("long.ppm", [&b"P6 "[..], &[b'9'; 30]].concat(), "longer than 20 bytes"),
        (
            "text.txt",
            b"hello, world\n".repeat(4),
            "not a Sun raster, PNG or PPM file (it starts with 0x68656c6c)",
        ),
    ];
    for (name, bytes, says) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        let out = psout()
            .arg("--screenshot")
            .arg(dir.path().join("never.png"))
            .arg(&path)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains(name) && stderr.contains(says), "{name}: {stderr}");
        assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    }
    assert!(!dir.path().join("never.png").exists());
}

/// psout reads a picture from a pipe (`raytrace DECK -o - | psout
/// --screenshot p.png /dev/stdin`): the file is opened once and read
/// front to back, so the bytes that tell its kind are not lost. A writer
/// that sends a valid header and then zeros without end does not hold it:
/// no more is read than the header declares.
#[cfg(feature = "png")]
#[test]
fn a_pipe_is_read_once_and_no_further_than_its_header() {
    use std::io::Write;
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    let raster = pseudo_random_raster(9, 7, 5);
    let file = dir.path().join("file.png");
    let piped = dir.path().join("piped.png");
    let shot = |input: &str, out: &Path, stdin: Stdio| {
        psout()
            .arg("--screenshot")
            .arg(out)
            .arg(input)
            .env_remove("DISPLAY")
            .stdin(stdin)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap()
    };
    let ras = dir.path().join("in.ras");
    outputframe(&ras, &raster).unwrap();
    let o = shot(ras.to_str().unwrap(), &file, Stdio::null())
        .wait_with_output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = encode_raster(&raster);
    // A Sun raster, a PNG and a PPM through the pipe.
    let (mut png, mut ppm) = (Vec::new(), Vec::new());
    raytrace::raster::write_png_to(&raster, &mut png).unwrap();
    raytrace::raster::write_ppm_to(&raster, &mut ppm).unwrap();
    for (kind, sent) in [("ras", &bytes), ("png", &png), ("ppm", &ppm)] {
        let mut child = shot("/dev/stdin", &piped, Stdio::piped());
        child.stdin.take().unwrap().write_all(sent).unwrap();
        let o = child.wait_with_output().unwrap();
        assert!(o.status.success(), "{kind}: {}", String::from_utf8_lossy(&o.stderr));
        assert_eq!(std::fs::read(&piped).unwrap(), std::fs::read(&file).unwrap(), "{kind}");
    }
    // The header of a 9×7 raster, then zeros for ever: read as a black picture.
    let mut child = shot("/dev/stdin", &piped, Stdio::piped());
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || {
        let _ = stdin.write_all(&bytes[..32]);
        let zeros = [0u8; 65536];
        while stdin.write_all(&zeros).is_ok() {}
    });
    // Stopped after a minute, when it would fail.
    let started = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() && started.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    let _ = child.kill();
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    writer.join().unwrap();
}

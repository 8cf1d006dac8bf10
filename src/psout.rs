//! `psout`: the PS 390 display emulation (the window-free core; the window
//! and the command line are in `src/bin/psout.rs`).
//!
//! The thesis rendered on a Sun 3 and sent each raster file "through the
//! interface psout" to an Evans & Sutherland PS 390 display with a
//! resolution of 1024×864 (Ch. 4 (一)–(二), Fig. 4.1; Ch. 4.1 (g)). That is
//! all it says of psout and of the display. Everything here is therefore
//! reconstructed: a 1024×864 framebuffer, black, with the raster centred
//! and enlarged by pixel replication, as a frame-buffer program of the time
//! would show a 256×256 image.
//!
//! Colour: the thesis does not say how many colours the PS 390 showed nor
//! how psout mapped 24-bit pixels to them. One museum catalogue entry (UvA
//! Computer Museum, no. 04.73) lists "(probably) 6 bitplanes for color" —
//! itself hedged. So the default shows the raster's full 24-bit colour, and
//! the optional lookup-table mode ([`Lut`]) shows what a display limited to
//! N colours would make of it; it is an approximation, not a record of the
//! PS 390's behaviour.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::raster::Raster;

pub mod player;

/// The PS 390 screen width in pixels (Ch. 4 (一)).
pub const SCREEN_WIDTH: usize = 1024;
/// The PS 390 screen height in pixels (Ch. 4 (一)).
pub const SCREEN_HEIGHT: usize = 864;
/// The largest zoom: 256×256 rasters (Ch. 5) show at 768×768.
pub const MAX_ZOOM: u32 = 3;

/// A 1024×864 screen, row-major from the top left, each pixel `0x00RRGGBB`
/// (the layout minifb draws).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Framebuffer {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<u32>,
}

impl Framebuffer {
    /// The pixel at column `x`, row `y`; panics outside the screen, like
    /// slice indexing.
    pub fn pixel(&self, x: usize, y: usize) -> u32 {
        self.pixels[y * self.width + x]
    }

    /// The screen as a raster (for a PNG screenshot).
    pub fn to_raster(&self) -> Raster {
        Raster {
            width: self.width,
            height: self.height,
            pixels: self
                .pixels
                .iter()
                .map(|&p| [(p >> 16) as u8, (p >> 8) as u8, p as u8])
                .collect(),
        }
    }
}

/// `[r, g, b]` as `0x00RRGGBB`.
pub fn pack_rgb([r, g, b]: [u8; 3]) -> u32 {
    (r as u32) << 16 | (g as u32) << 8 | b as u32
}

/// The largest zoom of 1..=[`MAX_ZOOM`] at which a `width`×`height` raster
/// fits the screen; 1 if even 1× does not fit.
pub fn default_zoom(width: usize, height: usize) -> u32 {
    (1..=MAX_ZOOM)
        .rev()
        .find(|&z| width * z as usize <= SCREEN_WIDTH && height * z as usize <= SCREEN_HEIGHT)
        .unwrap_or(1)
}

/// Where a raster lands on the screen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placement {
    /// The zoom used (1..=3).
    pub zoom: u32,
    /// Screen column of the raster's left edge (negative when clipped).
    pub left: i64,
    /// Screen row of the raster's top edge (negative when clipped).
    pub top: i64,
    /// The pan actually applied, after clamping.
    pub pan: (i64, i64),
}

/// Places a `width`×`height` raster: scaled by `zoom` (default
/// [`default_zoom`]; clamped to 1..=3), centred — the spare space's odd
/// pixel goes to the right and bottom margins — then moved by the pan.
///
/// `pan` is the view's offset in screen pixels: (+x, +y) shows more of the
/// raster's right and bottom, i.e. moves the raster left and up. It applies
/// only along an axis where the (zoomed) raster is larger than the screen,
/// and is clamped there so the raster always covers the screen along that
/// axis: a raster can never be dragged off the screen, and one that fits
/// stays centred (there is nothing hidden to pan to).
pub fn placement(width: usize, height: usize, zoom: Option<u32>, pan: (i64, i64)) -> Placement {
    let zoom = zoom.unwrap_or_else(|| default_zoom(width, height)).clamp(1, MAX_ZOOM);
    let (sw, sh) = (width as i64 * zoom as i64, height as i64 * zoom as i64);
    let (screen_w, screen_h) = (SCREEN_WIDTH as i64, SCREEN_HEIGHT as i64);
    let centre_left = (screen_w - sw).div_euclid(2);
    let centre_top = (screen_h - sh).div_euclid(2);
    let pan = (
        clamp_pan(pan.0, centre_left, sw, screen_w),
        clamp_pan(pan.1, centre_top, sh, screen_h),
    );
    Placement {
        zoom,
        left: centre_left - pan.0,
        top: centre_top - pan.1,
        pan,
    }
}

/// The pan along one axis: 0 when the raster fits the screen along it,
/// else clamped so that the raster's edge `centre - p` stays in
/// [screen − size, 0]; `centre` lies in that range, so the clamp bounds
/// are ordered.
fn clamp_pan(p: i64, centre: i64, size: i64, screen: i64) -> i64 {
    if size <= screen {
        return 0;
    }
    p.clamp(centre, centre - (screen - size))
}

/// The PS 390 screen showing `raster`: black, the raster centred, enlarged
/// by pixel replication, clipped to the screen, moved by `pan` (see
/// [`placement`]).
///
/// Reconstructed: the thesis only says psout sent the raster to the
/// 1024×864 display (Ch. 4 (二), Fig. 4.1). A raster whose `pixels` is short
/// of `width × height` shows black where pixels are missing.
pub fn compose(raster: &Raster, zoom: Option<u32>, pan: (i64, i64)) -> Framebuffer {
    let p = placement(raster.width, raster.height, zoom, pan);
    let z = p.zoom as i64;
    let mut pixels = vec![0u32; SCREEN_WIDTH * SCREEN_HEIGHT];
    let x_from = p.left.max(0);
    let x_to = (p.left + raster.width as i64 * z).min(SCREEN_WIDTH as i64);
    let y_from = p.top.max(0);
    let y_to = (p.top + raster.height as i64 * z).min(SCREEN_HEIGHT as i64);
    for sy in y_from..y_to {
        let ry = ((sy - p.top) / z) as usize;
        let screen_row = &mut pixels[sy as usize * SCREEN_WIDTH..][..SCREEN_WIDTH];
        for sx in x_from..x_to {
            let rx = ((sx - p.left) / z) as usize;
            if let Some(&rgb) = raster.pixels.get(ry * raster.width + rx) {
                screen_row[sx as usize] = pack_rgb(rgb);
            }
        }
    }
    Framebuffer {
        width: SCREEN_WIDTH,
        height: SCREEN_HEIGHT,
        pixels,
    }
}

/// A colour lookup table: the `--lut N` mode, showing a raster as a display
/// limited to N simultaneous colours would (see the module doc for why this
/// is an approximation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Lut {
    /// The table, at most N entries (fewer when the image has fewer colours).
    pub entries: Vec<[u8; 3]>,
}

impl Lut {
    /// The fewest entries a table may have.
    pub const MIN_ENTRIES: usize = 2;
    /// The most entries a table may have.
    pub const MAX_ENTRIES: usize = 256;

    /// Builds an `n`-entry table by median cut (Heckbert 1982) over the
    /// colours of `pixels`; `n` is clamped to 2..=256.
    ///
    /// An image with at most `n` distinct colours gets exactly those. Else,
    /// starting from one box holding all colours, the box with the widest
    /// channel range (ties: more pixels, then the earlier box) is split at
    /// the pixel-weighted median of that channel, until there are `n` boxes;
    /// each entry is its box's pixel-weighted mean colour. Deterministic.
    pub fn median_cut(pixels: &[[u8; 3]], n: usize) -> Lut {
        let n = n.clamp(Self::MIN_ENTRIES, Self::MAX_ENTRIES);
        let mut counts: HashMap<[u8; 3], u64> = HashMap::new();
        for &c in pixels {
            *counts.entry(c).or_insert(0) += 1;
        }
        let mut colours: Vec<([u8; 3], u64)> = counts.into_iter().collect();
        colours.sort_unstable();
        if colours.is_empty() {
            return Lut {
                entries: vec![[0, 0, 0]],
            };
        }
        if colours.len() <= n {
            return Lut {
                entries: colours.into_iter().map(|(c, _)| c).collect(),
            };
        }
        // Boxes are ranges of `colours` (each sorted as its split needs),
        // with their widest channel, its range and their pixel count.
        let stats = |colours: &[([u8; 3], u64)], b: std::ops::Range<usize>| {
            let (channel, range) = widest_channel(&colours[b.clone()]);
            let weight: u64 = colours[b.clone()].iter().map(|&(_, w)| w).sum();
            (b, channel, range, weight)
        };
        let mut boxes = vec![stats(&colours, 0..colours.len())];
        while boxes.len() < n {
            let mut best: Option<(usize, (u8, u64))> = None;
            for (i, (b, _, range, weight)) in boxes.iter().enumerate() {
                if b.len() >= 2 && best.is_none_or(|(_, key)| (*range, *weight) > key) {
                    best = Some((i, (*range, *weight)));
                }
            }
            let Some((i, _)) = best else {
                break;
            };
            let (b, channel, _, weight) = boxes[i].clone();
            let slice = &mut colours[b.clone()];
            slice.sort_unstable_by_key(|&(c, _)| (c[channel], c));
            // The first split point where the left part holds half the
            // pixels, kept inside the box so both halves are non-empty.
            let mut left_weight = 0;
            let mut split = slice.len() - 1;
            for (k, &(_, w)) in slice.iter().enumerate() {
                left_weight += w;
                if 2 * left_weight >= weight {
                    split = k + 1;
                    break;
                }
            }
            let split = b.start + split.clamp(1, b.len() - 1);
            boxes[i] = stats(&colours, b.start..split);
            boxes.push(stats(&colours, split..b.end));
        }
        let entries = boxes
            .into_iter()
            .map(|(b, ..)| {
                let part = &colours[b];
                let total: u64 = part.iter().map(|&(_, w)| w).sum();
                let mean = |ch: usize| {
                    let sum: u64 = part.iter().map(|&(c, w)| c[ch] as u64 * w).sum();
                    ((sum + total / 2) / total) as u8
                };
                [mean(0), mean(1), mean(2)]
            })
            .collect();
        Lut { entries }
    }

    /// The index of the entry nearest to `c` by squared RGB distance; ties
    /// go to the lower index.
    pub fn nearest(&self, c: [u8; 3]) -> usize {
        let mut best = (u32::MAX, 0);
        for (i, e) in self.entries.iter().enumerate() {
            let d = distance2(c, *e);
            if d < best.0 {
                best = (d, i);
            }
        }
        best.1
    }

    /// The raster with each pixel replaced by its nearest entry.
    pub fn apply(&self, raster: &Raster) -> Raster {
        let mut cache: HashMap<[u8; 3], [u8; 3]> = HashMap::new();
        let pixels = raster
            .pixels
            .iter()
            .map(|&c| *cache.entry(c).or_insert_with(|| self.entries[self.nearest(c)]))
            .collect();
        Raster {
            width: raster.width,
            height: raster.height,
            pixels,
        }
    }
}

/// The squared RGB distance of two colours.
pub fn distance2(a: [u8; 3], b: [u8; 3]) -> u32 {
    (0..3)
        .map(|i| {
            let d = a[i] as i32 - b[i] as i32;
            (d * d) as u32
        })
        .sum()
}

/// The channel (0 red, 1 green, 2 blue) with the widest range over the
/// colours, and that range; ties go to the lower channel.
fn widest_channel(colours: &[([u8; 3], u64)]) -> (usize, u8) {
    let mut best = (0, 0);
    for ch in 0..3 {
        let (lo, hi) = colours
            .iter()
            .fold((u8::MAX, u8::MIN), |(lo, hi), (c, _)| (lo.min(c[ch]), hi.max(c[ch])));
        let range = hi.saturating_sub(lo);
        if ch == 0 || range > best.1 {
            best = (ch, range);
        }
    }
    best
}

/// The window title: file name, raster size and zoom, e.g.
/// `psout — fig5_6.ras 256×256 ×3`, with ` LUT 16` in lookup-table mode.
pub fn title(path: &Path, width: usize, height: usize, zoom: u32, lut: Option<usize>) -> String {
    let name = path
        .file_name()
        .map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
    let mut t = format!("psout — {name} {width}×{height} ×{zoom}");
    if let Some(n) = lut {
        t.push_str(&format!(" LUT {n}"));
    }
    t
}

/// The raster files (extension `.ras`, any case) in the folder of `path`,
/// sorted by file name: what the window's n and p keys step through.
pub fn rasters_in_folder(path: &Path) -> std::io::Result<Vec<PathBuf>> {
    let dir = folder_of(path);
    let mut found = Vec::new();
    for entry in std::fs::read_dir(&dir)? {
        let entry = entry?;
        let p = entry.path();
        let is_ras = p.extension().is_some_and(|e| e.eq_ignore_ascii_case("ras"));
        if is_ras && p.is_file() {
            found.push(p);
        }
    }
    found.sort_by(|a, b| a.file_name().cmp(&b.file_name()));
    Ok(found)
}

/// The raster after (`forward`) or before `path` in [`rasters_in_folder`],
/// wrapping around at the ends; `None` if the folder has no other raster.
/// A `path` that is not itself in the list steps to the nearest name.
pub fn neighbour(path: &Path, forward: bool) -> std::io::Result<Option<PathBuf>> {
    let list = rasters_in_folder(path)?;
    let name = path.file_name();
    let pick = match list.iter().position(|p| p.file_name() == name) {
        Some(i) if list.len() > 1 => {
            let n = list.len();
            Some(list[if forward { (i + 1) % n } else { (i + n - 1) % n }].clone())
        }
        Some(_) => None,
        None if forward => list.iter().find(|p| p.file_name() > name).or(list.first()).cloned(),
        None => list
            .iter()
            .rev()
            .find(|p| p.file_name() < name)
            .or(list.last())
            .cloned(),
    };
    Ok(pick)
}

/// Where the window's s key saves the screen: beside the raster, named
/// `<raster stem>.psout.png` (`fig5_6.ras` → `fig5_6.psout.png`).
pub fn screenshot_path(raster_path: &Path) -> PathBuf {
    let stem = raster_path
        .file_stem()
        .map_or_else(|| "raster".into(), |s| s.to_string_lossy().into_owned());
    raster_path.with_file_name(format!("{stem}.psout.png"))
}

/// Why a window cannot be opened, or `None` when one may be: `DISPLAY`
/// unset or empty (the window is an X11 window), or no `window` feature.
/// Every program with a window asks this first (`psout`, `contour`,
/// `raytrace --show`).
pub fn display_missing() -> Option<&'static str> {
    if !cfg!(feature = "window") {
        return Some("this program was built without the `window` feature");
    }
    // `DISPLAY=` (empty) is as good as unset.
    match std::env::var_os("DISPLAY").is_none_or(|d| d.is_empty()) {
        true => Some("DISPLAY is not set"),
        false => None,
    }
}

/// The message when no window can be opened: why, and both ways out —
/// an X server such as Xvfb, or `instead`, the program's way to work
/// without a window.
pub fn no_display_message(program: &str, reason: &str, instead: &str) -> String {
    format!(
        "cannot open a window ({reason}).\n\
         Run {program} under an X display, e.g. `xvfb-run -s \"-screen 0 1024x864x24\" {program} …`,\n\
         or {instead}."
    )
}

/// minifb's message with its detail (its `Display` drops the detail, e.g.
/// "XOpenDisplay failed" or "failed to load Xlib").
#[cfg(feature = "window")]
pub fn window_error(e: minifb::Error) -> String {
    match &e {
        minifb::Error::WindowCreate(detail) | minifb::Error::UpdateFailed(detail) => {
            format!("{e}: {detail}")
        }
        _ => e.to_string(),
    }
}

fn folder_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

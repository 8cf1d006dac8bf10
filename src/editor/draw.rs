//! Drawing on the 1024×864 screen ([`Framebuffer`]): rectangles, lines,
//! point marks, text in an 8×8 bitmap font (font8x8's ASCII glyphs) and a
//! raster enlarged into a box. Everything is clipped to the screen, so a
//! point panned off the plane draws nothing and costs nothing.

use crate::psout::{pack_rgb, Framebuffer, SCREEN_HEIGHT, SCREEN_WIDTH};
use crate::raster::Raster;

/// A box on the screen: left, top, width, height in pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    pub x: i64,
    pub y: i64,
    pub w: i64,
    pub h: i64,
}

impl Rect {
    /// Whether the screen pixel (x, y) lies in the box.
    pub fn holds(&self, x: f64, y: f64) -> bool {
        x >= self.x as f64 && y >= self.y as f64 && x < (self.x + self.w) as f64 && y < (self.y + self.h) as f64
    }
}

/// The width and height of a character of [`text`], in pixels.
pub const CHAR: i64 = 8;

/// A black screen.
pub fn blank() -> Framebuffer {
    Framebuffer {
        width: SCREEN_WIDTH,
        height: SCREEN_HEIGHT,
        pixels: vec![0; SCREEN_WIDTH * SCREEN_HEIGHT],
    }
}

/// Sets pixel (x, y) when it is on the screen and inside `clip`.
fn plot(fb: &mut Framebuffer, clip: Rect, x: i64, y: i64, colour: u32) {
    let inside = x >= clip.x.max(0)
        && y >= clip.y.max(0)
        && x < (clip.x + clip.w).min(fb.width as i64)
        && y < (clip.y + clip.h).min(fb.height as i64);
    if inside {
        fb.pixels[y as usize * fb.width + x as usize] = colour;
    }
}

/// Fills `r` (clipped to the screen).
pub fn fill(fb: &mut Framebuffer, r: Rect, colour: u32) {
    let (x0, x1) = (r.x.max(0), (r.x + r.w).min(fb.width as i64));
    let (y0, y1) = (r.y.max(0), (r.y + r.h).min(fb.height as i64));
    for y in y0..y1 {
        for x in x0..x1 {
            fb.pixels[y as usize * fb.width + x as usize] = colour;
        }
    }
}

/// The one-pixel border just inside `r`.
pub(crate) fn outline(fb: &mut Framebuffer, r: Rect, colour: u32) {
    for side in [
        Rect { h: 1, ..r },
        Rect {
            y: r.y + r.h - 1,
            h: 1,
            ..r
        },
        Rect { w: 1, ..r },
        Rect {
            x: r.x + r.w - 1,
            w: 1,
            ..r
        },
    ] {
        fill(fb, side, colour);
    }
}

/// A line from (x0, y0) to (x1, y1), one pixel wide, drawn inside `clip`;
/// a line far outside it is cut to it first, so its length costs nothing.
pub fn line(fb: &mut Framebuffer, clip: Rect, (x0, y0): (f64, f64), (x1, y1): (f64, f64), colour: u32) {
    let Some(((x0, y0), (x1, y1))) = cut(clip, (x0, y0), (x1, y1)) else {
        return;
    };
    let steps = (x1 - x0).abs().max((y1 - y0).abs()).ceil().max(1.0) as i64;
    for i in 0..=steps {
        let f = i as f64 / steps as f64;
        let (x, y) = (x0 + (x1 - x0) * f, y0 + (y1 - y0) * f);
        plot(fb, clip, x.round() as i64, y.round() as i64, colour);
    }
}

/// The part of a segment inside `clip` widened by a pixel (Liang–Barsky),
/// or `None`; an end that is not finite gives `None`.
fn cut(clip: Rect, a: (f64, f64), b: (f64, f64)) -> Option<((f64, f64), (f64, f64))> {
    if ![a.0, a.1, b.0, b.1].iter().all(|c| c.is_finite()) {
        return None;
    }
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (lo_x, hi_x) = (clip.x as f64 - 1.0, (clip.x + clip.w) as f64 + 1.0);
    let (lo_y, hi_y) = (clip.y as f64 - 1.0, (clip.y + clip.h) as f64 + 1.0);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-dx, a.0 - lo_x), (dx, hi_x - a.0), (-dy, a.1 - lo_y), (dy, hi_y - a.1)] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some(((a.0 + t0 * dx, a.1 + t0 * dy), (a.0 + t1 * dx, a.1 + t1 * dy)))
}

/// How a point is marked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mark {
    /// A filled square (a point the curve passes through).
    Square,
    /// A ring (a point the curve is drawn toward).
    Ring,
    /// A small cross (a joint of two segments).
    Cross,
}

/// A mark of radius `r` pixels centred on (x, y), inside `clip`.
pub(crate) fn mark(fb: &mut Framebuffer, clip: Rect, (x, y): (f64, f64), r: i64, kind: Mark, colour: u32) {
    if !(x.is_finite() && y.is_finite()) {
        return;
    }
    let (cx, cy) = (x.round() as i64, y.round() as i64);
    for dy in -r..=r {
        for dx in -r..=r {
            let d2 = dx * dx + dy * dy;
            let on = match kind {
                Mark::Square => true,
                Mark::Ring => d2 <= r * r && d2 >= (r - 1) * (r - 1),
                Mark::Cross => dx == dy || dx == -dy,
            };
            if on {
                plot(fb, clip, cx + dx, cy + dy, colour);
            }
        }
    }
}

/// `s` in the 8×8 font from (x, y) (its top left), clipped to `clip`;
/// characters past ASCII show as `?`. Returns the x after the text.
pub fn text(fb: &mut Framebuffer, clip: Rect, (x, y): (i64, i64), s: &str, colour: u32) -> i64 {
    let mut at = x;
    for c in s.chars() {
        let glyph = font8x8::legacy::BASIC_LEGACY[if c.is_ascii() { c as usize } else { '?' as usize }];
        for (row, bits) in glyph.iter().enumerate() {
            for col in 0..8 {
                if bits & (1 << col) != 0 {
                    plot(fb, clip, at + col, y + row as i64, colour);
                }
            }
        }
        at += CHAR;
    }
    at
}

/// `s` cut into lines of at most `width` characters at spaces (a word
/// longer than a line is cut where it must be).
pub fn wrap(s: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in s.split(' ') {
        let mut word = word.to_string();
        while word.chars().count() > width {
            if !line.is_empty() {
                lines.push(std::mem::take(&mut line));
            }
            let head: String = word.chars().take(width).collect();
            word = word.chars().skip(width).collect();
            lines.push(head);
        }
        let need = line.chars().count() + usize::from(!line.is_empty()) + word.chars().count();
        if need > width && !line.is_empty() {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// `raster` enlarged by pixel replication `zoom` times, centred in `r`.
pub fn picture(fb: &mut Framebuffer, r: Rect, raster: &Raster, zoom: i64) {
    let (w, h) = (raster.width as i64 * zoom, raster.height as i64 * zoom);
    let (left, top) = (r.x + (r.w - w).div_euclid(2), r.y + (r.h - h).div_euclid(2));
    for y in 0..h {
        for x in 0..w {
            let p = raster.pixels[(y / zoom) as usize * raster.width + (x / zoom) as usize];
            plot(fb, r, left + x, top + y, pack_rgb(p));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: Rect = Rect {
        x: 0,
        y: 0,
        w: 1024,
        h: 864,
    };

    fn lit(fb: &Framebuffer) -> usize {
        fb.pixels.iter().filter(|&&p| p != 0).count()
    }

    #[test]
    fn a_line_lights_its_length_and_is_clipped() {
        let mut fb = blank();
        line(&mut fb, ALL, (10.0, 10.0), (20.0, 10.0), 1);
        assert_eq!(lit(&fb), 11);
        assert_eq!(fb.pixel(15, 10), 1);
        let mut fb = blank();
        let clip = Rect {
            x: 0,
            y: 0,
            w: 100,
            h: 100,
        };
        line(&mut fb, clip, (-1e12, 50.0), (1e12, 50.0), 1);
        assert_eq!(lit(&fb), 100);
        line(&mut fb, clip, (f64::NAN, 0.0), (5.0, 5.0), 2);
        assert_eq!(lit(&fb), 100);
    }

    #[test]
    fn text_draws_glyphs_and_advances() {
        let mut fb = blank();
        assert_eq!(text(&mut fb, ALL, (0, 0), "AB", 7), 16);
        assert!(lit(&fb) > 10);
        assert!((0..8).any(|y| (0..8).any(|x| fb.pixel(x, y) == 7)));
        assert!((0..8).any(|y| (8..16).any(|x| fb.pixel(x, y) == 7)));
        let mut fb = blank();
        text(&mut fb, ALL, (0, 0), " ", 7);
        assert_eq!(lit(&fb), 0);
    }

    #[test]
    fn wrapping_keeps_words_whole_when_they_fit() {
        assert_eq!(wrap("one two three", 7), vec!["one two", "three"]);
        assert_eq!(wrap("abcdefghij", 4), vec!["abcd", "efgh", "ij"]);
        assert_eq!(wrap("", 4), Vec::<String>::new());
    }

    #[test]
    fn a_picture_is_replicated_and_centred() {
        let mut fb = blank();
        let raster = Raster {
            width: 2,
            height: 1,
            pixels: vec![[255, 0, 0], [0, 0, 255]],
        };
        picture(
            &mut fb,
            Rect {
                x: 0,
                y: 0,
                w: 10,
                h: 10,
            },
            &raster,
            3,
        );
        // 6×3 centred in 10×10: from (2, 3).
        assert_eq!(fb.pixel(2, 3), 0xFF0000);
        assert_eq!(fb.pixel(7, 5), 0x0000FF);
        assert_eq!(fb.pixel(1, 3), 0);
        assert_eq!(lit(&fb), 18);
    }

    #[test]
    fn an_outline_is_the_border_only() {
        let mut fb = blank();
        outline(&mut fb, Rect { x: 2, y: 3, w: 4, h: 5 }, 9);
        assert_eq!(lit(&fb), 2 * 4 + 2 * 3);
        assert_eq!((fb.pixel(2, 3), fb.pixel(5, 7), fb.pixel(3, 4)), (9, 9, 0));
    }

    #[test]
    fn marks_are_drawn_round_their_centre() {
        let mut fb = blank();
        mark(&mut fb, ALL, (10.0, 10.0), 2, Mark::Square, 5);
        assert_eq!(lit(&fb), 25);
        let mut fb = blank();
        mark(&mut fb, ALL, (10.0, 10.0), 3, Mark::Ring, 5);
        assert_eq!(fb.pixel(10, 10), 0);
        assert_eq!(fb.pixel(13, 10), 5);
    }
}

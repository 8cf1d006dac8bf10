//! The editor's screen, 1024×864 like the PS 390's (the psout screen): on
//! the left the (U, V) plane with the grid, the control points (numbered
//! from 1), the closed curve `spline` gives and its joints; for a Bezier
//! the points the curve passes through (every third) as squares and the
//! others as rings joined to them; for a key shape the pair of key shapes,
//! the expander's matches and the in-between at the time slider. On the
//! right the rendered preview and what the contour is: its kind, its
//! points and segments, whether it can be saved, and the keys. Drawn the
//! same for the window and for `--screenshot`.

use super::curve::{joints, polylines, shape};
use super::draw::{blank, fill, line, mark, outline, picture, text, wrap, Mark, Rect};
use super::keyshapes::{self, ChainView};
use super::layout::{INFO, PLANE, PREVIEW, SCREEN, SLIDER, STATUS};
use super::model::{class_word, curve_word};
use super::plane::Plane;
use super::preview::{render_pass, FINE};
use super::session::Editor;
use crate::psout::Framebuffer;
use crate::raster::Raster;
use crate::types::{CurveKind, PrimitiveClass};

const LINE_HEIGHT: i64 = 12;

/// Colours.
const PLANE_BG: u32 = 0x0C1018;
const GRID: u32 = 0x1A2230;
const AXES: u32 = 0x3A4A60;
const NEGATIVE_U: u32 = 0x1E1012;
const POLYGON: u32 = 0x40506A;
const HANDLE: u32 = 0x6A7A90;
const CURVE: u32 = 0xF0F0F0;
const JOINT: u32 = 0x50D050;
const POINT: u32 = 0xFFA040;
const TOWARD: u32 = 0x80C0FF;
const BAD: u32 = 0xFF5050;
const SELECTED: u32 = 0xFFFF40;
const NUMBER: u32 = 0x8090A0;
const FROM: u32 = 0x7A5A30;
const TO: u32 = 0x305A7A;
const MATCH: u32 = 0x505050;
const INBETWEEN: u32 = 0x30C0C0;
const TEXT: u32 = 0xC8C8C8;
const DIM: u32 = 0x808080;
const GOOD: u32 = 0x60D060;

/// What the preview box shows: the last render and its M×M rays a pixel,
/// or why there is none.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Preview {
    pub raster: Option<Raster>,
    pub mask: usize,
    /// A render that failed, or a contour that is not rendered.
    pub note: Option<String>,
}

/// The screen as the window shows it once idle: the finer preview
/// rendered at once (`contour --screenshot`, the docs' pictures).
pub fn screenshot(editor: &Editor) -> Framebuffer {
    let preview = match editor.contour.check() {
        Err(r) => Preview {
            note: Some(format!("not rendered: {r}")),
            ..Preview::default()
        },
        Ok(_) => {
            let job = editor.job();
            match render_pass(&job, FINE) {
                Ok(raster) => Preview {
                    raster: Some(raster),
                    mask: job.mask(FINE),
                    note: None,
                },
                Err(e) => Preview {
                    note: Some(e),
                    ..Preview::default()
                },
            }
        }
    };
    draw(editor, &preview)
}

/// The screen of `editor` with `preview`.
pub fn draw(editor: &Editor, preview: &Preview) -> Framebuffer {
    let mut fb = blank();
    let chain = editor.chain.map(|c| {
        keyshapes::view(
            &editor.doc.scene_with(&editor.contour),
            c,
            editor.time,
            editor.doc.fidelity,
        )
    });
    draw_plane(&mut fb, editor, chain.as_ref().and_then(|c| c.as_ref().ok()));
    draw_preview(&mut fb, preview);
    let mut y = draw_info(&mut fb, editor);
    if let Some(Err(e)) = &chain {
        for l in wrap(&format!("key shapes: {e}"), 54) {
            text(&mut fb, SCREEN, (INFO.x, y), &l, BAD);
            y += LINE_HEIGHT;
        }
    }
    if editor.chain.is_some() {
        draw_slider(&mut fb, editor);
    }
    if let Some(m) = &editor.message {
        let colour = if m.error { BAD } else { GOOD };
        for (i, l) in wrap(&m.text, 126).iter().take(2).enumerate() {
            text(&mut fb, STATUS, (8, STATUS.y + 2 + i as i64 * LINE_HEIGHT), l, colour);
        }
    }
    fb
}

/// The grid, the axes, the chain, the control polygon, the curve, the
/// joints and the points.
fn draw_plane(fb: &mut Framebuffer, editor: &Editor, chain: Option<&ChainView>) {
    let p = &editor.plane;
    let c = &editor.contour;
    fill(fb, PLANE, PLANE_BG);
    let (x0, _) = p.to_screen([0.0, 0.0]);
    if c.class == PrimitiveClass::Rotation && x0 > PLANE.x as f64 {
        let w = (x0.floor() as i64 - PLANE.x).min(PLANE.w);
        fill(fb, Rect { w, ..PLANE }, NEGATIVE_U);
    }
    draw_grid(fb, p);
    let pts = c.uv();
    let screen: Vec<(f64, f64)> = pts.iter().map(|&q| p.to_screen(q)).collect();
    let curves = |fb: &mut Framebuffer, lines: &[Vec<[f64; 2]>], colour: u32| {
        for l in lines {
            for w in l.windows(2) {
                line(fb, PLANE, p.to_screen(w[0]), p.to_screen(w[1]), colour);
            }
        }
    };
    if let Some(v) = chain {
        curves(fb, &v.from, FROM);
        curves(fb, &v.to, TO);
        for (i, (a, b)) in v.matches.iter().enumerate() {
            let (a, b) = (p.to_screen(*a), p.to_screen(*b));
            line(fb, PLANE, a, b, MATCH);
            text(
                fb,
                PLANE,
                (a.0 as i64 - 16, a.1 as i64 - 4),
                &(i + 1).to_string(),
                MATCH,
            );
        }
        curves(fb, &v.inbetween, INBETWEEN);
    }
    let n = screen.len();
    for i in 0..n {
        line(fb, PLANE, screen[i], screen[(i + 1) % n], POLYGON);
    }
    let bezier = c.curve == CurveKind::Bezier;
    if bezier {
        for k in (0..n - n % 3).step_by(3) {
            line(fb, PLANE, screen[k], screen[k + 1], HANDLE);
            line(fb, PLANE, screen[k + 2], screen[(k + 3) % (n - n % 3)], HANDLE);
        }
    }
    let sw = shape(c);
    curves(fb, &polylines(&sw.u, &sw.v), CURVE);
    for j in joints(&sw.u, &sw.v) {
        mark(fb, PLANE, p.to_screen(j), 3, Mark::Cross, JOINT);
    }
    for (k, &s) in screen.iter().enumerate() {
        let left_over = bezier && k >= n - n % 3;
        let negative = c.class == PrimitiveClass::Rotation && pts[k][0] < 0.0;
        let (kind, r, colour) = match (bezier, k % 3) {
            _ if left_over || negative => (Mark::Square, 3, BAD),
            (true, 0) => (Mark::Square, 3, POINT),
            (true, _) => (Mark::Ring, 4, TOWARD),
            (false, _) => (Mark::Ring, 4, POINT),
        };
        if editor.selected == Some(k) {
            mark(fb, PLANE, s, 7, Mark::Ring, SELECTED);
        }
        mark(fb, PLANE, s, r, kind, colour);
        text(
            fb,
            PLANE,
            (s.0 as i64 + 6, s.1 as i64 - 12),
            &(k + 1).to_string(),
            NUMBER,
        );
    }
    fill(
        fb,
        Rect {
            x: PLANE.w,
            y: 0,
            w: 1,
            h: PLANE.h,
        },
        AXES,
    );
}

/// Grid lines at the plane's step, the U and V axes brighter.
fn draw_grid(fb: &mut Framebuffer, p: &Plane) {
    let step = p.grid_step();
    let lo = p.to_plane((PLANE.x as f64, (PLANE.y + PLANE.h) as f64));
    let hi = p.to_plane(((PLANE.x + PLANE.w) as f64, PLANE.y as f64));
    for axis in 0..2 {
        let first = (lo[axis] / step).floor() as i64;
        let last = (hi[axis] / step).ceil() as i64;
        for k in first..=last {
            let at = k as f64 * step;
            let colour = if k == 0 { AXES } else { GRID };
            let (a, b) = match axis {
                0 => ([at, lo[1]], [at, hi[1]]),
                _ => ([lo[0], at], [hi[0], at]),
            };
            line(fb, PLANE, p.to_screen(a), p.to_screen(b), colour);
        }
    }
}

/// The preview's picture, enlarged to fill its box, and its pass.
fn draw_preview(fb: &mut Framebuffer, preview: &Preview) {
    fill(fb, PREVIEW, 0x000000);
    let r = PREVIEW;
    outline(
        fb,
        Rect {
            x: r.x - 1,
            y: r.y - 1,
            w: r.w + 2,
            h: r.h + 2,
        },
        AXES,
    );
    if let Some(r) = &preview.raster {
        let zoom = (PREVIEW.w / r.width.max(r.height).max(1) as i64).max(1);
        picture(fb, PREVIEW, r, zoom);
        let m = preview.mask;
        let label = format!(
            "{}x{}, {m}x{m} ray{} a pixel",
            r.width,
            r.height,
            if m == 1 { "" } else { "s" }
        );
        text(fb, SCREEN, (PREVIEW.x, PREVIEW.y + PREVIEW.h + 4), &label, DIM);
    }
    if let Some(note) = &preview.note {
        for (i, l) in wrap(note, 46).iter().enumerate() {
            text(
                fb,
                PREVIEW,
                (PREVIEW.x + 8, PREVIEW.y + 8 + i as i64 * LINE_HEIGHT),
                l,
                BAD,
            );
        }
    }
}

/// The text under the preview; returns the row after it.
fn draw_info(fb: &mut Framebuffer, editor: &Editor) -> i64 {
    let c = &editor.contour;
    let doc = &editor.doc;
    let mut lines: Vec<(String, u32)> = vec![
        (
            format!("sweep {} ({}:{})", doc.name, short(&doc.deck.name), doc.record.line),
            TEXT,
        ),
        (
            format!(
                "{} {}: {} points, {} segments",
                class_word(c.class),
                curve_word(c.curve),
                c.points.len(),
                c.segments()
            ),
            TEXT,
        ),
        (
            match c.curve {
                CurveKind::Bspline => "bspline: n >= 4 points make n segments".into(),
                CurveKind::Bezier => "bezier: 3k points make k segments; squares on it".into(),
            },
            DIM,
        ),
        (
            match c.class {
                PrimitiveClass::Rotation => "rotation about the V axis: U is the radius".into(),
                PrimitiveClass::Conic => format!("length {}, scale {}", c.length, c.scale),
                _ => format!("length {}", c.length),
            },
            DIM,
        ),
        (
            format!(
                "grid {}, {} pixels a unit, {} edit{} to undo",
                editor.plane.grid_step(),
                editor.plane.scale,
                editor.undoable(),
                if editor.undoable() == 1 { "" } else { "s" }
            ),
            DIM,
        ),
    ];
    if let Some(ch) = editor.chain {
        lines.push((
            format!(
                "key shape {} of {}, key-frame chain at t = {:.2}",
                ch.place + 1,
                ch.shapes,
                editor.time
            ),
            INBETWEEN,
        ));
    }
    lines.push((String::new(), TEXT));
    match c.check() {
        Ok(_) => lines.push(("a closed curve: s saves it".into(), GOOD)),
        Err(r) => lines.extend(wrap(&format!("cannot save: {r}"), 52).into_iter().map(|l| (l, BAD))),
    }
    lines.push((String::new(), TEXT));
    for help in [
        "click add, drag move, right click delete",
        "b bspline/bezier  k t c r sweep kind",
        "u y undo redo  x delete  + - 0 zoom  arrows pan",
        ", . time slider  s save  q quit",
    ] {
        lines.push((help.into(), DIM));
    }
    let mut y = INFO.y;
    for (l, colour) in lines {
        text(fb, INFO, (INFO.x, y), &l, colour);
        y += LINE_HEIGHT;
    }
    y
}

/// The time slider: a bar, a tick at each key shape's time, the time.
fn draw_slider(fb: &mut Framebuffer, editor: &Editor) {
    let mid = SLIDER.y + SLIDER.h / 2;
    text(fb, SCREEN, (8, mid - 4), &format!("t={:.2}", editor.time), INBETWEEN);
    fill(
        fb,
        Rect {
            x: SLIDER.x,
            y: mid,
            w: SLIDER.w,
            h: 1,
        },
        DIM,
    );
    let at = |t: f64| SLIDER.x + (t * (SLIDER.w - 1) as f64).round() as i64;
    if let Some(ch) = editor.chain {
        for k in 0..ch.shapes {
            let x = at(k as f64 / (ch.shapes - 1) as f64);
            fill(
                fb,
                Rect {
                    x,
                    y: mid - 5,
                    w: 1,
                    h: 11,
                },
                DIM,
            );
        }
    }
    let x = at(editor.time);
    fill(
        fb,
        Rect {
            x: x - 3,
            y: mid - 6,
            w: 7,
            h: 13,
        },
        INBETWEEN,
    );
}

/// A deck's name without its folders (for the info line).
fn short(name: &str) -> &str {
    name.rsplit('/').next().unwrap_or(name)
}

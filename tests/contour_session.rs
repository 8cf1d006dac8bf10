//! The contour editor's window without a window: what the mouse and the
//! keys do to the contour (a click adds, a drag moves, a right click
//! deletes), undo and redo, zoom and pan, the time slider of a key-frame
//! chain, the save and its refusals, the screen it draws, and that a
//! script's edits draw the very screen the same edits by mouse do.

use std::path::{Path, PathBuf};

use raytrace::editor::document::Document;
use raytrace::editor::layout::{PLANE, SLIDER};
use raytrace::editor::model::Edit;
use raytrace::editor::screen::{draw, Preview};
use raytrace::editor::session::{Button, Editor, Effect, Key};
use raytrace::options::Fidelity;
use raytrace::run::DeckInput;
use raytrace::types::{CurveKind, PrimitiveClass};

fn deck(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("legacy_pascal/decks")
        .join(name)
}

fn editor(file: &str, name: &str) -> Editor {
    let doc = Document::open(DeckInput::read(&deck(file)).unwrap(), name, Fidelity::Thesis).unwrap();
    Editor::new(doc)
}

/// Where point `k` (from 0) is on the screen.
fn at(e: &Editor, k: usize) -> (f64, f64) {
    let p = e.contour.points[k];
    let (x, y) = e.plane.to_screen([p.u, p.v]);
    (x.round(), y.round())
}

#[test]
fn a_drag_moves_the_point_by_the_pixels_over_the_scale() {
    let mut e = editor("fig5_6.deck", "star");
    let before = e.contour.uv()[2];
    let (x, y) = at(&e, 2);
    assert_eq!(e.mouse_down(Button::Left, (x, y)), Effect::Redraw);
    assert_eq!(e.mouse_move((x + 10.0, y)), Effect::Edited);
    assert_eq!(e.mouse_move((x + 50.0, y - 25.0)), Effect::Edited);
    assert_eq!(e.mouse_up((x + 50.0, y - 25.0)), Effect::Nothing);
    let s = e.plane.scale;
    assert_eq!(e.contour.uv()[2], [before[0] + 50.0 / s, before[1] + 25.0 / s]);
    assert_eq!(e.selected, Some(2));
    assert_eq!(e.undoable(), 1, "one drag is one edit");
    assert!(e.dirty());
    e.press(Key::Undo);
    assert_eq!(e.contour.uv()[2], before);
    assert!(!e.dirty());
}

#[test]
fn a_click_adds_between_the_nearest_pair_and_a_right_click_deletes() {
    let mut e = editor("fig5_10.deck", "last");
    // Halfway along the top side (points 1 and 2, (1, 1) and (-1, 1)), a
    // little above it.
    let (x, y) = e.plane.to_screen([0.0, 1.1]);
    assert_eq!(e.mouse_down(Button::Left, (x, y)), Effect::Nothing);
    assert_eq!(e.mouse_up((x, y)), Effect::Edited);
    assert_eq!(e.contour.points.len(), 5);
    let new = e.contour.uv()[1];
    assert!((new[0] - 0.0).abs() < 1.0 / e.plane.scale && (new[1] - 1.1).abs() < 1.0 / e.plane.scale);
    assert_eq!(e.selected, Some(1));
    let p = at(&e, 3);
    assert_eq!(e.mouse_down(Button::Right, p), Effect::Edited);
    assert_eq!(e.contour.uv(), vec![[1.0, 1.0], new, [-1.0, 1.0], [1.0, -1.0]]);
    // A right click on nothing does nothing.
    assert_eq!(e.mouse_down(Button::Right, (5.0, 5.0)), Effect::Nothing);
}

#[test]
fn a_drag_on_the_empty_plane_pans_and_adds_nothing() {
    let mut e = editor("fig5_10.deck", "last");
    let centre = e.plane.centre;
    e.mouse_down(Button::Left, (20.0, 20.0));
    assert_eq!(e.mouse_move((60.0, 20.0)), Effect::Redraw);
    e.mouse_up((60.0, 20.0));
    assert_eq!(e.contour.points.len(), 4);
    assert_eq!(e.plane.centre[0], centre[0] - 40.0 / e.plane.scale);
}

#[test]
fn the_keys_switch_the_curve_and_the_sweep_kind_and_undo_redo_them() {
    let mut e = editor("fig5_8.deck", "goblet");
    assert_eq!(e.press(Key::Curve), Effect::Edited);
    assert_eq!(e.contour.curve, CurveKind::Bspline);
    assert_eq!(e.press(Key::NextSweep), Effect::Edited);
    assert_eq!(e.contour.class, PrimitiveClass::Translation);
    assert_eq!(e.press(Key::Sweep(PrimitiveClass::Translation)), Effect::Nothing);
    assert_eq!(e.press(Key::Sweep(PrimitiveClass::Conic)), Effect::Edited);
    assert_eq!(e.undoable(), 3);
    e.press(Key::Undo);
    e.press(Key::Undo);
    assert_eq!(e.contour.class, PrimitiveClass::Rotation);
    e.press(Key::Redo);
    assert_eq!(e.contour.class, PrimitiveClass::Translation);
    assert_eq!(e.press(Key::Redo), Effect::Edited);
    assert_eq!(e.press(Key::Redo), Effect::Nothing);
}

#[test]
fn delete_takes_the_selected_point_or_says_to_click_one() {
    let mut e = editor("fig5_10.deck", "first");
    assert_eq!(e.press(Key::Delete), Effect::Redraw);
    assert!(e.message.as_ref().unwrap().error);
    let p = at(&e, 4);
    e.mouse_down(Button::Left, p);
    e.mouse_up(p);
    assert_eq!(e.press(Key::Delete), Effect::Edited);
    assert_eq!(e.contour.points.len(), 9);
    assert_eq!(e.selected, None);
}

#[test]
fn zoom_pan_and_fit_change_the_view_only() {
    let mut e = editor("fig5_8.deck", "goblet");
    let (scale, centre) = (e.plane.scale, e.plane.centre);
    assert_eq!(e.press(Key::ZoomIn), Effect::Redraw);
    assert_eq!(e.plane.scale, 2.0 * scale);
    e.press(Key::Right);
    assert!(e.plane.centre[0] > centre[0]);
    e.press(Key::Fit);
    assert_eq!((e.plane.scale, e.plane.centre), (scale, centre));
    assert_eq!(e.undoable(), 0);
}

#[test]
fn the_time_slider_moves_only_in_a_chain() {
    let mut e = editor("fig5_10.deck", "last");
    assert_eq!(e.time, 1.0, "LAST stands at the end of its pair");
    assert_eq!(e.press(Key::Earlier), Effect::Edited);
    assert_eq!(e.time, 0.95);
    let mid = SLIDER.y as f64 + SLIDER.h as f64 / 2.0;
    e.mouse_down(Button::Left, (SLIDER.x as f64, mid));
    assert_eq!(e.time, 0.0);
    e.mouse_move((SLIDER.x as f64 + (SLIDER.w - 1) as f64 / 4.0, mid));
    assert_eq!(e.time, 0.25);
    e.mouse_up((0.0, 0.0));
    assert_eq!(e.job().time, 0.25, "the preview stands at the slider's time");
    let mut g = editor("fig5_8.deck", "goblet");
    assert_eq!(g.press(Key::Later), Effect::Nothing);
}

#[test]
fn the_save_writes_the_record_or_refuses_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("d.deck");
    std::fs::copy(deck("fig5_8.deck"), &path).unwrap();
    let doc = Document::open(DeckInput::read(&path).unwrap(), "goblet", Fidelity::Thesis).unwrap();
    let mut e = Editor::new(doc);
    e.edit(Edit::Delete { k: 20 });
    assert_eq!(e.press(Key::Save), Effect::Save);
    e.save_to(&path);
    let m = e.message.clone().unwrap();
    assert!(m.error && m.text.starts_with("not saved: no closed curve"), "{m:?}");
    assert_eq!(
        std::fs::read(&path).unwrap(),
        std::fs::read(deck("fig5_8.deck")).unwrap()
    );
    e.edit(Edit::Delete { k: 19 });
    e.edit(Edit::Delete { k: 18 });
    e.save_to(&path);
    let m = e.message.clone().unwrap();
    assert!(!m.error && m.text.contains("3 lines of the record changed"), "{m:?}");
    assert!(!e.dirty());
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains("\n   { down the axis }\n"),
        "a deleted point's comment stays"
    );
    // Undos after the save put the points back (as new lines: their old
    // ones are gone), and the deck reads back as it was.
    e.press(Key::Undo);
    e.press(Key::Undo);
    e.press(Key::Undo);
    e.save_to(&path);
    let again = Document::open(DeckInput::read(&path).unwrap(), "goblet", Fidelity::Thesis).unwrap();
    let first = Document::open(
        DeckInput::read(&deck("fig5_8.deck")).unwrap(),
        "goblet",
        Fidelity::Thesis,
    )
    .unwrap();
    assert_eq!(again.original.uv(), first.original.uv());
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("{ down the axis }\n        0    1.35\n"), "{text}");
}

#[test]
fn quitting_with_unsaved_edits_asks_again() {
    let mut e = editor("fig5_8.deck", "goblet");
    assert_eq!(e.press(Key::Quit), Effect::Quit);
    e.press(Key::Curve);
    assert_eq!(e.press(Key::Quit), Effect::Redraw);
    assert_eq!(e.press(Key::Quit), Effect::Quit);
}

#[test]
fn a_scripted_edit_draws_the_screen_the_mouse_draws() {
    let mut by_mouse = editor("fig5_6.deck", "star");
    let (x, y) = at(&by_mouse, 2);
    by_mouse.mouse_down(Button::Left, (x, y));
    by_mouse.mouse_move((x + 50.0, y - 25.0));
    by_mouse.mouse_up((x + 50.0, y - 25.0));
    by_mouse.press(Key::Sweep(PrimitiveClass::Conic));
    let mut by_script = editor("fig5_6.deck", "star");
    let s = by_script.plane.scale;
    by_script.edit(Edit::Move {
        k: 2,
        du: 50.0 / s,
        dv: 25.0 / s,
    });
    by_script.edit(Edit::Sweep(PrimitiveClass::Conic));
    let none = Preview::default();
    assert_eq!(draw(&by_mouse, &none), draw(&by_script, &none));
    let untouched = draw(&editor("fig5_6.deck", "star"), &none);
    assert_ne!(draw(&by_script, &none), untouched);
}

#[test]
fn the_screen_shows_the_points_and_the_refusal() {
    let mut e = editor("fig5_10.deck", "last");
    let none = Preview::default();
    let lit = |fb: &raytrace::psout::Framebuffer| {
        let mut n = 0;
        for y in 0..PLANE.h as usize {
            for x in 0..PLANE.w as usize {
                n += usize::from(fb.pixel(x, y) == 0xFFA040);
            }
        }
        n
    };
    let four = lit(&draw(&e, &none));
    e.edit(Edit::Insert { k: 0, u: 0.0, v: 0.0 });
    assert!(lit(&draw(&e, &none)) > four, "a point is drawn for the new point");
    let ok = draw(&e, &none);
    e.edit(Edit::Curve(CurveKind::Bezier));
    let refused = draw(&e, &none);
    let red = |fb: &raytrace::psout::Framebuffer| fb.pixels.iter().filter(|&&p| p == 0xFF5050).count();
    assert!(red(&refused) > red(&ok) + 100, "the reason is written in red");
}

#[test]
fn a_script_stops_at_the_line_it_cannot_make() {
    let mut e = editor("fig5_10.deck", "last");
    let err = e.run_script("delete 1\n# a comment\ndelete 4\n", "edits").unwrap_err();
    assert_eq!(err, "edits:3: there is no point 4: the points are 1..3");
    assert_eq!(e.contour.points.len(), 3, "the edits before it are made");
    assert_eq!(e.undoable(), 1);
    assert!(e.message.is_none());
}

//! What the editor's window does with the mouse and the keys, without the
//! window: the contour, its history, the plane's view, the point last
//! edited, the key-frame time slider and the message line, and how each
//! press, drag and click changes them. The window (`src/bin/contour.rs`)
//! turns minifb's events into these calls and does what an [`Effect`]
//! asks; a script's edits go through [`Editor::edit`] as the mouse's do,
//! so that a scripted run draws the very screen the window shows.

use std::path::Path;

use super::document::Document;
use super::keyshapes::Chain;
use super::layout::{PLANE, SLIDER};
use super::model::{Contour, Edit, History, Refusal};
use super::plane::{insertion_place, Plane};
use super::preview::Job;
use crate::types::{CurveKind, PrimitiveClass};

/// How far an arrow key pans, in pixels.
pub const PAN_STEP: f64 = 64.0;

/// How far `,` and `.` move the time slider.
pub(crate) const TIME_STEP: f64 = 0.05;

/// A key of the editor's window.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    /// b: B-spline ↔ Bezier.
    Curve,
    /// k: the next sweep kind (translation → conic → rotation → …).
    NextSweep,
    /// t, c, r: this sweep kind.
    Sweep(PrimitiveClass),
    /// u (or z): undo.
    Undo,
    /// y: redo.
    Redo,
    /// x, Delete: delete the point last edited or clicked.
    Delete,
    /// + (=) and −.
    ZoomIn,
    ZoomOut,
    Left,
    Right,
    Up,
    Down,
    /// 0, Home: fit the view to the points.
    Fit,
    /// , and .: the time slider back and on.
    Earlier,
    Later,
    /// s: save into the deck.
    Save,
    /// q, Esc.
    Quit,
}

/// The window's keys, as `contour --help` lists them and the screen
/// shows them.
pub const KEYS_HELP: &str = "\
Mouse in the plane: click to add a point (between the two it is nearest to join), drag a
point to move it, right click a point to delete it, drag elsewhere to pan.
Keys in the window:
  b          B-spline or Bezier
  k          the next sweep kind; t c r translation, conic, rotation
  u y        undo, redo
  x Delete   delete the point last edited or clicked
  + - 0      zoom in, out, fit; arrows pan
  , .        a key-frame chain: the time slider back, on
  s          save the record into the deck (refused with the reason if it is no closed curve)
  q Esc      quit (twice with unsaved edits)";

/// A mouse button.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Button {
    Left,
    Right,
}

/// What the window must do after an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effect {
    Nothing,
    /// Draw the screen again.
    Redraw,
    /// The contour or the time changed: draw again and render a new preview.
    Edited,
    /// Save the deck ([`Editor::save_to`]).
    Save,
    Quit,
}

/// A line of news under the plane: a save, a refusal.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Message {
    pub text: String,
    pub error: bool,
}

/// What a mouse button held down is doing.
#[derive(Clone, Debug)]
enum Drag {
    /// Moving point `k` from `start`; `before` is the contour before the drag.
    Point {
        k: usize,
        from: (f64, f64),
        before: Contour,
        moved: bool,
    },
    /// Panning (or, released where it was pressed, a click that adds).
    Plane {
        last: (f64, f64),
        moved: bool,
    },
    Slider,
}

/// The editor's state.
#[derive(Clone, Debug)]
pub struct Editor {
    pub doc: Document,
    pub contour: Contour,
    history: History,
    pub plane: Plane,
    /// The point last edited or clicked (deleted by [`Key::Delete`]).
    pub selected: Option<usize>,
    drag: Option<Drag>,
    /// The chain the sweep is a key shape of.
    pub chain: Option<Chain>,
    /// The time slider's place (the key shape's own time at first).
    pub time: f64,
    pub message: Option<Message>,
    /// A quit was asked with unsaved edits: the next one quits.
    quit_asked: bool,
}

impl Editor {
    pub fn new(doc: Document) -> Editor {
        let contour = doc.original.clone();
        let chain = Chain::of(&doc.scene, doc.target);
        Editor {
            plane: Plane::fit(PLANE, &shown_points(&doc, chain)),
            time: chain.map_or(0.0, |c| c.key_time()),
            chain,
            contour,
            history: History::default(),
            selected: None,
            drag: None,
            message: None,
            quit_asked: false,
            doc,
        }
    }

    /// Makes `edit` as an undoable step; the point it moves or adds is
    /// then the one selected. A refused edit leaves the contour and says why.
    pub fn edit(&mut self, edit: Edit) -> Effect {
        let before = self.contour.clone();
        match self.contour.apply(edit) {
            Ok(()) => {
                self.history.push(before);
                self.selected = match edit {
                    Edit::Move { k, .. } | Edit::Insert { k, .. } => Some(k),
                    Edit::Delete { .. } => None,
                    _ => self.selected,
                };
                self.message = None;
                Effect::Edited
            }
            Err(r) => self.refuse(r),
        }
    }

    /// Makes the edits of a script ([`super::script`]) one by one as
    /// [`Editor::edit`] does; the first that cannot be parsed or made is an
    /// error at `FILE:LINE`, the edits before it made.
    pub fn run_script(&mut self, text: &str, file: &str) -> Result<(), String> {
        for line in super::script::parse(text, file)? {
            self.edit(line.edit);
            if let Some(m) = self.message.take() {
                return Err(format!("{file}:{}: {}", line.line, m.text));
            }
        }
        Ok(())
    }

    fn refuse(&mut self, r: Refusal) -> Effect {
        self.message = Some(Message { text: r.0, error: true });
        Effect::Redraw
    }

    /// Whether the contour differs from the deck's.
    pub fn dirty(&self) -> bool {
        self.contour.uv() != self.doc.original.uv()
            || self.contour.curve != self.doc.original.curve
            || self.contour.class != self.doc.original.class
    }

    /// How many edits can be undone.
    pub fn undoable(&self) -> usize {
        self.history.depth()
    }

    /// What the preview renders now.
    pub fn job(&self) -> Job {
        Job::new(&self.doc, &self.contour, self.time)
    }

    pub fn press(&mut self, key: Key) -> Effect {
        if key != Key::Quit {
            self.quit_asked = false;
        }
        let kind = |c: PrimitiveClass| match c {
            PrimitiveClass::Translation => PrimitiveClass::Conic,
            PrimitiveClass::Conic => PrimitiveClass::Rotation,
            _ => PrimitiveClass::Translation,
        };
        match key {
            Key::Curve => self.edit(Edit::Curve(match self.contour.curve {
                CurveKind::Bspline => CurveKind::Bezier,
                CurveKind::Bezier => CurveKind::Bspline,
            })),
            Key::NextSweep => self.edit(Edit::Sweep(kind(self.contour.class))),
            Key::Sweep(c) if c == self.contour.class => Effect::Nothing,
            Key::Sweep(c) => self.edit(Edit::Sweep(c)),
            Key::Undo | Key::Redo => {
                let step = match key {
                    Key::Undo => self.history.undo(&self.contour),
                    _ => self.history.redo(&self.contour),
                };
                match step {
                    Some(c) => {
                        self.contour = c;
                        self.selected = self.selected.filter(|&k| k < self.contour.points.len());
                        self.message = None;
                        Effect::Edited
                    }
                    None => Effect::Nothing,
                }
            }
            Key::Delete => match self.selected {
                Some(k) => self.edit(Edit::Delete { k }),
                None => self.refuse(Refusal(
                    "click a point first: x deletes the point last edited or clicked".into(),
                )),
            },
            Key::ZoomIn | Key::ZoomOut => {
                self.plane.zoom(if key == Key::ZoomIn { 2.0 } else { 0.5 });
                Effect::Redraw
            }
            Key::Left | Key::Right | Key::Up | Key::Down => {
                let (dx, dy) = match key {
                    Key::Left => (-PAN_STEP, 0.0),
                    Key::Right => (PAN_STEP, 0.0),
                    Key::Up => (0.0, -PAN_STEP),
                    _ => (0.0, PAN_STEP),
                };
                self.plane.pan((dx, dy));
                Effect::Redraw
            }
            Key::Fit => {
                let mut points = shown_points(&self.doc, self.chain);
                points.extend(self.contour.uv());
                self.plane = Plane::fit(PLANE, &points);
                Effect::Redraw
            }
            Key::Earlier | Key::Later => {
                let step = if key == Key::Later { TIME_STEP } else { -TIME_STEP };
                self.set_time(self.time + step)
            }
            Key::Save => Effect::Save,
            Key::Quit if self.dirty() && !self.quit_asked => {
                self.quit_asked = true;
                self.message = Some(Message {
                    text: "the edits are not saved: q again quits without them, s saves".into(),
                    error: true,
                });
                Effect::Redraw
            }
            Key::Quit => Effect::Quit,
        }
    }

    /// Moves the time slider (a key-frame chain only), to 0..1 rounded to
    /// a hundredth.
    fn set_time(&mut self, time: f64) -> Effect {
        if self.chain.is_none() {
            return Effect::Nothing;
        }
        let time = ((time.clamp(0.0, 1.0)) * 100.0).round() / 100.0;
        if time == self.time {
            return Effect::Nothing;
        }
        self.time = time;
        Effect::Edited
    }

    /// The slider's time under screen column `x`.
    fn slider_time(x: f64) -> f64 {
        (x - SLIDER.x as f64) / (SLIDER.w - 1) as f64
    }

    pub fn mouse_down(&mut self, button: Button, at: (f64, f64)) -> Effect {
        self.quit_asked = false;
        let hit = self
            .plane
            .point_at(&self.contour.uv(), at)
            .filter(|_| PLANE.holds(at.0, at.1));
        match button {
            Button::Right => match hit {
                Some(k) => self.edit(Edit::Delete { k }),
                None => Effect::Nothing,
            },
            Button::Left if self.chain.is_some() && SLIDER.holds(at.0, at.1) => {
                self.drag = Some(Drag::Slider);
                self.set_time(Editor::slider_time(at.0))
            }
            Button::Left => {
                if let Some(k) = hit {
                    self.selected = Some(k);
                    self.drag = Some(Drag::Point {
                        k,
                        from: at,
                        before: self.contour.clone(),
                        moved: false,
                    });
                    Effect::Redraw
                } else if PLANE.holds(at.0, at.1) {
                    self.drag = Some(Drag::Plane { last: at, moved: false });
                    Effect::Nothing
                } else {
                    Effect::Nothing
                }
            }
        }
    }

    pub fn mouse_move(&mut self, at: (f64, f64)) -> Effect {
        match &mut self.drag {
            Some(Drag::Point { k, from, before, moved }) => {
                let [du, dv] = self.plane.delta((at.0 - from.0, at.1 - from.1));
                let mut c = before.clone();
                if c.apply(Edit::Move { k: *k, du, dv }).is_err() || c == self.contour {
                    return Effect::Nothing;
                }
                if !*moved {
                    *moved = true;
                    self.history.push(before.clone());
                }
                self.contour = c;
                self.message = None;
                Effect::Edited
            }
            Some(Drag::Plane { last, moved }) => {
                let d = (last.0 - at.0, last.1 - at.1);
                if d == (0.0, 0.0) {
                    return Effect::Nothing;
                }
                *last = at;
                *moved = true;
                self.plane.pan(d);
                Effect::Redraw
            }
            Some(Drag::Slider) => self.set_time(Editor::slider_time(at.0)),
            None => Effect::Nothing,
        }
    }

    pub fn mouse_up(&mut self, at: (f64, f64)) -> Effect {
        match self.drag.take() {
            Some(Drag::Plane { moved: false, .. }) => {
                let uv = self.plane.to_plane(at);
                let k = insertion_place(&self.contour.uv(), uv);
                self.edit(Edit::Insert { k, u: uv[0], v: uv[1] })
            }
            _ => Effect::Nothing,
        }
    }

    /// Saves the contour into the deck at `path` (atomically), or refuses
    /// with the reason and writes nothing; the message line tells which.
    pub fn save_to(&mut self, path: &Path) -> Effect {
        let bytes = match self.doc.save(&self.contour) {
            Ok(bytes) => bytes,
            Err(r) => return self.refuse(Refusal(format!("not saved: {r}"))),
        };
        let written =
            crate::output::write_atomically(path, |w| w.write_all(&bytes).map_err(crate::output::OutputError::from));
        if let Err(e) = written {
            return self.refuse(Refusal(format!("not saved: {}: {e}", path.display())));
        }
        let changed = changed_lines(&self.doc.deck.source, &bytes);
        if let Err(r) = self.doc.saved(bytes, &self.contour) {
            return self.refuse(r);
        }
        self.message = Some(Message {
            text: format!("saved {} ({changed})", path.display()),
            error: false,
        });
        Effect::Redraw
    }
}

/// The points the view first shows: the sweep's, or every key shape's
/// of its chain.
fn shown_points(doc: &Document, chain: Option<Chain>) -> Vec<[f64; 2]> {
    let Some(ch) = chain else {
        return doc.original.uv();
    };
    super::keyshapes::key_shapes(&doc.scene, ch.record)
        .into_iter()
        .flat_map(|sw| sw.points.clone())
        .collect()
}

/// "N lines changed" between two texts (lines at the same place that
/// differ, and lines one has beyond the other).
fn changed_lines(a: &[u8], b: &[u8]) -> String {
    let (a, b): (Vec<&[u8]>, Vec<&[u8]>) = (a.split(|&c| c == b'\n').collect(), b.split(|&c| c == b'\n').collect());
    let head = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let tail = a[head..]
        .iter()
        .rev()
        .zip(b[head..].iter().rev())
        .take_while(|(x, y)| x == y)
        .count();
    let n = (a.len() - head - tail).max(b.len() - head - tail);
    format!("{n} line{} of the record changed", if n == 1 { "" } else { "s" })
}

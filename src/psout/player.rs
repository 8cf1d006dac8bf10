//! What psout's window does with its keys and its clock, without the
//! window: the state of the screen (which frame, zoom, pan, paused) and how
//! each key press and each tick of time changes it. The window
//! (`src/bin/psout.rs`) only turns minifb's key events into [`Key`]s,
//! draws, and does the file work an [`Effect`] asks for.
//!
//! Playing a film (a sequence of rasters, [`crate::film`]) is the port's
//! extension: the thesis only says psout sent a raster to the PS 390
//! (Ch. 4 (二), Fig. 4.1).

use std::path::Path;
use std::time::Duration;

use super::{placement, MAX_ZOOM};

/// How far an arrow key pans, in screen pixels.
pub const PAN_STEP: i64 = 32;

/// A key of the window, as psout reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    /// q or Esc.
    Quit,
    /// Space.
    Pause,
    Left,
    Right,
    Up,
    Down,
    Home,
    End,
    /// + (or =, its key on most layouts).
    ZoomIn,
    /// −.
    ZoomOut,
    /// n.
    Next,
    /// p.
    Previous,
    /// s.
    Save,
}

/// The window's keys, as `psout --help` lists them.
pub const KEYS_HELP: &str = "\
Keys in the window:
  space      pause or play a film
  ← →        a paused film: the previous or next frame; a still wider than the screen: pan
  ↑ ↓        pan a raster taller than the screen
  Home End   a film: the first or last frame
  + −        zoom in or out (1× to 3×)
  n p        a still: the next or previous raster file in its folder
  s          save the screen as <raster>.psout.png beside the raster
  q Esc      quit";

/// The key presses since the last frame, in order, gathered from key
/// events: a key pressed and released between two frames is still one
/// press (the window's per-frame key state would have lost it).
#[derive(Debug)]
pub struct KeyQueue<K> {
    presses: Vec<K>,
}

impl<K> Default for KeyQueue<K> {
    fn default() -> Self {
        KeyQueue { presses: Vec::new() }
    }
}

impl<K> KeyQueue<K> {
    /// One key event: `down` for a press (auto-repeat sends more), false
    /// for a release, which changes nothing already queued.
    pub fn event(&mut self, key: K, down: bool) {
        if down {
            self.presses.push(key);
        }
    }

    /// The presses queued so far, oldest first; the queue is left empty.
    pub fn take(&mut self) -> Vec<K> {
        std::mem::take(&mut self.presses)
    }
}

/// What the window must do after a key press.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Effect {
    /// Nothing changed.
    Nothing,
    /// Draw the screen again (frame, zoom or pan changed) and set the title.
    Redraw,
    /// Load the next (true) or previous raster of the folder.
    Neighbour(bool),
    /// Save the screen.
    Save,
    /// Close the window.
    Quit,
}

/// The screen's state: a still (one raster) or a film of `frames` rasters
/// of one size, played at `rate` frames a second.
#[derive(Clone, Debug, PartialEq)]
pub struct Player {
    frames: usize,
    /// The frame shown, 0-based.
    current: usize,
    paused: bool,
    rate: u32,
    /// Time since the frame shown was put up.
    shown_for: Duration,
    width: usize,
    height: usize,
    /// `--zoom`, kept for the rasters n and p load.
    fixed_zoom: Option<u32>,
    zoom: u32,
    pan: (i64, i64),
}

impl Player {
    /// `frames` rasters (1 for a still) of `width`×`height`, shown at
    /// `zoom` (default: the largest that fits), playing from the first.
    pub fn new(frames: usize, width: usize, height: usize, zoom: Option<u32>, rate: u32) -> Player {
        Player {
            frames: frames.max(1),
            current: 0,
            paused: false,
            rate: rate.max(1),
            shown_for: Duration::ZERO,
            width,
            height,
            fixed_zoom: zoom,
            zoom: placement(width, height, zoom, (0, 0)).zoom,
            pan: (0, 0),
        }
    }

    /// Whether it shows a film (more than one frame).
    pub fn is_film(&self) -> bool {
        self.frames > 1
    }

    /// The frame shown, 0-based.
    pub fn current(&self) -> usize {
        self.current
    }

    pub fn paused(&self) -> bool {
        self.paused
    }

    pub fn zoom(&self) -> u32 {
        self.zoom
    }

    /// The pan, clamped as [`placement`] applies it.
    pub fn pan(&self) -> (i64, i64) {
        self.pan
    }

    /// Shows frame `index` (0-based, clamped to the film) and pauses there.
    pub fn show_paused(&mut self, index: usize) {
        self.current = index.min(self.frames - 1);
        self.paused = true;
        self.shown_for = Duration::ZERO;
    }

    /// A new still of `width`×`height` took the screen (n or p): the zoom
    /// as at the start, no pan.
    pub fn replaced(&mut self, width: usize, height: usize) {
        (self.width, self.height) = (width, height);
        self.zoom = placement(width, height, self.fixed_zoom, (0, 0)).zoom;
        self.pan = (0, 0);
    }

    /// One key press.
    pub fn press(&mut self, key: Key) -> Effect {
        let before = self.clone();
        match key {
            Key::Quit => return Effect::Quit,
            Key::Save => return Effect::Save,
            Key::Next | Key::Previous if !self.is_film() => return Effect::Neighbour(key == Key::Next),
            Key::Next | Key::Previous => {}
            Key::Pause if self.is_film() => {
                self.paused = !self.paused;
                self.shown_for = Duration::ZERO;
            }
            Key::Pause => {}
            Key::Left | Key::Right if self.is_film() => {
                if self.paused {
                    self.step(key == Key::Right);
                }
            }
            Key::Left => self.pan.0 -= PAN_STEP,
            Key::Right => self.pan.0 += PAN_STEP,
            Key::Up => self.pan.1 -= PAN_STEP,
            Key::Down => self.pan.1 += PAN_STEP,
            Key::Home => self.current = 0,
            Key::End => self.current = self.frames - 1,
            Key::ZoomIn => self.zoom = (self.zoom + 1).min(MAX_ZOOM),
            Key::ZoomOut => self.zoom = self.zoom.saturating_sub(1).max(1),
        }
        // Keep the clamped pan, so arrows pressed at an edge (or on a
        // raster that fits) do not pile up an offset later keys must undo.
        self.pan = placement(self.width, self.height, Some(self.zoom), self.pan).pan;
        if *self == before {
            Effect::Nothing
        } else {
            Effect::Redraw
        }
    }

    /// The previous or next frame, wrapping around.
    fn step(&mut self, forward: bool) {
        let n = self.frames;
        self.current = if forward {
            (self.current + 1) % n
        } else {
            (self.current + n - 1) % n
        };
    }

    /// `elapsed` has passed: a playing film moves on by whole frames at its
    /// rate, forward, and after the last from the first again. True if the
    /// frame changed.
    pub fn tick(&mut self, elapsed: Duration) -> bool {
        if !self.is_film() || self.paused {
            return false;
        }
        let period = Duration::from_secs(1) / self.rate;
        self.shown_for += elapsed;
        let before = self.current;
        while self.shown_for >= period {
            self.shown_for -= period;
            self.step(true);
        }
        self.current != before
    }

    /// The window title: [`super::title`], then for a film `frame k/F`
    /// and `paused` when it is.
    pub fn title(&self, path: &Path, lut: Option<usize>) -> String {
        let mut t = super::title(path, self.width, self.height, self.zoom, lut);
        if self.is_film() {
            t.push_str(&format!(" frame {}/{}", self.current + 1, self.frames));
            if self.paused {
                t.push_str(" paused");
            }
        }
        t
    }
}

//! The editor's window: minifb's keys and mouse turned into the calls of
//! `raytrace::editor::session::Editor`, the preview thread fed with each
//! edit, and the screen drawn again when anything changed. Nothing is
//! decided here.

use std::cell::RefCell;
use std::path::Path;
use std::rc::Rc;

use minifb::{Key as K, MouseButton, MouseMode, Window, WindowOptions};
use raytrace::editor::screen::{self, Preview};
use raytrace::editor::session::{Button, Editor, Effect, Key};
use raytrace::editor::worker::Worker;
use raytrace::psout::player::KeyQueue;
use raytrace::psout::{window_error, SCREEN_HEIGHT, SCREEN_WIDTH};
use raytrace::types::PrimitiveClass;

/// Why the window stopped.
pub enum Error {
    /// It could not be opened.
    Open(String),
    /// It failed while open.
    Failed(String),
}

/// Key events from minifb into a queue (a press between two frames is kept).
struct KeyEvents(Rc<RefCell<KeyQueue<K>>>);

impl minifb::InputCallback for KeyEvents {
    fn add_char(&mut self, _uni_char: u32) {}

    fn set_key_state(&mut self, key: K, state: bool) {
        self.0.borrow_mut().event(key, state);
    }
}

/// The editor's key for a minifb key.
fn editor_key(key: K) -> Option<Key> {
    Some(match key {
        K::B => Key::Curve,
        K::K => Key::NextSweep,
        K::T => Key::Sweep(PrimitiveClass::Translation),
        K::C => Key::Sweep(PrimitiveClass::Conic),
        K::R => Key::Sweep(PrimitiveClass::Rotation),
        K::U | K::Z => Key::Undo,
        K::Y => Key::Redo,
        K::X | K::Delete | K::Backspace => Key::Delete,
        // `+` shares its key with `=` on most layouts.
        K::Equal | K::NumPadPlus => Key::ZoomIn,
        K::Minus | K::NumPadMinus => Key::ZoomOut,
        K::Key0 | K::Home => Key::Fit,
        K::Left => Key::Left,
        K::Right => Key::Right,
        K::Up => Key::Up,
        K::Down => Key::Down,
        K::Comma => Key::Earlier,
        K::Period => Key::Later,
        K::S => Key::Save,
        K::Q | K::Escape => Key::Quit,
        _ => return None,
    })
}

/// The window's title: the deck, the sweep, and a star for unsaved edits.
fn title(editor: &Editor) -> String {
    let star = if editor.dirty() { " *" } else { "" };
    format!("contour — {}: {}{star}", editor.doc.deck.name, editor.doc.name)
}

/// The mouse as the last frame saw it.
#[derive(Default)]
struct Mouse {
    at: Option<(f64, f64)>,
    left: bool,
    right: bool,
}

/// Runs the window until q (or the window is closed); `s` saves into `deck`.
pub fn run(mut editor: Editor, deck: &Path) -> Result<(), Error> {
    let mut window = Window::new(&title(&editor), SCREEN_WIDTH, SCREEN_HEIGHT, WindowOptions::default())
        .map_err(|e| Error::Open(window_error(e)))?;
    window.set_target_fps(60);
    let queue = Rc::new(RefCell::new(KeyQueue::default()));
    window.set_input_callback(Box::new(KeyEvents(queue.clone())));
    let worker = Worker::editor();
    let mut revision = 0;
    let mut preview = Preview::default();
    let submit = |editor: &Editor, preview: &mut Preview, revision: &mut u64| {
        *revision += 1;
        match editor.contour.check() {
            Ok(_) => worker.submit(*revision, editor.job()),
            Err(_) => preview.note = Some("the contour is refused (see below): the last good one shown".into()),
        }
    };
    submit(&editor, &mut preview, &mut revision);
    let mut screen = screen::draw(&editor, &preview);
    let mut mouse = Mouse::default();
    while window.is_open() {
        let mut effects = Vec::new();
        for key in queue.borrow_mut().take().into_iter().filter_map(editor_key) {
            effects.push(editor.press(key));
        }
        effects.extend(mouse_events(&window, &mut mouse, &mut editor));
        let mut changed = false;
        for effect in effects {
            match effect {
                Effect::Quit => return Ok(()),
                Effect::Save => {
                    editor.save_to(deck);
                    changed = true;
                }
                Effect::Edited => {
                    submit(&editor, &mut preview, &mut revision);
                    changed = true;
                }
                Effect::Redraw => changed = true,
                Effect::Nothing => {}
            }
        }
        for done in worker.finished().into_iter().filter(|d| d.revision == revision) {
            match done.result {
                Ok(raster) => {
                    preview = Preview {
                        raster: Some(raster),
                        mask: editor.job().mask(done.pass),
                        note: None,
                    }
                }
                Err(e) => preview.note = Some(e),
            }
            changed = true;
        }
        if changed {
            screen = screen::draw(&editor, &preview);
            window.set_title(&title(&editor));
        }
        window
            .update_with_buffer(&screen.pixels, SCREEN_WIDTH, SCREEN_HEIGHT)
            .map_err(|e| Error::Failed(window_error(e)))?;
    }
    Ok(())
}

/// The mouse's presses, moves and releases since the last frame.
fn mouse_events(window: &Window, mouse: &mut Mouse, editor: &mut Editor) -> Vec<Effect> {
    let mut effects = Vec::new();
    let at = window
        .get_mouse_pos(MouseMode::Discard)
        .map(|(x, y)| (f64::from(x), f64::from(y)));
    let (left, right) = (
        window.get_mouse_down(MouseButton::Left),
        window.get_mouse_down(MouseButton::Right),
    );
    if let Some(at) = at.or(mouse.at) {
        if at != mouse.at.unwrap_or(at) && mouse.left {
            effects.push(editor.mouse_move(at));
        }
        if left && !mouse.left {
            effects.push(editor.mouse_down(Button::Left, at));
        }
        if !left && mouse.left {
            effects.push(editor.mouse_move(at));
            effects.push(editor.mouse_up(at));
        }
        if right && !mouse.right {
            effects.push(editor.mouse_down(Button::Right, at));
        }
    }
    *mouse = Mouse {
        at: at.or(mouse.at),
        left,
        right,
    };
    effects
}

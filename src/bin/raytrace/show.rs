//! `raytrace --show` and `--watch`: the window (psout's 1024×864 screen)
//! that fills with rows as they finish (`raytrace::show` renders the
//! bands), stays until a key, and under `--watch` waits for the deck file
//! to change. Nothing is decided here but what the window's keys mean.

use raytrace::cli::RenderArgs;
use raytrace::exit::Failure;
use raytrace::options::{Options, TimeSampler};
use raytrace::psout;
use raytrace::raytrace::Prepared;
use raytrace::run::DeckInput;
#[cfg(not(feature = "window"))]
use raytrace::run::Rendered;
use raytrace::show::quick_size;

/// The error when no window can be opened (as psout gives it).
pub fn no_display(reason: &str) -> Failure {
    Failure::other(psout::no_display_message(
        "raytrace",
        reason,
        "render without --show or --watch and look at the raster with `psout FILE` (or `psout --screenshot OUT.png FILE`)",
    ))
}

/// The quick pass of `--watch`: the deck at a quarter of its size (or of
/// --size) on each side, one ray a pixel, the thesis's time table.
pub fn quick(render: &RenderArgs, deck: &DeckInput, opts: &Options) -> Result<Prepared, Failure> {
    let mut scene = deck.initialize(opts.fidelity)?;
    let (w, h) = render.size.unwrap_or((scene.image.width, scene.image.height));
    let (w, h, m) = quick_size(w, h);
    scene.resize(w, h, m);
    let opts = Options {
        sampler: TimeSampler::Table,
        ..*opts
    };
    Prepared::new(scene, opts).map_err(Failure::input)
}

/// The window's title while `--watch` waits for the deck to change: with
/// the last error, until a good deck clears it.
#[cfg(any(feature = "window", test))]
pub fn watching_title(deck: &str, error: Option<&str>) -> String {
    match error {
        None => format!("raytrace — {deck}: watching for changes, q quits"),
        Some(e) => format!("raytrace — {deck}: ERROR {e} — fix the deck; watching for changes, q quits"),
    }
}

/// Lines of the error on the screen, at most: the rest is cut.
#[cfg(any(feature = "window", test))]
const ERROR_LINES: usize = 4;

/// The error of a deck that failed under `--watch`, over the bottom of the
/// screen: white on dark red, wrapped to the screen's width, the last
/// picture left above it.
#[cfg(any(feature = "window", test))]
pub fn overlay_error(fb: &mut psout::Framebuffer, error: &str) {
    use raytrace::editor::draw::{fill, text, wrap, Rect, CHAR};
    let margin = CHAR;
    let width = (fb.width as i64 - 2 * margin) / CHAR;
    let mut lines = wrap(&format!("raytrace: {error}"), width.max(1) as usize);
    lines.truncate(ERROR_LINES);
    let high = (lines.len() as i64 + 1) * (CHAR + 4);
    let band = Rect {
        x: 0,
        y: fb.height as i64 - high,
        w: fb.width as i64,
        h: high,
    };
    fill(fb, band, psout::pack_rgb([110, 0, 0]));
    for (i, line) in lines.iter().enumerate() {
        let y = band.y + (CHAR + 4) / 2 + i as i64 * (CHAR + 4);
        text(fb, band, (margin, y), line, psout::pack_rgb([255, 255, 255]));
    }
}

#[cfg(not(feature = "window"))]
pub struct Screen;

#[cfg(not(feature = "window"))]
impl Screen {
    pub fn open(_deck: &str, _watched: Option<std::path::PathBuf>) -> Result<Screen, Failure> {
        Err(no_display("this raytrace was built without the `window` feature"))
    }
    pub fn render(
        &mut self,
        _p: &Prepared,
        _r: &raytrace::raytrace::Request,
        _pool: &rayon::ThreadPool,
        _what: &str,
    ) -> Rendered {
        Rendered::Quit
    }
    pub fn quick(&mut self, _p: &Prepared, _size: (usize, usize)) {}
    pub fn failed(&mut self, _error: &str) {}
    pub fn hold(&mut self) {}
    pub fn wait_for_change(&mut self) -> bool {
        false
    }
}

#[cfg(feature = "window")]
pub use window::Screen;

#[cfg(feature = "window")]
mod window {
    use std::path::PathBuf;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::mpsc::channel;
    use std::time::SystemTime;

    use std::cell::RefCell;
    use std::rc::Rc;

    use minifb::{Key, Window, WindowOptions};
    use raytrace::exit::Failure;
    use raytrace::psout::player::KeyQueue;
    use raytrace::psout::{self, SCREEN_HEIGHT, SCREEN_WIDTH};
    use raytrace::raytrace::{Prepared, Request};
    use raytrace::show::{render_in_bands, stamp, Progressive};

    use super::{no_display, overlay_error, watching_title};
    use raytrace::run::Rendered;

    /// The window, the picture so far, and the deck it watches.
    pub struct Screen {
        window: Window,
        picture: Progressive,
        screen: Vec<u32>,
        deck: String,
        watched: Option<(PathBuf, Option<(SystemTime, u64)>)>,
        /// The window was closed (a --show render goes on without it).
        closed: bool,
        /// The keys pressed since the last look (a press and release
        /// between two frames is still a press).
        keys: Rc<RefCell<KeyQueue<Key>>>,
        /// The last deck's error under --watch, shown until a deck is good.
        error: Option<String>,
    }

    /// Key events from minifb into the queue.
    struct KeyEvents(Rc<RefCell<KeyQueue<Key>>>);

    impl minifb::InputCallback for KeyEvents {
        fn add_char(&mut self, _uni_char: u32) {}

        fn set_key_state(&mut self, key: Key, state: bool) {
            self.0.borrow_mut().event(key, state);
        }
    }

    /// What a look at the window finds.
    enum Look {
        Nothing,
        Quit,
        AnyKey,
    }

    impl Screen {
        pub fn open(deck: &str, watched: Option<PathBuf>) -> Result<Screen, Failure> {
            let mut window = Window::new(
                &format!("raytrace — {deck}"),
                SCREEN_WIDTH,
                SCREEN_HEIGHT,
                WindowOptions::default(),
            )
            .map_err(|e| no_display(&psout::window_error(e)))?;
            window.set_target_fps(60);
            let keys = Rc::new(RefCell::new(KeyQueue::default()));
            window.set_input_callback(Box::new(KeyEvents(keys.clone())));
            Ok(Screen {
                keys,
                window,
                picture: Progressive::new(0, 0),
                screen: vec![0; SCREEN_WIDTH * SCREEN_HEIGHT],
                deck: deck.to_string(),
                watched: watched.map(|p| {
                    let s = stamp(&p);
                    (p, s)
                }),
                closed: false,
                error: None,
            })
        }

        /// Draws the picture so far and reads the keys.
        fn look(&mut self, redraw: bool) -> Look {
            if self.closed {
                return Look::Nothing;
            }
            if !self.window.is_open() {
                self.closed = true;
                return Look::Quit;
            }
            if redraw {
                let mut fb = psout::compose(&self.picture.raster, None, (0, 0));
                if let Some(e) = &self.error {
                    overlay_error(&mut fb, e);
                }
                self.screen = fb.pixels;
            }
            if self
                .window
                .update_with_buffer(&self.screen, SCREEN_WIDTH, SCREEN_HEIGHT)
                .is_err()
            {
                self.closed = true;
                return Look::Quit;
            }
            let keys = self.keys.borrow_mut().take();
            if keys.iter().any(|k| matches!(k, Key::Q | Key::Escape)) {
                Look::Quit
            } else if keys.is_empty() {
                Look::Nothing
            } else {
                Look::AnyKey
            }
        }

        /// Whether the watched deck changed since it was last rendered
        /// (and then its new stamp is kept).
        fn deck_changed(&mut self) -> bool {
            let Some((path, last)) = &mut self.watched else {
                return false;
            };
            let now = stamp(path);
            if now.is_some() && now != *last {
                *last = now;
                return true;
            }
            false
        }

        /// The quick pass, shown enlarged to `size` (the render's) until
        /// the bands replace it.
        pub fn quick(&mut self, prepared: &Prepared, (w, h): (usize, usize)) {
            // The deck is good again: its error goes.
            self.error = None;
            if let Ok(r) = raytrace::raytrace::render(prepared, &Request::STILL) {
                if (self.picture.raster.width, self.picture.raster.height) != (w, h) {
                    self.picture = Progressive::new(w, h);
                }
                self.picture.fill_from(&r.raster);
                self.look(true);
            }
        }

        /// Renders `request` band by band on `pool`, each band shown as it
        /// comes; q stops it, and under --watch so does a change of the deck.
        pub fn render(
            &mut self,
            prepared: &Prepared,
            request: &Request,
            pool: &rayon::ThreadPool,
            what: &str,
        ) -> Rendered {
            let img = &prepared.scene().image;
            if (self.picture.raster.width, self.picture.raster.height) != (img.width, img.height) {
                self.picture = Progressive::new(img.width, img.height);
            }
            if !self.closed {
                self.window.set_title(&format!("raytrace — {what}"));
            }
            let stop = AtomicBool::new(false);
            let (bands, inbox) = channel();
            let mut stopped = None;
            let result = std::thread::scope(|s| {
                let worker = s.spawn(|| {
                    pool.install(|| {
                        render_in_bands(prepared, request, |band| {
                            let _ = bands.send(band.clone());
                            !stop.load(Ordering::Relaxed)
                        })
                    })
                });
                loop {
                    let mut redraw = false;
                    for band in inbox.try_iter() {
                        self.picture.band(&band);
                        redraw = true;
                    }
                    let quit = matches!(self.look(redraw), Look::Quit) && (!self.closed || self.watched.is_some());
                    if stopped.is_none() && (quit || self.deck_changed()) {
                        stopped = Some(if quit { Rendered::Quit } else { Rendered::Changed });
                        stop.store(true, Ordering::Relaxed);
                    }
                    if worker.is_finished() {
                        break;
                    }
                }
                worker.join()
            });
            for band in inbox.try_iter() {
                self.picture.band(&band);
            }
            self.look(true);
            match (stopped, result) {
                (Some(s), _) => s,
                (None, Ok(Ok(Some(r)))) => Rendered::Done(Ok(r)),
                (None, Ok(Ok(None))) => Rendered::Quit,
                (None, Ok(Err(e))) => Rendered::Done(Err(e)),
                (None, Err(panic)) => std::panic::resume_unwind(panic),
            }
        }

        /// Keeps the window until a key is pressed or it is closed.
        pub fn hold(&mut self) {
            self.window
                .set_title(&format!("raytrace — {}: done, a key closes", self.deck));
            while !matches!(self.look(false), Look::Quit | Look::AnyKey) && !self.closed {}
        }

        /// Shows a deck's error (under --watch: the last picture stays)
        /// in the title and over the bottom of the screen.
        pub fn failed(&mut self, error: &str) {
            self.error = Some(error.to_string());
            self.look(true);
        }

        /// Waits until the watched deck changes (`true`) or q, Esc or the
        /// window's closing ends the watch (`false`).
        pub fn wait_for_change(&mut self) -> bool {
            self.window
                .set_title(&watching_title(&self.deck, self.error.as_deref()));
            loop {
                if matches!(self.look(false), Look::Quit) || self.closed {
                    return false;
                }
                if self.deck_changed() {
                    return true;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The error is in the title and over the screen's bottom rows, and a
    /// good deck's title has none.
    #[test]
    fn a_deck_error_shows_in_the_title_and_over_the_picture() {
        let e = "w.deck:3:1: unknown record 'sphre' — did you mean 'sphere'?";
        assert_eq!(
            watching_title("w.deck", Some(e)),
            format!("raytrace — w.deck: ERROR {e} — fix the deck; watching for changes, q quits")
        );
        assert_eq!(
            watching_title("w.deck", None),
            "raytrace — w.deck: watching for changes, q quits"
        );
        let picture = raytrace::raster::Raster {
            width: 4,
            height: 4,
            pixels: vec![[0, 200, 0]; 16],
        };
        let clean = psout::compose(&picture, None, (0, 0));
        let mut fb = clean.clone();
        overlay_error(&mut fb, e);
        let w = fb.width;
        let changed: Vec<usize> = (0..fb.pixels.len())
            .filter(|&i| fb.pixels[i] != clean.pixels[i])
            .collect();
        // Only the bottom band changes: one line of text and its margins.
        assert!(
            changed.iter().all(|&i| i / w >= fb.height - 24),
            "{:?}",
            changed.first()
        );
        let red = psout::pack_rgb([110, 0, 0]);
        let white = psout::pack_rgb([255, 255, 255]);
        assert_eq!(fb.pixels[(fb.height - 1) * w], red);
        assert!(fb.pixels[(fb.height - 24) * w..].contains(&white));
        // A long error wraps, at most four lines.
        let mut long = clean.clone();
        overlay_error(&mut long, &"word ".repeat(2000));
        let top = (0..long.pixels.len())
            .find(|&i| long.pixels[i] != clean.pixels[i])
            .unwrap()
            / w;
        assert_eq!(top, long.height - 5 * 12);
    }
}

//! `psout FILE…`: shows a raster file (or a PNG or PPM) as the thesis's
//! PS 390 display did (1024×864), in a window, or plays several (a film's
//! frames) in order; `--screenshot OUT.png` writes the screen to a PNG
//! instead. See
//! docs/psout.md, docs/film.md and the `raytrace::psout` module; the keys
//! are `raytrace::psout::player`'s.
//!
//! Exit codes: 0 done; 1 no window could be opened (or a screenshot could
//! not be written); 2 the raster file (or the command line) is bad; 130 or
//! 143 stopped by SIGINT or SIGTERM (a screenshot being written leaves no
//! temporary file).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;
use raytrace::cli::exit_code;
use raytrace::exit::Failure;
use raytrace::image_file::read_image_file;
use raytrace::psout;

use raytrace::psout::{player, Lut};
use raytrace::raster::Raster;

/// Show a Sun raster, PNG or PPM file on an emulated PS 390 display
/// (1024×864); several files (a film's frames, `STEM.*.ras`) are played in
/// order as a film.
#[derive(Parser, Debug)]
#[command(name = "psout", version, after_help = player::KEYS_HELP)]
struct Args {
    /// Integer zoom by pixel replication [default: the largest of 1–3 at
    /// which the raster fits the screen].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=3))]
    zoom: Option<u32>,
    /// Quantise the raster to an N-entry colour lookup table (median cut),
    /// N from 2 to 256.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(2..=256))]
    lut: Option<u16>,
    /// Write the 1024×864 screen to OUT.png (or - for standard output) and exit, without a
    /// window.
    #[arg(long, value_name = "OUT.png")]
    screenshot: Option<PathBuf>,
    /// A film: the frame (1-based) to write with --screenshot, or to start
    /// the window paused at [default: play from the first].
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..))]
    frame: Option<u32>,
    /// A film: frames a second (the deck's `film … rate FPS`).
    #[arg(long, value_name = "FPS", default_value_t = 12, value_parser = clap::value_parser!(u32).range(1..=60))]
    rate: u32,
    /// The picture to show (a Sun raster, PNG or PPM file), or the frames
    /// of a film in order.
    #[arg(required = true, value_name = "FILE")]
    files: Vec<PathBuf>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    exit_code("psout", run(&args))
}

fn run(args: &Args) -> Result<(), Failure> {
    raytrace::cli::remove_temp_files_on_signals()?;
    if let Some(out) = &args.screenshot {
        raytrace::cli::check_screenshot_name(out)?;
    }
    let lut = args.lut.map(usize::from);
    let bad = Failure::input;
    let frames = if args.files.len() == 1 {
        vec![load(&args.files[0], lut).map_err(bad)?]
    } else {
        let frames = raytrace::film::read_sequence(&args.files).map_err(|e| bad(e.to_string()))?;
        match lut {
            Some(n) => frames.iter().map(|r| Lut::median_cut(&r.pixels, n).apply(r)).collect(),
            None => frames,
        }
    };
    let start = match args.frame {
        Some(k) if k as usize > frames.len() => {
            return Err(Failure::usage(format!(
                "--frame {k}: there are {} frame{} (1..{})",
                frames.len(),
                if frames.len() == 1 { "" } else { "s" },
                frames.len()
            )))
        }
        Some(k) => Some(k as usize - 1),
        None => None,
    };
    match &args.screenshot {
        Some(out) => screenshot(out, &frames[start.unwrap_or(0)], args.zoom),
        None => show(args, frames, start),
    }
}

/// Reads the picture (a Sun raster, PNG or PPM), in lookup-table mode
/// quantised; the message names the file.
fn load(path: &Path, lut: Option<usize>) -> Result<Raster, String> {
    let raster = read_image_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(match lut {
        Some(n) => Lut::median_cut(&raster.pixels, n).apply(&raster),
        None => raster,
    })
}

/// `--screenshot`: the screen psout would show, as a PNG.
fn screenshot(out: &Path, raster: &Raster, zoom: Option<u32>) -> Result<(), Failure> {
    raytrace::cli::write_screenshot("psout", out, &psout::compose(raster, zoom, (0, 0)))
}

/// The error when no window can be opened: names both ways out.
fn no_display(reason: &str) -> Failure {
    Failure::other(psout::no_display_message(
        "psout",
        reason,
        "write the screen to a file with `psout --screenshot OUT.png FILE`",
    ))
}

#[cfg(not(feature = "window"))]
fn show(_args: &Args, _frames: Vec<Raster>, _start: Option<usize>) -> Result<(), Failure> {
    Err(no_display("this psout was built without the `window` feature"))
}

/// Key events from minifb into the player's queue.
#[cfg(feature = "window")]
struct KeyEvents(std::rc::Rc<std::cell::RefCell<player::KeyQueue<minifb::Key>>>);

#[cfg(feature = "window")]
impl minifb::InputCallback for KeyEvents {
    fn add_char(&mut self, _uni_char: u32) {}

    fn set_key_state(&mut self, key: minifb::Key, state: bool) {
        self.0.borrow_mut().event(key, state);
    }
}

/// The player's key for a minifb key.
#[cfg(feature = "window")]
fn player_key(key: minifb::Key) -> Option<player::Key> {
    use minifb::Key as K;
    use player::Key as P;
    Some(match key {
        K::Escape | K::Q => P::Quit,
        K::Space => P::Pause,
        K::Left => P::Left,
        K::Right => P::Right,
        K::Up => P::Up,
        K::Down => P::Down,
        K::Home => P::Home,
        K::End => P::End,
        // `+` shares its key with `=` on most layouts.
        K::Equal | K::NumPadPlus => P::ZoomIn,
        K::Minus | K::NumPadMinus => P::ZoomOut,
        K::N => P::Next,
        K::P => P::Previous,
        K::S => P::Save,
        _ => return None,
    })
}

#[cfg(feature = "window")]
fn show(args: &Args, mut frames: Vec<Raster>, start: Option<usize>) -> Result<(), Failure> {
    use minifb::{Window, WindowOptions};
    use player::Effect;
    use psout::{SCREEN_HEIGHT, SCREEN_WIDTH};
    use std::time::Instant;

    if let Some(reason) = psout::display_missing() {
        return Err(no_display(reason));
    }
    let lut = args.lut.map(usize::from);
    let film = frames.len() > 1;
    let mut paths = args.files.clone();
    let (w, h) = (frames[0].width, frames[0].height);
    let mut play = player::Player::new(frames.len(), w, h, args.zoom, args.rate);
    if let Some(k) = start {
        play.show_paused(k);
    }
    let path_of = |paths: &[PathBuf], play: &player::Player| paths[if film { play.current() } else { 0 }].clone();

    let mut window = Window::new(
        &play.title(&path_of(&paths, &play), lut),
        SCREEN_WIDTH,
        SCREEN_HEIGHT,
        WindowOptions::default(),
    )
    .map_err(|e| no_display(&psout::window_error(e)))?;
    window.set_target_fps(60);
    let queue = std::rc::Rc::new(std::cell::RefCell::new(player::KeyQueue::default()));
    window.set_input_callback(Box::new(KeyEvents(queue.clone())));
    let draw = |frames: &[Raster], play: &player::Player| {
        psout::compose(
            &frames[if film { play.current() } else { 0 }],
            Some(play.zoom()),
            play.pan(),
        )
    };
    let mut screen = draw(&frames, &play);
    let mut last_tick = Instant::now();

    'window: while window.is_open() {
        let mut changed = false;
        for key in queue.borrow_mut().take().into_iter().filter_map(player_key) {
            match play.press(key) {
                Effect::Quit => break 'window,
                Effect::Save => save(&path_of(&paths, &play), &screen),
                Effect::Redraw => changed = true,
                Effect::Neighbour(forward) => {
                    if let Some((next, r)) = step(&paths[0], forward, lut) {
                        play.replaced(r.width, r.height);
                        paths = vec![next];
                        frames = vec![r];
                        changed = true;
                    }
                }
                Effect::Nothing => {}
            }
        }
        let now = Instant::now();
        changed |= play.tick(now - last_tick);
        last_tick = now;
        if changed {
            screen = draw(&frames, &play);
            window.set_title(&play.title(&path_of(&paths, &play), lut));
        }
        window
            .update_with_buffer(&screen.pixels, SCREEN_WIDTH, SCREEN_HEIGHT)
            .map_err(|e| Failure::other(format!("the window failed: {}", psout::window_error(e))))?;
    }
    Ok(())
}

/// The next or previous raster in the folder, read; problems are reported
/// and leave the current raster on screen.
#[cfg(feature = "window")]
fn step(path: &Path, forward: bool, lut: Option<usize>) -> Option<(PathBuf, Raster)> {
    let next = match psout::neighbour(path, forward) {
        Ok(Some(p)) => p,
        Ok(None) => return None,
        Err(e) => {
            eprintln!("psout: cannot list the folder of {}: {e}", path.display());
            return None;
        }
    };
    match load(&next, lut) {
        Ok(r) => Some((next, r)),
        Err(message) => {
            eprintln!("psout: {message}");
            None
        }
    }
}

/// The s key: the screen as a PNG beside the raster.
#[cfg(feature = "window")]
fn save(path: &Path, screen: &psout::Framebuffer) {
    let out = psout::screenshot_path(path);
    match screenshot_of(&out, screen) {
        Ok(()) => println!("psout: saved the screen to {}", out.display()),
        Err(e) => eprintln!("psout: cannot write {}: {e}", out.display()),
    }
}

#[cfg(all(feature = "window", feature = "png"))]
fn screenshot_of(out: &Path, screen: &psout::Framebuffer) -> Result<(), String> {
    raytrace::raster::write_png(out, &screen.to_raster()).map_err(|e| e.to_string())
}

#[cfg(all(feature = "window", not(feature = "png")))]
fn screenshot_of(_out: &Path, _screen: &psout::Framebuffer) -> Result<(), String> {
    Err("this psout was built without the `png` feature".into())
}

//! `psout FILE`: shows a raster file as the thesis's PS 390 display did
//! (1024×864), in a window; `--screenshot OUT.png` writes the screen to a
//! PNG instead. See docs/psout.md and the `raytrace::psout` module.
//!
//! Exit codes: 0 done; 1 no window could be opened (or a screenshot could
//! not be written); 2 the raster file (or the command line) is bad; 130 or
//! 143 stopped by SIGINT or SIGTERM (a screenshot being written leaves no
//! temporary file).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Parser;
#[cfg(any(feature = "png", feature = "window"))]
use raytrace::psout;
use raytrace::psout::Lut;
use raytrace::raster::{self, Raster};

/// Show a Sun raster file on an emulated PS 390 display (1024×864).
#[derive(Parser, Debug)]
#[command(name = "psout", version)]
struct Args {
    /// Integer zoom by pixel replication [default: the largest of 1–3 at
    /// which the raster fits the screen].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=3))]
    zoom: Option<u32>,
    /// Quantise the raster to an N-entry colour lookup table (median cut),
    /// N from 2 to 256.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(2..=256))]
    lut: Option<u16>,
    /// Write the 1024×864 screen to OUT.png and exit, without a window.
    #[arg(long, value_name = "OUT.png")]
    screenshot: Option<PathBuf>,
    /// The raster file to show.
    file: PathBuf,
}

/// Why psout stops: an exit code and the message for stderr.
struct Failure {
    code: u8,
    message: String,
}

fn main() -> ExitCode {
    let args = Args::parse();
    if let Err(e) = raytrace::output::remove_temp_files_on_signals() {
        eprintln!("psout: cannot watch for SIGINT and SIGTERM: {e}");
        return ExitCode::from(1);
    }
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("psout: {}", f.message);
            ExitCode::from(f.code)
        }
    }
}

fn run(args: &Args) -> Result<(), Failure> {
    if let Some(out) = &args.screenshot {
        check_screenshot_name(out)?;
    }
    let lut = args.lut.map(usize::from);
    let raster = load(&args.file, lut).map_err(|message| Failure { code: 2, message })?;
    match &args.screenshot {
        Some(out) => screenshot(out, &raster, args.zoom),
        None => show(args, raster),
    }
}

/// A usage error (exit 2) unless `out` is standard output (`-`) or names
/// a PNG: the format follows the extension, as for `raytrace -o`.
fn check_screenshot_name(out: &Path) -> Result<(), Failure> {
    use raytrace::output::{Format, OutputError, STDOUT};
    let problem = match Format::of(out) {
        _ if out.as_os_str() == STDOUT => return Ok(()),
        Ok(Format::Png) => return Ok(()),
        Ok(_) | Err(OutputError::UnknownFormat(_)) => "a screenshot is a PNG, so the name must end in .png".to_string(),
        Err(e) => e.to_string(),
    };
    Err(Failure {
        code: 2,
        message: format!("--screenshot '{}': {problem}", out.display()),
    })
}

/// Reads the raster, in lookup-table mode quantised; the message names the
/// file.
fn load(path: &Path, lut: Option<usize>) -> Result<Raster, String> {
    let raster = raster::read_raster_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(match lut {
        Some(n) => Lut::median_cut(&raster.pixels, n).apply(&raster),
        None => raster,
    })
}

#[cfg(feature = "png")]
fn screenshot(out: &Path, raster: &Raster, zoom: Option<u32>) -> Result<(), Failure> {
    let screen = psout::compose(raster, zoom, (0, 0));
    raster::write_png(out, &screen.to_raster()).map_err(|e| Failure {
        code: 1,
        message: format!("cannot write {}: {e}", out.display()),
    })
}

#[cfg(not(feature = "png"))]
fn screenshot(_out: &Path, _raster: &Raster, _zoom: Option<u32>) -> Result<(), Failure> {
    Err(Failure {
        code: 1,
        message: "this psout was built without the `png` feature, so --screenshot is not available".into(),
    })
}

/// The error when no window can be opened: names both ways out.
fn no_display(reason: &str) -> Failure {
    Failure {
        code: 1,
        message: format!(
            "cannot open a window ({reason}).\n\
             Run psout under an X display, e.g. `xvfb-run -s \"-screen 0 1024x864x24\" psout FILE`,\n\
             or write the screen to a file with `psout --screenshot OUT.png FILE`."
        ),
    }
}

#[cfg(not(feature = "window"))]
fn show(_args: &Args, _raster: Raster) -> Result<(), Failure> {
    Err(no_display("this psout was built without the `window` feature"))
}

/// How far an arrow key pans, in screen pixels.
#[cfg(feature = "window")]
const PAN_STEP: i64 = 32;

#[cfg(feature = "window")]
fn show(args: &Args, raster: Raster) -> Result<(), Failure> {
    use minifb::{Key, KeyRepeat, Window, WindowOptions};
    use psout::{SCREEN_HEIGHT, SCREEN_WIDTH};

    // `DISPLAY=` (empty) is as good as unset.
    if std::env::var_os("DISPLAY").is_none_or(|d| d.is_empty()) {
        return Err(no_display("DISPLAY is not set"));
    }
    let lut = args.lut.map(usize::from);
    let mut path = args.file.clone();
    let mut raster = raster;
    let mut zoom = args
        .zoom
        .unwrap_or_else(|| psout::default_zoom(raster.width, raster.height));
    let mut pan = (0, 0);
    let title = |path: &Path, r: &Raster, zoom| psout::title(path, r.width, r.height, zoom, lut);

    let mut window = Window::new(
        &title(&path, &raster, zoom),
        SCREEN_WIDTH,
        SCREEN_HEIGHT,
        WindowOptions::default(),
    )
    .map_err(|e| no_display(&window_error(e)))?;
    window.set_target_fps(30);
    let mut screen = psout::compose(&raster, Some(zoom), pan);

    while window.is_open() && !window.is_key_down(Key::Escape) && !window.is_key_down(Key::Q) {
        let mut changed = false;
        for key in window.get_keys_pressed(KeyRepeat::Yes) {
            match key {
                // `+` shares its key with `=` on most layouts.
                Key::Equal | Key::NumPadPlus => zoom = (zoom + 1).min(psout::MAX_ZOOM),
                Key::Minus | Key::NumPadMinus => zoom = zoom.saturating_sub(1).max(1),
                Key::Left => pan.0 -= PAN_STEP,
                Key::Right => pan.0 += PAN_STEP,
                Key::Up => pan.1 -= PAN_STEP,
                Key::Down => pan.1 += PAN_STEP,
                Key::N | Key::P => match step(&path, key == Key::N, lut) {
                    Some((next, r)) => {
                        zoom = args.zoom.unwrap_or_else(|| psout::default_zoom(r.width, r.height));
                        pan = (0, 0);
                        path = next;
                        raster = r;
                    }
                    None => continue,
                },
                Key::S => save(&path, &screen),
                _ => continue,
            }
            changed = true;
        }
        if changed {
            // Keep the clamped pan, so arrows pressed at an edge do not
            // pile up an offset that later keys must undo.
            pan = psout::placement(raster.width, raster.height, Some(zoom), pan).pan;
            screen = psout::compose(&raster, Some(zoom), pan);
            window.set_title(&title(&path, &raster, zoom));
        }
        window
            .update_with_buffer(&screen.pixels, SCREEN_WIDTH, SCREEN_HEIGHT)
            .map_err(|e| Failure {
                code: 1,
                message: format!("the window failed: {}", window_error(e)),
            })?;
    }
    Ok(())
}

/// minifb's message with its detail (its `Display` drops the detail, e.g.
/// "XOpenDisplay failed" or "failed to load Xlib").
#[cfg(feature = "window")]
fn window_error(e: minifb::Error) -> String {
    match &e {
        minifb::Error::WindowCreate(detail) | minifb::Error::UpdateFailed(detail) => {
            format!("{e}: {detail}")
        }
        _ => e.to_string(),
    }
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
    raster::write_png(out, &screen.to_raster()).map_err(|e| e.to_string())
}

#[cfg(all(feature = "window", not(feature = "png")))]
fn screenshot_of(_out: &Path, _screen: &psout::Framebuffer) -> Result<(), String> {
    Err("this psout was built without the `png` feature".into())
}

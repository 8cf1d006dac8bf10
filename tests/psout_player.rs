//! psout's keys and films through its window-free core
//! (`raytrace::psout::player`), and the command line that plays a film.

use std::path::PathBuf;
use std::process::Command;
use std::time::Duration;

use raytrace::psout::player::{Effect, Key, KeyQueue, Player, KEYS_HELP, PAN_STEP};
use raytrace::raster::{outputframe, Raster};

fn psout() -> Command {
    Command::new(env!("CARGO_BIN_EXE_psout"))
}

/// A key pressed and released before the next frame is drawn (a 12 ms tap
/// of q) is still a press: it quits.
#[test]
fn a_tap_between_two_frames_is_not_lost() {
    let mut queue = KeyQueue::default();
    queue.event(Key::Quit, true);
    queue.event(Key::Quit, false);
    let mut play = Player::new(1, 256, 256, None, 12);
    let effects: Vec<Effect> = queue.take().into_iter().map(|k| play.press(k)).collect();
    assert_eq!(effects, [Effect::Quit]);
    // Taken once: the next frame sees no press.
    assert!(queue.take().is_empty());
    // Presses keep their order, and a repeat is one press more.
    for (key, down) in [
        (Key::ZoomOut, true),
        (Key::ZoomOut, false),
        (Key::ZoomOut, true),
        (Key::Save, true),
    ] {
        queue.event(key, down);
    }
    assert_eq!(queue.take(), [Key::ZoomOut, Key::ZoomOut, Key::Save]);
}

/// The arrows do not pan a raster that fits the screen (256×256 at 3× is
/// 768×768 of 1024×864), at any zoom; they pan one that is larger.
#[test]
fn the_arrows_pan_only_a_raster_larger_than_the_screen() {
    let mut play = Player::new(1, 256, 256, None, 12);
    assert_eq!(play.zoom(), 3);
    for key in [Key::Left, Key::Right, Key::Up, Key::Down] {
        assert_eq!(play.press(key), Effect::Nothing, "{key:?}");
        assert_eq!(play.pan(), (0, 0));
    }
    let mut big = Player::new(1, 2000, 1000, None, 12);
    assert_eq!(big.press(Key::Right), Effect::Redraw);
    assert_eq!(big.pan(), (PAN_STEP, 0));
    assert_eq!(big.press(Key::Down), Effect::Redraw);
    assert_eq!(big.pan(), (PAN_STEP, PAN_STEP));
    // Wide but not tall: only across.
    let mut wide = Player::new(1, 700, 10, Some(2), 12);
    assert_eq!(wide.press(Key::Down), Effect::Nothing);
    assert_eq!(wide.press(Key::Left), Effect::Redraw);
    assert_eq!(wide.pan(), (-PAN_STEP, 0));
}

#[test]
fn zoom_keys_and_the_still_keys() {
    let mut play = Player::new(1, 256, 256, None, 12);
    assert_eq!(play.press(Key::ZoomIn), Effect::Nothing); // already 3×
    assert_eq!(play.press(Key::ZoomOut), Effect::Redraw);
    assert_eq!(play.zoom(), 2);
    assert_eq!(play.press(Key::Next), Effect::Neighbour(true));
    assert_eq!(play.press(Key::Previous), Effect::Neighbour(false));
    assert_eq!(play.press(Key::Save), Effect::Save);
    // A still has no frames to pause or jump to.
    for key in [Key::Pause, Key::Home, Key::End] {
        assert_eq!(play.press(key), Effect::Nothing, "{key:?}");
    }
    assert!(!play.tick(Duration::from_secs(10)));
    // n and p load a raster of another size: its own zoom, no pan.
    play.replaced(512, 400);
    assert_eq!((play.zoom(), play.pan()), (2, (0, 0)));
}

/// A film plays at its rate, wraps at the end; space pauses; ←/→ step
/// only when paused; Home and End jump; the title shows `frame k/F`.
#[test]
fn a_film_plays_pauses_steps_and_jumps() {
    let mut play = Player::new(36, 256, 256, None, 12);
    assert!(play.is_film());
    let title = |p: &Player| p.title(std::path::Path::new("nec.0001.ras"), None);
    assert_eq!(title(&play), "psout — nec.0001.ras 256×256 ×3 frame 1/36");
    // 1/12 s a frame: 40 ms is not yet a frame, 90 ms is one, then 1 s is 12.
    assert!(!play.tick(Duration::from_millis(40)));
    assert!(play.tick(Duration::from_millis(50)));
    assert_eq!(play.current(), 1);
    play.tick(Duration::from_secs(1));
    assert_eq!(play.current(), 13);
    // While playing, ← and → do not step (and do not pan a film that fits).
    assert_eq!(play.press(Key::Right), Effect::Nothing);
    assert_eq!(play.current(), 13);
    assert_eq!(play.press(Key::Pause), Effect::Redraw);
    assert!(play.paused());
    assert!(title(&play).ends_with("frame 14/36 paused"));
    assert!(!play.tick(Duration::from_secs(5)));
    assert_eq!(play.current(), 13);
    assert_eq!(play.press(Key::Right), Effect::Redraw);
    assert_eq!(play.current(), 14);
    assert_eq!(play.press(Key::Left), Effect::Redraw);
    assert_eq!(play.press(Key::Left), Effect::Redraw);
    assert_eq!(play.current(), 12);
    assert_eq!(play.press(Key::End), Effect::Redraw);
    assert_eq!(play.current(), 35);
    assert_eq!(play.press(Key::End), Effect::Nothing);
    assert_eq!(play.press(Key::Right), Effect::Redraw);
    assert_eq!(play.current(), 0, "→ on the last frame wraps to the first");
    assert_eq!(play.press(Key::Left), Effect::Redraw);
    assert_eq!(play.current(), 35);
    assert_eq!(play.press(Key::Home), Effect::Redraw);
    assert_eq!(play.current(), 0);
    // n and p do not leave a film.
    assert_eq!(play.press(Key::Next), Effect::Nothing);
    // Playing again, it wraps from the last frame to the first.
    play.press(Key::End);
    play.press(Key::Pause);
    assert!(play.tick(Duration::from_millis(84)));
    assert_eq!(play.current(), 0);
    play.show_paused(99);
    assert_eq!((play.current(), play.paused()), (35, true));
}

#[test]
fn help_lists_the_window_keys() {
    let out = psout().arg("--help").output().unwrap();
    assert!(out.status.success());
    let help = String::from_utf8_lossy(&out.stdout);
    assert!(help.contains(KEYS_HELP), "{help}");
    for keys in [
        "space", "← →", "↑ ↓", "Home End", "+ −", "n p", "s ", "q Esc", "--frame", "--rate",
    ] {
        assert!(help.contains(keys), "{keys}: {help}");
    }
}

fn flat(width: usize, height: usize, c: u8) -> Raster {
    Raster {
        width,
        height,
        pixels: vec![[c, 255 - c, c / 2]; width * height],
    }
}

fn write_frames(dir: &std::path::Path, rasters: &[Raster]) -> Vec<PathBuf> {
    rasters
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let p = dir.join(format!("f.{:04}.ras", i + 1));
            outputframe(&p, r).unwrap();
            p
        })
        .collect()
}

/// `--screenshot OUT.png --frame K` of a sequence writes frame K's screen.
#[cfg(feature = "png")]
#[test]
fn a_screenshot_of_frame_k_of_a_film() {
    let dir = tempfile::tempdir().unwrap();
    let frames = [flat(16, 8, 10), flat(16, 8, 120), flat(16, 8, 240)];
    let files = write_frames(dir.path(), &frames);
    for k in 1..=3 {
        let png = dir.path().join(format!("shot{k}.png"));
        let out = psout()
            .args(&files)
            .arg("--screenshot")
            .arg(&png)
            .args(["--frame", &k.to_string()])
            .env_remove("DISPLAY")
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let img = image::open(&png).unwrap().to_rgb8();
        let want = raytrace::psout::compose(&frames[k - 1], None, (0, 0));
        let got: Vec<u32> = img.pixels().map(|p| raytrace::psout::pack_rgb(p.0)).collect();
        assert!(got == want.pixels, "frame {k}");
    }
}

/// A sequence whose rasters differ in size names the first that differs;
/// `--frame` past the film is an error. Exit 2, nothing written.
#[test]
fn a_sequence_of_two_sizes_and_a_frame_past_the_end_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let files = write_frames(
        dir.path(),
        &[flat(16, 8, 1), flat(16, 8, 2), flat(8, 8, 3), flat(4, 4, 4)],
    );
    let png = dir.path().join("shot.png");
    let out = psout()
        .args(&files)
        .arg("--screenshot")
        .arg(&png)
        .env_remove("DISPLAY")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("f.0003.ras: 8×8, but"), "{err}");
    assert!(err.contains("f.0001.ras is 16×8"), "{err}");
    assert!(!png.exists());

    let out = psout()
        .args(&files[..2])
        .arg("--screenshot")
        .arg(&png)
        .args(["--frame", "3"])
        .env_remove("DISPLAY")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--frame 3: there are 2 frames"));
    assert!(!png.exists());
}

//! The output files of `raytrace` and `psout --screenshot` as a user meets
//! them: standard output, the format by extension, usage errors, folders
//! never made up, every output checked before the render, FIFOs written
//! into, and signals that leave no temporary file.

use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use raytrace::raster::{read_raster, read_raster_file};

mod common;
use common::{file_names, raytrace_command, SMALL_DECK};

/// A folder with small.deck in it.
fn small_deck() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("small.deck");
    std::fs::write(&deck, SMALL_DECK).unwrap();
    (dir, deck)
}

fn run(cmd: &mut Command) -> Output {
    cmd.output().unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `-o -` writes the Sun raster to standard output, the same bytes as
/// `-o FILE`, and nothing named `-`.
#[test]
fn dash_writes_the_raster_to_standard_output() {
    let (dir, deck) = small_deck();
    let piped = run(raytrace_command()
        .arg("-q")
        .arg(&deck)
        .args(["-o", "-"])
        .current_dir(dir.path()));
    assert!(piped.status.success(), "{}", stderr(&piped));
    let file = dir.path().join("small.ras");
    let written = run(raytrace_command().arg("-q").arg(&deck).arg("-o").arg(&file));
    assert!(written.status.success(), "{}", stderr(&written));
    assert_eq!(piped.stdout, std::fs::read(&file).unwrap());
    assert_eq!(read_raster(&piped.stdout).unwrap().width, 16);
    assert_eq!(file_names(dir.path()), ["small.deck", "small.ras"]);
}

/// `raytrace deck -o - | rasttopnm` works (when netpbm is installed).
#[test]
fn dash_pipes_into_rasttopnm() {
    let (_dir, deck) = small_deck();
    let Ok(mut convert) = Command::new("rasttopnm")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
    else {
        assert!(std::env::var_os("CI").is_none(), "CI needs netpbm's rasttopnm");
        eprintln!("skipped: rasttopnm not installed (apt-get install -y netpbm)");
        return;
    };
    let status = raytrace_command()
        .arg("-q")
        .arg(&deck)
        .args(["-o", "-"])
        .stdout(convert.stdin.take().unwrap())
        .status()
        .unwrap();
    assert!(status.success());
    let out = convert.wait_with_output().unwrap();
    assert!(out.status.success());
    assert!(out.stdout.starts_with(b"P6\n16 12\n255\n"), "{:?}", &out.stdout[..12]);
}

/// `.ras`, `.png`, `.ppm` and `.pnm` each get their format.
#[test]
fn the_format_follows_the_extension() {
    let (dir, deck) = small_deck();
    let reference = dir.path().join("ref.ras");
    assert!(run(raytrace_command().arg("-q").arg(&deck).arg("-o").arg(&reference))
        .status
        .success());
    let pixels = read_raster_file(&reference).unwrap().pixels;
    for name in ["x.png", "x.PNG", "x.ppm", "x.pnm"] {
        let out = dir.path().join(name);
        let o = run(raytrace_command().arg("-q").arg(&deck).arg("-o").arg(&out));
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let bytes = std::fs::read(&out).unwrap();
        if name.to_lowercase().ends_with(".png") {
            assert!(bytes.starts_with(b"\x89PNG"), "{name}");
        } else {
            let header = b"P6\n16 12\n255\n";
            assert_eq!(&bytes[..header.len()], header, "{name}");
            assert_eq!(&bytes[header.len()..], pixels.as_flattened(), "{name}");
        }
    }
}

/// A bad output name is a usage error: exit 2, a sentence naming the flag,
/// the name and what is wrong, and nothing written.
#[test]
fn bad_output_names_are_usage_errors_and_write_nothing() {
    let (dir, deck) = small_deck();
    let cases: &[(&[&str], &str)] = &[
        (
            &["-o", "x.jpg"],
            "-o 'x.jpg': unknown extension '.jpg': the format follows the extension, one of .ras",
        ),
        (&["-o", "x"], "-o 'x': no extension"),
        (&["-o", ""], "a value is required for '--output <FILE>'"),
        (
            &["-o", "x.ras", "--png", "x.jpg"],
            "--png 'x.jpg': --png writes a PNG, so the name must end in .png",
        ),
        (&["-o", "x.ras", "--png", "x.ras"], "--png 'x.ras': --png writes a PNG"),
        (&["-o", "x.ras", "--png", ""], "a value is required for '--png <FILE>'"),
        (
            &["-o", "x.ras", "--debug", ""],
            "a value is required for '--debug <FILE>'",
        ),
        (&["-o", "-", "--png", "-"], "only one output can go to standard output"),
        (
            &["-o", "x.ras", "--apng", "film.gif"],
            "--apng 'film.gif': --apng writes an animated PNG, so the name must end in .png",
        ),
        (&["-o", "-", "--apng", "-"], "only one output can go to standard output"),
        // An existing folder is named as one, not as a name without an extension.
        (&["-o", "."], "-o '.': it is a folder: name a file in it"),
        (&["-o", "sub/"], "-o 'sub/': it is a folder: name a file in it"),
    ];
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    for (args, says) in cases {
        let o = run(raytrace_command().arg(&deck).args(*args).current_dir(dir.path()));
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
        assert!(o.stdout.is_empty(), "{args:?}");
        assert_eq!(file_names(dir.path()), ["small.deck", "sub"], "{args:?}");
    }
    // The help says what exit status 2 means.
    let help = String::from_utf8(run(raytrace_command().arg("--help")).stdout).unwrap();
    assert!(help.contains("2 for a usage error"), "{help}");
}

/// Only the default raster/ folder is created: a folder the user names
/// must exist, and a file in a folder's place is named as such.
#[test]
fn a_missing_or_blocked_folder_is_an_error_and_is_not_created() {
    let (dir, deck) = small_deck();
    let missing = dir.path().join("nonexistent/dir/x.ras");
    let o = run(raytrace_command().arg("-q").arg(&deck).arg("-o").arg(&missing));
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let folder = dir.path().join("nonexistent/dir");
    assert!(
        stderr(&o).contains(&format!("x.ras: the folder {} does not exist", folder.display())),
        "{}",
        stderr(&o)
    );
    assert!(!dir.path().join("nonexistent").exists());

    std::fs::write(dir.path().join("old.ras"), b"old").unwrap();
    let o = run(raytrace_command()
        .arg("-q")
        .arg(&deck)
        .args(["-o", "old.ras/x.ras"])
        .current_dir(dir.path()));
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("old.ras/x.ras: old.ras is a file, not a folder"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(dir.path().join("old.ras")).unwrap(), b"old");

    // The default output goes to raster/ under the working folder, made
    // when missing, wherever the deck is.
    let elsewhere = tempfile::tempdir().unwrap();
    let o = run(raytrace_command().arg("-q").arg(&deck).current_dir(elsewhere.path()));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(read_raster_file(&elsewhere.path().join("raster/small.ras")).is_ok());
}

/// Run from a folder that is not the checkout, a deck whose texture path is
/// relative to the deck (fig5_3.deck's `../../raster/card.tex.ras`) finds
/// it, and the default raster lands under the working folder.
#[test]
fn a_deck_with_a_texture_renders_from_another_folder() {
    let root = tempfile::tempdir().unwrap();
    let checkout = Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::create_dir_all(root.path().join("legacy_pascal/decks")).unwrap();
    std::fs::create_dir_all(root.path().join("raster")).unwrap();
    std::fs::copy(
        checkout.join("raster/card.tex.ras"),
        root.path().join("raster/card.tex.ras"),
    )
    .unwrap();
    let deck = std::fs::read_to_string(checkout.join("legacy_pascal/decks/fig5_3.deck")).unwrap();
    assert!(deck.contains("texture picture   ../../raster/card.tex.ras"));
    let deck_path = root.path().join("legacy_pascal/decks/tex.deck");
    std::fs::write(
        &deck_path,
        deck.replace("image      256 256  mask 2", "image 24 24 mask 1"),
    )
    .unwrap();
    let work = tempfile::tempdir().unwrap();
    let o = run(raytrace_command().arg("-q").arg(&deck_path).current_dir(work.path()));
    assert!(o.status.success(), "{}", stderr(&o));
    let r = read_raster_file(&work.path().join("raster/tex.ras")).unwrap();
    assert_eq!((r.width, r.height), (24, 24));
}

/// When the PNG or the debug log cannot be written, that is found before
/// the render: exit 1, the reason, and neither the raster nor a temporary
/// file written.
#[test]
fn every_output_is_checked_before_rendering() {
    let (dir, deck) = small_deck();
    let out = dir.path().join("small.ras");
    for (flag, bad) in [("--png", "gone/x.png"), ("--debug", "gone/x.log")] {
        let o = run(raytrace_command()
            .arg("-q")
            .arg(&deck)
            .arg("-o")
            .arg(&out)
            .arg(flag)
            .arg(dir.path().join(bad)));
        assert_eq!(o.status.code(), Some(1), "{flag}: {}", stderr(&o));
        assert!(stderr(&o).contains("gone does not exist"), "{flag}: {}", stderr(&o));
        assert_eq!(file_names(dir.path()), ["small.deck"], "{flag}");
    }
}

/// A FIFO named as the output is written into and stays a FIFO, for
/// `raytrace -o` and `psout --screenshot` alike.
#[test]
fn a_fifo_output_is_written_into() {
    let (dir, deck) = small_deck();
    let fifo = dir.path().join("pipe.ras");
    let shot = dir.path().join("pipe.png");
    for f in [&fifo, &shot] {
        if !Command::new("mkfifo").arg(f).status().is_ok_and(|s| s.success()) {
            eprintln!("skipped: mkfifo failed");
            return;
        }
    }
    let reader = |path: &Path| {
        let path = path.to_path_buf();
        std::thread::spawn(move || std::fs::read(path).unwrap())
    };
    let got = reader(&fifo);
    let o = run(raytrace_command().arg("-q").arg(&deck).arg("-o").arg(&fifo));
    assert!(o.status.success(), "{}", stderr(&o));
    // Checked before joining: a replaced FIFO would leave the reader waiting.
    assert!(std::fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    let bytes = got.join().unwrap();
    assert_eq!(read_raster(&bytes).unwrap().height, 12);

    let raster = dir.path().join("small.ras");
    std::fs::write(&raster, &bytes).unwrap();
    let got = reader(&shot);
    let o = run(Command::new(env!("CARGO_BIN_EXE_psout"))
        .arg("--screenshot")
        .arg(&shot)
        .arg(&raster));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(std::fs::symlink_metadata(&shot).unwrap().file_type().is_fifo());
    assert!(got.join().unwrap().starts_with(b"\x89PNG"));
    assert_eq!(
        file_names(dir.path()),
        ["pipe.png", "pipe.ras", "small.deck", "small.ras"]
    );
}

/// A device or FIFO named without an extension gets the Sun raster, the
/// original's format: `-o /dev/null` renders and writes nothing anywhere,
/// `-o /dev/stdout` (a pipe here) the bytes of `-o -`, a FIFO `pipe` the
/// raster. A regular file without an extension is still refused.
#[test]
fn a_device_or_fifo_without_an_extension_gets_the_sun_raster() {
    let (dir, deck) = small_deck();
    let null = run(raytrace_command().arg("-q").arg(&deck).args(["-o", "/dev/null"]));
    assert!(null.status.success(), "{}", stderr(&null));
    assert!(null.stdout.is_empty() && null.stderr.is_empty());
    let dash = run(raytrace_command().arg("-q").arg(&deck).args(["-o", "-"]));
    let dev = run(raytrace_command().arg("-q").arg(&deck).args(["-o", "/dev/stdout"]));
    assert!(dev.status.success(), "{}", stderr(&dev));
    assert_eq!(dev.stdout, dash.stdout);
    assert_eq!(read_raster(&dev.stdout).unwrap().width, 16);

    let fifo = dir.path().join("pipe");
    if Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
        let path = fifo.clone();
        let got = std::thread::spawn(move || std::fs::read(path).unwrap());
        let o = run(raytrace_command().arg("-q").arg(&deck).arg("-o").arg(&fifo));
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(std::fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
        assert_eq!(got.join().unwrap(), dash.stdout);
    }
    std::fs::write(dir.path().join("plain"), b"a regular file").unwrap();
    let o = run(raytrace_command().arg(&deck).arg("-o").arg(dir.path().join("plain")));
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("plain': no extension"), "{}", stderr(&o));
    assert_eq!(std::fs::read(dir.path().join("plain")).unwrap(), b"a regular file");
}

/// `raytrace DECK -o - | head -c 10`: the reader takes ten bytes of a
/// raster far larger than a pipe holds and closes its end; raytrace drops
/// the rest and ends as the render did, status 0, with no message.
#[test]
fn a_reader_that_stops_early_ends_the_run_quietly() {
    use std::io::Read;
    let (_dir, deck) = small_deck();
    let mut child = raytrace_command()
        .arg("-q")
        .arg(&deck)
        .args(["--size", "512x512", "-o", "-"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut head = [0; 10];
    child.stdout.take().unwrap().read_exact(&mut head).unwrap();
    // The read end is dropped here: 786 KB of raster cannot all fit in the pipe.
    let out = child.wait_with_output().unwrap();
    assert_eq!(&head[..4], &[0x59, 0xa6, 0x6a, 0x95], "a Sun raster's magic number");
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(out.stderr.is_empty(), "{}", stderr(&out));
}

/// `psout --screenshot` writes a PNG, so its name must say so.
#[test]
fn psout_screenshot_name_must_be_a_png() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(Command::new(env!("CARGO_BIN_EXE_psout"))
        .arg("--screenshot")
        .arg(dir.path().join("shot.jpg"))
        .arg(dir.path().join("whatever.ras")));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("shot.jpg': a screenshot is a PNG"),
        "{}",
        stderr(&o)
    );
}

/// A deck big enough that its render takes far longer than the test's
/// signal: 4096×4096 pixels, one thread.
const BIG: &str = "\
view  eye 0 -10 3  look 0 0 0  screen 4  distance 5
image 4096 4096  mask 2
light sun 5 -5 10  1 1 1
surface red opaque color 1 0 0 ka 0.2 kd 0.8 ks 0.5 kt 0
sphere ball red at 0 0 0 radius 1
";

/// Starts a big render into `out` and waits until its temporary file is
/// there (it is made before the render starts); returns the child and
/// the temporary file.
fn start_big_render(dir: &Path, out: &Path) -> (Child, PathBuf) {
    start_render(dir, out, &[])
}

/// [`start_big_render`] with further flags (`--size` for a shorter one).
fn start_render(dir: &Path, out: &Path, flags: &[&str]) -> (Child, PathBuf) {
    let deck = dir.join("big.deck");
    std::fs::write(&deck, BIG).unwrap();
    let mut child = raytrace_command()
        .args(["-q", "--threads", "1"])
        .args(flags)
        .arg(&deck)
        .arg("-o")
        .arg(out)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let temp = PathBuf::from(format!(
        "{}/.{}.{}.{}.0.tmp",
        out.parent().unwrap().display(),
        out.file_name().unwrap().to_string_lossy(),
        raytrace::output::this_host(),
        child.id()
    ));
    let started = Instant::now();
    while !temp.exists() {
        if let Some(status) = child.try_wait().unwrap() {
            let out = child.wait_with_output().unwrap();
            panic!("raytrace ended ({status}) before its temporary file: {}", stderr(&out));
        }
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "no temporary file {}",
            temp.display()
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    (child, temp)
}

/// Waits for the child, killing it if it takes longer than a minute.
fn wait(mut child: Child) -> std::process::ExitStatus {
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            return status;
        }
        if started.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("raytrace did not stop on the signal");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// SIGINT and SIGTERM while the output is pending: the temporary file is
/// removed, the exit status is 130 or 143, the last good file is intact.
#[test]
fn sigint_and_sigterm_remove_the_temporary_file() {
    for (signal, code) in [("INT", 130), ("TERM", 143)] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("big.ras");
        std::fs::write(&out, b"the last good raster").unwrap();
        let (child, temp) = start_big_render(dir.path(), &out);
        let pid = child.id().to_string();
        assert!(Command::new("kill")
            .args([&format!("-{signal}"), &pid])
            .status()
            .unwrap()
            .success());
        let status = wait(child);
        assert_eq!(status.code(), Some(code), "SIG{signal}: {status:?}");
        assert!(!temp.exists(), "SIG{signal} left {}", temp.display());
        assert_eq!(std::fs::read(&out).unwrap(), b"the last good raster");
        assert_eq!(file_names(dir.path()), ["big.deck", "big.ras"]);
    }
}

/// A SIGKILL leaves the temporary file; the next run that writes the same
/// target removes it.
#[test]
fn after_sigkill_the_next_run_removes_the_stale_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big.ras");
    let (mut child, temp) = start_big_render(dir.path(), &out);
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(temp.exists(), "SIGKILL cannot be caught: the temporary file stays");
    std::fs::write(dir.path().join("small.deck"), SMALL_DECK).unwrap();
    let o = run(raytrace_command()
        .arg("-q")
        .arg(dir.path().join("small.deck"))
        .arg("-o")
        .arg(&out));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!temp.exists(), "{} is still there", temp.display());
    assert_eq!(file_names(dir.path()), ["big.deck", "big.ras", "small.deck"]);
}

/// The fault of a farm: another writer of the same file (on a shared
/// folder, in another PID namespace) removes a live writer's temporary
/// file. The writer renders to the end and then fails, exit 1, naming the
/// temporary file that vanished, not only the target; the last good target
/// stays.
#[test]
fn a_temporary_file_removed_during_the_render_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big.ras");
    std::fs::write(&out, b"the last good raster").unwrap();
    let (child, temp) = start_render(dir.path(), &out, &["--size", "400x400"]);
    std::fs::remove_file(&temp).unwrap();
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains(&temp.display().to_string()) && e.contains("vanished"), "{e}");
    assert_eq!(std::fs::read(&out).unwrap(), b"the last good raster");
    assert_eq!(file_names(dir.path()), ["big.deck", "big.ras"]);
}

/// An existing file keeps its mode when it is written again (the new
/// file is a temporary one renamed over it, which would have the umask's
/// mode); this holds for any user, root included.
#[test]
fn a_file_written_again_keeps_its_mode() {
    use std::os::unix::fs::PermissionsExt;
    let (dir, deck) = small_deck();
    let out = dir.path().join("kept.ras");
    for mode in [0o640, 0o600, 0o664] {
        std::fs::write(&out, b"old").unwrap();
        std::fs::set_permissions(&out, std::fs::Permissions::from_mode(mode)).unwrap();
        let o = run(raytrace_command().arg("-q").arg(&deck).arg("-o").arg(&out));
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(read_raster_file(&out).is_ok());
        let now = std::fs::metadata(&out).unwrap().permissions().mode() & 0o7777;
        assert_eq!(now, mode, "{now:o} against {mode:o}");
    }
}

/// An output over a file this user may not write, in a folder anyone may
/// write (a shared folder): refused as `cp` refuses it, exit 1, the
/// reason named, the file untouched. The rename would need only the
/// folder's permission, so without the check the file would be replaced.
///
/// Root may write a mode-0444 file (`access(2)` W_OK succeeds for root),
/// so as root the program runs as the user `nobody` (setpriv), for whom
/// the file, root's, is read-only; as anyone else the file is theirs with
/// mode 0444, which its owner may not write either. Either way the test
/// fails without the refusal.
#[test]
fn a_read_only_file_of_another_user_is_not_replaced() {
    use std::os::unix::fs::{MetadataExt, PermissionsExt};
    let (dir, deck) = small_deck();
    let open = std::fs::Permissions::from_mode;
    std::fs::set_permissions(dir.path(), open(0o777)).unwrap();
    std::fs::set_permissions(&deck, open(0o644)).unwrap();
    let out = dir.path().join("theirs.ras");
    std::fs::write(&out, b"another user's raster").unwrap();
    std::fs::set_permissions(&out, open(0o444)).unwrap();
    let root = std::fs::metadata(&out).unwrap().uid() == 0;
    let mut cmd = if root {
        let mut c = Command::new("setpriv");
        c.args(["--reuid=nobody", "--regid=nogroup", "--clear-groups", "--"])
            .arg(env!("CARGO_BIN_EXE_raytrace"));
        c
    } else {
        raytrace_command()
    };
    let o = run(cmd.arg("-q").arg(&deck).arg("-o").arg(&out).current_dir(dir.path()));
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("theirs.ras: it exists and this user may not write it (mode 0444") && e.contains("not replaced"),
        "{e}"
    );
    assert_eq!(std::fs::read(&out).unwrap(), b"another user's raster");
    assert_eq!(std::fs::metadata(&out).unwrap().mode() & 0o7777, 0o444);
    assert_eq!(file_names(dir.path()), ["small.deck", "theirs.ras"]);
}

/// `-o NAME.exr`: OpenEXR (its magic number first), R, G and B as 32-bit
/// floats equal to the render's colours before the raster's clamp and
/// rounding (the library's render of the same deck), not the bytes.
#[test]
fn exr_holds_the_radiance_before_quantisation() {
    use exr::prelude::{read_first_rgba_layer_from_file, Vec2};
    let (dir, deck) = small_deck();
    let out = dir.path().join("small.exr");
    let o = run(raytrace_command().arg("-q").arg(&deck).arg("-o").arg(&out));
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(bytes[..4], [0x76, 0x2f, 0x31, 0x01], "the OpenEXR magic number");

    let input = raytrace::run::DeckInput::read(&deck).unwrap();
    let opts = raytrace::options::Options::default();
    let prepared = raytrace::raytrace::Prepared::new(input.initialize(opts.fidelity).unwrap(), opts).unwrap();
    let r = raytrace::raytrace::render(&prepared, &raytrace::raytrace::Request::STILL).unwrap();
    let (w, h) = (r.raster.width, r.raster.height);
    let image = read_first_rgba_layer_from_file(
        &out,
        |size: Vec2<usize>, _| (size, vec![[0f32; 3]; size.0 * size.1]),
        |(size, px): &mut (Vec2<usize>, Vec<[f32; 3]>), Vec2(x, y), (red, g, b, _): (f32, f32, f32, f32)| {
            px[y * size.0 + x] = [red, g, b]
        },
    )
    .unwrap();
    let (size, pixels) = &image.layer_data.channel_data.pixels;
    assert_eq!((size.0, size.1), (w, h));
    let mut between = 0;
    for (i, (got, c)) in pixels.iter().zip(&r.colours).enumerate() {
        assert_eq!(*got, [c.x as f32, c.y as f32, c.z as f32], "pixel {i}");
        // A value no byte of the raster could give (k/255).
        between += got
            .iter()
            .filter(|v| ((**v * 255.0).round() - **v * 255.0).abs() > 1e-3)
            .count();
    }
    assert!(between > 0, "{between} values between the bytes");
}

/// SIGINT says what was kept and the command that goes on: for a still,
/// nothing (it is written whole when done) and the command again with
/// `--resume`; for a film, the frames written whole so far and
/// `--resume`, which renders only the rest.
#[test]
fn a_signal_says_what_is_kept_and_how_to_go_on() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("big.ras");
    let (child, _temp) = start_big_render(dir.path(), &out);
    let kill = |pid: u32| {
        assert!(Command::new("kill")
            .args(["-INT", &pid.to_string()])
            .status()
            .unwrap()
            .success())
    };
    kill(child.id());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("raytrace: stopped by SIGINT (Ctrl-C): nothing is written: a still is written whole"),
        "{e}"
    );
    assert!(e.contains(" -o ") && e.trim_end().ends_with("big.ras --resume"), "{e}");

    // A film of 200 frames, each a moment: stopped once two are there.
    let deck = dir.path().join("film.deck");
    std::fs::write(
        &deck,
        BIG.replace("image 4096 4096  mask 2", "image 300 300 mask 3") + "motion ball to 1 0 0\nfilm 200\n",
    )
    .unwrap();
    let stem = dir.path().join("f");
    let child = raytrace_command()
        .args(["-q", "--threads", "1"])
        .arg(&deck)
        .arg("-o")
        .arg(&stem)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let first = dir.path().join("f.0001.ras");
    // Once the second is there, the first is counted (it is counted as soon
    // as it is renamed into place, before the second's render begins).
    let second = dir.path().join("f.0002.ras");
    let started = Instant::now();
    while !second.exists() {
        assert!(started.elapsed() < Duration::from_secs(120), "no first frame");
        std::thread::sleep(Duration::from_millis(5));
    }
    kill(child.id());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(130), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("raytrace: stopped by SIGINT (Ctrl-C): "), "{e}");
    assert!(e.contains(" of frames 1..200 written whole and kept ("), "{e}");
    assert!(e.contains(&format!("({} … ", first.display())), "{e}");
    assert!(e.trim_end().ends_with(&format!("{} --resume", stem.display())), "{e}");
}

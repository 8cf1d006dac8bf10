//! `tools join --tiles` as a user meets it: the bands of a still stacked
//! into the whole image, and the parts that do not fit one image (another
//! width, another N, a band missing, repeated or out of order, a file that
//! is no band) refused with exit 2, naming the file, writing nothing.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use raytrace::options::Options;
use raytrace::raster::{encode_raster, Raster};
use raytrace::raytrace::{render, Prepared, Request};
use raytrace::tile::{write_tile, Tile};

/// A small scene of the shipped decks, `width`×`height`.
fn prepared(width: usize, height: usize) -> Prepared {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../legacy_pascal/decks");
    let src = std::fs::read(dir.join("fig5_8.deck")).unwrap();
    let mut scene = raytrace::deck::initialize(&src, "fig5_8.deck", &dir, Default::default()).unwrap();
    scene.resize(width, height, 1);
    Prepared::new(scene, Options::default()).unwrap()
}

/// Writes band `k` of `n` of `p`'s image to `dir/name`.
fn band(p: &Prepared, k: u32, n: u32, dir: &Path, name: &str) -> PathBuf {
    let tile = Tile { k, n };
    let height = p.scene().image.height;
    let r = render(p, &Request::STILL.rows(tile.band(height).unwrap())).unwrap();
    let mut bytes = Vec::new();
    write_tile(&r.raster, tile, height, &mut bytes).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn join(parts: &[&PathBuf], out: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tools"))
        .args(["join", "--tiles"])
        .args(parts)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn the_bands_stack_into_the_whole_image() {
    let dir = tempfile::tempdir().unwrap();
    let p = prepared(17, 10);
    let parts: Vec<PathBuf> = (1..=3)
        .map(|k| band(&p, k, 3, dir.path(), &format!("b{k}.ras")))
        .collect();
    let out = dir.path().join("whole.ras");
    let o = join(&parts.iter().collect::<Vec<_>>(), &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let whole: Raster = render(&p, &Request::STILL).unwrap().raster;
    assert_eq!(std::fs::read(&out).unwrap(), encode_raster(&whole));
    // Another format by the extension.
    let png = dir.path().join("whole.png");
    assert!(join(&parts.iter().collect::<Vec<_>>(), &png).status.success());
    assert_eq!(raytrace::image_file::read_image_file(&png).unwrap(), whole);
}

#[test]
fn parts_that_do_not_fit_one_image_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let p = prepared(17, 10);
    let b: Vec<PathBuf> = (1..=3).map(|k| band(&p, k, 3, d, &format!("b{k}.ras"))).collect();
    let narrow = band(&prepared(16, 10), 2, 3, d, "narrow.ras");
    let of_two = band(&p, 2, 2, d, "of_two.ras");
    let first_of_two = band(&p, 1, 2, d, "first_of_two.ras");
    let taller = band(&prepared(17, 11), 2, 3, d, "taller.ras");
    let plain = d.join("plain.ras");
    std::fs::write(&plain, encode_raster(&render(&p, &Request::STILL).unwrap().raster)).unwrap();
    let cut = d.join("cut.ras");
    std::fs::write(&cut, &std::fs::read(&b[1]).unwrap()[..100]).unwrap();
    let cases: Vec<(Vec<&PathBuf>, &PathBuf, &str)> = vec![
        (vec![&b[0], &narrow, &b[2]], &narrow, "16×10 image"),
        (vec![&b[0], &of_two, &b[2]], &of_two, "they are not bands of one image"),
        (vec![&b[0], &taller, &b[2]], &taller, "17×11 image"),
        (vec![&b[0], &b[2]], &b[2], "tile 2/3 is missing before it"),
        (vec![&b[0], &b[1]], &b[1], "tile 3/3 is missing"),
        (
            vec![&first_of_two],
            &first_of_two,
            "the last tile given is 1/2: tile 2/2 is missing",
        ),
        (
            vec![&b[0]],
            &b[0],
            "the last tile given is 1/3: tiles 2..3 of 3 are missing",
        ),
        (vec![&b[1], &b[2]], &b[1], "tile 1/3 is missing before it"),
        (vec![&b[0], &b[0], &b[1]], &b[0], "again or out of order"),
        (vec![&b[0], &b[1], &b[2], &b[2]], &b[2], "again or out of order"),
        (
            vec![&b[0], &plain, &b[2]],
            &plain,
            "not a tile of `raytrace --tile K/N`",
        ),
        (vec![&b[0], &cut, &b[2]], &cut, "truncated"),
    ];
    let out = d.join("whole.ras");
    for (parts, named, says) in cases {
        let o = join(&parts, &out);
        let e = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{parts:?}: {e}");
        assert!(
            e.starts_with(&format!("tools: {}: ", named.display())) && e.contains(says),
            "{parts:?}: {e}"
        );
        assert!(!out.exists(), "{parts:?} wrote {}", out.display());
    }
    let missing = d.join("none.ras");
    let o = join(&[&b[0], &missing], &out);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("none.ras"), "{}", stderr(&o));
    // A bad output name is a usage error, before any band is read.
    let o = join(&[&b[0], &b[1], &b[2]], &d.join("whole.jpg"));
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

/// A FIFO at `path` that a thread fills with `bytes` once a reader opens
/// it (the shell's `<(cat a.ras)`).
fn fifo(path: &Path, bytes: Vec<u8>) -> std::thread::JoinHandle<()> {
    assert!(Command::new("mkfifo").arg(path).status().unwrap().success());
    let path = path.to_path_buf();
    std::thread::spawn(move || {
        use std::io::Write;
        let mut f = std::fs::OpenOptions::new().write(true).open(path).unwrap();
        // The reader may stop at the end of what it needs.
        let _ = f.write_all(&bytes);
    })
}

/// `tools join <(cat a.ras) <(cat b.ras) -o f.png` and `--tiles` through
/// pipes: each part is opened once and read front to back.
#[test]
fn parts_are_read_from_pipes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let p = prepared(17, 10);
    let b: Vec<PathBuf> = (1..=2).map(|k| band(&p, k, 2, d, &format!("b{k}.ras"))).collect();
    let whole = d.join("whole.ras");
    assert!(join(&b.iter().collect::<Vec<_>>(), &whole).status.success());
    let pipes: Vec<PathBuf> = (1..=2).map(|k| d.join(format!("pipe{k}"))).collect();
    let writers: Vec<_> = pipes
        .iter()
        .zip(&b)
        .map(|(f, part)| fifo(f, std::fs::read(part).unwrap()))
        .collect();
    let piped = d.join("piped.ras");
    let o = join(&pipes.iter().collect::<Vec<_>>(), &piped);
    assert!(o.status.success(), "{}", stderr(&o));
    writers.into_iter().for_each(|w| w.join().unwrap());
    assert_eq!(std::fs::read(&piped).unwrap(), std::fs::read(&whole).unwrap());

    // A film's frames: the whole image twice, as an animated PNG.
    let frames: Vec<PathBuf> = (1..=2).map(|k| d.join(format!("frame{k}"))).collect();
    let writers: Vec<_> = frames.iter().map(|f| fifo(f, std::fs::read(&whole).unwrap())).collect();
    let apng = d.join("film.png");
    let o = Command::new(env!("CARGO_BIN_EXE_tools"))
        .arg("join")
        .args(&frames)
        .arg("-o")
        .arg(&apng)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", stderr(&o));
    writers.into_iter().for_each(|w| w.join().unwrap());
    let first = raytrace::image_file::read_image_file(&apng).unwrap();
    assert_eq!(first, raytrace::raster::read_raster_file(&whole).unwrap());
}

/// Bad input is exit 2 in every program: a file that is no picture, for
/// `tools join` as for `tools join --tiles`; a name that is not a PNG is a
/// usage error (2), found before any frame is read; nothing is written.
#[test]
fn join_exits_2_on_bad_input_and_bad_names() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let garbage = d.join("garbage.bin");
    std::fs::write(&garbage, b"this is no raster, PNG or PPM file").unwrap();
    let ok = band(&prepared(8, 4), 1, 1, d, "whole.ras");
    let cases: &[(&[&str], &str)] = &[
        (
            &["garbage.bin", "-o", "f.png"],
            "garbage.bin: not a Sun raster, PNG or PPM file",
        ),
        (
            &["--tiles", "garbage.bin", "-o", "f.png"],
            "garbage.bin: not a Sun raster",
        ),
        (
            &["whole.ras", "-o", "f.gif"],
            "-o 'f.gif': an animated PNG or a strip is a PNG",
        ),
        (&["whole.ras", "-o", "f.png", "--strip", "s.jpg"], "--strip 's.jpg'"),
        (&["missing.ras", "-o", "f.png"], "missing.ras: No such file"),
    ];
    for (args, says) in cases {
        let o = Command::new(env!("CARGO_BIN_EXE_tools"))
            .arg("join")
            .args(*args)
            .current_dir(d)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
        assert!(!d.join("f.png").exists() && !d.join("s.jpg").exists(), "{args:?}");
    }
    assert!(ok.exists());
}

/// Bad input is exit 2 in every program: the tools that read a deck
/// (`frames`, `heatmap`, `preview`, as `bench` and `pov` did) refuse a bad
/// one as an input error, naming it, before their own work.
#[test]
fn the_tools_exit_2_on_a_bad_deck() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.deck"), "garbage\n").unwrap();
    for args in [
        &["frames", "bad.deck"][..],
        &["heatmap", "bad.deck", "--out", "h.png"],
        &["preview", "bad.deck", "goblet"],
        &["pov", "bad.deck", "-o", "x.pov"],
        &["bench", "bad.deck", "--runs", "1"],
    ] {
        let o = Command::new(env!("CARGO_BIN_EXE_tools"))
            .args(args)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("bad.deck:1:1"), "{args:?}: {}", stderr(&o));
    }
}

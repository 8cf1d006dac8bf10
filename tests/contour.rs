//! `contour`, the contour editor, without a window: the scripted edits and
//! the save back into the deck (only the record's lines change), the bad
//! input of issue 28 (too few points, more than 60 segments, no closed
//! curve, a deck with an error, a NAME that is no sweep), and what the
//! saved deck renders.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use raytrace::editor::document::{sweeps, Document, Target};
use raytrace::editor::model::Edit;
use raytrace::options::Fidelity;
use raytrace::run::DeckInput;
use raytrace::types::{CurveKind, PrimitiveClass};

fn decks() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/decks")
}

fn contour(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_contour"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs `contour DECK NAME --script (edits) -o new.deck` in a temporary
/// folder; the output, and the new deck's text when written.
fn scripted(deck: &str, name: &str, edits: &str) -> (Output, Option<String>) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("edits"), edits).unwrap();
    let deck = decks().join(deck);
    let o = contour(
        &[deck.to_str().unwrap(), name, "--script", "edits", "-o", "new.deck"],
        dir.path(),
    );
    let text = std::fs::read_to_string(dir.path().join("new.deck")).ok();
    (o, text)
}

/// The lines of `a` and `b` that differ, by line number (both must have
/// as many lines).
fn changed_lines(a: &str, b: &str) -> Vec<usize> {
    let (a, b): (Vec<&str>, Vec<&str>) = (a.lines().collect(), b.lines().collect());
    assert_eq!(a.len(), b.len());
    (0..a.len()).filter(|&i| a[i] != b[i]).map(|i| i + 1).collect()
}

#[test]
fn a_script_changes_only_the_lines_of_the_record_it_edits() {
    let original = std::fs::read_to_string(decks().join("fig5_8.deck")).unwrap();
    let (o, new) = scripted("fig5_8.deck", "goblet", "move 4 0.05 0\nmove 13 -0.1 0.25\n");
    assert!(o.status.success(), "{}", stderr(&o));
    let new = new.unwrap();
    // Point 4 is line 21, point 13 line 30: nothing else moved, comments
    // and all.
    assert_eq!(changed_lines(&original, &new), vec![21, 30]);
    assert!(new.contains("\n     1.05       0\n"), "{new}");
    assert!(new.contains("\n     0.85    2.75   { the lip }\n"), "{new}");
}

#[test]
fn the_saved_deck_reads_back_as_the_edited_contour() {
    let (o, new) = scripted(
        "fig5_10.deck",
        "last",
        "insert 3 -1.2 0\ndelete 1\nmove 1 0.25 0.125\ncurve bspline\n",
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let deck = DeckInput {
        source: new.unwrap().into_bytes(),
        name: "new.deck".into(),
        dir: decks(),
        stem: "new".into(),
    };
    let doc = Document::open(deck, "last", Fidelity::Thesis).unwrap();
    assert_eq!(doc.target, Target::KeyShape { record: 0, index: 0 });
    assert_eq!(
        doc.original.uv(),
        vec![[-0.75, 1.125], [-1.2, 0.0], [-1.0, -1.0], [1.0, -1.0]]
    );
}

#[test]
fn the_document_edits_what_it_opened() {
    let deck = DeckInput::read(&decks().join("fig5_8.deck")).unwrap();
    let doc = Document::open(deck, "goblet", Fidelity::Thesis).unwrap();
    assert_eq!(sweeps(&doc.scene), vec![("goblet".to_string(), Target::Object(1))]);
    assert_eq!(
        (doc.original.class, doc.original.curve),
        (PrimitiveClass::Rotation, CurveKind::Bezier)
    );
    assert_eq!(doc.original.points.len(), 21);
    let mut c = doc.original.clone();
    assert_eq!(doc.save(&c).unwrap(), doc.deck.source, "no edit saves the same bytes");
    c.apply(Edit::Sweep(PrimitiveClass::Translation)).unwrap();
    let scene = doc.scene_with(&c);
    assert_eq!(scene.objects[1].class, PrimitiveClass::Translation);
    assert_eq!(
        doc.scene.objects[1].class,
        PrimitiveClass::Rotation,
        "the opened scene stays"
    );
}

#[test]
fn refused_contours_write_nothing_and_exit_2() {
    let many: String = (0..61)
        .map(|k| format!("insert 1 {} 0.5\n", 0.5 + k as f64 * 0.001))
        .collect();
    for (deck, name, edits, reason) in [
        (
            "fig5_10.deck",
            "last",
            "delete 1\n",
            "too few points: a bspline contour needs at least 4",
        ),
        (
            "fig5_8.deck",
            "goblet",
            "delete 1\n",
            "no closed curve: a bezier contour is 3k points",
        ),
        ("fig5_10.deck", "first", many.as_str(), "more than 60 segments"),
        (
            "fig5_10.deck",
            "last",
            "move 1 -1 0\nmove 2 1 0\nmove 3 1 0\nmove 4 -1 0\n",
            "no closed curve: the points lie on one line",
        ),
        ("fig5_10.deck", "last", "sweep rotation\n", "point 2 has U = -1 < 0"),
        (
            "fig5_10.deck",
            "last",
            "sweep conic\n",
            "key shapes must be of one class",
        ),
    ] {
        let (o, new) = scripted(deck, name, edits);
        assert_eq!(o.status.code(), Some(2), "{deck} {name}: {}", stderr(&o));
        assert!(stderr(&o).contains(reason), "{}", stderr(&o));
        assert!(stderr(&o).contains("new.deck: not saved: "), "{}", stderr(&o));
        assert!(new.is_none(), "{deck} {name}: nothing is written");
    }
}

#[test]
fn a_script_error_names_its_line_and_exits_2() {
    let (o, new) = scripted("fig5_8.deck", "goblet", "move 1 0 0\n\nmove 99 0 0\n");
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("edits:3: there is no point 99: the points are 1..21"),
        "{}",
        stderr(&o)
    );
    assert!(new.is_none());
}

#[test]
fn a_name_that_is_no_sweep_lists_the_sweeps() {
    let (o, _) = scripted("fig5_9.deck", "floor", "");
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("'floor' is a block, not a sweep; its sweeps: "), "{e}");
    for name in ["N", "E", "C"] {
        assert!(e.contains(name), "{e}");
    }
    let (o, _) = scripted("fig5_1.deck", "ball", "");
    assert!(stderr(&o).contains("the deck has no sweep"), "{}", stderr(&o));
}

#[test]
fn a_deck_with_an_error_is_named_at_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.deck"), "view eye 0 0 0 lok 0 0 0\n").unwrap();
    let o = contour(&["bad.deck", "s", "-o", "x.deck"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("bad.deck:1:16: view"), "{}", stderr(&o));
    assert!(!dir.path().join("x.deck").exists());
}

#[test]
fn the_command_line_is_checked() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("e"), "").unwrap();
    let deck = decks().join("fig5_8.deck");
    let deck = deck.to_str().unwrap();
    let o = contour(&[deck, "goblet", "--script", "e"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("-o NEW.deck"), "{}", stderr(&o));
    let o = contour(&[deck], dir.path());
    assert_eq!(o.status.code(), Some(2), "NAME is required");
    let o = contour(&["--new", deck, "-o", "x.deck"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("the file exists"), "{}", stderr(&o));
}

#[test]
fn a_new_deck_is_a_deck_with_a_sweep_to_edit() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("e"), "sweep conic\n").unwrap();
    let o = contour(&["--new", "n.deck", "--script", "e", "-o", "n.deck"], dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path().join("n.deck")).unwrap();
    assert!(
        text.contains("sweep shape red conic bspline at 0 0 0 length 1 scale 0.5\n"),
        "{text}"
    );
    let deck = DeckInput::read(&dir.path().join("n.deck")).unwrap();
    assert!(deck.initialize(Fidelity::Thesis).is_ok());
}

#[test]
fn without_a_display_the_window_says_how_to_do_without() {
    let dir = tempfile::tempdir().unwrap();
    let deck = decks().join("fig5_8.deck");
    let o = Command::new(env!("CARGO_BIN_EXE_contour"))
        .args([deck.to_str().unwrap(), "goblet"])
        .current_dir(dir.path())
        .env_remove("DISPLAY")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("cannot open a window (DISPLAY is not set)"), "{e}");
    assert!(
        e.contains("--script EDITS -o NEW.deck") && e.contains("xvfb-run"),
        "{e}"
    );
}

#[test]
fn a_screenshot_and_the_list_are_made_without_a_window() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("e"), "move 1 0.5 0\n").unwrap();
    let deck = decks().join("fig5_10.deck");
    let o = contour(
        &[
            deck.to_str().unwrap(),
            "last",
            "--script",
            "e",
            "--screenshot",
            "s.png",
            "--list",
            "--time",
            "0.5",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let list = String::from_utf8_lossy(&o.stdout);
    let lines: Vec<&str> = list.lines().collect();
    assert!(
        lines[0].starts_with("# K\tU\tV\tX\tY (") && lines[0].ends_with(" pixels a unit)"),
        "{list}"
    );
    assert_eq!(lines.len(), 5);
    assert!(lines[1].starts_with("1\t1.5\t1\t"), "{list}");
    let png = raytrace::image_file::read_image_file(&dir.path().join("s.png")).unwrap();
    assert_eq!((png.width, png.height), (1024, 864));
    // `--screenshot -` writes the PNG to standard output, as psout's does.
    let o = contour(&[deck.to_str().unwrap(), "last", "--screenshot", "-"], dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let png = raytrace::image_file::read_image(&o.stdout[..], None).unwrap();
    assert_eq!((png.width, png.height), (1024, 864));
    let o = contour(&[deck.to_str().unwrap(), "last", "--screenshot", "s.ppm"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    let o = contour(&[deck.to_str().unwrap(), "last", "--list", "--time", "2"], dir.path());
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn a_rotation_made_a_translation_gets_a_length_and_back_loses_it() {
    let (o, new) = scripted("fig5_8.deck", "goblet", "sweep translation\n");
    assert!(o.status.success(), "{}", stderr(&o));
    let new = new.unwrap();
    assert!(
        new.contains("\nsweep goblet red translation bezier at 0 0 0 axis z length 1\n"),
        "{new}"
    );
    let (o, new) = scripted("fig5_6.deck", "star", "sweep rotation\nsweep translation\n");
    assert!(o.status.success(), "{}", stderr(&o));
    let original = std::fs::read_to_string(decks().join("fig5_6.deck")).unwrap();
    assert_eq!(new.unwrap(), original, "there and back is no change");
}

/// A script without end (`--script /dev/zero`, or `yes | contour …
/// --script -`) is read as a deck is, to 64 MiB and a byte: exit 2, the
/// error at the line of the byte past the limit, nothing written.
#[test]
fn a_script_without_end_is_refused_at_its_limit() {
    let dir = tempfile::tempdir().unwrap();
    let deck = decks().join("fig5_8.deck");
    let deck = deck.to_str().unwrap();
    let o = contour(&[deck, "goblet", "--script", "/dev/zero", "-o", "new.deck"], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        "contour: /dev/zero:1: the script is larger than 64 MiB, the most the editor reads\n"
    );
    let mut yes = Command::new("yes")
        .arg("# a comment")
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_contour"))
        .args([deck, "goblet", "--script", "-", "-o", "new.deck"])
        .current_dir(dir.path())
        .stdin(yes.stdout.take().unwrap())
        .output()
        .unwrap();
    let _ = yes.kill();
    let _ = yes.wait();
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    // 64 MiB of "# a comment\n", 12 bytes a line: the byte past is on line 5592406.
    assert!(
        stderr(&o).starts_with("contour: <stdin>:5592406: the script is larger than 64 MiB"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.path().join("new.deck").exists());
}

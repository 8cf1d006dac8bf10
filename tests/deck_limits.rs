//! The deck reader's limits (issues 14 and 15): the numbers' range, the
//! deck's size, bytes that are not ASCII, what an error echoes, the
//! suggestion after an unknown name; and the renderer's refusal of colours
//! that are not finite.
//!
//! The decks of tests/data/decks are the issues' reproducers and the
//! fuzzer's findings: each says on its second line what reading it gives,
//! `{ expect: ok }` (and every pixel of a small render is finite) or
//! `{ expect: LINE:COL: RECORD 'NAME': MESSAGE }`.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::render_still;
use raytrace::deck::{initialize, DeckError, FIELDS, MAX_DECK_BYTES, MAX_OBJECTS, RECORDS};
use raytrace::options::{Fidelity, Options};
use raytrace::scene::Scene;

fn read(deck: impl AsRef<[u8]>) -> Result<Scene, DeckError> {
    initialize(&deck, "t.deck", Path::new("."), Fidelity::Thesis)
}

/// The message of a deck's error, without the file name.
#[track_caller]
fn error(deck: impl AsRef<[u8]>) -> String {
    match read(deck) {
        Ok(_) => panic!("the deck was accepted"),
        Err(e) => e.to_string().trim_start_matches("t.deck:").to_string(),
    }
}

const BASE: &str = "\
view eye 0 -10 4 look 0 0 1 screen 4 distance 5
image 16 16 mask 1
light sun 5 -5 10 1 1 1
surface red opaque color 1 0 0 ka 0.1 kd 0.7 ks 0.2 kt 0
sphere ball red at 0 0 1 radius 1
";

fn fixtures() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/decks");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "deck"))
        .collect();
    files.sort();
    files
}

/// Every fixture reads as its second line says; the accepted ones render
/// (24×24) with every pixel finite.
#[test]
fn the_fixtures_read_as_they_say() {
    let files = fixtures();
    assert!(files.len() >= 13, "{files:?}");
    for path in files {
        let bytes = std::fs::read(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let second = bytes.split(|&b| b == b'\n').nth(1).unwrap();
        let expect = std::str::from_utf8(second)
            .ok()
            .and_then(|l| l.strip_prefix("{ expect: "))
            .and_then(|l| l.strip_suffix(" }"))
            .unwrap_or_else(|| panic!("{name}: no '{{ expect: … }}' on line 2"));
        let dir = path.parent().unwrap();
        match initialize(&bytes, &name, dir, Fidelity::Thesis) {
            Err(e) => assert_eq!(e.to_string(), format!("{name}:{expect}"), "{name}"),
            Ok(mut scene) => {
                assert_eq!(expect, "ok", "{name} was accepted");
                let opts = Options::default();
                scene.image.width = 24;
                scene.image.height = 24;
                let colours = render_still(&scene, &opts).colours;
                let bad = colours.iter().filter(|c| !c.is_finite()).count();
                assert_eq!(bad, 0, "{name}: pixels that are not finite");
            }
        }
    }
}

#[test]
fn numbers_at_the_edges_of_the_range() {
    assert!(read(BASE.replace("radius 1", "radius 1e7")).is_ok());
    assert!(read(BASE.replace("radius 1", "radius 1e-7")).is_ok());
    assert!(read(BASE.replace("at 0 0 1", "at -1e7 0 10000000.0")).is_ok());
    assert_eq!(
        error(BASE.replace("radius 1", "radius 1.0000001e7")),
        "5:33: sphere 'ball': expected a number in 1e-7..1e7 after 'radius', found '1.0000001e7'"
    );
    assert_eq!(
        error(BASE.replace("radius 1", "radius 9.9e-8")),
        "5:33: sphere 'ball': expected a number in 1e-7..1e7 after 'radius', found '9.9e-8'"
    );
    assert_eq!(
        error(BASE.replace("at 0 0 1", "at 0 -10000001 1")),
        "5:22: sphere 'ball': expected a number in -1e7..1e7 after 'at', found '-10000001'"
    );
    // Past what a 64-bit real holds: the same error.
    assert_eq!(
        error(BASE.replace("5 -5 10", "5 -5 1e400")),
        "3:16: light 'sun': expected a number in -1e7..1e7 for Z, found '1e400'"
    );
    // An emitting surface's colour: ≥ 0, in range.
    assert_eq!(
        error(format!("{BASE}surface lamp light color 1 2e7 1 ka 0 kd 0 ks 0 kt 0\n")),
        "6:28: surface 'lamp': expected a number in -1e7..1e7 after 'color', found '2e7'"
    );
}

/// `translate` may not carry an object out of the range.
#[test]
fn translate_stays_in_the_range() {
    let deck = format!("{BASE}translate ball 6e6 0 0\n");
    assert!(read(&deck).is_ok());
    assert_eq!(
        error(format!("{deck}translate ball 6e6 0 0\n")),
        "7:16: translate 'ball': this moves the object to (12000000, 0, 1), out of the deck's range -1e7..1e7"
    );
}

#[test]
fn unknown_records_fields_and_names_get_the_nearest_one() {
    assert_eq!(
        error(format!("{BASE}surfce blue opaque\n")),
        "6:1: deck: unknown record 'surfce' — did you mean 'surface'?"
    );
    assert_eq!(
        error(format!("{BASE}SPHEER b red at 0 0 0 radius 1\n")),
        "6:1: deck: unknown record 'SPHEER' — did you mean 'sphere'?"
    );
    // Nothing near: no suggestion.
    assert_eq!(error(format!("{BASE}zzzz\n")), "6:1: deck: unknown record 'zzzz'");
    assert_eq!(
        error(BASE.replace("kt 0", "kt 0 refelct 0.5")),
        "4:58: surface 'red': expected end of line or 'ambient', 'reflect', 'index', 'gloss', found 'refelct' — did you mean 'reflect'?"
    );
    assert_eq!(
        error(BASE.replace("opaque", "opaqe")),
        "4:13: surface 'red': expected a surface kind (opaque, mirrored, transparent, crystal, light, background), found 'opaqe' — did you mean 'opaque'?"
    );
    assert_eq!(
        error(BASE.replace("ball red", "ball rde")),
        "5:13: sphere 'ball': unknown surface 'rde' — did you mean 'red'?"
    );
    assert_eq!(
        error(format!("{BASE}rotate bal z 10\n")),
        "6:8: rotate: unknown object 'bal' — did you mean 'ball'?"
    );
}

/// DECK.md's synopsis of the records: the code block under "## Records".
fn records_synopsis() -> String {
    let doc = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/DECK.md")).unwrap();
    let block = doc.split("## Records\n```\n").nth(1).unwrap();
    block.split("```").next().unwrap().to_string()
}

/// Every record DECK.md lists is one `RECORDS` holds, and each is read as a
/// record (not "unknown record").
#[test]
fn the_suggested_records_are_deck_md_s() {
    let block = records_synopsis();
    let mut listed: Vec<&str> = block
        .lines()
        .filter(|l| l.starts_with(|c: char| c.is_ascii_lowercase()))
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    listed.sort_unstable();
    listed.dedup();
    let mut known = RECORDS.to_vec();
    known.sort_unstable();
    assert_eq!(listed, known);
    for kw in RECORDS {
        let e = error(format!("{BASE}{kw} @\n"));
        assert!(!e.contains("unknown record"), "{kw}: {e}");
    }
}

/// `FIELDS`, the order a misplaced field is told, is DECK.md's: each
/// record's lower-case words in its synopsis (comments, choices such as
/// `x|y|z` and `end` aside), in order.
#[test]
fn the_field_order_is_deck_md_s() {
    let block = records_synopsis();
    let mut listed: Vec<(&str, Vec<&str>)> = Vec::new();
    for line in block.lines() {
        let mut words = line.split('{').next().unwrap().split_whitespace();
        if line.starts_with(|c: char| c.is_ascii_lowercase()) {
            listed.push((words.next().unwrap(), Vec::new()));
        }
        let fields = words
            .map(|w| w.trim_matches(['[', ']']))
            .filter(|w| !w.is_empty() && *w != "end" && w.chars().all(|c| c.is_ascii_lowercase()));
        listed.last_mut().unwrap().1.extend(fields);
    }
    // Records without fields are not in FIELDS; `keyframe` has two lines.
    listed.retain(|(_, fields)| !fields.is_empty());
    listed.dedup();
    let known: Vec<(&str, Vec<&str>)> = FIELDS.iter().map(|(r, f)| (*r, f.to_vec())).collect();
    assert_eq!(listed, known);
}

/// DECK.md's sample error is one the reader prints.
#[test]
fn deck_md_s_sample_error_is_real() {
    let doc = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/DECK.md")).unwrap();
    let errors = doc.split("## Errors\n").nth(1).unwrap();
    let sample: String = errors
        .split('`')
        .nth(1)
        .unwrap()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    // `FILE:LINE:…`: the shipped deck FILE with `length` misspelt on LINE.
    let mut parts = sample.split(':');
    let (file, line) = (parts.next().unwrap(), parts.next().unwrap().parse::<usize>().unwrap());
    let deck = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("legacy_pascal/decks")
        .join(file);
    let text = std::fs::read_to_string(&deck).unwrap();
    assert!(text.lines().nth(line - 1).unwrap().contains(" length "));
    let broken: String = text
        .lines()
        .enumerate()
        .map(|(i, l)| if i == line - 1 { l.replacen(" length ", " lenght ", 1) } else { l.to_string() } + "\n")
        .collect();
    let e = initialize(&broken, file, deck.parent().unwrap(), Fidelity::Thesis).unwrap_err();
    assert_eq!(e.to_string(), sample);
}

#[test]
fn a_deck_past_the_size_limit_is_refused_where_the_limit_is_passed() {
    let mut deck = BASE.as_bytes().to_vec();
    deck.resize(MAX_DECK_BYTES, b'\n');
    assert!(read(&deck).is_ok(), "a deck of exactly the limit is read");
    deck.push(b'\n');
    let lines = MAX_DECK_BYTES - BASE.len() + 5;
    assert_eq!(
        error(&deck),
        format!(
            "{}:1: deck: the deck is larger than 64 MiB, the most the reader takes",
            lines + 1
        )
    );
}

/// A deck of more object records than the port takes (within the 64 MiB
/// of text: a million short records) is refused at the first name past the
/// limit, before it is prepared.
#[test]
fn a_deck_past_the_object_limit_is_refused_where_the_limit_is_passed() {
    let mut deck = String::from(BASE);
    for i in 1..=MAX_OBJECTS {
        deck.push_str(&format!("sphere s{i} red at 0 0 {} radius 1\n", i % 7));
    }
    assert!(deck.len() < MAX_DECK_BYTES);
    assert_eq!(
        error(&deck),
        format!(
            "{}:8: sphere 's{MAX_OBJECTS}': a deck may have at most {MAX_OBJECTS} object records (the port's \
             limit, which keeps a render of the largest deck within about 1.5 GB of memory): this is one more",
            MAX_OBJECTS + 5
        )
    );
}

#[test]
fn echoed_words_are_cut_and_escaped() {
    let long = "x".repeat(100_000);
    let e = error(format!("{BASE}{long}\n"));
    assert_eq!(
        e,
        format!("6:1: deck: unknown record '{}…' (100000 characters)", "x".repeat(40))
    );
    let e = error(format!("{BASE}a\0b\tc\x1b\n"));
    assert_eq!(e, "6:1: deck: unknown record 'a\\0b'");
    let e = error(format!("{BASE}sphere b red at 0 0 0 radius 1\x07\n"));
    assert_eq!(e, "6:30: sphere 'b': expected a number after 'radius', found '1\\x07'");
}

/// A pixel whose colour is NaN is counted and refused, not written black:
/// a sphere whose radius² overflows, put in past the reader.
#[test]
fn a_render_with_colours_that_are_not_finite_is_refused() {
    let mut scene = read(BASE).unwrap();
    let opts = Options::default();
    let fine = render_still(&scene, &opts);
    assert_eq!(fine.nonfinite, 0);
    assert!(fine.check_finite().is_ok());
    scene.objects[0].radius = 1e155;
    scene.objects[0].sphereo.z = 0.0;
    let bad = render_still(&scene, &opts);
    assert!(bad.nonfinite > 0);
    let e = bad.check_finite().unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "{} of 256 pixels have a colour that is not finite (NaN or infinite): the scene's numbers overflowed; nothing was written",
            bad.nonfinite
        )
    );
}

fn raytrace() -> Command {
    Command::new(env!("CARGO_BIN_EXE_raytrace"))
}

/// A deck read from a file without end stops at the limit with an error.
#[test]
fn a_deck_from_dev_zero_ends_with_the_size_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x.ras");
    let run = raytrace().args(["-q", "/dev/zero", "-o"]).arg(&out).output().unwrap();
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(
        stderr.trim_end(),
        format!(
            "raytrace: /dev/zero:1:{}: deck: the deck is larger than 64 MiB, the most the reader takes",
            MAX_DECK_BYTES + 1
        )
    );
    assert!(!out.exists());
}

/// Through the binary: a deck that is not UTF-8 keeps its position.
#[test]
fn a_deck_that_is_not_utf8_is_read_by_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/decks");
    let out = dir.path().join("x.ras");
    let run = raytrace()
        .arg("-q")
        .arg(fixtures.join("big5_comment.deck"))
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    assert!(out.exists());
    let deck = fixtures.join("latin1_outside_comment.deck");
    let run = raytrace()
        .arg("-q")
        .arg(&deck)
        .arg("-o")
        .arg(dir.path().join("y.ras"))
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.starts_with(&format!(
            "raytrace: {}:7:9: sphere: the byte 0xE9 is not ASCII",
            deck.display()
        )),
        "{stderr}"
    );
    assert!(!dir.path().join("y.ras").exists());
}

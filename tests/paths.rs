//! The path library (DECK.md, "The path library"; the port's extension of
//! §3.2.2): `path` records, `motion NAME path PATH`, `include FILE`, their
//! errors and their limits.

use std::path::{Path, PathBuf};

mod common;
use common::{raytrace_command, render_still};
use raytrace::deck::{initialize, DeckError, MAX_DECK_BYTES, MAX_INCLUDES, MAX_INCLUDE_DEPTH};
use raytrace::options::{Fidelity, Options};
use raytrace::raster::encode_raster;
use raytrace::scene::{Law, Scene};

/// A ball on a floor, lit, 24×20 pixels of 2×2 subpixels: the scene the
/// motions below move.
const SCENE: &str = "\
view  eye 0 -10 4  look 0 0 1  screen 8  distance 5
image 24 20  mask 2
light sun 5 -5 10  1 1 1
surface red opaque color 1 0 0 ka 0.2 kd 0.8 ks 0 kt 0
sphere ball red at -1.5 -0.5 0.8 radius 0.8
translate ball 0.25 0 0
";

/// The checkout's legacy_pascal folder.
fn legacy() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal")
}

/// Writes `files` (name, text) under `dir`, making folders as needed.
fn write(dir: &Path, files: &[(&str, &str)]) {
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
}

/// Reads the deck `name` under `dir` as `raytrace DIR/NAME` does: named by
/// its path, its files relative to its folder.
fn read(dir: &Path, name: &str) -> Result<Scene, DeckError> {
    let path = dir.join(name);
    let bytes = std::fs::read(&path).unwrap();
    initialize(
        &bytes,
        &path.to_string_lossy(),
        path.parent().unwrap(),
        Fidelity::Thesis,
    )
}

/// The error of the deck `name` under `dir`, with `dir/` taken off the
/// file names it holds.
#[track_caller]
fn error(dir: &Path, name: &str) -> String {
    match read(dir, name) {
        Ok(_) => panic!("{name} was accepted"),
        Err(e) => e.to_string().replace(&format!("{}/", dir.display()), ""),
    }
}

/// The bytes of the raster a render of `scene` writes.
fn rendered(scene: &Scene) -> Vec<u8> {
    encode_raster(&render_still(scene, &Options::default()).raster)
}

/// A path's `by` and `via` are offsets from the object's place (its
/// `sphereo` after the `translate` above): worked by hand.
#[test]
fn a_library_motion_is_offset_from_the_object_s_place() {
    let dir = tempfile::tempdir().unwrap();
    let deck = format!("{SCENE}path hop by 2 0 0 turn 0 0 90 via 0 0 2 2 0 2 law smooth\nmotion ball path hop\n");
    write(dir.path(), &[("t.deck", &deck)]);
    let scene = read(dir.path(), "t.deck").unwrap();
    let m = &scene.motions[0];
    assert_eq!(m.object, 0);
    assert_eq!(m.to.to_array(), [0.75, -0.5, 0.8]);
    assert_eq!(m.turn.to_array(), [0.0, 0.0, 90.0]);
    let via = m.via.unwrap().map(|p| p.to_array());
    assert_eq!(via, [[-1.25, -0.5, 2.8], [0.75, -0.5, 2.8]]);
    assert_eq!(m.law, Law::Smooth);
    // Without the optional fields: no turn, a straight line, constant.
    let deck = format!("{SCENE}path east by 1 2 3\nmotion ball path east\n");
    write(dir.path(), &[("t.deck", &deck)]);
    let m = read(dir.path(), "t.deck").unwrap().motions[0].clone();
    assert_eq!((m.to.to_array(), m.turn.to_array()), ([-0.25, 1.5, 3.8], [0.0; 3]));
    assert_eq!((m.via, m.law), (None, Law::Constant));
}

/// Every path of legacy_pascal/paths, taken from the library by a deck
/// that includes it, renders the same bytes as the same motion written
/// inline: its end and `via` points written out as the object's place plus
/// the offsets (`{}` of an f64 reads back as the same f64).
#[test]
fn each_library_path_renders_as_the_same_motion_written_inline() {
    let dir = tempfile::tempdir().unwrap();
    let include = legacy().join("paths/library.deck");
    let names = ["line", "line_accel", "line_decel", "line_ease", "arc", "hop", "quarter"];
    let mut pictures = Vec::new();
    for name in names {
        let library = format!("{SCENE}include {}\nmotion ball path {name}\n", include.display());
        write(dir.path(), &[("lib.deck", &library)]);
        let from_library = read(dir.path(), "lib.deck").unwrap();
        let m = &from_library.motions[0];
        let law = match m.law {
            Law::Constant => "constant",
            Law::Accelerate => "accelerate",
            Law::Decelerate => "decelerate",
            Law::Smooth => "smooth",
        };
        let v = |p: glam::DVec3| format!("{} {} {}", p.x, p.y, p.z);
        let via = m
            .via
            .map(|[a, b]| format!(" via {} {}", v(a), v(b)))
            .unwrap_or_default();
        let inline = format!("{SCENE}motion ball to {} turn {}{via} law {law}\n", v(m.to), v(m.turn));
        write(dir.path(), &[("inline.deck", &inline)]);
        let written = read(dir.path(), "inline.deck").unwrap();
        assert_eq!(written.motions[0].to, m.to, "{name}");
        let bytes = rendered(&from_library);
        assert_eq!(
            bytes,
            rendered(&written),
            "{name}: the library's render differs from the inline one"
        );
        pictures.push(bytes);
    }
    // The paths differ, and the ball moves: no two pictures alike.
    for (i, a) in pictures.iter().enumerate() {
        for (b, name) in pictures[i + 1..].iter().zip(&names[i + 1..]) {
            assert_ne!(a, b, "{} and {name} render alike", names[i]);
        }
    }
}

/// A library motion may take its object to the edge of the deck's range,
/// not past it.
#[test]
fn a_library_motion_reaches_the_edge_of_the_range() {
    let dir = tempfile::tempdir().unwrap();
    let deck = format!(
        "{SCENE}translate ball 1.25 0.5 -0.8\npath edge by -1e7 1e7 0 via 1e7 0 0 0 0 -1e7\nmotion ball path edge\n"
    );
    write(dir.path(), &[("t.deck", &deck)]);
    let m = read(dir.path(), "t.deck").unwrap().motions[0].clone();
    assert_eq!(m.to.to_array(), [-1e7, 1e7, 0.0]);
    assert_eq!(
        m.via.unwrap().map(|p| p.to_array()),
        [[1e7, 0.0, 0.0], [0.0, 0.0, -1e7]]
    );
}

/// Through the binary: tutorial step 5 (`motion ball2 path hop` from the
/// library) and the same deck with the motion written inline, as its
/// comment gives it, write the same raster file, byte for byte.
#[test]
fn tutorial_step_5_renders_as_its_inline_motion_through_the_binary() {
    let tutorial = legacy().join("tutorial");
    let text = std::fs::read_to_string(tutorial.join("5_path.deck")).unwrap();
    let inline_line = text
        .lines()
        .find(|l| l.trim_start().starts_with("motion ball2 to"))
        .expect("the comment gives the inline motion")
        .trim();
    let inline = text.replace("motion ball2 path hop\n", &format!("{inline_line}\n"));
    assert_ne!(inline, text);
    // A copy of the tutorial and the library, so that `include
    // ../paths/library.deck` holds for the decks written beside it.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for entry in std::fs::read_dir(legacy().join("paths")).unwrap() {
        let entry = entry.unwrap();
        let text = std::fs::read_to_string(entry.path()).unwrap();
        write(d, &[(&format!("paths/{}", entry.file_name().to_string_lossy()), &text)]);
    }
    let still = text.replace("motion ball2 path hop\n", "");
    write(
        d,
        &[
            ("tutorial/5_path.deck", &text),
            ("tutorial/inline.deck", &inline),
            ("tutorial/still.deck", &still),
        ],
    );
    let run = |deck: &str| {
        let out = d.join(format!("{deck}.ras"));
        let status = raytrace_command()
            .arg(d.join("tutorial").join(deck))
            .args(["-q", "--size", "64x48", "--mask", "2", "-o"])
            .arg(&out)
            .status()
            .unwrap();
        assert!(status.success(), "{deck}");
        std::fs::read(out).unwrap()
    };
    let library = run("5_path.deck");
    assert_eq!(library, run("inline.deck"));
    // And the hop shows: without the motion the picture differs.
    assert_ne!(library, run("still.deck"));
}

/// An included file's records are read in place: its surfaces and lights
/// join the scene, its `texture` is relative to its own folder, and a path
/// is named by a deck and by the files it includes.
#[test]
fn an_included_file_adds_its_records_in_place() {
    let dir = tempfile::tempdir().unwrap();
    let texture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/psout_check.ras");
    std::fs::create_dir_all(dir.path().join("lib/more")).unwrap();
    std::fs::copy(texture, dir.path().join("lib/more/tex.ras")).unwrap();
    write(
        dir.path(),
        &[
            (
                "lib/shared.deck",
                "{ a library }\nlight lamp 0 0 9 1 1 1\nsurface blue opaque color 0 0 1 ka 0.1 kd 0.9 ks 0 kt 0\ninclude more/paths.deck\n",
            ),
            (
                "lib/more/paths.deck",
                "path up by 0 0 1\nsurface pic opaque color 1 1 1 ka 0.1 kd 0.9 ks 0 kt 0\ntexture pic tex.ras",
            ),
            (
                "t.deck",
                &format!("{SCENE}include lib/shared.deck\nsphere b2 blue at 2 0 1 radius 1\nmotion b2 path up\n"),
            ),
        ],
    );
    let scene = read(dir.path(), "t.deck").unwrap();
    let lights: Vec<&str> = scene.lights.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(lights, ["sun", "lamp"]);
    let surfaces: Vec<&str> = scene.surfaces.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(surfaces, ["red", "blue", "pic"]);
    assert!(scene.surfaces[2].texture.is_some());
    assert_eq!(scene.objects[1].surface, 1);
    assert_eq!(scene.motions[0].to.to_array(), [2.0, 0.0, 2.0]);
}

/// The errors of the library, each at the file, line and column where it
/// stands.
#[test]
fn library_errors_name_the_file_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let cases: &[(&[(&str, &str)], &str)] = &[
        // A missing file: as written and as found from the deck's folder.
        (
            &[("t.deck", &format!("{SCENE}include lib/none.deck\n"))],
            "t.deck:7:9: include: cannot read the included file 'lib/none.deck': No such file or directory (os error 2); from the deck's folder, that is 'lib/none.deck'",
        ),
        // A path used before it is defined, here in the file included after.
        (
            &[
                ("t.deck", &format!("{SCENE}motion ball path hop\ninclude lib.deck\n")),
                ("lib.deck", "\n\npath hop by 1 0 0\n"),
            ],
            "t.deck:7:18: motion 'ball': the path 'hop' is used before it is defined (on line 3 of lib.deck): a record may name only what stands above it",
        ),
        (
            &[("t.deck", &format!("{SCENE}motion ball path hop\npath hop by 1 0 0\n"))],
            "t.deck:7:18: motion 'ball': the path 'hop' is used before it is defined (on line 8): a record may name only what stands above it",
        ),
        // Never defined: the nearest name suggested, after the deck is read.
        (
            &[
                ("t.deck", &format!("{SCENE}include lib.deck\nmotion ball path hpo\n")),
                ("lib.deck", "path hop by 1 0 0\n"),
            ],
            "t.deck:8:18: motion 'ball': unknown path 'hpo' — did you mean 'hop'?",
        ),
        // The first error stands: a later one does not hide the unknown path.
        (
            &[("t.deck", &format!("{SCENE}motion ball path hop\nsphere\n"))],
            "t.deck:7:18: motion 'ball': unknown path 'hop'",
        ),
        // An unknown field, in an included file: that file's name.
        (
            &[
                ("t.deck", &format!("{SCENE}include lib/p.deck\n")),
                ("lib/p.deck", "{ paths }\npath hop by 1 0 0  speed 3\n"),
            ],
            "lib/p.deck:2:20: path 'hop': expected end of line or 'turn', 'via', 'law', found 'speed'",
        ),
        (
            &[("t.deck", &format!("{SCENE}path hop bye 1 0 0\n"))],
            "t.deck:7:10: path 'hop': expected 'by', found 'bye' — did you mean 'by'?",
        ),
        (
            &[("t.deck", &format!("{SCENE}path hop lw smooth by 1 0 0\n"))],
            "t.deck:7:10: path 'hop': expected 'by', found 'lw' — did you mean 'law'?",
        ),
        (
            &[("t.deck", &format!("{SCENE}path hop law smooth by 1 0 0\n"))],
            "t.deck:7:10: path 'hop': expected 'by', found 'law' — 'by' comes before 'law'",
        ),
        // A path name given twice: in one file, and across files.
        (
            &[("t.deck", &format!("{SCENE}path hop by 1 0 0\npath hop by 2 0 0\n"))],
            "t.deck:8:6: path 'hop': the path name 'hop' is already used on line 7",
        ),
        (
            &[
                ("t.deck", &format!("{SCENE}include lib.deck\npath hop by 2 0 0\n")),
                ("lib.deck", "path hop by 1 0 0\n"),
            ],
            "t.deck:8:6: path 'hop': the path name 'hop' is already used on line 1 of lib.deck",
        ),
        // A surface of the deck defined again in a library.
        (
            &[
                ("t.deck", &format!("{SCENE}include lib.deck\n")),
                ("lib.deck", "surface red opaque color 1 0 0 ka 0 kd 1 ks 0 kt 0\n"),
            ],
            "lib.deck:1:9: surface 'red': the surface name 'red' is already used on line 4 of t.deck",
        ),
        // The motion's two forms.
        (
            &[("t.deck", &format!("{SCENE}path hop by 1 0 0\nmotion ball path hop law smooth\n"))],
            "t.deck:8:22: motion 'ball': expected end of line, found 'law' — a motion from the library takes its end, turn, via and law from the path 'hop'",
        ),
        (
            &[("t.deck", &format!("{SCENE}path hop by 1 0 0\nmotion ball pth hop\n"))],
            "t.deck:8:13: motion 'ball': expected 'to' or 'path', found 'pth' — did you mean 'path'?",
        ),
        (
            &[("t.deck", &format!("{SCENE}path hop by 1 0 0\nmotion ball to 1 2 3 path hop\n"))],
            "t.deck:8:22: motion 'ball': expected end of line or 'turn', 'via', 'law', found 'path'",
        ),
        // A scene record in an included file.
        (
            &[
                ("t.deck", &format!("{SCENE}include lib.deck\n")),
                ("lib.deck", "path hop by 1 0 0\nsphere b2 red at 0 0 0 radius 1\n"),
            ],
            "lib.deck:2:1: deck: a 'sphere' record cannot stand in an included file, which holds path, surface, paint, texture, light, include records only",
        ),
        // A lexical error in an included file.
        (
            &[
                ("t.deck", &format!("{SCENE}include lib.deck\n")),
                ("lib.deck", "path hop by 1 0 0\n  { open\n"),
            ],
            "lib.deck:2:3: deck: unterminated comment: '{' has no '}'",
        ),
        // A path that carries its object out of the deck's range.
        (
            &[("t.deck", &format!("{SCENE}path far by 0 0 1e7\nmotion ball path far\n"))],
            "t.deck:8:18: motion 'ball': the path 'far' takes the object to (-1.25, -0.5, 10000000.8), out of the deck's range -1e7..1e7",
        ),
        (
            &[("t.deck", &format!("{SCENE}path far by 0 0 0 via 0 0 0 -1e7 0 0\nmotion ball path far\n"))],
            "t.deck:8:18: motion 'ball': the path 'far' takes the object to (-10000001.25, -0.5, 0.8), out of the deck's range -1e7..1e7",
        ),
    ];
    for (k, (files, expected)) in cases.iter().enumerate() {
        let case = d.join(format!("case{k}"));
        write(&case, files);
        assert_eq!(error(&case, "t.deck"), *expected, "case {k}");
    }
}

/// A file that includes itself, directly or through others, is an error
/// at the `include` that closes the cycle, naming the files round it.
#[test]
fn an_include_cycle_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(
        d,
        &[
            ("t.deck", &format!("{SCENE}include a.deck\n")),
            ("a.deck", "path one by 1 0 0\ninclude sub/b.deck\n"),
            ("sub/b.deck", "\ninclude ../a.deck\n"),
            ("self.deck", &format!("{SCENE}include self.deck\n")),
        ],
    );
    assert_eq!(
        error(d, "t.deck"),
        "sub/b.deck:2:9: include: an include cycle: 'a.deck' includes 'sub/b.deck' includes 'sub/../a.deck' (a file may not include itself)"
    );
    assert_eq!(
        error(d, "self.deck"),
        "self.deck:7:9: include: an include cycle: 'self.deck' includes 'self.deck' (a file may not include itself)"
    );
    // A hard link is the file it links: the include of the link closes
    // the cycle, and the error stands there and names it.
    write(
        d,
        &[
            ("hard.deck", &format!("{SCENE}include lib.deck\n")),
            ("lib.deck", "\ninclude link.deck\n"),
        ],
    );
    std::fs::hard_link(d.join("lib.deck"), d.join("link.deck")).unwrap();
    assert_eq!(
        error(d, "hard.deck"),
        "lib.deck:2:9: include: an include cycle: 'lib.deck' includes 'link.deck', which is 'lib.deck' under another name (a hard link) (a file may not include itself)"
    );
    // A file included twice, not inside itself, is no cycle (here its path
    // is then named twice).
    write(
        d,
        &[
            ("twice.deck", &format!("{SCENE}include a2.deck\ninclude a2.deck\n")),
            ("a2.deck", "light l2 0 0 9 1 1 1\n"),
        ],
    );
    assert_eq!(
        error(d, "twice.deck"),
        "a2.deck:1:7: light 'l2': the light name 'l2' is already used on line 1"
    );
}

/// Includes nest at most MAX_INCLUDE_DEPTH deep.
#[test]
fn includes_nest_at_most_sixteen_deep() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    assert_eq!(MAX_INCLUDE_DEPTH, 16);
    let chain = |n: usize| {
        write(d, &[("t.deck", &format!("{SCENE}include f1.deck\n"))]);
        for k in 1..=n {
            let next = if k < n {
                format!("include f{}.deck\n", k + 1)
            } else {
                String::new()
            };
            write(d, &[(&format!("f{k}.deck"), &format!("path p{k} by {k} 0 0\n{next}"))]);
        }
    };
    chain(MAX_INCLUDE_DEPTH);
    let scene = read(d, "t.deck").expect("16 deep is read");
    assert!(scene.motions.is_empty());
    chain(MAX_INCLUDE_DEPTH + 1);
    assert_eq!(
        error(d, "t.deck"),
        "f16.deck:2:9: include: files may include files at most 16 deep; this would be one deeper"
    );
}

/// A bomb of includes (each file including the next ten times, an empty
/// file at the bottom) is refused when it has read MAX_INCLUDES files.
#[test]
fn a_bomb_of_includes_is_refused_at_the_count() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ten = |file: &str| format!("include {file}\n").repeat(10);
    write(
        d,
        &[
            ("t.deck", &format!("{SCENE}{}", ten("l1.deck"))),
            ("l1.deck", &ten("l2.deck")),
            ("l2.deck", &ten("l3.deck")),
            ("l3.deck", &ten("l4.deck")),
            ("l4.deck", &ten("l5.deck")),
            ("l5.deck", ""),
        ],
    );
    assert_eq!(MAX_INCLUDES, 10_000);
    // Read depth first, each l2.deck brings 1 + 10 + 100 + 1000 includes:
    // the first l1.deck and nine l2.deck are 10,000, and the tenth include
    // of l2.deck is refused.
    assert_eq!(
        error(d, "t.deck"),
        "l1.deck:10:9: include: a deck may include at most 10000 files in all, counting each include"
    );
    // Two levels less are read: 10 × (1 + 10 × (1 + 10)) = 1,110 includes.
    write(d, &[("l3.deck", "")]);
    assert!(read(d, "t.deck").is_ok());
}

/// The deck and what it includes hold at most MAX_DECK_BYTES together: a
/// deck including a 20 MiB file four times is refused at the first byte
/// past the limit, in the file where it falls.
#[test]
fn the_size_limit_holds_across_includes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let big = 20 << 20;
    let mut filler = "{ filler }\n".repeat(big / 11);
    filler.push_str(&" ".repeat(big - filler.len()));
    assert_eq!(filler.len(), big);
    write(d, &[("big.deck", &filler)]);
    let deck = format!("{SCENE}include big.deck\ninclude big.deck\ninclude big.deck\n");
    write(d, &[("three.deck", &deck)]);
    assert!(read(d, "three.deck").is_ok(), "60 MiB and a little are read");
    write(d, &[("four.deck", &format!("{deck}include big.deck\n"))]);
    // Past the deck and three files, 64 MiB leave this many bytes of the
    // fourth: the error stands at the byte after them.
    let left = MAX_DECK_BYTES - deck.len() - "include big.deck\n".len() - 3 * big;
    let line = left / 11 + 1;
    let column = left % 11 + 1;
    assert_eq!(
        error(d, "four.deck"),
        format!("big.deck:{line}:{column}: deck: the deck and the files it includes are larger than 64 MiB, the most the reader takes")
    );
    // Exactly at the limit, the deck and one file: read.
    let main = format!("{SCENE}include rest.deck\n");
    let mut rest = "{ filler }\n".repeat((MAX_DECK_BYTES - main.len()) / 11);
    rest.push_str(&" ".repeat(MAX_DECK_BYTES - main.len() - rest.len()));
    write(d, &[("exact.deck", &main), ("rest.deck", &rest)]);
    assert!(read(d, "exact.deck").is_ok(), "64 MiB in all are read");
    rest.push('\n');
    write(d, &[("rest.deck", &rest)]);
    let line = rest.lines().count();
    assert_eq!(
        error(d, "exact.deck"),
        format!("rest.deck:{line}:{}: deck: the deck and the files it includes are larger than 64 MiB, the most the reader takes", rest.len() - 11 * (line - 1))
    );
    // An endless file stops at the limit too.
    assert_eq!(
        error(d, &{
            write(d, &[("zero.deck", &format!("{SCENE}include /dev/zero\n"))]);
            "zero.deck".to_string()
        }),
        format!(
            "/dev/zero:1:{}: deck: the deck and the files it includes are larger than 64 MiB, the most the reader takes",
            MAX_DECK_BYTES - SCENE.len() - "include /dev/zero\n".len() + 1
        )
    );
}

/// Through the binary: a bad include is a deck error, exit 2, naming the
/// file; nothing is written. From standard input, FILE is relative to the
/// current folder.
#[test]
fn the_binary_exits_2_on_a_bad_include_and_reads_stdin_s_from_here() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write(
        d,
        &[
            ("t.deck", &format!("{SCENE}include lib.deck\nmotion ball path hop\n")),
            ("lib.deck", "path hop by 1 0 0 via 0 0\n"),
        ],
    );
    let out = d.join("t.ras");
    let run = raytrace_command()
        .arg(d.join("t.deck"))
        .arg("-q")
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(
        stderr.trim_end(),
        format!(
            "raytrace: {}/lib.deck:1:26: path 'hop': expected a number after 'via', found end of line",
            d.display()
        )
    );
    assert!(!out.exists());
    write(d, &[("lib.deck", "path hop by 1 0 0\n")]);
    let mut child = raytrace_command()
        .current_dir(d)
        .args(["-", "-q", "-o", "stdin.ras"])
        .stdin(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    use std::io::Write;
    child
        .stdin
        .take()
        .unwrap()
        .write_all(format!("{SCENE}include lib.deck\nmotion ball path hop\n").as_bytes())
        .unwrap();
    assert!(child.wait().unwrap().success());
    assert!(d.join("stdin.ras").exists());
}

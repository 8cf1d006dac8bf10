//! `tools scale --quick`: the run completes (which means every `--accel`
//! rendered each scene to the same raster: the tool fails otherwise), and
//! what it writes has the shape docs/scale.md reads: a row a scene with a
//! time for every method, POV-Ray's column exactly when POV-Ray is
//! installed, the moving spheres' ratio, and the chart as a PNG and an SVG
//! of its size with every method named. Times are not asserted, only that
//! ours are measured (positive, finite).

use std::path::Path;
use std::process::{Command, Output, Stdio};

fn tools(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tools"))
        .args(args)
        .stdin(Stdio::null())
        .output()
        .unwrap()
}

fn povray_installed() -> bool {
    Command::new("povray")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_ok()
}

/// The cells of the Markdown table whose header starts `| scene | N |`.
fn time_table(stdout: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let cells = |l: &str| -> Vec<String> {
        l.trim()
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect()
    };
    let mut lines = stdout.lines().skip_while(|l| !l.starts_with("| scene | N |"));
    let head = cells(lines.next().expect("the table of times"));
    let rows = lines.skip(1).take_while(|l| l.starts_with('|')).map(cells).collect();
    (head, rows)
}

#[test]
fn the_quick_run_writes_the_chart_and_a_row_a_scene() {
    let dir = tempfile::tempdir().unwrap();
    let out = tools(&["scale", "--quick", "--dir", &dir.path().display().to_string()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "tools scale --quick failed:\n{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (head, rows) = time_table(&stdout);
    let accels = ["--accel none", "--accel bvh", "--accel octree", "--accel auto"];
    let mut methods: Vec<&str> = accels.to_vec();
    if povray_installed() {
        methods.push("POV-Ray 3.7");
    }
    assert_eq!(head[2..2 + methods.len()], methods[..], "{head:?}");
    assert_eq!(head.len(), 3 + methods.len(), "{head:?}");
    let scenes: Vec<(String, String)> = rows.iter().map(|r| (r[0].clone(), r[1].clone())).collect();
    let expected = [
        ("sphere", "1"),
        ("sphere", "10"),
        ("sphere", "100"),
        ("star", "1"),
        ("star", "10"),
        ("goblet", "1"),
        ("goblet", "10"),
    ]
    .map(|(k, n)| (k.to_string(), n.to_string()));
    assert_eq!(scenes, expected);
    for row in &rows {
        for (k, cell) in row[2..2 + methods.len()].iter().enumerate() {
            let t: f64 = cell.parse().unwrap_or_else(|_| panic!("{row:?}: '{cell}' is no time"));
            // POV-Ray reports its trace time in ms: a 24² render may be 0.
            let ours = k < accels.len();
            assert!(t.is_finite() && (t > 0.0 || !ours && t == 0.0), "{row:?}");
        }
    }
    let moving: Vec<&str> = stdout.lines().filter(|l| l.starts_with("| each moving ")).collect();
    assert_eq!(moving.len(), 2, "the moving spheres' rows, two radii and 4.6");
    for row in moving {
        let ratio: f64 = row
            .trim_end_matches([' ', '|'])
            .rsplit('|')
            .next()
            .unwrap()
            .trim()
            .parse()
            .unwrap();
        assert!(ratio.is_finite() && ratio > 0.0, "{row}");
    }

    let png = image::open(dir.path().join("scale.png")).unwrap().to_rgb8();
    assert_eq!(png.dimensions(), (2100, 700));
    assert!(png.pixels().any(|p| p.0 == [200, 40, 40]), "the loop's line is drawn");
    let svg = std::fs::read_to_string(dir.path().join("scale.svg")).unwrap();
    for name in methods
        .iter()
        .chain(&["Random spheres", "fig5_6 stars", "fig5_8 goblets"])
    {
        assert!(svg.contains(name), "the SVG names {name}");
    }
}

/// `--decks` writes each scene of the run as a deck that reads, with as
/// many objects as its name says, and the moving spheres with a motion each.
#[test]
fn the_quick_decks_read_with_their_objects() {
    let dir = tempfile::tempdir().unwrap();
    let out = tools(&["scale", "--quick", "--decks", &dir.path().display().to_string()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let mut names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "goblet1.deck",
            "goblet10.deck",
            "sphere1.deck",
            "sphere10.deck",
            "sphere100.deck",
            "sphere10_moving2.deck",
            "sphere10_moving4.6.deck",
            "star1.deck",
            "star10.deck"
        ]
    );
    for name in &names {
        let path = dir.path().join(name);
        let text = std::fs::read_to_string(&path).unwrap();
        let scene = tools::decks::load_source(&text, name, Path::new("."), raytrace::options::Fidelity::Thesis)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let n: usize = name
            .trim_end_matches(".deck")
            .split('_')
            .next()
            .unwrap()
            .trim_start_matches(char::is_alphabetic)
            .parse()
            .unwrap();
        assert_eq!(scene.objects.len(), n, "{name}");
        let moving = name.contains("moving");
        assert_eq!(scene.motions.len(), if moving { n } else { 0 }, "{name}");
    }
}

/// A flag out of its range is a usage error (exit 2) naming the flag.
#[test]
fn bad_flags_exit_2() {
    for args in [
        &["scale", "--mask", "0"][..],
        &["scale", "--max", "0"],
        &["scale", "--size", "4"],
        // raytrace's parsers and ranges: refused, never clamped.
        &["scale", "--mask", "33"],
        &["scale", "--size", "0x8"],
        &["vs-povray", "--mask", "0"],
        &["heatmap", "--size", "9000x8", "x.deck"],
        &["preview", "--threads", "257"],
    ] {
        let out = tools(args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&out.stderr).contains(args[1]), "{args:?}");
    }
}

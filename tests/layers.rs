//! The module graph of the library: every `crate::X` a module names in its
//! code (comments and doc links aside) is a module of a lower layer, or
//! itself. The layers are the house's (legacy_pascal/README.md, "Where each
//! part of the port sits"): the records at the bottom, the thesis's units above them,
//! the render above all. A new module gets a layer here.

use std::collections::BTreeMap;
use std::path::Path;

/// Each module of src/ and its layer: a module may name only modules of a
/// lower layer (or itself), so there is no circle and nothing runs back up.
const LAYERS: &[(&str, u32)] = &[
    // The records of Fig. 4.3, the choices of a render, the port's
    // uniform from a key, the port's root solver.
    ("types", 0),
    ("options", 0),
    ("hash", 0),
    ("robust", 0),
    // How a program ends: a failure's kind and its exit status.
    ("exit", 0),
    // Structures over the objects' boxes (the port's).
    ("accel", 1),
    // The deck's scene records; the file system (its signal handler exits
    // with a status of `exit`).
    ("scene", 1),
    ("output", 1),
    // Unit `proc`; the raster file and its formats.
    ("proc", 2),
    ("raster", 2),
    // Unit `drt`; reading a picture of any kind psout shows.
    ("drt", 3),
    ("image_file", 3),
    // The reconstructed intersections.
    ("shapes", 4),
    // Unit `paper`.
    ("paper", 5),
    // Reading a deck; the film's frames and files; a still's bands and
    // their files; the PS 390.
    ("deck", 6),
    ("film", 6),
    ("tile", 6),
    ("psout", 6),
    // Where and when samples fall; what moves over the shutter.
    ("sampler", 6),
    ("motion", 6),
    // How many samples a pixel gets; which object a ray meets; how pixels
    // are made from samples (`--denoise`), the thesis's coherence.
    ("adaptive", 7),
    ("intersect", 7),
    ("reconstruct", 7),
    ("coherence", 7),
    // Cook's soft shadows and blurred reflection (the port's).
    ("distributed", 7),
    // The reconstructed shading.
    ("trace", 8),
    // The main program.
    ("raytrace", 9),
    // A render's jobs: the deck read, a film's frames, a still's files.
    ("run", 10),
    // The picture as it renders (`raytrace --show`, `--watch`).
    ("show", 10),
    // The command line's words for a render.
    ("cli", 11),
    // The port's contour editor (`contour`): edits a deck's sweep, shows
    // it rendered.
    ("editor", 11),
];

/// The top module a file of src/ belongs to (`None` for lib.rs and the binaries).
fn module_of(path: &Path, src: &Path) -> Option<String> {
    let rel = path.strip_prefix(src).ok()?;
    let first = rel.components().next()?.as_os_str().to_string_lossy().into_owned();
    match first.as_str() {
        "lib.rs" | "bin" => None,
        f => Some(f.trim_end_matches(".rs").to_string()),
    }
}

/// The modules `crate::X` names in the code of `text`, comments left out.
fn named(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for line in text.lines() {
        let code = match line.find("//") {
            Some(i) => &line[..i],
            None => line,
        };
        let mut rest = code;
        while let Some(i) = rest.find("crate::") {
            let tail = &rest[i + "crate::".len()..];
            let name: String = tail
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.push(name);
            }
            rest = tail;
        }
    }
    out
}

fn files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn no_module_names_one_above_it() {
    let layer: BTreeMap<&str, u32> = LAYERS.iter().copied().collect();
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    files(&src, &mut all);
    let mut wrong = Vec::new();
    for path in &all {
        let Some(module) = module_of(path, &src) else {
            continue;
        };
        let own = *layer
            .get(module.as_str())
            .unwrap_or_else(|| panic!("{}: module '{module}' has no layer in tests/layers.rs", path.display()));
        for other in named(&std::fs::read_to_string(path).unwrap()) {
            if other == module {
                continue;
            }
            let theirs = *layer
                .get(other.as_str())
                .unwrap_or_else(|| panic!("{}: names crate::{other}, which has no layer", path.display()));
            if theirs >= own {
                wrong.push(format!(
                    "{} ({module}, layer {own}) names crate::{other} (layer {theirs})",
                    path.display()
                ));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "imports that run back up or sideways:\n{}",
        wrong.join("\n")
    );
}

/// Every module lib.rs declares has a layer, and every layer a module.
#[test]
fn every_module_has_a_layer() {
    let lib = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("src/lib.rs")).unwrap();
    let declared: Vec<&str> = lib
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod ").and_then(|r| r.strip_suffix(';')))
        .collect();
    let mut listed: Vec<&str> = LAYERS.iter().map(|(m, _)| *m).collect();
    let mut declared_sorted = declared.clone();
    listed.sort_unstable();
    declared_sorted.sort_unstable();
    assert_eq!(declared_sorted, listed);
}

/// The check sees what it should: a name in code counts, one in a comment
/// or doc link does not.
#[test]
fn names_in_code_count_and_in_comments_not() {
    let text = "use crate::types::Ray;\n/// See [`crate::raytrace`].\nlet x = crate::drt::LAW(a); // crate::film\n";
    assert_eq!(named(text), ["types", "drt"]);
}

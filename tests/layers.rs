//! The module graph of the library. Every path a module names in its code
//! (`crate::…`, `super::…`, `self::…`, comments, strings and doc links
//! aside) is resolved to the module it names; then
//! - between the top modules, a module names only modules of a lower
//!   layer than its own (or itself): nothing runs back up;
//! - among the modules inside one (`editor/screen.rs` and
//!   `editor/session.rs`, say), there is no circle.
//!
//! The layers are the house's, read from the one table that shows them:
//! legacy_pascal/README.md, "Where each part of the port sits". A module of
//! src/ without a row there fails; a row naming a module that src/ does not
//! have (yet) is left alone.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A module's path in the crate: `["editor", "screen"]`.
type ModPath = Vec<String>;

const TABLE_HEADING: &str = "## Where each part of the port sits";

/// The layer of each module named in the README's table: its rows are
/// `| N | `a`, `b` | what they are |`, the names in the second cell.
fn parse_layers(readme: &str) -> Vec<(String, u32)> {
    let mut rows = Vec::new();
    let Some(start) = readme.find(TABLE_HEADING) else {
        return rows;
    };
    let section = &readme[start + TABLE_HEADING.len()..];
    let section = &section[..section.find("\n#").unwrap_or(section.len())];
    for line in section.lines() {
        let cells: Vec<&str> = line.split('|').map(str::trim).collect();
        let (Some(layer), Some(modules)) = (cells.get(1), cells.get(2)) else {
            continue;
        };
        let Ok(layer) = layer.parse::<u32>() else {
            continue;
        };
        for name in modules.split('`').skip(1).step_by(2) {
            rows.push((name.to_string(), layer));
        }
    }
    rows
}

fn layers() -> BTreeMap<String, u32> {
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("legacy_pascal/README.md")).unwrap();
    let rows = parse_layers(&readme);
    let table: BTreeMap<String, u32> = rows.iter().cloned().collect();
    assert_eq!(
        table.len(),
        rows.len(),
        "legacy_pascal/README.md names a module in two rows"
    );
    table
}

/// What the lexer keeps of Rust source: names, `::`, and the punctuation
/// of a `use` tree and of blocks.
#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Name(String),
    Sep,
    Open,
    Close,
    Comma,
    Star,
    Other,
}

/// The tokens of `text`, comments, strings and characters left out.
fn tokens(text: &str) -> Vec<Tok> {
    let c: Vec<char> = text.chars().collect();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        match (c[i], at(i + 1)) {
            ('/', '/') => {
                while i < c.len() && c[i] != '\n' {
                    i += 1;
                }
            }
            ('/', '*') => {
                i += 2;
                while i < c.len() && !(c[i] == '*' && at(i + 1) == '/') {
                    i += 1;
                }
                i += 2;
            }
            ('"', _) => {
                i += 1;
                while i < c.len() && c[i] != '"' {
                    i += if c[i] == '\\' { 2 } else { 1 };
                }
                i += 1;
            }
            ('\'', '\\') => {
                i += 2;
                while i < c.len() && c[i] != '\'' {
                    i += 1;
                }
                i += 1;
            }
            ('\'', _) if at(i + 2) == '\'' => i += 3,
            (':', ':') => {
                out.push(Tok::Sep);
                i += 2;
            }
            (ch, _) if ch.is_ascii_alphanumeric() || ch == '_' => {
                let start = i;
                while i < c.len() && (c[i].is_ascii_alphanumeric() || c[i] == '_') {
                    i += 1;
                }
                out.push(Tok::Name(c[start..i].iter().collect()));
            }
            (ch, _) => {
                out.push(match ch {
                    '{' => Tok::Open,
                    '}' => Tok::Close,
                    ',' => Tok::Comma,
                    '*' => Tok::Star,
                    _ if ch.is_whitespace() => {
                        i += 1;
                        continue;
                    }
                    _ => Tok::Other,
                });
                i += 1;
            }
        }
    }
    out
}

/// Reads the rest of a path after `prefix` (at a `::` or its end), a `use`
/// tree's braces included, and adds every full path it names to `out`.
fn rest(t: &[Tok], i: &mut usize, mut prefix: ModPath, out: &mut Vec<ModPath>) {
    while t.get(*i) == Some(&Tok::Sep) {
        *i += 1;
        match t.get(*i) {
            Some(Tok::Name(n)) if n == "super" => {
                prefix.pop();
            }
            Some(Tok::Name(n)) if n == "self" => {}
            Some(Tok::Name(n)) => prefix.push(n.clone()),
            Some(Tok::Open) => {
                *i += 1;
                while let Some(Tok::Name(n)) = t.get(*i) {
                    let mut item = prefix.clone();
                    match n.as_str() {
                        "self" => {}
                        "super" => {
                            item.pop();
                        }
                        _ => item.push(n.clone()),
                    }
                    *i += 1;
                    rest(t, i, item, out);
                    // `as NAME`, up to the next item
                    while !matches!(t.get(*i), None | Some(Tok::Comma | Tok::Close)) {
                        *i += 1;
                    }
                    if t.get(*i) == Some(&Tok::Comma) {
                        *i += 1;
                    }
                }
                if t.get(*i) == Some(&Tok::Close) {
                    *i += 1;
                }
                return;
            }
            _ => break,
        }
        *i += 1;
    }
    out.push(prefix);
}

/// Every path the code of `text` names from `crate::`, `super::` or
/// `self::`, resolved from the module `here` (and the inline modules of
/// the text, `mod tests { use super::*; }` naming `here`).
fn named(text: &str, here: &[String]) -> Vec<ModPath> {
    let t = tokens(text);
    let mut out = Vec::new();
    let mut depth = 0;
    // The inline modules open at this point, with the depth they opened at.
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut i = 0;
    while i < t.len() {
        match &t[i] {
            Tok::Open => depth += 1,
            Tok::Close => {
                depth -= 1;
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
            }
            Tok::Name(m) if m == "mod" => {
                if let (Some(Tok::Name(n)), Some(Tok::Open)) = (t.get(i + 1), t.get(i + 2)) {
                    inline.push((n.clone(), depth));
                    depth += 1;
                    i += 3;
                    continue;
                }
            }
            Tok::Name(root)
                if matches!(root.as_str(), "crate" | "super" | "self")
                    && t.get(i + 1) == Some(&Tok::Sep)
                    && (i == 0 || t[i - 1] != Tok::Sep) =>
            {
                let mut prefix: ModPath = here.to_vec();
                prefix.extend(inline.iter().map(|(n, _)| n.clone()));
                match root.as_str() {
                    "crate" => prefix.clear(),
                    "super" => {
                        prefix.pop();
                    }
                    _ => {}
                }
                i += 1;
                rest(&t, &mut i, prefix, &mut out);
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// The module a full path names: its longest start that is a module of
/// `known`; else its first name (a top module with no file, or none).
fn module_named(path: &[String], known: &BTreeSet<ModPath>) -> Option<ModPath> {
    (1..=path.len())
        .rev()
        .map(|n| path[..n].to_vec())
        .find(|p| known.contains(p))
        .or_else(|| path.first().map(|f| vec![f.clone()]))
}

/// The edges of the module graph of `files` (each a module's path and its
/// text): between top modules, `(from, to)`; inside a module, `(parent,
/// from, to)` for two of the parent's modules.
#[derive(Default)]
struct Graph {
    top: BTreeSet<(String, String)>,
    siblings: BTreeSet<(ModPath, String, String)>,
}

fn graph(files: &[(ModPath, String)], known: &BTreeSet<ModPath>) -> Graph {
    let mut g = Graph::default();
    for (from, text) in files {
        for path in named(text, from) {
            let Some(to) = module_named(&path, known) else {
                continue;
            };
            let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
            if common == from.len() || common == to.len() {
                // itself, a module inside it, or one it is inside
                continue;
            }
            if common == 0 {
                g.top.insert((from[0].clone(), to[0].clone()));
            } else {
                g.siblings
                    .insert((from[..common].to_vec(), from[common].clone(), to[common].clone()));
            }
        }
    }
    g
}

/// The circles among the modules inside a module, each written
/// `editor: screen -> session -> screen`.
fn circles(g: &Graph) -> Vec<String> {
    let mut by_parent: BTreeMap<&ModPath, BTreeMap<&str, Vec<&str>>> = BTreeMap::new();
    for (parent, from, to) in &g.siblings {
        by_parent.entry(parent).or_default().entry(from).or_default().push(to);
    }
    let mut found = Vec::new();
    for (parent, next) in by_parent {
        // Depth first from each module; a module on the current path met
        // again closes a circle.
        let mut done: BTreeSet<&str> = BTreeSet::new();
        for &start in next.keys() {
            let mut path: Vec<&str> = Vec::new();
            visit(start, &next, &mut path, &mut done, &mut |circle| {
                found.push(format!("{}: {}", parent.join("::"), circle.join(" -> ")));
            });
        }
    }
    found
}

fn visit<'a>(
    at: &'a str,
    next: &BTreeMap<&'a str, Vec<&'a str>>,
    path: &mut Vec<&'a str>,
    done: &mut BTreeSet<&'a str>,
    report: &mut dyn FnMut(Vec<&str>),
) {
    if let Some(k) = path.iter().position(|m| *m == at) {
        let mut circle = path[k..].to_vec();
        circle.push(at);
        report(circle);
        return;
    }
    if !done.insert(at) {
        return;
    }
    path.push(at);
    for &to in next.get(at).into_iter().flatten() {
        visit(to, next, path, done, report);
    }
    path.pop();
}

/// A file's module: `src/editor/screen.rs` is `["editor", "screen"]`,
/// `src/editor/mod.rs` is `["editor"]`; `None` for lib.rs and the binaries.
fn module_of(path: &Path, src: &Path) -> Option<ModPath> {
    let rel = path.strip_prefix(src).ok()?;
    let mut parts: ModPath = rel.iter().map(|p| p.to_string_lossy().into_owned()).collect();
    if parts.first().is_some_and(|f| f == "lib.rs" || f == "bin") {
        return None;
    }
    let last = parts.pop()?;
    if last != "mod.rs" {
        parts.push(last.trim_end_matches(".rs").to_string());
    }
    Some(parts)
}

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The library's modules and their text.
fn library() -> (Vec<(ModPath, String)>, BTreeSet<ModPath>) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    files(&src, &mut all);
    all.sort();
    let modules: Vec<(ModPath, String)> = all
        .iter()
        .filter_map(|p| Some((module_of(p, &src)?, std::fs::read_to_string(p).unwrap())))
        .collect();
    let known = modules.iter().map(|(m, _)| m.clone()).collect();
    (modules, known)
}

#[test]
fn no_module_names_one_above_it() {
    let layer = layers();
    let (modules, known) = library();
    let of = |m: &str| {
        *layer
            .get(m)
            .unwrap_or_else(|| panic!("module '{m}' has no row in legacy_pascal/README.md's layer table"))
    };
    let wrong: Vec<String> = graph(&modules, &known)
        .top
        .iter()
        .filter(|(from, to)| of(to) >= of(from))
        .map(|(from, to)| format!("{from} (layer {}) names {to} (layer {})", of(from), of(to)))
        .collect();
    assert!(
        wrong.is_empty(),
        "imports that run back up or sideways:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn no_circle_inside_a_module() {
    let (modules, known) = library();
    let found = circles(&graph(&modules, &known));
    assert!(
        found.is_empty(),
        "modules that import each other:\n{}",
        found.join("\n")
    );
}

/// Every module of src/ has a row in the table.
#[test]
fn every_module_has_a_layer() {
    let layer = layers();
    let (_, known) = library();
    let missing: Vec<&String> = known
        .iter()
        .map(|m| &m[0])
        .filter(|m| !layer.contains_key(*m))
        .collect();
    assert!(
        missing.is_empty(),
        "modules with no row in legacy_pascal/README.md: {missing:?}"
    );
}

fn names(list: &[&str]) -> ModPath {
    list.iter().map(|s| s.to_string()).collect()
}

/// The check sees what it should: a name in code counts, one in a comment,
/// a doc link or a string does not; `super::` and `self::` resolve from the
/// module (and from a module inside the file), through a `use` tree's
/// braces across lines.
#[test]
fn paths_resolve_and_comments_do_not_count() {
    let text = "use crate::types::Ray;\n/// See [`crate::raytrace`].\n\
        let x = crate::drt::LAW(a, \"crate::film\", '{'); // crate::film\n\
        use super::{\n    draw::Rect,\n    keyshapes::{self, Chain as C},\n};\n\
        let y = self::inner::f();\n\
        #[cfg(test)]\nmod tests {\n    use super::*;\n    use super::super::model::Edit;\n}\n\
        use super::session::Editor;\n";
    let here = names(&["editor", "screen"]);
    let got: Vec<String> = named(text, &here).iter().map(|p| p.join("::")).collect();
    assert_eq!(
        got,
        [
            "types::Ray",
            "drt::LAW",
            "editor::draw::Rect",
            "editor::keyshapes",
            "editor::keyshapes::Chain",
            "editor::screen::inner::f",
            "editor::screen",
            "editor::model::Edit",
            "editor::session::Editor",
        ]
    );
}

/// The planted circle of two modules inside one, each naming the other
/// (once through a `use` tree), is found; named through a third module
/// they both take from, it is gone.
#[test]
fn a_planted_circle_is_caught() {
    let known: BTreeSet<ModPath> = [
        &["editor"][..],
        &["editor", "screen"],
        &["editor", "session"],
        &["editor", "layout"],
    ]
    .iter()
    .map(|m| names(m))
    .collect();
    let screen = (
        names(&["editor", "screen"]),
        "use super::session::Editor;\nuse super::layout::PLANE;".to_string(),
    );
    let circle = [
        screen.clone(),
        (
            names(&["editor", "session"]),
            "use super::{\n    layout::SLIDER,\n    screen::PLANE,\n};".to_string(),
        ),
    ];
    assert_eq!(
        circles(&graph(&circle, &known)),
        ["editor: screen -> session -> screen"]
    );
    let none = [
        screen,
        (
            names(&["editor", "session"]),
            "use crate::editor::layout::{PLANE, SLIDER};".to_string(),
        ),
    ];
    assert!(circles(&graph(&none, &known)).is_empty());
}

/// The table is read from the README: a row's names and its layer.
#[test]
fn the_table_is_read() {
    let readme = "# x\n## Where each part of the port sits\n\n| layer | modules | what |\n|---|---|---|\n\
        | 0 | `types` | the records |\n| 6 | `film`, `tile` | the `--tile` bands |\n## State\n| 9 | `not` | x |\n";
    let rows = parse_layers(readme);
    assert_eq!(
        rows,
        [
            ("types".to_string(), 0),
            ("film".to_string(), 6),
            ("tile".to_string(), 6)
        ]
    );
}

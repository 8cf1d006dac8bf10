//! The command lines of a Markdown page, and what each one names.
//!
//! The rule (the test's doc, docs_commands.rs, says what happens to each):
//! - In a fenced code block, a line (a line ending in `\` joined with the
//!   next) is a command line when, outside a trailing `# comment`, it
//!   starts with `cargo` or has `raytrace`, `psout`, `contour` or `tools`
//!   as a word.
//!   The block's other lines are its plumbing (`mkdir`, `for`, `cd`, `printf`, an
//!   assignment, a comment) or not the port's (they are not run).
//! - An inline code span that starts with `cargo ` is a whole command, as
//!   a block's line is, unless it ends in `--` (then it names the way to
//!   reach a program, as in "`cargo run --release --` runs raytrace").
//! - An inline code span that starts with `raytrace`, `psout`, `contour` or `tools` is
//!   a program, a flag or a subcommand named in a sentence: a mention.

/// The port's programs, as a doc names them when they are on PATH.
pub const PROGRAMS: [&str; 5] = ["raytrace", "psout", "contour", "tools", "fidelity-mutants"];

/// How a line names an example of the root package (`cargo run --example
/// render` names `example-render`).
pub const EXAMPLE: &str = "example-";

/// One command line of a page.
#[derive(Clone, Debug)]
pub struct DocLine {
    /// 1-based line of the page where it starts.
    pub line: usize,
    /// The line as written (continuations joined by a space).
    pub text: String,
}

/// A fenced code block: its lines, continuations joined.
pub struct Block {
    pub lines: Vec<DocLine>,
}

/// The fenced code blocks of a page, in order.
pub fn blocks(page: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut current: Option<Block> = None;
    let mut pending: Option<DocLine> = None;
    for (i, raw) in page.lines().enumerate() {
        if raw.trim_start().starts_with("```") {
            match current.take() {
                Some(block) => out.push(block),
                None => current = Some(Block { lines: Vec::new() }),
            }
            continue;
        }
        let Some(block) = current.as_mut() else { continue };
        let (body, continued) = match raw.trim_end().strip_suffix('\\') {
            Some(body) => (body.trim_end(), true),
            None => (raw.trim_end(), false),
        };
        let line = match pending.take() {
            Some(mut p) => {
                p.text = format!("{} {}", p.text, body.trim_start());
                p
            }
            None => DocLine {
                line: i + 1,
                text: body.to_string(),
            },
        };
        if continued {
            pending = Some(line);
        } else {
            block.lines.push(line);
        }
    }
    out
}

/// The inline code spans of a page outside its code blocks, each with its
/// white space (line breaks included) made single spaces.
pub fn inline_spans(page: &str) -> Vec<DocLine> {
    let mut prose = String::with_capacity(page.len());
    let mut fenced = false;
    for line in page.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            prose.push('\n');
            continue;
        }
        // A fenced line keeps its place (line numbers) but not its text.
        prose.push_str(if fenced { "" } else { line });
        prose.push('\n');
    }
    let bytes = prose.as_bytes();
    let mut spans = Vec::new();
    let mut at = 0;
    while let Some(open) = prose[at..].find('`').map(|o| o + at) {
        let ticks = bytes[open..].iter().take_while(|&&b| b == b'`').count();
        let fence = "`".repeat(ticks);
        let start = open + ticks;
        let Some(close) = prose[start..].find(&fence).map(|c| c + start) else {
            break;
        };
        let text = prose[start..close].split_whitespace().collect::<Vec<_>>().join(" ");
        spans.push(DocLine {
            line: prose[..open].matches('\n').count() + 1,
            text,
        });
        at = close + ticks;
    }
    spans
}

/// The targets of a page's links, `[text](target)`, outside code blocks.
pub fn links(page: &str) -> Vec<DocLine> {
    let mut out = Vec::new();
    let mut fenced = false;
    for (i, line) in page.lines().enumerate() {
        fenced ^= line.trim_start().starts_with("```");
        for (at, _) in line.match_indices("](").filter(|_| !fenced) {
            let target = line[at + 2..].split([')', ' ']).next().unwrap_or("");
            out.push(DocLine {
                line: i + 1,
                text: target.to_string(),
            });
        }
    }
    out
}

/// The anchors of a page's headings, as GitHub makes them: lower case,
/// punctuation dropped, spaces made hyphens.
pub fn anchors(page: &str) -> Vec<String> {
    page.lines()
        .filter_map(|l| l.strip_prefix('#').map(|h| h.trim_start_matches('#').trim()))
        .map(|h| {
            h.chars()
                .filter(|c| c.is_alphanumeric() || ['-', '_', ' '].contains(c))
                .map(|c| if c == ' ' { '-' } else { c })
                .collect::<String>()
                .to_lowercase()
        })
        .collect()
}

/// The line without a trailing `# comment` (a `#` after white space,
/// outside quotes), and without a leading `$ ` prompt.
pub fn code_of(line: &str) -> &str {
    let line = line.trim();
    let line = line.strip_prefix("$ ").unwrap_or(line);
    let (mut single, mut double) = (false, false);
    let mut prev = ' ';
    for (i, c) in line.char_indices() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '#' if !single && !double && prev.is_whitespace() => return line[..i].trim_end(),
            _ => {}
        }
        prev = c;
    }
    line
}

/// The shell words of a line, quotes and brackets stripped from their ends
/// (`'tools` is `tools`, `[--png` is `--png`).
pub fn words(code: &str) -> Vec<String> {
    code.split_whitespace()
        .map(|w| w.trim_matches(|c| "'\"()[]{},;".contains(c)).to_string())
        .filter(|w| !w.is_empty())
        .collect()
}

/// Whether a block's line is a command line of the port's programs.
pub fn names_a_program(line: &str) -> bool {
    let code = code_of(line);
    if code.is_empty() || code.starts_with('#') {
        return false;
    }
    let words = words(code);
    words.first().is_some_and(|w| w == "cargo") || (0..words.len()).any(|i| program_at(&words, i))
}

/// Program names that are also words of prose and of decks' comments
/// (`{ control points of the closed contour }`): one names the program only
/// where a command starts, first on the line or after a shell operator.
const PLAIN_WORDS: [&str; 1] = ["contour"];

/// Whether `words[i]` names one of the port's programs.
fn program_at(words: &[String], i: usize) -> bool {
    let w = words[i].as_str();
    PROGRAMS.contains(&w) && (!PLAIN_WORDS.contains(&w) || i == 0 || ends_stage(&words[i - 1]))
}

/// A synopsis rather than a command: an optional `[…]` group or an `…`.
pub fn is_synopsis(line: &str) -> bool {
    let code = code_of(line);
    code.contains('…')
        || code
            .split_whitespace()
            .any(|w| w.starts_with('[') && code.contains(']'))
}

/// What a command line (or a mention) names: the program and its
/// subcommand, the arguments it gives them, and for `cargo` the cargo
/// subcommand and its own options.
#[derive(Debug, Default, PartialEq)]
pub struct Named {
    /// `raytrace`, `psout`, `contour`, `tools`, `fidelity-mutants`, an
    /// example (`example-render`); None for a cargo command that runs no
    /// program (`cargo test`, `cargo install`).
    pub program: Option<String>,
    /// The tools subcommand (`join`), when one is named.
    pub sub: Option<String>,
    /// The program's arguments, up to the end of its pipeline stage.
    pub args: Vec<String>,
    /// `run`, `test`, `install`, … when the line starts with `cargo`.
    pub cargo: Option<String>,
    /// The cargo command's `-p` package and `--path`, when given.
    pub package: Option<String>,
    pub path: Option<String>,
}

/// Words that end a program's arguments: the shell's operators.
fn ends_stage(word: &str) -> bool {
    ["|", "||", "&&", ";", ">", ">>", "<", "2>", "&"].contains(&word)
}

/// What a line names (None when it names none of the port's programs).
pub fn named(line: &str) -> Option<Named> {
    let code = code_of(line);
    let words = words(code);
    let mut out = Named::default();
    let rest: &[String] = if words.first().map(String::as_str) == Some("cargo") {
        let sub = words.get(1)?.clone();
        let mut i = 2;
        let mut bin = None;
        while i < words.len() && words[i] != "--" {
            match words[i].as_str() {
                "-p" | "--package" => out.package = words.get(i + 1).cloned(),
                "--bin" => bin = words.get(i + 1).cloned(),
                "--example" => bin = words.get(i + 1).map(|e| format!("{EXAMPLE}{e}")),
                "--path" => out.path = words.get(i + 1).cloned(),
                _ => {}
            }
            i += if ["-p", "--package", "--bin", "--example", "--path"].contains(&words[i].as_str()) {
                2
            } else {
                1
            };
        }
        if sub == "run" {
            out.program = Some(bin.unwrap_or_else(|| match out.package.as_deref() {
                Some("tools") => "tools".to_string(),
                _ => "raytrace".to_string(),
            }));
        }
        out.cargo = Some(sub);
        words.get(i + 1..).unwrap_or(&[])
    } else {
        let at = (0..words.len()).find(|&i| program_at(&words, i))?;
        out.program = Some(words[at].clone());
        &words[at + 1..]
    };
    out.args = rest.iter().take_while(|w| !ends_stage(w)).cloned().collect();
    if out.program.as_deref() == Some("tools") {
        out.sub = out
            .args
            .first()
            .filter(|w| w.chars().all(|c| c.is_ascii_lowercase() || c == '-') && !w.starts_with('-'))
            .cloned();
    }
    Some(out)
}

/// The flags among a line's arguments (`--size`, `-o`), without values.
pub fn flags(args: &[String]) -> Vec<String> {
    args.iter()
        .filter(|a| a.starts_with('-') && a.trim_start_matches('-').starts_with(|c: char| c.is_ascii_alphabetic()))
        .map(|a| a.split('=').next().unwrap_or(a).to_string())
        .collect()
}

/// The paths under `dir`, folders ending in `/`, except under raster/
/// (which git ignores in a checkout).
pub fn outside_raster(dir: &std::path::Path) -> std::collections::BTreeSet<String> {
    let mut found = std::collections::BTreeSet::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let path = e.unwrap().path();
            let rel = path.strip_prefix(dir).unwrap().display().to_string();
            if rel == "raster" {
                continue;
            }
            if path.is_dir() && !path.is_symlink() {
                found.insert(format!("{rel}/"));
                todo.push(path);
            } else {
                found.insert(rel);
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_join_continued_lines_and_spans_cross_line_breaks() {
        let page = "a `cargo run\n--release -- x` b\n```\nraytrace d \\\n    --quiet\ntools join a\n```\n`psout`\n";
        let b = blocks(page);
        assert_eq!(b.len(), 1);
        assert_eq!(b[0].lines[0].text, "raytrace d --quiet");
        assert_eq!((b[0].lines[1].line, b[0].lines[1].text.as_str()), (6, "tools join a"));
        let s = inline_spans(page);
        assert_eq!(s.len(), 2);
        assert_eq!((s[0].line, s[0].text.as_str()), (1, "cargo run --release -- x"));
        assert_eq!((s[1].line, s[1].text.as_str()), (8, "psout"));
    }

    #[test]
    fn what_a_line_names() {
        let n = named("cargo run --release -p tools -- join raster/a.*.ras -o film.png # x").unwrap();
        assert_eq!(n.program.as_deref(), Some("tools"));
        assert_eq!(n.sub.as_deref(), Some("join"));
        assert_eq!(flags(&n.args), ["-o"]);
        assert!(!names_a_program("sweep s r rotation bspline at 0 0 0 { the contour }"));
        assert!(names_a_program("contour d.deck s --list"));
        assert_eq!(
            named("cat e | contour d s --script -").unwrap().args,
            ["d", "s", "--script", "-"]
        );
        let n = named("cargo run --release --bin psout -- --screenshot s.png f.ras").unwrap();
        assert_eq!(n.program.as_deref(), Some("psout"));
        let n = named("cargo run --release --example render -- d.deck raster/o.png").unwrap();
        assert_eq!(n.program.as_deref(), Some("example-render"));
        assert_eq!(n.args, ["d.deck", "raster/o.png"]);
        let n = named("seq 36 | parallel -S 2/: raytrace d.deck --frames {} | head").unwrap();
        assert_eq!(
            (n.program.as_deref(), flags(&n.args)),
            (Some("raytrace"), vec!["--frames".to_string()])
        );
        let n = named("cargo install --path tools").unwrap();
        assert_eq!(
            (n.program, n.cargo.as_deref(), n.path.as_deref()),
            (None, Some("install"), Some("tools"))
        );
        assert!(named("mkdir -p frames").is_none());
        assert!(!names_a_program("#SBATCH --job-name=raytrace"));
        assert!(!names_a_program("mkdir x   # then raytrace"));
        assert!(is_synopsis("tools join FILE… -o OUT.png"));
        assert!(is_synopsis("raytrace [DECK|-] [-o FILE]"));
        assert!(!is_synopsis("raytrace d.deck --frames \"$A..$B\""));
    }
}

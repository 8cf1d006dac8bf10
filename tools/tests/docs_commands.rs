//! Docs that run: every command line of README.md, docs/*.md and
//! legacy_pascal/*.md that invokes `cargo`, `raytrace`, `psout`, `contour` or `tools`
//! is run, or when it cannot be, checked, so that a renamed flag or binary
//! fails here and not in a reader's hands.
//!
//! Which lines are command lines is doc_lines/mod.rs's rule: a fenced code
//! block's lines that name a program, inline spans that start `cargo `
//! (whole commands, unless they end in `--`), and inline spans that start
//! with a program's name (mentions: a flag or subcommand in a sentence).
//!
//! What happens to each:
//! - A block's command lines run in order as one bash script (`set -eo
//!   pipefail`) with the block's plumbing (`mkdir`, `for`, `cd`, an
//!   assignment, a `printf` that writes a file the commands read); a
//!   block's other lines are not run. An inline `cargo`
//!   command runs alone. Every script runs in a temporary copy of what a
//!   fresh checkout gives the docs' commands (legacy_pascal/ and the texture
//!   rasters), one copy a page, with stdin empty, and must exit 0: no doc
//!   shows an error on purpose in a command line.
//! - The programs are this build's, through shims first on PATH: `cargo run
//!   [-p P] [--bin B] -- ARGS` runs B's binary with ARGS; `raytrace` renders
//!   at `--size 32x32` unless the line sets a size; `psout` writes
//!   `--screenshot raster/psout-window.png` unless the line does (a window needs a
//!   display and waits for a key), and so does `contour` (`--screenshot
//!   raster/contour-window.png`) unless it writes something else (`-o`, `--list`);
//!   a `raytrace --show` or `--watch` line is not run (a window that waits
//!   for a key) but must parse; `tools bench` renders at 32×32 and `tools
//!   fuzz` tries 300 inputs unless the line says otherwise.
//! - The placeholder DECK is `film200.deck`, the commercial's scene as a
//!   film of 200 frames: DECK stands for any deck, and docs/farm.md's recipe
//!   for a long film renders frames 101..200. A Slurm task script runs
//!   with SLURM_ARRAY_TASK_ID=1, SLURM_CPUS_PER_TASK=1 and
//!   SLURM_SUBMIT_DIR the page's folder.
//! - Not run, with the reason, by [`skip`]: cargo's own commands, Slurm
//!   submissions (docs/farm.md's recipes call the port's programs through
//!   the farm/ scripts, which CI's farm/check.sh runs on a one-node
//!   cluster; [`farm_md_quotes_the_scripts_and_the_lines_ci_runs`] holds the
//!   page to them), GNU parallel over remote hosts, the tools that time or
//!   draw for minutes or write into the checkout (`tools scale` runs with
//!   `--quick` or `--decks`), and lines whose outside
//!   program (`parallel`, `povray`, …) is not installed. A synopsis (a
//!   `[…]` group or an `…`) is not run either.
//! - Every line, run or not, is checked as a mention: its program exists,
//!   a tools subcommand answers `--help`, each flag it names is in that
//!   `--help`, a `-p` names a package of the workspace and a `--path` a
//!   package's folder. A skipped tools line must also parse as written
//!   (the line with `--help` added exits 0).
//!
//! The test lives in the tools package, where `CARGO_BIN_EXE_tools` is
//! this build's tools; raytrace, psout and contour are the root package's binaries
//! beside it, which `cargo test --workspace` builds in the same run (the
//! test refuses them when they are older than the sources).

mod doc_lines;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant, SystemTime};

use doc_lines::{
    anchors, blocks, code_of, flags, inline_spans, is_synopsis, links, named, names_a_program, outside_raster, words,
    DocLine, Named, EXAMPLE,
};

/// The checkout.
fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The pages whose commands are run: the README, docs/*.md, legacy_pascal/*.md.
fn pages() -> Vec<PathBuf> {
    let mut pages = vec![PathBuf::from("README.md")];
    for dir in ["docs", "legacy_pascal"] {
        let mut md: Vec<PathBuf> = std::fs::read_dir(repo().join(dir))
            .unwrap()
            .map(|e| Path::new(dir).join(e.unwrap().file_name()))
            .filter(|p| p.extension().is_some_and(|e| e == "md"))
            .collect();
        md.sort();
        pages.extend(md);
    }
    pages
}

/// The newest modification time of a file under `path`.
fn newest(path: &Path) -> SystemTime {
    let meta = std::fs::metadata(path).unwrap();
    if !meta.is_dir() {
        return meta.modified().unwrap();
    }
    std::fs::read_dir(path)
        .unwrap()
        .map(|e| newest(&e.unwrap().path()))
        .max()
        .unwrap_or(SystemTime::UNIX_EPOCH)
}

/// The programs of this build, by name.
fn binaries() -> BTreeMap<&'static str, PathBuf> {
    let tools = PathBuf::from(env!("CARGO_BIN_EXE_tools"));
    let dir = tools.parent().unwrap().to_path_buf();
    let sources = ["src", "examples", "Cargo.toml", "Cargo.lock"]
        .map(|p| newest(&repo().join(p)))
        .into_iter()
        .max()
        .unwrap();
    let mut bins = BTreeMap::from([
        ("tools", tools),
        (
            "fidelity-mutants",
            PathBuf::from(env!("CARGO_BIN_EXE_fidelity-mutants")),
        ),
    ]);
    for (name, file) in [
        ("raytrace", "raytrace"),
        ("psout", "psout"),
        ("contour", "contour"),
        ("example-render", "examples/render"),
    ] {
        let path = dir.join(file);
        let built = std::fs::metadata(&path).and_then(|m| m.modified());
        assert!(
            built.as_ref().is_ok_and(|&b| b >= sources),
            "{} is missing or older than src/: `cargo test --workspace` builds it with this test",
            path.display()
        );
        bins.insert(name, path);
    }
    bins
}

/// `raytrace`: renders at 32×32 unless the line sets a size.
const RAYTRACE_SHIM: &str = r#"#!/bin/sh
for a in "$@"; do case $a in --size|-h|--help|-V|--version) exec REAL "$@";; esac; done
exec REAL --size 32x32 "$@"
"#;

/// `psout`: writes its screen instead of opening a window, which needs a
/// display and waits for a key.
const PSOUT_SHIM: &str = r#"#!/bin/sh
for a in "$@"; do case $a in --screenshot|-h|--help|-V|--version) exec REAL "$@";; esac; done
exec REAL --screenshot raster/psout-window.png "$@"
"#;

/// `contour`: writes its screen instead of opening a window, unless the
/// line writes a deck or lists the points.
const CONTOUR_SHIM: &str = r#"#!/bin/sh
for a in "$@"; do case $a in --screenshot|-o|--output|--list|-h|--help|-V|--version) exec REAL "$@";; esac; done
exec REAL --screenshot raster/contour-window.png "$@"
"#;

/// `tools`: `bench` at 32×32 and `fuzz` over 300 inputs unless the line
/// says otherwise; the rest as written.
const TOOLS_SHIM: &str = r#"#!/bin/sh
case $1 in
  bench) flag=--size; add='--size 32x32';;
  fuzz) flag=--inputs; add='--inputs 300';;
  *) exec REAL "$@";;
esac
for a in "$@"; do case $a in "$flag"|-h|--help) exec REAL "$@";; esac; done
sub=$1; shift
exec REAL "$sub" $add "$@"
"#;

/// `cargo run [--release] [-p P] [--bin B | --example E] [-- ARGS]`: B (or
/// P's default binary, or the root package's example E) with ARGS, through
/// the shims above; any other form is refused.
const CARGO_SHIM: &str = r#"#!/bin/sh
[ "$1" = run ] || { echo "docs test: only 'cargo run' runs here: cargo $*" >&2; exit 97; }
shift; pkg=raytrace; bin=
while [ $# -gt 0 ]; do case $1 in
  --release) shift;;
  -p|--package) pkg=$2; shift 2;;
  --bin) bin=$2; shift 2;;
  --example) bin=example-$2; shift 2;;
  --) shift; break;;
  *) echo "docs test: 'cargo run $1' is not known here" >&2; exit 97;;
esac; done
case $pkg/$bin in
  raytrace/|raytrace/raytrace) exec raytrace "$@";;
  raytrace/psout) exec psout "$@";;
  raytrace/contour) exec contour "$@";;
  raytrace/example-render) exec example-render "$@";;
  tools/|tools/tools) exec tools "$@";;
  tools/fidelity-mutants) exec fidelity-mutants "$@";;
esac
echo "docs test: package $pkg has no binary '$bin'" >&2; exit 97
"#;

/// Writes the shims, first on the scripts' PATH, with REAL each program's
/// binary.
fn write_shims(dir: &Path, bins: &BTreeMap<&str, PathBuf>) {
    let shims = [
        ("raytrace", RAYTRACE_SHIM),
        ("psout", PSOUT_SHIM),
        ("contour", CONTOUR_SHIM),
        ("tools", TOOLS_SHIM),
        ("fidelity-mutants", "#!/bin/sh\nexec REAL \"$@\"\n"),
        ("example-render", "#!/bin/sh\nexec REAL \"$@\"\n"),
        ("cargo", CARGO_SHIM),
    ];
    for (name, body) in shims {
        let real = bins.get(name).map(|b| format!("'{}'", b.display())).unwrap_or_default();
        let path = dir.join(name);
        std::fs::write(&path, body.replace("REAL", &real)).unwrap();
        let mut perm = std::fs::metadata(&path).unwrap().permissions();
        std::os::unix::fs::PermissionsExt::set_mode(&mut perm, 0o755);
        std::fs::set_permissions(&path, perm).unwrap();
    }
}

/// Outside programs the docs use: a line that uses one runs only where it
/// is installed.
const OUTSIDE: [&str; 5] = ["parallel", "povray", "/usr/bin/time", "rasttopnm", "xvfb-run"];

fn installed(program: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {program}")])
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// Why a command line is not run, and whether its arguments must still
/// parse as written (a tools line with literal arguments).
fn skip(n: &Named, words: &[String]) -> Option<(String, bool)> {
    let has = |w: &str| words.iter().any(|x| x == w);
    let why = |s: &str| Some((s.to_string(), false));
    match n.cargo.as_deref() {
        Some("test") => return why("the command that runs this test"),
        Some("build") => return why("a build: this test's binaries are that build"),
        Some("bench") => return why("criterion's benchmarks take minutes"),
        Some("install") => return why("installs into ~/.cargo/bin"),
        Some("run") | None => {}
        Some(_) => return why("cargo's own command"),
    }
    if has("sbatch") {
        return why("submits a Slurm job; the task script itself runs here");
    }
    if has("parallel") && has("-S") {
        return why("runs on the remote hosts it names, over ssh");
    }
    if let Some(outside) = OUTSIDE.iter().find(|o| has(o) && !installed(o)) {
        return why(&format!("{outside} is not installed"));
    }
    let parse = |s: &str| Some((s.to_string(), true));
    match (n.program.as_deref(), n.sub.as_deref()) {
        (Some("raytrace"), _) if has("--show") || has("--watch") => {
            parse("opens a window that waits for a key (or for the deck to change)")
        }
        (Some("tools"), Some("chart" | "goal" | "frontier")) => parse("times renders for minutes"),
        (Some("tools"), Some("stability")) => parse("solves hard cases for minutes"),
        (Some("tools"), Some("vs-povray")) => parse("times POV-Ray against the port for minutes"),
        (Some("tools"), Some("scale")) if !has("--quick") && !has("--decks") => {
            parse("times scenes of up to 100,000 objects for many minutes (`--quick` runs)")
        }
        (Some("tools"), Some("gallery")) if !has("--list") => {
            parse("draws into the checkout's docs/ (`--check` renders every picture: minutes)")
        }
        (Some("fidelity-mutants"), _) => parse("builds and tests the crate once per listing branch"),
        _ => None,
    }
}

/// The `--help` of each program and subcommand, asked once.
struct Helps<'a> {
    bins: &'a BTreeMap<&'static str, PathBuf>,
    seen: BTreeMap<String, Result<String, String>>,
}

impl Helps<'_> {
    fn help(&mut self, program: &str, sub: Option<&str>) -> Result<String, String> {
        let key = format!("{program} {}", sub.unwrap_or(""));
        let bins = self.bins;
        self.seen
            .entry(key.clone())
            .or_insert_with(|| {
                let bin = bins.get(program).ok_or(format!("no program {program}"))?;
                let out = Command::new(bin).args(sub).arg("--help").output().unwrap();
                match out.status.success() {
                    true => Ok(String::from_utf8_lossy(&out.stdout).into_owned()),
                    false => Err(format!("`{} --help` fails", key.trim_end())),
                }
            })
            .clone()
    }
}

/// Whether a help text names a flag as a whole word.
fn help_has(help: &str, flag: &str) -> bool {
    help.match_indices(flag).any(|(i, _)| {
        let after = help[i + flag.len()..].chars().next();
        let before = help[..i].chars().next_back();
        !after.is_some_and(|c| c.is_ascii_alphanumeric() || c == '-')
            && !before.is_some_and(|c| c.is_ascii_alphanumeric() || c == '-')
    })
}

/// The workspace's packages, by name (the root's members).
fn packages() -> Vec<String> {
    let root = std::fs::read_to_string(repo().join("Cargo.toml")).unwrap();
    let members = root.lines().find(|l| l.starts_with("members")).expect("a workspace");
    members
        .split('"')
        .skip(1)
        .step_by(2)
        .map(|m| {
            let toml = std::fs::read_to_string(repo().join(m).join("Cargo.toml")).unwrap();
            let name = toml.lines().find_map(|l| l.strip_prefix("name = ")).unwrap();
            name.trim_matches('"').to_string()
        })
        .collect()
}

/// The mention check of the module's doc.
fn check_mention(n: &Named, helps: &mut Helps) -> Result<(), String> {
    if let Some(p) = &n.package {
        if !packages().contains(p) {
            return Err(format!("no package '{p}' in the workspace"));
        }
    }
    if let Some(path) = &n.path {
        if !repo().join(path).join("Cargo.toml").is_file() {
            return Err(format!("'{path}' is not a package's folder"));
        }
    }
    let Some(program) = n.program.as_deref() else {
        return Ok(());
    };
    if program.starts_with(EXAMPLE) {
        // An example takes no flags and answers no --help: it must exist.
        return match (helps.bins.contains_key(program), flags(&n.args).first()) {
            (false, _) => Err(format!("no example {program}")),
            (true, Some(f)) => Err(format!("{program} takes no flags, not {f}")),
            (true, None) => Ok(()),
        };
    }
    let help = helps.help(program, n.sub.as_deref())?;
    match flags(&n.args).into_iter().find(|f| !help_has(&help, f)) {
        Some(f) => Err(format!(
            "`{program}{} --help` has no {f}",
            n.sub.as_deref().map(|s| format!(" {s}")).unwrap_or_default()
        )),
        None => Ok(()),
    }
}

/// A skipped line's arguments parse as written: with `--help` added, the
/// program exits 0.
fn check_parse(n: &Named, helps: &Helps) -> Result<(), String> {
    let bin = &helps.bins[n.program.as_deref().unwrap()];
    let out = Command::new(bin).args(&n.args).arg("--help").output().unwrap();
    match out.status.success() {
        true => Ok(()),
        false => Err(format!(
            "does not parse: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        )),
    }
}

/// DECK, the placeholder of the docs' commands, as a word.
fn with_placeholders(line: &str) -> String {
    let mut out = String::new();
    let mut rest = line;
    while let Some(i) = rest.find("DECK") {
        let before = rest[..i].chars().next_back();
        let after = rest[i + 4..].chars().next();
        // Part of a longer name (DECK.md, DECKS) is not the placeholder.
        let word = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || "_./".contains(c));
        out.push_str(&rest[..i]);
        out.push_str(if word(before) || word(after) {
            "DECK"
        } else {
            "film200.deck"
        });
        rest = &rest[i + 4..];
    }
    out + rest
}

/// A page's folder: what a fresh checkout gives its commands.
fn sandbox() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let copy = Command::new("cp")
        .arg("-R")
        .arg(repo().join("legacy_pascal"))
        .arg(dir.path())
        .status();
    assert!(copy.unwrap().success());
    std::fs::create_dir(dir.path().join("raster")).unwrap();
    for e in std::fs::read_dir(repo().join("raster")).unwrap() {
        let name = e.unwrap().file_name();
        if name.to_string_lossy().ends_with(".tex.ras") {
            std::fs::copy(repo().join("raster").join(&name), dir.path().join("raster").join(&name)).unwrap();
        }
    }
    let commercial = std::fs::read_to_string(dir.path().join("legacy_pascal/decks/nec_commercial.deck")).unwrap();
    let film: Vec<&str> = commercial
        .lines()
        .map(|l| {
            if l.starts_with("film ") {
                "film 200  shutter 0.5  rate 12"
            } else {
                l
            }
        })
        .collect();
    assert_ne!(
        film.join("\n"),
        commercial.trim_end(),
        "the commercial has a film record"
    );
    std::fs::write(dir.path().join("film200.deck"), film.join("\n")).unwrap();
    dir
}

/// Runs a script in a page's folder; Err with its output when it fails or
/// takes over two minutes.
fn run_script(dir: &Path, shims: &Path, script: &str) -> Result<(), String> {
    let file = dir.join(".docs-script.sh");
    std::fs::write(&file, format!("set -eo pipefail\n{script}\n")).unwrap();
    let path = format!("{}:{}", shims.display(), std::env::var("PATH").unwrap_or_default());
    let mut child = Command::new("bash")
        .arg(&file)
        .current_dir(dir)
        .env("PATH", path)
        .env("HOME", dir)
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_CPUS_PER_TASK", "1")
        .env("SLURM_SUBMIT_DIR", dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(120) {
            child.kill().unwrap();
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    match out.status.success() {
        true => Ok(()),
        false => Err(format!(
            "{:?}\n{}{}",
            out.status,
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )),
    }
}

/// Whether a block's line that names no program is plumbing its commands
/// need (kept in the script), rather than something of its own.
fn plumbing(code: &str) -> bool {
    let first = words(code).into_iter().next().unwrap_or_default();
    let assignment = first
        .split_once('=')
        .is_some_and(|(v, _)| v.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'));
    // A command substitution (not arithmetic) runs a program of its own.
    let substitutes = code.replace("$((", "").contains("$(") || code.contains('`');
    !substitutes
        && (code.is_empty()
            || code.starts_with('#')
            || assignment
            || ["mkdir", "cd", "for", "do", "done", "printf"].contains(&first.as_str()))
}

/// What became of a page's lines.
#[derive(Default)]
struct Report {
    ran: Vec<String>,
    skipped: Vec<String>,
    failed: Vec<String>,
}

/// Checks one command line; returns the script line to run, if it runs.
fn command_line(page: &str, l: &DocLine, helps: &mut Helps, report: &mut Report) -> Option<String> {
    let at = format!("{page}:{}: {}", l.line, l.text);
    let n = named(&l.text)?;
    if let Err(e) = check_mention(&n, helps) {
        report.failed.push(format!("{at}\n  {e}"));
        return None;
    }
    if is_synopsis(&l.text) {
        report.skipped.push(format!("{at}\n  a synopsis: its flags checked"));
        return None;
    }
    match skip(&n, &words(code_of(&l.text))) {
        Some((why, parse)) => {
            if let Err(e) = if parse { check_parse(&n, helps) } else { Ok(()) } {
                report.failed.push(format!("{at}\n  {e}"));
            }
            report.skipped.push(format!("{at}\n  not run: {why}"));
            None
        }
        None => {
            report.ran.push(at);
            Some(with_placeholders(&l.text))
        }
    }
}

/// Runs and checks every command line of one page in its own folder; what
/// the commands write goes under raster/ (git ignores it), never beside
/// the checkout's own files.
fn check_page(page: &Path, shims: &Path, helps: &mut Helps) -> (Report, tempfile::TempDir) {
    let text = std::fs::read_to_string(repo().join(page)).unwrap();
    let name = page.display().to_string();
    let dir = sandbox();
    let fresh = outside_raster(dir.path());
    let mut report = Report::default();
    for block in blocks(&text) {
        if !block.lines.iter().any(|l| names_a_program(&l.text)) {
            continue;
        }
        let mut script = String::new();
        let mut runs = false;
        for l in &block.lines {
            let line = match names_a_program(&l.text) {
                true => command_line(&name, l, helps, &mut report),
                false if plumbing(code_of(&l.text)) => Some(l.text.clone()),
                false => None,
            };
            runs |= line.is_some() && names_a_program(&l.text);
            writeln!(script, "{}", line.unwrap_or_else(|| ":".into())).unwrap();
        }
        if runs {
            if let Err(e) = run_script(dir.path(), shims, &script) {
                let first = block.lines[0].line;
                report
                    .failed
                    .push(format!("{name}: the block at line {first} fails:\n{script}{e}"));
            }
        }
    }
    for span in inline_spans(&text) {
        let first = words(&span.text).into_iter().next().unwrap_or_default();
        let command = first == "cargo" && !span.text.ends_with(" --");
        if !command {
            let mention = first == "cargo" || doc_lines::PROGRAMS.contains(&first.as_str());
            if let Some(n) = named(&span.text).filter(|_| mention) {
                if let Err(e) = check_mention(&n, helps) {
                    report
                        .failed
                        .push(format!("{name}:{}: `{}`\n  {e}", span.line, span.text));
                }
            }
        } else if let Some(line) = command_line(&name, &span, helps, &mut report) {
            if let Err(e) = run_script(dir.path(), shims, &line) {
                report
                    .failed
                    .push(format!("{name}:{}: `{}` fails:\n{e}", span.line, span.text));
            }
        }
    }
    // The first name of each new path (a folder's files are its folder's);
    // the test's own script, and GNU parallel's state in HOME (the page's
    // folder here), aside.
    let now = outside_raster(dir.path());
    let written: std::collections::BTreeSet<&str> = now
        .difference(&fresh)
        .map(|p| p.split_inclusive('/').next().unwrap_or(p))
        .filter(|p| ![".docs-script.sh", ".parallel/"].contains(p))
        .collect();
    let written: Vec<&str> = written.into_iter().collect();
    if !written.is_empty() {
        report.failed.push(format!(
            "{name}: its commands write outside raster/ (into a checkout's own folder): {}",
            written.join(", ")
        ));
    }
    (report, dir)
}

#[test]
fn every_command_line_of_the_docs_runs() {
    let bins = binaries();
    let shims = tempfile::tempdir().unwrap();
    write_shims(shims.path(), &bins);
    let mut helps = Helps {
        bins: &bins,
        seen: BTreeMap::new(),
    };
    let (mut ran, mut failed) = (0, Vec::new());
    for page in pages() {
        let (report, dir) = check_page(&page, shims.path(), &mut helps);
        for r in &report.ran {
            println!("{r}\n  ran");
        }
        for s in &report.skipped {
            println!("{s}");
        }
        if page == Path::new("README.md") {
            // The first of the two commands of a fresh machine ran and did what it says.
            let ran_first = report
                .ran
                .iter()
                .any(|r| code_of(r.split_once(": ").unwrap().1) == "cargo run --release");
            assert!(
                ran_first,
                "the README's `cargo run --release` did not run: {:?}",
                report.ran
            );
            for out in ["raster/default.ras", "raster/default.png"] {
                assert!(
                    dir.path().join(out).is_file(),
                    "the README's `cargo run --release` wrote no {out}"
                );
            }
        }
        ran += report.ran.len();
        failed.extend(report.failed);
    }
    println!("{ran} command lines ran");
    assert!(
        failed.is_empty(),
        "{} documented command lines fail:\n\n{}",
        failed.len(),
        failed.join("\n\n")
    );
}

/// The README's usage block gives each program's synopsis as `--help`
/// gives its options: every long option of `raytrace --help`, `psout
/// --help` and `contour --help` is in it (its flags being real is the
/// mention check's).
#[test]
fn the_readme_synopsis_has_every_option_of_help() {
    let bins = binaries();
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let usage = blocks(&readme)
        .into_iter()
        .find(|b| b.lines.iter().any(|l| l.text.starts_with("raytrace [")))
        .expect("the README has a usage block");
    for program in ["raytrace", "psout", "contour"] {
        // The program's lines: its own, and the indented ones after it.
        let mut synopsis = String::new();
        let mut inside = false;
        for l in &usage.lines {
            inside = l.text.starts_with(program) || (inside && l.text.starts_with(' '));
            if inside {
                synopsis.push_str(&l.text);
                synopsis.push(' ');
            }
        }
        let help = Command::new(&bins[program]).arg("--help").output().unwrap();
        // An option's line of --help: `-o, --output <FILE>`, `--png <FILE>`.
        for line in String::from_utf8_lossy(&help.stdout).lines() {
            let names: Vec<&str> = line
                .split("  ")
                .map(str::trim)
                .find(|s| !s.is_empty())
                .filter(|s| s.starts_with('-'))
                .unwrap_or("")
                .split([',', ' '])
                .filter(|w| {
                    w.starts_with('-') && w.trim_start_matches('-').starts_with(|c: char| c.is_ascii_alphabetic())
                })
                .collect();
            if names.is_empty() || names.iter().any(|n| ["--help", "--version"].contains(n)) {
                continue;
            }
            let listed = names.iter().any(|n| help_has(&synopsis, n));
            assert!(listed, "the README's synopsis of {program} lacks {}", names.join(", "));
        }
    }
}

/// CI runs the README's test command as the README writes it.
#[test]
fn ci_runs_the_readmes_test_command() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let tests: Vec<String> = blocks(&readme)
        .into_iter()
        .flat_map(|b| b.lines)
        .map(|l| code_of(&l.text).to_string())
        .filter(|c| c.starts_with("cargo test"))
        .collect();
    assert_eq!(tests.len(), 1, "the README gives one test command: {tests:?}");
    let ci = std::fs::read_to_string(repo().join(".ci/run")).unwrap();
    assert!(
        ci.lines().any(|l| code_of(l) == tests[0]),
        ".ci/run does not run `{}`",
        tests[0]
    );
}

/// The README is a front page: at most 200 lines, no paragraph (a run of
/// prose lines, outside code blocks and tables) over 12 lines, and none of
/// the port's row numbers (D33, erratum 9) that only DEVIATIONS.md explains.
#[test]
fn the_readme_is_a_front_page() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    assert!(
        readme.lines().count() <= 200,
        "the README has {} lines",
        readme.lines().count()
    );
    let (mut fenced, mut run, mut longest) = (false, 0, (0, 0));
    for (i, line) in readme.lines().enumerate() {
        fenced ^= line.starts_with("```");
        let prose = !fenced && !line.starts_with("```") && !line.trim().is_empty() && !line.starts_with('|');
        run = if prose { run + 1 } else { 0 };
        longest = longest.max((run, i + 1));
    }
    assert!(
        longest.0 <= 12,
        "the README's paragraph ending at line {} has {} lines",
        longest.1,
        longest.0
    );
    for word in words(&readme) {
        let row = word
            .strip_prefix('D')
            .is_some_and(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
        assert!(
            !row && !word.starts_with("errat"),
            "the README names '{word}' unexplained"
        );
    }
}

/// Every link of the pages leads to a file of the checkout, and an anchor
/// to a heading of its page: moved text leaves no link behind.
#[test]
fn every_link_of_the_docs_leads_somewhere() {
    let mut broken = Vec::new();
    for page in pages() {
        let text = std::fs::read_to_string(repo().join(&page)).unwrap();
        for link in links(&text).into_iter().filter(|l| !l.text.contains("://")) {
            let (path, anchor) = link.text.split_once('#').unwrap_or((&link.text, ""));
            let target = match path {
                "" => repo().join(&page),
                _ => repo().join(&page).parent().unwrap().join(path),
            };
            let found = target.exists()
                && (anchor.is_empty()
                    || target.extension().is_none_or(|e| e != "md")
                    || anchors(&std::fs::read_to_string(&target).unwrap())
                        .iter()
                        .any(|a| a == anchor));
            if !found {
                broken.push(format!("{}:{}: {}", page.display(), link.line, link.text));
            }
        }
    }
    assert!(broken.is_empty(), "links that lead nowhere:\n{}", broken.join("\n"));
}

/// docs/farm.md gives the farm's recipes exactly as CI runs them: each
/// task script of farm/slurm/ is quoted whole in a code block, each line of
/// a block marked `<!-- farm/check.sh runs these lines -->` is in a line of
/// farm/check.sh, and .ci/run runs farm/check.sh.
#[test]
fn farm_md_quotes_the_scripts_and_the_lines_ci_runs() {
    let page = std::fs::read_to_string(repo().join("docs/farm.md")).unwrap();
    let check = std::fs::read_to_string(repo().join("farm/check.sh")).unwrap();
    let ci = std::fs::read_to_string(repo().join(".ci/run")).unwrap();
    assert!(
        ci.lines().any(|l| l.trim() == "bash farm/check.sh"),
        ".ci/run does not run farm/check.sh"
    );
    let fenced: Vec<String> = page
        .split("```")
        .skip(1)
        .step_by(2)
        .map(|b| b.split_once('\n').map_or("", |(_, body)| body).to_string())
        .collect();
    let mut scripts = 0;
    for e in std::fs::read_dir(repo().join("farm/slurm")).unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_some_and(|x| x == "sbatch") {
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(
                fenced.contains(&text),
                "docs/farm.md does not quote {} as it is",
                path.display()
            );
            scripts += 1;
        }
    }
    assert_eq!(scripts, 2, "farm/slurm/ has film.sbatch and still.sbatch");
    let marker = "<!-- farm/check.sh runs these lines -->\n```";
    let marked: Vec<&str> = page.split(marker).skip(1).collect();
    assert!(
        marked.len() >= 2,
        "docs/farm.md marks the Slurm and GNU parallel recipes"
    );
    for block in marked {
        let body = block.split_once('\n').unwrap().1.split("```").next().unwrap();
        for line in body.lines().filter(|l| !l.trim().is_empty()) {
            assert!(
                check.lines().any(|c| c.contains(line)),
                "docs/farm.md's recipe line is not one farm/check.sh runs: {line}"
            );
        }
    }
}

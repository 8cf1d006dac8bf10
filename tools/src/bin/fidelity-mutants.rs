//! `fidelity-mutants`: does a test notice every `Fidelity::Listing` arm?
//!
//! For every `match` in the root crate's `src/` (outside `#[cfg(test)]`
//! modules) with an arm whose pattern names `Fidelity::Listing`, one at a
//! time: the match's scrutinee is made `Fidelity::Thesis`, so the listing
//! takes the thesis's arm; the crate is rebuilt and its tests run (`cargo
//! test -p raytrace --lib --tests`). An arm no test notices is a survivor:
//! either a test is missing or the arm is behaviour-neutral, which
//! legacy_pascal/DEVIATIONS.md must then explain.
//!
//! The work happens in a copy of the tree (`--work`, default a folder under
//! the system's temporary directory) with its own target directory, so the
//! tree itself is never changed and can be edited meanwhile.
//!
//! ```text
//! cargo run -p tools --bin fidelity-mutants -- [--list] [--only src/drt.rs:403] [--target-dir DIR] [--skip-baseline]
//! ```
//! Exit status 0 when no arm survives, 1 when some do, 2 on a usage or
//! setup error (the unchanged tree must pass its tests first).

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::{Duration, Instant};

use clap::Parser;

#[derive(Parser)]
#[command(
    name = "fidelity-mutants",
    about = "Swap each Fidelity::Listing arm for the thesis's and see whether a test notices"
)]
struct Cli {
    /// The root of the project (the folder with the workspace Cargo.toml).
    #[arg(long, default_value = ".")]
    root: PathBuf,
    /// Where to copy the tree [default: a new folder in the temporary directory].
    #[arg(long)]
    work: Option<PathBuf>,
    /// The target directory of the copy's builds [default: WORK/target]. Seed it
    /// with a copy of an existing target directory to skip building the dependencies.
    #[arg(long)]
    target_dir: Option<PathBuf>,
    /// Only list the matches with a Fidelity::Listing arm.
    #[arg(long)]
    list: bool,
    /// Only the matches with an arm on these lines (FILE:LINE, FILE relative to the root).
    #[arg(long)]
    only: Vec<String>,
    /// Do not run the tests of the unchanged tree first (when they were just run).
    #[arg(long)]
    skip_baseline: bool,
    /// Give up on a build and test run after this many seconds.
    #[arg(long, default_value_t = 1800)]
    timeout: u64,
}

/// A `match` with one or more `Fidelity::Listing` arms.
struct Site {
    /// Relative to the root, e.g. `src/drt.rs`.
    file: PathBuf,
    /// 1-based lines of its `Fidelity::Listing` arms.
    arms: Vec<usize>,
    /// Byte range of the scrutinee's fidelity expression in the file.
    range: (usize, usize),
    /// That expression, e.g. `self.fidelity`.
    expr: String,
}

/// Which bytes of `src` are code (not inside a comment, string or char literal).
fn code_mask(src: &str) -> Vec<bool> {
    let b = src.as_bytes();
    let mut mask = vec![true; b.len()];
    let mut i = 0;
    while i < b.len() {
        if b[i..].starts_with(b"//") {
            while i < b.len() && b[i] != b'\n' {
                mask[i] = false;
                i += 1;
            }
        } else if b[i..].starts_with(b"/*") {
            let mut depth = 0;
            while i < b.len() {
                if b[i..].starts_with(b"/*") {
                    depth += 1;
                    mask[i] = false;
                    mask[i + 1] = false;
                    i += 2;
                } else if b[i..].starts_with(b"*/") {
                    depth -= 1;
                    mask[i] = false;
                    mask[i + 1] = false;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    mask[i] = false;
                    i += 1;
                }
            }
        } else if b[i] == b'"' {
            mask[i] = false;
            i += 1;
            while i < b.len() && b[i] != b'"' {
                if b[i] == b'\\' {
                    mask[i] = false;
                    i += 1;
                }
                if i < b.len() {
                    mask[i] = false;
                    i += 1;
                }
            }
            if i < b.len() {
                mask[i] = false;
                i += 1;
            }
        } else if b[i] == b'\'' && i + 2 < b.len() && (b[i + 2] == b'\'' || b[i + 1] == b'\\') {
            // A char literal ('{', '\n'); a lifetime ('a) has no closing quote.
            let end = b[i + 1..]
                .iter()
                .position(|&c| c == b'\'')
                .map_or(b.len(), |p| i + 2 + p);
            for m in &mut mask[i..end.min(b.len())] {
                *m = false;
            }
            i = end;
        } else {
            i += 1;
        }
    }
    mask
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// The matches of one file with `Fidelity::Listing` arms, outside the
/// `#[cfg(test)]` module at its end.
fn sites_in(root: &Path, file: &Path) -> Result<Vec<Site>, String> {
    let src = std::fs::read_to_string(root.join(file)).map_err(|e| format!("{}: {e}", file.display()))?;
    let end = src.find("#[cfg(test)]").unwrap_or(src.len());
    let mask = code_mask(&src);
    let b = src.as_bytes();
    let line_of = |pos: usize| src[..pos].matches('\n').count() + 1;
    let mut sites: Vec<Site> = Vec::new();
    let needle = "Fidelity::Listing";
    let mut from = 0;
    while let Some(p) = src[from..end].find(needle).map(|p| p + from) {
        from = p + needle.len();
        // A pattern: code, not `FidelityArg::Listing`, and `=>` follows on its line.
        let line_end = src[p..].find('\n').map_or(src.len(), |e| p + e);
        let rest = &src[from..line_end];
        let is_arm = rest.find("=>").is_some_and(|a| !rest[..a].contains(';'));
        if !mask[p] || (p > 0 && is_ident(b[p - 1])) || !is_arm {
            continue;
        }
        // The enclosing block: back to the `{` that opens it, then its `match`.
        let mut depth = 0usize;
        let mut open = None;
        for q in (0..p).rev() {
            if !mask[q] {
                continue;
            }
            match b[q] {
                b'}' => depth += 1,
                b'{' if depth == 0 => {
                    open = Some(q);
                    break;
                }
                b'{' => depth -= 1,
                _ => {}
            }
        }
        let open = open.ok_or(format!("{}:{}: no enclosing block", file.display(), line_of(p)))?;
        let head = &src[..open];
        let m = head
            .rmatch_indices("match")
            .map(|(i, _)| i)
            .find(|&i| mask[i] && (i == 0 || !is_ident(b[i - 1])) && !is_ident(b[i + 5]))
            .ok_or(format!("{}:{}: no match before the arm", file.display(), line_of(p)))?;
        let scrutinee = &src[m + 5..open];
        // The fidelity in the scrutinee: a path ending in the word `fidelity`.
        let word = scrutinee
            .rmatch_indices("fidelity")
            .map(|(i, _)| m + 5 + i)
            .find(|&i| !is_ident(b[i + 8]))
            .ok_or(format!(
                "{}:{}: the match `match{}` names no fidelity to swap",
                file.display(),
                line_of(p),
                scrutinee.trim_end()
            ))?;
        let mut start = word;
        while start > m + 5 && (is_ident(b[start - 1]) || b[start - 1] == b'.') {
            start -= 1;
        }
        let range = (start, word + 8);
        let line = line_of(p);
        match sites.iter_mut().find(|s| s.range == range) {
            Some(s) => s.arms.push(line),
            None => sites.push(Site {
                file: file.to_path_buf(),
                arms: vec![line],
                range,
                expr: src[range.0..range.1].to_string(),
            }),
        }
    }
    Ok(sites)
}

fn rust_files(root: &Path, dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    let mut entries: Vec<_> = std::fs::read_dir(root.join(dir))?.collect::<Result<_, _>>()?;
    entries.sort_by_key(|e| e.file_name());
    for e in entries {
        let rel = dir.join(e.file_name());
        if e.file_type()?.is_dir() {
            rust_files(root, &rel, out)?;
        } else if rel.extension().is_some_and(|x| x == "rs") {
            out.push(rel);
        }
    }
    Ok(())
}

/// Copy the tree at `from` to `to`, leaving out `target` folders and `.git`.
fn copy_tree(from: &Path, to: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(to)?;
    for e in std::fs::read_dir(from)? {
        let e = e?;
        let name = e.file_name();
        if name == "target" || name == ".git" {
            continue;
        }
        let (src, dst) = (e.path(), to.join(&name));
        if e.file_type()?.is_dir() {
            copy_tree(&src, &dst)?;
        } else if e.file_type()?.is_file() {
            std::fs::copy(&src, &dst)?;
        }
    }
    Ok(())
}

/// What one build and test run came to.
enum Outcome {
    Pass,
    TestsFail,
    BuildFails,
    Timeout,
}

fn run_tests(work: &Path, target: &Path, timeout: Duration) -> Result<Outcome, String> {
    let mut child = Command::new(std::env::var("CARGO").unwrap_or("cargo".into()))
        .args(["test", "-p", "raytrace", "--lib", "--tests", "-q"])
        .current_dir(work)
        .env("CARGO_TARGET_DIR", target)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .map_err(|e| format!("cargo: {e}"))?;
    let started = Instant::now();
    // Drain stderr on a thread so that a chatty build cannot block.
    let mut stderr = child.stderr.take().expect("piped");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = std::io::Read::read_to_string(&mut stderr, &mut s);
        s
    });
    loop {
        if let Some(status) = child.try_wait().map_err(|e| e.to_string())? {
            let log = reader.join().unwrap_or_default();
            return Ok(if status.success() {
                Outcome::Pass
            } else if log.contains("error: test failed") || log.contains("test result: FAILED") {
                Outcome::TestsFail
            } else {
                Outcome::BuildFails
            });
        }
        if started.elapsed() > timeout {
            let _ = child.kill();
            let _ = child.wait();
            return Ok(Outcome::Timeout);
        }
        std::thread::sleep(Duration::from_millis(200));
    }
}

fn main() -> ExitCode {
    match run(&Cli::parse()) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("fidelity-mutants: {e}");
            ExitCode::from(2)
        }
    }
}

/// Ok(true) when no arm survives.
fn run(cli: &Cli) -> Result<bool, String> {
    let root = cli
        .root
        .canonicalize()
        .map_err(|e| format!("{}: {e}", cli.root.display()))?;
    let mut files = Vec::new();
    rust_files(&root, Path::new("src"), &mut files).map_err(|e| format!("{}/src: {e}", root.display()))?;
    let mut sites = Vec::new();
    for f in &files {
        sites.extend(sites_in(&root, f)?);
    }
    let arms: usize = sites.iter().map(|s| s.arms.len()).sum();
    let show = |s: &Site| {
        let lines: Vec<String> = s.arms.iter().map(|l| l.to_string()).collect();
        format!("{}:{} (match on `{}`)", s.file.display(), lines.join(","), s.expr)
    };
    if !cli.only.is_empty() {
        sites.retain(|s| {
            s.arms
                .iter()
                .any(|l| cli.only.contains(&format!("{}:{l}", s.file.display())))
        });
    }
    println!(
        "{arms} Fidelity::Listing arms; swapping the scrutinee of {} matches",
        sites.len()
    );
    if cli.list {
        for s in &sites {
            println!("  {}", show(s));
        }
        return Ok(true);
    }

    let work = match &cli.work {
        Some(w) => w.clone(),
        None => std::env::temp_dir().join(format!("fidelity-mutants-{}", std::process::id())),
    };
    copy_tree(&root, &work).map_err(|e| format!("copying the tree to {}: {e}", work.display()))?;
    let target = cli.target_dir.clone().unwrap_or_else(|| work.join("target"));
    let timeout = Duration::from_secs(cli.timeout);
    let all = Instant::now();

    let t0 = Instant::now();
    if !cli.skip_baseline {
        match run_tests(&work, &target, timeout)? {
            Outcome::Pass => println!("unchanged tree: tests pass ({:.0} s)", t0.elapsed().as_secs_f64()),
            _ => return Err("the unchanged tree does not build or pass its tests".into()),
        }
    }

    let mut survivors = Vec::new();
    for (k, s) in sites.iter().enumerate() {
        let path = work.join(&s.file);
        let original = std::fs::read_to_string(&path).map_err(|e| e.to_string())?;
        let thesis = if s.file.starts_with("src/bin") {
            "raytrace::options::Fidelity::Thesis"
        } else {
            "crate::options::Fidelity::Thesis"
        };
        let mutated = format!("{}{thesis}{}", &original[..s.range.0], &original[s.range.1..]);
        std::fs::write(&path, mutated).map_err(|e| e.to_string())?;
        let t = Instant::now();
        let outcome = run_tests(&work, &target, timeout);
        std::fs::write(&path, &original).map_err(|e| e.to_string())?;
        let verdict = match outcome? {
            Outcome::TestsFail => "caught",
            Outcome::Pass => {
                survivors.push(show(s));
                "SURVIVED"
            }
            Outcome::BuildFails => {
                survivors.push(format!("{} (does not build)", show(s)));
                "does not build"
            }
            Outcome::Timeout => {
                survivors.push(format!("{} (timed out)", show(s)));
                "timed out"
            }
        };
        println!(
            "[{}/{}] {}: {verdict} ({:.0} s)",
            k + 1,
            sites.len(),
            show(s),
            t.elapsed().as_secs_f64()
        );
    }
    println!(
        "{} of {} matches survive; {:.1} min in all",
        survivors.len(),
        sites.len(),
        all.elapsed().as_secs_f64() / 60.0
    );
    for s in &survivors {
        println!("  survivor: {s}");
    }
    Ok(survivors.is_empty())
}

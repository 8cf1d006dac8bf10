//! `tools scale --instructions`: the instructions a sample, ours and
//! POV-Ray's, as valgrind's cachegrind counts them (`I refs`), which do not
//! move with the machine's load as CPU times do. Each count is a 64×64
//! render less a 1×1 render of the same scene, so that start-up, parsing
//! and preparing cancel; the difference is over the (64² − 1)·M² samples
//! between them. Ours runs as `tools bench DECK --runs 1 --threads 1`
//! (this program: a warm-up render and a timed one, so the difference is
//! halved), `--accel auto`; POV-Ray as `tools scale` times it.

use std::path::Path;
use std::process::Command;

use raytrace::options::Fidelity;

use super::scenes::{self, Frame, Kind};
use super::{count, Settings};
use crate::vs_povray::povray_args;

/// The side of the counted render.
pub const SIDE: usize = 64;

/// One scene's instructions a sample.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub kind: Kind,
    pub n: usize,
    pub ours: f64,
    pub pov: Option<f64>,
}

/// Fails with a clear message when valgrind cannot be run.
pub fn check_valgrind() -> Result<(), String> {
    match Command::new("valgrind").arg("--version").output() {
        Ok(o) if o.status.success() => Ok(()),
        _ => Err("--instructions needs valgrind (the Debian package `valgrind`)".into()),
    }
}

/// The scenes counted: spheres from 10 to 10,000 by decades, and 1,000
/// stars and goblets, those within the run's N.
pub fn scenes(set: &Settings) -> Vec<(Kind, usize)> {
    let top = |k: Kind| set.ns(k).iter().copied().max().unwrap_or(0);
    let spheres = [10, 100, 1_000, 10_000].map(|n| (Kind::Sphere, n));
    let sweeps = [(Kind::Star, 1_000), (Kind::Goblet, 1_000)];
    spheres
        .into_iter()
        .chain(sweeps)
        .filter(|&(k, n)| n <= top(k))
        .collect()
}

/// The `I refs` of `program args` under cachegrind.
fn irefs(program: &Path, args: &[String]) -> Result<u64, String> {
    let o = Command::new("valgrind")
        .args(["--tool=cachegrind", "--cache-sim=no", "--cachegrind-out-file=/dev/null"])
        .arg(program)
        .args(args)
        .output()
        .map_err(|e| format!("valgrind: {e}"))?;
    let err = String::from_utf8_lossy(&o.stderr);
    if !o.status.success() {
        return Err(format!(
            "valgrind {} failed: {}",
            program.display(),
            err.lines().last().unwrap_or("")
        ));
    }
    parse_irefs(&err).ok_or_else(|| format!("valgrind {}: no 'I refs' line", program.display()))
}

/// The count of cachegrind's `==PID== I   refs:      1,234,567` line.
pub fn parse_irefs(report: &str) -> Option<u64> {
    let line = report.lines().find(|l| l.contains("I") && l.contains("refs:"))?;
    let digits: String = line
        .split("refs:")
        .nth(1)?
        .chars()
        .filter(char::is_ascii_digit)
        .collect();
    digits.parse().ok()
}

/// Counts every scene of [`scenes()`]; files go to `tmp`.
pub fn measure(set: &Settings, tmp: &Path) -> Result<Vec<Row>, String> {
    let exe = std::env::current_exe().map_err(|e| format!("this program's path: {e}"))?;
    let samples = ((SIDE * SIDE - 1) * set.mask * set.mask) as f64;
    let mut rows = Vec::new();
    for (kind, n) in scenes(set) {
        let frame = Frame {
            size: (SIDE, SIDE),
            mask: set.mask,
            travel: 0.0,
        };
        let text = scenes::deck(kind, n, frame)?;
        let deck = tmp.join("instructions.deck");
        std::fs::write(&deck, &text).map_err(|e| format!("{}: {e}", deck.display()))?;
        let bench = |side: usize| {
            let args = [
                "bench",
                &deck.display().to_string(),
                "--runs",
                "1",
                "--threads",
                "1",
                "--size",
            ];
            let mut args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
            args.push(format!("{side}x{side}"));
            irefs(&exe, &args)
        };
        let ours = (bench(SIDE)? as f64 - bench(1)? as f64) / 2.0 / samples;
        let pov = match set.povray {
            false => None,
            true => {
                let scene = crate::decks::load_source(&text, "instructions", tmp, Fidelity::Thesis)?;
                let sdl = tmp.join("instructions.pov");
                std::fs::write(&sdl, crate::pov::scene_sdl(&scene, Fidelity::Thesis))
                    .map_err(|e| format!("{}: {e}", sdl.display()))?;
                let ppm = tmp.join("instructions.ppm");
                let povray = |side| irefs(Path::new("povray"), &povray_args(&sdl, &ppm, (side, side), set.mask));
                Some((povray(SIDE)? as f64 - povray(1)? as f64) / samples)
            }
        };
        eprintln!(
            "{} {}s: {:.0} instructions a sample{}",
            count(n),
            kind.name(),
            ours,
            pov.map(|p| format!(", POV-Ray {p:.0}")).unwrap_or_default()
        );
        rows.push(Row { kind, n, ours, pov });
    }
    Ok(rows)
}

/// The rows as a Markdown table, and the growth of ours from the fewest
/// spheres to the most; nothing for no rows.
pub fn table(rows: &[Row]) -> String {
    use std::fmt::Write;
    if rows.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "\nInstructions a sample (cachegrind, a {SIDE}² render less a 1×1)\n\n| scene | N | ours | POV-Ray | ours/POV |\n|---|---|---|---|---|\n"
    );
    for r in rows {
        let pov = r.pov.map_or("–".into(), |p| format!("{p:.0}"));
        let ratio = r.pov.map_or("–".into(), |p| format!("{:.2}", r.ours / p));
        let _ = writeln!(
            s,
            "| {} | {} | {:.0} | {pov} | {ratio} |",
            r.kind.name(),
            count(r.n),
            r.ours
        );
    }
    let spheres: Vec<&Row> = rows.iter().filter(|r| r.kind == Kind::Sphere).collect();
    if let (Some(a), Some(b)) = (spheres.first(), spheres.last()) {
        if a.n < b.n {
            let _ = writeln!(
                s,
                "\nOurs from {} to {} spheres: {:.2}× the instructions a sample.",
                count(a.n),
                count(b.n),
                b.ours / a.ours
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn irefs_of_a_cachegrind_report() {
        let report = "==12== Cachegrind, a high-precision tracing profiler\n==12== \n==12== I   refs:      1,234,567\n";
        assert_eq!(parse_irefs(report), Some(1_234_567));
        assert_eq!(parse_irefs("==12== I refs: none"), None);
        assert_eq!(parse_irefs(""), None);
    }

    /// The quick run counts the spheres within its N; the full run the
    /// issue's six scenes.
    #[test]
    fn scenes_within_the_runs_n() {
        assert_eq!(scenes(&Settings::quick()), [(Kind::Sphere, 10), (Kind::Sphere, 100)]);
        assert_eq!(scenes(&Settings::full()).len(), 6);
    }

    #[test]
    fn growth_from_the_fewest_spheres() {
        let row = |n, ours| Row {
            kind: Kind::Sphere,
            n,
            ours,
            pov: None,
        };
        let t = table(&[row(10, 1000.0), row(10_000, 2500.0)]);
        assert!(t.contains("from 10 to 10,000 spheres: 2.50×"), "{t}");
        assert_eq!(table(&[]), "");
    }
}

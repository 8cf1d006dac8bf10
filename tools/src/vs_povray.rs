//! `tools vs-povray DECK…`: our renderer against POV-Ray 3.7 on the same
//! geometry (the scene [`crate::pov`] exports). For each deck: CPU time of
//! both, one thread each, at equal samples (our `mask` M against POV's
//! `+A0.0 +AM1 +RM -J`, M×M rays a pixel), the renders interleaved and the
//! medians taken; then the silhouettes of the sweep objects, blobs and
//! patches at one sample a pixel (those alone, white on black, no light),
//! compared pixel by pixel. `--shapes` compares the scenes of blobs and
//! patches of tools/decks ([`crate::decks::SHAPE_DECKS`]). Not the thesis's: a cross-check of the port. Linux only (ours
//! from the rendering thread's CPU clock, POV-Ray's process from
//! /proc/self/stat's children's times).
//!
//! With `--depth-of-field`, [`depth_of_field`] instead: `cook.deck`'s lens
//! against POV-Ray's focal blur, CPU at equal RMSE against each renderer's
//! own 1024-ray reference (issue 26).
//!
//! POV-Ray is the Debian package `povray`; without it the tool says so and
//! stops. Nothing here is asserted in tests.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use raytrace::options::{Options, Solver, TimeSampler};
use raytrace::scene::Scene;
use raytrace::types::{DVec3, Shape, SurfaceAttribute};

use crate::decks::{deck_path, load};
use crate::measure::timed_still;
use crate::pov::scene_sdl;

/// The settings of one comparison.
#[derive(Clone, Debug)]
pub struct Settings {
    /// Width and height in pixels.
    pub size: (usize, usize),
    /// M: M×M samples a pixel on both sides.
    pub mask: usize,
    /// Timed rounds (each renders ours with each solver, then POV-Ray's).
    pub runs: usize,
}

/// The deepest antialiasing POV-Ray takes (`+R1` to `+R9`).
pub const POVRAY_MAX_MASK: usize = 9;

/// Fails with a clear message when `povray` cannot be run.
pub fn check_povray() -> Result<(), String> {
    match Command::new("povray")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
    {
        Ok(_) => Ok(()),
        Err(e) => Err(format!(
            "povray could not be run ({e}): install POV-Ray 3.7, the Debian package `povray` (apt-get install povray)"
        )),
    }
}

/// CPU seconds used so far: (this process, its waited-for children), from
/// /proc/self/stat (utime + stime, cutime + cstime).
fn cpu_seconds() -> Result<(f64, f64), String> {
    let stat = std::fs::read_to_string("/proc/self/stat").map_err(|e| format!("/proc/self/stat: {e}"))?;
    // The fields after the command name, which is in parentheses.
    let rest = stat.rsplit_once(')').map(|(_, r)| r).unwrap_or("");
    let f: Vec<f64> = rest.split_whitespace().map(|x| x.parse().unwrap_or(0.0)).collect();
    // rest[0] is field 3 (state): utime is field 14, cstime field 17.
    if f.len() < 15 {
        return Err("/proc/self/stat: too few fields".into());
    }
    let tick = clock_ticks();
    Ok(((f[11] + f[12]) / tick, (f[13] + f[14]) / tick))
}

/// Clock ticks a second (`getconf CLK_TCK`, 100 if that fails).
fn clock_ticks() -> f64 {
    Command::new("getconf")
        .arg("CLK_TCK")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or(100.0)
}

/// What one POV-Ray run cost, in CPU seconds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PovRun {
    /// The whole process (from /proc/self/stat's cutime and cstime: clock
    /// ticks, 10 ms on Linux).
    pub process: f64,
    /// What POV-Ray reports for its trace ("Trace Time: … with S
    /// CPU-seconds total"), without its start-up, parse and bounding.
    pub trace: Option<f64>,
    /// What it reports for its parse and its bounding boxes, together.
    pub setup: Option<f64>,
}

/// The CPU seconds of POV-Ray's report line `NAME Time:` (the number
/// before "CPU-seconds" on the line after it), if it is there.
pub fn reported_cpu(report: &str, name: &str) -> Option<f64> {
    let mut lines = report.lines();
    lines.find(|l| l.trim_start().starts_with(&format!("{name} Time:")))?;
    let next = lines.next()?;
    let (before, _) = next.split_once("CPU-seconds")?;
    before.split_whitespace().last()?.parse().ok()
}

/// POV-Ray's arguments to render `pov` on one thread at `size` (W×H),
/// `mask`² samples a pixel (1: no anti-aliasing), into `out` (PPM).
pub fn povray_args(pov: &Path, out: &Path, (width, height): (usize, usize), mask: usize) -> Vec<String> {
    let mut args = vec![format!("+I{}", pov.display()), format!("+O{}", out.display())];
    args.extend(["+FP", "-D", "-V", "+WT1"].map(String::from));
    args.extend([format!("+W{width}"), format!("+H{height}")]);
    if mask > 1 {
        args.extend(["+A0.0", "+AM1", "-J"].map(String::from));
        args.push(format!("+R{mask}"));
    } else {
        args.push("-A".into());
    }
    args
}

/// Renders `pov` with POV-Ray as [`povray_args`] says; returns what it cost.
pub fn povray(pov: &Path, out: &Path, size: (usize, usize), mask: usize) -> Result<PovRun, String> {
    if mask > POVRAY_MAX_MASK {
        return Err(format!(
            "--mask {mask}: POV-Ray's antialiasing depth (+R) goes to {POVRAY_MAX_MASK}, so it cannot take {mask}×{mask} \
             samples a pixel; use a mask of at most {POVRAY_MAX_MASK}"
        ));
    }
    let mut cmd = Command::new("povray");
    cmd.args(povray_args(pov, out, size, mask));
    let before = cpu_seconds()?.1;
    let o = cmd.output().map_err(|e| format!("povray: {e}"))?;
    let report = String::from_utf8_lossy(&o.stderr);
    if !o.status.success() {
        return Err(format!(
            "povray failed on {}: {}",
            pov.display(),
            report.lines().last().unwrap_or("")
        ));
    }
    let parse = reported_cpu(&report, "Parse");
    let bounding = reported_cpu(&report, "Bounding");
    Ok(PovRun {
        process: cpu_seconds()?.1 - before,
        trace: reported_cpu(&report, "Trace"),
        setup: parse.zip(bounding).map(|(p, b)| p + b),
    })
}

/// The pixels of a binary PPM (P6, 8 or 16 bits a channel).
pub fn read_ppm(bytes: &[u8]) -> Result<(usize, usize, Vec<[u8; 3]>), String> {
    let mut fields = Vec::new();
    let mut i = 0;
    while fields.len() < 4 && i < bytes.len() {
        while i < bytes.len() && bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        if i < bytes.len() && bytes[i] == b'#' {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
            continue;
        }
        let start = i;
        while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        fields.push(String::from_utf8_lossy(&bytes[start..i]).to_string());
    }
    i += 1; // the one whitespace after maxval
    if fields.len() < 4 || fields[0] != "P6" {
        return Err("not a binary PPM (P6)".into());
    }
    let num = |s: &str| s.parse::<usize>().map_err(|_| format!("PPM header: {s}"));
    let (w, h, max) = (num(&fields[1])?, num(&fields[2])?, num(&fields[3])?);
    let wide = max > 255;
    let per = if wide { 6 } else { 3 };
    let data = bytes.get(i..).unwrap_or(&[]);
    if data.len() < w * h * per || max == 0 {
        return Err("PPM: short pixel data".into());
    }
    let px = data
        .chunks_exact(per)
        .take(w * h)
        .map(|c| {
            if wide {
                std::array::from_fn(|k| ((u16::from_be_bytes([c[2 * k], c[2 * k + 1]]) as usize * 255) / max) as u8)
            } else {
                [c[0], c[1], c[2]]
            }
        })
        .collect();
    Ok((w, h, px))
}

/// The scene's sweep objects, blobs and patches alone, white (ambient 1)
/// on black, no light: a render of it is their silhouette.
fn silhouette_scene(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    let keep: Vec<usize> = (0..s.objects.len())
        .filter(|&i| matches!(s.objects[i].shape, Shape::Sweep(_) | Shape::Blob(_) | Shape::Patch(_)))
        .collect();
    s.object_pos = keep.iter().map(|&i| s.object_pos[i].clone()).collect();
    s.objects = keep.iter().map(|&i| s.objects[i].clone()).collect();
    s.motions.clear();
    s.keyframes.clear();
    s.lights.clear();
    s.backgrnd = DVec3::ZERO;
    for surf in &mut s.surfaces {
        surf.color = DVec3::ONE;
        surf.iobject = DVec3::ONE;
        (surf.ka, surf.kd, surf.ks, surf.kt) = (1.0, 0.0, 0.0, 0.0);
        surf.surface = SurfaceAttribute::Opaque;
        surf.paint = None;
        surf.texture = None;
    }
    s
}

fn lit(p: &[u8; 3]) -> bool {
    p.iter().map(|&c| c as u32).sum::<u32>() > 3 * 128
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// One deck's comparison, printed as a table row.
fn compare(deck: &str, set: &Settings, pool: &rayon::ThreadPool, dir: &Path) -> Result<(), String> {
    let solvers = [Solver::Laguerre, Solver::Robust];
    let opts = |solver| Options {
        solver,
        ..Options::default()
    };
    let mut base = load(deck, Options::default().fidelity)?;
    base.resize(set.size.0, set.size.1, set.mask);
    let stem = deck_path(deck)
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| "deck".into());
    let pov = dir.join(format!("{stem}.pov"));
    std::fs::write(&pov, scene_sdl(&base, Options::default().fidelity))
        .map_err(|e| format!("{}: {e}", pov.display()))?;
    let ppm = dir.join(format!("{stem}.ppm"));
    let mut scenes = Vec::new();
    for s in solvers {
        scenes.push(crate::decks::prepare(base.clone(), &opts(s))?);
    }
    let mut ours_t = vec![Vec::new(); solvers.len()];
    let mut pov_t = Vec::new();
    for _ in 0..set.runs {
        for k in 0..solvers.len() {
            ours_t[k].push(timed_still(pool, &scenes[k]).0);
        }
        pov_t.push(povray(&pov, &ppm, set.size, set.mask)?.process);
    }
    let pov_m = median(pov_t);
    let ours_m: Vec<f64> = ours_t.into_iter().map(median).collect();

    // Silhouettes at one sample a pixel.
    let mut sil = silhouette_scene(&base);
    sil.resize(set.size.0, set.size.1, 1);
    let sil_pov = dir.join(format!("{stem}_silhouette.pov"));
    std::fs::write(&sil_pov, scene_sdl(&sil, Options::default().fidelity))
        .map_err(|e| format!("{}: {e}", sil_pov.display()))?;
    povray(&sil_pov, &ppm, set.size, 1)?;
    let bytes = std::fs::read(&ppm).map_err(|e| format!("{}: {e}", ppm.display()))?;
    let (w, h, theirs) = read_ppm(&bytes)?;
    if (w, h) != set.size {
        return Err(format!("povray wrote {w}×{h}, not {}×{}", set.size.0, set.size.1));
    }
    let mut agree = Vec::new();
    for s in solvers {
        let (_, mine) = timed_still(pool, &crate::decks::prepare(sil.clone(), &opts(s))?);
        let union = mine.iter().zip(&theirs).filter(|(a, b)| lit(a) || lit(b)).count();
        let differ = mine.iter().zip(&theirs).filter(|(a, b)| lit(a) != lit(b)).count();
        agree.push((differ, union));
    }
    let pct = |(d, u): (usize, usize)| 100.0 * (u - d) as f64 / u.max(1) as f64;
    println!(
        "| {stem} | {:.3} | {:.3} | {:.3} | {:.2} | {:.2} | {} of {} ({:.2} %) | {} of {} ({:.2} %) |",
        ours_m[0],
        ours_m[1],
        pov_m,
        ours_m[0] / pov_m,
        ours_m[1] / pov_m,
        agree[0].0,
        agree[0].1,
        pct(agree[0]),
        agree[1].0,
        agree[1].1,
        pct(agree[1]),
    );
    Ok(())
}

/// Compares every deck (see the module doc) and prints a Markdown table.
pub fn run(decks: &[PathBuf], set: &Settings) -> Result<(), String> {
    check_povray()?;
    let pool = crate::measure::one_thread()?;
    let dir = crate::measure::scratch_dir("vs-povray")?;
    println!(
        "{}×{}, {} samples a pixel, one thread each, CPU seconds (median of {}, interleaved); silhouettes of the sweeps, blobs and patches at 1 sample a pixel: pixels that differ of the pixels either shows.\n",
        set.size.0,
        set.size.1,
        set.mask * set.mask,
        set.runs
    );
    println!("| deck | ours laguerre | ours robust | POV-Ray | laguerre/POV | robust/POV | silhouette, laguerre | silhouette, robust |");
    println!("|---|---|---|---|---|---|---|---|");
    let result = decks
        .iter()
        .try_for_each(|d| compare(&d.display().to_string(), set, &pool, &dir));
    let _ = std::fs::remove_dir_all(&dir);
    result
}

/// The rays a pixel of the depth-of-field reference, on both sides.
const REFERENCE_RAYS: usize = 1024;

/// RMSE of two rasters' pixels, 0..1 a channel.
fn rmse(a: &[[u8; 3]], b: &[[u8; 3]]) -> f64 {
    let n = (a.len().min(b.len()) * 3).max(1);
    let sum: f64 = a
        .iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |k| (p[k] as f64 - q[k] as f64) / 255.0))
        .map(|d| d * d)
        .sum();
    (sum / n as f64).sqrt()
}

/// POV-Ray's CPU seconds at the RMSE `target`, from its (RMSE, CPU)
/// points: log-log interpolation between the two that bracket it (or the
/// nearest two, extrapolated), `None` with fewer than two.
fn cpu_at(points: &[(f64, f64)], target: f64) -> Option<f64> {
    let mut p: Vec<(f64, f64)> = points.iter().copied().filter(|&(e, c)| e > 0.0 && c > 0.0).collect();
    p.sort_by(|a, b| b.0.total_cmp(&a.0));
    if p.len() < 2 {
        return None;
    }
    let i = p.windows(2).position(|w| w[1].0 <= target).unwrap_or(p.len() - 2);
    let ((e0, c0), (e1, c1)) = (p[i], p[i + 1]);
    let t = (target.ln() - e0.ln()) / (e1.ln() - e0.ln());
    Some((c0.ln() + t * (c1.ln() - c0.ln())).exp())
}

/// The depth-of-field scene: `cook.deck` (its `lens` focused on the
/// middle letter) with its sphere of light a point and its gloss 0, so
/// that the lens is the only effect, `size` (W×H) pixels.
fn dof_scene(size: (usize, usize), rays_side: usize) -> Result<Scene, String> {
    let mut s = load("cook", Options::default().fidelity)?;
    s.lights.iter_mut().for_each(|l| l.radius = 0.0);
    s.surfaces.iter_mut().for_each(|f| f.gloss = 0.0);
    s.motions.clear();
    s.keyframes.clear();
    s.resize(size.0, size.1, rays_side);
    Ok(s)
}

/// A render's CPU seconds (all of it; the part like ours, POV-Ray's
/// reported trace) and its pixels.
type DofRender = (f64, Option<f64>, Vec<[u8; 3]>);

/// One side's render of the depth-of-field scene at `rays_side`² rays a
/// pixel: ours with `sampler` (`None`: POV-Ray's focal blur, with
/// `blur_samples` the same count and no antialiasing). Returns the CPU
/// seconds (ours: the render; POV-Ray: its process and its reported
/// trace) and the pixels.
fn dof_render(
    sampler: Option<TimeSampler>,
    size: (usize, usize),
    rays_side: usize,
    pool: &rayon::ThreadPool,
    dir: &Path,
) -> Result<DofRender, String> {
    let scene = dof_scene(size, rays_side)?;
    let Some(sampler) = sampler else {
        let pov = dir.join(format!("dof_{rays_side}.pov"));
        let ppm = dir.join(format!("dof_{rays_side}.ppm"));
        std::fs::write(&pov, scene_sdl(&scene, Options::default().fidelity))
            .map_err(|e| format!("{}: {e}", pov.display()))?;
        let run = povray(&pov, &ppm, size, 1)?;
        let bytes = std::fs::read(&ppm).map_err(|e| format!("{}: {e}", ppm.display()))?;
        return Ok((run.process, run.trace, read_ppm(&bytes)?.2));
    };
    let opts = Options {
        sampler,
        ..Options::default()
    };
    let (cpu, px) = timed_still(pool, &crate::decks::prepare(scene, &opts)?);
    Ok((cpu, Some(cpu), px))
}

/// The sides M of the measured counts M² (4, 16, 64 rays a pixel).
const DOF_SIDES: [usize; 3] = [2, 4, 8];

/// One count's figures: our RMSE and CPU for each sampler, POV-Ray's RMSE
/// and CPU (process, reported trace).
struct DofRow {
    ours: Vec<(f64, f64)>,
    pov_rmse: f64,
    pov_process: f64,
    pov_trace: Option<f64>,
}

/// The depth-of-field comparison (issue 26): for each renderer its own
/// reference of 1024 rays a pixel (ours: `--sampler stratified`, its
/// 32×32 cells of the lens, one reference for every sampler measured, so
/// that a sampler's own pattern is not taken for the image), then 4, 16
/// and 64 rays a pixel timed (`runs` rounds, every sampler and POV-Ray
/// interleaved, medians) and their RMSE against that reference;
/// POV-Ray's CPU at our RMSE by log-log interpolation of its points, and
/// the ratio, against its reported trace time (like against like: ours
/// is the render alone) and against its process. Printed as Markdown.
pub fn depth_of_field(set: &Settings, samplers: &[TimeSampler]) -> Result<(), String> {
    check_povray()?;
    let pool = crate::measure::one_thread()?;
    let dir = crate::measure::scratch_dir("vs-povray-dof")?;
    let result = (|| {
        let side = (REFERENCE_RAYS as f64).sqrt() as usize;
        let (.., ref_ours) = dof_render(Some(TimeSampler::Stratified), set.size, side, &pool, &dir)?;
        let (.., ref_pov) = dof_render(None, set.size, side, &pool, &dir)?;
        println!(
            "cook.deck, lens only, {}×{}, one thread each; RMSE (0..1) against each renderer's own {REFERENCE_RAYS}-ray render (ours: stratified); CPU seconds, median of {} interleaved rounds: ours the render (its thread's CPU clock), POV-Ray its process (/proc, 10 ms ticks) and its reported trace.\n",
            set.size.0, set.size.1, set.runs
        );
        let mut rows = Vec::new();
        for m in DOF_SIDES {
            let mut t_ours = vec![Vec::new(); samplers.len()];
            let mut e_ours = vec![0.0; samplers.len()];
            let (mut t_pov, mut t_trace, mut e_pov) = (Vec::new(), Vec::new(), 0.0);
            for _ in 0..set.runs {
                for (k, &sampler) in samplers.iter().enumerate() {
                    let (c, _, px) = dof_render(Some(sampler), set.size, m, &pool, &dir)?;
                    t_ours[k].push(c);
                    e_ours[k] = rmse(&px, &ref_ours);
                }
                let (c, trace, px) = dof_render(None, set.size, m, &pool, &dir)?;
                t_pov.push(c);
                t_trace.extend(trace);
                e_pov = rmse(&px, &ref_pov);
            }
            rows.push(DofRow {
                ours: e_ours.into_iter().zip(t_ours.into_iter().map(median)).collect(),
                pov_rmse: e_pov,
                pov_process: median(t_pov),
                pov_trace: (!t_trace.is_empty()).then(|| median(t_trace)),
            });
        }
        print_dof(samplers, &rows);
        Ok(())
    })();
    let _ = std::fs::remove_dir_all(&dir);
    result
}

/// The depth-of-field tables: POV-Ray's points, then ours against them.
fn print_dof(samplers: &[TimeSampler], rows: &[DofRow]) {
    let secs = |c: Option<f64>| c.map_or("–".to_string(), |c| format!("{c:.3}"));
    println!("| rays | POV-Ray RMSE | POV-Ray CPU s, process | POV-Ray CPU s, trace |");
    println!("|---|---|---|---|");
    for (m, r) in DOF_SIDES.iter().zip(rows) {
        println!(
            "| {} | {:.4} | {:.3} | {} |",
            m * m,
            r.pov_rmse,
            r.pov_process,
            secs(r.pov_trace)
        );
    }
    let process: Vec<(f64, f64)> = rows.iter().map(|r| (r.pov_rmse, r.pov_process)).collect();
    let trace: Vec<(f64, f64)> = rows.iter().filter_map(|r| Some((r.pov_rmse, r.pov_trace?))).collect();
    println!("\n| sampler | rays | ours RMSE | ours CPU s | POV-Ray trace at that RMSE | ours/POV (trace) | POV-Ray process at that RMSE | ours/POV (process) |");
    println!("|---|---|---|---|---|---|---|---|");
    for (k, sampler) in samplers.iter().enumerate() {
        let name = format!("{sampler:?}").to_lowercase();
        for (m, r) in DOF_SIDES.iter().zip(rows) {
            let (e, c) = r.ours[k];
            let at = |points: &[(f64, f64)]| cpu_at(points, e);
            let ratio = |p: Option<f64>| p.map_or("–".to_string(), |p| format!("{:.2}", c / p));
            println!(
                "| {name} | {} | {e:.4} | {c:.3} | {} | {} | {} | {} |",
                m * m,
                secs(at(&trace)),
                ratio(at(&trace)),
                secs(at(&process)),
                ratio(at(&process)),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ppm_eight_and_sixteen_bits() {
        let mut b = b"P6\n# c\n2 1\n255\n".to_vec();
        b.extend_from_slice(&[1, 2, 3, 250, 251, 252]);
        assert_eq!(read_ppm(&b).unwrap(), (2, 1, vec![[1, 2, 3], [250, 251, 252]]));
        let mut w = b"P6 1 1 65535\n".to_vec();
        w.extend_from_slice(&[0xff, 0xff, 0x80, 0x00, 0, 0]);
        assert_eq!(read_ppm(&w).unwrap(), (1, 1, vec![[255, 127, 0]]));
        assert!(read_ppm(b"P3 1 1 255\n1 2 3").is_err());
        assert!(read_ppm(b"P6 2 2 255\n\x01\x02").is_err());
    }

    /// The CPU seconds of POV-Ray's report, as POV-Ray 3.7 prints them.
    #[test]
    fn reported_cpu_seconds() {
        let report = "  Parse Time:       0 hours  0 minutes  0 seconds (0.001 seconds)
              using 1 thread(s) with 0.002 CPU-seconds total
  Bounding Time:    0 hours  0 minutes  0 seconds (0.000 seconds)
              using 1 thread(s) with 0.000 CPU-seconds total
  Trace Time:       0 hours  0 minutes  1 seconds (1.042 seconds)
              using 1 thread(s) with 1.031 CPU-seconds total
";
        assert_eq!(reported_cpu(report, "Parse"), Some(0.002));
        assert_eq!(reported_cpu(report, "Trace"), Some(1.031));
        assert_eq!(reported_cpu(report, "Photon"), None);
        assert_eq!(reported_cpu("  Trace Time:  no CPU line", "Trace"), None);
    }

    #[test]
    fn rmse_and_cpu_at_equal_rmse() {
        assert_eq!(rmse(&[[0, 0, 0]], &[[255, 255, 255]]), 1.0);
        assert!((rmse(&[[0, 0, 0], [0, 0, 0]], &[[255, 0, 0], [0, 0, 0]]) - (1.0f64 / 6.0).sqrt()).abs() < 1e-12);
        // CPU ∝ RMSE⁻²: at RMSE 0.02 between (0.04, 1) and (0.01, 16), 4.
        let pts = [(0.04, 1.0), (0.01, 16.0), (0.08, 0.25)];
        assert!((cpu_at(&pts, 0.02).unwrap() - 4.0).abs() < 1e-9);
        // Beyond the points: extrapolated on the nearest two.
        assert!((cpu_at(&pts, 0.005).unwrap() - 64.0).abs() < 1e-9);
        assert!(cpu_at(&pts[..1], 0.02).is_none());
    }
}

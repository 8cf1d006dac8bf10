//! The report: the tables of every family and what they show, written to
//! docs/STABILITY.md.

use std::fmt::Write;
use std::path::Path;

use super::{
    blob_families, inbetween_blobs, keyframe_families, keyframe_shapes, patch_families, poly_families, ray_families,
    tally_poly, tally_rays, tally_soft, Method, SoftFamily, Sweeps, Tally, HIT_TOL, METHODS, ROOT_TOL, ROUGH_TOL,
};

type Summary = [(String, Vec<(Method, Tally)>)];

/// A method's tally on the family whose name starts with `prefix`.
fn find<'a>(rows: &'a Summary, prefix: &str, m: Method) -> &'a Tally {
    rows.iter()
        .find(|(n, _)| n.starts_with(prefix))
        .and_then(|(_, t)| t.iter().find(|(k, _)| *k == m))
        .map(|(_, t)| t)
        .unwrap_or_else(|| panic!("the family {prefix} is measured"))
}

/// Sums over the families whose names start with `prefix`.
fn total(rows: &Summary, prefix: &str, m: Method) -> Tally {
    let mut sum = Tally::default();
    for (_, ts) in rows.iter().filter(|(n, _)| n.starts_with(prefix)) {
        for (k, t) in ts {
            if *k == m {
                sum.cases += t.cases;
                sum.truths += t.truths;
                sum.missed += t.missed;
                sum.rough += t.rough;
                sum.spurious += t.spurious;
                sum.worst = sum.worst.max(t.worst);
                sum.worst_bound_missed = sum.worst_bound_missed.max(t.worst_bound_missed);
            }
        }
    }
    sum
}

fn pct(a: usize, b: usize) -> f64 {
    100.0 * a as f64 / b.max(1) as f64
}

/// What the tables show, in numbers taken from them.
fn summary(poly: &Summary, rays: &Summary) -> String {
    use Method::*;
    let mut s = String::from("\n## What the tables show\n\n");
    let same = poly
        .iter()
        .chain(rays)
        .all(|(_, t)| (t[0].1.missed, t[0].1.spurious) == (t[1].1.missed, t[1].1.spurious));
    let sep3 = find(poly, "separated roots, cubic", LaguerreThesis);
    let sep6 = find(poly, "separated roots, sextic", LaguerreThesis);
    let dbl3 = find(poly, "double roots, cubic", LaguerreThesis);
    let nd = total(poly, "near-double", LaguerreThesis);
    let cl = total(poly, "clustered", LaguerreThesis);
    let _ = writeln!(
        s,
        "- `laguerre`{}: even with its roots at least 0.1 apart it misses {:.0} % of the cubics' roots \
         and {:.0} % of the sextics' (those below its first start 0.98/n and those its four steps \
         do not settle on); it finds no double root of a cubic to {ROOT_TOL:.0e} ({} of {} only \
         roughly, within {ROUGH_TOL:.0e}: convergence there is linear); it misses {:.0} % of \
         near-double roots and {:.0} % of clustered ones (its 0.001 de-duplication merges them). \
         It never returned a spurious root.",
        if same {
            " (listing and thesis fidelity alike: erratum 7 moves no count here)"
        } else {
            ""
        },
        pct(sep3.missed, sep3.truths),
        pct(sep6.missed, sep6.truths),
        dbl3.rough,
        dbl3.truths,
        pct(nd.missed, nd.truths),
        pct(cl.missed, cl.truths),
    );
    let rob = total(poly, "", Robust);
    let rob_fams: Vec<&str> = poly
        .iter()
        .filter(|(_, t)| t[2].1.missed > 0)
        .map(|(n, _)| n.as_str())
        .collect();
    let _ = writeln!(
        s,
        "- The robust solver finds {} of {} roots to {ROOT_TOL:.0e}, none spurious.{}",
        rob.truths - rob.missed,
        rob.truths,
        if rob_fams.is_empty() {
            String::new()
        } else {
            format!(
                " The {} it misses are in the families {}: it reports two close roots as one double \
                 root between them, at most {:.0e} from each. Rounding the coefficients alone moves \
                 those roots by up to {:.0e} (ε·Σ|aₖ|wᵏ/|p′(w)|, the largest over the missed roots of \
                 each family in turn: {}), so where that exceeds {ROOT_TOL:.0e} no f64 solver can \
                 promise them; where it does not, the solver's test for a double root (about √ε of the \
                 polynomial's scale) is what merges the pair. An error of that size in a contour \
                 parameter is far below a pixel at the decks' scales.",
                rob.missed,
                rob_fams
                    .iter()
                    .map(|n| format!("\"{n}\""))
                    .collect::<Vec<_>>()
                    .join(" and "),
                poly.iter().map(|(_, t)| t[2].1.worst_rough).fold(0.0, f64::max),
                rob.worst_bound_missed,
                poly.iter()
                    .filter(|(_, t)| t[2].1.missed > 0)
                    .map(|(_, t)| format!("{:.0e}", t[2].1.worst_bound_missed))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        }
    );
    let graze = find(rays, "grazing", LaguerreThesis);
    let graze_r = find(rays, "grazing", Robust);
    let perp = total(rays, "rays perpendicular to the rotation axis, tilt 1", LaguerreThesis);
    let along = total(rays, "rays along the rotation axis, tilt 1e-9", LaguerreThesis);
    let spur: usize = METHODS.iter().map(|&m| total(rays, "", m).spurious).sum();
    let rob_rays = total(rays, "", Robust);
    let mut easy = Tally::default();
    for prefix in [
        "rays through segment joints",
        "rays parallel",
        "rays perpendicular to the rotation axis, tilt 0",
        "rays along the rotation axis, tilt 0",
        "rays along the rotation axis, tilt 1e-13",
        "rays through a conic apex",
    ] {
        let t = total(rays, prefix, LaguerreThesis);
        easy.truths += t.truths;
        easy.missed += t.missed;
    }
    let _ = writeln!(
        s,
        "- In the sweep driver every root is polished and checked on the surface: {spur} spurious hits \
         over all families and methods. With `laguerre` the driver loses {} of {} grazing rays (the \
         robust solver {}), {} of {} rays tilted 1e-9 to 1e-3 from perpendicular to a rotation axis \
         (front and back of a ring at nearly one height: a near-double root), and {} of {} rays 1e-9 \
         off a rotation axis. Rays parallel to a translation sweep's axis (tilted up to 1e-6), exactly \
         along or across a rotation axis (or within 1e-13 of it, where the driver takes the same \
         special path), through joints and through a conic apex: `laguerre` misses {} of their {} \
         true hits. The robust solver misses {} of {} true hits in all.",
        graze.missed,
        graze.truths,
        graze_r.missed,
        perp.missed,
        perp.truths,
        along.missed,
        along.truths,
        easy.missed,
        easy.truths,
        rob_rays.missed,
        rob_rays.truths,
    );
    let c3l = find(poly, "separated roots, cubic", LaguerreThesis).ns;
    let c3r = find(poly, "separated roots, cubic", Robust).ns;
    let c6l = find(poly, "separated roots, sextic", LaguerreThesis).ns;
    let c6r = find(poly, "separated roots, sextic", Robust).ns;
    let ratios: Vec<f64> = rays.iter().map(|(_, t)| t[2].1.ns / t[1].1.ns).collect();
    let (lo, hi) = ratios
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), r| (lo.min(*r), hi.max(*r)));
    let _ = writeln!(
        s,
        "- Cost: on separated roots `laguerre` takes {c3l:.0} ns a cubic and {c6l:.0} ns a sextic, the \
         robust solver {c3r:.0} and {c6r:.0} ns ({:.1}× and {:.1}×). In the driver, where a ray \
         solves one polynomial a segment its box lets through and polishes what it finds, the robust \
         solver takes {lo:.1} to {hi:.1} times as long as `laguerre` (thesis) per family here (the \
         last column of the second table; the chart in docs/speed_accuracy.md has the cost a ray in \
         whole renders).",
        c3r / c3l,
        c6r / c6l
    );
    s
}

/// The report's table rows of one family.
fn rows(out: &mut String, family: &str, tallies: &[(Method, Tally)]) {
    let labelled: Vec<(&str, &Tally)> = tallies.iter().map(|(m, t)| (m.label(), t)).collect();
    labelled_rows(out, family, &labelled);
}

/// The rows of one family, each method by its label; the family's misses
/// and spurious roots a method on stderr, as the report is made.
fn labelled_rows(out: &mut String, family: &str, tallies: &[(&str, &Tally)]) {
    eprintln!(
        "{family}: {:?}",
        tallies.iter().map(|(_, t)| (t.missed, t.spurious)).collect::<Vec<_>>()
    );
    for (k, (label, t)) in tallies.iter().enumerate() {
        let worst = if t.truths > t.missed {
            format!("{:.1e}", t.worst)
        } else {
            "—".into()
        };
        let missed = if t.rough > 0 {
            format!("{} ({} rough)", t.missed, t.rough)
        } else {
            t.missed.to_string()
        };
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {:.0} |",
            if k == 0 { family } else { "" },
            label,
            t.cases,
            t.truths,
            missed,
            t.spurious,
            worst,
            t.ns
        );
    }
}

/// Measures every family and writes the report to `out`.
pub fn run(out: &Path) -> Result<(), String> {
    let per_poly = 1000;
    let per_ray = 1200;
    let mut report = String::new();
    report.push_str(HEADER);
    let _ = writeln!(
        report,
        "\n## Constructed polynomials\n\n{per_poly} polynomials a family (fixed seeds), solved on [0, 1]; a root \
         counts as found within {ROOT_TOL:.0e} of a true root (each true root matched once, the nearest \
         first; a root the robust solver reports as double may match two). A found root that matches \
         none but lies within {ROUGH_TOL:.0e} of a true root is \"rough\" (its true root is counted \
         missed); farther from every true root it is spurious. Worst error: the largest \
         |found − true| of the matched roots. Time: one solve, median of 7 timing runs, release build.\n"
    );
    report.push_str(TABLE_HEAD);
    let mut poly_summary = Vec::new();
    for fam in poly_families(per_poly) {
        let tallies: Vec<(Method, Tally)> = METHODS.iter().map(|&m| (m, tally_poly(m, &fam))).collect();
        rows(&mut report, &fam.name, &tallies);
        poly_summary.push((fam.name.clone(), tallies));
    }
    let sweeps = Sweeps::new();
    let _ = writeln!(
        report,
        "\n## Constructed rays against constructed sweeps\n\n{per_ray} rays a kind of ray (fixed seeds; where \
         each tilt is a family of its own, shared evenly among the tilts), each intersected by `shapes::sweep::Sweep::intersect` with the method's solver. A hit is the true one \
         within {HIT_TOL:.0e} of the object's size (its largest box coordinate); \"missed\" counts no hit \
         or a farther one (a hole, or the surface behind), \"spurious\" a hit where there is none or a \
         nearer one. Worst error: the largest |t − t_true| of the hits found, relative to the size. \
         Time: one call of `Sweep::intersect` (every segment's polynomial, the polish and the checks).\n"
    );
    report.push_str(TABLE_HEAD);
    let mut truths = String::new();
    let mut ray_summary = Vec::new();
    for fam in ray_families(&sweeps, per_ray) {
        let tallies: Vec<(Method, Tally)> = METHODS.iter().map(|&m| (m, tally_rays(m, &fam))).collect();
        rows(&mut report, &fam.name, &tallies);
        // One line a kind of ray (the tilts of one kind share it).
        let kind = fam.name.split(", tilt").next().unwrap_or(&fam.name);
        if !truths.contains(&format!("- {kind}:")) {
            let _ = writeln!(truths, "- {kind}: {}.", fam.truth);
        }
        ray_summary.push((fam.name.clone(), tallies));
    }
    let _ = write!(report, "\nWhere each true hit comes from:\n\n{truths}");
    report.push_str(&summary(&poly_summary, &ray_summary));
    let shapes = keyframe_shapes()?;
    let _ = writeln!(
        report,
        "\n## Key-frame inputs\n\nRays against the in-between sweeps of key-frame deformation (§3.1–3.3): \
         for each key-frame deck, its in-between contour at 8 instants of the shutter ((j + ½)/8) as the \
         renderer builds it (`goahead`, then the Hermite in-between per instant), and {per_ray} random rays \
         from a sphere of radius 8 about the shape's box, aimed into the box. No analytic truth exists for \
         an in-between contour: the true hit is the robust solver's, so its row is the reference and \
         counts nothing; the `laguerre` rows count where it differs (tolerance as above).\n"
    );
    report.push_str(TABLE_HEAD);
    for fam in keyframe_families(&shapes, per_ray) {
        let tallies: Vec<(Method, Tally)> = METHODS.iter().map(|&m| (m, tally_rays(m, &fam))).collect();
        rows(&mut report, &fam.name, &tallies);
    }
    report.push_str(&soft_section(per_ray)?);
    report.push_str(&star_section()?);
    report.push_str(ROOTTESTING);
    std::fs::write(out, &report).map_err(|e| format!("{}: {e}", out.display()))?;
    println!("{report}");
    println!("wrote {}", out.display());
    Ok(())
}

/// The label of the patches' one method.
const PATCH_METHOD: &str = "pieces: Newton where certified, else clipping";

/// The blobs' and patches' families (§6.2, the port's extension): their
/// tables, where each true hit comes from, and what they show.
fn soft_section(per: usize) -> Result<String, String> {
    let mut s = format!(
        "\n## Blobs and patches (§6.2, the port's extension)\n\n{per} rays a family (fixed seeds) against \
         constructed blobs and patches, counted as the sweeps' rays above (a hit within {HIT_TOL:.0e} of the \
         shape's size). A blob's hit is the first root of the quartic of a chord interval by the method's \
         solver (`shapes::blob`); a patch's is found by its one method, the same for every solver: Newton's \
         method on each flat piece where a contraction bound makes the root the piece's only one, Bezier \
         clipping elsewhere (`shapes::patch`).\n\n"
    );
    s.push_str(TABLE_HEAD);
    let mut fams: Vec<SoftFamily> = blob_families(per);
    fams.push(inbetween_blobs(per)?);
    fams.extend(patch_families(per));
    let mut truths = String::new();
    let mut blobs: Vec<(String, Vec<(Method, Tally)>)> = Vec::new();
    let mut patches: Vec<(String, Tally)> = Vec::new();
    for fam in &fams {
        if fam.patches {
            let t = tally_soft(&Method::Robust.options(), fam);
            labelled_rows(&mut s, &fam.name, &[(PATCH_METHOD, &t)]);
            patches.push((fam.name.clone(), t));
        } else {
            let tallies: Vec<(Method, Tally)> = METHODS.iter().map(|&m| (m, tally_soft(&m.options(), fam))).collect();
            rows(&mut s, &fam.name, &tallies);
            blobs.push((fam.name.clone(), tallies));
        }
        let _ = writeln!(truths, "- {}: {}.", fam.name, fam.truth);
    }
    let _ = write!(s, "\nWhere each true hit comes from:\n\n{truths}");
    let lag = total(&blobs, "", Method::LaguerreThesis);
    let rob = total(&blobs, "", Method::Robust);
    let graze = find(&blobs, "one component, grazing", Method::LaguerreThesis);
    let graze_r = find(&blobs, "one component, grazing", Method::Robust);
    let touch = find(&blobs, "two components", Method::LaguerreThesis);
    let p_truths: usize = patches.iter().map(|(_, t)| t.truths).sum();
    let p_missed: usize = patches.iter().map(|(_, t)| t.missed).sum();
    let p_spur: usize = patches.iter().map(|(_, t)| t.spurious).sum();
    let p_graze = &patches
        .iter()
        .find(|(n, _)| n.contains("grazing"))
        .ok_or("no grazing patch family")?
        .1;
    let _ = writeln!(
        s,
        "\nWhat they show: a blob's roots are the quartics' roots of the solver the deck chose, so its \
         failures are the solver's. With `laguerre` (thesis fidelity) the blobs lose {} of {} true hits over \
         the families (its grazing rays {} of {}, the robust solver {}; its rays by two components that \
         touch, whose chords share an end, {} of {}); the robust solver loses {} of {}; spurious hits: {} and \
         {} (every root is polished and its residual checked). The patches' one method loses {} of {} true \
         hits, its grazing rays (a double root, where Newton's step is not certified and the clips shrink \
         slowly) {} of {}; spurious hits: {}.",
        lag.missed,
        lag.truths,
        graze.missed,
        graze.truths,
        graze_r.missed,
        touch.missed,
        touch.truths,
        rob.missed,
        rob.truths,
        lag.spurious,
        rob.spurious,
        p_missed,
        p_truths,
        p_graze.missed,
        p_graze.truths,
        p_spur,
    );
    Ok(s)
}

/// `laguerre`'s missed roots in a whole picture: fig5_6's star at 256².
fn star_section() -> Result<String, String> {
    let size = 256;
    let m = crate::deck_misses::deck_misses("fig5_6", size)?;
    Ok(format!(
        "\n## A deck: fig5_6's star\n\nOne ray a pixel centre of fig5_6 at {size}², against its translation \
         sweep (the eight-pointed star), with each solver (`tools::deck_misses`). Of the {} pixels whose ray \
         the robust solver finds on the star, `laguerre` misses {} ({:.1} %): no hit, or the far side of a \
         lobe where the ray grazes the near side (the grazing ray's double root, which its four steps from \
         fixed starts do not find). That is the thesis's method (§2.5) and the port keeps it as the default; \
         `--solver robust` is right there. `laguerre` found a nearer hit than the robust solver's on {} pixels.\n",
        m.object_pixels,
        m.missed,
        100.0 * m.missed as f64 / m.object_pixels.max(1) as f64,
        m.nearer
    ))
}

const TABLE_HEAD: &str =
    "| family | method | cases | true roots (hits) | missed | spurious | worst error | ns a solve |\n\
                          |---|---|---|---|---|---|---|---|\n";

const HEADER: &str = "# Stability of the root solvers\n\n\
Written by `cargo run -p tools --release -- stability` (tools/src/stability/); every case comes from a \
fixed seed, so the counts are the same on every run; the times are not (medians on a shared 2-core \
machine). Three methods: `laguerre` as printed (§2.5, 4 steps from the fixed starts 0.98/n, …) in \
listing and thesis fidelity (erratum 7 parts them: the derivative stored and the zero-denominator \
guards), and the robust solver (`robust::real_roots`, `--solver robust`). \
docs/laguerre_misses.md has laguerre's miss rates on random polynomials and random rays; this report \
takes the hard cases one family at a time. Where the reconstructions fail (what `--denoise` blurs \
that it should not, the thin things `--coherence N` misses, with pictures) is in \
docs/reconstruction.md, \"Where they fail\".\n";

const ROOTTESTING: &str = "\n`roottesting`'s odd root counts are not measured in this report: the sweep driver \
decides the caps by `point_in_contour`, not by the parity of the side roots, so it never calls \
`roottesting` and no odd count reaches it (DEVIATIONS D10; `proc::sweep::roottesting` is ported and \
tested on its own).\n";

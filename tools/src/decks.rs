//! The decks the measurements use, and how they are read and resized.
//!
//! Every list below is a plain slice of deck names: a deck joins a
//! measurement with one line (the key-frame decks of Figs. 5.10–5.12 were
//! added so, when the `paper` unit landed).

use std::path::{Path, PathBuf};

use raytrace::options::{Fidelity, Options};
use raytrace::raytrace::{render, Prepared, Render, Request};
use raytrace::scene::Scene;

/// The decks of Chapter 5, rendered as they are by the benches.
pub const CHAPTER5: &[&str] = &[
    "fig5_1", "fig5_2", "fig5_3", "fig5_4", "fig5_5", "fig5_6", "fig5_7", "fig5_8", "fig5_9", "fig5_10", "fig5_11",
    "fig5_12",
];

/// The motion-blurred decks of the chart's time-sampler panels: a moving
/// textured cube, moving translation sweeps, a deforming translation sweep
/// and a deforming rotation sweep.
pub const BLUR_DECKS: &[&str] = &["fig5_3", "fig5_9", "fig5_10", "fig5_12"];

/// The motion scenes of `tools frontier` (the reconstructions' goals):
/// the moving textured cube and the deforming letter of Chapter 5, and
/// two made here ([`generated`]): many moving spheres, and the small ball
/// of Fig. 5.1 on its path over the checker floor, blurred.
pub const FRONTIER_DECKS: &[&str] = &["fig5_3", "fig5_10", "spheres", "ball"];

/// The decks made here rather than shipped, by name: `spheres`, the
/// scene of `tools scale` of 1000 spheres each moving two radii across
/// (as the peers were measured on, issue 34); `ball`, fig5_1.deck with
/// `blur 1` in place of `blur 0` (jittered times: a streak, not four
/// copies).
pub fn generated(name: &str) -> Option<Result<String, String>> {
    match name {
        "spheres" => Some(crate::scale::scenes::deck(
            crate::scale::scenes::Kind::Sphere,
            1000,
            crate::scale::scenes::Frame {
                size: (128, 128),
                mask: 1,
                travel: 2.0,
            },
        )),
        "ball" => Some(
            std::fs::read_to_string(deck_path("fig5_1"))
                .map(|text| text.replace("\nblur 0", "\nblur 1"))
                .map_err(|e| format!("fig5_1: {e}")),
        ),
        _ => None,
    }
}

/// The sweep decks of the chart's second panel (root solvers): one of each
/// kind of sweep (translation, conic, rotation) and the deliberately hard
/// view of a rotation sweep seen edge-on.
pub const SOLVER_DECKS: &[&str] = &["fig5_6", "fig5_7", "fig5_8", "stress_edge_on"];

/// The three sweep kinds for the rays-per-second bench: translation,
/// conic, rotation.
pub const SWEEP_KINDS: &[&str] = &["fig5_6", "fig5_7", "fig5_8"];

/// The scenes of blobs and patches (the port's extension, §6.2) that
/// `tools vs-povray --shapes` compares, in tools/decks: a blob of 24
/// components and one that carves, a vase and a floor of 20 patches, and
/// the speed goal's one blob of 60 components with those 20 patches.
pub const SHAPE_DECKS: &[&str] = &["blob", "patches", "blob_patches"];

/// The path of a deck of tools/decks by name.
pub fn tools_deck(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("decks")
        .join(format!("{name}.deck"))
}

/// The folder of the shipped decks, legacy_pascal/decks.
pub fn deck_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../legacy_pascal/decks")
}

/// The path of a shipped deck by name (`fig5_3`), or the path itself when
/// `name` names a file.
pub fn deck_path(name: &str) -> PathBuf {
    let p = Path::new(name);
    if p.extension().is_some() || p.components().count() > 1 {
        p.to_path_buf()
    } else {
        deck_dir().join(format!("{name}.deck"))
    }
}

/// Reads a deck (a shipped deck's name, a [`generated`] one's, or a
/// path) for a fidelity.
pub fn load(name: &str, fidelity: Fidelity) -> Result<Scene, String> {
    if let Some(text) = generated(name) {
        return load_source(&text?, name, &deck_dir(), fidelity);
    }
    let path = deck_path(name);
    let source = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    load_source(
        &source,
        &path.display().to_string(),
        path.parent().unwrap_or(Path::new(".")),
        fidelity,
    )
}

/// Reads deck text: `file_name` names it in errors, `dir` is where its
/// `texture` files are looked for.
pub fn load_source(source: &str, file_name: &str, dir: &Path, fidelity: Fidelity) -> Result<Scene, String> {
    raytrace::deck::initialize(source, file_name, dir, fidelity).map_err(|e| e.to_string())
}

/// A scene ready to render with `opts`: read, resized to `width`×`height`
/// with `mask`×`mask` subpixels when `size` is given, and prepared.
pub fn prepared(name: &str, opts: &Options, size: Option<(usize, usize, usize)>) -> Result<Prepared, String> {
    let mut scene = load(name, opts.fidelity)?;
    if let Some((w, h, m)) = size {
        scene.resize(w, h, m);
    }
    prepare(scene, opts)
}

/// `scene` prepared with `opts`.
pub fn prepare(scene: Scene, opts: &Options) -> Result<Prepared, String> {
    Prepared::new(scene, *opts).map_err(|e| e.to_string())
}

/// The whole still of a prepared scene (a whole image always renders:
/// only a window can be refused).
pub fn still(prepared: &Prepared) -> Render {
    render(prepared, &Request::STILL).unwrap_or_else(|e| panic!("a whole image: {e}"))
}

/// The deck of the segment-count bench: a translation sweep whose contour
/// is a closed uniform B-spline of `n` control points on a circle of
/// radius 1.2 (so `n` segments), extruded 1.2 up z, on a checker floor,
/// seen as fig5_6 is. `n` must be 3..=60 (`MAXSEGMENTS`).
pub fn circle_sweep_deck(n: usize, width: usize, height: usize, mask: usize) -> String {
    let mut s = format!(
        "{{ A translation sweep of a B-spline circle of {n} points. }}\n\
         view eye 0 -7 4 look 0 0 0.6 screen 2.9 distance 5\n\
         image {width} {height} mask {mask}\n\
         background 0.1 0.1 0.2\n\
         light sun 5 -6 10 1 1 1\n\
         surface grnd opaque color 0.8 0.8 0.8 ka 0.2 kd 0.8 ks 0 kt 0\n\
         paint grnd floor scale 1 1 color 0.2 0.2 0.5\n\
         surface red opaque color 0.8 0.25 0.15 ka 0.15 kd 0.75 ks 0.1 kt 0\n\
         block floor grnd at 0 0 -0.25 size 14 14 0.5\n\
         sweep drum red translation bspline at 0 0 0 length 1.2 axis z\n"
    );
    for j in 0..n {
        let a = std::f64::consts::TAU * j as f64 / n as f64;
        s.push_str(&format!("  {:.6} {:.6}\n", 1.2 * a.cos(), 1.2 * a.sin()));
    }
    s.push_str("end\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every deck the measurements name reads and prepares.
    #[test]
    fn every_listed_deck_prepares() {
        let mut names: Vec<&str> = CHAPTER5.to_vec();
        names.extend(BLUR_DECKS);
        names.extend(SOLVER_DECKS);
        names.extend(FRONTIER_DECKS);
        for name in names {
            prepared(name, &Options::default(), Some((8, 8, 1))).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }

    /// The generated decks: a thousand moving spheres; the ball of Fig.
    /// 5.1 blurred.
    #[test]
    fn generated_decks_move() {
        let spheres = load("spheres", Fidelity::Thesis).unwrap();
        assert_eq!(spheres.objects.len(), 1000);
        assert_eq!(spheres.motions.len(), 1000);
        let ball = load("ball", Fidelity::Thesis).unwrap();
        let fig5_1 = load("fig5_1", Fidelity::Thesis).unwrap();
        assert_eq!(ball.objects.len(), fig5_1.objects.len());
        let n = |s: &Scene| s.blur.as_ref().map(|b| b.n);
        assert_eq!((n(&fig5_1), n(&ball)), (Some(0), Some(1)));
    }

    /// The generated circle deck has n segments, for each count the bench uses.
    #[test]
    fn circle_sweep_deck_has_n_segments() {
        for n in [4, 8, 15, 30, 60] {
            let text = circle_sweep_deck(n, 16, 16, 1);
            let scene = load_source(&text, "circle", Path::new("."), Fidelity::Thesis).unwrap();
            let prepared = prepare(scene, &Options::default()).unwrap();
            let sweep = prepared
                .scene()
                .objects
                .iter()
                .find_map(|o| match &o.shape {
                    raytrace::types::Shape::Sweep(s) => Some(s),
                    _ => None,
                })
                .expect("a sweep");
            assert_eq!(sweep.segment, n);
            assert_eq!(sweep.points.len(), n);
        }
    }

    /// Resizing keeps the view and sets the mask; a pattern record of another
    /// mask is dropped.
    #[test]
    fn resize_sets_the_image() {
        let mut scene = load("fig5_3", Fidelity::Thesis).unwrap();
        let view = scene.view.clone();
        scene.resize(96, 64, 8);
        assert_eq!(
            (scene.image.width, scene.image.height, scene.image.masksize),
            (96, 64, 8)
        );
        assert_eq!(scene.view, view);
        assert!(scene.pattern.is_none());
    }
}

//! `tools pov` of blobs and patches (§6.2, the port's extension): a blob
//! is POV-Ray's `blob` (its field is ours), a patch a `bicubic_patch` of
//! type 1, the points swapped as every point is (<x, z, y>); when POV-Ray
//! is installed, it renders the export.

use std::path::Path;

use raytrace::deck::initialize;
use raytrace::options::Fidelity;
use tools::pov::{blob_sdl, patch_sdl, scene_sdl, PATCH_STEPS};

const DECK: &str = "\
view eye 0 -8 2 look 0 0 0.5 screen 4 distance 5
image 32 32 mask 1
light sun 5 -6 9 1 1 1
surface red opaque color 0.9 0.3 0.2 ka 0.2 kd 0.8 ks 0 kt 0
blob body red at -1 0 0.5 threshold 0.5
  -0.5 0 0 0.9 1
  0.5 0 2 0.9 -0.75
end
patch dome red at 1.2 0 0
  -0.8 -0.8 0  -0.27 -0.8 0.3  0.27 -0.8 0.3  0.8 -0.8 0
  -0.8 -0.27 0.3  -0.27 -0.27 1  0.27 -0.27 1  0.8 -0.27 0.3
  -0.8 0.27 0.3  -0.27 0.27 1  0.27 0.27 1  0.8 0.27 0.3
  -0.8 0.8 0  -0.27 0.8 0.3  0.27 0.8 0.3  0.8 0.8 7
end
";

#[test]
fn blobs_and_patches_are_exported_as_povray_s() {
    let scene = initialize(DECK, "t.deck", Path::new("."), Fidelity::Thesis).unwrap();
    let raytrace::types::Shape::Blob(b) = &scene.objects[0].shape else {
        panic!("a blob")
    };
    assert_eq!(
        blob_sdl(b).unwrap(),
        "blob { threshold 0.5 sphere { <-0.5, 0.0, 0.0>, 0.9, strength 1.0 } sphere { <0.5, 2.0, 0.0>, 0.9, strength -0.75 }"
    );
    let raytrace::types::Shape::Patch(p) = &scene.objects[1].shape else {
        panic!("a patch")
    };
    let text = patch_sdl(p);
    assert!(
        text.starts_with(&format!(
            "bicubic_patch {{ type 1 flatness 0 u_steps {PATCH_STEPS} v_steps {PATCH_STEPS} <-0.8, 0.0, -0.8>, <-0.27, 0.3, -0.8>"
        )),
        "{text}"
    );
    // The last point, (0.8, 0.8, 7) in our world, last and swapped.
    assert!(text.ends_with("<0.8, 7.0, 0.8>"), "{text}");
    assert_eq!(text.matches('<').count(), 16);
    // In the scene: each with its texture and matrix, and closed.
    let sdl = scene_sdl(&scene, Fidelity::Thesis);
    for name in ["body", "dome"] {
        let line = sdl.lines().find(|l| l.ends_with(&format!("// {name}"))).unwrap();
        assert!(line.contains("pigment") && line.contains("matrix <"), "{line}");
        assert_eq!(line.matches('{').count(), line.matches('}').count(), "{line}");
    }
}

/// POV-Ray reads the export and renders it (skipped without POV-Ray).
#[test]
fn povray_renders_the_export() {
    if tools::vs_povray::check_povray().is_err() {
        eprintln!("povray is not installed: not run");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let scene = initialize(DECK, "t.deck", Path::new("."), Fidelity::Thesis).unwrap();
    let pov = dir.path().join("shapes.pov");
    std::fs::write(&pov, scene_sdl(&scene, Fidelity::Thesis)).unwrap();
    let out = dir.path().join("shapes.ppm");
    tools::vs_povray::povray(&pov, &out, (32, 32), 1).unwrap();
    let (w, h, pixels) = tools::vs_povray::read_ppm(&std::fs::read(&out).unwrap()).unwrap();
    assert_eq!((w, h), (32, 32));
    assert!(
        pixels.iter().any(|p| p[0] > 60 && p[0] > p[2]),
        "the red shapes are drawn"
    );
}

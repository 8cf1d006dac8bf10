//! `tools pov` and Cook's distributed ray tracing (issue 26, item 6): a
//! `lens` becomes POV-Ray's focal blur (`aperture` 4× the lens's radius,
//! `focal_point` FOCUS along the line of sight, `blur_samples` the deck's
//! M×M rays), a light of `radius` R an `area_light` of diameter 2R
//! (`circular`, `orient`, `jitter`, M×M lights); a deck without them, or
//! with `lens 0 F` and `radius 0`, exports as before.

use std::path::Path;

use raytrace::deck::initialize;
use raytrace::options::Fidelity;
use raytrace::scene::Scene;
use raytrace::types::DVec3;
use tools::pov::scene_sdl;

const FIDELITIES: [Fidelity; 2] = [Fidelity::Thesis, Fidelity::Listing];

/// A small deck seen from `eye` toward `look`, with the `light`'s
/// optional field and the records in `extra`.
fn deck(eye: &str, look: &str, light: &str, extra: &str) -> String {
    format!(
        "view eye {eye} look {look} screen 4 distance 5
image 200 100 mask 3
light sun 3 -4 8  1 0.5 0.25 {light}
surface red opaque color 0.9 0.1 0.1  ka 0.2 kd 0.8 ks 0 kt 0
sphere ball red at 0 0 0 radius 1
{extra}
"
    )
}

fn scene(text: &str, fidelity: Fidelity) -> Scene {
    initialize(text, "pov.deck", Path::new("."), fidelity).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// The line of `text` that starts with `start`.
fn line<'a>(text: &'a str, start: &str) -> &'a str {
    text.lines()
        .find(|l| l.starts_with(start))
        .unwrap_or_else(|| panic!("no {start} line in\n{text}"))
}

/// The POV-Ray vector after `key` in `line`, as our world's point (POV's
/// <x, y, z> is our (x, z, y)).
fn vector_after(line: &str, key: &str) -> DVec3 {
    let rest = &line[line.find(key).unwrap_or_else(|| panic!("no {key} in {line}")) + key.len()..];
    let inner = rest.trim_start().trim_start_matches('<');
    let v: Vec<f64> = inner[..inner.find('>').unwrap()]
        .split(',')
        .map(|s| s.trim().parse().unwrap())
        .collect();
    DVec3::new(v[0], v[2], v[1])
}

#[test]
fn a_lens_is_focal_blur_and_a_sphere_of_light_an_area_light() {
    let text = scene_sdl(
        &scene(&deck("0 -10 0", "0 0 0", "radius 0.5", "lens 0.25 8"), Fidelity::Thesis),
        Fidelity::Thesis,
    );
    let camera = line(&text, "camera {");
    // POV-Ray's lens radius is aperture/4: the deck's radius 0.25 is aperture 1.
    assert!(
        camera.ends_with(" aperture 1.0 focal_point <0.0, 0.0, -2.0> blur_samples 9, 9 }"),
        "{camera}"
    );
    let light = line(&text, "light_source {");
    assert_eq!(
        light,
        "light_source { <3.0, 8.0, -4.0> color rgb <1.0, 0.5, 0.25> area_light <1.0, 0, 0>, <0, 0, 1.0>, 3, 3 jitter circular orient } // sun"
    );
    // Mask 1: 2×2 lights, as POV-Ray refuses `circular` with one.
    let mut one = scene(&deck("0 -10 0", "0 0 0", "radius 0.5", ""), Fidelity::Thesis);
    one.resize(20, 10, 1);
    let text = scene_sdl(&one, Fidelity::Thesis);
    assert!(
        line(&text, "light_source {").contains(", 2, 2 jitter circular orient }"),
        "{text}"
    );
}

/// Seen obliquely, the focal point is FOCUS along the line of sight (the
/// eye toward the look point), which is along the camera's `direction`,
/// so POV-Ray's plane of focus (through `focal_point`, across `direction`)
/// is ours; the aperture is 4 times the lens's radius.
#[test]
fn the_focal_point_is_focus_along_the_line_of_sight() {
    for fidelity in FIDELITIES {
        let (eye, look) = (DVec3::new(3.0, -7.0, 2.0), DVec3::new(0.0, 1.0, 0.5));
        let text = scene_sdl(
            &scene(&deck("3 -7 2", "0 1 0.5", "", "lens 0.1 6.5"), fidelity),
            fidelity,
        );
        let camera = line(&text, "camera {");
        assert_eq!(vector_after(camera, "location"), eye);
        let focal = vector_after(camera, "focal_point");
        let want = eye + (look - eye).normalize() * 6.5;
        assert!((focal - want).length() < 1e-12, "{focal} against {want}");
        let direction = vector_after(camera, "direction").normalize();
        assert!(((focal - eye).normalize() - direction).length() < 1e-12, "{camera}");
        assert!(camera.contains(" aperture 0.4 "), "{camera}");
        // The listing's one-dimensional lens has no POV-Ray form: said so.
        assert_eq!(
            text.contains("// The lens as the thesis's thin lens"),
            fidelity == Fidelity::Listing,
            "{text}"
        );
    }
}

/// `lens 0 F` and `radius 0` are the pinhole and the point light: the
/// export of the deck without them, byte for byte.
#[test]
fn zero_lens_and_radius_export_as_none() {
    for fidelity in FIDELITIES {
        let none = scene_sdl(&scene(&deck("0 -10 1", "0 0 0", "", ""), fidelity), fidelity);
        let zero = scene_sdl(
            &scene(&deck("0 -10 1", "0 0 0", "radius 0", "lens 0 7"), fidelity),
            fidelity,
        );
        assert_eq!(zero, none);
        assert!(!none.contains("aperture") && !none.contains("area_light"), "{none}");
    }
}

/// Every shipped deck: its export differs from the export of the same
/// scene without lens, radii and gloss only by what those add at the end
/// of the camera, light and object lines (and the listing's lens note),
/// so what the base exported stands as it was; a deck with none of them
/// exports exactly that.
#[test]
fn shipped_decks_export_as_before_but_for_the_new_records() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../legacy_pascal/decks");
    let mut decks = 0;
    let mut with_records = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("deck") {
            continue;
        }
        let name = path.display().to_string();
        let src = std::fs::read_to_string(&path).unwrap();
        for fidelity in FIDELITIES {
            let full = initialize(&src, &name, &dir, fidelity).unwrap_or_else(|e| panic!("{e}"));
            let mut bare = full.clone();
            bare.lens = None;
            bare.lights.iter_mut().for_each(|l| l.radius = 0.0);
            bare.surfaces.iter_mut().for_each(|s| s.gloss = 0.0);
            let has_records = bare != full;
            let (a, b) = (scene_sdl(&full, fidelity), scene_sdl(&bare, fidelity));
            if !has_records {
                assert_eq!(a, b, "{name}");
                assert!(!a.contains("aperture") && !a.contains("area_light") && !a.contains("gloss"));
                continue;
            }
            with_records += 1;
            let note = |l: &&str| !l.starts_with("// The lens as the thesis's thin lens");
            let (la, lb): (Vec<&str>, Vec<&str>) = (a.lines().filter(note).collect(), b.lines().collect());
            assert_eq!(la.len(), lb.len(), "{name}");
            for (x, y) in la.iter().zip(&lb) {
                if x == y {
                    continue;
                }
                // x is y with one piece inserted: all of y is x's head and tail.
                let head = x.bytes().zip(y.bytes()).take_while(|(p, q)| p == q).count();
                let tail = x.bytes().rev().zip(y.bytes().rev()).take_while(|(p, q)| p == q).count();
                assert!(head + tail >= y.len() && x.len() > y.len(), "{name}:\n{x}\n{y}");
                let extra = &x[head.min(y.len())..x.len() - (y.len() - head.min(y.len()))];
                let added = ["aperture", "area_light", "/* gloss is not exported */"];
                assert!(added.iter().any(|w| extra.contains(w)), "{name}: {extra}");
            }
        }
        decks += 1;
    }
    assert!(decks >= 17, "{decks} decks");
    // cook.deck has a lens, a sphere of light and a glossy floor.
    assert!(with_records >= 2, "{with_records}");
}

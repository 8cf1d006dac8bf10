//! Cook's distributed ray tracing whole (issue 26, the port's extension
//! where the thesis stops): `lens APERTURE FOCUS`, `light … radius R`,
//! surface `gloss G`. Each effect draws from the sample's own dimensions;
//! with the new records at 0 a deck renders as without them.

mod common;

use common::prepare;
use raytrace::deck::initialize;
use raytrace::options::*;
use raytrace::raytrace::{render, Request};
use raytrace::scene::Scene;
use std::path::Path;

/// Two spheres, near (y = −2) and far (y = 6), a floor, one light; the
/// records of the effects come in `extra`, and `LIGHT`/`FLOOR` stand for
/// the light's and the floor surface's optional fields.
fn deck(extra: &str, light: &str, floor: &str) -> String {
    format!(
        "view eye 0 -10 1.5  look 0 0 1  screen 4  distance 5
image 40 30 mask 4
background 0.1 0.1 0.2
light sun 3 -4 8  1 1 1 {light}
surface floors mirrored color 0.6 0.6 0.6  ka 0.2 kd 0.5 ks 0.6 kt 0 {floor}
surface red opaque color 0.9 0.1 0.1  ka 0.2 kd 0.8 ks 0 kt 0
surface white opaque color 0.9 0.9 0.9  ka 0.2 kd 0.8 ks 0 kt 0
block floor floors at 0 0 -0.5 size 40 40 1
sphere near red at -0.8 -2 0.8 radius 0.8
sphere far white at 1.2 6 1.2 radius 1.2
{extra}
"
    )
}

fn scene(text: &str, fidelity: Fidelity) -> Scene {
    initialize(text, "cook.deck", Path::new("."), fidelity).unwrap_or_else(|e| panic!("{e}"))
}

fn bytes(text: &str, fidelity: Fidelity, sampler: TimeSampler) -> Vec<u8> {
    bytes_at(text, fidelity, sampler, 4)
}

/// The raster's bytes of the deck `text` rendered with `mask`×`mask`
/// subpixels (rays) a pixel.
fn bytes_at(text: &str, fidelity: Fidelity, sampler: TimeSampler, mask: usize) -> Vec<u8> {
    let mut scene = scene(text, fidelity);
    scene.resize(40, 30, mask);
    let opts = Options {
        fidelity,
        sampler,
        ..Options::default()
    };
    let r = render(&prepare(scene, opts), &Request::STILL).unwrap();
    assert_eq!(r.nonfinite, 0);
    r.raster.pixels.iter().flat_map(|p| p.to_vec()).collect()
}

/// The samplers of a fidelity: the adaptive sampler is the thesis's only.
fn samplers(fidelity: Fidelity) -> &'static [TimeSampler] {
    match fidelity {
        Fidelity::Thesis => &SAMPLERS,
        Fidelity::Listing => &SAMPLERS[..3],
    }
}

const SAMPLERS: [TimeSampler; 4] = [
    TimeSampler::Table,
    TimeSampler::Random,
    TimeSampler::Stratified,
    TimeSampler::Adaptive,
];

/// `lens 0 F`, `radius 0` and `gloss 0` give the bytes of the deck without
/// them, with every sampler and both fidelities.
#[test]
fn zero_effects_give_the_bytes_of_none() {
    for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
        for &sampler in samplers(fidelity) {
            let plain = bytes(&deck("", "", ""), fidelity, sampler);
            let zeros = bytes(&deck("lens 0 8", "radius 0", "gloss 0"), fidelity, sampler);
            assert_eq!(plain, zeros, "{fidelity:?} {sampler:?}");
            let lensed = bytes(&deck("lens 0.3 8", "", ""), fidelity, sampler);
            assert_ne!(plain, lensed, "{fidelity:?} {sampler:?}: the lens changed nothing");
        }
    }
}

/// The mean absolute difference, per channel byte, between two renders
/// over the pixels `inside` picks (x, y).
fn difference(a: &[u8], b: &[u8], width: usize, inside: impl Fn(usize, usize) -> bool) -> f64 {
    let (mut sum, mut n) = (0.0, 0);
    for (i, (x, y)) in a.chunks(3).zip(b.chunks(3)).enumerate() {
        if inside(i % width, i / width) {
            sum += x
                .iter()
                .zip(y)
                .map(|(p, q)| (f64::from(*p) - f64::from(*q)).abs())
                .sum::<f64>();
            n += 3;
        }
    }
    sum / n as f64
}

/// Focused on the near sphere (8 from the eye along the line of sight),
/// the lens keeps the near sphere as the pinhole shows it and blurs the
/// far one: the image differs from the pinhole's around the far sphere
/// several times more than around the near one (thesis fidelity; each
/// sphere's box of pixels, the floor's reflection below them aside).
#[test]
fn the_focused_object_stays_sharp_and_the_far_one_blurs() {
    for sampler in SAMPLERS {
        let pinhole = bytes(&deck("", "", ""), Fidelity::Thesis, sampler);
        let lens = bytes(&deck("lens 0.4 8", "", ""), Fidelity::Thesis, sampler);
        // Near sphere: centre at screen x ≈ −0.8·5/8, left of middle, low;
        // far sphere right of middle, higher (40×30 pixels, 0.1 a pixel).
        let near = difference(&pinhole, &lens, 40, |x, y| {
            (8..19).contains(&x) && (12..24).contains(&y)
        });
        let far = difference(&pinhole, &lens, 40, |x, y| {
            (22..28).contains(&x) && (9..16).contains(&y)
        });
        assert!(far > 3.0 * near && far > 2.0, "{sampler:?}: near {near}, far {far}");
    }
}

/// The listing's `depthoffield`: the far point moved onto the world
/// plane y = FOCUS and the eye moved in z only. Focused on y = −2 (the
/// near sphere's plane), the near sphere changes less than the far one.
#[test]
fn the_listings_depthoffield_moves_the_eye_in_z() {
    // The scene 10 further along y: the near sphere's plane is y = 8.
    let moved = |extra: &str| {
        deck(extra, "", "")
            .replace("eye 0 -10 1.5  look 0 0 1", "eye 0 0 1.5  look 0 10 1")
            .replace("at -0.8 -2 0.8", "at -0.8 8 0.8")
            .replace("at 1.2 6 1.2", "at 1.2 16 1.2")
            .replace("3 -4 8  1 1 1", "3 6 8  1 1 1")
            .replace("at 0 0 -0.5", "at 0 10 -0.5")
    };
    let pinhole = bytes(&moved(""), Fidelity::Listing, TimeSampler::Table);
    let lens = bytes(&moved("lens 0.4 8"), Fidelity::Listing, TimeSampler::Table);
    let near = difference(&pinhole, &lens, 40, |x, y| {
        (8..19).contains(&x) && (10..24).contains(&y)
    });
    let far = difference(&pinhole, &lens, 40, |x, y| {
        (20..30).contains(&x) && (5..18).contains(&y)
    });
    assert!(far > 2.0 * near, "near {near}, far {far}");
}

/// How many pixels see the light partly: their floor's share of the light
/// (the pixel over the same pixel with the near sphere taken away; the
/// floor has no ambient term) between 0.1 and 0.9, on the grey floor.
fn penumbra(light: &str, sampler: TimeSampler) -> usize {
    let text = deck("", light, "")
        .replace(
            "surface floors mirrored color 0.6 0.6 0.6  ka 0.2 kd 0.5 ks 0.6 kt 0",
            "surface floors opaque color 0.6 0.6 0.6  ka 0 kd 0.8 ks 0 kt 0",
        )
        // Behind the spheres, so that the near one's shadow falls toward the eye.
        .replace("3 -4 8  1 1 1", "2 4 5  1 1 1");
    let with = bytes(&text, Fidelity::Thesis, sampler);
    let without = bytes(
        &text.replace("sphere near red at -0.8 -2 0.8 radius 0.8", ""),
        Fidelity::Thesis,
        sampler,
    );
    with.chunks(3)
        .zip(without.chunks(3))
        .filter(|(a, b)| {
            // Grey pixels only: the floor, not the red sphere.
            let grey = a[0].abs_diff(a[1]) <= 2 && b[0].abs_diff(b[1]) <= 2;
            let share = f64::from(a[1]) / f64::from(b[1]).max(1.0);
            grey && b[1] > 20 && share > 0.1 && share < 0.9
        })
        .count()
}

/// A sphere of light gives a penumbra: several times more pixels see it
/// partly than see the point light partly (those only along the shadow's
/// edge, by the pixel's own subpixels).
#[test]
fn an_area_light_gives_a_penumbra() {
    for sampler in SAMPLERS {
        let hard = penumbra("", sampler);
        let soft = penumbra("radius 2", sampler);
        assert!(soft > 2 * hard + 10, "{sampler:?}: hard {hard}, soft {soft}");
    }
}

/// A glossy floor blurs the near sphere's reflection: the reflection's
/// pixels differ from their neighbours less than with the mirror.
#[test]
fn gloss_blurs_the_reflection() {
    for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
        let rough = |floor: &str| {
            let b = bytes_at(&deck("", "", floor), fidelity, TimeSampler::Stratified, 8);
            // Horizontal steps over the rows below the near sphere.
            let mut steps = 0.0;
            for y in 24..30 {
                for x in 5..22 {
                    let (p, q) = ((y * 40 + x) * 3, (y * 40 + x + 1) * 3);
                    steps += (f64::from(b[p]) - f64::from(b[q])).abs();
                }
            }
            steps
        };
        let (mirror, glossy) = (rough(""), rough("gloss 0.3"));
        assert!(glossy < 0.8 * mirror, "{fidelity:?}: mirror {mirror}, glossy {glossy}");
    }
}

/// A light whose sphere holds the eye, or a surface, renders without NaN.
#[test]
fn a_light_around_the_eye_or_a_surface_renders() {
    for at in ["0 -10 1.5", "-0.8 -2 0.8", "0 0 0"] {
        let text = deck("lens 0.2 8", "radius 3", "gloss 0.2").replace("3 -4 8  1 1 1", &format!("{at}  1 1 1"));
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            for &sampler in samplers(fidelity) {
                bytes(&text, fidelity, sampler);
            }
        }
    }
}

/// Bad input: an error at the number's line and column, for each record.
#[test]
fn bad_effects_are_errors_at_their_place() {
    let cases = [
        ("lens -0.1 8", "", "", "11:6"),
        ("lens 0.1 0", "", "", "11:10"),
        ("lens 0.1 -3", "", "", "11:10"),
        ("lens 0.1 1e8", "", "", "11:10"),
        ("lens 0.1 5\nlens 0.1 5", "", "", "12:1"),
        ("", "radius -1", "", "4:32"),
        ("", "", "gloss -0.5", "5:76"),
        ("", "", "gloss 1e9", "5:76"),
    ];
    for (extra, light, floor, at) in cases {
        let text = deck(extra, light, floor);
        let e = initialize(&text, "cook.deck", Path::new("."), Fidelity::Thesis).unwrap_err();
        let place = format!("{}:{}", e.line, e.column);
        assert_eq!(place, at, "{extra} {light} {floor}: {e}");
    }
}

/// The RMSE, over the pixels' colours before rounding, of `text` rendered
/// with `mask`² rays a pixel against `reference`.
fn rmse(text: &str, sampler: TimeSampler, mask: usize, reference: &[f64]) -> f64 {
    let colours = colours(text, sampler, mask);
    let sum: f64 = colours.iter().zip(reference).map(|(a, b)| (a - b) * (a - b)).sum();
    (sum / colours.len() as f64).sqrt()
}

/// The pixels' colours (every channel) of `text`, 16×12 pixels of `mask`²
/// rays, thesis fidelity.
fn colours(text: &str, sampler: TimeSampler, mask: usize) -> Vec<f64> {
    let mut scene = scene(text, Fidelity::Thesis);
    scene.resize(16, 12, mask);
    let opts = Options {
        sampler,
        ..Options::default()
    };
    let r = render(&prepare(scene, opts), &Request::STILL).unwrap();
    r.colours.iter().flat_map(|c| c.to_array()).collect()
}

/// Every sampler converges on each effect alone: the RMSE against the
/// sampler's own render of 1024 rays a pixel falls at each step of 1, 4,
/// 16 and 64 rays a pixel (docs/cook.md has the table).
#[test]
fn every_sampler_converges_on_each_effect() {
    let effects = [
        ("lens", deck("lens 0.4 8", "", "")),
        (
            "radius",
            deck("", "radius 2", "").replace("3 -4 8  1 1 1", "2 4 5  1 1 1"),
        ),
        ("gloss", deck("", "", "gloss 0.3")),
    ];
    for (name, text) in &effects {
        for sampler in [TimeSampler::Random, TimeSampler::Stratified, TimeSampler::Adaptive] {
            let reference = colours(text, sampler, 32);
            let errors: Vec<f64> = [1, 2, 4, 8]
                .iter()
                .map(|&m| rmse(text, sampler, m, &reference))
                .collect();
            eprintln!("{name} {sampler:?}: {errors:?}");
            assert!(errors.windows(2).all(|w| w[1] < w[0]), "{name} {sampler:?}: {errors:?}");
        }
    }
}

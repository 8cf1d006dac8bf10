//! Renders of the legacy decks with an answer known beforehand.

mod common;
use common::load_deck as load;
use common::render_still;
use raytrace::options::*;
use raytrace::types::*;

/// The connected regions (4-neighbours) of the pixels where `mask` holds.
fn regions(mask: &[bool], width: usize) -> usize {
    let height = mask.len() / width;
    let mut seen = vec![false; mask.len()];
    let mut count = 0;
    for start in 0..mask.len() {
        if !mask[start] || seen[start] {
            continue;
        }
        count += 1;
        let mut stack = vec![start];
        seen[start] = true;
        while let Some(i) = stack.pop() {
            let (x, y) = (i % width, i / width);
            let mut push = |j: usize| {
                if mask[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            };
            if x > 0 {
                push(i - 1);
            }
            if x + 1 < width {
                push(i + 1);
            }
            if y > 0 {
                push(i - width);
            }
            if y + 1 < height {
                push(i + width);
            }
        }
    }
    count
}

/// Fig. 5.1 with `blur 0` and 2×2 subpixels: the ball shows as exactly four
/// copies, one per subpixel time. The ball is made emissive (so it casts no
/// shadow that could join or add regions) and compared with the scene
/// without it.
#[test]
fn fig5_1_shows_four_copies() {
    let mut scene = load("fig5_1.deck", Fidelity::Thesis);
    assert_eq!(scene.image.masksize, 2);
    assert_eq!(scene.blur.as_ref().map(|b| b.n), Some(0));
    let ball = scene.objects.iter().position(|o| o.name == "ball").unwrap();
    let surface = scene.objects[ball].surface;
    scene.surfaces[surface].surface = SurfaceAttribute::Light;
    let with = render_still(&scene, &Options::default()).raster;
    let mut without = scene.clone();
    without.objects.remove(ball);
    without.motions.clear();
    let without = render_still(&without, &Options::default()).raster;
    let mask: Vec<bool> = with.pixels.iter().zip(&without.pixels).map(|(a, b)| a != b).collect();
    assert!(mask.iter().filter(|&&m| m).count() > 400, "the copies are visible");
    assert_eq!(regions(&mask, with.width), 4);
}

/// A textured block shows the texture: the card's eight colour bars reach
/// the image (Fig. 5.3 at rest), and the static deck's picture changes when
/// the texture is taken away.
#[test]
fn texture_reaches_the_image() {
    let mut scene = load("fig5_3.deck", Fidelity::Thesis);
    scene.motions.clear();
    let textured = render_still(&scene, &Options::default()).raster;
    // Saturated bar colours: one channel high, another low.
    let vivid = |p: &[u8; 3]| p.iter().max().unwrap() > &180 && p.iter().min().unwrap() < &60;
    assert!(textured.pixels.iter().filter(|p| vivid(p)).count() > 500);
    let picture = scene.objects.iter().find(|o| o.name == "cube").unwrap().surface;
    scene.surfaces[picture].texture = None;
    let plain = render_still(&scene, &Options::default()).raster;
    assert_eq!(plain.pixels.iter().filter(|p| vivid(p)).count(), 0);
}

/// The still life.s floor carries the `floortest` checker: along a row
/// of the nearer floor the floor changes between its two colours many times.
#[test]
fn still_life_floor_is_a_checker() {
    let scene = load("still_life.deck", Fidelity::Thesis);
    let img = render_still(&scene, &Options::default()).raster;
    let y = img.height * 7 / 8;
    let row = &img.pixels[y * img.width..(y + 1) * img.width];
    let light = |p: &[u8; 3]| p[0] > 150;
    let changes = row.windows(2).filter(|w| light(&w[0]) != light(&w[1])).count();
    assert!(changes >= 6, "{changes} changes along row {y}");
}

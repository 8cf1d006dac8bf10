//! Whitted's model (Ch. 4 (f)) and the main program's camera, against
//! values derived by hand.

mod common;
use common::render_still;
use common::*;
use raytrace::options::*;
use raytrace::raytrace::{trace_ray, Camera};
use raytrace::scene::*;
use raytrace::trace::refract;
use raytrace::types::*;

fn opts() -> Options {
    Options::default()
}

/// `raytrace(aray, 1.0, false, acolor, 1)` in a scene where nothing moves.
fn trace_one(s: &Scene, ray: &Ray) -> Intensity {
    trace_ray(&prepare(s.clone(), opts()), ray, 0.0).0
}

/// I = ka·Iobject + kd·cosθ·light·colour at a known angle θ = 60°.
#[test]
fn diffuse_term_at_a_known_angle() {
    let mut s = scene();
    s.surfaces
        .push(surface(SurfaceAttribute::Opaque, [0.8, 0.6, 0.4], 0.1, 0.7, 0.0, 0.0));
    s.objects.push(sphere("ball", 0, [0.0, 0.0, 0.0], 1.0));
    let theta = 60f64.to_radians();
    // The hit is (0, −1, 0) with normal −y; the light lies 60° off the normal.
    let l = DVec3::new(theta.sin(), -theta.cos(), 0.0);
    let at = DVec3::new(0.0, -1.0, 0.0) + l * 1e4;
    s.lights.push(light(at.to_array(), [1.0, 0.5, 0.25]));
    let ray = Ray::new(DVec3::new(0.0, -10.0, 0.0), DVec3::Y);
    let got = trace_one(&s, &ray);
    let color = DVec3::new(0.8, 0.6, 0.4);
    let want = 0.1 * color + 0.7 * theta.cos() * DVec3::new(1.0, 0.5, 0.25) * color;
    assert!(close(got, want, 1e-9), "{got} vs {want}");

    // A block between the point and the light leaves the ambient term alone.
    s.surfaces
        .push(surface(SurfaceAttribute::Opaque, [1.0, 1.0, 1.0], 0.0, 1.0, 0.0, 0.0));
    let mid = DVec3::new(0.0, -1.0, 0.0) + l * 5.0;
    s.objects.push(block("wall", 1, mid.to_array(), [1.0, 1.0, 1.0]));
    let got = trace_one(&s, &ray);
    assert!(close(got, 0.1 * color, 1e-12), "{got}");
}

/// A `crystal` object lets kt·colour of the light through; a
/// `transparent` one casts a full shadow.
#[test]
fn shadows_through_crystal_and_transparent() {
    let mut s = scene();
    s.surfaces
        .push(surface(SurfaceAttribute::Opaque, [1.0, 1.0, 1.0], 0.0, 1.0, 0.0, 0.0));
    s.objects.push(block("floor", 0, [0.0, 0.0, -0.5], [20.0, 20.0, 1.0]));
    s.lights.push(light([0.0, 0.0, 10.0], [1.0, 1.0, 1.0]));
    let mut glass = surface(SurfaceAttribute::Crystal, [0.5, 1.0, 1.0], 0.0, 0.0, 0.0, 0.8);
    s.surfaces.push(glass.clone());
    s.objects.push(sphere("gem", 1, [0.0, 0.0, 5.0], 1.0));
    // Straight down onto the floor under the gem: N·L = 1.
    let ray = Ray::new(DVec3::new(0.0, 0.0, 3.0), DVec3::NEG_Z);
    let got = trace_one(&s, &ray);
    assert!(close(got, DVec3::new(0.4, 0.8, 0.8), 1e-9), "{got}");
    glass.surface = SurfaceAttribute::Transparent;
    s.surfaces[1] = glass;
    let got = trace_one(&s, &ray);
    assert!(close(got, DVec3::ZERO, 0.0), "{got}");
}

/// A mirror floor at 45°: the reflected ray meets an emissive ball, and
/// the pixel is ks·prcntrfl of its colour; moved off the reflected line,
/// the ball is not seen.
#[test]
fn mirror_reflection_at_45_degrees() {
    let mut s = scene();
    s.backgrnd = DVec3::new(0.0, 0.0, 0.2);
    let mut mirror = surface(SurfaceAttribute::Mirrored, [1.0, 1.0, 1.0], 0.0, 0.0, 0.8, 0.0);
    mirror.prcntrfl = 0.5;
    s.surfaces.push(mirror);
    s.surfaces
        .push(surface(SurfaceAttribute::Light, [1.0, 0.8, 0.6], 0.0, 0.0, 0.0, 0.0));
    s.objects.push(block("mirror", 0, [0.0, 0.0, -0.5], [4.0, 4.0, 1.0]));
    s.objects.push(sphere("lamp", 1, [0.0, 5.0, 5.0], 0.1));
    let ray = Ray::new(DVec3::new(0.0, -5.0, 5.0), DVec3::new(0.0, 1.0, -1.0).normalize());
    let got = trace_one(&s, &ray);
    assert!(close(got, 0.4 * DVec3::new(1.0, 0.8, 0.6), 1e-12), "{got}");
    s.objects[1].sphereo = DVec3::new(0.0, 5.0, 5.5);
    s.objects[1].transfm = DMat4::from_translation(s.objects[1].sphereo);
    s.objects[1].inverse = DMat4::from_translation(-s.objects[1].sphereo);
    let got = trace_one(&s, &ray);
    assert!(close(got, 0.4 * s.backgrnd, 1e-12), "{got}");
}

/// Snell's law at 30° into glass of index 1.5: sin θt = ½/1.5 = ⅓; and
/// total internal reflection from inside at 60°.
#[test]
fn snell_refraction_and_total_internal_reflection() {
    let d = DVec3::new(0.5, 0.0, -(0.75f64).sqrt()); // 30° from −z
    let t = refract(d, DVec3::Z, 1.0 / 1.5).unwrap();
    assert!((t.length() - 1.0).abs() < 1e-12);
    assert!((t.x - 1.0 / 3.0).abs() < 1e-12, "{t}");
    assert!(t.z < 0.0 && t.y == 0.0);
    let inside = DVec3::new(60f64.to_radians().sin(), 0.0, 60f64.to_radians().cos());
    assert!(refract(inside, DVec3::NEG_Z, 1.5).is_none());
}

/// A glass slab of thickness 1 shifts a 45° ray sideways by
/// 1·(tan 45° − tan θt); an emissive ball on the shifted line is seen
/// through it, the ball on the unrefracted line is not.
#[test]
fn refraction_through_a_slab() {
    let mut s = scene();
    s.backgrnd = DVec3::ZERO;
    s.surfaces.push(surface(
        SurfaceAttribute::Transparent,
        [1.0, 1.0, 1.0],
        0.0,
        0.0,
        0.0,
        1.0,
    ));
    s.surfaces
        .push(surface(SurfaceAttribute::Light, [0.3, 0.9, 0.6], 0.0, 0.0, 0.0, 0.0));
    s.objects.push(block("slab", 0, [0.0, 0.0, -0.5], [20.0, 20.0, 1.0]));
    let sin_t = 45f64.to_radians().sin() / 1.5;
    let tan_t = sin_t / (1.0 - sin_t * sin_t).sqrt();
    // Enters at the origin, leaves z = −1 at x = tan θt, then goes on at 45°.
    let exit = DVec3::new(tan_t, 0.0, -1.0);
    let target = exit + DVec3::new(1.0, 0.0, -1.0).normalize() * 3.0;
    s.objects.push(sphere("lamp", 1, target.to_array(), 0.05));
    let ray = Ray::new(DVec3::new(-2.0, 0.0, 2.0), DVec3::new(1.0, 0.0, -1.0).normalize());
    let got = trace_one(&s, &ray);
    assert!(close(got, DVec3::new(0.3, 0.9, 0.6), 1e-12), "{got}");
    // The unrefracted line would pass 1 − tan θt ≈ 0.47 away.
    let straight = DVec3::new(1.0, 0.0, -1.0) + DVec3::new(1.0, 0.0, -1.0).normalize() * 3.0;
    s.objects[1] = sphere("lamp", 1, straight.to_array(), 0.05);
    let got = trace_one(&s, &ray);
    assert!(close(got, DVec3::ZERO, 0.0), "{got}");
}

fn busy_scene() -> Scene {
    let mut s = scene();
    s.image = ImageSpec {
        width: 24,
        height: 18,
        masksize: 2,
        aliasing: 0.5,
    };
    s.backgrnd = DVec3::new(0.1, 0.1, 0.3);
    s.lights.push(light([5.0, -5.0, 8.0], [1.0, 1.0, 1.0]));
    s.surfaces
        .push(surface(SurfaceAttribute::Opaque, [0.9, 0.3, 0.2], 0.1, 0.8, 0.0, 0.0));
    let mut glass = surface(SurfaceAttribute::Transparent, [1.0, 1.0, 1.0], 0.0, 0.1, 0.2, 0.8);
    glass.index = 1.5;
    s.surfaces.push(glass);
    s.surfaces
        .push(surface(SurfaceAttribute::Mirrored, [1.0, 1.0, 1.0], 0.1, 0.2, 0.7, 0.0));
    s.objects.push(block("floor", 0, [0.0, 0.0, -1.5], [10.0, 10.0, 1.0]));
    s.objects.push(sphere("glass", 1, [-0.8, 0.0, 0.0], 0.8));
    s.objects.push(sphere("mirror", 2, [1.0, 1.5, 0.0], 0.9));
    s.view.eyept = DVec3::new(1.0, -8.0, 3.0);
    s
}

/// The image is bit-identical for 1, 2 and 8 threads.
#[test]
fn same_image_for_any_thread_count() {
    let s = busy_scene();
    let images: Vec<_> = [1, 2, 8]
        .into_iter()
        .map(|n| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
            pool.install(|| render_still(&s, &opts())).raster
        })
        .collect();
    assert_eq!(images[0], images[1]);
    assert_eq!(images[0], images[2]);
    // And it is not a blank image.
    let distinct: std::collections::HashSet<_> = images[0].pixels.iter().collect();
    assert!(distinct.len() > 20, "{} colours", distinct.len());
}

/// Erratum 13: the listing traces one column more per scanline.
#[test]
fn erratum_13_the_extra_column() {
    let s = busy_scene();
    let thesis = render_still(&s, &opts());
    let listing = render_still(
        &s,
        &Options {
            fidelity: Fidelity::Listing,
            ..opts()
        },
    );
    let (w, h, m) = (s.image.width as u64, s.image.height as u64, s.image.masksize as u64);
    assert_eq!(thesis.stats.primary, w * m * h * m);
    assert_eq!(listing.stats.primary, (w * m + 1) * h * m);
}

/// Erratum 14: for a 2:1 raster the thesis keeps pixels square, the
/// listing stretches them vertically: both axes span `screensize`, and
/// (D5) a subpixel step is 1/(2h − 1) of it, h = `halfvirtualx` = N div 2,
/// so the steps are screensize/31 across and screensize/15 down.
#[test]
fn erratum_14_pixel_aspect() {
    let mut s = scene();
    s.image = ImageSpec {
        width: 32,
        height: 16,
        masksize: 1,
        aliasing: 0.0,
    };
    for (fidelity, ratio) in [(Fidelity::Thesis, 1.0), (Fidelity::Listing, 31.0 / 15.0)] {
        let cam = Camera::new(&s, fidelity);
        let a = cam.ray(10.0, 8.0, 0.0, 0.0).dir;
        let right = cam.ray(11.0, 8.0, 0.0, 0.0).dir;
        let down = cam.ray(10.0, 9.0, 0.0, 0.0).dir;
        // Directions are unit; the screen is 5 away: compare on the screen plane.
        let dx = (right / right.y - a / a.y).length();
        let dz = (down / down.y - a / a.y).length();
        assert!((dz / dx - ratio).abs() < 1e-9, "{fidelity:?}: {}", dz / dx);
    }
}

/// Erratum 15: with `aliasing`, the listing moves every subpixel by the same
/// noise2 entry (`aindex := aindex + 1` is commented out); the thesis gives
/// each its own. Seen on a vertical edge (a flat block's side) in a square
/// image, so that erratum 14 plays no part: a common shift keeps every row
/// of pixels alike, jitter of its own per subpixel does not. The edge is put
/// at 20 places across a pixel, so that wherever each fidelity puts its
/// subpixels (D5), some place has a subpixel within the jitter of the edge.
#[test]
fn erratum_15_jitter_cursor() {
    let mut s = scene();
    s.image = ImageSpec {
        width: 16,
        height: 16,
        masksize: 2,
        aliasing: 1.0,
    };
    s.surfaces = vec![surface(SurfaceAttribute::Opaque, [1.0, 1.0, 1.0], 1.0, 0.0, 0.0, 0.0)];
    let rows =
        |r: &raytrace::raster::Raster| -> Vec<Vec<[u8; 3]>> { r.pixels.chunks(r.width).map(|c| c.to_vec()).collect() };
    for fidelity in [Fidelity::Listing, Fidelity::Thesis] {
        let o = Options { fidelity, ..opts() };
        let mut rows_differ = 0;
        for i in 0..20 {
            // The block's left side at x = 0.3 + i/40: on the screen
            // (0.3 + i/40)·5/9.5 right of the centre, across a pixel.
            let x = 0.3 + f64::from(i) / 40.0;
            s.objects = vec![block("wall", 0, [50.0 + x, 0.0, 0.0], [100.0, 1.0, 100.0])];
            let rs = rows(&render_still(&s, &o).raster);
            // The edge is in the picture: some pixel is white, some black.
            assert!(rs[0].contains(&[255; 3]) && rs[0].contains(&[0; 3]));
            if rs.iter().any(|r| *r != rs[0]) {
                rows_differ += 1;
            }
        }
        match fidelity {
            Fidelity::Listing => assert_eq!(rows_differ, 0, "listing: one shift for every subpixel"),
            Fidelity::Thesis => assert!(rows_differ > 0, "thesis: each subpixel its own jitter"),
        }
    }
    s.objects = vec![block("wall", 0, [50.3, 0.0, 0.0], [100.0, 1.0, 100.0])];
    let thesis_a = render_still(&s, &opts()).raster;
    s.image.aliasing = 0.0;
    let thesis_0 = render_still(&s, &opts()).raster;
    assert_ne!(thesis_a, thesis_0, "jitter changes the image");
}

/// fig5_6's star casts its shadow (the sweep's shadow query, `Sweep::blocks`):
/// a floor point whose ray to a low light crosses the star is lit by the
/// ambient term alone, and lit by the light once the star is gone;
/// a floor point whose ray passes beside it is lit the same either way.
#[test]
fn a_sweep_casts_its_shadow() {
    let mut s = common::load_deck("fig5_6.deck", Fidelity::Thesis);
    s.lights = vec![light([10.0, 0.0, 0.6], [1.0, 1.0, 1.0])];
    let down = |x: f64, y: f64| Ray::new(DVec3::new(x, y, 3.0), DVec3::NEG_Z);
    let (behind, beside) = (down(-3.0, 0.0), down(0.0, -5.0));
    let with_star = (trace_one(&s, &behind), trace_one(&s, &beside));
    let star = s
        .objects
        .iter()
        .position(|o| matches!(o.shape, Shape::Sweep(_)))
        .unwrap();
    s.objects[star].shape = match &s.objects[star].shape {
        // No control points: `spline` makes no segment of it.
        Shape::Sweep(sw) => Shape::Sweep(SweepShape {
            points: Vec::new(),
            ..sw.clone()
        }),
        _ => unreachable!(),
    };
    let without = (trace_one(&s, &behind), trace_one(&s, &beside));
    s.lights.clear();
    let unlit = trace_one(&s, &behind);
    assert_eq!(with_star.0, unlit, "in the star's shadow: the ambient term alone");
    assert!(without.0.element_sum() > unlit.element_sum() + 0.01, "{without:?}");
    assert_eq!(with_star.1, without.1);
}

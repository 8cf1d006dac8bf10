//! Unit `drt`: the tables, LAW, motionblur and the printed helpers, and
//! renders with a known answer.

mod common;
use common::render_still;
use common::*;
use raytrace::drt::*;
use raytrace::options::*;
use raytrace::sampler::{random_time, strata, stratified_time};
use raytrace::scene::*;
use raytrace::types::*;

/// LAW 1–4 of Fig. 3.2 at FRACT = 0, ½, 1.
#[test]
fn law_at_zero_half_one() {
    let want = [
        (Law::Constant, 0.5),
        (Law::Accelerate, 0.292_893_218_813_452_5),
        (Law::Decelerate, std::f64::consts::FRAC_1_SQRT_2), // sin(π/4)
        (Law::Smooth, 0.5),
    ];
    for (law, half) in want {
        assert!(LAW(law, 1.0, 0.0).abs() < 1e-15, "{law:?} at 0");
        assert!((LAW(law, 1.0, 0.5) - half).abs() < 1e-12, "{law:?} at ½");
        assert!((LAW(law, 1.0, 1.0) - 1.0).abs() < 1e-15, "{law:?} at 1");
        assert!(
            (LAW(law, 3.0, 0.5) - 3.0 * half).abs() < 1e-12,
            "{law:?} scales by MAXVAL"
        );
    }
}

fn is_permutation(rows: &[Vec<u32>]) -> bool {
    let mut all: Vec<u32> = rows.iter().flatten().copied().collect();
    all.sort_unstable();
    all == (0..all.len() as u32).collect::<Vec<_>>()
}

/// Erratum 1: the printed table has 10 twice and no 9; the thesis's is a
/// permutation of 0..15 and differs from the printed one in one place.
#[test]
fn fig_2_33_in_both_fidelities() {
    let listing: Vec<Vec<u32>> = fig_2_33(Fidelity::Listing).iter().map(|r| r.to_vec()).collect();
    let thesis: Vec<Vec<u32>> = fig_2_33(Fidelity::Thesis).iter().map(|r| r.to_vec()).collect();
    assert_eq!(
        fig_2_33(Fidelity::Listing),
        [[7, 11, 3, 14], [4, 15, 13, 0], [10, 1, 8, 12], [6, 10, 5, 2]]
    );
    assert_eq!(listing.iter().flatten().filter(|&&v| v == 10).count(), 2);
    assert!(!listing.iter().flatten().any(|&v| v == 9));
    assert!(!is_permutation(&listing));
    assert!(is_permutation(&thesis));
    let changed = listing
        .iter()
        .flatten()
        .zip(thesis.iter().flatten())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(changed, 1);
    for m in 1..=8 {
        assert!(is_permutation(&default_pattern(m, Fidelity::Thesis)), "default {m}×{m}");
    }
}

/// §2.6.5: the sum of n uniforms has mean n/2 and variance n/12; the
/// table's 1000 entries estimate both within four standard errors.
#[test]
fn clt_table_mean_and_variance() {
    for n in [1u32, 2, 4, 12] {
        let t = clt_table(n);
        assert_eq!(t.len(), MAXINDEX);
        let k = t.len() as f64;
        let mean = t.iter().sum::<f64>() / k;
        let var = t.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / (k - 1.0);
        let (mu, sigma2) = (n as f64 / 2.0, n as f64 / 12.0);
        // SE of the mean: σ/√k; of the variance: σ²·√(2/(k−1)) (normal
        // approximation; the uniform's lighter tails make it smaller).
        assert!((mean - mu).abs() < 4.0 * (sigma2 / k).sqrt(), "n={n}: mean {mean}");
        assert!(
            (var - sigma2).abs() < 4.0 * sigma2 * (2.0 / (k - 1.0)).sqrt(),
            "n={n}: var {var}"
        );
        assert!(t.iter().all(|&v| v > 0.0 && v < n as f64));
    }
    assert!(clt_table(0).is_empty());
}

/// Errata 1 and 2: the listing's times are pattern·0.1, read with row and
/// column swapped; the thesis's are strata of [0,1).
#[test]
fn subpixel_times() {
    let listing = TimeTable::new(4, None, 3, Fidelity::Listing).unwrap();
    // scanline 1, scancol 2: col = 1 mod 4 + 1 = 2, row = 2 mod 4 + 1 = 3.
    assert!((listing.time(1, 2, 0) - 0.1 * FIG_2_33[2][1] as f64).abs() < 1e-15);
    let max = (1..=4)
        .flat_map(|l| (1..=4).map(move |c| (l, c)))
        .map(|(l, c)| listing.time(l, c, 0))
        .fold(0.0, f64::max);
    assert!((max - 1.5).abs() < 1e-12, "listing reaches 1.5: {max}");
    // Thesis, blur 0: the centres of the strata, (v + ½)/16.
    let t0 = TimeTable::new(4, None, 0, Fidelity::Thesis).unwrap();
    let thesis_table = fig_2_33(Fidelity::Thesis);
    assert!((t0.time(1, 2, 0) - (thesis_table[1][2] as f64 + 0.5) / 16.0).abs() < 1e-15);
    // Thesis, blur 1: one time in each stratum of [0,1) over a pixel.
    let t1 = TimeTable::new(4, None, 1, Fidelity::Thesis).unwrap();
    let mut strata: Vec<usize> = Vec::new();
    for l in 1..=4 {
        for c in 1..=4 {
            let t = t1.time(l, c, (l - 1) * 4 + c - 1);
            assert!((0.0..1.0).contains(&t));
            strata.push((t * 16.0) as usize);
        }
    }
    strata.sort_unstable();
    assert_eq!(strata, (0..16).collect::<Vec<_>>());
    // A deck table of another size than the mask does not fit.
    let p = PatternRecord {
        pos: Pos::default(),
        m: 2,
        values: vec![vec![0, 1], vec![2, 3]],
    };
    assert!(TimeTable::new(4, Some(&p), 0, Fidelity::Thesis).is_err());
}

fn mover() -> (ObjectRecord, MotionRecord) {
    let obj = sphere("ball", 0, [1.0, 2.0, 3.0], 1.0);
    let motion = MotionRecord {
        pos: Pos::default(),
        object: 0,
        to: DVec3::new(5.0, 2.0, 3.0),
        turn: DVec3::new(0.0, 0.0, 90.0),
        via: None,
        law: Law::Constant,
    };
    (obj, motion)
}

/// Thesis fidelity: the user's path and turn; erratum 3: the listing's
/// hard-coded slide and spin.
#[test]
fn motionblur_poses() {
    let (obj, mut motion) = mover();
    let rest = motionblur_pose(&obj, &motion, 0.0, Fidelity::Thesis);
    assert!(rest.transfm.abs_diff_eq(obj.transfm, 1e-12));
    let end = motionblur_pose(&obj, &motion, 1.0, Fidelity::Thesis);
    assert!(close(end.sphereo, motion.to, 1e-12));
    // Turned 90° about z: local +x points along world +y.
    assert!(close(end.transfm.transform_vector3(DVec3::X), DVec3::Y, 1e-12));
    assert!(end.inverse.abs_diff_eq(end.transfm.inverse(), 1e-12));
    let half = motionblur_pose(&obj, &motion, 0.5, Fidelity::Thesis);
    assert!(close(half.sphereo, DVec3::new(3.0, 2.0, 3.0), 1e-12));
    motion.law = Law::Accelerate;
    let half = motionblur_pose(&obj, &motion, 0.5, Fidelity::Thesis);
    assert!(close(
        half.sphereo,
        DVec3::new(1.0 + 4.0 * 0.292_893_218_813_452_5, 2.0, 3.0),
        1e-12
    ));
    // A Bezier path passes its ends and, at ½, (P0 + 3P1 + 3P2 + P3)/8.
    motion.law = Law::Constant;
    motion.via = Some([DVec3::new(1.0, 6.0, 3.0), DVec3::new(5.0, 6.0, 3.0)]);
    let mid = motionblur_pose(&obj, &motion, 0.5, Fidelity::Thesis);
    assert!(close(mid.sphereo, DVec3::new(3.0, 5.0, 3.0), 1e-12));
    // The listing ignores the record: x + 6t, and 270·50·t degrees about x.
    let l = motionblur_pose(&obj, &motion, 0.1, Fidelity::Listing);
    assert!(close(l.sphereo, DVec3::new(1.6, 2.0, 3.0), 1e-12));
    let turned = l.transfm.transform_vector3(DVec3::Y);
    let a = (1350f64).to_radians();
    assert!(close(turned, DVec3::new(0.0, a.cos(), a.sin()), 1e-12));
}

/// Erratum 12: a ray whose x–y and x–z shadows cross the box's but that
/// misses it; the y–z projection sees it.
#[test]
fn boundvolume_projections() {
    let bx = BoundingBox {
        xmin: -1.0,
        xmax: 1.0,
        ymin: -1.0,
        ymax: 1.0,
        zmin: -1.0,
        zmax: 1.0,
    };
    let through = Ray::new(DVec3::new(-5.0, 0.2, 0.3), DVec3::X);
    assert!(boundvolume(&through, &bx, Fidelity::Listing));
    assert!(boundvolume(&through, &bx, Fidelity::Thesis));
    // Along y+z = 2.9 in the plane x = 0: misses the box (|y|,|z| ≤ 1 gives
    // y+z ≤ 2); its x–y and x–z shadows are the lines x = 0, which cross.
    let miss = Ray::new(DVec3::new(0.0, -2.0, 4.9), DVec3::new(0.0, 1.0, -1.0));
    assert!(boundvolume(&miss, &bx, Fidelity::Listing));
    assert!(!boundvolume(&miss, &bx, Fidelity::Thesis));
    let far = Ray::new(DVec3::new(-5.0, 3.0, 0.0), DVec3::X);
    assert!(!boundvolume(&far, &bx, Fidelity::Listing));
}

/// Erratum 16: the thesis's jitter is across the direction and of length
/// r; the listing's is neither. Each of `jittering`'s three branches (a ≠ 0;
/// a = 0, b ≠ 0; a = b = 0) against the listing's statements (OCR
/// 2204–2238) done by hand in their order: the second and third branches
/// read `a` (and `b`) after overwriting them.
#[test]
fn jittering_offsets() {
    let (x0, y0, z0, r) = (1.0, 1.0, 1.0, 0.25);
    for dir in [[1.0, 2.0, 3.0], [0.0, 1.0, -2.0], [0.0, 0.0, 4.0]] {
        let d = DVec3::from_array(dir).normalize();
        let centre = DVec3::new(x0, y0, z0) + d * 5.0;
        let (mut a, mut b, mut c) = (dir[0], dir[1], dir[2]);
        jittering(x0, y0, z0, r, &mut a, &mut b, &mut c, Fidelity::Thesis);
        let off = DVec3::new(a, b, c) - centre;
        assert!(off.dot(d).abs() < 1e-12, "{dir:?}: across");
        assert!((off.length() - r).abs() < 1e-12, "{dir:?}: length");

        // The listing, statement by statement, on the normalised direction.
        let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        let (na, nb, nc) = (dir[0] / len, dir[1] / len, dir[2] / len);
        let (xi, yi, zi) = (x0 + na * 5.0, y0 + nb * 5.0, z0 + nc * 5.0);
        let want = if na != 0.0 {
            let t = (na * na / (2.0 * na * na + (nb + nc) * (nb + nc))).sqrt();
            [xi - (nb + nc) * r / na, yi + r * t, zi + r * t]
        } else if nb != 0.0 {
            let t = (nb * nb / (2.0 * nb * nb + (na + nc) * (na + nc))).sqrt();
            let a1 = xi + r * t;
            [a1, yi - (a1 + nc) * r / nb, zi + r * t]
        } else {
            let t = (nc * nc / (2.0 * nc * nc + (nb + na) * (nb + na))).sqrt();
            let (a1, b1) = (xi + r * t, yi + r * t);
            [a1, b1, zi - (a1 + b1) * r / nc]
        };
        let (mut a, mut b, mut c) = (dir[0], dir[1], dir[2]);
        jittering(x0, y0, z0, r, &mut a, &mut b, &mut c, Fidelity::Listing);
        assert_eq!([a, b, c], want, "{dir:?}: the listing's arithmetic");
        let off = DVec3::new(a, b, c) - centre;
        assert!(
            off.dot(d).abs() > 1e-3 || (off.length() - r).abs() > 1e-3,
            "{dir:?}: the listing's offset is not the thesis's"
        );
    }
}

/// `depthoffield` keeps the ray through the same point of the focal plane
/// and moves the eye by `fradius*noise[dindex]*2`, in z only.
#[test]
fn depthoffield_keeps_the_focal_point() {
    let noise = noise_table();
    for dindex in [0, 17, 999] {
        let (x0, y0, mut z0) = (0.5, -10.0, 1.0);
        let (mut x1, mut y1, mut z1) = (0.7, -9.0, 1.1);
        depthoffield(x0, y0, &mut z0, &mut x1, &mut y1, &mut z1, 4.0, 0.3, &noise, dindex);
        // The focal point: where the old ray meets y = 4 (t = 14).
        assert!((y1 - 4.0).abs() < 1e-12);
        assert!((x1 - (0.5 + 0.2 * 14.0)).abs() < 1e-12);
        assert!((z1 - (1.0 + 0.1 * 14.0)).abs() < 1e-12);
        assert_eq!(z0, 1.0 + 0.3 * noise[dindex] * 2.0);
        assert!(noise[dindex] != 0.0 && (z0 - 1.0).abs() <= 0.3);
    }
}

#[test]
fn isblur_is_true_for_objects_that_do_not_move() {
    assert!(Isblur(3, &[0, 2]));
    assert!(!Isblur(2, &[0, 2]));
    assert!(Isblur(0, &[]));
}

/// A flat (emissive) square moving at constant speed across a black
/// background, seen head-on: each pixel is the share of the shutter during
/// which it is covered. Per subpixel k the covered times form an interval
/// I_k; with one time in each of the M² strata (blur 1), the count of hits
/// differs from Σ|I_k|·M² by at most 2 strata per interval end, and the
/// I_k of one pixel differ by the pixel's width w over the path D. So
/// |pixel − mean_k |I_k|| ≤ 2/M² + 2w/D + 1/255 (rounding to a byte).
#[test]
fn moving_square_matches_its_coverage() {
    for sampler in [TimeSampler::Table, TimeSampler::Stratified] {
        moving_square(sampler);
    }
}

fn moving_square(sampler: TimeSampler) {
    let m = 8usize;
    let s = common::moving_block(m, 4, 20.0);
    let (w_sq, x0, d) = (2.0, -5.0, 10.0);
    let img = render_still(
        &s,
        &Options {
            sampler,
            ..Options::default()
        },
    )
    .raster;
    let cam = raytrace::raytrace::Camera::new(&s, Fidelity::Thesis);
    let pixel_w = 16.0 / 64.0; // screen 16 wide over 64 pixels, nearly parallel projection
    let bound = 2.0 / (m * m) as f64 + 2.0 * pixel_w / d + 1.0 / 255.0;
    let mut worst: f64 = 0.0;
    for row in 0..4 {
        for col in 0..64 {
            let mut cover = 0.0;
            for sl in 0..m {
                for sc in 0..m {
                    let (line, c) = (row * m + sl + 1, col * m + sc + 1);
                    let ray = cam.ray(c as f64, line as f64, 0.0, 0.0);
                    let x = ray.at(-ray.origin.y / ray.dir.y).x;
                    // Covered while |x − (x0 + D t)| ≤ w/2.
                    let lo = ((x - w_sq / 2.0 - x0) / d).clamp(0.0, 1.0);
                    let hi = ((x + w_sq / 2.0 - x0) / d).clamp(0.0, 1.0);
                    cover += hi - lo;
                }
            }
            let want = cover / (m * m) as f64;
            let got = img.pixels[row * 64 + col][1] as f64 / 255.0;
            worst = worst.max((got - want).abs());
            assert!(
                (got - want).abs() <= bound,
                "pixel ({col},{row}): {got} vs {want}, bound {bound}"
            );
        }
    }
    eprintln!("moving square, {sampler:?}: worst error {worst:.4}, bound {bound:.4}");
}

/// The same image for 1, 2 and 8 threads with motion; a static object
/// renders the same whether or not another moves.
#[test]
fn motion_is_deterministic_and_leaves_static_objects_alone() {
    let mut s = scene();
    s.image = ImageSpec {
        width: 32,
        height: 16,
        masksize: 2,
        aliasing: 0.3,
    };
    s.view.screensize = 8.0;
    s.surfaces
        .push(surface(SurfaceAttribute::Light, [0.9, 0.5, 0.2], 0.0, 0.0, 0.0, 0.0));
    s.objects.push(sphere("still", 0, [-2.0, 0.0, 0.0], 1.0));
    s.objects.push(sphere("mover", 0, [1.5, 0.0, 0.0], 0.8));
    let still = render_still(&s, &Options::default()).raster;
    s.motions.push(MotionRecord {
        pos: Pos::default(),
        object: 1,
        to: DVec3::new(3.0, 0.0, 0.5),
        turn: DVec3::ZERO,
        via: None,
        law: Law::Smooth,
    });
    s.blur = Some(BlurRecord {
        pos: Pos::default(),
        n: 2,
    });
    let images: Vec<_> = [1, 2, 8]
        .into_iter()
        .map(|n| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(n).build().unwrap();
            pool.install(|| render_still(&s, &Options::default())).raster
        })
        .collect();
    assert_eq!(images[0], images[1]);
    assert_eq!(images[0], images[2]);
    assert_ne!(images[0], still, "the mover moved");
    // The left half holds only the still sphere.
    for row in 0..16 {
        for col in 0..16 {
            assert_eq!(
                images[0].pixels[row * 32 + col],
                still.pixels[row * 32 + col],
                "({col},{row})"
            );
        }
    }
}

/// The samplers that are not the thesis's: random times are uniform on
/// [0,1); stratified times put one time in each of a pixel's n strata, in
/// an order that differs from pixel to pixel.
#[test]
fn random_and_stratified_times() {
    let t: Vec<f64> = (0..4000).map(random_time).collect();
    assert!(t.iter().all(|v| (0.0..1.0).contains(v)));
    let mean = t.iter().sum::<f64>() / t.len() as f64;
    assert!((mean - 0.5).abs() < 4.0 * (1.0 / 12.0 / 4000f64).sqrt(), "{mean}");
    for n in [1usize, 4, 16, 64] {
        let mut orders = std::collections::HashSet::new();
        for pixel in 0..50 {
            let perm = strata(pixel, n);
            let mut seen: Vec<usize> = (0..n)
                .map(|j| {
                    let time = stratified_time(pixel, j, perm[j], n);
                    assert!((0.0..1.0).contains(&time));
                    (time * n as f64) as usize
                })
                .collect();
            orders.insert(seen.clone());
            seen.sort_unstable();
            assert_eq!(seen, (0..n).collect::<Vec<_>>(), "pixel {pixel}, n {n}");
        }
        // 4 strata have 24 orders; 16 and more have more orders than pixels here.
        let want = match n {
            1 => 1,
            4 => 15,
            _ => 45,
        };
        assert!(
            orders.len() >= want,
            "n {n}: only {} orders over 50 pixels",
            orders.len()
        );
    }
}

//! The blob and patch records (§6.2, the port's extension) in the deck and
//! the render: what the deck reads, the bad input it refuses, key shapes
//! that are one shape, the same image for any number of threads and any
//! structure over the objects, and numbers at the ends of the deck's
//! ranges.

mod common;
use common::{raytrace_command, render_still};

use std::path::Path;

use raytrace::accel::Accel;
use raytrace::deck::initialize;
use raytrace::options::{Fidelity, Options, Solver};
use raytrace::raytrace::{render, Prepared, Request};
use raytrace::scene::Scene;
use raytrace::types::{DVec3, PrimitiveClass, Shape};

/// A view, a light, two surfaces: the lines 1–4 every case adds to.
const HEAD: &str = "\
view eye 0 -8 2 look 0 0 0.5 screen 4 distance 5
image 48 40 mask 2
light sun 5 -6 9 1 1 1
surface red opaque color 0.9 0.3 0.2 ka 0.2 kd 0.8 ks 0 kt 0
";

/// A blob of three components (lines 5–9).
const BLOB: &str = "\
blob body red at -1 0 0.5 threshold 0.5
  -0.5 0 0 0.9 1
  0.5 0 0 0.9 1
  0 0 0.5 0.7 1.5
end
";

/// A patch bent into a dome, two rows on a line and one point a line
/// (lines 10–18).
const PATCH: &str = "\
patch dome red at 1.2 0 0
  -0.8 -0.8 0  -0.27 -0.8 0.3  0.27 -0.8 0.3  0.8 -0.8 0
  -0.8 -0.27 0.3  -0.27 -0.27 1  0.27 -0.27 1  0.8 -0.27 0.3
  -0.8 0.27 0.3  -0.27 0.27 1  0.27 0.27 1  0.8 0.27 0.3
  -0.8 0.8 0
  -0.27 0.8 0.3
  0.27 0.8 0.3
  0.8 0.8 0
end
";

fn read(deck: &str) -> Result<Scene, raytrace::deck::DeckError> {
    initialize(deck, "t.deck", Path::new("."), Fidelity::Thesis)
}

#[track_caller]
fn error(deck: &str) -> String {
    match read(deck) {
        Ok(_) => panic!("the deck was read:\n{deck}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn blob_and_patch_are_read() {
    let s = read(&format!("{HEAD}{BLOB}{PATCH}")).unwrap();
    assert_eq!(s.objects.len(), 2);
    let (blob, patch) = (&s.objects[0], &s.objects[1]);
    assert_eq!((blob.class, patch.class), (PrimitiveClass::Blob, PrimitiveClass::Patch));
    let Shape::Blob(b) = &blob.shape else { panic!("a blob") };
    assert_eq!(b.threshold, 0.5);
    assert_eq!(b.components.len(), 3);
    assert_eq!(b.components[2].centre, DVec3::new(0.0, 0.0, 0.5));
    assert_eq!((b.components[2].radius, b.components[2].strength), (0.7, 1.5));
    // The bounding radius reaches the farthest sphere: |(±0.5, 0, 0)| + 0.9.
    assert_eq!(blob.radius, 1.4);
    assert_eq!(blob.sphereo, DVec3::new(-1.0, 0.0, 0.5));
    let Shape::Patch(p) = &patch.shape else {
        panic!("a patch")
    };
    assert_eq!(p.points[0], DVec3::new(-0.8, -0.8, 0.0));
    assert_eq!(p.points[5], DVec3::new(-0.27, -0.27, 1.0));
    assert_eq!(p.points[15], DVec3::new(0.8, 0.8, 0.0));
    assert!((patch.radius - (0.8f64 * 0.8 + 0.8 * 0.8).sqrt()).abs() < 1e-12);
}

#[test]
fn bad_blobs_are_refused_where_they_go_wrong() {
    let cases = [
        (
            "blob b red at 0 0 0 threshold 0.5\nend\n",
            "t.deck:6:1: blob 'b': a blob needs at least one component 'X Y Z RADIUS STRENGTH'",
        ),
        (
            "blob b red at 0 0 0 threshold 0.5\n 0 0 0 0 1\nend\n",
            "t.deck:6:8: blob 'b': expected a number in 1e-7..1e7 for RADIUS, found '0'",
        ),
        (
            "blob b red at 0 0 0 threshold 0.5\n 0 0 0 -2 1\nend\n",
            "t.deck:6:8: blob 'b': expected a number in 1e-7..1e7 for RADIUS, found '-2'",
        ),
        (
            "blob b red at 0 0 0 threshold 0\n 0 0 0 1 1\nend\n",
            "t.deck:5:31: blob 'b': expected a number in 1e-7..1e7 after 'threshold', found '0'",
        ),
        (
            "blob b red at 0 0 0 threshold -1\n 0 0 0 1 1\nend\n",
            "t.deck:5:31: blob 'b': expected a number in 1e-7..1e7 after 'threshold', found '-1'",
        ),
        (
            "blob b red at 0 0 0\n 0 0 0 1 1\nend\n",
            "t.deck:5:20: blob 'b': expected 'threshold', found end of line",
        ),
        (
            "blob b red at 0 0 0 threshold 1\n 0 0 0 1\nend\n",
            "t.deck:6:9: blob 'b': expected a number for STRENGTH, found end of line",
        ),
        (
            "blob b red at 0 0 0 threshold 1\n 0 0 0 1 1 7\nend\n",
            "t.deck:6:12: blob 'b': expected end of line after the component 'X Y Z RADIUS STRENGTH', found '7'",
        ),
        (
            "blob b red at 0 0 0 threshold 1\n 0 0 0 1 2e7\nend\n",
            "t.deck:6:10: blob 'b': expected a number in -1e7..1e7 for STRENGTH, found '2e7'",
        ),
        // The next record where the blob's `end` belongs.
        (
            "blob b red at 0 0 0 threshold 1\n 0 0 0 1 1\nsphere s red at 0 0 0 radius 1\n",
            "t.deck:7:1: blob 'b': expected a component 'X Y Z RADIUS STRENGTH' or 'end', found 'sphere'",
        ),
    ];
    for (blob, want) in cases {
        assert_eq!(error(&format!("{HEAD}{blob}")), want, "{blob}");
    }
    // 61 components: an error at the 61st.
    let many: String = (0..61).map(|k| format!(" {k} 0 0 1 1\n")).collect();
    assert_eq!(
        error(&format!("{HEAD}blob b red at 0 0 0 threshold 1\n{many}end\n")),
        "t.deck:66:2: blob 'b': more than 60 components: a blob has at most 60"
    );
}

#[test]
fn bad_patches_are_refused_where_they_go_wrong() {
    let rows = |n: usize| -> String { (0..n).map(|k| format!(" {k} 0 0\n")).collect() };
    assert_eq!(
        error(&format!("{HEAD}patch p red at 0 0 0\n{}end\n", rows(15))),
        "t.deck:21:1: patch 'p': a patch needs 16 control points (4 rows of 4), found 15"
    );
    assert_eq!(
        error(&format!("{HEAD}patch p red at 0 0 0\n{}end\n", rows(17))),
        "t.deck:22:2: patch 'p': more than 16 control points: a patch has 4 rows of 4"
    );
    // The 17th point on the line of the 16th.
    assert_eq!(
        error(&format!("{HEAD}patch p red at 0 0 0\n{} 1 1 1 2 2 2\nend\n", rows(15))),
        "t.deck:21:8: patch 'p': more than 16 control points: a patch has 4 rows of 4"
    );
    // A point split over two lines.
    assert_eq!(
        error(&format!("{HEAD}patch p red at 0 0 0\n 1 2\n 3\nend\n")),
        "t.deck:6:5: patch 'p': expected a number for a control point's X Y Z, found end of line"
    );
    // The next record where the patch's `end` belongs.
    assert_eq!(
        error(&format!(
            "{HEAD}patch p red at 0 0 0\n{}sphere s red at 0 0 0 radius 1\n",
            rows(16)
        )),
        "t.deck:22:1: patch 'p': expected a control point 'X Y Z' or 'end', found 'sphere'"
    );
    assert_eq!(
        error(&format!("{HEAD}patch p red at 0 0 0 axis x\n{}end\n", rows(16))),
        "t.deck:5:22: patch 'p': expected end of line, found 'axis'"
    );
}

/// A sweep (lines 19–24 after BLOB and PATCH) to pair with the others.
const SWEEP: &str = "\
sweep wave red translation bspline at 0 0 0 length 1
  1 0
  0 1
  -1 0
  0 -1
end
";

#[test]
fn a_keyframe_pairs_only_shapes_of_one_kind() {
    let base = format!("{HEAD}{BLOB}{PATCH}{SWEEP}");
    let blob2 = "blob body2 red at 0 0 0 threshold 0.5\n 0 0 0 1 1\nend\n";
    let cases = [
        (
            "keyframe body dome\n",
            "t.deck:25:15: keyframe 'body': 'dome' is a patch but 'body' is a blob: key shapes must be of one class",
        ),
        (
            "keyframe dome body\n",
            "t.deck:25:15: keyframe 'dome': 'body' is a blob but 'dome' is a patch: key shapes must be of one class",
        ),
        (
            "keyframe body wave\n",
            "t.deck:25:15: keyframe 'body': 'wave' is a translation sweep but 'body' is a blob: key shapes must be of one class",
        ),
        (
            "keyframe wave dome\n",
            "t.deck:25:15: keyframe 'wave': 'dome' is a patch but 'wave' is a translation sweep: key shapes must be of one class",
        ),
    ];
    for (line, want) in cases {
        assert_eq!(error(&format!("{base}{line}")), want);
    }
    // Blobs go with blobs, but take no expander.
    assert!(read(&format!("{base}{blob2}keyframe body body2\n")).is_ok());
    assert_eq!(
        error(&format!("{base}{blob2}keyframe body body2 expander burtnyk\n")),
        "t.deck:28:21: keyframe 'body': an expander matches the segments of sweep contours; blobs are matched point by point"
    );
}

/// A deck error in a blob: exit status 2, FILE:LINE:COLUMN, nothing written.
#[test]
fn a_bad_blob_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("bad.deck");
    std::fs::write(&deck, format!("{HEAD}blob b red at 0 0 0 threshold 1\nend\n")).unwrap();
    let out = dir.path().join("bad.ras");
    let run = raytrace_command().arg(&deck).arg("-o").arg(&out).output().unwrap();
    assert_eq!(run.status.code(), Some(2));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("bad.deck:6:1: blob 'b'"), "{err}");
    assert!(!out.exists());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
}

fn opts(solver: Solver) -> Options {
    Options {
        solver,
        ..Options::default()
    }
}

/// Key shapes that are one shape render as that shape: in either
/// fidelity the in-between is the key shape to the bit at every time
/// (the shutter's and the listing's times past it, erratum 2); a pair of
/// two identical blobs, or patches, at one place renders the bytes of the
/// one at rest with either solver (thesis fidelity: the listing's
/// `difference`, erratum 4, moves a pair that stands still), and a pair
/// at two places the colours of the one shape with the motion from the
/// first place to the second.
#[test]
fn identical_key_shapes_render_as_the_shape_alone() {
    let twice = |record: &str, name: &str, at: &str, to: &str| {
        let second = record.replacen(name, &format!("{name}2"), 1).replacen(at, to, 1);
        format!("{HEAD}{record}{second}keyframe {name} {name}2\n")
    };
    let blob_at = "at -1 0 0.5";
    let patch_at = "at 1.2 0 0";
    let cases = [(BLOB, "body", blob_at), (PATCH, "dome", patch_at)];
    for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
        for (record, name, at) in cases {
            let deck = twice(record, name, at, "at 0.3 -0.2 0.9");
            let scene = initialize(&deck, "t.deck", Path::new("."), fidelity).unwrap();
            let key = scene.objects[0].shape.clone();
            let o = Options {
                fidelity,
                ..Options::default()
            };
            let prepared = Prepared::new(scene, o).unwrap();
            for t in [0.0, 0.1, 0.37, 0.5, 0.99, 1.0, 1.2, 1.5] {
                assert!(
                    prepared.still_at(t).scene().objects[0].shape == key,
                    "{name} {fidelity:?} at {t}"
                );
            }
        }
    }
    for solver in [Solver::Laguerre, Solver::Robust] {
        let render_of = |deck: &str| render_still(&read(deck).unwrap(), &opts(solver)).raster;
        for (record, name, at) in cases {
            let alone = render_of(&format!("{HEAD}{record}"));
            assert!(render_of(&twice(record, name, at, at)) == alone, "{name} {solver:?}");
        }
    }
    // Moving: the colours of the motion record from the first place to
    // the second.
    for (record, name, at, to) in [
        (BLOB, "body", blob_at, "at -0.4 0.3 0.8"),
        (PATCH, "dome", patch_at, "at 0.7 -0.2 0.4"),
    ] {
        let place = to.trim_start_matches("at ");
        let moving = read(&format!("{HEAD}{record}motion {name} to {place}\n")).unwrap();
        let pair = read(&twice(record, name, at, to)).unwrap();
        let a = render_still(&moving, &Options::default()).colours;
        let b = render_still(&pair, &Options::default()).colours;
        let worst = a
            .iter()
            .zip(&b)
            .map(|(x, y)| (*x - *y).abs().max_element())
            .fold(0.0, f64::max);
        assert!(worst < 1e-9, "{name}: {worst}");
    }
}

/// The deck of §6.2 (a blob and a patch deforming while they move,
/// blurred) renders the same bytes for any number of threads and with
/// each structure over the objects or none.
#[test]
fn the_same_image_for_any_threads_and_accel() {
    let src = std::fs::read_to_string(common::decks().join("sec6_2.deck")).unwrap();
    let mut scene = initialize(&src, "sec6_2.deck", common::decks(), Fidelity::Thesis).unwrap();
    scene.resize(40, 40, 2);
    let mut images = Vec::new();
    for accel in [Accel::None, Accel::Bvh, Accel::Octree] {
        for threads in [1, 3] {
            let prepared = Prepared::new(
                scene.clone(),
                Options {
                    accel,
                    ..Options::default()
                },
            )
            .unwrap();
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            images.push(pool.install(|| render(&prepared, &Request::STILL).unwrap().raster));
        }
    }
    for (k, image) in images.iter().enumerate() {
        assert!(image == &images[0], "image {k}");
    }
    let distinct: std::collections::HashSet<_> = images[0].pixels.iter().collect();
    assert!(distinct.len() > 50, "{} colours", distinct.len());
}

/// Numbers at the ends of the deck's ranges: components of radius 1e-7
/// and 1e7, strengths of ±1e7, a threshold of 1e-7; patches 1e7 across
/// and 1e-7 across, far out: every pixel's colour is a number, with
/// either solver, at rest and deforming.
#[test]
fn huge_and_tiny_numbers_render_without_nan() {
    let deck = format!(
        "{HEAD}\
blob tiny red at 0 0 0 threshold 1e-7
  0 0 0 1e-7 1e7
  1e-7 0 0 1e-7 -1e7
end
blob huge red at 0 0 -1e7 threshold 1e-7
  1e7 0 0 1e7 1e7
  -1e7 0 0 1e7 1
  0 0 0 1e7 -1e7
end
blob far red at 1e7 1e7 1e7 threshold 1e7
  -1e7 -1e7 -1e7 1e7 1e7
end
patch wide red at 0 0 -1
  -1e7 -1e7 0  -3e6 -1e7 1e7  3e6 -1e7 1e7  1e7 -1e7 0
  -1e7 -3e6 0  -3e6 -3e6 -1e7  3e6 -3e6 1e7  1e7 -3e6 0
  -1e7 3e6 0  -3e6 3e6 1e7  3e6 3e6 -1e7  1e7 3e6 0
  -1e7 1e7 0  -3e6 1e7 1e7  3e6 1e7 1e7  1e7 1e7 0
end
patch small red at 0.5 0 0.5
  0 0 0  1e-7 0 0  2e-7 0 0  3e-7 0 0
  0 1e-7 0  1e-7 1e-7 1e-7  2e-7 1e-7 0  3e-7 1e-7 0
  0 2e-7 0  1e-7 2e-7 0  2e-7 2e-7 1e-7  3e-7 2e-7 0
  0 3e-7 0  1e-7 3e-7 0  2e-7 3e-7 0  3e-7 3e-7 0
end
patch flat red at -0.5 0 0.5
  0 0 0  0 0 0  0 0 0  0 0 0
  0 0 0  0 0 0  0 0 0  0 0 0
  0 0 0  0 0 0  0 0 0  0 0 0
  0 0 0  0 0 0  0 0 0  0 0 0
end
blob tiny2 red at 0 0 0 threshold 1e7
  1e7 1e7 1e7 1e-7 1
end
keyframe tiny tiny2
patch flat2 red at 1e7 -1e7 1e7
  0 0 0  0 0 0  0 0 0  0 0 0
  0 0 0  0 0 0  0 0 0  0 0 0
  0 0 0  0 0 0  0 0 0  0 0 0
  0 0 0  0 0 0  0 0 0  1e7 1e7 1e7
end
keyframe flat flat2
"
    );
    let scene = read(&deck).unwrap();
    for solver in [Solver::Laguerre, Solver::Robust] {
        let r = render_still(&scene, &opts(solver));
        assert_eq!(r.nonfinite, 0, "{solver:?}");
        assert!(r.colours.iter().all(|c| c.is_finite()), "{solver:?}");
    }
}

/// The hierarchy bounds a deforming blob or patch by its swept components'
/// spheres or control hull (`Moving::swept_bounds`), tighter than its
/// origin's box widened by its radius, and a part of the shutter by a box
/// within the whole's: sec6_2.deck's two chains.
#[test]
fn the_hierarchy_bounds_blobs_and_patches_by_their_swept_shapes() {
    let src = std::fs::read_to_string(common::decks().join("sec6_2.deck")).unwrap();
    let scene = initialize(&src, "sec6_2.deck", common::decks(), Fidelity::Thesis).unwrap();
    let prepared = Prepared::new(scene, Options::default()).unwrap();
    let (objects, moving) = (&prepared.scene().objects, prepared.moving());
    let volume = |b: &raytrace::types::BoundingBox| (b.xmax - b.xmin) * (b.ymax - b.ymin) * (b.zmax - b.zmin);
    let within = |a: &raytrace::types::BoundingBox, b: &raytrace::types::BoundingBox| b.union(a) == *b;
    let whole = raytrace::motion::object_boxes(objects, moving, 0.0, 1.0, Fidelity::Thesis);
    let part = raytrace::motion::object_boxes(objects, moving, 0.25, 0.5, Fidelity::Thesis);
    let mut chains = 0;
    for m in moving.iter().filter(|m| m.key_chain().is_some()) {
        chains += 1;
        let i = m.object;
        let swept = m.swept_bounds(0.0, 1.0).expect("a chain of blobs or patches");
        let loose = m
            .centre_bounds(&objects[i], 0.0, 1.0, Fidelity::Thesis)
            .widened(objects[i].radius);
        assert!(
            within(&swept, &whole[i]) && within(&whole[i], &swept.widened(1e-6)),
            "{}",
            objects[i].name
        );
        assert!(
            volume(&whole[i]) < 0.8 * volume(&loose),
            "{}: no tighter than the sphere's",
            objects[i].name
        );
        assert!(within(&part[i], &whole[i]), "{}", objects[i].name);
        assert!(volume(&part[i]) < volume(&whole[i]), "{}", objects[i].name);
    }
    assert_eq!(chains, 2);
}

//! The listing/thesis branches that live between the units: the class
//! box of erratum 9 on a whole scene, `do34`'s records (D15), the pattern
//! table (D9), the screen position (D5), one object of each kind moving
//! (the `paper` flag), and the listing's own lines in the `--debug` log.
//! Each test fails when its branch takes the other fidelity's arm.

mod common;

use raytrace::drt::{default_pattern, TimeTable};
use raytrace::options::*;
use raytrace::paper::{do34, widen_tbox, Hermite, PaperChain};
use raytrace::raytrace::{debug_log, key_frame_chains, render, Camera, Prepared, Request};
use raytrace::scene::*;
use raytrace::shapes::prepare_caches;
use raytrace::types::*;

fn opts(fidelity: Fidelity) -> Options {
    Options {
        fidelity,
        ..Options::default()
    }
}

fn read_prepared(deck: &str, fidelity: Fidelity) -> Prepared {
    let scene = raytrace::deck::initialize(deck, "test.deck", common::decks(), fidelity).unwrap();
    common::prepare(scene, opts(fidelity))
}

fn read(deck: &str, fidelity: Fidelity) -> Scene {
    read_prepared(deck, fidelity).scene().clone()
}

fn sweep_box(obj: &ObjectRecord) -> BoundingBox {
    match &obj.shape {
        Shape::Sweep(sw) => sw.bbox,
        _ => panic!("{} is not a sweep", obj.name),
    }
}

const HEAD: &str = "view eye 0 -12 0  look 0 0 0  screen 4  distance 5
image 8 8  mask 1
background 0 0 0
surface s opaque  color 1 1 1  ka 1 kd 0 ks 0 kt 0
";

/// A translation sweep, the unit square's corners as B-spline points.
const TA: &str = "sweep ta s translation bspline at 0 0 0 length 1
 1 1
 -1 1
 -1 -1
 1 -1
end
";

/// Three pairs (translation, conic, rotation) and a translation sweep and
/// a conic sweep of their own.
const BOXES: &str = "
sweep tb s translation bspline at 1 0 0 length 1
 2 2
 -2 2
 -2 -2
 2 -2
end
keyframe ta tb expander burtnyk
sweep ca s conic bspline at 0 0 0 length 1 scale 0.5
 1 1
 -1 1
 -1 -1
 1 -1
end
sweep cb s conic bspline at 0 0 0 length 1 scale 0.5
 1.5 1
 -1 1.5
 -1 -1
 1 -1
end
keyframe ca cb
sweep ra s rotation bspline at 0 0 0
 1 0
 2 0
 2 1
 1 1
end
sweep rb s rotation bspline at 0 0 0
 1.5 0
 3 0
 3 1
 1.5 1
end
keyframe ra rb
sweep lone s translation bspline at 0 3 0 length 1
 0.5 0.5
 -0.5 0.5
 -0.5 -0.5
 0.5 -0.5
end
sweep cone s conic bspline at 0 -3 0 length 1 scale 2
 0.5 0.5
 -0.5 0.5
 -0.5 -0.5
 0.5 -0.5
end
";

/// Erratum 9: the listing widens the one `tbox` by 2 for every pair
/// (`tbox.xmax := tbox.xmax+2; …`, OCR 2439–2442), whatever the pair's
/// class: every translation sweep's box grows by 2·3 in x and y, the conic
/// and rotation boxes (`cbox`, `rbox`) do not. Each in-between object uses
/// its class's box, and `Hermite` bounds segment i by `p1u[i].max + 2`,
/// `p1u[i].min − 2`.
#[test]
fn erratum_9_tbox_widened_by_2_for_every_pair() {
    let deck = format!("{HEAD}{TA}{BOXES}");
    let listing = read(&deck, Fidelity::Listing);
    // The class boxes before goahead: `spline`'s alone.
    let mut spline_only = raytrace::deck::initialize(&deck, "test.deck", common::decks(), Fidelity::Listing).unwrap();
    raytrace::shapes::sweep::prepare_sweeps(&mut spline_only, Fidelity::Listing);
    for (obj, before) in listing.objects.iter().zip(&spline_only.objects) {
        let (got, want) = (sweep_box(obj), sweep_box(before));
        match obj.class {
            PrimitiveClass::Translation => {
                assert_eq!(got.xmax, want.xmax + 6.0, "{}", obj.name);
                assert_eq!(got.xmin, want.xmin - 6.0, "{}", obj.name);
                assert_eq!(got.ymax, want.ymax + 6.0, "{}", obj.name);
                assert_eq!(got.ymin, want.ymin - 6.0, "{}", obj.name);
                assert_eq!((got.zmin, got.zmax), (want.zmin, want.zmax), "{}", obj.name);
            }
            _ => assert_eq!(got, want, "{}", obj.name),
        }
    }
    // The thesis widens nothing.
    let thesis = read(&deck, Fidelity::Thesis);
    let mut own = raytrace::deck::initialize(&deck, "test.deck", common::decks(), Fidelity::Thesis).unwrap();
    raytrace::shapes::sweep::prepare_sweeps(&mut own, Fidelity::Thesis);
    for (obj, before) in thesis.objects.iter().zip(&own.objects) {
        assert_eq!(sweep_box(obj), sweep_box(before), "{}", obj.name);
    }
    // widen_tbox itself, once more on the prepared listing scene: 2 per pair.
    let mut again = listing.clone();
    widen_tbox(&mut again, Fidelity::Listing);
    assert_eq!(
        sweep_box(&again.objects[0]).xmax,
        sweep_box(&listing.objects[0]).xmax + 6.0
    );
    widen_tbox(&mut again, Fidelity::Thesis);
    assert_eq!(
        sweep_box(&again.objects[0]).xmax,
        sweep_box(&listing.objects[0]).xmax + 6.0
    );
    // The bounds every ray takes from the box are kept by the caches made
    // once the boxes are final: for the widened boxes; those made before
    // the widening are for the old boxes (and would be passed over).
    let (before, after) = (prepare_caches(&listing), prepare_caches(&again));
    for (i, obj) in again.objects.iter().enumerate() {
        if let Shape::Sweep(sw) = &obj.shape {
            assert!(
                after[i]
                    .as_ref()
                    .is_some_and(|c| c.sweep().is_some_and(|c| c.fits(obj.class, sw))),
                "{}",
                obj.name
            );
            let widened = obj.class == PrimitiveClass::Translation;
            assert_eq!(
                before[i]
                    .as_ref()
                    .is_some_and(|c| c.sweep().is_some_and(|c| c.fits(obj.class, sw))),
                !widened,
                "{}",
                obj.name
            );
        }
    }

    let chains = key_frame_chains(&listing, Fidelity::Listing).unwrap();
    assert_eq!(chains.len(), 3);
    for (k, chain) in &chains {
        let first = &listing.objects[listing.keyframes[*k].first];
        let pair = &chain.pairs()[0];
        // The in-between uses its class's box: FIRST's box as prepared.
        assert_eq!(pair.bbox, sweep_box(first), "{}", first.name);
        let mut out = pair.scratch();
        for t in [0.3, 0.7] {
            Hermite(pair, t, &mut out);
            assert_eq!(out.bbox, pair.bbox, "{}: Hermite at {t}", first.name);
            for i in 1..=pair.snu {
                assert_eq!(out.u[i - 1].max, pair.p1u[i].max + 2.0);
                assert_eq!(out.u[i - 1].min, pair.p1u[i].min - 2.0);
                assert_eq!(out.v[i - 1].max, pair.p1v[i].max + 2.0);
                assert_eq!(out.v[i - 1].min, pair.p1v[i].min - 2.0);
            }
        }
        for t in [0.0, 1.0] {
            do34(t, pair, &mut out);
            assert_eq!(out.bbox, pair.bbox, "{}: do34 at {t}", first.name);
        }
    }
    // The rotation pair's box is `rbox`: the radius range min U … max U in
    // x, not ±max |U|.
    let rotation = listing.objects.iter().find(|o| o.name == "ra").unwrap();
    let rb = sweep_box(rotation);
    assert!(rb.xmin > 0.5 && rb.xmax < 3.5, "{rb:?}");
    // The thesis's rotation pair: ±(largest radius).
    let tchains = key_frame_chains(&thesis, Fidelity::Thesis).unwrap();
    let tb = tchains[2].1.pairs()[0].bbox;
    assert!(tb.xmin < -2.0 && tb.xmax > 2.0, "{tb:?}");
}

/// D15: `do34` copies `u[i] := p3u[int][i]` as stored in the listing (the
/// pieces of a cut segment keep `first`, `last`); the thesis writes each
/// piece as the same curve on [0, 1]. `PaperChain::inbetween`, which feeds
/// the sweep intersection, gives [0, 1] in both, the same curve.
#[test]
fn d15_do34_holds_the_listing_records() {
    let deck = format!(
        "{HEAD}{TA}sweep tb s translation bspline at 1 0 0 length 1
 2 2
 0 3
 -2 2
 -3 0
 -2 -2
 0 -3
 2 -2
 3 0
 2.5 1
 1 2.5
end
keyframe ta tb expander burtnyk
"
    );
    let curve = |c: &Coeff, s: f64| {
        let t = c.first + s * (c.last - c.first);
        ((c.a * t + c.b) * t + c.c) * t + c.d
    };
    let mut seen = Vec::new();
    for fidelity in [Fidelity::Listing, Fidelity::Thesis] {
        let scene = read(&deck, fidelity);
        let chains = key_frame_chains(&scene, fidelity).unwrap();
        let chain: &PaperChain = &chains[0].1;
        let pair = &chain.pairs()[0];
        let mut out = pair.scratch();
        do34(0.0, pair, &mut out);
        let cut = (1..=pair.snu).filter(|&i| pair.p3u[i].first != 0.0).count();
        assert!(cut > 0, "4 segments to 10 cut some");
        for i in 1..=pair.snu {
            let (got, stored) = (out.u[i - 1], pair.p3u[i]);
            match fidelity {
                Fidelity::Listing => assert_eq!(got, stored, "segment {i}"),
                Fidelity::Thesis => {
                    assert_eq!((got.first, got.last), (0.0, 1.0));
                    for s in [0.0, 0.4, 1.0] {
                        assert!((curve(&got, s) - curve(&stored, s)).abs() < 1e-12);
                    }
                }
            }
        }
        let mut fed = pair.scratch();
        chain.inbetween(0.0, &mut fed);
        for i in 1..=pair.snu {
            let c = fed.u[i - 1];
            assert_eq!((c.first, c.last), (0.0, 1.0), "{fidelity:?} segment {i}");
            for s in [0.0, 0.4, 1.0] {
                assert!((curve(&c, s) - curve(&pair.p3u[i], s)).abs() < 1e-12);
            }
        }
        seen.push(fed.u.clone());
    }
    assert_eq!(seen[0].len(), seen[1].len());
}

/// D9: without a `pattern` record the listing reads the top-left M×M of
/// Fig. 2.33 as printed (`row := (scancol mod masksize)+1`, `col :=
/// (scanline mod masksize)+1`, `time := pattern[row,col]*0.1`); the thesis
/// takes a permutation of the M² strata.
#[test]
fn d9_the_listing_reads_the_corner_of_fig_2_33() {
    assert_eq!(default_pattern(2, Fidelity::Listing), [[7, 11], [4, 15]]);
    assert_eq!(default_pattern(1, Fidelity::Listing), [[7]]);
    assert_eq!(
        default_pattern(3, Fidelity::Listing),
        [[7, 11, 3], [4, 15, 13], [10, 1, 8]]
    );
    assert_eq!(default_pattern(2, Fidelity::Thesis), [[0, 2], [3, 1]]);
    assert_eq!(default_pattern(1, Fidelity::Thesis), [[0]]);
    let t = TimeTable::with_default_pattern(2, 0, Fidelity::Listing);
    // (scanline, scancol): row from scancol, column from scanline (erratum 2).
    let at = |line, col| (t.time(line, col, 0) * 10.0).round() as u32;
    assert_eq!([at(2, 2), at(1, 2), at(2, 1), at(1, 1)], [7, 11, 4, 15]);
    assert!((t.time(2, 2, 0) - 0.7).abs() < 1e-15);
}

/// The listing indexes a deck's table by scanline and scancol mod
/// masksize: a larger table is read at its top-left corner in listing
/// fidelity and refused in thesis fidelity; a smaller one is refused in
/// both.
#[test]
fn a_pattern_larger_than_the_mask() {
    let p = PatternRecord {
        pos: Pos::default(),
        m: 4,
        values: vec![vec![3, 1, 9, 9], vec![0, 2, 9, 9], vec![9; 4], vec![9; 4]],
    };
    let t = TimeTable::new(2, Some(&p), 0, Fidelity::Listing).unwrap();
    let at = |line, col| (t.time(line, col, 0) * 10.0).round() as u32;
    assert_eq!([at(2, 2), at(1, 2), at(2, 1), at(1, 1)], [3, 1, 0, 2]);
    assert!(TimeTable::new(2, Some(&p), 0, Fidelity::Thesis).is_err());
    for fidelity in [Fidelity::Listing, Fidelity::Thesis] {
        assert!(TimeTable::new(8, Some(&p), 0, fidelity).is_err());
        assert!(TimeTable::new(4, Some(&p), 0, fidelity).is_ok());
    }
}

/// D5: the listing puts subpixel k at `k/(halfvirtualx*2-1)` of the
/// window (OCR 3114–3117), the thesis at the centre of the k-th of N
/// cells; both centre a window `screensize` wide on the line of sight.
#[test]
fn d5_where_a_subpixel_lies() {
    let mut s = common::scene(); // eye (0, −10, 0) looking along +y, screen 4 at 5
    s.image = ImageSpec {
        width: 8,
        height: 8,
        masksize: 2,
        aliasing: 0.0,
    };
    let n = 16.0;
    for (fidelity, place) in [
        (
            Fidelity::Listing,
            Box::new(|k: f64| k / (n - 1.0)) as Box<dyn Fn(f64) -> f64>,
        ),
        (Fidelity::Thesis, Box::new(|k: f64| (k - 0.5) / n)),
    ] {
        let cam = Camera::new(&s, fidelity);
        for (col, line) in [(0.0, 1.0), (1.0, 1.0), (5.0, 9.0), (16.0, 16.0)] {
            let d = cam.ray(col, line, 0.0, 0.0).dir;
            let on_screen = d * (5.0 / d.y);
            let want = DVec3::new((place(col) - 0.5) * 4.0, 5.0, (0.5 - place(line)) * 4.0);
            assert!(
                (on_screen - want).length() < 1e-12,
                "{fidelity:?} ({col}, {line}): {on_screen}"
            );
        }
    }
}

/// The listing tests one `paper` flag for the whole scene and passes the
/// motion-table index as the pair (DEVIATIONS D23); the
/// port gives each moving object its own branch, in both fidelities: in a
/// deck with a key-frame pair and a moving sphere, the sphere keeps
/// erratum 3's motion (x + 6t) and the in-between its own pair's `diff`.
#[test]
fn a_deck_mixing_both_kinds_of_moving_object() {
    let deck = format!(
        "{HEAD}sphere ball s at 0 0 2 radius 0.5
motion ball to 1 0 2
{TA}sweep tb s translation bspline at 2 0 0 length 1
 1 1
 -1 1
 -1 -1
 1 -1
end
keyframe ta tb
"
    );
    let prepared = read_prepared(&deck, Fidelity::Listing);
    let (scene, still) = (prepared.scene(), prepared.still_at(0.5));
    let still = still.scene();
    let ball = scene.objects.iter().position(|o| o.name == "ball").unwrap();
    let ta = scene.objects.iter().position(|o| o.name == "ta").unwrap();
    assert_eq!(still.objects[ball].sphereo, DVec3::new(3.0, 0.0, 2.0));
    // diff = (2, 2 − 0, 2 − 0) with erratum 4's dif.y := po2.x - po1.y.
    assert_eq!(still.objects[ta].sphereo, DVec3::new(1.0, 1.0, 1.0));
    assert!(matches!(&still.objects[ball].shape, Shape::Sphere));
}

/// Erratum 8 and the listing's `debugf`: `goahead`'s lines go to the
/// `--debug` log before the scanlines: `expanding` / `expanding2`, the
/// expanders' messages and `path : a b c d` for every segment start.
#[test]
fn the_listing_lines_of_goahead_in_the_debug_log() {
    // FIRST: a Bezier pentagon with straight sides; LAST: a square with two
    // petals of length 0 at its start (tests/paper.rs, impossible_pair).
    let third = |p: [f64; 2], q: [f64; 2]| {
        (0..3)
            .map(|k| {
                let f = k as f64 / 3.0;
                format!(" {} {}\n", p[0] + (q[0] - p[0]) * f, p[1] + (q[1] - p[1]) * f)
            })
            .collect::<String>()
    };
    let polygon = |c: &[[f64; 2]]| {
        (0..c.len())
            .map(|i| third(c[i], c[(i + 1) % c.len()]))
            .collect::<String>()
    };
    let first = polygon(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
    let last = polygon(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])
        + " 0 0\n -1 -0.5\n -0.5 -1\n 0 0\n -1 0.5\n -0.5 1\n";
    for (expander, lines) in [
        (
            "arclength",
            vec![
                "expanding2",
                "It is impossible (segment 2)",
                " error : plus. nu:-1",
                " error : more2. n2 <> (k-1) 6 4",
            ],
        ),
        ("burtnyk", vec!["expanding", " equal "]),
    ] {
        let deck = format!(
            "{HEAD}sweep five s translation bezier at 0 0 0 length 1\n{first}end\nsweep petals s translation bezier at 0 0 0 length 1\n{last}end\nkeyframe five petals expander {expander}\n"
        );
        let prepared = read_prepared(&deck, Fidelity::Listing);
        let out = render(&prepared, &Request::STILL).unwrap();
        let log = debug_log(&prepared, &out);
        let got: Vec<&str> = log.lines().collect();
        assert_eq!(&got[..lines.len()], &lines[..], "{expander}");
        let paths = got.iter().filter(|l| l.starts_with("path : ")).count();
        assert_eq!(paths, 6, "{expander}: one line per segment start");
        // `pathx[1]`: (0, 0, LAST's x − FIRST's x, FIRST's x), three decimals.
        assert_eq!(got[lines.len()], "path : 0.000 0.000 0.000 0.000");
        assert!(got[lines.len() + 6].starts_with(" scanline="));
    }
    // Equal counts: no expander runs, no line of its own.
    let deck = format!(
        "{HEAD}sweep five s translation bezier at 0 0 0 length 1\n{first}end\nsweep same s translation bezier at 1 0 0 length 1\n{first}end\nkeyframe five same\n"
    );
    let prepared = read_prepared(&deck, Fidelity::Thesis);
    let out = render(&prepared, &Request::STILL).unwrap();
    let log = debug_log(&prepared, &out);
    assert_eq!(log.lines().next(), Some("path : 0.000 0.000 1.000 0.000"));
}

//! Key-frame deformation in the renderer: the in-between object of a
//! `keyframe` record as `motionblur`'s `paper = 1` branch draws it.

mod common;
use common::load_deck as load;
use common::{prepare, render_still};
use raytrace::options::*;
use raytrace::raytrace::{key_frame_chains, render, Request};
use raytrace::scene::*;

const KEY_FRAME_DECKS: [&str; 4] = ["fig5_10.deck", "fig5_11.deck", "fig5_12.deck", "nec_morph.deck"];

/// Every key-frame deck prepares in both fidelities; nec_morph's chain of
/// three shapes makes two pairs, the others one.
#[test]
fn key_frame_decks_prepare() {
    for name in KEY_FRAME_DECKS {
        for fidelity in [Fidelity::Thesis, Fidelity::Listing] {
            let prepared = prepare(load(name, fidelity), options(fidelity));
            let chains = key_frame_chains(prepared.scene(), fidelity).unwrap();
            assert_eq!(chains.len(), 1, "{name}");
            let pairs = chains[0].1.pairs().len();
            assert_eq!(pairs, if name == "nec_morph.deck" { 2 } else { 1 }, "{name}");
        }
    }
}

fn options(fidelity: Fidelity) -> Options {
    Options {
        fidelity,
        ..Options::default()
    }
}

/// With one subpixel and a 1×1 pattern table every sample is at t = ½ (the
/// centre of the one stratum): the render equals the still scene with the
/// in-between shape of t = ½ put in by hand.
#[test]
fn render_draws_the_in_between_shape() {
    for name in KEY_FRAME_DECKS {
        let mut scene = load(name, Fidelity::Thesis);
        scene.image = ImageSpec {
            width: 64,
            height: 64,
            masksize: 1,
            aliasing: 0.0,
        };
        scene.blur = None;
        scene.pattern = Some(PatternRecord {
            pos: Pos::default(),
            m: 1,
            values: vec![vec![0]],
        });
        let prepared = prepare(scene.clone(), Options::default());
        let drawn = render(&prepared, &Request::STILL).unwrap().raster;
        // The scene with the in-between object put in at time ½, still.
        let still = prepared.still_at(0.5);
        let by_hand = render(&still, &Request::STILL).unwrap().raster;
        assert_eq!(drawn, by_hand, "{name}");
        // And the object is in the picture: it differs from the floor alone.
        let mut empty = still.scene().clone();
        let first = scene.keyframes[0].first;
        empty.objects.remove(first);
        let floor = render_still(&empty, &Options::default()).raster;
        let differ = drawn.pixels.iter().zip(&floor.pixels).filter(|(a, b)| a != b).count();
        assert!(differ > 50, "{name}: {differ} pixels show the object");
    }
}

/// The in-between contour stays inside the bounding sphere `prepare` gave
/// the object (the renderer culls with it), at 64 times and at points
/// along every segment.
#[test]
fn in_between_contours_stay_in_the_bounding_sphere() {
    for name in KEY_FRAME_DECKS {
        let prepared = prepare(load(name, Fidelity::Thesis), Options::default());
        let scene = prepared.scene();
        let chains = key_frame_chains(scene, Fidelity::Thesis).unwrap();
        let (k, chain) = &chains[0];
        let obj = &scene.objects[scene.keyframes[*k].first];
        let mut contour = chain.scratch();
        for i in 0..64 {
            let t = i as f64 / 63.0;
            chain.inbetween(t, &mut contour);
            for (u, v) in contour.u.iter().zip(&contour.v) {
                for j in 0..=8 {
                    let s = u.first + (u.last - u.first) * j as f64 / 8.0;
                    let uu = ((u.a * s + u.b) * s + u.c) * s + u.d;
                    let vv = ((v.a * s + v.b) * s + v.c) * s + v.d;
                    // A translation sweep reaches z = length; a rotation sweep's
                    // point (U, V) is at radius |U|, height V.
                    let z = contour.length.max(0.0);
                    let far = (uu * uu + vv * vv + z * z).sqrt();
                    assert!(far <= obj.radius, "{name} t={t}: {far} > {}", obj.radius);
                }
            }
        }
    }
}

//! `deck::initialize` on valid decks: every record kind parses to the
//! expected `Scene` values.

use std::path::Path;

use raytrace::deck::initialize;
use raytrace::options::*;
use raytrace::scene::*;
use raytrace::types::*;

/// A deck with every record kind (except `texture`, which needs a raster
/// file), in mixed case and with both comment forms.
const FULL: &str = "\
{ every record of DECK.md;
  a comment spanning lines }
VIEW eye 1 -8 3 Look 0 0 1 SCREEN 3.5 distance 5   (* keywords in any case *)
image 320 200 mask 3 aliasing .5
background 0.1 0.2 0.3
light sun 5 -5 10 1 1 0.9
light Sun 0 0 10 .2 .2 .2
surface red opaque color 1 0 0 ka 0.1 kd 0.7 ks 0.2 kt 0
surface chrome mirrored color 0.8 0.8 0.8 ka 0 kd 0.1 ks 0.9 kt 0
surface glass transparent color 1 1 1 ka 0 kd 0 ks 0.2 kt 0.9 index 1.5 reflect 0.1 ambient 0.5 0.5 0.5
surface lamp light color 4 4 2 ka 1 kd 0 ks 0 kt 0
surface floorsurf OPAQUE color 0.3 0.3 0.3 ka 0.2 kd 0.8 ks 0 kt 0
paint floorsurf floor
paint red floorstar color 0 0 1 scale 2 0.5
sphere ball red at 1 2 3 radius 1.5
rotate ball z 90
block floor floorsurf at 0 0 -0.5 size 20 10 1
cylinder post chrome at 0 0 0 radius 0.5 bottom -1 top 2 axis x
prism wedge glass at 0 0 0 height 2 axis y
  0 0
  { clockwise: stored reversed }
  0 1
  1 0
END
sphere gone red at 0 0 0 radius 1
sweep wave red translation bspline at 0 0 0 length 2
  1 0
  0 1
  -1 0
  0 -1
end
sweep cone red conic bezier at 0 0 0 scale 0 length 3
  1 0
  1 1
  0 1
  -1 0
  -1 -1
  0 -1
end
sweep vase chrome rotation bspline at 0 0 0 axis y
  0 0
  1 0
  1.5 1
  0 2
end
sweep wave2 red translation bspline at 0 0 0 length 2
  2 0
  0 2
  -2 0
  0 -2
end
translate ball 1 1 1
rotate post x 30
rotate post x 60
delete gone
sweep k1 red rotation bspline at 0 0 0
  0 0
  1 0
  1 1
  0 1
end
sweep k2 red rotation bspline at 0 0 1
  0 0
  2 0
  2 1
  0 1
end
sweep k3 red rotation bezier at 0 0 2
  0 0
  1 0
  2 0
  2 1
  1 1
  0 1
end
keyframe wave wave2
keyframe k1 k2 k3 expander burtnyk
motion vase to 1 1 1 turn 0 0 90 via 0 0 1 1 0 1 law smooth
motion ball to 5 5 5
blur 6
pattern 2
  0 3
  2 1
end
";

fn full() -> Scene {
    initialize(FULL, "full.deck", Path::new("."), Fidelity::Thesis).expect("the full deck is valid")
}

/// Where a record of the full deck stands: line `line`, column 1, of
/// full.deck (a position names its file).
fn full_at(line: u32) -> Pos {
    Pos {
        file: "full.deck".into(),
        line,
        column: 1,
    }
}

fn object<'a>(scene: &'a Scene, name: &str) -> &'a ObjectRecord {
    scene
        .objects
        .iter()
        .find(|o| o.name == name)
        .unwrap_or_else(|| panic!("no object {name}"))
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).length() < 1e-12
}

#[test]
fn view_image_background_and_lights() {
    let s = full();
    assert_eq!(
        s.view,
        View {
            eyept: DVec3::new(1.0, -8.0, 3.0),
            lookpt: DVec3::new(0.0, 0.0, 1.0),
            screensize: 3.5,
            scrndistance: 5.0,
        }
    );
    assert_eq!(
        s.image,
        ImageSpec {
            width: 320,
            height: 200,
            masksize: 3,
            aliasing: 0.5,
        }
    );
    assert_eq!(s.backgrnd, DVec3::new(0.1, 0.2, 0.3));
    // Names are case-sensitive: `sun` and `Sun` are two lights.
    assert_eq!(s.lights.len(), 2);
    assert_eq!(s.lights[0].name, "sun");
    assert_eq!(s.lights[0].position, DVec3::new(5.0, -5.0, 10.0));
    assert_eq!(s.lights[0].color, DVec3::new(1.0, 1.0, 0.9));
    assert_eq!(s.lights[1].name, "Sun");
    assert_eq!(s.lights[1].color, DVec3::splat(0.2));
}

#[test]
fn surfaces_with_defaults_paint_and_light_emission() {
    let s = full();
    let names: Vec<&str> = s.surfaces.iter().map(|x| x.name.as_str()).collect();
    assert_eq!(names, ["red", "chrome", "glass", "lamp", "floorsurf"]);
    let red = &s.surfaces[0];
    assert_eq!(red.surface, SurfaceAttribute::Opaque);
    assert_eq!((red.ka, red.kd, red.ks, red.kt), (0.1, 0.7, 0.2, 0.0));
    assert_eq!(red.iobject, red.color, "ambient defaults to color");
    assert_eq!(red.prcntrfl, 0.0, "reflect defaults to 0 unless mirrored");
    assert_eq!(red.index, 1.0);
    assert_eq!(
        red.paint,
        Some(Paint {
            kind: PaintKind::Floorstar,
            lengthx: 2.0,
            lengthy: 0.5,
            color: DVec3::new(0.0, 0.0, 1.0),
        })
    );
    assert_eq!(s.surfaces[1].surface, SurfaceAttribute::Mirrored);
    assert_eq!(s.surfaces[1].prcntrfl, 1.0, "reflect defaults to 1 for mirrored");
    let glass = &s.surfaces[2];
    assert_eq!(glass.surface, SurfaceAttribute::Transparent);
    assert_eq!((glass.index, glass.prcntrfl), (1.5, 0.1));
    assert_eq!(glass.iobject, DVec3::splat(0.5));
    let lamp = &s.surfaces[3];
    assert_eq!(lamp.surface, SurfaceAttribute::Light);
    assert_eq!(lamp.color, DVec3::new(4.0, 4.0, 2.0), "a light surface may exceed 1");
    assert_eq!(
        s.surfaces[4].paint,
        Some(Paint {
            kind: PaintKind::Floor,
            lengthx: 1.0,
            lengthy: 1.0,
            color: DVec3::ONE,
        })
    );
    assert!(s.surfaces.iter().all(|x| x.texture.is_none()));
}

#[test]
fn rotate_and_translate_build_transfm_and_its_inverse() {
    let s = full();
    let ball = object(&s, "ball");
    // At (1,2,3) turned 90 degrees about z: local (1,0,0) lies at (1,3,3);
    // then translated by (1,1,1).
    assert_eq!(ball.sphereo, DVec3::new(2.0, 3.0, 4.0));
    assert!(close(
        ball.transfm.transform_point3(DVec3::X),
        DVec3::new(2.0, 4.0, 4.0)
    ));
    assert_eq!(ball.angle, DVec3::new(0.0, 0.0, 90.0));
    assert_eq!(ball.radius, 1.5);
    assert_eq!(ball.class, PrimitiveClass::Sphere);
    assert_eq!(ball.surface, 0);
    for o in &s.objects {
        let d = (o.inverse * o.transfm - DMat4::IDENTITY).to_cols_array();
        assert!(d.iter().all(|x| x.abs() < 1e-12), "{}: {d:?}", o.name);
    }
}

#[test]
fn an_object_at_1_2_3_turned_90_about_z() {
    let deck = "view eye 0 -10 0 look 0 0 0 screen 1 distance 1\nimage 8 8 mask 1\n\
                surface s opaque color 1 1 1 ka 0 kd 1 ks 0 kt 0\n\
                block b s at 1 2 3 size 1 1 1\nrotate b z 90\n";
    let s = initialize(deck, "t.deck", Path::new("."), Fidelity::Thesis).unwrap();
    let b = &s.objects[0];
    assert_eq!(b.transfm.transform_point3(DVec3::X), DVec3::new(1.0, 3.0, 3.0));
    assert_eq!(b.inverse.transform_point3(DVec3::new(1.0, 3.0, 3.0)), DVec3::X);
    assert_eq!(s.backgrnd, DVec3::ZERO, "background defaults to black");
    assert!(s.blur.is_none() && s.pattern.is_none());
    assert!(s.lights.is_empty() && s.motions.is_empty() && s.keyframes.is_empty());
}

#[test]
fn axis_maps_local_z_onto_the_world_axis() {
    let s = full();
    let post = object(&s, "post");
    // axis x, then turned 30 + 60 degrees about world x: x stays x.
    assert!(close(post.transfm.transform_vector3(DVec3::Z), DVec3::X));
    // local x: onto -z by the axis, then onto +y by the quarter turn about x.
    assert!(close(post.transfm.transform_vector3(DVec3::X), DVec3::Y));
    assert_eq!(post.angle, DVec3::new(90.0, 0.0, 0.0));
    assert_eq!(
        post.shape,
        Shape::Cylinder {
            cylradius: 0.5,
            orient: Axis::X,
            top: 2.0,
            bottom: -1.0,
        }
    );
    assert!((post.radius - (0.25f64 + 4.0).sqrt()).abs() < 1e-15);
    let wedge = object(&s, "wedge");
    assert_eq!(wedge.transfm.transform_vector3(DVec3::Z), DVec3::Y);
    let vase = object(&s, "vase");
    assert_eq!(vase.transfm.transform_vector3(DVec3::Z), DVec3::Y);
}

#[test]
fn block_and_prism_shapes() {
    let s = full();
    let floor = object(&s, "floor");
    assert_eq!(
        floor.shape,
        Shape::Block {
            lengths: DVec3::new(20.0, 10.0, 1.0)
        }
    );
    assert!((floor.radius - (400.0f64 + 100.0 + 1.0).sqrt() / 2.0).abs() < 1e-12);
    let wedge = object(&s, "wedge");
    assert_eq!(
        wedge.shape,
        Shape::Prism {
            orientp: Axis::Y,
            height: 2.0,
            vertex: vec![[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]],
        }
    );
    assert!((wedge.radius - 5f64.sqrt()).abs() < 1e-15);
}

#[test]
fn sweeps() {
    let s = full();
    let Shape::Sweep(wave) = &object(&s, "wave").shape else {
        panic!("wave is a sweep")
    };
    assert_eq!(wave.curve, CurveKind::Bspline);
    assert_eq!(wave.points, vec![[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]]);
    assert_eq!((wave.segment, wave.length, wave.scale), (4, 2.0, 1.0));
    assert_eq!(wave.orientt, Axis::Z);
    assert!(wave.u.is_empty() && wave.v.is_empty());
    assert_eq!(wave.bbox, BoundingBox::default());
    assert!((object(&s, "wave").radius - 5f64.sqrt()).abs() < 1e-15);

    let cone = object(&s, "cone");
    assert_eq!(cone.class, PrimitiveClass::Conic);
    let Shape::Sweep(c) = &cone.shape else {
        panic!("cone is a sweep")
    };
    assert_eq!(
        (c.curve, c.segment, c.length, c.scale),
        (CurveKind::Bezier, 2, 3.0, 0.0)
    );
    assert!((cone.radius - (2.0f64 + 9.0).sqrt()).abs() < 1e-15);

    let vase = object(&s, "vase");
    assert_eq!(vase.class, PrimitiveClass::Rotation);
    let Shape::Sweep(v) = &vase.shape else {
        panic!("vase is a sweep")
    };
    assert_eq!((v.segment, v.length, v.scale, v.orientt), (4, 0.0, 1.0, Axis::Y));
    // The farthest control point is (0, 2).
    assert_eq!(vase.radius, 2.0);
}

#[test]
fn delete_and_keyframe_remove_objects_and_indices_follow() {
    let s = full();
    let names: Vec<&str> = s.objects.iter().map(|o| o.name.as_str()).collect();
    assert_eq!(names, ["ball", "floor", "post", "wedge", "wave", "cone", "vase", "k1"]);
    let lines: Vec<u32> = s.object_pos.iter().map(|p| p.line).collect();
    assert_eq!(lines, [15, 17, 18, 19, 26, 32, 40, 56]);
    assert!(s.object_pos.iter().all(|p| p.column == 1));

    assert_eq!(s.keyframes.len(), 2);
    let k = &s.keyframes[0];
    assert_eq!(s.objects[k.first].name, "wave");
    assert_eq!(k.rest.iter().map(|o| o.name.as_str()).collect::<Vec<_>>(), ["wave2"]);
    assert_eq!(k.expander, Expander::Arclength);
    assert_eq!(k.pos, full_at(76));
    let Shape::Sweep(w2) = &k.rest[0].shape else {
        panic!("wave2 is a sweep")
    };
    assert_eq!(w2.points[0], [2.0, 0.0]);

    let chain = &s.keyframes[1];
    assert_eq!(s.objects[chain.first].name, "k1");
    assert_eq!(
        chain.rest.iter().map(|o| o.name.as_str()).collect::<Vec<_>>(),
        ["k2", "k3"]
    );
    assert_eq!(chain.rest[0].sphereo, DVec3::new(0.0, 0.0, 1.0));
    assert_eq!(chain.expander, Expander::Burtnyk);
}

#[test]
fn motions_blur_and_pattern() {
    let s = full();
    assert_eq!(s.motions.len(), 2);
    let m = &s.motions[0];
    assert_eq!(s.objects[m.object].name, "vase");
    assert_eq!(m.to, DVec3::ONE);
    assert_eq!(m.turn, DVec3::new(0.0, 0.0, 90.0));
    assert_eq!(m.via, Some([DVec3::new(0.0, 0.0, 1.0), DVec3::new(1.0, 0.0, 1.0)]));
    assert_eq!(m.law, Law::Smooth);
    assert_eq!(m.pos, full_at(78));
    let m = &s.motions[1];
    assert_eq!(s.objects[m.object].name, "ball");
    assert_eq!((m.turn, m.via, m.law), (DVec3::ZERO, None, Law::Constant));

    assert_eq!(s.blur, Some(BlurRecord { pos: full_at(80), n: 6 }));
    assert_eq!(
        s.pattern,
        Some(PatternRecord {
            pos: full_at(81),
            m: 2,
            values: vec![vec![0, 3], vec![2, 1]],
        })
    );
}

#[test]
fn the_deck_reads_the_same_in_both_fidelities_when_the_pattern_is_a_permutation() {
    let listing = initialize(FULL, "full.deck", Path::new("."), Fidelity::Listing).unwrap();
    assert_eq!(listing, full());
}

#[test]
fn a_repeated_pattern_value_is_accepted_in_listing_fidelity() {
    // Fig. 2.33 as printed: 10 twice, 9 never (erratum 1).
    let deck = "view eye 0 -10 0 look 0 0 0 screen 1 distance 1\nimage 8 8 mask 2\n\
                pattern 4\n 0 8 2 10\n 12 4 14 6\n 3 11 1 10\n 15 7 13 5\nend\n";
    let s = initialize(deck, "t.deck", Path::new("."), Fidelity::Listing).unwrap();
    assert_eq!(s.pattern.map(|p| p.values[2].clone()), Some(vec![3, 11, 1, 10]));
    assert!(initialize(deck, "t.deck", Path::new("."), Fidelity::Thesis).is_err());
}

#[test]
fn comments_of_both_forms_anywhere() {
    let deck = "(* a\n(* does not nest *)view eye 0 -10 0 {x} look 0 0 0 screen 1 distance 1 { trailing }\n\
                { only a comment }\n\n image(**) 8 8 mask 1 (* multi\nline *)\n";
    let s = initialize(deck, "t.deck", Path::new("."), Fidelity::Thesis).unwrap();
    assert_eq!(s.image.width, 8);
    assert_eq!(s.view.eyept, DVec3::new(0.0, -10.0, 0.0));
}

#[test]
fn default_deck_initializes() {
    let text = include_str!("../legacy_pascal/decks/still_life.deck");
    let s = initialize(
        text,
        "still_life.deck",
        Path::new("legacy_pascal/decks"),
        Fidelity::Thesis,
    )
    .unwrap();
    assert_eq!((s.image.width, s.image.height, s.image.masksize), (256, 256, 2));
    let classes: Vec<PrimitiveClass> = s.objects.iter().map(|o| o.class).collect();
    for c in [
        PrimitiveClass::Sphere,
        PrimitiveClass::Block,
        PrimitiveClass::Cylinder,
        PrimitiveClass::Prism,
    ] {
        assert!(classes.contains(&c), "{c:?}");
    }
    let kinds: Vec<SurfaceAttribute> = s.surfaces.iter().map(|x| x.surface).collect();
    assert!(kinds.contains(&SurfaceAttribute::Mirrored));
    assert!(kinds.contains(&SurfaceAttribute::Transparent));
    assert!(s
        .surfaces
        .iter()
        .any(|x| x.paint.as_ref().map(|p| p.kind) == Some(PaintKind::Floor)));
    assert!(!s.lights.is_empty());
    // Every object but the floor rests on the floor's top (z = 0): its
    // lowest point is at z = 0.
    let floor = s.objects.iter().find(|o| o.name == "floor").unwrap();
    let Shape::Block { lengths } = floor.shape else {
        panic!("the floor is a block")
    };
    assert_eq!(floor.sphereo.z + lengths.z / 2.0, 0.0);
    for o in s.objects.iter().filter(|o| o.name != "floor") {
        let bottom = match &o.shape {
            Shape::Sphere => o.sphereo.z - o.radius,
            Shape::Block { lengths } => o.sphereo.z - lengths.z / 2.0,
            Shape::Cylinder { bottom, .. } => o.sphereo.z + bottom,
            Shape::Prism { .. } => o.sphereo.z,
            Shape::Sweep(_) | Shape::Blob(_) | Shape::Patch(_) => panic!("no sweeps, blobs or patches in still_life"),
        };
        assert!(bottom.abs() < 1e-12, "{} floats at {bottom}", o.name);
    }
    assert!(s.motions.is_empty() && s.keyframes.is_empty());
}

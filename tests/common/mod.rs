//! Scenes built by hand for the tests, without the deck reader.
#![allow(dead_code)] // each test file uses a different part of this module

use raytrace::types::*;

pub fn surface(kind: SurfaceAttribute, color: [f64; 3], ka: f64, kd: f64, ks: f64, kt: f64) -> SurfaceRecord {
    SurfaceRecord {
        name: "s".into(),
        color: DVec3::from_array(color),
        ka,
        kd,
        ks,
        kt,
        iobject: DVec3::from_array(color),
        surface: kind,
        prcntrfl: 1.0,
        index: 1.5,
        paint: None,
        texture: None,
    }
}

pub fn object(name: &str, surface: usize, at: [f64; 3], shape: Shape, radius: f64) -> ObjectRecord {
    let sphereo = DVec3::from_array(at);
    let class = match &shape {
        Shape::Sphere => PrimitiveClass::Sphere,
        Shape::Block { .. } => PrimitiveClass::Block,
        Shape::Cylinder { .. } => PrimitiveClass::Cylinder,
        Shape::Prism { .. } => PrimitiveClass::Prism,
        Shape::Sweep(_) => PrimitiveClass::Translation,
    };
    ObjectRecord {
        name: name.into(),
        class,
        surface,
        transfm: DMat4::from_translation(sphereo),
        inverse: DMat4::from_translation(-sphereo),
        sphereo,
        angle: DVec3::ZERO,
        radius,
        shape,
    }
}

pub fn sphere(name: &str, surface: usize, at: [f64; 3], radius: f64) -> ObjectRecord {
    object(name, surface, at, Shape::Sphere, radius)
}

pub fn block(name: &str, surface: usize, at: [f64; 3], lengths: [f64; 3]) -> ObjectRecord {
    let l = DVec3::from_array(lengths);
    object(name, surface, at, Shape::Block { lengths: l }, l.length() / 2.0)
}

/// An empty scene: eye at (0, −10, 0) looking at the origin, 16×16, 1 subpixel.
pub fn scene() -> Scene {
    Scene {
        view: View {
            eyept: DVec3::new(0.0, -10.0, 0.0),
            lookpt: DVec3::ZERO,
            screensize: 4.0,
            scrndistance: 5.0,
        },
        image: ImageSpec {
            width: 16,
            height: 16,
            masksize: 1,
            aliasing: 0.0,
        },
        backgrnd: DVec3::ZERO,
        lights: vec![],
        surfaces: vec![],
        objects: vec![],
        object_pos: vec![],
        motions: vec![],
        keyframes: vec![],
        blur: None,
        pattern: None,
        film: None,
    }
}

pub fn light(at: [f64; 3], color: [f64; 3]) -> LightRecord {
    LightRecord {
        name: "l".into(),
        position: DVec3::from_array(at),
        color: DVec3::from_array(color),
    }
}

pub fn close(a: DVec3, b: DVec3, eps: f64) -> bool {
    (a - b).abs().max_element() <= eps
}

/// legacy_pascal/decks, where the legacy decks stand.
pub fn decks() -> &'static std::path::Path {
    std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/legacy_pascal/decks"))
}

/// A legacy deck read by `initialize` and set up by `prepare`.
pub fn load_deck(name: &str, fidelity: Fidelity) -> Scene {
    let src = std::fs::read_to_string(decks().join(name)).unwrap();
    let mut scene = raytrace::deck::initialize(&src, name, decks(), fidelity).unwrap();
    let opts = Options {
        fidelity,
        ..Options::default()
    };
    raytrace::raytrace::prepare(&mut scene, &opts).unwrap();
    scene
}

/// A flat (emissive) block 2 wide and `z_size` high moving at constant
/// speed from x = −5 to 5 across a black background, seen head-on through
/// a nearly parallel projection (screen 16 wide at distance 1000), 64 ×
/// `height` pixels of `m`×`m` subpixels, `blur 1`.
pub fn moving_block(m: usize, height: usize, z_size: f64) -> Scene {
    let mut s = scene();
    s.view = View {
        eyept: DVec3::new(0.0, -1000.0, 0.0),
        lookpt: DVec3::ZERO,
        screensize: 16.0,
        scrndistance: 1000.0,
    };
    s.image = ImageSpec {
        width: 64,
        height,
        masksize: m,
        aliasing: 0.0,
    };
    s.surfaces
        .push(surface(SurfaceAttribute::Light, [1.0, 1.0, 1.0], 0.0, 0.0, 0.0, 0.0));
    s.objects
        .push(block("square", 0, [-5.0, 0.0, 0.0], [2.0, 0.01, z_size]));
    s.motions.push(MotionRecord {
        pos: Pos::default(),
        object: 0,
        to: DVec3::new(5.0, 0.0, 0.0),
        turn: DVec3::ZERO,
        via: None,
        law: Law::Constant,
    });
    s.blur = Some(BlurRecord {
        pos: Pos::default(),
        n: 1,
    });
    s
}

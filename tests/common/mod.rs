//! Scenes built by hand for the tests, without the deck reader.
#![allow(dead_code)] // each test file uses a different part of this module

use raytrace::options::*;
use raytrace::raytrace::{render, Prepared, Render, Request};
use raytrace::scene::*;
use raytrace::types::*;

pub mod sweeps;

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
        gloss: 0.0,
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
        Shape::Blob(_) => PrimitiveClass::Blob,
        Shape::Patch(_) => PrimitiveClass::Patch,
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
        lens: None,
    }
}

pub fn light(at: [f64; 3], color: [f64; 3]) -> LightRecord {
    LightRecord {
        name: "l".into(),
        position: DVec3::from_array(at),
        color: DVec3::from_array(color),
        radius: 0.0,
    }
}

pub fn close(a: DVec3, b: DVec3, eps: f64) -> bool {
    (a - b).abs().max_element() <= eps
}

/// legacy_pascal/decks, where the legacy decks stand.
pub fn decks() -> &'static std::path::Path {
    std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/legacy_pascal/decks"))
}

/// A legacy deck as `initialize` reads it (prepared by [`prepare`]).
pub fn load_deck(name: &str, fidelity: Fidelity) -> Scene {
    let src = std::fs::read_to_string(decks().join(name)).unwrap();
    raytrace::deck::initialize(&src, name, decks(), fidelity).unwrap()
}

/// `scene` prepared with `opts`; a test's scene must prepare.
pub fn prepare(scene: Scene, opts: Options) -> Prepared {
    Prepared::new(scene, opts).unwrap_or_else(|e| panic!("{e}"))
}

/// The whole still of `scene` rendered with `opts`.
pub fn render_still(scene: &Scene, opts: &Options) -> Render {
    render_request(scene, opts, &Request::STILL)
}

/// `request` of `scene` rendered with `opts`.
pub fn render_request(scene: &Scene, opts: &Options, request: &Request) -> Render {
    render(&prepare(scene.clone(), *opts), request).unwrap_or_else(|e| panic!("{e}"))
}

/// The whole of film frame `frame` of `scene` rendered with `opts`.
pub fn render_frame(scene: &Scene, opts: &Options, frame: raytrace::film::Frame) -> Render {
    render_request(scene, opts, &Request::frame(frame))
}

/// A raster file from its header fields, colour map and (encoded) data.
#[allow(clippy::too_many_arguments)]
pub fn sun_raster_file(
    width: u32,
    height: u32,
    depth: u32,
    length: u32,
    ras_type: u32,
    maptype: u32,
    map: &[u8],
    data: &[u8],
) -> Vec<u8> {
    let mut out = Vec::new();
    for v in [
        0x59a6_6a95,
        width,
        height,
        depth,
        length,
        ras_type,
        maptype,
        map.len() as u32,
    ] {
        out.extend_from_slice(&v.to_be_bytes());
    }
    out.extend_from_slice(map);
    out.extend_from_slice(data);
    out
}

/// The `raytrace` binary of this build.
pub fn raytrace_command() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_raytrace"))
}

/// A deck that renders in a moment: a red ball, 16×12 pixels.
pub const SMALL_DECK: &str = "\
view  eye 0 -10 3  look 0 0 0  screen 4  distance 5
image 16 12  mask 1
light sun 5 -5 10  1 1 1
surface red opaque color 1 0 0 ka 0.2 kd 0.8 ks 0 kt 0
sphere ball red at 0 0 0 radius 1
";

/// The names in a folder, sorted.
pub fn file_names(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A prepared sweep's box as the intersection uses it: a rotation sweep's
/// spans ± its largest radius in x and y.
pub fn sweep_box(class: PrimitiveClass, sw: &SweepShape) -> (DVec3, DVec3) {
    let b = &sw.bbox;
    match class {
        PrimitiveClass::Rotation => {
            let r = b.xmax.abs().max(b.xmin.abs());
            (DVec3::new(-r, -r, b.zmin), DVec3::new(r, r, b.zmax))
        }
        _ => (DVec3::new(b.xmin, b.ymin, b.zmin), DVec3::new(b.xmax, b.ymax, b.zmax)),
    }
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

/// The (first) sweep object of a deck, prepared as the renderer prepares
/// it: its class and shape.
pub fn deck_sweep(deck: &str) -> (PrimitiveClass, SweepShape) {
    let prepared = prepare(load_deck(deck, Fidelity::Thesis), Options::default());
    prepared
        .scene()
        .objects
        .iter()
        .find_map(|o| match &o.shape {
            Shape::Sweep(sw) => Some((o.class, sw.clone())),
            _ => None,
        })
        .expect("the deck has a sweep")
}

/// `drt::motionblur`'s pose of `obj` at `time`, written over a pose of
/// NaNs: a field it did not write would show.
pub fn motionblur_pose(obj: &ObjectRecord, motion: &MotionRecord, time: f64, fidelity: Fidelity) -> Pose {
    let nan = DMat4::from_cols_array(&[f64::NAN; 16]);
    let mut pose = Pose {
        transfm: nan,
        inverse: nan,
        sphereo: DVec3::NAN,
    };
    raytrace::drt::motionblur(obj, motion, time, fidelity, &mut pose);
    pose
}

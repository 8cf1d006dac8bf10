//! `tools pov DECK -o SCENE.pov`: a deck's scene as POV-Ray 3.7 SDL, to
//! render the same geometry with the renderer a user would otherwise pick
//! (POV-Ray's `prism` and `lathe` are van Wijk's sweeps too). Not the
//! thesis's: a cross-check of the port.
//!
//! What is exported: the view as an explicit camera (location, direction,
//! right, up: no `look_at`, so the window is exactly the deck's), the
//! background, the lights, each surface's colour and Whitted constants as
//! a pigment and finish, and every object at rest. Our world is
//! right-handed with z up, POV-Ray's left-handed with y up: every point
//! and vector (x, y, z) becomes <x, z, y>, which is the same picture (the
//! swap turns one handedness into the other). Object frames are written as
//! `matrix` of the swapped `transfm`, and in the local frame the sweep
//! axis (local z) is POV's local y, along which `prism` and `lathe` sweep:
//! - translation: `prism { linear_sweep bezier_spline 0, length, … }`;
//! - conic: `prism { conic_sweep bezier_spline 1, scale, … }`, whose
//!   section at height y is the contour scaled by y, then scaled and moved
//!   along y so that height 1 is z = 0 and height `scale` is z = `length`;
//! - rotation: `lathe { bezier_spline … }` of the (radius U, height V)
//!   contour.
//!
//! A uniform cubic B-spline contour is converted to Bezier segments
//! exactly (each segment's four Bezier points from its four B-spline
//! points). Not exported, and said so in the file: motion and key frames
//! (the scene stands as at rest, a key-frame object as its first shape).
//!
//! Paints and textures ([`pigment`]) are painted where our renderer
//! paints them (`shapes::face_coords`): `floor` is POV-Ray's `checker`,
//! moved and scaled so that its squares are `floortest`'s; `star` and
//! `floorstar` are `function` patterns of `startest`'s and `floorstar`'s
//! inequalities (with the listing's whole odd tiles under
//! `--fidelity listing`, erratum 6); a texture is an `image_map` of the
//! texture raster, written beside the .pov as a PNG ([`Export::images`]):
//! on each of a block's six faces (the block is written as six polygons,
//! each with its picture placed as ours is), around a cylinder's side
//! (`map_type 2`) with its caps and every other shape projected along
//! local z. A paint on a block follows its top and bottom faces (the
//! checker and stars of a floor); on the sides, and on a cylinder's side,
//! it is the pattern through the solid, not ours.
//!
//! Cook's distributed ray tracing (the port's extension, docs/cook.md):
//! a `lens` of aperture > 0 becomes the camera's focal blur
//! ([`focal_blur`]), a light of `radius` > 0 an `area_light`
//! ([`area_light`]); a deck without them exports as before. Surface
//! `gloss` is not exported (POV-Ray's blurred reflection is a micro-normal
//! average, not a turn of the ray), and said so in the file.

use std::fmt::Write as _;

use raytrace::options::Fidelity;
use raytrace::raster::Raster;
use raytrace::raytrace::{getangle, translookpt};
use raytrace::scene::{LightRecord, Scene};
use raytrace::shapes::sweep::segment_points;
use raytrace::types::{
    BlobShape, CurveKind, DMat4, DVec3, ObjectRecord, Paint, PaintKind, PatchShape, PrimitiveClass, Shape,
    SurfaceAttribute, SurfaceRecord, SweepShape, MAXSEGMENTS,
};

/// A point or vector of our world as POV-Ray's: (x, y, z) → <x, z, y>.
pub fn pov_vec(v: DVec3) -> String {
    format!("<{}, {}, {}>", num(v.x), num(v.z), num(v.y))
}

/// A number as SDL reads it back exactly (Rust's shortest round-trip
/// form), with a finite fallback of 0.
fn num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:?}")
    } else {
        "0".into()
    }
}

/// The camera of our renderer's window as POV-Ray vectors: location,
/// direction (the eye to the window's centre), right (the window's width,
/// left to right) and up (its height, bottom to top), so that POV-Ray's
/// ray through a pixel centre is ours.
pub fn camera(scene: &Scene, fidelity: Fidelity) -> [DVec3; 4] {
    let view = &scene.view;
    let (sinz, cosz, sinx, cosx) = getangle(view);
    // As `Camera::new`: the main program negates both sines.
    let axis = |x: f64, y: f64, z: f64| translookpt(x, y, z, -sinz, cosz, -sinx, cosx, DVec3::ZERO);
    let img = &scene.image;
    let screen_w = view.screensize;
    let screen_h = match fidelity {
        Fidelity::Listing => screen_w,
        Fidelity::Thesis => screen_w * img.height as f64 / img.width.max(1) as f64,
    };
    [
        view.eyept,
        axis(0.0, -1.0, 0.0) * view.scrndistance,
        // The view frame's −x is the viewer's right.
        axis(-1.0, 0.0, 0.0) * screen_w,
        axis(0.0, 0.0, 1.0) * screen_h,
    ]
}

/// The Bezier control points of each segment of a sweep's contour: as
/// they are for a Bezier contour; for a uniform cubic B-spline, the exact
/// conversion of each segment (B-spline points P0…P3):
/// (P0 + 4P1 + P2)/6, (2P1 + P2)/3, (P1 + 2P2)/3, (P1 + 4P2 + P3)/6.
pub fn bezier_segments(sw: &SweepShape) -> Vec<[[f64; 2]; 4]> {
    let n = sw.points.len();
    let segments = match sw.curve {
        CurveKind::Bspline => n,
        CurveKind::Bezier => n / 3,
    }
    .min(MAXSEGMENTS);
    (0..segments)
        .map(|i| {
            let p = segment_points(sw.curve, &sw.points, i);
            match sw.curve {
                CurveKind::Bezier => p,
                CurveKind::Bspline => {
                    let mix = |w: [f64; 4]| -> [f64; 2] {
                        std::array::from_fn(|k| (0..4).map(|j| w[j] * p[j][k]).sum::<f64>())
                    };
                    [
                        mix([1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0]),
                        mix([0.0, 2.0 / 3.0, 1.0 / 3.0, 0.0]),
                        mix([0.0, 1.0 / 3.0, 2.0 / 3.0, 0.0]),
                        mix([0.0, 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0]),
                    ]
                }
            }
        })
        .collect()
}

/// The `matrix` of an object frame: POV-Ray's rows are the images of its
/// axes and the translation, each swapped; POV's local y is our local z.
fn pov_matrix(m: &DMat4) -> String {
    let body = [m.x_axis, m.z_axis, m.y_axis, m.w_axis]
        .map(|v| pov_vec(v.truncate()))
        .iter()
        .map(|s| s.trim_start_matches('<').trim_end_matches('>').to_string())
        .collect::<Vec<_>>()
        .join(", ");
    format!("matrix <{body}>")
}

/// The finish and interior of a surface, after `pigment` (its colour,
/// paint or texture: [`pigment`]).
fn texture(s: &SurfaceRecord, pigment: &str) -> String {
    let mut out = String::new();
    let _ = write!(
        out,
        "{pigment} finish {{ ambient rgb <{}, {}, {}> diffuse {}",
        num(s.ka * s.iobject.x),
        num(s.ka * s.iobject.y),
        num(s.ka * s.iobject.z),
        num(s.kd)
    );
    if s.surface == SurfaceAttribute::Mirrored {
        let _ = write!(out, " reflection {}", num(s.ks * s.prcntrfl));
    }
    out.push_str(" }");
    if filter(s) > 0.0 {
        let _ = write!(out, " interior {{ ior {} }}", num(s.index));
    }
    if s.gloss > 0.0 {
        out.push_str(" /* gloss is not exported */");
    }
    out
}

/// The share of light a surface lets through, as POV-Ray's `filter`.
fn filter(s: &SurfaceRecord) -> f64 {
    match s.surface {
        SurfaceAttribute::Transparent | SurfaceAttribute::Crystal => s.kt.clamp(0.0, 1.0),
        _ => 0.0,
    }
}

/// A colour with the surface's filter, `rgbf <r, g, b, f>`.
fn rgbf(c: DVec3, filter: f64) -> String {
    format!("rgbf <{}, {}, {}, {}>", num(c.x), num(c.y), num(c.z), num(filter))
}

/// Where `face_coords` puts a paint's or a texture's coordinates (s, t) on
/// an object, in its local frame (ours: x, y, z): from the corner
/// (−`corner.x`, −`corner.y`) of the x–y plane, s along x and t along y,
/// projected along z, which spans −`depth`..`depth`: a block's top face,
/// and every shape's but a block's side faces and a cylinder's side.
struct Plane {
    corner: (f64, f64),
    depth: f64,
}

impl Plane {
    fn of(obj: &ObjectRecord) -> Plane {
        match &obj.shape {
            Shape::Block { lengths } => Plane {
                corner: (lengths.x / 2.0, lengths.y / 2.0),
                depth: lengths.z / 2.0,
            },
            _ => Plane {
                corner: (obj.radius, obj.radius),
                depth: obj.radius,
            },
        }
    }

    /// POV-Ray's expression of s·`ls` (x the POV local x, our x) and of
    /// t·`lt` (POV z, our y).
    fn scaled(&self, ls: f64, lt: f64) -> (String, String) {
        (
            format!("((x+{})*{})", num(self.corner.0), num(ls)),
            format!("((z+{})*{})", num(self.corner.1), num(lt)),
        )
    }
}

/// 1/`l`, for a pattern scaled by `l` cells a unit; a huge scale for a
/// pattern of no cells (`scale 0 0`, one colour everywhere, as
/// `floortest` of 0 gives).
fn inverse(l: f64) -> f64 {
    if l.abs() > 1e-9 {
        1.0 / l
    } else {
        1e9
    }
}

/// The pigment of a surface on `obj`: its colour, its paint's pattern
/// (`floortest`, `startest`, `floorstar` of unit `proc`, painted where our
/// renderer paints them), or its texture's picture, `image` (the PNG
/// written beside the .pov), projected along local z; a block's and a
/// cylinder's textures are placed face by face by [`textured_sdl`].
pub fn pigment(s: &SurfaceRecord, obj: &ObjectRecord, fidelity: Fidelity, image: Option<&str>) -> String {
    let f = filter(s);
    let plane = Plane::of(obj);
    if let (Some(_), Some(file)) = (&s.texture, image) {
        // The unit square of the picture, bottom left at its origin, made
        // the face's (2·corner) and turned from the x–y plane into POV's
        // x–z (ours x–y).
        return format!(
            "pigment {{ image_map {{ png \"{file}\" once filter all {} }} scale <{}, {}, 1> rotate x*90 translate <{}, 0, {}> }}",
            num(f),
            num(2.0 * plane.corner.0),
            num(2.0 * plane.corner.1),
            num(-plane.corner.0),
            num(-plane.corner.1)
        );
    }
    let Some(paint) = &s.paint else {
        return format!("pigment {{ {} }}", rgbf(s.color, f));
    };
    let (painted, own) = (rgbf(paint.color, f), rgbf(s.color, f));
    let function =
        |body: String| format!("pigment {{ function {{ {body} }} color_map {{ [0 {own}] [1 {painted}] }} }}");
    match paint.kind {
        // round(s·lx) mod 2 + round(t·ly) mod 2 even is POV's first
        // colour: floor(X) + floor(Y) + floor(Z) even with X = s·lx + ½,
        // Z = t·ly + ½ and Y in [0, 1) across the object.
        PaintKind::Floor => format!(
            "pigment {{ checker {painted} {own} scale <{}, {}, {}> translate <{}, {}, {}> }}",
            num(inverse(paint.lengthx)),
            num(4.0 * plane.depth + 1.0),
            num(inverse(paint.lengthy)),
            num(-plane.corner.0 - 0.5 * inverse(paint.lengthx)),
            num(-plane.depth),
            num(-plane.corner.1 - 0.5 * inverse(paint.lengthy))
        ),
        PaintKind::Star => function(star_function(paint, obj.radius)),
        PaintKind::Floorstar => function(floorstar_function(paint, &plane, fidelity)),
    }
}

/// `startest(x·lx, y, z·ly, 1)` of the point scaled to the unit sphere:
/// the two triangles of the hexagram in the x–z plane (ours; POV's x–y),
/// 1 inside, 0 outside.
fn star_function(paint: &Paint, radius: f64) -> String {
    let r = if radius > 0.0 { radius } else { 1.0 };
    let x = format!("(x*{})", num(paint.lengthx / r));
    let w = format!("(y*{})", num(paint.lengthy / r));
    let t = num(3f64.sqrt());
    let t9 = num(3f64.sqrt() / 9.0);
    format!(
        "(({w}-{t9}<0)&({t}*{x}+{w}+2*{t9}>0)&({t}*{x}-{w}-2*{t9}<0))|(({w}+{t9}>0)&({t}*{x}+{w}-2*{t9}<0)&({t}*{x}-{w}+2*{t9}>0))"
    )
}

/// `floorstar(s, t, lx, ly)`: the tiles of 3×3 of the scaled coordinates
/// (`while tx > 3 do tx := tx − 3`: tile max(0, ⌈tx/3⌉ − 1)), and in the
/// odd ones the two triangles of a star; under the listing the whole odd
/// tile (erratum 6). 1 painted, 0 not.
fn floorstar_function(paint: &Paint, plane: &Plane, fidelity: Fidelity) -> String {
    let (tx, ty) = plane.scaled(paint.lengthx, paint.lengthy);
    let tile = |t: &str| format!("max(0,ceil({t}/3)-1)");
    let (xx, yy) = (tile(&tx), tile(&ty));
    let (rx, ry) = (format!("({tx}-3*{xx})"), format!("({ty}-3*{yy})"));
    let odd = format!("(mod({xx}+{yy},2)>0.5)");
    let first = format!("(({rx}*15+{ry}*10-27.5>=0)&({ry}<=2)&({rx}*1.5-{ry}-1.75<=0))");
    let second = format!("(({rx}*15+{ry}*10-47.5<=0)&({ry}>=1)&({rx}*1.5-{ry}+0.25>=0))");
    match fidelity {
        Fidelity::Listing => odd,
        Fidelity::Thesis => format!("{odd}&({first}|{second})"),
    }
}

/// A textured block or cylinder as its faces, each with its picture where
/// `face_coords` puts it: a block's six faces as polygons (s along the
/// face's first axis, t its second, from the corner ours measures from);
/// a cylinder's side by POV-Ray's cylindrical map (the angle from local +x
/// counter-clockwise, as ours unrolls it; the height from `bottom`) and
/// its caps by the projection along z. `None` for other shapes, whose
/// pictures [`pigment`] projects.
pub fn textured_sdl(obj: &ObjectRecord, s: &SurfaceRecord, image: &str, matrix: &str) -> Option<String> {
    let f = num(filter(s));
    let finish = texture(s, "");
    let faces: Vec<String> = match &obj.shape {
        Shape::Block { lengths } => {
            let h = *lengths * 0.5;
            // Each face: the corner where s = t = 0, the s and t axes
            // (as long as the face), and the outward normal.
            let x = DVec3::X * lengths.x;
            let y = DVec3::Y * lengths.y;
            let z = DVec3::Z * lengths.z;
            let faces = [
                (DVec3::new(-h.x, -h.y, h.z), x, y, DVec3::Z),
                (DVec3::new(-h.x, h.y, -h.z), x, -y, -DVec3::Z),
                (DVec3::new(h.x, h.y, -h.z), -x, z, DVec3::Y),
                (DVec3::new(-h.x, -h.y, -h.z), x, z, -DVec3::Y),
                (DVec3::new(h.x, -h.y, -h.z), y, z, DVec3::X),
                (DVec3::new(-h.x, h.y, -h.z), -y, z, -DVec3::X),
            ];
            faces
                .iter()
                .map(|&(o, es, et, n)| {
                    let corners = [o, o + es, o + es + et, o + et, o];
                    let points: Vec<String> = corners.iter().map(|&c| pov_vec(c)).collect();
                    let frame = [es, et, n, o].map(|v| pov_vec(v).trim_matches(['<', '>']).to_string());
                    format!(
                        "polygon {{ 5, {} pigment {{ image_map {{ png \"{image}\" once filter all {f} }} matrix <{}> }} }}",
                        points.join(", "),
                        frame.join(", ")
                    )
                })
                .collect()
        }
        Shape::Cylinder {
            cylradius, top, bottom, ..
        } => {
            let r = num(*cylradius);
            let planar = pigment(s, obj, Fidelity::Thesis, Some(image));
            vec![
                format!(
                    "cylinder {{ <0, {}, 0>, <0, {}, 0>, {r} open pigment {{ image_map {{ png \"{image}\" map_type 2 filter all {f} }} scale <1, {}, 1> translate <0, {}, 0> }} }}",
                    num(*bottom),
                    num(*top),
                    num(top - bottom),
                    num(*bottom)
                ),
                format!("disc {{ <0, {}, 0>, <0, 1, 0>, {r} {planar} }}", num(*top)),
                format!("disc {{ <0, {}, 0>, <0, -1, 0>, {r} {planar} }}", num(*bottom)),
            ]
        }
        _ => return None,
    };
    Some(format!(
        "union {{ {} {} {matrix} }}",
        faces.join(" "),
        finish.trim_start()
    ))
}

/// The PNG of a surface's texture beside the .pov `stem`: `STEM.SURFACE.png`,
/// the surface's name with any character but a letter, a digit, `-` or `_`
/// made `_`.
pub fn image_name(stem: &str, surface: &str) -> String {
    let word: String = surface
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    format!("{stem}.{word}.png")
}

/// A 2-D spline point list, four points a Bezier segment.
fn spline_points(segs: &[[[f64; 2]; 4]]) -> String {
    segs.iter()
        .flat_map(|s| s.iter())
        .map(|p| format!("<{}, {}>", num(p[0]), num(p[1])))
        .collect::<Vec<_>>()
        .join(", ")
}

/// One sweep object's SDL (without its texture and matrix), or `None`
/// when it has no segment.
pub fn sweep_sdl(class: PrimitiveClass, sw: &SweepShape) -> Option<String> {
    let segs = bezier_segments(sw);
    if segs.is_empty() {
        return None;
    }
    let pts = spline_points(&segs);
    let count = 4 * segs.len();
    Some(match class {
        PrimitiveClass::Rotation => format!("lathe {{ bezier_spline {count}, {pts}"),
        PrimitiveClass::Conic if sw.scale != 1.0 && sw.scale.is_finite() => {
            // Height y of the cone is the section scaled by y: height 1 at
            // z = 0, `scale` at z = length; c = length/(scale − 1).
            let c = sw.length / (sw.scale - 1.0);
            format!(
                "prism {{ conic_sweep bezier_spline 1, {}, {count}, {pts} scale <1, {}, 1> translate <0, {}, 0>",
                num(sw.scale),
                num(c),
                num(-c)
            )
        }
        _ => format!(
            "prism {{ linear_sweep bezier_spline 0, {}, {count}, {pts}",
            num(sw.length)
        ),
    })
}

/// The SDL of one object (without texture and matrix).
fn shape_sdl(class: PrimitiveClass, shape: &Shape, radius: f64) -> Option<String> {
    Some(match shape {
        Shape::Sphere => format!("sphere {{ <0, 0, 0>, {}", num(radius)),
        Shape::Block { lengths } => {
            let h = *lengths * 0.5;
            format!("box {{ {}, {}", pov_vec(-h), pov_vec(h))
        }
        Shape::Cylinder {
            cylradius, top, bottom, ..
        } => format!(
            "cylinder {{ <0, {}, 0>, <0, {}, 0>, {}",
            num(*bottom),
            num(*top),
            num(*cylradius)
        ),
        Shape::Prism { height, vertex, .. } => {
            let mut pts: Vec<String> = vertex
                .iter()
                .map(|p| format!("<{}, {}>", num(p[0]), num(p[1])))
                .collect();
            let first = pts.first()?.clone();
            pts.push(first);
            format!(
                "prism {{ linear_sweep linear_spline 0, {}, {}, {}",
                num(*height),
                pts.len(),
                pts.join(", ")
            )
        }
        Shape::Sweep(sw) => sweep_sdl(class, sw)?,
        Shape::Blob(b) => blob_sdl(b)?,
        Shape::Patch(p) => patch_sdl(p),
    })
}

/// A blob's SDL (without its texture and matrix): POV-Ray's `blob`, whose
/// field is ours (each component strength·(1 − r²/R²)² within R), one
/// `sphere` component each; `None` for a blob without components.
pub fn blob_sdl(b: &BlobShape) -> Option<String> {
    if b.components.is_empty() {
        return None;
    }
    let parts: Vec<String> = b
        .components
        .iter()
        .map(|c| {
            format!(
                "sphere {{ {}, {}, strength {} }}",
                pov_vec(c.centre),
                num(c.radius),
                num(c.strength)
            )
        })
        .collect();
    Some(format!("blob {{ threshold {} {}", num(b.threshold), parts.join(" ")))
}

/// How finely POV-Ray cuts a patch into triangles (`u_steps`, `v_steps`
/// of `bicubic_patch` type 1: 2⁶ = 64 strips each way): fine enough that
/// its silhouettes are the exact patch's to a pixel at 256².
pub const PATCH_STEPS: u32 = 6;

/// A patch's SDL (without its texture and matrix): POV-Ray's
/// `bicubic_patch` of type 1 (its triangles made once, [`PATCH_STEPS`]
/// each way), the 16 points in our order (rows of four), each swapped.
pub fn patch_sdl(p: &PatchShape) -> String {
    let pts: Vec<String> = p.points.iter().map(|&q| pov_vec(q)).collect();
    format!(
        "bicubic_patch {{ type 1 flatness 0 u_steps {PATCH_STEPS} v_steps {PATCH_STEPS} {}",
        pts.join(", ")
    )
}

/// POV-Ray's focal blur for a `lens` of aperture > 0 (the port's
/// extension; nothing for no lens or `lens 0 F`, which render as the
/// pinhole): the camera's ` aperture … focal_point … blur_samples N, N`.
/// POV-Ray 3.7 moves the eye by `aperture`/2 times a point of its sample
/// grid, which fills the disk of radius ½ (`TracePixel::JitterCameraRay`,
/// `FocalBlurData`): its lens radius is `aperture`/4, so `aperture` is 4
/// times the deck's APERTURE (the lens's radius). Its plane of focus is the
/// plane through `focal_point` across `direction`: the point FOCUS along
/// the line of sight is our plane of focus (thesis fidelity). N is the
/// deck's M×M rays a pixel, as both the minimum and the maximum, so that
/// POV-Ray's adaptive stop never ends a pixel early; with focal blur
/// POV-Ray jitters each of those rays in the pixel too (its antialiasing
/// is then not needed).
pub fn focal_blur(scene: &Scene, location: DVec3, direction: DVec3) -> String {
    let Some(lens) = scene.lens.as_ref().filter(|l| l.aperture > 0.0) else {
        return String::new();
    };
    let focal_point = location + direction.normalize() * lens.focus;
    let m = scene.image.masksize.max(1);
    format!(
        " aperture {} focal_point {} blur_samples {}, {}",
        num(4.0 * lens.aperture),
        pov_vec(focal_point),
        m * m,
        m * m
    )
}

/// POV-Ray's area light for a sphere of light (`light … radius R`, R > 0;
/// the port's extension; nothing for a point light): a `circular` light
/// of diameter 2R that POV-Ray turns to face each point it lights
/// (`orient`), which is the disk the sphere shows that point; its M×M
/// point lights (`samples` M, the deck's mask; at least 2×2, as POV-Ray
/// 3.7 refuses `circular` with one) `jitter`ed in their cells.
/// `orient` needs both axes of one length and one count (POV-Ray 3.7
/// reference, area lights).
pub fn area_light(light: &LightRecord, samples: usize) -> String {
    if light.radius <= 0.0 {
        return String::new();
    }
    let d = num(2.0 * light.radius);
    // POV-Ray 3.7 refuses `circular` with one light ("Cannot parse input").
    let n = samples.max(2);
    format!(" area_light <{d}, 0, 0>, <0, 0, {d}>, {n}, {n} jitter circular orient")
}

/// A scene exported: its SDL, and the texture pictures it names, to be
/// written beside it under their names.
pub struct Export {
    pub sdl: String,
    pub images: Vec<(String, Raster)>,
}

/// The whole scene as POV-Ray 3.7 SDL (see the module doc), its textures'
/// pictures named `image_stem.SURFACE.png` ([`image_name`]).
pub fn export(scene: &Scene, fidelity: Fidelity, image_stem: &str) -> Export {
    let mut images = Vec::new();
    for s in &scene.surfaces {
        if let Some(t) = &s.texture {
            let raster = Raster {
                width: t.width,
                height: t.height,
                pixels: t.texels.clone(),
            };
            images.push((image_name(image_stem, &s.name), raster));
        }
    }
    Export {
        sdl: sdl(scene, fidelity, image_stem),
        images,
    }
}

/// `tools pov DECK -o SCENE.pov`: the SDL to `out`, and each texture's
/// picture beside it as `SCENE.SURFACE.png`, which the SDL names (POV-Ray
/// looks for it in the folder it runs in: run it in `out`'s folder).
pub fn write(scene: &Scene, fidelity: Fidelity, out: &std::path::Path) -> Result<(), raytrace::exit::Failure> {
    let failed = |path: &std::path::Path, e: &dyn std::fmt::Display| {
        raytrace::exit::Failure::other(format!("{}: {e}", path.display()))
    };
    let stem = out
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let export = export(scene, fidelity, &stem);
    let folder = out.parent().unwrap_or(std::path::Path::new(""));
    for (name, raster) in &export.images {
        let path = folder.join(name);
        raytrace::raster::write_png(&path, raster).map_err(|e| failed(&path, &e))?;
        println!("wrote {}", path.display());
    }
    raytrace::output::write_atomically(out, |w| {
        w.write_all(export.sdl.as_bytes())
            .map_err(raytrace::output::OutputError::from)
    })
    .map_err(|e| failed(out, &e))?;
    println!("wrote {}", out.display());
    Ok(())
}

/// The whole scene as POV-Ray 3.7 SDL, its textures' pictures named
/// `texture.SURFACE.png` ([`export`] names them and gives them).
pub fn scene_sdl(scene: &Scene, fidelity: Fidelity) -> String {
    sdl(scene, fidelity, "texture")
}

fn sdl(scene: &Scene, fidelity: Fidelity, image_stem: &str) -> String {
    let mut out = String::new();
    let [location, direction, right, up] = camera(scene, fidelity);
    let _ = writeln!(
        out,
        "// Exported by `tools pov` from a TR-88-036 deck: (x, y, z) -> <x, z, y>."
    );
    if !scene.motions.is_empty() || !scene.keyframes.is_empty() {
        let _ = writeln!(
            out,
            "// Motion and key frames are not exported: the scene as at rest, key-frame objects as their first shape."
        );
    }
    let _ = writeln!(out, "#version 3.7;");
    let _ = writeln!(
        out,
        "global_settings {{ assumed_gamma 1.0 ambient_light rgb <1, 1, 1> max_trace_level 6 }}"
    );
    let b = scene.backgrnd;
    let _ = writeln!(out, "background {{ rgb <{}, {}, {}> }}", num(b.x), num(b.y), num(b.z));
    if fidelity == Fidelity::Listing && scene.lens.as_ref().is_some_and(|l| l.aperture > 0.0) {
        let _ = writeln!(
            out,
            "// The lens as the thesis's thin lens: the listing's depthoffield (sharp on the plane y = FOCUS, a lens of one dimension) has no POV-Ray form."
        );
    }
    let _ = writeln!(
        out,
        "camera {{ perspective location {} direction {} right {} up {}{} }}",
        pov_vec(location),
        pov_vec(direction),
        pov_vec(right),
        pov_vec(up),
        focal_blur(scene, location, direction)
    );
    let samples = scene.image.masksize.max(1);
    for l in &scene.lights {
        let c = l.color;
        let _ = writeln!(
            out,
            "light_source {{ {} color rgb <{}, {}, {}>{} }} // {}",
            pov_vec(l.position),
            num(c.x),
            num(c.y),
            num(c.z),
            area_light(l, samples),
            l.name
        );
    }
    for obj in &scene.objects {
        let Some(shape) = shape_sdl(obj.class, &obj.shape, obj.radius) else {
            let _ = writeln!(out, "// {}: no segment, not exported", obj.name);
            continue;
        };
        let Some(surface) = scene.surfaces.get(obj.surface) else {
            let _ = writeln!(out, "{shape} {} }} // {}", pov_matrix(&obj.transfm), obj.name);
            continue;
        };
        let image = surface.texture.as_ref().map(|_| image_name(image_stem, &surface.name));
        let matrix = pov_matrix(&obj.transfm);
        if let Some(faces) = image.as_deref().and_then(|i| textured_sdl(obj, surface, i, &matrix)) {
            let _ = writeln!(out, "{faces} // {}", obj.name);
            continue;
        }
        let tex = texture(surface, &pigment(surface, obj, fidelity, image.as_deref()));
        let _ = writeln!(out, "{shape} {tex} {matrix} }} // {}", obj.name);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use raytrace::proc::sweep::spline;
    use raytrace::types::{BoundingBox, Coeff};

    fn sweep(curve: CurveKind, points: Vec<[f64; 2]>) -> SweepShape {
        SweepShape {
            orientt: raytrace::types::Axis::Z,
            curve,
            points,
            segment: 0,
            u: vec![],
            v: vec![],
            length: 2.0,
            scale: 0.5,
            bbox: BoundingBox::default(),
            orientation: 0.0,
        }
    }

    fn bezier_at(p: &[[f64; 2]; 4], s: f64, k: usize) -> f64 {
        let r = 1.0 - s;
        r * r * r * p[0][k] + 3.0 * r * r * s * p[1][k] + 3.0 * r * s * s * p[2][k] + s * s * s * p[3][k]
    }

    /// Each Bezier segment of a B-spline contour is the B-spline's own
    /// segment (`spline`'s coefficients) at every parameter, and the
    /// segments join up into a closed contour.
    #[test]
    fn bspline_to_bezier_is_exact() {
        let pts = vec![[1.0, 0.0], [0.3, 0.9], [-1.2, 0.4], [-0.7, -1.1], [0.8, -0.6]];
        let sw = sweep(CurveKind::Bspline, pts.clone());
        let segs = bezier_segments(&sw);
        assert_eq!(segs.len(), 5);
        for (i, seg) in segs.iter().enumerate() {
            let p = segment_points(CurveKind::Bspline, &pts, i);
            for k in [0, 1] {
                let mut c = Coeff::default();
                let mut b = BoundingBox::EMPTY;
                spline(
                    CurveKind::Bspline,
                    p[0][k],
                    p[1][k],
                    p[2][k],
                    p[3][k],
                    &mut c,
                    PrimitiveClass::Translation,
                    1,
                    &mut b,
                );
                for s in [0.0, 0.2, 0.5, 0.77, 1.0] {
                    assert!((bezier_at(seg, s, k) - c.value(s)).abs() < 1e-14, "segment {i}, s {s}");
                }
            }
            let next = &segs[(i + 1) % segs.len()];
            assert!((seg[3][0] - next[0][0]).abs() < 1e-15 && (seg[3][1] - next[0][1]).abs() < 1e-15);
        }
    }

    #[test]
    fn axes_are_swapped() {
        assert_eq!(pov_vec(DVec3::new(1.0, 2.0, 3.0)), "<1.0, 3.0, 2.0>");
        // A translation by (1, 2, 3): POV's matrix rows x, y(our z), z(our y), move.
        let m = DMat4::from_translation(DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(
            pov_matrix(&m),
            "matrix <1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 3.0, 2.0>"
        );
        // A turn taking our x to our y: POV's x goes to POV's z.
        let turn = DMat4::from_rotation_z(std::f64::consts::FRAC_PI_2);
        let text = pov_matrix(&turn);
        let v: Vec<f64> = text
            .trim_start_matches("matrix <")
            .trim_end_matches('>')
            .split(", ")
            .map(|s| s.parse().unwrap())
            .collect();
        let row = |i: usize| DVec3::new(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        assert!((row(0) - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-15);
        assert!((row(1) - DVec3::new(0.0, 1.0, 0.0)).length() < 1e-15);
        assert!((row(2) - DVec3::new(-1.0, 0.0, 0.0)).length() < 1e-15);
    }

    #[test]
    fn sweep_kinds_become_prisms_and_lathes() {
        // A triangle of three straight Bezier sides.
        let triangle = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [3.0, 0.0],
            [2.0, 1.0],
            [1.0, 2.0],
            [0.0, 3.0],
            [0.0, 2.0],
            [0.0, 1.0],
        ];
        let sw = sweep(CurveKind::Bezier, triangle);
        let t = sweep_sdl(PrimitiveClass::Translation, &sw).unwrap();
        assert!(
            t.starts_with("prism { linear_sweep bezier_spline 0, 2.0, 12, <0.0, 0.0>, <1.0, 0.0>"),
            "{t}"
        );
        // The last segment closes on the first point.
        assert!(t.ends_with("<0.0, 1.0>, <0.0, 0.0>"), "{t}");
        // Conic, scale 0.5 over length 2: c = 2/(0.5 − 1) = −4.
        let c = sweep_sdl(PrimitiveClass::Conic, &sw).unwrap();
        assert!(c.starts_with("prism { conic_sweep bezier_spline 1, 0.5, 12, "), "{c}");
        assert!(c.ends_with("scale <1, -4.0, 1> translate <0, 4.0, 0>"), "{c}");
        let r = sweep_sdl(PrimitiveClass::Rotation, &sw).unwrap();
        assert!(r.starts_with("lathe { bezier_spline 12, <0.0, 0.0>"), "{r}");
        assert!(sweep_sdl(PrimitiveClass::Rotation, &sweep(CurveKind::Bezier, vec![[0.0, 1.0]])).is_none());
    }

    /// The camera's vectors: location the eye, direction to the window's
    /// centre at `scrndistance`, right to the viewer's right, up upward.
    #[test]
    fn camera_frames_the_window() {
        let mut scene = raytrace::deck::initialize(
            "view eye 0 -10 0 look 0 0 0 screen 4 distance 5\nimage 200 100 mask 1\n",
            "t.deck",
            std::path::Path::new("."),
            Fidelity::Thesis,
        )
        .unwrap();
        scene.lights.clear();
        let [l, d, r, u] = camera(&scene, Fidelity::Thesis);
        assert_eq!(l, DVec3::new(0.0, -10.0, 0.0));
        assert!((d - DVec3::new(0.0, 5.0, 0.0)).length() < 1e-12);
        assert!((r - DVec3::new(4.0, 0.0, 0.0)).length() < 1e-12, "{r}");
        assert!((u - DVec3::new(0.0, 0.0, 2.0)).length() < 1e-12, "{u}");
        let text = scene_sdl(&scene, Fidelity::Thesis);
        assert!(text.contains("camera { perspective location <0.0, 0.0, -10.0> direction <0.0, 0.0, 5.0> right <4.0, 0.0, 0.0> up <0.0, 2.0, 0.0> }"), "{text}");
    }
}

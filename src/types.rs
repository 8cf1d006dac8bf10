//! The records of Fig. 4.3 (Ch. 4 (b) "Create scene" and (e)), in Rust.
//!
//! The thesis prints the record types of the base program `Raytrace`:
//! `surfacerecord`, `points`, `coeff`, `objectrecord`, `ray` and
//! `intersectionrecord`. They are kept here with their Pascal field names.
//! Pascal pointers (`surfaceptr`, `objectptr`, `matrix = ^dualarray`) become
//! indices into the [`Scene`](crate::scene::Scene)'s vectors or plain values; the variant part of
//! `objectrecord` becomes the enum [`Shape`].
//!
//! Records the thesis does not print (the view, the image, lights, motion and
//! key frames) are reconstructed from Ch. 4 and the main program, and say so.

pub use glam::{DMat3, DMat4, DVec3};

/// `stringlength`: the Pascal `string` is `packed array [1..10] of char`.
pub const STRINGLENGTH: usize = 10;

/// The bound of `u, v : array [1..60] of coeff` in `objectrecord`.
pub const MAXSEGMENTS: usize = 60;

/// `axis = (xaxis, yaxis, zaxis)`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Axis {
    /// `xaxis`
    X,
    /// `yaxis`
    Y,
    /// `zaxis`
    #[default]
    Z,
}

impl Axis {
    /// The unit vector of the axis.
    pub fn unit(self) -> DVec3 {
        match self {
            Axis::X => DVec3::X,
            Axis::Y => DVec3::Y,
            Axis::Z => DVec3::Z,
        }
    }
}

/// `primitiveclass = (block, cylinder, sphere, prism, translation, conic, rotation)`,
/// and the two classes of §6.2 the port adds (`blob`, `patch`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PrimitiveClass {
    Block,
    Cylinder,
    Sphere,
    Prism,
    /// A translation sweep (§2.3).
    Translation,
    /// A conic sweep: a translation sweep whose contour scales linearly (§2.3).
    Conic,
    /// A rotation sweep (§2.3).
    Rotation,
    /// A soft object (§6.2's "soft object"; the port's extension).
    Blob,
    /// A bicubic Bezier patch (§6.2's "parametric surface"; the port's
    /// extension).
    Patch,
}

/// `surfaceattribute = (transparent, mirrored, opaque, background, light, crystal)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SurfaceAttribute {
    Transparent,
    Mirrored,
    Opaque,
    Background,
    Light,
    Crystal,
}

/// `intensity = array [red .. blue] of real`, each 0–1 (`x` red, `y` green,
/// `z` blue).
pub type Intensity = DVec3;

/// `points = record x, y, z : real end`.
pub type Points = DVec3;

/// What `floortest`, `startest` and `floorstar` (unit `proc`) set the global
/// `painting` to; the main program resets it to `normal1` after each pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Painting {
    /// `normal1`: the surface's own `color`.
    #[default]
    Normal1,
    /// `floor1`: the pattern colour of a `floortest` square.
    Floor1,
    /// `star1`: the pattern colour of a star.
    Star1,
}

/// Which pattern procedure of unit `proc` paints a surface (deck `paint`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PaintKind {
    /// `floortest`: a checker floor on a block.
    Floor,
    /// `startest`: a star on a sphere.
    Star,
    /// `floorstar`: stars on a block.
    Floorstar,
}

/// A pattern painted on a surface (deck `paint`). Reconstructed: the listing
/// reads `lengthx`, `lengthy` as globals and the pattern colours are not
/// printed.
#[derive(Clone, Debug, PartialEq)]
pub struct Paint {
    pub kind: PaintKind,
    /// `lengthx`: pattern cells per unit length along the first face axis.
    pub lengthx: f64,
    /// `lengthy`: pattern cells per unit length along the second face axis.
    pub lengthy: f64,
    /// The colour where the pattern procedure sets `floor1` or `star1`.
    pub color: Intensity,
}

/// A raster picture pasted on a surface (deck `texture`, Fig. 5.3–5.4):
/// texels row-major, row 0 at the top, kept as the raster's bytes (3 a
/// texel) and turned into colours 0–1 when looked up.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    pub width: usize,
    pub height: usize,
    pub texels: Vec<[u8; 3]>,
}

impl Texture {
    /// The texel under (s, t) in the unit square, s to the right, t upward; nearest
    /// texel, as a 1989 frame-buffer paste would take it.
    pub fn texel(&self, s: f64, t: f64) -> Intensity {
        let col = ((s.clamp(0.0, 1.0) * self.width as f64) as usize).min(self.width - 1);
        let row_up = ((t.clamp(0.0, 1.0) * self.height as f64) as usize).min(self.height - 1);
        let [r, g, b] = self.texels[(self.height - 1 - row_up) * self.width + col];
        let unit = |c: u8| BYTE_UNIT[c as usize];
        Intensity::new(unit(r), unit(g), unit(b))
    }
}

/// c / 255 for every byte c, the quotients a texel's channels take: looked
/// up, where three divisions a hit were the most of a textured surface's
/// colour (the same quotients, made once).
const BYTE_UNIT: [f64; 256] = {
    let mut t = [0.0; 256];
    let mut c = 0;
    while c < 256 {
        t[c] = c as f64 / 255.0;
        c += 1;
    }
    t
};

/// `surfacerecord` of Fig. 4.3, with the fields the deck's `surface`,
/// `paint` and `texture` records fill.
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceRecord {
    /// The surface's name in the deck (not a field of the printed record:
    /// the Pascal kept it in its symbol table).
    pub name: String,
    /// `color`: colour of the object under diffuse light.
    pub color: Intensity,
    /// `ka, kd, ks, kt`: the "tweaking constants" of Whitted's model,
    /// I = Ia + Kd Σ(N·Lj) + Ks Is + Kt It (Ch. 4 (f)).
    pub ka: f64,
    pub kd: f64,
    pub ks: f64,
    pub kt: f64,
    /// `Iobject`: ambient reflection colour of the object.
    pub iobject: Intensity,
    /// `surface`: the kind of surface.
    pub surface: SurfaceAttribute,
    /// `prcntrfl`: the share of the reflected ray a `mirrored` surface keeps.
    pub prcntrfl: f64,
    /// Refractive index for `transparent` and `crystal` (the base program's;
    /// not printed in Fig. 4.3).
    pub index: f64,
    pub paint: Option<Paint>,
    pub texture: Option<Texture>,
    /// `gloss`: how far `jittering` turns the reflected and transmitted
    /// rays, the tangent of the largest turn (the port's extension, Cook
    /// 1984's blurred reflection); 0 is the mirror of the base program.
    pub gloss: f64,
}

/// `coeff = record a, b, c, d, max, min, first, last : real end`: one
/// coordinate of one cubic segment, x(t) = a t³ + b t² + c t + d for t in
/// [first, last], with min/max the bounds of its control points (`spline`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Coeff {
    pub a: f64,
    pub b: f64,
    pub c: f64,
    pub d: f64,
    pub max: f64,
    pub min: f64,
    pub first: f64,
    pub last: f64,
}

impl Coeff {
    /// x(s) = a s³ + b s² + c s + d.
    pub fn value(&self, s: f64) -> f64 {
        ((self.a * s + self.b) * s + self.c) * s + self.d
    }

    /// dx/ds = 3a s² + 2b s + c.
    pub fn slope(&self, s: f64) -> f64 {
        (3.0 * self.a * s + 2.0 * self.b) * s + self.c
    }

    /// d²x/ds² = 6a s + 2b.
    pub fn curvature(&self, s: f64) -> f64 {
        6.0 * self.a * s + 2.0 * self.b
    }
}

/// The curve kind of a sweep contour (`spline`'s `Bezier` argument:
/// 0 is the uniform cubic B-spline, 1 the composite cubic Bezier).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CurveKind {
    Bspline,
    Bezier,
}

/// `boundingbox = record xmin, xmax, ymin, ymax, zmin, zmax : real end`,
/// in the object's local frame (`spline` fills it: `tbox`, `cbox`, `rbox`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BoundingBox {
    pub xmin: f64,
    pub xmax: f64,
    pub ymin: f64,
    pub ymax: f64,
    pub zmin: f64,
    pub zmax: f64,
}

impl BoundingBox {
    /// The box that holds nothing, to be widened by [`BoundingBox::union`].
    pub const EMPTY: BoundingBox = BoundingBox {
        xmin: f64::INFINITY,
        xmax: f64::NEG_INFINITY,
        ymin: f64::INFINITY,
        ymax: f64::NEG_INFINITY,
        zmin: f64::INFINITY,
        zmax: f64::NEG_INFINITY,
    };

    /// The smallest box holding this one and the point `p`.
    pub fn holding(&self, p: DVec3) -> BoundingBox {
        self.union(&BoundingBox {
            xmin: p.x,
            xmax: p.x,
            ymin: p.y,
            ymax: p.y,
            zmin: p.z,
            zmax: p.z,
        })
    }

    /// The box grown by `by` on every side.
    pub fn widened(&self, by: f64) -> BoundingBox {
        BoundingBox {
            xmin: self.xmin - by,
            xmax: self.xmax + by,
            ymin: self.ymin - by,
            ymax: self.ymax + by,
            zmin: self.zmin - by,
            zmax: self.zmax + by,
        }
    }

    /// Does the box hold the point `p` (its faces included)?
    pub fn holds(&self, p: DVec3) -> bool {
        (self.xmin..=self.xmax).contains(&p.x)
            && (self.ymin..=self.ymax).contains(&p.y)
            && (self.zmin..=self.zmax).contains(&p.z)
    }

    /// The smallest box holding both.
    pub fn union(&self, b: &BoundingBox) -> BoundingBox {
        BoundingBox {
            xmin: self.xmin.min(b.xmin),
            xmax: self.xmax.max(b.xmax),
            ymin: self.ymin.min(b.ymin),
            ymax: self.ymax.max(b.ymax),
            zmin: self.zmin.min(b.zmin),
            zmax: self.zmax.max(b.zmax),
        }
    }
}

/// The sweep variant of `objectrecord`: `orientt`, `segment`, `u`, `v`, and
/// what the deck gives besides (the control points, `length`, `scale`).
#[derive(Clone, Debug, PartialEq)]
pub struct SweepShape {
    /// `orientt`: the world axis the local z axis is mapped onto.
    pub orientt: Axis,
    pub curve: CurveKind,
    /// The contour's control points (U, V) in the local x–y plane
    /// (for `rotation`: U the radius, V the height).
    pub points: Vec<[f64; 2]>,
    /// `segment`: the number of cubic segments of the contour.
    pub segment: usize,
    /// `u[1..segment]`: the U (local x, or radius) coordinate of each segment.
    pub u: Vec<Coeff>,
    /// `v[1..segment]`: the V (local y, or height) coordinate of each segment.
    pub v: Vec<Coeff>,
    /// Extent of a translation or conic sweep along local +z.
    pub length: f64,
    /// Contour scale at z = `length` of a conic sweep (1 at z = 0).
    pub scale: f64,
    /// The bounding box of the contour (`spline`): one per object in
    /// `thesis` fidelity, the class's shared `tbox`/`cbox`/`rbox` in
    /// `listing` fidelity (erratum 9).
    pub bbox: BoundingBox,
    /// Which way the contour runs, +1 counter-clockwise or −1 clockwise in
    /// the (U, V) plane (the sign of its signed area), filled with `u` and
    /// `v` so that a hit's normal is turned outward without a pass over
    /// the contour per ray (the port's; the thesis keeps no such field).
    /// 0 where not known: computed from `u` and `v` when needed.
    pub orientation: f64,
}

/// One component of a blob: its field is `strength`·(1 − r²/`radius`²)²
/// at a distance r < `radius` from `centre`, 0 beyond (POV-Ray's blob
/// field, so that the two renderers can be compared).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BlobComponent {
    /// The centre, in the object's local frame.
    pub centre: DVec3,
    /// The radius of the component's sphere (> 0 from a deck; an
    /// in-between's may shrink to 0 or below, and then adds nothing).
    pub radius: f64,
    /// May be negative (the component then carves the others).
    pub strength: f64,
}

/// The most components a blob has: the bound of the in-between machinery's
/// arrays (`sdirection = array [1..60]`, [`MAXSEGMENTS`]).
pub const MAXCOMPONENTS: usize = MAXSEGMENTS;

/// A soft object (the port's extension, §6.2): the surface where the sum
/// of its components' fields equals `threshold`.
#[derive(Clone, Debug, PartialEq)]
pub struct BlobShape {
    /// T > 0.
    pub threshold: f64,
    /// At most [`MAXCOMPONENTS`].
    pub components: Vec<BlobComponent>,
}

/// A bicubic Bezier patch (the port's extension, §6.2): `points[4r + c]`
/// is the control point of row r (the parameter v = r/3 at it) and
/// column c (u = c/3), in the object's local frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchShape {
    pub points: [DVec3; 16],
}

/// The variant part of `objectrecord`, in local coordinates (the local
/// origin is the object's `sphereo`).
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere of the record's `radius` about the local origin.
    Sphere,
    /// A box centred on the local origin with edge lengths `lengths`.
    Block { lengths: DVec3 },
    /// `cylinder : (cylradius, orient, top, bottom, …)`: radius `cylradius`
    /// about local z from `bottom` to `top`, closed by two caps.
    Cylinder {
        cylradius: f64,
        orient: Axis,
        top: f64,
        bottom: f64,
    },
    /// `polyhydra : (orientp, vnu, …)`: a right prism over a convex polygon
    /// in the local x–y plane (counter-clockwise), from z = 0 to `height`.
    Prism {
        orientp: Axis,
        height: f64,
        vertex: Vec<[f64; 2]>,
    },
    /// `translation, conic, rotation : (orientt, segment, u, v)`.
    Sweep(SweepShape),
    /// A soft object (the port's extension).
    Blob(BlobShape),
    /// A bicubic Bezier patch (the port's extension), boxed: sixteen
    /// points would make every object's record twice as large.
    Patch(Box<PatchShape>),
}

/// `objectrecord` of Fig. 4.3.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectRecord {
    /// `name`: 1–10 characters.
    pub name: String,
    pub class: PrimitiveClass,
    /// `surface`: index into [`Scene::surfaces`](crate::scene::Scene::surfaces) (the Pascal `surfaceptr`).
    pub surface: usize,
    /// `transfm`: local → world.
    pub transfm: DMat4,
    /// `inverse`: world → local.
    pub inverse: DMat4,
    /// `sphereo`: where the local origin stands in the world.
    pub sphereo: Points,
    /// `angle`: the degrees the object has been turned about x, y and z.
    pub angle: Points,
    /// `radius`: a sphere's radius; for the other classes the radius of a
    /// sphere about `sphereo` that holds the whole object.
    pub radius: f64,
    pub shape: Shape,
}

impl ObjectRecord {
    /// The object where the deck leaves it (its pose at rest).
    pub fn pose(&self) -> Pose {
        Pose {
            transfm: self.transfm,
            inverse: self.inverse,
            sphereo: self.sphereo,
        }
    }
}

/// Where an object stands at one instant of the shutter: the fields of
/// `objectrecord` that `motionblur` rewrites per ray (`transfm`, `inverse`,
/// `sphereo`). The port keeps them in per-thread scratch instead of the
/// shared record (legacy_pascal/README.md, "State").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    pub transfm: DMat4,
    pub inverse: DMat4,
    pub sphereo: Points,
}

impl Pose {
    /// An object at the world's origin, unturned: what a pose is before it
    /// is written.
    pub const IDENTITY: Pose = Pose {
        transfm: DMat4::IDENTITY,
        inverse: DMat4::IDENTITY,
        sphereo: DVec3::ZERO,
    };

    /// This pose turned by `turn` (a rotation about axes through the
    /// object's origin) and moved to `sphereo`: T(sphereo) · turn · (the
    /// rotation and axis of this pose). The convention of every motion in
    /// the port (`drt::motionblur`, the key-frame pose; DEVIATIONS D8).
    pub fn turned(&self, turn: DMat3, sphereo: Points) -> Pose {
        let mut pose = Pose::IDENTITY;
        pose.turn_from(&self.transfm, turn, sphereo);
        pose
    }

    /// This pose made [`Pose::turned`] of the pose whose `transfm` is
    /// `transfm` (its inverse is not read), in place: `motionblur` writes
    /// the object's record for every ray, and a copy of a pose (two 4×4
    /// matrices) costs as much as making it.
    #[inline]
    pub fn turn_from(&mut self, transfm: &DMat4, turn: DMat3, sphereo: Points) {
        // Both matrices are rigid: transfm = T(s)·R and inverse = Rᵀ·T(−s),
        // so R is transfm without its translation, and the new pair is
        // T(sphereo)·R′ and R′ᵀ·T(−sphereo) with R′ = turn·R.
        let r = turn * DMat3::from_mat4(*transfm);
        self.place(&r, &r.transpose(), sphereo);
    }

    /// This pose made the rigid pose of rotation `r` (`rt` its transpose)
    /// about the origin moved to `sphereo`: T(sphereo)·r and
    /// rᵀ·T(−sphereo), as [`Pose::turn_from`] makes them, for a motion
    /// whose rotation is the same at every time (`crate::motion::Glide`).
    #[inline(always)]
    pub fn place(&mut self, r: &DMat3, rt: &DMat3, sphereo: Points) {
        self.transfm = DMat4::from_mat3(*r);
        self.inverse = DMat4::from_mat3(*rt);
        self.move_to(rt, sphereo);
    }

    /// This pose, which [`Pose::place`] made of rotation `rt`ᵀ, moved to
    /// `sphereo`: what `place` writes of the place alone, the rotation
    /// being there already.
    #[inline(always)]
    pub fn move_to(&mut self, rt: &DMat3, sphereo: Points) {
        self.transfm.w_axis = sphereo.extend(1.0);
        self.inverse.w_axis = (-(*rt * sphereo)).extend(1.0);
        self.sphereo = sphereo;
    }
}

/// `ray = record x0, x1, y0, y1, z0, z1 : real end`: the Pascal ray runs
/// from (x0, y0, z0) through (x1, y1, z1); here `origin` is the first point
/// and `dir` the difference (x1 − x0, y1 − y0, z1 − z0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
}

impl Ray {
    pub fn new(origin: DVec3, dir: DVec3) -> Self {
        Ray { origin, dir }
    }

    /// The point at parameter `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.dir * t
    }

    /// The ray carried by an affine transform (`transformray`).
    pub fn transformed(&self, m: &DMat4) -> Ray {
        Ray {
            origin: m.transform_point3(self.origin),
            dir: m.transform_vector3(self.dir),
        }
    }
}

/// `intersectionrecord` of Fig. 4.3 (the second "圖 4.3"): what a hit
/// returns to shading. `status` is the `Option` around it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntersectionRecord {
    /// `dx, dy, dz`: the unit outward normal, in world coordinates.
    pub normal: DVec3,
    /// `px, py, pz`: the fudged-out intersection point (just outside).
    pub p: DVec3,
    /// `insidepx, insidepy, insidepz`: the fudged-in point (just inside).
    pub insidep: DVec3,
    /// `surface`: index into [`Scene::surfaces`](crate::scene::Scene::surfaces).
    pub surface: usize,
    /// `parameter`: the ray parameter of the hit (the `dir` is unit length
    /// for every ray the port traces, so this is also Fig. 4.3's
    /// `distance`, from the ray's origin to the hit, which the port does
    /// not keep apart: nothing reads it, and it cost a square root a hit).
    pub parameter: f64,
    /// The object hit (index into [`Scene::objects`](crate::scene::Scene::objects)); not in Fig. 4.3.
    pub object: usize,
    /// The hit point in the object's local frame; not in Fig. 4.3: patterns
    /// and textures are painted from it.
    pub local: DVec3,
    /// The local outward normal, before transforming (chooses the block face
    /// a pattern or texture is painted on).
    pub local_normal: DVec3,
}

/// A hit in an object's local frame, as a shape's intersection returns it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalHit {
    /// Ray parameter of the hit (rays are rigidly transformed, so this is the
    /// world parameter too).
    pub t: f64,
    /// The hit point, local frame.
    pub point: DVec3,
    /// Unit outward normal, local frame.
    pub normal: DVec3,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `width`×`height` texture whose texel number i (row-major from the
    /// top) holds the bytes [i, 2i + 1, 255 − i]: a lookup names the texel
    /// it took.
    fn numbered(width: usize, height: usize) -> Texture {
        let texels = (0..width * height)
            .map(|i| [i as u8, (2 * i + 1) as u8, 255 - i as u8])
            .collect();
        Texture { width, height, texels }
    }

    /// The number of the texel a lookup took (and its three channels are
    /// that texel's).
    fn taken(tex: &Texture, s: f64, t: f64) -> usize {
        let c = tex.texel(s, t);
        let i = (c.x * 255.0).round() as usize;
        let [r, g, b] = tex.texels[i];
        assert_eq!(c.to_array(), [r, g, b].map(|c| c as f64 / 255.0), "({s}, {t})");
        i
    }

    /// Nearest texels of non-square textures: every texel at its centre;
    /// s to the right, t upward with row 0 at the top; the texel's own
    /// lower-left edge is its (exactly, on a dyadic grid), one ulp below it
    /// the neighbour's; s, t at 1 and beyond the square clamp to the last
    /// column and the top row, below 0 to the first.
    #[test]
    fn texel_at_centres_edges_and_beyond() {
        for (w, h) in [(3, 2), (2, 3), (4, 2), (5, 4), (1, 3), (3, 1)] {
            let tex = numbered(w, h);
            for row in 0..h {
                let up = h - 1 - row; // rows counted from the bottom
                for col in 0..w {
                    let s = (col as f64 + 0.5) / w as f64;
                    let t = (up as f64 + 0.5) / h as f64;
                    assert_eq!(taken(&tex, s, t), row * w + col, "{w}×{h} ({col}, {row})");
                }
            }
            let last = w - 1;
            assert_eq!(taken(&tex, 1.0, 1.0), last, "{w}×{h}");
            assert_eq!(taken(&tex, 7.0, 2.0), last, "{w}×{h}");
            assert_eq!(taken(&tex, 1.0, 0.0), (h - 1) * w + last, "{w}×{h}");
            assert_eq!(taken(&tex, 0.0, 0.0), (h - 1) * w, "{w}×{h}");
            assert_eq!(taken(&tex, -3.0, -0.5), (h - 1) * w, "{w}×{h}");
            assert_eq!(taken(&tex, -1.0, 1.0), 0, "{w}×{h}");
        }
        // 4×2: the edges s = 1/4, 1/2, 3/4 and t = 1/2 are exact.
        let tex = numbered(4, 2);
        for col in 1..4 {
            let s = col as f64 / 4.0;
            assert_eq!(taken(&tex, s, 0.75), col, "s = {s}");
            assert_eq!(taken(&tex, s.next_down(), 0.75), col - 1, "s below {s}");
            assert_eq!(taken(&tex, s, 0.25), 4 + col, "s = {s}");
        }
        assert_eq!(taken(&tex, 0.6, 0.5), 2, "t = 1/2 is the top row's edge");
        assert_eq!(taken(&tex, 0.6, 0.5f64.next_down()), 6);
    }
}

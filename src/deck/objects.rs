//! The object records `sphere`, `block`, `cylinder`, `prism` and `sweep`,
//! and the geometry `initialize` computes for them: the transforms
//! (`transfm`, `inverse`), the bounding `radius`, the prism's convexity.
//! Reconstructed (see the module comment of [`super`]).

use glam::{DMat3, DMat4, DVec2, DVec3};

use super::parse::Num;
use super::{Builder, DeckError, ObjEntry, MAX_OBJECTS};
use crate::scene::Pos;
use crate::types::{Axis, CurveKind, ObjectRecord, PrimitiveClass, Shape, SweepShape, MAXSEGMENTS};

/// The cosine and sine of an angle in degrees; exact for whole multiples of
/// 90°, so that quarter turns and `axis` give exact matrices.
fn cos_sin_deg(deg: f64) -> (f64, f64) {
    let r = deg.rem_euclid(360.0);
    if r == 0.0 {
        (1.0, 0.0)
    } else if r == 90.0 {
        (0.0, 1.0)
    } else if r == 180.0 {
        (-1.0, 0.0)
    } else if r == 270.0 {
        (0.0, -1.0)
    } else {
        let rad = deg.to_radians();
        (rad.cos(), rad.sin())
    }
}

/// R_axis(deg): the right-handed rotation about a world axis.
pub(super) fn rotation(axis: Axis, deg: f64) -> DMat3 {
    let (c, s) = cos_sin_deg(deg);
    match axis {
        Axis::X => DMat3::from_cols(DVec3::X, DVec3::new(0.0, c, s), DVec3::new(0.0, -s, c)),
        Axis::Y => DMat3::from_cols(DVec3::new(c, 0.0, -s), DVec3::Y, DVec3::new(s, 0.0, c)),
        Axis::Z => DMat3::from_cols(DVec3::new(c, s, 0.0), DVec3::new(-s, c, 0.0), DVec3::Z),
    }
}

/// A(axis): maps local z onto the named world axis (`x`: +90° about y;
/// `y`: −90° about x; `z`: the identity).
pub(super) fn axis_matrix(axis: Axis) -> DMat3 {
    match axis {
        Axis::X => rotation(Axis::Y, 90.0),
        Axis::Y => rotation(Axis::X, -90.0),
        Axis::Z => DMat3::IDENTITY,
    }
}

/// `transfm` = T(sphereo) · R · A and its exact inverse Aᵀ · Rᵀ · T(−sphereo).
pub(super) fn transforms(sphereo: DVec3, rot: DMat3, axis: DMat3) -> (DMat4, DMat4) {
    let ra = rot * axis;
    let transfm = DMat4::from_translation(sphereo) * DMat4::from_mat3(ra);
    let inverse = DMat4::from_mat3(ra.transpose()) * DMat4::from_translation(-sphereo);
    (transfm, inverse)
}

/// Whether a class is a sweep class.
pub(super) fn is_sweep(class: PrimitiveClass) -> bool {
    matches!(
        class,
        PrimitiveClass::Translation | PrimitiveClass::Conic | PrimitiveClass::Rotation
    )
}

/// A class as a message names it.
pub(super) fn class_name(class: PrimitiveClass) -> &'static str {
    match class {
        PrimitiveClass::Block => "block",
        PrimitiveClass::Cylinder => "cylinder",
        PrimitiveClass::Sphere => "sphere",
        PrimitiveClass::Prism => "prism",
        PrimitiveClass::Translation => "translation sweep",
        PrimitiveClass::Conic => "conic sweep",
        PrimitiveClass::Rotation => "rotation sweep",
        PrimitiveClass::Blob => "blob",
        PrimitiveClass::Patch => "patch",
    }
}

/// The largest U² + V² of a point list.
fn max_r2(points: &[[f64; 2]]) -> f64 {
    points.iter().map(|p| p[0] * p[0] + p[1] * p[1]).fold(0.0, f64::max)
}

/// Why a prism's polygon is refused: the vertex (0-based) and the message.
#[derive(Debug, PartialEq)]
pub(super) struct PolygonFault {
    pub vertex: usize,
    pub message: String,
}

/// Checks that `pts` (at least 3) is a strictly convex polygon and returns
/// it counter-clockwise. Refused: a vertex in line with its neighbours or
/// repeating one, a reflex vertex, a polygon winding more than once.
pub(super) fn convex_ccw(pts: &[[f64; 2]]) -> Result<Vec<[f64; 2]>, PolygonFault> {
    let n = pts.len();
    let p = |i: usize| DVec2::from_array(pts[i % n]);
    let area2: f64 = (0..n).map(|i| p(i).perp_dot(p(i + 1))).sum();
    let mut turns = Vec::with_capacity(n);
    for i in 0..n {
        let before = p(i) - p(i + n - 1);
        let after = p(i + 1) - p(i);
        let cross = before.perp_dot(after);
        if cross.abs() <= 1e-12 * before.length() * after.length() {
            return Err(PolygonFault {
                vertex: i,
                message: format!("vertex {} is in line with its neighbours or repeats one", i + 1),
            });
        }
        turns.push((cross, cross.atan2(before.dot(after))));
    }
    let sign = if area2 != 0.0 {
        area2.signum()
    } else {
        turns[0].0.signum()
    };
    for (i, (cross, _)) in turns.iter().enumerate() {
        if cross.signum() != sign {
            return Err(PolygonFault {
                vertex: i,
                message: format!("the polygon is not convex at vertex {}", i + 1),
            });
        }
    }
    let mut total = 0.0;
    for (i, (_, angle)) in turns.iter().enumerate() {
        total += angle.abs();
        if total > std::f64::consts::TAU + 1e-9 {
            return Err(PolygonFault {
                vertex: i,
                message: format!("the polygon crosses itself at vertex {}", i + 1),
            });
        }
    }
    let mut out = pts.to_vec();
    if sign < 0.0 {
        out.reverse();
    }
    Ok(out)
}

/// What an object record gives, before its pose is complete.
pub(super) struct NewObject {
    pub(super) name: String,
    pub(super) class: PrimitiveClass,
    pub(super) surface: usize,
    pub(super) sphereo: DVec3,
    pub(super) radius: f64,
    pub(super) shape: Shape,
}

/// The points of a prism or sweep: (U, V), where each U stands, and where
/// `end` stands.
struct PointList {
    points: Vec<[f64; 2]>,
    places: Vec<Pos>,
    end: Pos,
}

/// A point list's limit: the most points, and the message past it.
struct Limit {
    points: usize,
    message: String,
}

impl Builder<'_> {
    /// `NAME SURFACE` of an object record: the name (which becomes the
    /// record's) and the surface index.
    pub(super) fn declare(&mut self) -> Result<(String, usize), DeckError> {
        let (name, pos) = self.p.name("an object name")?;
        self.p.name = Some(name.clone());
        if self.entries.len() >= MAX_OBJECTS {
            return Err(self.p.error_at(
                pos,
                format!(
                    "a deck may have at most {MAX_OBJECTS} object records (the port's limit, which keeps a render of \
                     the largest deck within about 1.5 GB of memory): this is one more"
                ),
            ));
        }
        if let Some(&i) = self.object_index.get(&name) {
            let line = self.entries[i].pos.line;
            return Err(self
                .p
                .error_at(pos, format!("the object name '{name}' is already used on line {line}")));
        }
        let (surface, _) = self.surface_ref()?;
        Ok((name, surface))
    }

    /// `at X Y Z`.
    pub(super) fn at(&mut self) -> Result<DVec3, DeckError> {
        self.p.keyword("at")?;
        self.p.vec3("after 'at'")
    }

    /// An optional `axis x|y|z` field's value.
    fn axis(&mut self) -> Result<Axis, DeckError> {
        Ok(self
            .p
            .choice("an axis", &[("x", Axis::X), ("y", Axis::Y), ("z", Axis::Z)])?
            .0)
    }

    /// Adds an object to the scene; `transfm` and `inverse` are computed
    /// when the deck is read to its end.
    pub(super) fn push_object(&mut self, pos: Pos, axis: Axis, o: NewObject) {
        self.object_index.insert(o.name.clone(), self.entries.len());
        self.entries.push(ObjEntry {
            record: ObjectRecord {
                name: o.name,
                class: o.class,
                surface: o.surface,
                transfm: DMat4::IDENTITY,
                inverse: DMat4::IDENTITY,
                sphereo: o.sphereo,
                angle: DVec3::ZERO,
                radius: o.radius,
                shape: o.shape,
            },
            pos,
            rot: DMat3::IDENTITY,
            axis: axis_matrix(axis),
            deleted: false,
            motion_line: None,
            keyframe_line: None,
            key_rest: false,
        });
    }

    /// `sphere NAME SURFACE at X Y Z radius R`.
    pub(super) fn sphere(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("sphere");
        let (name, surface) = self.declare()?;
        let sphereo = self.at()?;
        self.p.keyword("radius")?;
        let radius = self.p.size("after 'radius'")?.value;
        self.p.end_of_line()?;
        self.push_object(
            pos,
            Axis::Z,
            NewObject {
                name,
                class: PrimitiveClass::Sphere,
                surface,
                sphereo,
                radius,
                shape: Shape::Sphere,
            },
        );
        Ok(())
    }

    /// `block NAME SURFACE at X Y Z size LX LY LZ`: a box centred on
    /// `sphereo`.
    pub(super) fn block(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("block");
        let (name, surface) = self.declare()?;
        let sphereo = self.at()?;
        self.p.keyword("size")?;
        let lx = self.p.size("after 'size'")?.value;
        let ly = self.p.size("after 'size'")?.value;
        let lz = self.p.size("after 'size'")?.value;
        self.p.end_of_line()?;
        let lengths = DVec3::new(lx, ly, lz);
        let radius = lengths.length() / 2.0;
        self.push_object(
            pos,
            Axis::Z,
            NewObject {
                name,
                class: PrimitiveClass::Block,
                surface,
                sphereo,
                radius,
                shape: Shape::Block { lengths },
            },
        );
        Ok(())
    }

    /// `cylinder NAME SURFACE at X Y Z radius R bottom B top T [axis x|y|z]`.
    pub(super) fn cylinder(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("cylinder");
        let (name, surface) = self.declare()?;
        let sphereo = self.at()?;
        self.p.keyword("radius")?;
        let cylradius = self.p.size("after 'radius'")?.value;
        self.p.keyword("bottom")?;
        let bottom: Num = self.p.number("after 'bottom'")?;
        self.p.keyword("top")?;
        let b = bottom.value;
        let top = self
            .p
            .number_where("after 'top'", &format!("> {}", bottom.text), |t| t > b)?
            .value;
        let mut orient = Axis::Z;
        let mut seen = Vec::new();
        while self.p.field(&["axis"], &mut seen)?.is_some() {
            orient = self.axis()?;
        }
        self.p.end_of_line()?;
        let radius = (cylradius * cylradius + (b * b).max(top * top)).sqrt();
        let shape = Shape::Cylinder {
            cylradius,
            orient,
            top,
            bottom: b,
        };
        self.push_object(
            pos,
            orient,
            NewObject {
                name,
                class: PrimitiveClass::Cylinder,
                surface,
                sphereo,
                radius,
                shape,
            },
        );
        Ok(())
    }

    /// The lines `U V` … `end` after a prism's or sweep's first line.
    /// `u_radius`: U is a radius (≥ 0).
    fn point_list(&mut self, limit: Option<Limit>, u_radius: bool) -> Result<PointList, DeckError> {
        let mut points = Vec::new();
        let mut places = Vec::new();
        loop {
            self.p.skip_blank_lines()?;
            let word = self.p.peek_word()?;
            match word {
                Some((w, pos)) if w.eq_ignore_ascii_case("end") => {
                    self.p.keyword("end")?;
                    self.p.end_of_line()?;
                    return Ok(PointList {
                        points,
                        places,
                        end: pos,
                    });
                }
                Some((w, pos)) if super::lex::is_number(&w) => {
                    if let Some(l) = &limit {
                        if points.len() == l.points {
                            return Err(self.p.error_at(pos, l.message.clone()));
                        }
                    }
                    let u = if u_radius {
                        self.p.number_where("for U (a radius)", ">= 0", |u| u >= 0.0)?
                    } else {
                        self.p.number("for U")?
                    };
                    let v = self.p.number("for V")?;
                    if !self.p.at_eol()? {
                        return Err(self.p.expected("end of line after the point 'U V'"));
                    }
                    self.p.end_of_line()?;
                    points.push([u.value, v.value]);
                    places.push(u.pos);
                }
                _ => return Err(self.p.expected("a point 'U V' or 'end'")),
            }
        }
    }

    /// `prism NAME SURFACE at X Y Z height H [axis x|y|z]`, then the
    /// vertices `U V` on lines, then `end`.
    pub(super) fn prism(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("prism");
        let (name, surface) = self.declare()?;
        let sphereo = self.at()?;
        self.p.keyword("height")?;
        let height = self.p.size("after 'height'")?.value;
        let mut orientp = Axis::Z;
        let mut seen = Vec::new();
        while self.p.field(&["axis"], &mut seen)?.is_some() {
            orientp = self.axis()?;
        }
        self.p.end_of_line()?;
        let PointList { points, places, end } = self.point_list(None, false)?;
        if points.len() < 3 {
            return Err(self.p.error_at(
                end,
                format!("a prism needs at least 3 vertices, found {}", points.len()),
            ));
        }
        let vertex = convex_ccw(&points).map_err(|f| self.p.error_at(places[f.vertex].clone(), f.message))?;
        let radius = (max_r2(&vertex) + height * height).sqrt();
        let shape = Shape::Prism {
            orientp,
            height,
            vertex,
        };
        self.push_object(
            pos,
            orientp,
            NewObject {
                name,
                class: PrimitiveClass::Prism,
                surface,
                sphereo,
                radius,
                shape,
            },
        );
        Ok(())
    }

    /// `sweep NAME SURFACE translation|conic|rotation bspline|bezier at X Y Z
    /// [length L] [scale S] [axis x|y|z]`, then the control points `U V` on
    /// lines, then `end`.
    pub(super) fn sweep(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("sweep");
        let (name, surface) = self.declare()?;
        let (class, _) = self.p.choice(
            "a sweep class",
            &[
                ("translation", PrimitiveClass::Translation),
                ("conic", PrimitiveClass::Conic),
                ("rotation", PrimitiveClass::Rotation),
            ],
        )?;
        let (curve, _) = self.p.choice(
            "a curve",
            &[("bspline", CurveKind::Bspline), ("bezier", CurveKind::Bezier)],
        )?;
        let sphereo = self.at()?;
        let mut length = None;
        let mut scale = None;
        let mut orientt = Axis::Z;
        let mut seen = Vec::new();
        while let Some((field, fpos)) = self.p.field(&["length", "scale", "axis"], &mut seen)? {
            match field {
                "length" => {
                    if class == PrimitiveClass::Rotation {
                        return Err(self.p.error_at(fpos, "a rotation sweep takes no 'length'"));
                    }
                    length = Some(self.p.size("after 'length'")?.value);
                }
                "scale" => {
                    if class != PrimitiveClass::Conic {
                        return Err(self.p.error_at(
                            fpos,
                            format!("only a conic sweep takes 'scale', not a {}", class_name(class)),
                        ));
                    }
                    scale = Some(self.p.number_where("after 'scale'", ">= 0", |s| s >= 0.0)?.value);
                }
                _ => orientt = self.axis()?,
            }
        }
        let length = match (class, length) {
            (PrimitiveClass::Rotation, _) => 0.0,
            (_, Some(l)) => l,
            (_, None) => {
                let pos = self.p.pos();
                return Err(self
                    .p
                    .error_at(pos, format!("a {} needs 'length L'", class_name(class))));
            }
        };
        let scale = match (class, scale) {
            (PrimitiveClass::Conic, Some(s)) => s,
            (PrimitiveClass::Conic, None) => {
                let pos = self.p.pos();
                return Err(self.p.error_at(pos, "a conic sweep needs 'scale S'"));
            }
            _ => 1.0,
        };
        self.p.end_of_line()?;
        let limit = match curve {
            CurveKind::Bspline => Limit {
                points: MAXSEGMENTS,
                message: format!("more than {MAXSEGMENTS} segments: a bspline contour has one segment per point"),
            },
            CurveKind::Bezier => Limit {
                points: 3 * MAXSEGMENTS,
                message: format!("more than {MAXSEGMENTS} segments: a bezier contour has one segment per 3 points"),
            },
        };
        let PointList { points, end, .. } = self.point_list(Some(limit), class == PrimitiveClass::Rotation)?;
        let n = points.len();
        let segment = match curve {
            CurveKind::Bspline if n < 4 => {
                return Err(self
                    .p
                    .error_at(end, format!("a bspline contour needs at least 4 points, found {n}")));
            }
            CurveKind::Bspline => n,
            CurveKind::Bezier if n % 3 != 0 => {
                return Err(self
                    .p
                    .error_at(end, format!("a bezier contour needs a multiple of 3 points, found {n}")));
            }
            CurveKind::Bezier if n < 6 => {
                return Err(self.p.error_at(
                    end,
                    format!("a bezier contour needs at least 6 points (2 segments), found {n}"),
                ));
            }
            CurveKind::Bezier => n / 3,
        };
        let radius = match class {
            PrimitiveClass::Rotation => max_r2(&points).sqrt(),
            PrimitiveClass::Conic => (max_r2(&points) * scale.max(1.0).powi(2) + length * length).sqrt(),
            _ => (max_r2(&points) + length * length).sqrt(),
        };
        let shape = Shape::Sweep(SweepShape {
            orientt,
            curve,
            points,
            segment,
            u: Vec::new(),
            v: Vec::new(),
            length,
            scale,
            bbox: Default::default(),
            orientation: 0.0,
        });
        self.push_object(
            pos,
            orientt,
            NewObject {
                name,
                class,
                surface,
                sphereo,
                radius,
                shape,
            },
        );
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turns_are_exact() {
        let m = rotation(Axis::Z, 90.0);
        assert_eq!(m * DVec3::X, DVec3::Y);
        assert_eq!(rotation(Axis::X, -270.0) * DVec3::Y, DVec3::Z);
        assert_eq!(axis_matrix(Axis::X) * DVec3::Z, DVec3::X);
        assert_eq!(axis_matrix(Axis::Y) * DVec3::Z, DVec3::Y);
        assert_eq!(axis_matrix(Axis::Z) * DVec3::Z, DVec3::Z);
    }

    #[test]
    fn rotations_are_right_handed() {
        let m = rotation(Axis::Z, 30.0);
        let p = m * DVec3::X;
        assert!((p - DVec3::new(3f64.sqrt() / 2.0, 0.5, 0.0)).length() < 1e-15);
        assert!((rotation(Axis::X, 90.0) * DVec3::Y - DVec3::Z).length() == 0.0);
        assert!((rotation(Axis::Y, 90.0) * DVec3::Z - DVec3::X).length() == 0.0);
    }

    #[test]
    fn inverse_undoes_transfm() {
        let rot = rotation(Axis::X, 33.0) * rotation(Axis::Z, -71.0);
        let (t, inv) = transforms(DVec3::new(1.0, -2.0, 5.0), rot, axis_matrix(Axis::Y));
        let d = (inv * t - DMat4::IDENTITY).to_cols_array();
        assert!(d.iter().all(|x| x.abs() < 1e-15), "{d:?}");
    }

    #[test]
    fn convex_polygons_come_out_counter_clockwise() {
        let cw = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
        assert_eq!(
            convex_ccw(&cw),
            Ok(vec![[1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 0.0]])
        );
        let ccw = [[0.0, 0.0], [2.0, 0.0], [0.0, 1.0]];
        assert_eq!(convex_ccw(&ccw), Ok(ccw.to_vec()));
    }

    #[test]
    fn bad_polygons_are_refused_at_the_vertex() {
        let reflex = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.5], [2.0, 2.0], [0.0, 2.0]];
        assert_eq!(convex_ccw(&reflex).map_err(|f| f.vertex), Err(2));
        let collinear = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [1.0, 1.0]];
        assert_eq!(convex_ccw(&collinear).map_err(|f| f.vertex), Err(1));
        let repeated = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        assert!(convex_ccw(&repeated).is_err());
        let line = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]];
        assert!(convex_ccw(&line).is_err());
        // A pentagram turns the same way at every vertex but winds twice.
        let star: Vec<[f64; 2]> = (0..5)
            .map(|k| {
                let a = (k as f64) * 4.0 * std::f64::consts::PI / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        let fault = convex_ccw(&star).unwrap_err();
        assert!(fault.message.contains("crosses itself"), "{}", fault.message);
    }
}

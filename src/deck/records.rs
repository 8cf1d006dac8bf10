//! The records that are not objects: `view`, `image`, `background`,
//! `light`, `surface`, `paint`, `texture`, `rotate`, `translate`, `delete`,
//! `motion`, `keyframe`, `blur`, `pattern`. Reconstructed (see the module
//! comment of [`super`]).

use glam::DVec3;

use super::library::PathFields;
use super::objects::rotation;
use super::{Builder, DeckError, PendingKeyframe, PendingMotion, SurfaceInfo, MAX_MAGNITUDE};
use crate::options::Fidelity;
use crate::raster::read_raster_file_within;
use crate::scene::{BlurRecord, Expander, ImageSpec, Law, LightRecord, MotionRecord, PatternRecord, Pos, View};
use crate::types::{Axis, Paint, PaintKind, PrimitiveClass, SurfaceAttribute, SurfaceRecord, Texture};

/// The largest `blur N`: the CLT sum costs N uniforms a sample.
const MAX_BLUR: i64 = 1000;
/// The largest `pattern M`.
const MAX_PATTERN: i64 = 16;
/// The largest image side.
const MAX_SIDE: i64 = 8192;
/// The largest `mask` (`masksize`).
const MAX_MASK: i64 = 8;

impl Builder<'_> {
    /// An error for a record that may stand once in a deck.
    pub(super) fn second(&self, pos: Pos, keyword: &str, first: Pos) -> DeckError {
        self.p.error_at(
            pos,
            format!("a second '{keyword}' record (the first is on line {})", first.line),
        )
    }

    /// R G B: each in 0..1, or any number ≥ 0 if `emissive`.
    pub(super) fn rgb(&mut self, what: [&str; 3], emissive: bool) -> Result<DVec3, DeckError> {
        let mut c = [0.0; 3];
        for (k, w) in what.iter().enumerate() {
            c[k] = if emissive {
                self.p.number_where(w, ">= 0", |v| v >= 0.0)?.value
            } else {
                self.p.unit(w)?.value
            };
        }
        Ok(DVec3::from_array(c))
    }

    /// A surface named by a record; its index.
    pub(super) fn surface_ref(&mut self) -> Result<(usize, Pos), DeckError> {
        let (name, pos) = self.p.name("a surface name")?;
        match self.surface_index.get(&name) {
            Some(&i) => Ok((i, pos)),
            None => {
                let known: Vec<&str> = self.surfaces.iter().map(|s| s.name.as_str()).collect();
                let hint = super::parse::did_you_mean(&name, &known);
                Err(self.p.error_at(pos, format!("unknown surface '{name}'{hint}")))
            }
        }
    }

    /// An object named by a record and still in the scene: its index in
    /// `entries`. Becomes the record's name.
    pub(super) fn object_ref(&mut self) -> Result<(usize, Pos), DeckError> {
        let (name, pos) = self.p.name("an object name")?;
        match self.object_index.get(&name) {
            Some(&i) => {
                self.p.name = Some(name);
                Ok((i, pos))
            }
            None => {
                // Sorted: the suggestion must not depend on the map's order.
                let mut known: Vec<&str> = self.object_index.keys().map(String::as_str).collect();
                known.sort_unstable();
                let hint = super::parse::did_you_mean(&name, &known);
                Err(self.p.error_at(pos, format!("unknown object '{name}'{hint}")))
            }
        }
    }

    /// Refuses to change the pose of an object that has a motion or is a
    /// key shape (`doing`: "turned", "moved", "deleted").
    fn pose_free(&self, i: usize, pos: Pos, doing: &str) -> Result<(), DeckError> {
        let e = &self.entries[i];
        let name = &e.record.name;
        if let Some(line) = e.motion_line {
            return Err(self.p.error_at(
                pos,
                format!("'{name}' has a motion (line {line}) and can no longer be {doing}"),
            ));
        }
        if let Some(line) = e.keyframe_line {
            return Err(self.p.error_at(
                pos,
                format!("'{name}' is a key shape (keyframe on line {line}) and can no longer be {doing}"),
            ));
        }
        Ok(())
    }

    /// `view eye X Y Z look X Y Z screen SIZE distance D`.
    pub(super) fn view(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("view");
        if let Some((_, first)) = &self.view {
            return Err(self.second(pos, "view", first.clone()));
        }
        self.p.keyword("eye")?;
        let eyept = self.p.vec3("after 'eye'")?;
        let look_pos = self.p.keyword("look")?;
        let lookpt = self.p.vec3("after 'look'")?;
        let d = eyept - lookpt;
        let across = d.x.hypot(d.y);
        if across <= 1e-9 * across.hypot(d.z) || d == DVec3::ZERO {
            return Err(self.p.error_at(
                look_pos,
                "the eye is straight above or below the look point (world z must be up in the image)",
            ));
        }
        self.p.keyword("screen")?;
        let screensize = self.p.size("after 'screen'")?.value;
        self.p.keyword("distance")?;
        let scrndistance = self.p.size("after 'distance'")?.value;
        self.p.end_of_line()?;
        self.view = Some((
            View {
                eyept,
                lookpt,
                screensize,
                scrndistance,
            },
            pos,
        ));
        Ok(())
    }

    /// `image WIDTH HEIGHT mask M [aliasing A]`.
    pub(super) fn image(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("image");
        if let Some((_, first)) = &self.image {
            return Err(self.second(pos, "image", first.clone()));
        }
        let (width, _) = self.p.integer("for WIDTH", 1, MAX_SIDE)?;
        let (height, _) = self.p.integer("for HEIGHT", 1, MAX_SIDE)?;
        self.p.keyword("mask")?;
        let (masksize, _) = self.p.integer("after 'mask'", 1, MAX_MASK)?;
        let mut aliasing = 0.0;
        let mut seen = Vec::new();
        while let Some((field, _)) = self.p.field(&["aliasing"], &mut seen)? {
            if field == "aliasing" {
                aliasing = self.p.unit("after 'aliasing'")?.value;
            }
        }
        self.p.end_of_line()?;
        // The ranges above make the casts exact.
        self.image = Some((
            ImageSpec {
                width: width as usize,
                height: height as usize,
                masksize: masksize as usize,
                aliasing,
            },
            pos,
        ));
        Ok(())
    }

    /// `background R G B`.
    pub(super) fn background(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("background");
        if let Some((_, first)) = &self.background {
            return Err(self.second(pos, "background", first.clone()));
        }
        let c = self.rgb(["for R", "for G", "for B"], false)?;
        self.p.end_of_line()?;
        self.background = Some((c, pos));
        Ok(())
    }

    /// `light NAME X Y Z R G B [radius R]`: R ≥ 0, a sphere of light (the
    /// port's extension; 0, the default, the base program's point).
    pub(super) fn light(&mut self) -> Result<(), DeckError> {
        self.p.begin("light");
        let (name, pos) = self.p.name("a light name")?;
        self.p.name = Some(name.clone());
        if let Some((_, first)) = self.light_index.get(&name) {
            let line = self.line_of(first);
            return Err(self
                .p
                .error_at(pos, format!("the light name '{name}' is already used on {line}")));
        }
        let x = self.p.number("for X")?.value;
        let y = self.p.number("for Y")?.value;
        let z = self.p.number("for Z")?.value;
        let color = self.rgb(["for R", "for G", "for B"], false)?;
        let mut radius = 0.0;
        let mut seen = Vec::new();
        if self.p.field(&["radius"], &mut seen)?.is_some() {
            radius = self.p.number_where("after 'radius'", ">= 0", |v| v >= 0.0)?.value;
        }
        self.p.end_of_line()?;
        self.light_index.insert(name.clone(), (self.lights.len(), pos));
        self.lights.push(LightRecord {
            name,
            position: DVec3::new(x, y, z),
            color,
            radius,
        });
        Ok(())
    }

    /// `surface NAME KIND color R G B ka K kd K ks K kt K [ambient R G B]
    /// [reflect P] [index N] [gloss G]` (`gloss`, G ≥ 0, the port's
    /// extension: Cook 1984's blurred reflection).
    pub(super) fn surface(&mut self, record_pos: Pos) -> Result<(), DeckError> {
        self.p.begin("surface");
        let (name, pos) = self.p.name("a surface name")?;
        self.p.name = Some(name.clone());
        if let Some(&i) = self.surface_index.get(&name) {
            let line = self.line_of(&self.surface_info[i].pos);
            return Err(self
                .p
                .error_at(pos, format!("the surface name '{name}' is already used on {line}")));
        }
        let (surface, _) = self.p.choice(
            "a surface kind",
            &[
                ("opaque", SurfaceAttribute::Opaque),
                ("mirrored", SurfaceAttribute::Mirrored),
                ("transparent", SurfaceAttribute::Transparent),
                ("crystal", SurfaceAttribute::Crystal),
                ("light", SurfaceAttribute::Light),
                ("background", SurfaceAttribute::Background),
            ],
        )?;
        let emissive = surface == SurfaceAttribute::Light;
        self.p.keyword("color")?;
        let color = self.rgb(["after 'color'"; 3], emissive)?;
        self.p.keyword("ka")?;
        let ka = self.p.unit("after 'ka'")?.value;
        self.p.keyword("kd")?;
        let kd = self.p.unit("after 'kd'")?.value;
        self.p.keyword("ks")?;
        let ks = self.p.unit("after 'ks'")?.value;
        self.p.keyword("kt")?;
        let kt = self.p.unit("after 'kt'")?.value;
        let mut iobject = color;
        let mut prcntrfl = if surface == SurfaceAttribute::Mirrored {
            1.0
        } else {
            0.0
        };
        let mut index = 1.0;
        let mut gloss = 0.0;
        let mut seen = Vec::new();
        while let Some((field, _)) = self.p.field(&["ambient", "reflect", "index", "gloss"], &mut seen)? {
            match field {
                "ambient" => iobject = self.rgb(["after 'ambient'"; 3], emissive)?,
                "reflect" => prcntrfl = self.p.unit("after 'reflect'")?.value,
                "gloss" => gloss = self.p.number_where("after 'gloss'", ">= 0", |v| v >= 0.0)?.value,
                _ => index = self.p.size("after 'index'")?.value,
            }
        }
        self.p.end_of_line()?;
        self.surface_index.insert(name.clone(), self.surfaces.len());
        self.surface_info.push(SurfaceInfo {
            pos: record_pos,
            decoration: None,
        });
        self.surfaces.push(SurfaceRecord {
            name,
            color,
            ka,
            kd,
            ks,
            kt,
            iobject,
            surface,
            prcntrfl,
            index,
            paint: None,
            texture: None,
            gloss,
        });
        Ok(())
    }

    /// The surface a `paint` or `texture` record decorates; it may have no
    /// decoration yet.
    fn decorated_surface(&mut self, keyword: &'static str, record_pos: Pos) -> Result<usize, DeckError> {
        let (i, pos) = self.surface_ref()?;
        self.p.name = Some(self.surfaces[i].name.clone());
        if let Some((first, what)) = &self.surface_info[i].decoration {
            let line = self.line_of(first);
            return Err(self.p.error_at(
                pos,
                format!("the surface already has a {what} ({line}); it may have one paint or texture"),
            ));
        }
        self.surface_info[i].decoration = Some((record_pos, keyword));
        Ok(i)
    }

    /// `paint SURFACE floor|star|floorstar [scale LX LY] [color R G B]`.
    pub(super) fn paint(&mut self, record_pos: Pos) -> Result<(), DeckError> {
        self.p.begin("paint");
        let i = self.decorated_surface("paint", record_pos)?;
        let (kind, _) = self.p.choice(
            "a pattern",
            &[
                ("floor", PaintKind::Floor),
                ("star", PaintKind::Star),
                ("floorstar", PaintKind::Floorstar),
            ],
        )?;
        let (mut lengthx, mut lengthy) = (1.0, 1.0);
        let mut color = DVec3::ONE;
        let mut seen = Vec::new();
        while let Some((field, _)) = self.p.field(&["scale", "color"], &mut seen)? {
            if field == "scale" {
                lengthx = self.p.size("after 'scale'")?.value;
                lengthy = self.p.size("after 'scale'")?.value;
            } else {
                color = self.rgb(["after 'color'"; 3], false)?;
            }
        }
        self.p.end_of_line()?;
        self.surfaces[i].paint = Some(Paint {
            kind,
            lengthx,
            lengthy,
            color,
        });
        Ok(())
    }

    /// `texture SURFACE FILE`: FILE relative to the deck's folder.
    pub(super) fn texture(&mut self, record_pos: Pos) -> Result<(), DeckError> {
        self.p.begin("texture");
        let i = self.decorated_surface("texture", record_pos)?;
        let (file, file_pos) = self.p.word("a raster file name")?;
        self.p.end_of_line()?;
        let path = self.deck_dir.join(&file);
        let raster = read_raster_file_within(&path, super::TEXTURE_LIMIT)
            .map_err(|e| self.unreadable(file_pos.clone(), "raster file", &file, &path, e))?;
        if raster.width == 0
            || raster.height == 0
            || raster.width.checked_mul(raster.height) != Some(raster.pixels.len())
        {
            return Err(self.p.error_at(
                file_pos,
                format!(
                    "the raster file {} holds no picture ({}×{})",
                    super::parse::shown(&file),
                    raster.width,
                    raster.height
                ),
            ));
        }
        self.surfaces[i].texture = Some(Texture {
            width: raster.width,
            height: raster.height,
            texels: raster.pixels,
        });
        Ok(())
    }

    /// The error for a file a record names (`what`: "raster file") that
    /// cannot be read: named as written (`file`, at `pos`), then, as it is
    /// relative to the deck's folder, as found from there (`path`) unless
    /// that is the same path.
    pub(super) fn unreadable(
        &self,
        pos: Pos,
        what: &str,
        file: &str,
        path: &std::path::Path,
        e: impl std::fmt::Display,
    ) -> DeckError {
        let looked = if path.as_os_str() == file {
            String::new()
        } else {
            format!("; from the deck's folder, that is {}", super::parse::shown_path(path))
        };
        self.p.error_at(
            pos,
            format!("cannot read the {what} {}: {e}{looked}", super::parse::shown(file)),
        )
    }

    /// `rotate NAME x|y|z DEGREES`: R ← R_axis(DEGREES) · R, `angle` += DEGREES.
    pub(super) fn rotate(&mut self) -> Result<(), DeckError> {
        self.p.begin("rotate");
        let (i, pos) = self.object_ref()?;
        self.pose_free(i, pos, "turned")?;
        let (axis, _) = self
            .p
            .choice("an axis", &[("x", Axis::X), ("y", Axis::Y), ("z", Axis::Z)])?;
        let deg = self.p.number("for DEGREES")?.value;
        self.p.end_of_line()?;
        let e = &mut self.entries[i];
        e.rot = rotation(axis, deg) * e.rot;
        match axis {
            Axis::X => e.record.angle.x += deg,
            Axis::Y => e.record.angle.y += deg,
            Axis::Z => e.record.angle.z += deg,
        }
        Ok(())
    }

    /// `translate NAME X Y Z`: `sphereo` += (X, Y, Z).
    pub(super) fn translate(&mut self) -> Result<(), DeckError> {
        self.p.begin("translate");
        let (i, pos) = self.object_ref()?;
        self.pose_free(i, pos, "moved")?;
        let x = self.p.number("for X")?;
        let y = self.p.number("for Y")?;
        let z = self.p.number("for Z")?;
        self.p.end_of_line()?;
        let to = self.entries[i].record.sphereo + DVec3::new(x.value, y.value, z.value);
        if to.abs().max_element() > MAX_MAGNITUDE {
            return Err(self.p.error_at(
                x.pos,
                format!("this moves the object to ({}, {}, {}), out of the deck's range -{MAX_MAGNITUDE:e}..{MAX_MAGNITUDE:e}", to.x, to.y, to.z),
            ));
        }
        self.entries[i].record.sphereo = to;
        Ok(())
    }

    /// `delete NAME`: the object leaves the scene; its name is free again.
    pub(super) fn delete(&mut self) -> Result<(), DeckError> {
        self.p.begin("delete");
        let (i, pos) = self.object_ref()?;
        self.pose_free(i, pos, "deleted")?;
        self.p.end_of_line()?;
        self.entries[i].deleted = true;
        let name = self.entries[i].record.name.clone();
        self.object_index.remove(&name);
        Ok(())
    }

    /// `motion NAME to X Y Z [turn AX AY AZ] [via X1 Y1 Z1 X2 Y2 Z2]
    /// [law constant|accelerate|decelerate|smooth]`, or `motion NAME path
    /// PATH`, a path of the library (the port's extension, [`super::library`]).
    pub(super) fn motion(&mut self, record_pos: Pos) -> Result<(), DeckError> {
        self.p.begin("motion");
        let (i, pos) = self.object_ref()?;
        let e = &self.entries[i];
        if let Some(line) = e.motion_line {
            return Err(self
                .p
                .error_at(pos, format!("'{}' already has a motion (line {line})", e.record.name)));
        }
        if let Some(line) = e.keyframe_line {
            return Err(self.p.error_at(
                pos,
                format!(
                    "'{}' is a key shape (keyframe on line {line}) and cannot have a motion",
                    e.record.name
                ),
            ));
        }
        let (form, _) = self.p.keyword_of(&["to", "path"])?;
        let path = if form == "path" {
            self.library_path(i)?
        } else {
            let to = self.p.vec3("after 'to'")?;
            Some(self.path_fields(to)?)
        };
        self.p.end_of_line()?;
        self.entries[i].motion_line = Some(record_pos.line);
        // A path not defined (yet) leaves the error to `initialize`.
        let Some(path) = path else { return Ok(()) };
        self.motions.push(PendingMotion {
            record: MotionRecord {
                pos: record_pos,
                object: i,
                to: path.end,
                turn: path.turn,
                via: path.via,
                law: path.law,
            },
            entry: i,
        });
        Ok(())
    }

    /// The optional fields of a motion and of a library path, after its
    /// end point `end`: `[turn AX AY AZ] [via X1 Y1 Z1 X2 Y2 Z2] [law
    /// constant|accelerate|decelerate|smooth]`.
    pub(super) fn path_fields(&mut self, end: DVec3) -> Result<PathFields, DeckError> {
        let mut path = PathFields {
            end,
            turn: DVec3::ZERO,
            via: None,
            law: Law::Constant,
        };
        let mut seen = Vec::new();
        while let Some((field, _)) = self.p.field(&["turn", "via", "law"], &mut seen)? {
            match field {
                "turn" => path.turn = self.p.vec3("after 'turn'")?,
                "via" => {
                    let a = self.p.vec3("after 'via'")?;
                    let b = self.p.vec3("after 'via'")?;
                    path.via = Some([a, b]);
                }
                _ => {
                    path.law = self
                        .p
                        .choice(
                            "a law",
                            &[
                                ("constant", Law::Constant),
                                ("accelerate", Law::Accelerate),
                                ("decelerate", Law::Decelerate),
                                ("smooth", Law::Smooth),
                            ],
                        )?
                        .0
                }
            }
        }
        Ok(path)
    }

    /// `keyframe FIRST LAST [expander burtnyk|arclength]`, or a chain
    /// `keyframe A B C … [expander …]`.
    pub(super) fn keyframe(&mut self, record_pos: Pos) -> Result<(), DeckError> {
        self.p.begin("keyframe");
        let mut shapes: Vec<usize> = Vec::new();
        loop {
            let at_expander = matches!(self.p.peek_word()?, Some((w, _)) if w.eq_ignore_ascii_case("expander"));
            if self.p.at_eol()? || at_expander {
                break;
            }
            let (i, pos) = if shapes.is_empty() {
                self.object_ref()?
            } else {
                let name = self.p.name.take();
                let r = self.object_ref();
                self.p.name = name;
                r?
            };
            let e = &self.entries[i];
            let name = &e.record.name;
            let class = e.record.class;
            if !super::objects::is_sweep(class) && !matches!(class, PrimitiveClass::Blob | PrimitiveClass::Patch) {
                return Err(self.p.error_at(
                    pos,
                    format!(
                        "'{name}' is a {}, not a sweep, blob or patch: key shapes are sweeps of one class, blobs or patches",
                        super::objects::class_name(class)
                    ),
                ));
            }
            if let Some(&f) = shapes.first() {
                let first = &self.entries[f].record;
                if first.class != class {
                    return Err(self.p.error_at(
                        pos,
                        format!(
                            "'{name}' is a {} but '{}' is a {}: key shapes must be of one class",
                            super::objects::class_name(class),
                            first.name,
                            super::objects::class_name(first.class)
                        ),
                    ));
                }
            }
            if shapes.contains(&i) {
                return Err(self
                    .p
                    .error_at(pos, format!("'{name}' is named twice in this keyframe")));
            }
            if let Some(line) = e.keyframe_line {
                return Err(self.p.error_at(
                    pos,
                    format!("'{name}' is already a key shape of the keyframe on line {line}"),
                ));
            }
            if let Some(line) = e.motion_line {
                return Err(self.p.error_at(
                    pos,
                    format!("'{name}' has a motion (line {line}) and cannot be a key shape"),
                ));
            }
            shapes.push(i);
        }
        if shapes.len() < 2 {
            let what = if shapes.is_empty() {
                "the FIRST key shape's name"
            } else {
                "the LAST key shape's name"
            };
            return Err(self.p.expected(what));
        }
        let mut expander = Expander::Arclength;
        let mut seen = Vec::new();
        while let Some((_, at)) = self.p.field(&["expander"], &mut seen)? {
            let class = self.entries[shapes[0]].record.class;
            if !super::objects::is_sweep(class) {
                return Err(self.p.error_at(
                    at,
                    format!(
                        "an expander matches the segments of sweep contours; {}s are matched point by point",
                        super::objects::class_name(class)
                    ),
                ));
            }
            expander = self
                .p
                .choice(
                    "an expander",
                    &[("burtnyk", Expander::Burtnyk), ("arclength", Expander::Arclength)],
                )?
                .0;
        }
        self.p.end_of_line()?;
        for (k, &i) in shapes.iter().enumerate() {
            self.entries[i].keyframe_line = Some(record_pos.line);
            self.entries[i].key_rest = k > 0;
        }
        self.keyframes.push(PendingKeyframe {
            pos: record_pos,
            first: shapes[0],
            rest: shapes[1..].to_vec(),
            expander,
        });
        Ok(())
    }

    /// `blur N`.
    pub(super) fn blur(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("blur");
        if let Some(first) = &self.blur {
            return Err(self.second(pos, "blur", first.pos.clone()));
        }
        let (n, _) = self.p.integer("for N", 0, MAX_BLUR)?;
        self.p.end_of_line()?;
        self.blur = Some(BlurRecord { pos, n: n as u32 });
        Ok(())
    }

    /// `pattern M`, M rows of M integers on lines, `end`.
    ///
    /// Erratum 1: the printed table of Fig. 2.33 holds 10 twice and 9 never.
    /// `Fidelity::Thesis` wants a permutation of 0..M²−1 (a repeated value
    /// is an error); `Fidelity::Listing` accepts repeats as the listing did.
    pub(super) fn pattern(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("pattern");
        if let Some(first) = &self.pattern {
            return Err(self.second(pos, "pattern", first.pos.clone()));
        }
        let (m, _) = self.p.integer("for M", 1, MAX_PATTERN)?;
        self.p.end_of_line()?;
        let m = m as usize;
        let cells = m * m;
        let mut used = vec![false; cells];
        let mut values = Vec::with_capacity(m);
        for row in 1..=m {
            self.p.skip_blank_lines()?;
            if matches!(self.p.peek_word()?, Some((w, _)) if w.eq_ignore_ascii_case("end")) {
                return Err(self.p.expected(&format!("row {row} of {m}")));
            }
            let mut r = Vec::with_capacity(m);
            for _ in 0..m {
                let (v, vpos) = self.p.integer(&format!("for row {row}"), 0, cells as i64 - 1)?;
                let v = v as usize;
                if used[v] {
                    match self.fidelity {
                        Fidelity::Thesis => {
                            return Err(self.p.error_at(
                                vpos,
                                format!(
                                    "the value {v} appears twice: the table must be a permutation of 0..{} (erratum 1; the listing fidelity accepts repeats)",
                                    cells - 1
                                ),
                            ))
                        }
                        Fidelity::Listing => {}
                    }
                }
                used[v] = true;
                r.push(v as u32);
            }
            self.p.end_of_line()?;
            values.push(r);
        }
        self.p.skip_blank_lines()?;
        self.p.keyword("end")?;
        self.p.end_of_line()?;
        self.pattern = Some(PatternRecord { pos, m, values });
        Ok(())
    }
}

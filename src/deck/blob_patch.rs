//! The object records `blob` and `patch`: the soft objects and parametric
//! surfaces §6.2 names as what comes after the sweeps. The port's
//! extension (legacy_pascal/DECK.md, "Blobs and patches").

use glam::DVec3;

use super::objects::NewObject;
use super::{Builder, DeckError};
use crate::scene::Pos;
use crate::shapes::{blob_reach, patch_reach};
use crate::types::{Axis, BlobComponent, BlobShape, PatchShape, PrimitiveClass, Shape, MAXCOMPONENTS};

/// The control points of a patch: 4 rows of 4.
const PATCH_POINTS: usize = 16;

impl Builder<'_> {
    /// `blob NAME SURFACE at X Y Z threshold T`, then one component
    /// `X Y Z RADIUS STRENGTH` a line (1 to 60), then `end`. T and RADIUS
    /// are sizes (> 0); STRENGTH any number of the deck's range.
    pub(super) fn blob(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("blob");
        let (name, surface) = self.declare()?;
        let sphereo = self.at()?;
        self.p.keyword("threshold")?;
        let threshold = self.p.size("after 'threshold'")?.value;
        self.p.end_of_line()?;
        let mut components = Vec::new();
        let end = loop {
            self.p.skip_blank_lines()?;
            match self.p.peek_word()? {
                Some((w, at)) if w.eq_ignore_ascii_case("end") => {
                    self.p.keyword("end")?;
                    self.p.end_of_line()?;
                    break at;
                }
                Some((w, at)) if super::lex::is_number(&w) => {
                    if components.len() == MAXCOMPONENTS {
                        return Err(self.p.error_at(
                            at,
                            format!("more than {MAXCOMPONENTS} components: a blob has at most {MAXCOMPONENTS}"),
                        ));
                    }
                    let centre = self.p.vec3("for the component's X Y Z")?;
                    let radius = self.p.size("for RADIUS")?.value;
                    let strength = self.p.number("for STRENGTH")?.value;
                    if !self.p.at_eol()? {
                        return Err(self
                            .p
                            .expected("end of line after the component 'X Y Z RADIUS STRENGTH'"));
                    }
                    self.p.end_of_line()?;
                    components.push(BlobComponent {
                        centre,
                        radius,
                        strength,
                    });
                }
                _ => return Err(self.p.expected("a component 'X Y Z RADIUS STRENGTH' or 'end'")),
            }
        };
        if components.is_empty() {
            return Err(self
                .p
                .error_at(end, "a blob needs at least one component 'X Y Z RADIUS STRENGTH'"));
        }
        let shape = BlobShape { threshold, components };
        let radius = blob_reach(&shape);
        self.push_object(
            pos,
            Axis::Z,
            NewObject {
                name,
                class: PrimitiveClass::Blob,
                surface,
                sphereo,
                radius,
                shape: Shape::Blob(shape),
            },
        );
        Ok(())
    }

    /// `patch NAME SURFACE at X Y Z`, then the 16 control points `X Y Z`
    /// row by row (4 rows of 4; whole points on a line, several a line
    /// allowed), then `end`.
    pub(super) fn patch(&mut self, pos: Pos) -> Result<(), DeckError> {
        self.p.begin("patch");
        let (name, surface) = self.declare()?;
        let sphereo = self.at()?;
        self.p.end_of_line()?;
        let mut points = Vec::with_capacity(PATCH_POINTS);
        loop {
            self.p.skip_blank_lines()?;
            match self.p.peek_word()? {
                Some((w, at)) if w.eq_ignore_ascii_case("end") => {
                    if points.len() != PATCH_POINTS {
                        return Err(self.p.error_at(
                            at,
                            format!(
                                "a patch needs {PATCH_POINTS} control points (4 rows of 4), found {}",
                                points.len()
                            ),
                        ));
                    }
                    self.p.keyword("end")?;
                    self.p.end_of_line()?;
                    break;
                }
                Some((w, _)) if super::lex::is_number(&w) => {
                    while !self.p.at_eol()? {
                        if let Some((_, at)) = self.p.peek_word()?.filter(|_| points.len() == PATCH_POINTS) {
                            return Err(self.p.error_at(
                                at,
                                format!("more than {PATCH_POINTS} control points: a patch has 4 rows of 4"),
                            ));
                        }
                        points.push(self.p.vec3("for a control point's X Y Z")?);
                    }
                    self.p.end_of_line()?;
                }
                _ => return Err(self.p.expected("a control point 'X Y Z' or 'end'")),
            }
        }
        let points: [DVec3; PATCH_POINTS] = std::array::from_fn(|k| points[k]);
        let shape = PatchShape { points };
        let radius = patch_reach(&shape);
        self.push_object(
            pos,
            Axis::Z,
            NewObject {
                name,
                class: PrimitiveClass::Patch,
                surface,
                sphereo,
                radius,
                shape: Shape::Patch(Box::new(shape)),
            },
        );
        Ok(())
    }
}

//! The closed curve of a contour as the editor draws it: the segments'
//! coefficients from the port's own `spline` (through the same
//! `fill_segments` the renderer prepares a sweep with), each segment
//! sampled into a polyline, and the joints where one segment ends and the
//! next begins (§2.2.2–2.2.3).

use super::model::Contour;
use crate::shapes::sweep::fill_segments;
use crate::types::{Axis, BoundingBox, Coeff, SweepShape};

/// Points a segment is drawn through (its ends included).
pub(crate) const SAMPLES: usize = 32;

/// A sweep record holding `contour`'s points, its `u`, `v` filled by
/// `spline` (a B-spline of fewer than 4 points has no segment; a Bezier
/// uses its first 3k points).
pub fn shape(contour: &Contour) -> SweepShape {
    let mut sw = SweepShape {
        orientt: Axis::Z,
        curve: contour.curve,
        points: contour.uv(),
        segment: 0,
        u: Vec::new(),
        v: Vec::new(),
        length: contour.length,
        scale: contour.scale,
        bbox: BoundingBox::default(),
        orientation: 0.0,
    };
    if contour.segments() > 0 {
        fill_segments(contour.class, &mut sw);
    }
    sw
}

/// Each segment of (u, v) as a polyline of [`SAMPLES`] points over its
/// parameter range [first, last].
pub(crate) fn polylines(u: &[Coeff], v: &[Coeff]) -> Vec<Vec<[f64; 2]>> {
    u.iter()
        .zip(v)
        .map(|(cu, cv)| {
            (0..SAMPLES)
                .map(|k| {
                    let f = k as f64 / (SAMPLES - 1) as f64;
                    let (su, sv) = (cu.first + (cu.last - cu.first) * f, cv.first + (cv.last - cv.first) * f);
                    [cu.value(su), cv.value(sv)]
                })
                .collect()
        })
        .collect()
}

/// Where each segment starts: the joints of the closed curve.
pub fn joints(u: &[Coeff], v: &[Coeff]) -> Vec<[f64; 2]> {
    u.iter()
        .zip(v)
        .map(|(cu, cv)| [cu.value(cu.first), cv.value(cv.first)])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::types::{CurveKind, PrimitiveClass};

    fn contour(curve: CurveKind, points: &[[f64; 2]]) -> Contour {
        Contour::of_deck(PrimitiveClass::Translation, curve, points, 1.0, 1.0)
    }

    #[test]
    fn a_bspline_joint_is_a_sixth_of_its_neighbours() {
        // §2.2.3: x(0) of segment i = (x_i + 4 x_{i+1} + x_{i+2}) / 6.
        let pts = [[0.0, 0.0], [6.0, 0.0], [6.0, 6.0], [0.0, 6.0]];
        let sw = shape(&contour(CurveKind::Bspline, &pts));
        assert_eq!(sw.segment, 4);
        let j = joints(&sw.u, &sw.v);
        assert_eq!(j[0], [5.0, 1.0]);
        let lines = polylines(&sw.u, &sw.v);
        assert_eq!(lines.len(), 4);
        assert_eq!(lines[0][SAMPLES - 1], j[1], "a segment ends where the next begins");
        assert_eq!(lines[3][SAMPLES - 1], j[0], "the curve is closed");
    }

    #[test]
    fn a_bezier_passes_through_every_third_point() {
        let pts = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0], [2.0, 2.0], [1.0, 3.0], [0.0, 2.0]];
        let sw = shape(&contour(CurveKind::Bezier, &pts));
        assert_eq!(joints(&sw.u, &sw.v), vec![[0.0, 0.0], [2.0, 2.0]]);
        let lines = polylines(&sw.u, &sw.v);
        assert_eq!(lines[1][SAMPLES - 1], [0.0, 0.0]);
    }

    #[test]
    fn too_few_points_make_no_segment() {
        let sw = shape(&contour(CurveKind::Bspline, &[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]));
        assert!(sw.u.is_empty() && polylines(&sw.u, &sw.v).is_empty());
    }
}

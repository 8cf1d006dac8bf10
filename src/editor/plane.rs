//! The (U, V) plane on the screen: where a point of the contour is drawn,
//! which point the mouse is on, and where a new point goes. U runs right,
//! V up; the scale is a round number of pixels a unit (1, 2, 2.5 or 5
//! times a power of ten), so that a drag of whole pixels is a round move.

use super::draw::Rect;

/// How near (in pixels) the mouse must be to a point to take it.
pub const HIT_RADIUS: f64 = 8.0;

/// The fewest and most pixels a unit.
const SCALES: (f64, f64) = (1e-3, 1e7);

/// The plane's view: its box on the screen, the (U, V) at the box's
/// centre, and the pixels a unit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    pub rect: Rect,
    pub centre: [f64; 2],
    pub scale: f64,
}

/// The largest round number (1, 2, 2.5 or 5 times a power of ten) not
/// above `x` (> 0).
pub(crate) fn round_below(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [5.0, 2.5, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|&r| r <= x * (1.0 + 1e-12))
        .unwrap_or(p)
}

impl Plane {
    /// The view that shows every point of `points` with a margin, at a
    /// round scale, centred on their box.
    pub fn fit(rect: Rect, points: &[[f64; 2]]) -> Plane {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points.iter().filter(|p| p[0].is_finite() && p[1].is_finite()) {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if lo[0] > hi[0] {
            return Plane {
                rect,
                centre: [0.0, 0.0],
                scale: 100.0,
            };
        }
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-6);
        let room = |k: usize, pixels: i64| pixels as f64 * 0.8 / (hi[k] - lo[k]).max(span * 1e-3);
        let scale = round_below(room(0, rect.w).min(room(1, rect.h))).clamp(SCALES.0, SCALES.1);
        Plane {
            rect,
            centre: [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0],
            scale,
        }
    }

    /// The screen place of (u, v).
    pub fn to_screen(&self, [u, v]: [f64; 2]) -> (f64, f64) {
        let (cx, cy) = self.middle();
        (
            cx + (u - self.centre[0]) * self.scale,
            cy - (v - self.centre[1]) * self.scale,
        )
    }

    /// The (u, v) of a screen place.
    pub fn to_plane(&self, (x, y): (f64, f64)) -> [f64; 2] {
        let (cx, cy) = self.middle();
        [
            self.centre[0] + (x - cx) / self.scale,
            self.centre[1] - (y - cy) / self.scale,
        ]
    }

    /// The move in (u, v) of a move of the mouse by (dx, dy) pixels.
    pub fn delta(&self, (dx, dy): (f64, f64)) -> [f64; 2] {
        [dx / self.scale, -dy / self.scale]
    }

    /// The box's centre on the screen.
    fn middle(&self) -> (f64, f64) {
        (
            self.rect.x as f64 + self.rect.w as f64 / 2.0,
            self.rect.y as f64 + self.rect.h as f64 / 2.0,
        )
    }

    /// Zooms in (`factor` > 1) or out about the box's centre.
    pub fn zoom(&mut self, factor: f64) {
        self.scale = (self.scale * factor).clamp(SCALES.0, SCALES.1);
    }

    /// Pans the view by (dx, dy) pixels: (+x, +y) shows more of the right
    /// and the bottom.
    pub fn pan(&mut self, (dx, dy): (f64, f64)) {
        self.centre[0] += dx / self.scale;
        self.centre[1] -= dy / self.scale;
    }

    /// The grid's step in units: the smallest round number at least 24
    /// pixels wide.
    pub fn grid_step(&self) -> f64 {
        let want = 24.0 / self.scale;
        let p = 10f64.powf(want.log10().floor());
        [1.0, 2.0, 2.5, 5.0, 10.0]
            .into_iter()
            .map(|m| m * p)
            .find(|&s| s >= want * (1.0 - 1e-12))
            .unwrap_or(10.0 * p)
    }

    /// The point of `points` nearest the screen place `at`, if one is
    /// within [`HIT_RADIUS`] pixels (the later one on a tie, as it is
    /// drawn on top).
    pub fn point_at(&self, points: &[[f64; 2]], at: (f64, f64)) -> Option<usize> {
        let mut best: Option<(f64, usize)> = None;
        for (i, &p) in points.iter().enumerate() {
            let (x, y) = self.to_screen(p);
            let d = (x - at.0).hypot(y - at.1);
            if d <= HIT_RADIUS && best.is_none_or(|(b, _)| d <= b) {
                best = Some((d, i));
            }
        }
        best.map(|(_, i)| i)
    }
}

/// Where a new point at (u, v) goes among `points` (the closed polygon of
/// the control points): after the first end of the polygon's side nearest
/// it, so that it falls between the two points it is nearest to join.
/// Among fewer than two points, at the end.
pub(crate) fn insertion_place(points: &[[f64; 2]], at: [f64; 2]) -> usize {
    let n = points.len();
    if n < 2 {
        return n;
    }
    let mut best = (f64::INFINITY, n);
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        let d = distance_to_side(a, b, at);
        if d < best.0 {
            best = (d, i + 1);
        }
    }
    best.1
}

/// The distance from `p` to the segment from `a` to `b`.
fn distance_to_side(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = match len2 {
        0.0 => 0.0,
        _ => (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0),
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    const RECT: Rect = Rect {
        x: 0,
        y: 0,
        w: 500,
        h: 800,
    };

    #[test]
    fn round_numbers() {
        assert_eq!(round_below(260.0), 250.0);
        assert_eq!(round_below(199.0), 100.0);
        assert_eq!(round_below(0.3), 0.25);
        assert_eq!(round_below(5.0), 5.0);
    }

    #[test]
    fn a_fit_shows_every_point_at_a_round_scale() {
        let pts = [[0.0, 0.0], [1.0, 2.56]];
        let p = Plane::fit(RECT, &pts);
        assert_eq!(p.scale, 250.0);
        for &q in &pts {
            assert!(RECT.holds(p.to_screen(q).0, p.to_screen(q).1));
        }
        assert_eq!(p.to_screen([0.5, 1.28]), (250.0, 400.0));
        assert_eq!(p.to_plane((250.0, 200.0)), [0.5, 2.08]);
    }

    #[test]
    fn screen_and_plane_are_inverse_and_v_runs_up() {
        let mut p = Plane::fit(RECT, &[[-1.0, -1.0], [1.0, 1.0]]);
        p.zoom(2.0);
        p.pan((30.0, -10.0));
        let q = [0.3, -0.7];
        let back = p.to_plane(p.to_screen(q));
        assert!((back[0] - q[0]).abs() < 1e-12 && (back[1] - q[1]).abs() < 1e-12);
        assert!(p.to_screen([0.0, 1.0]).1 < p.to_screen([0.0, 0.0]).1);
        assert_eq!(p.delta((p.scale, p.scale)), [1.0, -1.0]);
    }

    #[test]
    fn the_grid_step_is_round_and_at_least_24_pixels() {
        for scale in [1.0, 7.0, 100.0, 250.0, 333.0, 4000.0] {
            let p = Plane {
                rect: RECT,
                centre: [0.0, 0.0],
                scale,
            };
            let s = p.grid_step();
            assert!(s * scale >= 24.0 - 1e-9, "{scale}: {s}");
            assert!(s * scale < 24.0 * 2.6, "{scale}: {s}");
        }
    }

    #[test]
    fn the_mouse_takes_the_nearest_point_within_reach() {
        let p = Plane::fit(RECT, &[[-1.0, -1.0], [1.0, 1.0]]);
        let pts = [[0.0, 0.0], [0.02, 0.0], [1.0, 1.0]];
        let (x, y) = p.to_screen([0.0, 0.0]);
        assert_eq!(p.point_at(&pts, (x, y)), Some(0));
        assert_eq!(p.point_at(&pts, (x + 3.0, y)), Some(1));
        assert_eq!(p.point_at(&pts, (x, y + 40.0)), None);
    }

    #[test]
    fn a_new_point_goes_between_the_ends_of_the_nearest_side() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(insertion_place(&square, [0.5, -0.1]), 1);
        assert_eq!(insertion_place(&square, [1.2, 0.5]), 2);
        assert_eq!(insertion_place(&square, [-0.1, 0.5]), 4, "the closing side");
        assert_eq!(insertion_place(&square[..1], [3.0, 3.0]), 1);
    }
}

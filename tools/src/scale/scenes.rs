//! The scenes of `tools scale`: N objects of one kind at random in a
//! 6×6×3 box, their sizes shrinking as N^-1/3 so that they fill the same
//! share of the box at every N (issue 24's measured scenes). Not the
//! thesis's: scenes to time the structures over the objects (`--accel`).
//!
//! Each scene is deck text, so that `raytrace`, `tools pov` and valgrind
//! read the same scene the timings render. The kinds:
//! - spheres of radius N^-1/3 (one sphere of radius 1; 4 % of the box);
//! - fig5_6's star (a translation sweep of 16 B-spline segments, radius
//!   1.4, length 1.2), scaled by N^-1/3 and turned at random about z;
//! - fig5_8's goblet (a rotation sweep of 7 Bezier segments, radius 1,
//!   height 2.56), scaled by N^-1/3.
//!
//! The contours are read from the shipped decks, so a star here is the
//! star of Fig. 5.6. No floor: a ray that misses every object costs only
//! the structure's (or the loop's) tests. One light, so each hit casts one
//! shadow ray. Positions come from a fixed seed: the same N gives the
//! same scene on every run.

use std::fmt::Write as _;

use raytrace::options::Fidelity;
use raytrace::types::{CurveKind, Shape};

use crate::fuzz::Rng;

/// The box the objects stand in: x and y in −3..3, z in 0..3.
pub const HALF_WIDTH: f64 = 3.0;
pub const HEIGHT: f64 = 3.0;

/// What a scene is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Kind {
    Sphere,
    Star,
    Goblet,
}

impl Kind {
    pub const ALL: [Kind; 3] = [Kind::Sphere, Kind::Star, Kind::Goblet];

    /// The kind's name in the benches, the table and the chart.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Sphere => "sphere",
            Kind::Star => "star",
            Kind::Goblet => "goblet",
        }
    }

    /// The shipped deck a sweep kind takes its contour from.
    fn deck(self) -> Option<&'static str> {
        match self {
            Kind::Sphere => None,
            Kind::Star => Some("fig5_6"),
            Kind::Goblet => Some("fig5_8"),
        }
    }
}

/// A sweep's contour as its deck gives it.
#[derive(Clone, Debug)]
struct Contour {
    class: &'static str,
    curve: &'static str,
    points: Vec<[f64; 2]>,
    /// The sweep's length (0 for a rotation sweep, which has none).
    length: f64,
    /// The half extent across (the largest |U| or |V|; for a rotation
    /// sweep the largest radius) and the height at scale 1.
    half_width: f64,
    height: f64,
}

/// The first sweep of a shipped deck.
fn contour(deck: &str) -> Result<Contour, String> {
    let scene = crate::decks::load(deck, Fidelity::Thesis)?;
    let (obj, sw) = scene
        .objects
        .iter()
        .find_map(|o| match &o.shape {
            Shape::Sweep(sw) => Some((o, sw)),
            _ => None,
        })
        .ok_or_else(|| format!("{deck} has no sweep"))?;
    let rotation = obj.class == raytrace::types::PrimitiveClass::Rotation;
    let max = |f: fn(&[f64; 2]) -> f64| sw.points.iter().map(f).fold(0.0f64, f64::max);
    let (half_width, height) = match rotation {
        true => (max(|p| p[0].abs()), max(|p| p[1])),
        false => (max(|p| p[0].abs().max(p[1].abs())), sw.length),
    };
    Ok(Contour {
        class: if rotation { "rotation" } else { "translation" },
        curve: match sw.curve {
            CurveKind::Bspline => "bspline",
            CurveKind::Bezier => "bezier",
        },
        points: sw.points.clone(),
        length: sw.length,
        half_width,
        height,
    })
}

/// How a scene is drawn: image size, subpixels, and how far each object
/// moves over the shutter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Width and height in pixels.
    pub size: (usize, usize),
    pub mask: usize,
    /// Each object moves this many of its radii (half widths) in a random
    /// direction across z, with `blur 1`; 0: at rest, no `blur`.
    pub travel: f64,
}

impl Frame {
    pub fn moving(&self) -> bool {
        self.travel != 0.0
    }
}

/// The seed of every scene's positions.
const SEED: u64 = 0x5ca1_e000;

/// The deck of `n` objects of `kind` (see the module's doc).
pub fn deck(kind: Kind, n: usize, frame: Frame) -> Result<String, String> {
    let contour = kind.deck().map(contour).transpose()?;
    let k = (n.max(1) as f64).powf(-1.0 / 3.0);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{{ tools scale: {n} {}s in a 6x6x3 box, sizes times N^-1/3 = {k:.5}{}. }}",
        kind.name(),
        if frame.moving() {
            format!(", each moving {} radii", frame.travel)
        } else {
            String::new()
        }
    );
    s.push_str("view eye 0 -10.5 7 look 0 0 1.2 screen 3.8 distance 5\n");
    let _ = writeln!(s, "image {} {} mask {}", frame.size.0, frame.size.1, frame.mask);
    s.push_str(
        "background 0.1 0.1 0.2\n\
         light sun 5 -6 10 1 1 1\n\
         surface red opaque color 0.8 0.25 0.15 ka 0.15 kd 0.75 ks 0.1 kt 0\n",
    );
    if frame.moving() {
        s.push_str("blur 1\n");
    }
    // Half width and height of one object at this N.
    let (half, height) = match &contour {
        None => (k, 2.0 * k),
        Some(c) => (c.half_width * k, c.height * k),
    };
    let mut rng = Rng::new(SEED ^ kind as u64);
    let mut uniform = |lo: f64, hi: f64| lo + (hi - lo) * rng.unit();
    // The motions from a generator of their own: the moving scene's
    // objects stand where the scene at rest has them.
    let mut paths = Rng::new(!SEED ^ kind as u64);
    let room = (HALF_WIDTH - half).max(0.0);
    for i in 1..=n {
        let (x, y) = (uniform(-room, room), uniform(-room, room));
        let z = uniform(0.0, (HEIGHT - height).max(0.0));
        let name = format!("o{i}");
        match &contour {
            None => {
                let _ = writeln!(s, "sphere {name} red at {x:.5} {y:.5} {:.5} radius {k:.6}", z + k);
            }
            Some(c) => {
                let length = match c.class {
                    "rotation" => String::new(),
                    _ => format!(" length {:.6}", c.length * k),
                };
                let _ = writeln!(
                    s,
                    "sweep {name} red {} {} at {x:.5} {y:.5} {z:.5}{length} axis z",
                    c.class, c.curve
                );
                for p in &c.points {
                    let _ = writeln!(s, "  {:.6} {:.6}", p[0] * k, p[1] * k);
                }
                s.push_str("end\n");
                if kind == Kind::Star {
                    let _ = writeln!(s, "rotate {name} z {:.3}", uniform(0.0, 360.0));
                }
            }
        }
        if frame.moving() {
            let a = paths.unit() * std::f64::consts::TAU;
            let (dx, dy) = (frame.travel * half * a.cos(), frame.travel * half * a.sin());
            let base = if contour.is_none() { z + k } else { z };
            let _ = writeln!(s, "motion {name} to {:.5} {:.5} {base:.5}", x + dx, y + dy);
        }
    }
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use raytrace::types::PrimitiveClass;
    use std::path::Path;

    fn scene(kind: Kind, n: usize, moving: bool) -> raytrace::scene::Scene {
        let frame = Frame {
            size: (16, 16),
            mask: 1,
            travel: if moving { 2.0 } else { 0.0 },
        };
        let text = deck(kind, n, frame).unwrap();
        crate::decks::load_source(&text, "scale", Path::new("."), Fidelity::Thesis).unwrap()
    }

    /// N objects of the kind, each inside the 6×6×3 box (by its bounding
    /// sphere's centre and the object's extent), smaller as N grows.
    #[test]
    fn n_objects_of_the_kind_in_the_box() {
        for kind in Kind::ALL {
            let mut last = f64::INFINITY;
            for n in [1, 8, 64] {
                let s = scene(kind, n, false);
                assert_eq!(s.objects.len(), n, "{kind:?} {n}");
                let class = match kind {
                    Kind::Sphere => PrimitiveClass::Sphere,
                    Kind::Star => PrimitiveClass::Translation,
                    Kind::Goblet => PrimitiveClass::Rotation,
                };
                assert!(s.objects.iter().all(|o| o.class == class));
                for o in &s.objects {
                    let c = o.sphereo;
                    assert!(c.x.abs() <= HALF_WIDTH && c.y.abs() <= HALF_WIDTH, "{kind:?} {c}");
                    assert!((0.0..=HEIGHT).contains(&c.z), "{kind:?} {c}");
                }
                let size = s.objects[0].radius;
                assert!(size < last, "{kind:?}: {size} at {n}");
                // Eight times the objects, half the size.
                if last.is_finite() {
                    assert!((last / size - 2.0).abs() < 1e-3, "{kind:?}: {last} / {size}");
                }
                last = size;
            }
        }
    }

    /// A moving scene has a motion record per object and `blur 1`; the
    /// scene at rest has neither, and the same objects.
    #[test]
    fn moving_scenes_move_every_object() {
        let (rest, moving) = (scene(Kind::Sphere, 20, false), scene(Kind::Sphere, 20, true));
        assert!(rest.motions.is_empty());
        assert_eq!(moving.motions.len(), 20);
        assert_eq!(rest.objects.len(), moving.objects.len());
        for (a, b) in rest.objects.iter().zip(&moving.objects) {
            assert_eq!(a.sphereo, b.sphereo);
        }
        assert!(moving.blur.is_some() && rest.blur.is_none());
    }

    /// The same N gives the same deck; another N other positions.
    #[test]
    fn scenes_are_reproducible() {
        let f = Frame {
            size: (8, 8),
            mask: 1,
            travel: 0.0,
        };
        assert_eq!(deck(Kind::Star, 5, f).unwrap(), deck(Kind::Star, 5, f).unwrap());
        assert_ne!(deck(Kind::Star, 5, f).unwrap(), deck(Kind::Star, 6, f).unwrap());
    }
}

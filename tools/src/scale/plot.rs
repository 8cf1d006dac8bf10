//! The chart of `tools scale`: one log-log panel a scene kind, time a
//! sample against N, one line a method; drawn by the speed/accuracy
//! chart's panel (`crate::chart::panel`).

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use raytrace::accel::Accel;

use super::scenes::Kind;
use super::{count, Measured, Method, Settings, METHODS};
use crate::chart::{panel, Series};

/// The chart's size in pixels.
pub const WIDTH: u32 = 2100;
pub const HEIGHT: u32 = 700;

/// A method's colour: the loop red, the hierarchy blue, the octree green,
/// auto purple, POV-Ray black.
fn colour(m: Method) -> RGBColor {
    match m {
        Method::Ours(Accel::None) => RGBColor(200, 40, 40),
        Method::Ours(Accel::Bvh) => RGBColor(40, 90, 200),
        Method::Ours(Accel::Octree) => RGBColor(30, 150, 60),
        Method::Ours(Accel::Auto) => RGBColor(140, 50, 170),
        Method::Povray => RGBColor(30, 30, 30),
    }
}

fn title(kind: Kind) -> &'static str {
    match kind {
        Kind::Sphere => "Random spheres",
        Kind::Star => "fig5_6 stars (translation sweeps)",
        Kind::Goblet => "fig5_8 goblets (rotation sweeps)",
    }
}

/// Draws the three panels on `root`.
pub fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, m: &Measured, set: &Settings) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| format!("{e:?}"))?;
    let (left, rest) = root.split_horizontally(WIDTH / 3);
    let (middle, right) = rest.split_horizontally(WIDTH / 3);
    let loop_note = match set.loop_max < set.sphere_ns.iter().chain(&set.sweep_ns).copied().max().unwrap_or(0) {
        true => format!("; --accel none only to N = {}", count(set.loop_max)),
        false => String::new(),
    };
    for (k, (kind, area)) in Kind::ALL.into_iter().zip([&left, &middle, &right]).enumerate() {
        let series: Vec<Series> = METHODS
            .into_iter()
            .enumerate()
            .map(|(i, method)| Series {
                label: method.label(),
                colour: colour(method),
                marker: i,
                points: m
                    .points
                    .iter()
                    .filter(|p| p.kind == kind && p.method == method)
                    .map(|p| (p.n as f64, p.per_sample * 1e6))
                    .collect(),
            })
            .filter(|s| !s.points.is_empty())
            .collect();
        let note = match k {
            0 => format!(
                "{}×{}, {} samples a pixel; CPU, one thread, median of {} interleaved rounds{loop_note}",
                set.size.0,
                set.size.1,
                set.mask * set.mask,
                set.runs
            ),
            1 => "ours: the render alone; POV-Ray: its reported trace time (no parse, no bounding)".into(),
            _ => "objects at random in a 6×6×3 box, sizes × N^-1/3; --accel auto: the loop below 9 objects".into(),
        };
        panel(
            area,
            title(kind),
            "objects N",
            "µs a sample (a primary ray and its shadow ray)",
            &series,
            None,
            &note,
            (k == 0).then_some(SeriesLabelPosition::UpperLeft),
            1.0,
        )?;
    }
    root.present().map_err(|e| format!("{e:?}"))
}

/// Writes the chart as PNG and SVG.
pub fn write(m: &Measured, set: &Settings, png: &Path, svg: &Path) -> Result<(), String> {
    if let Some(dir) = png.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    let mut buf = vec![0u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        draw(&root, m, set)?;
    }
    image::save_buffer(png, &buf, WIDTH, HEIGHT, image::ExtendedColorType::Rgb8)
        .map_err(|e| format!("{}: {e}", png.display()))?;
    let root = SVGBackend::new(svg, (WIDTH, HEIGHT)).into_drawing_area();
    draw(&root, m, set)
}

#[cfg(test)]
mod tests {
    use super::super::Point;
    use super::*;

    /// The chart draws from made-up points without error, into a buffer,
    /// a method with no point left out of its panel.
    #[test]
    fn draws_from_points() {
        crate::fonts::register().unwrap();
        let set = Settings::quick();
        let mut m = Measured::default();
        for kind in Kind::ALL {
            for &n in set.ns(kind) {
                for method in METHODS.into_iter().filter(|x| *x != Method::Povray) {
                    m.points.push(Point {
                        kind,
                        n,
                        method,
                        per_sample: 1e-7 * n as f64,
                        setup: 0.0,
                    });
                }
            }
        }
        let mut buf = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        draw(&root, &m, &set).unwrap();
        drop(root);
        // The loop's red was drawn; POV-Ray's black line has no points,
        // so only text is near-black.
        let red = buf.chunks(3).filter(|p| p == &[200, 40, 40]).count();
        assert!(red > 20, "{red} red pixels");
    }
}

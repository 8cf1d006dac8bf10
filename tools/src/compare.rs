//! Pictures that set renders of one deck side by side: the deck with other
//! flags (`--sampler`, `--mask`, `--denoise`, `--coherence N`), the pixels
//! a render traced, and where two renders differ. For the gallery
//! ([`crate::gallery::Drawing::Compare`]): the README's pair of the thesis's
//! settings and `--denoise`, and the pictures of where the reconstructions
//! fail.

use raytrace::options::{Options, TimeSampler};
use raytrace::raster::{rgbtochars, Raster};
use raytrace::raytrace::{render, Render, Request};
use raytrace::reconstruct::Reconstruction;

use crate::gallery::{side_by_side, GAP};

/// A render of the deck with flags beside its own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Look {
    /// `--sampler` (the deck's default, the table, when `None`).
    pub sampler: Option<TimeSampler>,
    /// `--mask` (the deck's when `None`).
    pub mask: Option<usize>,
    pub reconstruction: Reconstruction,
}

/// The deck as it is: the thesis's settings.
pub const THESIS: Look = Look {
    sampler: None,
    mask: None,
    reconstruction: Reconstruction::Box,
};

impl Look {
    /// The flags `raytrace` takes for this look.
    pub fn flags(&self) -> String {
        let mut f = Vec::new();
        if let Some(s) = self.sampler {
            f.push(format!("--sampler {}", format!("{s:?}").to_lowercase()));
        }
        if let Some(m) = self.mask {
            f.push(format!("--mask {m}"));
        }
        match self.reconstruction {
            Reconstruction::Box => {}
            Reconstruction::Denoise => f.push("--denoise".into()),
            Reconstruction::Coherence(n) => f.push(format!("--coherence {n}")),
        }
        f.join(" ")
    }

    /// The deck rendered so (thesis fidelity).
    pub fn render(&self, deck: &str) -> Result<Render, String> {
        let opts = Options {
            sampler: self.sampler.unwrap_or_default(),
            ..Options::default()
        };
        let mut scene = crate::decks::load(deck, opts.fidelity)?;
        if let Some(m) = self.mask {
            let (w, h) = (scene.image.width, scene.image.height);
            scene.resize(w, h, m);
        }
        let prepared = crate::decks::prepare(scene, &opts)?;
        render(&prepared, &Request::STILL.reconstruction(self.reconstruction)).map_err(|e| e.to_string())
    }
}

/// One panel of a comparison.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Panel {
    /// The render.
    Render(Look),
    /// The render dimmed to a third, the pixels it traced white (`--coherence`).
    Traced(Look),
    /// |a − b| of the renders of panels `a` and `b`, times `gain`, as grey.
    Difference { a: usize, b: usize, gain: f64 },
}

impl Panel {
    /// What the panel shows, for the gallery's command line.
    pub fn describe(&self) -> String {
        match self {
            Panel::Render(l) => format!("[{}]", l.flags()),
            Panel::Traced(l) => format!("[the pixels {} traced]", l.flags()),
            Panel::Difference { a, b, gain } => format!("[|{a} − {b}| × {gain}]"),
        }
    }
}

/// The panels side by side, [`GAP`] white columns between them.
pub fn draw(deck: &str, panels: &[Panel]) -> Result<Raster, String> {
    let mut renders: Vec<Option<Render>> = Vec::new();
    for p in panels {
        renders.push(match p {
            Panel::Render(l) | Panel::Traced(l) => Some(l.render(deck)?),
            Panel::Difference { .. } => None,
        });
    }
    let mut out: Option<Raster> = None;
    for (p, r) in panels.iter().zip(&renders) {
        let picture = match (p, r) {
            (Panel::Render(_), Some(r)) => r.raster.clone(),
            (Panel::Traced(_), Some(r)) => traced(r),
            (Panel::Difference { a, b, gain }, _) => {
                let colours = |k: usize| renders.get(k).and_then(|r| r.as_ref()).map(|r| &r.colours);
                match (colours(*a), colours(*b)) {
                    (Some(a), Some(b)) => difference(a, b, r_width(&renders), *gain),
                    _ => return Err(format!("a difference of panels {a} and {b}, which are not renders")),
                }
            }
            _ => unreachable!("every render panel was rendered"),
        };
        out = Some(match out {
            None => picture,
            Some(left) => side_by_side(&left, &picture, GAP),
        });
    }
    out.ok_or_else(|| "no panels".into())
}

/// The width of the renders (they are all the deck's).
fn r_width(renders: &[Option<Render>]) -> usize {
    renders.iter().flatten().map(|r| r.raster.width).next().unwrap_or(0)
}

/// A render dimmed to a third, its traced pixels (those with rays) white.
fn traced(r: &Render) -> Raster {
    Raster {
        pixels: r
            .raster
            .pixels
            .iter()
            .zip(&r.counts)
            .map(|(p, &n)| if n > 0 { [255; 3] } else { p.map(|c| c / 3) })
            .collect(),
        ..r.raster.clone()
    }
}

/// |a − b| × `gain` as grey, the largest channel's, an image `width` wide.
fn difference(a: &[raytrace::types::Intensity], b: &[raytrace::types::Intensity], width: usize, gain: f64) -> Raster {
    let pixels: Vec<[u8; 3]> = a
        .iter()
        .zip(b)
        .map(|(x, y)| rgbtochars(raytrace::types::Intensity::splat((*x - *y).abs().max_element() * gain)))
        .collect();
    Raster {
        width,
        height: pixels.len() / width.max(1),
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The flags of a look, as the command line takes them.
    #[test]
    fn flags_of_a_look() {
        assert_eq!(THESIS.flags(), "");
        let l = Look {
            sampler: Some(TimeSampler::Adaptive),
            mask: Some(2),
            reconstruction: Reconstruction::Denoise,
        };
        assert_eq!(l.flags(), "--sampler adaptive --mask 2 --denoise");
        let c = Look {
            reconstruction: Reconstruction::Coherence(8),
            ..THESIS
        };
        assert_eq!(c.flags(), "--coherence 8");
    }

    /// A difference of a render with itself is black; its traced pixels
    /// are white; the panels stand side by side.
    #[test]
    fn panels_side_by_side() {
        let deck = "fig5_1";
        let look = Look {
            mask: Some(1),
            ..THESIS
        };
        let coherent = Look {
            reconstruction: Reconstruction::Coherence(8),
            ..look
        };
        let panels = [
            Panel::Render(look),
            Panel::Traced(coherent),
            Panel::Difference { a: 0, b: 0, gain: 8.0 },
        ];
        let r = draw(deck, &panels).unwrap();
        let one = look.render(deck).unwrap().raster;
        assert_eq!(r.width, 3 * one.width + 2 * GAP);
        assert_eq!(r.pixels[..one.width], one.pixels[..one.width]);
        let last = 2 * (one.width + GAP);
        assert!(r
            .pixels
            .chunks(r.width)
            .all(|row| row[last..].iter().all(|p| *p == [0; 3])));
        // The top left pixel is a lattice crossing: traced.
        assert_eq!(r.pixels[one.width + GAP], [255; 3]);
        assert!(draw(deck, &[Panel::Difference { a: 0, b: 1, gain: 1.0 }]).is_err());
    }
}

//! `tools gallery`: every picture of the docs, drawn again from its deck
//! with the options it was made with.
//!
//! [`GALLERY`] is the one table of them: a picture, its deck, how it is
//! drawn. `cargo run -p tools --release -- gallery` rewrites them all
//! (after the texture rasters the decks paste, as `tools texture` writes
//! them); `--check` only compares, in memory, and names the pictures (and
//! texture rasters) that are stale: it writes nothing.
//! The tests hold the README's first picture to a render of the default
//! deck, so it cannot go stale silently. The charts (docs/speed_accuracy.png,
//! docs/scale.png) are measured, not drawn from one deck: `tools chart` and
//! `tools scale` make them.

use std::path::{Path, PathBuf};

use raytrace::options::{Fidelity, Options, Solver};
use raytrace::psout;
use raytrace::raster::Raster;
use raytrace::reconstruct::Reconstruction;

use crate::compare::{Look, Panel, THESIS};

/// How a picture is drawn from its deck.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Drawing {
    /// The deck's render, as `raytrace DECK --png FILE` writes it.
    Render,
    /// The filmstrip `tools frames DECK --times T,… --size NxN` writes: the
    /// scene still at each instant, `size`×`size` pixels a frame.
    Frames { times: &'static [f64], size: usize },
    /// The render with `laguerre` (left) and with `--solver robust`
    /// (right), [`GAP`] white pixels between them.
    Solvers,
    /// psout's 1024×864 screen showing the render, as
    /// `psout --screenshot OUT.png FILE` writes it.
    Screen,
    /// A film deck's frames as one animated PNG, as `raytrace DECK --apng
    /// FILE` writes it (the port's extension, docs/film.md).
    Film,
    /// Every `every`-th frame of a film deck side by side, as `tools join
    /// … --strip FILE --every N` writes it.
    Strip { every: usize },
    /// `--sampler adaptive` at `size`² and `mask`² rays a pixel: the image
    /// beside the heat map of its rays, as `tools heatmap` writes it.
    Heatmap { size: usize, mask: usize },
    /// The contour editor's screen on the deck's sweep `sweep` after the
    /// edits of `script` (one a line, as `--script` reads them), the time
    /// slider at `time` for a key shape, as `contour DECK NAME --screenshot
    /// FILE` writes it.
    Editor {
        sweep: &'static str,
        script: &'static str,
        time: Option<f64>,
    },
    /// The deck's renders with other flags, the pixels a render traced,
    /// and where two differ, side by side ([`crate::compare`]).
    Compare { panels: &'static [Panel] },
}

/// One picture of the docs.
#[derive(Clone, Copy, Debug)]
pub struct Picture {
    /// The PNG, relative to the checkout.
    pub image: &'static str,
    /// Its deck, relative to the checkout.
    pub deck: &'static str,
    pub drawing: Drawing,
}

/// The white columns between the two halves of a [`Drawing::Solvers`] picture.
pub const GAP: usize = 8;

/// The shutter at five instants, as `tools frames` takes them by default.
const FIVE: &[f64] = &[0.0, 0.25, 0.5, 0.75, 1.0];
/// The shutter at nine instants, for the three key shapes of the default deck.
const NINE: &[f64] = &[0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0];

const fn render(image: &'static str, deck: &'static str) -> Picture {
    Picture {
        image,
        deck,
        drawing: Drawing::Render,
    }
}

const fn editor(image: &'static str, deck: &'static str, sweep: &'static str, script: &'static str) -> Picture {
    Picture {
        image,
        deck,
        drawing: Drawing::Editor {
            sweep,
            script,
            time: None,
        },
    }
}

const fn frames(image: &'static str, deck: &'static str, times: &'static [f64], size: usize) -> Picture {
    Picture {
        image,
        deck,
        drawing: Drawing::Frames { times, size },
    }
}

/// `--denoise` on the adaptive sampler's 4 rays a pixel.
const DENOISED: Look = Look {
    sampler: Some(raytrace::options::TimeSampler::Adaptive),
    mask: Some(2),
    reconstruction: Reconstruction::Denoise,
};

/// The reference of the failure pictures: 64 stratified rays a pixel.
const SMOOTH: Look = Look {
    sampler: Some(raytrace::options::TimeSampler::Stratified),
    mask: Some(8),
    reconstruction: Reconstruction::Box,
};

/// `--coherence 8` at the deck's settings.
const COHERENT: Look = Look {
    reconstruction: Reconstruction::Coherence(8),
    ..THESIS
};

/// Every picture of the docs that is drawn from a deck. A new picture gets
/// a line here, and `tools gallery` draws it from then on.
pub const GALLERY: &[Picture] = &[
    render("docs/img/nec_morph.png", "legacy_pascal/decks/nec_morph.deck"),
    frames(
        "docs/img/nec_morph_frames.png",
        "legacy_pascal/decks/nec_morph.deck",
        NINE,
        112,
    ),
    Picture {
        image: "docs/psout_screenshot.png",
        deck: "legacy_pascal/decks/nec_morph.deck",
        drawing: Drawing::Screen,
    },
    render("docs/img/still_life.png", "legacy_pascal/decks/still_life.deck"),
    render("docs/img/cook.png", "legacy_pascal/decks/cook.deck"),
    render("docs/img/fig5_1.png", "legacy_pascal/decks/fig5_1.deck"),
    render("docs/img/fig5_2.png", "legacy_pascal/decks/fig5_2.deck"),
    render("docs/img/fig5_3.png", "legacy_pascal/decks/fig5_3.deck"),
    render("docs/img/fig5_4.png", "legacy_pascal/decks/fig5_4.deck"),
    render("docs/img/fig5_5.png", "legacy_pascal/decks/fig5_5.deck"),
    render("docs/img/fig5_6.png", "legacy_pascal/decks/fig5_6.deck"),
    render("docs/img/fig5_7.png", "legacy_pascal/decks/fig5_7.deck"),
    render("docs/img/fig5_8.png", "legacy_pascal/decks/fig5_8.deck"),
    render("docs/img/fig5_9.png", "legacy_pascal/decks/fig5_9.deck"),
    render("docs/img/fig5_10.png", "legacy_pascal/decks/fig5_10.deck"),
    frames(
        "docs/img/fig5_10_frames.png",
        "legacy_pascal/decks/fig5_10.deck",
        FIVE,
        96,
    ),
    render("docs/img/fig5_11.png", "legacy_pascal/decks/fig5_11.deck"),
    frames(
        "docs/img/fig5_11_frames.png",
        "legacy_pascal/decks/fig5_11.deck",
        FIVE,
        96,
    ),
    render("docs/img/fig5_12.png", "legacy_pascal/decks/fig5_12.deck"),
    frames(
        "docs/img/fig5_12_frames.png",
        "legacy_pascal/decks/fig5_12.deck",
        FIVE,
        96,
    ),
    render("docs/img/sec6_2.png", "legacy_pascal/decks/sec6_2.deck"),
    frames(
        "docs/img/sec6_2_frames.png",
        "legacy_pascal/decks/sec6_2.deck",
        FIVE,
        128,
    ),
    Picture {
        image: "docs/img/stress_edge_on.png",
        deck: "legacy_pascal/decks/stress_edge_on.deck",
        drawing: Drawing::Solvers,
    },
    Picture {
        image: "docs/img/nec_commercial.png",
        deck: "legacy_pascal/decks/nec_commercial.deck",
        drawing: Drawing::Film,
    },
    Picture {
        image: "docs/img/nec_commercial_strip.png",
        deck: "legacy_pascal/decks/nec_commercial.deck",
        drawing: Drawing::Strip { every: 6 },
    },
    Picture {
        image: "docs/img/adaptive_heatmap.png",
        deck: "legacy_pascal/decks/fig5_10.deck",
        drawing: Drawing::Heatmap { size: 256, mask: 4 },
    },
    render("docs/img/tutorial_1_sphere.png", "legacy_pascal/tutorial/1_sphere.deck"),
    render("docs/img/tutorial_2_sweep.png", "legacy_pascal/tutorial/2_sweep.deck"),
    render("docs/img/tutorial_3_motion.png", "legacy_pascal/tutorial/3_motion.deck"),
    render(
        "docs/img/tutorial_4_keyframe.png",
        "legacy_pascal/tutorial/4_keyframe.deck",
    ),
    frames(
        "docs/img/tutorial_4_keyframe_frames.png",
        "legacy_pascal/tutorial/4_keyframe.deck",
        FIVE,
        128,
    ),
    render("docs/img/tutorial_5_path.png", "legacy_pascal/tutorial/5_path.deck"),
    render(
        "docs/img/tutorial_6_blob_patch.png",
        "legacy_pascal/tutorial/6_blob_patch.deck",
    ),
    frames(
        "docs/img/tutorial_6_blob_patch_frames.png",
        "legacy_pascal/tutorial/6_blob_patch.deck",
        FIVE,
        128,
    ),
    editor(
        "docs/img/editor_goblet.png",
        "legacy_pascal/decks/fig5_8.deck",
        "goblet",
        "",
    ),
    editor(
        "docs/img/editor_refused.png",
        "legacy_pascal/decks/fig5_8.deck",
        "goblet",
        "move 11 0.2 0\ndelete 20\n",
    ),
    Picture {
        image: "docs/img/editor_keyshapes.png",
        deck: "legacy_pascal/decks/fig5_10.deck",
        drawing: Drawing::Editor {
            sweep: "last",
            script: "",
            time: Some(0.5),
        },
    },
    Picture {
        image: "docs/img/denoise_pair.png",
        deck: "legacy_pascal/decks/fig5_10.deck",
        drawing: Drawing::Compare {
            panels: &[Panel::Render(THESIS), Panel::Render(DENOISED)],
        },
    },
    Picture {
        image: "docs/img/denoise_fails.png",
        deck: "legacy_pascal/decks/fig5_10.deck",
        drawing: Drawing::Compare {
            panels: &[
                Panel::Render(SMOOTH),
                Panel::Render(DENOISED),
                Panel::Difference { a: 0, b: 1, gain: 8.0 },
            ],
        },
    },
    Picture {
        image: "docs/img/coherence_fails.png",
        deck: "legacy_pascal/decks/fig5_1.deck",
        drawing: Drawing::Compare {
            panels: &[Panel::Render(THESIS), Panel::Render(COHERENT), Panel::Traced(COHERENT)],
        },
    },
    editor(
        "docs/img/editor_tutorial.png",
        "legacy_pascal/tutorial/2_sweep.deck",
        "star",
        "",
    ),
];

/// The checkout the tools were built from: the pictures and decks of
/// [`GALLERY`] are relative to it, wherever the tool is run from.
pub fn checkout() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

impl Picture {
    /// The command line that draws this picture by hand.
    pub fn command(&self) -> String {
        let (deck, image) = (self.deck, self.image);
        match self.drawing {
            Drawing::Render => format!("cargo run --release -- {deck} --png {image}"),
            Drawing::Frames { times, size } => {
                let times: Vec<String> = times.iter().map(f64::to_string).collect();
                format!(
                    "cargo run -p tools --release -- frames {deck} --times {} --size {size}x{size} --out {image}",
                    times.join(",")
                )
            }
            Drawing::Solvers => format!("{deck} with --solver laguerre and --solver robust, side by side"),
            Drawing::Screen => format!("psout --screenshot {image} on the raster of {deck}"),
            Drawing::Film => format!("cargo run --release -- {deck} --apng {image}"),
            Drawing::Strip { every } => {
                format!(
                    "cargo run -p tools --release -- join FRAMES… --strip {image} --every {every} (frames of {deck})"
                )
            }
            Drawing::Heatmap { size, mask } => {
                format!(
                    "cargo run -p tools --release -- heatmap {deck} --size {size}x{size} --mask {mask} --out {image}"
                )
            }
            Drawing::Compare { panels } => {
                let shown: Vec<String> = panels.iter().map(Panel::describe).collect();
                format!("{deck} rendered as {}, side by side", shown.join(" "))
            }
            Drawing::Editor { sweep, script, time } => {
                let time = time.map(|t| format!(" --time {t}")).unwrap_or_default();
                let edits = match script {
                    "" => String::new(),
                    s => format!(" --script EDITS (EDITS: {})", s.trim_end().replace('\n', "; ")),
                };
                format!("cargo run --release --bin contour -- {deck} {sweep}{time} --screenshot {image}{edits}")
            }
        }
    }

    /// Draws the picture from its deck under `root`.
    pub fn draw(&self, root: &Path) -> Result<Raster, String> {
        let deck = root.join(self.deck);
        match self.drawing {
            Drawing::Render => render_deck(&deck, Solver::Laguerre),
            Drawing::Frames { times, size } => crate::frames::filmstrip(&deck, times, (size, size), Fidelity::Thesis),
            Drawing::Solvers => {
                let left = render_deck(&deck, Solver::Laguerre)?;
                let right = render_deck(&deck, Solver::Robust)?;
                Ok(side_by_side(&left, &right, GAP))
            }
            Drawing::Screen => Ok(psout::compose(&render_deck(&deck, Solver::Laguerre)?, None, (0, 0)).to_raster()),
            Drawing::Film => Ok(film_frames(&deck, 1)?.0.swap_remove(0)),
            Drawing::Strip { every } => {
                let (frames, _) = film_frames(&deck, u32::MAX)?;
                let picked: Vec<&Raster> = frames.iter().step_by(every.max(1)).collect();
                Ok(crate::join::strip_of(&picked))
            }
            Drawing::Heatmap { size, mask } => Ok(crate::heatmap::draw(&deck, (size, size), mask)?.0),
            Drawing::Editor { sweep, script, time } => editor_screen(&deck, sweep, script, time),
            Drawing::Compare { panels } => crate::compare::draw(&deck.display().to_string(), panels),
        }
    }
}

/// The contour editor's screen, as `contour --screenshot` draws it.
fn editor_screen(deck: &Path, sweep: &str, script: &str, time: Option<f64>) -> Result<Raster, String> {
    use raytrace::editor::{document::Document, screen::screenshot, session::Editor};
    let input = raytrace::run::DeckInput::read(deck).map_err(|e| e.message)?;
    let mut editor = Editor::new(Document::open(input, sweep, Fidelity::Thesis).map_err(|e| e.message)?);
    if let Some(t) = time {
        editor.time = t;
    }
    editor.run_script(script, "EDITS")?;
    Ok(screenshot(&editor).to_raster())
}

/// A film deck's first `limit` frames (all, when it has fewer) rendered as
/// `raytrace` renders them (thesis fidelity, the table sampler), and its
/// rate.
pub fn film_frames(deck: &Path, limit: u32) -> Result<(Vec<Raster>, u32), String> {
    let opts = Options::default();
    let scene = crate::decks::prepared(&deck.display().to_string(), &opts, None)?;
    let film = scene
        .scene()
        .film
        .as_ref()
        .ok_or_else(|| format!("{}: no 'film' record", deck.display()))?;
    let frames = (1..=film.frames.min(limit))
        .map(|k| {
            let request = raytrace::raytrace::Request::frame(film.frame(k));
            raytrace::raytrace::render(&scene, &request).map(|r| r.raster)
        })
        .collect::<Result<_, _>>()
        .map_err(|e| e.to_string())?;
    Ok((frames, film.rate))
}

/// The frames of an animated PNG (one for a still PNG), 8-bit RGB.
pub fn read_png_frames(path: &Path) -> Result<Vec<Raster>, String> {
    use image::AnimationDecoder;
    let err = |e: image::ImageError| format!("{}: {e}", path.display());
    let file = std::io::BufReader::new(std::fs::File::open(path).map_err(|e| format!("{}: {e}", path.display()))?);
    let decoder = image::codecs::png::PngDecoder::new(file).map_err(err)?;
    if !decoder.is_apng().map_err(err)? {
        return Ok(vec![read_png(path)?]);
    }
    decoder
        .apng()
        .map_err(err)?
        .into_frames()
        .map(|f| {
            let img = image::DynamicImage::ImageRgba8(f.map_err(err)?.into_buffer()).to_rgb8();
            Ok(Raster {
                width: img.width() as usize,
                height: img.height() as usize,
                pixels: img.pixels().map(|p| p.0).collect(),
            })
        })
        .collect()
}

/// The deck's render in thesis fidelity with the table sampler, as the
/// `raytrace` command renders it by default (with `--solver` as given).
pub fn render_deck(deck: &Path, solver: Solver) -> Result<Raster, String> {
    let opts = Options {
        solver,
        ..Options::default()
    };
    let scene = crate::decks::prepared(&deck.display().to_string(), &opts, None)?;
    Ok(crate::decks::still(&scene).raster)
}

/// `left` and `right` side by side, `gap` white columns between them; the
/// taller sets the height, the shorter's rows below it are white.
pub fn side_by_side(left: &Raster, right: &Raster, gap: usize) -> Raster {
    let width = left.width + gap + right.width;
    let height = left.height.max(right.height);
    let mut out = Raster {
        width,
        height,
        pixels: vec![[255; 3]; width * height],
    };
    for (r, x0) in [(left, 0), (right, left.width + gap)] {
        for y in 0..r.height {
            let row = y * width + x0;
            out.pixels[row..row + r.width].copy_from_slice(&r.pixels[y * r.width..(y + 1) * r.width]);
        }
    }
    out
}

/// Reads a PNG of the docs as a raster (8-bit RGB).
pub fn read_png(path: &Path) -> Result<Raster, String> {
    let img = image::open(path)
        .map_err(|e| format!("{}: {e}", path.display()))?
        .to_rgb8();
    Ok(Raster {
        width: img.width() as usize,
        height: img.height() as usize,
        pixels: img.pixels().map(|p| p.0).collect(),
    })
}

/// How many pixels of `a` and `b` differ; every pixel when the sizes differ.
pub fn pixels_differing(a: &Raster, b: &Raster) -> usize {
    if (a.width, a.height) != (b.width, b.height) {
        return a.pixels.len().max(b.pixels.len());
    }
    a.pixels.iter().zip(&b.pixels).filter(|(p, q)| p != q).count()
}

/// `tools gallery`: draws the pictures of [`GALLERY`] whose image path
/// contains one of `only` (all when it is empty) and writes them, or with
/// `check` compares them with the files, in memory, and fails naming the
/// stale ones: a check writes nothing.
pub fn run(root: &Path, only: &[String], check: bool) -> Result<(), String> {
    let chosen: Vec<&Picture> = GALLERY
        .iter()
        .filter(|p| only.is_empty() || only.iter().any(|o| p.image.contains(o.as_str())))
        .collect();
    if chosen.is_empty() {
        return Err(format!("no picture of the gallery matches {only:?}"));
    }
    // The decks of Figs. 5.3–5.5 paste the texture rasters: written before
    // drawing, or checked like the pictures.
    let mut stale = Vec::new();
    if check {
        stale.extend(crate::textures::stale_textures(&root.join("raster")));
    } else {
        crate::textures::write_textures(&root.join("raster"))?;
    }
    for picture in chosen {
        // A film is all its frames and its rate; any other picture one raster.
        let (drawn, rate) = match picture.drawing {
            Drawing::Film => film_frames(&root.join(picture.deck), u32::MAX)?,
            _ => (vec![picture.draw(root)?], 0),
        };
        let path = root.join(picture.image);
        if check {
            let differ = match read_png_frames(&path) {
                Ok(on_disk) if on_disk.len() == drawn.len() => drawn
                    .iter()
                    .zip(&on_disk)
                    .map(|(a, b)| pixels_differing(a, b))
                    .sum::<usize>(),
                _ => drawn.iter().map(|d| d.pixels.len()).sum(),
            };
            println!("{:>7} pixels differ  {}", differ, picture.image);
            if differ > 0 {
                stale.push(picture.image.to_string());
            }
        } else if picture.drawing == Drawing::Film {
            raytrace::film::write_apng(&path, &drawn, rate).map_err(|e| format!("{}: {e}", path.display()))?;
            println!("wrote {}  ({})", picture.image, picture.command());
        } else {
            raytrace::raster::write_png(&path, &drawn[0]).map_err(|e| format!("{}: {e}", path.display()))?;
            println!("wrote {}  ({})", picture.image, picture.command());
        }
    }
    if stale.is_empty() {
        Ok(())
    } else {
        Err(format!(
            "stale: {}; `cargo run -p tools --release -- gallery` draws them again",
            stale.join(", ")
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first picture the README shows.
    fn readme_first_picture(root: &Path) -> String {
        let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
        let start = readme.find("![").expect("the README shows a picture");
        let rest = &readme[start..];
        let open = rest.find("](").unwrap() + 2;
        let close = rest[open..].find(')').unwrap();
        rest[open..open + close].to_string()
    }

    /// The README's first picture is the default deck's render as the
    /// renderer draws it today, decoded pixel for pixel: a picture left
    /// behind by a change of the deck or the renderer fails here.
    #[test]
    fn the_readmes_first_picture_is_todays_render_of_the_default_deck() {
        let root = checkout();
        let first = readme_first_picture(&root);
        let picture = GALLERY
            .iter()
            .find(|p| p.image == first)
            .unwrap_or_else(|| panic!("{first} is not in the gallery"));
        // The deck `raytrace` embeds and draws when none is given.
        let embedded = std::fs::read_to_string(root.join("src/bin/raytrace.rs")).unwrap();
        assert!(embedded.contains(&format!("include_str!(\"../../{}\")", picture.deck)));
        assert_eq!(picture.drawing, Drawing::Render);
        let drawn = picture.draw(&root).unwrap();
        let on_disk = read_png(&root.join(&first)).unwrap();
        assert_eq!(
            pixels_differing(&drawn, &on_disk),
            0,
            "{first} is stale: `cargo run -p tools --release -- gallery` draws it again"
        );
        // psout's screenshot in the README shows that same render.
        let screen = GALLERY.iter().find(|p| p.drawing == Drawing::Screen).unwrap();
        assert_eq!(screen.deck, picture.deck);
        let shot = read_png(&root.join(screen.image)).unwrap();
        let composed = psout::compose(&drawn, None, (0, 0)).to_raster();
        assert_eq!(pixels_differing(&composed, &shot), 0, "{} is stale", screen.image);
    }

    /// Every PNG under docs/ is in the gallery (or is a chart: `tools chart`
    /// and `tools scale` draw those from their measurements), every deck of
    /// the gallery exists, and no picture is listed twice.
    #[test]
    fn the_gallery_lists_every_picture_of_the_docs() {
        let root = checkout();
        let mut listed: Vec<&str> = GALLERY.iter().map(|p| p.image).collect();
        listed.sort();
        let before = listed.len();
        listed.dedup();
        assert_eq!(listed.len(), before, "a picture is listed twice");
        for dir in ["docs", "docs/img"] {
            for entry in std::fs::read_dir(root.join(dir)).unwrap() {
                let name = format!("{dir}/{}", entry.unwrap().file_name().to_string_lossy());
                if name.ends_with(".png") && !["docs/speed_accuracy.png", "docs/scale.png"].contains(&name.as_str()) {
                    assert!(listed.contains(&name.as_str()), "{name} is not in the gallery");
                }
            }
        }
        for p in GALLERY {
            assert!(root.join(p.deck).is_file(), "{}: no deck {}", p.image, p.deck);
            assert!(root.join(p.image).is_file(), "{} is not drawn yet", p.image);
        }
    }

    /// The tutorial's decks, in the order of its steps.
    fn tutorial_decks(root: &Path) -> Vec<PathBuf> {
        let mut decks: Vec<PathBuf> = std::fs::read_dir(root.join("legacy_pascal/tutorial"))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "deck"))
            .collect();
        decks.sort();
        decks
    }

    /// A deck's records: its lines without comments, blank lines dropped.
    fn records(deck: &Path) -> Vec<String> {
        let text = std::fs::read_to_string(deck).unwrap();
        let mut out = String::new();
        let mut in_comment = false;
        for c in text.chars() {
            match c {
                '{' => in_comment = true,
                '}' => in_comment = false,
                c if !in_comment => out.push(c),
                _ => {}
            }
        }
        out.lines()
            .filter(|l| !l.trim().is_empty())
            .map(str::to_owned)
            .collect()
    }

    /// Each tutorial deck reads, prepares and renders (here at 48×48), shows
    /// something its step before does not, keeps every record of the step
    /// before (but the image record), and has its pictures in the gallery.
    #[test]
    fn each_tutorial_deck_renders_and_builds_on_the_one_before() {
        let root = checkout();
        let decks = tutorial_decks(&root);
        assert_eq!(decks.len(), 6);
        let mut before: Option<(Vec<String>, Raster)> = None;
        for deck in &decks {
            let name = deck.strip_prefix(&root).unwrap().to_str().unwrap().to_owned();
            assert!(
                GALLERY.iter().any(|p| p.deck == name && p.drawing == Drawing::Render),
                "{name} has no picture in the gallery"
            );
            let opts = Options::default();
            let mut scene = crate::decks::load(deck.to_str().unwrap(), opts.fidelity).unwrap();
            scene.resize(48, 48, 2);
            let drawn = crate::decks::still(&crate::decks::prepare(scene, &opts).unwrap()).raster;
            let recs = records(deck);
            if let Some((recs_before, drawn_before)) = &before {
                assert!(
                    pixels_differing(&drawn, drawn_before) > 20,
                    "{name} looks like the step before"
                );
                for r in recs_before.iter().filter(|r| !r.starts_with("image")) {
                    assert!(recs.contains(r), "{name} drops `{r}` of the step before");
                }
            } else {
                assert!(
                    drawn
                        .pixels
                        .iter()
                        .any(|p| u32::from(p[0]) > 2 * u32::from(p[2]).max(20)),
                    "{name}: no red ball"
                );
            }
            before = Some((recs, drawn));
        }
    }

    /// Every line TUTORIAL.md shows in a step is a line of that step's deck,
    /// and the step's picture is the gallery's render of it.
    #[test]
    fn the_tutorial_page_quotes_its_decks() {
        let root = checkout();
        let page = std::fs::read_to_string(root.join("legacy_pascal/TUTORIAL.md")).unwrap();
        let steps: Vec<&str> = page.split("\n## Step ").skip(1).collect();
        assert_eq!(steps.len(), tutorial_decks(&root).len());
        for step in steps {
            let at = step.find("](tutorial/").unwrap() + 2;
            let end = at + step[at..].find(')').unwrap();
            let deck = format!("legacy_pascal/{}", &step[at..end]);
            let lines: Vec<String> = std::fs::read_to_string(root.join(&deck))
                .unwrap()
                .lines()
                .map(|l| l.trim_end().to_owned())
                .collect();
            let mut blocks = step.split("```").skip(1).step_by(2).peekable();
            assert!(blocks.peek().is_some(), "{deck}: no lines shown");
            for block in blocks {
                for line in block.lines().filter(|l| !l.trim().is_empty()) {
                    assert!(lines.contains(&line.to_owned()), "{deck} has no line `{line}`");
                }
            }
            let picture = GALLERY
                .iter()
                .find(|p| p.deck == deck && p.drawing == Drawing::Render)
                .unwrap();
            assert!(step.contains(&format!("(../{})", picture.image)), "{deck}: no picture");
        }
    }

    /// The two halves of the solvers' picture are drawn with each solver:
    /// on the edge-on goblet `laguerre` leaves bands the robust solver fills.
    #[test]
    fn the_solvers_picture_is_drawn_with_each_solver() {
        let deck = checkout().join("legacy_pascal/decks/stress_edge_on.deck");
        let laguerre = render_deck(&deck, Solver::Laguerre).unwrap();
        let robust = render_deck(&deck, Solver::Robust).unwrap();
        assert!(pixels_differing(&laguerre, &robust) > 100);
    }

    #[test]
    fn side_by_side_puts_a_white_gap_between() {
        let a = Raster {
            width: 2,
            height: 2,
            pixels: vec![[1; 3]; 4],
        };
        let b = Raster {
            width: 1,
            height: 1,
            pixels: vec![[2; 3]],
        };
        let s = side_by_side(&a, &b, 3);
        assert_eq!((s.width, s.height), (6, 2));
        assert_eq!(s.pixels[..6], [[1; 3], [1; 3], [255; 3], [255; 3], [255; 3], [2; 3]]);
        assert_eq!(s.pixels[6..], [[1; 3], [1; 3], [255; 3], [255; 3], [255; 3], [255; 3]]);
    }

    #[test]
    fn pixels_differing_counts() {
        let a = Raster {
            width: 2,
            height: 1,
            pixels: vec![[0; 3], [5; 3]],
        };
        let mut b = a.clone();
        assert_eq!(pixels_differing(&a, &b), 0);
        b.pixels[1][2] = 6;
        assert_eq!(pixels_differing(&a, &b), 1);
        b.width = 1;
        b.height = 2;
        assert_eq!(pixels_differing(&a, &b), 2);
    }

    /// Every file under `dir`, with its bytes.
    fn files_under(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
        let mut files = Vec::new();
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                files.extend(files_under(&path));
            } else {
                files.push((path.clone(), std::fs::read(&path).unwrap()));
            }
        }
        files.sort();
        files
    }

    /// `gallery --check` compares in memory: it writes no texture and no
    /// picture, and names a missing texture and a stale picture.
    #[test]
    fn a_check_writes_nothing() {
        let (root, copy) = (checkout(), tempfile::tempdir().unwrap());
        let picture = "docs/img/fig5_10_frames.png";
        for file in ["legacy_pascal/decks/fig5_10.deck", picture] {
            std::fs::create_dir_all(copy.path().join(file).parent().unwrap()).unwrap();
            std::fs::copy(root.join(file), copy.path().join(file)).unwrap();
        }
        // A picture of another size: every pixel differs.
        let small = Raster {
            width: 1,
            height: 1,
            pixels: vec![[0; 3]],
        };
        raytrace::raster::write_png(&copy.path().join(picture), &small).unwrap();
        let before = files_under(copy.path());
        let e = run(copy.path(), &["fig5_10_frames".into()], true).unwrap_err();
        assert!(
            e.starts_with("stale: raster/card.tex.ras, raster/nec.tex.ras, docs/img/fig5_10_frames.png;"),
            "{e}"
        );
        assert!(files_under(copy.path()) == before, "the check wrote a file");
    }

    /// The commands printed for the pictures name the options they are drawn with.
    #[test]
    fn the_commands_name_the_options() {
        let frames = GALLERY
            .iter()
            .find(|p| p.image == "docs/img/nec_morph_frames.png")
            .unwrap();
        assert_eq!(
            frames.command(),
            "cargo run -p tools --release -- frames legacy_pascal/decks/nec_morph.deck \
             --times 0,0.125,0.25,0.375,0.5,0.625,0.75,0.875,1 --size 112x112 --out docs/img/nec_morph_frames.png"
        );
        assert_eq!(
            GALLERY[0].command(),
            "cargo run --release -- legacy_pascal/decks/nec_morph.deck --png docs/img/nec_morph.png"
        );
    }
}

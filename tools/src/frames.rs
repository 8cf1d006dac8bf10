//! `tools frames DECK`: a filmstrip of a deck with key frames.

use std::path::{Path, PathBuf};

use raytrace::options::{Fidelity, Options};
use raytrace::raster::Raster;

/// Writes the [`filmstrip`] of `deck` to the PNG `out`; without `out`,
/// to `raster/<deck name>_frames.png` (the folder the renders go to, which
/// git ignores).
pub fn frames(
    deck: &Path,
    out: Option<&Path>,
    times: &[f64],
    size: (usize, usize),
    fidelity: Fidelity,
) -> Result<(), String> {
    let strip = filmstrip(deck, times, size, fidelity)?;
    let out = match out {
        Some(out) => out.to_path_buf(),
        None => {
            std::fs::create_dir_all("raster").map_err(|e| format!("raster: {e}"))?;
            default_out(deck)
        }
    };
    raytrace::raster::write_png(&out, &strip).map_err(|e| format!("{}: {e}", out.display()))?;
    println!("wrote {} ({} frames at t = {:?})", out.display(), times.len(), times);
    Ok(())
}

/// Where `tools frames DECK` writes without `--out`: `raster/<deck name>_frames.png`.
pub fn default_out(deck: &Path) -> PathBuf {
    let stem = deck.file_stem().map(|s| s.to_string_lossy()).unwrap_or("deck".into());
    Path::new("raster").join(format!("{stem}_frames.png"))
}

/// The scene of `deck` at each instant of `times`: every moving object at
/// its pose then, every key-frame object at its in-between shape and pose,
/// rendered still, `size` (W×H) pixels each, and laid side by side.
pub fn filmstrip(deck: &Path, times: &[f64], size: (usize, usize), fidelity: Fidelity) -> Result<Raster, String> {
    let source = std::fs::read_to_string(deck).map_err(|e| format!("{}: {e}", deck.display()))?;
    let dir = deck.parent().unwrap_or(Path::new("."));
    let opts = Options {
        fidelity,
        ..Options::default()
    };
    let mut scene =
        raytrace::deck::initialize(&source, &deck.display().to_string(), dir, fidelity).map_err(|e| e.to_string())?;
    let (w, h) = size;
    scene.image.width = w;
    scene.image.height = h;
    let prepared = crate::decks::prepare(scene, &opts)?;
    let mut strip = Raster {
        width: w * times.len().max(1),
        height: h,
        pixels: vec![[0; 3]; w * h * times.len().max(1)],
    };
    for (i, &t) in times.iter().enumerate() {
        let r = crate::decks::still(&prepared.still_at(t)).raster;
        for y in 0..h {
            let row = y * strip.width + i * w;
            strip.pixels[row..row + w].copy_from_slice(&r.pixels[y * w..(y + 1) * w]);
        }
    }
    Ok(strip)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Without --out the filmstrip goes to raster/, which git ignores.
    #[test]
    fn the_default_file_is_under_raster() {
        assert_eq!(
            default_out(Path::new("legacy_pascal/decks/fig5_10.deck")),
            Path::new("raster/fig5_10_frames.png")
        );
        let ignore = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../.gitignore")).unwrap();
        assert!(ignore.lines().any(|l| l == "/raster/*"));
    }
}

//! The texture rasters the decks paste on blocks and cylinders.

use raytrace::raster::Raster;

/// A 64×64 test card: eight colour bars over the top half, a grey ramp,
/// and a black frame with a white diagonal, so that a pasted picture shows
/// its orientation (which way is up, which is left) at a glance.
pub fn test_card(width: usize, height: usize) -> Raster {
    const BARS: [[u8; 3]; 8] = [
        [255, 255, 255],
        [255, 255, 0],
        [0, 255, 255],
        [0, 255, 0],
        [255, 0, 255],
        [255, 0, 0],
        [0, 0, 255],
        [0, 0, 0],
    ];
    let mut pixels = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let frame = x < 2 || y < 2 || x >= width - 2 || y >= height - 2;
            let diagonal = y >= height / 2 && (x as i64 - (y - height / 2) as i64 * 2).abs() <= 1;
            let px = if frame {
                [0, 0, 0]
            } else if diagonal {
                [255, 255, 255]
            } else if y < height / 2 {
                BARS[x * BARS.len() / width]
            } else {
                let g = (x * 255 / (width - 1)) as u8;
                [g, g, g / 2]
            };
            pixels.push(px);
        }
    }
    Raster { width, height, pixels }
}

/// The letters N, E, C in blue on white, 96×48, for the advertising cube
/// of Fig. 5.5. Each letter is drawn from strokes on a 5×7 grid.
pub fn nec_card() -> Raster {
    const GLYPHS: [[&str; 7]; 3] = [
        ["X...X", "XX..X", "XX..X", "X.X.X", "X..XX", "X..XX", "X...X"],
        ["XXXXX", "X....", "X....", "XXXX.", "X....", "X....", "XXXXX"],
        [".XXXX", "X....", "X....", "X....", "X....", "X....", ".XXXX"],
    ];
    let (cell, width, height) = (4usize, 96usize, 48usize);
    let (left, top) = (6usize, 10usize);
    let mut pixels = vec![[255u8, 255, 255]; width * height];
    for (g, glyph) in GLYPHS.iter().enumerate() {
        for (row, line) in glyph.iter().enumerate() {
            for (col, ch) in line.bytes().enumerate() {
                if ch != b'X' {
                    continue;
                }
                let x0 = left + g * (6 * cell + 4) + col * cell;
                let y0 = top + row * cell;
                for y in y0..y0 + cell {
                    for x in x0..x0 + cell {
                        pixels[y * width + x] = [20, 40, 170];
                    }
                }
            }
        }
    }
    Raster { width, height, pixels }
}

/// The texture rasters the decks paste, by file name: card.tex.ras
/// ([`test_card`], 64×64) and nec.tex.ras ([`nec_card`]).
pub fn textures() -> [(&'static str, Raster); 2] {
    [("card.tex.ras", test_card(64, 64)), ("nec.tex.ras", nec_card())]
}

/// The paths (`raster/NAME`) of the [`textures`] whose file in `dir` is
/// missing or differs from what [`write_textures`] writes: nothing is written.
pub fn stale_textures(dir: &std::path::Path) -> Vec<String> {
    textures()
        .into_iter()
        .filter(|(name, raster)| std::fs::read(dir.join(name)).ok() != Some(raytrace::raster::encode_raster(raster)))
        .map(|(name, _)| format!("raster/{name}"))
        .collect()
}

/// Writes the [`textures`] into `dir` (created if missing).
pub fn write_textures(dir: &std::path::Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for (name, raster) in textures() {
        let out = dir.join(name);
        raytrace::raster::outputframe(&out, &raster).map_err(|e| format!("{}: {e}", out.display()))?;
        println!("wrote {} ({}×{})", out.display(), raster.width, raster.height);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The texture rasters in raster/ are what `tools texture` writes.
    #[test]
    fn shipped_textures_are_the_tools_output() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../raster");
        let stale = stale_textures(&dir);
        assert!(stale.is_empty(), "{stale:?}: run `cargo run -p tools -- texture`");
        // And a texture that differs is named.
        let other = tempfile::tempdir().unwrap();
        write_textures(other.path()).unwrap();
        std::fs::write(other.path().join("nec.tex.ras"), b"old").unwrap();
        assert_eq!(stale_textures(other.path()), ["raster/nec.tex.ras"]);
    }
}

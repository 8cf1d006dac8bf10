//! The chart's text font. plotters' `ttf` feature would find system fonts
//! through font-kit, which links fontconfig and freetype; the `ab_glyph`
//! feature draws from a font the program registers instead, here DejaVu
//! Sans as the `dejavu` crate embeds it, so the chart builds and draws on
//! a machine without font libraries or fonts.

use plotters::style::{register_font, FontStyle};

/// Registers DejaVu Sans as the `sans-serif` family (every style falls
/// back to it). Safe to call more than once.
pub fn register() -> Result<(), String> {
    register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
        .map_err(|_| "the embedded DejaVu Sans is not a font ab_glyph can read".to_string())
}

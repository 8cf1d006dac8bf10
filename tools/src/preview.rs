//! `tools preview`: how long the contour editor takes from an edit to the
//! first preview on the screen (the port's editor, issue 28: goal ≤ 100 ms
//! at 128² for Fig. 5.8's goblet on one core). Each run moves a point
//! (alternately there and back), then times what the window does before
//! the quick preview shows: the job (the deck's scene with the contour),
//! its preparation (`spline`, the boxes, the camera), the render of
//! 128×128 at one ray a pixel, and the screen drawn with it. Medians are
//! printed, never asserted.

use std::time::Instant;

use raytrace::editor::document::Document;
use raytrace::editor::model::Edit;
use raytrace::editor::preview::{render_rows, QUICK};
use raytrace::editor::screen::{draw, Preview};
use raytrace::editor::session::Editor;
use raytrace::options::Fidelity;
use raytrace::run::DeckInput;

/// Times `runs` edits of point `point` (from 1) of the sweep `name` of
/// `deck`, each followed by the quick preview on `threads` threads (0: one
/// per core).
pub fn run(deck: &std::path::Path, name: &str, point: usize, runs: usize, threads: u16) -> Result<(), String> {
    let input = DeckInput::read(deck).map_err(|e| e.message)?;
    let doc = Document::open(input, name, Fidelity::Thesis).map_err(|e| e.message)?;
    let mut editor = Editor::new(doc);
    let k = point.checked_sub(1).filter(|&k| k < editor.contour.points.len());
    let k = k.ok_or_else(|| format!("{name} has no point {point}"))?;
    let pool = raytrace::cli::thread_pool(threads).map_err(|e| e.message)?;
    let step = 1.0 / editor.plane.scale;
    let (mut total, mut render) = (Vec::new(), Vec::new());
    for run in 0..=runs {
        let du = if run % 2 == 0 { step } else { -step };
        let start = Instant::now();
        editor.edit(Edit::Move { k, du, dv: 0.0 });
        let job = editor.job();
        let prepared = job.prepare(QUICK)?;
        let traced = Instant::now();
        let height = prepared.scene().image.height;
        let raster = pool.install(|| render_rows(&prepared, 0..height))?;
        let rendered = traced.elapsed();
        let preview = Preview {
            raster: Some(raster),
            mask: 1,
            note: None,
        };
        std::hint::black_box(draw(&editor, &preview));
        // The first run warms the caches and is not counted.
        if run > 0 {
            total.push(start.elapsed().as_secs_f64() * 1e3);
            render.push(rendered.as_secs_f64() * 1e3);
        }
    }
    let stats = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        (v[v.len() / 2], v[0], v[v.len() - 1])
    };
    let (t, r) = (stats(&mut total), stats(&mut render));
    println!(
        "{} {name}: edit to first preview ({}x{}, 1 ray a pixel, {threads} thread{}): median {:.1} ms (fastest {:.1}, slowest {:.1}) over {runs} edits; of it the render {:.1} ms",
        deck.display(),
        QUICK.long_side,
        QUICK.long_side,
        if threads == 1 { "" } else { "s" },
        t.0,
        t.1,
        t.2,
        r.0
    );
    Ok(())
}

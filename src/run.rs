//! A render's jobs around the thesis's main program, the port's: the deck
//! a program names, read ([`DeckInput`]); the files a run writes, named
//! ([`Outputs`]), checked and reserved before the render ([`Job`]); a
//! film's frames or a still rendered in turn, each written as soon as it
//! is done, those already complete kept (`--resume`), a still's band of
//! rows (`--tile`, [`crate::tile`]); and the summary ([`Summary`]).
//! `raytrace`, the tools and the tests call it in-process; the program
//! supplies what it adds ([`Hooks`]: a progress bar, a window, what a stop
//! keeps) and prints what it is told. Nothing here prints or ends the
//! process.

mod job;
mod outputs;

use std::fmt;
use std::io::Read;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::time::Instant;

pub use job::Job;
pub use outputs::{Outputs, DEFAULT_FOLDER};

use crate::exit::Failure;
use crate::film::Frame;
use crate::options::{Fidelity, Options, TimeSampler};
use crate::raytrace::{Prepared, Render, RenderError, Request};
use crate::reconstruct::Reconstruction;
use crate::scene::{ImageSpec, Scene};
use crate::tile::Tile;

/// The deck argument that means standard input.
pub const STDIN: &str = "-";

/// The name a deck read from standard input has in errors.
pub const STDIN_NAME: &str = "<stdin>";

/// A deck as a command names it, read: its text, the name its errors give,
/// the folder its files (textures) are relative to, and the stem the
/// default output is named by.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DeckInput {
    pub source: Vec<u8>,
    /// The file name as the user gave it, or [`STDIN_NAME`].
    pub name: String,
    /// The deck's folder; the current folder for standard input.
    pub dir: PathBuf,
    /// The file name without its extension; `stdin` for standard input.
    pub stem: String,
}

impl DeckInput {
    /// Reads the deck at `path`, or standard input for `-` ([`STDIN`]),
    /// at most one byte past the reader's limit ([`crate::deck::MAX_DECK_BYTES`]).
    /// A deck that cannot be read is an input error naming it.
    pub fn read(path: &Path) -> Result<DeckInput, Failure> {
        if path.as_os_str() == STDIN {
            return DeckInput::from_reader(std::io::stdin().lock(), STDIN_NAME, Path::new(""), "stdin")
                .map_err(|e| Failure::input(format!("{STDIN_NAME}: {e}")));
        }
        let source =
            crate::deck::read_deck_file(path).map_err(|e| Failure::input(format!("{}: {e}", path.display())))?;
        Ok(DeckInput {
            source,
            name: path.display().to_string(),
            dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
            stem: path
                .file_stem()
                .map_or("out".into(), |s| s.to_string_lossy().into_owned()),
        })
    }

    /// The deck's text as bytes from any reader (standard input, a test's
    /// buffer), named `name` in errors, its files relative to `dir`.
    pub fn from_reader(reader: impl Read, name: &str, dir: &Path, stem: &str) -> std::io::Result<DeckInput> {
        Ok(DeckInput {
            source: crate::deck::read_deck(reader)?,
            name: name.to_string(),
            dir: dir.to_path_buf(),
            stem: stem.to_string(),
        })
    }

    /// The scene the deck describes ([`crate::deck::initialize`]); an
    /// error is an input error at its FILE:LINE:COLUMN.
    pub fn initialize(&self, fidelity: Fidelity) -> Result<Scene, Failure> {
        crate::deck::initialize(&self.source, &self.name, &self.dir, fidelity).map_err(Failure::input)
    }
}

/// The rows of `prepared`'s image a render covers: band `tile` (K of N),
/// or the whole image. A usage error (exit 2) for more bands than rows,
/// and for a band of a sampler that renders no windows (the adaptive
/// sampler deals its rays over the whole image: its band would be another
/// picture).
pub fn rows(tile: Option<Tile>, prepared: &Prepared) -> Result<Range<usize>, Failure> {
    let height = prepared.scene().image.height;
    let Some(tile) = tile else {
        return Ok(0..height);
    };
    if !prepared.options().sampler.renders_windows() {
        return Err(Failure::usage(format!(
            "--tile {tile}: --sampler adaptive deals its rays over the whole image by need, so a \
             band rendered alone would be another picture; render the image whole, or use \
             --sampler table, random or stratified"
        )));
    }
    tile.band(height).map_err(Failure::usage)
}

/// How one frame's render in a program's hands ended ([`Hooks::render`]).
pub enum Rendered {
    /// It finished (or failed): the render.
    Done(Result<Render, RenderError>),
    /// The program was asked to stop (q or Esc in a window).
    Quit,
    /// What is rendered changed (a watched deck): render it again.
    Changed,
}

/// What a program adds to a run: each call is told what happens, and does
/// nothing by default ([`Quiet`]).
pub trait Hooks {
    /// A file that is there and not complete (`--resume`): it is rendered
    /// again.
    fn incomplete(&mut self, _path: &Path, _why: &str) {}
    /// A frame's render starts; `what` names it (`tracing DECK frame K/N`).
    fn frame_started(&mut self, _what: &str) {}
    /// A film's frame is written whole, or found complete: a stop keeps it.
    fn frame_written(&mut self, _number: u32, _path: PathBuf) {}
    /// Renders `request` of `prepared`: on `pool`, unless the program shows
    /// the picture as it renders (and may be asked to stop).
    fn render(&mut self, prepared: &Prepared, request: &Request, pool: &rayon::ThreadPool, _what: &str) -> Rendered {
        Rendered::Done(pool.install(|| crate::raytrace::render(prepared, request)))
    }
}

/// A run told nothing: for tools and tests.
pub struct Quiet;

impl Hooks for Quiet {}

/// A run of a prepared deck, its outputs reserved and its frames planned:
/// [`Run::start`], then [`Run::render`].
pub struct Run<'a> {
    prepared: &'a Prepared,
    deck: &'a DeckInput,
    tile: Option<Tile>,
    rows: Range<usize>,
    reconstruction: Reconstruction,
    job: Job,
    /// Each frame with whether its file is complete already (`--resume`).
    plan: Vec<(Frame, bool)>,
}

/// How a run ended.
pub enum Ended {
    /// Every frame is written: the summary.
    Done(Summary),
    /// [`Rendered::Quit`]: stopped, the frames before written.
    Quit,
    /// [`Rendered::Changed`].
    Changed,
}

impl<'a> Run<'a> {
    /// Checks `outputs` (usage errors first), reserves them, and plans the
    /// frames: under `--resume` each complete file is kept (an incomplete
    /// one is told to `hooks` and rendered again).
    pub fn start(
        prepared: &'a Prepared,
        deck: &'a DeckInput,
        outputs: &Outputs,
        reconstruction: Reconstruction,
        hooks: &mut dyn Hooks,
    ) -> Result<Run<'a>, Failure> {
        let format = outputs.check_names()?;
        let rows = rows(outputs.tile, prepared)?;
        let job = Job::reserve(outputs, prepared.scene(), deck, format)?;
        let img = &prepared.scene().image;
        let plan = job
            .frames()
            .into_iter()
            .map(|f| {
                let complete = outputs.resume
                    && match job.complete(f, img) {
                        Ok(()) => true,
                        Err(why) => {
                            if let Some((path, why)) = why {
                                hooks.incomplete(&path, &why);
                            }
                            false
                        }
                    };
                (f, complete)
            })
            .collect();
        Ok(Run {
            prepared,
            deck,
            tile: outputs.tile,
            rows,
            reconstruction,
            job,
            plan,
        })
    }

    /// A film's frames to render: the first and last.
    pub fn film(&self) -> Option<(u32, u32)> {
        self.job.range().map(|r| (r.first, r.last))
    }

    /// The frames to render, those kept left out.
    pub fn rendered(&self) -> usize {
        self.plan.iter().filter(|&&(_, complete)| !complete).count()
    }

    /// The rows of pixels to render in all: the progress's whole.
    pub fn rows_to_render(&self) -> u64 {
        self.rows.len() as u64 * self.rendered() as u64
    }

    /// Renders the frames in order on `pool` (through `hooks`), `progress`
    /// called as each row is done; writes each as it is done, keeps those
    /// complete already, then writes the animated PNG.
    pub fn render(
        mut self,
        pool: &rayon::ThreadPool,
        progress: &(dyn Fn() + Sync),
        hooks: &mut dyn Hooks,
    ) -> Result<Ended, Failure> {
        let (written, film) = self.job.summary();
        let started = Instant::now();
        let mut rays = 0;
        let plan = std::mem::take(&mut self.plan);
        let deck = &self.deck.name;
        // In frame order, so that the animated PNG has them in order.
        for &(frame, complete) in &plan {
            if complete {
                self.job.keep(frame)?;
            } else {
                let what = self.job.tracing(deck, frame);
                hooks.frame_started(&what);
                let request = Request::frame(frame)
                    .rows(self.rows.clone())
                    .reconstruction(self.reconstruction)
                    .progress(progress);
                let render = match hooks.render(self.prepared, &request, pool, &what) {
                    Rendered::Done(r) => r,
                    Rendered::Quit => return Ok(Ended::Quit),
                    Rendered::Changed => return Ok(Ended::Changed),
                };
                let render = render
                    .and_then(|r| r.check_finite().map(|()| r))
                    .map_err(|e| Failure::other(format!("{}: {e}", self.job.what(deck, frame))))?;
                rays += render.stats.rays;
                self.job.write(frame, render, self.prepared)?;
            }
            if let Some(path) = self.job.frame_file(frame) {
                hooks.frame_written(frame.number, path);
            }
        }
        let elapsed = started.elapsed().as_secs_f64();
        self.job.finish()?;
        let kept = plan.iter().filter(|&&(_, complete)| complete).count();
        Ok(Ended::Done(Summary {
            deck: deck.clone(),
            written,
            film,
            band: self.tile.map(|t| (t, self.rows.clone())),
            image: self.prepared.scene().image.clone(),
            options: *self.prepared.options(),
            reconstruction: self.reconstruction,
            rays,
            seconds: elapsed,
            kept,
            rendered: plan.len() - kept,
        }))
    }
}

/// What a run did, for its summary line ([`fmt::Display`]): `DECK → FILES
/// (frames, band, size, sampling, rays, seconds, kept)`.
#[derive(Clone, Debug)]
pub struct Summary {
    pub deck: String,
    /// The files written.
    pub written: String,
    /// A film's frames: `frames A..B of N`.
    pub film: Option<String>,
    /// A still's band and its rows (`--tile`).
    pub band: Option<(Tile, Range<usize>)>,
    pub image: ImageSpec,
    pub options: Options,
    pub reconstruction: Reconstruction,
    /// The rays traced.
    pub rays: u64,
    /// The render's wall time.
    pub seconds: f64,
    /// The frames complete already (`--resume`), and those rendered.
    pub kept: usize,
    pub rendered: usize,
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let img = &self.image;
        let band = self
            .band
            .as_ref()
            .map(|(t, rows)| format!("band {t} (rows {}..{}) of ", rows.start, rows.end))
            .unwrap_or_default();
        let kept = match (self.kept, self.rendered) {
            (0, _) => String::new(),
            (_, 0) => ", all complete already (--resume): nothing rendered".into(),
            (n, _) => format!(", {n} complete already (--resume) kept"),
        };
        write!(
            f,
            "{} → {} ({}{band}{}×{}, {}, {} rays, {:.2} s{}{kept})",
            self.deck,
            self.written,
            self.film.as_ref().map(|f| format!("{f}, ")).unwrap_or_default(),
            img.width,
            img.height,
            sampling(&self.options, img, self.reconstruction),
            self.rays,
            self.seconds,
            self.film
                .as_ref()
                .filter(|_| self.rendered > 0)
                .map(|_| format!(", {:.2} s a frame", self.seconds / self.rendered as f64))
                .unwrap_or_default()
        )
    }
}

/// The summary line's words for the rays a pixel: M×M subpixels, or the
/// adaptive sampler's average; and how the pixels were made, when not by
/// `antialias`'s box.
fn sampling(opts: &Options, img: &ImageSpec, reconstruction: Reconstruction) -> String {
    let rays = match opts.sampler {
        TimeSampler::Adaptive => format!("{} rays a pixel on average, adaptive", img.masksize * img.masksize),
        _ => format!("{}×{} subpixels", img.masksize, img.masksize),
    };
    match reconstruction {
        Reconstruction::Box => rays,
        Reconstruction::Denoise => format!("{rays}, denoised"),
        Reconstruction::Coherence(n) => format!("{rays} in the pixels coherence {n} traced"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_deck_from_a_reader_keeps_its_name_folder_and_stem() {
        let deck = DeckInput::from_reader(&b"view"[..], STDIN_NAME, Path::new(""), "stdin").unwrap();
        assert_eq!(deck.source, b"view");
        assert_eq!((deck.dir.as_os_str(), deck.stem.as_str()), ("".as_ref(), "stdin"));
        let e = deck.initialize(Fidelity::Thesis).unwrap_err();
        assert_eq!(e.kind, crate::exit::Kind::Input);
        assert!(e.message.starts_with("<stdin>:1:"), "{e}");
    }

    #[test]
    fn a_missing_deck_file_is_an_input_error_naming_it() {
        let e = DeckInput::read(Path::new("/nonexistent/x.deck")).unwrap_err();
        assert_eq!(e.kind, crate::exit::Kind::Input);
        assert!(e.message.starts_with("/nonexistent/x.deck: "), "{e}");
    }
}

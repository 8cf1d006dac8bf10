//! What `raytrace` says when SIGINT (Ctrl-C) or SIGTERM stops it, after
//! the temporary files are removed (`raytrace::cli::on_signal`): what
//! was kept — a film's frames written whole so far; a still is written
//! whole at its end, so nothing — and the command that goes on: the same
//! one with `--resume` where that checks the outputs (Sun rasters), else a
//! film's `--frames` from the first frame not written.

use std::path::PathBuf;
use std::sync::{Mutex, PoisonError};

/// What the run has kept so far, and how it goes on.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Kept {
    /// The command's words as it was run.
    pub args: Vec<String>,
    /// Whether `--resume` goes on from here: the outputs are the Sun
    /// rasters it checks.
    pub resumable: bool,
    /// A film's frames: the range's first and last.
    pub film: Option<(u32, u32)>,
    /// The frames written (or found complete) so far, in order: number and file.
    pub done: Vec<(u32, PathBuf)>,
}

static KEPT: Mutex<Option<Kept>> = Mutex::new(None);

fn kept() -> std::sync::MutexGuard<'static, Option<Kept>> {
    KEPT.lock().unwrap_or_else(PoisonError::into_inner)
}

/// Starts the account of a run (again for each render under --watch), and
/// has a signal print it.
pub fn start(kept_now: Kept) {
    *kept() = Some(kept_now);
    raytrace::cli::on_signal(|signal| {
        if let Some(k) = kept().as_ref() {
            eprintln!("\nraytrace: {}", k.note(signal));
        }
    });
}

/// A frame of the film is written whole (or was, under `--resume`).
pub fn frame_done(number: u32, path: PathBuf) {
    if let Some(k) = kept().as_mut() {
        k.done.push((number, path));
    }
}

impl Kept {
    /// What a signal's stop leaves, and the command that goes on.
    pub fn note(&self, signal: i32) -> String {
        let name = match signal {
            2 => "SIGINT (Ctrl-C)".to_string(),
            15 => "SIGTERM".to_string(),
            n => format!("signal {n}"),
        };
        let kept = match (self.film, self.done.first(), self.done.last()) {
            (None, ..) => "nothing is written: a still is written whole when it is done".to_string(),
            (Some(_), None, _) | (Some(_), _, None) => "no frame is written whole yet".to_string(),
            (Some((first, last)), Some((_, a)), Some((_, b))) => format!(
                "{} of frames {first}..{last} written whole and kept ({} … {})",
                self.done.len(),
                a.display(),
                b.display()
            ),
        };
        format!("stopped by {name}: {kept}; to go on: {}", self.going_on())
    }

    /// The command that goes on: with `--resume` where it checks the
    /// outputs; else a film's rest by `--frames`; else the command again.
    fn going_on(&self) -> String {
        let mut words = self.args.clone();
        let next = self.done.last().map(|(n, _)| n + 1);
        match self.film {
            _ if self.resumable && words.iter().any(|w| w == "--resume") => {}
            _ if self.resumable => words.push("--resume".into()),
            Some((first, last)) => {
                drop_flag(&mut words, "--frames");
                words.push("--frames".into());
                words.push(format!("{}..{last}", next.unwrap_or(first).min(last)));
            }
            None => {}
        }
        words.iter().map(|w| shell_word(w)).collect::<Vec<_>>().join(" ")
    }
}

/// Removes `flag` and its value (`--frames 1..4` or `--frames=1..4`).
fn drop_flag(words: &mut Vec<String>, flag: &str) {
    let mut i = 0;
    while i < words.len() {
        if words[i] == flag {
            let end = (i + 2).min(words.len());
            words.drain(i..end);
        } else if words[i].strip_prefix(flag).is_some_and(|r| r.starts_with('=')) {
            words.remove(i);
        } else {
            i += 1;
        }
    }
}

/// A word as a POSIX shell reads it back: as it is when it holds only
/// characters no shell treats specially, else in single quotes.
fn shell_word(word: &str) -> String {
    let plain = |c: char| c.is_ascii_alphanumeric() || "_-./:=,+@%^".contains(c);
    if !word.is_empty() && word.chars().all(plain) {
        word.to_string()
    } else {
        format!("'{}'", word.replace('\'', r"'\''"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept(args: &[&str], resumable: bool, film: Option<(u32, u32)>, done: &[u32]) -> Kept {
        Kept {
            args: args.iter().map(|s| s.to_string()).collect(),
            resumable,
            film,
            done: done
                .iter()
                .map(|&k| (k, PathBuf::from(format!("f.{k:04}.ras"))))
                .collect(),
        }
    }

    #[test]
    fn a_film_keeps_its_frames_and_goes_on_with_resume() {
        let k = kept(
            &["raytrace", "film.deck", "--frames", "1..8"],
            true,
            Some((1, 8)),
            &[1, 2, 3],
        );
        assert_eq!(
            k.note(2),
            "stopped by SIGINT (Ctrl-C): 3 of frames 1..8 written whole and kept (f.0001.ras … f.0003.ras); \
             to go on: raytrace film.deck --frames 1..8 --resume"
        );
        let none = kept(&["raytrace", "film.deck", "--resume"], true, Some((1, 8)), &[]);
        assert_eq!(
            none.note(15),
            "stopped by SIGTERM: no frame is written whole yet; to go on: raytrace film.deck --resume"
        );
    }

    #[test]
    fn a_film_of_pngs_goes_on_from_its_next_frame() {
        let k = kept(
            &["raytrace", "my film.deck", "-o", "f.png", "--frames=2..9"],
            false,
            Some((2, 9)),
            &[2, 3],
        );
        assert!(
            k.note(2)
                .ends_with("to go on: raytrace 'my film.deck' -o f.png --frames 4..9"),
            "{}",
            k.note(2)
        );
    }

    #[test]
    fn a_still_keeps_nothing_and_is_run_again() {
        let k = kept(&["raytrace", "a.deck", "-o", "it's.png"], false, None, &[]);
        assert_eq!(
            k.note(2),
            "stopped by SIGINT (Ctrl-C): nothing is written: a still is written whole when it is done; \
             to go on: raytrace a.deck -o 'it'\\''s.png'"
        );
        let ras = kept(&["raytrace", "a.deck"], true, None, &[]);
        assert!(ras.note(2).ends_with("to go on: raytrace a.deck --resume"));
    }
}

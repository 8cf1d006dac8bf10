//! A render's job outside the thesis's main program: the deck a program
//! names, read ([`DeckInput`]). The port's; `raytrace`, the tools, the
//! editor and the tests call it in-process.

use std::io::Read;
use std::path::{Path, PathBuf};

use crate::exit::Failure;
use crate::options::Fidelity;
use crate::scene::Scene;

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

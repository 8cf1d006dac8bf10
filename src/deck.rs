//! `initialize` (stand-in until the deck branch lands).
use std::path::Path;

use crate::types::{Fidelity, Scene};

#[derive(Debug, thiserror::Error)]
#[error("{file}:{line}:{column}: {record}: {message}")]
pub struct DeckError {
    pub file: String,
    pub line: u32,
    pub column: u32,
    pub record: String,
    pub message: String,
}

pub fn initialize(_source: &str, file_name: &str, _deck_dir: &Path, _fidelity: Fidelity) -> Result<Scene, DeckError> {
    Err(DeckError { file: file_name.into(), line: 1, column: 1, record: "deck".into(), message: "not built yet".into() })
}

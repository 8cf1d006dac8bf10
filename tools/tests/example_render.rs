//! examples/render.rs, the program that embeds the renderer (docs/usage.md,
//! "Embedding"), refuses what it cannot use as `raytrace` does: a missing
//! or bad deck with the library's own error, exit 2, nothing written. (The
//! docs test runs its good command.) `cargo test --workspace` builds the
//! example beside this build's programs.

use std::path::PathBuf;
use std::process::Command;

fn example() -> PathBuf {
    let tools = PathBuf::from(env!("CARGO_BIN_EXE_tools"));
    let path = tools.parent().unwrap().join("examples/render");
    assert!(
        path.is_file(),
        "{} is missing: `cargo test --workspace` builds it",
        path.display()
    );
    path
}

#[test]
fn a_bad_or_missing_deck_is_exit_2_at_its_place_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("bad.deck");
    std::fs::write(&deck, "image 8 6 mask 2\nsphere").unwrap();
    let out = dir.path().join("o.png");
    for (input, says) in [
        (
            deck.clone(),
            format!("{}:2:7: sphere: expected an object name", deck.display()),
        ),
        (
            dir.path().join("missing.deck"),
            format!("{}: ", dir.path().join("missing.deck").display()),
        ),
    ] {
        let run = Command::new(example()).arg(&input).arg(&out).output().unwrap();
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "{stderr}");
        assert!(stderr.starts_with(&format!("render: {says}")), "{stderr}");
        assert!(!out.exists());
    }
    let usage = Command::new(example()).arg(&deck).output().unwrap();
    assert_eq!(usage.status.code(), Some(2));
}

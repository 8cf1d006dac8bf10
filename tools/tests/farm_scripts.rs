//! The farm scripts from a fresh checkout (docs/farm.md): with neither
//! `raytrace` nor `tools` on PATH, `farm/parallel.sh` builds the
//! checkout's release binaries once (`cargo build --release`) and runs
//! them; a second run builds nothing; with both on PATH it runs those.
//!
//! `cargo` here is a stand-in first on PATH that logs its arguments and
//! puts this build's binaries where the release build would leave them
//! (`$CARGO_TARGET_DIR/release`), so the test builds nothing itself. GNU
//! parallel is needed: without it the test is skipped, except under CI,
//! which installs it.

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The checkout.
fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// This build's binaries' folder (raytrace beside tools).
fn built() -> PathBuf {
    Path::new(env!("CARGO_BIN_EXE_tools")).parent().unwrap().to_path_buf()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn the_parallel_recipe_runs_from_a_checkout_building_once() {
    if Command::new("parallel").arg("--version").output().is_err() {
        assert!(std::env::var_os("CI").is_none(), "CI installs GNU parallel");
        eprintln!("skipped: GNU parallel is not installed");
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let work = tmp.path().join("checkout");
    std::fs::create_dir(&work).unwrap();
    for part in ["legacy_pascal", "farm"] {
        std::os::unix::fs::symlink(repo().join(part), work.join(part)).unwrap();
    }
    let fake = tmp.path().join("fakebin");
    std::fs::create_dir(&fake).unwrap();
    let log = tmp.path().join("cargo.log");
    let cargo = fake.join("cargo");
    std::fs::write(
        &cargo,
        format!(
            "#!/bin/sh\necho \"$*\" >> '{}'\nmkdir -p \"$CARGO_TARGET_DIR/release\"\ncp '{}/raytrace' '{}/tools' \"$CARGO_TARGET_DIR/release/\"\n",
            log.display(),
            built().display(),
            built().display()
        ),
    )
    .unwrap();
    std::fs::set_permissions(&cargo, std::fs::Permissions::from_mode(0o755)).unwrap();
    let target = tmp.path().join("target");
    let run = |path: &str| {
        Command::new("farm/parallel.sh")
            .args(["film", "legacy_pascal/decks/nec_commercial.deck", "1-2"])
            .current_dir(&work)
            .env("PATH", path)
            .env("CARGO_TARGET_DIR", &target)
            .env("FLAGS", "--size 16x16")
            .env("OUT", "out")
            .output()
            .unwrap()
    };
    let bare = format!("{}:/usr/bin:/bin", fake.display());
    let o = run(&bare);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("not on PATH: building the checkout's once"),
        "{}",
        stderr(&o)
    );
    for f in [
        "nec_commercial.0001.ras",
        "nec_commercial.0002.ras",
        "nec_commercial.png",
    ] {
        assert!(work.join("out").join(f).is_file(), "{f}");
    }
    let built_once = std::fs::read_to_string(&log).unwrap();
    assert_eq!(built_once.lines().count(), 1, "{built_once}");
    assert!(built_once.starts_with("build --release"), "{built_once}");
    // Again: the binaries are there, nothing is built.
    std::fs::remove_dir_all(work.join("out")).unwrap();
    let o = run(&bare);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stderr(&o).contains("using the checkout's"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&log).unwrap(), built_once);
    // Both on PATH: those are used.
    let o = run(&format!("{}:{bare}", built().display()));
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("using raytrace and tools from PATH"),
        "{}",
        stderr(&o)
    );
    assert!(work.join("out/nec_commercial.png").is_file());
}

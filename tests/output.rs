//! The output writer (`raytrace::output`): formats by extension, devices
//! and FIFOs written into and never replaced, symbolic links kept, clear
//! errors for missing folders, reservations that leave nothing behind, and
//! stale temporary files of dead processes removed.

use std::os::unix::fs::FileTypeExt;
use std::path::Path;
use std::process::Command;

use raytrace::output::{this_host, write_atomically, OutputError, PendingFile};

use raytrace::raster::{encode_raster, outputframe, read_raster, read_raster_file, Raster, RasterError};
use raytrace::raster::{write_image, Format, FormatError};

mod common;
use common::file_names;

fn raster(width: usize, height: usize) -> Raster {
    let pixels = (0..width * height)
        .map(|i| [i as u8, (i * 7) as u8, (255 - i) as u8])
        .collect();
    Raster { width, height, pixels }
}

#[test]
fn the_extension_chooses_the_format_and_anything_else_is_an_error_naming_them() {
    for (name, format) in [
        ("a.ras", Format::SunRaster),
        ("dir.d/A.RAS", Format::SunRaster),
        ("a.png", Format::Png),
        ("a.PNG", Format::Png),
        ("a.ppm", Format::Netpbm),
        ("a.pnm", Format::Netpbm),
    ] {
        assert_eq!(Format::of(Path::new(name)).unwrap(), format, "{name}");
    }
    for (name, says) in [
        ("a.jpg", "unknown extension '.jpg'"),
        ("a", "no extension"),
        ("ras", "no extension"),
    ] {
        let e = Format::of(Path::new(name)).unwrap_err();
        assert!(matches!(e, FormatError::UnknownFormat(_)), "{name}: {e:?}");
        let message = e.to_string();
        assert!(message.starts_with(says), "{name}: {message}");
        for ext in [".ras", ".png", ".ppm", ".pnm"] {
            assert!(message.contains(ext), "{name}: {message}");
        }
    }
    assert!(matches!(Format::of(Path::new("")), Err(FormatError::Empty)));
}

/// An output's format: standard output and a device or FIFO without an
/// extension get the Sun raster; a file or a new name without one none, a
/// folder none either (it is named as one); a device with an extension its
/// extension's.
#[test]
fn an_output_without_an_extension_that_is_a_stream_is_a_sun_raster() {
    for name in ["-", "/dev/null"] {
        assert_eq!(Format::of_output(Path::new(name)).unwrap(), Format::SunRaster, "{name}");
    }
    let dir = tempfile::tempdir().unwrap();
    let plain = dir.path().join("plain");
    std::fs::write(&plain, b"x").unwrap();
    let folder = Format::of_output(dir.path()).unwrap_err();
    assert!(matches!(folder, FormatError::IsAFolder), "{folder:?}");
    for path in [plain, dir.path().join("new")] {
        let e = Format::of_output(&path).unwrap_err();
        assert!(
            matches!(e, FormatError::UnknownFormat(None)),
            "{}: {e:?}",
            path.display()
        );
    }
    assert_eq!(Format::of_output(Path::new("a.png")).unwrap(), Format::Png);
    assert!(Format::of_output(Path::new("a.jpg")).is_err());
}

#[test]
fn each_format_writes_what_its_readers_read() {
    let dir = tempfile::tempdir().unwrap();
    let r = raster(5, 3);
    let ras = dir.path().join("x.ras");
    write_image(&ras, &r, Format::SunRaster).unwrap();
    assert_eq!(std::fs::read(&ras).unwrap(), encode_raster(&r));
    let ppm = dir.path().join("x.ppm");
    write_image(&ppm, &r, Format::Netpbm).unwrap();
    let bytes = std::fs::read(&ppm).unwrap();
    let header = b"P6\n5 3\n255\n";
    assert_eq!(&bytes[..header.len()], header);
    assert_eq!(&bytes[header.len()..], r.pixels.as_flattened());
    #[cfg(feature = "png")]
    {
        let png = dir.path().join("x.png");
        write_image(&png, &r, Format::Png).unwrap();
        let back = image::open(&png).unwrap().to_rgb8();
        assert_eq!(back.as_raw(), r.pixels.as_flattened());
    }
}

/// `mkfifo PATH`; false (with a note) where the command is missing.
fn mkfifo(path: &Path) -> bool {
    match Command::new("mkfifo").arg(path).status() {
        Ok(s) if s.success() => true,
        other => {
            eprintln!("skipped: mkfifo failed ({other:?})");
            false
        }
    }
}

/// A FIFO in the target's place is written into: its reader gets the
/// raster, and it is still a FIFO afterwards (a rename would have replaced
/// it by a regular file).
#[test]
fn a_fifo_is_written_into_not_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.ras");
    if !mkfifo(&fifo) {
        return;
    }
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let r = raster(4, 4);
    outputframe(&fifo, &r).unwrap();
    // Checked before joining: a replaced FIFO would leave the reader waiting.
    assert!(std::fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    let got = reader.join().unwrap();
    assert_eq!(read_raster(&got).unwrap(), r);
    assert_eq!(file_names(dir.path()), ["pipe.ras"]);
}

/// A character device made with mknod in a temporary folder (a copy of
/// /dev/null, never the real one) stays a device after a write. Needs
/// root; skipped otherwise.
#[test]
fn a_device_is_written_into_not_replaced() {
    let dir = tempfile::tempdir().unwrap();
    let null = dir.path().join("null.ras");
    match Command::new("mknod").arg(&null).args(["c", "1", "3"]).output() {
        Ok(o) if o.status.success() => {}
        other => {
            eprintln!("skipped: mknod needs root ({other:?})");
            return;
        }
    }
    outputframe(&null, &raster(3, 2)).unwrap();
    let kind = std::fs::symlink_metadata(&null).unwrap().file_type();
    assert!(kind.is_char_device(), "{kind:?}");
    assert_eq!(file_names(dir.path()), ["null.ras"]);
}

#[test]
fn a_symbolic_link_to_a_file_is_kept_and_its_file_replaced() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("real")).unwrap();
    let file = dir.path().join("real/frame.ras");
    std::fs::write(&file, b"old").unwrap();
    let link = dir.path().join("link.ras");
    std::os::unix::fs::symlink("real/frame.ras", &link).unwrap();
    let r = raster(2, 2);
    outputframe(&link, &r).unwrap();
    assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
    assert_eq!(read_raster_file(&file).unwrap(), r);
    assert_eq!(file_names(&dir.path().join("real")), ["frame.ras"]);
}

/// A missing folder, a file where a folder should be, and a folder where
/// the file should be: each a clear error naming the culprit, nothing
/// created.
#[test]
fn missing_folders_and_files_in_the_way_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("no/such/x.ras");
    let e = PendingFile::create(&missing).unwrap_err();
    assert!(
        matches!(&e, OutputError::MissingFolder(d) if d == &dir.path().join("no/such")),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        format!("the folder {} does not exist", dir.path().join("no/such").display())
    );

    let old = dir.path().join("old.ras");
    std::fs::write(&old, b"a raster").unwrap();
    for path in [old.join("x.ras"), old.join("deeper/x.ras")] {
        let e = PendingFile::create(&path).unwrap_err();
        assert!(
            matches!(&e, OutputError::NotAFolder(f) if f == &old),
            "{}: {e:?}",
            path.display()
        );
        assert_eq!(e.to_string(), format!("{} is a file, not a folder", old.display()));
    }
    let e = PendingFile::create(dir.path()).unwrap_err();
    assert!(matches!(e, OutputError::IsAFolder), "{e:?}");
    let e = PendingFile::create(Path::new("")).unwrap_err();
    assert!(matches!(e, OutputError::Empty), "{e:?}");
    // Through the raster writer, the same error.
    assert!(matches!(
        outputframe(&missing, &raster(1, 1)),
        Err(RasterError::Output(OutputError::MissingFolder(_)))
    ));
    assert_eq!(file_names(dir.path()), ["old.ras"]);
    assert_eq!(std::fs::read(&old).unwrap(), b"a raster");
}

/// A reservation holds a temporary file from `create` to `commit`; dropped
/// uncommitted, or failing in its writer, it leaves the target as it was
/// and no temporary file.
#[test]
fn a_reservation_left_or_failed_leaves_the_target_as_it_was() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("x.ras");
    std::fs::write(&target, b"last good").unwrap();
    let pending = PendingFile::create(&target).unwrap();
    let during = file_names(dir.path());
    assert_eq!(during.len(), 2, "{during:?}");
    assert!(
        during[0].starts_with(".x.ras.") && during[0].ends_with(".tmp"),
        "{during:?}"
    );
    drop(pending);
    assert_eq!(file_names(dir.path()), ["x.ras"]);
    let failed: Result<(), OutputError> = write_atomically(&target, |w| {
        w.write_all(b"half")?;
        Err(std::io::Error::other("the render failed").into())
    });
    assert!(failed.is_err());
    assert_eq!(file_names(dir.path()), ["x.ras"]);
    assert_eq!(std::fs::read(&target).unwrap(), b"last good");
    let pending = PendingFile::create(&target).unwrap();
    pending
        .commit(|w| w.write_all(b"new").map_err(OutputError::from))
        .unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"new");
    assert_eq!(file_names(dir.path()), ["x.ras"]);
}

/// The PID of a process that has exited (reaped, so /proc no longer lists it).
fn dead_pid() -> u32 {
    let mut child = Command::new("true").spawn().unwrap();
    let pid = child.id();
    child.wait().unwrap();
    assert!(!Path::new("/proc").join(pid.to_string()).exists());
    pid
}

/// After a SIGKILL the temporary file stays; the next write of the same
/// target removes the ones of dead processes of this host, and only those:
/// a live process's, another host's (its PIDs are not this host's), an
/// older version's without a host, another target's and a file that
/// merely looks alike stay.
#[test]
fn the_next_write_removes_stale_temporary_files_of_dead_processes_of_this_host() {
    if !Path::new("/proc/self").exists() {
        eprintln!("skipped: no /proc to tell dead processes from live ones");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let dead = dead_pid();
    let live = std::process::id();
    let host = this_host();
    assert!(!host.is_empty() && !host.contains('.'), "{host}");
    let stale = [
        format!(".x.ras.{host}.{dead}.0.tmp"),
        format!(".x.ras.{host}.{dead}.17.tmp"),
    ];
    let kept = [
        format!(".x.ras.{host}.{live}.999.tmp"),
        format!(".x.ras.other-{host}.{dead}.0.tmp"),
        format!(".x.ras.{dead}.0.tmp"),
        format!(".y.ras.{host}.{dead}.0.tmp"),
        format!(".x.ras.{host}.{dead}.tmp"),
        format!(".x.ras.{host}.{dead}.z.tmp"),
        format!("x.ras.{host}.{dead}.0.tmp"),
    ];
    for name in stale.iter().chain(&kept) {
        std::fs::write(dir.path().join(name), b"left over").unwrap();
    }
    outputframe(&dir.path().join("x.ras"), &raster(2, 1)).unwrap();
    let mut expected: Vec<String> = kept.to_vec();
    expected.push("x.ras".into());
    expected.sort();
    assert_eq!(file_names(dir.path()), expected);
}

/// The host of a temporary file's name is the kernel's host name, each
/// character other than a letter, a digit or `-` made `_` (the rule's own
/// test is `output::tests::a_host_name_becomes_one_word_without_dots`).
#[test]
fn the_host_is_the_kernels_host_name() {
    let Ok(name) = std::fs::read_to_string("/proc/sys/kernel/hostname") else {
        eprintln!("skipped: no /proc/sys/kernel/hostname");
        return;
    };
    let want: String = name
        .trim()
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' })
        .collect();
    assert!(!want.is_empty());
    assert_eq!(this_host(), want);
}

/// A temporary file's name is `.NAME.HOST.PID.N.tmp`, with this host and
/// this process.
#[test]
fn a_temporary_file_names_its_host_and_process() {
    let dir = tempfile::tempdir().unwrap();
    let _pending = PendingFile::create(&dir.path().join("x.y.ras")).unwrap();
    let names = file_names(dir.path());
    let prefix = format!(".x.y.ras.{}.{}.", this_host(), std::process::id());
    assert!(
        names.len() == 1 && names[0].starts_with(&prefix) && names[0].ends_with(".tmp"),
        "{names:?}, wanted {prefix}N.tmp"
    );
}

/// Another writer removes a live writer's temporary file (it took it for a
/// dead one's): the commit fails naming the temporary file, and the target
/// is as it was.
#[test]
fn a_temporary_file_removed_by_another_writer_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("x.ras");
    std::fs::write(&target, b"last good").unwrap();
    let pending = PendingFile::create(&target).unwrap();
    let temp = dir.path().join(file_names(dir.path()).remove(0));
    assert!(temp.file_name().unwrap().to_string_lossy().ends_with(".tmp"));
    std::fs::remove_file(&temp).unwrap();
    let e = pending
        .commit(|w| w.write_all(b"new").map_err(OutputError::from))
        .unwrap_err();
    assert!(matches!(&e, OutputError::TempVanished(t) if t == &temp), "{e:?}");
    let message = e.to_string();
    assert!(
        message.contains(&temp.display().to_string()) && message.contains("vanished"),
        "{message}"
    );
    assert_eq!(std::fs::read(&target).unwrap(), b"last good");
    assert_eq!(file_names(dir.path()), ["x.ras"]);
}

//! Output files: how the programs put what they make (rasters, PNGs, the
//! debug log) on disk. The port's extension: the thesis's main program only
//! calls `outputframe` (unit raster, OCR lines 3217–3223) with a file name;
//! what happens at the file system is decided here, in one place for every
//! writer (`raytrace`, `psout --screenshot`, the tools).
//!
//! - The format of an image follows its extension: that is the raster's
//!   business ([`crate::raster::Format`]); here only bytes reach files.
//!   `-` ([`STDOUT`]) is standard output.
//! - [`PendingFile::create`] checks that a file can be written and reserves
//!   it before the work that fills it, so a long render never ends on an
//!   output it cannot write; [`PendingFile::commit`] writes it.
//!   [`write_atomically`] does both at once.
//! - A new file, or one that is a regular file, is written to a temporary
//!   file beside it, `.NAME.HOST.PID.N.tmp`, synced and renamed over it: an
//!   interrupted write never leaves half a file or clobbers the last good
//!   one. The host is in the name because a folder may be shared by the
//!   hosts of a farm (docs/farm.md), where a PID means nothing off its host. A symbolic link to a regular file keeps its link: the file it
//!   points to is replaced. A path that exists and is not a regular file (a
//!   device such as /dev/null, a FIFO: [`is_stream`]) is written into,
//!   never replaced.
//! - Standard output whose reader has stopped reading (`raytrace DECK -o -
//!   | head -c 10`) is no error: the rest is dropped and the program ends
//!   as it would have, quietly, as a Unix filter does.
//! - No folder is created here; a missing folder, or a file where a folder
//!   should be, is an error that names it.
//! - [`remove_temp_files`]: what a program stopped by SIGINT or SIGTERM
//!   calls before it exits (the programs' `cli::remove_temp_files_on_signals`
//!   does, then exits with 130 or 143, 128 + the signal, as a shell reports
//!   it; the library never ends the process). A SIGKILL cannot be caught: the next write of the
//!   same target removes the temporary files of processes that no longer
//!   run (on Linux, where /proc tells which do), and only those this host
//!   wrote: another host's PIDs are not in this host's /proc.
//! - A writer whose temporary file vanished before the rename (another
//!   writer of the same file took it for a dead one's: one in another PID
//!   namespace, a container sharing the host name, looks the PID up in
//!   its own /proc) says so and names the temporary file, not the target.

use std::collections::HashMap;
use std::ffi::{OsStr, OsString};
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError};

/// The file name that means standard output.
pub const STDOUT: &str = "-";

/// What can go wrong before or while writing an output file. The messages
/// do not name the file; callers prefix it (`PATH: message`).
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("the file name is empty")]
    Empty,
    #[error("the folder {} does not exist", .0.display())]
    MissingFolder(PathBuf),
    #[error("{} is a file, not a folder", .0.display())]
    NotAFolder(PathBuf),
    #[error("it is a folder, not a file")]
    IsAFolder,
    /// The file exists and this user may not write it: it is not replaced.
    #[error(
        "it exists and this user may not write it ({0}): it was not replaced; remove it or make it writable first"
    )]
    ReadOnly(String),
    /// The temporary file was removed by someone else before it could be
    /// renamed over the target; the target is as it was.
    #[error("its temporary file {} vanished before it could be renamed over it: another process removed it (a second writer of the same file, on another host of a shared folder or in another PID namespace, that took it for a dead writer's); the file was not written", .0.display())]
    TempVanished(PathBuf),
    #[error("{0}")]
    Io(#[from] io::Error),
}

/// Whether `path` names an existing file that is not a regular file or a
/// folder: a device (`/dev/null`; `/dev/stdout` when it is a terminal or a
/// pipe), a FIFO, a socket. Such a file is written into, never replaced.
pub fn is_stream(path: &Path) -> bool {
    fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir())
}

/// Writes through `write` to `path`: [`PendingFile::create`] then
/// [`PendingFile::commit`]. On any error `path` is as it was and no
/// temporary file is left.
pub fn write_atomically<E: From<OutputError>>(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    PendingFile::create(path)?.commit(write)
}

/// An output file checked and reserved, not yet written. Dropped without
/// [`commit`](PendingFile::commit), it leaves `path` as it was.
#[derive(Debug)]
pub struct PendingFile {
    path: PathBuf,
    sink: Sink,
}

#[derive(Debug)]
enum Sink {
    Stdout,
    /// An existing file that is not a regular one: opened and written at
    /// commit.
    Into,
    /// A temporary file to rename over `target` (the path, or the file its
    /// symbolic link points to), in folder `dir`.
    Replace {
        temp: PathBuf,
        file: File,
        target: PathBuf,
        dir: PathBuf,
    },
    Done,
}

impl PendingFile {
    /// Checks that `path` can be written, and for a new or regular file
    /// creates its temporary file (which proves the folder is writable).
    /// [`STDOUT`] is standard output.
    pub fn create(path: &Path) -> Result<PendingFile, OutputError> {
        let pending = |sink| PendingFile {
            path: path.to_path_buf(),
            sink,
        };
        if path.as_os_str().is_empty() {
            return Err(OutputError::Empty);
        }
        if path.as_os_str() == STDOUT {
            return Ok(pending(Sink::Stdout));
        }
        let (target, existing) = match fs::metadata(path) {
            Ok(m) if m.is_dir() => return Err(OutputError::IsAFolder),
            Ok(m) if !m.is_file() => return Ok(pending(Sink::Into)),
            Ok(m) if fs::symlink_metadata(path)?.file_type().is_symlink() => (fs::canonicalize(path)?, Some(m)),
            Ok(m) => (path.to_path_buf(), Some(m)),
            Err(e) if e.kind() == io::ErrorKind::NotFound => (path.to_path_buf(), None),
            Err(e) if e.kind() == io::ErrorKind::NotADirectory => {
                return Err(OutputError::NotAFolder(first_file_among_ancestors(path)))
            }
            Err(e) => return Err(e.into()),
        };
        let name = target.file_name().ok_or(OutputError::IsAFolder)?.to_owned();
        let dir = match target.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        match fs::metadata(&dir) {
            Ok(m) if m.is_dir() => {}
            Ok(_) => return Err(OutputError::NotAFolder(dir)),
            Err(e) if e.kind() == io::ErrorKind::NotFound => return Err(OutputError::MissingFolder(dir)),
            Err(e) if e.kind() == io::ErrorKind::NotADirectory => {
                return Err(OutputError::NotAFolder(first_file_among_ancestors(&dir)))
            }
            Err(e) => return Err(e.into()),
        }
        if let Some(m) = &existing {
            may_replace(&target, m)?;
        }
        remove_stale_temp_files(&dir, &name);
        let (temp, file) = create_temp_file(&dir, &name)?;
        if let Some(m) = &existing {
            // The new file keeps the old one's mode, as a file written in
            // place would (the rename alone would give it the umask's).
            if let Err(e) = file.set_permissions(m.permissions()) {
                discard(&temp);
                return Err(e.into());
            }
        }
        Ok(pending(Sink::Replace {
            temp,
            file,
            target,
            dir,
        }))
    }

    /// The path it was created for.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes the file through `write` (buffered). A regular file is synced
    /// and renamed over the target; on any error the temporary file is
    /// removed and the target is as it was.
    pub fn commit<E: From<OutputError>>(
        mut self,
        write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
    ) -> Result<(), E> {
        match std::mem::replace(&mut self.sink, Sink::Done) {
            Sink::Done => Ok(()),
            Sink::Stdout => write_buffered(&mut ReaderMayStop::new(io::stdout().lock()), write),
            Sink::Into => {
                let mut file = File::options()
                    .write(true)
                    .open(&self.path)
                    .map_err(OutputError::from)?;
                write_buffered(&mut file, write)
            }
            Sink::Replace {
                temp,
                mut file,
                target,
                dir,
            } => {
                let result = write_buffered(&mut file, write).and_then(|()| {
                    file.sync_all().map_err(OutputError::from)?;
                    let mut registry = temp_files();
                    // The target's folder is the temporary file's, so a
                    // rename that finds nothing found no temporary file.
                    fs::rename(&temp, &target).map_err(|e| match e.kind() {
                        io::ErrorKind::NotFound => OutputError::TempVanished(temp.clone()),
                        _ => OutputError::from(e),
                    })?;
                    registry.retain(|t| t != &temp);
                    Ok(())
                });
                match &result {
                    Err(_) => discard(&temp),
                    // Make the rename itself durable where the platform allows it.
                    Ok(()) => {
                        if let Ok(d) = File::open(&dir) {
                            let _ = d.sync_all();
                        }
                    }
                }
                result
            }
        }
    }
}

/// Refuses to replace an existing file this user may not write, as `cp`
/// does: the rename over it needs only the folder's write permission, so
/// without this a read-only file of another user in a shared folder would
/// be replaced. The test is the one `access(2)` with `W_OK` makes, by the
/// effective user (whose rights the writing has): the file opened for
/// writing, without truncating or changing it. (Root may write any file,
/// so for root this refuses only what the kernel refuses root: a file on
/// a read-only mount, an immutable one.)
fn may_replace(target: &Path, meta: &fs::Metadata) -> Result<(), OutputError> {
    match File::options().write(true).open(target) {
        Ok(_) => Ok(()),
        Err(e)
            if matches!(
                e.kind(),
                io::ErrorKind::PermissionDenied | io::ErrorKind::ReadOnlyFilesystem
            ) =>
        {
            Err(OutputError::ReadOnly(read_only_reason(meta)))
        }
        Err(e) => Err(e.into()),
    }
}

/// Why a file may not be written, for the error: its mode and owner.
fn read_only_reason(meta: &fs::Metadata) -> String {
    use std::os::unix::fs::MetadataExt;
    format!("mode {:04o}, owner uid {}", meta.mode() & 0o7777, meta.uid())
}

/// Runs `write` on a buffer over `file` and flushes it.
fn write_buffered<E: From<OutputError>>(
    file: &mut dyn Write,
    write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E> {
    let mut w = BufWriter::new(file);
    write(&mut w)?;
    w.flush().map_err(OutputError::from)?;
    Ok(())
}

/// A stream whose reader may stop reading early (`| head`): once a write
/// finds it closed (EPIPE), the rest is dropped instead of being an error,
/// since what the reader did not want is no failure of the writer.
struct ReaderMayStop<W> {
    inner: W,
    closed: bool,
}

impl<W: Write> ReaderMayStop<W> {
    fn new(inner: W) -> Self {
        ReaderMayStop { inner, closed: false }
    }

    /// `result`, or success once the reader is gone.
    fn unless_closed<T>(&mut self, result: io::Result<T>, done: T) -> io::Result<T> {
        match result {
            Err(e) if e.kind() == io::ErrorKind::BrokenPipe => {
                self.closed = true;
                Ok(done)
            }
            r => r,
        }
    }
}

impl<W: Write> Write for ReaderMayStop<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.closed {
            return Ok(buf.len());
        }
        let r = self.inner.write(buf);
        self.unless_closed(r, buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        if self.closed {
            return Ok(());
        }
        let r = self.inner.flush();
        self.unless_closed(r, ())
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        if let Sink::Replace { temp, .. } = &self.sink {
            discard(temp);
        }
    }
}

/// The nearest ancestor of `path` that exists and is not a folder (the
/// reason for an ENOTDIR); `path` itself if none is found.
fn first_file_among_ancestors(path: &Path) -> PathBuf {
    path.ancestors()
        .skip(1)
        .filter(|a| !a.as_os_str().is_empty())
        .collect::<Vec<_>>()
        .into_iter()
        .rev()
        .find(|a| fs::metadata(a).is_ok_and(|m| !m.is_dir()))
        .unwrap_or(path)
        .to_path_buf()
}

/// The temporary files of this process not yet renamed or removed. Its
/// lock is held while one is created, renamed or removed, and by the signal
/// handler while it removes them all and exits, so none escapes it.
static TEMP_FILES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn temp_files() -> MutexGuard<'static, Vec<PathBuf>> {
    TEMP_FILES.lock().unwrap_or_else(PoisonError::into_inner)
}

/// This host's name as temporary file names carry it: the kernel's host
/// name (/proc/sys/kernel/hostname, else `$HOSTNAME`, else `localhost`)
/// with each character other than a letter, a digit or `-` made `_`, so
/// that it holds no dot and the name splits back into its parts.
pub fn this_host() -> &'static str {
    static HOST: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    HOST.get_or_init(|| {
        let name = fs::read_to_string("/proc/sys/kernel/hostname")
            .ok()
            .or_else(|| std::env::var("HOSTNAME").ok())
            .map(|h| h.trim().to_string())
            .filter(|h| !h.is_empty())
            .unwrap_or_else(|| "localhost".into());
        host_word(&name)
    })
}

/// A host name as one word of a temporary file's name: each character
/// other than a letter, a digit or `-` made `_` (so no dot).
fn host_word(name: &str) -> String {
    name.chars()
        .map(|c| if c.is_ascii_alphanumeric() || c == '-' { c } else { '_' })
        .collect()
}

/// Creates `.NAME.HOST.PID.N.tmp` in `dir`, a name no other writer uses.
fn create_temp_file(dir: &Path, name: &OsStr) -> Result<(PathBuf, File), OutputError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    loop {
        let mut temp_name = OsString::from(".");
        temp_name.push(name);
        temp_name.push(format!(
            ".{}.{}.{}.tmp",
            this_host(),
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let temp = dir.join(temp_name);
        let mut registry = temp_files();
        match File::options().write(true).create_new(true).open(&temp) {
            Ok(file) => {
                registry.push(temp.clone());
                return Ok((temp, file));
            }
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e.into()),
        }
    }
}

/// Removes a temporary file of this process (best effort: the error that
/// matters is the one that made it go).
fn discard(temp: &Path) {
    let mut registry = temp_files();
    let _ = fs::remove_file(temp);
    registry.retain(|t| t != temp);
}

/// Removes `dir`'s temporary files for `name` left by processes of this
/// host that no longer run (killed by SIGKILL, or a power cut):
/// `.NAME.HOST.PID.N.tmp` with this host's HOST and a PID that /proc does
/// not list. Another host's are left, whatever their PID (this host's
/// /proc knows nothing of that host's processes), and so are the names of
/// older versions without a host. Without /proc nothing is removed, since
/// nothing tells a dead writer from a live one. A folder is listed once per
/// process, so writing many files into it stays linear.
fn remove_stale_temp_files(dir: &Path, name: &OsStr) {
    static LISTED: Mutex<Option<HashMap<PathBuf, Vec<StaleTempFile>>>> = Mutex::new(None);
    if !Path::new("/proc/self").exists() {
        return;
    }
    let mut listed = LISTED.lock().unwrap_or_else(PoisonError::into_inner);
    let stale = listed
        .get_or_insert_with(HashMap::new)
        .entry(dir.to_path_buf())
        .or_insert_with(|| stale_temp_files(dir));
    stale.retain(|(target, temp)| {
        if target != name {
            return true;
        }
        let _ = fs::remove_file(temp);
        false
    });
}

/// A temporary file of a dead process: the target name it was for, and its path.
type StaleTempFile = (OsString, PathBuf);

/// The temporary files in `dir` of dead processes of this host.
fn stale_temp_files(dir: &Path) -> Vec<StaleTempFile> {
    let Ok(entries) = fs::read_dir(dir) else {
        return Vec::new();
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    let mut stale = Vec::new();
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(middle) = file_name
            .to_str()
            .and_then(|f| f.strip_prefix('.'))
            .and_then(|f| f.strip_suffix(".tmp"))
        else {
            continue;
        };
        // NAME.HOST.PID.N: NAME may itself hold dots, HOST, PID and N do not.
        let mut parts = middle.rsplitn(4, '.');
        let (Some(n), Some(pid), Some(host), Some(target)) = (parts.next(), parts.next(), parts.next(), parts.next())
        else {
            continue;
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        if host != this_host() {
            continue;
        }
        let alive = pid == std::process::id() || Path::new("/proc").join(pid.to_string()).exists();
        if digits(n) && !target.is_empty() && !alive && entry.file_type().is_ok_and(|t| t.is_file()) {
            stale.push((target.into(), entry.path()));
        }
    }
    stale
}

/// The temporary files of this process removed, and no more made or
/// renamed while this is held: what a program does when a signal stops
/// it, before it exits (`cli::remove_temp_files_on_signals`, the
/// programs'). Hold it until the process ends.
pub struct TempFilesRemoved(#[expect(dead_code, reason = "held for its lock")] MutexGuard<'static, Vec<PathBuf>>);

/// Removes every temporary file this process is writing, and keeps any
/// other from being made or renamed while the result is held. The library
/// never ends the process: the program that stops on a signal calls this
/// first.
pub fn remove_temp_files() -> TempFilesRemoved {
    let registry = temp_files();
    for temp in registry.iter() {
        let _ = fs::remove_file(temp);
    }
    TempFilesRemoved(registry)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A reader that takes `room` bytes and then closes its end.
    struct Pipe {
        got: Vec<u8>,
        room: usize,
    }

    impl Write for Pipe {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            if self.got.len() >= self.room {
                return Err(io::ErrorKind::BrokenPipe.into());
            }
            let n = buf.len().min(self.room - self.got.len());
            self.got.extend_from_slice(&buf[..n]);
            Ok(n)
        }

        fn flush(&mut self) -> io::Result<()> {
            if self.got.len() >= self.room {
                return Err(io::ErrorKind::BrokenPipe.into());
            }
            Ok(())
        }
    }

    /// Standard output as the program sees it, over a reader that takes
    /// `room` bytes.
    fn stdout_read_for(room: usize) -> ReaderMayStop<Pipe> {
        ReaderMayStop::new(Pipe { got: Vec::new(), room })
    }

    #[test]
    fn a_reader_that_stops_is_no_error_and_gets_what_it_read() {
        let mut w = stdout_read_for(10);
        w.write_all(b"0123456789abcdef").unwrap();
        w.write_all(b"more").unwrap();
        w.flush().unwrap();
        assert!(w.closed);
        assert_eq!(w.inner.got, b"0123456789");
    }

    #[test]
    fn other_errors_stay_errors() {
        struct Full;
        impl Write for Full {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::Error::other("disk full"))
            }
            fn flush(&mut self) -> io::Result<()> {
                Err(io::Error::other("disk full"))
            }
        }
        let mut w = ReaderMayStop::new(Full);
        assert!(w.write(b"x").is_err());
        assert!(w.flush().is_err());
        assert!(!w.closed);
    }

    #[test]
    fn an_open_reader_gets_everything() {
        let mut w = stdout_read_for(100);
        w.write_all(b"abc").unwrap();
        w.flush().unwrap();
        assert!(!w.closed);
        assert_eq!(w.inner.got, b"abc");
    }

    #[test]
    fn a_host_name_becomes_one_word_without_dots() {
        assert_eq!(host_word("node-7.cluster.example"), "node-7_cluster_example");
        assert_eq!(host_word("Vm2"), "Vm2");
        assert_eq!(host_word("a b/c"), "a_b_c");
    }

    #[test]
    fn devices_and_fifos_are_streams_and_files_and_folders_not() {
        assert!(is_stream(Path::new("/dev/null")));
        let dir = std::env::temp_dir();
        assert!(!is_stream(&dir));
        assert!(!is_stream(&dir.join("no such file, surely")));
        let file = dir.join(format!("is_stream.{}.tmp", std::process::id()));
        fs::write(&file, b"x").unwrap();
        assert!(!is_stream(&file));
        fs::remove_file(&file).unwrap();
    }
}

//! Output files: how the programs put what they make (rasters, PNGs, the
//! debug log) on disk. The port's extension: the thesis's main program only
//! calls `outputframe` (unit raster, OCR lines 3217–3223) with a file name;
//! what happens at the file system is decided here, in one place for every
//! writer (`raytrace`, `psout --screenshot`, the tools).
//!
//! - The format follows the extension ([`Format::of`]): `.ras` Sun raster,
//!   `.png` PNG, `.ppm` or `.pnm` netpbm (binary P6). Anything else is an
//!   error that names the extensions. `-` ([`STDOUT`]) is standard output.
//! - [`PendingFile::create`] checks that a file can be written and reserves
//!   it before the work that fills it, so a long render never ends on an
//!   output it cannot write; [`PendingFile::commit`] writes it.
//!   [`write_atomically`] does both at once.
//! - A new file, or one that is a regular file, is written to a temporary
//!   file beside it, `.NAME.PID.N.tmp`, synced and renamed over it: an
//!   interrupted write never leaves half a file or clobbers the last good
//!   one. A symbolic link to a regular file keeps its link: the file it
//!   points to is replaced. A path that exists and is not a regular file (a
//!   device such as /dev/null, a FIFO) is written into, never replaced.
//! - No folder is created here; a missing folder, or a file where a folder
//!   should be, is an error that names it.
//! - [`remove_temp_files_on_signals`]: SIGINT or SIGTERM removes the
//!   temporary files and exits with 130 or 143 (128 + the signal, as a
//!   shell reports it). A SIGKILL cannot be caught: the next write of the
//!   same target removes the temporary files of processes that no longer
//!   run (on Linux, where /proc tells which do).

use std::collections::HashMap;
use std::ffi::{OsStr, OsString};
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard, Once, PoisonError};

use crate::raster::{write_sun_raster, Raster, RasterError};

/// The file name that means standard output.
pub const STDOUT: &str = "-";

/// The extensions an image output may have, as the errors list them.
pub const EXTENSIONS: &str = ".ras (Sun raster), .png (PNG), .ppm or .pnm (netpbm)";

/// What can go wrong before or while writing an output file. The messages
/// do not name the file; callers prefix it (`PATH: message`).
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("the file name is empty")]
    Empty,
    #[error("{}: the format follows the extension, one of {EXTENSIONS}",
        .0.as_ref().map_or("no extension".to_string(), |e| format!("unknown extension '.{e}'")))]
    UnknownFormat(Option<String>),
    #[error("this build has no PNG export (the `png` feature is off)")]
    NoPng,
    #[error("the folder {} does not exist", .0.display())]
    MissingFolder(PathBuf),
    #[error("{} is a file, not a folder", .0.display())]
    NotAFolder(PathBuf),
    #[error("it is a folder, not a file")]
    IsAFolder,
    #[error("{0}")]
    Io(#[from] io::Error),
}

/// The format of an image output file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// A Sun rasterfile, 24-bit RT_STANDARD ([`crate::raster`]).
    SunRaster,
    /// An 8-bit RGB PNG.
    Png,
    /// A binary netpbm pixmap (P6, maxval 255).
    Netpbm,
}

impl Format {
    /// The format `path`'s extension names (in any case); [`STDOUT`] has
    /// none, so its format is the caller's choice.
    pub fn of(path: &Path) -> Result<Format, OutputError> {
        if path.as_os_str().is_empty() {
            return Err(OutputError::Empty);
        }
        let extension = path.extension().map(|e| e.to_string_lossy().to_ascii_lowercase());
        match extension.as_deref() {
            Some("ras") => Ok(Format::SunRaster),
            Some("png") if cfg!(feature = "png") => Ok(Format::Png),
            Some("png") => Err(OutputError::NoPng),
            Some("ppm" | "pnm") => Ok(Format::Netpbm),
            _ => Err(OutputError::UnknownFormat(extension)),
        }
    }

    /// Writes `raster` to `w` in this format.
    pub fn write(self, raster: &Raster, w: &mut dyn Write) -> Result<(), RasterError> {
        match self {
            Format::SunRaster => write_sun_raster(raster, w),
            Format::Png => write_png_to(raster, w),
            Format::Netpbm => write_ppm_to(raster, w),
        }
    }
}

/// Writes `raster` as an 8-bit RGB PNG to `w`.
#[cfg(feature = "png")]
pub fn write_png_to(raster: &Raster, w: &mut dyn Write) -> Result<(), RasterError> {
    use image::ImageEncoder;
    raster.check()?;
    image::codecs::png::PngEncoder::new(w).write_image(
        raster.pixels.as_flattened(),
        raster.width as u32,
        raster.height as u32,
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(())
}

#[cfg(not(feature = "png"))]
pub fn write_png_to(_raster: &Raster, _w: &mut dyn Write) -> Result<(), RasterError> {
    Err(OutputError::NoPng.into())
}

/// Writes `raster` as a binary netpbm pixmap (P6, maxval 255) to `w`.
pub fn write_ppm_to(raster: &Raster, w: &mut dyn Write) -> Result<(), RasterError> {
    raster.check()?;
    write!(w, "P6\n{} {}\n255\n", raster.width, raster.height)?;
    for row in raster.pixels.chunks_exact(raster.width) {
        w.write_all(row.as_flattened())?;
    }
    Ok(())
}

/// Writes `raster` to `path` in `format` ([`write_atomically`]).
pub fn write_image(path: &Path, raster: &Raster, format: Format) -> Result<(), RasterError> {
    write_atomically(path, |w| format.write(raster, w))
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
        let target = match fs::metadata(path) {
            Ok(m) if m.is_dir() => return Err(OutputError::IsAFolder),
            Ok(m) if !m.is_file() => return Ok(pending(Sink::Into)),
            Ok(_) if fs::symlink_metadata(path)?.file_type().is_symlink() => fs::canonicalize(path)?,
            Ok(_) => path.to_path_buf(),
            Err(e) if e.kind() == io::ErrorKind::NotFound => path.to_path_buf(),
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
        remove_stale_temp_files(&dir, &name);
        let (temp, file) = create_temp_file(&dir, &name)?;
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
            Sink::Stdout => write_buffered(&mut io::stdout().lock(), write),
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
                    fs::rename(&temp, &target).map_err(OutputError::from)?;
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

/// Creates `.NAME.PID.N.tmp` in `dir`, a name no other writer uses.
fn create_temp_file(dir: &Path, name: &OsStr) -> Result<(PathBuf, File), OutputError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    loop {
        let mut temp_name = OsString::from(".");
        temp_name.push(name);
        temp_name.push(format!(
            ".{}.{}.tmp",
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

/// Removes `dir`'s temporary files for `name` left by processes that no
/// longer run (killed by SIGKILL, or a power cut): `.NAME.PID.N.tmp` with a
/// PID that /proc does not list. Without /proc nothing is removed, since
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

/// The temporary files in `dir` of dead processes.
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
        // NAME.PID.N: NAME may itself hold dots, PID and N do not.
        let mut parts = middle.rsplitn(3, '.');
        let (Some(n), Some(pid), Some(target)) = (parts.next(), parts.next(), parts.next()) else {
            continue;
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        let alive = pid == std::process::id() || Path::new("/proc").join(pid.to_string()).exists();
        if digits(n) && !target.is_empty() && !alive && entry.file_type().is_ok_and(|t| t.is_file()) {
            stale.push((target.into(), entry.path()));
        }
    }
    stale
}

/// Makes SIGINT and SIGTERM remove this process's temporary files and exit
/// with 128 + the signal (130, 143). For the programs' `main`; a second call
/// does nothing.
///
/// The signals are taken by `signal-hook`'s iterator on a thread of its
/// own, so the removal runs as ordinary code, not inside a signal handler.
pub fn remove_temp_files_on_signals() -> io::Result<()> {
    static INSTALLED: Once = Once::new();
    let mut result = Ok(());
    INSTALLED.call_once(|| {
        result = (|| {
            use signal_hook::consts::{SIGINT, SIGTERM};
            let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM])?;
            std::thread::Builder::new()
                .name("output-signals".into())
                .spawn(move || {
                    if let Some(signal) = signals.forever().next() {
                        // Held until exit: no temporary file is made or
                        // renamed after this.
                        let registry = temp_files();
                        for temp in registry.iter() {
                            let _ = fs::remove_file(temp);
                        }
                        std::process::exit(128 + signal);
                    }
                })?;
            Ok(())
        })();
    });
    result
}

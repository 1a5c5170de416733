//! Writing without losing anything: whole files replaced atomically, and run directories staged
//! beside their target and renamed into place when complete.

use crate::error::Error;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The file that marks a directory as a previous `woodpile simulate` run.
pub const RUN_MARKER: &str = "run.json";

/// Turns an I/O error on `path` into [`Error::Output`] naming the path.
pub fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |e| Error::Output {
        path: path.to_path_buf(),
        source: e,
    }
}

/// The error for a file that cannot be read as expected.
pub fn read_error(path: &Path, reason: impl Into<String>) -> Error {
    Error::Read {
        path: path.to_path_buf(),
        source: std::io::Error::other(reason.into()),
    }
}

/// Staging directories of this process still in use: an interrupt handler removes them
/// ([`remove_active_staging`]) before the process exits.
static ACTIVE_STAGING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Removes every staging directory this process has not committed yet (for a SIGINT/SIGTERM
/// handler: the output location is left as it was before the command started).
pub fn remove_active_staging() {
    let dirs = match ACTIVE_STAGING.lock() {
        Ok(mut g) => std::mem::take(&mut *g),
        Err(p) => std::mem::take(&mut *p.into_inner()),
    };
    for d in dirs {
        let _ = fs::remove_dir_all(d);
    }
}

fn register(dir: &Path, active: bool) {
    let mut g = match ACTIVE_STAGING.lock() {
        Ok(g) => g,
        Err(p) => p.into_inner(),
    };
    g.retain(|d| d != dir);
    if active {
        g.push(dir.to_path_buf());
    }
}

/// Whether process `pid` is alive. On Linux, /proc tells; elsewhere a staging directory counts
/// as abandoned only when it is more than a day old.
fn process_alive(pid: u32, dir: &Path) -> bool {
    if Path::new("/proc/self").exists() {
        return Path::new(&format!("/proc/{pid}")).exists();
    }
    let age = fs::metadata(dir)
        .and_then(|m| m.modified())
        .ok()
        .and_then(|t| t.elapsed().ok());
    age.is_none_or(|a| a.as_secs() < 86_400)
}

/// Removes staging directories `.NAME.partial-PID` beside `target` left by killed runs (their
/// process is gone). Nothing else is touched.
fn remove_abandoned_staging(parent: &Path, name: &str) {
    let prefix = format!(".{name}.partial-");
    let Ok(entries) = fs::read_dir(parent) else {
        return;
    };
    for e in entries.flatten() {
        let file_name = e.file_name().to_string_lossy().into_owned();
        let Some(pid) = file_name
            .strip_prefix(&prefix)
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        let path = e.path();
        if pid != std::process::id() && path.is_dir() && !process_alive(pid, &path) {
            let _ = fs::remove_dir_all(&path);
        }
    }
}

/// What an existing output directory holds, and whether this run may write into it.
fn check_target(target: &Path, overwrite: bool, marker: &'static str) -> Result<(), Error> {
    match fs::read_dir(target) {
        Ok(mut entries) => {
            if entries.next().is_none() {
                Ok(())
            } else if target.join(marker).is_file() {
                if overwrite {
                    Ok(())
                } else {
                    Err(Error::OutputExists {
                        path: target.to_path_buf(),
                    })
                }
            } else {
                Err(Error::OutputNotEmpty {
                    path: target.to_path_buf(),
                    marker,
                })
            }
        }
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) if target.exists() && !target.is_dir() => Err(Error::Output {
            path: target.to_path_buf(),
            source: std::io::Error::new(e.kind(), "exists and is not a directory"),
        }),
        Err(e) => Err(io_err(target)(e)),
    }
}

/// An earlier run's refusal as a study's: nothing to overwrite, the directory is left as it is.
fn study_exists(marker: &'static str) -> impl Fn(Error) -> Error {
    move |e| match e {
        Error::OutputExists { path } => Error::StudyExists { path, marker },
        other => other,
    }
}

/// A staging directory `.NAME.partial-PID` next to the output directory NAME; removed on drop
/// (and by [`remove_active_staging`] on an interrupt) unless committed.
///
/// The policy of every run directory: an absent or empty target is created; a target that holds
/// an earlier run is written only with `overwrite`, and then only the run's own files
/// (`own_files`) are replaced or removed — the user's other files and folders (`plots/`, notes)
/// stay; any other non-empty directory is refused. `run.json` is moved in last, so its presence
/// marks a complete run.
#[derive(Debug)]
pub struct Staging {
    dir: PathBuf,
    target: PathBuf,
    overwrite: bool,
    marker: &'static str,
    committed: bool,
}

impl Staging {
    /// Checks that `target` may be written, removes staging directories of killed earlier runs
    /// into the same place, and creates this run's staging directory (and missing parents).
    pub fn prepare(target: &Path, overwrite: bool) -> Result<Self, Error> {
        Self::prepare_marked(target, overwrite, RUN_MARKER)
    }

    /// [`Staging::prepare`] for an output whose complete directory is marked by `marker` (e.g.
    /// `transmission.json`) instead of `run.json`.
    pub fn prepare_marked(
        target: &Path,
        overwrite: bool,
        marker: &'static str,
    ) -> Result<Self, Error> {
        check_target(target, overwrite, marker)?;
        let name = target
            .file_name()
            .ok_or_else(|| Error::Output {
                path: target.to_path_buf(),
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidInput,
                    "not a directory name",
                ),
            })?
            .to_string_lossy()
            .into_owned();
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        fs::create_dir_all(&parent).map_err(io_err(&parent))?;
        remove_abandoned_staging(&parent, &name);
        let dir = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if dir.exists() {
            fs::remove_dir_all(&dir).map_err(io_err(&dir))?;
        }
        fs::create_dir(&dir).map_err(io_err(&dir))?;
        register(&dir, true);
        Ok(Staging {
            dir,
            target: target.to_path_buf(),
            overwrite,
            marker,
            committed: false,
        })
    }

    /// Where to write the files.
    pub fn path(&self) -> &Path {
        &self.dir
    }

    /// The final output directory.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// [`Staging::prepare_marked`] for a study's directory (samples, a sensitivity design),
    /// which is never overwritten nor resumed: a target holding `marker` is
    /// [`Error::StudyExists`], whoever wrote it.
    pub fn prepare_study(target: &Path, marker: &'static str) -> Result<Self, Error> {
        Self::prepare_marked(target, false, marker).map_err(study_exists(marker))
    }

    /// [`Staging::commit`] of a study's directory: a target that another run completed
    /// meanwhile (`marker` found) is [`Error::StudyExists`], and this run's files are dropped.
    pub fn commit_study(self, own_files: &[&str], marker: &str) -> Result<PathBuf, Error> {
        let found = self.marker;
        self.commit(own_files, marker).map_err(study_exists(found))
    }

    /// Moves the staged files into place. A new target is one rename; into an empty directory
    /// or over an earlier run, each of `own_files` is moved in (or, when this run did not write
    /// it, an earlier run's copy is removed), `marker` last; nothing else in the target is touched.
    pub fn commit(mut self, own_files: &[&str], marker: &str) -> Result<PathBuf, Error> {
        check_target(&self.target, self.overwrite, self.marker)?;
        if !self.target.exists() {
            fs::rename(&self.dir, &self.target).map_err(io_err(&self.target))?;
        } else {
            // Without the marker the directory no longer claims to hold a complete run.
            let old_marker = self.target.join(marker);
            if old_marker.is_file() {
                fs::remove_file(&old_marker).map_err(io_err(&old_marker))?;
            }
            for name in own_files.iter().filter(|n| **n != marker) {
                let (from, to) = (self.dir.join(name), self.target.join(name));
                if from.is_file() {
                    fs::rename(&from, &to).map_err(io_err(&to))?;
                } else if to.is_file() {
                    fs::remove_file(&to).map_err(io_err(&to))?;
                }
            }
            let to = self.target.join(marker);
            fs::rename(self.dir.join(marker), &to).map_err(io_err(&to))?;
            let _ = fs::remove_dir_all(&self.dir);
        }
        self.committed = true;
        register(&self.dir, false);
        Ok(self.target.clone())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.dir);
            register(&self.dir, false);
        }
    }
}

/// Writes `bytes` to `dir/name` atomically: a temporary file in the same directory, flushed to
/// disk, then renamed over the old one.
pub fn write_atomic(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), Error> {
    let path = dir.join(name);
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    let result = (|| {
        let mut f = fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        fs::rename(&tmp, &path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    result.map_err(io_err(&path))
}

/// Removes `NNN.EXT` files of `dir` (`pareto/NNN.toml`, `robust/NNN.csv`) beyond the new
/// front's `count` (written by an earlier stop of the same run); other files are left alone.
pub(crate) fn remove_stale(dir: &Path, count: usize, ext: &str) -> Result<(), Error> {
    for entry in fs::read_dir(dir).map_err(io_err(dir))? {
        let path = entry.map_err(io_err(dir))?.path();
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
        let ours = path.extension().is_some_and(|e| e == ext)
            && stem.len() >= 3
            && stem.bytes().all(|b| b.is_ascii_digit());
        if ours && stem.parse::<usize>().is_ok_and(|k| k > count) {
            fs::remove_file(&path).map_err(io_err(&path))?;
        }
    }
    Ok(())
}

//! Writing without losing anything: whole files replaced atomically, and run directories staged
//! beside their target and renamed into place when complete.

use crate::error::Error;
use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The file that marks a directory as a previous `woodpile simulate` run.
pub const RUN_MARKER: &str = "run.json";

/// Turns an I/O error on `path` into [`Error::Output`] naming the path.
pub fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |e| Error::Output {
        path: path.to_path_buf(),
        source: e,
    }
}

/// What an existing output directory holds.
fn check_target(target: &Path) -> Result<(), Error> {
    match fs::read_dir(target) {
        Ok(mut entries) => {
            if entries.next().is_none() || target.join(RUN_MARKER).is_file() {
                Ok(())
            } else {
                Err(Error::OutputNotEmpty {
                    path: target.to_path_buf(),
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

/// A staging directory next to the output directory; removed on drop unless committed.
#[derive(Debug)]
pub struct Staging {
    dir: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl Staging {
    /// Checks that `target` may be written (absent, empty, or a previous run) and creates the
    /// staging directory beside it (and any missing parents).
    pub fn prepare(target: &Path) -> Result<Self, Error> {
        check_target(target)?;
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
        let dir = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if dir.exists() {
            fs::remove_dir_all(&dir).map_err(io_err(&dir))?;
        }
        fs::create_dir(&dir).map_err(io_err(&dir))?;
        Ok(Staging {
            dir,
            target: target.to_path_buf(),
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

    /// Moves the staged files into place, replacing a previous run.
    pub fn commit(mut self) -> Result<PathBuf, Error> {
        check_target(&self.target)?;
        let mut old = None;
        if self.target.exists() {
            if self.target.join(RUN_MARKER).is_file() {
                let aside = self.dir.with_file_name(format!(
                    ".{}.old-{}",
                    self.target
                        .file_name()
                        .unwrap_or_default()
                        .to_string_lossy(),
                    std::process::id()
                ));
                fs::rename(&self.target, &aside).map_err(io_err(&self.target))?;
                old = Some(aside);
            } else {
                fs::remove_dir(&self.target).map_err(io_err(&self.target))?;
            }
        }
        if let Err(e) = fs::rename(&self.dir, &self.target) {
            if let Some(aside) = &old {
                let _ = fs::rename(aside, &self.target);
            }
            return Err(io_err(&self.target)(e));
        }
        self.committed = true;
        if let Some(aside) = old {
            let _ = fs::remove_dir_all(aside);
        }
        Ok(self.target.clone())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.dir);
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

//! A lock file beside a results file (`STEM.lock`, created exclusively by rank 0, holding the
//! host and process id), so that two runs writing the same results (or the same sidecar and
//! status files) never mix their data. A lock is written whole (a temporary file linked into
//! place), so an empty one is what a failed write left; a lock that names no live process of
//! this host (its process gone, or no process at all) is stale and replaced, with a note. A
//! lock this process holds already (a check's, taken for all its files before its first
//! analysis) is held again by its analyses without being taken or removed.

use crate::error::{Error, Result};
use mpi::collective::SystemOperation;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Held while a run writes its results; removed on drop (rank 0) unless it was held already.
pub struct ResultsLock {
    path: Option<PathBuf>,
}

/// What taking a lock found.
enum Taken {
    /// Created by this call; the note says when a stale lock was replaced.
    New(Option<String>),
    /// Held by this process already.
    Held,
}

fn host() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname").map(|h| h.trim().to_string()).unwrap_or_else(|_| "unknown".into())
}

/// The lock's path for results file `results`: beside the file a link names (the file itself
/// is what two runs must not share), named by its stem, as the sidecar and status files are
/// (`out.h5` and `out.hdf5` would write one `out.xmf` and `out.sta`): `DIR/out.lock`.
pub fn lock_path(results: &Path) -> PathBuf {
    resolve(results, 0).with_extension("lock")
}

/// The file `path` leads to through links, whether or not it exists yet.
fn resolve(path: &Path, depth: usize) -> PathBuf {
    let parent = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let dir = std::fs::canonicalize(parent).unwrap_or_else(|_| parent.to_path_buf());
    let here = dir.join(path.file_name().unwrap_or_default());
    match std::fs::read_link(&here) {
        // a link (dangling too: the run would create its target) leads on, relative to its own
        // directory; 40 links deep is where the kernel stops as well
        Ok(target) if depth < 40 => resolve(&dir.join(target), depth + 1),
        _ => here,
    }
}

impl ResultsLock {
    /// Takes the lock on rank 0 (collective: every rank gets the same outcome); returns the
    /// note to print when a stale lock was replaced.
    pub fn acquire(results: &Path, world: &SimpleCommunicator) -> Result<(Self, Option<String>)> {
        let root = world.rank() == 0;
        let outcome = if root { take(&lock_path(results), results) } else { Ok(Taken::Held) };
        let failed = i32::from(outcome.is_err());
        let mut any = 0i32;
        world.all_reduce_into(&failed, &mut any, SystemOperation::max());
        match outcome {
            Err(e) => Err(e),
            Ok(_) if any != 0 => Err(Error::input(format!("{}: locked by another run (see rank 0's message)", results.display()))),
            Ok(Taken::Held) => Ok((ResultsLock { path: None }, None)),
            Ok(Taken::New(note)) => Ok((ResultsLock { path: Some(lock_path(results)) }, note)),
        }
    }

    /// Takes the locks of every file in `results` (collective), or none: for a command whose
    /// analyses write several files, before the first of them starts.
    pub fn acquire_all(results: &[PathBuf], world: &SimpleCommunicator) -> Result<(Vec<Self>, Vec<String>)> {
        let (mut locks, mut notes) = (Vec::new(), Vec::new());
        for path in results {
            let (lock, note) = Self::acquire(path, world)?;
            locks.push(lock);
            notes.extend(note);
        }
        Ok((locks, notes))
    }
}

impl Drop for ResultsLock {
    fn drop(&mut self) {
        if let Some(path) = &self.path {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// Whether a run may be writing `results` still: its lock is there, and not left by a process
/// of this host that is gone (a lock of another host may be a live run).
pub fn writer_may_be_alive(results: &Path) -> bool {
    live_writer(results).is_some()
}

/// The lock's path and text ("host H pid P") of a run that may be writing `results` still.
pub fn live_writer(results: &Path) -> Option<(PathBuf, String)> {
    let lock = lock_path(results);
    let held = std::fs::read_to_string(&lock).ok().filter(|held| !holder_gone(held))?;
    Some((lock, held.trim().to_string()))
}

/// Whether the lock text `held` names no live process: a process of this host that is gone,
/// or none at all (an empty lock is a write that failed: locks are written whole). A process
/// of another host may be alive.
fn holder_gone(held: &str) -> bool {
    match held.split_whitespace().collect::<Vec<_>>().as_slice() {
        ["host", h, "pid", p] => *h == host() && p.parse::<u32>().is_ok_and(|p| !Path::new(&format!("/proc/{p}")).exists()),
        _ => true,
    }
}

/// This process's lock text.
fn me() -> String {
    format!("host {} pid {}\n", host(), std::process::id())
}

/// Creates `lock` whole and exclusively (a temporary file beside it, hard-linked into place:
/// a full disk fails before any lock exists), replacing a stale one; the note says when it did.
fn take(lock: &Path, results: &Path) -> Result<Taken> {
    let cannot = |e: std::io::Error| Error::input(format!("cannot write {}: cannot create its lock {}: {e}", results.display(), lock.display()));
    let draft = lock.with_extension(format!("lock.{}", std::process::id()));
    let written = std::fs::File::create(&draft).and_then(|mut f| f.write_all(me().as_bytes()).and_then(|_| f.sync_all()));
    if let Err(e) = written {
        let _ = std::fs::remove_file(&draft);
        return Err(cannot(e));
    }
    // a file system without hard links (some network and FAT ones) gets the lock created in
    // place, exclusively, and written
    let link = || match std::fs::hard_link(&draft, lock) {
        Err(e) if e.kind() != std::io::ErrorKind::AlreadyExists => {
            std::fs::OpenOptions::new().write(true).create_new(true).open(lock).and_then(|mut f| f.write_all(me().as_bytes()))
        }
        linked => linked,
    };
    let outcome = match link() {
        Ok(()) => Ok(Taken::New(None)),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
            let held = std::fs::read_to_string(lock).unwrap_or_default();
            if held == me() {
                Ok(Taken::Held)
            } else if !holder_gone(&held) {
                Err(Error::input(format!(
                    "cannot write {}: another run is writing it ({}, lock {}); remove the lock if that run is gone",
                    results.display(),
                    held.trim(),
                    lock.display()
                )))
            } else {
                let what = if held.trim().is_empty() { "empty: a write that failed".to_string() } else { held.trim().to_string() };
                std::fs::remove_file(lock)
                    .and_then(|_| link())
                    .map(|_| Taken::New(Some(format!("replaced the stale lock {} of a run that is gone ({what})", lock.display()))))
                    .map_err(cannot)
            }
        }
        Err(e) => Err(cannot(e)),
    };
    let _ = std::fs::remove_file(&draft);
    outcome
}

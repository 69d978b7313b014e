//! Opening a results file as a run may have left it: another process's lock waited for, what
//! is not HDF5 (or a file killed while being created) named, a file a killed writer left
//! marked open, or with its end of allocation short of its metadata, repaired as `h5clear` does.

use crate::error::{Error, Result};
use std::path::Path;

/// `path` opened for reading, checked and, where a killed writer left it so, repaired.
pub(super) fn open_results(path: &Path) -> Result<hdf5::File> {
    if !path.exists() {
        return Err(Error::input(format!("{}: no such file", path.display())));
    }
    check_is_hdf5(path)?;
    open_waiting_for_lock(path)
}

/// HDF5 refuses a file another process holds locked (a writer, or one closing it just now),
/// and a process whose open failed so keeps failing; so the lock is waited for first (HDF5
/// takes it with flock, as `File::try_lock_shared` tests it), up to `LOCK_WAIT`.
const LOCK_WAIT: std::time::Duration = std::time::Duration::from_secs(3);

fn open_waiting_for_lock(path: &Path) -> Result<hdf5::File> {
    let start = std::time::Instant::now();
    if let Ok(probe) = std::fs::File::open(path) {
        while let Err(std::fs::TryLockError::WouldBlock) = probe.try_lock_shared() {
            if start.elapsed() >= LOCK_WAIT {
                return Err(Error::input(format!(
                    "{}: locked by another process for {} s (a run still writing it, or a program holding it open); read it when that has finished",
                    path.display(),
                    LOCK_WAIT.as_secs()
                )));
            }
            std::thread::sleep(std::time::Duration::from_millis(100));
        }
        // the probe's shared lock goes with it; HDF5 takes its own
    }
    let failed = |e: hdf5::Error| {
        let first = e.to_string().lines().next().unwrap_or_default().to_string();
        Error::input(format!("{}: an HDF5 file that does not open (truncated, or left open by a run that was killed?): {first}", path.display()))
    };
    if !crate::launch::launched_as_rank_zero() {
        return open_after_the_first_rank(path).map_err(failed);
    }
    match hdf5::File::open(path) {
        Ok(file) => repair_short_allocation(path, file).map_err(failed),
        Err(e) => match repair(path, &e.to_string()) {
            Some(note) => {
                eprintln!("note: {note}");
                hdf5::File::open(path).map_err(failed)
            }
            None => Err(failed(e)),
        },
    }
}

/// Only the launch's rank 0 repairs a file, so that no rank opens it while another rewrites its
/// superblock (HDF5 then read "sblock->base_addr = 0" on the other rank); the launcher's
/// environment says which rank this is, since a file is opened before MPI starts too (a
/// restart's deck). Another rank waits this long for the repair, then takes the file as it is
/// (rank 0's own error then says what is wrong).
const REPAIR_WAIT: std::time::Duration = std::time::Duration::from_secs(10);

/// The file opened by a rank other than the first: as it opens, once no repair is needed (a
/// file the first rank would repair is waited for while it does), or its error after
/// `REPAIR_WAIT`.
fn open_after_the_first_rank(path: &Path) -> hdf5::Result<hdf5::File> {
    let start = std::time::Instant::now();
    loop {
        let file = hdf5::File::open(path);
        let repaired = file.as_ref().is_ok_and(|f| !needs_allocation_repair(path, f));
        if repaired || start.elapsed() >= REPAIR_WAIT {
            return file;
        }
        drop(file);
        std::thread::sleep(std::time::Duration::from_millis(100));
    }
}

/// A file a killed writer left behind, repaired as HDF5's `h5clear` does (hdf5-tools, which
/// slideline's set-up installs): a superblock whose end-of-file mark lies past the data that
/// reached the disk ("truncated file") gets the file's own size, a superblock still marked open
/// for writing gets its marks cleared. The increments the writer completed are all before that
/// point (each is flushed before it is marked complete). The note to print, or None.
fn repair(path: &Path, error: &str) -> Option<String> {
    let (args, what): (&[&str], &str) = if error.contains("truncated file") {
        (&["--increment=0"], "its end-of-file mark set to the data on disk")
    } else if error.contains("status_flags") || error.contains("already open for write") {
        (&["-s"], "its open-for-writing marks cleared")
    } else {
        return None;
    };
    repair_with_h5clear(path, args, what)
}

/// Runs `h5clear ARGS path`; the note to print, or None where it failed.
fn repair_with_h5clear(path: &Path, args: &[&str], what: &str) -> Option<String> {
    let done = std::process::Command::new("h5clear").args(args).arg(path).output().ok()?;
    done.status.success().then(|| format!("{}: left by a writer that was killed; repaired with h5clear ({what})", path.display()))
}

/// A file whose writer was killed while it flushed an increment may hold metadata past the end
/// of allocation its superblock records (the superblock not rewritten yet: reading the
/// increments then fails with "addr overflow"); with no run writing it, the mark is set to the
/// file's size, as `h5clear --increment=0` does. A file closed cleanly ends at its mark.
fn repair_short_allocation(path: &Path, file: hdf5::File) -> hdf5::Result<hdf5::File> {
    if !needs_allocation_repair(path, &file) {
        return Ok(file);
    }
    drop(file);
    match repair_with_h5clear(path, &["--increment=0"], "its end-of-allocation mark set to the data on disk") {
        Some(note) => eprintln!("note: {note}"),
        None => eprintln!("note: {}: left by a writer that was killed, and h5clear could not repair it: increments may not read", path.display()),
    }
    hdf5::File::open(path)
}

/// Whether `file` (open at `path`) ends its allocation short of the file's size with no live
/// run writing it: what [`repair_short_allocation`] mends.
fn needs_allocation_repair(path: &Path, file: &hdf5::File) -> bool {
    let size = std::fs::metadata(path).map(|m| m.len()).unwrap_or(0);
    super::h5ffi::end_of_allocation(file).is_ok_and(|eoa| eoa < size) && !super::lock::writer_may_be_alive(path)
}

/// HDF5's signature, at the start of every file slideline writes.
const HDF5_SIGNATURE: [u8; 8] = *b"\x89HDF\r\n\x1a\n";

/// Refuses, naming it, what is not a regular file starting with HDF5's signature: a directory,
/// a FIFO (whose read would block), a CSV or a deck given by mistake.
fn check_is_hdf5(path: &Path) -> Result<()> {
    let meta = std::fs::metadata(path).map_err(|e| Error::input(format!("{}: {e}", path.display())))?;
    if !meta.is_file() {
        let kind = if meta.is_dir() { "a directory" } else { "not a regular file" };
        return Err(Error::input(format!("{}: {kind}, not a slideline results file", path.display())));
    }
    let mut head = [0u8; 8];
    let read = std::fs::File::open(path).and_then(|mut f| std::io::Read::read_exact(&mut f, &mut head));
    // HDF5 writes the superblock at the file's first flush, after the mesh: a run killed
    // before it leaves a file of nothing but zeros at its start, or of no bytes
    if meta.len() == 0 || (read.is_ok() && head == [0u8; 8]) {
        return Err(Error::input(format!(
            "{}: incomplete: the run writing it stopped while creating it, before its first increment (nothing to read); run it again",
            path.display()
        )));
    }
    if read.is_err() || head != HDF5_SIGNATURE {
        return Err(Error::input(format!("{}: not a slideline results file (not HDF5)", path.display())));
    }
    Ok(())
}

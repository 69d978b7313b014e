//! The check every command makes of an output path before any work: below every module (PETSc's
//! options name output files too), so nothing reaches up into `io` for it.

use crate::error::{Error, Result};
use std::path::Path;

/// Checks before any work that a file can be written at `path` (and is not `input`, the file
/// the command reads, under any name; `what` names it, such as "the input deck"): bad input,
/// exit 2, "cannot write FILE: reason".
pub fn check_output_path(path: &Path, input: Option<(&Path, &str)>) -> Result<()> {
    let refuse = |reason: String| Err(Error::input(format!("cannot write {}: {reason}", path.display())));
    if path.is_dir() {
        return refuse("it is a directory; give a file name".into());
    }
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !parent.is_dir() {
        return refuse(format!("the directory {} does not exist", parent.display()));
    }
    // the same file by device and inode, so a hard link or a symlink to the input is caught
    if let (Some((input, what)), Ok(out)) = (input, std::fs::metadata(path)) {
        use std::os::unix::fs::MetadataExt;
        if std::fs::metadata(input).is_ok_and(|i| (i.dev(), i.ino()) == (out.dev(), out.ino())) {
            return refuse(format!("it is {what} ({}), which this command reads; give the output another name", input.display()));
        }
    }
    if let Ok(meta) = std::fs::metadata(path) {
        // a device (/dev/full, /dev/null), a FIFO or a socket is no place for a file
        if !meta.is_file() {
            return refuse("it is not a regular file; give a file name".into());
        }
        if let Err(e) = std::fs::OpenOptions::new().write(true).open(path) {
            return refuse(e.to_string());
        }
    }
    // a probe file shows the directory takes new files (permissions, read-only mounts)
    let probe = parent.join(format!(".slideline-probe-{}", std::process::id()));
    match std::fs::OpenOptions::new().write(true).create_new(true).open(&probe) {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(e) => refuse(e.to_string()),
    }
}

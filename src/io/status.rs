//! The status file beside the results (`RESULTS.sta`, as Abaqus' `.sta`): a header, one line
//! per converged increment, each cutback and the end, appended and flushed as the run goes, so
//! `tail -f RESULTS.sta` follows a run whatever its terminal shows. Written by rank 0.

use super::history::HistoryRow;
use crate::error::{Error, Result};
use std::io::Write;
use std::path::{Path, PathBuf};

pub struct StatusFile {
    file: std::fs::File,
    path: PathBuf,
    /// A write failed: warned once, then no more writes (only rank 0 writes this file, so its
    /// failure must not stop the run, which every rank carries on together).
    failed: bool,
}

/// The status file of results file `results`.
pub fn status_path(results: &Path) -> PathBuf {
    results.with_extension("sta")
}

impl StatusFile {
    pub fn create(results: &Path, title: &str) -> Result<Self> {
        let path = status_path(results);
        let file = std::fs::File::create(&path).map_err(|e| Error::Output { path: path.clone(), message: e.to_string() })?;
        let mut status = StatusFile { file, path, failed: false };
        status.line(&format!("slideline {}: {title}\n{}", env!("CARGO_PKG_VERSION"), HistoryRow::STATUS_HEADER));
        Ok(status)
    }

    /// One converged increment.
    pub fn record(&mut self, row: &HistoryRow) {
        self.line(&row.status_line())
    }

    /// A free-text line (a cutback, the end of the run).
    pub fn note(&mut self, text: &str) {
        self.line(&format!("  # {text}"))
    }

    fn line(&mut self, text: &str) {
        if self.failed {
            return;
        }
        if let Err(e) = writeln!(self.file, "{text}").and_then(|()| self.file.flush()) {
            eprintln!("warning: cannot write the status file {}: {e}; the run goes on", self.path.display());
            self.failed = true;
        }
    }
}

//! Studies: independent runs of one model's variants, handed out to groups of ranks as each
//! comes free ([`pool`]), each run to its own results file, and a study file (HDF5, with a CSV
//! beside it) that world rank 0 keeps current as the runs report. `penalty-study` varies the
//! contact penalty of a deck or the bellows ([`penalty`]); `bellows-sweep` varies a design
//! specification's keys ([`sweep`]).

pub mod penalty;
mod pool;
mod subject;
pub mod sweep;

pub use penalty::{parse_penalties, penalty_study, StudyPlan, StudyRow, MAX_RUNS};
pub use subject::{Measures, Subject};

use crate::error::{Error, Result};
use crate::petsc::PetscSession;
use mpi::traits::{Communicator, CommunicatorCollectives};
use std::path::{Path, PathBuf};

/// The most runs a study makes: beyond it a mistyped range would start hours of runs.
pub const MOST_RUNS: usize = 1000;

/// Field output of a study's run, set on its `every` (a deck's `[output] every`, the bellows'
/// `output_every`): its history and the last increment of each step, or as asked with `full`
/// (a 100-variant study would otherwise write tens of gigabytes).
pub fn study_output(every: &mut usize, full: bool) {
    if !full {
        *every = u32::MAX as usize;
    }
}

/// The study's file checked and locked, and the directory its runs write to (`STEM_runs`),
/// made (collective over every rank).
pub fn prepare(session: &PetscSession, output: &Path, inputs: &[(&Path, &str)]) -> Result<(crate::io::lock::ResultsLock, PathBuf)> {
    let everyone = session.everyone();
    let root = everyone.rank() == 0;
    crate::output_path::check_output_path(output, None)?;
    for (input, what) in inputs {
        crate::output_path::check_output_path(output, Some((input, what)))?;
    }
    // the study's file, and with it its runs directory, is one study's at a time
    let (lock, note) = crate::io::lock::ResultsLock::acquire(output, &everyone)?;
    if let (true, Some(note)) = (root, note) {
        println!("note: {note}");
    }
    let dir = PathBuf::from(format!("{}_runs", output.with_extension("").display()));
    let made = if root { std::fs::create_dir_all(&dir).map_err(|e| Error::input(format!("cannot write {}: {e}", dir.display()))) } else { Ok(()) };
    // rank 0 made the directory: every rank learns whether it could
    let mut failed = 0u8;
    everyone.all_reduce_into(&u8::from(made.is_err()), &mut failed, mpi::collective::SystemOperation::max());
    made?;
    if failed != 0 {
        return Err(Error::input(format!("cannot write {}: rank 0 could not make it", dir.display())));
    }
    Ok((lock, dir))
}

/// How a study's run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    Converged,
    NotConverged,
    /// Refused or failed for another reason (an impossible geometry, a write error, ...).
    Failed,
    /// Stopped by SIGINT or SIGTERM.
    Interrupted,
}

impl Outcome {
    /// The outcome of a run's result, with the reason where it did not converge.
    pub fn of<T>(result: &Result<T>) -> (Self, String) {
        match result {
            Ok(_) => (Outcome::Converged, String::new()),
            Err(e @ Error::NotConverged { .. }) => (Outcome::NotConverged, e.to_string()),
            Err(e @ Error::Interrupted { .. }) => (Outcome::Interrupted, e.to_string()),
            Err(e) => (Outcome::Failed, e.to_string()),
        }
    }

    pub fn label(self) -> &'static str {
        match self {
            Outcome::Converged => "converged",
            Outcome::NotConverged => "not converged",
            Outcome::Failed => "failed",
            Outcome::Interrupted => "interrupted",
        }
    }
}

/// Writes a file whole or not at all: into `PATH.part`, then renamed over `path`, so a study
/// killed at any moment leaves its last complete study file.
pub fn write_whole(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    let part = PathBuf::from(format!("{}.part", path.display()));
    write(&part)?;
    std::fs::rename(&part, path).map_err(|e| Error::Output { path: path.to_path_buf(), message: e.to_string() })
}

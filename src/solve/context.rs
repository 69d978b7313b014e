//! What every procedure's driver works with: the run's context, handed down by its one
//! dispatch (`run`), and the rule for a results file that cannot be written.

use crate::decomposition::Partition;
use crate::error::{Error, Result};
use crate::io::progress::Progress;
use crate::io::restart::RestartFrom;
use crate::io::status::StatusFile;
use crate::io::ResultsFile;
use crate::model::Model;
use crate::petsc::PetscSession;
use mpi::traits::*;
use std::path::PathBuf;
use std::time::Instant;

/// What a run is asked for beside its model.
#[derive(Clone, Debug)]
pub struct RunOptions {
    pub output: PathBuf,
    /// Print a line per increment (rank 0).
    pub progress: bool,
    /// The long line per increment, with every reaction and the contact.
    pub verbose: bool,
    /// A line per Newton iteration: the convergence test's measures against their bounds.
    pub monitor: bool,
    /// Continue the run that wrote this file from one of its increments.
    pub restart: Option<RestartFrom>,
}

/// What every procedure's driver works with, handed down by the run's one dispatch: the
/// session, the model (with the heat steps' field, once they have run), its partition, the
/// run's options, the progress lines, the status and results files, the run's clock.
pub(in crate::solve) struct RunContext<'a, 's> {
    pub session: &'s PetscSession,
    pub model: &'a Model,
    pub partition: &'a Partition,
    pub options: &'a RunOptions,
    pub progress: &'a Progress,
    pub status: Option<StatusFile>,
    pub results: ResultsFile,
    pub start: Instant,
}

/// A write that failed on one rank (a full disk, a vanished directory) leaves the others
/// waiting inside HDF5's collective calls: the rank that met it prints the error and stops every
/// rank (MPI_Abort). The increments completed before are on disk, each flushed and marked. On
/// one rank too: HDF5 closes the file it could not write at MPI_Finalize, and with 32-bit
/// fields that close crashed (a segfault in H5F__close_cb, every time on a full 2 MB disk).
pub(in crate::solve) fn stop_all_on_write_error<T>(world: &impl Communicator, output: &std::path::Path, result: Result<T>) -> Result<T> {
    match result {
        Err(e @ Error::Output { .. }) => {
            eprintln!("error: {e}; every rank stops (the increments completed before are in the file)");
            // the abort runs no destructor: the lock goes first, whichever rank holds it (a
            // file that stays locked would refuse the next run into it)
            let _ = std::fs::remove_file(crate::io::lock::lock_path(output));
            world.abort(1)
        }
        other => other,
    }
}

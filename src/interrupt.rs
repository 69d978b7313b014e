//! A run asked to stop by SIGINT or SIGTERM (Ctrl-C, `kill`, mpirun or a batch system passing
//! the signal on): the handlers [`crate::petsc::PetscSession`] installs only set a flag, and
//! the general step's driver stops after the increment under way, its file complete, every
//! rank of the run agreeing (collective). A second signal ends the process at once.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, LazyLock};

/// The signal that asked for a stop (0: none); shared with the SIGINT handler.
static REQUESTED: LazyLock<Arc<AtomicUsize>> = LazyLock::new(|| Arc::new(AtomicUsize::new(0)));

/// The flag the handlers set (forced before any handler is installed, so that a handler only
/// stores into it).
pub fn flag() -> Arc<AtomicUsize> {
    Arc::clone(&REQUESTED)
}

/// Records that `signal` asked the run to stop (async-signal-safe once [`flag`] has been
/// called: one atomic store).
pub fn request(signal: i32) {
    REQUESTED.store(signal as usize, Ordering::SeqCst);
}

/// The signal that asked this rank to stop, if any.
pub fn requested() -> Option<i32> {
    match REQUESTED.load(Ordering::SeqCst) {
        0 => None,
        s => Some(s as i32),
    }
}

/// A signal's name, for the message that says why a run stopped.
pub fn name(signal: i32) -> &'static str {
    match signal {
        2 => "SIGINT",
        15 => "SIGTERM",
        _ => "a signal",
    }
}

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
        BUDGET => "its time budget",
        _ => "a signal",
    }
}

/// The code a time budget stops a run with (SIGALRM's number: no signal handler sets it).
pub const BUDGET: i32 = 14;

/// A time budget: after `seconds` the run is asked to stop as by a signal ([`BUDGET`]), after
/// its increment under way; dropped before that, it asks nothing (and a stop it asked for but
/// the run did not reach is withdrawn).
pub struct Budget {
    cancel: Option<std::sync::mpsc::Sender<()>>,
    timer: Option<std::thread::JoinHandle<()>>,
}

impl Budget {
    pub fn start(seconds: f64) -> Budget {
        let (cancel, cancelled) = std::sync::mpsc::channel::<()>();
        let timer = std::thread::spawn(move || {
            if let Err(std::sync::mpsc::RecvTimeoutError::Timeout) = cancelled.recv_timeout(std::time::Duration::from_secs_f64(seconds)) {
                // a signal the user sent first stays the reason
                let _ = REQUESTED.compare_exchange(0, BUDGET as usize, Ordering::SeqCst, Ordering::SeqCst);
            }
        });
        Budget { cancel: Some(cancel), timer: Some(timer) }
    }
}

impl Drop for Budget {
    fn drop(&mut self) {
        drop(self.cancel.take());
        if let Some(t) = self.timer.take() {
            let _ = t.join();
        }
        let _ = REQUESTED.compare_exchange(BUDGET as usize, 0, Ordering::SeqCst, Ordering::SeqCst);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A budget asks for a stop once its time is out, and withdraws it when dropped; one
    /// dropped in time asks nothing. (One test: the flag is the process's.)
    #[test]
    fn a_time_budget_stops_a_run_only_once_it_is_spent() {
        let budget = Budget::start(0.05);
        std::thread::sleep(std::time::Duration::from_millis(300));
        assert_eq!(requested(), Some(BUDGET));
        assert_eq!(name(BUDGET), "its time budget");
        drop(budget);
        assert_eq!(requested(), None);
        drop(Budget::start(60.0));
        assert_eq!(requested(), None, "dropped in time");
    }
}

//! Independent runs handed out to a study's groups as each group comes free (runs differ in
//! cost several times over, so a fixed share would leave groups idle). World rank 0 keeps the
//! list in a thread of its own beside its group's work: each group's leader reports the run it
//! finished and asks for the next over MPI_COMM_WORLD; the answer is broadcast in the group,
//! so every rank of a group runs the same model on the group's PETSc world. Nothing else
//! travels over MPI_COMM_WORLD in a study.

use crate::interrupt;
use crate::petsc::PetscSession;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::time::Duration;

const ASK: i32 = 7101;
const ANSWER: i32 = 7102;

/// A finished run's report: its index in the study's list and what its group's leader said.
type Report = (usize, Vec<u8>);

/// Runs `count` tasks over the session's groups (collective over every rank): `work(k)` is
/// called by every rank of the group that takes task k and returns its report (the leader's is
/// kept); `reported` is called on world rank 0, from the coordinator's thread, with every
/// report so far each time one arrives (to keep the study's file current). After SIGINT or
/// SIGTERM no task is handed out; the runs under way end as their drivers stop them. Returns
/// the reports in the order they came on world rank 0, nothing elsewhere. `reported` may write
/// HDF5 files while rank 0's own run writes its results: the `hdf5` crate serialises every
/// call of the library behind one lock (and `io::h5ffi` takes it too).
fn run_tasks<W, R>(session: &PetscSession, count: usize, mut work: W, reported: R) -> Vec<Report>
where
    W: FnMut(usize) -> Vec<u8>,
    R: FnMut(&[Report]) + Send,
{
    let groups = session.groups().map_or(1, |g| g.count);
    let coordinator_rank = session.everyone().rank() == 0;
    std::thread::scope(|scope| {
        let coordinator = coordinator_rank.then(|| scope.spawn(move || coordinate(count, groups, reported)));
        let group = session.world();
        let leader = group.rank() == 0;
        let mut finished: Option<Report> = None;
        loop {
            let mut next: i64 = -1;
            if leader {
                ask(finished.take(), &mut next);
            }
            group.process_at_rank(0).broadcast_into(&mut next);
            let Ok(k) = usize::try_from(next) else { break };
            finished = Some((k, work(k)));
        }
        coordinator.map(|c| c.join().unwrap_or_default()).unwrap_or_default()
    })
}

/// [`run_tasks`] for runs that report a row: `work(k)` returns task k's row (the group
/// leader's is kept, sent as TOML); `reported(rows, newest)` gets every row so far in task
/// order, and which of them just arrived, each time one does (world rank 0); the rows in task
/// order are returned there, nothing elsewhere.
pub fn run_rows<Row, W, R>(session: &PetscSession, count: usize, mut work: W, mut reported: R) -> Vec<Row>
where
    Row: serde::Serialize + serde::de::DeserializeOwned,
    W: FnMut(usize) -> Row,
    R: FnMut(&[Row], usize) + Send,
{
    let leader = session.world().rank() == 0;
    // the rows in task order, with their tasks
    let decode = |reports: &[Report]| -> (Vec<usize>, Vec<Row>) {
        let mut decoded: Vec<(usize, Row)> = reports.iter().filter_map(|(k, b)| Some((*k, toml::from_str(std::str::from_utf8(b).ok()?).ok()?))).collect();
        decoded.sort_by_key(|(k, _)| *k);
        decoded.into_iter().unzip()
    };
    let reports = run_tasks(
        session,
        count,
        |k| {
            let row = work(k);
            if leader {
                toml::to_string(&row).unwrap_or_default().into_bytes()
            } else {
                Vec::new()
            }
        },
        |reports: &[Report]| {
            let (tasks, rows) = decode(reports);
            if let Some(newest) = reports.last().and_then(|(k, _)| tasks.iter().position(|t| t == k)) {
                reported(&rows, newest);
            }
        },
    );
    decode(&reports).1
}

/// A leader's report of the run it finished (if any) and its question for the next: the
/// answer is a task's index, or -1 when there is none.
fn ask(finished: Option<Report>, next: &mut i64) {
    let everyone = SimpleCommunicator::world();
    let (index, bytes) = finished.map_or((-1, Vec::new()), |(k, b)| (k as i64, b));
    let stop = interrupt::requested().unwrap_or(0) as i64;
    let mut message = Vec::with_capacity(16 + bytes.len());
    message.extend(index.to_le_bytes());
    message.extend(stop.to_le_bytes());
    message.extend(bytes);
    let coordinator = everyone.process_at_rank(0);
    coordinator.send_with_tag(&message[..], ASK);
    coordinator.receive_into_with_tag(next, ANSWER);
}

/// World rank 0's thread: answers each leader's question with the next task until the list
/// (or a stop signal, here or at any leader) ends it, and each group has been told.
fn coordinate<R: FnMut(&[Report])>(count: usize, groups: usize, mut reported: R) -> Vec<Report> {
    let everyone = SimpleCommunicator::world();
    let (mut next, mut released, mut stopped) = (0, 0, false);
    let mut reports = Vec::new();
    while released < groups {
        let Some(probed) = everyone.any_process().immediate_matched_probe_with_tag(ASK) else {
            // a sleeping poll: the thread must not take a core from the runs
            std::thread::sleep(Duration::from_millis(2));
            continue;
        };
        let (bytes, status) = probed.matched_receive_vec::<u8>();
        let word = |at: usize| i64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes"));
        stopped |= word(8) != 0 || interrupt::requested().is_some();
        if let Ok(k) = usize::try_from(word(0)) {
            reports.push((k, bytes[16..].to_vec()));
            reported(&reports);
        }
        let answer: i64 = if next < count && !stopped {
            next += 1;
            next as i64 - 1
        } else {
            released += 1;
            -1
        };
        everyone.process_at_rank(status.source_rank()).send_with_tag(&answer, ANSWER);
    }
    reports
}

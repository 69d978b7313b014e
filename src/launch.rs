//! Which rank of its launch this process is, read from the launcher's environment: known
//! before MPI starts (a command's bad input is reported by one process, a file is repaired by
//! one) and without a communicator.

/// Whether this process is the launch's rank 0 (or was not launched by mpirun).
pub fn launched_as_rank_zero() -> bool {
    ["OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"].iter().all(|v| std::env::var(v).map_or(true, |r| r == "0"))
}

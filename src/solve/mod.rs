//! The parallel solution: a run dispatches each step to its procedure's driver; the general
//! steps' driver solves the discrete problem with SNES, its contact assembled beside the
//! elements into a Jacobian of a fixed layout. Reading order:
//!
//! 1. `run`: a run's set-up and the one dispatch of its steps, each with the run's `context`.
//! 2. `procedures`: the drivers, one per procedure (general, heat, perturbation, modes).
//! 3. `problem`: the discrete problem F(u) = 0 over the free DOFs and its assembly: the loads
//!    in force (`schedule`), constraints, what an evaluation keeps, the round-off floor.
//! 4. `contact`: contact in the parallel problem: the surfaces, the slave nodes' engagements,
//!    what contact reports, its weight in the partition.
//! 5. `jacobian`: where each Jacobian entry goes and is stored, and the contact pattern.

pub mod contact;
mod context;
pub mod jacobian;
pub mod problem;
pub mod procedures;
pub mod run;

pub use context::RunOptions;
pub use run::{run, RunSummary};

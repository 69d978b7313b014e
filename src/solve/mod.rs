//! Parallel drivers: the discrete problem for SNES and the load-stepping loop.

pub mod affinity;
mod attempt;
pub mod conduction;
pub mod constraints;
pub mod contact;
mod contact_surfaces;
pub mod energy;
mod engagement;
mod general_step;
mod held;
mod kept;
pub mod layout;
mod linear_system;
pub mod modes;
pub mod pattern;
pub mod perturbation;
pub mod problem;
mod resume;
mod roundoff;
pub mod schedule;
pub mod stepping;
mod storage;

pub use stepping::{run, RunOptions, RunSummary};

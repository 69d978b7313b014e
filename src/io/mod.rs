//! Output: the HDF5 results file (written by all ranks, each its own slab) and its XDMF
//! sidecar for ParaView.

pub mod assessment;
pub mod describe;
mod h5;
mod h5ffi;
mod heat;
mod history;
pub mod lock;
pub mod nodal;
mod opening;
mod perturbation;
pub mod restart;
pub mod results;
pub mod state;
pub mod status;
pub mod table_file;
pub mod xdmf;

pub use history::{ContactSummary, HistoryRow};
pub use results::ResultsFile;
pub mod plots;
pub mod progress;
pub mod reader;

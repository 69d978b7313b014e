//! Output: the HDF5 results file (written by all ranks, each its own slab) and its XDMF
//! sidecar for ParaView.

pub mod results;
pub mod xdmf;

pub use results::{ContactSummary, HistoryRow, IncrementFields, ResultsFile};
pub mod plots;
pub mod reader;

//! Distribution of the mesh over MPI ranks and numbering of the unknowns.
//!
//! Every rank holds the whole (small) mesh. Elements are partitioned by PETSc's
//! MatPartitioning (ptscotch) on the element dual graph, with the elements that contact couples
//! linked and weighted by their work (`Affinity`); each node is owned by the lowest rank
//! among its elements. Nodes and elements are then put in *partition order* (by owning rank,
//! then original index), which is also the order of the output file, so each rank's owned
//! nodes and elements are one contiguous slab. Unknowns are the free (not prescribed) DOFs,
//! numbered contiguously per rank in partition order.

mod dofs;
mod partition;

pub use dofs::DofMap;
pub use partition::{Affinity, Partition};

//! The Jacobian's layout: where each of this rank's entries goes in PETSc's coordinate assembly
//! (`layout`), where PETSc then stores each value (`storage`), and the contact couplings the
//! pattern reserves as contacts close (`pattern`).

pub mod layout;
pub mod pattern;
mod storage;

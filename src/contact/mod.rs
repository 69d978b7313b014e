//! Frictionless node-to-segment ("slide line") contact: the kernel of eqs. (1)-(6) of the
//! seed paper (Wriggers), contact surfaces as polylines with consistent axisymmetric
//! tributary areas, and the closest-segment search. Pure: no PETSc, no MPI.

pub mod friction;
pub mod integrated;
pub mod node_to_edge;
pub mod search;
pub mod slideline;
pub mod surface;

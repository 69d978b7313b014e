//! Finite-element building blocks: shape functions, quadrature, axisymmetric kinematics.
//! Pure functions over small fixed-size types; no PETSc, MPI or I/O.

pub mod axisymmetric;
pub mod linearize;
pub mod quadrature;
pub mod recover;
pub mod shape;

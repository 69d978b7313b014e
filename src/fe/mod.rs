//! Finite-element building blocks: shape functions, quadrature, axisymmetric kinematics,
//! the sections (axisymmetric, plane strain, plane stress).
//! Pure functions over small fixed-size types; no PETSc, MPI or I/O.

pub mod axisymmetric;
pub mod edge_projection;
pub mod linearize;
pub mod quadrature;
pub mod recover;
pub mod section;
pub mod shape;

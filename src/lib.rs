//! slideline: a parallel nonlinear finite-element solver on PETSc for axisymmetric solids in
//! contact. Layers (see docs/code.md): readers -> `model`; pure kernels (`fe`, `material`,
//! `element`); parallel drivers (`decomposition`, `solve`, `io`) over the `petsc` binding.
#![deny(unsafe_code)]
#![deny(unsafe_op_in_unsafe_fn)]
// Kernels are written in index notation, as their formulas are.
#![allow(clippy::needless_range_loop)]

pub mod error;
pub mod petsc;

pub use error::{Error, Result};
pub mod ad;
pub mod assessment;
pub mod bellows;
pub mod contact;
pub mod dba;
pub mod decomposition;
pub mod element;
pub mod fe;
pub mod interrupt;
pub mod io;
pub mod launch;
pub mod material;
pub mod model;
pub mod output_path;
pub mod post;
pub mod preprocess;
pub mod records;
pub mod solve;
pub mod study;

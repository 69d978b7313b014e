//! Element kernels: local residual and tangent from the current state. Pure functions.

pub mod harmonic;
pub mod pressure;
pub mod solid;

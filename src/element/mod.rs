//! Element kernels: local residual and tangent from the current state. Pure functions.

pub mod body_load;
pub mod conduction;
pub mod harmonic;
pub mod harmonic_pressure;
pub mod pressure;
pub mod solid;

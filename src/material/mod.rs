//! Constitutive kernels: stress and consistent tangent at a quadrature point.

pub mod j2;
pub mod log_exp;

pub use j2::{Kinematics, PointState, Update, J2};

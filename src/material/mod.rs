//! Constitutive kernels: stress and consistent tangent at a quadrature point.

pub mod backstress;
pub mod hardening;
pub mod j2;
pub mod kinematic;
pub mod log_exp;
mod update;

pub use backstress::{Backstress, KinematicHardening};
pub use hardening::Hardening;
pub use j2::{Kinematics, PointState, SurfaceBranch, Update, J2};

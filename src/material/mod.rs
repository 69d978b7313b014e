//! Constitutive kernels: stress and consistent tangent at a quadrature point.

pub mod hardening;
pub mod j2;
pub mod kinematic;
pub mod log_exp;

pub use hardening::Hardening;
pub use j2::{Kinematics, PointState, SurfaceBranch, Update, J2};
pub use kinematic::{Backstress, KinematicHardening};

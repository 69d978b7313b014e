//! What a perturbation step gives: the harmonic response, or the eigenmodes of a frequency or
//! buckle step.

use crate::element::solid::QUADRATURE_POINTS;
use crate::model::perturbation::Analysis;
use std::f64::consts::PI;

/// A set's reactions: the sums of its nodal forces per radian, and the full ring's resultants
/// their mode has (n = 0: axial force and torque; n = 1: lateral force and the moment about the
/// diameter through the set's centre, conjugate to a ring's `rotation`).
#[derive(Clone, Debug, PartialEq)]
pub struct SetReaction {
    pub set: String,
    pub force: [f64; 3],
    /// (name, value, units) of each resultant.
    pub resultants: Vec<(&'static str, f64, &'static str)>,
}

/// What a perturbation step gives.
#[derive(Clone, Debug)]
pub struct PerturbationAnswer {
    /// [U_r, U_z, U_t] of every node (model order).
    pub amplitudes: Vec<[f64; 3]>,
    pub reactions: Vec<SetReaction>,
    /// The stress amplitudes [rr, zz, tt, rz, rt, zt] (MPa; the first four x cos n theta, the
    /// shears with theta x sin n theta, n = 0: constant) at the Gauss points of this rank's
    /// elements (partition order): the material's response D : strain, as Abaqus reports a
    /// perturbation's stress.
    pub stress: Vec<[[f64; 6]; QUADRATURE_POINTS]>,
    /// Frequency and buckle steps: the eigenmodes, nearest zero first (the fields above are
    /// empty).
    pub modes: Vec<EigenMode>,
    pub analysis: Analysis,
    pub notes: Vec<String>,
}

/// One eigenmode of a frequency or buckle step.
#[derive(Clone, Debug, PartialEq)]
pub struct EigenMode {
    /// omega^2 (rad^2/s^2) or the load factor lambda.
    pub eigenvalue: f64,
    /// [U_r, U_z, U_t] of every node (model order), scaled to a largest amplitude of 1.
    pub amplitudes: Vec<[f64; 3]>,
    /// Frequency steps: the mode's effective mass along its mode's rigid motion, full ring (t),
    /// where the mode has one (n = 0 axial, n = 1 lateral).
    pub effective_mass: Option<f64>,
    /// SLEPc's relative residual of the eigenpair.
    pub error: f64,
    /// Buckle steps: the critical pressure on each surface the step loads, the base state's
    /// pressure there plus the load factor times the step's (MPa).
    pub critical_pressures: Vec<(String, f64)>,
}

/// Frequency (Hz) of an eigenvalue omega^2 (negative: the base state is unstable in this mode).
pub fn frequency_hz(omega_squared: f64) -> f64 {
    omega_squared.signum() * omega_squared.abs().sqrt() / (2.0 * PI)
}

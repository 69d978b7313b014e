//! The procedures' drivers, one per kind of step: the general (static) steps' load stepping
//! (`general`, with its attempts, the state it carries and its energy audit), the steady heat
//! steps (`conduction`), and the perturbation steps about the general steps' end: a harmonic
//! response (`perturbation`) and the eigenproblems of frequency and buckling (`modes`), both
//! on one linear system over the nodes' amplitudes (`linear_system`).

pub mod conduction;
pub(super) mod general;
pub(super) mod linear_system;
pub mod modes;
pub mod perturbation;

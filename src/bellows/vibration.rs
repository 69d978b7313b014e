//! The bellows' natural frequencies by frequency steps (`solve::procedures::modes`) about a state of the
//! joint, both tubes' ends held: the axial modes (mode 0, twist held) and the lateral ones
//! (mode 1), the lowest of each beside the beam and spring analogies EJMA's frequency formulas
//! come from, evaluated with slideline's own axial rate Kb of the same state and the
//! convolutions' live mass (the metal alone: the fluid's mass is left out, on both sides):
//! - axial: a spring with its mass spread along it, fixed at both ends, (1/2) sqrt(Kb / m);
//! - lateral: a beam clamped at both ends with the equivalent bending stiffness Kb Lb Dm^2 / 8,
//!   and the same beam with the convolutions' rotary inertia (a Rayleigh beam), which EJMA's
//!   leaves out and which, in a bellows about as wide as it is long, decides the mode.
//!
//! The axial rate comes from the `axial` perturbation of `flexibility`.

use super::flexibility::AXIAL;
use super::stability::lowest_positive_mode;
use crate::bellows::spec::DesignSpec;
use crate::error::Result;
use crate::model::perturbation::{Analysis, HarmonicComponent, HarmonicDisplacement, Perturbation};
use crate::petsc::PetscSession;
use crate::records::perturbation::frequency_hz;
use crate::records::perturbation::PerturbationAnswer;

pub const AXIAL_MODES: &str = "axial_modes";
pub const LATERAL_MODES: &str = "lateral_modes";
/// Eigenvalues asked of each frequency step.
const EIGENVALUES: usize = 3;

/// The lowest mode of one frequency step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mode {
    /// Hz.
    pub frequency: f64,
    /// The mode's effective mass along its rigid motion, full ring (t).
    pub effective_mass: f64,
}

/// The lowest natural frequencies about one state, and the state's axial rate (N/mm, full ring).
#[derive(Clone, Debug, PartialEq)]
pub struct Frequencies {
    pub axial_rate: f64,
    /// The state's convolved length Lb + x (mm; x the axial movement, extension positive).
    pub convolved_length: f64,
    pub axial: Option<Mode>,
    pub lateral: Option<Mode>,
}

/// The frequency steps (and the axial rate's step) on joint `p`.
pub fn steps(p: &DesignSpec) -> Vec<Perturbation> {
    let hold = |set: &str, components: &[HarmonicComponent]| {
        components.iter().map(|&component| HarmonicDisplacement { node_set: set.into(), component, value: 0.0 }).collect::<Vec<_>>()
    };
    let all = [HarmonicComponent::R, HarmonicComponent::Z, HarmonicComponent::T];
    let ends: Vec<HarmonicDisplacement> = hold("fixed_end", &all).into_iter().chain(hold("moving_end", &all)).collect();
    let frequency = |name: &str, mode: u32, more: Vec<HarmonicDisplacement>| Perturbation {
        name: name.into(),
        mode,
        displacements: ends.iter().cloned().chain(more).collect(),
        rings: Vec::new(),
        pressures: Vec::new(),
        without_contact: Vec::new(),
        analysis: Analysis::Frequency { eigenvalues: EIGENVALUES },
    };
    let axial = super::flexibility::steps(p, super::flexibility::Movements { lateral: 0.0, angular: 0.0 }).into_iter().filter(|s| s.name == AXIAL);
    // twist held: mode 0's torsion is not an axial mode
    axial.chain([frequency(AXIAL_MODES, 0, hold("all", &[HarmonicComponent::T])), frequency(LATERAL_MODES, 1, Vec::new())]).collect()
}

/// The frequencies from the answers to [`steps`] of a run of joint `p` (its end state).
pub fn from_answers(p: &DesignSpec, answers: &[(String, PerturbationAnswer)]) -> Result<Frequencies> {
    let axial_rate = super::flexibility::axial_rate(answers)?;
    let lowest = |name: &str| {
        lowest_positive_mode(answers, name).map(|m| Mode { frequency: frequency_hz(m.eigenvalue), effective_mass: m.effective_mass.unwrap_or(f64::NAN) })
    };
    let stroke = if p.joint.cycle { 0.0 } else { p.displacement() };
    let convolved_length = p.bellows.convolutions as f64 * p.bellows.pitch - stroke;
    Ok(Frequencies { axial_rate, convolved_length, axial: lowest(AXIAL_MODES), lateral: lowest(LATERAL_MODES) })
}

/// The joint `p` at rest (no pressure, heat or stroke, elastic) and its frequency steps
/// (collective; the run's file is removed).
pub fn at_rest(session: &PetscSession, p: &DesignSpec) -> Result<Frequencies> {
    super::at_rest(session, p, "frequencies", steps, |rest, summary, _| from_answers(rest, &summary.perturbations))
}

/// The analogies' first frequencies (Hz) with axial rate Kb and the convolutions' live mass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimates {
    /// The spring with its mass spread along it, (1/2) sqrt(Kb / m).
    pub axial: f64,
    /// The clamped beam with (E I)eq = Kb Lb Dm^2 / 8 (EJMA's analogy).
    pub lateral: f64,
    /// The same beam with the convolutions' rotary inertia (a Rayleigh beam).
    pub lateral_rotary: f64,
    /// The live mass, t.
    pub mass: f64,
}

/// The analogies for joint `p` in state `f`: its axial rate and convolved length.
pub fn estimates(p: &DesignSpec, f: &Frequencies) -> Estimates {
    use crate::assessment::formulas::{axial_frequency, lateral_frequency, rayleigh_lateral_frequency};
    let g = p.geometry();
    let (mass, dm, lb, axial_rate) = (g.live_mass(p.density()), g.mean_diameter(), f.convolved_length, f.axial_rate);
    Estimates {
        axial: axial_frequency(axial_rate, mass),
        lateral: lateral_frequency(axial_rate, mass, dm, lb),
        lateral_rotary: rayleigh_lateral_frequency(axial_rate, mass, dm, lb),
        mass,
    }
}

//! The bellows' instability pressures by buckle steps (`solve::procedures::modes`) about a state of the
//! joint, both tubes' ends held: mode 1, the column instability ("squirm", the joint bowing
//! sideways under its pressure thrust), and mode 0, the in-plane instability of the
//! convolutions; each beside the codes' estimates:
//! - the column formula of EJMA and ASME VIII-1 App. 26 with both ends held, Psc = 0.34 pi Kb /
//!   (N q) (it reproduces two printed reports, `../shared/bellows-code/worked-examples.md`), with
//!   slideline's own axial rate Kb of the same state;
//! - the equivalent column it comes from, unfactored: (EI)eq = Kb Lb Dm^2 / 8 fixed at both ends,
//!   4 pi^2 (EI)eq / Lb^2 = p pi Dm^2 / 4 gives p = 2 pi Kb / (N q), so the code's 0.34 is 0.17
//!   of it;
//! - the code's in-plane instability pressure (the code check's).
//!
//! And the harmonics above them, n = 2 to [`HIGHEST_HARMONIC`]: the crest and sidewall modes,
//! which on a thin bellows with both ends held can buckle below the column; the lowest pressure
//! of all the harmonics governs, and the section names its harmonic (and says so when the
//! pressures still fall at the highest one asked).
//!
//! The step's load is 1 MPa on the wetted surface: the critical pressure is the state's
//! pressure plus the load factor. The axial rate comes from the `axial` perturbation of
//! `flexibility`.

use super::flexibility::AXIAL;
use crate::bellows::spec::DesignSpec;
use crate::error::Result;
use crate::model::perturbation::{Analysis, HarmonicComponent, HarmonicDisplacement, Perturbation};
use crate::model::Pressure;
use crate::petsc::PetscSession;
use crate::records::perturbation::PerturbationAnswer;

pub const SQUIRM: &str = "squirm";
pub const IN_PLANE: &str = "in_plane";
/// Eigenvalues asked of each buckle step: the lowest positive one is the answer.
const EIGENVALUES: usize = 3;
/// The highest harmonic of the buckle steps above the column's (n = 2, 3, ...).
pub const HIGHEST_HARMONIC: u32 = 4;

/// The buckle step of harmonic `n` >= 2.
fn higher_step(n: u32) -> String {
    format!("buckle_n{n}")
}

/// The critical pressures about one state (MPa) and the state's axial rate (N/mm, full ring).
#[derive(Clone, Debug, PartialEq)]
pub struct Stability {
    pub axial_rate: f64,
    pub squirm: Option<f64>,
    pub in_plane: Option<f64>,
    /// The harmonics n = 2 to [`HIGHEST_HARMONIC`] and their critical pressures.
    pub higher: Vec<(u32, Option<f64>)>,
    /// For a harmonic (1 the squirm, 0 in-plane, the higher) whose eigenvalues found were all negative (buckling under an external
    /// pressure), the pressure its internal critical pressure lies above: the state's pressure
    /// plus the largest of their magnitudes (the solver finds those nearest zero).
    pub above: Vec<(u32, f64)>,
}

impl Stability {
    /// The lowest critical pressure over every harmonic, with its harmonic.
    pub fn governing(&self) -> Option<(u32, f64)> {
        let all = [(1, self.squirm), (0, self.in_plane)].into_iter().chain(self.higher.iter().copied());
        all.filter_map(|(n, p)| p.map(|p| (n, p))).min_by(|a, b| a.1.total_cmp(&b.1))
    }
}

/// The buckle steps (and the axial rate's step) on joint `p`.
pub fn steps(p: &DesignSpec) -> Vec<Perturbation> {
    let held = |set: &str| {
        [HarmonicComponent::R, HarmonicComponent::Z, HarmonicComponent::T].map(|component| HarmonicDisplacement { node_set: set.into(), component, value: 0.0 })
    };
    let buckle = |name: &str, mode: u32| Perturbation {
        name: name.into(),
        mode,
        displacements: held("fixed_end").into_iter().chain(held("moving_end")).collect(),
        rings: Vec::new(),
        pressures: vec![Pressure { surface: "wetted".into(), value: 1.0 }],
        without_contact: Vec::new(),
        analysis: Analysis::Buckle { eigenvalues: EIGENVALUES },
    };
    let axial = super::flexibility::steps(p, super::flexibility::Movements { lateral: 0.0, angular: 0.0 }).into_iter().filter(|s| s.name == AXIAL);
    let higher = (2..=HIGHEST_HARMONIC).map(|n| buckle(&higher_step(n), n));
    axial.chain([buckle(SQUIRM, 1), buckle(IN_PLANE, 0)]).chain(higher).collect()
}

/// The critical pressures from a run's answers to [`steps`].
pub fn from_answers(answers: &[(String, PerturbationAnswer)]) -> Result<Stability> {
    let axial_rate = super::flexibility::axial_rate(answers)?;
    // the lowest positive load factor's critical pressure
    let critical = |name: &str| lowest_positive_mode(answers, name).and_then(|m| m.critical_pressures.first().map(|c| c.1));
    let higher: Vec<(u32, Option<f64>)> = (2..=HIGHEST_HARMONIC).map(|n| (n, critical(&higher_step(n)))).collect();
    let harmonics = [(1, SQUIRM.to_string()), (0, IN_PLANE.to_string())].into_iter().chain((2..=HIGHEST_HARMONIC).map(|n| (n, higher_step(n))));
    let above = harmonics.filter(|(_, step)| critical(step).is_none()).filter_map(|(n, step)| lower_bound(answers, &step).map(|b| (n, b))).collect();
    Ok(Stability { axial_rate, squirm: critical(SQUIRM), in_plane: critical(IN_PLANE), higher, above })
}

/// The pressure a buckle step's internal critical pressure lies above when every eigenvalue
/// found is negative: base + |lambda| of the largest, from its critical pressure base + lambda.
fn lower_bound(answers: &[(String, PerturbationAnswer)], step: &str) -> Option<f64> {
    let (_, answer) = answers.iter().find(|(s, _)| s == step)?;
    let farthest = answer.modes.iter().filter(|m| m.eigenvalue < 0.0).max_by(|x, y| x.eigenvalue.abs().total_cmp(&y.eigenvalue.abs()))?;
    farthest.critical_pressures.first().map(|c| c.1 - 2.0 * farthest.eigenvalue)
}

/// The mode of the lowest positive eigenvalue of eigenvalue step `step` (a stable state's first
/// frequency, the first load factor that buckles it).
pub(super) fn lowest_positive_mode<'a>(answers: &'a [(String, PerturbationAnswer)], step: &str) -> Option<&'a crate::records::perturbation::EigenMode> {
    let (_, answer) = answers.iter().find(|(s, _)| s == step)?;
    answer.modes.iter().filter(|m| m.eigenvalue > 0.0).min_by(|x, y| x.eigenvalue.total_cmp(&y.eigenvalue))
}

/// The joint `p` at rest (no pressure, heat or stroke, elastic) and its buckle steps
/// (collective); `keep` sees the run's file and its answer on every rank (a picture of a mode,
/// say) before the file is removed.
pub fn at_rest(session: &PetscSession, p: &DesignSpec, keep: impl FnOnce(&std::path::Path, &Stability)) -> Result<Stability> {
    super::at_rest(session, p, "stability", steps, |_, summary, file| {
        let stability = from_answers(&summary.perturbations)?;
        keep(file, &stability);
        Ok(stability)
    })
}

/// EJMA's column instability pressure with both ends held, 0.34 pi Kb / (N q), and the
/// unfactored equivalent column's, 2 pi Kb / (N q) (MPa).
pub fn column_estimates(p: &DesignSpec, axial_rate: f64) -> (f64, f64) {
    let code = p.geometry().column_instability_pressure(axial_rate);
    (code, code * 2.0 / 0.34)
}

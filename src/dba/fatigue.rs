//! Fatigue by elastic-plastic analysis (ASME VIII-2 5.5.4): the model with its materials as
//! the deck gives them (their kinematic hardening the cyclic stress-strain behaviour; see
//! docs/deck.md), the deck's cycle of steps run `cycles` times so that the last cycle is the
//! stabilised one, and at every Gauss point of that cycle:
//! - the effective strain range, the largest over pairs of the cycle's states i, j of
//!   delta_eps_eff = S_P(sigma_i - sigma_j) / E + eps_peq(eps_p,i - eps_p,j), S_P the von
//!   Mises equivalent of the stress range and eps_peq the von Mises equivalent plastic strain
//!   range (`effective_strain_range`, sqrt(2/3 d:d) for a plastic strain) (5.5.4.4, steps 4
//!   and 5);
//! - the alternating stress S_alt = E delta_eps_eff / 2 (step 6), and the permissible cycles N
//!   read off the fatigue curve at S_alt E_FC / E (step 7, Annex 3-F);
//! - the damage of the design cycles n / N, which must not exceed 1 (step 8).
//!
//! The states are the increments of the last cycle and the end of the cycle before; the plastic
//! strain is the restart state's (eps_p at small strain, ln(C_p) / 2 at finite strain).

use super::fatigue_curve::Cycles;
use super::table::{DbaTable, FatigueTable};
use crate::assessment::fe_check::effective_strain_range;
use crate::element::solid::QUADRATURE_POINTS as QP;
use crate::error::{Error, Result};
use crate::io::reader::ResultsReader;
use crate::material::PointState;
use crate::model::{Convergence, Model, Step};
use crate::petsc::PetscSession;
use crate::solve::RunOptions;
use std::collections::HashMap;
use std::path::Path;

/// What the fatigue analysis found at its worst Gauss point.
#[derive(Clone, Debug, PartialEq)]
pub struct Fatigue {
    pub cycles_run: usize,
    /// The largest effective strain range of the last cycle.
    pub strain_range: f64,
    /// Where (undeformed r, z of the Gauss point's element centre, mm) and in which element.
    pub at: [f64; 2],
    pub element: u64,
    /// S_alt = E delta_eps_eff / 2 there, MPa.
    pub alternating_stress: f64,
    /// Permissible cycles there.
    pub allowed: Cycles,
    /// The design cycles n and the damage n / N.
    pub design_cycles: f64,
    pub damage: f64,
    pub curve: String,
}

/// The suffix of the repeated cycle steps' names: "heat (cycle 2)".
fn cycle_name(name: &str, k: usize) -> String {
    format!("{name} (cycle {k})")
}

/// The fatigue model of `model`: its heat and general steps, the cycle repeated; the tight
/// residual test; fields (with the restart state) at every increment.
pub fn model(model: &Model, f: &FatigueTable) -> Result<Model> {
    let mut m = model.clone();
    let mut steps: Vec<Step> = model.steps.iter().filter(|s| !matches!(s, Step::Perturbation(_))).cloned().collect();
    let cycle: Vec<_> = model.general_steps().filter(|s| f.cycle.contains(&s.name)).cloned().collect();
    for k in 2..=f.cycles {
        for s in &cycle {
            steps.push(Step::General(crate::model::GeneralStep { name: cycle_name(&s.name, k), ..s.clone() }));
        }
    }
    m.steps = steps;
    m.stepping.convergence = Convergence::Residual;
    m.output.every = 1;
    m.output.fields.stress = true;
    // the stress ranges as computed (a strain range of 1e-6 is 0.2 MPa of a 200 GPa steel)
    m.output.precision = crate::model::Precision::Double;
    m.validate()?;
    Ok(m)
}

/// Runs the fatigue analysis of `model` into `output` and evaluates its last cycle
/// (collective).
pub fn run(session: &PetscSession, model: &Model, spec: &DbaTable, output: &Path, progress: bool) -> Result<Fatigue> {
    let f = spec.fatigue.as_ref().ok_or_else(|| Error::input("[design_by_analysis] has no fatigue"))?;
    let m = self::model(model, f)?;
    crate::solve::run(session, &m, &RunOptions { output: output.to_path_buf(), progress, verbose: false, monitor: false, restart: None })?;
    evaluate(output, model, f)
}

/// The last cycle's figures from the fatigue run's file.
pub fn evaluate(file: &Path, model: &Model, f: &FatigueTable) -> Result<Fatigue> {
    let reader = ResultsReader::open(file)?;
    let rows = reader.history_rows()?;
    let general = model.general_steps().count();
    let c = f.cycle.len();
    // the run-wide steps of the last cycle, and the increment that ends the cycle before
    let first_step = general + c * (f.cycles - 1) - c + 1;
    let mut increments: Vec<usize> = rows.iter().filter(|(_, r)| r.step >= first_step).map(|(_, r)| r.number).collect();
    let before = rows.iter().filter(|(_, r)| r.step < first_step).map(|(_, r)| r.number).max();
    increments.extend(before);
    increments.sort_unstable();
    if increments.len() < 2 {
        return Err(Error::Output { path: file.to_path_buf(), message: "the fatigue run's file lacks its last cycle".into() });
    }
    let element_index: HashMap<u64, usize> = reader.element_ids()?.into_iter().enumerate().map(|(i, id)| (id, i)).collect();
    let ne = element_index.len();
    let mut states: Vec<PointStates> = Vec::new();
    for &n in &increments {
        let name = format!("{n:06}");
        let stress: Vec<[f64; 4]> = reader.field(&name, "stress")?.chunks_exact(4).map(|s| [s[0], s[1], s[2], s[3]]).collect();
        let mut plastic = vec![[0.0; 4]; ne * QP];
        let points = reader.field(&name, "state/plastic_points").unwrap_or_default();
        let values = reader.field(&name, "state/plastic_state").unwrap_or_default();
        for (p, s) in points.chunks_exact(2).zip(values.chunks_exact(5)) {
            let e = *element_index
                .get(&(p[0] as u64))
                .ok_or_else(|| Error::Output { path: file.to_path_buf(), message: format!("plastic state of an unknown element {}", p[0]) })?;
            plastic[e * QP + p[1] as usize] = PointState::isotropic([s[0], s[1], s[2], s[3]], s[4]).plastic_strain_tensor(model.kinematics);
        }
        if stress.len() != ne * QP {
            return Err(Error::Output { path: file.to_path_buf(), message: format!("increment {n}: no Gauss-point stress") });
        }
        states.push(PointStates { stress, plastic });
    }
    let coords = reader.coordinates()?;
    let connectivity = reader.connectivity()?;
    let ids = reader.element_ids()?;
    let mut worst = (0.0, 0usize);
    for e in 0..ne {
        let youngs = model.materials[model.element_material[e]].youngs_modulus;
        for q in 0..QP {
            let k = e * QP + q;
            if states.iter().any(|s| !s.stress[k].iter().all(|v| v.is_finite())) {
                continue; // a slot the element's rule leaves unused
            }
            for i in 0..states.len() {
                for j in 0..i {
                    let ds: [f64; 4] = std::array::from_fn(|c| states[i].stress[k][c] - states[j].stress[k][c]);
                    let dp: [f64; 4] = std::array::from_fn(|c| states[i].plastic[k][c] - states[j].plastic[k][c]);
                    let range = crate::fe::axisymmetric::von_mises(&ds) / youngs + effective_strain_range(dp);
                    if range > worst.0 {
                        worst = (range, k);
                    }
                }
            }
        }
    }
    let (strain_range, k) = worst;
    let e = k / QP;
    let youngs = model.materials[model.element_material[e]].youngs_modulus;
    let alternating_stress = youngs * strain_range / 2.0;
    let curve = f.curve()?;
    let allowed = curve.cycles(alternating_stress, youngs);
    let centre = connectivity[e].iter().take(4).fold([0.0, 0.0], |a, &n| [a[0] + coords[n][0] / 4.0, a[1] + coords[n][1] / 4.0]);
    Ok(Fatigue {
        cycles_run: f.cycles,
        strain_range,
        at: centre,
        element: ids[e],
        alternating_stress,
        allowed,
        design_cycles: f.design_cycles,
        damage: f.design_cycles / allowed.value(),
        curve: curve.name,
    })
}

/// One increment's Gauss-point states, [element * 9 + point].
struct PointStates {
    /// Cauchy stress [rr, zz, tt, rz], MPa.
    stress: Vec<[f64; 4]>,
    /// Plastic strain (eps_p, or ln(C_p) / 2 at finite strain).
    plastic: Vec<[f64; 4]>,
}

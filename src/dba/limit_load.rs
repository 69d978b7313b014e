//! Protection against plastic collapse by the limit-load method (ASME VIII-2 5.2.3, 2010 and
//! later editions): the model elastic-perfectly plastic at 1.5 S (von Mises, associated
//! flow), small displacements, the primary loads (pressures, forces, body loads) times the
//! factor of Table 5.3 (1.5 on P + Ps + D); prescribed displacements as the deck gives them
//! and no thermal strain (Table 5.3 leaves the secondary loads out); the deck's general steps,
//! or those `steps` names (a stroke, a secondary load, left out). The check passes when
//! the factored loads are carried (every increment converges). Past them the loads rise to
//! `search_to` times the design loads until Newton fails at the smallest increment: the
//! factor reached then is the collapse load factor, the check's figure. The run takes the
//! residual convergence test (||F|| down by 1e-10), whatever the deck's: the field test
//! relaxes as Newton stalls near collapse and once accepted an increment whose residual was
//! 4 % of the forces, past the load the supports carried; under the residual test the applied
//! factor is the carried one to 1e-10 of the forces.

use super::spec::{DbaSpec, LimitLoadSpec};
use crate::error::{Error, Result};
use crate::model::{BodyLoad, Convergence, GeneralStep, Kinematics, Model, NodalForce, Plasticity, Pressure, Step};
use crate::petsc::PetscSession;
use crate::solve::RunOptions;
use std::path::Path;

/// What the limit-load analysis reached.
#[derive(Clone, Debug, PartialEq)]
pub struct LimitLoad {
    /// Whether the loads times `factor` were carried.
    pub carried: bool,
    /// The factor on the design loads at the last converged increment: the collapse load
    /// factor when the search failed, `search_to` when it carried everything. None when a
    /// factored step before the last failed (its loads are not one multiple of the design's).
    pub reached: Option<f64>,
    /// Where Newton failed at the smallest increment (a collapse): the step's name and its
    /// load factor; None when the search reached `search_to`.
    pub failed_in: Option<(String, f64)>,
}

/// The loads a deck's general steps leave applied at their end: each surface's pressure,
/// each node's force component, each element set's body load (a later step's value wins).
#[derive(Default)]
pub(super) struct AppliedLoads {
    pub(super) pressures: Vec<Pressure>,
    pub(super) forces: Vec<NodalForce>,
    pub(super) body_loads: Vec<BodyLoad>,
}

impl AppliedLoads {
    pub(super) fn apply(&mut self, step: &GeneralStep) {
        for p in &step.pressures {
            self.pressures.retain(|q| q.surface != p.surface);
            self.pressures.push(p.clone());
        }
        for f in &step.nodal_forces {
            self.forces.retain(|g| (g.node, g.component) != (f.node, f.component));
            self.forces.push(f.clone());
        }
        for b in &step.body_loads {
            let kind = |l: &BodyLoad| std::mem::discriminant(&l.force);
            self.body_loads.retain(|c| (c.elements.as_str(), kind(c)) != (b.elements.as_str(), kind(b)));
            self.body_loads.push(b.clone());
        }
    }
}

/// The step's primary loads times `s`.
fn scale_primary(step: &mut GeneralStep, s: f64) {
    step.pressures.iter_mut().for_each(|p| p.value *= s);
    step.nodal_forces.iter_mut().for_each(|f| f.value *= s);
    step.body_loads.iter_mut().for_each(|b| b.force = b.force.scaled(s));
}

/// Name of the search step the check appends.
pub const SEARCH_STEP: &str = "collapse search";

/// The limit-load model of `model`: its materials elastic-perfectly plastic at 1.5 S, small
/// displacements, no thermal strain, its general steps with the primary loads times the
/// factor, then the search step.
pub fn model(model: &Model, spec: &DbaSpec, ll: &LimitLoadSpec) -> Result<Model> {
    let mut m = model.clone();
    m.kinematics = Kinematics::Small;
    for mat in &mut m.materials {
        mat.plasticity = Some(Plasticity::linear(1.5 * spec.allowable(&mat.name)?, 0.0));
        mat.kinematic = crate::model::KinematicHardening::NONE;
        mat.thermal_expansion = 0.0;
    }
    let mut applied = AppliedLoads::default();
    let mut steps = Vec::new();
    let kept = |name: &str| ll.steps.as_ref().is_none_or(|steps| steps.iter().any(|s| s == name));
    for step in model.general_steps().filter(|s| kept(&s.name)) {
        let mut s = step.clone();
        scale_primary(&mut s, ll.factor);
        applied.apply(&s);
        // temperatures no longer strain anything; none is carried into the check's file
        s.temperature = None;
        steps.push(Step::General(s));
    }
    if applied.pressures.is_empty() && applied.forces.is_empty() && applied.body_loads.is_empty() {
        return Err(Error::input(
            "[design_by_analysis] limit_load: the deck's steps apply no pressure, force or body load (the primary loads the check factors)",
        ));
    }
    let mut search = GeneralStep::new(SEARCH_STEP, ll.search_increments, Vec::new());
    search.pressures = applied.pressures;
    search.nodal_forces = applied.forces;
    search.body_loads = applied.body_loads;
    scale_primary(&mut search, ll.search_to / ll.factor);
    steps.push(Step::General(search));
    m.steps = steps;
    m.stepping.convergence = Convergence::Residual;
    m.validate()?;
    Ok(m)
}

/// Runs the limit-load analysis of `model` into `output` (collective).
pub fn run(session: &PetscSession, model: &Model, spec: &DbaSpec, output: &Path, progress: bool) -> Result<LimitLoad> {
    let ll = spec.limit_load.as_ref().ok_or_else(|| Error::input("[design_by_analysis] has no limit_load"))?;
    let m = self::model(model, spec, ll)?;
    let steps: Vec<String> = m.general_steps().map(|s| s.name.clone()).collect();
    let options = RunOptions { output: output.to_path_buf(), progress, verbose: false, monitor: false, restart: None };
    let failure = match crate::solve::run(session, &m, &options) {
        Ok(_) => None,
        Err(Error::NotConverged { step, load_factor, .. }) => Some((step, load_factor)),
        Err(e) => return Err(e),
    };
    let Some(failure) = failure else {
        return Ok(LimitLoad { carried: true, reached: Some(ll.search_to), failed_in: None });
    };
    // the last converged increment, from the file the run kept
    let rows = crate::io::reader::ResultsReader::open(output)?.history_rows()?;
    let last = rows.last().map(|(_, r)| (r.step, r.load_factor));
    let search = steps.len();
    let factored = search - 1;
    let (carried, reached) = match last {
        // in the search: from the factor up to search_to
        Some((step, lambda)) if step == search => (true, Some(ll.factor + (ll.search_to - ll.factor) * lambda)),
        // every factored step done, nothing of the search
        Some((step, lambda)) if step == factored && lambda >= 1.0 => (true, Some(ll.factor)),
        // in the last factored step: its loads are the factor times lambda of the design's
        Some((step, lambda)) if step == factored => (false, Some(ll.factor * lambda)),
        // an earlier factored step, or none converged
        _ => (false, None),
    };
    Ok(LimitLoad { carried, reached, failed_in: Some(failure) })
}

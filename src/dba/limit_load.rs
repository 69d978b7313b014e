//! Protection against plastic collapse by the limit-load method (ASME VIII-2 5.2.3, 2010 and
//! later editions): the model elastic-perfectly plastic at 1.5 S (von Mises, associated
//! flow), small displacements, the primary loads (pressures, forces, body loads) times the
//! factor of Table 5.3 (1.5 on P + Ps + D); prescribed displacements as the deck gives them
//! and no thermal strain (Table 5.3 leaves the secondary loads out); the deck's general steps,
//! or those `steps` names (a stroke, a secondary load, left out). The check passes when
//! the factored loads are carried (every increment converges): a run of the factored steps
//! alone ([`run_factored`]). Past them the loads rise to `search_to` times the design loads
//! until Newton fails at the smallest increment ([`search`], that run continued, after the
//! other checks): the factor reached then is the collapse load factor, the check's figure.
//! Both take the residual convergence test (||F|| down by 1e-10), whatever the deck's: the
//! field test relaxes as Newton stalls near collapse and once accepted an increment whose
//! residual was 4 % of the forces, past the load the supports carried; under the residual
//! test the applied factor is the carried one to 1e-10 of the forces.

use super::table::{DbaTable, LimitLoadTable};
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
    /// Where the analysis stopped (a collapse, where Newton failed at the smallest increment):
    /// the step's name, its load factor on the design loads and why; None when the search
    /// reached `search_to`.
    pub failed_in: Option<Stop>,
}

/// Where and why the limit-load analysis stopped.
#[derive(Clone, Debug, PartialEq)]
pub struct Stop {
    pub step: String,
    /// The factor on the design loads of the attempt that failed (None in a factored step
    /// before the last, whose loads are not one multiple of the design's).
    pub factor: Option<f64>,
    /// The solver's words: the reason and whether a smaller increment was tried.
    pub why: String,
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
pub fn model(model: &Model, spec: &DbaTable, ll: &LimitLoadTable) -> Result<Model> {
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

/// The factored steps of the limit-load analysis of `model`, run into `output` (collective):
/// whether the factored loads are carried, the check's verdict, known before any search.
pub fn run_factored(session: &PetscSession, model: &Model, spec: &DbaTable, output: &Path, progress: bool) -> Result<LimitLoad> {
    let ll = spec.limit_load.as_ref().ok_or_else(|| Error::input("[design_by_analysis] has no limit_load"))?;
    let mut m = self::model(model, spec, ll)?;
    m.steps.retain(|s| !matches!(s, Step::General(g) if g.name == SEARCH_STEP));
    let options = RunOptions { output: output.to_path_buf(), progress, verbose: false, monitor: false, restart: None };
    match crate::solve::run(session, &m, &options) {
        Ok(_) => Ok(LimitLoad { carried: true, reached: Some(ll.factor), failed_in: None }),
        Err(Error::NotConverged { step, load_factor, reason }) => {
            let last_step = m.general_step_count();
            let rows = crate::io::reader::ResultsReader::open(output)?.history_rows()?;
            // in the last factored step its loads are the factor times lambda of the design's
            let reached = rows.last().filter(|(_, r)| r.step == last_step).map(|(_, r)| ll.factor * r.load_factor);
            let factor = m.general_steps().last().is_some_and(|s| s.name == step).then_some(ll.factor * load_factor);
            Ok(LimitLoad { carried: false, reached, failed_in: Some(Stop { step, factor, why: first_clause(&reason) }) })
        }
        Err(e) => Err(e),
    }
}

/// The collapse search (collective): the factored run `factored` continued (a restart from its
/// last increment) by the search step into `output`, the loads raised to `search_to` times the
/// design's until Newton fails at the smallest increment. Run after every other check: however
/// long its last attempts take near collapse, the verdict is known and written before it.
pub fn search(session: &PetscSession, model: &Model, spec: &DbaTable, factored: &Path, output: &Path, progress: bool) -> Result<LimitLoad> {
    let ll = spec.limit_load.as_ref().ok_or_else(|| Error::input("[design_by_analysis] has no limit_load"))?;
    let m = self::model(model, spec, ll)?;
    let restart = Some(crate::io::restart::RestartFrom { file: factored.to_path_buf(), increment: None });
    let options = RunOptions { output: output.to_path_buf(), progress, verbose: false, monitor: false, restart };
    let budget = ll.search_seconds.map(crate::interrupt::Budget::start);
    let outcome = crate::solve::run(session, &m, &options);
    drop(budget);
    let failure = match outcome {
        Ok(_) => return Ok(LimitLoad { carried: true, reached: Some(ll.search_to), failed_in: None }),
        Err(Error::NotConverged { step, load_factor, reason }) => {
            Stop { step, factor: Some(ll.factor + (ll.search_to - ll.factor) * load_factor), why: first_clause(&reason) }
        }
        Err(Error::Interrupted { signal, .. }) if signal == crate::interrupt::name(crate::interrupt::BUDGET) => {
            let seconds = ll.search_seconds.unwrap_or_default();
            Stop { step: SEARCH_STEP.into(), factor: None, why: format!("the search stopped at its budget of {seconds} s") }
        }
        Err(e) => return Err(e),
    };
    // the last converged increment, from the file the run kept (its history from the start)
    let rows = crate::io::reader::ResultsReader::open(output)?.history_rows()?;
    let search = m.general_step_count();
    let reached = match rows.last() {
        Some((_, r)) if r.step == search => ll.factor + (ll.search_to - ll.factor) * r.load_factor,
        _ => ll.factor,
    };
    Ok(LimitLoad { carried: true, reached: Some(reached), failed_in: Some(failure) })
}

/// The solver's reason up to its first ';' (the rest names the file, which the table does).
pub(super) fn first_clause(reason: &str) -> String {
    reason.split(';').next().unwrap_or_default().to_string()
}

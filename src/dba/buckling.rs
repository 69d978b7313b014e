//! Protection against collapse from buckling (ASME VIII-2 5.4.1, 2010 and later editions),
//! type 1: a bifurcation (eigenvalue) analysis on an elastic prestress without geometric
//! nonlinearity. Each of the deck's buckle steps (its mode n, its holds) takes the design
//! pressures as its load, about the model held by the deck's supports and otherwise unloaded:
//! its lowest load factor is then the factor on the design loads at which mode n bifurcates,
//! and must reach the design factor Phi_B = 2 / beta_cr (5.4.1.3(a)), beta_cr the capacity
//! reduction factor for the shell's geometry and loading.

use super::limit_load::AppliedLoads;
use super::table::DbaTable;
use crate::error::{Error, Result};
use crate::model::perturbation::Analysis;
use crate::model::{GeneralStep, Kinematics, Model, PrescribedDisplacement, Step};
use crate::petsc::PetscSession;
use crate::solve::RunOptions;
use std::path::Path;

/// What the buckling analysis found.
#[derive(Clone, Debug, PartialEq)]
pub struct Buckling {
    /// Phi_B = 2 / beta_cr.
    pub design_factor: f64,
    /// Per buckle step: its name, its mode n and its lowest positive load factor (None: no
    /// positive one among those asked).
    pub steps: Vec<(String, u32, Option<f64>)>,
}

/// The buckling model of `model`: elastic, the pressure a follower load, no thermal strain; one
/// general step holding the deck's supports (every prescribed displacement of its general
/// steps, at zero); its buckle steps with the design pressures as their load.
pub fn model(model: &Model) -> Result<Model> {
    let mut m = model.clone();
    // the base is unloaded, so its prestress is the linear one type 1 asks for whatever the
    // kinematics; finite kinematics give the eigenproblem the pressure's load stiffness: a
    // fluid's pressure follows the surface (a ring: 3 E I / R^3, not a dead load's 4 E I / R^3)
    m.kinematics = Kinematics::Finite;
    for mat in &mut m.materials {
        mat.plasticity = None;
        mat.kinematic = crate::model::KinematicHardening::NONE;
        mat.thermal_expansion = 0.0;
    }
    let mut applied = AppliedLoads::default();
    let mut supports: Vec<PrescribedDisplacement> = Vec::new();
    for step in model.general_steps() {
        applied.apply(step);
        for d in &step.displacements {
            if !supports.iter().any(|s| (s.node_set.as_str(), s.component) == (d.node_set.as_str(), d.component)) {
                supports.push(PrescribedDisplacement { value: 0.0, ..d.clone() });
            }
        }
    }
    if !applied.forces.is_empty() || !applied.body_loads.is_empty() {
        return Err(Error::input(
            "[design_by_analysis] buckling: the design loads are a buckle step's load, pressures only; the deck's steps also apply forces or body loads",
        ));
    }
    if applied.pressures.is_empty() {
        return Err(Error::input("[design_by_analysis] buckling: the deck's steps apply no pressure (the design load the buckle steps take)"));
    }
    let mut steps = vec![Step::General(GeneralStep::new("supports", 1, supports))];
    for p in model.perturbations().filter(|p| matches!(p.analysis, Analysis::Buckle { .. })) {
        let mut b = p.clone();
        b.pressures = applied.pressures.clone();
        b.displacements.iter_mut().for_each(|d| d.value = 0.0);
        steps.push(Step::Perturbation(b));
    }
    if steps.len() == 1 {
        return Err(Error::input("[design_by_analysis] buckling: the deck has no buckle step (procedure = \"buckle\") naming the modes to check"));
    }
    m.steps = steps;
    m.validate()?;
    Ok(m)
}

/// Runs the buckling analysis of `model` into `output` (collective).
pub fn run(session: &PetscSession, model: &Model, spec: &DbaTable, output: &Path, progress: bool) -> Result<Buckling> {
    let b = spec.buckling.as_ref().ok_or_else(|| Error::input("[design_by_analysis] has no buckling"))?;
    let m = self::model(model)?;
    let summary = crate::solve::run(session, &m, &RunOptions { output: output.to_path_buf(), progress, verbose: false, monitor: false, restart: None })?;
    let modes: Vec<u32> = m.perturbations().map(|p| p.mode).collect();
    let steps = summary
        .perturbations
        .iter()
        .zip(modes)
        .map(|((name, answer), n)| (name.clone(), n, answer.modes.iter().map(|e| e.eigenvalue).filter(|&l| l > 0.0).reduce(f64::min)))
        .collect();
    Ok(Buckling { design_factor: 2.0 / b.beta_cr, steps })
}

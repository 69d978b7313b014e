//! Protection against ratcheting by elastic-plastic analysis (ASME VIII-2 5.5.7, 2010 and
//! later editions): the model elastic-perfectly plastic at each material's yield strength
//! (von Mises, associated flow), its loads as the deck gives them, the deck's cycle of steps
//! run `cycles` times (at least three). The criteria, of which one must hold:
//! (a) no plastic action in the last cycle;
//! (b) an elastic core in the primary-load-bearing section over the last cycle;
//! (c) no permanent change of the overall dimensions between the ends of the last two cycles.
//! "No" is read against a tolerance of 1e-3 of the smallest yield strain (sigma_y / E): a
//! growth of the equivalent plastic strain below it is no plastic action, and a node moving
//! less than it times the model's size between the cycles' ends is no change of dimensions.

use super::table::{DbaTable, RatchetingTable};
use crate::error::{Error, Result};
use crate::fe::linearize::StressSampler;
use crate::fe::recover::Rule;
use crate::io::reader::ResultsReader;
use crate::model::{Convergence, Model, Plasticity, Step};
use crate::petsc::PetscSession;
use crate::solve::RunOptions;
use std::path::Path;

/// What the ratcheting analysis found.
#[derive(Clone, Debug, PartialEq)]
pub struct Ratcheting {
    pub cycles: usize,
    /// The run-wide increments that end the last two cycles, compared.
    pub compared: [usize; 2],
    /// Whether any point yielded in the whole analysis.
    pub yielded: bool,
    /// (a) The largest growth of the equivalent plastic strain over the last cycle.
    pub last_cycle_plastic: f64,
    /// (b) The least growth along the section over the last cycle (None without a section).
    pub core: Option<f64>,
    /// (c) The largest change of a node's displacement between the ends of the last two
    /// cycles, mm.
    pub dimension_change: f64,
    /// No plastic action below this strain.
    pub strain_tolerance: f64,
    /// No change of dimensions below this length, mm.
    pub length_tolerance: f64,
}

impl Ratcheting {
    pub fn no_plastic_action(&self) -> bool {
        self.last_cycle_plastic <= self.strain_tolerance
    }
    pub fn elastic_core(&self) -> Option<bool> {
        self.core.map(|c| c <= self.strain_tolerance)
    }
    pub fn dimensions_kept(&self) -> bool {
        self.dimension_change <= self.length_tolerance
    }
    /// Whether one of the three criteria holds.
    pub fn passes(&self) -> bool {
        self.no_plastic_action() || self.elastic_core() == Some(true) || self.dimensions_kept()
    }
}

/// The suffix of the repeated cycle steps' names: "heat (cycle 2)".
fn cycle_name(name: &str, k: usize) -> String {
    format!("{name} (cycle {k})")
}

/// The ratcheting model of `model`: its materials elastic-perfectly plastic at their yield
/// strength, its heat and general steps, the cycle repeated; the tight residual test (the
/// criteria compare states to 1e-3 of the yield strain); fields at each step's end.
pub fn model(model: &Model, r: &RatchetingTable) -> Result<Model> {
    let mut m = model.clone();
    for mat in &mut m.materials {
        let h = mat.plasticity.ok_or_else(|| Error::input(format!("[design_by_analysis] ratcheting: material '{}' has no yield stress", mat.name)))?;
        // elastic-perfectly plastic: no hardening of either kind
        mat.plasticity = Some(Plasticity::linear(h.initial_yield_stress(), 0.0));
        mat.kinematic = crate::model::KinematicHardening::NONE;
    }
    let mut steps: Vec<Step> = model.steps.iter().filter(|s| !matches!(s, Step::Perturbation(_))).cloned().collect();
    let cycle: Vec<_> = model.general_steps().filter(|s| r.cycle.contains(&s.name)).cloned().collect();
    for k in 2..=r.cycles {
        for s in &cycle {
            steps.push(Step::General(crate::model::GeneralStep { name: cycle_name(&s.name, k), ..s.clone() }));
        }
    }
    m.steps = steps;
    m.stepping.convergence = Convergence::Residual;
    m.output.every = usize::MAX;
    m.output.fields.plastic_strain = true;
    m.validate()?;
    Ok(m)
}

/// Runs the ratcheting analysis of `model` into `output` and reads the criteria from it
/// (collective).
pub fn run(session: &PetscSession, model: &Model, spec: &DbaTable, output: &Path, progress: bool) -> Result<Ratcheting> {
    let r = spec.ratcheting.as_ref().ok_or_else(|| Error::input("[design_by_analysis] has no ratcheting"))?;
    let m = self::model(model, r)?;
    crate::solve::run(session, &m, &RunOptions { output: output.to_path_buf(), progress, verbose: false, monitor: false, restart: None })?;
    let yield_strain = m.materials.iter().filter_map(|mat| mat.plasticity.map(|h| h.initial_yield_stress() / mat.youngs_modulus)).fold(f64::INFINITY, f64::min);
    let size = model_size(&model.mesh, model.is_axisymmetric());
    criteria(output, model.general_steps().count(), r, 1e-3 * yield_strain, 1e-3 * yield_strain * size)
}

/// The largest overall dimension of the body, mm: its extent, and for a body of revolution
/// at least its outer radius (a ring's diameter changes as it ratchets, however thin its wall).
fn model_size(mesh: &crate::model::Mesh, axisymmetric: bool) -> f64 {
    let radius = if axisymmetric { mesh.coords.iter().map(|x| x[0]).fold(0.0, f64::max) } else { 0.0 };
    mesh.largest_extent().max(radius)
}

/// The criteria read from the ratcheting run's file: `general` general steps in the deck
/// (its cycle the last of them, once), run `r.cycles` times.
fn criteria(file: &Path, general: usize, r: &RatchetingTable, strain_tolerance: f64, length_tolerance: f64) -> Result<Ratcheting> {
    let reader = ResultsReader::open(file)?;
    let rows = reader.history_rows()?;
    let c = r.cycle.len();
    // the last increment of the step ending cycle k (1-based), run-wide
    let end_of = |k: usize| rows.iter().filter(|(_, row)| row.step == general + c * (k - 1)).map(|(_, row)| row.number).max();
    let missing = || Error::Output { path: file.to_path_buf(), message: "the ratcheting run's file lacks a cycle's end".into() };
    let compared = [end_of(r.cycles - 1).ok_or_else(missing)?, end_of(r.cycles).ok_or_else(missing)?];
    let name = |n: usize| format!("{n:06}");
    let ep = |n: usize| reader.field(&name(n), "equivalent_plastic_strain");
    let (before, after) = (ep(compared[0])?, ep(compared[1])?);
    let growth: Vec<f64> = after.iter().zip(&before).map(|(a, b)| a - b).collect();
    let last_cycle_plastic = growth.iter().copied().fold(0.0, f64::max);
    let yielded = rows.iter().any(|(_, row)| row.max_plastic_strain > 0.0);
    let core = match r.section {
        None => None,
        Some([a, b]) => Some(least_along(&reader, &growth, a, b)?),
    };
    let (u0, u1) = (reader.displacement(&name(compared[0]))?, reader.displacement(&name(compared[1]))?);
    let dimension_change = u0.iter().zip(&u1).map(|(p, q)| (q[0] - p[0]).hypot(q[1] - p[1])).fold(0.0, f64::max);
    Ok(Ratcheting { cycles: r.cycles, compared, yielded, last_cycle_plastic, core, dimension_change, strain_tolerance, length_tolerance })
}

/// The least of a Gauss-point field (9 slots per element) along the section a -> b, read
/// through each element's Gauss points (never extrapolated past them) and held within them
/// (the polynomial through a steep growth undershoots zero between its Gauss points, and
/// found an elastic core in a wall every point of which grows), at 200 points.
fn least_along(reader: &ResultsReader, field: &[f64], a: [f64; 2], b: [f64; 2]) -> Result<f64> {
    let (coords, elements) = (reader.coordinates()?, reader.connectivity()?);
    let packed: Vec<[[f64; 4]; 9]> = field.chunks_exact(9).map(|e| std::array::from_fn(|q| [e[q], 0.0, 0.0, 0.0])).collect();
    let rules = vec![Rule::Copy; elements.len()];
    let sampler = StressSampler::integrated(&coords, &elements, &reader.integration()?, &rules, &packed).with_slack(1e-6);
    const POINTS: usize = 200;
    let values: Vec<f64> = (0..=POINTS)
        .filter_map(|k| {
            let t = k as f64 / POINTS as f64;
            sampler.within_gauss_values([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]).map(|v| v[0])
        })
        .collect();
    if values.len() < POINTS / 2 {
        return Err(Error::input(format!(
            "[design_by_analysis] ratcheting.section ({}, {}) -> ({}, {}) runs mostly outside the model",
            a[0], a[1], b[0], b[1]
        )));
    }
    Ok(values.into_iter().fold(f64::INFINITY, f64::min))
}

//! The TOML deck's schema: the tables and keys a deck may hold (unknown keys refused), with
//! their defaults; `deck` turns them into a model.

use crate::error::{Error, Result};
use crate::fe::section::Section;
use crate::model::mesh::Mesh;
use crate::model::{Convergence, Precision, Predictor, SteppingControls, Temperature};
use serde::Deserialize;
use std::path::PathBuf;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct DeckFile {
    #[serde(default = "default_reference_temperature")]
    pub(super) reference_temperature: TemperatureToml,
    #[serde(default = "yes")]
    pub(super) nlgeom: bool,
    #[serde(default)]
    pub(super) geometry: GeometryToml,
    pub(super) thickness: Option<f64>,
    pub(super) mesh: MeshToml,
    #[serde(default)]
    pub(super) stepping: SteppingToml,
    #[serde(default)]
    pub(super) output: OutputToml,
    #[serde(default)]
    pub(super) material: Vec<MaterialToml>,
    #[serde(default)]
    pub(super) section: Vec<SectionToml>,
    #[serde(default)]
    pub(super) contact: Vec<ContactToml>,
    #[serde(default)]
    pub(super) tie: Vec<TieToml>,
    #[serde(default)]
    pub(super) step: Vec<StepToml>,
    /// `[design_by_analysis]`: read by `slideline check` (`dba::table`), not by the model.
    #[allow(dead_code)]
    pub(super) design_by_analysis: Option<toml::Value>,
}

/// `[[tie]]`: the slave surface's nodes glued to the master's faces (`model::constraint::tie`).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct TieToml {
    pub(super) name: Option<String>,
    pub(super) slave: String,
    pub(super) master: String,
    /// mm; default 5 % of the master faces' mean length.
    pub(super) tolerance: Option<f64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct OutputToml {
    /// Fields of every N-th increment (and of the last of each step).
    pub(super) every: Option<usize>,
    /// Which fields beside the displacement (default: all).
    pub(super) fields: Option<Vec<String>>,
    /// "double" (default) or "single" for the visualisation fields.
    pub(super) precision: Option<Precision>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ContactToml {
    pub(super) name: Option<String>,
    pub(super) slave: String,
    pub(super) master: String,
    #[serde(default)]
    pub(super) two_pass: bool,
    #[serde(default)]
    pub(super) integration: IntegrationToml,
    pub(super) penalty: Option<f64>,
    pub(super) penalty_factor: Option<f64>,
    pub(super) exponential: Option<ExponentialToml>,
    pub(super) capture_distance: Option<f64>,
    pub(super) augmented_lagrangian: Option<AugmentedToml>,
    #[serde(default = "two")]
    pub(super) exclude_neighbours: usize,
    pub(super) friction: Option<f64>,
    pub(super) tangential_penalty: Option<f64>,
    pub(super) elastic_slip: Option<f64>,
    pub(super) adjust: Option<AdjustToml>,
}

/// `exponential = { clearance = c0, pressure = p0 }`: CalculiX's exponential
/// pressure-overclosure law in place of a penalty.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ExponentialToml {
    pub(super) clearance: f64,
    pub(super) pressure: f64,
}

/// `adjust = 0.01` (a clearance, mm) or `adjust = "node_set"`.
#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum AdjustToml {
    Clearance(f64),
    NodeSet(String),
}

#[derive(Deserialize, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
pub(super) enum IntegrationToml {
    #[default]
    Segment,
    NodeToSegment,
}

pub(super) fn two() -> usize {
    2
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct AugmentedToml {
    pub(super) penetration_tolerance: f64,
    #[serde(default = "ten")]
    pub(super) max_augmentations: usize,
}

pub(super) fn ten() -> usize {
    10
}

pub(super) fn default_reference_temperature() -> TemperatureToml {
    TemperatureToml::Uniform(20.0)
}

/// `temperature = 20.0` (every node) or `temperature = [{ set = "hot", value = 150.0 }, ...]`:
/// node sets in order, a later entry winning on shared nodes, an entry without `set` for every
/// node; in a step, nodes no entry names keep their temperature.
#[derive(Deserialize, Clone)]
#[serde(untagged)]
pub(super) enum TemperatureToml {
    Uniform(f64),
    Sets(Vec<SetTemperatureToml>),
}

#[derive(Deserialize, Clone)]
#[serde(deny_unknown_fields)]
pub(super) struct SetTemperatureToml {
    pub(super) set: Option<String>,
    pub(super) value: f64,
}

impl TemperatureToml {
    /// The field it gives over `before` (None: the reference temperature, which must reach
    /// every node); `what` names it in errors.
    pub(super) fn field(
        &self,
        mesh: &Mesh,
        node_sets: &std::collections::BTreeMap<String, Vec<usize>>,
        before: Option<&Temperature>,
        what: &str,
    ) -> Result<Temperature> {
        let entries = match self {
            TemperatureToml::Uniform(t) => return Ok(Temperature::Uniform(*t)),
            TemperatureToml::Sets(entries) => entries,
        };
        let all: Vec<usize> = (0..mesh.coords.len()).collect();
        let mut assignments = Vec::new();
        for e in entries {
            let nodes = match &e.set {
                None => all.as_slice(),
                Some(name) => node_sets.get(name).map(Vec::as_slice).ok_or_else(|| {
                    Error::input(format!("{what}: unknown node set '{name}' (known: {})", node_sets.keys().cloned().collect::<Vec<_>>().join(", ")))
                })?,
            };
            assignments.push((nodes, e.value));
        }
        crate::model::temperature::assign(mesh.coords.len(), before, &assignments)
            .map_err(|missing| Error::input(format!("{what}: {missing} nodes are in none of the sets given (add an entry without `set` for every node first)")))
    }
}

pub(super) fn yes() -> bool {
    true
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct SteppingToml {
    pub(super) cutback_factor: Option<f64>,
    pub(super) growth_factor: Option<f64>,
    pub(super) easy_iterations: Option<usize>,
    pub(super) min_increment: Option<f64>,
    pub(super) max_newton_iterations: Option<usize>,
    pub(super) predictor: Option<Predictor>,
    pub(super) convergence: Option<Convergence>,
}

impl SteppingToml {
    pub(super) fn controls(&self) -> SteppingControls {
        let d = SteppingControls::default();
        SteppingControls {
            cutback_factor: self.cutback_factor.unwrap_or(d.cutback_factor),
            growth_factor: self.growth_factor.unwrap_or(d.growth_factor),
            easy_iterations: self.easy_iterations.unwrap_or(d.easy_iterations),
            min_increment: self.min_increment.unwrap_or(d.min_increment),
            max_newton_iterations: self.max_newton_iterations.unwrap_or(d.max_newton_iterations),
            predictor: self.predictor.unwrap_or(d.predictor),
            convergence: self.convergence.unwrap_or(d.convergence),
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MeshToml {
    pub(super) file: Option<PathBuf>,
    pub(super) rectangle: Option<RectangleToml>,
    #[serde(default)]
    pub(super) block: Vec<BlockToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BlockToml {
    pub(super) name: String,
    pub(super) r: [f64; 2],
    pub(super) z: [f64; 2],
    pub(super) divisions: [usize; 2],
    #[serde(default = "no_grading")]
    pub(super) grading: [f64; 2],
    #[serde(default)]
    pub(super) triangles: bool,
}

pub(super) fn no_grading() -> [f64; 2] {
    [1.0, 1.0]
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RectangleToml {
    pub(super) r: [f64; 2],
    pub(super) z: [f64; 2],
    pub(super) divisions: [usize; 2],
    /// Each quadrilateral split into two 6-node triangles.
    #[serde(default)]
    pub(super) triangles: bool,
}

#[derive(Deserialize, Clone, Copy, PartialEq, Eq, Debug)]
#[serde(rename_all = "snake_case")]
pub(super) enum MaterialKind {
    Elastic,
    J2,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct MaterialToml {
    pub(super) name: String,
    #[serde(default = "default_kind")]
    pub(super) model: MaterialKind,
    /// MPa; a heat-conduction deck's materials may leave it and Poisson's ratio out.
    pub(super) youngs_modulus: Option<f64>,
    pub(super) poissons_ratio: Option<f64>,
    #[serde(default)]
    pub(super) thermal_expansion: f64,
    /// t/mm^3.
    #[serde(default)]
    pub(super) density: f64,
    /// mW/(mm K), numerically W/(m K): heat steps need it.
    pub(super) conductivity: Option<f64>,
    pub(super) yield_stress: Option<f64>,
    pub(super) hardening_modulus: Option<f64>,
    /// Kinematic hardening: up to three Armstrong-Frederick terms.
    #[serde(default)]
    pub(super) backstresses: Vec<crate::material::Backstress>,
}

pub(super) fn default_kind() -> MaterialKind {
    MaterialKind::Elastic
}

#[derive(Deserialize, Default, Clone, Copy, PartialEq)]
#[serde(rename_all = "snake_case")]
pub(super) enum GeometryToml {
    #[default]
    Axisymmetric,
    PlaneStrain,
    PlaneStress,
}

impl DeckFile {
    /// The section every element gets.
    pub(super) fn section(&self) -> Result<Section> {
        let thickness = self.thickness.unwrap_or(1.0);
        if self.geometry == GeometryToml::Axisymmetric {
            if self.thickness.is_some() {
                return Err(Error::input("thickness: only a plane geometry has one (geometry = \"plane_strain\" or \"plane_stress\")"));
            }
            return Ok(Section::Axisymmetric);
        }
        if !(thickness > 0.0 && thickness.is_finite()) {
            return Err(Error::input(format!("thickness = {thickness}: must be a positive length (mm)")));
        }
        Ok(if self.geometry == GeometryToml::PlaneStrain { Section::PlaneStrain { thickness } } else { Section::PlaneStress { thickness } })
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct SectionToml {
    pub(super) elements: String,
    pub(super) material: String,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct StepToml {
    pub(super) name: Option<String>,
    /// "static" (the default) or "harmonic", a linear perturbation about the state before.
    pub(super) procedure: Option<String>,
    /// The harmonic's circumferential mode n.
    pub(super) mode: Option<u32>,
    /// Harmonic steps: contact pairs left out of the step's stiffness.
    pub(super) without_contact: Option<Vec<String>>,
    /// Frequency and buckle steps: how many eigenvalues.
    pub(super) eigenvalues: Option<usize>,
    pub(super) increments: Option<usize>,
    pub(super) temperature: Option<TemperatureToml>,
    #[serde(default)]
    pub(super) boundary: Vec<BoundaryToml>,
    #[serde(default)]
    pub(super) pressure: Vec<PressureToml>,
    /// Concentrated forces on the nodes of node sets.
    #[serde(default)]
    pub(super) force: Vec<ForceToml>,
    /// Body loads on element sets: gravity along the axis or spin about it.
    #[serde(default)]
    pub(super) body_load: Vec<BodyLoadToml>,
    /// Contact pairs whose friction changes from this step on.
    #[serde(default)]
    pub(super) contact_friction: Vec<FrictionChangeToml>,
}

/// `{ pair = "fit", friction = 0.1 }`, with `tangential_penalty` or `elastic_slip` as in a
/// `[[contact]]`; `friction = 0` makes the pair frictionless.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct FrictionChangeToml {
    pub(super) pair: String,
    pub(super) friction: f64,
    pub(super) tangential_penalty: Option<f64>,
    pub(super) elastic_slip: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BodyLoadToml {
    pub(super) elements: String,
    /// Acceleration along +z, mm/s^2 (downward along the axis: -9810).
    pub(super) gravity: Option<f64>,
    /// Angular velocity about the axis, rad/s (the load ramps as its square).
    pub(super) spin: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BoundaryToml {
    pub(super) set: String,
    #[serde(alias = "ux")]
    pub(super) ur: Option<f64>,
    #[serde(alias = "uy")]
    pub(super) uz: Option<f64>,
    /// Harmonic steps: the U_t amplitude, and a ring's rigid motion (mode 1).
    pub(super) ut: Option<f64>,
    pub(super) lateral: Option<f64>,
    pub(super) rotation: Option<f64>,
    /// The z (current, mm) of the axis point the rotation's diameter passes through.
    pub(super) pivot: Option<f64>,
}

/// `{ set = "top", fz = -1000.0 }`: a force on each node of the set, N around the whole ring
/// (as CalculiX's *CLOAD).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct ForceToml {
    pub(super) set: String,
    #[serde(alias = "fx")]
    pub(super) fr: Option<f64>,
    #[serde(alias = "fy")]
    pub(super) fz: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PressureToml {
    pub(super) surface: String,
    pub(super) value: f64,
}

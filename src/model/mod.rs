//! The analysis model as plain data: mesh, named sets and surfaces, materials, sections,
//! boundary conditions, loads and steps. Every reader and generator produces a [`Model`];
//! [`Model::validate`] checks it once, and nothing downstream knows where it came from.
//!
//! Units: mm, N, MPa, degC. Coordinates are (r, z), r >= 0 the radius, z the axis.

pub mod constraint;
mod controls;
pub mod deck;
pub mod fingerprint;
pub mod gmsh;
pub mod heat;
pub mod inp;
pub mod mesh;
pub mod perturbation;
pub mod temperature;
mod validate;

pub use constraint::{Constraint, Term};
pub use mesh::{Edge, Mesh, NODES_PER_ELEMENT};
pub use temperature::Temperature;

use crate::element::solid::ElementGeometry;
use crate::error::{Error, Result};
use crate::fe::quadrature::Integration;
use crate::fe::section::Section;
pub use crate::material::Kinematics;
pub use controls::{Convergence, OutputControls, OutputFields, Precision, Predictor, SteppingControls};
use std::collections::BTreeMap;
use std::path::Path;

/// Reads an input deck by its extension: an Abaqus/CalculiX deck (.inp), with the notes on
/// how it was read (formulations, conventions), or a TOML deck. The model as written: the
/// adjustments that need contact geometry are `preprocess`'s.
pub fn read_deck(path: &Path) -> Result<(Model, Vec<String>)> {
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("inp")) {
        let read = inp::read(path)?;
        Ok((read.model, read.notes))
    } else {
        Ok((deck::read(path)?, Vec::new()))
    }
}

/// A contact pair's default capture distance: twice the longest edge a slave node may meet
/// (the master's, and in a two-pass pair the slave's too).
pub fn default_capture_distance(mesh: &Mesh, slave: &[Edge], master: &[Edge], two_pass: bool) -> f64 {
    let met = if two_pass { slave } else { &[] };
    2.0 * master.iter().chain(met).map(|&e| mesh.edge_length(e)).fold(0.0, f64::max)
}

/// Smallest Young's modulus accepted, MPa: below it the displacements of any load overflow
/// what an engineering model means (and the data are in the wrong units).
pub const MIN_YOUNGS_MODULUS: f64 = 1e-6;

/// Most increments a step may ask for.
pub const MAX_INCREMENTS: usize = 1_000_000;

/// Displacement component in the (r, z) plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Component {
    R = 0,
    Z = 1,
}

impl Component {
    pub fn name(self) -> &'static str {
        match self {
            Component::R => "ur",
            Component::Z => "uz",
        }
    }
}

/// Isotropic material (MPa, 1/degC): elastic (Hencky at finite strain), optionally with
/// J2 plasticity, isotropic hardening (linear or tabulated) and kinematic hardening.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    pub youngs_modulus: f64,
    pub poissons_ratio: f64,
    pub thermal_expansion: f64,
    pub plasticity: Option<Plasticity>,
    /// Backstress terms of kinematic hardening (none: isotropic hardening alone); only with
    /// `plasticity`.
    pub kinematic: KinematicHardening,
    /// Mass density, t/mm^3 (so that N, mm and s stay consistent; steel 7.85e-9); 0 when not
    /// given (only frequency steps need it).
    pub density: f64,
    /// Thermal conductivity, mW/(mm K) (numerically W/(m K); steel about 50); 0 when not
    /// given (only heat steps need it).
    pub conductivity: f64,
}

/// Isotropic hardening of a J2 material: linear, or a piecewise-linear table.
pub use crate::material::Hardening as Plasticity;
pub use crate::material::{Backstress, KinematicHardening};

/// The normal law of a contact pair: a linear penalty eps_n, or CalculiX's exponential
/// pressure-overclosure law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Penalty {
    /// Contact pressure per unit penetration, N/mm^3 (MPa/mm): mesh-independent.
    Stiffness(f64),
    /// Dimensionless kappa: eps_n = kappa E / h, E of the master element's material and h the
    /// length of the master element edge.
    Factor(f64),
    /// p = p0 exp(-ln(100) g / c0) (`contact::node_to_edge::Overclosure::Exponential`): the
    /// pressure p0 (MPa) at touch and the clearance c0 (mm) where it has fallen to p0 / 100.
    Exponential { clearance: f64, pressure: f64 },
}

/// How a pair's constraint is collocated along the slave surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ContactIntegration {
    /// The paper's slide line: the gap at each slave node (nodal collocation).
    NodeToSegment,
    /// The same pointwise gap integrated along the slave surface with each node's shape
    /// function (passes the contact patch test between non-matching quadratic meshes).
    Segment,
}

/// Uzawa augmented-Lagrangian iterations on a pair's contact pressures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AugmentedLagrangian {
    /// Largest penetration (mm) accepted at the end of an increment.
    pub penetration_tolerance: f64,
    /// Multiplier updates allowed per increment.
    pub max_augmentations: usize,
}

/// A penalty contact pair, node-to-segment or integrated, with Coulomb friction where given:
/// the nodes of `slave` against the segments of `master` (and, two-pass, also the reverse).
/// `slave == master` is self-contact.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactPair {
    pub name: String,
    pub slave: String,
    pub master: String,
    pub two_pass: bool,
    pub integration: ContactIntegration,
    pub penalty: Penalty,
    /// Largest distance (mm) at which a slave node is matched to a master segment.
    pub capture_distance: f64,
    pub augmented_lagrangian: Option<AugmentedLagrangian>,
    /// Self-contact: segments within this many segments of a node along the surface are
    /// never its master.
    pub exclude_neighbours: usize,
    /// Coulomb friction; None: frictionless.
    pub friction: Option<Friction>,
    /// Slave nodes moved onto the master before the analysis (see `contact::adjust`).
    pub adjust: Option<Adjust>,
    /// A node-based slave surface (CalculiX's `*SURFACE, TYPE=NODE`): these mesh nodes
    /// (sorted) are the slave points, each bearing with the area of the master face it meets
    /// (CalculiX's rule); None: the slave surface's nodes with their tributary areas.
    pub slave_nodes: Option<Vec<usize>>,
}

/// Which slave nodes a pair's ADJUST moves onto its master.
#[derive(Clone, Debug, PartialEq)]
pub enum Adjust {
    /// Those within this clearance (mm), and every penetrating one.
    Clearance(f64),
    /// Those of this node set.
    NodeSet(String),
}

/// Coulomb friction of a contact pair, regularised by a tangential penalty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// Friction coefficient mu (> 0).
    pub coefficient: f64,
    /// Tangential traction per unit slip in stick, MPa/mm; None: the pair's normal penalty.
    pub tangential_penalty: Option<f64>,
    /// Instead of a fixed penalty, the elastic slip gamma (mm) at which a node reaches the
    /// Coulomb limit: eps_T = mu p / gamma, Abaqus's default form (its slip tolerance times the
    /// element length): the stiffness follows the pressure, and no stiffness needs choosing.
    pub elastic_slip: Option<f64>,
}

impl Friction {
    /// The friction of a deck's `friction`, `tangential_penalty` and `elastic_slip` values
    /// (pair `name`): None for mu = 0; bad input for a negative or non-finite mu, a stiffness
    /// or slip that is not positive, or both of these given.
    pub fn from_values(
        name: &str,
        coefficient: Option<f64>,
        tangential_penalty: Option<f64>,
        elastic_slip: Option<f64>,
    ) -> crate::error::Result<Option<Friction>> {
        let bad = |m: String| crate::error::Error::input(format!("contact '{name}': {m}"));
        match (coefficient, tangential_penalty, elastic_slip) {
            (None, Some(_), _) => Err(bad("tangential_penalty without friction (give friction = mu)".into())),
            (None, _, Some(_)) => Err(bad("elastic_slip without friction (give friction = mu)".into())),
            (None, None, None) => Ok(None),
            (Some(mu), _, _) if !mu.is_finite() || mu < 0.0 => Err(bad(format!("friction coefficient {mu}: give mu >= 0"))),
            (Some(_), Some(_), Some(_)) => Err(bad("give tangential_penalty (MPa/mm) or elastic_slip (mm), not both".into())),
            (Some(_), Some(k), _) if !k.is_finite() || k <= 0.0 => Err(bad(format!("tangential_penalty {k}: give a positive stiffness (MPa/mm)"))),
            (Some(_), _, Some(g)) if !g.is_finite() || g <= 0.0 => Err(bad(format!("elastic_slip {g}: give a positive slip (mm)"))),
            // mu = 0: frictionless
            (Some(mu), k, g) => Ok((mu > 0.0).then_some(Friction { coefficient: mu, tangential_penalty: k, elastic_slip: g })),
        }
    }
}

/// A displacement prescribed on every node of a node set; `value` is reached at the end of
/// the step, ramped linearly from the value at the step's start.
#[derive(Clone, Debug, PartialEq)]
pub struct PrescribedDisplacement {
    pub node_set: String,
    pub component: Component,
    pub value: f64,
}

/// A uniform pressure (MPa) on a surface, positive pushing into the body; its `value` is
/// reached at the end of the step, ramped from the value at the step's start.
#[derive(Clone, Debug, PartialEq)]
pub struct Pressure {
    pub surface: String,
    pub value: f64,
}

/// A concentrated force on a node (N per radian: the ring's total over 2 pi), reached at the
/// end of the step, ramped from its value at the step's start; a dead load.
#[derive(Clone, Debug, PartialEq)]
pub struct NodalForce {
    pub node: usize,
    pub component: Component,
    pub value: f64,
}

/// One step of the analysis, of one procedure. A model keeps its steps in one list, in the
/// order they run: heat steps first (the last one's temperature field is the general steps'),
/// then the general steps, then the linear perturbation steps about the last general step's end.
#[derive(Clone, Debug)]
pub enum Step {
    /// Steady heat conduction.
    Heat(heat::HeatStep),
    /// A general (nonlinear static) step: the results file's increments and step numbers.
    General(GeneralStep),
    /// A linear perturbation: a harmonic response, buckling or natural frequencies.
    Perturbation(perturbation::Perturbation),
}

impl Step {
    pub fn name(&self) -> &str {
        match self {
            Step::Heat(h) => &h.name,
            Step::General(g) => &g.name,
            Step::Perturbation(p) => &p.name,
        }
    }

    /// The procedure's name in the deck's terms, for messages.
    pub fn procedure(&self) -> &'static str {
        match self {
            Step::Heat(_) => "heat",
            Step::General(_) => "general",
            Step::Perturbation(_) => "perturbation",
        }
    }
}

/// A general load step: targets at its end, reached in `increments` equal increments. What a
/// step does not mention keeps its value from the previous step (constraints persist, as in
/// Abaqus).
#[derive(Clone, Debug, PartialEq)]
pub struct GeneralStep {
    pub name: String,
    pub increments: usize,
    pub displacements: Vec<PrescribedDisplacement>,
    pub pressures: Vec<Pressure>,
    /// Nodal forces at the end of the step (ramped from the previous step's, per node and
    /// component).
    pub nodal_forces: Vec<NodalForce>,
    /// Temperature (degC) at the end of the step, ramped from the step's start; `None` keeps
    /// the previous one.
    pub temperature: Option<Temperature>,
    /// The input deck's total time at the start and end of the step (CalculiX/Abaqus *STATIC
    /// periods), for the history's `time`; `None`: step k spans the time k - 1 to k.
    pub time_span: Option<[f64; 2]>,
    /// Body loads at the end of the step (ramped from the previous step's, per element set).
    pub body_loads: Vec<BodyLoad>,
    /// The prescribed displacements of earlier steps that this one does not restate are
    /// released at its start (CalculiX's *BOUNDARY, OP=NEW).
    pub release_constraints: bool,
    /// Only the history is written in this step, no field output (CalculiX's FREQUENCY=0).
    pub without_field_output: bool,
    /// Contact pairs whose friction changes at the step's start, for this step and the
    /// following ones (CalculiX's *CHANGE FRICTION).
    pub friction_changes: Vec<FrictionChange>,
}

impl GeneralStep {
    /// A step that prescribes `displacements` in `increments` increments and nothing else:
    /// no pressure, force or body load, the temperature kept, field output written.
    pub fn new(name: &str, increments: usize, displacements: Vec<PrescribedDisplacement>) -> Self {
        GeneralStep {
            name: name.into(),
            increments,
            displacements,
            pressures: Vec::new(),
            nodal_forces: Vec::new(),
            temperature: None,
            time_span: None,
            body_loads: Vec::new(),
            release_constraints: false,
            without_field_output: false,
            friction_changes: Vec::new(),
        }
    }
}

/// A pair's friction from a step on: `None` makes it frictionless.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionChange {
    pub pair: String,
    pub friction: Option<Friction>,
}

/// A body load on an element set: gravity along the axis or spin about it, its value at the
/// end of the step.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyLoad {
    pub elements: String,
    pub force: crate::element::body_load::BodyForce,
}

#[derive(Clone, Debug)]
pub struct Model {
    pub mesh: Mesh,
    pub node_sets: BTreeMap<String, Vec<usize>>,
    pub element_sets: BTreeMap<String, Vec<usize>>,
    pub surfaces: BTreeMap<String, Vec<Edge>>,
    pub materials: Vec<Material>,
    /// Material index of every element.
    pub element_material: Vec<usize>,
    /// Section of every element: axisymmetric, or a plane section with its thickness.
    pub element_section: Vec<Section>,
    /// Integration of every element: full, or a Q8's reduced 2 x 2 (an .inp deck's ..8R types).
    pub element_integration: Vec<Integration>,
    /// Temperature (degC) at which thermal strain is zero, and the initial temperature (a
    /// field where it varies from node to node).
    pub reference_temperature: Temperature,
    /// Finite strains and rotations with follower pressure (NLGEOM), or small strain.
    pub kinematics: Kinematics,
    pub stepping: SteppingControls,
    /// What the results file keeps of each increment.
    pub output: OutputControls,
    pub contacts: Vec<ContactPair>,
    /// Linear multi-point constraints, in force in every step.
    pub constraints: Vec<Constraint>,
    /// Every step, in the order they run (see [`Step`]).
    pub steps: Vec<Step>,
    /// The text the model was read from, kept for the output file.
    pub source_text: String,
    /// The files it was read from (the deck, its mesh, its includes): a run never writes over
    /// them.
    pub source_files: Vec<std::path::PathBuf>,
    /// Also write reactions per segment of this angle (degrees): 2 for CalculiX/Abaqus decks,
    /// whose axisymmetric reactions are per 2-degree segment.
    pub reaction_segment_degrees: Option<f64>,
}

impl Model {
    /// A model of `mesh` alone, the rest to fill: no sets, materials, contacts, constraints or
    /// steps; every element axisymmetric, fully integrated, of material 0; a uniform 20 degC;
    /// finite kinematics; the default stepping and output controls.
    pub fn on_mesh(mesh: Mesh) -> Model {
        let n = mesh.elements.len();
        Model {
            mesh,
            node_sets: BTreeMap::new(),
            element_sets: BTreeMap::new(),
            surfaces: BTreeMap::new(),
            materials: Vec::new(),
            element_material: vec![0; n],
            element_section: vec![Section::Axisymmetric; n],
            element_integration: vec![Integration::Full; n],
            reference_temperature: Temperature::Uniform(20.0),
            kinematics: Kinematics::Finite,
            stepping: SteppingControls::default(),
            output: OutputControls::default(),
            contacts: Vec::new(),
            constraints: Vec::new(),
            steps: Vec::new(),
            source_text: String::new(),
            source_files: Vec::new(),
            reaction_segment_degrees: None,
        }
    }

    /// Whether some element is axisymmetric: forces are then per radian (a plane model's are
    /// over its thickness).
    pub fn is_axisymmetric(&self) -> bool {
        self.element_section.iter().any(|s| s.is_axisymmetric())
    }

    /// The geometry of element `e` with nodal coordinates `x` (reference or current), of its
    /// shape, integration and section.
    pub fn element_geometry(&self, e: usize, x: &[[f64; 2]; 8]) -> std::result::Result<ElementGeometry, String> {
        ElementGeometry::new(self.mesh.shape(e), self.element_integration[e], self.element_section[e], x)
    }

    /// The general steps, in order: the results file's steps are numbered by them alone.
    pub fn general_steps(&self) -> impl Iterator<Item = &GeneralStep> + Clone {
        self.steps.iter().filter_map(|s| match s {
            Step::General(g) => Some(g),
            _ => None,
        })
    }

    /// General step `k` (0-based, the results file's step k + 1).
    pub fn general_step(&self, k: usize) -> &GeneralStep {
        self.general_steps().nth(k).expect("a general step of the model")
    }

    pub fn general_step_count(&self) -> usize {
        self.general_steps().count()
    }

    pub fn heat_steps(&self) -> impl Iterator<Item = &heat::HeatStep> {
        self.steps.iter().filter_map(|s| match s {
            Step::Heat(h) => Some(h),
            _ => None,
        })
    }

    pub fn perturbations(&self) -> impl Iterator<Item = &perturbation::Perturbation> {
        self.steps.iter().filter_map(|s| match s {
            Step::Perturbation(p) => Some(p),
            _ => None,
        })
    }

    /// Replaces the model's perturbation steps by `perturbations` (after the general steps).
    pub fn set_perturbations(&mut self, perturbations: impl IntoIterator<Item = perturbation::Perturbation>) {
        self.steps.retain(|s| !matches!(s, Step::Perturbation(_)));
        self.steps.extend(perturbations.into_iter().map(Step::Perturbation));
    }

    /// Whether some material has kinematic hardening (its points carry backstresses).
    pub fn has_kinematic_hardening(&self) -> bool {
        self.materials.iter().any(|m| !m.kinematic.is_empty())
    }

    /// Whether the temperature varies over the mesh at the start or in some step.
    pub fn has_temperature_field(&self) -> bool {
        std::iter::once(&self.reference_temperature).chain(self.general_steps().filter_map(|s| s.temperature.as_ref())).any(|t| t.uniform().is_none())
    }

    /// The friction of every contact pair (in `contacts` order) in step `step`: the pair's
    /// own, changed by the friction changes of that step and the steps before it.
    pub fn friction_in_step(&self, step: usize) -> Vec<Option<Friction>> {
        let mut friction: Vec<Option<Friction>> = self.contacts.iter().map(|c| c.friction).collect();
        for change in self.general_steps().take(step + 1).flat_map(|s| &s.friction_changes) {
            if let Some(p) = self.contacts.iter().position(|c| c.name == change.pair) {
                friction[p] = change.friction;
            }
        }
        friction
    }

    /// Whether contact pair `pair` has friction in some step.
    pub fn pair_has_friction(&self, pair: usize) -> bool {
        self.contacts[pair].friction.is_some()
            || self.general_steps().flat_map(|s| &s.friction_changes).any(|c| c.pair == self.contacts[pair].name && c.friction.is_some())
    }

    pub fn node_set(&self, name: &str) -> Result<&[usize]> {
        self.node_sets
            .get(name)
            .map(|v| v.as_slice())
            .ok_or_else(|| Error::input(format!("unknown node set '{name}' (known: {})", known(self.node_sets.keys()))))
    }

    pub fn element_set(&self, name: &str) -> Result<&[usize]> {
        self.element_sets
            .get(name)
            .map(|v| v.as_slice())
            .ok_or_else(|| Error::input(format!("unknown element set '{name}' (known: {})", known(self.element_sets.keys()))))
    }

    pub fn surface(&self, name: &str) -> Result<&[Edge]> {
        self.surfaces.get(name).map(|v| v.as_slice()).ok_or_else(|| Error::input(format!("unknown surface '{name}' (known: {})", known(self.surfaces.keys()))))
    }

    /// The edges of contact surface `name`: its faces, and where it is a pair's node-based
    /// slave (`ContactPair::slave_nodes`) also the free faces holding two or three of those
    /// nodes, so that a node of the set on a face with a corner outside it (a mid-side node)
    /// has a face for its normal.
    pub fn contact_edges(&self, name: &str) -> Vec<Edge> {
        let mut edges = self.surfaces[name].clone();
        for nodes in self.contacts.iter().filter(|c| c.slave == name).filter_map(|c| c.slave_nodes.as_ref()) {
            let holds = |e: &Edge| self.mesh.edge_nodes(*e).iter().filter(|n| nodes.binary_search(n).is_ok()).count() >= 2;
            edges.extend(self.mesh.free_edges().into_iter().filter(holds));
        }
        edges.sort();
        edges.dedup();
        edges
    }
}

fn known<'a>(names: impl Iterator<Item = &'a String>) -> String {
    let v: Vec<&str> = names.map(|s| s.as_str()).collect();
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

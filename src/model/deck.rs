//! The TOML input deck. Unknown keys are rejected; units are mm, N, MPa, degC.
//!
//! ```toml
//! reference_temperature = 20.0      # degC, zero thermal strain; also the initial temperature
//!                                   # (or a field: [{ value = 20.0 }, { set = "hot", value = 80.0 }])
//! nlgeom = true                     # finite strain + follower pressure (default); false: small
//! geometry = "axisymmetric"         # (r, z) about the z axis, per radian (default); or a plane
//! # geometry = "plane_strain"       # slice (x, y) of a long body, or "plane_stress": a thin plate,
//! # thickness = 1.0                 # mm, of the plane slice (default 1)
//!
//! [stepping]                        # optional; defaults shown
//! cutback_factor = 0.5              # increment x this after a failed attempt
//! growth_factor = 1.5               # increment x this after an easy one (never past the request)
//! easy_iterations = 4               # "easy" = converged within this many Newton iterations
//! min_increment = 1e-5              # fraction of the step; below it the run stops (exit 3)
//! max_newton_iterations = 25
//! predictor = "extrapolate"         # the last increment scaled; "tangent"; "none"
//! convergence = "field"            # CalculiX's / Abaqus's field test; "residual": ||F|| / ||F0|| <= 1e-10
//!
//! [output]                         # optional
//! every = 1                         # fields of every N-th increment (and the last of each step)
//! fields = ["stress", "von_mises", "plastic_strain", "temperature", "contact"]  # default: all
//!
//! [mesh]
//! file = "cylinder.msh"             # Gmsh 4.1 or 2.2 ASCII, relative to the deck; or instead:
//! # rectangle = { r = [100.0, 130.0], z = [0.0, 10.0], divisions = [12, 2] }
//! # or separate bodies, sets prefixed by the block name (tube, tube_inner, tube_top, ...):
//! # [[mesh.block]]
//! # name = "tube"
//! # r = [100.0, 110.0]
//! # z = [0.0, 50.0]
//! # divisions = [4, 25]
//! # grading = [1.0, 0.2]          # last/first element size along r and z (optional)
//!
//! [[material]]
//! name = "steel"
//! model = "j2"                      # or "elastic"
//! youngs_modulus = 200000.0         # MPa
//! poissons_ratio = 0.3
//! thermal_expansion = 1.2e-5        # 1/degC
//! yield_stress = 300.0              # MPa, j2 only
//! hardening_modulus = 1000.0        # MPa, j2 only (default 0: perfectly plastic)
//!
//! [[section]]                       # optional when there is a single material
//! elements = "all"
//! material = "steel"
//!
//! [[contact]]                       # a penalty contact pair, optional
//! slave = "inner_tube_outside"      # surfaces (physical curves); slave == master: self-contact
//! master = "outer_tube_bore"
//! two_pass = false                  # true: symmetric, each surface also slave of the other
//! integration = "segment"           # gap integrated along the slave surface (default), or
//!                                   # "node-to-segment": the paper's nodal slide line
//! penalty = 1.0e5                   # N/mm^3 (MPa per mm of penetration); or instead
//! # penalty_factor = 10.0           # kappa: eps = kappa E / h (master E and edge length h)
//! # exponential = { clearance = 1e-4, pressure = 0.1 }  # or CalculiX's p = p0 exp(-ln(100) g / c0),
//!                                   # c0 mm, p0 MPa (node-to-segment pairs)
//! capture_distance = 1.0            # mm (default: twice the longest edge a slave node may meet)
//! augmented_lagrangian = { penetration_tolerance = 1e-4, max_augmentations = 10 }  # optional
//! exclude_neighbours = 2            # self-contact: segments this close along the surface
//! friction = 0.2                    # Coulomb's mu (optional; default frictionless)
//! tangential_penalty = 1.0e5        # MPa/mm of slip in stick (default: the normal penalty)
//! # elastic_slip = 0.005            # or: mm of slip at the Coulomb limit, eps_T = mu p / gamma
//! adjust = 0.01                     # optional: before the analysis, move the slave nodes within
//!                                   # 0.01 mm of the master (and all penetrating) onto it, or
//!                                   # adjust = "node_set": those of a set (CalculiX's ADJUST)
//!
//! [[step]]
//! name = "load"
//! increments = 1
//! temperature = 20.0                # degC at the end of the step (optional); or on node sets,
//!                                   # the others keeping theirs: [{ set = "bore", value = 150.0 }]
//! boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 } ]
//! pressure = [ { surface = "inner", value = 50.0 } ]
//! force = [ { set = "tip", fz = -1000.0 } ]  # N around the whole ring, on each node of the set
//! contact_friction = [ { pair = "fit", friction = 0.1 } ]  # from this step on (optional;
//!                                   # tangential_penalty / elastic_slip as in [[contact]])
//! ```

mod schema;
mod steps;

use super::constraint::{default_tie_tolerance, tie};
use super::mesh::{blocks, rectangle, split_into_triangles, Block, MeshSets};
use super::{
    default_capture_distance, gmsh, Adjust, AugmentedLagrangian, ContactIntegration, ContactPair, Friction, KinematicHardening, Kinematics, Material, Model,
    OutputControls, OutputFields, Penalty, Plasticity, Pressure, Step,
};
use crate::error::{Error, Result};
use crate::fe::quadrature::Integration;
use schema::{AdjustToml, DeckFile, GeometryToml, IntegrationToml, MaterialKind};
use std::path::Path;

/// A TOML error on one line, naming the line and the key (with its table) where there is one:
/// `deck.toml:2: [stepping] cutback_factor: invalid type: string "half", expected f64`; `doc`
/// names the page that lists the keys (for an error with no place in the text).
pub(crate) fn toml_error(path: &Path, text: &str, e: &toml::de::Error, doc: &str) -> Error {
    let message = e.message().trim().replace('\n', " ");
    let Some(span) = e.span().filter(|s| s.start > 0 || !message.starts_with("missing field")) else {
        return Error::input(format!("{}: {message} (see {doc})", path.display()));
    };
    let line_no = text[..span.start.min(text.len())].matches('\n').count() + 1;
    let line = text.lines().nth(line_no - 1).unwrap_or("").trim();
    let table = text.lines().take(line_no).filter(|l| l.trim_start().starts_with('[')).last().map(|l| format!("{} ", l.trim())).unwrap_or_default();
    match line.split_once('=').map(|(key, _)| key.trim()).filter(|k| !k.is_empty() && !k.starts_with('[')) {
        Some(key) => Error::input(format!("{}:{line_no}: {table}{key}: {message}", path.display())),
        None if line.is_empty() => Error::input(format!("{}:{line_no}: {message}", path.display())),
        None => Error::input(format!("{}:{line_no}: {line}: {message}", path.display())),
    }
}

/// Reads and validates a deck file.
/// The deck's ties as linear constraints, each tying at least one node.
fn ties(deck: &DeckFile, mesh: &super::Mesh, surfaces: &std::collections::BTreeMap<String, Vec<super::Edge>>) -> Result<Vec<super::constraint::Constraint>> {
    let mut constraints = Vec::new();
    for t in &deck.tie {
        let name = t.name.clone().unwrap_or_else(|| format!("{}-{}", t.slave, t.master));
        let edges = |s: &String| surfaces.get(s).map(|v| v.as_slice()).ok_or_else(|| Error::input(format!("tie '{name}': unknown surface '{s}'")));
        let (slave, master) = (edges(&t.slave)?, edges(&t.master)?);
        let tolerance = match t.tolerance {
            Some(v) if v > 0.0 && v.is_finite() => v,
            Some(v) => return Err(Error::input(format!("tie '{name}': tolerance {v}: give a distance > 0 (mm)"))),
            None => default_tie_tolerance(mesh, master),
        };
        let (tied, count, _) = tie(mesh, &vec![deck.section()?; mesh.elements.len()], &name, slave, master, tolerance);
        if count == 0 {
            return Err(Error::input(format!("tie '{name}': no node of '{}' lies within {tolerance:.3e} mm of '{}'", t.slave, t.master)));
        }
        constraints.extend(tied);
    }
    Ok(constraints)
}

/// The deck's materials, by name, each checked.
fn materials(deck: &DeckFile, path: &Path) -> Result<Vec<Material>> {
    let mut materials = Vec::new();
    for m in &deck.material {
        if materials.iter().any(|x: &Material| x.name == m.name) {
            return Err(Error::input(format!("material '{}' is defined twice", m.name)));
        }
        let plasticity = match (m.model, m.yield_stress) {
            (MaterialKind::Elastic, None) if m.hardening_modulus.is_none() => None,
            (MaterialKind::Elastic, _) => return Err(Error::input(format!("material '{}': yield_stress and hardening_modulus need model = \"j2\"", m.name))),
            (MaterialKind::J2, None) => return Err(Error::input(format!("material '{}': model = \"j2\" needs yield_stress (MPa)", m.name))),
            (MaterialKind::J2, Some(yield_stress)) => Some(Plasticity::linear(yield_stress, m.hardening_modulus.unwrap_or(0.0))),
        };
        // a heat deck needs no elastic constants: NaN marks them unused (`validate` skips them)
        let heat = deck.step.iter().any(|s| s.procedure.as_deref() == Some("heat"));
        let elastic = |value: Option<f64>, key: &str| match (value, heat) {
            (Some(v), _) => Ok(v),
            (None, true) => Ok(f64::NAN),
            (None, false) => Err(Error::input(format!("material '{}': missing {key}", m.name))),
        };
        if !m.backstresses.is_empty() && plasticity.is_none() {
            return Err(Error::input(format!("material '{}': backstresses need model = \"j2\" and its yield_stress", m.name)));
        }
        let kinematic = KinematicHardening::new(&m.backstresses).map_err(|e| Error::input(format!("material '{}': {e}", m.name)))?;
        materials.push(Material {
            name: m.name.clone(),
            youngs_modulus: elastic(m.youngs_modulus, "youngs_modulus (MPa)")?,
            poissons_ratio: elastic(m.poissons_ratio, "poissons_ratio")?,
            thermal_expansion: m.thermal_expansion,
            plasticity,
            kinematic,
            density: m.density,
            conductivity: m.conductivity.unwrap_or(0.0),
        });
    }
    if materials.is_empty() {
        return Err(Error::input(format!("{}: no [[material]] defined", path.display())));
    }
    Ok(materials)
}

/// Each element's material (an index into `materials`), from the sections (the one material
/// everywhere without any).
fn element_materials(
    deck: &DeckFile,
    materials: &[Material],
    mesh: &super::Mesh,
    element_sets: &std::collections::BTreeMap<String, Vec<usize>>,
) -> Result<Vec<usize>> {
    let mut element_material = vec![usize::MAX; mesh.elements.len()];
    if deck.section.is_empty() && materials.len() == 1 {
        element_material.fill(0);
    }
    for s in &deck.section {
        let mat = materials
            .iter()
            .position(|m| m.name == s.material)
            .ok_or_else(|| Error::input(format!("section on '{}': unknown material '{}'", s.elements, s.material)))?;
        let elems = element_sets.get(&s.elements).ok_or_else(|| {
            Error::input(format!("section: unknown element set '{}' (known: {})", s.elements, element_sets.keys().cloned().collect::<Vec<_>>().join(", ")))
        })?;
        for &e in elems {
            element_material[e] = mat;
        }
    }
    if let Some(e) = element_material.iter().position(|&m| m == usize::MAX) {
        return Err(Error::input(format!("element {} has no material: add a [[section]] covering it", mesh.element_ids[e])));
    }
    Ok(element_material)
}

pub fn read(path: &Path) -> Result<Model> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Read { path: path.to_path_buf(), source })?;
    parse(&text, path)
}

/// Parses deck `text`; `path` names it in messages and anchors relative mesh paths.
pub fn parse(text: &str, path: &Path) -> Result<Model> {
    let deck: DeckFile = toml::from_str(text).map_err(|e| toml_error(path, text, &e, "docs/deck.md"))?;
    let mut source_files = vec![path.to_path_buf()];
    let (mesh, sets) = match (&deck.mesh.file, &deck.mesh.rectangle, deck.mesh.block.is_empty()) {
        (Some(file), None, true) => {
            let full = path.parent().unwrap_or(Path::new(".")).join(file);
            source_files.push(full.clone());
            gmsh::read(&full)?
        }
        (None, Some(r), true) => {
            let (mesh, sets) = rectangle(r.r, r.z, r.divisions)?;
            if r.triangles {
                split_into_triangles(&mesh, &sets)
            } else {
                (mesh, sets)
            }
        }
        (None, None, false) => {
            let specs: Vec<Block> = deck
                .mesh
                .block
                .iter()
                .map(|b| Block { name: b.name.clone(), r: b.r, z: b.z, divisions: b.divisions, grading: b.grading, triangles: b.triangles })
                .collect();
            blocks(&specs)?
        }
        _ => return Err(Error::input(format!("{}: [mesh] needs exactly one of `file`, `rectangle` or [[mesh.block]]", path.display()))),
    };
    let MeshSets { node_sets, element_sets, surfaces } = sets;

    let materials = materials(&deck, path)?;
    let element_material = element_materials(&deck, &materials, &mesh, &element_sets)?;

    let reference_temperature = deck.reference_temperature.field(&mesh, &node_sets, None, "reference_temperature")?;
    let mut temperature_now = reference_temperature.clone();
    let mut steps = Vec::new();
    let plane = deck.geometry != GeometryToml::Axisymmetric;
    for (k, s) in deck.step.iter().enumerate() {
        let name = s.name.clone().unwrap_or_else(|| format!("step-{}", k + 1));
        let pressures: Vec<Pressure> = s.pressure.iter().map(|p| Pressure { surface: p.surface.clone(), value: p.value }).collect();
        match s.procedure.as_deref().unwrap_or("static") {
            // in the deck's order (the model's validation holds them to the order they run in)
            "static" => steps.push(Step::General(steps::general(s, name, pressures, &mesh, &node_sets, plane, &mut temperature_now)?)),
            procedure @ ("harmonic" | "frequency" | "buckle") => steps.push(Step::Perturbation(steps::perturbation(s, name, pressures, procedure)?)),
            "heat" => steps.push(Step::Heat(steps::heat(s, &name)?)),
            other => {
                return Err(Error::input(format!(
                    "step '{name}': procedure {other:?} is not one of \"static\", \"harmonic\", \"frequency\", \"buckle\", \"heat\""
                )))
            }
        }
    }

    let contacts = contact_pairs(&deck, &mesh, &surfaces)?;
    let constraints = ties(&deck, &mesh, &surfaces)?;
    let kinematics = if deck.nlgeom { Kinematics::Finite } else { Kinematics::Small };
    let section = deck.section()?;
    let n_elements = mesh.elements.len();
    let model = Model {
        mesh,
        node_sets,
        element_sets,
        surfaces,
        materials,
        element_material,
        element_section: vec![section; n_elements],
        element_integration: vec![Integration::Full; n_elements],
        reference_temperature,
        kinematics,
        stepping: deck.stepping.controls(),
        output: OutputControls {
            every: deck.output.every.unwrap_or(1),
            fields: deck.output.fields.as_deref().map(OutputFields::from_names).transpose()?.unwrap_or(OutputFields::DEFAULT),
            precision: deck.output.precision.unwrap_or_default(),
        },
        contacts,
        constraints,
        steps,
        source_text: text.to_string(),
        source_files,
        reaction_segment_degrees: None,
    };
    model.validate()?;
    Ok(model)
}

/// The deck's contact pairs, their penalties, capture distances and friction read.
fn contact_pairs(deck: &DeckFile, mesh: &super::Mesh, surfaces: &std::collections::BTreeMap<String, Vec<super::Edge>>) -> Result<Vec<ContactPair>> {
    let mut contacts = Vec::new();
    for c in &deck.contact {
        let name = c.name.clone().unwrap_or_else(|| if c.slave == c.master { c.slave.clone() } else { format!("{}-{}", c.slave, c.master) });
        let penalty = match (c.penalty, c.penalty_factor, &c.exponential) {
            (Some(v), None, None) => Penalty::Stiffness(v),
            (None, Some(v), None) => Penalty::Factor(v),
            (None, None, Some(e)) => Penalty::Exponential { clearance: e.clearance, pressure: e.pressure },
            _ => {
                return Err(Error::input(format!(
                    "contact '{name}': give exactly one of penalty (N/mm^3), penalty_factor (kappa in eps = kappa E / h) or exponential = {{ clearance = c0, pressure = p0 }}"
                )))
            }
        };
        let capture_distance = match c.capture_distance {
            Some(d) => d,
            None => {
                let edges = |s: &String| surfaces.get(s).map(|v| v.as_slice()).ok_or_else(|| Error::input(format!("contact '{name}': unknown surface '{s}'")));
                let (master, slave) = (edges(&c.master)?, edges(&c.slave)?);
                default_capture_distance(mesh, slave, master, c.two_pass)
            }
        };
        let augmented_lagrangian = c
            .augmented_lagrangian
            .as_ref()
            .map(|a| AugmentedLagrangian { penetration_tolerance: a.penetration_tolerance, max_augmentations: a.max_augmentations });
        let friction = Friction::from_values(&name, c.friction, c.tangential_penalty, c.elastic_slip)?;
        contacts.push(ContactPair {
            name,
            slave: c.slave.clone(),
            master: c.master.clone(),
            two_pass: c.two_pass,
            integration: match c.integration {
                IntegrationToml::Segment => ContactIntegration::Segment,
                IntegrationToml::NodeToSegment => ContactIntegration::NodeToSegment,
            },
            penalty,
            capture_distance,
            augmented_lagrangian,
            exclude_neighbours: c.exclude_neighbours,
            friction,
            adjust: c.adjust.as_ref().map(|a| match a {
                AdjustToml::Clearance(v) => Adjust::Clearance(*v),
                AdjustToml::NodeSet(s) => Adjust::NodeSet(s.clone()),
            }),
            slave_nodes: None,
        });
    }
    Ok(contacts)
}

//! Abaqus/CalculiX input decks (`.inp`): the subset that axisymmetric contact models use,
//! read into a [`Model`]. Anything outside the subset is an error naming the keyword, the file
//! and the line; every place where slideline's model differs from the deck's words (element
//! formulation, contact algorithm, output requests, force convention) becomes a note that the
//! run prints.
//!
//! Read: *HEADING, *NODE, *ELEMENT (CAX8, CAX8R, CAX6, CAX4, CAX4R, CAX3), *NSET/*ELSET (GENERATE),
//! *SURFACE (element faces S1..S4, or nodes), *MATERIAL with *ELASTIC, *PLASTIC, *EXPANSION
//! (ZERO), *DENSITY, *SOLID SECTION, *BOUNDARY, *DLOAD (P1..P4), *INITIAL CONDITIONS
//! (TEMPERATURE), *TEMPERATURE, *AMPLITUDE, *SURFACE INTERACTION, *SURFACE BEHAVIOR
//! (PRESSURE-OVERCLOSURE=LINEAR), *FRICTION, *CONTACT PAIR (ADJUST), *STEP (NLGEOM), *STATIC,
//! *END STEP, *INCLUDE, and the output requests (*NODE PRINT, *EL FILE, ...), which slideline
//! answers by writing every field at every increment.
//!
//! CalculiX's axisymmetric convention: reaction forces are per 2-degree segment (the element
//! is expanded over 2 degrees); results files of an .inp run carry reactions per radian, per
//! ring and per 2-degree segment (columns `..._2deg`).

pub mod cards;
mod constraints;
mod expand;
mod finish;
mod loads;
mod mesh;
mod model_cards;
mod properties;
mod steps;
mod write;

pub use write::{to_inp, write};

use super::mesh::{Edge, Mesh};
use super::{Component, Model, Predictor};
use crate::error::{Error, Result};
use crate::fe::quadrature::Integration;
use crate::fe::section::Section;
use cards::{Card, DataLine, Location};
use properties::ListedPair;
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::Path;

/// Angle (degrees) of the segment CalculiX reports axisymmetric reactions for.
pub const CALCULIX_SEGMENT_DEGREES: f64 = 2.0;

/// A model read from an input deck, with the notes on how it was read.
pub struct InpModel {
    pub model: Model,
    pub notes: Vec<String>,
}

/// Reads `path` (and its includes).
pub fn read(path: &Path) -> Result<InpModel> {
    let cards = cards::read(path)?;
    if cards.is_empty() {
        return Err(Error::input(format!(
            "{}: the deck is empty (no keyword card: an .inp deck is *NODE, *ELEMENT, *MATERIAL, ... and a *STEP)",
            path.display()
        )));
    }
    let text = std::fs::read_to_string(path).map_err(|source| Error::Read { path: path.to_path_buf(), source })?;
    build(&cards, text)
}

/// Parses deck `text`; `path` names it in messages and anchors includes.
pub fn parse(text: &str, path: &Path) -> Result<InpModel> {
    let mut cards = Vec::new();
    cards::parse_into(text, path, &mut cards, 0)?;
    build(&cards, text.to_string())
}

const OUTPUT_REQUESTS: &[&str] = &[
    "NODE PRINT",
    "EL PRINT",
    "NODE FILE",
    "EL FILE",
    "NODE OUTPUT",
    "ELEMENT OUTPUT",
    "OUTPUT",
    "CONTACT PRINT",
    "CONTACT FILE",
    "CONTACT OUTPUT",
    "RESTART",
];

struct MaterialDef {
    name: String,
    at: Location,
    elastic: Option<(f64, f64)>,
    expansion: f64,
    /// *DENSITY, t/mm^3 (0 without), and where it was given.
    density: f64,
    density_at: Option<Location>,
    plastic: Vec<(f64, f64)>,
    plastic_at: Option<Location>,
    /// HARDENING=KINEMATIC: the *PLASTIC curve is the kinematic hardening curve.
    kinematic: bool,
    /// *CONDUCTIVITY (0 without): heat steps use it.
    conductivity: f64,
}

struct Interaction {
    /// *SURFACE BEHAVIOR: the LINEAR slope (`Penalty::Stiffness`, MPa/mm) or the EXPONENTIAL
    /// law, as one pass carrying the whole force.
    behaviour: Option<crate::model::Penalty>,
    /// *FRICTION: mu and the stick slope (MPa/mm), if given.
    friction: properties::CalculixFriction,
}

/// A displacement, pressure or temperature target of a step, optionally through an amplitude.
#[derive(Clone)]
struct Target<K> {
    key: K,
    value: f64,
    amplitude: Option<String>,
}

impl<K> Target<K> {
    /// The value at step time `time`: through the amplitude, or ramped from `before`.
    fn at(&self, before: f64, time: f64, period: f64, amplitudes: &BTreeMap<String, Vec<(f64, f64)>>) -> f64 {
        match &self.amplitude {
            Some(a) => self.value * interpolate(&amplitudes[a], time),
            None => before + (self.value - before) * time / period,
        }
    }
}

struct StepDef {
    name: String,
    at: Location,
    nlgeom: Option<bool>,
    initial: f64,
    period: f64,
    minimum: Option<f64>,
    boundaries: Vec<Target<(String, Component)>>,
    pressures: Vec<Target<String>>,
    /// *CLOAD: (node, component) -> force per radian; with OP=NEW, earlier ones not restated
    /// are removed.
    cloads: Vec<Target<(usize, Component)>>,
    new_cloads: bool,
    /// *DLOAD GRAV and CENTRIF: (element set, spin) -> g along the axis, or omega^2.
    body: Vec<Target<(String, bool)>>,
    /// *TEMPERATURE lines in order: (their nodes, the value at the step's end).
    temperature: Vec<Target<Vec<usize>>>,
    /// *DLOAD, OP=NEW: loads of earlier steps not restated are removed.
    new_loads: bool,
    /// *BOUNDARY, OP=NEW on the step's first *BOUNDARY card: earlier constraints not restated
    /// are released; and whether a *BOUNDARY card was read in the step.
    new_boundaries: bool,
    boundary_cards: usize,
    /// The step's file output requests (*NODE FILE, *EL FILE, *CONTACT FILE): [with
    /// FREQUENCY=0, with another frequency]; only zeros mean no field output in the step.
    file_requests: [usize; 2],
    /// A procedure card (*STATIC) was read.
    has_procedure: bool,
    /// The time points its output requests name: (times, in total time).
    time_points: Vec<(Vec<f64>, bool)>,
    /// A *HEAT TRANSFER step, and the temperatures it holds (*BOUNDARY, degree of freedom 11):
    /// (node set, degC) in order.
    heat: bool,
    held_temperatures: Vec<(String, f64)>,
    /// *CHANGE FRICTION: (interaction, its new mu and stick slope), from this step on.
    friction_changes: Vec<(String, properties::CalculixFriction)>,
}

/// A temperature line: its nodes and the value, degC.
type NodeTemperatures = (Vec<usize>, f64);

#[derive(Default)]
struct Builder {
    mesh: Mesh,
    node_index: HashMap<u64, usize>,
    element_index: HashMap<u64, usize>,
    /// Mid-side nodes added to CAX4 elements, by their corner pair.
    added_midside: HashMap<(usize, usize), usize>,
    node_sets: BTreeMap<String, Vec<usize>>,
    element_sets: BTreeMap<String, Vec<usize>>,
    surfaces: BTreeMap<String, Vec<Edge>>,
    /// The nodes of each node-based surface (`*SURFACE, TYPE=NODE`): a node-to-surface
    /// pair's slave points when it is the slave.
    node_surfaces: BTreeMap<String, BTreeSet<usize>>,
    /// Point masses (type MASS) by element set: their nodes and the *MASS value (t, the whole
    /// ring's, as CalculiX's and its *CLOAD); not in the model's mesh.
    point_masses: BTreeMap<String, (Vec<usize>, Option<f64>)>,
    /// Where a point mass is first loaded (GRAV or CENTRIF): refused with NLGEOM.
    mass_load_at: Option<Location>,
    materials: Vec<MaterialDef>,
    /// *SOLID SECTION: element set, material, the thickness line's value (if any), where.
    sections: Vec<(String, String, Option<f64>, Location)>,
    /// Each element's section family from its type (CAX, CPE, CPS), thickness 1 until its
    /// *SOLID SECTION gives one.
    element_family: Vec<Section>,
    /// Reduced (CalculiX's rules) for the ..8R and ..6 types, full for the rest.
    element_integration: Vec<Integration>,
    interactions: BTreeMap<String, Interaction>,
    current_interaction: Option<String>,
    contacts: Vec<ListedPair>,
    /// *EQUATION, *TIE and *PRE-TENSION SECTION, as linear constraints.
    constraints: Vec<crate::model::Constraint>,
    /// The *TIE cards, resolved at the deck's end.
    ties: Vec<constraints::TieDef>,
    /// The node set names the deck defines (NSET=): a set the reader makes for a node named
    /// by number steers clear of them.
    deck_node_sets: BTreeSet<String>,
    /// (node, its partner) of every pre-tension section: the partner takes the node's
    /// temperatures.
    section_partners: Vec<(usize, usize)>,
    amplitudes: BTreeMap<String, Vec<(f64, f64)>>,
    /// *INITIAL CONDITIONS, TYPE=TEMPERATURE lines in order, and where the first card is.
    initial_temperature: Option<(Vec<NodeTemperatures>, Location)>,
    fixed: Vec<(String, Component)>,
    /// Model data's *BOUNDARY on degree of freedom 11: temperatures every heat step holds.
    fixed_temperatures: Vec<(String, f64)>,
    steps: Vec<StepDef>,
    in_step: bool,
    element_types: BTreeMap<String, usize>,
    output_requests: BTreeSet<String>,
    /// FREQUENCY= of the file output requests (the smallest given).
    output_every: Option<usize>,
    /// *CONTROLS, PARAMETERS=TIME INCREMENTATION's I_G: the most iterations after which the
    /// next increment grows (slideline's easy_iterations; CalculiX's default 4 is slideline's).
    easy_iterations: Option<usize>,
    /// *STEP, EXTRAPOLATION= (Abaqus's; one for the whole deck): LINEAR the extrapolating
    /// predictor, NO none; without it, slideline's tangent predictor.
    predictor: Option<(Predictor, Location)>,
    /// *TIME POINTS by name: (times, in total time).
    time_points: BTreeMap<String, (Vec<f64>, bool)>,
    notes: Vec<String>,
}

fn build(cards: &[Card], source_text: String) -> Result<InpModel> {
    let mut b = Builder { deck_node_sets: cards.iter().filter_map(|c| c.param("NSET")).map(|n| n.to_uppercase()).collect(), ..Builder::default() };
    // the card a material / interaction property belongs to
    let mut last_owner = "";
    let mut changing: Option<&Card> = None;
    for card in cards {
        let kw = card.keyword.as_str();
        // *CHANGE FRICTION takes its new coefficient from the *FRICTION card right after it
        if let Some(change) = changing.take().filter(|_| kw != "FRICTION") {
            return Err(change.error("names no new friction: a *FRICTION card must follow it (the interaction's coefficient would stay as it was)"));
        }
        match kw {
            "HEADING" => {
                card.only(&[])?;
                let title: Vec<String> = card.data.iter().map(|d| d.fields.join(", ")).collect();
                if !title.is_empty() {
                    b.notes.push(format!("heading: {}", title.join(" ")));
                }
            }
            "NODE" => b.nodes(card)?,
            "ELEMENT" => b.elements(card)?,
            "NSET" | "ELSET" => b.set(card)?,
            "SURFACE" => b.surface(card)?,
            "MATERIAL" => {
                b.material(card)?;
                last_owner = "MATERIAL";
            }
            "SPECIFIC HEAT" => {
                if last_owner != "MATERIAL" {
                    return Err(card.error("must follow a *MATERIAL card"));
                }
                let material = &b.materials.last().expect("after a *MATERIAL").name;
                b.notes.push(format!("material {material}: *{kw} ({}) has no effect in a static step or a steady heat transfer step", card.at));
            }
            "PHYSICAL CONSTANTS" => {
                b.notes.push(format!("*PHYSICAL CONSTANTS ({}) have no effect in a static structural analysis", card.at));
            }
            "MASS" => b.mass(card)?,
            "ELASTIC" | "PLASTIC" | "EXPANSION" | "DENSITY" | "CONDUCTIVITY" => {
                if last_owner != "MATERIAL" {
                    return Err(card.error("must follow a *MATERIAL card"));
                }
                b.material_property(card)?;
            }
            "SOLID SECTION" => {
                b.solid_section(card)?;
                last_owner = "";
            }
            "SURFACE INTERACTION" => {
                card.only(&["NAME"])?;
                let name = card.required("NAME")?.to_uppercase();
                b.interactions.insert(name.clone(), Interaction { behaviour: None, friction: None });
                b.current_interaction = Some(name);
                last_owner = "SURFACE INTERACTION";
            }
            "CHANGE FRICTION" => {
                b.step_mut(card)?;
                card.only(&["INTERACTION"])?;
                let name = card.required("INTERACTION")?.to_uppercase();
                if !b.interactions.contains_key(&name) {
                    return Err(card.error(format!("surface interaction {name} is not defined")));
                }
                b.current_interaction = Some(name);
                last_owner = "CHANGE FRICTION";
                changing = Some(card);
            }
            "FRICTION" if last_owner == "CHANGE FRICTION" => {
                let name = b.current_interaction.clone().expect("set by *CHANGE FRICTION");
                let friction = properties::friction_values(card)?;
                let step = b.step_mut(card)?;
                if step.friction_changes.iter().any(|(i, _)| *i == name) {
                    return Err(card.error(format!("the friction of interaction {name} is changed twice in the step")));
                }
                step.friction_changes.push((name, friction));
                last_owner = "";
            }
            "SURFACE BEHAVIOR" | "FRICTION" => {
                if last_owner != "SURFACE INTERACTION" {
                    return Err(card.error("must follow a *SURFACE INTERACTION card"));
                }
                b.interaction_property(card)?;
            }
            "CONTACT PAIR" => b.contact_pair(card)?,
            "EQUATION" => b.equation(card)?,
            "TIE" => b.tie(card)?,
            "PRE-TENSION SECTION" => b.pretension_section(card)?,
            "AMPLITUDE" => b.amplitude(card)?,
            "INITIAL CONDITIONS" => b.initial_conditions(card)?,
            "BOUNDARY" => b.boundary(card)?,
            "STEP" => b.step(card)?,
            "STATIC" => b.static_procedure(card)?,
            "HEAT TRANSFER" => b.heat_transfer_procedure(card)?,
            "DLOAD" => b.dload(card)?,
            "CLOAD" => b.cload(card)?,
            "TEMPERATURE" => b.temperature(card)?,
            "END STEP" => b.end_step(card)?,
            "CONTROLS" => b.controls(card)?,
            "TIME POINTS" => b.time_points(card)?,
            kw if OUTPUT_REQUESTS.contains(&kw) => b.output_request(card, kw)?,
            other => return Err(unsupported(card, other)),
        }
    }
    if let Some(change) = changing {
        return Err(change.error("names no new friction: a *FRICTION card must follow it (the interaction's coefficient would stay as it was)"));
    }
    let mut files: Vec<std::path::PathBuf> = Vec::new();
    for card in cards {
        if !files.iter().any(|f| f == card.at.file.as_ref()) {
            files.push(card.at.file.as_ref().clone());
        }
    }
    b.finish(source_text, files)
}

/// The refusal of a keyword slideline does not read: why, where a reason is known.
fn unsupported(card: &Card, other: &str) -> Error {
    let why = match other {
        "COUPLED TEMPERATURE-DISPLACEMENT" | "UNCOUPLED TEMPERATURE-DISPLACEMENT" => {
            "slideline solves static structural steps and steady heat conduction (*HEAT TRANSFER, STEADY STATE) apart, not coupled: give the temperatures with *TEMPERATURE"
        }
        "FILM" | "RADIATE" | "VIEWFACTOR" | "GAP HEAT GENERATION" | "GAP CONDUCTANCE" | "CFLUX" | "DFLUX" => {
            "a heat-transfer load: slideline's heat steps hold temperatures (*BOUNDARY, degree of freedom 11) on insulated surfaces, nothing else"
        }
        "FLUID CONSTANTS" | "FLUID SECTION" | "SPECIFIC GAS CONSTANT" => "slideline has no fluid networks",
        "FREQUENCY" | "BUCKLE" => "eigenvalue steps are read from the TOML deck only (procedure = \"frequency\" / \"buckle\", docs/deck.md)",
        _ => return card.error(format!("keyword *{other} is outside the subset slideline reads (docs/inp.md lists it)")),
    };
    card.error(why)
}

impl Builder {
    /// What CalculiX's nodal forces and masses are divided by: 2 pi (the whole ring's, kept
    /// per radian) in a deck with axisymmetric elements, 1 in a plane deck.
    fn ring_measure(&self) -> f64 {
        if self.element_family.iter().any(|s| s.is_axisymmetric()) {
            std::f64::consts::TAU
        } else {
            1.0
        }
    }
}

/// Side index 0..3 of a face label `S1`..`S4` (surfaces) or `P1`..`P4` (pressures): face k
/// runs from corner k to corner k + 1.
fn face_side(label: &str, prefix: char) -> Option<usize> {
    let k: usize = label.strip_prefix(prefix)?.parse().ok()?;
    (1..=4).contains(&k).then(|| k - 1)
}

/// The one data line of a material property card.
fn single(card: &Card) -> Result<&DataLine> {
    match card.data.as_slice() {
        [d] => Ok(d),
        [] => Err(card.error("needs a data line")),
        _ => Err(card.error("temperature-dependent data (more than one line) is not supported")),
    }
}

/// Piecewise-linear amplitude at `t`, held constant outside its points.
fn interpolate(points: &[(f64, f64)], t: f64) -> f64 {
    match points.windows(2).find(|w| t <= w[1].0) {
        Some(w) if t >= w[0].0 => w[0].1 + (w[1].1 - w[0].1) * (t - w[0].0) / (w[1].0 - w[0].0),
        Some(_) => points[0].1,
        None => points[points.len() - 1].1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::GeneralStep;

    const MESH: &str = "*NODE
1, 10., 0.
2, 12., 0.
3, 12., 2.
4, 10., 2.
5, 14., 0.
6, 14., 2.
*ELEMENT, TYPE=CAX4, ELSET=A
1, 1, 2, 3, 4
2, 2, 5, 6, 3
*NSET, NSET=BOTTOM, GENERATE
1, 2
*NSET, NSET=BOTTOM
5
*NSET, NSET=TOP
4, 3, 6
*MATERIAL, NAME=Steel
*Elastic
200000., 0.3
*Plastic
300., 0.
400., 0.1
*Solid Section, Elset=a, Material=STEEL
";

    fn read(rest: &str) -> InpModel {
        parse(&format!("{MESH}{rest}"), Path::new("t.inp")).unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn cax4_elements_share_their_added_mid_side_nodes() {
        let m = read("*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n").model;
        // 6 corners + 7 distinct edges
        assert_eq!(m.mesh.coords.len(), 13);
        let shared = m.mesh.elements[0][5]; // side 2-3 of element 1 ...
        assert_eq!(m.mesh.elements[1][7], shared); // ... is side 3-2 of element 2
        assert_eq!(m.mesh.coords[shared], [12.0, 1.0]);
        // GENERATE plus a second card extend one set; set names are case-insensitive; the
        // mid-side nodes of edges 1-2 and 2-5 join it
        assert_eq!(m.node_sets["BOTTOM"].len(), 5);
        assert_eq!(m.element_material, vec![0, 0]);
        // a two-point *PLASTIC table is linear hardening up to its last point
        let h = m.materials[0].plasticity.unwrap();
        assert!((h.yield_stress(0.05) - 350.0).abs() < 1e-9 && h.yield_stress(1.0) == 400.0);
    }

    /// A density is noted as idle only where no step loads it; the reduced element says what
    /// it runs as.
    #[test]
    fn a_density_is_noted_idle_only_without_a_body_load() {
        let density = MESH
            .replace("*Plastic", "*DENSITY\n7.85e-9\n*Plastic")
            .replace("TYPE=CAX4,", "TYPE=CAX8R,")
            .replace("1, 1, 2, 3, 4\n2, 2, 5, 6, 3", "1, 1, 2, 3, 4, 7, 8, 9, 10\n2, 2, 5, 6, 3, 11, 12, 13, 8")
            .replace("6, 14., 2.\n", "6, 14., 2.\n7, 11., 0.\n8, 12., 1.\n9, 11., 2.\n10, 10., 1.\n11, 13., 0.\n12, 14., 1.\n13, 13., 2.\n");
        let parse_with = |step: &str| parse(&format!("{density}{step}"), Path::new("t.inp")).unwrap_or_else(|e| panic!("{e}"));
        let idle = parse_with("*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n");
        assert!(idle.notes.iter().any(|n| n.contains("*DENSITY (t.inp:") && n.contains("no step loads it")), "{:?}", idle.notes);
        assert!(
            idle.notes.iter().any(|n| n.contains("2 CAX8R elements run as CalculiX's reduced 8-node axisymmetric quadrilateral: 2 x 2 Gauss points")),
            "{:?}",
            idle.notes
        );
        assert_eq!(idle.model.element_integration, [Integration::Reduced; 2]);
        let spun = parse_with("*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*DLOAD\nA, CENTRIF, 1.e6, 0., 0., 0., 0., 1., 0.\n*END STEP\n");
        assert!(!spun.notes.iter().any(|n| n.contains("DENSITY")), "{:?}", spun.notes);
    }

    #[test]
    fn an_amplitude_splits_its_step_at_its_points_and_time_follows_the_deck() {
        let deck = "*AMPLITUDE, NAME=UP\n0., 0., 1., 1., 2., 1.\n*STEP\n*STATIC\n0.5, 4.\n*BOUNDARY\nBOTTOM, 2, 2\n*BOUNDARY, AMPLITUDE=UP\nTOP, 2, 2, -0.1\n*DLOAD\nA, P1, 5.\n*END STEP\n";
        let read = read(deck);
        let steps: Vec<&GeneralStep> = read.model.general_steps().collect();
        // amplitude points at step times 1 and 2 (of 4): sub-steps ending at 1, 2, 4
        assert_eq!(steps.len(), 3);
        assert_eq!(steps.iter().map(|s| s.increments).collect::<Vec<_>>(), vec![2, 2, 4]);
        assert_eq!(steps.iter().map(|s| s.time_span.unwrap()).collect::<Vec<_>>(), vec![[0.0, 1.0], [1.0, 2.0], [2.0, 4.0]]);
        let top = |s: &GeneralStep| s.displacements.iter().find(|d| d.node_set == "TOP").unwrap().value;
        assert_eq!(steps.iter().copied().map(top).collect::<Vec<_>>(), vec![-0.1, -0.1, -0.1]);
        // the pressure without an amplitude ramps over the whole step
        let p = |s: &GeneralStep| s.pressures[0].value;
        assert_eq!(steps.iter().copied().map(p).collect::<Vec<_>>(), vec![1.25, 2.5, 5.0]);
        assert!(read.notes.iter().any(|n| n.contains("3 sub-steps")), "{:?}", read.notes);
    }

    #[test]
    fn an_amplitude_ramp_is_followed_through_its_interior_point() {
        let deck = "*AMPLITUDE, NAME=TRI\n0., 0., 0.5, 1., 1., 0.\n*BOUNDARY\nBOTTOM, 2, 2\n*STEP\n*STATIC\n0.1, 1.\n*BOUNDARY, AMPLITUDE=TRI\nTOP, 2, 2, -0.1\n*END STEP\n";
        let m = read(deck).model;
        let top: Vec<f64> = m.general_steps().map(|s| s.displacements.iter().find(|d| d.node_set == "TOP").unwrap().value).collect();
        assert_eq!(top, vec![-0.1, 0.0]);
        // the model-data constraint joins the first step
        assert!(m.general_step(0).displacements.iter().any(|d| d.node_set == "BOTTOM" && d.value == 0.0));
    }

    #[test]
    fn a_node_based_surface_is_the_free_faces_on_its_nodes() {
        let deck = "*SURFACE, NAME=UPPER, TYPE=NODE\nTOP\n*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n";
        let m = read(deck).model;
        // faces 3-4 of element 1 and 6-3 of element 2 (S3 of both); the shared face 2-3 is not free
        assert_eq!(m.surfaces["UPPER"], vec![Edge { element: 0, side: 2 }, Edge { element: 1, side: 2 }]);
        // node 2 is on no free face whose corners are all in the set: the note names it
        let deck = "*SURFACE, NAME=UPPER, TYPE=NODE\nTOP\n2\n*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n";
        let read = read(deck);
        assert_eq!(read.model.surfaces["UPPER"].len(), 2);
        let note = read.notes.iter().find(|n| n.contains("surface UPPER")).unwrap();
        assert!(note.contains("(1 of its nodes, 2, lie on none of them)"), "{note}");
        assert!(note.contains("each of its 4 nodes bears on the master with the area of the master face it meets"), "{note}");
        assert!(!read.notes.iter().any(|n| n.contains("area given beside")), "{:?}", read.notes);
        // Abaqus's area beside a node is not read, and the note says so
        let read = self::read(&deck.replace("TOP\n2\n", "TOP\n2, 0.5\n"));
        assert!(read.notes.iter().any(|n| n.contains("surface UPPER: the area given beside a node (t.inp:") && n.contains("is not used")), "{:?}", read.notes);
    }

    #[test]
    fn a_node_based_surface_is_no_master() {
        let deck = "*SURFACE, NAME=UPPER, TYPE=NODE\nTOP\n*SURFACE, NAME=LOWER\nA, S1\n*CONTACT PAIR, INTERACTION=I\nLOWER, UPPER\n\
            *SURFACE INTERACTION, NAME=I\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1e5\n*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n";
        let err = parse(&format!("{MESH}{deck}"), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("surface UPPER is node-based (TYPE=NODE): a master surface must be element faces"), "{err}");
    }

    #[test]
    fn face_labels_map_to_sides_and_others_are_refused() {
        assert_eq!([face_side("S1", 'S'), face_side("S4", 'S'), face_side("P2", 'P')], [Some(0), Some(3), Some(1)]);
        for bad in ["S0", "S5", "S12", "P", "P1", "BX"] {
            assert_eq!(face_side(bad, 'S'), None, "{bad}");
        }
        let err = parse(&format!("{MESH}*SURFACE, NAME=X\nA, S5\n"), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("t.inp:25") && err.contains("'S5'"), "{err}");
    }

    #[test]
    fn initial_temperatures_must_cover_every_node_and_may_vary() {
        let deck = "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nTOP, 20.\n*STEP\n*STATIC\n*END STEP\n";
        let err = parse(&format!("{MESH}{deck}"), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("t.inp:24") && err.contains("3 of the 6 nodes have no temperature"), "{err}");
        // a field per node set (a later line wins), and a step that heats one set: the others
        // keep theirs; a node number works as a set
        let deck = "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nBOTTOM, 20.\nTOP, 40.\n*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*TEMPERATURE\nTOP, 100.\n1, 60.\n*END STEP\n";
        let m = read(deck).model;
        let (top, bottom) = (&m.node_sets["TOP"], &m.node_sets["BOTTOM"]);
        assert!(top.iter().all(|&n| m.reference_temperature.at(n) == 40.0) && bottom.iter().all(|&n| m.reference_temperature.at(n) == 20.0));
        let end = m.general_step(0).temperature.as_ref().unwrap();
        assert!(top.iter().all(|&n| end.at(n) == 100.0), "{end:?}");
        let node = |id: u64| m.mesh.node_ids.iter().position(|&i| i == id).unwrap();
        assert_eq!([1, 2, 5].map(|id| end.at(node(id))), [60.0, 20.0, 20.0]);
        // the mid-side node slideline added between nodes 1 and 2 takes their mean
        let (a, b) = (m.mesh.coords[node(1)], m.mesh.coords[node(2)]);
        let mid = bottom.iter().find(|&&n| m.mesh.coords[n] == [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]).unwrap();
        assert_eq!(end.at(*mid), 40.0);
    }

    #[test]
    fn a_dload_on_an_element_face_surface_loads_the_surface_faces() {
        // as CalculiX's dloads.f: the name is a surface, whose own faces are loaded (S3 here,
        // whatever the label's face number)
        let deck = "*SURFACE, NAME=UPPER\nA, S3\n*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*DLOAD\nUPPER, P1, 50.\n*END STEP\n";
        let m = read(deck).model;
        let p = &m.general_step(0).pressures;
        assert_eq!((p.len(), p[0].surface.as_str(), p[0].value), (1, "UPPER", 50.0));
        assert_eq!(m.surfaces["UPPER"], vec![Edge { element: 0, side: 2 }, Edge { element: 1, side: 2 }]);
    }

    #[test]
    fn controls_are_noted_time_points_end_increments_and_a_step_needs_a_procedure() {
        let deck = "*TIME POINTS, NAME=T1\n0.3, 1.\n*STEP\n*STATIC\n0.25, 1.\n*CONTROLS, PARAMETERS=TIME INCREMENTATION\n4, 8\n*BOUNDARY\nBOTTOM, 2, 2\n*NODE PRINT, NSET=TOP, TIME POINTS=T1\nU\n*END STEP\n";
        let read = read(deck);
        assert!(read.notes.iter().any(|n| n.contains("*CONTROLS") && n.contains("ignored")), "{:?}", read.notes);
        // I_G, the sixth value, is the iterations after which an increment grows
        let controlled = self::read(&deck.replace("4, 8\n", "4, 8, 9, 16, 10, 12\n"));
        assert_eq!(controlled.model.stepping.easy_iterations, 12);
        assert_eq!(read.model.stepping.easy_iterations, 4, "CalculiX's default I_G is slideline's");
        // 4 increments of 0.25 and a time point at 0.3: sub-steps ending at 0.3 and 1
        let ends: Vec<f64> = read.model.general_steps().map(|s| s.time_span.unwrap()[1]).collect();
        assert_eq!(ends, vec![0.3, 1.0]);
        let generated =
            "*TIME POINTS, NAME=T2, GENERATE\n0., 1., 0.5\n*STEP\n*STATIC\n0.1, 1.\n*BOUNDARY\nBOTTOM, 2, 2\n*NODE FILE, TIME POINTS=T2\nU\n*END STEP\n";
        let ends: Vec<f64> = self::read(generated).model.general_steps().map(|s| s.time_span.unwrap()[1]).collect();
        assert_eq!(ends, vec![0.5, 1.0]);
        let err = parse(&format!("{MESH}*STEP\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n"), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("t.inp:24") && err.contains("no procedure card"), "{err}");
    }

    #[test]
    fn extrapolation_chooses_the_predictor_once_for_the_deck() {
        let step = |e: &str| format!("*STEP{e}\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n");
        assert_eq!(read(&step("")).model.stepping.predictor, Predictor::Tangent, "slideline's default");
        assert_eq!(read(&step(", EXTRAPOLATION=LINEAR")).model.stepping.predictor, Predictor::Extrapolate);
        assert_eq!(read(&step(", EXTRAPOLATION=no")).model.stepping.predictor, Predictor::None);
        let err = parse(&format!("{MESH}{}", step(", EXTRAPOLATION=PARABOLIC")), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("t.inp:24") && err.contains("PARABOLIC is not supported"), "{err}");
        let two = format!("{MESH}{}{}", step(", EXTRAPOLATION=LINEAR"), step(", EXTRAPOLATION=NO"));
        let err = parse(&two, Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("t.inp:29") && err.contains("t.inp:24") && err.contains("one predictor"), "{err}");
    }

    #[test]
    fn an_interaction_may_follow_its_contact_pair_and_isotropic_is_spelt_out() {
        let deck = "*MATERIAL, NAME=IRON\n*ELASTIC, TYPE=ISOTROPIC\n200000., 0.3\n*SURFACE, NAME=L\nA, S2\n*SURFACE, NAME=R\nA, S4\n\
*CONTACT PAIR, INTERACTION=LATER, TYPE=SURFACE TO SURFACE\nL, R\n*SURFACE INTERACTION, NAME=LATER\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.e5\n\
*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n";
        let m = read(deck).model;
        assert_eq!(m.materials[1].youngs_modulus, 200000.0);
        assert_eq!(m.contacts.len(), 1);
        assert_eq!(m.contacts[0].penalty, crate::model::Penalty::Stiffness(1e5));
    }

    #[test]
    fn change_friction_changes_every_pair_of_its_interaction_from_its_step_on() {
        let pairs = "*SURFACE, NAME=L\nA, S2\n*SURFACE, NAME=R\nA, S4\n*SURFACE, NAME=T\nA, S3\n\
*SURFACE INTERACTION, NAME=I\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.e5\n*FRICTION\n0.2, 4.e4\n\
*CONTACT PAIR, INTERACTION=I\nL, R\nR, L\n*CONTACT PAIR, INTERACTION=I\nT, R\n";
        let step = |change: &str| format!("*STEP\n*STATIC\n{change}*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n");
        let deck = format!("{pairs}{}{}{}", step(""), step("*CHANGE FRICTION, INTERACTION=i\n*FRICTION\n0.1\n"), step(""));
        let m = read(&deck).model;
        let mu = |s: usize| m.friction_in_step(s).iter().map(|f| f.map(|f| (f.coefficient, f.tangential_penalty))).collect::<Vec<_>>();
        // the two-pass pair L-R carries each direction's half: twice the stick slope
        assert_eq!(mu(0), vec![Some((0.2, Some(8e4))), Some((0.2, Some(4e4)))]);
        assert_eq!(mu(1), vec![Some((0.1, None)), Some((0.1, None))], "the normal penalty as the stick slope when none is given");
        assert_eq!(mu(2), mu(1), "the change holds in the steps after it");
        for (change, needle) in [
            ("*CHANGE FRICTION, INTERACTION=NONE\n*FRICTION\n0.1\n", "surface interaction NONE is not defined"),
            ("*CHANGE FRICTION, INTERACTION=I\n*FRICTION\n0.1\n*CHANGE FRICTION, INTERACTION=I\n*FRICTION\n0.3\n", "changed twice"),
            ("*CHANGE FRICTION, INTERACTION=I\n*FRICTION\n-0.1\n", "friction coefficient -0.1"),
            ("*CHANGE FRICTION, INTERACTION=I\n", "*CHANGE FRICTION: names no new friction: a *FRICTION card must follow it"),
        ] {
            let err = parse(&format!("{MESH}{pairs}{}", step(change)), Path::new("t.inp")).err().unwrap().to_string();
            assert!(err.contains(needle), "{change}: {err}");
        }
        let err = parse(&format!("{MESH}{pairs}*CHANGE FRICTION, INTERACTION=I\n*FRICTION\n0.1\n{}", step("")), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("inside a *STEP"), "{err}");
    }

    #[test]
    fn file_output_frequency_sets_how_often_fields_are_written() {
        let deck = "*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*NODE FILE, FREQUENCY=5\nU\n*EL FILE, FREQUENCY=4\nS\n*END STEP\n";
        let read = read(deck);
        assert_eq!(read.model.output.every, 4, "the smaller of the two");
        assert!(read.notes.iter().any(|n| n.contains("every 4th increment")), "{:?}", read.notes);
        // FREQUENCY=0 on every file request of a step: no fields in it; beside a request that
        // writes, fields as before
        let two = "*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*NODE FILE, FREQUENCY=0\nU\n*END STEP\n*STEP\n*STATIC\n*NODE FILE, FREQUENCY=0\nU\n*EL FILE\nS\n*END STEP\n";
        let m = self::read(two).model;
        assert_eq!(m.general_steps().map(|s| s.without_field_output).collect::<Vec<_>>(), vec![true, false]);
        let err = parse(&format!("{MESH}*STEP\n*STATIC\n*NODE FILE, FREQUENCY=-1\nU\n*END STEP\n"), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("FREQUENCY=-1"), "{err}");
    }

    #[test]
    fn boundary_op_new_releases_what_the_step_does_not_restate() {
        // model data holds BOTTOM axially; step 1 pushes TOP; step 2 restates only TOP
        let deck = "*BOUNDARY\nBOTTOM, 2, 2\n*STEP\n*STATIC\n*BOUNDARY\nTOP, 2, 2, 0.1\n*END STEP\n\
*STEP\n*STATIC\n*BOUNDARY, OP=NEW\nTOP, 2, 2, 0.2\n*BOUNDARY, OP=NEW\nTOP, 1, 1\n*END STEP\n";
        let given = read(deck);
        let m = &given.model;
        assert_eq!(m.general_steps().map(|s| s.release_constraints).collect::<Vec<_>>(), vec![false, true]);
        assert!(given.notes.iter().any(|n| n.contains("OP=NEW releases BOTTOM u_z")), "{:?}", given.notes);
        assert!(given.notes.iter().any(|n| n.contains("later *BOUNDARY card has no effect")), "{:?}", given.notes);
        let err = parse(&format!("{MESH}*BOUNDARY, OP=NEW\nBOTTOM, 2, 2\n*STEP\n*STATIC\n*END STEP\n"), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("t.inp:24") && err.contains("OP=NEW belongs in a *STEP"), "{err}");
        // in the first step OP=NEW releases the model data's constraints too (CalculiX: the
        // reaction there is zero; they were kept, 3.0e5 N/rad)
        let first = read("*BOUNDARY\nBOTTOM, 2, 2\n*STEP\n*STATIC\n*BOUNDARY, OP=NEW\nTOP, 2, 2, 0.1\n*END STEP\n");
        let held: Vec<&str> = first.model.general_step(0).displacements.iter().map(|d| d.node_set.as_str()).collect();
        assert!(first.model.general_step(0).release_constraints && !held.iter().any(|s| s.eq_ignore_ascii_case("bottom")), "{held:?}");
        assert!(first.notes.iter().any(|n| n.contains("OP=NEW releases BOTTOM u_z")), "{:?}", first.notes);
    }
}

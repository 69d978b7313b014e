//! Abaqus/CalculiX input decks (`.inp`): the subset that axisymmetric contact models use,
//! read into a [`Model`]. Anything outside the subset is an error naming the keyword, the file
//! and the line; every place where slideline's model differs from the deck's words (element
//! formulation, contact algorithm, output requests, force convention) becomes a note that the
//! run prints.
//!
//! Read: *HEADING, *NODE, *ELEMENT (CAX8, CAX8R, CAX4, CAX4R), *NSET/*ELSET (GENERATE),
//! *SURFACE (element faces S1..S4, or nodes), *MATERIAL with *ELASTIC, *PLASTIC, *EXPANSION
//! (ZERO), *DENSITY, *SOLID SECTION, *BOUNDARY, *DLOAD (P1..P4), *INITIAL CONDITIONS
//! (TEMPERATURE), *TEMPERATURE, *AMPLITUDE, *SURFACE INTERACTION, *SURFACE BEHAVIOR
//! (PRESSURE-OVERCLOSURE=LINEAR), *FRICTION (0 only), *CONTACT PAIR, *STEP (NLGEOM), *STATIC,
//! *END STEP, *INCLUDE, and the output requests (*NODE PRINT, *EL FILE, ...), which slideline
//! answers by writing every field at every increment.
//!
//! CalculiX's axisymmetric convention: reaction forces are per 2-degree segment (the element
//! is expanded over 2 degrees); results files of an .inp run carry reactions per radian, per
//! ring and per 2-degree segment (columns `..._2deg`).

pub mod cards;

use super::mesh::{Edge, Mesh};
use super::{
    Component, ContactIntegration, ContactPair, Kinematics, Material, Model, Penalty, Plasticity, PrescribedDisplacement, Pressure, Step, SteppingControls,
};
use crate::error::{Error, Result};
use cards::{error_at, normalise, Card, DataLine, Location};
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
    plastic: Vec<(f64, f64)>,
    plastic_at: Option<Location>,
}

struct Interaction {
    slope: Option<f64>,
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
    temperature: Option<Target<()>>,
    /// *DLOAD, OP=NEW: loads of earlier steps not restated are removed.
    new_loads: bool,
}

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
    materials: Vec<MaterialDef>,
    sections: Vec<(String, String, Location)>,
    interactions: BTreeMap<String, Interaction>,
    current_interaction: Option<String>,
    contacts: Vec<(String, String, String, ContactIntegration, Location)>,
    amplitudes: BTreeMap<String, Vec<(f64, f64)>>,
    initial_temperature: Option<f64>,
    fixed: Vec<(String, Component)>,
    steps: Vec<StepDef>,
    in_step: bool,
    element_types: BTreeMap<String, usize>,
    output_requests: BTreeSet<String>,
    notes: Vec<String>,
}

fn build(cards: &[Card], source_text: String) -> Result<InpModel> {
    let mut b = Builder::default();
    // the card a material / interaction property belongs to
    let mut last_owner = "";
    for card in cards {
        let kw = card.keyword.as_str();
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
                card.only(&["NAME"])?;
                let name = card.required("NAME")?.to_uppercase();
                if b.materials.iter().any(|m| m.name == name) {
                    return Err(card.error(format!("material {name} is defined twice")));
                }
                b.materials.push(MaterialDef { name, at: card.at.clone(), elastic: None, expansion: 0.0, plastic: Vec::new(), plastic_at: None });
                last_owner = "MATERIAL";
            }
            "ELASTIC" | "PLASTIC" | "EXPANSION" | "DENSITY" => {
                if last_owner != "MATERIAL" {
                    return Err(card.error("must follow a *MATERIAL card"));
                }
                b.material_property(card)?;
            }
            "SOLID SECTION" => {
                card.only(&["ELSET", "MATERIAL"])?;
                let elset = card.required("ELSET")?.to_uppercase();
                if !b.element_sets.contains_key(&elset) {
                    return Err(card.error(format!("element set {elset} is not defined (define it before its use)")));
                }
                b.sections.push((elset, card.required("MATERIAL")?.to_uppercase(), card.at.clone()));
                last_owner = "";
            }
            "SURFACE INTERACTION" => {
                card.only(&["NAME"])?;
                let name = card.required("NAME")?.to_uppercase();
                b.interactions.insert(name.clone(), Interaction { slope: None });
                b.current_interaction = Some(name);
                last_owner = "SURFACE INTERACTION";
            }
            "SURFACE BEHAVIOR" | "FRICTION" => {
                if last_owner != "SURFACE INTERACTION" {
                    return Err(card.error("must follow a *SURFACE INTERACTION card"));
                }
                b.interaction_property(card)?;
            }
            "CONTACT PAIR" => b.contact_pair(card)?,
            "AMPLITUDE" => b.amplitude(card)?,
            "INITIAL CONDITIONS" => {
                card.only(&["TYPE"])?;
                if !card.param("TYPE").is_some_and(|t| t.eq_ignore_ascii_case("TEMPERATURE")) {
                    return Err(card.error("only TYPE=TEMPERATURE is supported"));
                }
                b.initial_temperature = Some(b.uniform_temperature(card)?);
            }
            "BOUNDARY" => b.boundary(card)?,
            "STEP" => b.step(card)?,
            "STATIC" => b.static_procedure(card)?,
            "DLOAD" => b.dload(card)?,
            "TEMPERATURE" => {
                b.step_mut(card)?;
                card.only(&["AMPLITUDE", "OP"])?;
                if card.param("OP").is_some_and(|o| !o.eq_ignore_ascii_case("MOD")) {
                    return Err(card.error("only OP=MOD is supported"));
                }
                let value = b.uniform_temperature(card)?;
                let amplitude = b.amplitude_ref(card)?;
                b.step_mut(card)?.temperature = Some(Target { key: (), value, amplitude });
            }
            "END STEP" => {
                if !b.in_step {
                    return Err(card.error("without a *STEP"));
                }
                b.in_step = false;
            }
            kw if OUTPUT_REQUESTS.contains(&kw) => {
                b.output_requests.insert(format!("*{kw}"));
            }
            other => {
                return Err(card.error(format!(
                    "keyword *{other} is outside the subset slideline reads (see `slideline run --help` or the README's \"Abaqus/CalculiX input\" section)"
                )))
            }
        }
    }
    b.finish(source_text)
}

impl Builder {
    fn nodes(&mut self, card: &Card) -> Result<()> {
        card.only(&["NSET"])?;
        let mut ids = Vec::new();
        for d in &card.data {
            let id = d.id("NODE", 0, "node number")?;
            let r = d.number("NODE", 1, "r (first coordinate)", Some(0.0))?;
            let z = d.number("NODE", 2, "z (second coordinate)", Some(0.0))?;
            if d.fields.len() > 3 && d.number("NODE", 3, "third coordinate", Some(0.0))? != 0.0 {
                return Err(error_at(&d.at, "NODE", format!("node {id} has a third coordinate: axisymmetric models lie in the r-z plane")));
            }
            if self.node_index.contains_key(&id) {
                return Err(error_at(&d.at, "NODE", format!("node {id} is defined twice (or clashes with a mid-side node added to a CAX4 element)")));
            }
            self.node_index.insert(id, self.mesh.coords.len());
            ids.push(self.mesh.coords.len());
            self.mesh.coords.push([r, z]);
            self.mesh.node_ids.push(id);
        }
        if let Some(name) = card.param("NSET") {
            self.node_sets.entry(name.to_uppercase()).or_default().extend(ids);
        }
        Ok(())
    }

    fn node(&self, d: &DataLine, keyword: &str, k: usize) -> Result<usize> {
        let id = d.id(keyword, k, "node number")?;
        self.node_index.get(&id).copied().ok_or_else(|| error_at(&d.at, keyword, format!("node {id} is not defined")))
    }

    fn elements(&mut self, card: &Card) -> Result<()> {
        card.only(&["TYPE", "ELSET"])?;
        let kind = card.required("TYPE")?.to_uppercase();
        let corners_only = match kind.as_str() {
            "CAX8" | "CAX8R" => false,
            "CAX4" | "CAX4R" => true,
            other => {
                return Err(card
                    .error(format!("element type {other} is outside the subset (slideline reads the axisymmetric quadrilaterals CAX8, CAX8R, CAX4, CAX4R)")))
            }
        };
        let per_element = if corners_only { 4 } else { 8 };
        // an element's node list may continue on following lines
        let mut pending: Vec<(String, Location)> = Vec::new();
        let mut ids = Vec::new();
        for d in &card.data {
            pending.extend(d.fields.iter().filter(|f| !f.is_empty()).map(|f| (f.clone(), d.at.clone())));
            if pending.len() < per_element + 1 {
                continue;
            }
            if pending.len() > per_element + 1 {
                return Err(error_at(&d.at, "ELEMENT", format!("{kind} takes {per_element} nodes, got {}", pending.len() - 1)));
            }
            let line = DataLine { fields: pending.iter().map(|p| p.0.clone()).collect(), at: pending[0].1.clone() };
            pending.clear();
            let id = line.id("ELEMENT", 0, "element number")?;
            if self.element_index.contains_key(&id) {
                return Err(error_at(&line.at, "ELEMENT", format!("element {id} is defined twice")));
            }
            let mut conn = [0usize; 8];
            for (k, slot) in conn.iter_mut().take(per_element).enumerate() {
                *slot = self.node(&line, "ELEMENT", k + 1)?;
            }
            if corners_only {
                for s in 0..4 {
                    conn[4 + s] = self.midside(conn[s], conn[(s + 1) % 4]);
                }
            }
            self.element_index.insert(id, self.mesh.elements.len());
            ids.push(self.mesh.elements.len());
            self.mesh.elements.push(conn);
            self.mesh.element_ids.push(id);
        }
        if let Some((_, at)) = pending.first() {
            return Err(error_at(at, "ELEMENT", format!("{kind} takes {per_element} nodes, the last element has {}", pending.len() - 1)));
        }
        *self.element_types.entry(kind).or_default() += ids.len();
        if let Some(name) = card.param("ELSET") {
            self.element_sets.entry(name.to_uppercase()).or_default().extend(ids);
        }
        Ok(())
    }

    /// The mid-side node between corners `a` and `b` of a CAX4 element (shared by both
    /// elements on the edge), at the middle of the straight edge.
    fn midside(&mut self, a: usize, b: usize) -> usize {
        let key = (a.min(b), a.max(b));
        if let Some(&n) = self.added_midside.get(&key) {
            return n;
        }
        let (pa, pb) = (self.mesh.coords[a], self.mesh.coords[b]);
        let id = self.node_index.keys().max().copied().unwrap_or(0) + 1;
        let n = self.mesh.coords.len();
        self.mesh.coords.push([0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])]);
        self.mesh.node_ids.push(id);
        self.node_index.insert(id, n);
        self.added_midside.insert(key, n);
        n
    }

    /// The nodes of data field `k`: a node number or a node set name.
    fn node_items(&self, d: &DataLine, keyword: &str, k: usize) -> Result<Vec<usize>> {
        let f = d.fields.get(k).map(|s| s.as_str()).unwrap_or("");
        if f.chars().all(|c| c.is_ascii_digit()) && !f.is_empty() {
            return Ok(vec![self.node(d, keyword, k)?]);
        }
        self.node_sets
            .get(&f.to_uppercase())
            .cloned()
            .ok_or_else(|| error_at(&d.at, keyword, format!("node set '{f}' is not defined (define it before its use)")))
    }

    /// The elements of data field `k`: an element number or an element set name.
    fn element_items(&self, d: &DataLine, keyword: &str, k: usize) -> Result<Vec<usize>> {
        let f = d.fields.get(k).map(|s| s.as_str()).unwrap_or("");
        if f.chars().all(|c| c.is_ascii_digit()) && !f.is_empty() {
            let id = d.id(keyword, k, "element number")?;
            return self.element_index.get(&id).map(|&e| vec![e]).ok_or_else(|| error_at(&d.at, keyword, format!("element {id} is not defined")));
        }
        self.element_sets
            .get(&f.to_uppercase())
            .cloned()
            .ok_or_else(|| error_at(&d.at, keyword, format!("element set '{f}' is not defined (define it before its use)")))
    }

    fn set(&mut self, card: &Card) -> Result<()> {
        let nodes = card.keyword == "NSET";
        let kw = card.keyword.as_str();
        let param = if nodes { "NSET" } else { "ELSET" };
        card.only(&[param, "GENERATE"])?;
        let name = card.required(param)?.to_uppercase();
        let mut members = Vec::new();
        for d in &card.data {
            if card.has("GENERATE") {
                let (first, last) = (d.id(kw, 0, "first number")?, d.id(kw, 1, "last number")?);
                let step = if d.fields.len() > 2 { d.id(kw, 2, "increment")? } else { 1 };
                if last < first {
                    return Err(error_at(&d.at, kw, format!("GENERATE from {first} to {last}: the last number is smaller")));
                }
                for id in (first..=last).step_by(step as usize) {
                    let index = if nodes { self.node_index.get(&id) } else { self.element_index.get(&id) };
                    let what = if nodes { "node" } else { "element" };
                    members.push(*index.ok_or_else(|| error_at(&d.at, kw, format!("{what} {id} (generated) is not defined")))?);
                }
            } else {
                for k in (0..d.fields.len()).filter(|&k| !d.fields[k].is_empty()) {
                    members.extend(if nodes { self.node_items(d, kw, k)? } else { self.element_items(d, kw, k)? });
                }
            }
        }
        let set = if nodes { self.node_sets.entry(name).or_default() } else { self.element_sets.entry(name).or_default() };
        set.extend(members);
        set.sort_unstable();
        set.dedup();
        Ok(())
    }

    fn surface(&mut self, card: &Card) -> Result<()> {
        card.only(&["NAME", "TYPE"])?;
        let name = card.required("NAME")?.to_uppercase();
        let mut edges = Vec::new();
        match card.param("TYPE").map(|t| t.to_uppercase()).as_deref() {
            None | Some("ELEMENT") => {
                for d in &card.data {
                    let face = d.fields.get(1).map(|s| s.to_uppercase()).unwrap_or_default();
                    let side = face_side(&face, 'S')
                        .ok_or_else(|| error_at(&d.at, "SURFACE", format!("face '{face}': axisymmetric quadrilaterals have faces S1 to S4")))?;
                    edges.extend(self.element_items(d, "SURFACE", 0)?.into_iter().map(|element| Edge { element, side }));
                }
            }
            Some("NODE") => {
                let mut nodes = BTreeSet::new();
                for d in &card.data {
                    nodes.extend(self.node_items(d, "SURFACE", 0)?);
                }
                // the free faces whose two corners belong to the set (CAX4 faces have no mid-side node in it)
                let mut count: HashMap<(usize, usize), usize> = HashMap::new();
                for conn in &self.mesh.elements {
                    for s in 0..4 {
                        let (a, b) = (conn[s], conn[(s + 1) % 4]);
                        *count.entry((a.min(b), a.max(b))).or_default() += 1;
                    }
                }
                for (element, conn) in self.mesh.elements.iter().enumerate() {
                    for side in 0..4 {
                        let (a, b) = (conn[side], conn[(side + 1) % 4]);
                        if count[&(a.min(b), a.max(b))] == 1 && nodes.contains(&a) && nodes.contains(&b) {
                            edges.push(Edge { element, side });
                        }
                    }
                }
                if edges.is_empty() {
                    return Err(card.error(format!("node-based surface {name}: no free element face has both corners in the set")));
                }
                self.notes.push(format!(
                    "surface {name} ({}) is node-based: slideline uses the {} free element faces whose corners belong to it",
                    card.at,
                    edges.len()
                ));
            }
            Some(other) => return Err(card.error(format!("TYPE={other} is not supported (ELEMENT or NODE)"))),
        }
        edges.sort();
        edges.dedup();
        self.surfaces.entry(name).or_default().extend(edges);
        Ok(())
    }

    fn material_property(&mut self, card: &Card) -> Result<()> {
        let m = self.materials.last_mut().expect("checked by the caller");
        match card.keyword.as_str() {
            "ELASTIC" => {
                card.only(&["TYPE"])?;
                if card.param("TYPE").is_some_and(|t| !t.eq_ignore_ascii_case("ISO")) {
                    return Err(card.error("only TYPE=ISO (isotropic) is supported"));
                }
                let d = single(card)?;
                m.elastic = Some((d.number("ELASTIC", 0, "Young's modulus", None)?, d.number("ELASTIC", 1, "Poisson's ratio", None)?));
            }
            "EXPANSION" => {
                card.only(&["TYPE", "ZERO"])?;
                if card.param("TYPE").is_some_and(|t| !t.eq_ignore_ascii_case("ISO")) {
                    return Err(card.error("only TYPE=ISO (isotropic) is supported"));
                }
                m.expansion = single(card)?.number("EXPANSION", 0, "expansion coefficient", None)?;
                if card.has("ZERO") {
                    self.notes.push(format!(
                        "material {}: ZERO= of *EXPANSION ({}) has no effect with a constant coefficient: thermal strain alpha (T - T_initial), as in CalculiX and Abaqus",
                        m.name, card.at
                    ));
                }
            }
            "PLASTIC" => {
                card.only(&["HARDENING"])?;
                if card.param("HARDENING").is_some_and(|t| !t.eq_ignore_ascii_case("ISOTROPIC")) {
                    return Err(card.error("only HARDENING=ISOTROPIC is supported"));
                }
                m.plastic.clear();
                for d in &card.data {
                    if d.fields.len() > 2 && !d.fields[2].is_empty() {
                        return Err(error_at(&d.at, "PLASTIC", "temperature-dependent hardening is not supported"));
                    }
                    m.plastic.push((d.number("PLASTIC", 1, "plastic strain", None)?, d.number("PLASTIC", 0, "yield stress", None)?));
                }
                m.plastic_at = Some(card.at.clone());
            }
            _ => {
                card.only(&[])?;
                self.notes.push(format!("material {}: *DENSITY ({}) has no effect in a static analysis", m.name, card.at));
            }
        }
        Ok(())
    }

    fn interaction_property(&mut self, card: &Card) -> Result<()> {
        let name = self.current_interaction.clone().expect("checked by the caller");
        if card.keyword == "FRICTION" {
            card.only(&[])?;
            let mu = card.data.first().map(|d| d.number("FRICTION", 0, "friction coefficient", None)).transpose()?.unwrap_or(0.0);
            if mu != 0.0 {
                return Err(card.error(format!("friction coefficient {mu}: slideline's contact is frictionless")));
            }
            return Ok(());
        }
        card.only(&["PRESSURE-OVERCLOSURE"])?;
        let law = card.required("PRESSURE-OVERCLOSURE")?.to_uppercase();
        if law != "LINEAR" {
            return Err(card.error(format!("PRESSURE-OVERCLOSURE={law}: slideline's penalty contact reads LINEAR (its slope is the penalty, N/mm^3)")));
        }
        let d = card.data.first().ok_or_else(|| card.error("needs the slope of the pressure-overclosure line"))?;
        let slope = d.number("SURFACE BEHAVIOR", 0, "slope (MPa/mm)", None)?;
        if d.fields.len() > 1 && d.fields.iter().skip(1).any(|f| !f.is_empty()) {
            self.notes.push(format!(
                "interaction {name}: the tension at large clearance and c0 of *SURFACE BEHAVIOR ({}) are not used: slideline's penalty gives zero pressure at any clearance",
                card.at
            ));
        }
        self.interactions.get_mut(&name).expect("registered").slope = Some(slope);
        Ok(())
    }

    fn contact_pair(&mut self, card: &Card) -> Result<()> {
        card.only(&["INTERACTION", "TYPE", "SMALL SLIDING"])?;
        let interaction = card.required("INTERACTION")?.to_uppercase();
        if !self.interactions.contains_key(&interaction) {
            return Err(card.error(format!("surface interaction {interaction} is not defined")));
        }
        let integration = match card.param("TYPE").map(normalise).as_deref() {
            None | Some("NODE TO SURFACE") => ContactIntegration::NodeToSegment,
            Some("SURFACE TO SURFACE") => ContactIntegration::Segment,
            Some(other) => return Err(card.error(format!("TYPE={other} is not supported (NODE TO SURFACE or SURFACE TO SURFACE)"))),
        };
        if card.has("SMALL SLIDING") {
            self.notes.push(format!("*CONTACT PAIR ({}): SMALL SLIDING ignored, slideline searches for the closest segment at every iteration", card.at));
        }
        for d in &card.data {
            let name = |k: usize| -> Result<String> {
                let s = d.fields.get(k).map(|s| s.to_uppercase()).unwrap_or_default();
                if self.surfaces.contains_key(&s) {
                    Ok(s)
                } else {
                    Err(error_at(&d.at, "CONTACT PAIR", format!("surface '{s}' is not defined (define it before its use)")))
                }
            };
            self.contacts.push((name(0)?, name(1)?, interaction.clone(), integration, d.at.clone()));
        }
        Ok(())
    }

    fn amplitude(&mut self, card: &Card) -> Result<()> {
        card.only(&["NAME", "TIME", "DEFINITION"])?;
        if card.param("TIME").is_some_and(|t| normalise(t) != "STEP TIME") {
            return Err(card.error("only TIME=STEP TIME is supported"));
        }
        if card.param("DEFINITION").is_some_and(|t| !t.eq_ignore_ascii_case("TABULAR")) {
            return Err(card.error("only DEFINITION=TABULAR is supported"));
        }
        let name = card.required("NAME")?.to_uppercase();
        let mut values = Vec::new();
        for d in &card.data {
            let fields: Vec<usize> = (0..d.fields.len()).filter(|&k| !d.fields[k].is_empty()).collect();
            if !fields.len().is_multiple_of(2) {
                return Err(error_at(&d.at, "AMPLITUDE", "values come in (time, amplitude) pairs"));
            }
            for pair in fields.chunks(2) {
                values.push((d.number("AMPLITUDE", pair[0], "time", None)?, d.number("AMPLITUDE", pair[1], "amplitude", None)?));
            }
        }
        if values.is_empty() || values.windows(2).any(|w| w[1].0 <= w[0].0) {
            return Err(card.error(format!("amplitude {name} needs (time, value) pairs with increasing times")));
        }
        self.amplitudes.insert(name, values);
        Ok(())
    }

    fn amplitude_ref(&self, card: &Card) -> Result<Option<String>> {
        match card.param("AMPLITUDE") {
            None => Ok(None),
            Some(a) => {
                let a = a.to_uppercase();
                if self.amplitudes.contains_key(&a) {
                    Ok(Some(a))
                } else {
                    Err(card.error(format!("amplitude {a} is not defined (define it before its use)")))
                }
            }
        }
    }

    /// The single temperature that the data lines set on every node.
    fn uniform_temperature(&self, card: &Card) -> Result<f64> {
        let mut covered = BTreeSet::new();
        let mut value: Option<f64> = None;
        for d in &card.data {
            let t = d.number(&card.keyword, 1, "temperature", None)?;
            if value.is_some_and(|v| v != t) {
                return Err(error_at(&d.at, &card.keyword, "slideline applies one uniform temperature: every line must give the same value"));
            }
            value = Some(t);
            covered.extend(self.node_items(d, &card.keyword, 0)?);
        }
        let t = value.ok_or_else(|| card.error("needs a data line: node set, temperature"))?;
        // the deck's own nodes (mid-side nodes added to CAX4 elements cannot be named)
        let named = self.mesh.coords.len() - self.added_midside.len();
        if covered.len() != named {
            return Err(card.error(format!("slideline applies one uniform temperature: the sets given cover {} of the {named} nodes", covered.len())));
        }
        Ok(t)
    }

    fn step_mut(&mut self, card: &Card) -> Result<&mut StepDef> {
        match self.steps.last_mut() {
            Some(s) if self.in_step => Ok(s),
            _ => Err(card.error("belongs inside a *STEP")),
        }
    }

    fn step(&mut self, card: &Card) -> Result<()> {
        card.only(&["NLGEOM", "INC", "NAME", "AMPLITUDE"])?;
        if self.in_step {
            return Err(card.error("the previous *STEP has no *END STEP"));
        }
        if card.param("AMPLITUDE").is_some_and(|a| !a.eq_ignore_ascii_case("RAMP")) {
            return Err(card.error("only AMPLITUDE=RAMP (loads ramped over the step) is supported; use an *AMPLITUDE for other histories"));
        }
        let nlgeom = match card.param("NLGEOM").map(|v| v.to_uppercase()) {
            None => None,
            Some(v) if v.is_empty() || v == "YES" => Some(true),
            Some(v) if v == "NO" => Some(false),
            Some(v) => return Err(card.error(format!("NLGEOM={v}: YES or NO"))),
        };
        let name = card.param("NAME").map(|s| s.to_string()).unwrap_or_else(|| format!("step-{}", self.steps.len() + 1));
        self.steps.push(StepDef {
            name,
            at: card.at.clone(),
            nlgeom,
            initial: 1.0,
            period: 1.0,
            minimum: None,
            boundaries: Vec::new(),
            pressures: Vec::new(),
            temperature: None,
            new_loads: false,
        });
        self.in_step = true;
        Ok(())
    }

    fn static_procedure(&mut self, card: &Card) -> Result<()> {
        card.only(&["DIRECT", "SOLVER"])?;
        if card.has("SOLVER") {
            self.notes.push(format!("*STATIC ({}): SOLVER= ignored, the linear solver is PETSc's (options after `--`)", card.at));
        }
        let step = self.step_mut(card)?;
        if let Some(d) = card.data.first() {
            let period = d.number("STATIC", 1, "time period", Some(1.0))?;
            let initial = d.number("STATIC", 0, "initial increment", Some(period))?;
            if !(period > 0.0 && initial > 0.0 && initial <= period * (1.0 + 1e-12)) {
                return Err(error_at(&d.at, "STATIC", format!("need 0 < initial increment ({initial}) <= time period ({period})")));
            }
            step.period = period;
            step.initial = initial;
            step.minimum = d.fields.get(2).filter(|f| !f.is_empty()).map(|_| d.number("STATIC", 2, "minimum increment", None)).transpose()?;
        }
        Ok(())
    }

    fn boundary(&mut self, card: &Card) -> Result<()> {
        card.only(&["OP", "AMPLITUDE"])?;
        if card.param("OP").is_some_and(|o| !o.eq_ignore_ascii_case("MOD")) {
            return Err(card.error("only OP=MOD is supported (slideline keeps a constraint once applied)"));
        }
        let amplitude = self.amplitude_ref(card)?;
        for d in &card.data {
            let target = d.fields.first().cloned().unwrap_or_default();
            let nodes = self.node_items(d, "BOUNDARY", 0)?;
            let set = if target.chars().all(|c| c.is_ascii_digit()) {
                let name = format!("N{target}");
                self.node_sets.insert(name.clone(), nodes);
                name
            } else {
                target.to_uppercase()
            };
            let word = d.fields.get(1).map(|s| s.to_uppercase()).unwrap_or_default();
            let (first, last, value) = match word.as_str() {
                "ENCASTRE" | "PINNED" => (1, 2, 0.0),
                "XSYMM" => (1, 1, 0.0),
                "YSYMM" => (2, 2, 0.0),
                _ => {
                    let first = d.id("BOUNDARY", 1, "first degree of freedom")?;
                    let last = if d.fields.get(2).is_some_and(|f| !f.is_empty()) { d.id("BOUNDARY", 2, "last degree of freedom")? } else { first };
                    (first, last, d.number("BOUNDARY", 3, "value", Some(0.0))?)
                }
            };
            if first > last || last > 2 {
                return Err(error_at(&d.at, "BOUNDARY", format!("degrees of freedom {first} to {last}: axisymmetric nodes have 1 (ur) and 2 (uz)")));
            }
            for dof in first..=last {
                let component = if dof == 1 { Component::R } else { Component::Z };
                if self.in_step {
                    let step = self.steps.last_mut().expect("in a step");
                    step.boundaries.retain(|b| b.key != (set.clone(), component));
                    step.boundaries.push(Target { key: (set.clone(), component), value, amplitude: amplitude.clone() });
                } else {
                    if value != 0.0 || amplitude.is_some() {
                        return Err(error_at(&d.at, "BOUNDARY", "a prescribed (non-zero) value belongs inside a *STEP; model data only fixes"));
                    }
                    self.fixed.push((set.clone(), component));
                }
            }
        }
        Ok(())
    }

    fn dload(&mut self, card: &Card) -> Result<()> {
        card.only(&["OP", "AMPLITUDE"])?;
        let new = match card.param("OP").map(|o| o.to_uppercase()).as_deref() {
            None | Some("MOD") => false,
            Some("NEW") => true,
            Some(o) => return Err(card.error(format!("OP={o}: MOD or NEW"))),
        };
        let amplitude = self.amplitude_ref(card)?;
        self.step_mut(card)?;
        let mut loads = Vec::new();
        for d in &card.data {
            let label = d.fields.get(1).map(|s| s.to_uppercase()).unwrap_or_default();
            let side =
                face_side(&label, 'P').ok_or_else(|| error_at(&d.at, "DLOAD", format!("load type '{label}': slideline reads face pressures P1 to P4")))?;
            let elements = self.element_items(d, "DLOAD", 0)?;
            let value = d.number("DLOAD", 2, "magnitude", None)?;
            // the loaded faces as a surface named after the element set and face
            let surface = format!("DLOAD_{}_{label}", d.fields[0].to_uppercase());
            self.surfaces.insert(surface.clone(), elements.into_iter().map(|element| Edge { element, side }).collect());
            loads.push(Target { key: surface, value, amplitude: amplitude.clone() });
        }
        let step = self.step_mut(card)?;
        step.new_loads |= new;
        for l in loads {
            step.pressures.retain(|p| p.key != l.key);
            step.pressures.push(l);
        }
        Ok(())
    }

    fn finish(mut self, source_text: String) -> Result<InpModel> {
        if self.in_step {
            let at = &self.steps.last().expect("in a step").at;
            return Err(error_at(at, "STEP", "has no *END STEP"));
        }
        for (kind, n) in &self.element_types {
            let how = match kind.as_str() {
                "CAX8" => "slideline's 8-node axisymmetric quadrilateral (3 x 3 Gauss points, F-bar)",
                "CAX8R" => "slideline's 8-node axisymmetric quadrilateral with full 3 x 3 integration and F-bar (no reduced integration)",
                _ => "8-node quadrilaterals with mid-side nodes added at the middle of each straight edge (quadratic displacements, 3 x 3 Gauss points, F-bar)",
            };
            self.notes.push(format!("{n} {kind} elements run as {how}"));
        }
        if !self.output_requests.is_empty() {
            let list: Vec<&str> = self.output_requests.iter().map(|s| s.as_str()).collect();
            self.notes.push(format!("output requests ({}) are answered by the results file: every field at every increment", list.join(", ")));
        }

        let mut materials = Vec::new();
        for m in &self.materials {
            let (youngs_modulus, poissons_ratio) = m.elastic.ok_or_else(|| error_at(&m.at, "MATERIAL", format!("material {} has no *ELASTIC", m.name)))?;
            // piecewise linear through the points, flat after the last (as Abaqus): two points
            // are linear hardening exactly up to the second
            let plasticity = match (m.plastic.as_slice(), &m.plastic_at) {
                ([], _) | (_, None) => None,
                (points, Some(at)) => Some(Plasticity::table(points).map_err(|e| error_at(at, "PLASTIC", e))?),
            };
            materials.push(Material { name: m.name.clone(), youngs_modulus, poissons_ratio, thermal_expansion: m.expansion, plasticity });
        }
        if materials.is_empty() {
            return Err(Error::input("the deck defines no *MATERIAL"));
        }
        let mut element_material = vec![usize::MAX; self.mesh.elements.len()];
        for (elset, material, at) in &self.sections {
            let k = materials
                .iter()
                .position(|m| &m.name == material)
                .ok_or_else(|| error_at(at, "SOLID SECTION", format!("material {material} is not defined")))?;
            for &e in &self.element_sets[elset] {
                element_material[e] = k;
            }
        }
        if let Some(e) = element_material.iter().position(|&m| m == usize::MAX) {
            return Err(Error::input(format!("element {} has no *SOLID SECTION", self.mesh.element_ids[e])));
        }

        if self.steps.is_empty() {
            return Err(Error::input("the deck has no *STEP"));
        }
        let kinematics = if self.steps.iter().any(|s| s.nlgeom == Some(true)) { Kinematics::Finite } else { Kinematics::Small };
        if kinematics == Kinematics::Finite && self.steps.first().is_some_and(|s| s.nlgeom != Some(true)) {
            self.notes.push("NLGEOM is set in a later step: slideline runs every step with finite strain".into());
        }
        let uses_temperature = self.steps.iter().any(|s| s.temperature.is_some());
        let reference_temperature = match self.initial_temperature {
            Some(t) => t,
            None if uses_temperature => return Err(Error::input("*TEMPERATURE needs *INITIAL CONDITIONS, TYPE=TEMPERATURE (the stress-free temperature)")),
            None => 0.0,
        };
        let steps = self.expand_steps(reference_temperature)?;

        let mut contacts = Vec::new();
        for (slave, master, interaction, integration, at) in &self.contacts {
            let slope = self.interactions[interaction]
                .slope
                .ok_or_else(|| error_at(at, "CONTACT PAIR", format!("interaction {interaction} has no *SURFACE BEHAVIOR")))?;
            let longest = self.surfaces[master].iter().map(|&e| self.mesh.edge_length(e)).fold(0.0, f64::max);
            let name = if slave == master { slave.clone() } else { format!("{slave}-{master}") };
            self.notes.push(format!(
                "contact {name}: frictionless penalty {slope} N/mm^3 (the LINEAR slope), {}",
                match integration {
                    ContactIntegration::Segment => "gap integrated along the slave surface (SURFACE TO SURFACE)",
                    ContactIntegration::NodeToSegment => "node-to-segment slide line (NODE TO SURFACE)",
                }
            ));
            contacts.push(ContactPair {
                name,
                slave: slave.clone(),
                master: master.clone(),
                two_pass: false,
                integration: *integration,
                penalty: Penalty::Stiffness(slope),
                capture_distance: 2.0 * longest,
                augmented_lagrangian: None,
                exclude_neighbours: 2,
            });
        }
        let mut stepping = SteppingControls::default();
        if let Some(min) = self.steps.iter().filter_map(|s| s.minimum.map(|m| m / s.period)).reduce(f64::min) {
            stepping.min_increment = min.clamp(1e-12, 1.0);
        }
        self.notes.push(format!(
            "reactions are written per radian, per full ring (_ring) and per {CALCULIX_SEGMENT_DEGREES}-degree segment (_2deg, CalculiX's axisymmetric convention)"
        ));
        let model = Model {
            mesh: self.mesh,
            node_sets: self.node_sets,
            element_sets: self.element_sets,
            surfaces: self.surfaces,
            materials,
            element_material,
            reference_temperature,
            kinematics,
            stepping,
            contacts,
            steps,
            source_text,
            reaction_segment_degrees: Some(CALCULIX_SEGMENT_DEGREES),
        };
        model.validate()?;
        Ok(InpModel { model, notes: self.notes })
    }

    /// slideline steps ramp every target linearly from the previous step's value; a step whose
    /// loads follow an *AMPLITUDE is split at the amplitude's points so that the piecewise-linear
    /// history is followed exactly.
    fn expand_steps(&mut self, initial_temperature: f64) -> Result<Vec<Step>> {
        let mut displacement_now: BTreeMap<(String, Component), f64> = self.fixed.iter().map(|k| (k.clone(), 0.0)).collect();
        let mut pressure_now: BTreeMap<String, f64> = BTreeMap::new();
        let mut temperature_now = initial_temperature;
        let mut out = Vec::new();
        let mut total_time = 0.0;
        for (k, s) in self.steps.iter_mut().enumerate() {
            // fixed model-data constraints join the first step
            if k == 0 {
                for key in &self.fixed {
                    if !s.boundaries.iter().any(|b| &b.key == key) {
                        s.boundaries.insert(0, Target { key: key.clone(), value: 0.0, amplitude: None });
                    }
                }
            }
            if s.new_loads {
                for (surface, v) in pressure_now.iter_mut() {
                    if !s.pressures.iter().any(|p| &p.key == surface) {
                        s.pressures.push(Target { key: surface.clone(), value: 0.0, amplitude: None });
                        *v = 0.0;
                    }
                }
            }
            let increments = ((s.period / s.initial) - 1e-9).ceil().max(1.0) as usize;
            let mut used: BTreeSet<&String> = BTreeSet::new();
            used.extend(s.boundaries.iter().filter_map(|b| b.amplitude.as_ref()));
            used.extend(s.pressures.iter().filter_map(|b| b.amplitude.as_ref()));
            used.extend(s.temperature.iter().filter_map(|b| b.amplitude.as_ref()));
            let mut times: Vec<f64> =
                used.iter().flat_map(|a| self.amplitudes[*a].iter().map(|p| p.0)).filter(|&t| t > 1e-12 * s.period && t < s.period * (1.0 - 1e-12)).collect();
            times.push(s.period);
            times.sort_by(f64::total_cmp);
            times.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * s.period);
            let period = s.period;
            let (d0, p0, t0) = (displacement_now.clone(), pressure_now.clone(), temperature_now);
            let mut previous_time = 0.0;
            for (j, &time) in times.iter().enumerate() {
                let displacements = s
                    .boundaries
                    .iter()
                    .map(|b| {
                        let before = d0.get(&b.key).copied().unwrap_or(0.0);
                        PrescribedDisplacement { node_set: b.key.0.clone(), component: b.key.1, value: b.at(before, time, period, &self.amplitudes) }
                    })
                    .collect::<Vec<_>>();
                let pressures = s
                    .pressures
                    .iter()
                    .map(|p| Pressure { surface: p.key.clone(), value: p.at(p0.get(&p.key).copied().unwrap_or(0.0), time, period, &self.amplitudes) })
                    .collect::<Vec<_>>();
                let temperature = s.temperature.as_ref().map(|t| t.at(t0, time, period, &self.amplitudes));
                for d in &displacements {
                    displacement_now.insert((d.node_set.clone(), d.component), d.value);
                }
                for p in &pressures {
                    pressure_now.insert(p.surface.clone(), p.value);
                }
                if let Some(t) = temperature {
                    temperature_now = t;
                }
                let name = if times.len() == 1 { s.name.clone() } else { format!("{}.{}", s.name, j + 1) };
                let share = ((increments as f64) * (time - previous_time) / s.period).round().max(1.0) as usize;
                let time_span = Some([total_time + previous_time, total_time + time]);
                out.push(Step { name, increments: share, displacements, pressures, temperature, time_span });
                previous_time = time;
            }
            total_time += s.period;
            if times.len() > 1 {
                self.notes.push(format!(
                    "{} ({}) follows its amplitudes in {} sub-steps ending at step times {}",
                    s.name,
                    s.at,
                    times.len(),
                    times.iter().map(|t| format!("{t}")).collect::<Vec<_>>().join(", ")
                ));
            }
        }
        Ok(out)
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
        // GENERATE plus a second card extend one set; set names are case-insensitive
        assert_eq!(m.node_sets["BOTTOM"].len(), 3);
        assert_eq!(m.element_material, vec![0, 0]);
        // a two-point *PLASTIC table is linear hardening up to its last point
        let h = m.materials[0].plasticity.unwrap();
        assert!((h.yield_stress(0.05) - 350.0).abs() < 1e-9 && h.yield_stress(1.0) == 400.0);
    }

    #[test]
    fn an_amplitude_splits_its_step_at_its_points_and_time_follows_the_deck() {
        let deck = "*AMPLITUDE, NAME=UP\n0., 0., 1., 1., 2., 1.\n*STEP\n*STATIC\n0.5, 4.\n*BOUNDARY\nBOTTOM, 2, 2\n*BOUNDARY, AMPLITUDE=UP\nTOP, 2, 2, -0.1\n*DLOAD\nA, P1, 5.\n*END STEP\n";
        let read = read(deck);
        let steps = &read.model.steps;
        // amplitude points at step times 1 and 2 (of 4): sub-steps ending at 1, 2, 4
        assert_eq!(steps.len(), 3);
        assert_eq!(steps.iter().map(|s| s.increments).collect::<Vec<_>>(), vec![2, 2, 4]);
        assert_eq!(steps.iter().map(|s| s.time_span.unwrap()).collect::<Vec<_>>(), vec![[0.0, 1.0], [1.0, 2.0], [2.0, 4.0]]);
        let top = |s: &Step| s.displacements.iter().find(|d| d.node_set == "TOP").unwrap().value;
        assert_eq!(steps.iter().map(top).collect::<Vec<_>>(), vec![-0.1, -0.1, -0.1]);
        // the pressure without an amplitude ramps over the whole step
        let p = |s: &Step| s.pressures[0].value;
        assert_eq!(steps.iter().map(p).collect::<Vec<_>>(), vec![1.25, 2.5, 5.0]);
        assert!(read.notes.iter().any(|n| n.contains("3 sub-steps")), "{:?}", read.notes);
    }

    #[test]
    fn an_amplitude_ramp_is_followed_through_its_interior_point() {
        let deck = "*AMPLITUDE, NAME=TRI\n0., 0., 0.5, 1., 1., 0.\n*BOUNDARY\nBOTTOM, 2, 2\n*STEP\n*STATIC\n0.1, 1.\n*BOUNDARY, AMPLITUDE=TRI\nTOP, 2, 2, -0.1\n*END STEP\n";
        let m = read(deck).model;
        let top: Vec<f64> = m.steps.iter().map(|s| s.displacements.iter().find(|d| d.node_set == "TOP").unwrap().value).collect();
        assert_eq!(top, vec![-0.1, 0.0]);
        // the model-data constraint joins the first step
        assert!(m.steps[0].displacements.iter().any(|d| d.node_set == "BOTTOM" && d.value == 0.0));
    }

    #[test]
    fn a_node_based_surface_is_the_free_faces_on_its_nodes() {
        let deck = "*SURFACE, NAME=UPPER, TYPE=NODE\nTOP\n*STEP\n*STATIC\n*BOUNDARY\nBOTTOM, 2, 2\n*END STEP\n";
        let m = read(deck).model;
        // faces 3-4 of element 1 and 6-3 of element 2 (S3 of both); the shared face 2-3 is not free
        assert_eq!(m.surfaces["UPPER"], vec![Edge { element: 0, side: 2 }, Edge { element: 1, side: 2 }]);
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
    fn a_uniform_temperature_must_cover_every_node() {
        let deck = "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nTOP, 20.\n*STEP\n*STATIC\n*END STEP\n";
        let err = parse(&format!("{MESH}{deck}"), Path::new("t.inp")).err().unwrap().to_string();
        assert!(err.contains("t.inp:24") && err.contains("cover 3 of the 6 nodes"), "{err}");
    }
}

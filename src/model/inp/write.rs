//! A [`Model`] written as a CalculiX/Abaqus deck that both CalculiX and slideline's reader run:
//! CAX8 mesh, node and element sets, element-face surfaces, materials (*PLASTIC as a table),
//! one *SURFACE INTERACTION and *CONTACT PAIR per pair with its normal law (the penalty as the LINEAR slope, or EXPONENTIAL)
//! (and its *FRICTION: mu and the stick slope; a step's change of it as *CHANGE FRICTION),
//! *DLOAD per loaded face label (and GRAV / CENTRIF for body loads), the steps with *STATIC (the requested increment, which both
//! codes cut back when Newton fails and never exceed; the smallest is `min_increment`), and
//! *NODE PRINT of every constrained set's reaction.
//!
//! slideline's two-pass pair (each direction carrying half the force) is written as two pairs,
//! one per direction, each with half the penalty: the same forces, and what CalculiX needs to
//! treat both surfaces alike.

use crate::element::body_load::BodyForce;
use crate::error::{Error, Result};
use crate::fe::quadrature::Integration;
use crate::fe::section::Section;
use crate::fe::shape::Shape;
use crate::model::{Component, ContactIntegration, Friction, Material, Model, Penalty, Plasticity, Predictor, Temperature};
use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::Path;

/// Plastic strain of the last point of a linear-hardening table: past any strain a run reaches,
/// since slideline's (and Abaqus') tables are flat after their last point.
const LINEAR_TABLE_END_STRAIN: f64 = 10.0;

/// Writes `model` to `path` as an .inp deck; `title` heads it.
pub fn write(model: &Model, title: &str, path: &Path) -> Result<()> {
    let text = to_inp(model, title)?;
    std::fs::write(path, text).map_err(|e| Error::Output { path: path.to_path_buf(), message: e.to_string() })
}

/// CalculiX's *FRICTION of pair `name`: mu and the stick slope per listing, as the reader maps
/// it back (a two-pass pair's directions each carry half, so each takes half the slope).
fn friction_card(w: &mut String, name: &str, f: &Friction, two_pass: bool) -> Result<()> {
    if f.elastic_slip.is_some() {
        return Err(Error::input(format!(
            "contact '{name}': friction with an elastic slip has no CalculiX form (its *FRICTION takes a stick slope): give --tangential-penalty for the export"
        )));
    }
    let passes = if two_pass { 2.0 } else { 1.0 };
    let _ = match f.tangential_penalty {
        Some(k) => writeln!(w, "*FRICTION\n{}, {}", num(f.coefficient), num(k / passes)),
        None => writeln!(w, "*FRICTION\n{}", num(f.coefficient)),
    };
    Ok(())
}

/// CalculiX's type of element `e`: CAX, CPE or CPS by its section, then 8, 8R or 6.
fn element_type(model: &Model, e: usize) -> String {
    let family = match model.element_section[e] {
        Section::Axisymmetric => "CAX",
        Section::PlaneStrain { .. } => "CPE",
        Section::PlaneStress { .. } => "CPS",
    };
    let suffix = match (model.mesh.shape(e), model.element_integration[e]) {
        (Shape::Tri6, _) => "6",
        (Shape::Quad8, Integration::Full) => "8",
        (Shape::Quad8, Integration::Reduced) => "8R",
    };
    format!("{family}{suffix}")
}

/// Every multi-point constraint as an equation (a pre-tension section's and a tie's too: the
/// mesh written holds their partner nodes).
fn write_equations(w: &mut String, model: &Model) {
    for c in &model.constraints {
        let _ = writeln!(w, "*EQUATION\n{}", c.terms.len());
        for line in c.terms.chunks(4) {
            let terms: Vec<String> =
                line.iter().map(|t| format!("{}, {}, {}", model.mesh.node_ids[t.node], t.component as usize + 1, num(t.coefficient))).collect();
            let _ = writeln!(w, "{}", terms.join(", "));
        }
    }
}

/// A contact pair's interaction, its behaviour and friction, and the pair (both ways for two
/// passes).
fn write_contact(w: &mut String, c: &crate::model::ContactPair) -> Result<()> {
    let two_pass = c.two_pass && c.slave != c.master;
    let passes = if two_pass { 2.0 } else { 1.0 };
    let behaviour = match c.penalty {
        Penalty::Stiffness(penalty) => format!("LINEAR\n{}", num(penalty / passes)),
        Penalty::Exponential { clearance, pressure } => format!("EXPONENTIAL\n{}, {}", num(clearance), num(pressure / passes)),
        Penalty::Factor(_) => {
            return Err(Error::input(format!("contact '{}': a dimensionless penalty factor has no .inp form: give the penalty in N/mm^3", c.name)))
        }
    };
    let kind = match c.integration {
        ContactIntegration::Segment => "SURFACE TO SURFACE",
        ContactIntegration::NodeToSegment => "NODE TO SURFACE",
    };
    let name = checked_name(&c.name)?;
    let _ = writeln!(w, "*SURFACE INTERACTION, NAME={name}\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE={behaviour}");
    if let Some(f) = &c.friction {
        friction_card(w, &c.name, f, two_pass)?;
    }
    let _ = writeln!(w, "*CONTACT PAIR, INTERACTION={name}, TYPE={kind}\n{}, {}", c.slave, c.master);
    if two_pass {
        let _ = writeln!(w, "*CONTACT PAIR, INTERACTION={name}, TYPE={kind}\n{}, {}", c.master, c.slave);
    }
    Ok(())
}

/// Material `k` (`m`): its cards and one *SOLID SECTION per section its elements have.
fn write_material(w: &mut String, model: &Model, k: usize, m: &Material) -> Result<()> {
    let mesh = &model.mesh;
    let _ = writeln!(w, "*MATERIAL, NAME={}", checked_name(&m.name)?);
    let _ = writeln!(w, "*ELASTIC\n{}, {}", num(m.youngs_modulus), num(m.poissons_ratio));
    // ZERO= is the stress-free temperature of a uniform field (for a constant alpha both codes
    // count thermal strain from the initial conditions, so a field needs none)
    match model.reference_temperature.uniform() {
        Some(t) => writeln!(w, "*EXPANSION, ZERO={}\n{}", num(t), num(m.thermal_expansion)),
        None => writeln!(w, "*EXPANSION\n{}", num(m.thermal_expansion)),
    }
    .ok();
    if m.density > 0.0 {
        let _ = writeln!(w, "*DENSITY\n{}", num(m.density));
    }
    match m.plasticity {
        None => {}
        Some(Plasticity::Linear { yield_stress, modulus }) => {
            let end = yield_stress + modulus * LINEAR_TABLE_END_STRAIN;
            let _ = writeln!(w, "*PLASTIC\n{}, 0.\n{}, {}", num(yield_stress), num(end), num(LINEAR_TABLE_END_STRAIN));
        }
        Some(Plasticity::Table { points, len }) => {
            let _ = writeln!(w, "*PLASTIC");
            for (strain, stress) in &points[..len] {
                let _ = writeln!(w, "{}, {}", num(*stress), num(*strain));
            }
        }
    }
    // one *SOLID SECTION per section the material's elements have
    let of_material: Vec<usize> = (0..mesh.elements.len()).filter(|&e| model.element_material[e] == k).collect();
    let mut sections: Vec<Section> = Vec::new();
    for &e in &of_material {
        if !sections.contains(&model.element_section[e]) {
            sections.push(model.element_section[e]);
        }
    }
    for (j, &section) in sections.iter().enumerate() {
        let elements = of_material.iter().filter(|&&e| model.element_section[e] == section).map(|&e| mesh.element_ids[e]);
        let suffix = if sections.len() > 1 { format!("_{}", j + 1) } else { String::new() };
        let elset = format!("MATERIAL_{}{suffix}", checked_name(&m.name)?);
        listing(w, &format!("*ELSET, ELSET={elset}"), elements);
        let _ = writeln!(w, "*SOLID SECTION, ELSET={elset}, MATERIAL={}", checked_name(&m.name)?);
        if let Section::PlaneStrain { thickness } | Section::PlaneStress { thickness } = section {
            // beside axisymmetric elements the reader took thickness / 2 pi (per radian)
            let t = if model.is_axisymmetric() { thickness * std::f64::consts::TAU } else { thickness };
            let _ = writeln!(w, "{}", num(t));
        }
    }
    Ok(())
}

/// The deck's text.
pub fn to_inp(model: &Model, title: &str) -> Result<String> {
    let mut out = String::new();
    let w = &mut out;
    let mesh = &model.mesh;
    let _ = writeln!(w, "*HEADING\n{title}\n** written by slideline {}; units mm, N, MPa, degC", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(w, "*NODE, NSET=NALL");
    for (id, c) in mesh.node_ids.iter().zip(&mesh.coords) {
        let _ = writeln!(w, "{id}, {}, {}", num(c[0]), num(c[1]));
    }
    let type_of: Vec<String> = (0..mesh.elements.len()).map(|e| element_type(model, e)).collect();
    for kind in type_of.iter().collect::<BTreeSet<_>>() {
        let _ = writeln!(w, "*ELEMENT, TYPE={kind}, ELSET=EALL");
        for e in (0..mesh.elements.len()).filter(|&e| &type_of[e] == kind) {
            let nodes: Vec<String> = mesh.element_nodes(e).iter().map(|&n| mesh.node_ids[n].to_string()).collect();
            let _ = writeln!(w, "{}, {}", mesh.element_ids[e], nodes.join(", "));
        }
    }
    for (name, nodes) in &model.node_sets {
        listing(w, &format!("*NSET, NSET={}", checked_name(name)?), nodes.iter().map(|&n| mesh.node_ids[n]));
    }
    for (name, elements) in &model.element_sets {
        listing(w, &format!("*ELSET, ELSET={}", checked_name(name)?), elements.iter().map(|&e| mesh.element_ids[e]));
    }
    let contact_surfaces: BTreeSet<&str> = model.contacts.iter().flat_map(|c| [c.slave.as_str(), c.master.as_str()]).collect();
    for name in contact_surfaces {
        // a node-based slave (never a master) is written back as its nodes
        if let Some(nodes) = model.contacts.iter().find(|c| c.slave == name).and_then(|c| c.slave_nodes.as_ref()) {
            // one node a line: the line's second field would be an area
            let _ = writeln!(w, "*SURFACE, NAME={}, TYPE=NODE", checked_name(name)?);
            for &n in nodes {
                let _ = writeln!(w, "{}", mesh.node_ids[n]);
            }
            continue;
        }
        let _ = writeln!(w, "*SURFACE, NAME={}, TYPE=ELEMENT", checked_name(name)?);
        for e in model.surface(name)? {
            let _ = writeln!(w, "{}, S{}", mesh.element_ids[e.element], e.side + 1);
        }
    }
    // loaded faces: an element set per surface and face label, the form every reader knows
    let mut loaded: Vec<(String, Vec<(String, usize)>)> = Vec::new();
    for surface in model.general_steps().flat_map(|s| s.pressures.iter().map(|p| p.surface.as_str())).collect::<BTreeSet<_>>() {
        let mut labels = Vec::new();
        for side in 0..4 {
            let elements: Vec<u64> = model.surface(surface)?.iter().filter(|e| e.side == side).map(|e| mesh.element_ids[e.element]).collect();
            if !elements.is_empty() {
                let elset = format!("{}_P{}", checked_name(surface)?, side + 1);
                listing(w, &format!("*ELSET, ELSET={elset}"), elements.into_iter());
                labels.push((elset, side + 1));
            }
        }
        loaded.push((surface.to_string(), labels));
    }

    for (k, m) in model.materials.iter().enumerate() {
        write_material(w, model, k, m)?;
    }

    for c in &model.contacts {
        write_contact(w, c)?;
    }
    write_equations(w, model);
    let _ = writeln!(w, "*INITIAL CONDITIONS, TYPE=TEMPERATURE");
    temperature_lines(w, model, &model.reference_temperature);

    let constrained: BTreeSet<&str> = model.general_steps().flat_map(|s| s.displacements.iter().map(|d| d.node_set.as_str())).collect();
    let mut time = 0.0;
    for step in model.general_steps() {
        let period = step.time_span.map_or(1.0, |[a, b]| b - a);
        if let Some([start, _]) = step.time_span {
            if (start - time).abs() > 1e-12 * period.max(1.0) {
                return Err(Error::input(format!("step '{}' starts at time {start}, not where the previous one ended ({time})", step.name)));
            }
        }
        time += period;
        let nlgeom = if model.kinematics == crate::model::Kinematics::Finite { ", NLGEOM" } else { "" };
        // Abaqus's EXTRAPOLATION (CalculiX warns that it does not know it, and goes on)
        let predictor = match model.stepping.predictor {
            Predictor::Extrapolate => ", EXTRAPOLATION=LINEAR",
            Predictor::None => ", EXTRAPOLATION=NO",
            Predictor::Tangent => "",
        };
        let _ = writeln!(w, "** step {}\n*STEP{nlgeom}, INC=1000000{predictor}", step.name);
        let dt = period / step.increments as f64;
        let dt_min = model.stepping.min_increment * period;
        let _ = writeln!(w, "*STATIC\n{}, {}, {}, {}", num(dt), num(period), num(dt_min), num(dt));
        if model.stepping.easy_iterations != crate::model::SteppingControls::default().easy_iterations {
            // CalculiX's defaults but for I_G, the iterations after which an increment grows
            let _ = writeln!(w, "*CONTROLS, PARAMETERS=TIME INCREMENTATION\n4, 8, 9, 16, 10, {}", model.stepping.easy_iterations);
        }
        for change in &step.friction_changes {
            let c = model.contacts.iter().find(|c| c.name == change.pair).expect("validated: the pair exists");
            let _ = writeln!(w, "*CHANGE FRICTION, INTERACTION={}", checked_name(&c.name)?);
            match &change.friction {
                Some(f) => friction_card(w, &c.name, f, c.two_pass && c.slave != c.master)?,
                None => {
                    let _ = writeln!(w, "*FRICTION\n0.");
                }
            }
        }
        write_step_loads(w, model, step, &loaded)?;
        for set in &constrained {
            let _ = writeln!(w, "*NODE PRINT, NSET={set}, TOTALS=ONLY\nRF");
        }
        let frequency = if step.without_field_output { ", FREQUENCY=0" } else { "" };
        let _ = writeln!(w, "*NODE FILE{frequency}\nU\n*EL FILE{frequency}\nS, PEEQ\n*END STEP");
    }
    Ok(out)
}

/// A step's loads: its *BOUNDARY, its pressures on the `loaded` faces' element sets and body
/// loads (*DLOAD), its *TEMPERATURE.
fn write_step_loads(w: &mut String, model: &Model, step: &crate::model::GeneralStep, loaded: &[(String, Vec<(String, usize)>)]) -> Result<()> {
    if !step.displacements.is_empty() || step.release_constraints {
        let _ = writeln!(w, "*BOUNDARY{}", if step.release_constraints { ", OP=NEW" } else { "" });
        for d in &step.displacements {
            let dof = match d.component {
                Component::R => 1,
                Component::Z => 2,
            };
            let _ = writeln!(w, "{}, {dof}, {dof}, {}", d.node_set, num(d.value));
        }
    }
    if !step.pressures.is_empty() {
        let _ = writeln!(w, "*DLOAD");
        for p in &step.pressures {
            let (_, labels) = loaded.iter().find(|(s, _)| s == &p.surface).expect("every loaded surface listed");
            for (elset, face) in labels {
                let _ = writeln!(w, "{elset}, P{face}, {}", num(p.value));
            }
        }
    }
    if !step.body_loads.is_empty() {
        // about CalculiX's axisymmetric axis, y
        let _ = writeln!(w, "*DLOAD");
        for b in &step.body_loads {
            let set = checked_name(&b.elements)?;
            let _ = match b.force {
                BodyForce::Gravity(g) => writeln!(w, "{set}, GRAV, {}, 0., 1., 0.", num(g)),
                BodyForce::Spin(w2) => writeln!(w, "{set}, CENTRIF, {}, 0., 0., 0., 0., 1., 0.", num(w2)),
            };
        }
    }
    if let Some(t) = &step.temperature {
        let _ = writeln!(w, "*TEMPERATURE");
        temperature_lines(w, model, t);
    }
    Ok(())
}

/// A number in at most 20 characters (CalculiX reads fields of 20): the shortest text that
/// reads back to the same double where it fits, else 14 digits after the point.
/// The data lines of a temperature: `NALL, T` when uniform, else a line per node.
fn temperature_lines(w: &mut String, model: &Model, t: &Temperature) {
    match t.uniform() {
        Some(t) => writeln!(w, "NALL, {}", num(t)).ok(),
        None => (0..model.mesh.coords.len()).try_for_each(|n| writeln!(w, "{}, {}", model.mesh.node_ids[n], num(t.at(n)))).ok(),
    };
}

fn num(x: f64) -> String {
    let shortest = format!("{x:?}");
    if shortest.len() <= 20 {
        shortest
    } else {
        format!("{x:.13e}")
    }
}

/// `keyword` and its members, 16 numbers a line.
fn listing(w: &mut String, keyword: &str, ids: impl Iterator<Item = u64>) {
    let ids: Vec<String> = ids.map(|i| i.to_string()).collect();
    let _ = writeln!(w, "{keyword}");
    for chunk in ids.chunks(16) {
        let _ = writeln!(w, "{}", chunk.join(", "));
    }
}

/// A name both readers take as one word: letters, digits and underscores, at most 80 long.
fn checked_name(name: &str) -> Result<&str> {
    let ok =
        !name.is_empty() && name.len() <= 80 && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') && !name.starts_with(|c: char| c.is_ascii_digit());
    if ok {
        Ok(name)
    } else {
        Err(Error::input(format!("name '{name}' cannot be written to an .inp deck: use letters, digits and underscores, starting with a letter")))
    }
}

#[cfg(test)]
mod tests {
    use crate::element::body_load::BodyForce;
    use crate::fe::quadrature::Integration;
    use crate::fe::section::Section;
    use crate::model::Model;
    use std::path::Path;

    /// A deck's body loads survive the trip through a written .inp and the reader: gravity
    /// and spin on their element sets, in every step that has them (the reader restates the
    /// loads in force, as CalculiX keeps them).
    #[test]
    fn body_loads_are_written_and_read_back() {
        let deck = r#"
[mesh.rectangle]
r = [20.0, 100.0]
z = [0.0, 1.0]
divisions = [4, 1]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
density = 7.85e-9
[[step]]
name = "spin"
boundary = [ { set = "bottom", uz = 0.0 } ]
body_load = [ { elements = "all", spin = 3000.0 }, { elements = "all", gravity = -9810.0 } ]
"#;
        let model = crate::model::deck::parse(deck, Path::new("disc.toml")).unwrap();
        let text = super::to_inp(&model, "disc").unwrap();
        let read = crate::model::inp::parse(&text, Path::new("disc.inp")).unwrap().model;
        let mut loads: Vec<(String, BodyForce)> = read.general_step(0).body_loads.iter().map(|b| (b.elements.clone(), b.force)).collect();
        loads.sort_by(|a, b| a.1.value().total_cmp(&b.1.value()));
        assert_eq!(loads, vec![("ALL".to_string(), BodyForce::Gravity(-9810.0)), ("ALL".to_string(), BodyForce::Spin(9.0e6))]);
    }

    /// Two blocks side by side (r 10..20 and 20..30, z 0..5) of one steel: the contact pairs'
    /// tests add their pairs and steps.
    const TWO_BLOCKS: &str = r#"
[[mesh.block]]
name = "a"
r = [10.0, 20.0]
z = [0.0, 5.0]
divisions = [2, 1]
[[mesh.block]]
name = "b"
r = [20.0, 30.0]
z = [0.0, 5.0]
divisions = [2, 1]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
"#;

    /// Friction changed in steps (CalculiX's *CHANGE FRICTION) survives the trip through a
    /// written deck and the reader: per step, every pair's friction, a two-pass pair's stick
    /// slope included (written per listing, halved, and doubled back).
    #[test]
    fn friction_changes_are_written_and_read_back() {
        let deck = TWO_BLOCKS.to_string()
            + r#"
[[contact]]
name = "one"
slave = "a_outer"
master = "b_inner"
penalty = 1.0e5
friction = 0.2
[[contact]]
name = "two"
slave = "b_top"
master = "a_top"
two_pass = true
penalty = 1.0e5
[[step]]
name = "first"
boundary = [ { set = "a_bottom", uz = 0.0 }, { set = "b_bottom", uz = 0.0 } ]
[[step]]
name = "second"
contact_friction = [ { pair = "one", friction = 0.1, tangential_penalty = 3.0e4 }, { pair = "two", friction = 0.3, tangential_penalty = 2.0e4 } ]
[[step]]
name = "third"
contact_friction = [ { pair = "one", friction = 0.0 } ]
"#;
        let model = crate::model::deck::parse(&deck, Path::new("pair.toml")).unwrap();
        let text = super::to_inp(&model, "pairs").unwrap();
        assert!(text.contains("*CHANGE FRICTION, INTERACTION=two\n*FRICTION\n0.3, 10000"), "{text}");
        let read = crate::model::inp::parse(&text, Path::new("pairs.inp")).unwrap().model;
        for step in 0..3 {
            assert_eq!(read.friction_in_step(step), model.friction_in_step(step), "step {}", step + 1);
        }
        assert_eq!(model.friction_in_step(2)[0], None);
        assert_eq!(model.friction_in_step(2)[1].map(|f| f.coefficient), Some(0.3), "a change holds in the steps after it");
    }

    /// A deck's constraints (here a pre-tension section's and an equation) are written as
    /// equations over the mesh with its partner nodes, and read back the same.
    #[test]
    fn constraints_are_written_as_equations_and_read_back() {
        let deck = "*NODE\n1,0.1,2.\n2,0.1,1.\n3,1.1,1.\n4,1.1,2.\n5,0.1,1.5\n6,0.6,1.\n7,1.1,1.5\n8,0.6,2.\n9,0.1,0.\n10,1.1,0.\n11,0.1,0.5\n12,0.6,0.\n13,1.1,0.5\n14,0.,0.\n\
            *ELEMENT, TYPE=CAX8, ELSET=EALL\n1, 1, 2, 3, 4, 5, 6, 7, 8\n2, 2, 9, 10, 3, 11, 12, 13, 6\n*MATERIAL,NAME=EL\n*ELASTIC\n210000.,.3\n\
            *SOLID SECTION,ELSET=EALL,MATERIAL=EL\n*NSET,NSET=ENDS\n1,4,8,9,10,12\n*BOUNDARY\nENDS,2,2\n*SURFACE,NAME=CUT\n1,S2\n\
            *PRE-TENSION SECTION,SURFACE=CUT,NODE=14\n*EQUATION\n2\n5,1,1.,7,1,-0.5\n*STEP\n*STATIC\n*BOUNDARY\n14,1,1,.01\n*END STEP\n";
        let model = crate::model::inp::parse(deck, Path::new("pret.inp")).unwrap().model;
        assert_eq!(model.constraints.len(), 7, "3 pairs x (tangential, normal) and the equation");
        let text = super::to_inp(&model, "pret").unwrap();
        let read = crate::model::inp::parse(&text, Path::new("back.inp")).unwrap().model;
        assert_eq!(read.mesh.node_ids, model.mesh.node_ids);
        assert_eq!(read.mesh.elements, model.mesh.elements);
        let terms = |m: &Model| m.constraints.iter().map(|c| c.terms.clone()).collect::<Vec<_>>();
        assert_eq!(terms(&read), terms(&model));
    }

    /// A pair's exponential pressure-overclosure law is written as CalculiX's EXPONENTIAL line
    /// (c0, p0 per listing: a two-pass pair's p0 halved) and read back to the same law.
    #[test]
    fn the_exponential_law_is_written_and_read_back() {
        let deck = TWO_BLOCKS.to_string()
            + r#"
[[contact]]
name = "one"
slave = "a_outer"
master = "b_inner"
integration = "node-to-segment"
exponential = { clearance = 2.0e-4, pressure = 0.5 }
[[contact]]
name = "two"
slave = "b_top"
master = "a_top"
integration = "node-to-segment"
two_pass = true
exponential = { clearance = 1.0e-3, pressure = 0.2 }
[[step]]
boundary = [ { set = "a_bottom", uz = 0.0 }, { set = "b_bottom", uz = 0.0 } ]
"#;
        let model = crate::model::deck::parse(&deck, Path::new("pair.toml")).unwrap();
        let text = super::to_inp(&model, "pairs").unwrap();
        assert!(text.contains("PRESSURE-OVERCLOSURE=EXPONENTIAL\n0.0002, 0.5\n"), "{text}");
        assert!(text.contains("PRESSURE-OVERCLOSURE=EXPONENTIAL\n0.001, 0.1\n"), "{text}");
        let read = crate::model::inp::parse(&text, Path::new("pairs.inp")).unwrap().model;
        let laws = |m: &Model| m.contacts.iter().map(|c| (c.two_pass, c.penalty)).collect::<Vec<_>>();
        assert_eq!(laws(&read), laws(&model));
    }

    /// Every element keeps its type: section family (CAX, CPE, CPS), shape and integration,
    /// and a plane section its thickness, also beside axisymmetric elements (where the reader
    /// holds thickness / 2 pi per radian).
    #[test]
    fn element_types_and_plane_thicknesses_are_written_and_read_back() {
        let deck = "*NODE\n1,1.,0.\n2,3.,0.\n3,3.,1.\n4,1.,1.\n5,2.,0.\n6,3.,.5\n7,2.,1.\n8,1.,.5\n\
            11,1.,2.\n12,3.,2.\n13,2.,2.\n14,1.,1.5\n15,3.,1.5\n16,2.,1.5\n\
            21,5.,0.\n22,7.,0.\n23,5.,1.\n24,6.,0.\n25,6.,.5\n26,5.,.5\n\
            *ELEMENT,TYPE=CAX8R,ELSET=A\n1,1,2,3,4,5,6,7,8\n*ELEMENT,TYPE=CPS8,ELSET=B\n2,4,3,12,11,7,15,13,14\n\
            *ELEMENT,TYPE=CPE6,ELSET=C\n3,21,22,23,24,25,26\n*MATERIAL,NAME=S\n*ELASTIC\n210000.,.3\n\
            *SOLID SECTION,ELSET=A,MATERIAL=S\n*SOLID SECTION,ELSET=B,MATERIAL=S\n2.5\n*SOLID SECTION,ELSET=C,MATERIAL=S\n4.\n\
            *BOUNDARY\n1,1,2\n21,1,2\n*STEP\n*STATIC\n*END STEP\n";
        let model = crate::model::inp::parse(deck, Path::new("types.inp")).unwrap().model;
        assert_eq!(model.element_integration, [Integration::Reduced, Integration::Full, Integration::Reduced]);
        let text = super::to_inp(&model, "types").unwrap();
        for card in ["TYPE=CAX8R", "TYPE=CPS8,", "TYPE=CPE6,"] {
            assert!(text.contains(card), "{card}: {text}");
        }
        let read = crate::model::inp::parse(&text, Path::new("back.inp")).unwrap().model;
        // (the elements come back grouped by type)
        let by_id = |m: &Model| {
            let mut v: Vec<_> = (0..3).map(|e| (m.mesh.element_ids[e], m.element_integration[e], m.element_section[e])).collect();
            v.sort_by_key(|k| k.0);
            v
        };
        let (read, model) = (by_id(&read), by_id(&model));
        assert_eq!(read.iter().map(|k| k.1).collect::<Vec<_>>(), model.iter().map(|k| k.1).collect::<Vec<_>>());
        for ((_, _, a), (_, _, b)) in read.iter().zip(&model) {
            match (a, b) {
                (Section::PlaneStress { thickness: s }, Section::PlaneStress { thickness: t })
                | (Section::PlaneStrain { thickness: s }, Section::PlaneStrain { thickness: t }) => assert!((s - t).abs() < 1e-12 * t, "{s} vs {t}"),
                _ => assert_eq!(a, b),
            }
        }
    }

    /// A node-based slave surface is written back as its nodes, one a line, and read back as
    /// the same slave points.
    #[test]
    fn a_node_based_slave_is_written_as_its_nodes_and_read_back() {
        let deck = "*NODE\n1,0.,0.\n2,2.,0.\n3,2.,1.\n4,0.,1.\n5,1.,0.\n6,2.,.5\n7,1.,1.\n8,0.,.5\n\
            11,.5,1.\n12,1.5,1.\n13,1.5,2.\n14,.5,2.\n15,1.,1.\n16,1.5,1.5\n17,1.,2.\n18,.5,1.5\n\
            *ELEMENT,TYPE=CPE8,ELSET=EALL\n1,1,2,3,4,5,6,7,8\n2,11,12,13,14,15,16,17,18\n*MATERIAL,NAME=S\n*ELASTIC\n210000.,.3\n\
            *SOLID SECTION,ELSET=EALL,MATERIAL=S\n1.\n*SURFACE,NAME=BOTTOM,TYPE=NODE\n11\n12\n15\n18\n*SURFACE,NAME=TOP\n1,S3\n\
            *CONTACT PAIR,INTERACTION=I,TYPE=NODE TO SURFACE\nBOTTOM,TOP\n*SURFACE INTERACTION,NAME=I\n\
            *SURFACE BEHAVIOR,PRESSURE-OVERCLOSURE=EXPONENTIAL\n.01,1.\n*BOUNDARY\n1,1,2\n2,2,2\n*STEP\n*STATIC\n*DLOAD\n2,P3,.3\n*END STEP\n";
        let mut model = crate::model::inp::parse(deck, Path::new("nodes.inp")).unwrap().model;
        // the reader names a pair SLAVE-MASTER, which the writer's names may not hold
        model.contacts[0].name = "PAIR".into();
        let ids = |m: &Model| m.contacts[0].slave_nodes.as_ref().map(|n| n.iter().map(|&k| m.mesh.node_ids[k]).collect::<Vec<_>>());
        assert_eq!(ids(&model), Some(vec![11, 12, 15, 18]));
        let text = super::to_inp(&model, "nodes").unwrap();
        assert!(text.contains("*SURFACE, NAME=BOTTOM, TYPE=NODE\n11\n12\n15\n18\n"), "{text}");
        let read = crate::model::inp::parse(&text, Path::new("back.inp")).unwrap().model;
        assert_eq!(ids(&read), ids(&model));
    }
}

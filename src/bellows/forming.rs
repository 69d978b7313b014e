//! The bellows hydroformed from a straight tube (`bellows --form`): the tube of n nested plies
//! (each its own body, the interfaces in contact), its ends clamped as tangents, between die
//! plates at every root. Internal pressure bulges the tube between the dies (step `bulge`, then
//! `settle` to the forming pressure), the dies close axially to the pitch with the pressure
//! held (`close`), the pressure is let out (`release`) and the dies drawn out radially past the
//! crests with the far tangent let go (`springback`): what is left is the formed bellows, its
//! thinning, cold work and residual stress. The dies are rigid: every node of a die plate
//! moves as prescribed. [`service_model`] puts the formed bellows in service after these steps.
//!
//! Geometry: the tube's inside at the bellows' inside radius Db / 2 (the pack on the tangents),
//! its convoluted part N developed lengths long; die k's plate (2 rir thick, a full-round nose
//! of radius rir) first touches the tube's outside at z = Lt + k L, closing to Lt + k (q - c).
//! The figures of what was formed are `forming::measure`'s, of its service `forming::service`'s.

pub mod code;
pub mod measure;
pub mod pictures;
pub mod service;
pub mod workflow;

use super::spec::forming::FORMING_TEMPERATURE;
use super::spec::DesignSpec;
use crate::error::Result;
use crate::model::mesh::{mapped_block, Edge, Mesh, MeshSets};
use crate::model::perturbation::{HarmonicComponent, HarmonicDisplacement, Perturbation};
use crate::model::{
    Component, ContactIntegration, ContactPair, Friction, GeneralStep, Material, Model, OutputControls, Penalty, Predictor, PrescribedDisplacement, Pressure,
    Step, SteppingControls, Temperature,
};
use std::f64::consts::PI;

/// Elements around a die's nose (a half circle).
const NOSE_ELEMENTS: usize = 16;

/// Increments of the springback: the plates slide off the sidewalls, each release a small
/// snap; asked in 20 (the increment grown back after each cutback and cut again) the seed's
/// took 299 with 150 cutbacks, 86 s on the quick mesh; asked in 100, 100 and none, 23 s.
const SPRINGBACK_INCREMENTS: usize = 100;

/// How many times `--form` forms the bellows at most: a first forming, then, where its w or
/// q misses the target by more than [`measure::TOLERANCE`], again with the tube and the dies
/// corrected by what it missed (the maker's tool tryout).
pub const TRYOUTS: usize = 3;

/// The forming's steps: the service's follow them.
pub const FORMING_STEPS: usize = 5;

/// How far past the crests the dies are drawn out at the end, mm (beyond the convolution height):
/// clear of the crests through the service's stroke.
const DRAW_CLEAR: f64 = 5.0;

/// The forming's dimensions, from the joint.
#[derive(Clone, Copy, Debug)]
pub struct FormingGeometry {
    /// The pack's inside radius (the tube's bore), its thickness, one ply's.
    pub bore: f64,
    pub pack: f64,
    pub ply: f64,
    /// The tube's developed length per convolution, and the tangents'.
    pub developed: f64,
    pub tangent: f64,
    /// The dies' nose radius (rir), the radius of the nose's centre, the plate's outer radius.
    pub nose: f64,
    pub nose_centre: f64,
    pub plate_outer: f64,
    pub convolutions: usize,
    /// The pitch the dies close to (the pitch less the overclosure).
    pub closed_pitch: f64,
}

impl FormingGeometry {
    pub fn of(p: &DesignSpec) -> Self {
        let (bore, pack) = (p.tube_outer_radius(), p.pack_thickness());
        let nose = p.torus_radius() - pack / 2.0;
        FormingGeometry {
            bore,
            pack,
            ply: p.bellows.ply_thickness,
            developed: p.developed_length(),
            tangent: p.bellows.tangent_length,
            nose,
            nose_centre: bore + pack + nose,
            plate_outer: bore + pack + p.bellows.convolution_height + nose,
            convolutions: p.bellows.convolutions,
            closed_pitch: p.bellows.pitch - p.overclose(),
        }
    }

    /// Where the convoluted part of the tube starts and ends (z, before forming).
    pub fn convoluted(&self) -> [f64; 2] {
        [self.tangent, self.tangent + self.convolutions as f64 * self.developed]
    }

    /// The tube's length.
    pub fn tube_length(&self) -> f64 {
        self.convoluted()[1] + self.tangent
    }

    /// Die k's axial movement when the dies have closed.
    pub fn die_travel(&self, k: usize) -> f64 {
        k as f64 * (self.closed_pitch - self.developed)
    }
}

fn count(length: f64, size: f64) -> usize {
    ((length / size).round() as usize).max(1)
}

/// The tube's plies and the die plates, their sets: `plyK` (elements), `plyK_inner` and
/// `plyK_outer` (surfaces), `dieK` (elements and nodes), `dies` (the plates' faces), the
/// clamped tangents `tangent_a` and `tangent_b` (nodes).
pub fn mesh(p: &DesignSpec) -> Result<(Mesh, MeshSets)> {
    let g = FormingGeometry::of(p);
    let h = p.joint.ply_element_length;
    let [z0, z1] = g.convoluted();
    // stations along the tube: the tangents, then each convolution's developed length
    let mut along = super::joint::stations(0.0, z0, count(g.tangent, h));
    for k in 0..g.convolutions {
        let a = z0 + k as f64 * g.developed;
        along.extend(&super::joint::stations(a, a + g.developed, count(g.developed, h))[1..]);
    }
    along.extend(&super::joint::stations(z1, g.tube_length(), count(g.tangent, h))[1..]);
    let mut mesh = Mesh::default();
    let mut sets = MeshSets::default();
    let add = |name: String, (m, s): (Mesh, MeshSets), mesh: &mut Mesh, sets: &mut MeshSets| {
        let (n0, e0) = mesh.append(&m);
        sets.element_sets.insert(name.clone(), (e0..mesh.elements.len()).collect());
        sets.node_sets.insert(name.clone(), (n0..mesh.coords.len()).collect());
        for side in ["inner", "outer"] {
            let edges = s.surfaces[side].iter().map(|e| Edge { element: e.element + e0, side: e.side }).collect();
            sets.add_surface(mesh, &format!("{name}_{side}"), edges);
        }
    };
    for ply in 0..p.bellows.plies {
        let inside = g.bore + ply as f64 * g.ply;
        let through = super::joint::stations(inside, inside + g.ply, p.joint.ply_elements);
        let block = mapped_block([p.joint.ply_elements, (along.len() - 1) / 2], |i, j| [through[i], along[j]]);
        add(format!("ply{}", ply + 1), block, &mut mesh, &mut sets);
    }
    let path = die_profile(&g, h);
    let depth = 0.4 * g.nose;
    for k in 0..=g.convolutions {
        let zk = z0 + k as f64 * g.developed;
        // i through the plate (0 on the face), j along the profile: (i, j) counter-clockwise
        let block = mapped_block([1, (path.len() - 1) / 2], |i, j| {
            let ([r, z], [a, b]) = path[j];
            let d = depth * i as f64 / 2.0;
            [r + d * b, zk + z - d * a]
        });
        add(format!("die{k}"), block, &mut mesh, &mut sets);
    }
    mesh.node_ids = (1..=mesh.coords.len() as u64).collect();
    mesh.element_ids = (1..=mesh.elements.len() as u64).collect();
    let dies: Vec<Edge> = (0..=g.convolutions).flat_map(|k| sets.surfaces[&format!("die{k}_inner")].clone()).collect();
    sets.add_surface(&mesh, "dies", dies);
    let eps = 1e-9 * g.tube_length();
    let plies: Vec<usize> = (1..=p.bellows.plies).flat_map(|k| sets.node_sets[&format!("ply{k}")].clone()).collect();
    let on = |pred: &dyn Fn(f64) -> bool| -> Vec<usize> { plies.iter().copied().filter(|&n| pred(mesh.coords[n][1])).collect() };
    let (a, b) = (on(&|z| z <= z0 + eps), on(&|z| z >= z1 - eps));
    // the joint's names, which its perturbation steps hold and load (`formed_perturbations`)
    sets.node_sets.insert("fixed_end".into(), a.clone());
    sets.node_sets.insert("moving_end".into(), b.clone());
    sets.node_sets.insert("tangent_a".into(), a);
    sets.node_sets.insert("tangent_b".into(), b);
    sets.node_sets.insert("all".into(), (0..mesh.coords.len()).collect());
    let wetted = sets.surfaces["ply1_inner"].clone();
    sets.add_surface(&mesh, "wetted", wetted);
    Ok((mesh, sets))
}

/// A die plate's face (z about its nose's centre), each station with its unit tangent: down
/// the face towards the tube, round the nose, up the other face.
fn die_profile(g: &FormingGeometry, h: f64) -> Vec<([f64; 2], [f64; 2])> {
    let face = g.plate_outer - g.nose_centre;
    let n_face = count(face, h);
    let mut path: Vec<([f64; 2], [f64; 2])> = Vec::new();
    for s in super::joint::stations(0.0, 1.0, n_face) {
        path.push(([g.plate_outer - s * face, -g.nose], [-1.0, 0.0]));
    }
    // the nose from 3 pi / 2 down to pi / 2 (through pi: the tip, nearest the axis)
    for s in &super::joint::stations(0.0, 1.0, NOSE_ELEMENTS)[1..] {
        let a = 1.5 * PI - s * PI;
        path.push(([g.nose_centre + g.nose * a.cos(), g.nose * a.sin()], [a.sin(), -a.cos()]));
    }
    for s in &super::joint::stations(0.0, 1.0, n_face)[1..] {
        path.push(([g.nose_centre + s * face, g.nose], [1.0, 0.0]));
    }
    path
}

/// The formed bellows in service, continuing the forming's file from its end: the design
/// pressure inside with the far tangent held where the springback left it (`sprung`, its axial
/// displacement) (`pressure`), then the stroke (`compress`); the forming's model with these two
/// steps after its own.
pub fn service_model(p: &DesignSpec, sprung: f64, perturbations: Vec<Perturbation>) -> Result<Model> {
    let mut m = model(p)?;
    let hold = |value: f64| vec![PrescribedDisplacement { node_set: "tangent_b".into(), component: Component::Z, value }];
    let pressure = GeneralStep {
        pressures: vec![Pressure { surface: "ply1_inner".into(), value: p.design.pressure }],
        ..GeneralStep::new(SERVICE_STEPS[0], 4, hold(sprung))
    };
    let compress = GeneralStep::new(SERVICE_STEPS[1], p.joint.increments, hold(sprung - p.displacement()));
    m.steps.extend([pressure, compress].map(Step::General));
    m.set_perturbations(perturbations);
    m.validate()?;
    Ok(m)
}

/// Whether `r` is a `--form` run's file (the forming's or its service's): its mesh has the dies.
pub fn is_forming_file(r: &crate::io::reader::ResultsReader) -> Result<bool> {
    Ok(r.element_set_names()?.iter().any(|s| s == "die0"))
}

/// The joint's perturbation steps `steps` (its stability's, frequencies', flexibility's) on the
/// formed bellows: its tangents for the joint's tube ends (the sets of [`mesh`]), the dies held
/// still (drawn out past the crests, their contact left out) and the contact pairs the formed
/// bellows has not (the joint's guide sleeve) dropped.
pub fn formed_perturbations(p: &DesignSpec, steps: Vec<Perturbation>) -> Vec<Perturbation> {
    let plies = (1..p.bellows.plies).map(|k| format!("ply{k}_ply{}", k + 1));
    let pairs: Vec<String> = super::joint::FOLD_PAIRS.iter().map(|s| s.to_string()).chain(plies).collect();
    let held = |set: String| {
        [HarmonicComponent::R, HarmonicComponent::Z, HarmonicComponent::T].map(|component| HarmonicDisplacement {
            node_set: set.clone(),
            component,
            value: 0.0,
        })
    };
    steps
        .into_iter()
        .map(|mut s| {
            s.without_contact.retain(|name| pairs.contains(name));
            s.without_contact.push("dies".into());
            s.displacements.extend((0..=p.bellows.convolutions).flat_map(|k| held(format!("die{k}"))));
            s
        })
        .collect()
}

/// The service's steps, after the forming's five.
pub const SERVICE_STEPS: [&str; 2] = ["pressure", "compress"];

/// The forming's model: the annealed tube, its five steps.
pub fn model(p: &DesignSpec) -> Result<Model> {
    p.validate_forming()?;
    let g = FormingGeometry::of(p);
    let (mesh, sets) = mesh(p)?;
    let material = Material {
        name: "annealed".into(),
        youngs_modulus: p.forming_modulus()?,
        poissons_ratio: p.material.poissons_ratio,
        thermal_expansion: 0.0,
        plasticity: Some(p.forming_curve()?),
        kinematic: crate::model::KinematicHardening::NONE,
        density: p.density(),
        conductivity: 0.0,
    };
    let friction = p.forming.friction.filter(|&mu| mu > 0.0).map(|mu| Friction {
        coefficient: mu,
        tangential_penalty: p.joint.elastic_slip.is_none().then_some(p.joint.tangential_penalty),
        elastic_slip: p.joint.elastic_slip,
    });
    let pair = |name: String, slave: String, master: &str, two_pass: bool| ContactPair {
        name,
        slave,
        master: master.to_string(),
        two_pass,
        integration: ContactIntegration::Segment,
        penalty: Penalty::Stiffness(p.forming_penalty()),
        capture_distance: (2.0 * g.ply).max(2.0 * p.joint.ply_element_length),
        augmented_lagrangian: None,
        exclude_neighbours: 4,
        friction,
        adjust: None,
        slave_nodes: None,
    };
    let n = p.bellows.plies;
    let mut contacts: Vec<ContactPair> =
        (1..n).map(|k| pair(format!("ply{k}_ply{}", k + 1), format!("ply{}_inner", k + 1), &format!("ply{k}_outer"), true)).collect();
    contacts.push(pair("dies".into(), format!("ply{n}_outer"), "dies", false));
    // the convolutions' faces on each other in service (in the model from the start: a restart
    // keeps its contact pairs)
    let [outside, inside] = super::joint::FOLD_PAIRS;
    contacts.push(pair(outside.into(), format!("ply{n}_outer"), &format!("ply{n}_outer"), false));
    contacts.push(pair(inside.into(), "ply1_inner".into(), "ply1_inner", false));
    let set = |s: &str, component: Component, value: f64| PrescribedDisplacement { node_set: s.into(), component, value };
    // the dies out by `radial`, at `pitch` apart (the straight tube's developed length at first)
    let dies = |radial: f64, pitch: f64| -> Vec<PrescribedDisplacement> {
        (0..=g.convolutions)
            .flat_map(|k| {
                let name = format!("die{k}");
                [set(&name, Component::R, radial), set(&name, Component::Z, k as f64 * (pitch - g.developed))]
            })
            .collect()
    };
    let end = g.die_travel(g.convolutions);
    let clamps = |b: f64| {
        vec![set("tangent_a", Component::R, 0.0), set("tangent_a", Component::Z, 0.0), set("tangent_b", Component::R, 0.0), set("tangent_b", Component::Z, b)]
    };
    let pressure = |value: f64| vec![Pressure { surface: "ply1_inner".into(), value }];
    let forming_pressure = p.forming_pressure()?;
    let bulge = GeneralStep { pressures: pressure(p.bulge_pressure()?), ..GeneralStep::new("bulge", 4, [clamps(0.0), dies(0.0, g.developed)].concat()) };
    let settle = GeneralStep { pressures: pressure(forming_pressure), ..GeneralStep::new("settle", 2, Vec::new()) };
    let close = GeneralStep::new("close", p.forming_increments(), [clamps(end), dies(0.0, g.closed_pitch)].concat());
    let release = GeneralStep { pressures: pressure(0.0), ..GeneralStep::new("release", 4, Vec::new()) };
    // the dies drawn out past the crests, the far tangent free to spring back along the axis
    // (opening the dies first does not help: the bellows springs less than they open, and the
    // last dies drag their convolutions; measured on the seed joint, 334 increments for 35)
    let free = vec![set("tangent_a", Component::R, 0.0), set("tangent_a", Component::Z, 0.0), set("tangent_b", Component::R, 0.0)];
    let springback = GeneralStep {
        release_constraints: true,
        ..GeneralStep::new("springback", SPRINGBACK_INCREMENTS, [free, dies(p.bellows.convolution_height + DRAW_CLEAR, g.closed_pitch)].concat())
    };
    // the dies move as prescribed at every node: their material only has to be something (elastic,
    // that no return map runs there); their stresses mean nothing (drawn out radially, a ring
    // is stretched in hoop)
    let die = Material { name: "die".into(), plasticity: None, ..material.clone() };
    let mut element_material = vec![0; mesh.elements.len()];
    for k in 0..=g.convolutions {
        for &e in &sets.element_sets[&format!("die{k}")] {
            element_material[e] = 1;
        }
    }
    let model = Model {
        element_material,
        node_sets: sets.node_sets,
        element_sets: sets.element_sets,
        surfaces: sets.surfaces,
        materials: vec![material, die],
        reference_temperature: Temperature::Uniform(FORMING_TEMPERATURE),
        stepping: SteppingControls { easy_iterations: 12, convergence: p.joint.convergence, predictor: Predictor::Extrapolate, ..SteppingControls::default() },
        output: OutputControls { every: p.joint.output_every, precision: p.joint.output_precision, ..OutputControls::default() },
        contacts,
        steps: [bulge, settle, close, release, springback].into_iter().map(Step::General).collect(),
        source_text: p.to_toml(),
        ..Model::on_mesh(mesh)
    };
    model.validate()?;
    Ok(model)
}

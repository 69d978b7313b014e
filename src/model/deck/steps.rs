//! The TOML deck's steps, each by its procedure: a general (static) step, a perturbation step
//! (harmonic, frequency, buckle), a heat step.

use super::schema::{SetTemperatureToml, StepToml, TemperatureToml};
use crate::element::body_load::BodyForce;
use crate::error::{Error, Result};
use crate::model::heat::{HeatStep, HeldTemperature};
use crate::model::mesh::Mesh;
use crate::model::perturbation::{Analysis, HarmonicComponent, HarmonicDisplacement, Perturbation, RingMotion};
use crate::model::{BodyLoad, Component, Friction, FrictionChange, GeneralStep, NodalForce, PrescribedDisplacement, Pressure, Temperature};
use std::collections::BTreeMap;

/// General step `s` named `name` with its `pressures`; a temperature it sets becomes
/// `temperature_now`, the next step's start (`plane`: forces are the thickness's, not a ring's).
pub(super) fn general(
    s: &StepToml,
    name: String,
    pressures: Vec<Pressure>,
    mesh: &Mesh,
    node_sets: &BTreeMap<String, Vec<usize>>,
    plane: bool,
    temperature_now: &mut Temperature,
) -> Result<GeneralStep> {
    if let Some(mode) = s.mode {
        return Err(Error::input(format!("step '{name}': mode = {mode} is for the perturbation procedures (\"harmonic\", \"frequency\", \"buckle\")")));
    }
    if s.without_contact.is_some() || s.eigenvalues.is_some() {
        return Err(Error::input(format!("step '{name}': without_contact and eigenvalues are for the perturbation procedures")));
    }
    let mut displacements = Vec::new();
    for b in &s.boundary {
        if let Some(key) =
            [("ut", b.ut), ("lateral", b.lateral), ("rotation", b.rotation), ("pivot", b.pivot)].iter().find(|(_, v)| v.is_some()).map(|(k, _)| k)
        {
            return Err(Error::input(format!("step '{name}': boundary on '{}': {key} is for procedure = \"harmonic\"", b.set)));
        }
        if b.ur.is_none() && b.uz.is_none() {
            return Err(Error::input(format!("step '{name}': boundary on '{}' sets neither ur nor uz", b.set)));
        }
        for (component, value) in [(Component::R, b.ur), (Component::Z, b.uz)] {
            if let Some(value) = value {
                displacements.push(PrescribedDisplacement { node_set: b.set.clone(), component, value });
            }
        }
    }
    let mut nodal_forces = Vec::new();
    for f in &s.force {
        let nodes = node_sets.get(&f.set).ok_or_else(|| Error::input(format!("step '{name}': force on an unknown node set '{}'", f.set)))?;
        if f.fr.is_none() && f.fz.is_none() {
            return Err(Error::input(format!("step '{name}': force on '{}' gives neither fr nor fz (N around the ring)", f.set)));
        }
        // the whole ring's force, kept per radian (a plane model's force as it is)
        let per = if plane { 1.0 } else { std::f64::consts::TAU };
        for (component, ring) in [(Component::R, f.fr), (Component::Z, f.fz)] {
            let Some(ring) = ring else { continue };
            nodal_forces.extend(nodes.iter().map(|&node| NodalForce { node, component, value: ring / per }));
        }
    }
    let mut body_loads = Vec::new();
    for b in &s.body_load {
        let force = match (b.gravity, b.spin) {
            (Some(g), None) => BodyForce::Gravity(g),
            (None, Some(omega)) => BodyForce::Spin(omega * omega),
            _ => return Err(Error::input(format!("step '{name}': body_load on '{}': give one of gravity (mm/s^2) or spin (rad/s)", b.elements))),
        };
        body_loads.push(BodyLoad { elements: b.elements.clone(), force });
    }
    let increments = s.increments.unwrap_or(1);
    let temperature = s.temperature.as_ref().map(|t| t.field(mesh, node_sets, Some(temperature_now), &format!("step '{name}': temperature"))).transpose()?;
    if let Some(t) = &temperature {
        *temperature_now = t.clone();
    }
    let friction_changes = s
        .contact_friction
        .iter()
        .map(|c| {
            let friction = Friction::from_values(&c.pair, Some(c.friction), c.tangential_penalty, c.elastic_slip)
                .map_err(|e| Error::input(format!("step '{name}': contact_friction: {e}")))?;
            Ok(FrictionChange { pair: c.pair.clone(), friction })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(GeneralStep {
        name,
        increments,
        displacements,
        pressures,
        temperature,
        time_span: None,
        body_loads,
        release_constraints: false,
        without_field_output: false,
        friction_changes,
        nodal_forces,
    })
}

/// Perturbation step `s` named `name` of `procedure` ("harmonic", "frequency" or "buckle"),
/// with its harmonic `pressures`.
pub(super) fn perturbation(s: &StepToml, name: String, pressures: Vec<Pressure>, procedure: &str) -> Result<Perturbation> {
    let mode = s.mode.ok_or_else(|| Error::input(format!("step '{name}': procedure = \"{procedure}\" needs its mode (mode = n)")))?;
    if procedure == "harmonic" && s.eigenvalues.is_some() {
        return Err(Error::input(format!("step '{name}': eigenvalues is for procedure = \"frequency\" or \"buckle\"")));
    }
    let analysis = Analysis::of_procedure(procedure, s.eigenvalues.unwrap_or(1)).expect("a perturbation procedure");
    if s.increments.is_some() || s.temperature.is_some() || !s.body_load.is_empty() || !s.contact_friction.is_empty() || !s.force.is_empty() {
        return Err(Error::input(format!(
            "step '{name}': a perturbation step has no increments, temperature, body loads, nodal forces or friction changes (it is linear, about the state before)"
        )));
    }
    let (mut displacements, mut rings) = (Vec::new(), Vec::new());
    for b in &s.boundary {
        let set = b.set.clone();
        let amplitudes = [(HarmonicComponent::R, b.ur), (HarmonicComponent::Z, b.uz), (HarmonicComponent::T, b.ut)];
        let ring = b.lateral.is_some() || b.rotation.is_some() || b.pivot.is_some();
        if ring && amplitudes.iter().any(|(_, v)| v.is_some()) {
            return Err(Error::input(format!(
                "step '{name}': boundary on '{set}': lateral and rotation move the ring rigidly; give them or ur, uz, ut, not both"
            )));
        }
        if ring {
            rings.push(RingMotion { node_set: set, lateral: b.lateral.unwrap_or(0.0), rotation: b.rotation.unwrap_or(0.0), pivot: b.pivot });
            continue;
        }
        if amplitudes.iter().all(|(_, v)| v.is_none()) {
            return Err(Error::input(format!("step '{name}': boundary on '{set}' sets none of ur, uz, ut, lateral, rotation")));
        }
        for (component, value) in amplitudes {
            if let Some(value) = value {
                displacements.push(HarmonicDisplacement { node_set: set.clone(), component, value });
            }
        }
    }
    Ok(Perturbation { name, mode, displacements, rings, pressures, without_contact: s.without_contact.clone().unwrap_or_default(), analysis })
}

/// A `procedure = "heat"` step: `temperature = [{ set = ..., value = ... }, ...]` holds those
/// sets' temperatures; nothing else belongs in it.
pub(super) fn heat(s: &StepToml, name: &str) -> Result<HeatStep> {
    let mechanical = [
        ("mode", s.mode.is_some()),
        ("without_contact", s.without_contact.is_some()),
        ("eigenvalues", s.eigenvalues.is_some()),
        ("increments", s.increments.is_some()),
        ("boundary", !s.boundary.is_empty()),
        ("pressure", !s.pressure.is_empty()),
        ("force", !s.force.is_empty()),
        ("body_load", !s.body_load.is_empty()),
        ("contact_friction", !s.contact_friction.is_empty()),
    ];
    if let Some((key, _)) = mechanical.iter().find(|(_, given)| *given) {
        return Err(Error::input(format!("step '{name}': {key} has no meaning in a heat step (it holds temperatures alone)")));
    }
    let held = |t: &SetTemperatureToml| {
        let set =
            t.set.clone().ok_or_else(|| Error::input(format!("step '{name}': a heat step's temperature entries each name their node set (set = ...)")))?;
        Ok(HeldTemperature { node_set: set, value: t.value })
    };
    let temperatures = match &s.temperature {
        Some(TemperatureToml::Sets(sets)) => sets.iter().map(held).collect::<Result<Vec<_>>>()?,
        _ => {
            return Err(Error::input(format!(
                "step '{name}': a heat step holds temperatures on node sets: temperature = [{{ set = \"...\", value = ... }}, ...]"
            )))
        }
    };
    Ok(HeatStep { name: name.to_string(), temperatures })
}

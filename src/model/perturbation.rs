//! Linear perturbation steps (Abaqus's perturbation procedures): after the general steps, the
//! response to a load of one circumferential harmonic n about the state they end in, which
//! they leave unchanged. The load is prescribed harmonic displacement amplitudes on node sets,
//! rigid motions of end rings (n = 1) and harmonic pressure amplitudes; the answer is the
//! harmonic displacement field and each set's reactions (`solve::procedures::perturbation`,
//! `element::harmonic`).

use super::{Model, Pressure};
use crate::error::{Error, Result};

/// A harmonic amplitude component: u_r = U_r cos n theta, u_z = U_z cos n theta, u_theta =
/// U_t sin n theta (n = 0: U_t alone, the twist).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HarmonicComponent {
    R,
    Z,
    T,
}

impl HarmonicComponent {
    pub fn index(self) -> usize {
        match self {
            HarmonicComponent::R => 0,
            HarmonicComponent::Z => 1,
            HarmonicComponent::T => 2,
        }
    }

    pub fn name(self) -> &'static str {
        ["ur", "uz", "ut"][self.index()]
    }
}

/// An amplitude prescribed on every node of a set (mm).
#[derive(Clone, Debug, PartialEq)]
pub struct HarmonicDisplacement {
    pub node_set: String,
    pub component: HarmonicComponent,
    pub value: f64,
}

/// A rigid motion of a set's ring (mode 1): a translation `lateral` (mm) across the axis and a
/// rotation `rotation` (radians) about a diameter through the point z_c on the axis (`pivot`, in
/// the base state's current geometry; by default the set's centre), u_x = lateral + rotation
/// (z - z_c), u_z = -rotation x: all three amplitudes of its nodes, U_r = -U_t = lateral +
/// rotation (z - z_c), U_z = -rotation r. The set's moment is reported about the same point.
#[derive(Clone, Debug, PartialEq)]
pub struct RingMotion {
    pub node_set: String,
    pub lateral: f64,
    pub rotation: f64,
    pub pivot: Option<f64>,
}

/// What a perturbation step computes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Analysis {
    /// The response to its prescribed amplitudes and harmonic pressures.
    Response,
    /// The lowest natural frequencies of its mode, its amplitudes held at zero where it names
    /// them.
    Frequency { eigenvalues: usize },
    /// The lowest buckling load factors of its mode under its load: the axisymmetric load of its
    /// pressures and its ur / uz values, applied about the base state.
    Buckle { eigenvalues: usize },
}

impl Analysis {
    /// The step's procedure as decks and the results file name it.
    pub fn procedure(&self) -> &'static str {
        match self {
            Analysis::Response => "harmonic",
            Analysis::Frequency { .. } => "frequency",
            Analysis::Buckle { .. } => "buckle",
        }
    }

    /// The analysis a procedure name stands for, with `eigenvalues` asked of an eigenvalue
    /// procedure; None for a name that is no perturbation procedure.
    pub fn of_procedure(procedure: &str, eigenvalues: usize) -> Option<Analysis> {
        match procedure {
            "harmonic" => Some(Analysis::Response),
            "frequency" => Some(Analysis::Frequency { eigenvalues }),
            "buckle" => Some(Analysis::Buckle { eigenvalues }),
            _ => None,
        }
    }
}

/// The most eigenvalues a step may ask for.
pub const MAX_EIGENVALUES: usize = 50;

/// One perturbation step.
#[derive(Clone, Debug, PartialEq)]
pub struct Perturbation {
    pub name: String,
    pub mode: u32,
    pub displacements: Vec<HarmonicDisplacement>,
    pub rings: Vec<RingMotion>,
    /// Harmonic pressure amplitudes, p cos n theta (MPa, positive pushing into the body).
    pub pressures: Vec<Pressure>,
    /// Contact pairs whose closed nodes carry nothing in this step (by name).
    pub without_contact: Vec<String>,
    pub analysis: Analysis,
}

/// The largest mode accepted: beyond it a Q8 mesh of any reasonable ring resolves nothing.
pub const MAX_MODE: u32 = 1000;

impl Perturbation {
    /// Checks the step against its model: known sets and surfaces, rings only for n = 1, finite
    /// values, a general step before it.
    pub fn validate(&self, model: &Model) -> Result<()> {
        let at = |what: String| Error::input(format!("perturbation step '{}': {what}", self.name));
        if model.general_step_count() == 0 {
            return Err(at("a perturbation step needs a general step before it (its base state)".into()));
        }
        // the spin of the base state: each set's last value, kept by the steps that do not
        // restate it (a spin ramped back to 0 leaves a base state at rest)
        let mut spin: std::collections::BTreeMap<&str, (f64, &str)> = std::collections::BTreeMap::new();
        for s in model.general_steps() {
            for b in &s.body_loads {
                if let crate::element::body_load::BodyForce::Spin(omega) = b.force {
                    spin.insert(b.elements.as_str(), (omega, s.name.as_str()));
                }
            }
        }
        if let Some((_, (omega, step))) = spin.iter().find(|(_, (omega, _))| *omega != 0.0) {
            return Err(at(format!(
                "the base state spins ({omega} rad/s, from step '{step}'): perturbation steps leave the spin's softening out, and are refused about it (ramp the spin to 0 in a general step first)"
            )));
        }
        if let Some(m) = model.materials.iter().find(|m| !m.kinematic.is_empty()) {
            return Err(at(format!(
                "material '{}' has kinematic hardening: a perturbation step's elastic-plastic tangent about the base state is built for isotropic hardening only (the base state's backstresses are not carried to it)",
                m.name
            )));
        }
        if self.mode > MAX_MODE {
            return Err(at(format!("mode {} is above {MAX_MODE}", self.mode)));
        }
        for d in &self.displacements {
            model.node_set(&d.node_set).map_err(|e| at(e.to_string()))?;
            if !d.value.is_finite() {
                return Err(at(format!("{} on '{}' must be finite", d.component.name(), d.node_set)));
            }
        }
        for r in &self.rings {
            model.node_set(&r.node_set).map_err(|e| at(e.to_string()))?;
            if self.mode != 1 {
                return Err(at(format!("lateral and rotation (on '{}') move a ring rigidly only in mode 1, not {}", r.node_set, self.mode)));
            }
            if !(r.lateral.is_finite() && r.rotation.is_finite() && r.pivot.is_none_or(f64::is_finite)) {
                return Err(at(format!("lateral, rotation and pivot on '{}' must be finite", r.node_set)));
            }
        }
        for p in &self.pressures {
            if !model.surfaces.contains_key(&p.surface) {
                return Err(at(format!("unknown surface '{}'", p.surface)));
            }
            if !p.value.is_finite() {
                return Err(at(format!("pressure on '{}' must be finite", p.surface)));
            }
        }
        for name in &self.without_contact {
            if !model.contacts.iter().any(|c| &c.name == name) {
                return Err(at(format!("without_contact: no contact pair '{name}'")));
            }
        }
        match self.analysis {
            Analysis::Response => {}
            Analysis::Frequency { eigenvalues } | Analysis::Buckle { eigenvalues } if eigenvalues == 0 || eigenvalues > MAX_EIGENVALUES => {
                return Err(at(format!("eigenvalues = {eigenvalues}: give 1 to {MAX_EIGENVALUES}")));
            }
            Analysis::Frequency { .. } => {
                if let Some(d) = self.displacements.iter().find(|d| d.value != 0.0) {
                    return Err(at(format!("a frequency step holds amplitudes at zero: {} = {} on '{}'", d.component.name(), d.value, d.node_set)));
                }
                if let Some(r) = self.rings.iter().find(|r| r.lateral != 0.0 || r.rotation != 0.0) {
                    return Err(at(format!("a frequency step holds rings at rest: lateral = 0 and rotation = 0 on '{}'", r.node_set)));
                }
                if !self.pressures.is_empty() {
                    return Err(at("a frequency step has no load (no pressure)".into()));
                }
                if let Some(m) = model.materials.iter().find(|m| !(m.density > 0.0 && m.density.is_finite())) {
                    return Err(at(format!("material '{}' has no density (t/mm^3; steel 7.85e-9)", m.name)));
                }
                return Ok(());
            }
            Analysis::Buckle { .. } => {
                // a ring held at rest (no lateral motion, no rotation) is a support of the mode
                // alone: the axisymmetric load moves it freely
                if let Some(r) = self.rings.iter().find(|r| r.lateral != 0.0 || r.rotation != 0.0) {
                    return Err(at(format!(
                        "a buckle step's load is axisymmetric: pressures and ur / uz values; a ring ('{}') may only be held (lateral = 0, rotation = 0)",
                        r.node_set
                    )));
                }
                if self.pressures.iter().all(|p| p.value == 0.0) && self.displacements.iter().all(|d| d.value == 0.0) {
                    return Err(at("no load: give a pressure or nonzero ur / uz values (the load the load factors multiply)".into()));
                }
                return Ok(());
            }
        }
        let moved = self.displacements.iter().any(|d| d.value != 0.0) || self.rings.iter().any(|r| r.lateral != 0.0 || r.rotation != 0.0);
        if !moved && self.pressures.iter().all(|p| p.value == 0.0) {
            let pivot = if self.rings.iter().any(|r| r.pivot.is_some()) { " (a ring's pivot only says where it turns)" } else { "" };
            return Err(at(format!(
                "no load: every amplitude and pressure given is zero{pivot}; give nonzero amplitudes (ur, uz, ut), a ring's lateral or rotation, or a pressure"
            )));
        }
        Ok(())
    }
}

//! The deck's steps expanded into the model's: each split at its amplitudes' points and output
//! time points, the loads in force carried from step to step.

use super::properties::{pair_friction, ListedContact};
use super::steps::temperature_field;
use super::{Builder, StepDef, Target};
use crate::element::body_load::BodyForce;
use crate::error::{Error, Result};
use crate::model::{BodyLoad, Component, FrictionChange, GeneralStep, NodalForce, PrescribedDisplacement, Pressure, Temperature};
use std::collections::{BTreeMap, BTreeSet};

impl Builder {
    /// slideline steps ramp every target linearly from the previous step's value; a step whose
    /// loads follow an *AMPLITUDE is split at the amplitude's points so that the piecewise-linear
    /// history is followed exactly.
    /// The deck's steps as slideline's (`contacts`: the deck's pairs, for *CHANGE FRICTION).
    pub(super) fn expand_steps(&mut self, initial_temperature: &Temperature, contacts: &[ListedContact]) -> Result<Vec<GeneralStep>> {
        let mut now = LoadsInForce {
            displacement: self.fixed.iter().map(|k| (k.clone(), 0.0)).collect(),
            pressure: BTreeMap::new(),
            body: BTreeMap::new(),
            cload: BTreeMap::new(),
        };
        let mut temperature_now = initial_temperature.clone();
        let mut out = Vec::new();
        let mut total_time = 0.0;
        for (k, s) in self.steps.iter_mut().enumerate() {
            now.start_step(k, s, &self.fixed, &mut self.notes);
            let increments = ((s.period / s.initial) - 1e-9).ceil().max(1.0) as usize;
            let times = split_times(s, &self.amplitudes, total_time);
            let period = s.period;
            let (d0, p0, b0, t0) = (now.displacement.clone(), now.pressure.clone(), now.body.clone(), temperature_now.clone());
            let c0 = now.cload.clone();
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
                let body: Vec<((String, bool), f64)> =
                    s.body.iter().map(|b| (b.key.clone(), b.at(b0.get(&b.key).copied().unwrap_or(0.0), time, period, &self.amplitudes))).collect();
                for (key, value) in &body {
                    now.body.insert(key.clone(), *value);
                }
                for c in &s.cloads {
                    now.cload.insert(c.key, c.at(c0.get(&c.key).copied().unwrap_or(0.0), time, period, &self.amplitudes));
                }
                // every nodal force in force, as the step's end values
                let nodal_forces = now.cload.iter().map(|(&(node, component), &value)| NodalForce { node, component, value }).collect::<Vec<_>>();
                // every body load in force, as the step's end values
                let body_loads = now
                    .body
                    .iter()
                    .map(|((set, spin), &v)| BodyLoad { elements: set.clone(), force: if *spin { BodyForce::Spin(v) } else { BodyForce::Gravity(v) } })
                    .collect::<Vec<_>>();
                // each line's nodes ramp from their own start (or follow the line's amplitude)
                let temperature = if s.temperature.is_empty() {
                    None
                } else {
                    let amplitudes = &self.amplitudes;
                    let values = s.temperature.iter().flat_map(|t| t.key.iter().map(|&n| (n, t.at(t0.at(n), time, period, amplitudes))));
                    Some(
                        temperature_field(self.mesh.coords.len(), &self.added_midside, Some(&t0), values)
                            .map_err(|_| Error::input("internal: a step's temperature left nodes unset"))?,
                    )
                };
                for d in &displacements {
                    now.displacement.insert((d.node_set.clone(), d.component), d.value);
                }
                for p in &pressures {
                    now.pressure.insert(p.surface.clone(), p.value);
                }
                if let Some(t) = &temperature {
                    temperature_now = t.clone();
                }
                let name = if times.len() == 1 { s.name.clone() } else { format!("{}.{}", s.name, j + 1) };
                let share = ((increments as f64) * (time - previous_time) / s.period).round().max(1.0) as usize;
                let time_span = Some([total_time + previous_time, total_time + time]);
                let release_constraints = s.new_boundaries && j == 0;
                let without_field_output = s.file_requests[0] > 0 && s.file_requests[1] == 0;
                let friction_changes = if j > 0 { Vec::new() } else { friction_changes(s, contacts) };
                out.push(GeneralStep {
                    name,
                    increments: share,
                    displacements,
                    pressures,
                    temperature,
                    time_span,
                    body_loads,
                    release_constraints,
                    without_field_output,
                    friction_changes,
                    nodal_forces,
                });
                previous_time = time;
            }
            total_time += s.period;
            if times.len() > 1 {
                self.notes.push(format!(
                    "{} ({}) is split at its amplitudes' points and output time points into {} sub-steps ending at step times {}",
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

/// The loads in force as the steps expand: each prescribed displacement, pressure, body load
/// and nodal force by its key, at the last sub-step's end.
struct LoadsInForce {
    displacement: BTreeMap<(String, Component), f64>,
    pressure: BTreeMap<String, f64>,
    body: BTreeMap<(String, bool), f64>,
    cload: BTreeMap<(usize, Component), f64>,
}

impl LoadsInForce {
    /// Step `k` (`s`) begins: the model data's constraints join the first step (unless its
    /// *BOUNDARY, OP=NEW releases them); an OP=NEW card releases what it does not restate, the
    /// loads ramping to zero (a note names the constraints released).
    fn start_step(&mut self, k: usize, s: &mut StepDef, fixed: &[(String, Component)], notes: &mut Vec<String>) {
        // fixed model-data constraints join the first step, unless its *BOUNDARY, OP=NEW
        // releases them (as CalculiX does: a first step's OP=NEW starts from no constraint)
        if k == 0 && !s.new_boundaries {
            for key in fixed {
                if !s.boundaries.iter().any(|b| &b.key == key) {
                    s.boundaries.insert(0, Target { key: key.clone(), value: 0.0, amplitude: None });
                }
            }
        }
        if s.new_boundaries {
            // the constraints of earlier steps (and of the model data) not restated go
            let released: Vec<String> = self
                .displacement
                .keys()
                .filter(|k| !s.boundaries.iter().any(|b| &b.key == *k))
                .map(|(set, c)| format!("{set} {}", if *c == Component::R { "u_r" } else { "u_z" }))
                .collect();
            self.displacement.retain(|k, _| s.boundaries.iter().any(|b| &b.key == k));
            if !released.is_empty() {
                notes.push(format!("{} ({}): *BOUNDARY, OP=NEW releases {} at the step's start", s.name, s.at, released.join(", ")));
            }
        }
        if s.new_cloads {
            for (key, v) in self.cload.iter_mut() {
                if !s.cloads.iter().any(|c| &c.key == key) {
                    s.cloads.push(Target { key: *key, value: 0.0, amplitude: None });
                    *v = 0.0;
                }
            }
        }
        if s.new_loads {
            for (surface, v) in self.pressure.iter_mut() {
                if !s.pressures.iter().any(|p| &p.key == surface) {
                    s.pressures.push(Target { key: surface.clone(), value: 0.0, amplitude: None });
                    *v = 0.0;
                }
            }
            for (key, v) in self.body.iter_mut() {
                if !s.body.iter().any(|b| &b.key == key) {
                    s.body.push(Target { key: key.clone(), value: 0.0, amplitude: None });
                    *v = 0.0;
                }
            }
        }
    }
}

/// The times (from the step's start) where step `s` is split: its amplitudes' points and the
/// time points its output requests name, so that increments end there; its end last.
fn split_times(s: &StepDef, amplitudes: &BTreeMap<String, Vec<(f64, f64)>>, total_time: f64) -> Vec<f64> {
    let mut used: BTreeSet<&String> = BTreeSet::new();
    used.extend(s.boundaries.iter().filter_map(|b| b.amplitude.as_ref()));
    used.extend(s.pressures.iter().filter_map(|b| b.amplitude.as_ref()));
    used.extend(s.body.iter().filter_map(|b| b.amplitude.as_ref()));
    used.extend(s.cloads.iter().filter_map(|b| b.amplitude.as_ref()));
    used.extend(s.temperature.iter().filter_map(|b| b.amplitude.as_ref()));
    let listed = s.time_points.iter().flat_map(|(times, total)| times.iter().map(move |&t| if *total { t - total_time } else { t }));
    let mut times: Vec<f64> =
        used.iter().flat_map(|a| amplitudes[*a].iter().map(|p| p.0)).chain(listed).filter(|&t| t > 1e-12 * s.period && t < s.period * (1.0 - 1e-12)).collect();
    times.push(s.period);
    times.sort_by(f64::total_cmp);
    times.dedup_by(|a, b| (*a - *b).abs() <= 1e-12 * s.period);
    times
}

/// Step `s`'s friction changes, which act from its start (on its first sub-step), for every
/// pair of the interaction.
fn friction_changes(s: &StepDef, contacts: &[ListedContact]) -> Vec<FrictionChange> {
    s.friction_changes
        .iter()
        .flat_map(|(interaction, friction)| {
            contacts
                .iter()
                .filter(move |c| c.interaction == *interaction)
                .map(|c| FrictionChange { pair: c.pair.name.clone(), friction: pair_friction(*friction, c.passes) })
        })
        .collect()
}

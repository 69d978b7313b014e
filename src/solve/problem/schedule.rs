//! What each step asks for: prescribed values, pressures and temperature at its start and end,
//! interpolated linearly in the step's load factor.

use crate::element::body_load::BodyForce;
use crate::model::{Model, Temperature};
use crate::solve::problem::LoadState;
use std::collections::BTreeMap;

/// Start and end of every load quantity over one step.
#[derive(Clone, Debug)]
pub struct StepLoads {
    /// (node, component) -> (value at step start, value at step end).
    pub prescribed: BTreeMap<(usize, usize), (f64, f64)>,
    /// surface -> (start, end) pressure.
    pub pressures: BTreeMap<String, (f64, f64)>,
    /// (element set, spin) -> (start, end) gravity along the axis or omega^2.
    pub body_loads: BTreeMap<(String, bool), (f64, f64)>,
    /// (node, component) -> (start, end) force, N per radian.
    pub nodal_forces: BTreeMap<(usize, usize), (f64, f64)>,
    /// (start, end) temperature, degC.
    pub temperature: (Temperature, Temperature),
    /// Node sets with a prescribed displacement in this or an earlier step (reaction output).
    pub constrained_sets: Vec<String>,
}

impl StepLoads {
    /// Loads of step `index`, given the previous step's loads (None for the first) and the
    /// current nodal displacements (a newly prescribed DOF ramps from where it is).
    pub fn new(model: &Model, index: usize, previous: Option<&StepLoads>, displacement: &[[f64; 2]]) -> Self {
        let step = model.general_step(index);
        // what earlier steps prescribed holds, unless this step releases what it does not restate
        let earlier = previous.filter(|_| !step.release_constraints);
        let mut prescribed: BTreeMap<(usize, usize), (f64, f64)> =
            earlier.map(|p| p.prescribed.iter().map(|(&k, &(_, end))| (k, (end, end))).collect()).unwrap_or_default();
        let mut constrained_sets = previous.map(|p| p.constrained_sets.clone()).unwrap_or_default();
        for d in &step.displacements {
            for &n in &model.node_sets[&d.node_set] {
                let c = d.component as usize;
                let start = prescribed.get(&(n, c)).map(|v| v.0).unwrap_or(displacement[n][c]);
                prescribed.insert((n, c), (start, d.value));
            }
            if !constrained_sets.contains(&d.node_set) {
                constrained_sets.push(d.node_set.clone());
            }
        }
        let mut pressures: BTreeMap<String, (f64, f64)> =
            previous.map(|p| p.pressures.iter().map(|(k, &(_, end))| (k.clone(), (end, end))).collect()).unwrap_or_default();
        for p in &step.pressures {
            let start = pressures.get(&p.surface).map(|v| v.0).unwrap_or(0.0);
            pressures.insert(p.surface.clone(), (start, p.value));
        }
        let mut body_loads: BTreeMap<(String, bool), (f64, f64)> =
            previous.map(|p| p.body_loads.iter().map(|(k, &(_, end))| (k.clone(), (end, end))).collect()).unwrap_or_default();
        for b in &step.body_loads {
            let key = (b.elements.clone(), matches!(b.force, BodyForce::Spin(_)));
            let start = body_loads.get(&key).map(|v| v.0).unwrap_or(0.0);
            body_loads.insert(key, (start, b.force.value()));
        }
        let mut nodal_forces: BTreeMap<(usize, usize), (f64, f64)> =
            previous.map(|p| p.nodal_forces.iter().map(|(&k, &(_, end))| (k, (end, end))).collect()).unwrap_or_default();
        for f in &step.nodal_forces {
            let key = (f.node, f.component as usize);
            let start = nodal_forces.get(&key).map(|v| v.0).unwrap_or(0.0);
            nodal_forces.insert(key, (start, f.value));
        }
        let t0 = previous.map_or(&model.reference_temperature, |p| &p.temperature.1).clone();
        let t1 = step.temperature.clone().unwrap_or_else(|| t0.clone());
        StepLoads { prescribed, pressures, body_loads, nodal_forces, temperature: (t0, t1), constrained_sets }
    }

    /// Whether this step moves the prescribed DOFs back against the motion `previous` gave
    /// them (a load cycle's return stroke). At a reversal the response changes branch at once:
    /// plastic points unload elastically, and friction's traction flips within its elastic
    /// slip, a jump of the reaction at the increment's start that the energy audit's trapezoids
    /// integrate to within half the jump times the increment (the quick bellows' return stroke
    /// with sleeve friction: 555 N mm per radian of its 4e5 at the requested increment).
    pub fn reverses(&self, previous: Option<&StepLoads>) -> bool {
        let Some(previous) = previous else { return false };
        let along: f64 = self.prescribed.iter().filter_map(|(key, &(start, end))| previous.prescribed.get(key).map(|&(a, b)| (b - a) * (end - start))).sum();
        along < 0.0
    }

    /// Which DOFs are prescribed in this step: the step's, and those nothing touches (held
    /// at zero, `Model::unused_dofs`).
    pub fn prescribed_mask(&self, model: &Model) -> Vec<[bool; 2]> {
        let mut mask = model.unused_dofs();
        for &(n, c) in self.prescribed.keys() {
            mask[n][c] = true;
        }
        mask
    }

    /// The loads at load factor `lambda` in [0, 1] of this step.
    pub fn at(&self, model: &Model, lambda: f64) -> LoadState {
        let lerp = |(a, b): (f64, f64)| a + lambda * (b - a);
        let mut prescribed = vec![[0.0; 2]; model.mesh.coords.len()];
        for (&(n, c), &v) in &self.prescribed {
            prescribed[n][c] = lerp(v);
        }
        LoadState {
            prescribed,
            temperature: Temperature::lerp(&self.temperature.0, &self.temperature.1, lambda, model.mesh.coords.len()),
            pressures: self.pressures.iter().map(|(s, &v)| (s.clone(), lerp(v))).collect(),
            body_loads: self
                .body_loads
                .iter()
                .map(|((set, spin), &v)| (set.clone(), if *spin { BodyForce::Spin(lerp(v)) } else { BodyForce::Gravity(lerp(v)) }))
                .collect(),
            nodal_forces: self.nodal_forces.iter().map(|(&(n, c), &v)| (n, c, lerp(v))).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The loads of a step moving node 0's u_z from `from` to `to`.
    fn moving(from: f64, to: f64) -> StepLoads {
        StepLoads {
            prescribed: BTreeMap::from([((0, 1), (from, to)), ((1, 1), (0.0, 0.0))]),
            pressures: BTreeMap::new(),
            body_loads: BTreeMap::new(),
            nodal_forces: BTreeMap::new(),
            temperature: (Temperature::Uniform(20.0), Temperature::Uniform(20.0)),
            constrained_sets: Vec::new(),
        }
    }

    #[test]
    fn a_return_stroke_reverses_and_a_further_push_or_a_hold_does_not() {
        let compress = moving(0.0, -70.0);
        assert!(moving(-70.0, 0.0).reverses(Some(&compress)));
        assert!(!moving(-70.0, -80.0).reverses(Some(&compress)));
        assert!(!moving(-70.0, -70.0).reverses(Some(&compress)));
        assert!(!compress.reverses(None));
    }
}

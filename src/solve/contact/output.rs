//! What contact reports after a converged increment: the forces on the contact nodes and the
//! tractions recovered from them, per-pair summaries for the history, and each pass's slab
//! of slave-node states for the results file.

use super::ContactAssembly;
use crate::model::Model;
use crate::records::contact::PassOutput;

impl ContactAssembly {
    /// This rank's contact forces on every contact node (last evaluation), to be summed over
    /// ranks before [`ContactAssembly::recover_tractions`].
    pub fn nodal_forces(&self) -> Vec<f64> {
        self.nodal_forces.iter().flatten().copied().collect()
    }

    /// Sets the recovered traction of every owned slave node from the contact forces on all
    /// contact nodes summed over ranks (`forces`, as from [`ContactAssembly::nodal_forces`]).
    pub fn recover_tractions(&mut self, forces: &[f64]) {
        let slot = &self.slot;
        let positions = &self.positions;
        let x = |n: usize| positions[slot[n]];
        for (p, pass) in self.passes.iter().enumerate() {
            let slave = &self.surfaces[pass.slave];
            let normal_force: Vec<f64> = slave
                .nodes
                .iter()
                .map(|&n| {
                    let nn = slave.node_normal(n, x);
                    forces[2 * slot[n]] * nn[0] + forces[2 * slot[n] + 1] * nn[1]
                })
                .collect();
            let traction = slave.recover_pressure(&normal_force);
            for (k, &i) in pass.owned.iter().enumerate() {
                self.states[p][k].traction = traction[i];
            }
        }
    }

    /// This rank's slave nodes' contact energies at the last evaluation: (normal penalty stored,
    /// tangential penalty stored, dissipated by friction since the last converged increment),
    /// N mm per radian.
    pub fn energies(&self) -> [f64; 3] {
        let mut e = [0.0; 3];
        for s in self.states.iter().flatten() {
            e[0] += s.normal_energy;
            e[1] += s.friction_stored;
            e[2] += s.friction_dissipated;
        }
        e
    }

    /// Per pair: (active slave nodes, largest penetration, total normal force per radian)
    /// over this rank's slave nodes.
    pub fn pair_summaries(&self, model: &Model) -> Vec<(f64, f64, f64)> {
        let mut out = vec![(0.0, 0.0, 0.0); model.contacts.len()];
        for (p, pass) in self.passes.iter().enumerate() {
            let o = &mut out[pass.pair];
            for s in &self.states[p] {
                if s.pressure > 0.0 {
                    o.0 += 1.0;
                    o.1 = f64::max(o.1, -s.gap);
                    o.2 += s.force;
                }
            }
        }
        out
    }

    /// Per pair: (closed slave nodes, smallest gap in mm, infinite when no slave node has a
    /// master segment within reach) over this rank's slave nodes at the last evaluation. A
    /// node touching at a zero gap counts as closed: its penalty stiffness is in the tangent.
    pub fn pair_openings(&self, model: &Model) -> Vec<(f64, f64)> {
        let mut out = vec![(0.0, f64::INFINITY); model.contacts.len()];
        for (p, pass) in self.passes.iter().enumerate() {
            let o = &mut out[pass.pair];
            for s in &self.states[p] {
                if s.pressure > 0.0 || s.gap <= 0.0 {
                    o.0 += 1.0;
                }
                if s.gap.is_finite() {
                    o.1 = o.1.min(s.gap);
                }
            }
        }
        out
    }

    /// For output: per pass (pair index, pass number within the pair, slab offset, total,
    /// owned slave mesh nodes, their areas, states).
    pub fn pass_outputs(&self) -> Vec<PassOutput<'_>> {
        let mut number = vec![0usize; self.passes.iter().map(|p| p.pair + 1).max().unwrap_or(0)];
        self.passes
            .iter()
            .enumerate()
            .map(|(p, pass)| {
                let slave = &self.surfaces[pass.slave];
                let n = number[pass.pair];
                number[pass.pair] += 1;
                PassOutput {
                    pair: pass.pair,
                    pass: n,
                    offset: pass.offset,
                    total: pass.total,
                    nodes: pass.owned.iter().map(|&i| slave.nodes[i]).collect(),
                    // a node-based slave's area is where it bears, written with each increment
                    areas: match pass.master_face_area {
                        true => vec![f64::NAN; pass.owned.len()],
                        false => pass.owned.iter().map(|&i| slave.areas[i] * pass.weight).collect(),
                    },
                    bearing_areas: pass.master_face_area.then(|| self.states[p].iter().map(|s| s.area).collect()),
                    states: &self.states[p],
                    friction: pass.friction,
                }
            })
            .collect()
    }
}

//! The assembly of the problem's residual and Jacobian: the loops over this rank's elements,
//! follower-pressure edges and contact engagements, what SNES calls, and the load predictor's
//! coupling to the prescribed DOFs.

use super::Problem;
use crate::element::body_load::{body_load, body_load_stiffness, BodyForce};
use crate::element::pressure::{compute_pressure_load, pressure_load_stiffness};
use crate::element::solid::DOFS;
use crate::error::Result;
use crate::material::Kinematics;
use crate::petsc::{MatOps, MatrixView, NonlinearProblem, VecOps, VectorView};
use crate::solve::contact::Need;
use crate::solve::problem::kept::{ElementFields, LastEvaluation};
use crate::solve::problem::roundoff::ROUNDOFF_ULPS;
use mpi::collective::{CommunicatorCollectives, SystemOperation};

impl NonlinearProblem for Problem<'_, '_> {
    fn roundoff_squares(&self) -> f64 {
        self.roundoff
    }

    fn force_sums(&self) -> [f64; 2] {
        self.force_sums
    }

    fn residual(&mut self, x: &VectorView<'_>, f: &mut VectorView<'_>) -> Result<()> {
        let stage = self.stages.residual;
        stage.run(|| self.assemble_residual(x, f))?
    }

    fn jacobian(&mut self, x: &VectorView<'_>, jacobian: &mut MatrixView<'_>) -> Result<()> {
        self.assemble_jacobian(x, jacobian)
    }

    fn take_structure_change(&mut self) -> bool {
        std::mem::take(&mut self.structure_changed)
    }

    fn model_size(&self) -> f64 {
        self.model_size
    }

    fn force_unit(&self) -> &'static str {
        if self.model.is_axisymmetric() {
            "N/rad"
        } else {
            "N"
        }
    }
}

impl Problem<'_, '_> {
    /// F(x) at the free DOFs, assembled.
    pub fn assemble_residual(&mut self, x: &impl VecOps, f: &mut impl VecOps) -> Result<()> {
        let gathered = self.gather(x)?;
        f.set_all(0.0)?;
        let mut local = vec![0.0; gathered.len()];
        let slots = std::mem::take(&mut self.node_slots);
        // the last evaluation's buffers, refilled
        let mut fields = self.last.take().map_or_else(|| ElementFields::zeros(self.elements.len(), self.model.mesh.coords.len()), |l| l.fields);
        let result = self.residual_entries(&gathered, true, &mut fields, |node, c, v| {
            // prescribed DOFs (the only ones without a slot) take no residual
            if let Some(r) = local.get_mut(slots[node][c]) {
                *r += v;
            }
        });
        self.node_slots = slots;
        if result.is_ok() {
            let multipliers = self.contact.as_ref().map(|c| c.multipliers().clone());
            self.last = Some(LastEvaluation { gathered, load: self.load_generation, multipliers, fields });
        } else {
            // Assembly is collective: a rank whose evaluation failed (an inverted element)
            // still takes part, with nothing to add, and reports the failure afterwards;
            // returning before it would leave the other ranks waiting in the scatter.
            local.fill(0.0);
        }
        self.local_residual.write()?.copy_from_slice(&local);
        self.scatter.add_back(&self.local_residual, f)?;
        result
    }

    /// The tangent dF/du of the free DOFs at `x`, assembled.
    pub fn assemble_jacobian(&mut self, x: &impl VecOps, jacobian: &mut impl MatOps) -> Result<()> {
        let stage = self.stages.jacobian;
        stage.run(|| {
            let gathered = self.gather(x)?;
            self.fit_pattern(jacobian)?;
            self.layout.clear();
            let result = self.add_tangents(&gathered);
            // collective, whatever happened on this rank (see `assemble_residual`)
            if let Some(bound) = self.layout.hand_over(jacobian)? {
                let mut everywhere = 0;
                self.session.world().all_reduce_into(&i32::from(bound), &mut everywhere, SystemOperation::min());
                self.layout.keep_storage(everywhere == 1);
            }
            result
        })?
    }

    /// K_fp delta: the force at the free DOFs when the prescribed DOFs move by `delta`
    /// (per node, entries of free DOFs ignored) and the free ones stay at `x`, to first order,
    /// from the element tangents at `x`. The load predictor of an increment solves
    /// K_ff du = -K_fp delta, so a prescribed displacement spreads through the structure
    /// before Newton starts, instead of squashing the elements next to the moved nodes.
    /// The constraints' couplings are in; contact's and the load stiffness's are left out (a
    /// predictor).
    pub fn prescribed_coupling(&mut self, x: &impl VecOps, delta: &[[f64; 2]], f: &mut impl VecOps) -> Result<()> {
        let gathered = self.gather(x)?;
        f.set_all(0.0)?;
        let (mut rows, mut values) = (Vec::new(), Vec::new());
        let mut result = Ok(());
        for k in 0..self.elements.len() {
            let conn = self.model.mesh.elements[self.elements[k].element];
            let moved: Vec<usize> = (0..DOFS).filter(|&j| self.elements[k].dofs[j] < 0 && delta[conn[j / 2]][j % 2] != 0.0).collect();
            if moved.is_empty() {
                continue;
            }
            let u = self.displacements(&self.elements[k], &gathered);
            let tangent = match self.element_tangent(k, &u) {
                Ok(t) => t,
                Err(e) => {
                    result = Err(e);
                    break;
                }
            };
            for i in (0..DOFS).filter(|&i| self.elements[k].dofs[i] >= 0) {
                rows.push(self.elements[k].dofs[i]);
                values.push(moved.iter().map(|&j| tangent[(i, j)] * delta[conn[j / 2]][j % 2]).sum());
            }
        }
        if let Some(constraints) = self.constraints.as_ref() {
            constraints.prescribed_coupling(delta, |n, c, v| {
                rows.push(self.dofs.dof[n][c]);
                values.push(v);
            });
        }
        // collective, whatever happened on this rank (see `assemble_residual`)
        if result.is_ok() {
            f.add_values(&rows, &values)?;
        }
        f.assemble()?;
        result
    }

    /// Writes this rank's element, follower-pressure and contact tangents into the layout
    /// (contact evaluated by `fit_pattern` first).
    fn add_tangents(&mut self, gathered: &[f64]) -> Result<()> {
        let mut us = Vec::with_capacity(self.elements.len());
        for k in 0..self.elements.len() {
            let u = self.displacements(&self.elements[k], gathered);
            let k_e = self.element_tangent(k, &u)?;
            self.layout.add_element(k, k_e.as_slice());
            us.push(u);
        }
        if self.model.kinematics == Kinematics::Finite {
            // follower pressure, d(-f_ext)/du, at the entries of the element the edge bounds
            let edges: Vec<(usize, [usize; 3], f64)> = self.pressure_edges().collect();
            for (k, local, p) in edges {
                let kp = pressure_load_stiffness(self.elements[k].geometry.section(), &self.edge_positions(k, &local, &us[k]), p);
                let at = |i: usize| 2 * local[i / 2] + i % 2;
                for (i, row) in kp.iter().enumerate() {
                    for (j, v) in row.iter().enumerate() {
                        self.layout.add_element_entry(k, at(i), at(j), -v);
                    }
                }
            }
            // the spin's softening, d(-f_ext)/du
            let spinning: Vec<(usize, f64, BodyForce)> = self.body_loaded().filter(|(_, _, f)| matches!(f, BodyForce::Spin(_))).collect();
            for (k, rho, force) in spinning {
                let kb = body_load_stiffness(&self.elements[k].geometry, rho, force, self.model.kinematics);
                for (i, row) in kb.iter().enumerate() {
                    for (j, v) in row.iter().enumerate().filter(|(_, v)| **v != 0.0) {
                        self.layout.add_element_entry(k, i, j, -v);
                    }
                }
            }
        }
        if let Some(constraints) = self.constraints.as_ref() {
            constraints.tangent(|a, ca, b, cb, v| self.layout.add_coupling(a, ca, b, cb, v));
        }
        // the engagements and their tangents at this iterate: `fit_pattern` evaluated them
        if let Some(contact) = self.contact.as_ref() {
            for e in contact.engagements() {
                self.layout.add_engagement(&e.nodes, &e.tangent);
            }
        }
        Ok(())
    }
}

impl Problem<'_, '_> {
    /// Collective, before any value of a Jacobian is added: evaluates contact with tangents,
    /// and when an engagement on any rank couples two free DOFs that the pattern lacks, gives
    /// `jacobian` room for them in place (a new layout and COO preallocation on every rank)
    /// instead of letting PETSc reallocate the whole matrix once per row that overflows. The
    /// matrix keeps its identity, so SNES and the KSP keep theirs; its nonzero state changes,
    /// so MUMPS redoes its symbolic analysis once.
    fn fit_pattern(&mut self, jacobian: &mut impl MatOps) -> Result<()> {
        let Some(contact) = self.contact.as_mut() else { return Ok(()) };
        let stage = self.stages.contact;
        stage.run(|| contact.evaluate(self.model, Need::Tangent))?;
        let dof = &self.dofs.dof;
        let free = |n: usize| dof[n].iter().any(|&d| d >= 0);
        if contact.pattern_mut().synchronise(self.session.world(), |a, b| free(a) && free(b)) {
            contact.pattern_mut().refits += 1;
            self.layout.set_pairs(super::coupled_pairs(Some(contact), self.constraints.as_ref()), &self.dofs.dof);
            let (rows, cols) = self.layout.indices();
            jacobian.preallocate_coo(rows, cols)?;
            self.structure_changed = true;
        }
        Ok(())
    }

    /// Evaluates f_int - f_ext (+ contact) at the gathered state: calls `sink(node, component,
    /// value)` for every entry, stores the trial history (and, with `keep_tangents`, the
    /// material tangents for the Jacobian), and writes the output fields into `fields` (the
    /// nodal forces summed afresh).
    pub(super) fn residual_entries(
        &mut self,
        gathered: &[f64],
        keep_tangents: bool,
        fields: &mut ElementFields,
        mut sink: impl FnMut(usize, usize, f64),
    ) -> Result<()> {
        fields.nodal_force.fill([0.0; 2]);
        fields.pressure_force.fill([0.0; 2]);
        fields.energy = Default::default();
        fields.thermal_force.fill(0.0);
        let mut sink = |node: usize, c: usize, v: f64| {
            fields.nodal_force[node][c] += v;
            sink(node, c, v);
        };
        let mut us = Vec::with_capacity(self.elements.len());
        let mut roundoff = 0.0;
        let mut forces = [0.0, 0.0];
        let mut kept = std::mem::take(&mut self.kept);
        for k in 0..self.elements.len() {
            let u = self.displacements(&self.elements[k], gathered);
            let entry = &mut kept.elements[k];
            // written in place: invalid until the evaluation has succeeded
            entry.valid &= !keep_tangents;
            let temperature_change = self.temperature_change(k);
            let out = match self.solid(k, &u, &temperature_change, keep_tangents.then_some(&mut entry.material)) {
                Ok(out) => out,
                Err(e) => {
                    self.kept = kept;
                    return Err(e);
                }
            };
            if keep_tangents {
                (entry.valid, entry.u, entry.temperature_change) = (true, u, temperature_change);
            }
            self.trial[k] = out.state;
            fields.energy.elastic += out.energy.elastic;
            fields.energy.plastic_work += out.energy.plastic_work;
            let element = &self.elements[k];
            let size =
                element.roundoff_scale * (u.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())) + element.roundoff_length) + out.internal_force.abs().max();
            roundoff += (ROUNDOFF_ULPS * f64::EPSILON * size).powi(2);
            forces[0] += out.internal_force.iter().map(|v| v.abs()).sum::<f64>();
            forces[1] += DOFS as f64;
            fields.stress[k] = out.stress;
            fields.plastic_strain[k] = out.state.map(|s| s.ep);
            fields.thickness_stretch[k] = out.thickness_stretch;
            let conn = &self.model.mesh.elements[self.elements[k].element];
            for i in 0..DOFS {
                sink(conn[i / 2], i % 2, out.internal_force[i]);
            }
            for (a, &n) in conn.iter().enumerate() {
                fields.thermal_force[n] += out.thermal_force[a];
            }
            us.push(u);
        }
        self.kept = kept;
        // the pressure loads, also kept apart (the energy audit's external work; the sink
        // closure holds only `fields.nodal_force`)
        for (k, local, p) in self.pressure_edges() {
            let f = compute_pressure_load(self.elements[k].geometry.section(), &self.edge_positions(k, &local, &us[k]), p);
            let conn = &self.model.mesh.elements[self.elements[k].element];
            for (j, &a) in local.iter().enumerate() {
                for c in 0..2 {
                    sink(conn[a], c, -f[j][c]);
                    fields.pressure_force[conn[a]][c] += f[j][c];
                }
            }
        }
        // the body loads (and below the nodal forces), kept with the pressures' for the
        // audit's external work
        for (k, rho, force) in self.body_loaded() {
            let element = &self.elements[k];
            let f = body_load(&element.geometry, &element.coords, &us[k], rho, force, self.model.kinematics);
            let conn = &self.model.mesh.elements[element.element];
            for (a, f) in f.iter().enumerate() {
                for c in 0..2 {
                    sink(conn[a], c, -f[c]);
                    fields.pressure_force[conn[a]][c] += f[c];
                }
            }
        }
        // the nodal forces, by the rank that owns the node
        for &(n, c, f) in &self.load.nodal_forces {
            if self.owns_node[n] {
                sink(n, c, -f);
                fields.pressure_force[n][c] += f;
            }
        }
        if let Some(constraints) = self.constraints.as_ref() {
            let (sums, floor) = constraints.residual(gathered, &self.load.prescribed, &mut sink);
            forces = [forces[0] + sums[0], forces[1] + sums[1]];
            roundoff += floor;
        }
        let stage = self.stages.contact;
        if let Some(contact) = self.contact.as_mut() {
            stage.run(|| contact.evaluate(self.model, Need::Residual))?;
            for e in contact.engagements() {
                for (i, &v) in e.residual.iter().enumerate() {
                    sink(e.nodes[i / 2], i % 2, v);
                }
                forces[0] += e.residual.iter().map(|v| v.abs()).sum::<f64>();
                forces[1] += e.residual.len() as f64;
            }
            roundoff += contact.roundoff_squares();
        }
        self.roundoff = roundoff;
        self.force_sums = forces;
        Ok(())
    }
}

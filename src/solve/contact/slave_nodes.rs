//! The slave nodes' evaluation, pass by pass: the closest master segment, the gap (at the node,
//! or integrated along the slave surface), the normal kernel and, with friction, the return
//! map from the node's slip reference; the active nodes' engagements for the assembly.

use super::ContactAssembly;
use crate::contact::friction::{FrictionLaw, SlipReference};
use crate::contact::integrated::weighted_gaps_into;
use crate::contact::node_to_edge::{edge_residual, ContactLaw, Overclosure, SlaveArea};
use crate::contact::search::EdgeGrid;
use crate::contact::surface::ContactSurface;
use crate::model::{ContactPair, Model, Penalty};
use crate::records::contact::{SlaveState, SlipPoint};
use crate::solve::contact::engagement::{Engagements, FrictionRecipe};
use crate::solve::problem::roundoff::ROUNDOFF_ULPS;

/// The friction kernel's arguments for a slave node at `xs` projecting at `xi` on master edge
/// `edge`, its slip measured from `reference`.
#[allow(clippy::too_many_arguments)]
fn friction_recipe(
    master: &ContactSurface,
    x: &impl Fn(usize) -> [f64; 2],
    xs: [f64; 2],
    edge: usize,
    xi: f64,
    reference: SlipPoint,
    law: ContactLaw,
    friction: FrictionLaw,
) -> FrictionRecipe {
    FrictionRecipe {
        xs,
        master: master.edges[edge].map(x),
        reference: master.edges[reference.edge].map(x),
        xi,
        from: SlipReference { xi: reference.xi, traction: reference.traction },
        law,
        friction,
    }
}

impl ContactAssembly {
    /// The penalty eps (MPa/mm) of the pair on master edge `edge`; for the exponential law its
    /// slope at touch (the default stick slope and the round-off scale).
    fn penalty(model: &Model, pair: &ContactPair, master: &ContactSurface, edge: usize) -> f64 {
        match pair.penalty {
            Penalty::Stiffness(v) => v,
            Penalty::Factor(kappa) => kappa * model.materials[model.element_material[master.element[edge]]].youngs_modulus / master.edge_length[edge],
            Penalty::Exponential { .. } => Self::overclosure(model, pair, master, edge, 0.0).stiffness(0.0),
        }
    }

    /// The pair's pressure-overclosure law on master edge `edge`, with the node's multiplier.
    fn overclosure(model: &Model, pair: &ContactPair, master: &ContactSurface, edge: usize, multiplier: f64) -> Overclosure {
        match pair.penalty {
            Penalty::Exponential { clearance, pressure } => Overclosure::Exponential { clearance, pressure },
            _ => Overclosure::Linear { penalty: Self::penalty(model, pair, master, edge), multiplier },
        }
    }

    /// Node-to-segment: the gap at each slave node, on the master edge it projects to.
    pub(super) fn evaluate_nodal(&mut self, model: &Model, pair: &ContactPair, p: usize, out: &mut Engagements) {
        let pass = &self.passes[p];
        let (slot, positions) = (&self.slot, &self.positions);
        let x = |n: usize| positions[slot[n]];
        let (slave, master) = (&self.surfaces[pass.slave], &self.surfaces[pass.master]);
        let capture = pair.capture_distance;
        let grid = EdgeGrid::new(master, &x, capture);
        // the previous node's master edge: a good first guess where owned nodes are numbered
        // along the surface, harmless where not
        let mut hint = None;
        for (k, &i) in pass.owned.iter().enumerate() {
            let node = slave.nodes[i];
            let xs = x(node);
            let excluded = pass.excluded.get(k).map_or(&[][..], |v| v.as_slice());
            let found = grid.closest_edge(master, &x, xs, excluded, capture, hint);
            hint = found.as_ref().map(|(e, _)| *e).or(hint);
            let found = found.filter(|(edge, proj)| master.bears(*edge, proj, slave.node_normal(node, x), capture));
            let Some((edge, proj)) = found else {
                self.states[p][k] = SlaveState { gap: f64::NAN, ..SlaveState::default() };
                self.slip_trial[p][k] = None;
                continue;
            };
            let eps = Self::penalty(model, pair, master, edge);
            let en = master.edges[edge];
            let free_ends = master.neighbours[edge].map(|n| n.is_none());
            let normal = Self::overclosure(model, pair, master, edge, self.current[p][k]);
            let law = match pass.master_face_area {
                true => ContactLaw { area: pass.weight, slave_area: SlaveArea::MasterFace(master.section[edge]), normal, free_ends },
                false => ContactLaw { area: slave.areas[i] * pass.weight, slave_area: SlaveArea::Tributary, normal, free_ends },
            };
            let xe = en.map(x);
            // the area the pressure acts on here
            let area = law.area_at(&xe, proj.xi);
            let (residual, pressure) = edge_residual(xs, &xe, &proj, &law);
            let mut state = SlaveState { gap: proj.gap, pressure, force: pressure * area, area, ..SlaveState::default() };
            // an open node's slip is measured, once it closes, from where it is now
            self.slip_trial[p][k] = Some(SlipPoint { edge, xi: proj.xi, traction: 0.0 });
            let closed = normal.is_closed(proj.gap);
            if closed {
                self.roundoff += (ROUNDOFF_ULPS * f64::EPSILON * normal.stiffness(proj.gap) * area * xs[0].hypot(xs[1])).powi(2);
                out.next_slot().set_nodal(node, en, residual.as_slice(), xs, en.map(x), proj, law);
                state.normal_energy = normal.stored_energy(proj.gap, pressure) * area;
            }
            // a node without a reference (beyond reach when the increment started) slides freely
            // in this increment and has one from the next on
            let friction = self.friction[pass.pair].filter(|_| !self.without_friction);
            if let (Some(f), true, Some(reference)) = (friction, closed, self.slip_committed[p][k]) {
                let friction = FrictionLaw { coefficient: f.coefficient, penalty: f.tangential_penalty.unwrap_or(eps), elastic_slip: f.elastic_slip };
                let recipe = friction_recipe(master, &x, xs, edge, proj.xi, reference, law, friction);
                let (residual, slip) = recipe.residual();
                self.roundoff += (ROUNDOFF_ULPS * f64::EPSILON * friction.penalty * area * xs[0].hypot(xs[1])).powi(2);
                out.next_slot().set_friction(node, en, master.edges[reference.edge], residual.as_slice(), recipe);
                self.slip_trial[p][k] = Some(SlipPoint { edge, xi: proj.xi, traction: slip.traction });
                (state.shear, state.sliding) = (slip.traction, slip.slipping);
                (state.friction_stored, state.friction_dissipated) = (slip.stored, slip.dissipated);
            }
            self.states[p][k] = state;
        }
    }

    /// Segment integration: weighted gaps g_a = integral N_a g r ds and nodal pressures; with
    /// friction, each slave node's slip is measured at its own projection on the master (as
    /// node-to-segment), the Coulomb limit set by its integrated pressure.
    pub(super) fn evaluate_integrated(&mut self, model: &Model, pair: &ContactPair, p: usize, out: &mut Engagements) {
        let pass = &self.passes[p];
        let (slot, positions) = (&self.slot, &self.positions);
        let x = |n: usize| positions[slot[n]];
        let x0 = |n: usize| model.mesh.coords[n];
        let (slave, master) = (&self.surfaces[pass.slave], &self.surfaces[pass.master]);
        let gaps = &mut self.gaps[p];
        weighted_gaps_into(slave, master, &x, &x0, &pass.owned, &pass.excluded, pair.capture_distance, gaps);
        // number the points across passes
        let first = self.points;
        for s in gaps.iter_mut().flat_map(|g| g.samples.iter_mut()) {
            s.point += first;
            self.points = self.points.max(s.point + 1);
        }
        // the slip references are kept up to date wherever the pair has friction in some step
        let grid = pass.friction.then(|| EdgeGrid::new(master, &x, pair.capture_distance));
        // gaps[k] is owned slave node k's
        for (k, g) in gaps.iter().enumerate() {
            if g.samples.is_empty() {
                self.states[p][k] = SlaveState { gap: f64::NAN, ..SlaveState::default() };
                continue;
            }
            let area = slave.hat_areas[g.index];
            let eps = Self::penalty(model, pair, master, g.master_edge);
            let lambda = self.current[p][k];
            let trial = lambda - eps * g.gap / area;
            let pressure = trial.max(0.0);
            self.states[p][k] = SlaveState {
                gap: g.gap / area,
                pressure,
                force: pressure * area * pass.weight,
                area: area * pass.weight,
                normal_energy: if trial >= 0.0 { -0.5 * (g.gap / area) * pressure * area * pass.weight } else { 0.0 },
                ..SlaveState::default()
            };
            let node = slave.nodes[g.index];
            let xs = x(node);
            if trial >= 0.0 {
                self.roundoff += (ROUNDOFF_ULPS * f64::EPSILON * pass.weight * eps * area * xs[0].hypot(xs[1])).powi(2);
                out.next_slot().set_integrated(node, &g.samples, pass.weight * eps / area, pass.weight * pressure);
            }
            let (Some(grid), false) = (grid.as_ref(), self.without_friction) else { continue };
            // the node's own projection: where its slip is measured and its friction acts
            let excluded = if pass.slave == pass.master { slave.neighbourhood(node, pair.exclude_neighbours) } else { Vec::new() };
            let found = grid
                .closest_edge(master, &x, xs, &excluded, pair.capture_distance, None)
                .filter(|(edge, proj)| master.bears(*edge, proj, slave.node_normal(node, x), pair.capture_distance));
            let Some((edge, proj)) = found else {
                self.slip_trial[p][k] = None;
                continue;
            };
            self.slip_trial[p][k] = Some(SlipPoint { edge, xi: proj.xi, traction: 0.0 });
            let (Some(f), Some(reference)) = (self.friction[pass.pair], self.slip_committed[p][k].filter(|_| trial >= 0.0)) else { continue };
            // the pressure is given (the integrated one): a law of penalty 0 and multiplier p
            let law = ContactLaw::linear(area * pass.weight, 0.0, pressure, [false; 2]);
            let friction = FrictionLaw { coefficient: f.coefficient, penalty: f.tangential_penalty.unwrap_or(eps), elastic_slip: f.elastic_slip };
            let recipe = friction_recipe(master, &x, xs, edge, proj.xi, reference, law, friction);
            let (residual, slip) = recipe.residual();
            self.roundoff += (ROUNDOFF_ULPS * f64::EPSILON * friction.penalty * law.area * xs[0].hypot(xs[1])).powi(2);
            let slot = out.next_slot();
            slot.set_friction_integrated(
                node,
                master.edges[edge],
                master.edges[reference.edge],
                residual.as_slice(),
                recipe,
                &g.samples,
                pressure,
                -eps / area,
            );
            self.slip_trial[p][k] = Some(SlipPoint { edge, xi: proj.xi, traction: slip.traction });
            let state = &mut self.states[p][k];
            (state.shear, state.sliding, state.friction_stored, state.friction_dissipated) = (slip.traction, slip.slipping, slip.stored, slip.dissipated);
        }
    }
}

//! One active slave node's contribution to the problem: its residual at once, its tangent on
//! demand. An evaluation finds the engagements with the residual (the line search asks for no
//! more); the Jacobian at the same iterate then forms their tangents from what each kept (its
//! recipe), without searching again.

use crate::contact::friction::{friction_residual, friction_residual_and_tangent, FrictionLaw, FrictionState, FrictionVector, SlipReference};
use crate::contact::harmonic::Sticking;
use crate::contact::integrated::{GapSample, SampleMatrix};
use crate::contact::node_to_edge::{edge_residual_and_tangent, ContactLaw, EdgeProjection};

/// The contribution of one active slave node: residual and tangent over `nodes`. Its vectors
/// are refilled from one evaluation to the next (in an `Engagements` slot), not allocated again.
#[derive(Default)]
pub struct Engagement {
    /// Mesh nodes the contribution couples (the slave node first).
    pub nodes: Vec<usize>,
    /// Two entries per node, (r, z).
    pub residual: Vec<f64>,
    /// Row-major, (2 nodes) x (2 nodes); empty until the tangent is formed (`form_tangent`).
    pub tangent: Vec<f64>,
    /// What the tangent is formed from.
    recipe: TangentRecipe,
    /// Segment integration: the node's integration points, and dg over `nodes` (their sum).
    samples: Vec<GapSample>,
    gradient: Vec<f64>,
}

enum TangentRecipe {
    /// Node-to-segment: the kernel's arguments.
    Nodal { xs: [f64; 2], master: [[f64; 2]; 3], projection: EdgeProjection, law: ContactLaw },
    /// Segment integration: K = stiffness dg dg^T - weighted_pressure d2g, with dg (`gradient`)
    /// and d2g the sums over the node's integration points (`samples`).
    Integrated { stiffness: f64, weighted_pressure: f64 },
    /// Friction at a node-to-segment node: the kernel's arguments, and the position in `nodes`
    /// of each of its 7 nodes (slave, edge, reference edge; shared nodes listed once).
    Friction { recipe: FrictionRecipe, slots: [usize; 7] },
    /// Friction at a segment-integrated node: as `Friction`, the kernel taking the node's
    /// integrated pressure as given (`recipe.law`: penalty 0, multiplier p); in slip the
    /// traction mu p also moves with p, by dp = `gradient` over `nodes` (p's dependence on the
    /// sample nodes of its weighted gap).
    FrictionIntegrated { recipe: FrictionRecipe, slots: [usize; 7], pressure: f64 },
}

/// A closed contact node of the base state, for a perturbation step.
#[derive(Clone, Debug, PartialEq)]
pub enum BaseContact {
    /// The axisymmetric contact tangent over `nodes` (row-major, (r, z) per node).
    Normal { nodes: Vec<usize>, tangent: Vec<f64> },
    /// A frictional node, sticking: slave node and master edge [s, e_1, e_2, e_3].
    Sticking { nodes: [usize; 4], sticking: Sticking },
}

/// The friction kernel's arguments at one slave node (see `contact::friction`).
#[derive(Clone, Copy, Debug)]
pub(in crate::solve) struct FrictionRecipe {
    pub xs: [f64; 2],
    pub master: [[f64; 2]; 3],
    pub reference: [[f64; 2]; 3],
    pub xi: f64,
    pub from: SlipReference,
    pub law: ContactLaw,
    pub friction: FrictionLaw,
}

impl FrictionRecipe {
    pub fn residual(&self) -> (FrictionVector, FrictionState) {
        friction_residual(self.xs, &self.master, &self.reference, self.xi, &self.from, &self.law, &self.friction)
    }
}

/// A new slot's recipe, before a setter fills it: no samples, so no tangent.
impl Default for TangentRecipe {
    fn default() -> Self {
        TangentRecipe::Integrated { stiffness: 0.0, weighted_pressure: 0.0 }
    }
}

impl Engagement {
    /// What the engagement gives a harmonic perturbation about the state it was found in
    /// (`contact::harmonic`): a normal one its tangent (formed), a frictional one a sticking
    /// node on the edge it projects to.
    pub fn for_perturbation(&self) -> BaseContact {
        match &self.recipe {
            TangentRecipe::Friction { recipe: r, slots } | TangentRecipe::FrictionIntegrated { recipe: r, slots, .. } => {
                BaseContact::Sticking { nodes: [0, 1, 2, 3].map(|a| self.nodes[slots[a]]), sticking: Sticking::at(r.xs, &r.master, r.xi, &r.law, &r.friction) }
            }
            _ => BaseContact::Normal { nodes: self.nodes.clone(), tangent: self.tangent.clone() },
        }
    }

    /// Node-to-segment: slave node `node` at `xs` on the master edge with nodes `edge` at
    /// `x_master`, projected at `projection`; `residual` is the kernel's over [node, edge...].
    #[allow(clippy::too_many_arguments)]
    pub(in crate::solve) fn set_nodal(
        &mut self,
        node: usize,
        edge: [usize; 3],
        residual: &[f64],
        xs: [f64; 2],
        x_master: [[f64; 2]; 3],
        projection: EdgeProjection,
        law: ContactLaw,
    ) {
        self.recipe = TangentRecipe::Nodal { xs, master: x_master, projection, law };
        refill(&mut self.nodes, [node, edge[0], edge[1], edge[2]]);
        refill(&mut self.residual, residual.iter().copied());
        self.tangent.clear();
        self.samples.clear();
        self.gradient.clear();
    }

    /// Friction at slave node `node` projecting on the edge `edge`, its slip measured from the
    /// reference edge `reference`; `residual` is the kernel's over [node, edge, reference].
    pub(in crate::solve) fn set_friction(&mut self, node: usize, edge: [usize; 3], reference: [usize; 3], residual: &[f64], recipe: FrictionRecipe) {
        let slots = self.friction_nodes(node, edge, reference, &[], residual);
        self.recipe = TangentRecipe::Friction { recipe, slots };
        self.gradient.clear();
    }

    /// Friction at a segment-integrated slave node `node` (see `set_friction`), its pressure
    /// `pressure` = lambda - eps g / A from the weighted gap of `samples`, so dp/du =
    /// `dp_per_gap` x dg/du.
    #[allow(clippy::too_many_arguments)]
    pub(in crate::solve) fn set_friction_integrated(
        &mut self,
        node: usize,
        edge: [usize; 3],
        reference: [usize; 3],
        residual: &[f64],
        recipe: FrictionRecipe,
        samples: &[GapSample],
        pressure: f64,
        dp_per_gap: f64,
    ) {
        let slots = self.friction_nodes(node, edge, reference, samples, residual);
        self.sum_gradient(samples, dp_per_gap);
        self.recipe = TangentRecipe::FrictionIntegrated { recipe, slots, pressure };
    }

    /// `gradient` = `scale` times the sum of the samples' gap gradients, over `nodes` (which
    /// hold every sample's nodes).
    fn sum_gradient(&mut self, samples: &[GapSample], scale: f64) {
        self.gradient.clear();
        self.gradient.resize(2 * self.nodes.len(), 0.0);
        for s in samples {
            let sg = s.gradient();
            for (a, &n) in s.nodes.iter().enumerate() {
                let at = position_in(&self.nodes, n);
                self.gradient[2 * at] += scale * sg[2 * a];
                self.gradient[2 * at + 1] += scale * sg[2 * a + 1];
            }
        }
    }

    /// Lists the friction kernel's 7 nodes (shared ones once) and then the samples' other nodes
    /// in `nodes`, adds the kernel's `residual` there, and returns each kernel node's position.
    fn friction_nodes(&mut self, node: usize, edge: [usize; 3], reference: [usize; 3], samples: &[GapSample], residual: &[f64]) -> [usize; 7] {
        self.nodes.clear();
        let mut slots = [0usize; 7];
        for (a, n) in [node, edge[0], edge[1], edge[2], reference[0], reference[1], reference[2]].into_iter().enumerate() {
            slots[a] = match self.nodes.iter().position(|&q| q == n) {
                Some(at) => at,
                None => {
                    self.nodes.push(n);
                    self.nodes.len() - 1
                }
            };
        }
        for &n in samples.iter().flat_map(|s| s.nodes.iter()) {
            if !self.nodes.contains(&n) {
                self.nodes.push(n);
            }
        }
        self.residual.clear();
        self.residual.resize(2 * self.nodes.len(), 0.0);
        for (a, &at) in slots.iter().enumerate() {
            self.residual[2 * at] += residual[2 * a];
            self.residual[2 * at + 1] += residual[2 * a + 1];
        }
        self.tangent.clear();
        self.samples.clear();
        slots
    }

    /// Segment integration: slave node `node`, its weighted gap made of `samples`, at the
    /// nodal pressure times the pass's weight `weighted_pressure`; `stiffness` is the pass's
    /// weight times eps / A. The residual is -weighted_pressure dg.
    pub(in crate::solve) fn set_integrated(&mut self, node: usize, samples: &[GapSample], stiffness: f64, weighted_pressure: f64) {
        self.recipe = TangentRecipe::Integrated { stiffness, weighted_pressure };
        sample_nodes(node, samples, &mut self.nodes);
        refill(&mut self.samples, samples.iter().copied());
        self.sum_gradient(samples, 1.0);
        refill(&mut self.residual, self.gradient.iter().map(|v| -weighted_pressure * v));
        self.tangent.clear();
    }

    /// Forms the tangent at positions `x` (those of the evaluation that found the engagement),
    /// the segment-integrated ones from `hessians` of the same evaluation.
    pub(in crate::solve) fn form_tangent(&mut self, x: &impl Fn(usize) -> [f64; 2], hessians: &mut PointHessians) {
        self.tangent.clear();
        match &self.recipe {
            TangentRecipe::Nodal { xs, master, projection, law } => {
                let (_, k, _) = edge_residual_and_tangent(*xs, master, projection, law);
                self.tangent.extend_from_slice(k.transpose().as_slice());
            }
            TangentRecipe::Friction { recipe: r, slots } | TangentRecipe::FrictionIntegrated { recipe: r, slots, .. } => {
                let (_, k, state) = friction_residual_and_tangent(r.xs, &r.master, &r.reference, r.xi, &r.from, &r.law, &r.friction);
                let m = 2 * self.nodes.len();
                self.tangent.resize(m * m, 0.0);
                let at = |i: usize| 2 * slots[i / 2] + i % 2;
                for i in 0..14 {
                    for j in 0..14 {
                        self.tangent[at(i) * m + at(j)] += k[(i, j)];
                    }
                }
                // a segment-integrated node's pressure p is the integrated one (given to the
                // kernel as a constant): the residual, proportional to tau, varies with it as
                // d residual = residual / tau dtau/dp dp, with dtau/dp = tau / p in slip
                // (tau = mu p sign), (tau - tau_n) / p in stick with an elastic slip (eps_T =
                // mu p / gamma), and 0 in stick with a fixed penalty
                if let TangentRecipe::FrictionIntegrated { pressure, .. } = &self.recipe {
                    let tau = state.traction;
                    let dtau_dp = match (state.slipping, r.friction.elastic_slip) {
                        (true, _) => tau / pressure,
                        (false, Some(_)) => (tau - r.from.traction) / pressure,
                        (false, None) => 0.0,
                    };
                    if *pressure > 0.0 && tau != 0.0 && dtau_dp != 0.0 {
                        for i in 0..m {
                            let f = self.residual[i] / tau * dtau_dp;
                            for j in 0..m {
                                self.tangent[i * m + j] += f * self.gradient[j];
                            }
                        }
                    }
                }
            }
            &TangentRecipe::Integrated { stiffness, weighted_pressure } => {
                let (g, m) = (&self.gradient, self.gradient.len());
                self.tangent.extend((0..m * m).map(|ij| stiffness * g[ij / m] * g[ij % m]));
                // -p d2g
                for s in &self.samples {
                    let h = hessians.at(s, x);
                    let f = weighted_pressure * s.weight;
                    let map = s.nodes.map(|n| 2 * position_in(&self.nodes, n));
                    for a in 0..12 {
                        let row = map[a / 2] + a % 2;
                        for b in 0..12 {
                            self.tangent[row * m + map[b / 2] + b % 2] -= f * h[(a, b)];
                        }
                    }
                }
            }
        }
    }
}

/// The engagements of the last evaluation: the slots past `len` keep their vectors for the
/// next one, so an evaluation refills them instead of allocating (no allocation in
/// the hot path).
#[derive(Default)]
pub(in crate::solve) struct Engagements {
    slots: Vec<Engagement>,
    len: usize,
}

impl Engagements {
    pub(in crate::solve) fn clear(&mut self) {
        self.len = 0;
    }

    /// The next slot, for one of `Engagement`'s setters to fill.
    pub(in crate::solve) fn next_slot(&mut self) -> &mut Engagement {
        if self.len == self.slots.len() {
            self.slots.push(Engagement::default());
        }
        self.len += 1;
        &mut self.slots[self.len - 1]
    }

    pub(in crate::solve) fn as_slice(&self) -> &[Engagement] {
        &self.slots[..self.len]
    }

    pub(in crate::solve) fn as_mut_slice(&mut self) -> &mut [Engagement] {
        &mut self.slots[..self.len]
    }
}

fn refill<T>(v: &mut Vec<T>, items: impl IntoIterator<Item = T>) {
    v.clear();
    v.extend(items);
}

/// The nodes the samples of a slave node couple, the node first, into `nodes`.
fn sample_nodes(node: usize, samples: &[GapSample], nodes: &mut Vec<usize>) {
    refill(nodes, [node]);
    for s in samples {
        for &n in &s.nodes {
            if !nodes.contains(&n) {
                nodes.push(n);
            }
        }
    }
}

fn position_in(nodes: &[usize], n: usize) -> usize {
    nodes.iter().position(|&q| q == n).expect("listed")
}

/// The Hessians of the pointwise gap at the integration points of one evaluation, computed
/// when a tangent first asks (each point serves the two slave nodes whose hats cover it).
#[derive(Default)]
pub(in crate::solve) struct PointHessians {
    /// Per point, its index in `matrices` (u32::MAX until computed).
    slot: Vec<u32>,
    matrices: Vec<SampleMatrix>,
}

impl PointHessians {
    /// Forgets every Hessian; `points` points to come.
    pub(in crate::solve) fn reset(&mut self, points: usize) {
        self.slot.clear();
        self.slot.resize(points, u32::MAX);
        self.matrices.clear();
    }

    /// The (unweighted) Hessian at `sample`'s point.
    fn at(&mut self, sample: &GapSample, x: &impl Fn(usize) -> [f64; 2]) -> &SampleMatrix {
        if self.slot[sample.point] == u32::MAX {
            self.slot[sample.point] = self.matrices.len() as u32;
            self.matrices.push(sample.point_hessian(x));
        }
        &self.matrices[self.slot[sample.point] as usize]
    }
}

//! Contact in the parallel problem. Contact surfaces are small: every rank gathers the
//! current coordinates of all their nodes at each evaluation (with its elements' DOFs, in the
//! problem's one scatter), rebuilds the search grid, and evaluates the slave nodes it owns;
//! the contributions are assembled with the elements.
//!
//! A pair is one pass (its slave nodes against its master segments) or, two-pass, also the
//! reverse pass; each pass of a two-pass pair carries half of the penalty force, so the
//! pressure at a slave node, p = max(0, lambda - eps g), is the contact pressure in both modes.

use super::pattern::ContactPattern;
use super::problem::ROUNDOFF_ULPS;
use crate::contact::integrated::{weighted_gaps, GapSample, SampleMatrix};
use crate::contact::node_to_edge::{edge_residual, edge_residual_and_tangent, ContactLaw, EdgeProjection};
use crate::contact::search::EdgeGrid;
use crate::contact::surface::ContactSurface;
use crate::dist::{DofMap, Partition};
use crate::model::{ContactIntegration, ContactPair, Model, Penalty};
use crate::petsc::sys::PetscInt;

/// Mesh nodes of every contact surface of the model (sorted).
pub fn contact_nodes(model: &Model) -> Vec<usize> {
    let mut nodes: Vec<usize> =
        model.contacts.iter().flat_map(|c| [&c.slave, &c.master]).flat_map(|s| model.surfaces[s].iter().flat_map(|&e| model.mesh.edge_nodes(e))).collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

/// One direction of a pair, by surface index: its slave nodes bear on its master's edges and
/// carry `weight` of the pair's force (one half each in a two-pass pair).
pub(super) struct Direction {
    pub pair: usize,
    pub slave: usize,
    pub master: usize,
    pub weight: f64,
}

/// The model's contact surfaces (each once, however many pairs name it) and the directions of
/// every pair over them.
pub(super) fn surfaces_and_directions(model: &Model) -> (Vec<ContactSurface>, Vec<Direction>) {
    let mut names: Vec<&str> = Vec::new();
    for c in &model.contacts {
        for s in [c.slave.as_str(), c.master.as_str()] {
            if !names.contains(&s) {
                names.push(s);
            }
        }
    }
    let surfaces = names.iter().map(|n| ContactSurface::new(&model.mesh, &model.surfaces[*n])).collect();
    let index = |n: &str| names.iter().position(|m| *m == n).expect("surface listed");
    let mut directions = Vec::new();
    for (pair, c) in model.contacts.iter().enumerate() {
        let (s, m) = (index(&c.slave), index(&c.master));
        let two = c.two_pass && s != m;
        let weight = if two { 0.5 } else { 1.0 };
        directions.push(Direction { pair, slave: s, master: m, weight });
        if two {
            directions.push(Direction { pair, slave: m, master: s, weight });
        }
    }
    (surfaces, directions)
}

/// Self-contact: the edges a slave edge may not bear on, those within `hops` of its nodes.
pub(super) fn edge_neighbourhood(surface: &ContactSurface, edge: usize, hops: usize) -> Vec<usize> {
    let mut near: Vec<usize> = surface.edges[edge].iter().flat_map(|&n| surface.neighbourhood(n, hops)).collect();
    near.sort_unstable();
    near.dedup();
    near
}

/// One direction of a pair: slave nodes of one surface against the segments of another.
struct Pass {
    pair: usize,
    slave: usize,
    master: usize,
    weight: f64,
    /// Indices (into the slave surface's nodes) of the slave nodes this rank owns, in
    /// partition order.
    owned: Vec<usize>,
    /// Position of this rank's first owned slave node among all the pass's slave nodes.
    offset: usize,
    /// Number of slave nodes of the pass over all ranks.
    total: usize,
    /// Self-contact: the master edges each slave edge (segment integration) or each owned
    /// slave node (node-to-segment, in `owned` order) may not bear on, its own neighbourhood;
    /// fixed by the topology, so listed once. Empty for two surfaces.
    excluded: Vec<Vec<usize>>,
}

/// The contribution of one active slave node: residual and tangent over `nodes`.
pub struct Engagement {
    /// Mesh nodes the contribution couples (the slave node first).
    pub nodes: Vec<usize>,
    /// Two entries per node, (r, z).
    pub residual: Vec<f64>,
    /// Row-major, (2 nodes) x (2 nodes); empty until an evaluation asks for tangents.
    pub tangent: Vec<f64>,
    /// What the tangent is computed from, kept so a residual-only evaluation (the line
    /// search's) can be completed by the Jacobian at the same iterate without a new search.
    recipe: TangentRecipe,
}

enum TangentRecipe {
    /// Node-to-segment: the kernel's arguments.
    Nodal { xs: [f64; 2], master: [[f64; 2]; 3], projection: EdgeProjection, law: ContactLaw },
    /// Segment integration: K = stiffness dg dg^T - weighted_pressure d2g, with dg (`gradient`,
    /// over the engagement's nodes) and d2g the sums over the node's integration points.
    Integrated { samples: Vec<GapSample>, gradient: Vec<f64>, stiffness: f64, weighted_pressure: f64 },
}

/// What an evaluation must provide.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Need {
    Residual,
    Tangent,
}

/// State of one owned slave node after an evaluation.
#[derive(Clone, Copy, Debug, Default)]
pub struct SlaveState {
    /// Normal gap (mm), NaN when no master segment is within the capture distance.
    pub gap: f64,
    /// Contact pressure (MPa).
    pub pressure: f64,
    /// Normal force per radian on the slave node (this pass's share).
    pub force: f64,
    /// Contact traction (MPa) recovered from the total contact forces on the slave surface
    /// (both passes): the p with integral N_i p r ds = f_i.n_i at every node. Set after a
    /// converged increment.
    pub traction: f64,
}

/// Multipliers (augmented Lagrangian) of every owned slave node, per pass.
pub type Multipliers = Vec<Vec<f64>>;

/// What contact carries from one step's problem into the next: the committed multipliers and
/// the reserved sparsity pattern.
pub struct ContactCarry {
    pub multipliers: Multipliers,
    pub pattern: ContactPattern,
}

pub struct ContactAssembly {
    surfaces: Vec<ContactSurface>,
    passes: Vec<Pass>,
    /// Mesh node -> index into `nodes`, usize::MAX when not a contact node.
    slot: Vec<usize>,
    nodes: Vec<usize>,
    /// For each contact node DOF, its position in the problem's gathered values (usize::MAX
    /// when prescribed).
    gathered_slot: Vec<[usize; 2]>,
    /// Current positions of the contact nodes (refreshed by `gather`).
    positions: Vec<[f64; 2]>,
    /// Multipliers of the last converged increment and the ones in use.
    committed: Multipliers,
    current: Multipliers,
    /// Slave states of the last evaluation, per pass.
    pub states: Vec<Vec<SlaveState>>,
    /// Contact residual accumulated on every contact node by this rank's last evaluation.
    nodal_forces: Vec<[f64; 2]>,
    /// Round-off floor (squared) of the last evaluation: a gap is a difference of positions,
    /// so each active slave node's force carries about eps * penalty * area * |x|.
    roundoff: f64,
    /// The engagements of the last evaluation, and the positions and multipliers it was made
    /// at: SNES asks for the Jacobian at the iterate whose residual it has just evaluated, and
    /// the search need not run twice; only the tangents are added.
    engagements: Vec<Engagement>,
    evaluated_at: Option<(Vec<[f64; 2]>, Multipliers)>,
    /// Whether the engagements carry their tangents.
    with_tangents: bool,
    /// Integration points of the last evaluation's segment-integrated passes (their samples'
    /// `point`s, numbered across passes), and the Hessians computed at them for its tangents.
    points: usize,
    point_hessians: PointHessians,
    /// The contact couplings the Jacobian's pattern holds (and those it must take).
    pattern: ContactPattern,
}

impl ContactAssembly {
    /// None when the model has no contact pairs.
    /// `slot_of` gives the position of a free DOF in the values the problem gathers at each
    /// evaluation (it gathers every contact node's).
    pub fn new(model: &Model, partition: &Partition, dofs: &DofMap, slot_of: impl Fn(PetscInt) -> usize, carry: Option<ContactCarry>) -> Option<Self> {
        if model.contacts.is_empty() {
            return None;
        }
        let (surfaces, directions) = surfaces_and_directions(model);
        let mut passes = Vec::new();
        for d in directions {
            let (slave, master, c) = (d.slave, d.master, &model.contacts[d.pair]);
            let mut order: Vec<usize> = (0..surfaces[slave].nodes.len()).collect();
            order.sort_by_key(|&i| partition.node_position[surfaces[slave].nodes[i]]);
            let owner = |i: &usize| partition.node_owner[surfaces[slave].nodes[*i]];
            let offset = order.iter().filter(|i| owner(i) < partition.rank).count();
            let owned: Vec<usize> = order.iter().copied().filter(|i| owner(i) == partition.rank).collect();
            let surface = &surfaces[slave];
            let excluded = match (slave == master, c.integration) {
                (false, _) => Vec::new(),
                (true, ContactIntegration::NodeToSegment) => owned.iter().map(|&i| surface.neighbourhood(surface.nodes[i], c.exclude_neighbours)).collect(),
                (true, ContactIntegration::Segment) => (0..surface.edges.len()).map(|e| edge_neighbourhood(surface, e, c.exclude_neighbours)).collect(),
            };
            passes.push(Pass { pair: d.pair, slave, master, weight: d.weight, owned, offset, total: order.len(), excluded });
        }
        let mut nodes: Vec<usize> = surfaces.iter().flat_map(|s| s.nodes.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let mut slot = vec![usize::MAX; model.mesh.coords.len()];
        for (k, &n) in nodes.iter().enumerate() {
            slot[n] = k;
        }
        let gathered_slot = nodes.iter().map(|&n| dofs.dof[n].map(|g| if g >= 0 { slot_of(g) } else { usize::MAX })).collect();
        let (committed, pattern) = match carry {
            Some(c) => (c.multipliers, c.pattern),
            None => (passes.iter().map(|p| vec![0.0; p.owned.len()]).collect(), ContactPattern::default()),
        };
        let states = passes.iter().map(|p| vec![SlaveState::default(); p.owned.len()]).collect();
        Some(ContactAssembly {
            surfaces,
            current: committed.clone(),
            committed,
            passes,
            positions: nodes.iter().map(|&n| model.mesh.coords[n]).collect(),
            slot,
            nodes,
            gathered_slot,
            states,
            nodal_forces: Vec::new(),
            roundoff: 0.0,
            engagements: Vec::new(),
            evaluated_at: None,
            with_tangents: false,
            points: 0,
            point_hessians: PointHessians::default(),
            pattern,
        })
    }

    /// Refreshes the current positions of all contact nodes from the problem's gathered
    /// values `g` and the prescribed values.
    pub fn gather(&mut self, model: &Model, g: &[f64], prescribed: &[[f64; 2]]) {
        for (k, &n) in self.nodes.iter().enumerate() {
            let x0 = model.mesh.coords[n];
            self.positions[k] =
                std::array::from_fn(|c| x0[c] + if self.gathered_slot[k][c] != usize::MAX { g[self.gathered_slot[k][c]] } else { prescribed[n][c] });
        }
    }

    /// Evaluates every owned slave node at the gathered positions and records the slave
    /// states; the engagements are then in `engagements()`, with their tangents if `need`
    /// says so. At the positions and multipliers of the previous evaluation only what that
    /// one lacked is computed.
    pub fn evaluate(&mut self, model: &Model, need: Need) {
        let same = self.evaluated_at.as_ref().is_some_and(|(x, m)| *x == self.positions && *m == self.current);
        if !same {
            self.evaluate_residuals(model);
        }
        if need == Need::Tangent && !self.with_tangents {
            let (slot, positions) = (&self.slot, &self.positions);
            let x = |n: usize| positions[slot[n]];
            self.point_hessians.reset(self.points);
            for e in &mut self.engagements {
                e.tangent = tangent(&e.recipe, &e.nodes, &x, &mut self.point_hessians);
                self.pattern.require(&e.nodes);
            }
            self.with_tangents = true;
        }
    }

    fn evaluate_residuals(&mut self, model: &Model) {
        let mut out = std::mem::take(&mut self.engagements);
        out.clear();
        self.nodal_forces.clear();
        self.nodal_forces.resize(self.nodes.len(), [0.0; 2]);
        self.roundoff = 0.0;
        self.points = 0;
        for p in 0..self.passes.len() {
            let pair = &model.contacts[self.passes[p].pair];
            match pair.integration {
                ContactIntegration::NodeToSegment => self.evaluate_nodal(model, pair, p, &mut out),
                ContactIntegration::Segment => self.evaluate_integrated(model, pair, p, &mut out),
            }
        }
        for e in &out {
            for (a, &n) in e.nodes.iter().enumerate() {
                for c in 0..2 {
                    self.nodal_forces[self.slot[n]][c] += e.residual[2 * a + c];
                }
            }
        }
        self.engagements = out;
        self.with_tangents = false;
        self.evaluated_at = Some((self.positions.clone(), self.current.clone()));
    }

    /// The active slave nodes' contributions from the last `evaluate`.
    pub fn engagements(&self) -> &[Engagement] {
        &self.engagements
    }

    fn penalty(model: &Model, pair: &ContactPair, master: &ContactSurface, edge: usize) -> f64 {
        match pair.penalty {
            Penalty::Stiffness(v) => v,
            Penalty::Factor(kappa) => kappa * model.materials[model.element_material[master.element[edge]]].youngs_modulus / master.edge_length[edge],
        }
    }

    /// Node-to-segment: the gap at each slave node, on the master edge it projects to.
    fn evaluate_nodal(&mut self, model: &Model, pair: &ContactPair, p: usize, out: &mut Vec<Engagement>) {
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
            let found = found.filter(|(_, proj)| {
                // surfaces in contact face each other: never the back of a thin master
                let ns = slave.node_normal(node, x);
                ns[0] * proj.normal[0] + ns[1] * proj.normal[1] < 0.0 && proj.gap > -capture
            });
            let Some((edge, proj)) = found else {
                self.states[p][k] = SlaveState { gap: f64::NAN, ..SlaveState::default() };
                continue;
            };
            let eps = Self::penalty(model, pair, master, edge);
            let area = slave.areas[i] * pass.weight;
            let en = master.edges[edge];
            let free_ends = master.neighbours[edge].map(|n| n.is_none());
            let multiplier = self.current[p][k];
            let law = ContactLaw { area, penalty: eps, multiplier, free_ends };
            let (residual, pressure) = edge_residual(xs, &en.map(x), &proj, &law);
            self.states[p][k] = SlaveState { gap: proj.gap, pressure, force: pressure * area, traction: 0.0 };
            if multiplier - eps * proj.gap >= 0.0 {
                self.roundoff += (ROUNDOFF_ULPS * f64::EPSILON * eps * area * xs[0].hypot(xs[1])).powi(2);
                out.push(Engagement {
                    nodes: vec![node, en[0], en[1], en[2]],
                    residual: residual.as_slice().to_vec(),
                    tangent: Vec::new(),
                    recipe: TangentRecipe::Nodal { xs, master: en.map(x), projection: proj, law },
                });
            }
        }
    }

    /// Segment integration: weighted gaps g_a = integral N_a g r ds and nodal pressures.
    fn evaluate_integrated(&mut self, model: &Model, pair: &ContactPair, p: usize, out: &mut Vec<Engagement>) {
        let pass = &self.passes[p];
        let (slot, positions) = (&self.slot, &self.positions);
        let x = |n: usize| positions[slot[n]];
        let x0 = |n: usize| model.mesh.coords[n];
        let (slave, master) = (&self.surfaces[pass.slave], &self.surfaces[pass.master]);
        let mut gaps = weighted_gaps(slave, master, &x, &x0, &pass.owned, &pass.excluded, pair.capture_distance);
        // number the points across passes
        let first = self.points;
        for s in gaps.iter_mut().flat_map(|g| g.samples.iter_mut()) {
            s.point += first;
            self.points = self.points.max(s.point + 1);
        }
        let mut owned_position = vec![usize::MAX; slave.nodes.len()];
        for (k, &i) in pass.owned.iter().enumerate() {
            owned_position[i] = k;
        }
        for s in self.states[p].iter_mut() {
            *s = SlaveState { gap: f64::NAN, ..SlaveState::default() };
        }
        for g in gaps {
            let k = owned_position[g.index];
            let area = slave.hat_areas[g.index];
            let eps = Self::penalty(model, pair, master, g.master_edge);
            let lambda = self.current[p][k];
            let trial = lambda - eps * g.gap / area;
            let pressure = trial.max(0.0);
            self.states[p][k] = SlaveState { gap: g.gap / area, pressure, force: pressure * area * pass.weight, traction: 0.0 };
            if trial < 0.0 {
                continue;
            }
            // dg over the nodes the samples couple
            let nodes = sample_nodes(slave.nodes[g.index], &g.samples);
            let mut gradient = vec![0.0; 2 * nodes.len()];
            for s in &g.samples {
                let sg = s.gradient();
                for (a, &n) in s.nodes.iter().enumerate() {
                    let at = position_in(&nodes, n);
                    gradient[2 * at] += sg[2 * a];
                    gradient[2 * at + 1] += sg[2 * a + 1];
                }
            }
            let xs = x(slave.nodes[g.index]);
            self.roundoff += (ROUNDOFF_ULPS * f64::EPSILON * pass.weight * eps * area * xs[0].hypot(xs[1])).powi(2);
            let residual = gradient.iter().map(|v| -pass.weight * pressure * v).collect();
            let recipe =
                TangentRecipe::Integrated { samples: g.samples, gradient, stiffness: pass.weight * eps / area, weighted_pressure: pass.weight * pressure };
            out.push(Engagement { nodes, residual, tangent: Vec::new(), recipe });
        }
    }

    /// Round-off floor (squared) of this rank's last evaluation.
    pub fn roundoff_squares(&self) -> f64 {
        self.roundoff
    }

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

    /// Uzawa update of the augmented-Lagrangian pairs from the last evaluation:
    /// lambda <- max(0, lambda - eps g), the current pressure.
    pub fn augment(&mut self, model: &Model) {
        for (p, pass) in self.passes.iter().enumerate() {
            if model.contacts[pass.pair].augmented_lagrangian.is_some() {
                for (k, s) in self.states[p].iter().enumerate() {
                    self.current[p][k] = s.pressure;
                }
            }
        }
    }

    /// Whether an augmented-Lagrangian pair still penetrates beyond its tolerance at one of
    /// this rank's slave nodes (at the last evaluation).
    pub fn needs_augmentation(&self, model: &Model) -> bool {
        self.passes.iter().enumerate().any(|(p, pass)| match model.contacts[pass.pair].augmented_lagrangian {
            Some(al) => self.states[p].iter().any(|s| s.pressure > 0.0 && -s.gap > al.penetration_tolerance),
            None => false,
        })
    }

    /// Accepts the multipliers in use (after a converged increment).
    /// The multipliers in use (augmented Lagrangian; zeros for a pure penalty).
    pub fn multipliers(&self) -> &Multipliers {
        &self.current
    }

    pub fn commit(&mut self) {
        self.committed.clone_from(&self.current);
    }

    /// Drops multiplier updates of a failed attempt.
    pub fn reset(&mut self) {
        self.current.clone_from(&self.committed);
    }

    pub fn into_carry(self) -> ContactCarry {
        ContactCarry { multipliers: self.committed, pattern: self.pattern }
    }

    pub fn pattern(&self) -> &ContactPattern {
        &self.pattern
    }

    pub fn pattern_mut(&mut self) -> &mut ContactPattern {
        &mut self.pattern
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
                    areas: pass.owned.iter().map(|&i| slave.areas[i] * pass.weight).collect(),
                    states: &self.states[p],
                }
            })
            .collect()
    }
}

/// The nodes the samples of a slave node couple, the node first.
fn sample_nodes(node: usize, samples: &[GapSample]) -> Vec<usize> {
    let mut nodes = vec![node];
    for s in samples {
        for &n in &s.nodes {
            if !nodes.contains(&n) {
                nodes.push(n);
            }
        }
    }
    nodes
}

fn position_in(nodes: &[usize], n: usize) -> usize {
    nodes.iter().position(|&q| q == n).expect("listed")
}

/// The tangent (row-major over `nodes`) an engagement's recipe gives at positions `x`.
fn tangent(recipe: &TangentRecipe, nodes: &[usize], x: &impl Fn(usize) -> [f64; 2], hessians: &mut PointHessians) -> Vec<f64> {
    match recipe {
        TangentRecipe::Nodal { xs, master, projection, law } => {
            let (_, k, _) = edge_residual_and_tangent(*xs, master, projection, law);
            k.transpose().as_slice().to_vec()
        }
        TangentRecipe::Integrated { samples, gradient, stiffness, weighted_pressure } => {
            let m = gradient.len();
            let mut k = vec![0.0; m * m];
            for i in 0..m {
                for j in 0..m {
                    k[i * m + j] = stiffness * gradient[i] * gradient[j];
                }
            }
            // -p d2g
            for s in samples {
                let h = hessians.at(s, x);
                let f = weighted_pressure * s.weight;
                let map = s.nodes.map(|n| 2 * position_in(nodes, n));
                for a in 0..12 {
                    let row = map[a / 2] + a % 2;
                    for b in 0..12 {
                        k[row * m + map[b / 2] + b % 2] -= f * h[(a, b)];
                    }
                }
            }
            k
        }
    }
}

/// The Hessians of the pointwise gap at the integration points of one evaluation, computed
/// when a tangent first asks (each point serves the two slave nodes whose hats cover it).
#[derive(Default)]
struct PointHessians {
    /// Per point, its index in `matrices` (u32::MAX until computed).
    slot: Vec<u32>,
    matrices: Vec<SampleMatrix>,
}

impl PointHessians {
    /// Forgets every Hessian; `points` points to come.
    fn reset(&mut self, points: usize) {
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

/// This rank's slab of one pass, for the results file.
pub struct PassOutput<'a> {
    pub pair: usize,
    pub pass: usize,
    pub offset: usize,
    pub total: usize,
    pub nodes: Vec<usize>,
    pub areas: Vec<f64>,
    pub states: &'a [SlaveState],
}

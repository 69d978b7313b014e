//! Contact in the parallel problem. Contact surfaces are small: every rank gathers the
//! current coordinates of all their nodes at each evaluation (with its elements' DOFs, in the
//! problem's one scatter), rebuilds the search grid, and evaluates the slave nodes it owns;
//! the contributions are assembled with the elements.
//!
//! A pair is one pass (its slave nodes against its master segments) or, two-pass, also the
//! reverse pass; each pass of a two-pass pair carries half of the penalty force, so the
//! pressure at a slave node, p = max(0, lambda - eps g), is the contact pressure in both modes.

use crate::contact::integrated::WeightedGap;
use crate::contact::search::EdgeGrid;
use crate::contact::surface::ContactSurface;
use crate::decomposition::{DofMap, Partition};
use crate::model::{ContactIntegration, Friction, Model};
use crate::petsc::sys::PetscInt;
use crate::records::contact::{SlaveState, SlipPoint};
use crate::solve::contact::engagement::{Engagements, PointHessians};
use crate::solve::contact::surfaces::{edge_neighbourhood, surfaces_and_directions};
use crate::solve::jacobian::pattern::ContactPattern;
pub use engagement::{BaseContact, Engagement};
pub use surfaces::contact_nodes;

pub mod affinity;
pub(super) mod engagement;
mod output;
mod slave_nodes;
pub(super) mod surfaces;

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
    /// The pair has friction in some step (its slip references are kept).
    friction: bool,
    /// A node-based slave (`ContactPair::slave_nodes`): each owned node bears with the area of
    /// the master face it meets, times `weight`.
    master_face_area: bool,
}

/// What an evaluation must provide.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Need {
    Residual,
    Tangent,
}

/// Where each slave node of a pass with friction starts measuring its slip: its projection on
/// the master in the undeformed mesh (none beyond the capture distance).
fn initial_slip_references(model: &Model, surfaces: &[ContactSurface], passes: &[Pass]) -> SlipPoints {
    let x = |n: usize| model.mesh.coords[n];
    passes
        .iter()
        .map(|pass| {
            let pair = &model.contacts[pass.pair];
            if !pass.friction {
                return vec![None; pass.owned.len()];
            }
            let (slave, master) = (&surfaces[pass.slave], &surfaces[pass.master]);
            let grid = EdgeGrid::new(master, &x, pair.capture_distance);
            pass.owned
                .iter()
                .map(|&i| {
                    let node = slave.nodes[i];
                    let excluded = if pass.slave == pass.master { slave.neighbourhood(node, pair.exclude_neighbours) } else { Vec::new() };
                    let ns = slave.node_normal(node, x);
                    grid.closest_edge(master, &x, x(node), &excluded, pair.capture_distance, None)
                        .filter(|(edge, proj)| master.bears(*edge, proj, ns, pair.capture_distance))
                        .map(|(edge, proj)| SlipPoint { edge, xi: proj.xi, traction: 0.0 })
                })
                .collect()
        })
        .collect()
}

/// Per pass, per owned slave node: its slip reference (None where no master edge was within
/// reach).
pub type SlipPoints = Vec<Vec<Option<SlipPoint>>>;

/// Multipliers (augmented Lagrangian) of every owned slave node, per pass.
pub type Multipliers = Vec<Vec<f64>>;

/// What contact carries from one step's problem into the next: the committed multipliers and
/// the reserved sparsity pattern.
pub struct ContactCarry {
    pub multipliers: CarriedMultipliers,
    pub pattern: ContactPattern,
    pub slip: CarriedSlip,
}

/// Committed slip references handed to a new problem.
pub enum CarriedSlip {
    /// Per pass, per owned slave node (the same partition's previous step).
    Owned(SlipPoints),
    /// Per pass, (mesh node, reference) of the slave nodes that have one (a restart's).
    ByNode(Vec<Vec<(usize, SlipPoint)>>),
}

/// Committed multipliers handed to a new problem.
pub enum CarriedMultipliers {
    /// Per pass, per owned slave node (the same partition's previous step).
    Owned(Multipliers),
    /// Per pass, (mesh node, multiplier) of every slave node with a nonzero one (a restart's,
    /// from the results file; any partition).
    ByNode(Vec<Vec<(usize, f64)>>),
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
    engagements: Engagements,
    /// Per pass, the weighted gaps of the last evaluation (one per owned slave node), kept so
    /// the next one refills their sample vectors.
    gaps: Vec<Vec<WeightedGap>>,
    /// Per pass, the end of its engagements in `engagements` (passes in order).
    pass_ends: Vec<usize>,
    evaluated_at: Option<(Vec<[f64; 2]>, Multipliers)>,
    /// The friction of each pair in the current step (`Model::friction_in_step`).
    friction: Vec<Option<Friction>>,
    /// Friction left out of the evaluations (the load predictor's tangent; see
    /// `Problem::set_without_friction`).
    without_friction: bool,
    /// Whether the engagements carry their tangents.
    with_tangents: bool,
    /// Integration points of the last evaluation's segment-integrated passes (their samples'
    /// `point`s, numbered across passes), and the Hessians computed at them for its tangents.
    points: usize,
    point_hessians: PointHessians,
    /// The contact couplings the Jacobian's pattern holds (and those it must take).
    pattern: ContactPattern,
    /// Friction: the slip references of the last converged increment, and those the last
    /// evaluation found (committed with the increment).
    slip_committed: SlipPoints,
    slip_trial: SlipPoints,
}

impl ContactAssembly {
    /// None when the model has no contact pairs. The pairs' friction is that of step `step`.
    /// `slot_of` gives the position of a free DOF in the values the problem gathers at each
    /// evaluation (it gathers every contact node's).
    pub fn new(
        model: &Model,
        step: usize,
        partition: &Partition,
        dofs: &DofMap,
        slot_of: impl Fn(PetscInt) -> usize,
        carry: Option<ContactCarry>,
    ) -> Option<Self> {
        if model.contacts.is_empty() {
            return None;
        }
        let (surfaces, directions) = surfaces_and_directions(model);
        let mut passes = Vec::new();
        for d in directions {
            let (slave, master, c) = (d.slave, d.master, &model.contacts[d.pair]);
            // a node-based slave's points are its set's nodes (its surface also holds the other
            // nodes of the faces they lie on)
            let mut order: Vec<usize> =
                (0..surfaces[slave].nodes.len()).filter(|&i| d.slave_nodes.is_none_or(|set| set.binary_search(&surfaces[slave].nodes[i]).is_ok())).collect();
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
            passes.push(Pass {
                pair: d.pair,
                slave,
                master,
                weight: d.weight,
                owned,
                offset,
                total: order.len(),
                excluded,
                friction: model.pair_has_friction(d.pair),
                master_face_area: d.slave_nodes.is_some(),
            });
        }
        let mut nodes: Vec<usize> = surfaces.iter().flat_map(|s| s.nodes.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let mut slot = vec![usize::MAX; model.mesh.coords.len()];
        for (k, &n) in nodes.iter().enumerate() {
            slot[n] = k;
        }
        let gathered_slot = nodes.iter().map(|&n| dofs.dof[n].map(|g| if g >= 0 { slot_of(g) } else { usize::MAX })).collect();
        let zeros = || passes.iter().map(|p| vec![0.0; p.owned.len()]).collect::<Multipliers>();
        let nowhere = || passes.iter().map(|p| vec![None; p.owned.len()]).collect::<SlipPoints>();
        // per pass, the value saved for each owned slave node (a restart's, by mesh node)
        fn by_node<T: Copy>(passes: &[Pass], surfaces: &[ContactSurface], saved: &[Vec<(usize, T)>], out: &mut [Vec<T>], wrap: impl Fn(T) -> T) {
            for ((values, pass), saved) in out.iter_mut().zip(passes).zip(saved) {
                let saved: std::collections::HashMap<usize, T> = saved.iter().copied().collect();
                for (v, &i) in values.iter_mut().zip(&pass.owned) {
                    if let Some(&s) = saved.get(&surfaces[pass.slave].nodes[i]) {
                        *v = wrap(s);
                    }
                }
            }
        }
        let (committed, pattern, slip) = match carry {
            Some(ContactCarry { multipliers, pattern, slip }) => {
                let m = match multipliers {
                    CarriedMultipliers::Owned(m) => m,
                    CarriedMultipliers::ByNode(saved) => {
                        let mut m = zeros();
                        by_node(&passes, &surfaces, &saved, &mut m, |v| v);
                        m
                    }
                };
                let s = match slip {
                    CarriedSlip::Owned(s) => s,
                    CarriedSlip::ByNode(saved) => {
                        let mut s = nowhere();
                        let saved: Vec<Vec<(usize, Option<SlipPoint>)>> =
                            saved.into_iter().map(|v| v.into_iter().map(|(n, p)| (n, Some(p))).collect()).collect();
                        by_node(&passes, &surfaces, &saved, &mut s, |v| v);
                        s
                    }
                };
                (m, pattern, s)
            }
            None => (zeros(), ContactPattern::default(), initial_slip_references(model, &surfaces, &passes)),
        };
        let states = passes.iter().map(|p| vec![SlaveState::default(); p.owned.len()]).collect();
        let gaps = passes.iter().map(|_| Vec::new()).collect();
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
            engagements: Engagements::default(),
            gaps,
            pass_ends: Vec::new(),
            evaluated_at: None,
            friction: model.friction_in_step(step),
            without_friction: false,
            with_tangents: false,
            points: 0,
            point_hessians: PointHessians::default(),
            pattern,
            slip_trial: slip.clone(),
            slip_committed: slip,
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
            for e in self.engagements.as_mut_slice() {
                e.form_tangent(&x, &mut self.point_hessians);
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
        self.pass_ends.clear();
        for p in 0..self.passes.len() {
            let pair = &model.contacts[self.passes[p].pair];
            match pair.integration {
                ContactIntegration::NodeToSegment => self.evaluate_nodal(model, pair, p, &mut out),
                ContactIntegration::Segment => self.evaluate_integrated(model, pair, p, &mut out),
            }
            self.pass_ends.push(out.as_slice().len());
        }
        for e in out.as_slice() {
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
        self.engagements.as_slice()
    }

    /// The closed contact nodes this rank owns at the gathered positions (a converged state),
    /// with their pair, for the perturbation steps about it (`contact::harmonic`).
    pub fn base_contacts(&mut self, model: &Model) -> Vec<(usize, BaseContact)> {
        self.evaluate(model, Need::Tangent);
        let mut start = 0;
        let mut out = Vec::new();
        for (pass, &end) in self.passes.iter().zip(&self.pass_ends) {
            out.extend(self.engagements.as_slice()[start..end].iter().map(|e| (pass.pair, e.for_perturbation())));
            start = end;
        }
        out
    }

    /// Round-off floor (squared) of this rank's last evaluation.
    pub fn roundoff_squares(&self) -> f64 {
        self.roundoff
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

    /// The multipliers in use (augmented Lagrangian; zeros for a pure penalty).
    pub fn multipliers(&self) -> &Multipliers {
        &self.current
    }

    /// Accepts the multipliers in use and the slip references of the last evaluation (after a
    /// converged increment).
    pub fn commit(&mut self) {
        self.committed.clone_from(&self.current);
        if self.passes.iter().any(|p| p.friction) {
            self.slip_committed.clone_from(&self.slip_trial);
            // the last evaluation measured slip from the old references: the next one (the
            // predictor's tangent at this very state) must not reuse it
            self.evaluated_at = None;
        }
    }

    /// Leaves friction out of the evaluations from now on (or takes it back in); returns the
    /// previous choice.
    pub fn set_without_friction(&mut self, without: bool) -> bool {
        if without != self.without_friction {
            // the last evaluation was made with the other choice
            self.evaluated_at = None;
        }
        std::mem::replace(&mut self.without_friction, without)
    }

    /// Drops multiplier updates of a failed attempt.
    pub fn reset(&mut self) {
        self.current.clone_from(&self.committed);
    }

    pub fn into_carry(self) -> ContactCarry {
        ContactCarry { multipliers: CarriedMultipliers::Owned(self.committed), pattern: self.pattern, slip: CarriedSlip::Owned(self.slip_committed) }
    }

    /// The committed slip references of this rank's slave nodes, per pass: (mesh node,
    /// reference) where there is one (what a restart needs with friction).
    pub fn slip_by_node(&self) -> Vec<Vec<(usize, SlipPoint)>> {
        self.passes
            .iter()
            .zip(&self.slip_committed)
            .map(|(pass, points)| pass.owned.iter().zip(points).filter_map(|(&i, s)| s.map(|s| (self.surfaces[pass.slave].nodes[i], s))).collect())
            .collect()
    }

    /// The committed multipliers of this rank's slave nodes, per pass: (mesh node, value) where
    /// nonzero (what a restart needs; zero for every pure-penalty pair).
    pub fn committed_by_node(&self) -> Vec<Vec<(usize, f64)>> {
        self.passes
            .iter()
            .zip(&self.committed)
            .map(|(pass, values)| pass.owned.iter().zip(values).filter(|(_, v)| **v != 0.0).map(|(&i, &v)| (self.surfaces[pass.slave].nodes[i], v)).collect())
            .collect()
    }

    pub fn pattern(&self) -> &ContactPattern {
        &self.pattern
    }

    pub fn pattern_mut(&mut self) -> &mut ContactPattern {
        &mut self.pattern
    }
}

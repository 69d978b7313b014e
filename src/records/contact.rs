//! The contact state of the slave nodes, as the solver leaves it after an evaluation and the
//! results file writes it.

/// State of one owned slave node after an evaluation.
#[derive(Clone, Copy, Debug, Default)]
pub struct SlaveState {
    /// Normal gap (mm), NaN when no master segment is within the capture distance.
    pub gap: f64,
    /// Contact pressure (MPa).
    pub pressure: f64,
    /// Normal force per radian on the slave node (this pass's share).
    pub force: f64,
    /// The area its pressure acts on (this pass's share), per radian: the node's tributary
    /// area, or for a node-based slave the master face's where it projects (0 where no master
    /// face is within reach).
    pub area: f64,
    /// Contact traction (MPa) recovered from the total contact forces on the slave surface
    /// (both passes): the p with integral N_i p r ds = f_i.n_i at every node. Set after a
    /// converged increment.
    pub traction: f64,
    /// Frictional (tangential) traction, MPa, along the master's tangent (0 without friction).
    pub shear: f64,
    /// Whether the node slides (friction at its Coulomb limit).
    pub sliding: bool,
    /// Energies of the node's contact, N mm per radian: stored in the normal penalty and in the
    /// tangential one, and dissipated by friction since the last converged increment.
    pub normal_energy: f64,
    pub friction_stored: f64,
    pub friction_dissipated: f64,
}

/// Where a slave node's slip is measured from (friction): the master edge (an index into the
/// master surface's edges) and coordinate of the material point it was at after the last
/// converged increment, and its tangential traction then (0 when the contact was open).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipPoint {
    pub edge: usize,
    pub xi: f64,
    pub traction: f64,
}

/// This rank's slab of one pass, for the results file.
pub struct PassOutput<'a> {
    pub pair: usize,
    pub pass: usize,
    pub offset: usize,
    pub total: usize,
    pub nodes: Vec<usize>,
    pub areas: Vec<f64>,
    /// A node-based slave's areas this increment: the master face's where each node projects,
    /// 0 where none is within reach (its `areas` are NaN).
    pub bearing_areas: Option<Vec<f64>>,
    pub states: &'a [SlaveState],
    /// The pair has friction (its shear and sliding state are written).
    pub friction: bool,
}

//! What a heat step gives: temperatures, fluxes and the held sets' heat flows.

use crate::element::solid::QUADRATURE_POINTS;

/// The heat flowing into the body through a held set's nodes: per radian in axisymmetry (the
/// full ring's is 2 pi times), over the thickness in a plane model; mW.
#[derive(Clone, Debug, PartialEq)]
pub struct HeatFlow {
    pub set: String,
    pub flow: f64,
}

/// What a heat step gives.
#[derive(Clone, Debug)]
pub struct HeatAnswer {
    /// Every node's temperature, degC (model order).
    pub temperature: Vec<f64>,
    /// The heat flux [q_r, q_z] (mW/mm^2) at the Gauss points of this rank's elements
    /// (partition order).
    pub flux: Vec<[[f64; 2]; QUADRATURE_POINTS]>,
    /// Each held set's heat flow, in the step's order.
    pub flows: Vec<HeatFlow>,
}

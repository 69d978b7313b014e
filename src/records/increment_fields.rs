//! What the results file writes of a converged increment, as the solver hands it over.

use crate::element::solid::QUADRATURE_POINTS;
use crate::model::Temperature;
use crate::records::contact::PassOutput;

/// This rank's slabs of the fields of one converged increment.
#[derive(Clone, Copy)]
pub struct IncrementFields<'a> {
    /// Displacement of the owned nodes, partition order.
    pub displacement: &'a [[f64; 2]],
    /// Cauchy stress at the Gauss points of the local elements.
    pub stress: &'a [[[f64; 4]; QUADRATURE_POINTS]],
    pub plastic_strain: &'a [[f64; QUADRATURE_POINTS]],
    /// Total strain [rr, zz, tt, rz] (tensor shear) at the Gauss points of the local elements.
    pub strain: &'a [[[f64; 4]; QUADRATURE_POINTS]],
    /// Plastic strain tensor at the Gauss points of the local elements.
    pub plastic_strain_tensor: &'a [[[f64; 4]; QUADRATURE_POINTS]],
    /// The backstress (the sum of its terms, MPa) at the Gauss points of the local elements,
    /// where a material has kinematic hardening.
    pub backstress: Option<&'a [[[f64; 4]; QUADRATURE_POINTS]]>,
    /// Reaction force (r, z) of the owned nodes, per radian: zero on the free DOFs.
    pub reaction: &'a [[f64; 2]],
    /// The temperature of every node, degC.
    pub temperature: &'a Temperature,
    /// Contact slave nodes of the passes this rank owns.
    pub contact: &'a [PassOutput<'a>],
}

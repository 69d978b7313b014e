//! What a residual evaluation leaves for the calls that follow it at the same iterate: the
//! material tangents for the Jacobian SNES asks for next, and the output fields for the
//! output after convergence.

use crate::element::solid::{ElementEnergy, MaterialTangents, NODES, QUADRATURE_POINTS};
use crate::solve::contact::Multipliers;

/// The material tangents each local element's last residual evaluation computed, with the
/// displacements and temperature they belong to. SNES asks for the Jacobian at the iterate
/// whose residual it has just evaluated, so the Jacobian finds them here and only forms the
/// element matrices: the material update, the costly part, runs once per iterate (on dual
/// numbers, about 1.5 times a plain update) instead of twice. A commit drops those of the
/// elements whose history it changes; the others serve the next increment's predictor, which
/// asks for the Jacobian at the converged state.
#[derive(Default)]
pub(in crate::solve) struct KeptTangents {
    /// Per local element.
    pub elements: Vec<KeptTangent>,
}

#[derive(Clone, Default)]
pub(in crate::solve) struct KeptTangent {
    /// Whether `material` belongs to `u` and `temperature_change` (and today's history).
    pub valid: bool,
    pub u: [[f64; 2]; NODES],
    pub temperature_change: [f64; NODES],
    pub material: MaterialTangents,
}

impl KeptTangents {
    pub fn get(&self, k: usize, u: &[[f64; 2]; NODES], temperature_change: &[f64; NODES]) -> Option<&MaterialTangents> {
        let e = self.elements.get(k)?;
        (e.valid && e.u == *u && e.temperature_change == *temperature_change).then_some(&e.material)
    }

    /// Drops element `k`'s tangents (its history has changed).
    pub fn forget_element(&mut self, k: usize) {
        if let Some(e) = self.elements.get_mut(k) {
            e.valid = false;
        }
    }
}

/// What an evaluation at a converged state gives for output.
#[derive(Clone, Debug)]
pub struct ElementFields {
    /// Cauchy stress at the Gauss points of each local element (partition order).
    pub stress: Vec<[[f64; 4]; QUADRATURE_POINTS]>,
    /// Equivalent plastic strain at the Gauss points.
    pub plastic_strain: Vec<[f64; QUADRATURE_POINTS]>,
    /// F_33 at the Gauss points (`SolidResponse::thickness_stretch`).
    pub thickness_stretch: Vec<[f64; QUADRATURE_POINTS]>,
    /// This rank's part of f_int - f_ext at every node of the mesh (summed over ranks, it is
    /// the reaction at prescribed DOFs), per radian.
    pub nodal_force: Vec<[f64; 2]>,
    /// This rank's part of the pressure loads at every node (external force, per radian).
    pub pressure_force: Vec<[f64; 2]>,
    /// This rank's elements' energies, summed (per radian, N mm).
    pub energy: ElementEnergy,
    /// This rank's part of the thermal strain's stress power per degree at every node (see
    /// `SolidResponse::thermal_force`).
    pub thermal_force: Vec<f64>,
}

impl ElementFields {
    /// Zero fields for `elements` local elements and `nodes` mesh nodes.
    pub fn zeros(elements: usize, nodes: usize) -> Self {
        ElementFields {
            stress: vec![[[0.0; 4]; QUADRATURE_POINTS]; elements],
            plastic_strain: vec![[0.0; QUADRATURE_POINTS]; elements],
            thickness_stretch: vec![[1.0; QUADRATURE_POINTS]; elements],
            nodal_force: vec![[0.0; 2]; nodes],
            pressure_force: vec![[0.0; 2]; nodes],
            energy: ElementEnergy::default(),
            thermal_force: vec![0.0; nodes],
        }
    }
}

/// The output fields of the last residual evaluation and the state it was made at: after
/// convergence the output asks for the fields at the iterate whose residual SNES has just
/// evaluated, so they are kept rather than computed a second time.
pub(in crate::solve) struct LastEvaluation {
    pub gathered: Vec<f64>,
    /// The problem's load generation it was made under.
    pub load: u64,
    pub multipliers: Option<Multipliers>,
    pub fields: ElementFields,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kept_tangents_serve_only_the_state_they_were_computed_at() {
        let mut kept = KeptTangents { elements: vec![KeptTangent::default(); 2] };
        let u = [[0.1, -0.2]; NODES];
        kept.elements[1] = KeptTangent { valid: true, u, temperature_change: [180.0; NODES], material: MaterialTangents::default() };
        assert!(kept.get(1, &u, &[180.0; NODES]).is_some());
        assert!(kept.get(0, &u, &[180.0; NODES]).is_none(), "never computed");
        let mut moved = u;
        moved[3][1] += 1e-12;
        assert!(kept.get(1, &moved, &[180.0; NODES]).is_none(), "another iterate");
        assert!(kept.get(1, &u, &[180.5; NODES]).is_none(), "another temperature");
        kept.forget_element(0);
        assert!(kept.get(1, &u, &[180.0; NODES]).is_some(), "another element's history changed");
        kept.forget_element(1);
        assert!(kept.get(1, &u, &[180.0; NODES]).is_none(), "a commit changed the history");
    }
}

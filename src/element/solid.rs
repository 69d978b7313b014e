//! The 8-node axisymmetric solid (Q8 serendipity, 3x3 Gauss integration).
//!
//! Why Q8: the bellows plies are 1 mm thick and bend. A quadratic element represents the linear
//! bending strain through the thickness exactly, so it neither shear-locks (as plain bilinear Q4
//! does) nor needs incompatible modes; with full 3x3 integration it has no hourglass modes.
//! The kernel takes the current nodal displacements and returns the residual contribution
//! (internal force, per radian) and its tangent: the same interface the finite-strain and
//! plasticity work plugs into.

use crate::fe::axisymmetric::{b_column, map_point, small_strain};
use crate::fe::quadrature::square_3x3;
use crate::material::elastic::Elastic;
use nalgebra::{SMatrix, SVector};

pub const NODES: usize = 8;
pub const DOFS: usize = 16;
pub const QUADRATURE_POINTS: usize = 9;

pub type ElementVector = SVector<f64, DOFS>;
pub type ElementMatrix = SMatrix<f64, DOFS, DOFS>;

/// What one element evaluation produces.
#[derive(Clone, Debug)]
pub struct SolidResponse {
    /// Internal force per radian, f_int = sum_q B^T sigma r det(J) w.
    pub internal_force: ElementVector,
    /// d f_int / d u (only when requested).
    pub tangent: Option<ElementMatrix>,
    /// Stress `[rr, zz, tt, rz]` at each quadrature point.
    pub stress: [[f64; 4]; QUADRATURE_POINTS],
}

/// Evaluates the element with reference nodal coordinates `x` (r, z), nodal displacements `u`
/// and uniform temperature change `dt` from the reference temperature.
pub fn compute_solid(
    x: &[[f64; 2]; NODES],
    u: &[[f64; 2]; NODES],
    dt: f64,
    material: &Elastic,
    with_tangent: bool,
) -> Result<SolidResponse, String> {
    let mut f = ElementVector::zeros();
    let mut k = with_tangent.then(ElementMatrix::zeros);
    let mut stress = [[0.0; 4]; QUADRATURE_POINTS];
    let d = SMatrix::<f64, 4, 4>::from_fn(|i, j| material.tangent()[i][j]);
    for (q, (p, w)) in square_3x3().into_iter().enumerate() {
        let g = map_point(x, p)?;
        let sigma = material.stress(&small_strain(&g, u), dt);
        stress[q] = sigma;
        let dv = w * g.r * g.det_j;
        let mut b = SMatrix::<f64, 4, DOFS>::zeros();
        for a in 0..NODES {
            for c in 0..2 {
                let col = b_column(&g, a, c);
                for i in 0..4 {
                    b[(i, 2 * a + c)] = col[i];
                }
            }
        }
        f += b.transpose() * SVector::<f64, 4>::from(sigma) * dv;
        if let Some(k) = k.as_mut() {
            let db = d * b * dv;
            *k += b.transpose() * db;
        }
    }
    Ok(SolidResponse {
        internal_force: f,
        tangent: k,
        stress,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element() -> [[f64; 2]; 8] {
        [
            [10.0, 0.0],
            [12.5, 0.3],
            [12.0, 2.2],
            [9.7, 2.0],
            [11.2, 0.1],
            [12.3, 1.3],
            [10.9, 2.15],
            [9.9, 1.0],
        ]
    }

    #[test]
    fn tangent_matches_central_differences_of_internal_force() {
        let x = element();
        let m = Elastic::new(200e3, 0.3, 1.2e-5);
        let u: [[f64; 2]; 8] =
            std::array::from_fn(|a| [1e-3 * (a as f64).sin(), -2e-3 * (a as f64 * 0.7).cos()]);
        let k = compute_solid(&x, &u, 30.0, &m, true)
            .unwrap()
            .tangent
            .unwrap();
        let h = 1e-6;
        let scale = k.abs().max();
        for j in 0..DOFS {
            let (mut up, mut um) = (u, u);
            up[j / 2][j % 2] += h;
            um[j / 2][j % 2] -= h;
            let fp = compute_solid(&x, &up, 30.0, &m, false)
                .unwrap()
                .internal_force;
            let fm = compute_solid(&x, &um, 30.0, &m, false)
                .unwrap()
                .internal_force;
            let col = (fp - fm) / (2.0 * h);
            let err = (col - k.column(j)).abs().max();
            assert!(
                err <= 1e-6 * scale,
                "column {j}: error {err:e} vs scale {scale:e}"
            );
        }
    }

    #[test]
    fn rigid_axial_translation_gives_no_force_and_tangent_is_symmetric() {
        let x = element();
        let m = Elastic::new(200e3, 0.3, 0.0);
        let u = [[0.0, 0.37]; 8];
        let r = compute_solid(&x, &u, 0.0, &m, true).unwrap();
        assert!(r.internal_force.abs().max() < 1e-9);
        let k = r.tangent.unwrap();
        assert!((k - k.transpose()).abs().max() < 1e-9 * k.abs().max());
    }
}

//! Steady heat conduction in one element (`model::heat`): Fourier's law q = -k grad T over the
//! element's (r, z) section, weighted by the section's measure (r per radian in axisymmetry,
//! the thickness in a plane section), on the same Q8 / T6 geometry and Gauss points as
//! `element::solid`.
//!
//! The weak form of -div(k grad T) = 0 with insulated faces gives the residual
//! f_a = sum_q w_q k grad N_a . grad T_q (the heat leaving through node a) and its exact,
//! constant tangent K_ab = sum_q w_q k grad N_a . grad N_b, symmetric, with K 1 = 0 (a uniform
//! field conducts nothing).

use super::solid::{ElementGeometry, NODES, QUADRATURE_POINTS};

/// An element's conduction matrix over its 8 node slots (a T6's last two are zero rows).
pub type ConductionMatrix = [[f64; NODES]; NODES];

/// The conduction matrix K_ab = sum_q w_q k grad N_a . grad N_b of an element of conductivity
/// `k` (mW/(mm K)); mW/K per radian in axisymmetry.
pub fn conduction_matrix(geo: &ElementGeometry, k: f64) -> ConductionMatrix {
    let (points, weights) = geo.points();
    let mut m = [[0.0; NODES]; NODES];
    for (p, w) in points.iter().zip(weights) {
        for a in 0..NODES {
            for b in 0..NODES {
                m[a][b] += w * k * (p.grad[a][0] * p.grad[b][0] + p.grad[a][1] * p.grad[b][1]);
            }
        }
    }
    m
}

/// The heat leaving the element through each node at nodal temperatures `t`:
/// f_a = sum_q w_q k grad N_a . grad T_q (the residual whose tangent is `conduction_matrix`).
pub fn conduction_residual(geo: &ElementGeometry, k: f64, t: &[f64; NODES]) -> [f64; NODES] {
    let (points, weights) = geo.points();
    let mut f = [0.0; NODES];
    for (p, w) in points.iter().zip(weights) {
        let g = gradient(p, t);
        for a in 0..NODES {
            f[a] += w * k * (p.grad[a][0] * g[0] + p.grad[a][1] * g[1]);
        }
    }
    f
}

/// The heat flux q = -k grad T [q_r, q_z] (mW/mm^2) at each Gauss point.
pub fn heat_flux(geo: &ElementGeometry, k: f64, t: &[f64; NODES]) -> [[f64; 2]; QUADRATURE_POINTS] {
    let (points, _) = geo.points();
    points.map(|p| gradient(&p, t).map(|g| -k * g))
}

fn gradient(p: &crate::fe::axisymmetric::PointGeometry, t: &[f64; NODES]) -> [f64; 2] {
    [0, 1].map(|i| (0..NODES).map(|a| p.grad[a][i] * t[a]).sum())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::quadrature::Integration;
    use crate::fe::section::Section;
    use crate::fe::shape::Shape;

    /// A curved Q8 off the axis and a T6, both distorted, with their nodal coordinates.
    fn elements() -> Vec<(ElementGeometry, [[f64; 2]; NODES])> {
        let q8 = [[2.0, 0.0], [3.1, 0.2], [3.0, 1.3], [2.1, 1.0], [2.55, 0.05], [3.1, 0.7], [2.5, 1.2], [2.0, 0.5]];
        let tri = [[1.0, 0.0], [2.0, 0.3], [1.2, 1.0], [1.5, 0.1], [1.6, 0.7], [1.1, 0.5]];
        let t6: [[f64; 2]; NODES] = Shape::tri6_slots([0, 1, 2, 3, 4, 5]).map(|s| tri[s]);
        [(Shape::Quad8, Section::Axisymmetric, q8), (Shape::Tri6, Section::Axisymmetric, t6), (Shape::Quad8, Section::PlaneStrain { thickness: 3.0 }, q8)]
            .map(|(shape, section, x)| (ElementGeometry::new(shape, Integration::Full, section, &x).unwrap(), x))
            .to_vec()
    }

    #[test]
    fn the_matrix_is_the_residuals_derivative_by_finite_differences() {
        let k = 45.0;
        for (geo, _) in elements() {
            let t: [f64; NODES] = std::array::from_fn(|a| 20.0 + 7.0 * (a as f64).sin() + a as f64);
            let m = conduction_matrix(&geo, k);
            let scale = m.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
            for b in 0..NODES {
                let h = 1e-3;
                let (mut up, mut down) = (t, t);
                up[b] += h;
                down[b] -= h;
                let (fu, fd) = (conduction_residual(&geo, k, &up), conduction_residual(&geo, k, &down));
                for a in 0..NODES {
                    let fd_ab = (fu[a] - fd[a]) / (2.0 * h);
                    assert!((fd_ab - m[a][b]).abs() <= 1e-7 * scale, "K[{a}][{b}] {} against {fd_ab}", m[a][b]);
                    assert!((m[a][b] - m[b][a]).abs() <= 1e-12 * scale, "symmetric");
                }
            }
        }
    }

    #[test]
    fn a_uniform_field_conducts_nothing_and_a_linear_one_carries_its_exact_flux() {
        let k = 50.0;
        for (geo, x) in elements() {
            let m = conduction_matrix(&geo, k);
            for row in &m {
                let size = row.iter().map(|v| v.abs()).sum::<f64>();
                assert!(row.iter().sum::<f64>().abs() <= 1e-12 * size.max(1.0), "K 1 = 0");
            }
            // T = 3 r - 2 z + 5: q = -k (3, -2) at every point of the isoparametric element
            let t = x.map(|p| 3.0 * p[0] - 2.0 * p[1] + 5.0);
            for q in heat_flux(&geo, k, &t) {
                assert!((q[0] + 3.0 * k).abs() < 1e-10 && (q[1] - 2.0 * k).abs() < 1e-10, "{q:?}");
            }
        }
    }
}

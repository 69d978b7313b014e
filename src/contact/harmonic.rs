//! Contact in a harmonic perturbation (`solve::procedures::perturbation`): the stiffness the base state's
//! closed contact nodes give a displacement of one circumferential harmonic n.
//!
//! At each angle theta the perturbation moves the meridional half-plane's nodes by
//! (U_r, U_z) cos n theta and across it by U_t sin n theta. In the half-plane the contact is the
//! axisymmetric kernel's at that angle, so its stiffness for the (U_r, U_z) amplitudes is the
//! base state's axisymmetric contact tangent K times the ring factor (the mean of cos^2 n
//! theta: 1/2 for n >= 1, 1 for n = 0; `element::harmonic::ring_factor`). Across it a
//! frictionless contact carries nothing: the base pressure's work on the normal's tilt out of
//! the half-plane (a term of order p du_r/(r dtheta)) is left out, as Abaqus's perturbation
//! contact does for frictionless pairs.
//!
//! With friction the node sticks (the perturbation is infinitesimal): a tangential penalty
//! eps_T on the slave's motion relative to the master's material point under it, along the
//! master's meridional tangent t and along the hoop direction e_theta,
//!   f_s = eps_T A P (u_s - sum N_k u_k),  P = t t^T + e_theta e_theta^T,
//! and -N_k f_s on the edge's nodes; its harmonic stiffness is this times the ring factor (the
//! mean of cos^2 or sin^2). It replaces the base state's frictional tangent (which may be a
//! slip one) in the meridional direction.
//! DOF order of the stick matrix: [s, e_1, e_2, e_3], (U_r, U_z, U_t) each.

use super::friction::FrictionLaw;
use super::node_to_edge::{contact_point, ContactLaw};
use crate::element::harmonic::ring_factor;
use nalgebra::SMatrix;

pub type StickMatrix = SMatrix<f64, 12, 12>;

/// A sticking slave node: the master edge's shape functions at its contact point, the
/// master's unit meridional tangent there, and eps_T A (N/mm per radian).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sticking {
    pub shape: [f64; 3],
    pub tangent: [f64; 2],
    pub stiffness: f64,
}

impl Sticking {
    /// The slave node at `xs` on the edge `x` at its projection `xi`, with its contact law and
    /// friction law (eps_T at the node's contact pressure).
    pub fn at(xs: [f64; 2], x: &[[f64; 2]; 3], xi: f64, law: &ContactLaw, friction: &FrictionLaw) -> Self {
        let point = contact_point(&xs, x, xi, law);
        Sticking { shape: point.shape, tangent: point.tangent, stiffness: friction.stiffness(point.pressure) * point.area }
    }
}

/// The sticking node's stiffness for mode `mode` over [s, e_1, e_2, e_3] x (U_r, U_z, U_t).
pub fn sticking_stiffness(s: &Sticking, mode: u32) -> StickMatrix {
    let t = s.tangent;
    // P over (r, z, theta): the meridional tangent and the hoop direction
    let p = SMatrix::<f64, 3, 3>::new(t[0] * t[0], t[0] * t[1], 0.0, t[1] * t[0], t[1] * t[1], 0.0, 0.0, 0.0, 1.0);
    let d = [1.0, -s.shape[0], -s.shape[1], -s.shape[2]];
    let c = s.stiffness * ring_factor(mode);
    let mut k = StickMatrix::zeros();
    for a in 0..4 {
        for b in 0..4 {
            k.fixed_view_mut::<3, 3>(3 * a, 3 * b).copy_from(&(p * (c * d[a] * d[b])));
        }
    }
    k
}

/// The harmonic stiffness of mode `mode` of an axisymmetric contact tangent over `m` nodes
/// (row-major, (r, z) per node): ring factor x K on the (U_r, U_z) amplitudes, nothing on U_t;
/// column-major over (U_r, U_z, U_t) per node.
pub fn normal_stiffness(tangent: &[f64], m: usize, mode: u32) -> Vec<f64> {
    let factor = ring_factor(mode);
    let size = 3 * m;
    let mut k = vec![0.0; size * size];
    for i in 0..2 * m {
        for j in 0..2 * m {
            let (row, col) = (3 * (i / 2) + i % 2, 3 * (j / 2) + j % 2);
            k[col * size + row] = factor * tangent[i * 2 * m + j];
        }
    }
    k
}

#[cfg(test)]
mod tests {
    //! Each stiffness against the residual it linearises, evaluated around the ring: at angles
    //! theta_j the 3-D contact force of the harmonic displacement field, projected on the
    //! mode's weights (cos n theta on r and z, sin n theta on theta) and averaged over the ring
    //! (the trapezoidal rule with 4 n + 8 points is exact for these trigonometric products).
    use super::*;
    use crate::contact::node_to_edge::{edge_residual, edge_residual_and_tangent, project_on_edge};
    use std::f64::consts::PI;

    const FREE: [bool; 2] = [true, true];
    // a slave node penetrating a curved master edge, off its middle
    const XS: [f64; 2] = [101.22, 20.64];
    const EDGE: [[f64; 2]; 3] = [[100.0, 20.0], [103.0, 21.2], [101.5, 20.7]];

    fn angles(mode: u32) -> Vec<f64> {
        let count = 4 * mode as usize + 8;
        (0..count).map(|j| 2.0 * PI * j as f64 / count as f64).collect()
    }

    #[test]
    fn normal_stiffness_is_the_ring_mean_of_the_axisymmetric_kernel_at_each_angle() {
        let law = ContactLaw::linear(0.8, 3e3, 0.0, FREE);
        let proj = project_on_edge(XS, &EDGE).unwrap();
        assert!(proj.gap < 0.0, "closed: {proj:?}");
        let (_, k_axi, _) = edge_residual_and_tangent(XS, &EDGE, &proj, &law);
        let tangent: Vec<f64> = k_axi.transpose().as_slice().to_vec(); // row-major
        let amplitudes: Vec<f64> = (0..12).map(|i| 0.3 + 0.17 * i as f64 - 0.02 * (i * i) as f64).collect();
        for mode in [0, 1, 3] {
            let k = normal_stiffness(&tangent, 4, mode);
            // the harmonic residual of amplitudes h * U: the axisymmetric kernel at each angle
            // with the nodes moved by (U_r, U_z) cos n theta, weighed by cos n theta
            let harmonic_residual = |h: f64| -> Vec<f64> {
                let thetas = angles(mode);
                let mut out = vec![0.0; 12];
                for &theta in &thetas {
                    let c = (mode as f64 * theta).cos();
                    let moved = |a: usize, x: [f64; 2]| [x[0] + h * amplitudes[3 * a] * c, x[1] + h * amplitudes[3 * a + 1] * c];
                    let xs = moved(0, XS);
                    let x = [moved(1, EDGE[0]), moved(2, EDGE[1]), moved(3, EDGE[2])];
                    let p = project_on_edge(xs, &x).unwrap();
                    let (f, _) = edge_residual(xs, &x, &p, &law);
                    for a in 0..4 {
                        for comp in 0..2 {
                            out[3 * a + comp] += f[2 * a + comp] * c / thetas.len() as f64;
                        }
                    }
                }
                out
            };
            let h = 1e-6;
            let (plus, minus) = (harmonic_residual(h), harmonic_residual(-h));
            let scale = k.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for i in 0..12 {
                let ku: f64 = (0..12).map(|j| k[j * 12 + i] * amplitudes[j]).sum();
                let fd = (plus[i] - minus[i]) / (2.0 * h);
                assert!((ku - fd).abs() < 1e-6 * scale, "mode {mode}, row {i}: K U {ku:e}, difference {fd:e}");
            }
        }
    }

    #[test]
    fn sticking_stiffness_is_the_ring_mean_of_the_3d_tangential_penalty() {
        let law = ContactLaw::linear(0.8, 3e3, 0.0, FREE);
        let proj = project_on_edge(XS, &EDGE).unwrap();
        for (friction, pressure_dependent) in [
            (FrictionLaw { coefficient: 0.2, penalty: 450.0, elastic_slip: None }, false),
            (FrictionLaw { coefficient: 0.2, penalty: 0.0, elastic_slip: Some(0.004) }, true),
        ] {
            let s = Sticking::at(XS, &EDGE, proj.xi, &law, &friction);
            let pressure: f64 = law.normal.pressure(proj.gap);
            let expected = if pressure_dependent { 0.2 * pressure / 0.004 } else { 450.0 } * law.area;
            assert!((s.stiffness - expected).abs() < 1e-12 * expected, "{} vs {expected}", s.stiffness);
            let u: Vec<f64> = (0..12).map(|i| (1.3 * i as f64).sin() + 0.1).collect();
            for mode in [0, 1, 2] {
                let k = sticking_stiffness(&s, mode);
                // the 3-D force on the four nodes at each angle, in Cartesian components,
                // from the linearised sticking law, then projected on the mode's weights
                let thetas = angles(mode);
                let mut projected = [0.0; 12];
                for &theta in &thetas {
                    // n = 0: u_theta = U_t, the twist
                    let (c, sn) = ((mode as f64 * theta).cos(), if mode == 0 { 1.0 } else { (mode as f64 * theta).sin() });
                    let (er, et) = ([theta.cos(), theta.sin(), 0.0], [-theta.sin(), theta.cos(), 0.0]);
                    let ez = [0.0, 0.0, 1.0];
                    let displacement =
                        |a: usize| -> [f64; 3] { std::array::from_fn(|i| u[3 * a] * c * er[i] + u[3 * a + 1] * c * ez[i] + u[3 * a + 2] * sn * et[i]) };
                    let relative: [f64; 3] = std::array::from_fn(|i| displacement(0)[i] - (1..4).map(|a| s.shape[a - 1] * displacement(a)[i]).sum::<f64>());
                    let t3: [f64; 3] = std::array::from_fn(|i| s.tangent[0] * er[i] + s.tangent[1] * ez[i]);
                    let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
                    let force: [f64; 3] = std::array::from_fn(|i| s.stiffness * (dot(&t3, &relative) * t3[i] + dot(&et, &relative) * et[i]));
                    for a in 0..4 {
                        let weight = if a == 0 { 1.0 } else { -s.shape[a - 1] };
                        projected[3 * a] += weight * dot(&force, &er) * c / thetas.len() as f64;
                        projected[3 * a + 1] += weight * dot(&force, &ez) * c / thetas.len() as f64;
                        projected[3 * a + 2] += weight * dot(&force, &et) * sn / thetas.len() as f64;
                    }
                }
                let scale = k.abs().max();
                for i in 0..12 {
                    let ku: f64 = (0..12).map(|j| k[(i, j)] * u[j]).sum();
                    assert!((ku - projected[i]).abs() < 1e-12 * scale, "mode {mode}, row {i}: {ku:e} vs {:e}", projected[i]);
                }
                // a rigid motion of slave and master together carries nothing
                let rigid: Vec<f64> = (0..12).map(|i| [0.7, -0.4, 1.1][i % 3]).collect();
                let kr = k * nalgebra::SVector::<f64, 12>::from_column_slice(&rigid);
                assert!(kr.abs().max() < 1e-12 * scale, "mode {mode}: {kr:?}");
            }
        }
    }
}

//! The load stiffness of a follower pressure for a harmonic perturbation (`element::harmonic`)
//! of an axisymmetric state: how the pressure's force on a 3-node edge, turned about the axis,
//! changes when the surface moves by u = U_r cos e_r + U_z cos e_z + U_t sin e_theta (mode n).
//!
//! On the surface x(xi, theta) the force is -p (x_,theta x x_,xi) dxi dtheta (outward normal
//! area, `element::pressure`'s convention: positive pressure pushes into the body). Its change
//! is -p (du_,theta x x_,xi + x_,theta x du_,xi), with x_,xi = t_r e_r + t_z e_z and x_,theta =
//! r e_theta of the base state, and du_,theta carrying the turning of e_r and e_theta:
//!
//!   du_,theta = -(n U_r + U_t) sin e_r - n U_z sin e_z + (U_r + n U_t) cos e_theta
//!
//! so that the change of the area vector is
//!
//!   r:     cos ((U_r + n U_t) t_z + r U_z,xi)
//!   theta: sin ((n U_r + U_t) t_z - n U_z t_r)
//!   z:    -cos ((U_r + n U_t) t_r + r U_r,xi)
//!
//! Weighed by the harmonic test functions (cos, cos, sin), each term carries the ring factor.
//! For n = 0 and U_t = 0 it is `element::pressure`'s load stiffness.

use super::harmonic::ring_factor;
use crate::fe::quadrature::GAUSS3;
use crate::fe::shape::line3;

/// d f_ext / d U per radian of pressure `p` on the edge with base-state nodes `x` (start, end,
/// middle, the owning element's counter-clockwise order), mode `mode`: entry [3a + i][3b + j].
/// Not symmetric; the residual f_int - f_ext takes it with a minus sign.
pub fn harmonic_pressure_stiffness(x: &[[f64; 2]; 3], p: f64, mode: u32) -> [[f64; 9]; 9] {
    let n = f64::from(mode);
    let factor = ring_factor(mode);
    let mut k = [[0.0; 9]; 9];
    for &(s, w) in &GAUSS3 {
        let (shape, dshape) = line3(s);
        let r: f64 = (0..3).map(|a| shape[a] * x[a][0]).sum();
        let t = [0, 1].map(|i| (0..3).map(|a| dshape[a] * x[a][i]).sum::<f64>());
        for a in 0..3 {
            let c = -p * w * factor * shape[a];
            for b in 0..3 {
                let (nb, db) = (shape[b], dshape[b]);
                // rows: the test function's r, z, theta amplitude; columns: U_r, U_z, U_t of b
                let row_r = [nb * t[1], r * db, n * nb * t[1]];
                let row_z = [-(nb * t[0] + r * db), 0.0, -n * nb * t[0]];
                let row_t = [n * nb * t[1], -n * nb * t[0], nb * t[1]];
                for j in 0..3 {
                    k[3 * a][3 * b + j] += c * row_r[j];
                    k[3 * a + 1][3 * b + j] += c * row_z[j];
                    k[3 * a + 2][3 * b + j] += c * row_t[j];
                }
            }
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::pressure::pressure_load_stiffness;
    use nalgebra::Vector3;
    use std::f64::consts::PI;

    const EDGE: [[f64; 2]; 3] = [[40.0, 3.0], [46.0, 9.0], [42.5, 6.8]];

    /// n = 0 without U_t: the axisymmetric load stiffness (which has its own difference test).
    #[test]
    fn mode_zero_is_the_axisymmetric_load_stiffness() {
        let (h, axi) = (harmonic_pressure_stiffness(&EDGE, 7.0, 0), pressure_load_stiffness(crate::fe::section::Section::Axisymmetric, &EDGE, 7.0));
        for a in 0..3 {
            for b in 0..3 {
                for (i, j) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    assert!((h[3 * a + i][3 * b + j] - axi[2 * a + i][2 * b + j]).abs() < 1e-12, "{a} {i} {b} {j}");
                }
            }
        }
    }

    /// Against the pressure's force on the 3-D surface around the ring: x = X + u at 24 angles
    /// in Cartesian components, x_,theta by central differences (step 1e-4), the force -p x_,theta x x_,xi
    /// weighed by each harmonic test function and averaged over the angles (per radian); its
    /// derivative in each amplitude by central differences. To 1e-6 of the largest entry for
    /// n = 0, 1, 2.
    #[test]
    fn load_stiffness_is_the_derivative_of_the_3d_pressure_force() {
        let p = 7.0;
        for mode in [0u32, 1, 2] {
            let n = f64::from(mode);
            let trig = |t: f64| if mode == 0 { (1.0, 1.0) } else { ((n * t).cos(), (n * t).sin()) };
            // the harmonic field of amplitudes u (9: three nodes x [U_r, U_z, U_t]) at (xi, theta)
            let field = |u: &[f64; 9], shape: &[f64; 3], t: f64| -> Vector3<f64> {
                let amp = |k: usize| (0..3).map(|a| shape[a] * u[3 * a + k]).sum::<f64>();
                let (c, s) = trig(t);
                let (er, et) = (Vector3::new(t.cos(), t.sin(), 0.0), Vector3::new(-t.sin(), t.cos(), 0.0));
                er * (amp(0) * c) + Vector3::z() * (amp(1) * c) + et * (amp(2) * s)
            };
            let position = |u: &[f64; 9], shape: &[f64; 3], t: f64| -> Vector3<f64> {
                let (r, z) = ((0..3).map(|a| shape[a] * EDGE[a][0]).sum::<f64>(), (0..3).map(|a| shape[a] * EDGE[a][1]).sum::<f64>());
                Vector3::new(r * t.cos(), r * t.sin(), z) + field(u, shape, t)
            };
            let force = |u: &[f64; 9]| -> [f64; 9] {
                let mut f = [0.0; 9];
                let angles = 24;
                for j in 0..angles {
                    let t = 2.0 * PI * (j as f64 + 0.3) / angles as f64;
                    for &(s, w) in &GAUSS3 {
                        // x_,xi from the shape functions' derivatives (the position is linear
                        // in them); x_,theta by central differences
                        let (shape, dshape) = line3(s);
                        let h = 1e-4;
                        let x_xi = position(u, &dshape, t);
                        let x_t = (position(u, &shape, t + h) - position(u, &shape, t - h)) / (2.0 * h);
                        let traction = -p * x_t.cross(&x_xi);
                        for dof in 0..9 {
                            let mut unit = [0.0; 9];
                            unit[dof] = 1.0;
                            f[dof] += w * traction.dot(&field(&unit, &shape, t)) / angles as f64;
                        }
                    }
                }
                f
            };
            let k = harmonic_pressure_stiffness(&EDGE, p, mode);
            let scale = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            let base = [0.0; 9];
            for j in 0..9 {
                let (mut up, mut um) = (base, base);
                // the force is quadratic in the amplitudes: central differences are exact
                let h = 1.0;
                up[j] += h;
                um[j] -= h;
                let (fp, fm) = (force(&up), force(&um));
                for i in 0..9 {
                    let fd = (fp[i] - fm[i]) / (2.0 * h);
                    assert!((fd - k[i][j]).abs() <= 1e-6 * scale, "mode {mode}: K[{i}][{j}] = {} against {fd}", k[i][j]);
                }
            }
        }
    }
}

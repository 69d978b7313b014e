//! Body loads on the axisymmetric solid, as consistent nodal forces per radian (CalculiX's and
//! Abaqus's *DLOAD GRAV and CENTRIF about the axis):
//! - gravity along the axis, f_(a,z) = rho g integral N_a dV0: a dead load, the mass being
//!   the reference configuration's;
//! - spin about the axis at omega, f_(a,r) = rho omega^2 integral N_a x_r dV0, x_r = R + u_r the
//!   current radius (finite strain; R at small strain): the centrifugal force of the material
//!   where it now is. Its load stiffness d f / d u_r is rho omega^2 integral N_a N_b dV0 (the
//!   spin softening), which the residual takes with a minus sign.
//!
//! dV0 = R dR dZ per radian: the element geometry's Gauss weights.

use super::solid::{ElementGeometry, NODES, QUADRATURE_POINTS};
use crate::material::Kinematics;

/// One body force, per unit mass.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum BodyForce {
    /// Acceleration of gravity along +z, mm/s^2 (downward along the axis: negative).
    Gravity(f64),
    /// The square of the angular velocity about the axis, omega^2 (rad^2/s^2).
    Spin(f64),
}

impl BodyForce {
    /// The same force scaled by `s` (a load factor).
    pub fn scaled(self, s: f64) -> Self {
        match self {
            BodyForce::Gravity(g) => BodyForce::Gravity(s * g),
            BodyForce::Spin(w2) => BodyForce::Spin(s * w2),
        }
    }

    /// Its magnitude: g, or omega^2.
    pub fn value(self) -> f64 {
        match self {
            BodyForce::Gravity(v) | BodyForce::Spin(v) => v,
        }
    }
}

/// Nodal forces [f_r, f_z] per radian of `force` on an element of density `rho` with
/// reference geometry `geo`, coordinates `x0` and displacements `u`.
pub fn body_load(
    geo: &ElementGeometry,
    x0: &[[f64; 2]; NODES],
    u: &[[f64; 2]; NODES],
    rho: f64,
    force: BodyForce,
    kinematics: Kinematics,
) -> [[f64; 2]; NODES] {
    let (points, weights) = geo.points();
    let mut f = [[0.0; 2]; NODES];
    for q in 0..QUADRATURE_POINTS {
        let n = &points[q].n;
        let (component, per_volume) = match force {
            BodyForce::Gravity(g) => (1, rho * g),
            BodyForce::Spin(w2) => {
                let moved = if kinematics == Kinematics::Finite { 1.0 } else { 0.0 };
                let radius: f64 = (0..NODES).map(|b| n[b] * (x0[b][0] + moved * u[b][0])).sum();
                (0, rho * w2 * radius)
            }
        };
        for a in 0..NODES {
            f[a][component] += weights[q] * n[a] * per_volume;
        }
    }
    f
}

/// d f / d u of [`body_load`] (row 2a + i, column 2b + j): the spin's rho omega^2 integral N_a
/// N_b dV0 on the radial components at finite strain, zero otherwise.
pub fn body_load_stiffness(geo: &ElementGeometry, rho: f64, force: BodyForce, kinematics: Kinematics) -> [[f64; 2 * NODES]; 2 * NODES] {
    let mut k = [[0.0; 2 * NODES]; 2 * NODES];
    let BodyForce::Spin(w2) = force else { return k };
    if kinematics != Kinematics::Finite {
        return k;
    }
    let (points, weights) = geo.points();
    for q in 0..QUADRATURE_POINTS {
        let n = &points[q].n;
        for a in 0..NODES {
            for b in 0..NODES {
                k[2 * a][2 * b] += rho * w2 * weights[q] * n[a] * n[b];
            }
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::quadrature::Integration;
    use crate::fe::shape::Shape;

    /// A curved, distorted Q8 between r = 20 and 31.
    fn element() -> [[f64; 2]; NODES] {
        [[20.0, 0.0], [30.0, 1.0], [31.0, 12.0], [21.0, 10.0], [25.0, 0.2], [30.7, 6.0], [26.0, 11.5], [20.4, 5.0]]
    }

    /// The spin's load stiffness is the derivative of its load (central differences, 1e-7).
    #[test]
    fn the_spin_stiffness_is_the_derivative_of_the_centrifugal_load() {
        let x0 = element();
        let geo = ElementGeometry::new(Shape::Quad8, Integration::Full, crate::fe::section::Section::Axisymmetric, &x0).unwrap();
        let (rho, force) = (7.85e-9, BodyForce::Spin(1.0e6));
        let mut u = [[0.0; 2]; NODES];
        for (a, v) in u.iter_mut().enumerate() {
            *v = [0.01 * a as f64, -0.02 * (a as f64).sin()];
        }
        let k = body_load_stiffness(&geo, rho, force, Kinematics::Finite);
        let h = 1e-4;
        for j in 0..2 * NODES {
            let (mut up, mut down) = (u, u);
            up[j / 2][j % 2] += h;
            down[j / 2][j % 2] -= h;
            let (fp, fm) = (body_load(&geo, &x0, &up, rho, force, Kinematics::Finite), body_load(&geo, &x0, &down, rho, force, Kinematics::Finite));
            for i in 0..2 * NODES {
                let fd = (fp[i / 2][i % 2] - fm[i / 2][i % 2]) / (2.0 * h);
                assert!((fd - k[i][j]).abs() <= 1e-7 * k[i][i].abs().max(1e-30), "({i}, {j}): {fd} against {}", k[i][j]);
            }
        }
        // at small strain the load is fixed
        assert!(body_load_stiffness(&geo, rho, force, Kinematics::Small).iter().flatten().all(|&v| v == 0.0));
        assert_eq!(body_load(&geo, &x0, &u, rho, force, Kinematics::Small), body_load(&geo, &x0, &[[0.0; 2]; NODES], rho, force, Kinematics::Small));
    }

    /// The loads add up to their resultants (Pappus): gravity's to rho g V, the spin's to rho
    /// omega^2 integral R dV = rho omega^2 V R_c, over the exact volume and centroid of a
    /// straight-sided ring of rectangular section r 20..30, z 0..10 (per radian: V = integral R
    /// dR dZ = 2500).
    #[test]
    fn the_loads_add_up_to_the_weight_and_the_centrifugal_force() {
        let x0 = [[20.0, 0.0], [30.0, 0.0], [30.0, 10.0], [20.0, 10.0], [25.0, 0.0], [30.0, 5.0], [25.0, 10.0], [20.0, 5.0]];
        let geo = ElementGeometry::new(Shape::Quad8, Integration::Full, crate::fe::section::Section::Axisymmetric, &x0).unwrap();
        let u = [[0.0; 2]; NODES];
        let (rho, g, w2) = (7.85e-9, -9810.0, 1.0e6);
        let volume = 10.0 * (30.0f64.powi(2) - 20.0f64.powi(2)) / 2.0;
        let weight: f64 = body_load(&geo, &x0, &u, rho, BodyForce::Gravity(g), Kinematics::Finite).iter().map(|f| f[1]).sum();
        assert!((weight - rho * g * volume).abs() < 1e-12 * weight.abs(), "{weight}");
        let spin: f64 = body_load(&geo, &x0, &u, rho, BodyForce::Spin(w2), Kinematics::Finite).iter().map(|f| f[0]).sum();
        // integral R^2 dR dZ = 10 (30^3 - 20^3) / 3
        let expected = rho * w2 * 10.0 * (30.0f64.powi(3) - 20.0f64.powi(3)) / 3.0;
        assert!((spin - expected).abs() < 1e-12 * expected, "{spin} against {expected}");
    }
}

//! Axisymmetric kinematics in (r, z).
//!
//! Conventions, stated once for the whole code: strains and stresses in Voigt order
//! `[rr, zz, tt, rz]` (tt the hoop direction theta), with engineering shear
//! `gamma_rz = du_r/dz + du_z/dr` in strain and `sigma_rz` in stress. Element DOFs are ordered
//! node by node, `[u_r0, u_z0, u_r1, u_z1, ...]`. Integrals are per radian: `dV = r dr dz`;
//! multiply by 2*pi for the full ring.

use super::shape::Shape;

/// Shape functions and physical gradients at one point of an element (8 slots; see `fe::shape`).
#[derive(Clone, Copy, Debug)]
pub struct PointGeometry {
    pub n: [f64; 8],
    /// dN_a/dr, dN_a/dz.
    pub grad: [[f64; 2]; 8],
    /// Radius of the point.
    pub r: f64,
    /// det(d(r,z)/d(xi,eta)).
    pub det_j: f64,
}

/// Maps reference point `p` of the element of shape `shape` with nodal coordinates `x` (r, z).
/// Fails with a message when the Jacobian is not positive (inverted or degenerate element);
/// the radius `r` may be anything (an axisymmetric element checks it is positive).
pub fn map_point(shape: Shape, x: &[[f64; 2]; 8], p: [f64; 2]) -> Result<PointGeometry, String> {
    let (n, d) = shape.functions(p);
    let (j, det_j) = jacobian(x, &d, p)?;
    let r: f64 = (0..8).map(|a| n[a] * x[a][0]).sum();
    // inverse Jacobian: d xi_k / d x_i
    let inv = [[j[1][1] / det_j, -j[0][1] / det_j], [-j[1][0] / det_j, j[0][0] / det_j]];
    let mut grad = [[0.0; 2]; 8];
    for a in 0..8 {
        for i in 0..2 {
            grad[a][i] = d[a][0] * inv[0][i] + d[a][1] * inv[1][i];
        }
    }
    Ok(PointGeometry { n, grad, r, det_j })
}

/// J = d(r,z)/d(xi,eta) (`j[i][k] = d x_i / d xi_k`) and its determinant at `p`, given the
/// shape-function derivatives `d` there; fails when det J is not clearly positive.
pub fn jacobian(x: &[[f64; 2]; 8], d: &[[f64; 2]; 8], p: [f64; 2]) -> Result<([[f64; 2]; 2], f64), String> {
    let mut j = [[0.0; 2]; 2];
    for a in 0..8 {
        for i in 0..2 {
            for k in 0..2 {
                j[i][k] += x[a][i] * d[a][k];
            }
        }
    }
    let det_j = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let scale = (j[0][0].abs() + j[0][1].abs()) * (j[1][0].abs() + j[1][1].abs());
    if !det_j.is_finite() || det_j <= 1e-12 * scale {
        return Err(format!(
            "non-positive Jacobian determinant {det_j:.3e} at (xi, eta) = ({:.3}, {:.3}): element inverted, degenerate or nodes not counter-clockwise",
            p[0], p[1]
        ));
    }
    Ok((j, det_j))
}

/// Small strain `[e_rr, e_zz, e_tt, gamma_rz]` at a point from nodal displacements `u`.
pub fn small_strain(g: &PointGeometry, u: &[[f64; 2]; 8]) -> [f64; 4] {
    let mut e = [0.0; 4];
    for a in 0..8 {
        let [dr, dz] = g.grad[a];
        e[0] += dr * u[a][0];
        e[1] += dz * u[a][1];
        e[2] += g.n[a] * u[a][0] / g.r;
        e[3] += dz * u[a][0] + dr * u[a][1];
    }
    e
}

/// Von Mises equivalent stress of `[s_rr, s_zz, s_tt, s_rz]`.
pub fn von_mises(s: &[f64; 4]) -> f64 {
    let [a, b, c, t] = *s;
    (0.5 * ((a - b).powi(2) + (b - c).powi(2) + (c - a).powi(2)) + 3.0 * t * t).sqrt()
}

/// Principal stresses of `[s_rr, s_zz, s_tt, s_rz]`, largest first: the two of the (r, z)
/// plane and the hoop stress, which is principal by symmetry.
pub fn principal_stresses(s: &[f64; 4]) -> [f64; 3] {
    let [a, b, c, t] = *s;
    let (mean, radius) = (0.5 * (a + b), (0.5 * (a - b)).hypot(t));
    let mut p = [mean + radius, mean - radius, c];
    p.sort_by(|x, y| y.total_cmp(x));
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn principal_stresses_of_a_rotated_tensor() {
        // diag(200, -50) rotated by 30 degrees in (r, z), hoop 75
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let (p1, p2) = (200.0, -50.0);
        let t = [p1 * c * c + p2 * s * s, p1 * s * s + p2 * c * c, 75.0, (p1 - p2) * s * c];
        let p = principal_stresses(&t);
        assert!((p[0] - 200.0).abs() < 1e-12 && (p[1] - 75.0).abs() < 1e-12 && (p[2] + 50.0).abs() < 1e-12, "{p:?}");
    }

    fn ring_element() -> [[f64; 2]; 8] {
        // a distorted quadrilateral away from the axis with straight edges
        let c = [[10.0, 0.0], [14.0, 0.5], [13.0, 4.0], [9.5, 3.0]];
        let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        [c[0], c[1], c[2], c[3], mid(c[0], c[1]), mid(c[1], c[2]), mid(c[2], c[3]), mid(c[3], c[0])]
    }

    #[test]
    fn linear_field_gives_exact_strain() {
        let x = ring_element();
        let (a, b, c, d) = (1e-3, -2e-3, 5e-4, 0.1);
        let u: [[f64; 2]; 8] = std::array::from_fn(|k| [a * x[k][0] + c * x[k][1], b * x[k][1] + d]);
        let g = map_point(Shape::Quad8, &x, [0.2, -0.4]).unwrap();
        let e = small_strain(&g, &u);
        let zr = g.n.iter().zip(&x).map(|(n, p)| n * p[1]).sum::<f64>() / g.r;
        let exact = [a, b, a + c * zr, c];
        for k in 0..4 {
            assert!((e[k] - exact[k]).abs() < 1e-14, "component {k}: {} vs {}", e[k], exact[k]);
        }
    }

    #[test]
    fn clockwise_element_is_rejected() {
        let mut x = ring_element();
        x.swap(1, 3);
        x.swap(4, 7);
        x.swap(5, 6);
        assert!(map_point(Shape::Quad8, &x, [0.0, 0.0]).unwrap_err().contains("non-positive Jacobian"));
    }

    #[test]
    fn von_mises_of_uniaxial_and_shear() {
        assert!((von_mises(&[100.0, 0.0, 0.0, 0.0]) - 100.0).abs() < 1e-12);
        assert!((von_mises(&[0.0, 0.0, 0.0, 10.0]) - 10.0 * 3f64.sqrt()).abs() < 1e-12);
    }
}

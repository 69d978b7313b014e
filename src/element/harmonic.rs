//! The harmonic element: the Q8 of `element::solid` carrying displacement fields of one
//! circumferential harmonic n, for linear perturbations of an axisymmetric state by
//! non-axisymmetric loads (a lateral offset, a rotation about a diameter, a harmonic pressure):
//!
//!   u_r = U_r(r, z) cos n theta,   u_z = U_z(r, z) cos n theta,   u_theta = U_t(r, z) sin n theta
//!
//! (n = 0: u_theta = U_t(r, z), the torsion family; it decouples from U_r, U_z). Three unknowns
//! per node, ordered node by node [U_r, U_z, U_t]. The small strains of the 3-D solid in
//! cylindrical coordinates, Voigt order [rr, zz, tt, rz, rt, zt] with engineering shears:
//!
//!   e_rr = U_r,r   e_zz = U_z,z   e_tt = (U_r + n U_t) / r   g_rz = U_r,z + U_z,r      (x cos)
//!   g_rt = U_t,r - (U_t + n U_r) / r                          g_zt = U_t,z - n U_z / r  (x sin)
//!
//! (x 1 for n = 0). Integrated analytically around the ring, every term of the stiffness carries
//! the mean of cos^2 or sin^2 over theta: 1/2 for n >= 1, 1 for n = 0 (cross terms cos sin vanish
//! for a base state that is axisymmetric, whose tangent couples no normal strain to a theta
//! shear). So the stiffness here is, as everywhere in slideline, per radian: the full ring's is
//! 2 pi times it; for n = 0 with U_t = 0 it is the axisymmetric element's. The nodal forces are
//! per radian too: a set's lateral force (n = 1, full ring) is 2 pi sum (f_r - f_t).
//!
//! The dilatation is projected as in `element::solid` (its F-bar at small strain is this B-bar):
//! e_ii + (Pi tr e - tr e) / 3 on each normal strain, Pi the element's L2 projection onto
//! {1, R - Rc, Z - Zc}, which the harmonic's cos n theta factor passes through unchanged.

use super::solid::{ElementGeometry, NODES, QUADRATURE_POINTS};
use nalgebra::{SMatrix, SVector};

pub const DOFS: usize = 3 * NODES;

pub type HarmonicVector = SVector<f64, DOFS>;
pub type HarmonicMatrix = SMatrix<f64, DOFS, DOFS>;
/// A material tangent over [rr, zz, tt, rz, rt, zt] (engineering shears).
pub type Tangent6 = SMatrix<f64, 6, 6>;
/// The strain-displacement matrix of one point.
type StrainMap = SMatrix<f64, 6, DOFS>;

/// The mean over theta of cos^2 n theta (and of sin^2 for n >= 1): the ring's factor of a
/// per-radian harmonic integral.
pub fn ring_factor(mode: u32) -> f64 {
    if mode == 0 {
        1.0
    } else {
        0.5
    }
}

/// The isotropic elastic tangent over [rr, zz, tt, rz, rt, zt].
pub fn isotropic(youngs_modulus: f64, poissons_ratio: f64) -> Tangent6 {
    let (e, nu) = (youngs_modulus, poissons_ratio);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let mut d = Tangent6::zeros();
    for i in 0..3 {
        for j in 0..3 {
            d[(i, j)] = lambda + if i == j { 2.0 * mu } else { 0.0 };
        }
        d[(i + 3, i + 3)] = mu;
    }
    d
}

/// The strain-displacement matrices of mode `mode` at the element's Gauss points, the
/// dilatation projected.
fn strain_maps(geo: &ElementGeometry, mode: u32) -> [StrainMap; QUADRATURE_POINTS] {
    let (points, _) = geo.points();
    let n = f64::from(mode);
    let mut b: [StrainMap; QUADRATURE_POINTS] = [StrainMap::zeros(); QUADRATURE_POINTS];
    for (q, g) in points.iter().enumerate() {
        for a in 0..NODES {
            let ([dr, dz], h, c) = (g.grad[a], g.n[a] / g.r, 3 * a);
            // U_r
            b[q][(0, c)] = dr;
            b[q][(2, c)] = h;
            b[q][(3, c)] = dz;
            b[q][(4, c)] = -n * h;
            // U_z
            b[q][(1, c + 1)] = dz;
            b[q][(3, c + 1)] = dr;
            b[q][(5, c + 1)] = -n * h;
            // U_t
            b[q][(2, c + 2)] = n * h;
            b[q][(4, c + 2)] = dr - h;
            b[q][(5, c + 2)] = dz;
        }
    }
    // B-bar: each DOF's dilatation at the points, projected, replaces its own
    for k in 0..DOFS {
        let trace: [f64; QUADRATURE_POINTS] = std::array::from_fn(|q| b[q][(0, k)] + b[q][(1, k)] + b[q][(2, k)]);
        let projected = geo.project(&trace);
        for q in 0..QUADRATURE_POINTS {
            let shift = (projected[q] - trace[q]) / 3.0;
            for i in 0..3 {
                b[q][(i, k)] += shift;
            }
        }
    }
    b
}

/// The strain amplitudes [rr, zz, tt, rz, rt, zt] of mode `mode` at each Gauss point, for
/// nodal amplitudes `u` ([U_r, U_z, U_t] per node).
pub fn harmonic_strain(geo: &ElementGeometry, mode: u32, u: &[[f64; 3]; NODES]) -> [[f64; 6]; QUADRATURE_POINTS] {
    let v = HarmonicVector::from_iterator(u.iter().flatten().copied());
    strain_maps(geo, mode).map(|b| (b * v).into())
}

/// The material stiffness of mode `mode` per radian: the ring factor times the integral of
/// B^T D B over the meridian section (r dr dz), with the tangent `d` at each Gauss point.
pub fn material_stiffness(geo: &ElementGeometry, mode: u32, d: &[Tangent6; QUADRATURE_POINTS]) -> HarmonicMatrix {
    let (_, weights) = geo.points();
    let factor = ring_factor(mode);
    let mut k = HarmonicMatrix::zeros();
    for (q, b) in strain_maps(geo, mode).iter().enumerate() {
        k += b.transpose() * (d[q] * (weights[q] * factor)) * b;
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::solid::{compute_solid, solid_tangent, MaterialTangents, SolidInput};
    use crate::material::{Kinematics, PointState, SurfaceBranch, J2};

    fn ring_element() -> [[f64; 2]; 8] {
        // a distorted quadrilateral with one curved side, away from the axis
        let c = [[10.0, 0.0], [14.0, 0.5], [13.0, 4.0], [9.5, 3.0]];
        let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let mut x = [c[0], c[1], c[2], c[3], mid(c[0], c[1]), mid(c[1], c[2]), mid(c[2], c[3]), mid(c[3], c[0])];
        x[5][0] += 0.3;
        x
    }

    const E: f64 = 200_000.0;
    const NU: f64 = 0.3;

    /// n = 0 with U_t = 0 is the axisymmetric element: the solid's small-strain elastic tangent
    /// (its F-bar, at u = 0) to 1e-12, and U_t couples to nothing else.
    #[test]
    fn mode_zero_is_the_axisymmetric_element() {
        let geo = ElementGeometry::new(&ring_element()).unwrap();
        let k = material_stiffness(&geo, 0, &[isotropic(E, NU); QUADRATURE_POINTS]);
        let material = J2::elastic(E, NU, 0.0);
        let committed = [PointState::initial(Kinematics::Small); QUADRATURE_POINTS];
        let input = SolidInput {
            geometry: &geo,
            material: &material,
            kinematics: Kinematics::Small,
            temperature_change: 0.0,
            committed: &committed,
            surface: SurfaceBranch::Elastic,
        };
        let mut tangents: MaterialTangents = Default::default();
        compute_solid(&input, &[[0.0; 2]; NODES], Some(&mut tangents)).unwrap();
        let axi = solid_tangent(&geo, &tangents);
        let scale = axi.abs().max();
        for a in 0..NODES {
            for b in 0..NODES {
                for (i, j) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    let (h, s) = (k[(3 * a + i, 3 * b + j)], axi[(2 * a + i, 2 * b + j)]);
                    assert!((h - s).abs() <= 1e-12 * scale, "node {a} {i} / node {b} {j}: {h} against {s}");
                }
                for i in 0..2 {
                    assert_eq!(k[(3 * a + i, 3 * b + 2)], 0.0);
                }
            }
        }
    }

    /// The rigid motions of n = 1 strain nothing: a translation across the axis (U_r = c,
    /// U_t = -c, U_z = 0) and a rotation psi about a diameter (U_r = psi z, U_t = -psi z,
    /// U_z = -psi r), to 1e-10 of a unit deformation's force.
    #[test]
    fn rigid_motions_of_mode_one_strain_nothing() {
        let x = ring_element();
        let geo = ElementGeometry::new(&x).unwrap();
        let k = material_stiffness(&geo, 1, &[isotropic(E, NU); QUADRATURE_POINTS]);
        let unit = HarmonicVector::from_fn(|i, _| if i % 3 == 0 { 1.0 } else { 0.0 });
        let reference = (k * unit).norm();
        let psi = 1e-3;
        for (name, u) in [
            ("translation", HarmonicVector::from_fn(|i, _| [1.0, 0.0, -1.0][i % 3])),
            (
                "rotation",
                HarmonicVector::from_fn(|i, _| {
                    let p = x[i / 3];
                    [psi * p[1], -psi * p[0], -psi * p[1]][i % 3]
                }),
            ),
        ] {
            let f = k * u;
            assert!(f.norm() <= 1e-10 * reference * u.amax(), "{name}: {} against {reference}", f.norm());
            let u3: [[f64; 3]; NODES] = std::array::from_fn(|a| [u[3 * a], u[3 * a + 1], u[3 * a + 2]]);
            let strain = harmonic_strain(&geo, 1, &u3);
            assert!(strain.iter().flatten().all(|e| e.abs() < 1e-12), "{name}: {strain:?}");
        }
    }

    /// The stiffness is symmetric, and its null space on an unsupported element is the rigid
    /// motions of its mode and nothing more (no spurious mechanism): n = 0 the axial translation
    /// and the twist about the axis (U_t = c r); n = 1 the two above; n = 2 none.
    #[test]
    fn null_spaces_by_mode() {
        let geo = ElementGeometry::new(&ring_element()).unwrap();
        for (mode, zeros) in [(0, 2), (1, 2), (2, 0)] {
            let k = material_stiffness(&geo, mode, &[isotropic(E, NU); QUADRATURE_POINTS]);
            assert!((k - k.transpose()).amax() <= 1e-12 * k.amax());
            let mut eig: Vec<f64> = k.symmetric_eigenvalues().iter().copied().collect();
            eig.sort_by(f64::total_cmp);
            let top = eig[DOFS - 1];
            let count = eig.iter().filter(|&&l| l.abs() < 1e-9 * top).count();
            assert_eq!(count, zeros, "mode {mode}: {eig:?}");
        }
    }
}

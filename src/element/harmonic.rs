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

/// The continuum elastic-plastic tangent of J2 flow with isotropic hardening slope `hardening`
/// (MPa) at a point on the yield surface with Cauchy stress `stress` [rr, zz, tt, rz], over
/// [rr, zz, tt, rz, rt, zt]: D - a a^T / (3 mu + H), a = 2 mu N, N = (3/2) s / sigma_eq the
/// flow direction (Simo & Hughes, Computational Inelasticity, 2.3.2, at a vanishing increment,
/// where the radial return's consistent tangent becomes it). The axisymmetric stress has no
/// theta shear, so those two moduli stay mu.
pub fn elastoplastic(youngs_modulus: f64, poissons_ratio: f64, hardening: f64, stress: &[f64; 4]) -> Tangent6 {
    let d = isotropic(youngs_modulus, poissons_ratio);
    let mu = youngs_modulus / (2.0 * (1.0 + poissons_ratio));
    let [rr, zz, tt, rz] = *stress;
    let mean = (rr + zz + tt) / 3.0;
    let s = [rr - mean, zz - mean, tt - mean, rz];
    let q = crate::fe::axisymmetric::von_mises(stress);
    if q <= 0.0 {
        return d;
    }
    let a = SVector::<f64, 6>::from_column_slice(&[s[0], s[1], s[2], s[3], 0.0, 0.0]) * (2.0 * mu * 1.5 / q);
    d - a * a.transpose() / (3.0 * mu + hardening)
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

/// The displacement-gradient amplitudes of mode `mode` at one point: row 3 k + i is
/// H_ki = d u_k / d x_i (physical components, k and i over r, z, theta), without its cos or sin
/// factor:
///
///   H_rr = U_r,r  H_rz = U_r,z  H_rt = -(n U_r + U_t) / r      (x cos, cos, sin)
///   H_zr = U_z,r  H_zz = U_z,z  H_zt = -n U_z / r              (x cos, cos, sin)
///   H_tr = U_t,r  H_tz = U_t,z  H_tt = (U_r + n U_t) / r       (x sin, sin, cos)
///
/// For each component k the products H_ki H_kj the initial stress weighs pair like factors, so
/// the ring factor applies to them as to the strains.
fn gradient_map(g: &crate::fe::axisymmetric::PointGeometry, mode: u32) -> SMatrix<f64, 9, DOFS> {
    let n = f64::from(mode);
    let mut m = SMatrix::<f64, 9, DOFS>::zeros();
    for a in 0..NODES {
        let ([dr, dz], h, c) = (g.grad[a], g.n[a] / g.r, 3 * a);
        m[(0, c)] = dr;
        m[(1, c)] = dz;
        m[(2, c)] = -n * h;
        m[(2, c + 2)] = -h;
        m[(3, c + 1)] = dr;
        m[(4, c + 1)] = dz;
        m[(5, c + 1)] = -n * h;
        m[(6, c + 2)] = dr;
        m[(7, c + 2)] = dz;
        m[(8, c)] = h;
        m[(8, c + 2)] = n * h;
    }
    m
}

/// The initial-stress (geometric) stiffness of mode `mode` per radian about a base state with
/// Cauchy stress `stress` [rr, zz, tt, rz] at the Gauss points, the element `geo` in the base
/// state's current configuration: the ring factor times the integral of
/// sigma_ij H_ki H_kj (the second variation of the stress's work on the displacement gradient;
/// updated Lagrangian, Bathe's K_NL).
pub fn initial_stress_stiffness(geo: &ElementGeometry, mode: u32, stress: &[[f64; 4]; QUADRATURE_POINTS]) -> HarmonicMatrix {
    let (points, weights) = geo.points();
    let factor = ring_factor(mode);
    let mut k = HarmonicMatrix::zeros();
    for q in 0..QUADRATURE_POINTS {
        let [rr, zz, tt, rz] = stress[q];
        let sigma = nalgebra::Matrix3::new(rr, rz, 0.0, rz, zz, 0.0, 0.0, 0.0, tt);
        let mut s = SMatrix::<f64, 9, 9>::zeros();
        for c in 0..3 {
            s.fixed_view_mut::<3, 3>(3 * c, 3 * c).copy_from(&sigma);
        }
        let g = gradient_map(&points[q], mode);
        k += g.transpose() * (s * (weights[q] * factor)) * g;
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::solid::{compute_solid, solid_tangent, MaterialTangents, SolidInput};
    use crate::fe::quadrature::Integration;
    use crate::fe::shape::Shape;
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
        let geo = ElementGeometry::new(Shape::Quad8, Integration::Full, crate::fe::section::Section::Axisymmetric, &ring_element()).unwrap();
        let k = material_stiffness(&geo, 0, &[isotropic(E, NU); QUADRATURE_POINTS]);
        let material = J2::elastic(E, NU, 0.0);
        let committed = [PointState::initial(Kinematics::Small); QUADRATURE_POINTS];
        let input = SolidInput {
            geometry: &geo,
            material: &material,
            kinematics: Kinematics::Small,
            temperature_change: [0.0; NODES],
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
        let geo = ElementGeometry::new(Shape::Quad8, Integration::Full, crate::fe::section::Section::Axisymmetric, &x).unwrap();
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
        let geo = ElementGeometry::new(Shape::Quad8, Integration::Full, crate::fe::section::Section::Axisymmetric, &ring_element()).unwrap();
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

    /// The initial-stress stiffness against the stress's work on the full 3-D displacement
    /// field around the ring: u = U_r cos e_r + U_z cos e_z + U_t sin e_theta built in
    /// Cartesian components at 24 angles, its Cartesian gradient with the angular derivative by
    /// central differences, sigma rotated to Cartesian axes, and Pi = 1/2 sigma : (grad u^T grad
    /// u) averaged over the angles (per radian). Pi is quadratic, so its exact second
    /// differences are the stiffness: to 1e-7 for n = 0, 1, 3.
    #[test]
    fn initial_stress_stiffness_is_the_second_variation_of_the_3d_stress_work() {
        let x = ring_element();
        let geo = ElementGeometry::new(Shape::Quad8, Integration::Full, crate::fe::section::Section::Axisymmetric, &x).unwrap();
        let (points, weights) = geo.points();
        let stress: [[f64; 4]; QUADRATURE_POINTS] = std::array::from_fn(|q| [120.0 + q as f64, -80.0 + 3.0 * q as f64, 45.0 - 2.0 * q as f64, 30.0 + q as f64]);
        for mode in [0u32, 1, 3] {
            let k = initial_stress_stiffness(&geo, mode, &stress);
            let n = f64::from(mode);
            let cs = |t: f64| if mode == 0 { (1.0, 1.0) } else { ((n * t).cos(), (n * t).sin()) };
            let angles = 24;
            let work = |u: &HarmonicVector| -> f64 {
                let mut total = 0.0;
                for (q, g) in points.iter().enumerate() {
                    // amplitudes and their r, z derivatives at the point
                    let at = |k: usize| -> (f64, f64, f64) {
                        (0..NODES).fold((0.0, 0.0, 0.0), |(v, d_r, d_z), a| {
                            (v + g.n[a] * u[3 * a + k], d_r + g.grad[a][0] * u[3 * a + k], d_z + g.grad[a][1] * u[3 * a + k])
                        })
                    };
                    let (ur, uz, ut) = (at(0), at(1), at(2));
                    // Cartesian displacement at (r, theta), with U at the point (r, z fixed)
                    let field = |t: f64, v: [f64; 3]| -> nalgebra::Vector3<f64> {
                        let (c, s) = (cs(t).0, cs(t).1);
                        let er = nalgebra::Vector3::new(t.cos(), t.sin(), 0.0);
                        let et = nalgebra::Vector3::new(-t.sin(), t.cos(), 0.0);
                        er * (v[0] * c) + et * (v[2] * s) + nalgebra::Vector3::z() * (v[1] * c)
                    };
                    let [rr, zz, tt, rz] = stress[q];
                    for j in 0..angles {
                        let t = 2.0 * std::f64::consts::PI * (j as f64 + 0.3) / angles as f64;
                        let er = nalgebra::Vector3::new(t.cos(), t.sin(), 0.0);
                        let et = nalgebra::Vector3::new(-t.sin(), t.cos(), 0.0);
                        let ez = nalgebra::Vector3::z();
                        let value = [ur.0, uz.0, ut.0];
                        let du_dr = field(t, [ur.1, uz.1, ut.1]);
                        let du_dz = field(t, [ur.2, uz.2, ut.2]);
                        let h = 1e-5;
                        let du_dt = (field(t + h, value) - field(t - h, value)) / (2.0 * h);
                        // grad u = du/dr (x) e_r + (1/r) du/dtheta (x) e_theta + du/dz (x) e_z
                        let grad = du_dr * er.transpose() + du_dt * et.transpose() / g.r + du_dz * ez.transpose();
                        let sigma =
                            er * er.transpose() * rr + ez * ez.transpose() * zz + et * et.transpose() * tt + (er * ez.transpose() + ez * er.transpose()) * rz;
                        total += 0.5 * (sigma.component_mul(&(grad.transpose() * grad))).sum() * weights[q] / angles as f64;
                    }
                }
                total
            };
            let unit = |i: usize| HarmonicVector::from_fn(|k, _| if k == i { 1.0 } else { 0.0 });
            let scale = k.amax();
            for a in 0..DOFS {
                for b in a..DOFS {
                    let kab = work(&(unit(a) + unit(b))) - work(&unit(a)) - work(&unit(b));
                    let kab = if a == b { 2.0 * work(&unit(a)) } else { kab };
                    assert!((kab - k[(a, b)]).abs() <= 1e-7 * scale, "mode {mode}, ({a}, {b}): 3-D {kab} against {}", k[(a, b)]);
                }
            }
        }
    }

    /// The elastic-plastic tangent under uniaxial stress: d sigma_zz / d eps_zz with the other
    /// normal stresses held at zero is E H / (E + H) (the tangent modulus), the shears keep mu.
    #[test]
    fn elastoplastic_tangent_under_uniaxial_stress() {
        let (e, nu, h) = (200_000.0, 0.3, 1000.0);
        for stress in [[0.0, 300.0, 0.0, 0.0], [0.0, -300.0, 0.0, 0.0]] {
            let d = elastoplastic(e, nu, h, &stress);
            // eps_zz = 1, eps_rr = eps_tt = x with d sigma_rr = 0 (symmetric in rr, tt)
            let x = -d[(0, 1)] / (d[(0, 0)] + d[(0, 2)]);
            let modulus = d[(1, 1)] + 2.0 * d[(1, 0)] * x;
            assert!((modulus - e * h / (e + h)).abs() < 1e-9 * e, "{modulus}");
            assert!((d[(4, 4)] - e / (2.0 * (1.0 + nu))).abs() < 1e-9 && (d - d.transpose()).amax() < 1e-9);
        }
    }
}

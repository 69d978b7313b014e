//! The harmonic element (`element::harmonic`) on a tube r 90..100 mm, E 200 GPa, nu 0.3,
//! assembled densely here (the kernel alone, without the solver), against beam theory:
//! - n = 0, torsion: T = G J phi / L, J = pi (b^4 - a^4) / 2 (Timoshenko, Strength of
//!   Materials I, ch. 9): the twist field U_t = phi r z / L is in the element's space, so within
//!   1e-4 (measured to round-off);
//! - n = 1, a cantilever (base clamped) whose end ring is moved sideways by d, its rotation
//!   free: P = d / (L^3 / (3 E I) + L / (k G A)) (Timoshenko beam, bending plus shear), k the
//!   thin tube's shear coefficient by Cowper (1966), 6 (1 + nu)(1 + m^2)^2 / ((7 + 6 nu)(1 +
//!   m^2)^2 + (20 + 12 nu) m^2), m = a / b = 0.9: k = 0.533. L = 2000 (shear 1.6 % of the
//!   compliance): within 1 %;
//! - n = 1, the end ring rotated by psi about a diameter, its offset held: the end moment of a
//!   Timoshenko beam clamped at the base, M = (4 E I / L) (1 + Phi) / (1 + 4 Phi) psi with the
//!   shear parameter Phi = 3 E I / (k G A L^2) (Przemieniecki, Theory of Matrix Structural
//!   Analysis, the beam element with shear): within 1 %;
//! - n = 1 about a base state: the slender cantilever under half its Euler load, its lateral
//!   stiffness against the beam-column (below), within 2 %.

use nalgebra::{DMatrix, DVector};
use slideline::element::harmonic::{initial_stress_stiffness, isotropic, material_stiffness, DOFS};
use slideline::element::solid::{ElementGeometry, QUADRATURE_POINTS};
use slideline::fe::quadrature::Integration;
use slideline::fe::shape::Shape;
use slideline::model::mesh::mapped_block;
use std::f64::consts::PI;

const E: f64 = 200_000.0;
const NU: f64 = 0.3;
const A: f64 = 90.0;
const B: f64 = 100.0;

/// The tube of length `l`, `nr` x `nz` elements, and its mode-`mode` stiffness (dense).
fn tube(l: f64, nr: usize, nz: usize, mode: u32) -> (Vec<[f64; 2]>, DMatrix<f64>) {
    tube_under(l, nr, nz, mode, 0.0)
}

/// The same with the initial-stress stiffness of a uniform axial stress `szz` (MPa).
fn tube_under(l: f64, nr: usize, nz: usize, mode: u32, szz: f64) -> (Vec<[f64; 2]>, DMatrix<f64>) {
    let (mesh, _) = mapped_block([nr, nz], |i, j| [A + (B - A) * i as f64 / (2 * nr) as f64, l * j as f64 / (2 * nz) as f64]);
    let n = 3 * mesh.coords.len();
    let mut k = DMatrix::zeros(n, n);
    let d = [isotropic(E, NU); QUADRATURE_POINTS];
    for e in &mesh.elements {
        let x = e.map(|a| mesh.coords[a]);
        let geo = ElementGeometry::new(Shape::Quad8, Integration::Full, slideline::fe::section::Section::Axisymmetric, &x).unwrap();
        let ke = material_stiffness(&geo, mode, &d) + initial_stress_stiffness(&geo, mode, &[[0.0, szz, 0.0, 0.0]; QUADRATURE_POINTS]);
        for i in 0..DOFS {
            for j in 0..DOFS {
                k[(3 * e[i / 3] + i % 3, 3 * e[j / 3] + j % 3)] += ke[(i, j)];
            }
        }
    }
    (mesh.coords, k)
}

/// Solves K u = f with the DOFs in `fixed` prescribed; returns the nodal forces K u.
fn solve(k: &DMatrix<f64>, fixed: &[(usize, f64)]) -> DVector<f64> {
    let n = k.nrows();
    let mut prescribed = vec![None; n];
    for &(dof, v) in fixed {
        prescribed[dof] = Some(v);
    }
    let free: Vec<usize> = (0..n).filter(|&i| prescribed[i].is_none()).collect();
    let mut u = DVector::from_iterator(n, prescribed.iter().map(|p| p.unwrap_or(0.0)));
    let rhs = -(k * &u);
    let kff = DMatrix::from_fn(free.len(), free.len(), |i, j| k[(free[i], free[j])]);
    let rf = DVector::from_fn(free.len(), |i, _| rhs[free[i]]);
    let uf = kff.lu().solve(&rf).expect("a supported tube");
    for (i, &dof) in free.iter().enumerate() {
        u[dof] = uf[i];
    }
    k * u
}

fn second_moment() -> f64 {
    PI / 4.0 * (B.powi(4) - A.powi(4))
}

fn shear_stiffness() -> f64 {
    let m2 = (A / B).powi(2);
    let kappa = 6.0 * (1.0 + NU) * (1.0 + m2).powi(2) / ((7.0 + 6.0 * NU) * (1.0 + m2).powi(2) + (20.0 + 12.0 * NU) * m2);
    kappa * E / (2.0 * (1.0 + NU)) * PI * (B * B - A * A)
}

#[test]
fn torsion_of_a_tube() {
    let (l, phi) = (200.0, 1e-3);
    let (x, k) = tube(l, 2, 10, 0);
    // U_r, U_z held (they decouple at n = 0); U_t = 0 at the base, phi r at the end
    let mut fixed = Vec::new();
    for (a, p) in x.iter().enumerate() {
        fixed.extend([(3 * a, 0.0), (3 * a + 1, 0.0)]);
        if p[1] == 0.0 {
            fixed.push((3 * a + 2, 0.0));
        } else if p[1] == l {
            fixed.push((3 * a + 2, phi * p[0]));
        }
    }
    let f = solve(&k, &fixed);
    let torque: f64 = x.iter().enumerate().filter(|(_, p)| p[1] == l).map(|(a, p)| 2.0 * PI * p[0] * f[3 * a + 2]).sum();
    let g = E / (2.0 * (1.0 + NU));
    let expected = g * PI / 2.0 * (B.powi(4) - A.powi(4)) * phi / l;
    assert!((torque / expected - 1.0).abs() < 1e-4, "torque {torque} against G J phi / L = {expected}");
}

/// The end ring of a cantilever of length `l` moved sideways by `d` and, when given, rotated by
/// `psi` about a diameter (else its axial motion is free): the end's lateral force and moment
/// (full ring), the base clamped.
fn cantilever(l: f64, nz: usize, d: f64, psi: Option<f64>) -> (f64, f64) {
    cantilever_under(l, nz, d, psi, 0.0)
}

/// The same under a uniform axial stress `szz` (a dead end load of szz A).
fn cantilever_under(l: f64, nz: usize, d: f64, psi: Option<f64>, szz: f64) -> (f64, f64) {
    let (x, k) = tube_under(l, 2, nz, 1, szz);
    let mut fixed = Vec::new();
    for (a, p) in x.iter().enumerate() {
        if p[1] == 0.0 {
            fixed.extend([(3 * a, 0.0), (3 * a + 1, 0.0), (3 * a + 2, 0.0)]);
        } else if p[1] == l {
            // the ring's rigid motion: translation d, rotation psi about a diameter through
            // (0, l): u_x = d + psi (z - l) = d at the end, u_z = -psi r cos theta
            fixed.extend([(3 * a, d), (3 * a + 2, -d)]);
            if let Some(psi) = psi {
                fixed.push((3 * a + 1, -psi * p[0]));
            }
        }
    }
    let f = solve(&k, &fixed);
    let end = || x.iter().enumerate().filter(|(_, p)| p[1] == l);
    // lateral force 2 pi sum (f_r - f_t); moment about the diameter, conjugate to psi
    let force: f64 = end().map(|(a, _)| 2.0 * PI * (f[3 * a] - f[3 * a + 2])).sum();
    let moment: f64 = end().map(|(a, p)| -2.0 * PI * p[0] * f[3 * a + 1]).sum();
    (force, moment)
}

#[test]
fn a_slender_cantilever_tube_pushed_sideways() {
    let (l, d) = (2000.0, 1.0);
    let (force, _) = cantilever(l, 100, d, None);
    let compliance = l.powi(3) / (3.0 * E * second_moment()) + l / shear_stiffness();
    let expected = d / compliance;
    eprintln!("lateral force {force:.2} N against Timoshenko's {expected:.2} N ({:+.3} %)", 100.0 * (force / expected - 1.0));
    assert!((force / expected - 1.0).abs() < 0.01, "{force} against {expected}");
}

#[test]
fn a_cantilever_tube_end_rotated() {
    let (l, psi) = (2000.0, 1e-3);
    let (_, moment) = cantilever(l, 100, 0.0, Some(psi));
    let phi = 3.0 * E * second_moment() / (shear_stiffness() * l * l);
    let expected = 4.0 * E * second_moment() / l * (1.0 + phi) / (1.0 + 4.0 * phi) * psi;
    eprintln!("end moment {moment:.4e} N mm against Timoshenko's {expected:.4e} ({:+.3} %)", 100.0 * (moment / expected - 1.0));
    assert!((moment / expected - 1.0).abs() < 0.01, "{moment} against {expected}");
}

/// The same tube ten times shorter, L = 200 (the shear compliance 62 % of the total): within
/// 2 % of Timoshenko's beam.
#[test]
fn a_short_cantilever_tube_pushed_sideways() {
    let (l, d) = (200.0, 1.0);
    let (force, _) = cantilever(l, 40, d, None);
    let compliance = l.powi(3) / (3.0 * E * second_moment()) + l / shear_stiffness();
    let expected = d / compliance;
    eprintln!("short tube: lateral force {force:.2} N against Timoshenko's {expected:.2} N ({:+.3} %)", 100.0 * (force / expected - 1.0));
    assert!((force / expected - 1.0).abs() < 0.02, "{force} against {expected}");
}

/// The slender cantilever under an axial end compression of half its Euler load, P = pi^2 E I /
/// (8 L^2): the beam-column's lateral compliance (tan kL - kL) / (P k), k = sqrt(P / E I)
/// (Timoshenko & Gere, Theory of Elastic Stability, 1.11), plus the shear compliance L / (k G A):
/// the lateral stiffness falls to 0.50 of the unloaded one; within 2 % (measured -1.7 %: the
/// stress's work on the shear strain softens it further, as in Haringx's column, whose
/// k^2 = P (1 + P / k G A) / E I brings the difference to -0.5 %).
#[test]
fn a_compressed_cantilever_tube_is_softer_as_the_beam_column_says() {
    let (l, d) = (2000.0, 1.0);
    let ei = E * second_moment();
    let p = PI * PI * ei / (8.0 * l * l);
    let area = PI * (B * B - A * A);
    let (force, _) = cantilever_under(l, 100, d, None, -p / area);
    let k = (p / ei).sqrt();
    let compliance = ((k * l).tan() - k * l) / (p * k) + l / shear_stiffness();
    let expected = d / compliance;
    let (unloaded, _) = cantilever(l, 100, d, None);
    eprintln!(
        "compressed: lateral force {force:.2} N against the beam-column's {expected:.2} N ({:+.3} %); unloaded {unloaded:.2} N",
        100.0 * (force / expected - 1.0)
    );
    assert!((force / expected - 1.0).abs() < 0.02, "{force} against {expected}");
    assert!(force < 0.5 * unloaded, "the compression must soften the tube: {force} against {unloaded}");
}

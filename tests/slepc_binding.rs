//! The SLEPc binding on its own (one process: MPI starts once per process), against two
//! pencils with eigenvalues in closed form (tridiagonal Toeplitz matrices of order n: b + 2
//! sqrt(a c) cos(j pi / (n + 1)), j = 1..n; e.g. Golub & Van Loan, Matrix Computations):
//! - a fixed-fixed chain of n = 40 masses m = 2 and springs k = 3, K x = omega^2 M x with
//!   K = k tridiag(-1, 2, -1), M = m I: omega_j^2 = (2 k / m)(1 - cos(j pi / 41)); the three
//!   nearest 0 and the two nearest 1.5 (a target inside the spectrum), to 1e-10, with
//!   M-orthogonal eigenvectors;
//! - an unsymmetric tridiag(-0.9, 2, -1.1) against B = -I (the buckling problem's form, B
//!   indefinite): lambda_j = -(2 + 2 sqrt(0.99) cos(j pi / 41)), real; the two nearest 0 to
//!   1e-9 (a milder asymmetry than the eigenvalues' conditioning, (c / a)^(n / 2), would allow
//!   at 1e-16 round-off: tridiag(-0.5, 2, -2) puts them 2 % off in any solver).
//!
//! The two 2-rank paths are the frequency and buckling steps' tests.

use slideline::petsc::eigen::{nearest, Pencil};
use slideline::petsc::{MatOps, Matrix, PetscSession};
use std::f64::consts::PI;

const N: usize = 40;

fn tridiagonal<'s>(session: &'s PetscSession, lower: f64, diagonal: f64, upper: f64) -> Matrix<'s> {
    let mut rows = Vec::new();
    let mut cols = Vec::new();
    let mut values = Vec::new();
    for i in 0..N {
        for (j, v) in [(i.wrapping_sub(1), lower), (i, diagonal), (i + 1, upper)] {
            if j < N {
                rows.push(i as i32);
                cols.push(j as i32);
                values.push(v);
            }
        }
    }
    let mut m = Matrix::aij_coo(session, session.comm(), N, &rows, &cols).unwrap();
    m.set_values_coo(&values).unwrap();
    m
}

#[test]
fn generalised_eigenproblems_against_closed_forms() {
    let session = PetscSession::initialize(&[]).unwrap();
    let (k, m) = (3.0, 2.0);
    let stiffness = tridiagonal(&session, -k, 2.0 * k, -k);
    let mass = tridiagonal(&session, 0.0, m, 0.0);
    let exact: Vec<f64> = (1..=N).map(|j| 2.0 * k / m * (1.0 - (j as f64 * PI / (N + 1) as f64).cos())).collect();
    let pairs = nearest(&session, &stiffness, &mass, N, Pencil::Hermitian, 3, 0.0).unwrap();
    assert!(pairs.len() >= 3, "{} converged", pairs.len());
    for (pair, want) in pairs.iter().zip(&exact) {
        assert!((pair.value - want).abs() < 1e-10 * want, "{} against {want}", pair.value);
        assert_eq!(pair.imaginary, 0.0);
        assert!(pair.error < 1e-8, "residual {}", pair.error);
    }
    // M-orthogonality of the first two
    let dot: f64 = pairs[0].vector.iter().zip(&pairs[1].vector).map(|(a, b)| a * m * b).sum();
    let norm: f64 = pairs[0].vector.iter().map(|a| a * m * a).sum();
    assert!(dot.abs() < 1e-10 * norm, "{dot} against {norm}");
    // a target inside the spectrum: the two eigenvalues nearest it
    let target = 1.5;
    let mut by_distance = exact.clone();
    by_distance.sort_by(|a, b| (a - target).abs().total_cmp(&(b - target).abs()));
    let inside = nearest(&session, &stiffness, &mass, N, Pencil::Hermitian, 2, target).unwrap();
    for (pair, want) in inside.iter().zip(&by_distance) {
        assert!((pair.value - want).abs() < 1e-10 * want, "near {target}: {} against {want}", pair.value);
    }

    // unsymmetric A, B = -I
    let a = tridiagonal(&session, -0.9, 2.0, -1.1);
    let minus_identity = tridiagonal(&session, 0.0, -1.0, 0.0);
    let exact: Vec<f64> = (1..=N).rev().map(|j| -(2.0 + 2.0 * 0.99f64.sqrt() * (j as f64 * PI / (N + 1) as f64).cos())).collect();
    let pairs = nearest(&session, &a, &minus_identity, N, Pencil::General, 2, 0.0).unwrap();
    assert!(pairs.len() >= 2, "{} converged", pairs.len());
    for (pair, want) in pairs.iter().zip(&exact) {
        assert!((pair.value - want).abs() < 1e-9 * want.abs(), "{} against {want}", pair.value);
        assert!(pair.imaginary.abs() < 1e-12, "{}", pair.imaginary);
    }
}

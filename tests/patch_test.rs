//! Patch tests on a distorted mesh: five Q8 elements (a skewed inner quadrilateral inside a
//! square, r in [10, 20], z in [0, 10]; tests/data/patch5.msh, made by make_meshes.py) with the
//! eight boundary nodes prescribed to the field u_r = a r, u_z = b z + c. In axisymmetry this
//! is the linear field that is in equilibrium without body forces (u_r = const or u_r ~ z would
//! give a 1/r hoop strain that needs body forces). Exact strain [a, b, a, 0] everywhere, so the
//! stress at every quadrature point must equal C [a, b, a, 0] to 1e-10. At finite strain the
//! same field is a homogeneous F = diag(1 + a, 1 + b, 1 + a) whose Hencky stress every Gauss
//! point must reproduce.
//!
//!   (10,10) +-----------+ (20,10)
//!           | \  top  / |
//!           |  +-----+  |
//!           |l | ctr |r |
//!           |  +-----+  |
//!           | / bottom\ |
//!   (10, 0) +-----------+ (20, 0)

mod common;
use common::{data, run_deck, Results};
use slideline::material::{Kinematics, PointState, J2};

fn deck(nlgeom: bool, a: f64, b: f64, c: f64) -> String {
    // boundary node coordinates, in the order of the physical points b1..b8 in patch5.msh
    let pts = [(10.0, 0.0), (20.0, 0.0), (20.0, 10.0), (10.0, 10.0), (15.0, 0.0), (20.0, 5.0), (15.0, 10.0), (10.0, 5.0)];
    let mut d = format!("nlgeom = {nlgeom}\n[mesh]\nfile = \"patch5.msh\"\n");
    d.push_str("[[material]]\nname = \"m\"\nyoungs_modulus = 200000.0\npoissons_ratio = 0.3\n[[step]]\nboundary = [\n");
    for (k, (r, z)) in pts.iter().enumerate() {
        d.push_str(&format!("  {{ set = \"b{}\", ur = {:e}, uz = {:e} }},\n", k + 1, a * r, b * z + c));
    }
    d.push_str("]\n");
    d
}

/// Runs the patch with the field (a, b, c); returns the Gauss-point stresses and checks that
/// every node follows the field exactly.
fn run_patch(nlgeom: bool, a: f64, b: f64, c: f64) -> Vec<f64> {
    let run = run_deck(&deck(nlgeom, a, b, c), &[("patch5.msh", &data("patch5.msh"))], 1, common::DOUBLE);
    run.assert_ok();
    let res = Results::open(&run.h5);
    for (x, u) in res.nodes() {
        assert!((u[0] - a * x[0]).abs() < 1e-10 && (u[1] - (b * x[1] + c)).abs() < 1e-10, "node at {x:?}: {u:?}");
    }
    let stress = res.f64s(&format!("{}/stress", res.last_increment()));
    assert_eq!(stress.len(), 5 * 9 * 4);
    stress
}

fn max_error(stress: &[f64], exact: &[f64; 4]) -> f64 {
    stress.chunks(4).flat_map(|s| (0..4).map(move |i| (s[i] - exact[i]).abs())).fold(0.0f64, f64::max)
}

#[test]
fn small_strain_patch_reproduces_the_exact_linear_stress() {
    let (a, b) = (1.0e-3, -4.0e-4);
    let stress = run_patch(false, a, b, 0.05);
    let (e, nu) = (200e3, 0.3);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let tr = 2.0 * a + b;
    let exact = [lambda * tr + 2.0 * mu * a, lambda * tr + 2.0 * mu * b, lambda * tr + 2.0 * mu * a, 0.0];
    let scale = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = max_error(&stress, &exact);
    assert!(worst <= 1e-10 * scale, "max stress error {worst:e} (scale {scale})");
}

#[test]
fn finite_strain_patch_reproduces_the_homogeneous_hencky_stress() {
    // 20 % radial and hoop stretch, 10 % axial shortening: far from linear.
    let (a, b) = (0.2, -0.1);
    let stress = run_patch(true, a, b, 0.05);
    let f = [1.0 + a, 0.0, 0.0, 1.0 + b, 1.0 + a];
    let j = (1.0 + a) * (1.0 + b) * (1.0 + a);
    let m = J2::elastic(200e3, 0.3, 0.0);
    let exact = m.update(Kinematics::Finite, &f, j, 0.0, &PointState::initial(Kinematics::Finite)).unwrap().cauchy;
    // Hencky: tau = lambda tr(ln V) I + 2 mu ln V, sigma = tau / J, written out independently
    let (lam, mu) = (200e3 * 0.3 / (1.3 * 0.4), 200e3 / 2.6);
    let (lr, lz) = ((1.0 + a).ln(), (1.0 + b).ln());
    let tr = 2.0 * lr + lz;
    let by_hand = [(lam * tr + 2.0 * mu * lr) / j, (lam * tr + 2.0 * mu * lz) / j, (lam * tr + 2.0 * mu * lr) / j, 0.0];
    for i in 0..4 {
        assert!((exact[i] - by_hand[i]).abs() < 1e-9 * by_hand[0].abs(), "{exact:?} vs {by_hand:?}");
    }
    let scale = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = max_error(&stress, &exact);
    assert!(worst <= 1e-10 * scale, "max stress error {worst:e} (scale {scale:e})");
}

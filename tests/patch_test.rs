//! Patch test on a distorted mesh: five Q8 elements (a skewed inner quadrilateral inside a
//! square, r in [10, 20], z in [0, 10]; tests/data/patch5.msh, made by make_meshes.py) with the
//! eight boundary nodes prescribed to the field u_r = a r, u_z = b z + c. In axisymmetry this
//! is the linear field that is in equilibrium without body forces (u_r = const or u_r ~ z would
//! give a 1/r hoop strain that needs body forces). Exact strain [a, b, a, 0] everywhere, so the
//! stress at every quadrature point must equal C [a, b, a, 0] to 1e-10.
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

const A: f64 = 1.0e-3;
const B: f64 = -4.0e-4;
const C: f64 = 0.05;

fn deck() -> String {
    // boundary node coordinates, in the order of the physical points b1..b8 in patch5.msh
    let pts = [
        (10.0, 0.0),
        (20.0, 0.0),
        (20.0, 10.0),
        (10.0, 10.0),
        (15.0, 0.0),
        (20.0, 5.0),
        (15.0, 10.0),
        (10.0, 5.0),
    ];
    let mut d = String::from("[mesh]\nfile = \"patch5.msh\"\n\n[[material]]\nname = \"m\"\nyoungs_modulus = 200000.0\npoissons_ratio = 0.3\n\n[[step]]\nboundary = [\n");
    for (k, (r, z)) in pts.iter().enumerate() {
        d.push_str(&format!(
            "  {{ set = \"b{}\", ur = {:e}, uz = {:e} }},\n",
            k + 1,
            A * r,
            B * z + C
        ));
    }
    d.push_str("]\n");
    d
}

#[test]
fn distorted_patch_reproduces_exact_stress_and_displacement() {
    let run = run_deck(&deck(), &[("patch5.msh", &data("patch5.msh"))], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let (e, nu) = (200e3, 0.3);
    let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
    let mu = e / (2.0 * (1.0 + nu));
    let tr = 2.0 * A + B;
    let exact = [
        lambda * tr + 2.0 * mu * A,
        lambda * tr + 2.0 * mu * B,
        lambda * tr + 2.0 * mu * A,
        0.0,
    ];
    let scale = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let stress = res.f64s(&format!("{}/stress", res.last_increment()));
    assert_eq!(stress.len(), 5 * 9 * 4);
    let worst = stress
        .chunks(4)
        .flat_map(|s| (0..4).map(move |i| (s[i] - exact[i]).abs()))
        .fold(0.0f64, f64::max);
    assert!(
        worst <= 1e-10 * scale,
        "max stress error {worst:e} (scale {scale})"
    );
    // interior nodes too follow the field exactly
    for (x, u) in res.nodes() {
        assert!(
            (u[0] - A * x[0]).abs() < 1e-12 && (u[1] - (B * x[1] + C)).abs() < 1e-12,
            "node at {x:?}: {u:?}"
        );
    }
}

//! Clamped circular plate under uniform pressure.
//!
//! Source: Timoshenko & Woinowsky-Krieger, Theory of Plates and Shells, sec. 62:
//! w(0) = p a^4 / (64 D), D = E t^3 / (12 (1 - nu^2)). Radius a = 100 mm, thickness t = 1 mm,
//! p = 0.01 MPa, E = 200 GPa, nu = 0.3: D = 18315 N mm, w(0) = 0.8531 mm.
//! Mesh: 100 x 4 Q8 elements over r in [0, 100], z in [0, 1] (element 1 mm x 0.25 mm, aspect
//! ratio 4); u_r = 0 on the axis, u_r = u_z = 0 on the rim face r = 100, pressure on top.

mod common;
use common::{run_deck, Results};

const DECK: &str = r#"
nlgeom = false  # linear theory is the reference
[mesh]
rectangle = { r = [0.0, 100.0], z = [0.0, 1.0], divisions = [100, 4] }

[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3

[[step]]
boundary = [ { set = "inner", ur = 0.0 }, { set = "outer", ur = 0.0, uz = 0.0 } ]
pressure = [ { surface = "top", value = 0.01 } ]
"#;

#[test]
fn centre_deflection_within_2_percent_of_kirchhoff() {
    let run = run_deck(DECK, &[], 1, &[]);
    run.assert_ok();
    let nodes = Results::open(&run.h5).nodes();
    let (_, u) = nodes.iter().find(|(x, _)| x[0] == 0.0 && (x[1] - 0.5).abs() < 1e-12).expect("mid-plane node on the axis");
    let (e, nu, t, a, p) = (200e3f64, 0.3f64, 1.0f64, 100.0f64, 0.01);
    let d = e * t.powi(3) / (12.0 * (1.0 - nu * nu));
    let exact = -p * a.powi(4) / (64.0 * d);
    let rel = (u[1] - exact).abs() / exact.abs();
    eprintln!("centre deflection {:.5} mm, Kirchhoff {exact:.5} mm (rel {rel:.2e})", u[1]);
    assert!(rel < 0.02, "centre deflection {} vs {exact} (rel {rel:.3})", u[1]);
}

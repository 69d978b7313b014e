//! Lame's thick-walled cylinder under internal pressure, plane strain.
//!
//! Source: Timoshenko & Goodier, Theory of Elasticity, sec. 33. Inner radius a = 100 mm, outer
//! b = 130 mm, internal pressure p = 50 MPa, E = 200 GPa, nu = 0.3, axial ends held (u_z = 0).
//!   u_r(r)      = (1 + nu) / E * ((1 - 2 nu) A r + B / r),  A = p a^2 / (b^2 - a^2), B = A b^2
//!   sigma_tt(a) = p (b^2 + a^2) / (b^2 - a^2) = 194.93 MPa
//!   u_r(a) = 0.098442 mm, u_r(b) = 0.085725 mm.
//! Mesh: a 12 x 2 block of Q8 elements over r in [100, 130], z in [0, 10].
//!
//!   z=10 +--+--+-- ... --+   u_z = 0 (top)
//!   p -> |  |  |         |
//!   z=0  +--+--+-- ... --+   u_z = 0 (bottom)
//!       r=100          r=130

mod common;
use common::{run_deck, Results};

const DECK: &str = r#"
nlgeom = false  # linear theory is the reference
[mesh]
rectangle = { r = [100.0, 130.0], z = [0.0, 10.0], divisions = [12, 2] }

[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3

[[step]]
boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 } ]
pressure = [ { surface = "inner", value = 50.0 } ]
"#;

fn exact_ur(r: f64) -> f64 {
    let (a, b, p, e, nu) = (100.0f64, 130.0f64, 50.0, 200e3, 0.3);
    let aa = p * a * a / (b * b - a * a);
    let bb = aa * b * b;
    (1.0 + nu) / e * ((1.0 - 2.0 * nu) * aa * r + bb / r)
}

#[test]
fn displacements_and_bore_hoop_stress_within_0_2_percent() {
    let run = run_deck(DECK, &[], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let nodes = res.nodes();
    for (x, u) in &nodes {
        if (x[0] - 100.0).abs() < 1e-9 || (x[0] - 130.0).abs() < 1e-9 {
            let exact = exact_ur(x[0]);
            let rel = (u[0] - exact).abs() / exact;
            eprintln!("u_r({}) = {:.6} mm, exact {exact:.6} (rel {rel:.2e})", x[0], u[0]);
            assert!(rel < 2e-3, "u_r({}) = {} vs exact {exact} (rel {rel:.2e})", x[0], u[0]);
            assert!(u[1].abs() < 1e-12);
        }
    }
    // Hoop stress at the bore, extrapolated from the Gauss points of the first element.
    let at_bore = res.stress_at_inner_edge(&res.last_increment(), 100.0, 2);
    let exact = 50.0 * (130.0f64.powi(2) + 100.0f64.powi(2)) / (130.0f64.powi(2) - 100.0f64.powi(2));
    let rel = (at_bore - exact).abs() / exact;
    eprintln!("hoop stress at bore {at_bore:.4} MPa, exact {exact:.4} (rel {rel:.2e})");
    assert!(rel < 2e-3, "hoop stress at bore {at_bore} vs {exact} (rel {rel:.2e})");
}

/// The nodal stresses a ParaView user sees (`/increments/N/nodal/`, Gauss values extrapolated in
/// these elastic elements and averaged) against Lame's at every node: sigma_rr = A - B / r^2,
/// sigma_tt = A + B / r^2, sigma_zz = 2 nu A (plane strain), A = p a^2 / (b^2 - a^2) = 72.46 MPa,
/// B = A b^2; within 1 % of the bore hoop stress (194.93 MPa), von Mises of the exact tensor
/// likewise.
#[test]
fn nodal_stresses_within_1_percent_of_lame_at_every_node() {
    let run = run_deck(DECK, &[], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let inc = res.last_increment();
    let nodal = |name: &str| res.f64s(&format!("{inc}/nodal/{name}"));
    let (rr, zz, tt, vm) = (nodal("stress_rr"), nodal("stress_zz"), nodal("stress_tt"), nodal("von_mises"));
    let (a, b, p, nu) = (100.0f64, 130.0f64, 50.0, 0.3);
    let big_a = p * a * a / (b * b - a * a);
    let scale = p * (b * b + a * a) / (b * b - a * a);
    let mut worst = 0.0f64;
    for (k, (x, _)) in res.nodes().iter().enumerate() {
        let (sr, st) = (big_a - big_a * b * b / (x[0] * x[0]), big_a + big_a * b * b / (x[0] * x[0]));
        let sz = 2.0 * nu * big_a;
        let mises = (0.5 * ((sr - sz).powi(2) + (sz - st).powi(2) + (st - sr).powi(2))).sqrt();
        for (got, exact) in [(rr[k], sr), (zz[k], sz), (tt[k], st), (vm[k], mises)] {
            worst = worst.max((got - exact).abs() / scale);
        }
    }
    eprintln!("largest nodal stress error: {:.3e} of the bore hoop stress", worst);
    assert!(worst < 0.01, "nodal stresses off Lame's by {worst:.3e} of {scale:.2} MPa");
}

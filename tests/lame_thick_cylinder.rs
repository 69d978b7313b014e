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
    // Hoop stress at the bore: extrapolate the three Gauss-point values along r of the first
    // element (quadratic Lagrange through xi = -sqrt(3/5), 0, sqrt(3/5)) to xi = -1.
    let stress = res.f64s(&format!("{}/stress", res.last_increment()));
    let conn = res.i64s("mesh/connectivity");
    let coords = res.f64s("mesh/coordinates");
    let e = (0..conn.len() / 8).find(|&e| (coords[2 * conn[8 * e] as usize] - 100.0).abs() < 1e-9).expect("an element on the bore");
    let hoop = |q: usize| stress[(e * 9 + q) * 4 + 2];
    let g = (0.6f64).sqrt();
    let lagrange = |x: f64| {
        let pts = [-g, 0.0, g];
        let mut w = [1.0; 3];
        for i in 0..3 {
            for j in 0..3 {
                if i != j {
                    w[i] *= (x - pts[j]) / (pts[i] - pts[j]);
                }
            }
        }
        w
    };
    let w = lagrange(-1.0);
    // middle Gauss row (eta = 0): points 3, 4, 5
    let at_bore = w[0] * hoop(3) + w[1] * hoop(4) + w[2] * hoop(5);
    let exact = 50.0 * (130.0f64.powi(2) + 100.0f64.powi(2)) / (130.0f64.powi(2) - 100.0f64.powi(2));
    let rel = (at_bore - exact).abs() / exact;
    eprintln!("hoop stress at bore {at_bore:.4} MPa, exact {exact:.4} (rel {rel:.2e})");
    assert!(rel < 2e-3, "hoop stress at bore {at_bore} vs {exact} (rel {rel:.2e})");
}

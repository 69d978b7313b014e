//! Homogeneous uniaxial stretch of a short bar to 50 % logarithmic strain.
//!
//! Reference: for J2 with linear isotropic hardening in the Hencky / exponential-map
//! formulation, uniaxial Kirchhoff stress and log strain eps obey exactly
//!   tau = E eps                                  (elastic, tau <= sigma_y0)
//!   tau = sigma_y0 + H ep,  ep = eps - tau / E   =>  tau = (sigma_y0 + H eps) / (1 + H / E).
//! Solid cylinder r in [0, 5], z in [0, 10] (2 x 4 Q8 elements): axis u_r = 0, bottom u_z = 0,
//! top u_z = 10 (e^0.5 - 1), 25 increments; the lateral surface is free, so the state is
//! homogeneous uniaxial stress. The Kirchhoff stress is J sigma_zz with J = det F from the
//! displacements.

mod common;
use common::{run_deck, Results, PLASTIC_STEEL, TIGHT};

const L: f64 = 10.0;
const R: f64 = 5.0;

#[test]
fn kirchhoff_stress_follows_the_hardening_law_to_1e_8() {
    let top = L * (0.5f64.exp() - 1.0);
    let deck = format!(
        r#"[mesh]
rectangle = {{ r = [0.0, {R}], z = [0.0, {L}], divisions = [2, 4] }}
{PLASTIC_STEEL}[[step]]
increments = 25
boundary = [ {{ set = "inner", ur = 0.0 }}, {{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = {top} }} ]
"#
    );
    let run = run_deck(&deck, &[], 1, &[TIGHT, common::DOUBLE].concat());
    run.assert_ok();
    let res = Results::open(&run.h5);
    let (e, sy, h) = (200e3, 300.0, 1000.0);
    let coords = res.f64s("mesh/coordinates");
    let corner = (0..coords.len() / 2).find(|&n| coords[2 * n] == R && coords[2 * n + 1] == L).unwrap();
    for inc in res.increments() {
        let u = res.displacement(&inc);
        let (lr, lz) = (1.0 + u[2 * corner] / R, 1.0 + u[2 * corner + 1] / L);
        let eps = lz.ln();
        let j = lr * lr * lz;
        let stress = res.f64s(&format!("{inc}/stress"));
        let elastic = e * eps;
        let expected = if elastic <= sy { elastic } else { (sy + h * eps) / (1.0 + h / e) };
        for s in stress.chunks(4) {
            let tau = j * s[1];
            assert!(((tau - expected) / expected).abs() < 1e-8, "{inc}: log strain {eps:.4}: tau {tau} vs {expected}");
            assert!(s[0].abs() < 1e-8 * expected && s[2].abs() < 1e-8 * expected && s[3].abs() < 1e-8 * expected, "not uniaxial: {s:?}");
        }
    }
    let final_strain = (1.0 + res.displacement(&res.last_increment())[2 * corner + 1] / L).ln();
    assert!((final_strain - 0.5).abs() < 1e-12);
}

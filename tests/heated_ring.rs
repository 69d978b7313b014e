//! Uniform heating of a ring, r in [150, 160], z in [0, 10] (the bellows' tube wall), AISI 304:
//! E = 200 GPa, nu = 0.3, alpha = 1.875e-5 /degC, sigma_y0 = 300 MPa, H = 1000 MPa, from
//! 20 to 200 degC (dT = 180).
//!
//! - Free (only u_z = 0 at z = 0): no stress, u_r = (1 + alpha dT - 1) r exactly, also at
//!   finite strain (the thermal stretch 1 + alpha dT is removed multiplicatively).
//! - Both axial ends held (small strain): uniaxial stress sigma_z = -E alpha dT while elastic
//!   (dT = 50: -187.5 MPa); at dT = 180, E alpha dT = 675 MPa > sigma_y0, so it yields:
//!   ep = (E alpha dT - sigma_y0) / (E + H), sigma_z = -(sigma_y0 + H ep).

mod common;
use common::{run_deck, Results};

const ALPHA: f64 = 1.875e-5;

fn deck(nlgeom: bool, temperature: f64, ends: &str) -> String {
    format!(
        r#"nlgeom = {nlgeom}
reference_temperature = 20.0
[mesh]
rectangle = {{ r = [150.0, 160.0], z = [0.0, 10.0], divisions = [3, 3] }}
[[material]]
name = "aisi304"
model = "j2"
youngs_modulus = 200000.0
poissons_ratio = 0.3
thermal_expansion = {ALPHA}
yield_stress = 300.0
hardening_modulus = 1000.0
[[step]]
increments = 4
temperature = {temperature}
boundary = [ {ends} ]
"#
    )
}

#[test]
fn free_ring_heated_to_200_is_stress_free_and_grows_by_alpha_dt() {
    for nlgeom in [true, false] {
        let run = run_deck(&deck(nlgeom, 200.0, r#"{ set = "bottom", uz = 0.0 }"#), &[], 1, common::DOUBLE);
        run.assert_ok();
        let res = Results::open(&run.h5);
        let strain = ALPHA * 180.0;
        for (x, u) in res.nodes() {
            assert!((u[0] - strain * x[0]).abs() < 1e-9 * x[0], "nlgeom {nlgeom}: u_r at {x:?} = {} vs {}", u[0], strain * x[0]);
            assert!((u[1] - strain * x[1]).abs() < 1e-9 * 10.0, "nlgeom {nlgeom}: u_z at {x:?} = {}", u[1]);
        }
        let worst = res.f64s(&format!("{}/stress", res.last_increment())).iter().fold(0.0f64, |m, s| m.max(s.abs()));
        assert!(worst < 1e-8, "nlgeom {nlgeom}: stress {worst:e} MPa in free expansion");
    }
}

fn axial_stress_with_held_ends(temperature: f64) -> (Vec<f64>, f64) {
    let ends = r#"{ set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 }"#;
    let run = run_deck(&deck(false, temperature, ends), &[], 1, common::DOUBLE);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let stress = res.f64s(&format!("{}/stress", res.last_increment()));
    let ep = *res.history("max_equivalent_plastic_strain").last().unwrap();
    (stress, ep)
}

#[test]
fn held_ends_give_minus_e_alpha_dt_then_yield() {
    let e = 200e3;
    let (stress, ep) = axial_stress_with_held_ends(70.0);
    let expected = -e * ALPHA * 50.0;
    assert_eq!(ep, 0.0);
    for s in stress.chunks(4) {
        assert!((s[1] - expected).abs() < 1e-8 * expected.abs(), "sigma_z {} vs {expected}", s[1]);
        assert!(s[0].abs() < 1e-8 && s[2].abs() < 1e-8 && s[3].abs() < 1e-8, "{s:?}");
    }
    let (stress, ep) = axial_stress_with_held_ends(200.0);
    let (sy, h) = (300.0, 1000.0);
    let ep_exact = (e * ALPHA * 180.0 - sy) / (e + h);
    assert!((ep - ep_exact).abs() < 1e-10, "ep {ep} vs {ep_exact}");
    let expected = -(sy + h * ep_exact);
    for s in stress.chunks(4) {
        assert!((s[1] - expected).abs() < 1e-8 * expected.abs(), "sigma_z {} vs {expected}", s[1]);
    }
}

/// Temperatures given on node sets in the TOML deck: a stress-free state that varies (the top
/// nodes at 30, the rest at 20 degC) heated by the same 30 degC everywhere (the top to 60, the
/// rest to 50) is free expansion again: no stress, u = alpha 30 x. A set the mesh lacks is
/// refused by name.
#[test]
fn temperatures_on_node_sets_count_from_each_nodes_reference() {
    let text = deck(false, 0.0, r#"{ set = "bottom", uz = 0.0 }"#)
        .replace("reference_temperature = 20.0", r#"reference_temperature = [{ value = 20.0 }, { set = "top", value = 30.0 }]"#)
        .replace("temperature = 0\n", "temperature = [{ value = 50.0 }, { set = \"top\", value = 60.0 }]\n");
    assert!(text.contains("set = \"top\", value = 60.0"), "{text}");
    let run = run_deck(&text, &[], 2, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    for (x, u) in res.nodes() {
        let strain = ALPHA * 30.0;
        assert!((u[0] - strain * x[0]).abs() < 1e-9 * x[0] && (u[1] - strain * x[1]).abs() < 1e-9, "u at {x:?} = {u:?}");
    }
    let worst = res.f64s(&format!("{}/stress", res.last_increment())).iter().fold(0.0f64, |m, s| m.max(s.abs()));
    assert!(worst < 1e-8, "stress {worst:e} MPa in free expansion");
    // the field in the results file: 60 on the top nodes, 50 elsewhere
    let coords = res.f64s("mesh/coordinates");
    let t = res.f64s(&format!("{}/nodal/temperature", res.last_increment()));
    for (x, t) in coords.chunks(2).zip(t) {
        assert_eq!(t, if x[1] == 10.0 { 60.0 } else { 50.0 }, "at {x:?}");
    }
    let bad = run_deck(&text.replace("set = \"top\", value = 60.0", "set = \"lid\", value = 60.0"), &[], 1, &[]);
    common::assert_rejected(&bad, &["step", "temperature", "unknown node set 'lid'"]);
}

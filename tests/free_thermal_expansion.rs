//! Free thermal expansion of a ring: uniform heating by dT gives no stress and
//! u_r = alpha dT r, u_z = alpha dT z (with u_z held at z = 0 only).
//! Ring r in [50, 60], z in [0, 10], alpha = 1.2e-5 /degC, heated from 20 to 220 degC.

mod common;
use common::{run_deck, Results};

const DECK: &str = r#"
reference_temperature = 20.0

[mesh]
rectangle = { r = [50.0, 60.0], z = [0.0, 10.0], divisions = [3, 3] }

[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
thermal_expansion = 1.2e-5

[[step]]
name = "heat"
increments = 2
temperature = 220.0
boundary = [ { set = "bottom", uz = 0.0 } ]
"#;

#[test]
fn uniform_heating_is_stress_free_and_expands_by_alpha_dt() {
    let run = run_deck(DECK, &[], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let strain = 1.2e-5 * 200.0;
    for (x, u) in res.nodes() {
        assert!((u[0] - strain * x[0]).abs() < 1e-10, "u_r at {x:?} = {} vs {}", u[0], strain * x[0]);
        assert!((u[1] - strain * x[1]).abs() < 1e-10, "u_z at {x:?} = {}", u[1]);
    }
    let stress = res.f64s(&format!("{}/stress", res.last_increment()));
    let worst = stress.iter().fold(0.0f64, |m, s| m.max(s.abs()));
    assert!(worst < 1e-6, "stress {worst} MPa in free expansion");
}

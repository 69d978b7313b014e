//! PETSc's own check of the assembled Jacobian against finite differences of the assembled
//! residual (`-snes_test_jacobian`), on 2 ranks, for a model with pressure, thermal strain and
//! prescribed displacements (so eliminated DOFs and off-rank rows are exercised). The ratio
//! ||J - J_fd||_F / ||J||_F printed by PETSc must be below 1e-6 at every Newton iterate.

mod common;
use common::{jacobian_test_ratios, run_deck};

const DECK: &str = r#"
[mesh]
rectangle = { r = [20.0, 40.0], z = [0.0, 10.0], divisions = [8, 4] }

[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
thermal_expansion = 1.2e-5

[[step]]
temperature = 120.0
boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = -0.01 } ]
pressure = [ { surface = "inner", value = 30.0 }, { surface = "top", value = 5.0 } ]
"#;

#[test]
fn assembled_jacobian_matches_finite_differences_on_two_ranks() {
    let run = run_deck(DECK, &[], 2, &["--", "-snes_test_jacobian"]);
    run.assert_ok();
    let out = run.stdout();
    let ratios = jacobian_test_ratios(&out);
    assert!(!ratios.is_empty(), "PETSc printed no Jacobian test:\n{out}");
    for r in &ratios {
        assert!(*r < 1e-6, "||J - Jfd|| / ||J|| = {r:e}\n{out}");
    }
}

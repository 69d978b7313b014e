//! Adaptive increments: a deliberately too-large increment is cut back and then converges; an
//! absurd load ends cleanly with exit code 3, a message naming the step and load factor, and a
//! results file holding every converged increment, none of them a runaway past the limit load.
//! Model: the plastic thick cylinder (a = 100, b = 130, plane strain, sigma_y0 = 300,
//! H = 1000, or H = 0 for the failure), 20 Q8 elements across the wall.

mod common;
use common::{run_deck, Results};

fn deck(hardening: f64, stepping: &str, steps: &str) -> String {
    format!(
        r#"nlgeom = false
[stepping]
{stepping}
[mesh]
rectangle = {{ r = [100.0, 130.0], z = [0.0, 1.0], divisions = [20, 1] }}
[[material]]
name = "steel"
model = "j2"
youngs_modulus = 200000.0
poissons_ratio = 0.3
yield_stress = 300.0
hardening_modulus = {hardening}
{steps}"#
    )
}

#[test]
fn too_large_an_increment_is_cut_back_and_then_converges() {
    // One increment from 0 to 86 MPa (deep into plasticity) with at most 3 Newton iterations
    // per attempt cannot converge at once.
    let steps = r#"[[step]]
increments = 1
boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 } ]
pressure = [ { surface = "inner", value = 86.0 } ]
"#;
    let run = run_deck(&deck(1000.0, "max_newton_iterations = 3", steps), &[], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let cutbacks = res.history("cutbacks");
    let lambda = res.history("load_factor");
    assert!(cutbacks[0] >= 1.0, "the first increment should have needed a cutback: {cutbacks:?}");
    assert_eq!(*lambda.last().unwrap(), 1.0);
    assert!(lambda.windows(2).all(|w| w[1] > w[0]));
    // increments never exceed the requested size (1.0 here) and the run reaches the end
    assert!(res.history("max_equivalent_plastic_strain").last().unwrap() > &0.0);
}

#[test]
fn an_absurd_load_stops_with_exit_3_and_keeps_the_converged_increments() {
    // Perfect plasticity (H = 0): the limit pressure is 90.9 MPa. Step 1 is fine; step 2 asks
    // for ten times the limit.
    let steps = r#"[[step]]
name = "service"
increments = 2
boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 } ]
pressure = [ { surface = "inner", value = 50.0 } ]
[[step]]
name = "burst"
increments = 4
pressure = [ { surface = "inner", value = 900.0 } ]
"#;
    let run = run_deck(&deck(0.0, "min_increment = 1e-3", steps), &[], 1, &[]);
    assert_eq!(run.code(), 3, "stderr:\n{}", run.stderr());
    let err = run.stderr();
    assert!(err.contains("step burst") && err.contains("load factor"), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let res = Results::open(&run.h5);
    let steps = res.history("step");
    let lambda = res.history("load_factor");
    assert_eq!(res.increments().len(), steps.len(), "one history row per stored increment");
    assert_eq!(&steps[..2], &[1.0, 1.0]);
    // every stored increment of step 2 is below the limit load 90.9 MPa: lambda < (90.9-50)/850
    for (s, l) in steps.iter().zip(&lambda).skip(2) {
        assert_eq!(*s, 2.0);
        assert!(*l < (90.9 - 50.0) / 850.0, "converged past the limit load? lambda {l}");
    }
    // the last stored displacement field is readable, and no more than a wall's thickness
    // (the mechanism's runaway past the limit load, 3e9 mm, once passed a relative test)
    let nodes = res.nodes();
    assert!(!nodes.is_empty());
    let largest = nodes.iter().map(|(_, u)| u[0].abs().max(u[1].abs())).fold(0.0, f64::max);
    assert!(largest < 30.0, "a stored displacement of {largest:e} mm");
    // the status file: a line per stored increment, numbered as the file's groups, the
    // cutbacks, and why the run stopped
    let sta = std::fs::read_to_string(run.h5.with_extension("sta")).expect("out.sta beside the results");
    let rows: Vec<&str> = sta.lines().filter(|l| l.trim_start().chars().next().is_some_and(|c| c.is_ascii_digit())).collect();
    assert_eq!(rows.len(), steps.len(), "{sta}");
    let last_number: usize = rows.last().unwrap().split_whitespace().next().unwrap().parse().unwrap();
    assert_eq!(format!("increments/{last_number:06}"), *res.increments().last().unwrap());
    assert!(sta.contains("# step 2 cutback at lambda") && sta.trim_end().ends_with("stopped: the increment would fall below min_increment"), "{sta}");
}

/// Two rings stacked along the axis, `gap` apart: the lower one held at its bottom face, the
/// upper one held only by contact (its pair's extra lines `contact`) and pressed down onto the
/// lower one by 10 MPa on its top face.
fn stacked_rings(gap: f64, contact: &str) -> String {
    format!(
        r#"nlgeom = false
[[mesh.block]]
name = "base"
r = [10.0, 20.0]
z = [0.0, 4.0]
divisions = [4, 2]
[[mesh.block]]
name = "top"
r = [10.0, 20.0]
z = [{z0}, 8.0]
divisions = [4, 2]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[contact]]
name = "seat"
slave = "top_bottom"
master = "base_top"
penalty = 1.0e5
{contact}
[[step]]
name = "press"
increments = 2
boundary = [ {{ set = "base_bottom", uz = 0.0 }} ]
pressure = [ {{ surface = "top_top", value = 10.0 }} ]
"#,
        z0 = 4.0 + gap
    )
}

#[test]
fn a_body_only_open_contact_holds_is_named_with_its_gap() {
    // 0.01 mm apart, nothing fixes the upper ring's axial position until the gap closes: its
    // tangent is singular, Newton jumps, and the run cuts back to the minimum increment. The
    // warning at the step's start and the final error both name the ring and the gap.
    let run = run_deck(&stacked_rings(0.01, ""), &[], 2, &[]);
    assert_eq!(run.code(), 3, "stderr:\n{}", run.stderr());
    let err = run.stderr();
    let named = "(at r = 10, z = 4.01) has no prescribed uz and all its contact is open: 'seat' (smallest gap 0.0100 mm)";
    let warning = err.lines().find(|l| l.starts_with("warning: step 'press'")).unwrap_or_else(|| panic!("no warning:\n{err}"));
    assert!(warning.contains(named), "{warning}");
    let error = err.lines().find(|l| l.starts_with("error:")).unwrap_or_else(|| panic!("no error:\n{err}"));
    assert!(error.contains("at the last converged state the body containing node") && error.contains(named), "{error}");
    // touching at the start, or with the gap closed in the mesh by the pair's adjust, the contact
    // holds it: no warning, and the seat carries the load
    for (gap, contact) in [(0.0, ""), (0.01, "adjust = 0.02")] {
        let run = run_deck(&stacked_rings(gap, contact), &[], 2, &[]);
        run.assert_ok();
        assert!(!run.stderr().contains("warning"), "{}", run.stderr());
        let fz = Results::open(&run.h5).history("reaction_base_bottom_z");
        let expected = 10.0 * (20.0f64.powi(2) - 10.0f64.powi(2)) / 2.0;
        assert!((fz.last().unwrap() - expected).abs() < 1e-6 * expected, "F_z {fz:?} against {expected}");
    }
}

#[test]
fn a_failed_factorisation_says_what_mumps_reported() {
    // 4800 elements, whose factors need several MB, against MUMPS's workspace capped at 1 MB
    // per rank: the factorisation fails, and the error gives MUMPS's code and the remedy
    // instead of a bare DIVERGED_LINEAR_SOLVE.
    let deck = r#"nlgeom = false
[mesh]
rectangle = { r = [100.0, 130.0], z = [0.0, 10.0], divisions = [80, 60] }
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[step]]
increments = 1
boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 } ]
pressure = [ { surface = "inner", value = 50.0 } ]
"#;
    let run = run_deck(deck, &[], 2, &["--", "-mat_mumps_icntl_23", "1"]);
    assert_eq!(run.code(), 3, "stderr:\n{}", run.stderr());
    let err = run.stderr();
    let error = err.lines().find(|l| l.starts_with("error:")).unwrap_or_else(|| panic!("no error:\n{err}"));
    assert!(error.contains("DIVERGED_LINEAR_SOLVE (MUMPS reports INFOG(1) = -19") && error.contains("-mat_mumps_icntl_23"), "{error}");
    // the matrix is as large at any increment: the run stops at the first failure
    assert!(error.contains("a smaller increment cannot help"), "{error}");
    let sta = std::fs::read_to_string(run.h5.with_extension("sta")).expect("out.sta beside the results");
    assert_eq!(sta.matches("cutback at lambda").count(), 1, "{sta}");
    assert!(sta.trim_end().ends_with("stopped: a smaller increment cannot help"), "{sta}");
    assert!(!err.contains("PETSC ERROR") && !err.contains("panicked"), "{err}");
}

/// The runaway check allows for the prescribed motion: a ring lifted 50 mm in one increment
/// (its bottom moved, the rest free: a rigid translation, 2.5 times the ring's 20 mm size) takes
/// no cutback, and every node moves the 50 mm.
#[test]
fn a_rigid_lift_larger_than_the_model_is_no_runaway() {
    let steps = r#"[[step]]
increments = 1
boundary = [ { set = "bottom", uz = 50.0 } ]
"#;
    let deck =
        deck(1000.0, "", steps).replace("r = [100.0, 130.0], z = [0.0, 1.0], divisions = [20, 1]", "r = [100.0, 120.0], z = [0.0, 10.0], divisions = [4, 2]");
    let run = run_deck(&deck, &[], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    assert_eq!(res.history("cutbacks"), [0.0]);
    assert!(res.nodes().iter().all(|(_, u)| (u[1] - 50.0).abs() < 1e-9 && u[0].abs() < 1e-9), "{:?}", res.nodes());
}

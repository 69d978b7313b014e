//! The energy audit written in the history: on an elastic load cycle everything comes back
//! (external work and elastic energy to zero); on the elastoplastic thick cylinder loaded past
//! yield and unloaded, the external work equals the elastic energy plus the plastic work to
//! 1e-3 of the work done, and the plastic work stays put while it unloads; on a shrink fit
//! pushed along its shaft with friction, the work of the push goes into friction and the
//! balance holds to 1e-3 of it; on the quick bellows' load cycle with friction between the
//! plies (heat, pressure, compression in 120 increments and return), to 1e-3 of the largest
//! external work as well (the error is of first order in the increment: the dissipations are
//! backward Euler, the work trapezoidal; 40 increments give 1.3e-3, 80 give 8e-4 to 9e-4).

mod common;
use common::{command_in, run_deck, Results, TIGHT};

fn cylinder(yield_stress: f64, load_increments: usize, unload_increments: usize) -> String {
    format!(
        r#"[mesh]
rectangle = {{ r = [100.0, 130.0], z = [0.0, 1.0], divisions = [8, 1] }}
[[material]]
name = "steel"
model = "j2"
youngs_modulus = 200000.0
poissons_ratio = 0.3
yield_stress = {yield_stress}
hardening_modulus = 1000.0
[[step]]
name = "load"
increments = {load_increments}
boundary = [ {{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = 0.0 }} ]
pressure = [ {{ surface = "inner", value = 84.0 }} ]
[[step]]
name = "unload"
increments = {unload_increments}
pressure = [ {{ surface = "inner", value = 0.0 }} ]
"#
    )
}

/// (external work, elastic, plastic, friction, balance error) per increment.
fn audit(r: &Results) -> Vec<[f64; 5]> {
    let columns =
        ["energy_external_work", "energy_elastic", "energy_plastic_work", "energy_friction_dissipation", "energy_balance_error"].map(|c| r.history(c));
    (0..columns[0].len()).map(|k| std::array::from_fn(|c| columns[c][k])).collect()
}

fn largest_work(rows: &[[f64; 5]]) -> f64 {
    rows.iter().map(|r| r[0].abs()).fold(0.0, f64::max)
}

#[test]
fn an_elastic_load_cycle_gives_back_all_it_took() {
    let run = run_deck(&cylinder(1e9, 4, 4), &[], 1, TIGHT);
    run.assert_ok();
    let rows = audit(&Results::open(&run.h5));
    let peak = largest_work(&rows);
    let end = rows.last().unwrap();
    assert!(peak > 100.0, "work was done: {peak}");
    assert!(end[0].abs() < 1e-9 * peak && end[1].abs() < 1e-9 * peak, "back at zero: {end:?}");
    for r in &rows {
        assert!(r[2] == 0.0 && r[4].abs() < 1e-4 * peak, "{r:?}");
    }
}

#[test]
fn the_plastic_cylinder_balances_its_work_with_elastic_energy_and_plastic_work() {
    let run = run_deck(&cylinder(300.0, 40, 10), &[], 1, &[]);
    run.assert_ok();
    let rows = audit(&Results::open(&run.h5));
    let peak = largest_work(&rows);
    let loaded = rows[39];
    assert!(loaded[2] > 0.05 * loaded[1], "past yield: plastic work {} against elastic {}", loaded[2], loaded[1]);
    for (k, r) in rows.iter().enumerate() {
        assert!(r[4].abs() <= 1e-3 * peak, "#{}: balance error {} of {peak}", k + 1, r[4]);
    }
    // unloading is elastic: the plastic work stays, the elastic energy falls to what the
    // residual stresses hold
    for r in &rows[40..] {
        assert_eq!(r[2], loaded[2]);
    }
    assert!(rows.last().unwrap()[1] < 0.02 * loaded[1] && rows.last().unwrap()[1] > 0.0);
}

#[test]
fn a_pushed_shrink_fit_turns_the_push_into_friction() {
    // the fit and push of tests/friction.rs, segment-integrated, in 40 increments
    let deck = common::pushed_fit_deck(2.0e-4, 40, "friction = 0.2", r#"{ set = "tube_bottom", uz = 0.0 }, { set = "tube_top", uz = 0.0 }"#)
        .replace("integration = \"node-to-segment\"\n", "");
    let run = run_deck(&deck, &[], 1, &[]);
    run.assert_ok();
    let r = Results::open(&run.h5);
    let rows = audit(&r);
    // the fit's increment is the audit's start (the undeformed mesh overlaps)
    let initial = r.history("energy_initial_contact");
    assert!(initial[0] > 50.0, "the fitted state's energy counted as the start: {}", initial[0]);
    let end = rows.last().unwrap();
    let push = end[0] - rows[0][0];
    assert!(push > 0.0 && end[3] > 0.8 * push, "the push's work {push} goes mostly into friction ({})", end[3]);
    for (k, row) in rows.iter().enumerate() {
        assert!((row[4] - rows[0][4]).abs() <= 1e-3 * push, "#{}: balance error {} against the push's work {push}", k + 1, row[4]);
    }
}

#[test]
fn the_quick_bellows_cycle_with_friction_balances_its_energy() {
    let dir = tempfile::tempdir().unwrap();
    let out = command_in(dir.path(), 2)
        .args(["bellows", "--quick", "--friction-plies", "0.2", "--cycle", "--increments", "120", "-q", "-o"])
        .arg(dir.path().join("b.h5"))
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r = Results::open(&dir.path().join("b.h5"));
    let rows = audit(&r);
    let peak = largest_work(&rows);
    let end = rows.last().unwrap();
    assert!(end[2] > 0.5 * end[0] && end[3] > 0.0, "plastic work and friction: {end:?}");
    let worst = rows.iter().map(|row| row[4].abs()).fold(0.0, f64::max);
    println!("quick bellows cycle: worst balance error {:.2e} of the largest external work", worst / peak);
    assert!(worst <= 1e-3 * peak, "balance error {worst} of {peak}");
}

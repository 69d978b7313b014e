//! The default convergence test (CalculiX's and Abaqus's field test) against the residual test
//! (||F|| down by 1e-10 or to round-off) on verification decks: plasticity (a thick cylinder
//! pressed past yield, finite strain), a shrink fit pressurised after fitting (penalty contact)
//! and a shrink fit pushed out with Coulomb friction. Every answer checked moves by less than
//! 0.1 % between the two, and the field test takes fewer Newton iterations.

mod common;
use common::{pushed_fit_deck, run_deck, shrink_fit_deck, Results, PLASTIC_STEEL, TIGHT};

fn plastic_cylinder() -> String {
    format!(
        r#"nlgeom = true
[mesh]
rectangle = {{ r = [100.0, 200.0], z = [0.0, 1.0], divisions = [30, 1] }}
{PLASTIC_STEEL}[[step]]
increments = 20
boundary = [ {{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = 0.0 }} ]
pressure = [ {{ surface = "inner", value = 200.0 }} ]
"#
    )
}

/// Largest difference of `column`'s last value, relative to its magnitude.
fn last_difference(a: &Results, b: &Results, column: &str) -> f64 {
    let (x, y) = (*a.history(column).last().unwrap(), *b.history(column).last().unwrap());
    (x - y).abs() / x.abs().max(f64::MIN_POSITIVE)
}

/// Runs `deck` with both tests; checks the displacement field and the named history columns.
fn compare(name: &str, deck: &str, columns: &[&str]) {
    let field = run_deck(deck, &[], 1, &[]);
    field.assert_ok();
    let residual = run_deck(deck, &[], 1, TIGHT);
    residual.assert_ok();
    let (f, r) = (Results::open(&field.h5), Results::open(&residual.h5));
    let (its_f, its_r): (f64, f64) = (f.history("newton_iterations").iter().sum(), r.history("newton_iterations").iter().sum());
    assert!(its_f < its_r, "{name}: the field test should save iterations: {its_f} against the residual test's {its_r}");
    let (du, umax) = common::displacement_difference(&f, &r);
    assert!(du <= 1e-3 * umax, "{name}: displacements differ by {du:e} (largest {umax:e})");
    for c in columns {
        let d = last_difference(&f, &r, c);
        assert!(d < 1e-3, "{name}: {c} differs by {d:e}");
    }
    eprintln!("{name}: Newton iterations {its_f} (field) / {its_r} (residual), displacement difference {:.1e} of the largest", du / umax);
}

#[test]
fn the_field_test_moves_plastic_answers_by_less_than_a_thousandth() {
    compare("plastic cylinder", &plastic_cylinder(), &["max_equivalent_plastic_strain", "energy_plastic_work", "energy_external_work"]);
}

#[test]
fn the_field_test_moves_contact_answers_by_less_than_a_thousandth() {
    let pressure = "[[step]]\nname = \"pressure\"\nincrements = 4\nboundary = [ { set = \"inner_bottom\", uz = 0.0 }, { set = \"inner_top\", uz = 0.0 }, { set = \"outer_bottom\", uz = 0.0 }, { set = \"outer_top\", uz = 0.0 } ]\npressure = [ { surface = \"inner_inner\", value = 50.0 } ]\n";
    compare("shrink fit and pressure", &shrink_fit_deck(true, "penalty = 1.0e5", pressure), &["contact_fit_force", "energy_external_work"]);
    let tube = r#"{ set = "tube_bottom", uz = 0.0 }, { set = "tube_top", uz = 0.0 }"#;
    compare(
        "pushed fit with friction",
        &pushed_fit_deck(2.0e-4, 10, "friction = 0.2", tube),
        &["contact_fit_force", "reaction_ring_bottom_z", "energy_friction_dissipation"],
    );
}

#[test]
fn the_deck_chooses_the_test_and_the_flag_overrides_it() {
    let deck = plastic_cylinder().replace("[[step]]", "[stepping]\nconvergence = \"residual\"\n[[step]]");
    let from_deck = run_deck(&deck, &[], 1, &[]);
    from_deck.assert_ok();
    let from_flag = run_deck(&plastic_cylinder(), &[], 1, TIGHT);
    from_flag.assert_ok();
    let overridden = run_deck(&deck, &[], 1, &["--convergence", "field"]);
    overridden.assert_ok();
    let its = |run: &common::Run| -> f64 { Results::open(&run.h5).history("newton_iterations").iter().sum() };
    assert_eq!(its(&from_deck), its(&from_flag));
    assert!(its(&overridden) < its(&from_deck));
    let bad = run_deck(&plastic_cylinder().replace("[[step]]", "[stepping]\nconvergence = \"loose\"\n[[step]]"), &[], 1, &[]);
    common::assert_rejected(&bad, &["loose"]);
}

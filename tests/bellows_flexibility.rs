//! The bellows' lateral and angular spring rates by harmonic perturbations (`slideline bellows
//! --lateral 5 --angular 1`), on the default joint at rest (no pressure, heat or stroke: the run's
//! own end state is then the rest state too). References:
//! - statics: the lateral force leaves at the fixed end (1e-6), and the two ends' moments, each
//!   about its own centre, add up to the force times the 400 mm between them (1e-3; measured
//!   2.3085e7 + 2.3069e7 = 1.1539e5 x 400 N mm);
//! - the beam analogy of EJMA (10th ed.; `../shared/bellows-code/worked-examples.md`, where it
//!   reproduces a printed report): lateral rate 3 K Dm^2 / (2 Lb^2), angular K Dm^2 pi / 1440
//!   per degree, with the joint's own axial rate K by the same perturbations; the code column is
//!   recomputed here from the printed K, Dm and Lb, and the finite elements must sit within 15 %
//!   of it (measured 0.92 lateral, 1.01 angular: not tuned);
//! - the angular case rotates the end about the bellows' centre, the codes' pure rotation: the
//!   lateral force left is below 2 % of moment / (half the joint's length) (measured 0.7 %),
//!   and the moving end's moment, about that centre (z = 200 mm: the joint is symmetric), is
//!   the fixed end's less that force times the 200 mm between (1e-3 of the lever);
//! - 1 and 2 ranks agree to 1e-8.

mod common;
use common::{command_in, Results};

const FLAGS: &[&str] = &["--displacement", "0", "--pressure", "0", "--temperature", "20", "--increments", "1", "--lateral", "5", "--angular", "1", "--quiet"];

fn flexibility(dir: &std::path::Path, ranks: usize) -> (String, Results) {
    let h5 = dir.join(format!("flex{ranks}.h5"));
    let out = command_in(dir, ranks).args(["bellows", "-o"]).arg(&h5).args(FLAGS).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{text}\n{}", String::from_utf8_lossy(&out.stderr));
    let section = text.split("flexibility: harmonic").nth(1).unwrap_or_else(|| panic!("no flexibility section:\n{text}")).to_string();
    (section, Results::open(&h5))
}

/// The numbers of a row of the table (after its label).
fn row(section: &str, starts: &str) -> Vec<f64> {
    let line = section.lines().find(|l| l.trim_start().starts_with(starts)).unwrap_or_else(|| panic!("no row {starts:?} in\n{section}"));
    let label_end = line.rfind(|c: char| c.is_alphabetic() || c == ')').unwrap() + 1;
    line[label_end..].split_whitespace().filter_map(|w| w.parse().ok()).collect()
}

fn resultant(r: &Results, step: &str, set: &str, name: &str) -> f64 {
    r.file.group(&format!("perturbations/{step}/reactions/{set}")).unwrap().attr(name).unwrap().read_scalar::<f64>().unwrap()
}

#[test]
fn the_default_joint_at_rest_against_statics_the_beam_analogy_and_two_ranks() {
    let dir = tempfile::tempdir().unwrap();
    let (section, r) = flexibility(dir.path(), 1);
    // statics of the lateral offset
    let (force, fixed_force) = (resultant(&r, "lateral", "moving_end", "lateral_force_ring"), resultant(&r, "lateral", "fixed_end", "lateral_force_ring"));
    assert!((force + fixed_force).abs() < 1e-6 * force.abs(), "{force} {fixed_force}");
    let moments = resultant(&r, "lateral", "moving_end", "moment_ring").abs() + resultant(&r, "lateral", "fixed_end", "moment_ring").abs();
    assert!((moments / (force.abs() * 400.0) - 1.0).abs() < 1e-3, "moments {moments} against F L {}", force.abs() * 400.0);
    // the beam analogy, recomputed from the printed axial rate and dimensions
    let k = row(&section, "axial rate")[0];
    let dims = section.lines().find(|l| l.contains("Dm ")).unwrap();
    let number_after = |key: &str| -> f64 { dims.split(key).nth(1).unwrap().split_whitespace().next().unwrap().parse().unwrap() };
    let (dm, lb) = (number_after("Dm "), number_after("Lb "));
    let lateral = row(&section, "lateral rate");
    let angular = row(&section, "angular rate");
    let (lateral_code, angular_code) = (3.0 * k * dm * dm / (2.0 * lb * lb), k * dm * dm * std::f64::consts::PI / 1440.0);
    assert!((lateral[1] / lateral_code - 1.0).abs() < 1e-3, "{lateral:?} against {lateral_code}");
    assert!((angular[1] / angular_code - 1.0).abs() < 1e-3, "{angular:?} against {angular_code}");
    for (what, values) in [("lateral", &lateral), ("angular", &angular)] {
        let ratio = values[0] / values[1];
        eprintln!("{what} rate: FE {} against the beam analogy's {}: {ratio:.3}", values[0], values[1]);
        assert!((ratio - 1.0).abs() < 0.15, "{what}: FE/code {ratio}\n{section}");
        // at rest both columns are the same state
        assert!((values[3] / values[0] - 1.0).abs() < 1e-6, "{what}: at rest {} and operating {}", values[0], values[3]);
    }
    assert!((lateral[0] - force.abs() / 5.0).abs() < 1e-3 * lateral[0], "the printed rate is the file's force over 5 mm");
    // the angular case is (nearly) a pure rotation
    let (shear, moment) = (resultant(&r, "angular", "fixed_end", "lateral_force_ring"), resultant(&r, "angular", "fixed_end", "moment_ring"));
    assert!(shear.abs() < 0.02 * moment.abs() / 200.0, "lateral force {shear} N with moment {moment} N mm");
    let about_centre = resultant(&r, "angular", "moving_end", "moment_ring");
    let lever = (moment.abs() - about_centre.abs()) / shear.abs();
    assert!((lever / 200.0 - 1.0).abs() < 1e-3, "moments {moment} and {about_centre} N mm with {shear} N: lever {lever} mm");
    // the sleeve's contact, left out of the rates, is reported apart
    assert!(row(&section, "lateral force the guide sleeve")[0] > 0.0, "{section}");

    let (_, r2) = flexibility(dir.path(), 2);
    for (step, set, name) in
        [("axial", "moving_end", "axial_force_ring"), ("lateral", "moving_end", "lateral_force_ring"), ("angular", "moving_end", "moment_ring")]
    {
        let (a, b) = (resultant(&r, step, set, name), resultant(&r2, step, set, name));
        assert!((a - b).abs() < 1e-8 * a.abs(), "{step}: {a} on one rank, {b} on two");
    }
}

#[test]
fn a_zero_movement_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (flag, needle) in [
        ("--lateral", "--lateral 0: give a nonzero movement of at most 144 mm in size"),
        ("--angular", "--angular 0: give a nonzero movement of at most 45 degrees in size"),
    ] {
        let out = command_in(dir.path(), 1).args(["bellows", flag, "0", "-o"]).arg(dir.path().join("x.h5")).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(needle), "{stderr}");
    }
}

/// A restart leaves the perturbations unaffected: continuing the quick joint's run from an
/// increment in its stroke gives the same rates as the run in one go (1e-10: the general steps
/// continue bit for bit); from its very end (no increment left to converge: the state it resumes
/// is the base, its stress recomputed by the return map from the committed state, measured
/// 1.2e-10 off) within 1e-8.
#[test]
fn a_restart_gives_the_same_perturbations() {
    let dir = tempfile::tempdir().unwrap();
    let flags = ["--quick", "--increments", "12", "--lateral", "5", "--angular", "1", "--quiet"];
    let run = |extra: &[&str], output: &str| {
        let out = command_in(dir.path(), 1).current_dir(dir.path()).arg("bellows").args(flags).args(extra).args(["-o", output]).output().unwrap();
        assert!(out.status.success(), "{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
        Results::open(&dir.path().join(output))
    };
    let full = run(&[], "full.h5");
    for (extra, output, tolerance) in
        [(&["--restart", "full.h5", "--increment", "8"][..], "from8.h5", 1e-10), (&["--restart", "full.h5"][..], "from_end.h5", 1e-8)]
    {
        let again = run(extra, output);
        for (step, name) in
            [("axial", "axial_force_ring"), ("lateral", "lateral_force_ring"), ("angular", "moment_ring"), ("lateral_as_built", "lateral_force_ring")]
        {
            let (a, b) = (resultant(&full, step, "moving_end", name), resultant(&again, step, "moving_end", name));
            assert!((a - b).abs() <= tolerance * a.abs(), "{output}, {step}: {a} in one go, {b} restarted");
        }
    }
}

/// `--squirm` on the default joint at rest: the column instability by a buckling analysis lies
/// between EJMA's factored column formula and the unfactored equivalent column it comes from
/// (measured 22.1 < 63.0 < 129.8 MPa: the code is conservative here, by 2.9), the code column
/// recomputed from the printed Kb; the harmonics above, n = 2 to 4, each with its pressure and
/// the lowest of all named; 1 and 2 ranks agree to 1e-8 (the follower-pressure buckling itself
/// is checked against Palmer & Baldry's pipe in tests/eigen_steps.rs).
#[test]
fn the_default_joint_squirms_between_the_code_and_the_equivalent_column() {
    let dir = tempfile::tempdir().unwrap();
    let run = |ranks: usize| {
        let h5 = dir.path().join(format!("squirm{ranks}.h5"));
        let flags = ["--displacement", "0", "--pressure", "0", "--temperature", "20", "--increments", "1", "--squirm", "--quiet"];
        let out = command_in(dir.path(), ranks).args(["bellows", "-o"]).arg(&h5).args(flags).output().unwrap();
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(out.status.success(), "{text}\n{}", String::from_utf8_lossy(&out.stderr));
        (text.split("stability: buckling").nth(1).unwrap_or_else(|| panic!("no stability section:\n{text}")).to_string(), Results::open(&h5))
    };
    let (section, r) = run(1);
    let kb = row(&section, "axial rate Kb")[0];
    let squirm = row(&section, "column instability (squirm)")[0];
    let code = row(&section, "EJMA column formula")[0];
    let column = row(&section, "the equivalent column")[0];
    let (n, q) = (6.0, 24.0);
    assert!((code / (0.34 * std::f64::consts::PI * kb / (n * q)) - 1.0).abs() < 1e-3, "{code} against Kb {kb}");
    assert!((column / code - 2.0 / 0.34).abs() < 1e-2, "{column} {code}");
    assert!(code < squirm && squirm < column, "squirm {squirm} MPa against the code's {code} and the equivalent column's {column}\n{section}");
    // every harmonic that can govern, n = 0 to 4, and the lowest of them named
    let mut harmonics = vec![(1, squirm), (0, row(&section, "in-plane instability, mode 0")[0])];
    for n in 2..=3 {
        harmonics.push((n, row(&section, &format!("crest and sidewall mode n = {n}"))[0]));
    }
    assert!(section.contains("crest and sidewall mode n = 4"), "{section}");
    let (n, p) = harmonics.iter().copied().min_by(|a, b| a.1.total_cmp(&b.1)).unwrap();
    let lowest = section.lines().find(|l| l.contains("the lowest over the harmonics")).unwrap();
    assert!(lowest.contains(&format!("n = {n}: {p:.2}")), "{lowest} against {harmonics:?}");
    let (_, r2) = run(2);
    let p = |r: &Results| r.f64s("perturbations/squirm/critical_pressure_wetted")[0];
    assert!((p(&r) - p(&r2)).abs() < 1e-8 * p(&r), "{} on one rank, {} on two", p(&r), p(&r2));
}

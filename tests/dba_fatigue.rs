//! `slideline check DECK` with `[design_by_analysis.fatigue]`: fatigue by elastic-plastic
//! analysis (ASME VIII-2 5.5.4) on a case whose answer does not depend on the code's
//! plasticity: a solid bar (r 0..5, z 0..10 mm, small strain, radially free) whose end is
//! cycled between axial strains +-eps_a, of a steel with three Armstrong-Frederick
//! backstresses. In uniaxial stress eps = sigma / E + eps_p along the bar, so whatever loop the
//! material draws, the effective strain range sigma range / E + plastic strain range is the
//! total strain range 2 eps_a, and S_alt = E eps_a; the permissible cycles are those of
//! ASME III Figure I-9.2 (2010; the austenitic curve of VIII-2 Annex 3-F) at
//! S_alt E_FC / E, interpolated log-log between its tabulated points (N 500 -> 974 MPa,
//! 1000 -> 745 MPa). With E = 195 GPa, eps_a = 0.4 %: S_alt = 780 MPa on the curve at
//! 780.49 MPa, N = 500 x 2^(ln(974 / 780.49) / ln(974 / 745)) = 886.6 cycles. Checked:
//! the range within 1e-6, N within 1e-6, the damage of 800 design cycles (0.902, PASS) and of
//! 1000 (1.128, FAIL); and the stabilised loop is plastic (over the last cycle the equivalent
//! plastic strain grows by more than half the total strain range: a check that read the
//! elastic stress range alone would be off by more than a quarter).

mod common;
use common::{assert_rejected, command_in, Results, Run};

const E: f64 = 195_000.0;
const AMPLITUDE: f64 = 0.004;
const LENGTH: f64 = 10.0;

fn bar(design_cycles: f64, extra: &str) -> String {
    let d = AMPLITUDE * LENGTH;
    format!(
        r#"nlgeom = false
[mesh]
rectangle = {{ r = [0.0, 5.0], z = [0.0, {LENGTH}], divisions = [2, 2] }}
[[material]]
name = "steel"
model = "j2"
youngs_modulus = {E}
poissons_ratio = 0.3
yield_stress = 150.0
backstresses = [ {{ modulus = 60000.0, recall = 500.0 }}, {{ modulus = 15000.0, recall = 80.0 }}, {{ modulus = 2000.0 }} ]
[[step]]
name = "pull"
increments = 4
boundary = [ {{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = {d} }} ]
[[step]]
name = "push"
increments = 8
boundary = [ {{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = {m} }} ]
[[step]]
name = "pull back"
increments = 8
boundary = [ {{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = {d} }} ]
[design_by_analysis]
fatigue = {{ cycle = ["push", "pull back"], cycles = 3, design_cycles = {design_cycles}{extra} }}
"#,
        m = -d
    )
}

fn check(deck: &str) -> Run {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("bar.toml"), deck).unwrap();
    let h5 = dir.path().join("out.h5");
    let output = command_in(dir.path(), 1).current_dir(dir.path()).args(["check", "bar.toml", "-o"]).arg(&h5).arg("--quiet").output().expect("slideline");
    Run { dir, output, h5 }
}

/// ASME III Fig. I-9.2 (2010), the two points around 780 MPa, E_FC 195 123 MPa.
fn curve_cycles(s_alt: f64) -> f64 {
    let s = s_alt * 195_123.0 / E;
    let ((n0, s0), (n1, s1)) = ((500.0f64, 974.0f64), (1000.0f64, 745.0f64));
    assert!(s < s0 && s > s1, "{s} between the points");
    (n0.ln() + (s.ln() - s0.ln()) / (s1.ln() - s0.ln()) * (n1.ln() - n0.ln())).exp()
}

#[test]
fn a_bar_cycled_between_strains_reads_the_curve_at_e_times_its_strain_amplitude() {
    let expected_n = curve_cycles(E * AMPLITUDE);
    assert!((expected_n - 886.6).abs() < 0.1, "{expected_n}");
    for (design, passes) in [(800.0, true), (1000.0, false)] {
        let run = check(&bar(design, ""));
        run.assert_ok();
        let f = Results::open(&run.h5);
        let figures = f.f64s("dba/figure");
        let verdicts: Vec<String> =
            f.file.dataset("dba/verdict").unwrap().read_raw::<hdf5::types::VarLenUnicode>().unwrap().iter().map(|s| s.to_string()).collect();
        // rows: the strain range, the alternating stress, the damage
        let (range, s_alt, damage) = (figures[0], figures[1], figures[2]);
        assert!((range / (2.0 * AMPLITUDE) - 1.0).abs() < 1e-6, "effective strain range {range}, expected {}", 2.0 * AMPLITUDE);
        assert!((s_alt / (E * AMPLITUDE) - 1.0).abs() < 1e-6, "S_alt {s_alt}");
        let n = design / damage;
        assert!((n / expected_n - 1.0).abs() < 1e-6, "N {n} against {expected_n}");
        assert_eq!(verdicts[2], if passes { "PASS" } else { "FAIL" }, "{}", run.stdout());
        assert!(run.stdout().contains("fatigue, elastic-plastic"), "{}", run.stdout());
        // the loop is plastic
        let fatigue = Results::open(&run.dir.path().join("out_fatigue.h5"));
        let ep = fatigue.history("max_equivalent_plastic_strain");
        let last_cycle = ep[ep.len() - 1] - ep[ep.len() - 17];
        assert!(last_cycle > 0.5 * 2.0 * AMPLITUDE, "plastic strain accumulated over the last cycle: {last_cycle}");
    }
}

#[test]
fn bad_fatigue_tables_are_named() {
    for (extra, needles) in [
        (", curve = [[10.0, 500.0], [100.0, 600.0]], curve_modulus = 2e5", vec!["fatigue.curve", "point 2"]),
        (", curve = [[10.0, 500.0], [100.0, 400.0]]", vec!["fatigue.curve", "curve_modulus"]),
        (", cycles = 1", vec!["fatigue.cycles", "at least 2"]),
    ] {
        let deck = bar(800.0, extra).replace(", cycles = 3", "");
        let run = check(&deck);
        assert_rejected(&run, &needles);
    }
    assert_rejected(&check(&bar(0.0, "")), &["fatigue.design_cycles"]);
    assert_rejected(&check(&bar(800.0, "").replace("[\"push\", \"pull back\"]", "[\"push\"]")), &["fatigue.cycle", "last general steps"]);
}

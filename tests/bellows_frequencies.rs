//! The bellows' natural frequencies (`slideline bellows --frequencies`), on the default joint
//! at rest (no pressure, heat or stroke: the run's end state is the rest state too), both
//! tubes' ends held. References, evaluated with the joint's own axial rate Kb by the same
//! perturbations and the convolutions' live mass m (5.539 kg, the metal alone):
//! - the first axial mode against a spring with its mass spread along it, fixed at both ends,
//!   (1/2) sqrt(Kb / m) (Blevins 8-16): within 3 % (measured 371.0 against 366.4 Hz, 1.012),
//!   and the three lowest modes at 1 : 2 : 3 as the rod's (within 2 %);
//! - the first lateral mode against a clamped Rayleigh beam with the equivalent bending
//!   stiffness Kb Lb Dm^2 / 8 of EJMA's analogy and the convolutions' rotary inertia m Dm^2 /
//!   8: within 3 % (measured 703.8 against 696.1 Hz, 1.011); EJMA's beam without the rotary
//!   inertia is three times too high for a bellows as wide as it is long (ratio below 0.4,
//!   measured 0.32);
//! - the analogies' printed values recomputed here from the printed Kb and the geometry (1e-3);
//! - 1 and 2 ranks agree to 1e-8; four times the density (`--density`) halves every frequency.

mod common;
use common::{command_in, Results};
use std::f64::consts::PI;

const FLAGS: &[&str] = &["--displacement", "0", "--pressure", "0", "--temperature", "20", "--increments", "1", "--frequencies", "--quiet"];

fn frequencies(dir: &std::path::Path, ranks: usize, more: &[&str]) -> (Vec<(String, f64)>, Results) {
    let h5 = dir.join(format!("modes{ranks}{}.h5", if more.is_empty() { "" } else { "_more" }));
    let out = command_in(dir, ranks).args(["bellows", "-o"]).arg(&h5).args(FLAGS).args(more).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{text}\n{}", String::from_utf8_lossy(&out.stderr));
    let section = text.split("natural frequencies: the joint").nth(1).unwrap_or_else(|| panic!("no frequencies section:\n{text}"));
    // `post FILE` prints the table again, word for word
    let post = command_in(dir, 1).arg("post").arg(&h5).output().unwrap();
    let again = String::from_utf8_lossy(&post.stdout);
    let table = |t: &str| t.split("natural frequencies: the joint").nth(1).map(|p| p.split("\n\n").next().unwrap().to_string());
    assert_eq!(table(&again), table(&text), "post FILE:\n{again}");
    // each row: its label and its at-rest value (the next to last column)
    let rows = section
        .lines()
        .skip(2)
        .take_while(|l| !l.trim_start().starts_with("live mass"))
        .map(|l| {
            let words: Vec<&str> = l.split_whitespace().collect();
            (l.trim().to_string(), words[words.len() - 2].parse::<f64>().unwrap_or(f64::NAN))
        })
        .collect();
    (rows, Results::open(&h5))
}

fn value(rows: &[(String, f64)], starts: &str, nth: usize) -> f64 {
    rows.iter().filter(|(l, _)| l.starts_with(starts)).nth(nth).unwrap_or_else(|| panic!("no row {starts:?} ({nth}) in {rows:?}")).1
}

#[test]
fn the_joint_at_rest_rings_as_a_spring_axially_and_as_a_rayleigh_beam_laterally() {
    let dir = tempfile::tempdir().unwrap();
    let (rows, r) = frequencies(dir.path(), 1, &[]);
    let kb = value(&rows, "axial rate Kb", 0);
    // the default joint: Dm = 320 + 20 + 2 = 342 mm, Lb = 6 x 24 mm, two 1 mm plies, U-shaped
    // convolutions of torus radius 6 and height 20, AISI 304 at 8.0e-9 t/mm^3
    let (dm, lb) = (342.0, 144.0);
    let mass = 8.0e-9 * PI * dm * 2.0 * 1.0 * 6.0 * (2.0 * PI * 6.0 + 2.0 * (20.0 - 12.0));
    let spring = 0.5 * (kb / mass).sqrt();
    assert!((value(&rows, "spring analogy", 0) / spring - 1.0).abs() < 1e-3, "{rows:?}");
    let axial = value(&rows, "first axial mode", 0);
    assert!((axial / spring - 1.0).abs() < 0.03, "axial {axial} Hz against the spring's {spring}");
    let modes = r.f64s("perturbations/axial_modes/frequencies");
    for (k, f) in modes.iter().enumerate() {
        assert!((f / (modes[0] * (k + 1) as f64) - 1.0).abs() < 0.02, "axial modes {modes:?}");
    }
    let beam = 4.730_040_7f64.powi(2) / (2.0 * PI) * (dm / lb) * (kb / (8.0 * mass)).sqrt();
    assert!((value(&rows, "clamped beam", 0) / beam - 1.0).abs() < 1e-3, "{rows:?}");
    let lateral = value(&rows, "first lateral mode", 0);
    let rayleigh = value(&rows, "the same beam with the rotary inertia", 0);
    assert!((lateral / rayleigh - 1.0).abs() < 0.03, "lateral {lateral} Hz against the Rayleigh beam's {rayleigh}");
    assert!(lateral / beam < 0.4, "lateral {lateral} Hz against EJMA's beam {beam}");
    // the mode shape's picture beside the file
    assert!(dir.path().join("modes1_lateral_modes_mode.png").exists());

    let (_, r2) = frequencies(dir.path(), 2, &[]);
    for step in ["axial_modes", "lateral_modes"] {
        let (a, b) = (r.f64s(&format!("perturbations/{step}/frequencies")), r2.f64s(&format!("perturbations/{step}/frequencies")));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-8 * x, "{step}: {x} on one rank, {y} on two");
        }
    }
}

/// `--density`: four times the mass halves every frequency (the stiffness unchanged, 1e-9);
/// a density of zero is refused before any work.
#[test]
fn four_times_the_density_halves_the_frequencies() {
    let dir = tempfile::tempdir().unwrap();
    let (_, light) = frequencies(dir.path(), 1, &[]);
    let (_, heavy) = frequencies(dir.path(), 1, &["--density", "3.2e-8"]);
    for step in ["axial_modes", "lateral_modes"] {
        let (a, b) = (light.f64s(&format!("perturbations/{step}/frequencies")), heavy.f64s(&format!("perturbations/{step}/frequencies")));
        for (x, y) in a.iter().zip(&b) {
            assert!((y / x - 0.5).abs() < 1e-9, "{step}: {x} Hz, then {y} Hz");
        }
    }
    let out = command_in(dir.path(), 1).args(["bellows", "--density", "0", "--frequencies"]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("density must be > 0"), "{err}");
}

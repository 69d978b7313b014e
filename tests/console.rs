//! What a run prints under mpirun: one short line per increment (at most 100 characters: step,
//! increment, load factor, Newton iterations, the largest axial reaction, wall time); the long
//! line with `--verbose`; with `--monitor` a line per Newton iteration, the field test's
//! largest residual force and correction against their bounds (or ||F|| under the residual
//! test). Seen failing before: the lines were 150-310 characters and there was no monitor.

mod common;
use common::{command_in, shrink_fit_deck};

fn run(extra: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("fit.toml");
    std::fs::write(&deck, shrink_fit_deck(true, "penalty = 1e5", "")).unwrap();
    let out = command_in(dir.path(), 2).arg("run").arg(&deck).arg("-o").arg(dir.path().join("fit.h5")).args(extra).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{text}{}", String::from_utf8_lossy(&out.stderr));
    text
}

fn increment_lines(text: &str) -> Vec<&str> {
    text.lines().filter(|l| l.starts_with("step ") && l.contains(" inc ")).collect()
}

#[test]
fn short_lines_under_mpirun_long_ones_on_request_and_a_newton_monitor() {
    let text = run(&[]);
    let lines = increment_lines(&text);
    assert!(!lines.is_empty(), "{text}");
    for line in &lines {
        assert!(line.len() <= 100, "a {}-character line: {line}", line.len());
        assert!(line.contains("newton") && line.contains("F_z ") && line.trim_end().ends_with(" s"), "{line}");
        // the full ring's force, the set named whole (it was cut to 10 characters, "inner_bott")
        assert!(line.contains(" N ring ") && line.contains("F_z inner_bottom "), "{line}");
    }
    assert!(!text.contains("    newton "), "no monitor unless asked:\n{text}");

    let verbose = run(&["--verbose"]);
    let long = increment_lines(&verbose);
    assert_eq!(long.len(), lines.len());
    assert!(long.iter().all(|l| l.contains("ksp") && l.contains("|F|") && l.contains("contact")), "{verbose}");

    let monitored = run(&["--monitor", "--quiet"]);
    let iterations: Vec<&str> = monitored.lines().filter(|l| l.starts_with("    newton ")).collect();
    assert!(iterations.iter().any(|l| l.contains("r_max") && l.contains("(bound") && l.contains("c_max")), "{monitored}");
    assert!(iterations.iter().filter(|l| l.ends_with("converged")).count() >= lines.len(), "each increment ends converged:\n{monitored}");

    let residual = run(&["--monitor", "--quiet", "--convergence", "residual"]);
    assert!(residual.lines().any(|l| l.starts_with("    newton ") && l.contains("||F||") && l.contains("round-off floor")), "{residual}");
}

//! `slideline penalty-study` on 2 ranks:
//! - the shrink fit (a deck): the largest penetration falls as the penalty rises, by about the
//!   penalty ratio (p / eps at the same interface pressure), and the summary holds a row per run;
//! - a coarse, short bellows (2 penalties): the HDF5 summary holds one row per penalty with
//!   every field, each run's history is in its group, and the plots and recommendation exist.

mod common;
use common::{command_in, shrink_fit_deck};

const COLUMNS: [&str; 15] = [
    "penalty",
    "augmented",
    "converged",
    "reached_step",
    "reached_load_factor",
    "increments",
    "newton_iterations",
    "newton_per_increment",
    "linear_iterations",
    "cutbacks",
    "wall_time",
    "max_penetration",
    "relative_penetration",
    "reaction",
    "reaction_difference",
];

fn summary(path: &std::path::Path, column: &str) -> Vec<f64> {
    let f = hdf5::File::open(path).unwrap();
    f.dataset(&format!("summary/{column}")).unwrap_or_else(|e| panic!("summary/{column}: {e}")).read_raw::<f64>().unwrap()
}

/// Runs `penalty-study --deck DECK ARGS... -o study.h5` on `ranks` ranks in `dir`: the study
/// file and the printed output; panics with the output unless it succeeded.
fn study_deck(dir: &std::path::Path, ranks: usize, deck: &std::path::Path, args: &[&str]) -> (std::path::PathBuf, String) {
    let study = dir.join("study.h5");
    let out = command_in(dir, ranks).args(["penalty-study", "--deck"]).arg(deck).args(args).arg("-o").arg(&study).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    (study, stdout)
}

/// The shrink fit deck with a penalty each study run replaces, written in `dir`.
fn fit_deck(dir: &std::path::Path) -> std::path::PathBuf {
    let deck = dir.join("fit.toml");
    std::fs::write(&deck, shrink_fit_deck(true, "penalty = 1.0", "")).unwrap();
    deck
}

#[test]
fn shrink_fit_penetration_falls_as_the_penalty_rises() {
    let dir = tempfile::tempdir().unwrap();
    let (study, stdout) = study_deck(dir.path(), 2, &fit_deck(dir.path()), &["--reaction", "outer_top", "--penalties", "1e3,1e4,1e5"]);
    let penetration = summary(&study, "max_penetration");
    assert_eq!(penetration.len(), 3);
    for w in penetration.windows(2) {
        // 10 x the penalty: about a tenth of the penetration
        assert!(w[1] < 0.2 * w[0] && w[1] > 0.05 * w[0], "{penetration:?}");
    }
    assert!(summary(&study, "converged").iter().all(|&c| c == 1.0), "{stdout}");
    assert!(stdout.contains("recommendation: penalty"), "{stdout}");
}

#[test]
fn coarse_bellows_study_has_a_row_per_penalty() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("bellows_study.h5");
    let out = command_in(dir.path(), 2)
        .args(["penalty-study", "--quick", "--displacement", "5", "--increments", "5", "--penalties", "1e3,1e4", "-q", "-o"])
        .arg(&study)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    for column in COLUMNS {
        let values = summary(&study, column);
        assert_eq!(values.len(), 2, "{column}");
        assert!(values.iter().all(|v| v.is_finite()), "{column}: {values:?}");
    }
    assert_eq!(summary(&study, "penalty"), vec![1e3, 1e4]);
    let pen = summary(&study, "max_penetration");
    assert!(pen[1] < pen[0], "{pen:?}");
    let f = hdf5::File::open(&study).unwrap();
    let runs = f.group("runs").unwrap().member_names().unwrap();
    assert_eq!(runs.len(), 2);
    for run in &runs {
        let steps = f.dataset(&format!("runs/{run}/history/step")).unwrap().read_raw::<f64>().unwrap();
        assert_eq!(*steps.last().unwrap(), 2.0, "{run} reached the compression step's end");
    }
    for png in ["iterations", "penetration", "reaction"] {
        assert!(dir.path().join(format!("bellows_study_{png}.png")).exists(), "{png}");
    }
    assert!(stdout.contains("recommendation:"), "{stdout}");
}

/// An .inp deck that `slideline run` reads is studied as well (CalculiX's shrink fit of
/// tests/data/inp, its set names as the deck spells them).
#[test]
fn a_calculix_deck_is_studied_as_run_reads_it() {
    let dir = tempfile::tempdir().unwrap();
    let (study, stdout) = study_deck(dir.path(), 1, &common::data("inp/shrink_fit.inp"), &["--reaction", "RING_TOP", "--penalties", "1e4,1e5"]);
    assert!(stdout.contains("note: "), "the deck's reading notes are printed: {stdout}");
    assert_eq!(summary(&study, "converged"), vec![1.0, 1.0], "{stdout}");
}

/// The augmented-Lagrangian reference is driven below the stiffest plain run's penetration:
/// it does augment, and it penetrates least.
#[test]
fn the_augmented_reference_augments_past_the_stiffest_penalty() {
    let dir = tempfile::tempdir().unwrap();
    let (study, _) = study_deck(dir.path(), 1, &fit_deck(dir.path()), &["--reaction", "outer_top", "--penalties", "1e3,1e4", "--augmented"]);
    let (augmented, augmentations, penetration) = (summary(&study, "augmented"), summary(&study, "augmentations"), summary(&study, "max_penetration"));
    assert_eq!(augmented, vec![0.0, 0.0, 1.0]);
    assert!(augmentations[2] > 0.0 && augmentations[..2].iter().all(|&a| a == 0.0), "{augmentations:?}");
    assert!(penetration[2] < 0.6 * penetration[1], "the reference penetrates least: {penetration:?}");
}

/// A study that cannot make sense is refused before any run, with exit 2 and one line, on 2
/// ranks: an absurd count of runs (`--per-decade 100000` started 400 001), a penalty given
/// twice (it ended with exit 1 on HDF5's "name already exists"), a tolerance that is no
/// tolerance (accepted), an output in a directory that cannot be written (rank 1 waited
/// forever), and a study file (with its runs directory) that another study is writing.
#[test]
fn a_study_that_cannot_make_sense_is_refused_before_any_run() {
    let dir = tempfile::tempdir().unwrap();
    let deck = fit_deck(dir.path());
    let readonly = dir.path().join("readonly");
    std::fs::create_dir(&readonly).unwrap();
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    std::fs::write(dir.path().join("busy.lock"), format!("host {} pid {}\n", host.trim(), std::process::id())).unwrap();
    let is_root = std::process::Command::new("id").arg("-u").output().is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0");
    let mut cases = vec![
        (vec!["--penalties", "1e2..1e6", "--per-decade", "100000", "-o", "s.h5"], "more than 100"),
        (vec!["--penalties", "1e4,1e4", "-o", "s.h5"], "are the same run"),
        (vec!["--penalties", "1e3,1e4", "--tolerance=-1", "-o", "s.h5"], "--tolerance -1"),
        (vec!["--penalties", "1e3,1e4", "--tolerance", "nan", "-o", "s.h5"], "--tolerance NaN"),
        (vec!["--penalties", "1e3,1e4", "-o", "busy.h5"], "another run is writing it"),
        (vec!["--penalties", "1e3,1e4", "-o", "fit.toml"], "an input file of the model"),
    ];
    // a directory without write permission stands for a read-only mount (root writes anyway)
    let ro = readonly.join("s.h5");
    let ro = ro.to_str().unwrap().to_string();
    if !is_root {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&readonly, std::fs::Permissions::from_mode(0o555)).unwrap();
        cases.push((vec!["--penalties", "1e3,1e4", "-o", ro.as_str()], "cannot write"));
    }
    for (args, needle) in cases {
        let out = command_in(dir.path(), 2)
            .current_dir(dir.path())
            .args(["penalty-study", "--deck"])
            .arg(&deck)
            .args(["--reaction", "outer_top"])
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle) && err.lines().filter(|l| l.starts_with("error:")).count() == 1, "{args:?}: {err}");
        assert!(!dir.path().join("s_runs").exists(), "{args:?}: no run started");
    }
}

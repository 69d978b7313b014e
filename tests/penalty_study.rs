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

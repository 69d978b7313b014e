//! `slideline bellows --export-inp`: the built-in joint written as a CalculiX/Abaqus deck, read
//! back by `slideline run`, gives the same history as `slideline bellows` (to 1e-8 of each
//! column's scale): the same mesh, sets, material, pressure on the wetted faces, contact pairs
//! (a two-pass pair written both ways with half the penalty each), steps and reactions.
//!
//! Case: the quick joint (522 Q8), compressed 20 mm in 10 increments after the heat step, on
//! one rank (no partition, so the two runs do the same arithmetic but for the reader's roundings).

mod common;
use common::{command_in, Results};

const CASE: [&str; 5] = ["--quick", "--displacement", "20", "--increments", "10"];

#[test]
fn the_exported_deck_runs_to_the_same_history_as_the_built_in_model() {
    round_trip(&CASE, &[], &[]);
}

/// With friction between the plies and in the sleeve's fit (each pair's *FRICTION: mu and the
/// stick slope, halved per listing of the two-pass ply pair; the bellows' increment growth as
/// CalculiX's *CONTROLS I_G): the same history, friction dissipation included. Seen failing
/// before: the deck had no *FRICTION, so CalculiX and `slideline run` analysed a frictionless
/// joint. Both runs take the tight residual test and a short stroke (5 mm, one cutback): under
/// the field test two runs stop at iterates about 1e-7 apart, and with friction's cutbacks such
/// differences send them down different increment paths (measured at 20 mm: 25 and 29
/// increments), whatever the deck.
#[test]
fn a_frictional_joint_exported_runs_to_the_same_history() {
    let case = ["--quick", "--displacement", "5", "--increments", "5", "--friction-plies", "0.2", "--friction-sleeve", "0.1", "--convergence", "residual"];
    // the Newton iterations may differ by one where ||F|| meets the round-off floor
    let deck = round_trip(&case, &["--convergence", "residual"], &["newton_iterations", "linear_iterations"]);
    assert_eq!(deck.matches("*FRICTION").count(), 4, "one per pair with friction: the plies, the sleeve, the pack's outside and inside folds");
    assert!(deck.contains("*CONTROLS, PARAMETERS=TIME INCREMENTATION"), "the bellows' increment growth");
}

/// An elastic slip has no CalculiX form: the export is refused by name, not written without it.
#[test]
fn friction_with_an_elastic_slip_is_not_exported_silently() {
    let dir = tempfile::tempdir().unwrap();
    let out = command_in(dir.path(), 1)
        .current_dir(dir.path())
        .arg("bellows")
        .args(CASE)
        .args(["--friction-plies", "0.2", "--elastic-slip", "0.005", "--export-inp", "j.inp"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.code() == Some(2) && err.contains("elastic slip has no CalculiX form"), "{err}");
    assert!(!dir.path().join("j.inp").exists());
}

/// Exports the bellows of flags `case`, runs it and the deck (`run` taking `run_flags`),
/// compares every history column but `effort` ones; returns the deck.
fn round_trip(case: &[&str], run_flags: &[&str], effort: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let out = command_in(d, 1).current_dir(d).arg("bellows").args(case).args(["--export-inp", "joint.inp"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(!d.join("bellows.h5").exists(), "exporting runs no analysis");
    let deck = std::fs::read_to_string(d.join("joint.inp")).unwrap();
    for card in ["*ELEMENT, TYPE=CAX8", "*PLASTIC", "*CONTACT PAIR", "*DLOAD", "*NODE PRINT, NSET=moving_end"] {
        assert!(deck.contains(card), "the deck lacks {card}");
    }
    // CalculiX reads fields of at most 20 characters
    assert!(deck.lines().skip(2).filter(|l| !l.starts_with('*')).flat_map(|l| l.split(',')).all(|f| f.trim().len() <= 20), "a field longer than 20 characters");

    let built_in = command_in(d, 1).current_dir(d).arg("bellows").args(case).args(["-o", "built_in.h5", "--quiet"]).output().unwrap();
    assert!(built_in.status.success(), "{}", String::from_utf8_lossy(&built_in.stderr));
    let read = command_in(d, 1).current_dir(d).args(["run", "joint.inp", "-o", "read.h5", "--quiet"]).args(run_flags).output().unwrap();
    assert!(read.status.success(), "{}", String::from_utf8_lossy(&read.stderr));
    let (a, b) = (Results::open(&d.join("built_in.h5")), Results::open(&d.join("read.h5")));

    let columns = |r: &Results| r.file.group("history").unwrap().member_names().unwrap();
    let theirs = columns(&b);
    let mut compared = 0;
    // reactions: the deck's set names are upper case; both components scaled by the axial one
    let scale = a.history("reaction_moving_end_z").iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for name in columns(&a) {
        let Some(other) = theirs.iter().find(|t| t.eq_ignore_ascii_case(&name)) else { continue };
        let (x, y) = (a.history(&name), b.history(other));
        assert_eq!(x.len(), y.len(), "{name}: increments differ");
        let s = if name.starts_with("reaction_") { scale } else { x.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-300) };
        if ["wall_time", "residual_norm"].contains(&name.as_str()) || effort.contains(&name.as_str()) {
            continue;
        }
        let worst = x.iter().zip(&y).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max) / s;
        assert!(worst < 1e-8, "{name}: differs by {worst:e} of its scale");
        compared += 1;
    }
    assert!(compared >= 10, "only {compared} history columns in common");
    // contact forces pair by pair (the deck's pairs are named slave-master)
    let force = |r: &Results, names: &[String]| -> Vec<Vec<f64>> {
        let mut cols: Vec<&String> = names.iter().filter(|n| n.starts_with("contact_") && n.ends_with("_force")).collect();
        cols.sort_by_key(|n| n.to_lowercase());
        cols.iter().map(|n| r.history(n)).collect()
    };
    let (fa, fb) = (force(&a, &columns(&a)), force(&b, &theirs));
    assert_eq!(fa.len(), 4, "four pairs in the built-in model");
    let total_a: f64 = fa.iter().map(|f| f.iter().fold(0.0f64, |m, v| m.max(v.abs()))).sum();
    let sum = |f: &Vec<Vec<f64>>, k: usize| -> f64 { f.iter().map(|c| c[k]).sum() };
    for k in 0..fa[0].len() {
        assert!((sum(&fa, k) - sum(&fb, k)).abs() < 1e-8 * total_a, "contact forces at increment {}", k + 1);
    }
    // and the displacements at the end, node by node
    let (worst, size) = common::displacement_difference(&a, &b);
    assert!(worst < 1e-8 * size, "displacements differ by {worst:e} (largest {size})");
    deck
}

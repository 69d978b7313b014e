//! Studies whose runs are shared out to groups of ranks (`--ranks-per-run G`):
//! - a run of a study on a group of one rank is the same run as the variant alone on one rank,
//!   bit for bit (the shrink fit, three penalties, against `slideline run` of each deck);
//! - a study on 3 ranks in groups of 1 and on 2 ranks in one group of 2 agree (MUMPS sums in
//!   another order on 2 ranks: 1e-8);
//! - a variant that cannot be built, or a run that does not converge, is a row that says so,
//!   and the others finish;
//! - SIGTERM to mpirun during a study leaves each finished run and a readable study file;
//! - a sweep that cannot make sense is refused with exit 2, naming the item.

mod common;
use common::{command_in, shrink_fit_deck, Results};
use std::path::{Path, PathBuf};

fn column(path: &Path, group: &str, name: &str) -> Vec<f64> {
    let f = hdf5::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    f.dataset(&format!("{group}/{name}")).unwrap_or_else(|e| panic!("{group}/{name}: {e}")).read_raw::<f64>().unwrap()
}

fn texts(path: &Path, group: &str, name: &str) -> Vec<String> {
    let f = hdf5::File::open(path).unwrap();
    let d = f.dataset(&format!("{group}/{name}")).unwrap();
    d.read_raw::<hdf5::types::VarLenUnicode>().unwrap().iter().map(|s| s.as_str().to_string()).collect()
}

/// The shrink fit with penalty `penalty`, written in `dir` as `name`.
fn fit_deck(dir: &Path, name: &str, penalty: &str) -> PathBuf {
    let deck = dir.join(name);
    std::fs::write(&deck, shrink_fit_deck(true, &format!("penalty = {penalty}"), "")).unwrap();
    deck
}

/// `penalty-study --deck fit.toml --reaction outer_top ARGS -o NAME` on `ranks` ranks in `dir`.
fn fit_study(dir: &Path, ranks: usize, name: &str, args: &[&str]) -> (PathBuf, String) {
    let deck = fit_deck(dir, "fit.toml", "1.0");
    let study = dir.join(name);
    let out = command_in(dir, ranks)
        .current_dir(dir)
        .args(["penalty-study", "--deck"])
        .arg(&deck)
        .args(["--reaction", "outer_top"])
        .args(args)
        .arg("-o")
        .arg(&study)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    (study, stdout)
}

#[test]
fn a_study_run_on_one_rank_is_the_variant_run_alone() {
    let dir = tempfile::tempdir().unwrap();
    let penalties = ["1e3", "1e4", "1e5"];
    let (_, stdout) = fit_study(dir.path(), 2, "study.h5", &["--penalties", &penalties.join(","), "--ranks-per-run", "1", "--full-output"]);
    assert!(stdout.contains("3 runs on 2 group(s) of 1 rank(s)"), "{stdout}");
    for p in penalties {
        let deck = fit_deck(dir.path(), &format!("alone_{p}.toml"), p);
        let alone = dir.path().join(format!("alone_{p}.h5"));
        let out = command_in(dir.path(), 1).arg("run").arg(&deck).arg("-o").arg(&alone).arg("-q").output().unwrap();
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let label = format!("{:.3e}", p.parse::<f64>().unwrap());
        let (a, b) = (Results::open(&dir.path().join(format!("study_runs/penalty_{label}.h5"))), Results::open(&alone));
        // every increment's fields, bit for bit
        common::assert_same_datasets(&a.file.group("increments").unwrap(), &b.file.group("increments").unwrap());
        // and the history, but the wall time
        let names = a.file.group("history").unwrap().member_names().unwrap();
        assert_eq!(names, b.file.group("history").unwrap().member_names().unwrap());
        for name in names.iter().filter(|n| *n != "wall_time") {
            let (x, y) = (a.history(name), b.history(name));
            assert!(x.iter().zip(&y).all(|(u, v)| u.to_bits() == v.to_bits()) && x.len() == y.len(), "penalty {p}: history/{name} {x:?} {y:?}");
        }
    }
}

#[test]
fn three_groups_of_one_and_one_group_of_two_agree() {
    let dir = tempfile::tempdir().unwrap();
    let args = ["--penalties", "1e3,1e4,1e5"];
    let (ones, _) = fit_study(dir.path(), 3, "ones.h5", &[&args[..], &["--ranks-per-run", "1"]].concat());
    let (two, _) = fit_study(dir.path(), 2, "two.h5", &[&args[..], &["--ranks-per-run", "2"]].concat());
    for name in ["reaction", "max_penetration"] {
        let (a, b) = (column(&ones, "summary", name), column(&two, "summary", name));
        assert_eq!(a.len(), 3);
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() <= 1e-8 * x.abs().max(y.abs()), "{name}: {a:?} against {b:?}");
        }
    }
    assert_eq!(column(&ones, "summary", "increments"), column(&two, "summary", "increments"));
    // and each run kept only its history and its steps' last fields (1 step: one increment)
    let kept = Results::open(&dir.path().join("ones_runs/penalty_1.000e3.h5"));
    assert_eq!(kept.file.group("increments").unwrap().member_names().unwrap().len(), 1);
    assert_eq!(kept.history("step").len(), 2, "the history keeps every increment");
}

/// A run that does not converge (the residual test to 1e-10 in one Newton iteration, no room
/// to cut back) is a row saying so; the study ends with exit 0 and its other rows.
#[test]
fn a_run_that_does_not_converge_is_recorded_and_the_study_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("fit.toml");
    let stepping = "[stepping]\nconvergence = \"residual\"\nmax_newton_iterations = 1\nmin_increment = 0.5\n[[step]]";
    let text = shrink_fit_deck(true, "penalty = 1.0", "").replace("[[step]]", stepping);
    std::fs::write(&deck, text).unwrap();
    let study = dir.path().join("study.h5");
    let out = command_in(dir.path(), 2)
        .current_dir(dir.path())
        .args(["penalty-study", "--deck"])
        .arg(&deck)
        .args(["--reaction", "outer_top", "--penalties", "1e1,1e7", "-o"])
        .arg(&study)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    let outcome = texts(&study, "summary", "outcome");
    assert_eq!(outcome.len(), 2, "{outcome:?}");
    assert!(outcome.contains(&"not converged".to_string()), "{outcome:?}\n{stdout}");
    let reasons = texts(&study, "summary", "reason");
    assert!(reasons.iter().any(|r| r.contains("did not converge")), "{reasons:?}");
    // the CSV beside it holds the same rows, its headers with units
    let csv = std::fs::read_to_string(study.with_extension("csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "{csv}");
    assert!(csv.lines().next().unwrap().contains("max_penetration [mm]"), "{csv}");
}

/// A sweep of the DN200 example (elastic only: the code check and its coefficients) in which
/// one variant's plies are thicker than its convolution can hold: that variant is a failed row
/// naming why, the others have their verdicts, and the study file holds each settings column.
#[test]
fn a_variant_that_cannot_be_built_is_recorded_and_the_others_finish() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("sweep.h5");
    let out = command_in(dir.path(), 2)
        .current_dir(dir.path())
        .args(["bellows-sweep", "--spec"])
        .arg(common::data("../../examples/dn200_joint.toml"))
        .args(["--vary", "plies=2..3", "--vary", "bellows.ply_thickness=0.5,6.0", "--elastic-only", "--sort", "allowable_cycles", "-o"])
        .arg(&study)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}{}", String::from_utf8_lossy(&out.stderr));
    let outcome = texts(&study, "variants", "outcome");
    assert_eq!(outcome, ["converged", "failed", "converged", "failed"], "{stdout}");
    let reasons = texts(&study, "variants", "reason");
    assert!(reasons[1].contains("ply") || reasons[1].contains("thick"), "{reasons:?}");
    assert_eq!(column(&study, "variants", "bellows.plies"), [2.0, 2.0, 3.0, 3.0]);
    assert_eq!(column(&study, "variants", "bellows.ply_thickness"), [0.5, 6.0, 0.5, 6.0]);
    let rate = column(&study, "variants", "axial_rate");
    // three plies of the same thickness: about 1.5 times the rate of two (EJMA's fiw is
    // 1.7 Dm Eb tp^3 n / (w^3 Cf): n, and Dm and Cf a little with the added ply)
    assert!((rate[2] / rate[0] - 1.5).abs() < 0.03, "{rate:?}");
    assert!(rate[1].is_nan() && rate[3].is_nan(), "{rate:?}");
    assert!(!texts(&study, "variants", "verdict")[0].is_empty());
    assert!(dir.path().join("sweep_rate_cycles.png").exists());
    assert!(stdout.contains("variants sorted by allowable_cycles"), "{stdout}");
}

/// SIGTERM to mpirun while a study runs (what Ctrl-C in a batch job or `scancel` does):
/// mpirun exits, every run that had finished keeps a readable file, the study file is
/// readable and names only runs whose files are there, and the next study may write it.
#[test]
fn sigterm_during_a_study_keeps_every_finished_run() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.h5");
    let child = command_in(dir.path(), 2)
        .current_dir(dir.path())
        .args(["penalty-study", "--quick", "--displacement", "20", "--increments", "20", "--penalties", "1e3,2e3,4e3,8e3,1.6e4,3.2e4,6.4e4,1.28e5", "-o"])
        .arg(&study)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // wait for the first rows, then stop the study
    let start = std::time::Instant::now();
    while !(study.exists() && hdf5::File::open(&study).is_ok_and(|f| f.dataset("summary/penalty").is_ok_and(|d| d.size() >= 2))) {
        assert!(start.elapsed().as_secs() < 300, "no row after 300 s");
        std::thread::sleep(std::time::Duration::from_millis(200));
    }
    // `timeout` runs mpirun: signal mpirun itself, as a shell's kill or a batch system does
    let mpirun = std::process::Command::new("pgrep").args(["-P", &child.id().to_string()]).output().unwrap();
    let mpirun = String::from_utf8_lossy(&mpirun.stdout).trim().to_string();
    assert!(!mpirun.is_empty());
    std::process::Command::new("kill").args(["-TERM", &mpirun]).status().unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(!out.status.success(), "the study was stopped before its end");
    let outcome = texts(&study, "summary", "outcome");
    assert!(outcome.len() >= 2 && outcome.len() < 8, "{outcome:?}");
    for (label, outcome) in texts(&study, "summary", "label").iter().zip(&outcome) {
        let run = dir.path().join(format!("study_runs/penalty_{label}.h5"));
        if outcome == "converged" {
            let r = Results::open(&run);
            assert_eq!(*r.history("load_factor").last().unwrap(), 1.0, "{label}");
        }
    }
    // mpirun kills its ranks a second after passing SIGTERM on: on a loaded machine a rank
    // may die before it releases the lock, so the lock is the next study's to replace once
    // its writer is gone (mpirun may return while the kernel is still ending it)
    if let Ok(lock) = std::fs::read_to_string(dir.path().join("study.lock")) {
        let pid = lock.split_whitespace().skip_while(|w| *w != "pid").nth(1).unwrap_or("0").to_string();
        let start = std::time::Instant::now();
        while Path::new(&format!("/proc/{pid}")).exists() && start.elapsed().as_secs() < 30 {
            std::thread::sleep(std::time::Duration::from_millis(100));
        }
    }
    let again = command_in(dir.path(), 1)
        .current_dir(dir.path())
        .args(["penalty-study", "--quick", "--displacement", "2", "--increments", "2", "--penalties", "1e4", "-q", "-o"])
        .arg(&study)
        .output()
        .unwrap();
    assert!(again.status.success(), "the next study on the same file: {}", String::from_utf8_lossy(&again.stderr));
}

/// A sweep that cannot make sense is refused before any run, with exit 2 and one line naming
/// the item: an unknown key, an empty range, a value of the wrong kind, a key given twice, and
/// groups that do not divide the ranks.
#[test]
fn a_sweep_that_cannot_make_sense_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let spec = common::data("../../examples/dn200_joint.toml");
    let cases: [(usize, &[&str], &str); 6] = [
        (1, &["--vary", "thickness=0.3,0.5"], "no key \"thickness\""),
        (1, &["--vary", "bellows.thickness=0.3,0.5"], "unknown field `thickness`"),
        (1, &["--vary", "convolutions=8..6"], "the range is empty"),
        (1, &["--vary", "convolutions=4.5,5"], "--vary convolutions=4.5,5"),
        (1, &["--vary", "plies=1,2", "--vary", "bellows.plies=3"], "given twice"),
        (3, &["--vary", "plies=1,2", "--ranks-per-run", "2"], "--ranks-per-run 2"),
    ];
    for (ranks, args, needle) in cases {
        let out = command_in(dir.path(), ranks).current_dir(dir.path()).args(["bellows-sweep", "--spec"]).arg(&spec).args(args).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle) && err.lines().filter(|l| l.starts_with("error:")).count() == 1, "{args:?}: {err}");
        assert!(!dir.path().join("bellows_sweep_runs").exists(), "{args:?}: no run started");
    }
}

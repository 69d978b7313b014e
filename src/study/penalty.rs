//! `slideline penalty-study`: one model run for a list of penalty values (and optionally with
//! the augmented Lagrangian), the runs shared out to the study's groups of ranks, to show how
//! the penalty trades constraint accuracy against Newton convergence. Every run keeps its own
//! results file; the study file holds a group per run (its history, copied) and a summary
//! table, kept current as runs finish; rank 0 prints the table, draws the plots and names the
//! smallest penalty whose reaction is within a tolerance of the reference (the
//! augmented-Lagrangian run if there is one, else the stiffest converged run).

use super::{Measures, Outcome, Subject};
use crate::error::{Error, Result};
use crate::io::plots::{line_plot, Axes, Curve};
use crate::io::reader::ResultsReader;
use crate::io::table_file::{Table, TableFile};
use crate::model::{AugmentedLagrangian, Penalty};
use crate::petsc::PetscSession;
use crate::solve::RunOptions;
use mpi::traits::{Communicator, Root};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Penalty values from "a..b" (log-spaced, `per_decade` per decade, both ends included) or
/// "a,b,c".
pub fn parse_penalties(spec: &str, per_decade: usize) -> Result<Vec<f64>> {
    let number = |s: &str| -> Result<f64> {
        let v: f64 = s.trim().parse().map_err(|_| Error::input(format!("--penalties: {s:?} is not a number")))?;
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(Error::input(format!("--penalties: {v} is not a positive penalty")))
        }
    };
    let values: Vec<f64> = if let Some((a, b)) = spec.split_once("..") {
        let (a, b) = (number(a)?, number(b)?);
        if b <= a || per_decade == 0 {
            return Err(Error::input(format!("--penalties {spec}: need a..b with a < b and --per-decade >= 1")));
        }
        let steps = ((b / a).log10() * per_decade as f64).round().max(1.0);
        if steps >= MAX_RUNS as f64 {
            return Err(Error::input(format!(
                "--penalties {spec} with --per-decade {per_decade} asks for {} runs, more than {MAX_RUNS}: fewer per decade",
                steps + 1.0
            )));
        }
        let steps = steps as usize;
        (0..=steps).map(|k| a * (b / a).powf(k as f64 / steps as f64)).collect()
    } else {
        spec.split(',').map(number).collect::<Result<_>>()?
    };
    if values.len() > MAX_RUNS {
        return Err(Error::input(format!("--penalties {spec}: {} runs, more than {MAX_RUNS}", values.len())));
    }
    // each run is named by its penalty to four digits: two that share a name are one run
    for (k, v) in values.iter().enumerate() {
        if let Some(w) = values[..k].iter().find(|w| format!("{w:.3e}") == format!("{v:.3e}")) {
            return Err(Error::input(format!("--penalties {spec}: {w:e} and {v:e} are the same run (penalties are told apart to four digits)")));
        }
    }
    Ok(values)
}

/// The most runs a study makes: beyond it a mistyped --per-decade would start hours of runs.
pub const MAX_RUNS: usize = 100;

/// One run of the study.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct StudyRow {
    pub label: String,
    pub penalty: f64,
    pub augmented: bool,
    pub converged: bool,
    pub outcome: Outcome,
    /// Why a run did not converge or failed ("" for a converged run).
    pub reason: String,
    /// Step and load factor the run reached.
    pub reached: (usize, f64),
    pub increments: usize,
    pub newton_iterations: usize,
    pub linear_iterations: usize,
    pub cutbacks: usize,
    /// Augmented-Lagrangian multiplier updates over the run.
    pub augmentations: usize,
    pub wall_time: f64,
    /// Largest penetration over all pairs and increments, mm, and relative to `length`.
    pub penetration: f64,
    pub relative_penetration: f64,
    /// The reaction followed (history column), at the last increment.
    pub reaction: f64,
    /// Relative difference from the reference run.
    pub difference: f64,
    pub results: PathBuf,
}

/// What the study runs and how it reports.
pub struct StudyPlan {
    /// The model, run with each penalty (N/mm^3 or kappa, as `dimensionless` says).
    pub subject: Subject,
    pub penalties: Vec<f64>,
    pub dimensionless: bool,
    /// Also run the middle penalty with augmented-Lagrangian updates (the reference).
    pub augmented: bool,
    pub measures: Measures,
    pub tolerance: f64,
    pub output: PathBuf,
    pub progress: bool,
    /// Every increment's fields in each run's file (else the history and each step's end).
    pub full_output: bool,
}

fn penalty_of(value: f64, dimensionless: bool) -> Penalty {
    if dimensionless {
        Penalty::Factor(value)
    } else {
        Penalty::Stiffness(value)
    }
}

/// Runs the study over the session's groups (collective over every rank); world rank 0
/// returns the rows, in the order of the penalties, having written the file and pictures.
pub fn penalty_study(session: &PetscSession, spec: &StudyPlan) -> Result<Vec<StudyRow>> {
    let root = session.everyone().rank() == 0;
    if !(spec.tolerance > 0.0 && spec.tolerance.is_finite()) {
        return Err(Error::input(format!("--tolerance {}: give a relative tolerance > 0 (0.01 is 1 %)", spec.tolerance)));
    }
    let inputs: Vec<(&Path, &str)> = match &spec.subject {
        Subject::Deck(model) => model.source_files.iter().map(|f| (f.as_path(), "an input file of the model")).collect(),
        Subject::Bellows(_) => Vec::new(),
    };
    let (_lock, dir) = super::prepare(session, &spec.output, &inputs)?;
    let plain: Vec<Run> = spec.penalties.iter().map(|&p| Run { label: format!("{p:.3e}"), penalty: p, augmented: None }).collect();
    let announce = |what: &str| {
        if root && spec.progress {
            println!("penalty-study: {what}");
        }
    };
    announce(&format!("{} runs on {} group(s) of {} rank(s), results in {}", plain.len(), groups(session).0, groups(session).1, dir.display()));
    let mut rows = run_all(session, spec, &dir, &plain, &[])?;
    if spec.augmented {
        // the augmented reference is driven to half the smallest largest-penetration of the
        // plain runs (the stiffest's), so that it does augment and is the tightest of all
        let stiffest = rows.iter().filter(|r| r.converged && r.penetration > 0.0).map(|r| r.penetration).fold(f64::INFINITY, f64::min);
        let mut tolerance = if stiffest.is_finite() { 0.5 * stiffest } else { 1e-3 * spec.measures.length };
        session.everyone().process_at_rank(0).broadcast_into(&mut tolerance);
        let middle = spec.penalties[spec.penalties.len() / 2];
        let reference = [Run { label: format!("{middle:.3e}_al"), penalty: middle, augmented: Some(tolerance) }];
        announce(&format!("the augmented-Lagrangian reference at {middle:.3e}, to a penetration of {tolerance:.3e} mm"));
        rows = run_all(session, spec, &dir, &reference, &rows)?;
    }
    if root {
        compare_to_reference(&mut rows);
        write_study(spec, &rows)?;
        draw_pictures(spec, &rows)?;
        println!("{}", table(&rows, spec));
    }
    Ok(rows)
}

/// One run of a penalty study: its penalty, and the augmented Lagrangian's penetration
/// tolerance for the reference run.
struct Run {
    label: String,
    penalty: f64,
    augmented: Option<f64>,
}

/// (groups, ranks per group) of the session.
fn groups(session: &PetscSession) -> (usize, usize) {
    session.groups().map_or((1, session.world().size() as usize), |g| (g.count, g.ranks_per_group))
}

/// `runs` shared out to the groups; on world rank 0 the rows of `before` and theirs, in order,
/// the study file rewritten as each arrives.
fn run_all(session: &PetscSession, spec: &StudyPlan, dir: &Path, runs: &[Run], before: &[StudyRow]) -> Result<Vec<StudyRow>> {
    let total = runs.len();
    let rows = super::pool::run_rows(
        session,
        total,
        |k| run_one(session, spec, dir, &runs[k]),
        |done: &[StudyRow], newest| {
            if spec.progress {
                println!("  [{}/{total}] {}", done.len(), row_line(&done[newest]));
            }
            let all: Vec<StudyRow> = before.iter().cloned().chain(done.iter().cloned()).collect();
            if let Err(e) = write_study(spec, &all) {
                println!("note: the study file could not be written: {e}");
            }
        },
    );
    Ok(before.iter().cloned().chain(rows).collect())
}

/// One run, on its group's ranks: the model with the run's penalty, its results file, and its
/// row (read back from the file on the group's rank 0; a run that failed is a row that says
/// why).
fn run_one(session: &PetscSession, spec: &StudyPlan, dir: &Path, run: &Run) -> StudyRow {
    let results = dir.join(format!("penalty_{}.h5", run.label));
    let start = Instant::now();
    let outcome = spec.subject.model(penalty_of(run.penalty, spec.dimensionless)).and_then(|mut model| {
        if let Some(tolerance) = run.augmented {
            for c in &mut model.contacts {
                c.augmented_lagrangian = Some(AugmentedLagrangian { penetration_tolerance: tolerance, max_augmentations: 20 });
            }
        }
        super::study_output(&mut model.output.every, spec.full_output);
        crate::solve::run(session, &model, &RunOptions { output: results.clone(), progress: false, verbose: false, monitor: false, restart: None })
    });
    let wall = start.elapsed().as_secs_f64();
    let (outcome, reason) = Outcome::of(&outcome);
    let mut row = StudyRow {
        label: run.label.clone(),
        penalty: run.penalty,
        augmented: run.augmented.is_some(),
        converged: outcome == Outcome::Converged,
        outcome,
        reason,
        reached: (0, 0.0),
        increments: 0,
        newton_iterations: 0,
        linear_iterations: 0,
        cutbacks: 0,
        augmentations: 0,
        wall_time: wall,
        penetration: f64::NAN,
        relative_penetration: f64::NAN,
        reaction: f64::NAN,
        difference: f64::NAN,
        results: results.clone(),
    };
    if session.world().rank() == 0 && results.exists() {
        if let Err(e) = summarise(&results, &mut row, spec) {
            row.reason = format!("{}{}its results cannot be read: {e}", row.reason, if row.reason.is_empty() { "" } else { "; " });
        }
    }
    row
}

fn summarise(results: &Path, row: &mut StudyRow, spec: &StudyPlan) -> Result<()> {
    let r = ResultsReader::open(results)?;
    let rows = r.history_rows()?;
    let penetration = r
        .history_columns()?
        .iter()
        .filter(|c| c.ends_with("_max_penetration"))
        .map(|c| r.history(c).map(|v| v.into_iter().filter(|x| x.is_finite()).fold(0.0, f64::max)))
        .collect::<Result<Vec<f64>>>()?
        .into_iter()
        .fold(0.0, f64::max);
    row.reaction = r.history(&spec.measures.reaction_column).ok().and_then(|v| v.last().copied()).unwrap_or(f64::NAN) * spec.measures.reaction_scale;
    row.reached = rows.last().map_or((0, 0.0), |(_, h)| (h.step, h.load_factor));
    row.increments = rows.len();
    row.newton_iterations = rows.iter().map(|(_, h)| h.newton_iterations).sum();
    row.linear_iterations = rows.iter().map(|(_, h)| h.linear_iterations).sum();
    row.cutbacks = rows.iter().map(|(_, h)| h.cutbacks).sum();
    row.augmentations = rows.iter().map(|(_, h)| h.augmentations).sum();
    row.penetration = penetration;
    row.relative_penetration = penetration / spec.measures.length;
    Ok(())
}

/// Reference: the augmented-Lagrangian run if it converged, else the stiffest converged run.
fn compare_to_reference(rows: &mut [StudyRow]) {
    let reference = rows
        .iter()
        .filter(|r| r.converged && r.augmented)
        .chain(rows.iter().filter(|r| r.converged && !r.augmented).max_by(|a, b| a.penalty.total_cmp(&b.penalty)))
        .map(|r| r.reaction)
        .next();
    if let Some(reference) = reference {
        for r in rows.iter_mut() {
            r.difference = (r.reaction - reference) / reference.abs();
        }
    }
}

fn row_line(r: &StudyRow) -> String {
    format!(
        "{:>14} {:>4} {:>9} {:>6} {:>7} {:>7.2} {:>7} {:>7} {:>9.1} {:>11.3e} {:>9.3} % {:>14.4} {:>10}",
        r.label,
        if r.augmented { "AL" } else { "" },
        match r.outcome {
            Outcome::Converged => "yes".to_string(),
            Outcome::NotConverged => format!("no {:.3}", r.reached.1),
            other => other.label().to_string(),
        },
        r.increments,
        r.newton_iterations,
        r.newton_iterations as f64 / r.increments.max(1) as f64,
        r.linear_iterations,
        r.cutbacks,
        r.wall_time,
        r.penetration,
        100.0 * r.relative_penetration,
        r.reaction,
        if r.difference.is_finite() { format!("{:+.3} %", 100.0 * r.difference) } else { "-".into() }
    )
}

/// The printed summary table and the recommendation line.
pub fn table(rows: &[StudyRow], spec: &StudyPlan) -> String {
    let mut s = String::new();
    let unit = if spec.dimensionless { "kappa" } else { "N/mm^3" };
    let _ = writeln!(
        s,
        "{:>14} {:>4} {:>9} {:>6} {:>7} {:>7} {:>7} {:>7} {:>9} {:>11} {:>11} {:>14} {:>10}",
        format!("penalty {unit}"),
        "",
        "converged",
        "incs",
        "newton",
        "per inc",
        "linear",
        "cutback",
        "wall s",
        "max pen mm",
        format!("% {}", spec.measures.length_name),
        format!("reaction {}", spec.measures.reaction_unit),
        "vs ref"
    );
    for r in rows {
        let _ = writeln!(s, "{}", row_line(r));
    }
    let candidates = rows.iter().filter(|r| r.converged && !r.augmented && r.difference.abs() <= spec.tolerance);
    match candidates.min_by(|a, b| a.penalty.total_cmp(&b.penalty)) {
        Some(best) => {
            let _ = writeln!(
                s,
                "recommendation: penalty {} {unit}, the smallest whose reaction is within {} % of the reference ({:+.3} %), at {} Newton iterations ({:.2} per increment), {} cutbacks, {:.1} s, max penetration {:.2e} mm ({:.3} % of the {})",
                best.label,
                100.0 * spec.tolerance,
                100.0 * best.difference,
                best.newton_iterations,
                best.newton_iterations as f64 / best.increments.max(1) as f64,
                best.cutbacks,
                best.wall_time,
                best.penetration,
                100.0 * best.relative_penetration,
                spec.measures.length_name
            );
        }
        None => {
            let _ = writeln!(s, "recommendation: none: no converged run is within {} % of the reference", 100.0 * spec.tolerance);
        }
    }
    s
}

/// The study file, written whole (see [`super::write_whole`]): /summary/COLUMN (one row per
/// run, its differences from the reference among them) and /runs/LABEL/history/COLUMN copied
/// from each run's own results file (named in the group's attribute `results`); and the CSV.
fn write_study(spec: &StudyPlan, rows: &[StudyRow]) -> Result<()> {
    let mut rows = rows.to_vec();
    compare_to_reference(&mut rows);
    let path = &spec.output;
    let mut t = Table::default();
    t.text("label", rows.iter().map(|r| r.label.clone()).collect());
    t.numbers("penalty", if spec.dimensionless { "" } else { "N/mm^3" }, rows.iter().map(|r| r.penalty).collect());
    t.numbers("augmented", "", rows.iter().map(|r| f64::from(u8::from(r.augmented))).collect());
    t.numbers("converged", "", rows.iter().map(|r| f64::from(u8::from(r.converged))).collect());
    t.text("outcome", rows.iter().map(|r| r.outcome.label().to_string()).collect());
    t.text("reason", rows.iter().map(|r| r.reason.clone()).collect());
    t.numbers("reached_step", "", rows.iter().map(|r| r.reached.0 as f64).collect());
    t.numbers("reached_load_factor", "", rows.iter().map(|r| r.reached.1).collect());
    t.numbers("increments", "", rows.iter().map(|r| r.increments as f64).collect());
    t.numbers("newton_iterations", "", rows.iter().map(|r| r.newton_iterations as f64).collect());
    t.numbers("newton_per_increment", "", rows.iter().map(|r| r.newton_iterations as f64 / r.increments.max(1) as f64).collect());
    t.numbers("linear_iterations", "", rows.iter().map(|r| r.linear_iterations as f64).collect());
    t.numbers("cutbacks", "", rows.iter().map(|r| r.cutbacks as f64).collect());
    t.numbers("augmentations", "", rows.iter().map(|r| r.augmentations as f64).collect());
    t.numbers("wall_time", "s", rows.iter().map(|r| r.wall_time).collect());
    t.numbers("max_penetration", "mm", rows.iter().map(|r| r.penetration).collect());
    t.numbers("relative_penetration", "", rows.iter().map(|r| r.relative_penetration).collect());
    t.numbers("reaction", spec.measures.reaction_unit, rows.iter().map(|r| r.reaction).collect());
    t.numbers("reaction_difference", "", rows.iter().map(|r| r.difference).collect());
    super::write_whole(path, |part| {
        let file = TableFile::create(part)?;
        file.text_attr(None, "penalty_unit", if spec.dimensionless { "kappa (eps = kappa E / h)" } else { "N/mm^3" })?;
        file.text_attr(None, "reaction", &format!("{} x {} ({})", spec.measures.reaction_column, spec.measures.reaction_scale, spec.measures.reaction_unit))?;
        file.table("summary", &t)?;
        file.group("runs")?;
        for row in &rows {
            let group = format!("runs/{}", row.label);
            file.group(&group)?;
            file.text_attr(Some(&group), "results", &row.results.display().to_string())?;
            file.copy_history(&format!("{group}/history"), &row.results)?;
        }
        Ok(())
    })?;
    super::write_whole(&path.with_extension("csv"), |part| t.write_csv(part))
}

/// The pictures against log10 of the penalty (plain runs; the AL run is a marker line).
fn draw_pictures(spec: &StudyPlan, rows: &[StudyRow]) -> Result<()> {
    let path = &spec.output;
    let plain: Vec<&StudyRow> = rows.iter().filter(|r| !r.augmented && r.increments > 0).collect();
    let x = |r: &StudyRow| r.penalty.log10();
    let stem = path.with_extension("");
    let name = |s: &str| PathBuf::from(format!("{}_{s}.png", stem.display()));
    let xlabel = format!("log10 penalty ({})", if spec.dimensionless { "kappa" } else { "N/mm^3" });
    line_plot(
        &name("iterations"),
        "Newton iterations per increment vs penalty",
        &xlabel,
        "Newton iterations per increment",
        &[Curve { label: "mean per increment".into(), points: plain.iter().map(|r| (x(r), r.newton_iterations as f64 / r.increments as f64)).collect() }],
        &[],
        Axes::DataRange,
    )?;
    line_plot(
        &name("penetration"),
        "Largest penetration vs penalty",
        &xlabel,
        "log10 max penetration (mm)",
        &[Curve {
            label: "max over pairs and increments".into(),
            points: plain.iter().filter(|r| r.penetration > 0.0).map(|r| (x(r), r.penetration.log10())).collect(),
        }],
        &[],
        Axes::DataRange,
    )?;
    line_plot(
        &name("reaction"),
        "End reaction vs penalty",
        &xlabel,
        &format!("reaction ({})", spec.measures.reaction_unit),
        &[Curve { label: "reaction at the last increment".into(), points: plain.iter().map(|r| (x(r), r.reaction)).collect() }],
        &[],
        Axes::DataRange,
    )?;
    Ok(())
}

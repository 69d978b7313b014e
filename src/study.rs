//! `slideline penalty-study`: one model run for a list of penalty values (and optionally with
//! the augmented Lagrangian), each on the same ranks, to show how the penalty trades
//! constraint accuracy against Newton convergence. Every run keeps its own results file; the
//! study file holds a group per run (its history, copied) and a summary table, and rank 0
//! prints the table, draws the plots and names the smallest penalty whose reaction is within
//! a tolerance of the reference (the augmented-Lagrangian run if there is one, else the
//! stiffest converged run).

use crate::error::{Error, Result};
use crate::io::plots::{line_plot, Axes, Curve};
use crate::io::reader::ResultsReader;
use crate::model::{AugmentedLagrangian, Penalty};
use crate::petsc::PetscSession;
use crate::solve::{run, RunOptions};
use mpi::traits::{Communicator, CommunicatorCollectives};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

mod subject;
pub use subject::{Measures, Subject};

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
#[derive(Clone, Debug)]
pub struct StudyRow {
    pub label: String,
    pub penalty: f64,
    pub augmented: bool,
    pub converged: bool,
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
pub struct StudySpec {
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
}

fn penalty_of(value: f64, dimensionless: bool) -> Penalty {
    if dimensionless {
        Penalty::Factor(value)
    } else {
        Penalty::Stiffness(value)
    }
}

/// Runs the study; every rank returns the rows (rank 0 has written the file and pictures).
pub fn penalty_study(session: &PetscSession, spec: &StudySpec) -> Result<Vec<StudyRow>> {
    let world = session.world();
    let root = world.rank() == 0;
    if !(spec.tolerance > 0.0 && spec.tolerance.is_finite()) {
        return Err(Error::input(format!("--tolerance {}: give a relative tolerance > 0 (0.01 is 1 %)", spec.tolerance)));
    }
    crate::output_path::check_output_path(&spec.output, None)?;
    if let Subject::Deck(model) = &spec.subject {
        for input in &model.source_files {
            crate::output_path::check_output_path(&spec.output, Some((input, "an input file of the model")))?;
        }
    }
    // the study's file, and with it its runs directory, is one study's at a time
    let (_lock, note) = crate::io::lock::ResultsLock::acquire(&spec.output, &world)?;
    if let (true, Some(note)) = (root, note) {
        println!("note: {note}");
    }
    let dir = PathBuf::from(format!("{}_runs", spec.output.with_extension("").display()));
    let made = if root { std::fs::create_dir_all(&dir).map_err(|e| Error::input(format!("cannot write {}: {e}", dir.display()))) } else { Ok(()) };
    // rank 0 made the directory: every rank learns whether it could
    let mut failed = 0u8;
    world.all_reduce_into(&u8::from(made.is_err()), &mut failed, mpi::collective::SystemOperation::max());
    made?;
    if failed != 0 {
        return Err(Error::input(format!("cannot write {}: rank 0 could not make it", dir.display())));
    }
    let mut runs: Vec<(String, f64, bool)> = spec.penalties.iter().map(|&p| (format!("{p:.3e}"), p, false)).collect();
    if spec.augmented {
        let middle = spec.penalties[spec.penalties.len() / 2];
        runs.push((format!("{middle:.3e}_al"), middle, true));
    }
    let mut rows = Vec::new();
    // the smallest largest-penetration of the plain runs (the stiffest's): the augmented
    // reference is driven to half of it, so that it does augment and is the tightest of all
    let mut stiffest_penetration = f64::INFINITY;
    for (label, value, augmented) in runs {
        let mut model = spec.subject.model(penalty_of(value, spec.dimensionless))?;
        if augmented {
            let tolerance =
                if stiffest_penetration.is_finite() && stiffest_penetration > 0.0 { 0.5 * stiffest_penetration } else { 1e-3 * spec.measures.length };
            for c in &mut model.contacts {
                c.augmented_lagrangian = Some(AugmentedLagrangian { penetration_tolerance: tolerance, max_augmentations: 20 });
            }
        }
        let results = dir.join(format!("penalty_{label}.h5"));
        if root && spec.progress {
            println!(
                "penalty-study: {} {}{} -> {}",
                if spec.dimensionless { "kappa" } else { "penalty" },
                label,
                if augmented { " with augmented Lagrangian" } else { "" },
                results.display()
            );
        }
        let start = Instant::now();
        let outcome = run(session, &model, &RunOptions { output: results.clone(), progress: false, verbose: false, monitor: false, restart: None });
        let converged = match outcome {
            Ok(summary) => {
                // every rank has the history (its contact summaries are reduced)
                let penetration = summary.history.iter().flat_map(|r| r.contacts.iter().map(|c| c.max_penetration)).fold(0.0, f64::max);
                if !augmented {
                    stiffest_penetration = stiffest_penetration.min(penetration);
                }
                true
            }
            Err(Error::NotConverged { .. }) => false,
            Err(e) => return Err(e),
        };
        let wall = start.elapsed().as_secs_f64();
        let row = if root { Some(summarise(&results, &label, value, augmented, converged, wall, spec)?) } else { None };
        if let Some(row) = row {
            if spec.progress {
                println!("  {}", row_line(&row));
            }
            rows.push(row);
        }
    }
    if root {
        compare_to_reference(&mut rows);
        write_study(spec, &rows)?;
        println!("{}", table(&rows, spec));
    }
    Ok(rows)
}

fn summarise(results: &Path, label: &str, penalty: f64, augmented: bool, converged: bool, wall: f64, spec: &StudySpec) -> Result<StudyRow> {
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
    let reaction = r.history(&spec.measures.reaction_column).ok().and_then(|v| v.last().copied()).unwrap_or(f64::NAN) * spec.measures.reaction_scale;
    Ok(StudyRow {
        label: label.to_string(),
        penalty,
        augmented,
        converged,
        reached: rows.last().map_or((0, 0.0), |(_, row)| (row.step, row.load_factor)),
        increments: rows.len(),
        newton_iterations: rows.iter().map(|(_, row)| row.newton_iterations).sum(),
        linear_iterations: rows.iter().map(|(_, row)| row.linear_iterations).sum(),
        cutbacks: rows.iter().map(|(_, row)| row.cutbacks).sum(),
        augmentations: rows.iter().map(|(_, row)| row.augmentations).sum(),
        wall_time: wall,
        penetration,
        relative_penetration: penetration / spec.measures.length,
        reaction,
        difference: f64::NAN,
        results: results.to_path_buf(),
    })
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
        if r.converged { "yes".to_string() } else { format!("no {:.3}", r.reached.1) },
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
pub fn table(rows: &[StudyRow], spec: &StudySpec) -> String {
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

/// The study file: /summary/COLUMN (one row per run) and /runs/LABEL/history/COLUMN copied
/// from each run's own results file (named in the group's attribute `results`); and the PNGs.
fn write_study(spec: &StudySpec, rows: &[StudyRow]) -> Result<()> {
    let path = &spec.output;
    let err = |e: hdf5::Error| Error::Output { path: path.clone(), message: e.to_string() };
    let file = hdf5::File::create(path).map_err(err)?;
    let text = |s: &str| s.parse::<hdf5::types::VarLenUnicode>().map_err(|_| Error::Output { path: path.clone(), message: "text attribute".into() });
    file.new_attr::<hdf5::types::VarLenUnicode>()
        .create("penalty_unit")
        .map_err(err)?
        .write_scalar(&text(if spec.dimensionless { "kappa (eps = kappa E / h)" } else { "N/mm^3" })?)
        .map_err(err)?;
    file.new_attr::<hdf5::types::VarLenUnicode>()
        .create("reaction")
        .map_err(err)?
        .write_scalar(&text(&format!("{} x {} ({})", spec.measures.reaction_column, spec.measures.reaction_scale, spec.measures.reaction_unit))?)
        .map_err(err)?;
    let summary = file.create_group("summary").map_err(err)?;
    let columns: Vec<(&str, Vec<f64>)> = vec![
        ("penalty", rows.iter().map(|r| r.penalty).collect()),
        ("augmented", rows.iter().map(|r| f64::from(u8::from(r.augmented))).collect()),
        ("converged", rows.iter().map(|r| f64::from(u8::from(r.converged))).collect()),
        ("reached_step", rows.iter().map(|r| r.reached.0 as f64).collect()),
        ("reached_load_factor", rows.iter().map(|r| r.reached.1).collect()),
        ("increments", rows.iter().map(|r| r.increments as f64).collect()),
        ("newton_iterations", rows.iter().map(|r| r.newton_iterations as f64).collect()),
        ("newton_per_increment", rows.iter().map(|r| r.newton_iterations as f64 / r.increments.max(1) as f64).collect()),
        ("linear_iterations", rows.iter().map(|r| r.linear_iterations as f64).collect()),
        ("cutbacks", rows.iter().map(|r| r.cutbacks as f64).collect()),
        ("augmentations", rows.iter().map(|r| r.augmentations as f64).collect()),
        ("wall_time", rows.iter().map(|r| r.wall_time).collect()),
        ("max_penetration", rows.iter().map(|r| r.penetration).collect()),
        ("relative_penetration", rows.iter().map(|r| r.relative_penetration).collect()),
        ("reaction", rows.iter().map(|r| r.reaction).collect()),
        ("reaction_difference", rows.iter().map(|r| r.difference).collect()),
    ];
    for (name, values) in &columns {
        summary.new_dataset_builder().with_data(values.as_slice()).create(*name).map_err(err)?;
    }
    let runs = file.create_group("runs").map_err(err)?;
    for row in rows {
        let g = runs.create_group(&row.label).map_err(err)?;
        g.new_attr::<hdf5::types::VarLenUnicode>().create("results").map_err(err)?.write_scalar(&text(&row.results.display().to_string())?).map_err(err)?;
        let h = g.create_group("history").map_err(err)?;
        let r = ResultsReader::open(&row.results)?;
        for c in r.history_columns()? {
            h.new_dataset_builder().with_data(r.history(&c)?.as_slice()).create(c.as_str()).map_err(err)?;
        }
    }
    // pictures against log10 of the penalty (plain runs; the AL run is a marker line)
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

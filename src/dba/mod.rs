//! Design by analysis, ASME VIII-2 Part 5: the checks carried out on a deck's model, each by
//! an analysis of its own built from the deck's loads (the limit-load method of protection
//! against plastic collapse, [`limit_load`]; ratcheting by elastic-plastic analysis,
//! [`ratcheting`]; buckling by eigenvalue analysis, [`buckling`]), and their verdict table. What to check and the data it needs beyond the
//! model are the deck's `[design_by_analysis]` table ([`table`]).

pub mod buckling;
pub mod fatigue;
pub mod fatigue_curve;
pub mod limit_load;
pub mod ratcheting;
pub mod table;

use crate::error::{Error, Result};
use crate::io::table_file::{Table, TableFile};
use crate::model::Model;
use crate::petsc::PetscSession;
use mpi::traits::Communicator;
use std::path::{Path, PathBuf};
use table::DbaTable;

/// One line of the verdict table.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckRow {
    pub check: String,
    pub criterion: String,
    /// The figure the analysis gave (None: not evaluated, `note` says why).
    pub figure: Option<f64>,
    pub limit: f64,
    pub unit: String,
    /// None for a line that only informs (a criterion of which another may hold).
    pub passes: Option<bool>,
    pub rule: String,
}

/// The checks' answers.
pub struct Verdict {
    pub rows: Vec<CheckRow>,
    /// Each check's own results file.
    pub files: Vec<(String, PathBuf)>,
}

impl Verdict {
    pub fn passes(&self) -> bool {
        self.rows.iter().all(|r| r.passes != Some(false))
    }

    /// The verdict in a few words.
    pub fn summary(&self) -> &'static str {
        if self.passes() {
            "PASS: every check"
        } else {
            "FAIL"
        }
    }
}

/// The checks, by the names of their analyses' files.
pub const CHECKS: [&str; 4] = ["limit_load", "buckling", "ratcheting", "fatigue"];

/// The results file of check `name` beside the verdict file `output`: out.h5 -> out_NAME.h5.
pub fn check_file(output: &Path, name: &str) -> PathBuf {
    let stem = output.file_stem().unwrap_or_default().to_string_lossy();
    output.with_file_name(format!("{stem}_{name}.h5"))
}

/// The file of the limit-load check's collapse search: its factored run (`NAME_limit_load.h5`)
/// continued.
pub const SEARCH: &str = "collapse_search";

/// The verdict file `output` and every check's file beside it: what a run may write.
pub fn output_files(output: &Path) -> Vec<PathBuf> {
    std::iter::once(output.to_path_buf()).chain(CHECKS.iter().chain([&SEARCH]).map(|c| check_file(output, c))).collect()
}

/// Takes the locks of the verdict file `output` and of every check's file beside it, before
/// the first analysis starts (collective; notes printed on rank 0): two checks given the same
/// output never write into each other's files. Held until dropped.
pub fn lock_outputs(session: &PetscSession, output: &Path) -> Result<Vec<crate::io::lock::ResultsLock>> {
    let (locks, notes) = crate::io::lock::ResultsLock::acquire_all(&output_files(output), session.world())?;
    if session.world().rank() == 0 {
        notes.iter().for_each(|n| println!("note: {n}"));
    }
    Ok(locks)
}

/// The verdict printed under `title` and written to `output`'s `/dba` with the deck's text
/// (rank 0).
pub fn report(v: &Verdict, title: &str, output: &Path, deck_text: &str) -> Result<()> {
    print!("{}", table(v, title));
    write(v, output, deck_text)?;
    println!("verdict written to {} (/dba)", output.display());
    Ok(())
}

/// Runs every check `spec` names on `model` (collective); each check's run goes to its own
/// file beside `output`. Each check's rows are printed as soon as it ends (with `progress`); a
/// check whose analysis does not converge (ratcheting, fatigue) gets a failing row that says
/// where it stopped, and the checks after it still run.
pub fn run(session: &PetscSession, model: &Model, spec: &DbaTable, output: &Path, progress: bool) -> Result<Verdict> {
    let say = session.world().rank() == 0 && progress;
    let mut verdict = Verdict { rows: Vec::new(), files: Vec::new() };
    let [limit, buckle, ratchet, fatigue_name] = CHECKS;
    let mut carried = None;
    if let Some(ll) = &spec.limit_load {
        if say {
            println!("limit load: elastic-perfectly plastic at 1.5 S, small displacements, the primary loads x {} ...", ll.factor);
        }
        let file = check_file(output, limit);
        let answer = limit_load::run_factored(session, model, spec, &file, progress)?;
        verdict.add(limit, file.clone(), vec![limit_load_row(&answer, ll)], say);
        carried = answer.carried.then_some((ll, file));
    }
    if let Some(b) = &spec.buckling {
        if say {
            println!(
                "buckling: the deck's buckle steps about an elastic prestress of the design pressures, design factor 2 / beta_cr = {:.3} ...",
                2.0 / b.beta_cr
            );
        }
        let file = check_file(output, buckle);
        let answer = buckling::run(session, model, spec, &file, progress)?;
        verdict.add(buckle, file, buckling_rows(&answer, b.beta_cr), say);
    }
    if let Some(r) = &spec.ratcheting {
        if say {
            println!("ratcheting: elastic-perfectly plastic at the yield strength, {} cycles of steps {:?} ...", r.cycles, r.cycle);
        }
        let file = check_file(output, ratchet);
        let rows = match ratcheting::run(session, model, spec, &file, progress) {
            Ok(answer) => ratcheting_rows(&answer),
            Err(e) => vec![not_shown("ratcheting", e, &file, "VIII-2 5.5.7.2")?],
        };
        verdict.add(ratchet, file, rows, say);
    }
    if let Some(f) = &spec.fatigue {
        if say {
            println!("fatigue: elastic-plastic, the materials as given, {} cycles of steps {:?}, the last evaluated ...", f.cycles, f.cycle);
        }
        let file = check_file(output, fatigue_name);
        let rows = match fatigue::run(session, model, spec, &file, progress) {
            Ok(answer) => fatigue_rows(&answer),
            Err(e) => vec![not_shown("fatigue, elastic-plastic", e, &file, "VIII-2 5.5.4.4")?],
        };
        verdict.add(fatigue_name, file, rows, say);
    }
    // the collapse load last: every verdict is known, and written, before its search
    if let Some((ll, factored)) = carried {
        if session.world().rank() == 0 {
            write(&verdict, output, &model.source_text)?;
        }
        if say {
            println!("collapse search: the factored loads raised on up to x {} (the verdict so far is in {}) ...", ll.search_to, output.display());
        }
        let file = check_file(output, SEARCH);
        let answer = limit_load::search(session, model, spec, &factored, &file, progress)?;
        let row = limit_load_row(&answer, ll);
        if say {
            println!("{}", row.announced());
        }
        if let Some(first) = verdict.rows.iter_mut().find(|r| r.check == row.check) {
            *first = row;
        }
        verdict.files.push((SEARCH.to_string(), file));
    }
    Ok(verdict)
}

impl Verdict {
    /// Check `name`'s rows and file, its rows printed at once when `say`.
    fn add(&mut self, name: &str, file: PathBuf, rows: Vec<CheckRow>, say: bool) {
        if say {
            rows.iter().for_each(|r| println!("{}", r.announced()));
        }
        self.rows.extend(rows);
        self.files.push((name.to_string(), file));
    }
}

/// The failing row of a check whose analysis stopped without converging (`e`, a
/// non-convergence; any other error is passed on): the check is not shown to hold, and the
/// row says where its analysis stopped.
fn not_shown(check: &str, e: Error, file: &Path, rule: &str) -> Result<CheckRow> {
    let Error::NotConverged { step, load_factor, reason } = e else { return Err(e) };
    Ok(CheckRow {
        check: check.into(),
        criterion: format!(
            "not shown: its analysis stopped in step '{step}' at load factor {load_factor:.4} ({}; its converged increments in {})",
            limit_load::first_clause(&reason),
            file.file_name().unwrap_or_default().to_string_lossy()
        ),
        figure: None,
        limit: f64::NAN,
        unit: String::new(),
        passes: Some(false),
        rule: rule.into(),
    })
}

fn limit_load_row(a: &limit_load::LimitLoad, ll: &table::LimitLoadTable) -> CheckRow {
    // a collapse is where Newton fails at the smallest increment; any other stop is said
    let collapse = |stop: &limit_load::Stop| stop.why.contains("min_increment");
    let criterion = match &a.failed_in {
        // the factored run alone, before the search
        None if a.reached == Some(ll.factor) => format!("the loads x {} carried (the collapse search follows)", ll.factor),
        None => format!("the loads x {} carried (collapse above x {})", ll.factor, ll.search_to),
        Some(stop) if !a.carried => {
            let at = stop.factor.map_or(String::new(), |f| format!(" at x {f:.4}"));
            format!("the loads x {} carried: not so, Newton failed in step '{}'{at} ({})", ll.factor, stop.step, stop.why)
        }
        Some(stop) if collapse(stop) => format!("the loads x {} carried; the collapse load factor: Newton fails just past it", ll.factor),
        Some(stop) => format!("the loads x {} carried; the search stopped at the figure ({})", ll.factor, stop.why),
    };
    CheckRow {
        check: "plastic collapse, limit load".into(),
        criterion,
        figure: a.reached,
        limit: ll.factor,
        unit: LOAD_FACTOR.into(),
        passes: Some(a.carried),
        rule: "VIII-2 5.2.3, Table 5.3: 1.5 (P + Ps + D) at 1.5 S".into(),
    }
}

fn buckling_rows(a: &buckling::Buckling, beta_cr: f64) -> Vec<CheckRow> {
    a.steps
        .iter()
        .map(|(name, n, lambda)| CheckRow {
            check: format!("buckling, mode {n}"),
            criterion: match lambda {
                Some(_) => format!("step '{name}': the lowest load factor on the design pressures"),
                None => format!("step '{name}': no positive load factor among the eigenvalues asked"),
            },
            figure: *lambda,
            limit: a.design_factor,
            unit: LOAD_FACTOR.into(),
            passes: Some(lambda.is_none_or(|l| l >= a.design_factor)),
            rule: format!("VIII-2 5.4.1.3(a), type 1: 2 / beta_cr, beta_cr {beta_cr}"),
        })
        .collect()
}

fn ratcheting_rows(a: &ratcheting::Ratcheting) -> Vec<CheckRow> {
    let last = format!("cycles {} and {}", a.cycles - 1, a.cycles);
    let row = |criterion: String, figure: Option<f64>, limit: f64, unit: &str, rule: &str| CheckRow {
        check: "ratcheting".into(),
        criterion,
        figure,
        limit,
        unit: unit.into(),
        passes: None,
        rule: rule.into(),
    };
    vec![
        row(
            format!("(a) no plastic action in the last cycle: growth of eq. plastic strain, {last}"),
            Some(a.last_cycle_plastic),
            a.strain_tolerance,
            "-",
            "VIII-2 5.5.7.2 (a)",
        ),
        row(
            match a.core {
                Some(_) => "(b) an elastic core in the section: its least plastic strain growth".into(),
                None => "(b) an elastic core: not evaluated (no ratcheting.section)".into(),
            },
            a.core,
            a.strain_tolerance,
            "-",
            "VIII-2 5.5.7.2 (b)",
        ),
        row(
            format!("(c) no change of overall dimensions: largest node displacement change, {last}"),
            Some(a.dimension_change),
            a.length_tolerance,
            "mm",
            "VIII-2 5.5.7.2 (c)",
        ),
        CheckRow { passes: Some(a.passes()), ..row(format!("one of (a), (b), (c) holds; {} cycles", a.cycles), None, 0.0, "", "VIII-2 5.5.7.2") },
    ]
}

fn fatigue_rows(a: &fatigue::Fatigue) -> Vec<CheckRow> {
    use fatigue_curve::Cycles;
    let where_ = format!("element {} at r {:.2}, z {:.2} mm", a.element, a.at[0], a.at[1]);
    let cycles = match a.allowed {
        Cycles::Allowed(n) => format!("N = {n:.4e}, {}", a.curve),
        Cycles::Beyond(n) => format!("N above {n:.1e}, the end of {}", a.curve),
        Cycles::Below(n) => format!("N below {n:.0}, the start of {}", a.curve),
    };
    let info = |criterion: String, figure: f64, unit: &str, rule: &str| CheckRow {
        check: "fatigue, elastic-plastic".into(),
        criterion,
        figure: Some(figure),
        limit: f64::NAN,
        unit: unit.into(),
        passes: None,
        rule: rule.into(),
    };
    vec![
        info(format!("effective strain range of cycle {}, the largest: {where_}", a.cycles_run), a.strain_range, "-", "VIII-2 5.5.4.4 steps 4-5"),
        info(format!("S_alt = E x range / 2 there: {cycles}"), a.alternating_stress, "MPa", "VIII-2 5.5.4.4 steps 6-7, Annex 3-F"),
        CheckRow {
            check: "fatigue, elastic-plastic".into(),
            criterion: format!("damage n / N of {:.4e} design cycles", a.design_cycles),
            figure: Some(a.damage),
            limit: 1.0,
            unit: "-".into(),
            passes: Some(a.damage <= 1.0),
            rule: "VIII-2 5.5.4.4 step 8".into(),
        },
    ]
}

/// The unit of a figure that is a multiple of the design loads.
const LOAD_FACTOR: &str = "x loads";

impl CheckRow {
    /// The line that says the row as soon as its check ends.
    fn announced(&self) -> String {
        let [figure, limit, verdict] = self.cells();
        format!("  -> {}: {} {figure} {limit} {} {verdict}", self.check, self.criterion, self.unit)
    }

    /// The row's figure, limit and verdict as the table prints them.
    pub fn cells(&self) -> [String; 3] {
        let figure = match (self.figure, self.unit.as_str()) {
            (None, _) => "-".to_string(),
            (Some(f), LOAD_FACTOR) => format!("{f:.4}"),
            (Some(f), _) => format!("{f:.4e}"),
        };
        let limit = match self.unit.as_str() {
            _ if self.limit.is_nan() => String::new(),
            "" => String::new(),
            LOAD_FACTOR => format!(">= {:.2}", self.limit),
            _ => format!("<= {:.1e}", self.limit),
        };
        // a criterion of which another may hold says only whether it holds
        let verdict = match (self.passes, self.figure) {
            (Some(true), _) => "PASS",
            (Some(false), _) => "FAIL",
            // a figure that informs, with no limit of its own
            _ if self.limit.is_nan() => "",
            (None, Some(f)) if f <= self.limit => "holds",
            (None, Some(_)) => "fails",
            (None, None) => "",
        };
        [figure, limit, verdict.to_string()]
    }
}

/// The verdict table as printed.
pub fn table(v: &Verdict, title: &str) -> String {
    let mut out = format!("design by analysis (ASME VIII-2 Part 5): {title}\n");
    out += &format!("  {:<28} {:<84} {:>12} {:>12} {:<8} {:<7} {}\n", "check", "criterion", "figure", "limit", "unit", "verdict", "rule");
    for r in &v.rows {
        let [figure, limit, verdict] = r.cells();
        out += &format!("  {:<28} {:<84} {:>12} {:>12} {:<8} {:<7} {}\n", r.check, r.criterion, figure, limit, r.unit, verdict, r.rule);
    }
    out += &format!("verdict: {}\n", v.summary());
    for (name, file) in &v.files {
        out += &format!("  the {} analysis: {}\n", name.replace('_', " "), file.display());
    }
    out
}

/// The verdict in `output`'s group `/dba` (one row per line of the table; rank 0 only).
pub fn write(v: &Verdict, output: &Path, deck_text: &str) -> Result<()> {
    let file = TableFile::create(output)?;
    let mut t = Table::default();
    t.text("check", v.rows.iter().map(|r| r.check.clone()).collect());
    t.text("criterion", v.rows.iter().map(|r| r.criterion.clone()).collect());
    t.numbers("figure", "", v.rows.iter().map(|r| r.figure.unwrap_or(f64::NAN)).collect());
    t.numbers("limit", "", v.rows.iter().map(|r| r.limit).collect());
    t.text("unit", v.rows.iter().map(|r| r.unit.clone()).collect());
    t.text("verdict", v.rows.iter().map(|r| r.passes.map_or("", |p| if p { "PASS" } else { "FAIL" }).to_string()).collect());
    t.text("rule", v.rows.iter().map(|r| r.rule.clone()).collect());
    file.table("dba", &t)?;
    let files = v.files.iter().map(|(n, f)| format!("{n}: {}", f.display())).collect::<Vec<_>>().join("; ");
    file.text_attr(Some("dba"), "results", &files)?;
    file.text_attr(None, "deck", deck_text)
}

/// The verdict a `check` or `bellows --dba` wrote to `path`'s `/dba`; None where the file has
/// none.
pub fn read(path: &Path) -> Result<Option<Verdict>> {
    let file = TableFile::open(path, "dba")?;
    if !file.has_group("dba") {
        return Ok(None);
    }
    let text = |name: &str| file.texts("dba", name);
    let numbers = |name: &str| file.numbers("dba", name);
    let (checks, criteria, units, verdicts, rules) = (text("check")?, text("criterion")?, text("unit")?, text("verdict")?, text("rule")?);
    let (figures, limits) = (numbers("figure")?, numbers("limit")?);
    let n = checks.len();
    if [criteria.len(), units.len(), verdicts.len(), rules.len(), figures.len(), limits.len()].iter().any(|&l| l != n) {
        return Err(Error::input(format!("{}: /dba: columns of different lengths", path.display())));
    }
    let rows = (0..n)
        .map(|i| CheckRow {
            check: checks[i].clone(),
            criterion: criteria[i].clone(),
            figure: Some(figures[i]).filter(|f| !f.is_nan()),
            limit: limits[i],
            unit: units[i].clone(),
            passes: match verdicts[i].as_str() {
                "PASS" => Some(true),
                "FAIL" => Some(false),
                _ => None,
            },
            rule: rules[i].clone(),
        })
        .collect();
    let listed = file.group_text_attr("dba", "results")?;
    let files = listed.split("; ").filter_map(|entry| entry.split_once(": ")).map(|(name, file)| (name.to_string(), PathBuf::from(file))).collect();
    Ok(Some(Verdict { rows, files }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A check whose analysis stops without converging fails, saying where; any other error
    /// is passed on (it is not the check's answer).
    #[test]
    fn an_analysis_that_does_not_converge_fails_its_check_and_says_where() {
        let stopped = Error::NotConverged {
            step: "compress".into(),
            load_factor: 0.3698,
            reason: "DIVERGED_MAX_IT after 25 Newton iterations; the 25 converged increments before are in x.h5".into(),
        };
        let row = not_shown("ratcheting", stopped, Path::new("dir/out_ratcheting.h5"), "VIII-2 5.5.7.2").unwrap();
        assert_eq!(row.passes, Some(false));
        assert!(row.criterion.contains("step 'compress' at load factor 0.3698 (DIVERGED_MAX_IT after 25 Newton iterations;"), "{}", row.criterion);
        assert!(row.criterion.contains("out_ratcheting.h5") && !row.criterion.contains("dir/"), "{}", row.criterion);
        let verdict = Verdict { rows: vec![row], files: Vec::new() };
        assert!(!verdict.passes() && table(&verdict, "t").contains("FAIL"));
        assert!(not_shown("ratcheting", Error::input("bad"), Path::new("x.h5"), "r").is_err());
    }
}

//! `slideline bellows-sweep`: variants of a design specification (every combination of the
//! values given to its keys), each through the code check and the analyses asked, shared out
//! to the study's groups; one row per variant (its settings, the code's figures and verdict,
//! the finite-element figures, the wall time) in the study file and its CSV, a table sorted by
//! a chosen figure, and a picture of the axial rate against the allowable cycles with the
//! variants that pass marked.

use super::Outcome;
use crate::bellows::flexibility::Movements;
use crate::bellows::report::folds_first_touch;
use crate::bellows::spec::{keys, DesignSpec};
use crate::bellows::workflow::{self, BeforeTheRun, BellowsJob};
use crate::error::{Error, Result};
use crate::io::plots::{point_plot, Axes, Curve};
use crate::io::table_file::{Table, TableFile};
use crate::petsc::PetscSession;
use crate::solve::RunSummary;
use mpi::traits::Communicator;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// One `--vary KEY=VALUES`: the specification's key (`section.key`) and its values.
#[derive(Clone, Debug)]
pub struct Vary {
    pub section: String,
    pub key: String,
    pub values: Vec<toml::Value>,
}

impl Vary {
    /// The column a variant's value of this key is in.
    pub fn name(&self) -> String {
        format!("{}.{}", self.section, self.key)
    }
}

/// `KEY=VALUES` against the specification `base` (`path`'s text): KEY is `section.key`, or a
/// key found in one section of the file; VALUES a list `a,b,c`, the integers `a..b`, or `n`
/// values evenly spaced `a..b:n`. The key is tried on the specification with its first value,
/// so an unknown key or a value of the wrong kind is refused here, naming it.
pub fn parse_vary(arg: &str, base: &str, path: &Path) -> Result<Vary> {
    let bad = |why: String| Error::input(format!("--vary {arg}: {why}"));
    let (key, values) = arg.split_once('=').ok_or_else(|| bad("give KEY=VALUES (convolutions=6..12, bellows.bellows.ply_thickness=0.3,0.5)".into()))?;
    let table: toml::Table = base.parse().map_err(|e| Error::input(format!("{}: {e}", path.display())))?;
    let (section, key) = match key.trim().split_once('.') {
        Some((s, k)) => (s.to_string(), k.to_string()),
        None => {
            let key = key.trim();
            let holders: Vec<&String> = table.iter().filter(|(_, v)| v.as_table().is_some_and(|t| t.contains_key(key))).map(|(s, _)| s).collect();
            match holders.as_slice() {
                [one] => ((*one).clone(), key.to_string()),
                [] => return Err(bad(format!("no key {key:?} in {}: name it as section.key (docs/bellows-spec.md lists the keys)", path.display()))),
                _ => return Err(bad(format!("{key:?} is in several sections: name it as section.key"))),
            }
        }
    };
    let values = parse_values(values).map_err(bad)?;
    let vary = Vary { section, key, values };
    // the key and the kind of its value, checked on the specification's structure
    let text = with_values(&table, &[(&vary, &vary.values[0])])?;
    toml::from_str::<DesignSpec>(&text).map_err(|e| bad(e.message().to_string()))?;
    Ok(vary)
}

/// `a,b,c`, `a..b` (integers), `a..b:n` (n evenly spaced, ends included).
fn parse_values(text: &str) -> std::result::Result<Vec<toml::Value>, String> {
    let number = |s: &str| -> std::result::Result<toml::Value, String> {
        let s = s.trim();
        if let Ok(i) = s.parse::<i64>() {
            return Ok(toml::Value::Integer(i));
        }
        match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(toml::Value::Float(v)),
            _ => Err(format!("{s:?} is not a number")),
        }
    };
    let values: Vec<toml::Value> = if let Some((a, rest)) = text.split_once("..") {
        let (b, count) = match rest.split_once(':') {
            Some((b, n)) => (b, Some(n.trim().parse::<usize>().map_err(|_| format!("{n:?} is not a count of values"))?)),
            None => (rest, None),
        };
        let (a, b) = (number(a)?, number(b)?);
        match (count, &a, &b) {
            (None, toml::Value::Integer(a), toml::Value::Integer(b)) => (*a..=*b).map(toml::Value::Integer).collect(),
            (None, _, _) => return Err("a range without a count is of integers (a..b); give a..b:n for n values".into()),
            (Some(n), a, b) => {
                let (a, b) =
                    (a.as_float().or(a.as_integer().map(|i| i as f64)).unwrap_or(0.0), b.as_float().or(b.as_integer().map(|i| i as f64)).unwrap_or(0.0));
                match n {
                    0 => Vec::new(),
                    1 => vec![toml::Value::Float(a)],
                    _ => (0..n).map(|k| toml::Value::Float(a + (b - a) * k as f64 / (n - 1) as f64)).collect(),
                }
            }
        }
    } else {
        text.split(',').map(number).collect::<std::result::Result<_, _>>()?
    };
    if values.is_empty() {
        return Err("the range is empty".into());
    }
    Ok(values)
}

/// The specification's text with each key set to its value (as a flag sets it:
/// `bellows::spec::keys`).
fn with_values(base: &toml::Table, settings: &[(&Vary, &toml::Value)]) -> Result<String> {
    let mut table = base.clone();
    for (vary, value) in settings {
        keys::set(&mut table, &vary.name(), (*value).clone()).map_err(|why| Error::input(format!("--vary {}: {why}", vary.name())))?;
    }
    toml::to_string(&table).map_err(|e| Error::Internal(format!("the variant's specification: {e}")))
}

/// One variant: its settings and its specification's text.
#[derive(Clone, Debug)]
pub struct Variant {
    pub settings: Vec<(String, f64)>,
    pub text: String,
}

impl Variant {
    pub fn label(&self) -> String {
        self.settings.iter().map(|(k, v)| format!("{}={v}", k.rsplit('.').next().unwrap_or(k))).collect::<Vec<_>>().join(" ")
    }
}

/// Every combination of the values (the first key varying slowest).
pub fn variants(base: &str, vary: &[Vary]) -> Result<Vec<Variant>> {
    let count: usize = vary.iter().map(|v| v.values.len()).product();
    if count > super::MOST_RUNS {
        return Err(Error::input(format!("--vary: {count} variants, more than {}: fewer values", super::MOST_RUNS)));
    }
    let table: toml::Table = base.parse().map_err(|e| Error::input(format!("the specification: {e}")))?;
    (0..count)
        .map(|mut k| {
            let mut picks = vec![0; vary.len()];
            for (i, v) in vary.iter().enumerate().rev() {
                picks[i] = k % v.values.len();
                k /= v.values.len();
            }
            let settings: Vec<(&Vary, &toml::Value)> = vary.iter().zip(&picks).map(|(v, &p)| (v, &v.values[p])).collect();
            let numbers = settings.iter().map(|(v, x)| (v.name(), x.as_float().or(x.as_integer().map(|i| i as f64)).unwrap_or(f64::NAN))).collect();
            Ok(Variant { settings: numbers, text: with_values(&table, &settings)? })
        })
        .collect()
}

/// The analyses each variant goes through beside the code check.
#[derive(Clone, Copy, Debug, Default)]
pub struct Analyses {
    pub assess: bool,
    pub squirm: bool,
    pub frequencies: bool,
    pub lateral: Option<f64>,
    pub angular: Option<f64>,
    /// No elastic-plastic run of the design movement (the code check and the analyses at rest).
    pub elastic_only: bool,
}

/// What a sweep runs and how it reports.
pub struct SweepPlan {
    /// The specification the variants start from, and its file.
    pub base: String,
    pub path: PathBuf,
    pub vary: Vec<Vary>,
    pub analyses: Analyses,
    /// The column the printed table is sorted by.
    pub sort: String,
    pub output: PathBuf,
    pub progress: bool,
    pub full_output: bool,
}

/// One variant's answers.
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
pub struct SweepRow {
    pub variant: usize,
    pub label: String,
    pub settings: Vec<(String, f64)>,
    pub outcome: Outcome,
    pub reason: String,
    /// PASS, FAIL (the failing checks) or NOT APPLICABLE: the code's verdict ("" without one).
    pub verdict: String,
    pub passes: bool,
    /// Each code check: (name, value, limit, unit).
    pub checks: Vec<(String, f64, f64, String)>,
    /// The figures, (name, value, unit), in the order of [`FIGURES`]; NaN where not computed.
    pub figures: Vec<(String, f64, String)>,
    pub wall_time: f64,
    pub results: PathBuf,
}

/// The figures of a row, in order, with their units.
pub const FIGURES: [(&str, &str); 18] = [
    ("c1", ""),
    ("c2", ""),
    ("axial_rate", "N/mm"),
    ("allowable_cycles", "cycles"),
    ("equivalent_movement", "mm"),
    ("effective_area", "mm^2"),
    ("pressure_thrust", "N"),
    ("fe_axial_rate", "N/mm"),
    ("fe_squirm_pressure", "MPa"),
    ("fe_in_plane_pressure", "MPa"),
    ("fe_lateral_rate", "N/mm"),
    ("fe_angular_rate", "N mm/deg"),
    ("fe_axial_frequency", "Hz"),
    ("fe_lateral_frequency", "Hz"),
    ("end_force", "N"),
    ("folds_touch_at", "mm"),
    ("max_plastic_strain", ""),
    ("newton_iterations", ""),
];

impl SweepRow {
    fn new(variant: usize, v: &Variant, results: PathBuf) -> Self {
        SweepRow {
            variant,
            label: v.label(),
            settings: v.settings.clone(),
            outcome: Outcome::Failed,
            reason: String::new(),
            verdict: String::new(),
            passes: false,
            checks: Vec::new(),
            figures: FIGURES.iter().map(|(n, u)| (n.to_string(), f64::NAN, u.to_string())).collect(),
            wall_time: 0.0,
            results,
        }
    }

    fn set(&mut self, name: &str, value: f64) {
        if let Some(f) = self.figures.iter_mut().find(|f| f.0 == name) {
            f.1 = value;
        }
    }

    /// A figure or a check's value by its column name.
    pub fn figure(&self, name: &str) -> f64 {
        self.figures.iter().find(|f| f.0 == name).map(|f| f.1).or_else(|| self.settings.iter().find(|s| s.0 == name).map(|s| s.1)).unwrap_or(f64::NAN)
    }

    /// The code's figures and the analyses at rest.
    fn take_before(&mut self, before: &BeforeTheRun) {
        if let Some(c) = &before.code {
            self.set("c1", c.c1);
            self.set("c2", c.c2);
            self.set("axial_rate", c.axial_rate);
        }
        if let Some((v, _)) = &before.verdict {
            self.verdict = v.summary();
            self.passes = v.outside.is_empty() && v.failed().is_empty();
            self.checks = v.checks.iter().map(|c| (c.name.clone(), c.value, c.limit, c.unit.clone())).collect();
            self.set("allowable_cycles", v.allowable_cycles);
            self.set("equivalent_movement", v.equivalent_movement);
            self.set("effective_area", v.effective_area);
            self.set("pressure_thrust", v.pressure_thrust);
        }
        if let Some(s) = &before.stable {
            self.set("fe_axial_rate", s.axial_rate);
            self.set("fe_squirm_pressure", s.squirm.unwrap_or(f64::NAN));
            self.set("fe_in_plane_pressure", s.in_plane.unwrap_or(f64::NAN));
        }
        if let Some((_, f)) = &before.rest {
            self.set("fe_axial_rate", f.axial_rate);
            self.set("fe_lateral_rate", f.lateral.as_ref().map_or(f64::NAN, |m| m.rate));
            self.set("fe_angular_rate", f.angular.as_ref().map_or(f64::NAN, |m| m.rate));
        }
        if let Some(f) = &before.vibrating {
            self.set("fe_axial_rate", f.axial_rate);
            self.set("fe_axial_frequency", f.axial.as_ref().map_or(f64::NAN, |m| m.frequency));
            self.set("fe_lateral_frequency", f.lateral.as_ref().map_or(f64::NAN, |m| m.frequency));
        }
    }

    /// The elastic-plastic run's figures: the moving end's force (full ring, compression
    /// positive), the compression at which the folds first touch (NaN: never), the largest
    /// plastic strain, the Newton iterations.
    fn take_run(&mut self, summary: &RunSummary) {
        let Some(last) = summary.history.last() else { return };
        let force = last.reactions.iter().find(|(set, _)| set == "moving_end").map_or(f64::NAN, |(_, f)| -f[1] * 2.0 * std::f64::consts::PI);
        self.set("end_force", force);
        let compression = |k: usize| summary.history[k].set_displacements.iter().find(|(set, _)| set == "moving_end").map_or(f64::NAN, |(_, u)| -u[1]);
        self.set("folds_touch_at", folds_first_touch(&summary.history).map_or(f64::NAN, compression));
        self.set("max_plastic_strain", summary.history.iter().map(|r| r.max_plastic_strain).fold(0.0, f64::max));
        self.set("newton_iterations", summary.history.iter().map(|r| r.newton_iterations).sum::<usize>() as f64);
    }
}

/// Runs the sweep over the session's groups (collective over every rank); world rank 0
/// returns the rows in variant order, having written the study file, its CSV and picture.
pub fn bellows_sweep(session: &PetscSession, spec: &SweepPlan) -> Result<Vec<SweepRow>> {
    let root = session.everyone().rank() == 0;
    let all = variants(&spec.base, &spec.vary)?;
    if !sortable(&spec.sort, &spec.vary) {
        return Err(Error::input(format!(
            "--sort {}: not a figure of the sweep (one of {}, or a varied key)",
            spec.sort,
            FIGURES.iter().map(|f| f.0).collect::<Vec<_>>().join(", ")
        )));
    }
    let (_lock, dir) = super::prepare(session, &spec.output, &[(&spec.path, "the --spec file")])?;
    if root && spec.progress {
        let groups = session.groups().map_or(1, |g| g.count);
        println!("bellows-sweep: {} variants on {groups} group(s) of {} rank(s), results in {}", all.len(), session.world().size(), dir.display());
    }
    let total = all.len();
    let rows = super::pool::run_rows(
        session,
        total,
        |k| run_variant(session, spec, &dir, k, &all[k]),
        |done: &[SweepRow], newest| {
            if spec.progress {
                let r = &done[newest];
                println!("  [{}/{total}] {} ({:.1} s): {}", done.len(), r.label, r.wall_time, outcome_text(r));
            }
            if let Err(e) = write_study(spec, done) {
                println!("note: the study file could not be written: {e}");
            }
        },
    );
    if root {
        write_study(spec, &rows)?;
        let picture = picture(spec, &rows)?;
        println!("{}", table(spec, &rows));
        println!("study: {} and {}\npicture: {}", spec.output.display(), spec.output.with_extension("csv").display(), picture.display());
    }
    Ok(rows)
}

/// Whether `name` is a column the table can be sorted by.
fn sortable(name: &str, vary: &[Vary]) -> bool {
    FIGURES.iter().any(|f| f.0 == name) || vary.iter().any(|v| v.name() == name)
}

fn outcome_text(r: &SweepRow) -> String {
    match r.outcome {
        Outcome::Converged => r.verdict.clone(),
        other => format!("{}: {}", other.label(), r.reason),
    }
}

/// One variant on its group's ranks: the code check and the analyses at rest, then unless
/// elastic-only the run of the design movement; a variant that fails is a row that says why.
fn run_variant(session: &PetscSession, spec: &SweepPlan, dir: &Path, k: usize, v: &Variant) -> SweepRow {
    let start = Instant::now();
    let results = dir.join(format!("variant_{k:03}.h5"));
    let mut row = SweepRow::new(k, v, results.clone());
    let a = spec.analyses;
    let mut answers = || -> Result<()> {
        let mut params = DesignSpec::from_text(&v.text, &spec.path)?;
        super::study_output(&mut params.joint.output_every, spec.full_output);
        params.validate_joint()?;
        let movements = Movements::checked(a.lateral, a.angular, &params)?;
        let job = BellowsJob {
            params,
            report: None,
            movements,
            output: results.clone(),
            quiet: true,
            verbose: false,
            monitor: false,
            restart: None,
            squirm: a.squirm,
            assess: a.assess,
            frequencies: a.frequencies,
        };
        let before = workflow::before_the_run(session, &job)?;
        row.take_before(&before);
        if !a.elastic_only {
            row.take_run(&workflow::run(session, &job)?);
        }
        Ok(())
    };
    let result = answers();
    (row.outcome, row.reason) = Outcome::of(&result);
    row.wall_time = start.elapsed().as_secs_f64();
    row
}

/// The study's table: the variant, its settings, outcome and verdict, the figures, each
/// check's value and limit, the wall time and the reason of a failure.
fn study_table(rows: &[SweepRow], vary: &[Vary]) -> Table {
    let mut t = Table::default();
    t.numbers("variant", "", rows.iter().map(|r| r.variant as f64).collect());
    t.text("label", rows.iter().map(|r| r.label.clone()).collect());
    for v in vary {
        t.numbers(&v.name(), "", rows.iter().map(|r| r.figure(&v.name())).collect());
    }
    t.text("outcome", rows.iter().map(|r| r.outcome.label().to_string()).collect());
    t.text("verdict", rows.iter().map(|r| r.verdict.clone()).collect());
    t.numbers("passes", "", rows.iter().map(|r| f64::from(u8::from(r.passes))).collect());
    for (name, unit) in FIGURES {
        t.numbers(name, unit, rows.iter().map(|r| r.figure(name)).collect());
    }
    // the checks, by the names the first variant with a verdict gives them
    if let Some(first) = rows.iter().find(|r| !r.checks.is_empty()) {
        for (k, (name, _, _, unit)) in first.checks.iter().enumerate() {
            let slug: String = name.to_lowercase().chars().map(|c| if c.is_ascii_alphanumeric() { c } else { '_' }).collect();
            let slug = slug.split('_').filter(|s| !s.is_empty()).collect::<Vec<_>>().join("_");
            let pick = |f: fn(&(String, f64, f64, String)) -> f64| rows.iter().map(|r| r.checks.get(k).map_or(f64::NAN, f)).collect();
            t.numbers(&format!("{slug}_value"), unit, pick(|c| c.1));
            t.numbers(&format!("{slug}_limit"), unit, pick(|c| c.2));
        }
    }
    t.numbers("wall_time", "s", rows.iter().map(|r| r.wall_time).collect());
    t.text("reason", rows.iter().map(|r| r.reason.clone()).collect());
    t.text("results", rows.iter().map(|r| r.results.display().to_string()).collect());
    t
}

/// The study file (/variants/COLUMN, and the base specification's text as an attribute) and
/// the CSV, each written whole.
fn write_study(spec: &SweepPlan, rows: &[SweepRow]) -> Result<()> {
    let t = study_table(rows, &spec.vary);
    let path = &spec.output;
    super::write_whole(path, |part| {
        let file = TableFile::create(part)?;
        file.text_attr(None, "specification", &spec.base)?;
        file.table("variants", &t)
    })?;
    super::write_whole(&path.with_extension("csv"), |part| t.write_csv(part))
}

/// The printed table, sorted by `spec.sort` (ascending; variants without it last).
pub fn table(spec: &SweepPlan, rows: &[SweepRow]) -> String {
    let mut sorted: Vec<&SweepRow> = rows.iter().collect();
    sorted.sort_by(|a, b| {
        let (x, y) = (a.figure(&spec.sort), b.figure(&spec.sort));
        x.is_nan().cmp(&y.is_nan()).then(x.total_cmp(&y))
    });
    let mut s = String::new();
    let _ = writeln!(s, "variants sorted by {}:", spec.sort);
    let _ = writeln!(
        s,
        "{:>4} {:<40} {:>12} {:>14} {:>12} {:>12} {:>10} {:>8}  verdict",
        "#", "settings", "rate N/mm", "allow. cycles", "FE rate N/mm", "end force N", "folds mm", "wall s"
    );
    // a figure not computed (an analysis not asked, a variant that failed) is a dash
    let shown = |v: f64, digits: usize| if v.is_finite() { format!("{v:.digits$}") } else { "-".into() };
    for r in sorted {
        let _ = writeln!(
            s,
            "{:>4} {:<40} {:>12} {:>14} {:>12} {:>12} {:>10} {:>8.1}  {}",
            r.variant,
            r.label,
            shown(r.figure("axial_rate"), 1),
            shown(r.figure("allowable_cycles"), 0),
            shown(r.figure("fe_axial_rate"), 1),
            shown(r.figure("end_force"), 0),
            // a run that reached its stroke with the folds apart, beside one not made or cut short
            if r.outcome == Outcome::Converged && r.figure("end_force").is_finite() && r.figure("folds_touch_at").is_nan() {
                "never".into()
            } else {
                shown(r.figure("folds_touch_at"), 1)
            },
            r.wall_time,
            outcome_text(r)
        );
    }
    s
}

/// The axial rate against the allowable cycles (log10), the variants that pass every check
/// apart from those that do not: the trade-off at a glance (`STEM_rate_cycles.png`).
fn picture(spec: &SweepPlan, rows: &[SweepRow]) -> Result<PathBuf> {
    let path = PathBuf::from(format!("{}_rate_cycles.png", spec.output.with_extension("").display()));
    let point = |r: &&SweepRow| (r.figure("allowable_cycles").log10(), r.figure("axial_rate"));
    let kinds = [
        Curve { label: "passes every check".into(), points: rows.iter().filter(|r| r.passes).map(|r| point(&r)).collect() },
        Curve { label: "fails a check (or outside the code)".into(), points: rows.iter().filter(|r| !r.passes).map(|r| point(&r)).collect() },
    ];
    let required = rows.iter().find_map(|r| r.checks.iter().find(|c| c.0 == "fatigue").map(|c| c.2));
    let title = match required {
        Some(n) => format!("Design variants: axial rate against allowable cycles ({n} required)"),
        None => "Design variants: axial rate against allowable cycles".to_string(),
    };
    point_plot(&path, &title, "log10 allowable cycles (code)", "axial rate (N/mm, code)", &kinds, Axes::DataRange)?;
    Ok(path)
}

//! The bellows run's closing report: the figures the seed paper quotes (end reaction per
//! 2.5-degree sector, stiffness, largest von Mises stress) next to slideline's, with what the
//! paper does not give (plastic strain, penetration, effort), and the pictures (force vs
//! displacement, deformed joint coloured by von Mises at an intermediate and the last
//! increment). Rank 0 only, after the run: fields are read back from the results file.

use crate::assessment::code::CodeCheck;
use crate::assessment::fe_check::{FeCheck, Peak, StrainLife};
use crate::bellows::joint::FOLD_PAIRS;
use crate::bellows::spec::DesignSpec;
use crate::error::Result;
use crate::fe::shape::Shape;
use crate::io::plots::{deformed_field, line_plot, Axes, Curve, FieldPicture, Marker};
use crate::io::reader::ResultsReader;
use crate::io::HistoryRow;
use crate::records::energy::Energies;
use crate::solve::RunSummary;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

mod code_tables;
pub mod html;
mod mode_picture;
mod sections;
pub use code_tables::{code_section, verdict_table, CODE_VERDICT, EDITION};
pub use mode_picture::mode_picture;
pub use sections::{flexibility_section, frequencies_columns, frequencies_section, stability_columns, stability_section};

/// The paper modelled a 2.5-degree sector; its forces are per sector.
pub const SECTOR_RADIANS: f64 = 2.5 * PI / 180.0;

/// The seed paper's results (MSC Nastran): end reaction at 70 mm (N per 2.5-degree sector),
/// stiffness (N/mm per sector), largest von Mises stress (MPa).
pub const PAPER_REACTION: f64 = 1131.0;
pub const PAPER_STIFFNESS: f64 = 16.16;
pub const PAPER_VON_MISES: f64 = 103.36;

/// Where a field reaches its largest value.
#[derive(Clone, Debug)]
pub struct Extreme {
    pub value: f64,
    /// The element set (part) of the element, e.g. "ply2".
    pub part: String,
    /// Deformed position of the element's centre, (r, z) mm.
    pub at: [f64; 2],
}

#[derive(Clone, Debug)]
pub struct BellowsReport {
    /// Applied axial compression at the end of the compression (the last increment of step 2),
    /// mm.
    pub displacement: f64,
    /// The compression step 2 asks for, mm: a run that stopped short has `displacement` less.
    pub stroke: f64,
    /// Axial reaction at the moving end after step 1 (heat and pressure) and at the end, N per
    /// sector (compression positive).
    pub preload: f64,
    pub reaction: f64,
    /// Secant (F - F1)/u, the step-1 reaction F1 (temperature, pressure) subtracted, and
    /// initial dF/du (first compression increment), N/mm per sector.
    pub secant_stiffness: f64,
    pub initial_stiffness: f64,
    /// The code check (EJMA) of the joint's bellows at its pressure and stroke (None where the
    /// convolution is outside the charts).
    pub code: Option<CodeCheck>,
    /// The increment (its run-wide number) and compression (mm) the largest von Mises stress
    /// and plastic strain are read at: the end of the compression where a file of the run
    /// holds its fields.
    pub fields_at: (usize, f64),
    pub von_mises: Extreme,
    pub plastic_strain: Extreme,
    /// (compression mm, end reaction N per sector) where the folds first bear on each other
    /// ([`folds_first_touch`]); None where they never do.
    pub folds_touch: Option<(f64, f64)>,
    /// Largest ply-to-ply and sleeve penetration over the whole history, mm.
    pub ply_penetration: f64,
    pub sleeve_penetration: f64,
    pub ply_thickness: f64,
    pub increments: usize,
    pub cutbacks: usize,
    pub newton_iterations: usize,
    /// Wall time of the whole history (a restart's clock goes on from its file's), s.
    pub wall_time: f64,
    /// Wall time of this run alone, s.
    pub run_wall_time: f64,
    /// Increments a restart took over from its file (0 for a fresh run).
    pub continued: usize,
    pub ranks: usize,
    /// (applied displacement mm, reaction N per sector) at every converged increment.
    pub curve: Vec<(f64, f64)>,
    /// A load cycle (the joint compressed and brought back): the loop's area (N mm per sector:
    /// the work the end reaction did over the cycle, dissipated or left stored as residual
    /// stress) and the reaction once back at zero, N per sector.
    pub cycle: Option<(f64, f64)>,
    /// Friction coefficients between the plies and of the sleeve.
    pub friction: (f64, f64),
    /// The energy audit at the last increment, N mm per sector.
    pub energy: Option<Energies>,
    /// Whether the joint is the seed paper's (whatever its mesh, stepping or contact
    /// parameters): only then is the paper's column beside slideline's.
    pub seed: bool,
    /// Whether the code check's section closes the table; not where a design specification's
    /// verdict follows it (the verdict has the same stresses, and the life the design rests on).
    pub code_section: bool,
    /// The finite-element joint set beside the code's (`bellows::twin`), after a blank line.
    pub twin: String,
}

/// Axial reaction of the moving end, N per sector, compression positive.
fn end_reaction(row: &HistoryRow) -> f64 {
    row.reactions.iter().find(|(set, _)| set == "moving_end").map(|(_, f)| -f[1] * SECTOR_RADIANS).unwrap_or(f64::NAN)
}

/// Applied compression at a row: zero in step 1, the load factor's share in step 2, back to
/// zero through step 3 (a cycle's return).
fn applied(row: &HistoryRow, p: &DesignSpec) -> f64 {
    compression(row.step, row.load_factor, p.displacement())
}

/// The compression (mm) at `load_factor` of `step` of a joint compressed by `stroke`.
fn compression(step: usize, load_factor: f64, stroke: f64) -> f64 {
    match step {
        2 => load_factor * stroke,
        3 => (1.0 - load_factor) * stroke,
        _ => 0.0,
    }
}

/// The increments the report draws, of those with fields (`written`: name, step, load
/// factor), each with its compression (mm) and what it is: half the stroke, the stroke (the
/// end of step 2) and the last increment (a cycle's end), as far as the run got.
fn picture_increments(written: &[(String, usize, f64)], stroke: f64) -> Vec<(String, f64, &'static str)> {
    let half = written.iter().find(|w| w.1 == 2 && w.2 >= 0.5).map(|w| (w, "half the stroke"));
    let full = written.iter().rfind(|w| w.1 == 2 && w.2 >= 1.0).map(|w| (w, "the stroke"));
    let end = written.last().map(|w| (w, if w.1 == 3 && w.2 >= 1.0 { "the cycle's end" } else { "the last increment" }));
    let mut picks: Vec<(String, f64, &'static str)> = Vec::new();
    // a step 2 of one increment: its half and its end are the same picture
    for ((name, step, load_factor), what) in [half, full, end].into_iter().flatten() {
        if picks.last().is_none_or(|last| last.0 != *name) {
            picks.push((name.clone(), compression(*step, *load_factor, stroke), what));
        }
    }
    picks
}

/// Work of the end reaction around the force-displacement curve from the end of step 1 on,
/// N mm per sector: the area of the loop when the curve comes back (trapezoids).
fn loop_area(curve: &[(f64, f64)], from: usize) -> f64 {
    curve[from..].windows(2).map(|w| 0.5 * (w[0].1 + w[1].1) * (w[1].0 - w[0].0)).sum()
}

/// The first increment of the compression (step 2) at which the convolutions' folds bear on
/// each other (a node of a [`FOLD_PAIRS`] pair in contact): from there on the joint stiffens as
/// a closing stack of plies, which the code's formulas (free convolutions) do not describe.
pub fn folds_first_touch(history: &[HistoryRow]) -> Option<usize> {
    history.iter().position(|r| r.step == 2 && r.contacts.iter().any(|c| FOLD_PAIRS.contains(&c.name.as_str()) && c.active_nodes > 0))
}

fn largest_penetration(history: &[HistoryRow], pair: impl Fn(&str) -> bool) -> f64 {
    history.iter().flat_map(|r| &r.contacts).filter(|c| pair(&c.name)).map(|c| c.max_penetration).fold(0.0, f64::max)
}

/// The file holding increment `number`'s fields when `reader`'s does not: the file it was
/// restarted from, or that one's (None: `reader`'s own, or no file of the chain has them).
fn file_holding(reader: &ResultsReader, number: usize) -> Option<Option<ResultsReader>> {
    let name = format!("{number:06}");
    let has = |r: &ResultsReader| r.increments().is_ok_and(|names| names.contains(&name)) && r.field(&name, "von_mises").is_ok();
    if has(reader) {
        return Some(None);
    }
    let mut from = reader.restarted_from();
    for _ in 0..64 {
        let earlier = ResultsReader::open(&from?.0).ok()?;
        if has(&earlier) {
            return Some(Some(earlier));
        }
        from = earlier.restarted_from();
    }
    None
}

/// Largest value of a per-Gauss-point field at an increment, with its element's part and
/// deformed centre.
fn extreme(reader: &ResultsReader, increment: &str, field: &str) -> Result<Extreme> {
    let values = reader.field(increment, field)?;
    let conn = reader.connectivity()?;
    let per_element = values.len() / conn.len().max(1);
    // (a reduced element's spare Gauss slots hold NaN)
    let (k, &value) = values.iter().enumerate().filter(|v| !v.1.is_nan()).max_by(|a, b| a.1.total_cmp(b.1)).unwrap_or((0, &f64::NAN));
    let element = k / per_element.max(1);
    let (x0, u) = (reader.coordinates()?, reader.displacement(increment)?);
    let corners = &conn[element][..Shape::of(&conn[element]).corners()];
    let at = [0, 1].map(|c| corners.iter().map(|&n| x0[n][c] + u[n][c]).sum::<f64>() / corners.len() as f64);
    let mut part = String::from("?");
    for name in reader.element_set_names()? {
        if name != "all" && reader.element_set(&name)?.contains(&element) {
            part = name;
            break;
        }
    }
    Ok(Extreme { value, part, at })
}

impl BellowsReport {
    pub fn new(p: &DesignSpec, code: Option<CodeCheck>, run: &RunSummary, reader: &ResultsReader) -> Result<Self> {
        let history = &run.history;
        let curve: Vec<(f64, f64)> = history.iter().map(|r| (applied(r, p), end_reaction(r))).collect();
        let heated = history.iter().rposition(|r| r.step == 1);
        let preload = heated.map(|k| curve[k].1).unwrap_or(0.0);
        let initial_stiffness = match heated {
            Some(k) if k + 1 < curve.len() => (curve[k + 1].1 - curve[k].1) / (curve[k + 1].0 - curve[k].0),
            _ => f64::NAN,
        };
        // the paper's figures at the end of the compression (the cycle's turning point)
        let compressed = history.iter().rposition(|r| r.step == 2).unwrap_or(curve.len().saturating_sub(1));
        let &(displacement, reaction) = curve.get(compressed).unwrap_or(&(0.0, f64::NAN));
        let cycle = (p.joint.cycle && history.last().is_some_and(|r| r.step == 3 && r.load_factor >= 1.0))
            .then(|| (loop_area(&curve, heated.unwrap_or(0)), curve.last().map_or(f64::NAN, |c| c.1)));
        // fields at the end of the compression (always written: the last increment of a step),
        // from the file that holds them: a restart after it (a cycle carried on) continues a
        // file that does; else the last increment written, and the rows say which
        let (file, fields_at) = match history.get(compressed).and_then(|r| file_holding(reader, r.number).map(|f| (f, (r.number, displacement)))) {
            Some(found) => found,
            None => {
                let last = reader.increments()?.last().cloned().unwrap_or_default();
                let number = last.parse().unwrap_or(0);
                let at = history.iter().find(|r| r.number == number).map_or(f64::NAN, |r| applied(r, p));
                (None, (number, at))
            }
        };
        let fields = file.as_ref().unwrap_or(reader);
        let last = format!("{:06}", fields_at.0);
        Ok(BellowsReport {
            displacement,
            stroke: p.displacement(),
            preload,
            reaction,
            secant_stiffness: (reaction - preload) / displacement,
            initial_stiffness,
            code,
            von_mises: extreme(fields, &last, "von_mises")?,
            plastic_strain: extreme(fields, &last, "equivalent_plastic_strain")?,
            fields_at,
            folds_touch: folds_first_touch(history).map(|k| curve[k]),
            ply_penetration: largest_penetration(history, |n| n.starts_with("ply")),
            sleeve_penetration: largest_penetration(history, |n| n == "sleeve"),
            ply_thickness: p.bellows.ply_thickness,
            increments: history.len(),
            cutbacks: history.iter().map(|r| r.cutbacks).sum(),
            newton_iterations: history.iter().map(|r| r.newton_iterations).sum(),
            wall_time: history.last().map_or(run.wall_time, |r| r.wall_time),
            run_wall_time: run.wall_time,
            continued: run.continued,
            ranks: run.ranks,
            curve,
            cycle,
            friction: (p.joint.friction_plies, p.joint.friction_sleeve),
            energy: history.last().and_then(|r| r.energy),
            seed: p.is_seed_joint(),
            code_section: true,
            twin: crate::bellows::twin::section(p, reader)?,
        })
    }

    /// The closing table: the seed joint's beside the paper, per 2.5-degree sector as the paper
    /// gives its forces; any other joint's alone, its forces over the full ring.
    pub fn table(&self) -> String {
        let ring = 2.0 * PI / SECTOR_RADIANS;
        let seed = self.seed;
        // the forces' scale and unit: the paper's sector for the seed joint, else the ring
        let (scale, per) = if seed { (1.0, "per sector") } else { (ring, "full ring") };
        let mut t = String::new();
        let mut line = |what: &str, ours: String, paper: &str| match seed {
            true => t.push_str(&format!("  {what:<52} {ours:>20}   {paper:>12}\n")),
            false => t.push_str(&format!("  {what:<52} {ours:>20}\n")),
        };
        line("", "slideline".into(), "paper");
        if seed {
            line(&format!("end reaction at {:.1} mm, N per 2.5-deg sector", self.displacement), format!("{:.1}", self.reaction), &format!("{PAPER_REACTION}"));
        }
        line(
            &format!("end reaction at {:.1} mm, N full ring", self.displacement),
            format!("{:.0}", self.reaction * ring),
            &format!("{:.0}", PAPER_REACTION * ring),
        );
        line(&format!("  step 1's part (temperature, pressure), N {per}"), format!("{:.1}", self.preload * scale), "-");
        line(&format!("stiffness (F - F1)/u, N/mm {per}"), format!("{:.2}", self.secant_stiffness * scale), &format!("{PAPER_STIFFNESS}"));
        line(&format!("initial stiffness, N/mm {per}"), format!("{:.2}", self.initial_stiffness * scale), "-");
        if let Some(c) = &self.code {
            line(&format!("EJMA rate (Cf {:.3} {}), N/mm {per}", c.coefficients.cf, c.source.label()), format!("{:.2}", c.axial_rate * scale / ring), "-");
        }
        let (number, at) = self.fields_at;
        line(&format!("max von Mises (Gauss point) at {at:.1} mm (#{number}), MPa"), format!("{:.2}", self.von_mises.value), &format!("{PAPER_VON_MISES}"));
        line("  where (part, deformed r, z mm)", format!("{} ({:.1}, {:.1})", self.von_mises.part, self.von_mises.at[0], self.von_mises.at[1]), "-");
        line(&format!("max equivalent plastic strain at {at:.1} mm (#{number})"), format!("{:.4}", self.plastic_strain.value), "-");
        line(
            "  where (part, deformed r, z mm)",
            format!("{} ({:.1}, {:.1})", self.plastic_strain.part, self.plastic_strain.at[0], self.plastic_strain.at[1]),
            "-",
        );
        line(
            "max ply-to-ply penetration, mm (% of ply)",
            format!("{:.2e} ({:.2} %)", self.ply_penetration, 100.0 * self.ply_penetration / self.ply_thickness),
            "-",
        );
        line("max sleeve penetration, mm", format!("{:.2e}", self.sleeve_penetration), "-");
        line(
            &format!("folds first touch at, mm (end reaction there, N {per})"),
            self.folds_touch.map_or("never".into(), |(at, force)| format!("{at:.1} ({:.1})", force * scale)),
            "-",
        );
        if self.friction != (0.0, 0.0) {
            line("friction mu, plies / sleeve", format!("{} / {}", self.friction.0, self.friction.1), "0 / 0");
        }
        if let Some((area, back)) = self.cycle {
            line(&format!("cycle: loop area, N mm {per}"), format!("{:.1}", area * scale), "-");
            line(&format!("cycle: reaction back at 0 mm, N {per}"), format!("{:.1}", back * scale), "-");
        }
        if let Some(e) = self.energy {
            // as the forces
            let s = |v: f64| format!("{:.1}", v * SECTOR_RADIANS * scale);
            line(&format!("energy, N mm {per}: external work"), s(e.external_work), "-");
            line("  stored elastic / plastic work", format!("{} / {}", s(e.elastic), s(e.plastic_work)), "-");
            line("  thermal work / friction dissipated", format!("{} / {}", s(e.thermal_work), s(e.friction_dissipation)), "-");
            line(
                "  balance error (% of the external work)",
                format!("{} ({:.3} %)", s(e.balance_error()), 100.0 * e.balance_error() / e.external_work.abs().max(f64::MIN_POSITIVE)),
                "-",
            );
        }
        line("increments / cutbacks", format!("{} / {}", self.increments, self.cutbacks), "240");
        line("Newton iterations", format!("{}", self.newton_iterations), "-");
        line(&format!("wall time on {} rank(s), s", self.ranks), format!("{:.1}", self.wall_time), "-");
        if self.continued > 0 {
            let added = self.increments - self.continued;
            line(&format!("  a restart from #{}: this run's increments, s", self.continued), format!("{added} in {:.1}", self.run_wall_time), "-");
        }
        t.push_str(if !seed {
            ""
        } else {
            "  why they differ: slideline follows the plies past yield (sigma_y 300 MPa, H 1000 MPa) from a few mm of\n  \
             compression on, so the force levels off near the collapse load; the paper's 103 MPa and its linear\n  \
             1131 N = 16.16 N/mm x 70 mm are an elastic response, and its convolution shape (Figure 1) is not given.\n"
        });
        if let Some(c) = self.code.as_ref().filter(|_| self.code_section) {
            t.push_str(&code_section(c));
        }
        t.push('\n');
        t.push_str(&self.twin);
        t
    }
}

fn peak_of(p: &Peak) -> Option<(f64, &str)> {
    Some((p.value, p.at.as_str()))
}

/// The design assessment's section: each figure by the code (EJMA, the coefficients as the
/// check has them) beside the finite-element value of the joint itself and their ratio; then the
/// life from the elastic-plastic run's own strain range.
pub fn assessment_section(c: &CodeCheck, fe: &FeCheck, life: Option<&StrainLife>) -> String {
    let mut t = format!(
        "\n  design assessment: code (EJMA, coefficients {}) beside finite elements (linear elastic, the joint itself, each ply's membrane stress from its nodal forces, its bending stress linearised)\n",
        c.source.label()
    );
    t.push_str(&format!("  {:<50} {:>10} {:>10} {:>8}   {}\n", "", "code", "FE", "FE/code", "FE's largest at"));
    let mut row = |what: &str, code: f64, ours: Option<(f64, &str)>, digits: usize| {
        let value = |v: f64| match v {
            v if v.is_nan() => "-".to_string(),
            v if v.is_infinite() => "endurance".to_string(),
            v => format!("{v:.digits$}"),
        };
        let (fe, ratio, at) = match ours {
            Some((v, at)) => (value(v), if v.is_finite() && code.is_finite() { format!("{:.2}", v / code) } else { "-".into() }, at),
            None => ("-".to_string(), "-".to_string(), ""),
        };
        t.push_str(&format!("  {what:<50} {:>10} {fe:>10} {ratio:>8}   {at}\n", value(code)));
    };
    row("S2 hoop membrane, convolution mean, pressure, MPa", c.s2, peak_of(&fe.s2), 1);
    row("S3 meridional membrane, pressure, MPa", c.s3, peak_of(&fe.s3), 1);
    row("S4 meridional bending, pressure, MPa", c.s4, peak_of(&fe.s4), 1);
    row("S5 meridional membrane, stroke, MPa", c.s5, peak_of(&fe.s5), 1);
    row("S6 meridional bending, stroke, MPa", c.s6, peak_of(&fe.s6), 0);
    row("St = 0.7 (S3 + S4) + S5 + S6, MPa", c.stress_range, peak_of(&fe.stress_range), 0);
    row("axial rate, N/mm full ring", c.axial_rate, Some((fe.axial_rate, "")), 1);
    let cycles = |n: Option<f64>| n.unwrap_or(f64::INFINITY);
    row("allowable cycles from St (as-formed curve)", cycles(c.cycles), Some((cycles(fe.cycles), "")), 0);
    row("column instability pressure, MPa", c.column_instability, Some((fe.column_instability, "mode 1, at rest (buckling)")), 2);
    row("in-plane instability pressure, MPa", c.in_plane_instability, Some((fe.in_plane_instability, "mode 0, at rest (elastic buckling)")), 2);
    t.push_str("  stations: nine along every root, sidewall and crest of every convolution (the apexes and mid-sidewalls among them)\n");
    let [e3, e4, e5, e6] = &fe.ends;
    t.push_str(&format!(
        "  where the pack leaves the tubes (outside the code's convolutions, a bonded corner): S3 {:.1}, S4 {:.1}, S5 {:.1}, S6 {:.0} MPa\n",
        e3.value, e4.value, e5.value, e6.value
    ));
    t.push_str(
        "  the instability pressures by finite elements are elastic buckling pressures, unfactored; the code's column formula carries a margin\n  \
         (0.34 against the equivalent column's 2), and its in-plane pressure is a yield criterion, not a bifurcation\n",
    );
    if let Some(l) = life {
        t.push_str(&format!(
            "  the elastic-plastic run's own life: effective total strain range {:.4} at (r, z) = ({:.1}, {:.1}) mm,\n  \
             pseudo-elastic St = E x range = {:.0} MPa: {} cycles (as-formed curve)\n",
            l.strain_range,
            l.at[0],
            l.at[1],
            l.pseudo_stress,
            l.cycles.map_or("endurance: more than the curve's".into(), |n| if n < 1.0 { "less than 1".into() } else { format!("{n:.0}") })
        ));
    }
    t
}

impl BellowsReport {
    /// Writes the pictures next to `output` (the HDF5 file); returns their paths, each with what
    /// it shows.
    pub fn pictures(&self, output: &Path, reader: &ResultsReader) -> Result<Vec<(PathBuf, String)>> {
        let stem = output.with_extension("");
        let name = |suffix: &str| PathBuf::from(format!("{}_{suffix}.png", stem.display()));
        let mut pictures = Vec::new();
        let force = name("force_displacement");
        // in the full ring's newtons, as `post --plot` and the progress lines give forces
        let ring = 2.0 * PI / SECTOR_RADIANS;
        let mut curves = vec![Curve { label: "slideline".into(), points: self.curve.iter().map(|&(u, f)| (u, f * ring)).collect() }];
        if let Some(stiffness) = self.code.as_ref().map(|c| c.axial_rate) {
            let points = [0.0, self.displacement.max(1.0) * 0.35].iter().map(|&u| (u, self.preload * ring + stiffness * u)).collect();
            curves.push(Curve { label: format!("EJMA elastic rate {stiffness:.1} N/mm (from the step-1 preload)"), points });
        }
        // the paper's point for the seed joint alone: any other joint's axes are its own
        let paper = PAPER_REACTION * ring;
        let markers: Vec<Marker> = self
            .seed
            .then(|| Marker { label: format!("paper (MSC Nastran): {paper:.0} N at 70 mm ({PAPER_REACTION} N per sector)"), at: (70.0, paper) })
            .into_iter()
            .collect();
        line_plot(
            &force,
            "Bellows end reaction vs axial compression",
            "axial compression u (mm)",
            "end reaction F (N, full ring)",
            &curves,
            &markers,
            Axes::FromOrigin,
        )?;
        pictures.push((force, "the end reaction against the compression".to_string()));
        let increments = reader.increments()?;
        let (x0, conn) = (reader.coordinates()?, reader.connectivity()?);
        let mut plies: Vec<usize> = Vec::new();
        for name in reader.element_set_names()?.iter().filter(|n| n.starts_with("ply")) {
            plies.extend(reader.element_set(name)?);
        }
        let mut written = Vec::new();
        for inc in &increments {
            written.push((inc.clone(), reader.increment_attr(inc, "step")? as usize, reader.increment_attr(inc, "load_factor")?));
        }
        for (inc, compression, what) in picture_increments(&written, self.stroke) {
            let u = reader.displacement(&inc)?;
            let vm = reader.field(&inc, "von_mises_mean")?;
            // zoom on the convolutions: the plies' deformed extent
            let mut zoom = ((f64::INFINITY, f64::NEG_INFINITY), (f64::INFINITY, f64::NEG_INFINITY));
            for &e in &plies {
                for &n in &conn[e] {
                    let (r, z) = (x0[n][0] + u[n][0], x0[n][1] + u[n][1]);
                    zoom = ((zoom.0 .0.min(z), zoom.0 .1.max(z)), (zoom.1 .0.min(r), zoom.1 .1.max(r)));
                }
            }
            let window = Some(((zoom.0 .0 - 3.0, zoom.0 .1 + 3.0), (zoom.1 .0 - 12.0, zoom.1 .1 + 2.0)));
            let path = name(&format!("von_mises_{inc}"));
            let picture = FieldPicture {
                coordinates: &x0,
                connectivity: &conn,
                displacement: &u,
                values: &vm,
                title: format!(
                    "von Mises stress (element means, largest {:.1} MPa; the table's maximum is a Gauss point's), deformed, at {compression:.1} mm compression, {what} (increment {inc}); below: the convolutions",
                    vm.iter().copied().filter(|v| !v.is_nan()).fold(0.0, f64::max)
                ),
                value_label: "MPa".into(),
            };
            deformed_field(&path, &picture, &[None, window])?;
            pictures.push((path, format!("von Mises stress at {compression:.1} mm compression, {what}")));
        }
        Ok(pictures)
    }
}

/// The bellows closing table (slideline beside the paper, the code check) as the run printed
/// it, from the file alone; None for a file that is not a `slideline bellows` joint run's (a
/// `--form` run's has its own tables: read as a joint's, its forming steps would be taken for
/// the joint's pressure and stroke).
pub fn closing_table_from_file(r: &ResultsReader) -> Result<Option<String>> {
    let deck = r.text_attr("deck")?;
    if !deck.starts_with("# slideline bellows") || r.increments()?.is_empty() || crate::bellows::forming::is_forming_file(r)? {
        return Ok(None);
    }
    let Ok(params) = crate::bellows::spec::DesignSpec::from_deck(&deck, &r.path().display().to_string()) else { return Ok(None) };
    let history: Vec<crate::io::HistoryRow> = r.history_rows()?.into_iter().map(|(_, row)| row).collect();
    // what the table reads of the run: its history, ranks and restart point (the wall time is
    // the history's own)
    let summary = crate::solve::RunSummary {
        wall_time: history.last().map_or(0.0, |row| row.wall_time),
        history,
        ranks: r.count_attr("ranks")?,
        displacement: Vec::new(),
        reserved_couplings: 0,
        pattern_refits: 0,
        continued: r.restarted_from().map_or(0, |(_, at)| at),
        perturbations: Vec::new(),
        heat: Vec::new(),
        plane: r.is_plane(),
    };
    // a file a killed writer left may have lost its code check: the table goes without it
    let (code, lost) = match r.assessment() {
        Ok(code) => (code, None),
        Err(e) => (None, Some(e)),
    };
    let mut report = BellowsReport::new(&params, code, &summary, r)?;
    // a specification's verdict (among the tables reprinted after this one) replaces the
    // code section, as the run printed it
    report.code_section = !r.printed_tables()?.iter().any(|(name, _)| name == CODE_VERDICT);
    let note = lost.map_or(String::new(), |e| format!("  note: the code check cannot be read again ({e})\n"));
    Ok(Some(report.table() + &note))
}

#[cfg(test)]
mod tests {
    use super::picture_increments;

    fn run(rows: &[(usize, f64)]) -> Vec<(String, usize, f64)> {
        rows.iter().enumerate().map(|(k, &(step, load_factor))| (format!("{:06}", k + 1), step, load_factor)).collect()
    }

    #[test]
    fn a_cycle_is_drawn_at_half_the_stroke_at_the_stroke_and_back_at_zero() {
        let cycle = run(&[(1, 1.0), (2, 0.25), (2, 0.5), (2, 0.75), (2, 1.0), (3, 0.5), (3, 1.0)]);
        let picks = picture_increments(&cycle, 70.0);
        let got: Vec<(&str, f64)> = picks.iter().map(|p| (p.0.as_str(), p.1)).collect();
        assert_eq!(got, [("000003", 35.0), ("000005", 70.0), ("000007", 0.0)]);
        assert_eq!(picks[2].2, "the cycle's end");
    }

    #[test]
    fn a_compression_is_drawn_twice_and_a_run_that_stopped_at_its_last_increment() {
        let compression = run(&[(1, 1.0), (2, 0.5), (2, 1.0)]);
        let got: Vec<(String, f64)> = picture_increments(&compression, 70.0).into_iter().map(|p| (p.0, p.1)).collect();
        assert_eq!(got, [("000002".to_string(), 35.0), ("000003".to_string(), 70.0)]);
        // stopped in step 2 at 0.6 of the stroke: no picture claims the stroke
        let stopped = run(&[(1, 1.0), (2, 0.3), (2, 0.6)]);
        let picks = picture_increments(&stopped, 70.0);
        assert_eq!(picks.iter().map(|p| (p.1, p.2)).collect::<Vec<_>>(), [(42.0, "half the stroke")]);
        let one_step = run(&[(1, 0.5), (1, 1.0)]);
        assert_eq!(picture_increments(&one_step, 70.0).iter().map(|p| (p.1, p.2)).collect::<Vec<_>>(), [(0.0, "the last increment")]);
    }
}

//! The bellows run's closing report: the figures the seed paper quotes (end reaction per
//! 2.5-degree sector, stiffness, largest von Mises stress) next to slideline's, with what the
//! paper does not give (plastic strain, penetration, effort), and the pictures (force vs
//! displacement, deformed joint coloured by von Mises at an intermediate and the last
//! increment). Rank 0 only, after the run: fields are read back from the results file.

use crate::assessment::code::CodeCheck;
use crate::assessment::fe_check::{FeCheck, Peak, StrainLife};
use crate::bellows::flexibility::{Flexibility, Movements};
use crate::bellows::joint::BellowsParams;
use crate::bellows::stability::{column_estimates, Stability};
use crate::bellows::vibration::{estimates, Estimates, Frequencies, Mode};
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
pub use code_tables::{code_section, verdict_table, EDITION};
pub use mode_picture::mode_picture;

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
}

/// Axial reaction of the moving end, N per sector, compression positive.
fn end_reaction(row: &HistoryRow) -> f64 {
    row.reactions.iter().find(|(set, _)| set == "moving_end").map(|(_, f)| -f[1] * SECTOR_RADIANS).unwrap_or(f64::NAN)
}

/// Applied compression at a row: zero in step 1, the load factor's share in step 2, back to
/// zero through step 3 (a cycle's return).
fn applied(row: &HistoryRow, p: &BellowsParams) -> f64 {
    compression(row.step, row.load_factor, p.displacement)
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
    pub fn new(p: &BellowsParams, code: Option<CodeCheck>, run: &RunSummary, reader: &ResultsReader) -> Result<Self> {
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
        let cycle = (p.cycle && history.last().is_some_and(|r| r.step == 3 && r.load_factor >= 1.0))
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
            stroke: p.displacement,
            preload,
            reaction,
            secant_stiffness: (reaction - preload) / displacement,
            initial_stiffness,
            code,
            von_mises: extreme(fields, &last, "von_mises")?,
            plastic_strain: extreme(fields, &last, "equivalent_plastic_strain")?,
            fields_at,
            ply_penetration: largest_penetration(history, |n| n.starts_with("ply")),
            sleeve_penetration: largest_penetration(history, |n| n == "sleeve"),
            ply_thickness: p.ply_thickness,
            increments: history.len(),
            cutbacks: history.iter().map(|r| r.cutbacks).sum(),
            newton_iterations: history.iter().map(|r| r.newton_iterations).sum(),
            wall_time: history.last().map_or(run.wall_time, |r| r.wall_time),
            run_wall_time: run.wall_time,
            continued: run.continued,
            ranks: run.ranks,
            curve,
            cycle,
            friction: (p.friction_plies, p.friction_sleeve),
            energy: history.last().and_then(|r| r.energy),
            seed: p.is_seed_joint(),
            code_section: true,
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

/// The flexibility section: the lateral and angular spring rates and what the movements add,
/// by harmonic perturbations of the joint at rest and at the end of its run, each beside the
/// codes' beam analogy evaluated with the same state's axial rate (and, for the stresses, the
/// code check's S5 + S6 at the movement's equivalent axial movement per convolution).
pub fn flexibility_section(p: &BellowsParams, code: Option<&CodeCheck>, movements: Movements, rest: &Flexibility, operating: Option<&Flexibility>) -> String {
    let g = crate::bellows::joint::code_geometry(p);
    let (dm, lb, n) = (g.mean_diameter(), g.convolutions as f64 * g.pitch, g.convolutions as f64);
    // the axial movement the operating state has taken (the codes' Lb + x)
    let stroke = if p.cycle { 0.0 } else { -p.displacement };
    let states: Vec<(&str, &Flexibility, f64)> = std::iter::once(("at rest", rest, 0.0)).chain(operating.map(|f| ("operating", f, stroke))).collect();
    let mut t = format!(
        "\n  flexibility: harmonic perturbations (mode 1) of the joint, the guide sleeve's contact left out, beside the beam analogy\n  \
         (EJMA; lateral 3 K Dm^2 / (2 Lb^2), angular K Dm^2 pi / 1440, K the same state's axial rate by finite elements; Dm {dm:.1} mm, Lb {lb:.1} mm)\n"
    );
    t.push_str(&format!("  {:<52}", ""));
    for (name, _, _) in &states {
        t.push_str(&format!(" {:>11} {:>11} {:>7}", format!("{name} FE"), "code (FE K)", "FE/code"));
    }
    t.push('\n');
    let cell = |v: Option<f64>, digits: usize| v.filter(|v| v.is_finite()).map_or("-".to_string(), |v| format!("{v:.digits$}"));
    // (FE, code) of a row in a state of axial movement x
    type Pick<'a> = &'a dyn Fn(&Flexibility, f64) -> (Option<f64>, Option<f64>);
    let row = |what: &str, pick: Pick, digits: usize| {
        let mut t = format!("  {what:<52}");
        for (_, f, x) in &states {
            let (fe, code) = pick(f, *x);
            let ratio = match (fe, code) {
                (Some(a), Some(b)) if b != 0.0 && a.is_finite() => format!("{:.2}", a / b),
                _ => "-".into(),
            };
            t.push_str(&format!(" {:>11} {:>11} {ratio:>7}", cell(fe, digits), cell(code, digits)));
        }
        t + "\n"
    };
    t += &row("axial rate, N/mm full ring", &|f, _| (Some(f.axial_rate), None), 1);
    let lateral_code = |f: &Flexibility| crate::assessment::formulas::lateral_rate(f.axial_rate, dm, lb);
    let angular_code = |f: &Flexibility| crate::assessment::formulas::angular_rate_per_degree(f.axial_rate, dm);
    // the code check's S5 + S6 at the equivalent axial movement per convolution of a movement
    let code_stress = |e: f64| code.map(|c| g.s5(e, p.youngs_modulus, c.coefficients.cf) + g.s6(e, p.youngs_modulus, c.coefficients.cd));
    let (y, theta) = (movements.lateral, movements.angular.to_radians());
    let centre = crate::bellows::flexibility::centre(p);
    if rest.lateral.is_some() {
        let lateral = |f: &Flexibility| f.lateral.clone().expect("both states have the same steps");
        t.push_str(&format!("  lateral offset {y} mm of tube B's end, its rotation held:\n"));
        t += &row("  lateral rate, N/mm", &|f, _| (Some(lateral(f).rate), Some(lateral_code(f))), 1);
        t += &row("  force at the fixed end, N", &|f, _| (Some(lateral(f).fixed_force.abs()), Some(lateral_code(f) * y.abs())), 1);
        // the guided beam's inflection at the bellows' centre: M = F (z_centre - z_fixed)
        t += &row("  moment at the fixed end, N mm", &|f, _| (Some(lateral(f).fixed_moment.abs()), Some(lateral_code(f) * y.abs() * centre)), 0);
        let e = |x: f64| g.equivalent_axial_movement(x, y, 0.0) - x.abs() / n;
        t += &row("  meridional stress added at a crest, MPa (code S5 + S6)", &|f, x| (Some(lateral(f).crest.value), code_stress(e(x))), 1);
        t += &row("  meridional stress added at a root, MPa (code S5 + S6)", &|f, x| (Some(lateral(f).root.value), code_stress(e(x))), 1);
        t += &row("  lateral force the guide sleeve takes as built, N", &|f, _| (f.sleeve_force.map(f64::abs), None), 1);
    }
    if rest.angular.is_some() {
        let angular = |f: &Flexibility| f.angular.clone().expect("both states have the same steps");
        t.push_str(&format!("  rotation {} degrees of tube B's end about the bellows' centre:\n", movements.angular));
        t += &row("  angular rate, N mm/degree", &|f, _| (Some(angular(f).rate), Some(angular_code(f))), 0);
        t += &row("  moment at the fixed end, N mm", &|f, _| (Some(angular(f).fixed_moment.abs()), Some(angular_code(f) * movements.angular.abs())), 0);
        t += &row("  lateral force at the fixed end, N (the code's: none)", &|f, _| (Some(angular(f).fixed_force.abs()), None), 1);
        let e = g.equivalent_axial_movement(0.0, 0.0, theta);
        t += &row("  meridional stress added at a crest, MPa (code S5 + S6)", &|f, _| (Some(angular(f).crest.value), code_stress(e)), 1);
        t += &row("  meridional stress added at a root, MPa (code S5 + S6)", &|f, _| (Some(angular(f).root.value), code_stress(e)), 1);
    }
    t.push_str(
        "  at rest: no pressure, heat or stroke, elastic (the codes' assumption); operating: the end of the run's last step.\n  \
         the stresses are |membrane| + |bending| across a ply, the largest over the crests' and roots' stations; the code's are for\n  \
         the equivalent axial movement per convolution, 3 Dm y / (N (Lb + x)) and Dm theta / (2 N) (EJMA; ASME VIII-1 App. 26)\n",
    );
    t
}

/// The stability section: the buckling pressures of the joint at rest and at the end of its run
/// (both tubes' ends held) beside the codes' estimates with the same state's axial rate.
pub fn stability_section(p: &BellowsParams, code: Option<&CodeCheck>, rest: &Stability, operating: &Stability) -> String {
    let mut t = String::from("\n  stability: buckling analyses of the joint (both tubes' ends held), the critical internal pressure, MPa\n");
    t.push_str(&format!("  {:<58} {:>12} {:>12}\n", "", "at rest", "operating"));
    let cell = |v: Option<f64>| v.filter(|v| v.is_finite()).map_or("-".to_string(), |v| format!("{v:.2}"));
    let mut row = |what: &str, pick: &dyn Fn(&Stability) -> Option<f64>| {
        t.push_str(&format!("  {what:<58} {:>12} {:>12}\n", cell(pick(rest)), cell(pick(operating))));
    };
    row("axial rate Kb by finite elements, N/mm full ring", &|s| Some(s.axial_rate));
    row("column instability (squirm), mode 1, finite elements", &|s| s.squirm);
    row("  EJMA column formula 0.34 pi Kb / (N q), the same Kb", &|s| Some(column_estimates(p, s.axial_rate).0));
    row("  the equivalent column, unfactored, 2 pi Kb / (N q)", &|s| Some(column_estimates(p, s.axial_rate).1));
    row("in-plane instability, mode 0, finite elements", &|s| s.in_plane);
    let in_plane_code = code.map(|c| c.in_plane_instability);
    row("  the code's in-plane formula (the code check's)", &|_| in_plane_code);
    for (k, &(n, _)) in rest.higher.iter().enumerate() {
        // a harmonic whose nearest eigenvalues were all external pressures: its bound
        let cell = |s: &Stability| match (s.higher.get(k).and_then(|h| h.1), s.above.iter().find(|a| a.0 == n)) {
            (Some(p), _) => format!("{p:.2}"),
            (None, Some(&(_, b))) => format!("> {b:.1}"),
            (None, None) => "-".into(),
        };
        t.push_str(&format!("  {:<58} {:>12} {:>12}\n", format!("crest and sidewall mode n = {n}, finite elements"), cell(rest), cell(operating)));
    }
    let governing = |s: &Stability| s.governing().map_or("-".to_string(), |(n, p)| format!("n = {n}: {p:.2}"));
    t.push_str(&format!("  {:<58} {:>12} {:>12}\n", "the lowest over the harmonics, finite elements", governing(rest), governing(operating)));
    let highest = super::stability::HIGHEST_HARMONIC;
    if [rest, operating].iter().any(|s| s.governing().is_some_and(|(n, _)| n == highest)) {
        t.push_str(&format!("  note: the lowest pressure is the highest harmonic's (n = {highest}): those above it were not analysed\n"));
    }
    t.push_str(
        "  EJMA's 0.34 is 0.17 of the equivalent column's 2: the code's formula carries that margin on the beam analogy;\n  \
         the finite elements give the joint's own elastic buckling pressure, unfactored (the state's pressure plus the load factor);\n  \
         the code's in-plane pressure is a yield criterion (Sy* = 2.3 Sy), not an elastic bifurcation: the two are not the same limit\n",
    );
    t
}

/// The natural frequencies section: the lowest axial and lateral modes of the joint at rest and
/// at the end of its run (both tubes' ends held) beside the analogies of EJMA's frequency
/// formulas with the same state's axial rate, each with its ratio.
pub fn frequencies_section(p: &BellowsParams, rest: &Frequencies, operating: &Frequencies) -> String {
    let mut t = String::from("\n  natural frequencies: the joint with both tubes' ends held, Hz\n");
    t.push_str(&format!("  {:<58} {:>12} {:>12}\n", "", "at rest", "operating"));
    let cell = |v: Option<f64>, digits: usize| v.filter(|v| v.is_finite()).map_or("-".to_string(), |v| format!("{v:.digits$}"));
    // each state's analogies once (the Rayleigh beam is a root search)
    let states = [(rest, estimates(p, rest)), (operating, estimates(p, operating))];
    let mass = states[0].1.mass;
    let mut row = |what: &str, pick: &dyn Fn(&Frequencies, Estimates) -> Option<f64>, digits: usize| {
        let [a, b] = states.map(|(f, e)| cell(pick(f, e), digits));
        t.push_str(&format!("  {what:<58} {a:>12} {b:>12}\n"));
    };
    let ratio = |m: Option<Mode>, analogy: f64| m.map(|m| m.frequency / analogy);
    row("axial rate Kb by finite elements, N/mm full ring", &|f, _| Some(f.axial_rate), 1);
    row("convolved length Lb + x, mm", &|f, _| Some(f.convolved_length), 1);
    row("first axial mode (n = 0), finite elements", &|f, _| f.axial.map(|m| m.frequency), 1);
    row("  spring analogy (1/2) sqrt(Kb / m), the same Kb", &|_, e| Some(e.axial), 1);
    row("  ratio, finite elements / analogy", &|f, e| ratio(f.axial, e.axial), 3);
    row("  effective mass / live mass", &|f, e| f.axial.map(|m| m.effective_mass / e.mass), 3);
    row("first lateral mode (n = 1), finite elements", &|f, _| f.lateral.map(|m| m.frequency), 1);
    row("  clamped beam, (E I)eq = Kb Lb Dm^2 / 8 (EJMA's analogy)", &|_, e| Some(e.lateral), 1);
    row("  ratio, finite elements / analogy", &|f, e| ratio(f.lateral, e.lateral), 3);
    row("  the same beam with the rotary inertia m Dm^2 / 8", &|_, e| Some(e.lateral_rotary), 1);
    row("  ratio, finite elements / analogy", &|f, e| ratio(f.lateral, e.lateral_rotary), 3);
    row("  effective mass / live mass", &|f, e| f.lateral.map(|m| m.effective_mass / e.mass), 3);
    t.push_str(&format!(
        "  live mass m: the convolutions' metal, {:.3} kg at {:e} t/mm^3; the fluid's mass is left out (add it for a liquid line);\n  \
         a rod's first mode carries 8 / pi^2 = 0.81 of its mass, a clamped beam's 0.69 (less where the convolutions rock);\n  \
         EJMA's formulas, C sqrt(Kb / W) axially and C (Dm / Lb) sqrt(Kb / W) laterally, tend to the first two analogies for\n  \
         many convolutions; a bellows about as wide as it is long rocks more than it translates, so the rotary inertia they leave\n  \
         out lowers its lateral mode;\n  \
         the finite elements add the tangents' and tubes' mass and stiffness, the plies' contact and, operating, the state's stress;\n  \
         operating, where the folds bear on each other, the analogies are no longer the joint\n",
        mass * 1000.0,
        p.density
    ));
    t
}

/// The bellows closing table (slideline beside the paper, the code check) as the run printed
/// it, from the file alone; None for a file that is not a `slideline bellows` run's.
pub fn closing_table_from_file(r: &ResultsReader) -> Result<Option<String>> {
    let deck = r.text_attr("deck")?;
    if !deck.starts_with("# slideline bellows") || r.increments()?.is_empty() {
        return Ok(None);
    }
    let Ok(params) = crate::bellows::joint::BellowsParams::from_toml(&deck, &r.path().display().to_string()) else { return Ok(None) };
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
    report.code_section = !r.printed_tables()?.iter().any(|(name, _)| name == crate::bellows::workflow::CODE_VERDICT);
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

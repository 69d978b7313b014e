//! `slideline post FILE.h5`: what a results file holds, as text (and one picture). Every
//! function returns what it would print, so the CLI prints it and the tests read it.

use crate::error::{Error, Result};
use crate::fe::quadrature::Integration;
use crate::fe::shape::Shape;
use crate::io::plots::{line_plot, Axes, Curve};
use crate::io::reader::ResultsReader;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

pub mod sections;

/// Run summary: provenance, size, effort.
pub fn summary(r: &ResultsReader) -> Result<String> {
    let rows = r.history_rows()?;
    let mut s = String::new();
    let deck = r.text_attr("deck")?;
    let _ = writeln!(s, "file:        {}", r.path().display());
    let _ = writeln!(s, "written by:  slideline {} on {} rank(s)", r.text_attr("slideline_version")?, r.count_attr("ranks")?);
    let _ = writeln!(s, "model:       {} ({} lines of deck text, `--deck` prints it)", deck.lines().next().unwrap_or(""), deck.lines().count());
    let _ = writeln!(s, "mesh:        {} nodes, {} elements", r.coordinates()?.len(), r.connectivity()?.len());
    let _ = writeln!(s, "units:       {}", r.text_attr("units")?);
    let options = r.text_attr("petsc_options")?;
    let _ = writeln!(s, "PETSc:       {}", if options.is_empty() { "(defaults)" } else { &options });
    let steps = r.count_attr("steps").unwrap_or(0);
    let heat = r.heat_steps()?;
    for (name, [low, high], flows) in &heat {
        let _ = writeln!(
            s,
            "heat step '{name}': temperatures {low:.6e} to {high:.6e} degC; heat flowing in (mW, {}):",
            if r.is_plane() { "over the thickness" } else { "full ring" }
        );
        for (set, flow) in flows {
            let _ = writeln!(s, "  {set:<20} {flow:.6e}");
        }
    }
    if !heat.is_empty() {
        // a heat-conduction run has no increments
        return Ok(s);
    }
    let last_step = rows.last().map(|(_, row)| (row.step, row.load_factor));
    let _ = writeln!(
        s,
        "increments:  {} converged, {} cutbacks, {} Newton and {} linear iterations; reached step {} of {} at load factor {:.4}",
        rows.len(),
        rows.iter().map(|(_, r)| r.cutbacks).sum::<usize>(),
        rows.iter().map(|(_, r)| r.newton_iterations).sum::<usize>(),
        rows.iter().map(|(_, r)| r.linear_iterations).sum::<usize>(),
        last_step.map_or(0, |l| l.0),
        steps,
        last_step.map_or(0.0, |l| l.1)
    );
    let _ = writeln!(s, "wall time:   {:.2} s", rows.last().map_or(0.0, |(_, r)| r.wall_time));
    for p in r.perturbations()? {
        if !p.eigenvalues.is_empty() {
            let _ = writeln!(s, "{}", eigen_lines(&p.name, p.analysis, &p.eigenvalues));
            continue;
        }
        let _ = writeln!(s, "perturbation '{}' (mode {}): reactions, full ring (N, N mm)", p.name, p.mode);
        for (set, values) in p.reactions {
            let values: Vec<String> = values.iter().map(|(what, v)| format!("{what} {v:.6e}")).collect();
            let _ = writeln!(s, "  {set:<20} {}", values.join(", "));
        }
    }
    Ok(s)
}

/// An eigenvalue step's lines: each mode's frequency (Hz) and effective mass, or its load
/// factor, from (eigenvalue, effective mass) pairs.
pub fn eigen_lines(name: &str, analysis: crate::model::perturbation::Analysis, modes: &[(f64, Option<f64>)]) -> String {
    use crate::model::perturbation::Analysis;
    let mut s = match analysis {
        Analysis::Frequency { .. } => format!("perturbation step '{name}': natural frequencies"),
        _ => format!("perturbation step '{name}': buckling load factors (critical load = base load + factor x the step's load)"),
    };
    for (i, (value, mass)) in modes.iter().enumerate() {
        let line = match analysis {
            Analysis::Frequency { .. } => {
                let mass = mass.map_or(String::new(), |m| format!(", effective mass {m:.4e} t (full ring)"));
                format!("\n  mode {:>2}: {:.6e} Hz{mass}", i + 1, crate::records::perturbation::frequency_hz(*value))
            }
            _ => format!("\n  mode {:>2}: load factor {value:.6e}", i + 1),
        };
        s.push_str(&line);
    }
    s
}

/// The history as the run printed it, one line per converged increment (the long lines of
/// `--verbose` when `verbose`).
pub fn history_table(r: &ResultsReader, verbose: bool) -> Result<String> {
    let steps = r.count_attr("steps")?;
    let plane = r.is_plane();
    let line = |name: &str, row: &crate::io::HistoryRow| if verbose { row.progress_line(name, steps, plane) } else { row.short_line(name, steps, plane) };
    Ok(r.history_rows()?.iter().map(|(name, row)| line(name, row) + "\n").collect())
}

/// Whether a history column counts things (written as integers in the CSV).
fn is_count(column: &str) -> bool {
    ["step", "increment", "newton_iterations", "linear_iterations", "cutbacks", "augmentations"].contains(&column) || column.ends_with("_active_nodes")
}

/// The history columns as CSV (a header line of "name [units]", one row per increment): counts
/// as integers, every other value in full precision (the shortest text that reads back to the
/// same double). The constrained sets' mean displacements (the prescribed ones) are columns
/// `displacement_SET_r/z`, beside their reactions.
pub fn history_csv(r: &ResultsReader) -> Result<String> {
    let columns = r.history_columns()?;
    let data: Vec<Vec<f64>> = columns.iter().map(|c| r.history(c)).collect::<Result<_>>()?;
    let mut w = csv::Writer::from_writer(Vec::new());
    let csv_err = |e: csv::Error| Error::Internal(format!("CSV: {e}"));
    // each column's units in its name, as "name [units]" (a spreadsheet's header, and a name
    // pandas and numpy keep whole)
    let header: Vec<String> = columns.iter().map(|c| format!("{c} [{}]", r.units(&format!("history/{c}")))).collect();
    w.write_record(&header).map_err(csv_err)?;
    for k in 0..data.first().map_or(0, Vec::len) {
        let row =
            columns.iter().zip(&data).map(|(name, c)| if is_count(name) && c[k].fract() == 0.0 { format!("{}", c[k] as i64) } else { format!("{:?}", c[k]) });
        w.write_record(row).map_err(csv_err)?;
    }
    String::from_utf8(w.into_inner().map_err(|e| Error::Internal(format!("CSV: {e}")))?).map_err(|e| Error::Internal(format!("CSV: {e}")))
}

/// The run-wide number of an increment group's name ("000042" -> 42).
fn number_of(name: &str) -> usize {
    name.parse().unwrap_or(0)
}

/// The increment `which` names: `last` (the last one with fields), or a number (1-based, the
/// run's numbering).
pub fn increment_number(r: &ResultsReader, which: &str) -> Result<usize> {
    if which.eq_ignore_ascii_case("last") {
        return Ok(r.increments()?.last().map_or(0, |n| number_of(n)));
    }
    which.parse().map_err(|_| Error::input(format!("--increment {which}: give an increment number or `last`")))
}

/// Name of the group of increment `number` (the run's numbering) or a clear error: out of
/// range, or an increment whose fields the run did not write.
fn increment_name(r: &ResultsReader, number: usize) -> Result<String> {
    let names = r.increments()?;
    let rows = r.history("step")?.len();
    if number == 0 || number > rows {
        return Err(Error::input(format!("{}: increment {number} out of range: the file has increments 1..{rows}", r.path().display())));
    }
    let name = format!("{number:06}");
    if names.contains(&name) {
        return Ok(name);
    }
    let with_fields: Vec<String> = names.iter().map(|n| number_of(n).to_string()).collect();
    Err(Error::input(format!(
        "{}: increment {number} has no fields (the run wrote them for increments {}); its history row is there",
        r.path().display(),
        with_fields.join(", ")
    )))
}

/// The fields at the Gauss points (or per element) that `--field` reports.
const ELEMENT_FIELDS: [&str; 6] =
    ["stress", "von_mises", "von_mises_mean", "equivalent_plastic_strain", "equivalent_plastic_strain_max", "element_nodal_stress"];

/// Min and max of a field at an increment, per component, with where they are: nodal fields
/// (displacement, and every field ParaView shows at the nodes: `stress_rr`, `strain_zz`,
/// `reaction_force`, `contact_pressure`, ...; `nodal_von_mises` and
/// `nodal_equivalent_plastic_strain` for the nodal values of the Gauss-point fields of those
/// names) by node, element fields (stress, von_mises, ...) by element and Gauss point.
pub fn field(r: &ResultsReader, name: &str, number: usize) -> Result<String> {
    let inc = increment_name(r, number)?;
    let nodal_names = r.nodal_fields(&inc)?;
    let nodal_name = name.strip_prefix("nodal_").filter(|n| ELEMENT_FIELDS.contains(n)).unwrap_or(name);
    let (path, nodal) = if ELEMENT_FIELDS.contains(&name) {
        (name.to_string(), false)
    } else if name == "displacement" && !nodal_names.iter().any(|n| n == "displacement") {
        (name.to_string(), true) // a file from before the nodal 3-vector was the only one
    } else if nodal_names.iter().any(|n| n == nodal_name) {
        (format!("nodal/{nodal_name}"), true)
    } else {
        let nodal_listed: Vec<String> = nodal_names
            .iter()
            .filter(|n| *n != "displacement")
            .map(|n| if ELEMENT_FIELDS.contains(&n.as_str()) { format!("nodal_{n}") } else { n.clone() })
            .collect();
        return Err(Error::input(format!(
            "unknown field {name:?}: the fields are displacement, {} (Gauss points) and {} (nodes)",
            ELEMENT_FIELDS.join(", "),
            nodal_listed.join(", ")
        )));
    };
    // a Gauss-point field the run's [output] fields left out (element_nodal_stress is kept on
    // request only) is named as such, not as HDF5's missing object
    if !r.has_field(&inc, &path) {
        let how = if name == "element_nodal_stress" {
            "it is written only on request: [output] fields = [..., \"element_nodal\"]"
        } else {
            "the run's [output] fields left it out"
        };
        return Err(Error::input(format!("{}: increment {number} holds no {name}: {how}", r.path().display())));
    }
    let mut values = r.field(&inc, &path)?;
    let (x0, conn) = (r.coordinates()?, r.connectivity()?);
    let u = r.displacement(&inc)?;
    let count = if nodal { x0.len() } else { conn.len() };
    if values.len() == 3 * x0.len() && (name == "reaction_force" || name == "displacement") {
        // (r, z, 0) for ParaView: the two components
        values = values.chunks(3).flat_map(|v| [v[0], v[1]]).collect();
    }
    let per = values.len() / count.max(1);
    let [a, b] = directions(r);
    let components: Vec<String> = match name {
        "displacement" => vec![format!("u_{a}"), format!("u_{b}")],
        "reaction_force" => vec![format!("F_{a}"), format!("F_{b}")],
        "stress" | "element_nodal_stress" => vec![format!("s_{a}{a}"), format!("s_{b}{b}"), "s_tt".into(), format!("s_{a}{b}")],
        _ => vec![name.to_string()],
    };
    let points = per / components.len();
    // a reduced element's spare Gauss slots hold NaN
    let reduced = !nodal && r.integration()?.contains(&Integration::Reduced);
    let mut s = format!(
        "{name} at increment {number} (step {}, load factor {:.4}), {} per {}{}\n",
        r.increment_attr(&inc, "step")? as usize,
        r.increment_attr(&inc, "load_factor")?,
        r.units(&format!("increments/{inc}/{path}")),
        if nodal { "node" } else { "element" },
        match (points, name) {
            (1, _) => String::new(),
            (_, "element_nodal_stress") => format!(" ({points} nodes each)"),
            _ if reduced => format!(" ({points} Gauss slots each; a reduced element uses the first 4, a CAX6 the first 3)"),
            _ => format!(" ({points} Gauss points each)"),
        }
    );
    let ids = if nodal { r.node_ids()? } else { r.element_ids()? };
    let place = |entity: usize| -> [f64; 2] {
        if nodal {
            [x0[entity][0] + u[entity][0], x0[entity][1] + u[entity][1]]
        } else {
            let corners = &conn[entity][..Shape::of(&conn[entity]).corners()];
            [0, 1].map(|c| corners.iter().map(|&n| x0[n][c] + u[n][c]).sum::<f64>() / corners.len() as f64)
        }
    };
    for (c, label) in components.iter().enumerate() {
        let value = |(e, p): (usize, usize)| values[e * per + p * components.len() + c];
        let entries = (0..count).flat_map(|e| (0..points).map(move |p| (e, p))).filter(|&at| !value(at).is_nan());
        let min = entries.clone().min_by(|a, b| value(*a).total_cmp(&value(*b))).unwrap_or((0, 0));
        let max = entries.max_by(|a, b| value(*a).total_cmp(&value(*b))).unwrap_or((0, 0));
        for (what, at) in [("min", min), ("max", max)] {
            let p = place(at.0);
            let gp = if points > 1 { format!(" point {}", at.1 + 1) } else { String::new() };
            let _ = writeln!(
                s,
                "  {label:<10} {what} {:>14.6e}  at {} {}{gp}, deformed ({a}, {b}) = ({:.3}, {:.3}) mm",
                value(at),
                if nodal { "node" } else { "element" },
                ids[at.0],
                p[0],
                p[1]
            );
        }
    }
    Ok(s)
}

/// Time series of a node (by its external number): displacement at every increment.
pub fn node_series(r: &ResultsReader, id: u64) -> Result<String> {
    let ids = r.node_ids()?;
    let node = ids.iter().position(|&n| n == id).ok_or_else(|| Error::input(format!("{}: no node {id}", r.path().display())))?;
    let x = r.coordinates()?[node];
    let [a, b] = directions(r);
    let mut s = format!(
        "node {id} at ({a}, {b}) = ({:.4}, {:.4}) mm\n{:>10} {:>10} {:>16} {:>16}\n",
        x[0],
        x[1],
        "increment",
        "time",
        format!("u_{a} (mm)"),
        format!("u_{b} (mm)")
    );
    for inc in r.increments()? {
        let u = r.displacement(&inc)?[node];
        let _ = writeln!(s, "{:>10} {:>10.4} {:>16.8e} {:>16.8e}", number_of(&inc), r.increment_attr(&inc, "time")?, u[0], u[1]);
    }
    Ok(s)
}

/// Time series of a node set: its reaction where it is constrained (the history columns),
/// else the mean displacement of its nodes.
pub fn set_series(r: &ResultsReader, set: &str) -> Result<String> {
    let set = &r.node_set_name(set)?;
    let columns = r.history_columns()?;
    let time = r.history("time")?;
    let reaction = format!("reaction_{set}_z");
    if columns.contains(&reaction) {
        let (fr, fz) = (r.history(&format!("reaction_{set}_r"))?, r.history(&reaction)?);
        // a plane model's reactions are over its thickness: no ring
        let plane = r.is_plane();
        let [a, b] = directions(r);
        // the set's mean displacement where the increment has fields (the file's restart chain
        // and sparse output leave some without)
        let members = r.node_set(set)?;
        let written: std::collections::HashMap<usize, String> = r.increments()?.into_iter().map(|inc| (number_of(&inc), inc)).collect();
        let (unit, over) = if plane { ("N", " (over the thickness)") } else { ("N ring", "") };
        // the full ring first, as Abaqus and ANSYS report axisymmetric models; per radian beside
        let per_radian = if plane { String::new() } else { format!(" {:>16} {:>16}", format!("F_{a} (N/rad)"), format!("F_{b} (N/rad)")) };
        let mut s = format!(
            "reaction of node set {set}{over}\n{:>10} {:>10} {:>16} {:>16} {:>16} {:>16}{per_radian}\n",
            "increment",
            "time",
            format!("u_{a} (mm)"),
            format!("u_{b} (mm)"),
            format!("F_{a} ({unit})"),
            format!("F_{b} ({unit})")
        );
        let ring = if plane { 1.0 } else { 2.0 * std::f64::consts::PI };
        for k in 0..time.len() {
            let mean = match written.get(&(k + 1)) {
                Some(inc) => {
                    let u = r.displacement(inc)?;
                    [0, 1].map(|c| format!("{:.8e}", members.iter().map(|&n| u[n][c]).sum::<f64>() / members.len().max(1) as f64))
                }
                None => ["-".to_string(), "-".to_string()],
            };
            let per_radian = if plane { String::new() } else { format!(" {:>16.8e} {:>16.8e}", fr[k], fz[k]) };
            let _ = writeln!(s, "{:>10} {:>10.4} {:>16} {:>16} {:>16.8e} {:>16.8e}{per_radian}", k + 1, time[k], mean[0], mean[1], ring * fr[k], ring * fz[k]);
        }
        return Ok(s);
    }
    let members = r.node_set(set)?;
    let [a, b] = directions(r);
    let mut s = format!(
        "mean displacement of node set {set} ({} nodes)\n{:>10} {:>10} {:>16} {:>16}\n",
        members.len(),
        "increment",
        "time",
        format!("u_{a} (mm)"),
        format!("u_{b} (mm)")
    );
    for inc in r.increments()? {
        let u = r.displacement(&inc)?;
        let mean = [0, 1].map(|c| members.iter().map(|&n| u[n][c]).sum::<f64>() / members.len().max(1) as f64);
        let _ = writeln!(s, "{:>10} {:>10.4} {:>16.8e} {:>16.8e}", number_of(&inc), r.increment_attr(&inc, "time")?, mean[0], mean[1]);
    }
    Ok(s)
}

/// Two runs' histories side by side, matched by time: every reaction column both have, and
/// the Newton iterations.
pub fn compare(a: &ResultsReader, b: &ResultsReader, force: bool) -> Result<String> {
    let (na, nb) = (a.node_ids()?, b.node_ids()?);
    let (ea, eb) = (a.element_ids()?.len(), b.element_ids()?.len());
    let (mut sa, mut sb) = (na.clone(), nb.clone());
    sa.sort_unstable();
    sb.sort_unstable();
    if !force && (sa != sb || ea != eb) {
        return Err(Error::input(format!(
            "{} ({} nodes, {ea} elements) and {} ({} nodes, {eb} elements) are runs of different models; --force compares their histories anyway",
            a.path().display(),
            na.len(),
            b.path().display(),
            nb.len()
        )));
    }
    let (ca, cb) = (a.history_columns()?, b.history_columns()?);
    let shared: Vec<&String> = ca.iter().filter(|c| c.starts_with("reaction_") && !c.ends_with("_ring") && cb.contains(c)).collect();
    let (ta, tb) = (a.history("time")?, b.history("time")?);
    let (na, nb) = (a.history("newton_iterations")?, b.history("newton_iterations")?);
    let va: Vec<Vec<f64>> = shared.iter().map(|c| a.history(c)).collect::<Result<_>>()?;
    let vb: Vec<Vec<f64>> = shared.iter().map(|c| b.history(c)).collect::<Result<_>>()?;
    // increments at common times: (row in A, row in B)
    let matched: Vec<(usize, usize)> =
        ta.iter().enumerate().filter_map(|(i, &t)| tb.iter().position(|&u| (u - t).abs() <= 1e-9 * t.abs().max(1.0)).map(|j| (i, j))).collect();
    let mut s = format!("A = {}\nB = {}\n", a.path().display(), b.path().display());
    // the largest difference over every column: (|B - A|, column, time, relative)
    let mut largest: Option<(f64, &str, f64, f64)> = None;
    let unit = if a.is_plane() { "N over the thickness" } else { "N per radian" };
    // a value below a billionth of the largest reaction compared is round-off (a free
    // direction's reaction, an unloaded step's): no ratio between two round-off values
    let largest_of = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let scale = va.iter().map(|v| largest_of(v)).fold(0.0f64, f64::max);
    for (k, column) in shared.iter().enumerate() {
        // relative to |A|, but never to less than a thousandth of the column's largest |A|: a
        // reaction that is zero to round-off has no meaningful relative difference
        let floor = 1e-3 * largest_of(&va[k]);
        let _ = writeln!(s, "\n{column} ({unit})");
        let _ = writeln!(s, "{:>10} {:>6} {:>6} {:>16} {:>16} {:>12} {:>10}", "time", "its A", "its B", "A", "B", "B - A", "rel");
        for &(i, j) in &matched {
            let (x, y) = (va[k][i], vb[k][j]);
            let round_off = x.abs().max(y.abs()) <= 1e-9 * scale;
            let rel = if floor > 0.0 && !round_off { (y - x) / x.abs().max(floor) } else { 0.0 };
            let shown = if round_off { "-".to_string() } else { format!("{rel:.2e}") };
            let _ = writeln!(s, "{:>10.4} {:>6} {:>6} {x:>16.8e} {y:>16.8e} {:>12.4e} {shown:>10}", ta[i], na[i], nb[j], y - x);
            if !round_off && largest.is_none_or(|l| (y - x).abs() > l.0) {
                largest = Some(((y - x).abs(), column.as_str(), ta[i], rel));
            }
        }
    }
    let _ = writeln!(s, "\n{} increments at common times ({} in A, {} in B)", matched.len(), ta.len(), tb.len());
    if let Some((diff, column, time, rel)) = largest {
        let _ = writeln!(s, "largest difference: {column}, {diff:.4e} {unit} ({:.2e} relative) at time {time:.4}", rel.abs());
    }
    let _ = writeln!(
        s,
        "rel: (B - A) / |A|, |A| taken as at least a thousandth of the column's largest |A|;\n     '-' where both are round-off (below 1e-9 of the largest reaction compared)"
    );
    Ok(s)
}

/// The force-displacement picture's content: title, axis labels and curves.
pub struct ForcePlot {
    pub title: &'static str,
    pub x_label: String,
    pub y_label: String,
    pub curves: Vec<Curve>,
}

/// Force-displacement picture next to the file ([`force_curves`]). Returns its path.
pub fn plot(r: &ResultsReader, path: &Path) -> Result<PathBuf> {
    let p = force_curves(r)?;
    line_plot(path, p.title, &p.x_label, &p.y_label, &p.curves, &[], Axes::FromOrigin)?;
    Ok(path.to_path_buf())
}

/// Every constrained set's axial reaction (full ring; a plane model's y reaction over its
/// thickness) against the prescribed displacement (the history's mean u_z of the set that moves
/// the most), or the total time (step - 1 + load factor), one point per history row.
pub fn force_curves(r: &ResultsReader) -> Result<ForcePlot> {
    let columns = r.history_columns()?;
    let plane = r.is_plane();
    // the axial reactions: the full ring's, or a plane model's (it has no ring)
    let suffix = if plane { "_z" } else { "_z_ring" };
    let sets: Vec<&str> = columns.iter().filter_map(|c| c.strip_prefix("reaction_")?.strip_suffix(suffix)).collect();
    let [_, b] = directions(r);
    let force = if plane { format!("F_{b} (N, over the thickness") } else { format!("F_{b} (N, full ring") };
    // the prescribed displacement: the constrained set that moves the most along z (its mean
    // u_z, a history column; a file written before it had one: from the increments' fields, when
    // every increment has them); without one, the history's time
    let increments = r.increments()?;
    let rows = r.history("step")?.len();
    let mut travel: Vec<(&str, Vec<f64>)> = Vec::new();
    for &set in &sets {
        let uz = match r.history(&format!("displacement_{set}_z")) {
            Ok(uz) => uz,
            Err(_) if increments.len() == rows => {
                let members = r.node_set(set)?;
                increments
                    .iter()
                    .map(|inc| {
                        Ok(r.displacement(inc)?.iter().enumerate().filter(|(n, _)| members.binary_search(n).is_ok()).map(|(_, u)| u[1]).sum::<f64>()
                            / members.len().max(1) as f64)
                    })
                    .collect::<Result<_>>()?
            }
            Err(_) => continue,
        };
        travel.push((set, uz));
    }
    let moving = travel.iter().max_by(|a, b| a.1.iter().fold(0.0f64, |m, v| m.max(v.abs())).total_cmp(&b.1.iter().fold(0.0f64, |m, v| m.max(v.abs()))));
    // each quantity signed so that its largest value is positive (a compression plots up and
    // right), signs kept: a load cycle's return through zero and into tension stays visible
    let oriented = |v: &[f64]| {
        let extreme = v.iter().copied().filter(|x| x.is_finite()).fold(0.0f64, |m, x| if x.abs() > m.abs() { x } else { m });
        let sign = if extreme < 0.0 { -1.0 } else { 1.0 };
        v.iter().map(|x| sign * x).collect::<Vec<f64>>()
    };
    let (x, x_label): (Vec<f64>, String) = match moving {
        Some((set, uz)) if uz.iter().any(|v| *v != 0.0) => {
            (oriented(uz), format!("u_{b} of {set}, mm (the prescribed displacement, signed so its largest is positive)"))
        }
        _ => (r.history("time")?, "time (step - 1 + load factor)".into()),
    };
    let curves: Vec<Curve> = sets
        .iter()
        .map(|set| {
            let f = oriented(&r.history(&format!("reaction_{set}{suffix}"))?);
            Ok(Curve {
                label: format!("{set}: {force})"),
                points: x.iter().zip(&f).filter(|(u, v)| u.is_finite() && v.is_finite()).map(|(&u, &v)| (u, v)).collect(),
            })
        })
        .collect::<Result<_>>()?;
    let title = if plane { "Reactions along y" } else { "Axial reactions" };
    Ok(ForcePlot { title, x_label, y_label: format!("{force}; each signed so its largest is positive)"), curves })
}

/// The picture's default name: FILE_force.png beside the results file.
pub fn default_plot_path(r: &ResultsReader) -> PathBuf {
    PathBuf::from(format!("{}_force.png", r.path().with_extension("").display()))
}

/// The names of a results file's two in-plane directions: (r, z) about the axis, or a plane
/// model's (x, y), which the datasets store as r and z.
fn directions(r: &ResultsReader) -> [&'static str; 2] {
    if r.is_plane() {
        ["x", "y"]
    } else {
        ["r", "z"]
    }
}

//! Reading a results file back (serially, after the run): the mesh, the increments' fields
//! and the history columns, for pictures, summaries and post-processing. Every failure names
//! the file and the group or dataset that is missing, so a wrong file gives a clear message.

use super::history::{ContactSummary, HistoryRow};
use crate::error::{Error, Result};
use crate::fe::quadrature::Integration;
use crate::model::perturbation::Analysis;
use crate::records::energy::Energies;
use hdf5::types::VarLenUnicode;
use std::path::{Path, PathBuf};

pub struct ResultsReader {
    file: hdf5::File,
    path: PathBuf,
}

/// A group or dataset of the file that could not be read.
fn missing(path: &Path, what: &str, e: impl std::fmt::Display) -> Error {
    Error::input(format!("{}: cannot read {what}: {e}", path.display()))
}

impl ResultsReader {
    pub fn open(path: &Path) -> Result<Self> {
        let file = super::opening::open_results(path)?;
        let reader = ResultsReader { file, path: path.to_path_buf() };
        // a design-by-analysis verdict file (`/dba`) holds its checks' figures, not a run's
        let verdict_file = reader.file.link_exists("dba");
        for group in ["mesh", "increments", "history"] {
            if !reader.file.link_exists(group) && !verdict_file {
                return Err(Error::input(format!("{}: not a slideline results file (no /{group} group)", path.display())));
            }
        }
        Ok(reader)
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The file itself, for the restart's own groups.
    pub(super) fn file(&self) -> &hdf5::File {
        &self.file
    }

    fn read_f64(&self, name: &str) -> Result<Vec<f64>> {
        let ds = self.file.dataset(name).map_err(|e| missing(&self.path, name, e))?;
        ds.read_raw::<f64>().map_err(|e| missing(&self.path, name, e))
    }

    fn read_i64(&self, name: &str) -> Result<Vec<i64>> {
        let ds = self.file.dataset(name).map_err(|e| missing(&self.path, name, e))?;
        ds.read_raw::<i64>().map_err(|e| missing(&self.path, name, e))
    }

    /// Reference coordinates (r, z) of the nodes, in file order.
    /// Whether the file holds a mesh (a design-by-analysis verdict file does not).
    pub fn has_mesh(&self) -> bool {
        self.file.link_exists("mesh")
    }

    pub fn coordinates(&self) -> Result<Vec<[f64; 2]>> {
        Ok(self.read_f64("mesh/coordinates")?.chunks_exact(2).map(|c| [c[0], c[1]]).collect())
    }

    /// Q8 connectivity as rows of `coordinates` (checked: a row that names no node is refused).
    pub fn connectivity(&self) -> Result<Vec<[usize; 8]>> {
        let flat = self.read_i64("mesh/connectivity")?;
        let nodes = self.file.dataset("mesh/coordinates").map(|d| d.shape().first().copied().unwrap_or(0)).unwrap_or(0) as i64;
        if flat.len() % 8 != 0 {
            return Err(Error::input(format!("{}: mesh/connectivity holds {} values, not 8 per element", self.path.display(), flat.len())));
        }
        if let Some(k) = flat.iter().position(|&n| n < 0 || n >= nodes) {
            return Err(Error::input(format!(
                "{}: mesh/connectivity names node row {} in element row {}, and the mesh has {nodes} nodes",
                self.path.display(),
                flat[k],
                k / 8
            )));
        }
        Ok(flat.chunks_exact(8).map(|c| std::array::from_fn(|k| c[k] as usize)).collect())
    }

    /// How each element is integrated, in file order: `mesh/gauss_points` (4 for a reduced Q8);
    /// a file written before that dataset holds only fully integrated elements.
    pub fn integration(&self) -> Result<Vec<Integration>> {
        let elements = self.file.dataset("mesh/element_ids").map(|d| d.shape().first().copied().unwrap_or(0)).unwrap_or(0);
        if !self.file.link_exists("mesh/gauss_points") {
            return Ok(vec![Integration::Full; elements]);
        }
        let ds = self.file.dataset("mesh/gauss_points").map_err(|e| missing(&self.path, "mesh/gauss_points", e))?;
        let counts = ds.read_raw::<u32>().map_err(|e| missing(&self.path, "mesh/gauss_points", e))?;
        counts
            .iter()
            .enumerate()
            .map(|(e, &n)| match n {
                9 => Ok(Integration::Full),
                4 | 3 => Ok(Integration::Reduced),
                _ => Err(Error::input(format!("{}: mesh/gauss_points gives element row {e} {n} points (9, 4 or 3)", self.path.display()))),
            })
            .collect()
    }

    /// External node numbers (Gmsh tags), in file order.
    pub fn node_ids(&self) -> Result<Vec<u64>> {
        let ds = self.file.dataset("mesh/node_ids").map_err(|e| missing(&self.path, "mesh/node_ids", e))?;
        ds.read_raw::<u64>().map_err(|e| missing(&self.path, "mesh/node_ids", e))
    }

    /// External element numbers, in file order.
    pub fn element_ids(&self) -> Result<Vec<u64>> {
        let ds = self.file.dataset("mesh/element_ids").map_err(|e| missing(&self.path, "mesh/element_ids", e))?;
        ds.read_raw::<u64>().map_err(|e| missing(&self.path, "mesh/element_ids", e))
    }

    /// The node set `name` names, as .inp set names are read: without regard to case (an
    /// exact match first).
    pub fn node_set_name(&self, name: &str) -> Result<String> {
        let known = self.file.group("mesh/node_sets").and_then(|g| g.member_names()).unwrap_or_default();
        known
            .iter()
            .find(|k| *k == name)
            .or_else(|| known.iter().find(|k| k.eq_ignore_ascii_case(name)))
            .cloned()
            .ok_or_else(|| Error::input(format!("{}: no node set {name:?} (the sets are {})", self.path.display(), known.join(", "))))
    }

    /// Rows of `coordinates` of a node set's members.
    pub fn node_set(&self, name: &str) -> Result<Vec<usize>> {
        let path = format!("mesh/node_sets/{name}");
        let ds = self.file.dataset(&path).map_err(|_| {
            let known = self.file.group("mesh/node_sets").and_then(|g| g.member_names()).unwrap_or_default();
            Error::input(format!("{}: no node set {name:?} (the sets are {})", self.path.display(), known.join(", ")))
        })?;
        Ok(ds.read_raw::<u64>().map_err(|e| missing(&self.path, &path, e))?.into_iter().map(|k| k as usize).collect())
    }

    /// Names of the element sets.
    pub fn element_set_names(&self) -> Result<Vec<String>> {
        let g = self.file.group("mesh/element_sets").map_err(|e| missing(&self.path, "mesh/element_sets", e))?;
        g.member_names().map_err(|e| missing(&self.path, "mesh/element_sets", e))
    }

    /// Positions (rows of the element datasets) of an element set's members.
    pub fn element_set(&self, name: &str) -> Result<Vec<usize>> {
        let path = format!("mesh/element_sets/{name}");
        let ds = self.file.dataset(&path).map_err(|e| missing(&self.path, &path, e))?;
        Ok(ds.read_raw::<u64>().map_err(|e| missing(&self.path, &path, e))?.into_iter().map(|k| k as usize).collect())
    }

    /// Names of the complete increments (zero-padded, so sorted in order); an increment a run
    /// left half-written is not among them (see [`ResultsReader::notes`]).
    pub fn increments(&self) -> Result<Vec<String>> {
        let (complete, _) = self.increments_by_completion()?;
        Ok(complete)
    }

    /// (complete, incomplete) increment names. Files written before increments were marked
    /// have every increment complete.
    fn increments_by_completion(&self) -> Result<(Vec<String>, Vec<String>)> {
        let g = self.file.group("increments").map_err(|e| missing(&self.path, "increments", e))?;
        let mut names = g.member_names().map_err(|e| missing(&self.path, "increments", e))?;
        names.sort();
        if !self.file.attr_names().is_ok_and(|a| a.iter().any(|n| n == super::h5::COMPLETION_MARKED)) {
            return Ok((names, Vec::new()));
        }
        let is_complete = |n: &String| g.group(n).and_then(|inc| inc.attr_names()).is_ok_and(|a| a.iter().any(|x| x == super::h5::COMPLETE));
        Ok(names.into_iter().partition(is_complete))
    }

    /// What a reader of this file should be told: increments left incomplete by a run that
    /// died while writing them, history columns of unequal length (both ignored past the
    /// complete increments).
    pub fn notes(&self) -> Result<Vec<String>> {
        let mut notes = Vec::new();
        let (complete, incomplete) = self.increments_by_completion()?;
        if let Some((lock, held)) = super::lock::live_writer(&self.path) {
            // a run still at work: the increment it is writing and the history rows ahead of
            // its fields are no damage, so nothing else is noted
            let under_way = if incomplete.is_empty() { String::new() } else { format!("; increment(s) {} under way are left out", incomplete.join(", ")) };
            notes.push(format!(
                "{}: a run is still writing this file (its lock {} holds {held}): its {} complete increment(s) are read{under_way}",
                self.path.display(),
                lock.display(),
                complete.len()
            ));
            return Ok(notes);
        }
        if !incomplete.is_empty() {
            notes.push(format!(
                "{}: increment(s) {} were not completely written (the run stopped while writing them) and are ignored",
                self.path.display(),
                incomplete.join(", ")
            ));
        }
        let lengths: Vec<(String, usize)> =
            self.history_columns()?.into_iter().map(|c| Ok((c.clone(), self.read_f64(&format!("history/{c}"))?.len()))).collect::<Result<_>>()?;
        let held = self.rows_held()?;
        let missing = self.missing_increments(held)?;
        if !missing.is_empty() {
            notes.push(format!(
                "{}: the fields of increment(s) {} should be in the file and are not (their history rows are)",
                self.path.display(),
                crate::error::first_ten(&missing)
            ));
        }
        if lengths.iter().any(|(_, n)| *n != held) {
            let (shortest, n) = lengths.iter().min_by_key(|c| c.1).cloned().unwrap_or_default();
            notes.push(format!(
                "{}: the history columns differ in length (shortest: {shortest}, {n} rows; {} complete increments with fields): only the {held} rows all of them hold are read",
                self.path.display(),
                complete.len()
            ));
        }
        Ok(notes)
    }

    /// The increments among the first `rows` whose fields the run wrote (by its `output_every`
    /// and the last of each step) that have no group (none for files without the attribute).
    fn missing_increments(&self, rows: usize) -> Result<Vec<usize>> {
        let Ok(every) = self.file.attr(super::h5::OUTPUT_EVERY).and_then(|a| a.read_scalar::<u32>()) else {
            return Ok(Vec::new());
        };
        if rows == 0 {
            // no row, no column to read (a heat-conduction run, or one that converged nothing)
            return Ok(Vec::new());
        }
        let (step, load_factor) = (self.read_f64("history/step")?, self.read_f64("history/load_factor")?);
        let groups = self.file.group("increments").and_then(|g| g.member_names()).unwrap_or_default();
        let last_of_step = |k: usize| load_factor.get(k).is_some_and(|&l| l >= 1.0) || (k + 1 < step.len() && step[k + 1] != step[k]);
        // a restart's file holds the rows before it without their fields
        let restarted = self.restarted_from().map_or(0, |(_, at)| at);
        Ok((restarted..rows.min(step.len()))
            .filter(|&k| last_of_step(k) || (k + 1).is_multiple_of(every.max(1) as usize))
            .map(|k| k + 1)
            .filter(|n| !groups.contains(&format!("{n:06}")))
            .collect())
    }

    /// Nodal displacement (u_r, u_z) at an increment.
    pub fn displacement(&self, increment: &str) -> Result<Vec<[f64; 2]>> {
        match self.file.link_exists(&format!("increments/{increment}/nodal/displacement")) {
            // the (r, z, 0) vector ParaView warps by
            true => Ok(self.read_f64(&format!("increments/{increment}/nodal/displacement"))?.chunks_exact(3).map(|c| [c[0], c[1]]).collect()),
            // files of slideline 0.1 before it also kept an (r, z) copy, and older ones only it
            false => Ok(self.read_f64(&format!("increments/{increment}/displacement"))?.chunks_exact(2).map(|c| [c[0], c[1]]).collect()),
        }
    }

    /// The file a restart continued and the increment it continued from (the root attribute
    /// `restarted_from`, "PATH increment N"), None for a run from the start.
    pub fn restarted_from(&self) -> Option<(PathBuf, usize)> {
        let text = self.text_attr("restarted_from").ok()?;
        let (path, at) = text.rsplit_once(" increment ")?;
        Some((PathBuf::from(path), at.trim().parse().ok()?))
    }

    /// Whether increment group `increment` holds the displacement (complete or not).
    /// Whether increment `increment` holds the dataset `name` (a path below its group).
    pub fn has_field(&self, increment: &str, name: &str) -> bool {
        self.file.link_exists(&format!("increments/{increment}/{name}"))
    }

    pub fn has_displacement(&self, increment: &str) -> bool {
        ["nodal/displacement", "displacement"].iter().any(|d| self.file.link_exists(&format!("increments/{increment}/{d}")))
    }

    /// The bellows code check the file holds (`/assessment`), if any.
    pub fn assessment(&self) -> Result<Option<crate::assessment::code::CodeCheck>> {
        super::assessment::read(&self.file, &self.path)
    }

    /// A design specification's verdict the file holds, with the specification's text and its
    /// SHA-256 (`/assessment/verdict`), if any.
    pub fn verdict(&self) -> Result<Option<(crate::assessment::verdict::Verdict, String, String)>> {
        super::assessment::read_verdict(&self.file, &self.path)
    }

    /// The tables a bellows run printed after its closing table (name, text), in its order.
    pub fn printed_tables(&self) -> Result<Vec<(String, String)>> {
        super::assessment::read_tables(&self.file, &self.path)
    }

    /// The perturbation steps the file holds: (name, mode, per set its full-ring resultants
    /// (name, value)), sorted by name.
    pub fn perturbations(&self) -> Result<Vec<StoredPerturbation>> {
        let Ok(top) = self.file.group("perturbations") else { return Ok(Vec::new()) };
        let bad = |e: hdf5::Error| Error::input(format!("{}: /perturbations: {e}", self.path.display()));
        let mut out = Vec::new();
        for name in top.member_names().map_err(bad)? {
            let g = top.group(&name).map_err(bad)?;
            let mode = g.attr("mode").and_then(|a| a.read_scalar::<u32>()).map_err(bad)?;
            let reactions = g.group("reactions").map_err(bad)?;
            let mut sets = Vec::new();
            for set in reactions.member_names().map_err(bad)? {
                let sg = reactions.group(&set).map_err(bad)?;
                let mut values = Vec::new();
                for attr in sg.attr_names().map_err(bad)?.into_iter().filter(|a| a.ends_with("_ring")) {
                    values.push((attr.clone(), sg.attr(&attr).and_then(|a| a.read_scalar::<f64>()).map_err(bad)?));
                }
                sets.push((set, values));
            }
            let procedure = g.attr("procedure").and_then(|a| a.read_scalar::<hdf5::types::VarLenUnicode>()).map(|v| v.as_str().to_string()).unwrap_or_default();
            let list = |name: &str| g.dataset(name).and_then(|d| d.read_raw::<f64>()).unwrap_or_default();
            let (eigenvalues, masses) = (list("eigenvalues"), list("effective_mass_ring"));
            let analysis = Analysis::of_procedure(&procedure, eigenvalues.len()).unwrap_or(Analysis::Response);
            let eigenvalues = eigenvalues.iter().enumerate().map(|(i, &v)| (v, masses.get(i).copied())).collect();
            out.push(StoredPerturbation { name, mode, reactions: sets, analysis, eigenvalues });
        }
        Ok(out)
    }

    /// The heat steps the file holds, sorted by name.
    pub fn heat_steps(&self) -> Result<Vec<StoredHeat>> {
        let Ok(top) = self.file.group("heat") else { return Ok(Vec::new()) };
        let bad = |e: hdf5::Error| Error::input(format!("{}: /heat: {e}", self.path.display()));
        let mut out = Vec::new();
        for name in top.member_names().map_err(bad)? {
            let g = top.group(&name).map_err(bad)?;
            let t = g.dataset("temperature").and_then(|d| d.read_raw::<f64>()).map_err(bad)?;
            let range = t.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |[a, b], &v| [a.min(v), b.max(v)]);
            let flows = g.group("flows").map_err(bad)?;
            let mut sets = Vec::new();
            for set in flows.member_names().map_err(bad)? {
                let sg = flows.group(&set).map_err(bad)?;
                let flow = sg.attr("flow_ring").or_else(|_| sg.attr("flow")).and_then(|a| a.read_scalar::<f64>()).map_err(bad)?;
                sets.push((set, flow));
            }
            out.push((name, range, sets));
        }
        Ok(out)
    }

    /// A dataset of perturbation step `step`, flattened (row-major).
    pub fn perturbation_field(&self, step: &str, name: &str) -> Result<Vec<f64>> {
        self.read_f64(&format!("perturbations/{step}/{name}"))
    }

    /// The design assessment's finite-element figures the file holds, if any.
    pub fn finite_element_assessment(&self) -> Result<Option<(crate::assessment::fe_check::FeCheck, Option<crate::assessment::fe_check::StrainLife>)>> {
        super::assessment::read_finite_element(&self.file, &self.path)
    }

    /// Any field of an increment, flattened (row-major).
    pub fn field(&self, increment: &str, name: &str) -> Result<Vec<f64>> {
        self.read_f64(&format!("increments/{increment}/{name}"))
    }

    /// The datasets of an increment's nodal group (none in files written before it existed).
    pub fn nodal_fields(&self, increment: &str) -> Result<Vec<String>> {
        Ok(self.file.group(&format!("increments/{increment}/nodal")).and_then(|g| g.member_names()).unwrap_or_default())
    }

    /// The `units` attribute of a dataset ("-" where it has none).
    pub fn units(&self, dataset: &str) -> String {
        self.file
            .dataset(dataset)
            .and_then(|d| d.attr("units"))
            .and_then(|a| a.read_scalar::<hdf5::types::VarLenUnicode>())
            .map_or_else(|_| "-".to_string(), |u| u.to_string())
    }

    /// A numeric attribute of an increment (step, increment, load_factor, time).
    pub fn increment_attr(&self, increment: &str, name: &str) -> Result<f64> {
        let what = format!("increments/{increment} attribute {name}");
        let g = self.file.group(&format!("increments/{increment}")).map_err(|e| missing(&self.path, &what, e))?;
        g.attr(name).and_then(|a| a.read_scalar::<f64>()).map_err(|e| missing(&self.path, &what, e))
    }

    /// Names of the history columns, in the order the run printed them.
    pub fn history_columns(&self) -> Result<Vec<String>> {
        let g = self.file.group("history").map_err(|e| missing(&self.path, "history", e))?;
        let mut names = g.member_names().map_err(|e| missing(&self.path, "history", e))?;
        if let Ok(order) = g.attr("columns").and_then(|a| a.read_scalar::<VarLenUnicode>()) {
            let order: Vec<String> = order.as_str().split(',').map(str::to_string).collect();
            names.sort_by_key(|n| order.iter().position(|o| o == n).unwrap_or(usize::MAX));
        }
        Ok(names)
    }

    /// A text attribute of the file (deck, units, petsc_options, slideline_version).
    pub fn text_attr(&self, name: &str) -> Result<String> {
        let a = self.file.attr(name).map_err(|e| missing(&self.path, &format!("attribute {name}"), e))?;
        Ok(a.read_scalar::<VarLenUnicode>().map_err(|e| missing(&self.path, &format!("attribute {name}"), e))?.to_string())
    }

    /// Whether every element of the run was a plane section (the `geometry` attribute; files
    /// written before it existed are axisymmetric).
    pub fn is_plane(&self) -> bool {
        self.text_attr("geometry").is_ok_and(|g| g == "plane")
    }

    /// An integer attribute of the file (ranks, steps).
    pub fn count_attr(&self, name: &str) -> Result<usize> {
        let a = self.file.attr(name).map_err(|e| missing(&self.path, &format!("attribute {name}"), e))?;
        Ok(a.read_scalar::<u32>().map_err(|e| missing(&self.path, &format!("attribute {name}"), e))? as usize)
    }

    /// The history as the run recorded it: (step name, row) per converged increment.
    pub fn history_rows(&self) -> Result<Vec<(String, HistoryRow)>> {
        let columns = self.history_columns()?;
        if columns.is_empty() {
            // no increment converged, or a heat-conduction run (it has none)
            return Ok(Vec::new());
        }
        let data: Vec<Vec<f64>> = columns.iter().map(|c| self.history(c)).collect::<Result<_>>()?;
        let column = |name: &str| columns.iter().position(|c| c == name).map(|k| &data[k]);
        let need = |name: &str| column(name).ok_or_else(|| Error::input(format!("{}: no history column {name}", self.path.display())));
        let (step, increment, lambda, time) = (need("step")?, need("increment")?, need("load_factor")?, need("time")?);
        let (newton, linear, norm, cutbacks) = (need("newton_iterations")?, need("linear_iterations")?, need("residual_norm")?, need("cutbacks")?);
        let (augmentations, ep, wall) = (need("augmentations")?, need("max_equivalent_plastic_strain")?, need("wall_time")?);
        let sets: Vec<&str> = columns.iter().filter_map(|c| c.strip_prefix("reaction_")?.strip_suffix("_r")).collect();
        let pairs: Vec<&str> = columns.iter().filter_map(|c| c.strip_prefix("contact_")?.strip_suffix("_active_nodes")).collect();
        // a row's step name: its increment group's, or (a run that wrote the fields of some
        // increments only) the file's list of step names
        let step_names: Vec<String> = self.text_attr("step_names").map(|t| t.lines().map(str::to_string).collect()).unwrap_or_default();
        let mut rows = Vec::with_capacity(step.len());
        for k in 0..step.len() {
            let group = format!("{:06}", k + 1);
            let name = match self.increment_text_attr(&group, "step_name") {
                Ok(name) => name,
                Err(_) => step_names.get((step[k] as usize).saturating_sub(1)).cloned().unwrap_or_default(),
            };
            let reactions = sets
                .iter()
                .filter_map(|set| {
                    let f = [need(&format!("reaction_{set}_r")).ok()?[k], need(&format!("reaction_{set}_z")).ok()?[k]];
                    // NaN: the set is not constrained in this row's step
                    f[0].is_finite().then(|| (set.to_string(), f))
                })
                .collect();
            let set_displacements = sets
                .iter()
                .filter_map(|set| {
                    let u = [column(&format!("displacement_{set}_r"))?[k], column(&format!("displacement_{set}_z"))?[k]];
                    u[0].is_finite().then(|| (set.to_string(), u))
                })
                .collect();
            let contacts = pairs
                .iter()
                .map(|pair| {
                    let value = |what: &str| column(&format!("contact_{pair}_{what}")).map(|c| c[k]).unwrap_or(f64::NAN);
                    ContactSummary {
                        name: pair.to_string(),
                        active_nodes: value("active_nodes") as usize,
                        max_penetration: value("max_penetration"),
                        normal_force: value("force"),
                    }
                })
                .collect();
            let energy = column("energy_external_work").map(|_| {
                let value = |name: &str| column(name).map_or(f64::NAN, |c| c[k]);
                Energies {
                    external_work: value("energy_external_work"),
                    initial_contact: value("energy_initial_contact"),
                    elastic: value("energy_elastic"),
                    plastic_work: value("energy_plastic_work"),
                    thermal_work: value("energy_thermal_work"),
                    contact_stored: value("energy_contact_stored"),
                    friction_dissipation: value("energy_friction_dissipation"),
                }
            });
            let row = HistoryRow {
                number: k + 1,
                step: step[k] as usize,
                increment: increment[k] as usize,
                load_factor: lambda[k],
                time: time[k],
                newton_iterations: newton[k] as usize,
                linear_iterations: linear[k] as usize,
                residual_norm: norm[k],
                residual_norms: Vec::new(),
                // a file written before the column existed: no reference force to restore
                average_force: column("average_force").map_or(0.0, |c| c[k]),
                cutbacks: cutbacks[k] as usize,
                augmentations: augmentations[k] as usize,
                contacts,
                max_plastic_strain: ep[k],
                wall_time: wall[k],
                reactions,
                set_displacements,
                energy,
            };
            rows.push((name, row));
        }
        Ok(rows)
    }

    /// A text attribute of an increment (step_name).
    pub fn increment_text_attr(&self, increment: &str, name: &str) -> Result<String> {
        let what = format!("increments/{increment} attribute {name}");
        let g = self.file.group(&format!("increments/{increment}")).map_err(|e| missing(&self.path, &what, e))?;
        Ok(g.attr(name).and_then(|a| a.read_scalar::<VarLenUnicode>()).map_err(|e| missing(&self.path, &what, e))?.to_string())
    }

    /// One history column (a row per converged increment): the rows that every column holds
    /// and that come before any increment left incomplete, so that all columns line up.
    pub fn history(&self, column: &str) -> Result<Vec<f64>> {
        let mut rows = self.read_f64(&format!("history/{column}"))?;
        rows.truncate(self.rows_held()?);
        Ok(rows)
    }

    /// Rows of the history that every column holds, before the first increment left
    /// incomplete (its row may be cut short too).
    fn rows_held(&self) -> Result<usize> {
        let g = self.file.group("history").map_err(|e| missing(&self.path, "history", e))?;
        let names = g.member_names().map_err(|e| missing(&self.path, "history", e))?;
        let shortest =
            names.iter().map(|n| g.dataset(n).map(|d| d.size())).collect::<std::result::Result<Vec<_>, _>>().map_err(|e| missing(&self.path, "history", e))?;
        let (_, incomplete) = self.increments_by_completion()?;
        let before_incomplete = incomplete.first().and_then(|n| n.parse::<usize>().ok()).map_or(usize::MAX, |n| n - 1);
        Ok(shortest.into_iter().min().unwrap_or(0).min(before_incomplete))
    }
}

/// A heat step as the results file keeps it: (name, [lowest, highest] temperature (degC),
/// each held set's heat flow in (mW, full ring, or over a plane model's thickness)).
pub type StoredHeat = (String, [f64; 2], Vec<(String, f64)>);

/// A perturbation step as the results file keeps it: its name, mode and each set's full-ring
/// resultants (name, value).
#[derive(Clone, Debug, PartialEq)]
pub struct StoredPerturbation {
    pub name: String,
    pub mode: u32,
    pub reactions: Vec<(String, Vec<(String, f64)>)>,
    pub analysis: Analysis,
    /// Eigenvalue steps: each mode's (eigenvalue, effective mass).
    pub eigenvalues: Vec<(f64, Option<f64>)>,
}

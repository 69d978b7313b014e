//! Restart: reading back the state a converged increment left in the results file
//! (io/state.rs writes it) to continue the run from it exactly.
//!
//! Beside its fields, each increment group the run writes holds `state/` (attributes
//! `next_increment_size`, `pattern_refits`): the plastic state of every Gauss point that has
//! left its initial state (`plastic_points` (n, 2) [element id, point], `plastic_state` (n, 5)
//! [the four components of C_p^-1 or eps_p, equivalent plastic strain]; with kinematic hardening
//! also `backstress_state` (n, 13) [three backstresses rr, zz, tt, rz, their plastic work]) and the
//! augmented-Lagrangian multipliers that are nonzero (`multiplier_nodes_passK`, `multipliers_passK`).
//! The Jacobian's contact couplings grow through the run and are kept once, in
//! `/restart/pattern` (rows [increment number, rank, node id, node id]), so that a continued
//! run builds the very matrix structure the uninterrupted one had (MUMPS orders by structure:
//! the same structure, the same round-off). The displacement is the increment's own field.
//! Everything is keyed by node and element ids, so any partition can read it; the continued run
//! is bit-identical to the uninterrupted one on the same number of ranks.

use super::history::HistoryRow;
use super::reader::ResultsReader;
use super::state::{AUDIT_THERMAL, BACKSTRESS_COLUMNS, PREDICTOR_INCREMENT};
use crate::error::{Error, Result};
use crate::material::backstress::MAX_BACKSTRESSES;
use crate::material::PointState;
use crate::model::Model;
use crate::records::contact::SlipPoint;
use crate::records::energy::AuditPoint;
use crate::records::last_increment::LastIncrement;
use std::collections::HashMap;
use std::path::PathBuf;

/// Which increment to continue from.
#[derive(Clone, Debug)]
pub struct RestartFrom {
    pub file: PathBuf,
    /// The increment's run-wide number; None: the last complete one holding a state.
    pub increment: Option<usize>,
}

/// A converged increment read back for a restart, in the deck's node and element numbering.
pub struct RestartPoint {
    pub file: PathBuf,
    /// Run-wide number of the increment (its group /increments/NNNNNN).
    pub number: usize,
    /// Step index (0-based), increment within the step, load factor within the step.
    pub step: usize,
    pub increment: usize,
    pub load_factor: f64,
    pub next_size: f64,
    pub refits: usize,
    /// Displacement of every mesh node at the increment.
    pub displacement: Vec<[f64; 2]>,
    /// Displacement at the end of each step before the increment's (their loads carry over).
    pub step_ends: Vec<Vec<[f64; 2]>>,
    /// (mesh element, Gauss point, state) of every point not in its initial state.
    pub plastic: Vec<(usize, usize, PointState)>,
    /// Per pass, (mesh node, multiplier).
    pub multipliers: Vec<Vec<(usize, f64)>>,
    /// Per pass, (mesh node, slip reference) (friction).
    pub slip: Vec<Vec<(usize, SlipPoint)>>,
    /// The energy audit's starting point (its displacement is `displacement`; the totals are
    /// in the last row's energies).
    pub audit: AuditPoint,
    /// (rank that reserved it, mesh node, mesh node).
    pub pattern: Vec<(usize, usize, usize)>,
    /// Ranks of the run that wrote the file.
    pub ranks: usize,
    /// The increment before, as the extrapolation predictor takes it (None at a step's end).
    pub last_increment: Option<LastIncrement>,
    /// History rows up to and including the increment, with their step names.
    pub rows: Vec<(String, HistoryRow)>,
}

impl RestartPoint {
    /// Reads the state at `from` and checks that `model` is the model that wrote it (same
    /// mesh, same steps up to the increment's); bad input otherwise.
    pub fn read(from: &RestartFrom, model: &Model) -> Result<RestartPoint> {
        let reader = ResultsReader::open(&from.file)?;
        let path = from.file.display().to_string();
        let bad = |message: String| Error::input(format!("cannot restart from {path}: {message}"));
        let (nodes, elements) = check_mesh(&reader, model).map_err(bad)?;
        let (name, number, step) = restart_increment(&reader, from, model, &bad)?;
        // this file and those it continues (restarts of restarts), each with its node order
        let mut chain = vec![(reader, nodes.clone())];
        while chain.len() < 64 {
            let source = chain.last().and_then(|(r, _)| r.restarted_from());
            let Some(earlier) = source.and_then(|(p, _)| ResultsReader::open(&p).ok()) else { break };
            let (order, _) = check_mesh(&earlier, model).map_err(bad)?;
            chain.push((earlier, order));
        }
        let reader = &chain[0].0;
        // the displacement of increment group `g` from the first file of the chain holding it
        let field = |g: &str| -> Result<Option<Vec<[f64; 2]>>> {
            let what = format!("increments/{g}/nodal/displacement");
            let Some((r, order)) = chain.iter().find(|(r, _)| r.has_displacement(g)) else { return Ok(None) };
            let file_order = r.displacement(g)?;
            if file_order.len() != order.len() {
                return Err(bad(format!("{what} has {} rows, the mesh {} nodes", file_order.len(), order.len())));
            }
            if let Some(k) = file_order.iter().position(|u| !u.iter().all(|v| v.is_finite())) {
                return Err(bad(format!("{what} is not finite at row {k}")));
            }
            let mut out = vec![[0.0; 2]; order.len()];
            for (k, v) in file_order.into_iter().enumerate() {
                out[order[k]] = v;
            }
            Ok(Some(out))
        };
        let displacement = field(&name)?.ok_or_else(|| bad(format!("increments/{name} holds no displacement")))?;
        // the last complete increment of each earlier step (always written) gives its end
        let mut step_ends = Vec::new();
        for k in 0..step {
            let is_end = |r: &ResultsReader, g: &String| {
                r.increment_attr(g, "step").ok() == Some((k + 1) as f64) && r.increment_attr(g, "load_factor").ok() == Some(1.0)
            };
            let end = chain.iter().find_map(|(r, _)| r.increments().ok()?.into_iter().rev().find(|g| is_end(r, g)));
            let end = end.ok_or_else(|| bad(format!("the end of step {} is in neither the file nor those it continues", k + 1)))?;
            step_ends.push(field(&end)?.ok_or_else(|| bad(format!("increments/{end} holds no displacement")))?);
        }
        let group = format!("increments/{name}/state");
        let file = reader.file();
        let sg = file.group(&group).map_err(|e| bad(format!("{group}: {e}")))?;
        let next_size = sg.attr("next_increment_size").and_then(|a| a.read_scalar::<f64>()).map_err(|e| bad(format!("{group}: {e}")))?;
        if !(next_size > 0.0 && next_size <= 1.0) {
            return Err(bad(format!("{group} attribute next_increment_size is {next_size}, not a load factor in (0, 1]")));
        }
        let refits = sg.attr("pattern_refits").and_then(|a| a.read_scalar::<u64>()).map_err(|e| bad(format!("{group}: {e}")))? as usize;
        let state = StateGroup { sg, name: group.clone(), bad: &bad };
        let node_index: HashMap<u64, usize> = model.mesh.node_ids.iter().enumerate().map(|(k, &id)| (id, k)).collect();
        let node = |id: u64| node_index.get(&id).copied().ok_or_else(|| bad(format!("node {id} of its state is not in the mesh")));
        let plastic = plastic_points(&state, &elements)?;
        let (multipliers, slip) = contact_state(&state, model, &node)?;
        let audit = audit_point(&state, model, &displacement, &node)?;
        let pattern = chain_pattern(&chain, number, &node, &bad)?;
        let load_factor = reader.increment_attr(&name, "load_factor")?;
        if !(load_factor > 0.0 && load_factor <= 1.0) {
            return Err(bad(format!("increments/{name} attribute load_factor is {load_factor}, not in (0, 1]")));
        }
        let mut rows = reader.history_rows()?;
        if rows.len() < number {
            return Err(bad(format!("its history holds {} rows, fewer than the increment's number {number}", rows.len())));
        }
        rows.truncate(number);
        let increment = reader.increment_attr(&name, "increment")? as usize;
        let last_increment = if load_factor == 1.0 {
            None // the next step starts with the tangent predictor
        } else if increment == 1 {
            let start = if step == 0 { vec![[0.0; 2]; nodes.len()] } else { step_ends[step - 1].clone() };
            Some(LastIncrement::between(&start, &displacement, load_factor))
        } else {
            let before = &rows[number - 2].1;
            let size = load_factor - before.load_factor;
            let previous = format!("{:06}", number - 1);
            // the field of the increment before, from this file or one it continues
            let before = field(&previous)?;
            if let Some(before) = before {
                Some(LastIncrement::between(&before, &displacement, size))
            } else if state.sg.link_exists(PREDICTOR_INCREMENT) {
                let values = state.f64s(PREDICTOR_INCREMENT)?;
                if values.len() != 2 * nodes.len() || !values.iter().all(|v| v.is_finite()) {
                    return Err(bad(format!("{group}/{PREDICTOR_INCREMENT}: {} values for {} nodes, or not finite", values.len(), nodes.len())));
                }
                Some(LastIncrement { displacement: values.chunks_exact(2).map(|c| [c[0], c[1]]).collect(), size })
            } else {
                None // an older file: the tangent predictor
            }
        };
        Ok(RestartPoint {
            file: from.file.clone(),
            number,
            step,
            increment,
            load_factor,
            next_size,
            refits,
            displacement,
            step_ends,
            plastic,
            multipliers,
            slip,
            audit,
            pattern,
            ranks: reader.count_attr("ranks")?,
            rows,
            last_increment,
        })
    }
}

/// The Jacobian's contact couplings reserved up to increment `number`, (rank, mesh node, mesh
/// node), from the files of `chain` (this file first, then those it continues): each continued
/// file holds those after its restart point, the file it continues those before (oldest first,
/// the order the run reserved them).
fn chain_pattern(
    chain: &[(ResultsReader, Vec<usize>)],
    number: usize,
    node: &dyn Fn(u64) -> Result<usize>,
    bad: &dyn Fn(String) -> Error,
) -> Result<Vec<(usize, usize, usize)>> {
    let mut limits = vec![number];
    for (r, _) in &chain[..chain.len() - 1] {
        let at = r.restarted_from().map_or(0, |(_, at)| at);
        limits.push(at.min(*limits.last().unwrap_or(&number)));
    }
    let mut pattern = Vec::new();
    for ((r, _), &limit) in chain.iter().zip(&limits).rev() {
        if !r.file().link_exists("restart/pattern") {
            continue;
        }
        let rows = r.file().dataset("restart/pattern").and_then(|d| d.read_raw::<u64>()).map_err(|e| bad(format!("restart/pattern: {e}")))?;
        for row in rows.chunks_exact(4).filter(|row| row[0] as usize <= limit) {
            pattern.push((row[1] as usize, node(row[2])?, node(row[3])?));
        }
    }
    Ok(pattern)
}

/// An increment's restart state group: its datasets read (empty where absent), a refusal worded
/// by `bad`.
struct StateGroup<'b> {
    sg: hdf5::Group,
    name: String,
    bad: &'b dyn Fn(String) -> Error,
}

impl StateGroup<'_> {
    fn u64s(&self, ds: &str) -> Result<Vec<u64>> {
        if !self.sg.link_exists(ds) {
            return Ok(Vec::new());
        }
        self.sg.dataset(ds).and_then(|d| d.read_raw::<u64>()).map_err(|e| (self.bad)(format!("{}/{ds}: {e}", self.name)))
    }

    fn f64s(&self, ds: &str) -> Result<Vec<f64>> {
        if !self.sg.link_exists(ds) {
            return Ok(Vec::new());
        }
        self.sg.dataset(ds).and_then(|d| d.read_raw::<f64>()).map_err(|e| (self.bad)(format!("{}/{ds}: {e}", self.name)))
    }
}

/// The Gauss points not in their initial state: (mesh element, point, state), each checked.
fn plastic_points(state: &StateGroup<'_>, elements: &HashMap<u64, usize>) -> Result<Vec<(usize, usize, PointState)>> {
    let (bad, group) = (state.bad, &state.name);
    let points = state.u64s("plastic_points")?;
    let states = state.f64s("plastic_state")?;
    if points.len() / 2 != states.len() / 5 || points.len() % 2 != 0 || states.len() % 5 != 0 {
        return Err(bad(format!("{group}/plastic_points ({} values) and plastic_state ({} values) do not pair up", points.len(), states.len())));
    }
    // written only where a material has kinematic hardening: zero backstresses otherwise
    let back = match state.sg.link_exists("backstress_state") {
        true => state.f64s("backstress_state")?,
        false => vec![0.0; points.len() / 2 * BACKSTRESS_COLUMNS],
    };
    if back.len() != points.len() / 2 * BACKSTRESS_COLUMNS || !back.iter().all(|v| v.is_finite()) {
        return Err(bad(format!("{group}/backstress_state ({} values) does not pair with plastic_points ({} points)", back.len(), points.len() / 2)));
    }
    let mut plastic = Vec::with_capacity(points.len() / 2);
    for ((p, s), b) in points.chunks_exact(2).zip(states.chunks_exact(5)).zip(back.chunks_exact(BACKSTRESS_COLUMNS)) {
        let e = elements.get(&p[0]).copied().ok_or_else(|| bad(format!("element {} of its state is not in the mesh", p[0])))?;
        if p[1] >= 9 || !s.iter().all(|v| v.is_finite()) || s[4] < 0.0 {
            return Err(bad(format!("{group}/plastic_points, plastic_state: Gauss point {} of element {} ({s:?}) is no state", p[1], p[0])));
        }
        let back = std::array::from_fn(|k| std::array::from_fn(|c| b[4 * k + c]));
        let point = PointState { back, kinematic_work: b[4 * MAX_BACKSTRESSES], ..PointState::isotropic([s[0], s[1], s[2], s[3]], s[4]) };
        plastic.push((e, p[1] as usize, point));
    }
    Ok(plastic)
}

/// Per contact pass, the slave nodes' multipliers and (friction) slip references.
#[allow(clippy::type_complexity)]
fn contact_state(state: &StateGroup<'_>, model: &Model, node: &dyn Fn(u64) -> Result<usize>) -> Result<(Vec<Vec<(usize, f64)>>, Vec<Vec<(usize, SlipPoint)>>)> {
    let (bad, group, sg) = (state.bad, &state.name, &state.sg);
    let passes = sg.attr("contact_passes").and_then(|a| a.read_scalar::<u64>()).map_err(|e| bad(format!("{group}: {e}")))? as usize;
    let master_edges = pass_master_edges(model);
    if passes != master_edges.len() {
        return Err(bad(format!("{group} holds {passes} contact passes, the model has {}", master_edges.len())));
    }
    let mut multipliers = Vec::new();
    for p in 0..passes {
        let ids = state.u64s(&format!("multiplier_nodes_pass{p}"))?;
        let values = state.f64s(&format!("multipliers_pass{p}"))?;
        if ids.len() != values.len() || !values.iter().all(|v| v.is_finite()) {
            return Err(bad(format!("{group}/multipliers_pass{p}: {} values for {} nodes, or not finite", values.len(), ids.len())));
        }
        multipliers.push(ids.into_iter().zip(values).map(|(id, v)| Ok((node(id)?, v))).collect::<Result<Vec<_>>>()?);
    }
    let mut slip = Vec::new();
    for (p, &edges) in master_edges.iter().enumerate() {
        let ids = state.u64s(&format!("slip_nodes_pass{p}"))?;
        let values = state.f64s(&format!("slip_pass{p}"))?;
        let what = format!("{group}/slip_pass{p}");
        if 3 * ids.len() != values.len() {
            return Err(bad(format!("{what}: {} values for {} nodes", values.len(), ids.len())));
        }
        let point = |v: &[f64]| -> Result<SlipPoint> {
            // an edge of the pass's master surface, a coordinate on it, a finite traction
            let edge_ok = v[0] >= 0.0 && v[0].fract() == 0.0 && (v[0] as usize) < edges;
            let xi_ok = v[1].is_finite() && v[1].abs() <= 1.5;
            if !edge_ok || !xi_ok || !v[2].is_finite() {
                return Err(bad(format!("{what}: [{}, {}, {}] is no slip reference on the master's {edges} edges", v[0], v[1], v[2])));
            }
            Ok(SlipPoint { edge: v[0] as usize, xi: v[1], traction: v[2] })
        };
        slip.push(ids.into_iter().zip(values.chunks_exact(3)).map(|(id, v)| Ok((node(id)?, point(v)?))).collect::<Result<Vec<_>>>()?);
    }
    Ok((multipliers, slip))
}

/// The energy audit's starting point at the increment (its displacement `displacement`).
fn audit_point(state: &StateGroup<'_>, model: &Model, displacement: &[[f64; 2]], node: &dyn Fn(u64) -> Result<usize>) -> Result<AuditPoint> {
    let (bad, group, sg) = (state.bad, &state.name, &state.sg);
    let count = model.mesh.coords.len();
    let thermal = state.f64s(AUDIT_THERMAL)?;
    let (thermal_force, temperature) = if thermal.len() == 2 * count && thermal.iter().all(|v| v.is_finite()) {
        (thermal.iter().step_by(2).copied().collect(), thermal.iter().skip(1).step_by(2).copied().collect())
    } else if thermal.is_empty() && sg.attr("audit_temperature").is_ok() {
        // a model at one temperature throughout: the stress power summed over it, which a
        // uniform temperature change multiplies wherever it sits
        let attr = |name: &str| sg.attr(name).and_then(|a| a.read_scalar::<f64>()).map_err(|e| bad(format!("{group}: {e}")));
        let mut force = vec![0.0; count];
        force[0] = attr("audit_thermal_power")?;
        (force, vec![attr("audit_temperature")?; count])
    } else {
        return Err(bad(format!("{group}/{AUDIT_THERMAL}: {} values for {count} nodes, or not finite", thermal.len())));
    };
    let mut audit = AuditPoint { forces: vec![[0.0; 4]; count], displacement: displacement.to_vec(), thermal_force, temperature };
    for (id, f) in state.u64s("audit_nodes")?.into_iter().zip(state.f64s("audit_forces")?.chunks_exact(4)) {
        audit.forces[node(id)?] = [f[0], f[1], f[2], f[3]];
    }
    Ok(audit)
}

/// The increment `from` names (or the last with a restart state) in `reader`'s file, as its
/// group name, run-wide number and step (0-based), once the deck is shown to run the same
/// model and the same steps up to it (`bad` words a refusal).
fn restart_increment(reader: &ResultsReader, from: &RestartFrom, model: &Model, bad: &dyn Fn(String) -> Error) -> Result<(String, usize, usize)> {
    let with_state: Vec<String> = reader.increments()?.into_iter().filter(|name| reader.file().link_exists(&format!("increments/{name}/state"))).collect();
    let name = match from.increment {
        None => with_state
            .last()
            .cloned()
            .ok_or_else(|| bad("it holds no increment with a restart state (written by an older slideline, or no increment converged)".into()))?,
        Some(n) => {
            let name = format!("{n:06}");
            if !with_state.contains(&name) {
                let first = with_state.first().map(|s| s.trim_start_matches('0').to_string()).unwrap_or_default();
                let last = with_state.last().map(|s| s.trim_start_matches('0').to_string()).unwrap_or_default();
                return Err(bad(match with_state.is_empty() {
                    true => "it holds no increment with a restart state".into(),
                    false => format!(
                        "increment {n} is not among its {} restartable increments ({first} .. {last}; with [output] every = N only every N-th is)",
                        with_state.len()
                    ),
                }));
            }
            name
        }
    };
    let number: usize = name.parse().map_err(|_| bad(format!("increment group {name}")))?;
    // every value read is checked before it is used: a corrupt file is refused by name
    let step_attr = reader.increment_attr(&name, "step")?;
    if !(step_attr >= 1.0 && step_attr.fract() == 0.0) {
        return Err(bad(format!("increments/{name} attribute step is {step_attr}, not a step number")));
    }
    let step = step_attr as usize - 1;
    let names: Vec<String> = reader.text_attr("step_names")?.lines().map(str::to_string).collect();
    for (k, saved) in names.iter().enumerate().take(step + 1) {
        match model.general_steps().nth(k) {
            Some(s) if s.name == *saved => {}
            Some(s) => {
                return Err(bad(format!("its step {} is {saved:?}, the deck's is {:?} (a continued run may add steps, not change those done)", k + 1, s.name)))
            }
            None => return Err(bad(format!("increment {number} is in step {} ({saved:?}), the deck has {} step(s)", k + 1, model.general_step_count()))),
        }
    }
    // the model and every step begun must be the deck's (older files keep no fingerprints)
    if let Ok(stored) = reader.text_attr("fingerprints") {
        let changed = crate::model::fingerprint::changed(model, &stored, step);
        if !changed.is_empty() {
            return Err(bad(format!(
                "the deck changes {} of the run it continues (increment {number} is in step {}): a restart continues the same model and the steps begun; it may add steps after, or change those not yet begun",
                changed.join(", "),
                step + 1
            )));
        }
    }
    Ok((name, number, step))
}

/// The number of master edges of each contact pass, in the order of the passes: per pair, the
/// slave against the master, then (two-pass) the master against the slave.
fn pass_master_edges(model: &Model) -> Vec<usize> {
    let edges = |name: &str| model.surfaces.get(name).map_or(0, Vec::len);
    model
        .contacts
        .iter()
        .flat_map(|c| {
            let back = (c.two_pass && c.slave != c.master).then(|| edges(&c.slave));
            std::iter::once(edges(&c.master)).chain(back)
        })
        .collect()
}

/// The file's node rows as mesh nodes and its element ids as mesh elements, after checking
/// that the file's mesh is the model's: same nodes (ids and coordinates), same elements (ids
/// and connectivity). The first difference otherwise.
fn check_mesh(reader: &ResultsReader, model: &Model) -> std::result::Result<(Vec<usize>, HashMap<u64, usize>), String> {
    let io = |e: Error| e.to_string();
    let mesh = &model.mesh;
    let (ids, coords) = (reader.node_ids().map_err(io)?, reader.coordinates().map_err(io)?);
    let (element_ids, connectivity) = (reader.element_ids().map_err(io)?, reader.connectivity().map_err(io)?);
    if ids.len() != mesh.coords.len() || element_ids.len() != mesh.elements.len() {
        return Err(format!(
            "its mesh has {} nodes and {} elements, the deck's {} and {} (a restart continues the same model)",
            ids.len(),
            element_ids.len(),
            mesh.coords.len(),
            mesh.elements.len()
        ));
    }
    let node_index: HashMap<u64, usize> = mesh.node_ids.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    let scale = mesh.coords.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
    let mut nodes = Vec::with_capacity(ids.len());
    for (id, x) in ids.iter().zip(&coords) {
        let n = *node_index.get(id).ok_or_else(|| format!("its node {id} is not in the deck's mesh"))?;
        let y = mesh.coords[n];
        if (x[0] - y[0]).abs() > 1e-12 * scale || (x[1] - y[1]).abs() > 1e-12 * scale {
            return Err(format!("node {id} is at ({}, {}) in the file and at ({}, {}) in the deck", x[0], x[1], y[0], y[1]));
        }
        nodes.push(n);
    }
    let element_index: HashMap<u64, usize> = mesh.element_ids.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    for (id, conn) in element_ids.iter().zip(&connectivity) {
        let e = *element_index.get(id).ok_or_else(|| format!("its element {id} is not in the deck's mesh"))?;
        if conn.iter().zip(&mesh.elements[e]).any(|(&row, &n)| nodes.get(row) != Some(&n)) {
            return Err(format!("element {id} joins other nodes in the file than in the deck"));
        }
    }
    Ok((nodes, element_index))
}

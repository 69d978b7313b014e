//! The restart state: what a converged increment leaves in the results file so that a later
//! run can continue from it exactly (read back by io/restart.rs).
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

use super::h5::{describe_dataset, group_in, h5err, write_rows};
use crate::element::solid::QUADRATURE_POINTS as QP;
use crate::error::{Error, Result};
use crate::material::backstress::MAX_BACKSTRESSES;
use crate::material::PointState;
use crate::model::Mesh;
use crate::records::contact::SlipPoint;
use crate::records::energy::AuditPoint;
use mpi::datatype::PartitionMut;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::path::Path;

/// This rank's part of what a restart needs of a converged increment.
pub struct CommittedState<'a> {
    pub mesh: &'a Mesh,
    /// Committed history of the local elements (`local_elements` order).
    pub history: &'a [[PointState; QP]],
    /// Mesh indices of the local elements.
    pub local_elements: &'a [usize],
    /// The initial state of a Gauss point (points still in it are not stored).
    pub initial: PointState,
    /// Whether a material has kinematic hardening (the points' backstresses are then stored).
    pub kinematic: bool,
    /// Per contact pass, (mesh node, multiplier) of this rank's slave nodes with a nonzero one.
    pub multipliers: Vec<Vec<(usize, f64)>>,
    /// Per contact pass, (mesh node, slip reference) of this rank's slave nodes that have one.
    pub slip: Vec<Vec<(usize, SlipPoint)>>,
    /// Contact couplings this rank reserved since the last state written (mesh nodes).
    pub fresh_pattern: Vec<(usize, usize)>,
    /// Size of the next increment's first attempt (load factor).
    pub next_size: f64,
    /// The extrapolation predictor's last displacement increment (every mesh node), where a
    /// restart cannot take it from the previous increment's field in this file.
    pub predictor_increment: Option<&'a [[f64; 2]]>,
    /// Where the energy audit's next trapezoids start (the same on every rank).
    pub audit: &'a AuditPoint,
    /// Whether the temperature varies over the mesh in some step (the audit's thermal part
    /// is then kept per node; else as its sum and the one temperature).
    pub thermal_by_node: bool,
    pub refits: usize,
}

/// Writes `state` into increment group `g` (collective) and appends the fresh pattern rows to
/// `/restart/pattern`.
pub(super) fn write_state(
    file: &hdf5::File,
    g: &hdf5::Group,
    world: &SimpleCommunicator,
    number: usize,
    state: &CommittedState<'_>,
    path: &Path,
) -> Result<()> {
    let err = h5err(path);
    let mesh = state.mesh;
    let sg = g.create_group("state").map_err(&err)?;
    sg.new_attr::<f64>().create("next_increment_size").map_err(&err)?.write_scalar(&state.next_size).map_err(&err)?;
    sg.new_attr::<u64>().create("pattern_refits").map_err(&err)?.write_scalar(&(state.refits as u64)).map_err(&err)?;
    // a pass's datasets are left out where no rank has a row: the count says how many to read
    sg.new_attr::<u64>().create("contact_passes").map_err(&err)?.write_scalar(&(state.multipliers.len() as u64)).map_err(&err)?;
    let mut points = Vec::new();
    let mut values = Vec::new();
    let mut back = Vec::new();
    for (&e, history) in state.local_elements.iter().zip(state.history) {
        for (q, s) in history.iter().enumerate() {
            if *s != state.initial {
                points.extend([mesh.element_ids[e], q as u64]);
                values.extend(s.plastic.iter().copied().chain([s.ep]));
                back.extend(s.back.iter().flatten().copied().chain([s.kinematic_work]));
            }
        }
    }
    write_gathered(&sg, world, "plastic_points", 2, &points, path)?;
    write_gathered(&sg, world, "plastic_state", 5, &values, path)?;
    if state.kinematic {
        write_gathered(&sg, world, "backstress_state", BACKSTRESS_COLUMNS, &back, path)?;
    }
    for (p, pass) in state.multipliers.iter().enumerate() {
        let nodes: Vec<u64> = pass.iter().map(|&(n, _)| mesh.node_ids[n]).collect();
        let values: Vec<f64> = pass.iter().map(|&(_, v)| v).collect();
        write_gathered(&sg, world, &format!("multiplier_nodes_pass{p}"), 1, &nodes, path)?;
        write_gathered(&sg, world, &format!("multipliers_pass{p}"), 1, &values, path)?;
    }
    for (p, pass) in state.slip.iter().enumerate() {
        let nodes: Vec<u64> = pass.iter().map(|&(n, _)| mesh.node_ids[n]).collect();
        let values: Vec<f64> = pass.iter().flat_map(|(_, s)| [s.edge as f64, s.xi, s.traction]).collect();
        write_gathered(&sg, world, &format!("slip_nodes_pass{p}"), 1, &nodes, path)?;
        write_gathered(&sg, world, &format!("slip_pass{p}"), 3, &values, path)?;
    }
    // replicated, so rank 0 writes it, in the mesh's node order
    if let Some(delta) = state.predictor_increment {
        let local: Vec<f64> = if world.rank() == 0 { delta.iter().flatten().copied().collect() } else { Vec::new() };
        write_gathered(&sg, world, PREDICTOR_INCREMENT, 2, &local, path)?;
    }
    // the audit's starting point: replicated, so rank 0 writes it (the nodes with a load)
    let a = state.audit;
    if state.thermal_by_node {
        // per node, mesh order: the thermal stress power per degree and the temperature
        let local: Vec<f64> = if world.rank() == 0 { a.thermal_force.iter().zip(&a.temperature).flat_map(|(&f, &t)| [f, t]).collect() } else { Vec::new() };
        write_gathered(&sg, world, AUDIT_THERMAL, 2, &local, path)?;
    } else {
        // one temperature everywhere: only the sum of the stress power multiplies its changes
        let power: f64 = a.thermal_force.iter().sum();
        let temperature = a.temperature.first().copied().unwrap_or(0.0);
        sg.new_attr::<f64>().create("audit_thermal_power").map_err(&err)?.write_scalar(&power).map_err(&err)?;
        sg.new_attr::<f64>().create("audit_temperature").map_err(&err)?.write_scalar(&temperature).map_err(&err)?;
    }
    let loaded: Vec<usize> = if world.rank() == 0 { (0..a.forces.len()).filter(|&n| a.forces[n].iter().any(|&f| f != 0.0)).collect() } else { Vec::new() };
    let ids: Vec<u64> = loaded.iter().map(|&n| mesh.node_ids[n]).collect();
    let forces: Vec<f64> = loaded.iter().flat_map(|&n| a.forces[n]).collect();
    write_gathered(&sg, world, "audit_nodes", 1, &ids, path)?;
    write_gathered(&sg, world, "audit_forces", 4, &forces, path)?;
    // the pattern's new rows, gathered to every rank (resizing is collective), written by rank 0
    let local: Vec<u64> = state.fresh_pattern.iter().flat_map(|&(a, b)| [number as u64, world.rank() as u64, mesh.node_ids[a], mesh.node_ids[b]]).collect();
    let all = all_gather(world, &local);
    let restart = group_in(file, "restart", path)?;
    let ds = if restart.link_exists("pattern") {
        restart.dataset("pattern").map_err(&err)?
    } else {
        let ds = restart.new_dataset::<u64>().chunk((4096, 4)).shape((0.., 4)).create("pattern").map_err(&err)?;
        let (units, description) = super::describe::describe(&restart.name(), "pattern");
        describe_dataset(&ds, units, &description, path)?;
        ds
    };
    let held = ds.shape()[0];
    let rows = all.len() / 4;
    if rows > 0 {
        ds.resize((held + rows, 4)).map_err(&err)?;
        if world.rank() == 0 {
            let view = ndarray::ArrayView2::from_shape((rows, 4), &all).map_err(|e| Error::Output { path: path.to_path_buf(), message: e.to_string() })?;
            ds.write_slice(view, (held..held + rows, ..)).map_err(&err)?;
        }
    }
    Ok(())
}

/// Every rank's `local` values concatenated in rank order, on every rank.
fn all_gather<T: Equivalence + Copy + Default>(world: &SimpleCommunicator, local: &[T]) -> Vec<T> {
    let size = world.size() as usize;
    let mut counts = vec![0i32; size];
    world.all_gather_into(&(local.len() as i32), &mut counts[..]);
    let displs: Vec<i32> = counts.iter().scan(0, |acc, &c| Some(std::mem::replace(acc, *acc + c))).collect();
    let mut all = vec![T::default(); counts.iter().sum::<i32>() as usize];
    world.all_gather_varcount_into(local, &mut PartitionMut::new(&mut all[..], counts, displs));
    all
}

/// Dataset `name` of rows of `width` values, each rank writing its `local` rows after those of
/// the ranks before it (collective). Not created when no rank has a row.
fn write_gathered<T: hdf5::H5Type + Equivalence + Copy>(
    g: &hdf5::Group,
    world: &SimpleCommunicator,
    name: &str,
    width: usize,
    local: &[T],
    path: &Path,
) -> Result<()> {
    let rows = (local.len() / width) as u64;
    let size = world.size() as usize;
    let mut counts = vec![0u64; size];
    world.all_gather_into(&rows, &mut counts[..]);
    let total = counts.iter().sum::<u64>() as usize;
    if total == 0 {
        return Ok(());
    }
    let first = counts[..world.rank() as usize].iter().sum::<u64>() as usize;
    let shape = if width == 1 { vec![total] } else { vec![total, width] };
    write_rows(g, name, &shape, (first, first + rows as usize), local, path)
}

/// State dataset: the extrapolation predictor's displacement increment, mesh node order.
pub(super) const PREDICTOR_INCREMENT: &str = "predictor_increment";
pub(super) const AUDIT_THERMAL: &str = "audit_thermal";
/// Columns of `backstress_state`: the three backstresses [rr, zz, tt, rz] and their share of
/// the plastic work.
pub(super) const BACKSTRESS_COLUMNS: usize = 4 * MAX_BACKSTRESSES + 1;

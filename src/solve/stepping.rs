//! The analysis loop: steps, increments, one SNES solve per increment, output after each
//! converged increment.

use super::problem::Problem;
use super::schedule::StepLoads;
use crate::dist::{DofMap, Partition};
use crate::error::{Error, Result};
use crate::io::{HistoryRow, ResultsFile};
use crate::model::Model;
use crate::petsc::{Matrix, PetscSession, Snes, VecOps, Vector};
use mpi::collective::SystemOperation;
use mpi::datatype::PartitionMut;
use mpi::traits::*;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Clone, Debug)]
pub struct RunOptions {
    pub output: PathBuf,
    /// Print a line per increment (rank 0).
    pub progress: bool,
}

#[derive(Clone, Debug)]
pub struct RunSummary {
    pub history: Vec<HistoryRow>,
    pub wall_time: f64,
    pub ranks: usize,
    /// Final nodal displacements (u_r, u_z) of every node, in model order.
    pub displacement: Vec<[f64; 2]>,
}

/// Runs every step of `model` on the session's ranks, writing `options.output` as it goes.
pub fn run(session: &PetscSession, model: &Model, options: &RunOptions) -> Result<RunSummary> {
    let start = Instant::now();
    let world = session.world();
    let comm = session.comm();
    let root = world.rank() == 0;
    let nodes = model.mesh.coords.len();
    let partition = Partition::new(session, &model.mesh)?;
    let mut results = ResultsFile::create(&options.output, session, model, &partition)?;
    if root && options.progress {
        println!(
            "slideline: {} nodes, {} elements on {} rank(s); results -> {}",
            nodes,
            model.mesh.elements.len(),
            partition.size,
            options.output.display()
        );
    }
    let mut displacement = vec![[0.0; 2]; nodes];
    let mut history = Vec::new();
    let mut previous: Option<StepLoads> = None;
    for (s, step) in model.steps.iter().enumerate() {
        let loads = StepLoads::new(model, s, previous.as_ref(), &displacement);
        let dofs = DofMap::new(&partition, &loads.prescribed_mask(nodes))?;
        let mut x = Vector::mpi(session, comm, dofs.local_len())?;
        let mut residual = x.duplicate()?;
        let (diag, off) = dofs.preallocation(&model.mesh, &partition);
        let mut jacobian = Matrix::aij(session, comm, dofs.local_len(), &diag, &off)?;
        let mut problem = Problem::new(session, model, &partition, &dofs, &x)?;
        let mut snes = Snes::new(session, comm)?;
        for k in 1..=step.increments {
            let lambda = k as f64 / step.increments as f64;
            problem.load = loads.at(model, lambda);
            set_free_values(&mut x, &dofs, &partition, &displacement)?;
            let report = snes.solve(&mut problem, &mut x, &mut residual, &mut jacobian)?;
            if !report.converged() {
                return Err(Error::NotConverged {
                    step: step.name.clone(),
                    load_factor: lambda,
                    reason: format!(
                        "{} after {} Newton iterations; converged increments are kept in {}",
                        report.reason_name(),
                        report.newton_iterations,
                        options.output.display()
                    ),
                });
            }
            let fields = problem.evaluate_fields(&x)?;
            let owned = owned_displacement(&x, &dofs, &partition, &problem.load.prescribed)?;
            gather_displacement(&world, &partition, &owned, &mut displacement);
            let mut force = vec![0.0; 2 * nodes];
            let local: Vec<f64> = fields.nodal_force.iter().flatten().copied().collect();
            world.all_reduce_into(&local[..], &mut force[..], SystemOperation::sum());
            let reactions = loads
                .constrained_sets
                .iter()
                .map(|set| {
                    let f = model.node_sets[set].iter().fold([0.0; 2], |acc, &n| {
                        [acc[0] + force[2 * n], acc[1] + force[2 * n + 1]]
                    });
                    (set.clone(), f)
                })
                .collect();
            let row = HistoryRow {
                step: s + 1,
                increment: k,
                load_factor: lambda,
                time: s as f64 + lambda,
                newton_iterations: report.newton_iterations,
                linear_iterations: report.linear_iterations,
                residual_norm: report.residual_norms.last().copied().unwrap_or(f64::NAN),
                wall_time: start.elapsed().as_secs_f64(),
                reactions,
            };
            results.write_increment(&step.name, &row, &owned, &fields.stress)?;
            if root && options.progress {
                println!(
                    "{}",
                    progress_line(&step.name, s, model.steps.len(), k, step.increments, &row)
                );
            }
            history.push(row);
        }
        previous = Some(loads);
    }
    Ok(RunSummary {
        history,
        wall_time: start.elapsed().as_secs_f64(),
        ranks: partition.size,
        displacement,
    })
}

/// Puts the current displacement of this rank's free DOFs into `x` (the initial guess).
fn set_free_values(
    x: &mut Vector<'_>,
    dofs: &DofMap,
    partition: &Partition,
    displacement: &[[f64; 2]],
) -> Result<()> {
    let first = dofs.first() as i32;
    let mut a = x.write()?;
    for &n in partition.owned_nodes() {
        for c in 0..2 {
            let d = dofs.dof[n][c];
            if d >= 0 {
                a[(d - first) as usize] = displacement[n][c];
            }
        }
    }
    Ok(())
}

/// Displacement of this rank's owned nodes (partition order): solved values and prescribed ones.
fn owned_displacement(
    x: &Vector<'_>,
    dofs: &DofMap,
    partition: &Partition,
    prescribed: &[[f64; 2]],
) -> Result<Vec<[f64; 2]>> {
    let first = dofs.first() as i32;
    let a = x.read()?;
    Ok(partition
        .owned_nodes()
        .iter()
        .map(|&n| {
            std::array::from_fn(|c| {
                if dofs.dof[n][c] >= 0 {
                    a[(dofs.dof[n][c] - first) as usize]
                } else {
                    prescribed[n][c]
                }
            })
        })
        .collect())
}

/// All ranks' owned displacements into the replicated array (model node order).
fn gather_displacement(
    world: &impl Communicator,
    partition: &Partition,
    owned: &[[f64; 2]],
    displacement: &mut [[f64; 2]],
) {
    let counts: Vec<i32> = (0..partition.size)
        .map(|r| 2 * (partition.node_offsets[r + 1] - partition.node_offsets[r]) as i32)
        .collect();
    let displs: Vec<i32> = partition.node_offsets[..partition.size]
        .iter()
        .map(|&o| 2 * o as i32)
        .collect();
    let flat: Vec<f64> = owned.iter().flatten().copied().collect();
    let mut all = vec![0.0; 2 * displacement.len()];
    world.all_gather_varcount_into(
        &flat[..],
        &mut PartitionMut::new(&mut all[..], counts, displs),
    );
    for (k, &n) in partition.node_order.iter().enumerate() {
        displacement[n] = [all[2 * k], all[2 * k + 1]];
    }
}

fn progress_line(
    name: &str,
    s: usize,
    steps: usize,
    k: usize,
    increments: usize,
    row: &HistoryRow,
) -> String {
    let mut line = format!(
        "step {}/{} {:<10} inc {:>4}/{:<4} lambda {:.4}  newton {:>2}  ksp {:>3}  |F| {:.2e}  {:>7.2} s",
        s + 1,
        steps,
        name,
        k,
        increments,
        row.load_factor,
        row.newton_iterations,
        row.linear_iterations,
        row.residual_norm,
        row.wall_time
    );
    for (set, f) in &row.reactions {
        line.push_str(&format!("  {set}: Fr {:.4e} Fz {:.4e} N/rad", f[0], f[1]));
    }
    line
}

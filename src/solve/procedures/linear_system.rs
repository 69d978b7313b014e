//! One linear system over the nodes' amplitudes (a perturbation's three per node, a heat
//! step's temperature): its numbering (unknowns and prescribed values), its assembly from
//! element blocks, one solve, and the solution gathered back to every node on every rank.

use crate::decomposition::Partition;
use crate::error::Result;
use crate::petsc::sys::PetscInt;
use crate::petsc::{MatOps, Matrix, PetscSession, Snes, VecOps, Vector};
use mpi::datatype::PartitionMut;
use mpi::traits::*;

/// An amplitude's place in the system: an unknown (index, coefficient: an axis node's U_t of
/// mode 1 is -1 times its U_r) or a prescribed value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::solve) enum Amplitude {
    Unknown(PetscInt, f64),
    Prescribed(f64),
}

/// An element's or an edge's matrix over its nodes' amplitudes (column-major, 3 per node; a
/// heat step's over their temperatures, 1 per node).
pub(in crate::solve) type Block = (Vec<usize>, Vec<f64>);

/// The unknowns' matrix of `blocks` (K_ff) and the right-hand side's entries -K_fp U_p of the
/// prescribed amplitudes (collective: PETSc sums rows from every rank).
pub(in crate::solve) fn assemble<'s, const D: usize>(
    session: &'s PetscSession,
    blocks: &[Block],
    amplitude: &[[Amplitude; D]],
    local_len: usize,
) -> Result<(Matrix<'s>, Vec<(PetscInt, f64)>)> {
    let mut rows = Vec::new();
    let mut cols = Vec::new();
    let mut values = Vec::new();
    let mut rhs: Vec<(PetscInt, f64)> = Vec::new();
    for (conn, k) in blocks {
        let dofs: Vec<Amplitude> = conn.iter().flat_map(|&n| amplitude[n]).collect();
        let size = dofs.len();
        for (i, &ai) in dofs.iter().enumerate() {
            let Amplitude::Unknown(row, ci) = ai else { continue };
            for (j, &aj) in dofs.iter().enumerate() {
                let kij = k[j * size + i];
                match aj {
                    Amplitude::Unknown(col, cj) => {
                        rows.push(row);
                        cols.push(col);
                        values.push(ci * cj * kij);
                    }
                    Amplitude::Prescribed(v) => rhs.push((row, -ci * kij * v)),
                }
            }
        }
    }
    let mut matrix = Matrix::aij_coo(session, session.comm(), local_len, &rows, &cols)?;
    matrix.set_values_coo(&values)?;
    Ok((matrix, rhs))
}

/// Solves `matrix` u = b once, b from the right-hand side's entries `rhs` (rows summed over the
/// ranks), with the SNES's linear solver and its options (collective): this rank's part of u,
/// or None when the solve failed (a singular matrix).
pub(in crate::solve) fn solve_once(session: &PetscSession, matrix: &Matrix<'_>, rhs: Vec<(PetscInt, f64)>, local_len: usize) -> Result<Option<Vec<f64>>> {
    let mut b = Vector::mpi(session, session.comm(), local_len)?;
    b.set_all(0.0)?;
    let (indices, adds): (Vec<PetscInt>, Vec<f64>) = rhs.into_iter().unzip();
    b.add_values(&indices, &adds)?;
    b.assemble()?;
    let mut u = b.duplicate()?;
    let mut snes = Snes::new(session)?;
    if !snes.linear_solve(matrix, &b, &mut u)? {
        return Ok(None);
    }
    let values = u.read()?.to_vec();
    Ok(Some(values))
}

/// Every node's amplitudes on every rank from this rank's part `solution` of the unknowns
/// (collective).
pub(in crate::solve) fn amplitudes_of<const D: usize>(
    world: &impl Communicator,
    partition: &Partition,
    amplitude: &[[Amplitude; D]],
    offsets: &[usize],
    solution: &[f64],
) -> Vec<[f64; D]> {
    let first = offsets[partition.rank] as PetscInt;
    let value = |a: Amplitude| match a {
        Amplitude::Unknown(i, c) => c * solution[(i - first) as usize],
        Amplitude::Prescribed(v) => v,
    };
    // (an owned node's unknowns are this rank's rows: the numbering goes by owned nodes)
    let owned: Vec<f64> = partition.owned_nodes().iter().flat_map(|&n| amplitude[n].map(value)).collect();
    gather(world, partition, &owned, amplitude.len())
}

/// All ranks' owned values (D per node) into one array in model node order.
fn gather<const D: usize>(world: &impl Communicator, partition: &Partition, owned: &[f64], nodes: usize) -> Vec<[f64; D]> {
    let counts: Vec<i32> = (0..partition.size).map(|r| (D * (partition.node_offsets[r + 1] - partition.node_offsets[r])) as i32).collect();
    let displs: Vec<i32> = partition.node_offsets[..partition.size].iter().map(|&o| (D * o) as i32).collect();
    let mut all = vec![0.0; D * nodes];
    world.all_gather_varcount_into(owned, &mut PartitionMut::new(&mut all[..], counts, displs));
    let mut out = vec![[0.0; D]; nodes];
    for (k, &n) in partition.node_order.iter().enumerate() {
        out[n] = std::array::from_fn(|c| all[D * k + c]);
    }
    out
}

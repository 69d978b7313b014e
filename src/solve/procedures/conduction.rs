//! A steady heat-conduction step (`model::heat`): the conduction matrices of this rank's
//! elements (`element::conduction`) over one unknown temperature per free node, the held
//! temperatures moved to the right-hand side, one linear solve (the SNES's linear solver, as a
//! perturbation step's). Then the heat flux at the Gauss points and the heat flowing in
//! through each held set: the residual K T there.

use crate::decomposition::Partition;
use crate::element::conduction::{conduction_matrix, heat_flux};
use crate::element::solid::NODES;
use crate::error::{Error, Result};
use crate::model::heat::HeatStep;
use crate::petsc::sys::PetscInt;
use crate::records::heat::{HeatAnswer, HeatFlow};
use crate::solve::context::RunContext;
use crate::solve::procedures::linear_system::{amplitudes_of, assemble, solve_once, Amplitude, Block};
use mpi::collective::SystemOperation;
use mpi::traits::*;

/// Solves heat step `step` (collective). A node in no element keeps the initial temperature.
pub(in crate::solve) fn solve(ctx: &RunContext<'_, '_>, step: &HeatStep) -> Result<HeatAnswer> {
    let (session, model, partition) = (ctx.session, ctx.model, ctx.partition);
    let world = session.world();
    let mesh = &model.mesh;
    let nodes = mesh.coords.len();
    let mut held = step.held(model);
    let mut in_element = vec![false; nodes];
    for conn in &mesh.elements {
        conn.iter().for_each(|&n| in_element[n] = true);
    }
    for (n, h) in held.iter_mut().enumerate().filter(|(n, h)| !in_element[*n] && h.is_none()) {
        *h = Some(model.reference_temperature.at(n));
    }
    let (numbering, offsets) = number(partition, &held);
    let local_len = offsets[partition.rank + 1] - offsets[partition.rank];

    let mut blocks: Vec<Block> = Vec::new();
    let mut geometries = Vec::new();
    for &e in partition.local_elements() {
        let conn = mesh.elements[e];
        let x: [[f64; 2]; NODES] = conn.map(|n| mesh.coords[n]);
        let geo = model.element_geometry(e, &x).map_err(|m| Error::input(format!("heat step '{}': element {}: {m}", step.name, mesh.element_ids[e])))?;
        let k = model.materials[model.element_material[e]].conductivity;
        let m = conduction_matrix(&geo, k);
        blocks.push((conn.to_vec(), (0..NODES).flat_map(|j| (0..NODES).map(move |i| m[i][j])).collect()));
        geometries.push((geo, k));
    }

    // K_ff T_f = -K_fp T_p
    let (matrix, rhs) = assemble(session, &blocks, &numbering, local_len)?;
    let t = solve_once(session, &matrix, rhs, local_len)?.ok_or_else(|| Error::NotConverged {
        step: step.name.clone(),
        load_factor: 1.0,
        reason: "the linear solve failed: the conduction matrix is singular (a body that holds no temperature? hold one on each body)".into(),
    })?;
    let temperature: Vec<f64> = amplitudes_of(world, partition, &numbering, &offsets, &t).into_iter().map(|[v]| v).collect();

    // the heat flowing in at each node: K T, summed over the ranks
    let mut inflow = vec![0.0; nodes];
    for (conn, k) in &blocks {
        for (i, &n) in conn.iter().enumerate() {
            inflow[n] += (0..NODES).map(|j| k[j * NODES + i] * temperature[conn[j]]).sum::<f64>();
        }
    }
    let mut total = vec![0.0; nodes];
    world.all_reduce_into(&inflow[..], &mut total[..], SystemOperation::sum());
    let mut flows: Vec<HeatFlow> = Vec::new();
    for h in &step.temperatures {
        if !flows.iter().any(|f| f.set == h.node_set) {
            let flow = model.node_sets.get(&h.node_set).map_or(0.0, |set| set.iter().map(|&n| total[n]).sum());
            flows.push(HeatFlow { set: h.node_set.clone(), flow });
        }
    }
    let flux = partition.local_elements().iter().zip(&geometries).map(|(&e, (geo, k))| heat_flux(geo, *k, &mesh.elements[e].map(|n| temperature[n]))).collect();
    Ok(HeatAnswer { temperature, flux, flows })
}

/// Numbers the free temperatures rank by rank in partition order; returns every node's
/// temperature (an unknown or its held value) and the ranks' offsets.
fn number(partition: &Partition, held: &[Option<f64>]) -> (Vec<[Amplitude; 1]>, Vec<usize>) {
    let mut numbering = vec![[Amplitude::Prescribed(0.0)]; held.len()];
    let mut offsets = vec![0; partition.size + 1];
    let mut next: PetscInt = 0;
    for r in 0..partition.size {
        for &n in &partition.node_order[partition.node_offsets[r]..partition.node_offsets[r + 1]] {
            numbering[n] = [match held[n] {
                Some(v) => Amplitude::Prescribed(v),
                None => {
                    next += 1;
                    Amplitude::Unknown(next - 1, 1.0)
                }
            }];
        }
        offsets[r + 1] = next as usize;
    }
    (numbering, offsets)
}

//! The fields ParaView and meshio read at the nodes, as CalculiX and Abaqus write them for
//! plots: Gauss-point stresses, von Mises stress and equivalent plastic strain carried to the
//! nodes and averaged over the elements around each node ([`crate::fe::extrapolate`]), the
//! displacement as a 3-component vector (u_r, u_z, 0) for Warp By Vector, and the (uniform)
//! temperature. Written per increment under `/increments/NNNNNN/nodal/`, one dataset per
//! scalar so that every reader names it.

use super::results::write_rows;
use crate::dist::Partition;
use crate::element::solid::QUADRATURE_POINTS as QP;
use crate::error::Result;
use crate::fe::axisymmetric::von_mises;
use crate::fe::extrapolate::{accumulate_nodal, gauss_to_nodes};
use crate::model::{Mesh, OutputFields};
use crate::solve::contact::PassOutput;
use mpi::collective::SystemOperation;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::path::Path;

/// The nodal scalars, in dataset order: the four stress components, von Mises, equivalent
/// plastic strain.
pub const NODAL_SCALARS: [&str; 6] = ["stress_rr", "stress_zz", "stress_tt", "stress_rz", "von_mises", "equivalent_plastic_strain"];

/// Whether nodal scalar `name` (one of [`NODAL_SCALARS`]) belongs to the fields kept.
pub fn nodal_scalar_kept(name: &str, fields: OutputFields) -> bool {
    match name {
        "von_mises" => fields.von_mises,
        "equivalent_plastic_strain" => fields.plastic_strain,
        _ => fields.stress,
    }
}

/// What a rank needs to write the nodal fields: its elements' nodes as file rows.
pub struct NodalWriter {
    world: SimpleCommunicator,
    /// Nodes (rows of /mesh/coordinates) of this rank's elements, in its element order.
    connectivity: Vec<[usize; 8]>,
    nodes: usize,
    node_slab: (usize, usize),
    matrix: [[f64; 9]; 8],
    /// File row of each mesh node (contact slave nodes come by mesh index).
    node_position: Vec<usize>,
    fields: OutputFields,
}

impl NodalWriter {
    pub fn new(world: SimpleCommunicator, mesh: &Mesh, partition: &Partition, fields: OutputFields) -> Self {
        let connectivity = partition.local_elements().iter().map(|&e| mesh.elements[e].map(|n| partition.node_position[n])).collect();
        let rank = partition.rank;
        NodalWriter {
            world,
            connectivity,
            nodes: mesh.coords.len(),
            node_slab: (partition.node_offsets[rank], partition.node_offsets[rank + 1]),
            matrix: gauss_to_nodes(),
            node_position: partition.node_position.clone(),
            fields,
        }
    }

    /// Writes the nodal group of one increment (collective) from this rank's owned
    /// displacements and its elements' Gauss-point stress and plastic strain.
    #[allow(clippy::too_many_arguments)]
    pub fn write(
        &self,
        increment: &hdf5::Group,
        displacement: &[[f64; 2]],
        stress: &[[[f64; 4]; QP]],
        plastic_strain: &[[f64; QP]],
        temperature: f64,
        contact: &[PassOutput<'_>],
        path: &Path,
    ) -> Result<()> {
        let g = increment.create_group("nodal").map_err(|e| crate::error::Error::Output { path: path.to_path_buf(), message: e.to_string() })?;
        let u: Vec<f64> = displacement.iter().flat_map(|u| [u[0], u[1], 0.0]).collect();
        write_rows(&g, "displacement", &[self.nodes, 3], self.node_slab, &u, path)?;
        // every rank adds its elements' share to every node; the sums meet in one reduction
        const C: usize = NODAL_SCALARS.len();
        let gauss: Vec<[[f64; C]; QP]> =
            stress.iter().zip(plastic_strain).map(|(s, ep)| std::array::from_fn(|q| [s[q][0], s[q][1], s[q][2], s[q][3], von_mises(&s[q]), ep[q]])).collect();
        let mut local = vec![0.0f64; self.nodes * (C + 1)];
        let (sums, counts) = local.split_at_mut(self.nodes * C);
        accumulate_nodal(&self.matrix, &self.connectivity, &gauss, sums, counts);
        let mut total = vec![0.0f64; local.len()];
        self.world.all_reduce_into(&local[..], &mut total[..], SystemOperation::sum());
        let (sums, counts) = total.split_at(self.nodes * C);
        for (c, name) in NODAL_SCALARS.iter().enumerate().filter(|(_, name)| nodal_scalar_kept(name, self.fields)) {
            let owned: Vec<f64> = (self.node_slab.0..self.node_slab.1).map(|n| sums[n * C + c] / counts[n].max(1.0)).collect();
            write_rows(&g, name, &[self.nodes], self.node_slab, &owned, path)?;
        }
        if self.fields.temperature {
            let t = vec![temperature; self.node_slab.1 - self.node_slab.0];
            write_rows(&g, "temperature", &[self.nodes], self.node_slab, &t, path)?;
        }
        if !contact.is_empty() && self.fields.contact {
            self.write_contact(&g, contact, path)?;
        }
        Ok(())
    }

    /// The contact state at the nodes: pressure (MPa, the largest over the pairs and passes
    /// a node is a slave of, 0 elsewhere), status (1 in contact), gap (mm, the smallest; NaN
    /// off the slave surfaces).
    fn write_contact(&self, g: &hdf5::Group, contact: &[PassOutput<'_>], path: &Path) -> Result<()> {
        let n = self.nodes;
        let mut most = vec![0.0f64; 2 * n];
        let mut least = vec![f64::INFINITY; n];
        for p in contact {
            for (&node, state) in p.nodes.iter().zip(p.states) {
                let row = self.node_position[node];
                most[row] = most[row].max(state.pressure);
                most[n + row] = most[n + row].max(f64::from(u8::from(state.pressure > 0.0)));
                least[row] = least[row].min(state.gap);
            }
        }
        let (mut most_all, mut least_all) = (vec![0.0f64; 2 * n], vec![0.0f64; n]);
        self.world.all_reduce_into(&most[..], &mut most_all[..], SystemOperation::max());
        self.world.all_reduce_into(&least[..], &mut least_all[..], SystemOperation::min());
        let owned = self.node_slab.0..self.node_slab.1;
        let pressure: Vec<f64> = owned.clone().map(|r| most_all[r]).collect();
        let status: Vec<f64> = owned.clone().map(|r| most_all[n + r]).collect();
        let gap: Vec<f64> = owned.map(|r| if least_all[r].is_finite() { least_all[r] } else { f64::NAN }).collect();
        write_rows(g, "contact_pressure", &[n], self.node_slab, &pressure, path)?;
        write_rows(g, "contact_status", &[n], self.node_slab, &status, path)?;
        write_rows(g, "contact_gap", &[n], self.node_slab, &gap, path)
    }
}

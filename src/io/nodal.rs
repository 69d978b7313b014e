//! The fields ParaView and meshio read at the nodes. Tensor components (stress, total and
//! plastic strain) are carried from the Gauss points to each element's nodes by
//! [`crate::fe::recover`] (extrapolated in elastic elements, copied from the nearest Gauss point
//! in yielded ones, the rule of ANSYS's ERESX default) and averaged over the elements around each
//! node; the invariants (von Mises, pressure, principal stresses) are then computed from the
//! averaged components, so von Mises is never negative. The equivalent plastic strain is copied,
//! never extrapolated, so it is never below zero. Also: the displacement and the reaction force
//! as 3-component vectors (r, z, 0) for Warp By Vector and glyphs, the temperature, and the
//! contact state. Written per increment under `/increments/NNNNNN/nodal/`, one dataset per
//! scalar so that every reader names it; on request (`element_nodal`) also each element's own
//! nodal stresses before averaging, `/increments/NNNNNN/element_nodal_stress`.

use super::h5::{write_field, write_rows};
use crate::decomposition::Partition;
use crate::error::Result;
use crate::fe::axisymmetric::{principal_stresses, von_mises};
use crate::fe::quadrature::Integration;
use crate::fe::recover::{Recovery, Rule};
use crate::fe::shape::Shape;
use crate::model::{Model, OutputFields, Precision};
use crate::records::contact::PassOutput;
use crate::records::increment_fields::IncrementFields;
use mpi::collective::SystemOperation;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::path::Path;

/// The quantities averaged at the nodes, per node in this order: stress [rr, zz, tt, rz],
/// total strain (4), plastic strain tensor (4), equivalent plastic strain.
const AVERAGED: usize = 13;

/// The nodal scalars, in dataset order.
pub const NODAL_SCALARS: [&str; 16] = [
    "stress_rr",
    "stress_zz",
    "stress_tt",
    "stress_rz",
    "pressure",
    "principal_stress_max",
    "principal_stress_min",
    "von_mises",
    "strain_rr",
    "strain_zz",
    "strain_tt",
    "strain_rz",
    "plastic_strain_rr",
    "plastic_strain_zz",
    "plastic_strain_tt",
    "plastic_strain_rz",
];

/// The nodal scalars after [`NODAL_SCALARS`]: the equivalent plastic strain and temperature.
pub const NODAL_TAIL: [&str; 2] = ["equivalent_plastic_strain", "temperature"];

/// The backstress at the nodes (kinematic hardening): its components and von Mises
/// equivalent, copied from the nearest Gauss point as the plastic strain is.
pub const BACKSTRESS_SCALARS: [&str; 5] = ["backstress_rr", "backstress_zz", "backstress_tt", "backstress_rz", "backstress_von_mises"];

/// The contact scalars at the nodes, the last two only for pairs with friction.
pub const CONTACT_SCALARS: [&str; 5] = ["contact_pressure", "contact_status", "contact_gap", "friction_shear", "contact_sliding"];

/// Whether nodal scalar `name` (of [`NODAL_SCALARS`] or [`NODAL_TAIL`]) belongs to the fields kept.
pub fn nodal_scalar_kept(name: &str, fields: OutputFields) -> bool {
    match name {
        "von_mises" => fields.von_mises,
        "equivalent_plastic_strain" => fields.plastic_strain,
        "temperature" => fields.temperature,
        n if n.starts_with("strain_") || n.starts_with("plastic_strain_") => fields.strain,
        _ => fields.stress,
    }
}

/// The scalars of one node from its averaged quantities `a` (the order of [`AVERAGED`]), in
/// the order of [`NODAL_SCALARS`].
fn node_scalars(a: &[f64]) -> [f64; 16] {
    let s = [a[0], a[1], a[2], a[3]];
    let principal = principal_stresses(&s);
    let pressure = -(s[0] + s[1] + s[2]) / 3.0;
    [s[0], s[1], s[2], s[3], pressure, principal[0], principal[2], von_mises(&s), a[4], a[5], a[6], a[7], a[8], a[9], a[10], a[11]]
}

/// What a rank needs to write the nodal fields: its elements' nodes as file rows.
pub struct NodalWriter {
    world: SimpleCommunicator,
    /// Nodes (rows of /mesh/coordinates) of this rank's elements, in its element order.
    connectivity: Vec<[usize; 8]>,
    /// How each of this rank's elements is integrated.
    integration: Vec<Integration>,
    nodes: usize,
    node_slab: (usize, usize),
    elements: usize,
    element_slab: (usize, usize),
    recovery: Recovery,
    /// File row of each mesh node (contact slave nodes come by mesh index).
    node_position: Vec<usize>,
    /// The mesh nodes this rank writes, in file order.
    owned: Vec<usize>,
    fields: OutputFields,
    precision: Precision,
}

/// A response step's stress amplitudes at the nodes: [rr, zz, tt, rz] x cos n theta, [rt, zt]
/// x sin n theta.
pub const AMPLITUDE_STRESS: [&str; 6] = ["stress_rr", "stress_zz", "stress_tt", "stress_rz", "stress_rt", "stress_zt"];

impl NodalWriter {
    /// A response step's stress amplitudes (`stress`: this rank's elements' Gauss values)
    /// carried to the nodes and averaged, one dataset per component of [`AMPLITUDE_STRESS`]
    /// under `step`'s `nodal/` (collective). Extrapolated in every element: the perturbation is
    /// linear about its base state, its amplitudes a smooth field.
    pub fn write_amplitudes(&self, step: &hdf5::Group, stress: &[[[f64; 6]; 9]], path: &Path) -> Result<()> {
        let g = step.create_group("nodal").map_err(|e| crate::error::Error::Output { path: path.to_path_buf(), message: e.to_string() })?;
        let mut local = vec![0.0f64; self.nodes * 7];
        let (sums, counts) = local.split_at_mut(self.nodes * 6);
        for ((nodes, &integration), gauss) in self.connectivity.iter().zip(&self.integration).zip(stress) {
            let nodal = self.recovery.element_nodal(Shape::of(nodes), integration, Rule::Extrapolate, gauss);
            Recovery::accumulate(nodes, &nodal, sums, counts);
        }
        let mut total = vec![0.0f64; local.len()];
        self.world.all_reduce_into(&local[..], &mut total[..], SystemOperation::sum());
        let (sums, counts) = total.split_at(self.nodes * 6);
        for (c, name) in AMPLITUDE_STRESS.iter().enumerate() {
            let column: Vec<f64> = (self.node_slab.0..self.node_slab.1).map(|n| sums[n * 6 + c] / counts[n].max(1.0)).collect();
            write_rows(&g, name, &[self.nodes], self.node_slab, &column, path)?;
        }
        Ok(())
    }

    /// The backstress at the nodes, [`BACKSTRESS_SCALARS`] (collective): each element's nearest
    /// Gauss point's, averaged over the elements at a node.
    fn write_backstress(&self, g: &hdf5::Group, back: &[[[f64; 4]; 9]], path: &Path) -> Result<()> {
        const C: usize = BACKSTRESS_SCALARS.len();
        let mut local = vec![0.0f64; self.nodes * (C + 1)];
        let (sums, counts) = local.split_at_mut(self.nodes * C);
        for ((nodes, &integration), gauss) in self.connectivity.iter().zip(&self.integration).zip(back) {
            let values: [[f64; C]; 9] = gauss.map(|a| [a[0], a[1], a[2], a[3], von_mises(&a)]);
            Recovery::accumulate(nodes, &self.recovery.element_nodal(Shape::of(nodes), integration, Rule::Copy, &values), sums, counts);
        }
        let mut total = vec![0.0f64; local.len()];
        self.world.all_reduce_into(&local[..], &mut total[..], SystemOperation::sum());
        let (sums, counts) = total.split_at(self.nodes * C);
        for (c, name) in BACKSTRESS_SCALARS.iter().enumerate() {
            let column: Vec<f64> = (self.node_slab.0..self.node_slab.1).map(|n| sums[n * C + c] / counts[n].max(1.0)).collect();
            write_field(g, name, &[self.nodes], self.node_slab, &column, self.precision, &self.world, path)?;
        }
        Ok(())
    }

    pub fn new(world: SimpleCommunicator, model: &Model, partition: &Partition) -> Self {
        let (mesh, output) = (&model.mesh, model.output);
        let connectivity = partition.local_elements().iter().map(|&e| mesh.elements[e].map(|n| partition.node_position[n])).collect();
        let integration = partition.local_elements().iter().map(|&e| model.element_integration[e]).collect();
        let rank = partition.rank;
        NodalWriter {
            world,
            connectivity,
            integration,
            nodes: mesh.coords.len(),
            node_slab: (partition.node_offsets[rank], partition.node_offsets[rank + 1]),
            elements: mesh.elements.len(),
            element_slab: (partition.element_offsets[rank], partition.element_offsets[rank + 1]),
            recovery: Recovery::default(),
            node_position: partition.node_position.clone(),
            owned: partition.owned_nodes().to_vec(),
            fields: output.fields,
            precision: output.precision,
        }
    }

    /// Writes the nodal group of one increment (collective) from this rank's owned
    /// displacements and reactions and its elements' Gauss-point fields.
    pub fn write(&self, increment: &hdf5::Group, f: &IncrementFields<'_>, path: &Path) -> Result<()> {
        let g = increment.create_group("nodal").map_err(|e| crate::error::Error::Output { path: path.to_path_buf(), message: e.to_string() })?;
        let as_vector = |v: &[[f64; 2]]| -> Vec<f64> { v.iter().flat_map(|u| [u[0], u[1], 0.0]).collect() };
        write_rows(&g, "displacement", &[self.nodes, 3], self.node_slab, &as_vector(f.displacement), path)?;
        write_field(&g, "reaction_force", &[self.nodes, 3], self.node_slab, &as_vector(f.reaction), self.precision, &self.world, path)?;
        // every rank adds its elements' share to every node; the sums meet in one reduction
        let mut local = vec![0.0f64; self.nodes * (AVERAGED + 1)];
        let (sums, counts) = local.split_at_mut(self.nodes * AVERAGED);
        for (k, nodes) in self.connectivity.iter().enumerate() {
            let ep = &f.plastic_strain[k];
            let rule = Rule::for_element(ep);
            let gauss: [[f64; 8]; 9] = std::array::from_fn(|q| {
                let (s, e) = (f.stress[k][q], f.strain[k][q]);
                [s[0], s[1], s[2], s[3], e[0], e[1], e[2], e[3]]
            });
            let plastic: [[f64; 5]; 9] = std::array::from_fn(|q| {
                let p = f.plastic_strain_tensor[k][q];
                [p[0], p[1], p[2], p[3], ep[q]]
            });
            let (shape, integration) = (Shape::of(nodes), self.integration[k]);
            let elastic_part = self.recovery.element_nodal(shape, integration, rule, &gauss);
            let plastic_part = self.recovery.element_nodal(shape, integration, Rule::Copy, &plastic);
            let nodal: [[f64; AVERAGED]; 8] = std::array::from_fn(|a| std::array::from_fn(|c| if c < 8 { elastic_part[a][c] } else { plastic_part[a][c - 8] }));
            Recovery::accumulate(nodes, &nodal, sums, counts);
        }
        let mut total = vec![0.0f64; local.len()];
        self.world.all_reduce_into(&local[..], &mut total[..], SystemOperation::sum());
        let (sums, counts) = total.split_at(self.nodes * AVERAGED);
        let owned = self.node_slab.0..self.node_slab.1;
        let means: Vec<[f64; AVERAGED]> = owned.clone().map(|n| std::array::from_fn(|c| sums[n * AVERAGED + c] / counts[n].max(1.0))).collect();
        let scalars: Vec<[f64; 16]> = means.iter().map(|m| node_scalars(m)).collect();
        for (c, name) in NODAL_SCALARS.iter().enumerate().filter(|(_, name)| nodal_scalar_kept(name, self.fields)) {
            let column: Vec<f64> = scalars.iter().map(|s| s[c]).collect();
            write_field(&g, name, &[self.nodes], self.node_slab, &column, self.precision, &self.world, path)?;
        }
        if self.fields.plastic_strain {
            let ep: Vec<f64> = means.iter().map(|m| m[AVERAGED - 1]).collect();
            write_field(&g, "equivalent_plastic_strain", &[self.nodes], self.node_slab, &ep, self.precision, &self.world, path)?;
        }
        if let (true, Some(back)) = (self.fields.plastic_strain, f.backstress) {
            self.write_backstress(&g, back, path)?;
        }
        if self.fields.temperature {
            let t: Vec<f64> = self.owned.iter().map(|&n| f.temperature.at(n)).collect();
            write_field(&g, "temperature", &[self.nodes], self.node_slab, &t, self.precision, &self.world, path)?;
        }
        if !f.contact.is_empty() && self.fields.contact {
            self.write_contact(&g, f.contact, path)?;
        }
        if self.fields.element_nodal {
            let stress: Vec<f64> = (self.connectivity.iter().zip(&self.integration).zip(f.stress).zip(f.plastic_strain))
                .flat_map(|(((nodes, &integration), s), ep)| self.recovery.element_nodal(Shape::of(nodes), integration, Rule::for_element(ep), s))
                .flatten()
                .collect();
            write_field(increment, "element_nodal_stress", &[self.elements, 8, 4], self.element_slab, &stress, self.precision, &self.world, path)?;
        }
        Ok(())
    }

    /// The contact state at the nodes: pressure (MPa, the largest over the pairs and passes
    /// a node is a slave of, 0 elsewhere), status (1 in contact), gap (mm, the smallest; NaN
    /// off the slave surfaces); with friction, the frictional shear (MPa, the largest in
    /// magnitude, signed) and sliding (1 slipping, 0 sticking or open).
    fn write_contact(&self, g: &hdf5::Group, contact: &[PassOutput<'_>], path: &Path) -> Result<()> {
        let n = self.nodes;
        // [pressure, status, |shear|, sliding] by max; [gap] by min; shear's sign by sum
        let mut most = vec![0.0f64; 4 * n];
        let mut least = vec![f64::INFINITY; n];
        let mut shear = vec![0.0f64; n];
        for p in contact {
            for (&node, state) in p.nodes.iter().zip(p.states) {
                let row = self.node_position[node];
                most[row] = most[row].max(state.pressure);
                most[n + row] = most[n + row].max(f64::from(u8::from(state.pressure > 0.0)));
                least[row] = least[row].min(state.gap);
                if p.friction && state.shear.abs() > most[2 * n + row] {
                    most[2 * n + row] = state.shear.abs();
                    shear[row] = state.shear;
                    most[3 * n + row] = most[3 * n + row].max(f64::from(u8::from(state.sliding)));
                }
            }
        }
        let friction = u8::from(contact.iter().any(|p| p.friction));
        let mut any_friction = 0u8;
        self.world.all_reduce_into(&friction, &mut any_friction, SystemOperation::max());
        let (mut most_all, mut least_all) = (vec![0.0f64; 4 * n], vec![0.0f64; n]);
        self.world.all_reduce_into(&most[..], &mut most_all[..], SystemOperation::max());
        self.world.all_reduce_into(&least[..], &mut least_all[..], SystemOperation::min());
        let owned = self.node_slab.0..self.node_slab.1;
        let column = |k: usize| -> Vec<f64> { owned.clone().map(|r| most_all[k * n + r]).collect() };
        let gap: Vec<f64> = owned.clone().map(|r| if least_all[r].is_finite() { least_all[r] } else { f64::NAN }).collect();
        write_field(g, "contact_pressure", &[n], self.node_slab, &column(0), self.precision, &self.world, path)?;
        write_field(g, "contact_status", &[n], self.node_slab, &column(1), self.precision, &self.world, path)?;
        write_field(g, "contact_gap", &[n], self.node_slab, &gap, self.precision, &self.world, path)?;
        if any_friction == 1 {
            // a node is a slave on one rank only: the signed shear of the rank that has it
            let mut shear_all = vec![0.0f64; n];
            self.world.all_reduce_into(&shear[..], &mut shear_all[..], SystemOperation::sum());
            let signed: Vec<f64> = owned.clone().map(|r| shear_all[r]).collect();
            write_field(g, "friction_shear", &[n], self.node_slab, &signed, self.precision, &self.world, path)?;
            write_field(g, "contact_sliding", &[n], self.node_slab, &column(3), self.precision, &self.world, path)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nodal_scalars_are_the_components_and_their_invariants() {
        // uniaxial 300 along r with hoop -60: principal max 300, min -60, pressure -80
        let s = node_scalars(&[300.0, 0.0, -60.0, 0.0, 1e-3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!((s[5] - 300.0).abs() < 1e-12 && (s[6] + 60.0).abs() < 1e-12 && (s[4] + 80.0).abs() < 1e-12);
        assert!((s[7] - von_mises(&[300.0, 0.0, -60.0, 0.0])).abs() < 1e-12 && s[8] == 1e-3);
    }
}

//! Element partitioning and node ownership.

use crate::error::{Error, Result};
use crate::model::Mesh;
use crate::petsc::{partition_graph, PetscSession};
use mpi::datatype::PartitionMut;
use mpi::traits::*;
use std::collections::HashMap;

#[derive(Clone, Debug)]
pub struct Partition {
    pub rank: usize,
    pub size: usize,
    /// Rank that assembles each element.
    pub element_rank: Vec<usize>,
    /// Rank that owns each node (and its DOFs).
    pub node_owner: Vec<usize>,
    /// Nodes in partition order; `node_position` is its inverse.
    pub node_order: Vec<usize>,
    pub node_position: Vec<usize>,
    /// Elements in partition order; `element_position` is its inverse.
    pub element_order: Vec<usize>,
    pub element_position: Vec<usize>,
    /// `node_offsets[r]..node_offsets[r + 1]` are rank r's nodes in partition order.
    pub node_offsets: Vec<usize>,
    pub element_offsets: Vec<usize>,
}

/// What the partitioner weighs besides the elements' shared sides: how much work each element
/// brings (its own and the contact it carries) and the element pairs that contact couples
/// across a gap. Without them the plies of a bellows, separate bodies, are cut at unrelated
/// places (or land whole on different ranks), so most contact couplings cross ranks and the
/// rank holding more contact waits for nothing else.
#[derive(Clone, Debug, Default)]
pub struct Affinity {
    /// Relative work per element; empty: all alike.
    pub work: Vec<u32>,
    /// Element pairs to keep together, as if they shared a side.
    pub links: Vec<[usize; 2]>,
}

impl Partition {
    /// Partitions `mesh` over the ranks of the session's world (collective), balancing
    /// `affinity.work` and cutting as few shared sides and links as it can.
    pub fn new(session: &PetscSession, mesh: &Mesh, affinity: &Affinity) -> Result<Self> {
        let world = session.world();
        let (rank, size) = (world.rank() as usize, world.size() as usize);
        let ne = mesh.elements.len();
        if ne < size {
            return Err(Error::input(format!("the mesh has {ne} elements, fewer than the {size} MPI ranks")));
        }
        // Each rank hands PETSc an even block of rows of the dual graph.
        let first = rank * ne / size;
        let last = (rank + 1) * ne / size;
        let mut neighbours = dual_graph(mesh);
        for &[a, b] in &affinity.links {
            if a != b {
                neighbours[a].push(b);
                neighbours[b].push(a);
            }
        }
        for v in &mut neighbours {
            v.sort_unstable();
            v.dedup();
        }
        let mut offsets = vec![0];
        let mut adjacency = Vec::new();
        for nb in &neighbours[first..last] {
            adjacency.extend(nb);
            offsets.push(adjacency.len());
        }
        let weights = (!affinity.work.is_empty()).then(|| &affinity.work[first..last]);
        let local_parts = partition_graph(session, session.comm(), ne, &offsets, &adjacency, weights, size)?;
        let local_parts: Vec<u64> = local_parts.into_iter().map(|p| p as u64).collect();
        let counts: Vec<i32> = (0..size).map(|r| ((r + 1) * ne / size - r * ne / size) as i32).collect();
        let displs: Vec<i32> = (0..size).map(|r| (r * ne / size) as i32).collect();
        let mut all = vec![0u64; ne];
        world.all_gather_varcount_into(&local_parts[..], &mut PartitionMut::new(&mut all[..], counts, displs));
        let element_rank: Vec<usize> = all.into_iter().map(|p| p as usize).collect();
        Ok(Self::from_element_ranks(mesh, element_rank, rank, size))
    }

    /// Builds ownership and orders from a given element-to-rank map.
    pub fn from_element_ranks(mesh: &Mesh, element_rank: Vec<usize>, rank: usize, size: usize) -> Self {
        let mut node_owner = vec![usize::MAX; mesh.coords.len()];
        for (e, conn) in mesh.elements.iter().enumerate() {
            for &n in conn {
                node_owner[n] = node_owner[n].min(element_rank[e]);
            }
        }
        // a node of no element (a pre-tension section's reference node) goes to rank 0
        for owner in node_owner.iter_mut().filter(|o| **o == usize::MAX) {
            *owner = 0;
        }
        let (node_order, node_offsets) = order_by_rank(&node_owner, size);
        let (element_order, element_offsets) = order_by_rank(&element_rank, size);
        Partition {
            rank,
            size,
            node_position: inverse(&node_order),
            element_position: inverse(&element_order),
            element_rank,
            node_owner,
            node_order,
            element_order,
            node_offsets,
            element_offsets,
        }
    }

    /// Elements this rank assembles, in partition order.
    pub fn local_elements(&self) -> &[usize] {
        &self.element_order[self.element_offsets[self.rank]..self.element_offsets[self.rank + 1]]
    }

    /// Nodes this rank owns, in partition order.
    pub fn owned_nodes(&self) -> &[usize] {
        &self.node_order[self.node_offsets[self.rank]..self.node_offsets[self.rank + 1]]
    }
}

/// Items sorted by (rank, index), and the offsets of each rank's block.
fn order_by_rank(rank_of: &[usize], size: usize) -> (Vec<usize>, Vec<usize>) {
    let mut order: Vec<usize> = (0..rank_of.len()).collect();
    order.sort_by_key(|&i| (rank_of[i], i));
    let mut offsets = vec![0; size + 1];
    for &r in rank_of {
        offsets[r + 1] += 1;
    }
    for r in 0..size {
        offsets[r + 1] += offsets[r];
    }
    (order, offsets)
}

fn inverse(order: &[usize]) -> Vec<usize> {
    let mut inv = vec![0; order.len()];
    for (k, &i) in order.iter().enumerate() {
        inv[i] = k;
    }
    inv
}

/// Element dual graph: elements are neighbours when they share a side.
pub fn dual_graph(mesh: &Mesh) -> Vec<Vec<usize>> {
    let mut by_side: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for e in 0..mesh.elements.len() {
        for edge in mesh.sides(e) {
            let [a, b, _] = mesh.edge_nodes(edge);
            by_side.entry((a.min(b), a.max(b))).or_default().push(e);
        }
    }
    let mut out = vec![Vec::new(); mesh.elements.len()];
    for elems in by_side.values() {
        for &a in elems {
            for &b in elems {
                if a != b {
                    out[a].push(b);
                }
            }
        }
    }
    for v in &mut out {
        v.sort_unstable();
        v.dedup();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::mesh::rectangle;

    #[test]
    fn dual_graph_of_a_strip_is_a_path() {
        let (mesh, _) = rectangle([1.0, 5.0], [0.0, 1.0], [4, 1]).unwrap();
        let g = dual_graph(&mesh);
        assert_eq!(g, vec![vec![1], vec![0, 2], vec![1, 3], vec![2]]);
    }

    #[test]
    fn ownership_goes_to_the_lowest_rank_and_orders_are_contiguous() {
        let (mesh, _) = rectangle([1.0, 5.0], [0.0, 1.0], [4, 1]).unwrap();
        let p = Partition::from_element_ranks(&mesh, vec![1, 1, 0, 0], 0, 2);
        assert_eq!(p.local_elements(), &[2, 3]);
        // the shared side between elements 1 and 2 belongs to rank 0
        let shared = mesh.elements[1][1];
        assert_eq!(p.node_owner[shared], 0);
        assert!(p.owned_nodes().iter().all(|&n| p.node_owner[n] == 0));
        assert_eq!(p.node_offsets[2], mesh.coords.len());
    }
}

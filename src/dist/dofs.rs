//! Numbering of the unknowns: free DOFs only. Prescribed DOFs are eliminated (their values
//! enter the element kernels directly), so the Jacobian holds no penalty or identity rows and
//! keeps the conditioning of the free problem.

use super::Partition;
use crate::error::Result;
use crate::model::Mesh;
use crate::petsc::sys::PetscInt;

#[derive(Clone, Debug)]
pub struct DofMap {
    /// Global unknown number of (node, component), or -1 where the DOF is prescribed.
    pub dof: Vec<[PetscInt; 2]>,
    /// `offsets[r]..offsets[r + 1]` are rank r's unknowns.
    pub offsets: Vec<usize>,
    pub rank: usize,
}

impl DofMap {
    /// Numbers the DOFs not marked in `prescribed`, rank by rank in partition order.
    pub fn new(partition: &Partition, prescribed: &[[bool; 2]]) -> Result<Self> {
        let mut dof = vec![[-1; 2]; prescribed.len()];
        let mut offsets = vec![0; partition.size + 1];
        let mut next: usize = 0;
        for r in 0..partition.size {
            for &n in &partition.node_order[partition.node_offsets[r]..partition.node_offsets[r + 1]] {
                for c in 0..2 {
                    if !prescribed[n][c] {
                        dof[n][c] = crate::petsc::sys::PetscInt::try_from(next).map_err(|_| crate::Error::input("too many unknowns for 32-bit PetscInt"))?;
                        next += 1;
                    }
                }
            }
            offsets[r + 1] = next;
        }
        Ok(DofMap { dof, offsets, rank: partition.rank })
    }

    pub fn local_len(&self) -> usize {
        self.offsets[self.rank + 1] - self.offsets[self.rank]
    }

    pub fn total(&self) -> usize {
        *self.offsets.last().expect("offsets has size + 1 entries")
    }

    pub fn first(&self) -> usize {
        self.offsets[self.rank]
    }

    /// Exact nonzero counts of this rank's rows, split into the diagonal block (columns this
    /// rank owns) and the off-diagonal block, from the mesh graph and the node couplings
    /// `extra` (contact; each pair (a, b) couples both ways).
    pub fn preallocation(&self, mesh: &Mesh, partition: &Partition, extra: impl IntoIterator<Item = (usize, usize)>) -> (Vec<PetscInt>, Vec<PetscInt>) {
        let mut node_neighbours: Vec<Vec<usize>> = vec![Vec::new(); mesh.coords.len()];
        for conn in &mesh.elements {
            for &n in conn {
                node_neighbours[n].extend(conn);
            }
        }
        for (a, b) in extra {
            node_neighbours[a].push(b);
            node_neighbours[b].push(a);
        }
        let (lo, hi) = (self.offsets[self.rank] as PetscInt, self.offsets[self.rank + 1] as PetscInt);
        let mut diag = vec![0; self.local_len()];
        let mut off = vec![0; self.local_len()];
        for &n in partition.owned_nodes() {
            let neighbours = &mut node_neighbours[n];
            neighbours.sort_unstable();
            neighbours.dedup();
            let (mut d, mut o) = (0, 0);
            for &m in neighbours.iter() {
                for &col in &self.dof[m] {
                    if col >= 0 {
                        if (lo..hi).contains(&col) {
                            d += 1;
                        } else {
                            o += 1;
                        }
                    }
                }
            }
            for &row in &self.dof[n] {
                if row >= 0 {
                    diag[(row - lo) as usize] = d;
                    off[(row - lo) as usize] = o;
                }
            }
        }
        (diag, off)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::mesh::rectangle;

    #[test]
    fn prescribed_dofs_are_skipped_and_counts_cover_the_stencil() {
        let (mesh, sets) = rectangle([1.0, 3.0], [0.0, 1.0], [2, 1]).unwrap();
        let p = Partition::from_element_ranks(&mesh, vec![0, 0], 0, 1);
        let mut prescribed = vec![[false; 2]; mesh.coords.len()];
        for &n in &sets.node_sets["bottom"] {
            prescribed[n][1] = true;
        }
        let map = DofMap::new(&p, &prescribed).unwrap();
        assert_eq!(map.total(), 2 * mesh.coords.len() - sets.node_sets["bottom"].len());
        let (d, o) = map.preallocation(&mesh, &p, []);
        assert!(o.iter().all(|&v| v == 0));
        // a corner of the first element only sees that element's 8 nodes
        let corner = mesh.elements[0][3];
        assert_eq!(d[map.dof[corner][0] as usize], 16 - 3); // three bottom nodes have uz fixed
    }
}

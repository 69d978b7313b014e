//! Numbering of the unknowns: free DOFs only. Prescribed DOFs are eliminated (their values
//! enter the element kernels directly), so the Jacobian holds no penalty or identity rows and
//! keeps the conditioning of the free problem.

use super::Partition;
use crate::error::Result;
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::mesh::rectangle;

    #[test]
    fn prescribed_dofs_are_skipped() {
        let (mesh, sets) = rectangle([1.0, 3.0], [0.0, 1.0], [2, 1]).unwrap();
        let p = Partition::from_element_ranks(&mesh, vec![0, 0], 0, 1);
        let mut prescribed = vec![[false; 2]; mesh.coords.len()];
        for &n in &sets.node_sets["bottom"] {
            prescribed[n][1] = true;
        }
        let map = DofMap::new(&p, &prescribed).unwrap();
        assert_eq!(map.total(), 2 * mesh.coords.len() - sets.node_sets["bottom"].len());
        for &n in &sets.node_sets["bottom"] {
            assert!(map.dof[n][0] >= 0 && map.dof[n][1] == -1, "u_z of a bottom node is prescribed, u_r free");
        }
    }
}

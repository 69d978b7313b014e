//! Where each Jacobian entry goes: PETSc's coordinate (COO) assembly.
//!
//! Every entry a Jacobian can receive has a fixed place in one value array: first each local
//! element's 16 x 16 block (row-major over its DOFs, -1 where prescribed, which PETSc ignores),
//! then a 2 x 2 block for each ordered node pair this rank's contact engagements couple. PETSc
//! takes the index lists once per pattern (MatSetPreallocationCOO: it sums repeated entries,
//! routes the rows of other ranks to their owners and fixes the nonzero structure), and each
//! Jacobian writes its values by position and hands over the whole array (MatSetValuesCOO).
//! A MatSetValues call per block instead searches each row for every column and stashes the
//! off-rank entries one by one: on the default bellows that was a fifth of the Jacobian.

use crate::element::solid::DOFS;
use crate::petsc::sys::PetscInt;
use std::collections::HashMap;

/// Entries of an element block.
const ELEMENT_BLOCK: usize = DOFS * DOFS;

/// Position of a block that has no place in the layout (a contact pair found after the last
/// fit that couples no two free DOFs, so PETSc would ignore its values anyway).
const NOWHERE: usize = usize::MAX;

pub struct JacobianLayout {
    /// Global row and column of every entry, in value order.
    rows: Vec<PetscInt>,
    cols: Vec<PetscInt>,
    /// Offset of the blocks of each coupled node pair (a <= b): the 2 x 2 block (a, b), then,
    /// when a != b, the block (b, a).
    pairs: HashMap<(usize, usize), usize>,
    /// Per slave node: the nodes of its last engagement and the offset of each of that
    /// engagement's (row node, column node) blocks, so an engagement over the same nodes as at
    /// the last Jacobian (nearly all of them) finds its places without a lookup per pair.
    engagements: HashMap<usize, (Vec<usize>, Vec<usize>)>,
    values: Vec<f64>,
}

impl JacobianLayout {
    /// The layout of the local elements with global DOFs `element_dofs` and the contact node
    /// pairs `pairs` (a <= b), with `dof` the global DOFs of every node.
    pub fn new(element_dofs: &[[PetscInt; DOFS]], pairs: impl IntoIterator<Item = (usize, usize)>, dof: &[[PetscInt; 2]]) -> Self {
        let mut rows = Vec::with_capacity(element_dofs.len() * ELEMENT_BLOCK);
        let mut cols = Vec::with_capacity(rows.capacity());
        for dofs in element_dofs {
            for &r in dofs {
                rows.extend([r; DOFS]);
                cols.extend(dofs);
            }
        }
        let mut offsets = HashMap::new();
        for (a, b) in pairs {
            debug_assert!(a <= b, "pairs are ordered");
            offsets.insert((a, b), rows.len());
            let blocks: &[(usize, usize)] = if a == b { &[(a, a)] } else { &[(a, b), (b, a)] };
            for &(r, c) in blocks {
                for &row in &dof[r] {
                    rows.extend([row; 2]);
                    cols.extend(dof[c]);
                }
            }
        }
        let values = vec![0.0; rows.len()];
        JacobianLayout { rows, cols, pairs: offsets, engagements: HashMap::new(), values }
    }

    /// Global (row, column) of every entry, in value order, for MatSetPreallocationCOO.
    pub fn indices(&self) -> (&[PetscInt], &[PetscInt]) {
        (&self.rows, &self.cols)
    }

    /// Zeros every value, before a Jacobian's blocks are written.
    pub fn clear(&mut self) {
        self.values.fill(0.0);
    }

    /// The values of local element `k`'s block, row-major over its DOFs.
    pub fn element_block(&mut self, k: usize) -> &mut [f64] {
        &mut self.values[k * ELEMENT_BLOCK..(k + 1) * ELEMENT_BLOCK]
    }

    /// Adds a contact engagement's tangent (row-major over the DOFs of `nodes`, two per node)
    /// at the places of its node pairs.
    pub fn add_engagement(&mut self, nodes: &[usize], tangent: &[f64]) {
        let n = nodes.len();
        debug_assert_eq!(tangent.len(), 4 * n * n, "two DOFs per node");
        let slave = nodes[0];
        let fresh = self.engagements.get(&slave).is_none_or(|(known, _)| known != nodes);
        if fresh {
            let places = nodes.iter().flat_map(|&a| nodes.iter().map(move |&b| (a, b))).map(|(a, b)| self.place(a, b)).collect();
            self.engagements.insert(slave, (nodes.to_vec(), places));
        }
        let places = &self.engagements[&slave].1;
        for i in 0..n {
            for j in 0..n {
                let at = places[i * n + j];
                if at == NOWHERE {
                    continue;
                }
                for ci in 0..2 {
                    for cj in 0..2 {
                        self.values[at + 2 * ci + cj] += tangent[(2 * i + ci) * 2 * n + 2 * j + cj];
                    }
                }
            }
        }
    }

    /// Offset of the 2 x 2 block (row node a, column node b).
    fn place(&self, a: usize, b: usize) -> usize {
        match self.pairs.get(&(a.min(b), a.max(b))) {
            Some(&at) if a <= b => at,
            Some(&at) => at + 4,
            None => NOWHERE,
        }
    }

    /// Every value, in the order of [`JacobianLayout::indices`].
    pub fn values(&self) -> &[f64] {
        &self.values
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_blocks_then_pair_blocks_in_both_orders() {
        let element: [PetscInt; DOFS] = std::array::from_fn(|i| i as PetscInt);
        let dof = vec![[100, 101], [102, -1], [104, 105]];
        let mut layout = JacobianLayout::new(&[element], [(0, 2), (1, 1)], &dof);
        let (rows, cols) = layout.indices();
        let e = ELEMENT_BLOCK;
        assert_eq!(rows.len(), e + 8 + 4);
        assert_eq!((rows[17], cols[17]), (1, 1));
        // (0, 2) then (2, 0), row-major; then (1, 1) with its prescribed DOF
        assert_eq!(&rows[e..e + 8], &[100, 100, 101, 101, 104, 104, 105, 105]);
        assert_eq!(&cols[e..e + 8], &[104, 105, 104, 105, 100, 101, 100, 101]);
        assert_eq!(&rows[e + 8..], &[102, 102, -1, -1]);
        // an engagement over nodes 2 (slave) and 0: the (2, 2) pair has no place and is skipped
        let tangent: Vec<f64> = (0..16).map(|v| v as f64).collect();
        layout.add_engagement(&[2, 0], &tangent);
        layout.add_engagement(&[2, 0], &tangent);
        let v = &layout.values()[e..e + 8];
        // block (0, 2) is the engagement's (row node 0, column node 2): rows 2, 3, columns 0, 1
        assert_eq!(v, &[16.0, 18.0, 24.0, 26.0, 4.0, 6.0, 12.0, 14.0]);
        layout.clear();
        assert!(layout.values().iter().all(|&v| v == 0.0));
    }
}

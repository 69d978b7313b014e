//! Where PETSc stores a Jacobian's values: once a matrix has been assembled with the layout's
//! structure, each value of this rank's rows has a fixed place in the value array of the
//! diagonal or the off-diagonal block, so a Jacobian is handed over as runs of copies
//! (`JacobianLayout::hand_over`) instead of through MatSetValuesCOO.

use crate::petsc::sys::PetscInt;
use crate::petsc::OwnedStructure;

/// How the values reach the storage of a matrix PETSc has assembled with the layout's
/// structure: runs of consecutive values copied straight into the value arrays of this rank's
/// rows, the places no value of this rank's covers zeroed (other ranks add there), and the
/// entries of other ranks' rows added through MatSetValues. MatSetValuesCOO instead sums every
/// value through two index arrays of PETSc's (about 1.2 ms per Jacobian on the default bellows,
/// 1 rank, against a third of that for the copies).
pub(in crate::solve) struct Storage {
    pub matrix: usize,
    /// (first value, first place, length) in the diagonal and the off-diagonal block.
    pub diagonal: Vec<(usize, usize, usize)>,
    pub off_diagonal: Vec<(usize, usize, usize)>,
    /// Places in each block that no value of this rank's fills.
    pub diagonal_gaps: Vec<usize>,
    pub off_diagonal_gaps: Vec<usize>,
    /// Rows of other ranks: the row, its columns and the first of its (consecutive) values.
    pub remote: Vec<(PetscInt, Vec<PetscInt>, usize)>,
}

impl Storage {
    /// The runs for values in the order (`rows`, `cols`) (sorted, distinct) into the storage
    /// `s` of matrix `matrix`; None where PETSc stores an entry of this rank's rows that the
    /// lists lack in its order (then the values go through MatSetValuesCOO).
    pub fn bind(rows: &[PetscInt], cols: &[PetscInt], s: &OwnedStructure, matrix: usize) -> Option<Storage> {
        let mut storage =
            Storage { matrix, diagonal: Vec::new(), off_diagonal: Vec::new(), diagonal_gaps: Vec::new(), off_diagonal_gaps: Vec::new(), remote: Vec::new() };
        let push = |runs: &mut Vec<(usize, usize, usize)>, value: usize, place: usize| match runs.last_mut() {
            Some((v, p, n)) if *v + *n == value && *p + *n == place => *n += 1,
            _ => runs.push((value, place, 1)),
        };
        let owned = |r: PetscInt| r >= s.first && r < s.end;
        let mut start = 0;
        let mut covered = vec![false; s.end.saturating_sub(s.first) as usize];
        while start < rows.len() {
            let row = rows[start];
            let end = start + rows[start..].iter().take_while(|&&r| r == row).count();
            if !owned(row) {
                storage.remote.push((row, cols[start..end].to_vec(), start));
                start = end;
                continue;
            }
            let local = (row - s.first) as usize;
            covered[local] = true;
            // walk the row's values and PETSc's places of each block together (both ascending)
            let (mut d, mut o) = (s.diagonal_ptr[local], s.off_diagonal_ptr[local]);
            for v in start..end {
                let c = cols[v];
                let (runs, gaps, place, stored, until) = if owned(c) {
                    (&mut storage.diagonal, &mut storage.diagonal_gaps, &mut d, &s.diagonal_cols, s.diagonal_ptr[local + 1])
                } else {
                    (&mut storage.off_diagonal, &mut storage.off_diagonal_gaps, &mut o, &s.off_diagonal_cols, s.off_diagonal_ptr[local + 1])
                };
                while *place < until && stored[*place] < c {
                    gaps.push(*place);
                    *place += 1;
                }
                if *place == until || stored[*place] != c {
                    return None;
                }
                push(runs, v, *place);
                *place += 1;
            }
            storage.diagonal_gaps.extend(d..s.diagonal_ptr[local + 1]);
            storage.off_diagonal_gaps.extend(o..s.off_diagonal_ptr[local + 1]);
            start = end;
        }
        // rows this rank stores but lists nothing for: all gaps
        for (local, _) in covered.iter().enumerate().filter(|(_, c)| !**c) {
            storage.diagonal_gaps.extend(s.diagonal_ptr[local]..s.diagonal_ptr[local + 1]);
            storage.off_diagonal_gaps.extend(s.off_diagonal_ptr[local]..s.off_diagonal_ptr[local + 1]);
        }
        Some(storage)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn storage_runs_gaps_and_other_ranks_rows() {
        // this rank stores rows 2..5; values in (row, column) order, one per entry
        let entries = [(0, 1), (2, 0), (2, 2), (2, 3), (2, 6), (3, 3), (4, 2), (4, 4), (7, 7)];
        let (rows, cols): (Vec<PetscInt>, Vec<PetscInt>) = entries.iter().copied().unzip();
        // PETSc's storage: row 4 also holds (4, 5), another rank's entry
        let structure = OwnedStructure {
            first: 2,
            end: 5,
            diagonal_ptr: vec![0, 2, 3, 5],
            diagonal_cols: vec![2, 3, 3, 2, 4],
            off_diagonal_ptr: vec![0, 2, 2, 3],
            off_diagonal_cols: vec![0, 6, 5],
        };
        let s = Storage::bind(&rows, &cols, &structure, 7).expect("bound");
        assert_eq!(s.diagonal, vec![(2, 0, 2), (5, 2, 3)], "consecutive values into consecutive places, one run");
        assert_eq!(s.off_diagonal, vec![(1, 0, 1), (4, 1, 1)], "values 2, 3 lie between: two runs");
        assert_eq!((s.diagonal_gaps.as_slice(), s.off_diagonal_gaps.as_slice()), (&[][..], &[2][..]), "(4, 5) is zeroed for the other rank to add to");
        assert_eq!(s.remote, vec![(0, vec![1], 0), (7, vec![7], 8)]);
        // an entry PETSc does not store, or one stored elsewhere than in order: no binding
        let mut cols_missing = cols.clone();
        cols_missing[3] = 4;
        assert!(Storage::bind(&rows, &cols_missing, &structure, 7).is_none());
        let shuffled = OwnedStructure { diagonal_cols: vec![3, 2, 3, 2, 4], ..structure.clone() };
        assert!(Storage::bind(&rows, &cols, &shuffled, 7).is_none());
    }
}

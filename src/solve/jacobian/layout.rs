//! Where each Jacobian entry goes: PETSc's coordinate (COO) assembly.
//!
//! The entries this rank contributes are listed once each, sorted by (row, column): those of
//! the local elements' 16 x 16 blocks and of a 2 x 2 block for each ordered node pair this
//! rank's contact engagements couple, prescribed DOFs left out. Each has a fixed place in one
//! value array. PETSc takes the lists once per pattern (MatSetPreallocationCOO: it routes the
//! rows of other ranks to their owners and fixes the nonzero structure), and each Jacobian adds
//! its element and contact blocks into their places and hands over the whole array
//! (MatSetValuesCOO). A MatSetValues call per block instead searches each row for every column
//! and stashes the off-rank entries one by one (a fifth of the Jacobian on the default
//! bellows). Sorted and without repeats, the lists cost PETSc less than half as much to take
//! in as the blocks one after another (12 against 28 ms on the default bellows, 1 rank), and
//! that recurs at every refit: so the element entries are sorted once per step and a refit
//! only merges the contact pairs in. From a matrix's second assembly on, the values skip
//! MatSetValuesCOO: the layout knows by then where PETSc stores each of its rank's rows and
//! copies its values there in runs ([`JacobianLayout::hand_over`]).

use crate::element::solid::DOFS;
use crate::error::Result;
use crate::petsc::sys::PetscInt;
use crate::petsc::MatOps;
use crate::solve::jacobian::storage::Storage;
use std::collections::HashMap;

/// Entries of an element block.
const ELEMENT_BLOCK: usize = DOFS * DOFS;

/// The place of an entry that has none: a prescribed DOF's (PETSc would ignore its value), or a
/// contact pair found after the last fit.
const NOWHERE: usize = usize::MAX;
const NOWHERE_U32: u32 = u32::MAX;

/// A (row, column) pair as one sortable key (both are non-negative global indices).
fn key(row: PetscInt, col: PetscInt) -> u64 {
    ((row as u64) << 32) | col as u32 as u64
}

fn unkey(k: u64) -> (PetscInt, PetscInt) {
    ((k >> 32) as PetscInt, k as u32 as PetscInt)
}

pub struct JacobianLayout {
    /// The distinct keys of the element entries, sorted (fixed for the step).
    element_keys: Vec<u64>,
    /// For each element entry (local element k, row i, column j at k * 256 + 16 j + i: column
    /// by column, as the element matrices are stored): its index in `element_keys`,
    /// NOWHERE_U32 where a DOF is prescribed.
    element_key: Vec<u32>,
    /// For each element entry: its place in the values (through `element_key`, kept
    /// composed so the hot loop has one indirection).
    element_place: Vec<u32>,
    /// Global row and column of every entry, in value order (sorted, distinct).
    rows: Vec<PetscInt>,
    cols: Vec<PetscInt>,
    /// Places of the entries of each coupled node pair (a <= b): block (a, b) row-major, then
    /// block (b, a) (the same again when a == b).
    pairs: HashMap<(usize, usize), [usize; 8]>,
    /// Per slave node: the nodes of its last engagement and the places of each of that
    /// engagement's (row node, column node) blocks, so an engagement over the same nodes as at
    /// the last Jacobian (nearly all of them) finds its places without a lookup per pair.
    engagements: HashMap<usize, (Vec<usize>, Vec<[usize; 4]>)>,
    values: Vec<f64>,
    /// Where the values go in PETSc's own storage (see [`JacobianLayout::hand_over`]).
    binding: Binding,
}

/// How a Jacobian reaches the matrix.
enum Binding {
    /// Through MatSetValuesCOO, binding to the storage afterwards: a new matrix or structure.
    Unbound,
    /// Straight into the storage of this matrix.
    Bound(Storage),
    /// Through MatSetValuesCOO only: some rank's storage is not laid out as the lists (kept
    /// until the structure or the matrix changes, so the binding is not tried at every
    /// Jacobian).
    Refused,
}

impl JacobianLayout {
    /// The layout of the local elements with global DOFs `element_dofs` and the contact node
    /// pairs `pairs` (a <= b), with `dof` the global DOFs of every node (-1 where prescribed).
    pub fn new(element_dofs: &[[PetscInt; DOFS]], pairs: impl IntoIterator<Item = (usize, usize)>, dof: &[[PetscInt; 2]]) -> Self {
        let mut keyed: Vec<(u64, u32)> = Vec::with_capacity(element_dofs.len() * ELEMENT_BLOCK);
        for (k, dofs) in element_dofs.iter().enumerate() {
            for (i, &r) in dofs.iter().enumerate() {
                for (j, &c) in dofs.iter().enumerate() {
                    if r >= 0 && c >= 0 {
                        keyed.push((key(r, c), (k * ELEMENT_BLOCK + j * DOFS + i) as u32));
                    }
                }
            }
        }
        keyed.sort_unstable();
        let mut element_keys = Vec::new();
        let mut element_key = vec![NOWHERE_U32; element_dofs.len() * ELEMENT_BLOCK];
        for (k, entry) in keyed {
            if element_keys.last() != Some(&k) {
                element_keys.push(k);
            }
            element_key[entry as usize] = (element_keys.len() - 1) as u32;
        }
        let mut layout = JacobianLayout {
            rows: element_keys.iter().map(|&k| unkey(k).0).collect(),
            cols: element_keys.iter().map(|&k| unkey(k).1).collect(),
            element_keys,
            element_place: element_key.clone(),
            element_key,
            pairs: HashMap::new(),
            engagements: HashMap::new(),
            values: Vec::new(),
            binding: Binding::Unbound,
        };
        layout.set_pairs(pairs, dof);
        layout
    }

    /// Replaces the contact pairs (a <= b); the values are zeroed. Within a step the pattern
    /// only grows, so a refit merges the new pairs' entries into the lists and moves the places
    /// already known along (a refit costs a pass over the lists, not a sort of them and a
    /// search for every place); a pair left out sends the lists back to the elements' alone.
    pub fn set_pairs(&mut self, pairs: impl IntoIterator<Item = (usize, usize)>, dof: &[[PetscInt; 2]]) {
        let mut pairs: Vec<(usize, usize)> = pairs.into_iter().collect();
        pairs.sort_unstable();
        pairs.dedup();
        if pairs.iter().filter(|p| self.pairs.contains_key(p)).count() < self.pairs.len() {
            (self.rows, self.cols) = self.element_keys.iter().map(|&k| unkey(k)).unzip();
            self.element_place.copy_from_slice(&self.element_key);
            self.pairs.clear();
        }
        pairs.retain(|p| !self.pairs.contains_key(p));
        let blocks = |a: usize, b: usize| if a == b { [(a, a), (a, a)] } else { [(a, b), (b, a)] };
        let mut added: Vec<u64> = Vec::with_capacity(8 * pairs.len());
        for &(a, b) in &pairs {
            debug_assert!(a <= b, "pairs are ordered");
            for (r, c) in blocks(a, b) {
                for &row in &dof[r] {
                    for &col in &dof[c] {
                        if row >= 0 && col >= 0 {
                            added.push(key(row, col));
                        }
                    }
                }
            }
        }
        added.sort_unstable();
        added.dedup();
        // merge the two sorted lists; each known entry learns where it moved
        let known = self.rows.len();
        let mut merged = Vec::with_capacity(known + added.len());
        let mut moved = Vec::with_capacity(known);
        let (mut o, mut a) = (0, 0);
        while o < known || a < added.len() {
            let next_known = if o < known { key(self.rows[o], self.cols[o]) } else { u64::MAX };
            let next_added = added.get(a).copied().unwrap_or(u64::MAX);
            let k = next_known.min(next_added);
            if next_known == k {
                moved.push(merged.len() as u32);
                o += 1;
            }
            if next_added == k {
                a += 1;
            }
            merged.push(k);
        }
        if merged.len() > known {
            for place in self.element_place.iter_mut().filter(|p| **p != NOWHERE_U32) {
                *place = moved[*place as usize];
            }
            for place in self.pairs.values_mut().flatten().filter(|p| **p != NOWHERE) {
                *place = moved[*place] as usize;
            }
        }
        let place_of = |row: PetscInt, col: PetscInt| if row >= 0 && col >= 0 { merged.binary_search(&key(row, col)).expect("merged") } else { NOWHERE };
        for (a, b) in pairs {
            let mut places = [NOWHERE; 8];
            for (n, (r, c)) in blocks(a, b).into_iter().enumerate() {
                for ci in 0..2 {
                    for cj in 0..2 {
                        places[4 * n + 2 * ci + cj] = place_of(dof[r][ci], dof[c][cj]);
                    }
                }
            }
            self.pairs.insert((a, b), places);
        }
        (self.rows, self.cols) = merged.iter().map(|&k| unkey(k)).unzip();
        self.values = vec![0.0; merged.len()];
        self.engagements.clear();
        self.binding = Binding::Unbound;
    }

    /// Global (row, column) of every entry, in value order, for MatSetPreallocationCOO.
    pub fn indices(&self) -> (&[PetscInt], &[PetscInt]) {
        (&self.rows, &self.cols)
    }

    /// Zeros every value, before a Jacobian's blocks are added.
    pub fn clear(&mut self) {
        self.values.fill(0.0);
    }

    /// Adds local element `k`'s block, given column by column (entry (i, j) at 16 j + i, the
    /// storage of the element matrices).
    pub fn add_element(&mut self, k: usize, columns: &[f64]) {
        let places = &self.element_place[k * ELEMENT_BLOCK..(k + 1) * ELEMENT_BLOCK];
        for (&at, &v) in places.iter().zip(columns) {
            if at != NOWHERE_U32 {
                self.values[at as usize] += v;
            }
        }
    }

    /// Adds `value` at entry (i, j) of local element `k`'s block.
    pub fn add_element_entry(&mut self, k: usize, i: usize, j: usize, value: f64) {
        let at = self.element_place[k * ELEMENT_BLOCK + j * DOFS + i];
        if at != NOWHERE_U32 {
            self.values[at as usize] += value;
        }
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
                let block = places[i * n + j];
                for ci in 0..2 {
                    for cj in 0..2 {
                        let at = block[2 * ci + cj];
                        if at != NOWHERE {
                            self.values[at] += tangent[(2 * i + ci) * 2 * n + 2 * j + cj];
                        }
                    }
                }
            }
        }
    }

    /// Adds `value` at (row node a, component ca; column node b, component cb), a coupling
    /// of a pair in the layout (a multi-point constraint's); nothing where a DOF is prescribed.
    pub fn add_coupling(&mut self, a: usize, ca: usize, b: usize, cb: usize, value: f64) {
        let at = self.place(a, b)[2 * ca + cb];
        if at != NOWHERE {
            self.values[at] += value;
        }
    }

    /// Places of the 2 x 2 block (row node a, column node b), row-major.
    fn place(&self, a: usize, b: usize) -> [usize; 4] {
        match self.pairs.get(&(a.min(b), a.max(b))) {
            Some(p) if a <= b => [p[0], p[1], p[2], p[3]],
            Some(p) => [p[4], p[5], p[6], p[7]],
            None => [NOWHERE; 4],
        }
    }

    /// Every value, in the order of [`JacobianLayout::indices`].
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Forgets where the values went (a new matrix: its first hand-over goes through
    /// MatSetValuesCOO, which leaves it assembled).
    pub fn forget_storage(&mut self) {
        self.binding = Binding::Unbound;
    }

    /// Collective: sets `matrix`'s values (those of all ranks summed) from this layout's. The
    /// first time for a matrix or structure through MatSetValuesCOO, after which it returns
    /// whether this rank could bind to the storage PETSc then has (the caller makes every rank
    /// agree through [`JacobianLayout::keep_storage`]); afterwards straight into that storage
    /// (None).
    pub fn hand_over(&mut self, matrix: &mut impl MatOps) -> Result<Option<bool>> {
        let handle = matrix.raw() as usize;
        let storage = match &self.binding {
            Binding::Bound(storage) if storage.matrix == handle => storage,
            Binding::Refused => {
                matrix.set_values_coo(&self.values)?;
                return Ok(None);
            }
            _ => {
                matrix.set_values_coo(&self.values)?;
                let structure = matrix.owned_structure()?;
                let bound = Storage::bind(&self.rows, &self.cols, &structure, handle);
                let everywhere = bound.is_some();
                self.binding = bound.map_or(Binding::Refused, Binding::Bound);
                return Ok(Some(everywhere));
            }
        };
        let values = &self.values;
        matrix.write_owned(|diagonal, off_diagonal| {
            for (runs, gaps, target) in
                [(&storage.diagonal, &storage.diagonal_gaps, diagonal), (&storage.off_diagonal, &storage.off_diagonal_gaps, off_diagonal)]
            {
                for &(v, p, n) in runs {
                    target[p..p + n].copy_from_slice(&values[v..v + n]);
                }
                for &p in gaps {
                    target[p] = 0.0;
                }
            }
        })?;
        for (row, cols, first) in &storage.remote {
            matrix.add_block(&[*row], cols, &values[*first..*first + cols.len()])?;
        }
        matrix.assemble()?;
        Ok(None)
    }

    /// Keeps the storage bound by the last [`JacobianLayout::hand_over`] only if every rank
    /// could bind (`everywhere`): the direct path is collective through its assembly.
    pub fn keep_storage(&mut self, everywhere: bool) {
        if !everywhere {
            self.binding = Binding::Refused;
        }
    }

    /// Whether hand-overs go straight into PETSc's storage.
    pub fn writes_storage(&self) -> bool {
        matches!(self.binding, Binding::Bound(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A matrix that records what the layout asks of it and stores its rows unlike the lists.
    #[derive(Default)]
    struct Refusing {
        coo: usize,
        structures: std::cell::Cell<usize>,
    }

    impl MatOps for Refusing {
        fn raw(&self) -> crate::petsc::sys::Mat {
            std::ptr::null_mut()
        }
        fn set_values_coo(&mut self, _: &[f64]) -> Result<()> {
            self.coo += 1;
            Ok(())
        }
        fn owned_structure(&self) -> Result<crate::petsc::OwnedStructure> {
            self.structures.set(self.structures.get() + 1);
            Ok(crate::petsc::OwnedStructure {
                first: 0,
                end: 1,
                diagonal_ptr: vec![0, 0],
                diagonal_cols: vec![],
                off_diagonal_ptr: vec![0, 0],
                off_diagonal_cols: vec![],
            })
        }
    }

    #[test]
    fn a_refused_binding_is_not_tried_again_until_the_structure_changes() {
        let dof = vec![[0, 1]];
        let mut layout = JacobianLayout::new(&[], [(0, 0)], &dof);
        let mut m = Refusing::default();
        // the structure PETSc reports lacks the layout's entries: no binding
        assert_eq!(layout.hand_over(&mut m).unwrap(), Some(false));
        layout.keep_storage(false);
        assert!(!layout.writes_storage());
        assert_eq!(m.structures.get(), 1);
        for _ in 0..3 {
            assert_eq!(layout.hand_over(&mut m).unwrap(), None, "COO, no agreement to reach");
        }
        assert_eq!((m.coo, m.structures.get()), (4, 1), "values through COO every time, the structure not read again");
        // a refit tries again
        layout.set_pairs([(0, 0)], &dof);
        assert_eq!(layout.hand_over(&mut m).unwrap(), Some(false));
        assert_eq!(m.structures.get(), 2);
    }

    #[test]
    fn a_grown_pattern_is_laid_out_as_one_built_whole() {
        let first: [PetscInt; DOFS] = std::array::from_fn(|i| if i == 3 { -1 } else { i as PetscInt });
        let second: [PetscInt; DOFS] = std::array::from_fn(|i| (i + 8) as PetscInt);
        let dof = vec![[100, 101], [102, -1], [104, 105], [8, 9], [30, 31]];
        let all = [(0, 2), (1, 1), (0, 3), (2, 4), (3, 4)];
        let whole = JacobianLayout::new(&[first, second], all, &dof);
        let mut grown = JacobianLayout::new(&[first, second], [(0, 2), (1, 1)], &dof);
        grown.set_pairs(all[..4].iter().copied(), &dof);
        grown.set_pairs(all, &dof);
        assert_eq!(grown.indices(), whole.indices());
        // the element blocks land at their entries: the blocks' sums, entry by entry
        let mut layouts = [grown, whole];
        let columns: Vec<f64> = (0..ELEMENT_BLOCK).map(|n| n as f64).collect();
        let mut expected: HashMap<(PetscInt, PetscInt), f64> = HashMap::new();
        for (k, dofs) in [first, second].iter().enumerate() {
            for layout in &mut layouts {
                layout.add_element(k, &columns);
            }
            for (n, v) in columns.iter().enumerate() {
                let (r, c) = (dofs[n % DOFS], dofs[n / DOFS]);
                if r >= 0 && c >= 0 {
                    *expected.entry((r, c)).or_default() += v;
                }
            }
        }
        let (rows, cols) = layouts[0].indices();
        for ((r, c), v) in rows.iter().zip(cols).zip(layouts[0].values()) {
            assert_eq!(*v, expected.get(&(*r, *c)).copied().unwrap_or(0.0), "entry ({r}, {c})");
        }
        // and the engagements at the same places in both
        for layout in &mut layouts {
            let tangent: Vec<f64> = (0..36).map(|v| 1000.0 + v as f64).collect();
            layout.add_engagement(&[2, 0, 4], &tangent);
            layout.add_engagement(&[3, 4], &tangent[..16]);
        }
        assert_eq!(layouts[0].values(), layouts[1].values());
        assert!(layouts[0].values().iter().filter(|&&v| v >= 1000.0).count() >= 20, "the engagements found their places");
    }

    #[test]
    fn entries_sorted_once_each_and_every_block_added_at_its_place() {
        // two elements sharing DOFs 8..16 (the second's first half), one prescribed DOF (-1)
        let first: [PetscInt; DOFS] = std::array::from_fn(|i| if i == 3 { -1 } else { i as PetscInt });
        let second: [PetscInt; DOFS] = std::array::from_fn(|i| (i + 8) as PetscInt);
        let dof = vec![[100, 101], [102, -1], [104, 105], [8, 9]];
        let mut layout = JacobianLayout::new(&[first, second], [(0, 2), (1, 1), (0, 3)], &dof);
        let (rows, cols) = layout.indices();
        let entries: Vec<(PetscInt, PetscInt)> = rows.iter().copied().zip(cols.iter().copied()).collect();
        assert!(entries.windows(2).all(|w| w[0] < w[1]), "sorted, distinct");
        assert!(entries.iter().all(|&(r, c)| r >= 0 && c >= 0), "prescribed DOFs left out");
        // elements: 15 x 15 + 16 x 16 - the 8 x 8 shared; pairs: (0, 2) 8, (1, 1) 1 (102, 102),
        // (0, 3) 8 (100, 101 against the elements' 8, 9: new entries)
        assert_eq!(entries.len(), 15 * 15 + 16 * 16 - 8 * 8 + 8 + 1 + 8);
        let at = |r: PetscInt, c: PetscInt| entries.binary_search(&(r, c)).unwrap();

        // element blocks: repeats summed at their shared places
        let columns: Vec<f64> = (0..ELEMENT_BLOCK).map(|n| ((n % DOFS) * DOFS + n / DOFS) as f64).collect();
        layout.add_element(0, &columns);
        layout.add_element(1, &[1000.0; ELEMENT_BLOCK]);
        layout.add_element_entry(1, 0, 0, 0.5);
        let v = layout.values().to_vec();
        assert_eq!(v[at(1, 2)], (DOFS + 2) as f64);
        assert_eq!(v[at(8, 9)], (8 * DOFS + 9) as f64 + 1000.0);
        assert_eq!(v[at(8, 8)], (8 * DOFS + 8) as f64 + 1000.5);
        assert_eq!(v[at(23, 23)], 1000.0);

        // an engagement over nodes 2 (slave) and 0: block (row node 0, column node 2) is its
        // rows 2, 3 and columns 0, 1; the (2, 2) pair has no place and is skipped
        let tangent: Vec<f64> = (0..16).map(|v| v as f64).collect();
        layout.add_engagement(&[2, 0], &tangent);
        layout.add_engagement(&[2, 0], &tangent);
        let v = layout.values();
        assert_eq!([v[at(100, 104)], v[at(100, 105)], v[at(101, 104)], v[at(101, 105)]], [16.0, 18.0, 24.0, 26.0]);
        assert_eq!([v[at(104, 100)], v[at(104, 101)], v[at(105, 100)], v[at(105, 101)]], [4.0, 6.0, 12.0, 14.0]);

        // a refit keeps the element entries and takes the new pairs
        layout.set_pairs([(1, 2)], &dof);
        let (rows, cols) = layout.indices();
        let entries: Vec<(PetscInt, PetscInt)> = rows.iter().copied().zip(cols.iter().copied()).collect();
        assert_eq!(entries.len(), 15 * 15 + 16 * 16 - 8 * 8 + 4);
        assert!(entries.binary_search(&(102, 105)).is_ok() && entries.binary_search(&(100, 104)).is_err());
        assert!(layout.values().iter().all(|&v| v == 0.0));
        layout.add_element(1, &[1.0; ELEMENT_BLOCK]);
        layout.clear();
        assert!(layout.values().iter().all(|&v| v == 0.0));
    }
}

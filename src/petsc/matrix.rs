//! PETSc Mat: parallel AIJ with exact preallocation.

use super::{check, sys, to_petsc_int, Comm, PetscSession, SessionBorrow, VecOps};
use crate::error::Result;
use std::marker::PhantomData;

/// Operations shared by owned matrices and the views PETSc hands to callbacks.
pub trait MatOps {
    fn raw(&self) -> sys::Mat;

    fn zero_entries(&mut self) -> Result<()> {
        // SAFETY: valid Mat handle.
        check(unsafe { sys::MatZeroEntries(self.raw()) }, "MatZeroEntries")
    }

    /// Adds a dense block `values` (row-major, rows x cols) at global `rows`, `cols`.
    /// Negative indices are skipped by PETSc (used for eliminated, prescribed DOFs).
    fn add_block(&mut self, rows: &[sys::PetscInt], cols: &[sys::PetscInt], values: &[f64]) -> Result<()> {
        assert_eq!(rows.len() * cols.len(), values.len(), "add_block: values must be rows x cols");
        // SAFETY: slices sized as declared; PETSc copies the values.
        check(
            unsafe {
                sys::MatSetValues(
                    self.raw(),
                    to_petsc_int(rows.len())?,
                    rows.as_ptr(),
                    to_petsc_int(cols.len())?,
                    cols.as_ptr(),
                    values.as_ptr(),
                    sys::InsertMode_ADD_VALUES,
                )
            },
            "MatSetValues",
        )
    }

    /// Collective: makes the matrix's nonzero structure the entries (`rows[k]`, `cols[k]`),
    /// global indices, repeats allowed (summed), negative indices ignored, rows of other ranks
    /// allowed (sent to their owners); [`MatOps::set_values_coo`] then takes one value per entry in
    /// this order. Replaces any earlier structure. PETSc 3.18 does not raise the matrix's
    /// nonzero state for it, so a factorisation of the old structure must be reset by the
    /// caller (see `NonlinearProblem::take_structure_change`).
    fn preallocate_coo(&mut self, rows: &[sys::PetscInt], cols: &[sys::PetscInt]) -> Result<()> {
        assert_eq!(rows.len(), cols.len(), "one column per row index");
        // PETSc may permute the index arrays it is given: hand it copies.
        let (mut i, mut j) = (rows.to_vec(), cols.to_vec());
        let n = sys::PetscCount::try_from(i.len()).map_err(|_| crate::error::Error::input("too many matrix entries for PetscCount"))?;
        // SAFETY: two arrays of n indices, owned here for the call; PETSc copies what it keeps.
        check(unsafe { sys::MatSetPreallocationCOO(self.raw(), n, i.as_mut_ptr(), j.as_mut_ptr()) }, "MatSetPreallocationCOO")?;
        coo_entries().insert(self.raw() as usize, rows.len());
        Ok(())
    }

    /// Collective: sets every entry from `values`, one per entry given to
    /// [`MatOps::preallocate_coo`] in its order (repeats summed; INSERT_VALUES: what was there is
    /// replaced) and assembles.
    fn set_values_coo(&mut self, values: &[f64]) -> Result<()> {
        let entries = coo_entries().get(&(self.raw() as usize)).copied();
        assert_eq!(entries, Some(values.len()), "set_values_coo: one value per entry of the matrix's COO preallocation");
        // SAFETY: PETSc reads as many values as entries were preallocated, checked just above.
        check(unsafe { sys::MatSetValuesCOO(self.raw(), values.as_ptr(), sys::InsertMode_INSERT_VALUES) }, "MatSetValuesCOO")
    }

    /// Collective: y = A x (x and y distinct vectors laid out as the matrix's columns and
    /// rows).
    fn multiply(&self, x: &impl VecOps, y: &mut impl VecOps) -> Result<()> {
        // SAFETY: valid handles; x and y are distinct objects (one borrowed shared, one
        // exclusively), as MatMult requires.
        check(unsafe { sys::MatMult(self.raw(), x.raw(), y.raw()) }, "MatMult")
    }

    /// The nonzero structure of this rank's rows as PETSc stores their values: the diagonal
    /// block (columns this rank owns) and the off-diagonal block, each row by row, columns
    /// ascending, as global indices. Valid until the structure changes (a COO preallocation).
    fn owned_structure(&self) -> Result<OwnedStructure> {
        let mut first = 0;
        let mut end = 0;
        // SAFETY: valid handle; two output integers.
        check(unsafe { sys::MatGetOwnershipRange(self.raw(), &mut first, &mut end) }, "MatGetOwnershipRange")?;
        let LocalBlocks { diagonal, off_diagonal, colmap } = local_blocks(self.raw())?;
        let (diagonal_ptr, mut diagonal_cols) = block_structure(diagonal)?;
        diagonal_cols.iter_mut().for_each(|c| *c += first);
        let (off_diagonal_ptr, off_diagonal_cols) = match off_diagonal {
            Some(block) => {
                let (ptr, cols) = block_structure(block)?;
                if colmap.is_null() && !cols.is_empty() {
                    return Err(crate::error::Error::Internal("MatMPIAIJGetSeqAIJ: no column map for the off-diagonal block".into()));
                }
                // SAFETY: PETSc's column map has an entry for every local column the block
                // uses, and these are such columns.
                let global = cols.iter().map(|&c| unsafe { *colmap.add(c as usize) }).collect();
                (ptr, global)
            }
            None => (vec![0; diagonal_ptr.len()], Vec::new()),
        };
        Ok(OwnedStructure { first, end, diagonal_ptr, diagonal_cols, off_diagonal_ptr, off_diagonal_cols })
    }

    /// Lends `fill` the value arrays of this rank's rows, in the order of
    /// [`MatOps::owned_structure`] (diagonal block, off-diagonal block: empty on one rank), to
    /// overwrite. Entries of other ranks' rows go through [`MatOps::add_block`] after it, and
    /// [`MatOps::assemble`] finishes (it also tells the solver the values changed). Only for a
    /// matrix assembled at least once since its structure was set.
    fn write_owned(&mut self, fill: impl FnOnce(&mut [f64], &mut [f64])) -> Result<()> {
        let blocks = local_blocks(self.raw())?;
        let mut diagonal = BlockValues::lend(blocks.diagonal)?;
        let mut off_diagonal = match blocks.off_diagonal {
            Some(block) => Some(BlockValues::lend(block)?),
            None => None,
        };
        fill(diagonal.values(), off_diagonal.as_mut().map_or(&mut [][..], |b| b.values()));
        diagonal.give_back()?;
        off_diagonal.map_or(Ok(()), |b| b.give_back())
    }

    fn set_option(&mut self, option: sys::MatOption, value: bool) -> Result<()> {
        let flag = if value { sys::PetscBool_PETSC_TRUE } else { sys::PetscBool_PETSC_FALSE };
        // SAFETY: valid handle.
        check(unsafe { sys::MatSetOption(self.raw(), option, flag) }, "MatSetOption")
    }

    /// Collective: communicates stashed off-rank entries and finishes assembly.
    fn assemble(&mut self) -> Result<()> {
        // SAFETY: valid handle; Begin/End paired.
        check(unsafe { sys::MatAssemblyBegin(self.raw(), sys::MatAssemblyType_MAT_FINAL_ASSEMBLY) }, "MatAssemblyBegin")?;
        check(unsafe { sys::MatAssemblyEnd(self.raw(), sys::MatAssemblyType_MAT_FINAL_ASSEMBLY) }, "MatAssemblyEnd")
    }
}

/// This rank's rows of a matrix as PETSc stores them (see [`MatOps::owned_structure`]).
#[derive(Clone, Debug, PartialEq)]
pub struct OwnedStructure {
    /// The rows [first, end) are this rank's (and so are those columns).
    pub first: sys::PetscInt,
    pub end: sys::PetscInt,
    /// Row pointers (end - first + 1) and global columns of the diagonal block.
    pub diagonal_ptr: Vec<usize>,
    pub diagonal_cols: Vec<sys::PetscInt>,
    /// The same for the off-diagonal block (empty on one rank).
    pub off_diagonal_ptr: Vec<usize>,
    pub off_diagonal_cols: Vec<sys::PetscInt>,
}

/// The sequential blocks holding this rank's rows: the matrix itself on one rank (seqaij); the
/// diagonal and off-diagonal blocks on several (mpiaij).
struct LocalBlocks {
    diagonal: sys::Mat,
    off_diagonal: Option<sys::Mat>,
    /// The off-diagonal block's column map (global column of each local one), PETSc's own.
    colmap: *const sys::PetscInt,
}

fn local_blocks(mat: sys::Mat) -> Result<LocalBlocks> {
    let mut ty: sys::MatType = std::ptr::null();
    // SAFETY: valid handle; PETSc returns a pointer to its own type name (or null).
    check(unsafe { sys::MatGetType(mat, &mut ty) }, "MatGetType")?;
    // SAFETY: a non-null type name is a NUL-terminated string owned by PETSc.
    let name = if ty.is_null() { "" } else { unsafe { std::ffi::CStr::from_ptr(ty) }.to_str().unwrap_or("") };
    match name {
        "seqaij" => Ok(LocalBlocks { diagonal: mat, off_diagonal: None, colmap: std::ptr::null() }),
        "mpiaij" => {
            let (mut d, mut o, mut colmap) = (std::ptr::null_mut(), std::ptr::null_mut(), std::ptr::null());
            // SAFETY: valid mpiaij handle; PETSc returns its blocks and the off-diagonal block's
            // column map (alive as long as the structure).
            check(unsafe { sys::MatMPIAIJGetSeqAIJ(mat, &mut d, &mut o, &mut colmap) }, "MatMPIAIJGetSeqAIJ")?;
            Ok(LocalBlocks { diagonal: d, off_diagonal: Some(o), colmap })
        }
        other => Err(crate::error::Error::Internal(format!("matrix type '{other}': only seqaij and mpiaij expose their storage"))),
    }
}

/// Reads the row pointers (n + 1 entries) and local columns of a sequential AIJ block through
/// `read`, between MatGetRowIJ and MatRestoreRowIJ.
fn read_rows<R>(block: sys::Mat, read: impl FnOnce(&[sys::PetscInt], *const sys::PetscInt) -> R) -> Result<R> {
    let (mut n, mut ia, mut ja, mut done) = (0, std::ptr::null(), std::ptr::null(), sys::PetscBool_PETSC_FALSE);
    let no = sys::PetscBool_PETSC_FALSE;
    // SAFETY: valid handle; 0-based, not symmetrised, not inode-compressed: PETSc returns its
    // own CSR arrays (O(1) for seqaij), read here and handed back below.
    check(unsafe { sys::MatGetRowIJ(block, 0, no, no, &mut n, &mut ia, &mut ja, &mut done) }, "MatGetRowIJ")?;
    if done != sys::PetscBool_PETSC_TRUE || ia.is_null() {
        return Err(crate::error::Error::Internal("MatGetRowIJ: no row structure for this matrix".into()));
    }
    // SAFETY: ia has n + 1 entries.
    let result = read(unsafe { std::slice::from_raw_parts(ia, n as usize + 1) }, ja);
    // SAFETY: the arrays obtained above, handed back.
    check(unsafe { sys::MatRestoreRowIJ(block, 0, no, no, &mut n, &mut ia, &mut ja, &mut done) }, "MatRestoreRowIJ")?;
    Ok(result)
}

/// Row pointers and (local) columns of a sequential AIJ block, copied.
fn block_structure(block: sys::Mat) -> Result<(Vec<usize>, Vec<sys::PetscInt>)> {
    read_rows(block, |ia, ja| {
        let ptr: Vec<usize> = ia.iter().map(|&v| v as usize).collect();
        let nonzeros = *ptr.last().unwrap_or(&0);
        // SAFETY: ja has ia[n] entries.
        let cols = if nonzeros == 0 { Vec::new() } else { unsafe { std::slice::from_raw_parts(ja, nonzeros) }.to_vec() };
        (ptr, cols)
    })
}

/// The value array of a sequential AIJ block, lent by PETSc until `give_back`.
struct BlockValues {
    block: sys::Mat,
    array: *mut f64,
    len: usize,
}

impl BlockValues {
    fn lend(block: sys::Mat) -> Result<Self> {
        let len = read_rows(block, |ia, _| ia.last().map_or(0, |&n| n as usize))?;
        let mut array: *mut f64 = std::ptr::null_mut();
        // SAFETY: valid seqaij handle; PETSc lends its value array (len entries) until restored.
        check(unsafe { sys::MatSeqAIJGetArray(block, &mut array) }, "MatSeqAIJGetArray")?;
        Ok(BlockValues { block, array, len })
    }

    fn values(&mut self) -> &mut [f64] {
        if self.len == 0 || self.array.is_null() {
            return &mut [];
        }
        // SAFETY: PETSc's value array of `len` entries, lent to this object alone until
        // `give_back`; the borrow of self keeps it unique.
        unsafe { std::slice::from_raw_parts_mut(self.array, self.len) }
    }

    fn give_back(mut self) -> Result<()> {
        // SAFETY: the array lent in `lend`, handed back once (this marks the block changed).
        check(unsafe { sys::MatSeqAIJRestoreArray(self.block, &mut self.array) }, "MatSeqAIJRestoreArray")
    }
}

/// The entry count of each matrix's last COO preallocation (keyed by handle), so that
/// `set_values_coo` can refuse a value array PETSc would read past; a matrix leaves it when
/// destroyed.
fn coo_entries() -> std::sync::MutexGuard<'static, std::collections::BTreeMap<usize, usize>> {
    static ENTRIES: std::sync::Mutex<std::collections::BTreeMap<usize, usize>> = std::sync::Mutex::new(std::collections::BTreeMap::new());
    ENTRIES.lock().unwrap_or_else(|e| e.into_inner())
}

/// An owned AIJ matrix.
pub struct Matrix<'s> {
    raw: sys::Mat,
    _session: SessionBorrow<'s>,
}

impl<'s> Matrix<'s> {
    /// Square AIJ matrix with `local_rows` rows on this rank and exact per-row preallocation:
    /// `diag_nnz[i]` / `offdiag_nnz[i]` nonzeros of local row i in the diagonal / off-diagonal
    /// blocks. A new nonzero outside this pattern is an error (MAT_NEW_NONZERO_ALLOCATION_ERR),
    /// so a wrong pattern is found at once instead of slowing assembly silently.
    pub fn aij(_session: &'s PetscSession, comm: Comm, local_rows: usize, diag_nnz: &[sys::PetscInt], offdiag_nnz: &[sys::PetscInt]) -> Result<Self> {
        assert_eq!(diag_nnz.len(), local_rows, "one diagonal count per local row");
        assert_eq!(offdiag_nnz.len(), local_rows, "one off-diagonal count per local row");
        let m = to_petsc_int(local_rows)?;
        let mut raw = std::ptr::null_mut();
        // SAFETY: count arrays have local_rows entries and are copied by PETSc.
        check(unsafe { sys::MatCreateAIJ(comm, m, m, -1, -1, 0, diag_nnz.as_ptr(), 0, offdiag_nnz.as_ptr(), &mut raw) }, "MatCreateAIJ")?;
        let mut mat = Matrix { raw, _session: PhantomData };
        mat.set_option(sys::MatOption_MAT_NEW_NONZERO_ALLOCATION_ERR, true)?;
        Ok(mat)
    }
}

impl<'s> Matrix<'s> {
    /// Square AIJ matrix with `local_rows` rows on this rank whose nonzero structure is the
    /// COO entries (`rows[k]`, `cols[k]`) of all ranks (see [`MatOps::preallocate_coo`]).
    pub fn aij_coo(_session: &'s PetscSession, comm: Comm, local_rows: usize, rows: &[sys::PetscInt], cols: &[sys::PetscInt]) -> Result<Self> {
        let m = to_petsc_int(local_rows)?;
        let mut raw = std::ptr::null_mut();
        // SAFETY: no count arrays (NULL): the COO preallocation below sets the structure.
        check(unsafe { sys::MatCreateAIJ(comm, m, m, -1, -1, 0, std::ptr::null(), 0, std::ptr::null(), &mut raw) }, "MatCreateAIJ")?;
        let mut mat = Matrix { raw, _session: PhantomData };
        mat.preallocate_coo(rows, cols)?;
        Ok(mat)
    }
}

impl MatOps for Matrix<'_> {
    fn raw(&self) -> sys::Mat {
        self.raw
    }
}

impl Drop for Matrix<'_> {
    fn drop(&mut self) {
        coo_entries().remove(&(self.raw as usize));
        // SAFETY: owned handle.
        unsafe { sys::MatDestroy(&mut self.raw) };
    }
}

/// A Mat PETSc passes into a callback: borrowed, never destroyed by us.
pub struct MatrixView<'a> {
    raw: sys::Mat,
    _life: PhantomData<&'a ()>,
}

impl MatrixView<'_> {
    pub(crate) fn from_raw(raw: sys::Mat) -> Self {
        MatrixView { raw, _life: PhantomData }
    }
}

impl MatOps for MatrixView<'_> {
    fn raw(&self) -> sys::Mat {
        self.raw
    }
}

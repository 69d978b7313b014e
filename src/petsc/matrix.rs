//! PETSc Mat: parallel AIJ with exact preallocation.

use super::{check, sys, to_petsc_int, Comm, PetscSession, SessionBorrow};
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

    /// Collective: replaces the nonzero structure by room for exactly `diag_nnz[i]` /
    /// `offdiag_nnz[i]` entries in local row i (diagonal / off-diagonal block); the values are
    /// lost, and the next assembly fixes the new pattern (PETSc then sees a new nonzero state,
    /// so a factorisation redoes its symbolic analysis).
    fn preallocate(&mut self, diag_nnz: &[sys::PetscInt], offdiag_nnz: &[sys::PetscInt]) -> Result<()> {
        assert_eq!(diag_nnz.len(), offdiag_nnz.len(), "one count of each kind per local row");
        // SAFETY: count arrays of the local row count, copied by PETSc; no upper-triangular
        // counts (NULL) for AIJ.
        check(
            unsafe { sys::MatXAIJSetPreallocation(self.raw(), 1, diag_nnz.as_ptr(), offdiag_nnz.as_ptr(), std::ptr::null(), std::ptr::null()) },
            "MatXAIJSetPreallocation",
        )
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

impl MatOps for Matrix<'_> {
    fn raw(&self) -> sys::Mat {
        self.raw
    }
}

impl Drop for Matrix<'_> {
    fn drop(&mut self) {
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

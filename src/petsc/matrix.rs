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

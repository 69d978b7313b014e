//! PETSc Vec (distributed and sequential), index sets and scatters.

use super::{check, sys, to_petsc_int, Comm, PetscSession, SessionBorrow};
use crate::error::Result;
use std::marker::PhantomData;
use std::ops::{Deref, DerefMut};

/// Operations shared by owned vectors and the views PETSc hands to callbacks.
pub trait VecOps {
    fn raw(&self) -> sys::Vec;

    /// Half-open range of global indices owned by this rank.
    fn ownership_range(&self) -> Result<(usize, usize)> {
        let (mut lo, mut hi) = (0, 0);
        // SAFETY: valid Vec handle, out-pointers to locals.
        check(unsafe { sys::VecGetOwnershipRange(self.raw(), &mut lo, &mut hi) }, "VecGetOwnershipRange")?;
        Ok((lo as usize, hi as usize))
    }

    fn global_size(&self) -> Result<usize> {
        let mut n = 0;
        // SAFETY: valid Vec handle, out-pointer to a local.
        check(unsafe { sys::VecGetSize(self.raw(), &mut n) }, "VecGetSize")?;
        Ok(n as usize)
    }

    /// Read-only view of the local part; restored with VecRestoreArrayRead on drop.
    fn read(&self) -> Result<ReadArray<'_>> {
        let mut ptr: *const f64 = std::ptr::null();
        let mut n = 0;
        // SAFETY: valid Vec handle; the array stays valid until the matching Restore in Drop.
        check(unsafe { sys::VecGetLocalSize(self.raw(), &mut n) }, "VecGetLocalSize")?;
        check(unsafe { sys::VecGetArrayRead(self.raw(), &mut ptr) }, "VecGetArrayRead")?;
        Ok(ReadArray { vec: self.raw(), ptr, len: n as usize, _borrow: PhantomData })
    }

    /// Writable view of the local part; restored with VecRestoreArray on drop.
    fn write(&mut self) -> Result<WriteArray<'_>> {
        let mut ptr: *mut f64 = std::ptr::null_mut();
        let mut n = 0;
        // SAFETY: valid Vec handle, exclusively borrowed; restored in Drop.
        check(unsafe { sys::VecGetLocalSize(self.raw(), &mut n) }, "VecGetLocalSize")?;
        check(unsafe { sys::VecGetArray(self.raw(), &mut ptr) }, "VecGetArray")?;
        Ok(WriteArray { vec: self.raw(), ptr, len: n as usize, _borrow: PhantomData })
    }

    fn set_all(&mut self, value: f64) -> Result<()> {
        // SAFETY: valid Vec handle.
        check(unsafe { sys::VecSet(self.raw(), value) }, "VecSet")
    }

    fn copy_from(&mut self, other: &impl VecOps) -> Result<()> {
        // SAFETY: both handles valid with the same layout (PETSc checks and reports otherwise).
        check(unsafe { sys::VecCopy(other.raw(), self.raw()) }, "VecCopy")
    }

    /// self += alpha * other.
    fn axpy(&mut self, alpha: f64, other: &impl VecOps) -> Result<()> {
        // SAFETY: both handles valid with the same layout (PETSc checks and reports otherwise).
        check(unsafe { sys::VecAXPY(self.raw(), alpha, other.raw()) }, "VecAXPY")
    }

    /// The largest magnitude of an entry (collective).
    fn norm_max(&self) -> Result<f64> {
        let mut v = 0.0;
        // SAFETY: valid Vec handle, out-pointer to a local.
        check(unsafe { sys::VecNorm(self.raw(), sys::NormType_NORM_INFINITY, &mut v) }, "VecNorm")?;
        Ok(v)
    }

    /// self = a - b (collective; all three laid out alike).
    fn difference(&mut self, a: &impl VecOps, b: &impl VecOps) -> Result<()> {
        // SAFETY: valid Vec handles of the same layout (caller); VecWAXPY computes w = alpha x + y.
        check(unsafe { sys::VecWAXPY(self.raw(), -1.0, b.raw(), a.raw()) }, "VecWAXPY")
    }

    fn norm2(&self) -> Result<f64> {
        let mut v = 0.0;
        // SAFETY: valid Vec handle, out-pointer to a local.
        check(unsafe { sys::VecNorm(self.raw(), sys::NormType_NORM_2, &mut v) }, "VecNorm")?;
        Ok(v)
    }

    /// Adds `values` at global `indices` (any rank's rows; off-rank ones go through the stash).
    fn add_values(&mut self, indices: &[sys::PetscInt], values: &[f64]) -> Result<()> {
        assert_eq!(indices.len(), values.len(), "add_values: one value per index");
        let n = to_petsc_int(indices.len())?;
        // SAFETY: slices of equal length n; PETSc copies them.
        check(unsafe { sys::VecSetValues(self.raw(), n, indices.as_ptr(), values.as_ptr(), sys::InsertMode_ADD_VALUES) }, "VecSetValues")
    }

    /// Collective: communicates stashed off-rank entries.
    fn assemble(&mut self) -> Result<()> {
        // SAFETY: valid Vec handle; Begin/End paired.
        check(unsafe { sys::VecAssemblyBegin(self.raw()) }, "VecAssemblyBegin")?;
        check(unsafe { sys::VecAssemblyEnd(self.raw()) }, "VecAssemblyEnd")
    }
}

/// An owned Vec.
pub struct Vector<'s> {
    raw: sys::Vec,
    _session: SessionBorrow<'s>,
}

impl<'s> Vector<'s> {
    /// Distributed vector with `local` entries on this rank.
    pub fn mpi(_session: &'s PetscSession, comm: Comm, local: usize) -> Result<Self> {
        let mut raw = std::ptr::null_mut();
        // SAFETY: comm is a live communicator; PETSC_DETERMINE (-1) sums the local sizes.
        check(unsafe { sys::VecCreateMPI(comm, to_petsc_int(local)?, -1, &mut raw) }, "VecCreateMPI")?;
        Ok(Vector { raw, _session: PhantomData })
    }

    /// Sequential vector on this rank alone.
    pub fn seq(_session: &'s PetscSession, len: usize) -> Result<Self> {
        let mut raw = std::ptr::null_mut();
        // SAFETY: PETSC_COMM_SELF equivalent is MPI_COMM_SELF from the mpi crate.
        let comm = unsafe { mpi::ffi::RSMPI_COMM_SELF };
        check(unsafe { sys::VecCreateSeq(comm, to_petsc_int(len)?, &mut raw) }, "VecCreateSeq")?;
        Ok(Vector { raw, _session: PhantomData })
    }

    /// A new vector with the same layout (values not copied).
    pub fn duplicate(&self) -> Result<Vector<'s>> {
        let mut raw = std::ptr::null_mut();
        // SAFETY: valid source handle.
        check(unsafe { sys::VecDuplicate(self.raw, &mut raw) }, "VecDuplicate")?;
        Ok(Vector { raw, _session: PhantomData })
    }
}

impl VecOps for Vector<'_> {
    fn raw(&self) -> sys::Vec {
        self.raw
    }
}

impl Drop for Vector<'_> {
    fn drop(&mut self) {
        // SAFETY: we own the handle; VecDestroy nulls it. Errors cannot be reported from drop.
        unsafe { sys::VecDestroy(&mut self.raw) };
    }
}

/// A Vec PETSc passes into a callback: borrowed, never destroyed by us.
pub struct VectorView<'a> {
    raw: sys::Vec,
    _life: PhantomData<&'a ()>,
}

impl VectorView<'_> {
    pub(crate) fn from_raw(raw: sys::Vec) -> Self {
        VectorView { raw, _life: PhantomData }
    }
}

impl VecOps for VectorView<'_> {
    fn raw(&self) -> sys::Vec {
        self.raw
    }
}

/// Local array from VecGetArrayRead, restored with VecRestoreArrayRead.
pub struct ReadArray<'a> {
    vec: sys::Vec,
    ptr: *const f64,
    len: usize,
    _borrow: PhantomData<&'a ()>,
}

impl Deref for ReadArray<'_> {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        if self.len == 0 {
            return &[];
        }
        // SAFETY: PETSc guarantees `len` valid doubles until the Restore in Drop.
        unsafe { std::slice::from_raw_parts(self.ptr, self.len) }
    }
}

impl Drop for ReadArray<'_> {
    fn drop(&mut self) {
        // SAFETY: matches the VecGetArrayRead that produced `ptr`.
        unsafe { sys::VecRestoreArrayRead(self.vec, &mut self.ptr) };
    }
}

/// Local array from VecGetArray, restored with VecRestoreArray.
pub struct WriteArray<'a> {
    vec: sys::Vec,
    ptr: *mut f64,
    len: usize,
    _borrow: PhantomData<&'a mut ()>,
}

impl Deref for WriteArray<'_> {
    type Target = [f64];
    fn deref(&self) -> &[f64] {
        if self.len == 0 {
            return &[];
        }
        // SAFETY: as for ReadArray.
        unsafe { std::slice::from_raw_parts(self.ptr, self.len) }
    }
}

impl DerefMut for WriteArray<'_> {
    fn deref_mut(&mut self) -> &mut [f64] {
        if self.len == 0 {
            return &mut [];
        }
        // SAFETY: the vector is exclusively borrowed for the guard's life.
        unsafe { std::slice::from_raw_parts_mut(self.ptr, self.len) }
    }
}

impl Drop for WriteArray<'_> {
    fn drop(&mut self) {
        // SAFETY: matches the VecGetArray that produced `ptr`.
        unsafe { sys::VecRestoreArray(self.vec, &mut self.ptr) };
    }
}

/// An owned IS of global indices (copied from the caller's slice).
pub struct IndexSet<'s> {
    raw: sys::IS,
    _session: SessionBorrow<'s>,
}

impl<'s> IndexSet<'s> {
    pub fn general(_session: &'s PetscSession, comm: Comm, indices: &[sys::PetscInt]) -> Result<Self> {
        let mut raw = std::ptr::null_mut();
        // SAFETY: PETSC_COPY_VALUES (0): PETSc copies the slice.
        check(
            unsafe { sys::ISCreateGeneral(comm, to_petsc_int(indices.len())?, indices.as_ptr(), sys::PetscCopyMode_PETSC_COPY_VALUES, &mut raw) },
            "ISCreateGeneral",
        )?;
        Ok(IndexSet { raw, _session: PhantomData })
    }

    /// The local indices, copied out.
    pub fn to_vec(&self) -> Result<Vec<sys::PetscInt>> {
        let mut n = 0;
        let mut ptr: *const sys::PetscInt = std::ptr::null();
        // SAFETY: valid IS; Get/Restore paired around the copy.
        check(unsafe { sys::ISGetLocalSize(self.raw, &mut n) }, "ISGetLocalSize")?;
        check(unsafe { sys::ISGetIndices(self.raw, &mut ptr) }, "ISGetIndices")?;
        let out = if n == 0 { Vec::new() } else { unsafe { std::slice::from_raw_parts(ptr, n as usize) }.to_vec() };
        check(unsafe { sys::ISRestoreIndices(self.raw, &mut ptr) }, "ISRestoreIndices")?;
        Ok(out)
    }

    pub(crate) fn from_raw(_session: &'s PetscSession, raw: sys::IS) -> Self {
        IndexSet { raw, _session: PhantomData }
    }
}

impl Drop for IndexSet<'_> {
    fn drop(&mut self) {
        // SAFETY: owned handle.
        unsafe { sys::ISDestroy(&mut self.raw) };
    }
}

/// Gathers chosen global entries of a distributed vector into a sequential one
/// (each rank fetches the DOFs its elements touch).
pub struct Scatter<'s> {
    raw: sys::VecScatter,
    _session: SessionBorrow<'s>,
}

impl<'s> Scatter<'s> {
    /// Scatter from entries `from_global` of `from` into entries 0..n of the sequential `to`.
    pub fn gather(session: &'s PetscSession, from: &Vector<'s>, to: &Vector<'s>, from_global: &[sys::PetscInt]) -> Result<Self> {
        // SAFETY: reads the MPI library's predefined MPI_COMM_SELF handle, a constant static the
        // mpi crate exports once MPI is initialised (the session guarantees it is).
        let self_comm = unsafe { mpi::ffi::RSMPI_COMM_SELF };
        let is_from = IndexSet::general(session, self_comm, from_global)?;
        let mut raw = std::ptr::null_mut();
        // SAFETY: NULL `to` index set means the whole of `to`, in order.
        check(unsafe { sys::VecScatterCreate(from.raw(), is_from.raw, to.raw(), std::ptr::null_mut(), &mut raw) }, "VecScatterCreate")?;
        Ok(Scatter { raw, _session: PhantomData })
    }

    /// Collective: copies the selected entries of `from` into `to`.
    pub fn forward(&self, from: &impl VecOps, to: &mut Vector<'_>) -> Result<()> {
        // SAFETY: handles valid and matching those the scatter was built for.
        unsafe {
            check(sys::VecScatterBegin(self.raw, from.raw(), to.raw(), sys::InsertMode_INSERT_VALUES, sys::ScatterMode_SCATTER_FORWARD), "VecScatterBegin")?;
            check(sys::VecScatterEnd(self.raw, from.raw(), to.raw(), sys::InsertMode_INSERT_VALUES, sys::ScatterMode_SCATTER_FORWARD), "VecScatterEnd")
        }
    }
}

impl Scatter<'_> {
    /// Collective: adds the entries of the sequential `local` (the `to` of the scatter) into
    /// the global entries they were gathered from (the reverse scatter, ADD_VALUES), each
    /// rank's contributions to any rank's entries. The communication pattern is the forward
    /// one's, known in advance, unlike VecSetValues' stash.
    pub fn add_back(&self, local: &Vector<'_>, to: &mut impl VecOps) -> Result<()> {
        // SAFETY: handles valid and matching those the scatter was built for (reversed).
        unsafe {
            check(sys::VecScatterBegin(self.raw, local.raw(), to.raw(), sys::InsertMode_ADD_VALUES, sys::ScatterMode_SCATTER_REVERSE), "VecScatterBegin")?;
            check(sys::VecScatterEnd(self.raw, local.raw(), to.raw(), sys::InsertMode_ADD_VALUES, sys::ScatterMode_SCATTER_REVERSE), "VecScatterEnd")
        }
    }
}

impl Drop for Scatter<'_> {
    fn drop(&mut self) {
        // SAFETY: owned handle.
        unsafe { sys::VecScatterDestroy(&mut self.raw) };
    }
}

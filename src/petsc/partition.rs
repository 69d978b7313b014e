//! Graph partitioning through PETSc's MatPartitioning (ptscotch by default, overridable with
//! `-mat_partitioning_type`).

use super::{check, sys, to_petsc_int, Comm, IndexSet, PetscSession};
use crate::error::Result;

/// Partitions a distributed graph into `parts` parts. This rank holds rows `first_row..` of the
/// graph in CSR form (`offsets`, global `neighbours`, no self-loops) and, optionally, the
/// weight of each local row (balanced across the parts). Returns the part of each local row.
pub fn partition_graph(
    session: &PetscSession,
    comm: Comm,
    total_rows: usize,
    offsets: &[usize],
    neighbours: &[usize],
    weights: Option<&[u32]>,
    parts: usize,
) -> Result<Vec<usize>> {
    let local_rows = offsets.len() - 1;
    // MatCreateMPIAdj takes ownership of i and j and frees them with PetscFree: they must come
    // from PetscMalloc.
    let i = petsc_malloc_ints(offsets.iter().map(|&o| o as sys::PetscInt))?;
    let j = petsc_malloc_ints(neighbours.iter().map(|&n| n as sys::PetscInt))?;
    let mut adj = std::ptr::null_mut();
    // SAFETY: i has local_rows + 1 entries, j has offsets[last]; ownership passes to the Mat.
    check(
        unsafe { sys::MatCreateMPIAdj(comm, to_petsc_int(local_rows)?, to_petsc_int(total_rows)?, i, j, std::ptr::null_mut(), &mut adj) },
        "MatCreateMPIAdj",
    )?;
    let mut part = std::ptr::null_mut();
    let mut is_raw = std::ptr::null_mut();
    let result = (|| -> Result<Vec<usize>> {
        // SAFETY: adj and part are valid handles for the duration of this closure.
        unsafe {
            check(sys::MatPartitioningCreate(comm, &mut part), "MatPartitioningCreate")?;
            check(sys::MatPartitioningSetAdjacency(part, adj), "MatPartitioningSetAdjacency")?;
            check(sys::MatPartitioningSetNParts(part, to_petsc_int(parts)?), "MatPartitioningSetNParts")?;
            if let Some(w) = weights {
                // the array passes to PETSc, which frees it with the partitioning
                let w = petsc_malloc_ints(w.iter().map(|&v| v as sys::PetscInt))?;
                check(sys::MatPartitioningSetVertexWeights(part, w), "MatPartitioningSetVertexWeights")?;
            }
            if parts > 1 {
                check(sys::MatPartitioningSetType(part, c"ptscotch".as_ptr()), "MatPartitioningSetType")?;
            }
            check(sys::MatPartitioningSetFromOptions(part), "MatPartitioningSetFromOptions")?;
            check(sys::MatPartitioningApply(part, &mut is_raw), "MatPartitioningApply")?;
        }
        let is = IndexSet::from_raw(session, is_raw);
        Ok(is.to_vec()?.into_iter().map(|p| p as usize).collect())
    })();
    // SAFETY: both handles were created above (or are NULL, which Destroy accepts).
    unsafe {
        sys::MatPartitioningDestroy(&mut part);
        sys::MatDestroy(&mut adj);
    }
    result
}

fn petsc_malloc_ints(values: impl ExactSizeIterator<Item = sys::PetscInt>) -> Result<*mut sys::PetscInt> {
    let n = values.len().max(1);
    let mut ptr: *mut sys::PetscInt = std::ptr::null_mut();
    // SAFETY: PetscMallocA(1, clear, line, func, file, bytes, &ptr) is what PetscMalloc1 expands to.
    check(
        unsafe {
            sys::PetscMallocA(
                1,
                sys::PetscBool_PETSC_FALSE,
                line!() as i32,
                c"partition_graph".as_ptr(),
                c"partition.rs".as_ptr(),
                n * std::mem::size_of::<sys::PetscInt>(),
                &mut ptr as *mut *mut sys::PetscInt as *mut std::ffi::c_void,
            )
        },
        "PetscMallocA",
    )?;
    for (k, v) in values.enumerate() {
        // SAFETY: k < n entries were allocated just above.
        unsafe { *ptr.add(k) = v };
    }
    Ok(ptr)
}

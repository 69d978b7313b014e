//! Why a linear solve failed, in words: MUMPS's INFOG(1) and INFOG(2) after a failed
//! factorisation (MUMPS 5.5 users' guide, section "Error diagnostics"), with what to do.

use crate::error::Result;
use crate::petsc::{check, sys};
use std::ffi::CStr;

/// A failed factorisation: what MUMPS said, and whether a smaller increment can help (a
/// singular tangent may become regular, and a workspace that the pivots of one matrix's values
/// outgrew may do for another's; a matrix too large for the memory stays as large).
#[derive(Clone, Debug, PartialEq)]
pub struct FactorFailure {
    pub text: String,
    pub retry_may_help: bool,
}

/// MUMPS's errors about the machine's memory or the cap on it, not about the matrix's values
/// (its workspace too small, -8, -9, -11, -12, -14, -15, -17, -20, is the estimate of the
/// analysis outgrown by the pivots the values needed: a near-singular tangent's, at collapse).
fn memory_error(infog1: i64) -> bool {
    matches!(infog1, -5 | -7 | -13 | -19)
}

/// The sentence for MUMPS's error `infog1` (negative) with its detail `infog2`.
pub fn mumps_error(infog1: i64, infog2: i64) -> String {
    let what = match infog1 {
        -6 | -10 => {
            "the tangent matrix is singular: something is free to move (a missing boundary condition, a body only open contact holds) or has lost its stiffness"
        }
        -5 | -7 | -13 => "MUMPS could not allocate its workspace (the machine's memory)",
        -8 | -9 | -11 | -12 | -14 | -15 | -17 | -20 => {
            "MUMPS's workspace was too small: raise its relaxation, e.g. -mat_mumps_icntl_14 50 (per cent; default 20)"
        }
        -19 => "MUMPS's workspace exceeds the memory allowed by -mat_mumps_icntl_23",
        _ => "see the MUMPS users' guide, \"Error diagnostics\"",
    };
    format!("MUMPS reports INFOG(1) = {infog1}, INFOG(2) = {infog2}: {what}")
}

/// Collective on the KSP's matrix: MUMPS's diagnosis of the last factorisation of `ksp`'s
/// preconditioner, when that is MUMPS's LU or Cholesky and it failed; None otherwise (another
/// solver, or a Krylov method that did not converge).
///
/// # Safety
/// `ksp` must be a valid KSP handle.
pub unsafe fn mumps_failure(ksp: sys::KSP) -> Result<Option<FactorFailure>> {
    let mut pc = std::ptr::null_mut();
    // SAFETY: `ksp` is valid (the caller's contract); `pc` is a local out-pointer.
    check(unsafe { sys::KSPGetPC(ksp, &mut pc) }, "KSPGetPC")?;
    let mut pc_type: sys::PCType = std::ptr::null();
    // SAFETY: `pc` is the KSP's own preconditioner, valid while `ksp` is.
    check(unsafe { sys::PCGetType(pc, &mut pc_type) }, "PCGetType")?;
    // SAFETY: a non-null type name PETSc returns is a NUL-terminated string it owns.
    let is = |p: *const std::ffi::c_char, name: &str| !p.is_null() && unsafe { CStr::from_ptr(p) }.to_str().is_ok_and(|s| s == name);
    if !(is(pc_type, "lu") || is(pc_type, "cholesky")) {
        return Ok(None);
    }
    let mut solver: sys::MatSolverType = std::ptr::null();
    // SAFETY: `pc` is an LU or Cholesky preconditioner (checked above), valid while `ksp` is.
    check(unsafe { sys::PCFactorGetMatSolverType(pc, &mut solver) }, "PCFactorGetMatSolverType")?;
    if !is(solver, "mumps") {
        return Ok(None);
    }
    let mut factor = std::ptr::null_mut();
    // SAFETY: as above; `factor` is a local out-pointer.
    check(unsafe { sys::PCFactorGetMatrix(pc, &mut factor) }, "PCFactorGetMatrix")?;
    let (mut infog1, mut infog2): (sys::PetscInt, sys::PetscInt) = (0, 0);
    // SAFETY: `factor` is MUMPS's factored matrix (the solver checked above); the outs are locals.
    check(unsafe { sys::MatMumpsGetInfog(factor, 1, &mut infog1) }, "MatMumpsGetInfog")?;
    // SAFETY: as the line before.
    check(unsafe { sys::MatMumpsGetInfog(factor, 2, &mut infog2) }, "MatMumpsGetInfog")?;
    let (infog1, infog2) = (infog1 as i64, infog2 as i64);
    Ok((infog1 < 0).then(|| FactorFailure { text: mumps_error(infog1, infog2), retry_may_help: !memory_error(infog1) }))
}

#[cfg(test)]
mod tests {
    use super::mumps_error;

    #[test]
    fn each_error_class_says_what_to_do() {
        assert!(mumps_error(-10, 0).contains("singular"));
        assert!(mumps_error(-9, 1234).contains("-mat_mumps_icntl_14") && mumps_error(-9, 1234).contains("INFOG(2) = 1234"));
        assert!(mumps_error(-19, 5).contains("-mat_mumps_icntl_23"));
        assert!(mumps_error(-99, 0).contains("Error diagnostics"));
        // the machine's memory and its cap stay; a workspace the values' pivots outgrew, a
        // singular tangent may change with a smaller increment
        assert!(super::memory_error(-13) && super::memory_error(-19) && !super::memory_error(-9) && !super::memory_error(-10) && !super::memory_error(-6));
    }
}

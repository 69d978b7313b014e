//! SLEPc's eigensolver (EPS) over two assembled matrices: the generalised problem
//! A x = lambda B x, the eigenvalues nearest a target by shift-and-invert with Krylov-Schur, the
//! shifted operator A - sigma B factorised by MUMPS (as the SNES's solves are). `-eps_*` and
//! `-st_*` options given to the session override these settings (EPSSetFromOptions).

use super::{check, sys, MatOps, PetscSession, SessionBorrow, VecOps, Vector};
use crate::error::{Error, Result};
use std::marker::PhantomData;

/// The pencil's symmetry: `Hermitian` (A symmetric, B symmetric positive (semi)definite: a
/// vibration problem) or `General` (a buckling problem with a follower load's unsymmetric
/// stiffness, or B indefinite).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pencil {
    Hermitian,
    General,
}

/// One converged eigenpair: the eigenvalue (its imaginary part, 0 for a real one), this rank's
/// part of the eigenvector (real part, the matrices' row layout) and its relative residual
/// ||A x - lambda B x|| / (|lambda| ||x||) as SLEPc computes it.
#[derive(Clone, Debug, PartialEq)]
pub struct Eigenpair {
    pub value: f64,
    pub imaginary: f64,
    pub vector: Vec<f64>,
    pub error: f64,
}

/// An EPS object, destroyed on drop.
struct Eps<'s> {
    raw: sys::EPS,
    _session: SessionBorrow<'s>,
}

impl Drop for Eps<'_> {
    fn drop(&mut self) {
        // SAFETY: owned handle; EPSDestroy nulls it. Errors cannot be reported from drop.
        unsafe { sys::EPSDestroy(&mut self.raw) };
    }
}

/// An EPS on the session's communicator set up as the module says (Krylov-Schur, shift and
/// invert about `target`, MUMPS), then from the options database.
fn configured(session: &PetscSession, pencil: Pencil, nev: sys::PetscInt, target: f64) -> Result<Eps<'_>> {
    let mut eps = Eps { raw: std::ptr::null_mut(), _session: PhantomData };
    let kind = match pencil {
        Pencil::Hermitian => sys::EPSProblemType_EPS_GHEP,
        Pencil::General => sys::EPSProblemType_EPS_GNHEP,
    };
    // SAFETY: a fresh EPS on the session's communicator, owned by `eps` (destroyed on drop);
    // the ST and its KSP and PC are borrowed from the EPS, not owned.
    unsafe {
        check(sys::EPSCreate(session.comm(), &mut eps.raw), "EPSCreate")?;
        check(sys::EPSSetProblemType(eps.raw, kind), "EPSSetProblemType")?;
        check(sys::EPSSetType(eps.raw, c"krylovschur".as_ptr()), "EPSSetType")?;
        // PETSC_DEFAULT (-2) for the subspace sizes: SLEPc's choice for nev
        check(sys::EPSSetDimensions(eps.raw, nev, -2, -2), "EPSSetDimensions")?;
        check(sys::EPSSetTarget(eps.raw, target), "EPSSetTarget")?;
        check(sys::EPSSetWhichEigenpairs(eps.raw, sys::EPSWhich_EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs")?;
        let mut st = std::ptr::null_mut();
        check(sys::EPSGetST(eps.raw, &mut st), "EPSGetST")?;
        check(sys::STSetType(st, c"sinvert".as_ptr()), "STSetType")?;
        let mut ksp = std::ptr::null_mut();
        check(sys::STGetKSP(st, &mut ksp), "STGetKSP")?;
        check(sys::KSPSetType(ksp, c"preonly".as_ptr()), "KSPSetType")?;
        let mut pc = std::ptr::null_mut();
        check(sys::KSPGetPC(ksp, &mut pc), "KSPGetPC")?;
        check(sys::PCSetType(pc, c"lu".as_ptr()), "PCSetType")?;
        check(sys::PCFactorSetMatSolverType(pc, c"mumps".as_ptr()), "PCFactorSetMatSolverType")?;
        check(sys::EPSSetFromOptions(eps.raw), "EPSSetFromOptions")?;
    }
    Ok(eps)
}

/// Reads the `-eps_*` and `-st_*` options into an eigensolver set up as the solves' are, so
/// that a bad one (an unknown type, a tolerance <= 0) is refused as bad input before a run
/// with eigenvalue steps writes anything (collective).
pub fn check_options(session: &PetscSession) -> Result<()> {
    configured(session, Pencil::General, 1, 0.0).map(drop).map_err(|e| match e {
        Error::Petsc { message, .. } => Error::input(format!("SLEPc options: {message} (`-- -help` lists what each option takes)")),
        e => e,
    })
}

/// The `count` eigenpairs of A x = lambda B x nearest `target` (fewer if fewer converge;
/// collective). `a` and `b` share their row layout, `local_rows` of them on this rank.
pub fn nearest(
    session: &PetscSession,
    a: &impl MatOps,
    b: &impl MatOps,
    local_rows: usize,
    pencil: Pencil,
    count: usize,
    target: f64,
) -> Result<Vec<Eigenpair>> {
    let nev = super::to_petsc_int(count.max(1))?;
    let eps = configured(session, pencil, nev, target)?;
    // SAFETY: a configured EPS; the matrices outlive the solve (they are borrowed for this
    // call) and EPSSetOperators takes its own references to them.
    unsafe {
        check(sys::EPSSetOperators(eps.raw, a.raw(), b.raw()), "EPSSetOperators")?;
        check(sys::EPSSolve(eps.raw), "EPSSolve")?;
    }
    let mut converged: sys::PetscInt = 0;
    let mut reason: sys::EPSConvergedReason = 0;
    // SAFETY: solved EPS, out-pointers to locals.
    unsafe {
        check(sys::EPSGetConverged(eps.raw, &mut converged), "EPSGetConverged")?;
        check(sys::EPSGetConvergedReason(eps.raw, &mut reason), "EPSGetConvergedReason")?;
    }
    if reason < 0 {
        return Err(Error::NotConverged {
            step: "eigenvalues".into(),
            load_factor: 1.0,
            reason: format!("SLEPc's eigensolver stopped (EPSConvergedReason {reason}) with {converged} of {count} eigenpairs; raise -eps_max_it"),
        });
    }
    let (mut xr, mut xi) = (Vector::mpi(session, session.comm(), local_rows)?, Vector::mpi(session, session.comm(), local_rows)?);
    let mut out = Vec::new();
    for i in 0..converged.min(nev) {
        let (mut kr, mut ki, mut error) = (0.0, 0.0, 0.0);
        // SAFETY: i < the converged count; the vectors have the matrices' row layout.
        unsafe {
            check(sys::EPSGetEigenpair(eps.raw, i, &mut kr, &mut ki, xr.raw(), xi.raw()), "EPSGetEigenpair")?;
            check(sys::EPSComputeError(eps.raw, i, sys::EPSErrorType_EPS_ERROR_RELATIVE, &mut error), "EPSComputeError")?;
        }
        out.push(Eigenpair { value: kr, imaginary: ki, vector: xr.read()?.to_vec(), error });
        xr.set_all(0.0)?;
        xi.set_all(0.0)?;
    }
    Ok(out)
}

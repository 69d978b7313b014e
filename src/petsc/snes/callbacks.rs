//! The C callbacks SNES calls: residual, Jacobian and convergence test, each a generic
//! trampoline over the caller's problem (the context [`Snes::solve`](super::Snes::solve) sets),
//! run under `catch_unwind` with the outcome agreed across ranks.

use super::field_convergence::{field_bounds, field_converged, FieldRatios, ForceAverage, IterateMeasures};
use super::NonlinearProblem;
use crate::error::{Error, Result};
use crate::petsc::{check, sys, MatrixView, VecOps, VectorView};
use mpi::collective::SystemOperation;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::ffi::c_void;
use std::panic::{catch_unwind, AssertUnwindSafe};

pub(super) struct CallbackContext<'p, P> {
    pub problem: &'p mut P,
    pub world: &'p SimpleCommunicator,
    pub failure: Option<Error>,
    /// ||F|| at the start and at the previous iterate (convergence test).
    pub first_norm: f64,
    /// The round-off floor at the first iterate.
    pub first_floor: f64,
    pub previous_norm: f64,
    /// The field test's state, when it judges this solve.
    pub field: Option<FieldContext>,
    /// Print a line per iteration (rank 0): the test's measures against their bounds.
    pub monitor: bool,
}

/// What the field test keeps through a solve; the vectors are owned by `Snes::solve`.
pub(super) struct FieldContext {
    pub ratios: FieldRatios,
    pub average: ForceAverage,
    pub previous: sys::Vec,
    pub work: sys::Vec,
    pub start: sys::Vec,
    /// r_max of every iterate so far.
    pub residuals: Vec<f64>,
    /// q-bar of the last iterate judged.
    pub last_average_force: f64,
}

impl FieldContext {
    /// Judges iterate `it` (collective: norms and the force average are global).
    fn judge<P: NonlinearProblem>(&mut self, snes: sys::SNES, it: usize, problem: &P, world: &SimpleCommunicator, monitor: bool) -> Result<bool> {
        let (mut x, mut f) = (std::ptr::null_mut(), std::ptr::null_mut());
        // SAFETY: valid SNES inside its solve; the vectors are borrowed from it.
        unsafe {
            check(sys::SNESGetSolution(snes, &mut x), "SNESGetSolution")?;
            check(sys::SNESGetFunction(snes, &mut f, std::ptr::null_mut(), std::ptr::null_mut()), "SNESGetFunction")?;
        }
        let (x, f) = (VectorView::from_raw(x), VectorView::from_raw(f));
        let (mut previous, mut work, start) = (VectorView::from_raw(self.previous), VectorView::from_raw(self.work), VectorView::from_raw(self.start));
        let residual_max = f.norm_max()?;
        let say = monitor && world.rank() == 0;
        let verdict = if it == 0 {
            if say {
                println!("    newton {it:>2}  r_max {residual_max:.3e} {}", problem.force_unit());
            }
            false
        } else {
            work.difference(&x, &previous)?;
            let correction_max = work.norm_max()?;
            work.difference(&x, &start)?;
            let increment_max = work.norm_max()?;
            let local = problem.force_sums();
            let mut global = [0.0; 2];
            world.all_reduce_into(&local[..], &mut global[..], SystemOperation::sum());
            let average_force = if global[1] > 0.0 { global[0] / global[1] } else { 0.0 };
            self.last_average_force = average_force;
            let m = IterateMeasures { residual_max, correction_max, increment_max, model_size: problem.model_size(), average_force };
            let verdict = field_converged(&self.ratios, it, &m, self.average.with(average_force), &self.residuals);
            if say {
                let (residual_bound, correction_bound, _) = field_bounds(&self.ratios, it, &m, self.average.with(average_force));
                println!(
                    "    newton {it:>2}  r_max {residual_max:.3e} {} (bound {residual_bound:.3e})  c_max {correction_max:.3e} mm (bound {correction_bound:.3e}){}",
                    problem.force_unit(),
                    if verdict { "  converged" } else { "" }
                );
            }
            verdict
        };
        self.residuals.push(residual_max);
        previous.copy_from(&x)?;
        Ok(verdict)
    }
}

/// Outcome codes agreed across ranks; the largest wins.
const OK: i32 = 0;
const DOMAIN: i32 = 1;
const FAILED: i32 = 2;
/// PETSC_ERR_USER: what a callback returns to make SNESSolve stop with an error.
const ERR_USER: sys::PetscErrorCode = 83;

/// Runs a callback body under catch_unwind, agrees on the outcome across ranks and turns it
/// into the code PETSc expects.
fn guarded<P>(snes: sys::SNES, ctx: *mut c_void, body: impl FnOnce(&mut P) -> Result<()>) -> sys::PetscErrorCode {
    if ctx.is_null() {
        return ERR_USER;
    }
    // SAFETY: ctx was set by Snes::solve to a CallbackContext<P> that outlives SNESSolve, and
    // PETSc calls back on the solving thread only, so this is the only live reference.
    let ctx = unsafe { &mut *(ctx as *mut CallbackContext<'_, P>) };
    let outcome = catch_unwind(AssertUnwindSafe(|| body(ctx.problem)));
    let local = match outcome {
        Ok(Ok(())) => OK,
        Ok(Err(Error::Domain(msg))) => {
            ctx.failure.get_or_insert(Error::Domain(msg));
            DOMAIN
        }
        Ok(Err(e)) => {
            ctx.failure = Some(e);
            FAILED
        }
        Err(panic) => {
            let msg = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            ctx.failure = Some(Error::Panic(msg));
            FAILED
        }
    };
    let mut global = local;
    // every rank of the SNES's communicator runs this callback, so the reduction matches
    ctx.world.all_reduce_into(&local, &mut global, SystemOperation::max());
    match global {
        OK => 0,
        DOMAIN => {
            // A domain error is recoverable (the caller cuts the increment back): clear it.
            if matches!(ctx.failure, Some(Error::Domain(_))) {
                ctx.failure = None;
            }
            // SAFETY: valid SNES handle passed by PETSc.
            unsafe { sys::SNESSetFunctionDomainError(snes) };
            0
        }
        _ => {
            if ctx.failure.is_none() {
                ctx.failure = Some(Error::Mpi("a callback failed on another rank".into()));
            }
            ERR_USER
        }
    }
}

pub(super) unsafe extern "C" fn residual_trampoline<P: NonlinearProblem>(snes: sys::SNES, x: sys::Vec, f: sys::Vec, ctx: *mut c_void) -> sys::PetscErrorCode {
    guarded::<P>(snes, ctx, |p| p.residual(&VectorView::from_raw(x), &mut VectorView::from_raw(f)))
}

/// Relative residual below which a Newton step that no longer halves ||F|| means the
/// iteration has reached round-off (typically the linear solve's, with a stiff penalty).
const STAGNATION_RTOL: f64 = 1e-7;

/// The round-off floor is only accepted once ||F|| has dropped this far below ||F_0||, or
/// while the floor has grown less than this factor since the first iterate.
const FLOOR_GUARD_RTOL: f64 = 1e-4;
const FLOOR_GROWTH: f64 = 2.0;

/// PETSc's default test, plus two ways to recognise that the residual cannot go lower:
/// ||F|| at the round-off floor the problem reports (agreed across ranks: every rank runs the
/// test), or ||F|| below STAGNATION_RTOL ||F_0|| and no longer halving.
pub(super) unsafe extern "C" fn convergence_trampoline<P: NonlinearProblem>(
    snes: sys::SNES,
    it: sys::PetscInt,
    xnorm: f64,
    snorm: f64,
    fnorm: f64,
    reason: *mut sys::SNESConvergedReason,
    ctx: *mut c_void,
) -> sys::PetscErrorCode {
    // SAFETY: PETSc passes a valid reason pointer; the default test takes no context.
    let code = unsafe { sys::SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, std::ptr::null_mut()) };
    if code != 0 || ctx.is_null() {
        return code;
    }
    // SAFETY: ctx is the CallbackContext set by Snes::solve (see `guarded`).
    let ctx = unsafe { &mut *(ctx as *mut CallbackContext<'_, P>) };
    if let Some(field) = ctx.field.as_mut() {
        // SAFETY: PETSc passes a valid reason pointer for the duration of the call.
        let open = unsafe { *reason == sys::SNESConvergedReason_SNES_CONVERGED_ITERATING || *reason == sys::SNESConvergedReason_SNES_DIVERGED_MAX_IT };
        let problem = &*ctx.problem;
        let monitor = ctx.monitor;
        match catch_unwind(AssertUnwindSafe(|| field.judge(snes, it as usize, problem, ctx.world, monitor))) {
            Ok(Ok(true)) if open => {
                // SAFETY: as above.
                unsafe { *reason = sys::SNESConvergedReason_SNES_CONVERGED_FNORM_ABS };
            }
            Ok(Ok(_)) => {}
            Ok(Err(e)) => {
                ctx.failure = Some(e);
                return ERR_USER;
            }
            Err(_) => {
                ctx.failure = Some(Error::Panic("the field convergence test panicked".into()));
                return ERR_USER;
            }
        }
    }
    let local = catch_unwind(AssertUnwindSafe(|| ctx.problem.roundoff_squares())).unwrap_or(0.0);
    let mut global = 0.0f64;
    // every rank runs the convergence test, so the reduction matches; fnorm is global
    ctx.world.all_reduce_into(&local, &mut global, SystemOperation::sum());
    // SAFETY: PETSc passes a valid reason pointer for the duration of the call.
    unsafe {
        if it == 0 {
            ctx.first_norm = fnorm;
            ctx.first_floor = global.sqrt();
            // an increment that adds nothing above round-off (a load held, a step repeated)
            // starts converged; Newton from there only wanders in the round-off (the relative
            // guard below could never be met with F_0 itself at the floor)
            if *reason == sys::SNESConvergedReason_SNES_CONVERGED_ITERATING && fnorm <= global.sqrt() {
                *reason = sys::SNESConvergedReason_SNES_CONVERGED_FNORM_ABS;
            }
        } else if *reason == sys::SNESConvergedReason_SNES_CONVERGED_ITERATING {
            // the floor grows with the displacements: a runaway iterate must not pass for one
            // at round-off, hence the relative guard; or a floor that has not grown, for a
            // start already near it (an extrapolated increment of rigid sliding)
            let floor = global.sqrt();
            let at_floor = fnorm <= floor && (fnorm <= FLOOR_GUARD_RTOL * ctx.first_norm || floor <= FLOOR_GROWTH * ctx.first_floor);
            let stagnated = fnorm <= STAGNATION_RTOL * ctx.first_norm && fnorm > 0.5 * ctx.previous_norm;
            if at_floor || stagnated {
                *reason = sys::SNESConvergedReason_SNES_CONVERGED_FNORM_ABS;
            }
        }
    }
    if ctx.monitor && ctx.field.is_none() && ctx.world.rank() == 0 {
        // the residual test: ||F|| against the start's, and the round-off floor
        println!(
            "    newton {it:>2}  ||F|| {fnorm:.3e} {} ({:.2e} of the start's; round-off floor {:.2e})",
            ctx.problem.force_unit(),
            fnorm / ctx.first_norm,
            global.sqrt()
        );
    }
    ctx.previous_norm = fnorm;
    0
}

pub(super) unsafe extern "C" fn jacobian_trampoline<P: NonlinearProblem>(
    snes: sys::SNES,
    x: sys::Vec,
    a: sys::Mat,
    _p: sys::Mat,
    ctx: *mut c_void,
) -> sys::PetscErrorCode {
    guarded::<P>(snes, ctx, |p| {
        p.jacobian(&VectorView::from_raw(x), &mut MatrixView::from_raw(a))?;
        if p.take_structure_change() {
            // SAFETY: the SNES PETSc is calling back from; every rank refits together.
            unsafe { reset_factorisation(snes) }?;
        }
        Ok(())
    })
}

/// Collective: PCReset on the SNES's preconditioner (the factorisation and its symbolic
/// analysis go; type and options stay), so the next PCSetUp starts from the matrix as it is.
///
/// # Safety
/// `snes` must be a valid SNES handle.
pub(super) unsafe fn reset_factorisation(snes: sys::SNES) -> Result<()> {
    let mut ksp = std::ptr::null_mut();
    let mut pc = std::ptr::null_mut();
    // SAFETY: valid SNES (caller); the KSP and PC are borrowed from it, not owned.
    unsafe {
        check(sys::SNESGetKSP(snes, &mut ksp), "SNESGetKSP")?;
        check(sys::KSPGetPC(ksp, &mut pc), "KSPGetPC")?;
        check(sys::PCReset(pc), "PCReset")
    }
}

//! SNES (Newton with line search) and its residual/Jacobian callbacks.
//!
//! Callbacks go through generic trampolines whose context is a typed `&mut` to the caller's
//! problem, set just before SNESSolve: no global state. Each trampoline runs inside
//! `catch_unwind` so a panic never unwinds into C; an error or panic is stashed and returned
//! by [`Snes::solve`]. The outcome of every callback is agreed across ranks (MPI max) so a
//! failure on one rank makes all ranks take the same path instead of deadlocking.

mod callbacks;
mod factor_failure;
pub use factor_failure::FactorFailure;
mod field_convergence;

use super::{check, linesearch, sys, Comm, MatOps, Matrix, MatrixView, PetscSession, SessionBorrow, VecOps, Vector, VectorView};
use crate::error::{Error, Result};
use callbacks::{convergence_trampoline, jacobian_trampoline, reset_factorisation, residual_trampoline, CallbackContext, FieldContext};
pub use field_convergence::FieldRatios;
use field_convergence::ForceAverage;
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::ffi::{c_void, CStr};
use std::marker::PhantomData;

/// What a nonlinear problem provides to SNES. Implementations must be collective-safe:
/// every rank is called, and each adds its own contributions.
pub trait NonlinearProblem {
    /// F(x) into `f` (global, assembled by the callee).
    fn residual(&mut self, x: &VectorView<'_>, f: &mut VectorView<'_>) -> Result<()>;
    /// dF/dx at `x` into `jacobian` (assembled by the callee).
    fn jacobian(&mut self, x: &VectorView<'_>, jacobian: &mut MatrixView<'_>) -> Result<()>;
    /// This rank's part of the squared round-off floor of the last residual: the sum over the
    /// assembled contributions of (size of the numbers that cancelled in it x machine epsilon)^2.
    /// When ||F|| is down to the floor (summed over ranks), the solve has converged whatever
    /// the relative tolerance asks: it cannot go lower.
    fn roundoff_squares(&self) -> f64 {
        0.0
    }
    /// True (once) after a Jacobian evaluation replaced the matrix's nonzero structure in
    /// place: the factorisation of the old structure is then dropped, since PETSc 3.18 does not
    /// see the change (its nonzero state stays) and would reuse the symbolic analysis.
    fn take_structure_change(&mut self) -> bool {
        false
    }
    /// This rank's sum of the magnitudes of the element (and contact) nodal forces of the last
    /// residual, and how many there are: the field test's average force.
    fn force_sums(&self) -> [f64; 2] {
        [0.0, 0.0]
    }
    /// The model's size in the unknowns' unit (its largest distance from the origin): the
    /// field test's floor on the corrections scales with it (0: CalculiX's absolute floor).
    fn model_size(&self) -> f64 {
        0.0
    }
    /// The unit of the residual's forces, for the monitor's lines.
    fn force_unit(&self) -> &'static str {
        "N/rad"
    }
}

/// Summary of one SNESSolve.
#[derive(Clone, Debug)]
pub struct SolveReport {
    /// SNESConvergedReason: positive converged, negative diverged.
    pub reason: i32,
    pub newton_iterations: usize,
    pub linear_iterations: usize,
    /// ||F|| at each Newton iterate, starting with the initial one.
    pub residual_norms: Vec<f64>,
    /// Why the linear solve failed (DIVERGED_LINEAR_SOLVE), where the solver says.
    pub linear_failure: Option<FactorFailure>,
    /// Why the caller refused a solve PETSc counted as converged (see [`SolveReport::refuse`]).
    pub refused: Option<String>,
}

impl SolveReport {
    pub fn converged(&self) -> bool {
        self.reason > 0 && self.refused.is_none()
    }

    /// Counts a converged solve as failed, for a reason the convergence tests cannot see.
    pub fn refuse(&mut self, why: String) {
        self.refused = Some(why);
    }

    /// The reason's name, with the linear solver's diagnosis where it failed.
    pub fn describe(&self) -> String {
        match (&self.refused, &self.linear_failure) {
            (Some(why), _) => why.clone(),
            (None, Some(why)) => format!("{} ({})", self.reason_name(), why.text),
            (None, None) => self.reason_name().to_string(),
        }
    }

    /// Whether a smaller increment may converge: not after the linear solver ran out of memory.
    pub fn retry_may_help(&self) -> bool {
        self.linear_failure.as_ref().is_none_or(|f| f.retry_may_help)
    }

    /// PETSc's name for the converged reason.
    pub fn reason_name(&self) -> &'static str {
        match self.reason {
            2 => "CONVERGED_FNORM_ABS",
            3 => "CONVERGED_FNORM_RELATIVE",
            4 => "CONVERGED_SNORM_RELATIVE",
            5 => "CONVERGED_ITS",
            -1 => "DIVERGED_FUNCTION_DOMAIN",
            -2 => "DIVERGED_FUNCTION_COUNT",
            -3 => "DIVERGED_LINEAR_SOLVE",
            -4 => "DIVERGED_FNORM_NAN",
            -5 => "DIVERGED_MAX_IT",
            -6 => "DIVERGED_LINE_SEARCH",
            -7 => "DIVERGED_INNER",
            -8 => "DIVERGED_LOCAL_MIN",
            -9 => "DIVERGED_DTOL",
            -10 => "DIVERGED_JACOBIAN_DOMAIN",
            -11 => "DIVERGED_TR_DELTA",
            _ => "UNKNOWN_REASON",
        }
    }
}

const HISTORY_LEN: usize = 1000;

/// What the options database refused (an unknown type, a value that is no number) is bad
/// input, named in PETSc's own words.
fn option_error(e: Error) -> Error {
    match e {
        Error::Petsc { message, .. } => Error::input(format!("PETSc options: {message} (`-- -help` lists what each option takes)")),
        e => e,
    }
}

/// An owned SNES configured as Newton + line search (cp) + preonly/LU(MUMPS); every choice
/// can be overridden from the options database (`-snes_*`, `-ksp_*`, `-pc_*`).
pub struct Snes<'s> {
    raw: sys::SNES,
    /// The communicator the SNES lives on (the session's world).
    world: &'s SimpleCommunicator,
    // PETSc writes the residual history into these; boxed so the addresses never move.
    history: Box<[f64]>,
    history_its: Box<[sys::PetscInt]>,
    /// The field convergence test, when it judges the solves (besides the residual test).
    field: Option<FieldRatios>,
    /// Its time-averaged force over the increments accepted.
    force_average: ForceAverage,
    /// The average force of the last converged solve (0 without the field test).
    last_average_force: f64,
    /// The unknowns at the start of the increment (the field test's Delta u).
    increment_start: Option<Vector<'s>>,
    /// A line per Newton iteration on rank 0: the convergence test's measures and bounds.
    monitor: bool,
    /// Whether the line search is PETSc's `l2`, as after a failed attempt (else slideline's
    /// shell); None when `-snes_linesearch_type` chose it.
    after_failure: Option<bool>,
    _session: SessionBorrow<'s>,
}

/// With the default `-ksp_type preonly` a preconditioner other than an exact factorisation
/// would be applied once instead of solving: on one rank Newton then fails to converge, on
/// two PETSc may refuse the type. Refused up front, the same on any number of ranks.
fn check_preconditioner_alone(options: &[String]) -> Result<()> {
    let value = |name: &str| options.iter().rposition(|o| o == name).and_then(|k| options.get(k + 1));
    let preonly = value("-ksp_type").is_none_or(|k| k == "preonly");
    match value("-pc_type") {
        Some(pc) if !["lu", "cholesky", "redundant"].contains(&pc.as_str()) && preonly => Err(Error::input(format!(
            "-pc_type {pc} with slideline's default -ksp_type preonly applies the preconditioner once instead of solving: add a Krylov method (e.g. -ksp_type gmres), or use -pc_type lu"
        ))),
        _ => Ok(()),
    }
}

impl<'s> Snes<'s> {
    /// A SNES on the session's world communicator.
    pub fn new(session: &'s PetscSession) -> Result<Self> {
        let world = session.world();
        let comm: Comm = world.as_raw();
        let mut raw = std::ptr::null_mut();
        // SAFETY: comm is live; the handle is owned by the returned value.
        check(unsafe { sys::SNESCreate(comm, &mut raw) }, "SNESCreate")?;
        let mut snes = Snes {
            raw,
            world,
            history: vec![0.0; HISTORY_LEN].into_boxed_slice(),
            history_its: vec![0; HISTORY_LEN].into_boxed_slice(),
            field: None,
            force_average: ForceAverage::default(),
            last_average_force: 0.0,
            increment_start: None,
            after_failure: (!session.has_option("-snes_linesearch_type")).then_some(false),
            monitor: false,
            _session: PhantomData,
        };
        snes.configure_defaults(session)?;
        Ok(snes)
    }

    fn configure_defaults(&mut self, session: &PetscSession) -> Result<()> {
        check_preconditioner_alone(session.options())?;
        // SAFETY: valid SNES; the KSP, PC and line search are borrowed from it, not owned.
        unsafe {
            let mut ksp = std::ptr::null_mut();
            check(sys::SNESGetKSP(self.raw, &mut ksp), "SNESGetKSP")?;
            check(sys::KSPSetType(ksp, c"preonly".as_ptr()), "KSPSetType")?;
            let mut pc = std::ptr::null_mut();
            check(sys::KSPGetPC(ksp, &mut pc), "KSPGetPC")?;
            check(sys::PCSetType(pc, c"lu".as_ptr()), "PCSetType")?;
            // MUMPS factorises MPIAIJ on any rank count; only name it when LU stays the PC.
            if !session.has_option("-pc_type") || session.has_option("-pc_factor_mat_solver_type") {
                check(sys::PCFactorSetMatSolverType(pc, c"mumps".as_ptr()), "PCFactorSetMatSolverType")?;
            }
            let mut ls = std::ptr::null_mut();
            check(sys::SNESGetLineSearch(self.raw, &mut ls), "SNESGetLineSearch")?;
            // cp: a secant search on F.d, the slope of the incremental potential that
            // plasticity with associated flow and frictionless penalty contact have. Measured
            // (total Newton iterations / cutbacks): plastic thick cylinder cp 31, basic 32,
            // l2 41, bt fails (the plastic tangent is E/H = 200 times softer than the elastic
            // one, so ||F||_2 is a poor merit function for Armijo); heated, pushed plastic ring
            // cp 25, l2 27, bt 45, basic 186 / 4; Hertz contact cp 30, basic 30, l2 44,
            // bt 143 / 4. slideline's shell is cp without its second residual when the secant
            // keeps the full step (see linesearch.rs). -snes_linesearch_type overrides.
            check(linesearch::install(ls), "SNESLineSearchSetType (shell)")?;
            check(
                sys::SNESSetConvergenceHistory(
                    self.raw,
                    self.history.as_mut_ptr(),
                    self.history_its.as_mut_ptr(),
                    HISTORY_LEN as sys::PetscInt,
                    sys::PetscBool_PETSC_TRUE,
                ),
                "SNESSetConvergenceHistory",
            )?;
        }
        self.apply_options()
    }

    /// Applies the options database (SNESSetFromOptions: what it refuses is bad input), and
    /// refuses a nonlinear solver whose solves slideline's convergence test cannot judge (the
    /// type may come from an options file or PETSC_OPTIONS as well as the command line).
    fn apply_options(&mut self) -> Result<()> {
        let mut kind: sys::SNESType = std::ptr::null();
        // SAFETY: valid handle; SNESGetType points `kind` at the type's NUL-terminated name,
        // owned by the SNES and read before any other call on it.
        let kind = unsafe {
            check(sys::SNESSetFromOptions(self.raw), "SNESSetFromOptions").map_err(option_error)?;
            check(sys::SNESGetType(self.raw, &mut kind), "SNESGetType")?;
            if kind.is_null() {
                String::new()
            } else {
                CStr::from_ptr(kind).to_string_lossy().into_owned()
            }
        };
        if !super::options::JUDGED_SNES_TYPES.contains(&kind.as_str()) {
            return Err(super::options::snes_type_refused(&kind));
        }
        Ok(())
    }

    /// Sets the convergence tolerances, then applies the options database again so
    /// `-snes_atol`, `-snes_rtol`, `-snes_stol`, `-snes_max_it` still win. `None` keeps PETSc's
    /// value. `stol` (step-size test) defaults to 0 here: after a line search has shrunk the
    /// step, a small step says nothing about equilibrium, so convergence is judged on the
    /// residual alone.
    pub fn set_tolerances(&mut self, atol: Option<f64>, rtol: Option<f64>, max_iterations: Option<usize>) -> Result<()> {
        const DEFAULT: f64 = -2.0; // PETSC_DEFAULT
        let maxit = max_iterations.map(|m| m as sys::PetscInt).unwrap_or(-2);
        // SAFETY: valid handle.
        unsafe {
            check(sys::SNESSetTolerances(self.raw, atol.unwrap_or(DEFAULT), rtol.unwrap_or(DEFAULT), 0.0, maxit, -2), "SNESSetTolerances")?;
        }
        self.apply_options()
    }

    /// PETSc's `l2` line search (a secant minimisation of ||F||^2 along the Newton step) for
    /// the solves after a failed attempt (`failed`), else slideline's shell. The shell follows
    /// the slope of an incremental potential, which friction has not: at a stiff tangential
    /// penalty Newton cycles between stick and slip, where `l2` gets through (and going back
    /// to the shell at the next increment fails again). `-snes_linesearch_type` keeps its
    /// choice throughout.
    pub fn search_after_failure(&mut self, failed: bool) -> Result<()> {
        if self.after_failure.is_none_or(|current| current == failed) {
            return Ok(());
        }
        let mut ls = std::ptr::null_mut();
        // SAFETY: valid handle; the line search is the SNES's own.
        unsafe {
            check(sys::SNESGetLineSearch(self.raw, &mut ls), "SNESGetLineSearch")?;
            if failed {
                check(sys::SNESLineSearchSetType(ls, c"l2".as_ptr()), "SNESLineSearchSetType (l2)")?;
            } else {
                check(linesearch::install(ls), "SNESLineSearchSetType (shell)")?;
            }
        }
        self.after_failure = Some(failed);
        Ok(())
    }

    /// Judges the solves by CalculiX's field test as well (a solve converges when either test
    /// passes); `None` leaves the residual test alone.
    pub fn set_field_test(&mut self, ratios: Option<FieldRatios>) {
        self.field = ratios;
    }

    /// Prints a line per Newton iteration on rank 0: the convergence test's measures against
    /// their bounds.
    pub fn set_monitor(&mut self, on: bool) {
        self.monitor = on;
    }

    /// Takes the last converged solve's average force into the step's time average (call once
    /// per accepted increment) and returns it (0 without the field test).
    pub fn accept_increment(&mut self) -> f64 {
        let f = if self.field.is_some() { self.last_average_force } else { 0.0 };
        self.force_average.add(f);
        f
    }

    /// Restores the step's time average from the average forces of its accepted increments
    /// (a restart).
    pub fn restore_force_average(&mut self, accepted: impl IntoIterator<Item = f64>) {
        accepted.into_iter().for_each(|f| self.force_average.add(f));
    }

    /// Records the unknowns at the start of an increment (before its predictor): the field
    /// test measures the increment's displacement from here. Without it, from the solve's
    /// initial guess.
    pub fn mark_increment_start(&mut self, x: &Vector<'s>) -> Result<()> {
        if self.increment_start.is_none() {
            self.increment_start = Some(x.duplicate()?);
        }
        self.increment_start.as_mut().expect("set above").copy_from(x)
    }

    /// Solves J y = b with the SNES's own linear solver (the same KSP, PC and options as the
    /// Newton steps). While J is unchanged since the last solve, the factorization is reused.
    /// Returns false when the linear solver did not converge (a singular J, a failed pivot).
    pub fn linear_solve(&mut self, jacobian: &Matrix<'_>, b: &Vector<'_>, y: &mut Vector<'_>) -> Result<bool> {
        let mut reason: sys::KSPConvergedReason = 0;
        // SAFETY: valid handles; the KSP is borrowed from the SNES, not owned.
        unsafe {
            let mut ksp = std::ptr::null_mut();
            check(sys::SNESGetKSP(self.raw, &mut ksp), "SNESGetKSP")?;
            check(sys::KSPSetOperators(ksp, jacobian.raw(), jacobian.raw()), "KSPSetOperators")?;
            check(sys::KSPSolve(ksp, b.raw(), y.raw()), "KSPSolve")?;
            check(sys::KSPGetConvergedReason(ksp, &mut reason), "KSPGetConvergedReason")?;
        }
        Ok(reason > 0)
    }

    /// MUMPS's diagnosis of the last failed factorisation (None for another solver or none).
    fn linear_failure(&self) -> Result<Option<FactorFailure>> {
        let mut ksp = std::ptr::null_mut();
        // SAFETY: valid SNES handle; the KSP is borrowed from it.
        unsafe {
            check(sys::SNESGetKSP(self.raw, &mut ksp), "SNESGetKSP")?;
            factor_failure::mumps_failure(ksp)
        }
    }

    /// Collective: drops the linear solver's factorisation, so the next solve analyses the
    /// matrix's structure afresh (after it was replaced in place).
    pub fn reset_factorisation(&mut self) -> Result<()> {
        // SAFETY: valid SNES handle.
        unsafe { reset_factorisation(self.raw) }
    }

    /// Solves F(x) = 0 from the initial guess in `x`, using `residual` and `jacobian` as work
    /// storage. A non-converged solve is not an error: read `SolveReport::reason`.
    pub fn solve<P: NonlinearProblem>(
        &mut self,
        problem: &mut P,
        x: &mut Vector<'_>,
        residual: &mut Vector<'_>,
        jacobian: &mut Matrix<'_>,
    ) -> Result<SolveReport> {
        // the field test's work vectors (the previous iterate, a difference) and the start: the
        // marked increment start (unchanged while this solve runs), else a copy of the guess
        let field_vectors = match self.field {
            Some(_) => {
                let guess = match self.increment_start {
                    Some(_) => None,
                    None => Some(x.duplicate().and_then(|mut v| v.copy_from(x).map(|_| v))?),
                };
                Some((x.duplicate()?, x.duplicate()?, guess))
            }
            None => None,
        };
        let field = match (&self.field, &field_vectors) {
            (Some(ratios), Some((previous, work, guess))) => Some(FieldContext {
                ratios: *ratios,
                average: self.force_average,
                previous: previous.raw(),
                work: work.raw(),
                start: guess.as_ref().or(self.increment_start.as_ref()).map(|v| v.raw()).expect("a start"),
                residuals: Vec::new(),
                last_average_force: 0.0,
            }),
            _ => None,
        };
        let mut ctx =
            CallbackContext { problem, world: self.world, failure: None, first_norm: 0.0, first_floor: 0.0, previous_norm: 0.0, field, monitor: self.monitor };
        let ctx_ptr = &mut ctx as *mut CallbackContext<'_, P> as *mut c_void;
        // SAFETY: ctx outlives SNESSolve; the callbacks are cleared again (context NULL) below
        // so PETSc never holds a dangling pointer after this function returns.
        let code = unsafe {
            check(sys::SNESSetFunction(self.raw, residual.raw(), Some(residual_trampoline::<P>), ctx_ptr), "SNESSetFunction")?;
            check(sys::SNESSetJacobian(self.raw, jacobian.raw(), jacobian.raw(), Some(jacobian_trampoline::<P>), ctx_ptr), "SNESSetJacobian")?;
            check(sys::SNESSetConvergenceTest(self.raw, Some(convergence_trampoline::<P>), ctx_ptr, None), "SNESSetConvergenceTest")?;
            sys::SNESSolve(self.raw, std::ptr::null_mut(), x.raw())
        };
        // SAFETY: resetting the contexts to NULL; the function pointers stay but are never
        // called without a new context from the next solve.
        unsafe {
            sys::SNESSetFunction(self.raw, residual.raw(), Some(residual_trampoline::<P>), std::ptr::null_mut());
            sys::SNESSetJacobian(self.raw, jacobian.raw(), jacobian.raw(), Some(jacobian_trampoline::<P>), std::ptr::null_mut());
            sys::SNESSetConvergenceTest(self.raw, Some(sys::SNESConvergedDefault), std::ptr::null_mut(), None);
        }
        if let Some(err) = ctx.failure.take() {
            return Err(err);
        }
        check(code, "SNESSolve")?;
        let report = self.report()?;
        if let (true, Some(field)) = (report.converged(), &ctx.field) {
            self.last_average_force = field.last_average_force;
        }
        drop(field_vectors);
        Ok(report)
    }

    fn report(&self) -> Result<SolveReport> {
        let mut reason: sys::SNESConvergedReason = 0;
        let (mut its, mut lits) = (0, 0);
        let mut hist: *mut f64 = std::ptr::null_mut();
        let mut hist_its: *mut sys::PetscInt = std::ptr::null_mut();
        let mut nhist = 0;
        // SAFETY: valid handle, out-pointers to locals; the history points into self.history.
        unsafe {
            check(sys::SNESGetConvergedReason(self.raw, &mut reason), "SNESGetConvergedReason")?;
            check(sys::SNESGetIterationNumber(self.raw, &mut its), "SNESGetIterationNumber")?;
            check(sys::SNESGetLinearSolveIterations(self.raw, &mut lits), "SNESGetLinearSolveIterations")?;
            check(sys::SNESGetConvergenceHistory(self.raw, &mut hist, &mut hist_its, &mut nhist), "SNESGetConvergenceHistory")?;
        }
        let n = (nhist.max(0) as usize).min(HISTORY_LEN);
        let linear_failure = if reason == sys::SNESConvergedReason_SNES_DIVERGED_LINEAR_SOLVE { self.linear_failure()? } else { None };
        Ok(SolveReport {
            reason: reason as i32,
            newton_iterations: its as usize,
            linear_iterations: lits as usize,
            residual_norms: self.history[..n].to_vec(),
            linear_failure,
            refused: None,
        })
    }
}

impl Drop for Snes<'_> {
    fn drop(&mut self) {
        // SAFETY: owned handle.
        unsafe { sys::SNESDestroy(&mut self.raw) };
    }
}

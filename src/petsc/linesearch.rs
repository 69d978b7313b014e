//! slideline's default line search, a PETSc shell line search: PETSc's critical-point search
//! (`cp`, one secant step on F.y, the slope of the incremental potential along the Newton step)
//! that keeps the full step without a second residual when the secant puts the potential's
//! minimum within `FULL_STEP_BAND` of it.
//!
//! `cp` evaluates the residual twice per Newton iteration: at the full step, for the secant,
//! and again at the step the secant chooses, even when that is the full step to three digits,
//! as it is throughout the quadratic phase of Newton. Skipping the second evaluation there
//! halves the residual work of most iterations and changes the iterates only where the secant
//! would have moved the step by less than the band. `-snes_linesearch_type cp` restores PETSc's.
//!
//! Where a solve stalls (its residual norm has not halved over six iterations), the
//! slope F.y is a poor guide: friction has no potential, and at a stiff tangential penalty the
//! secant takes the same short step at every iteration while ||F|| alternates between two
//! values. From there to the end of that solve each step is PETSc's `l2` step instead (the
//! minimum of the parabola through ||F||^2 at 0, half and the full step), which gets through.

use super::sys;
use std::os::raw::c_void;

/// The full step is kept when the secant's step length is within this of 1.
pub const FULL_STEP_BAND: f64 = 0.1;

/// Halvings of a step that leaves the residual's domain before the line search gives up.
const DOMAIN_HALVINGS: usize = 5;

/// A solve has stalled when, for this many iterations in a row, the residual norm stayed above
/// `STALL_RATIO` of the norm before them.
pub const STALL_WINDOW: usize = 6;
pub const STALL_RATIO: f64 = 0.5;

/// Whether the residual norms of a solve so far (`norms[k]` at its k-th iterate) show a stall:
/// somewhere `STALL_WINDOW` iterates in a row above `STALL_RATIO` of the iterate before them.
/// The predictor's iterate 0 is not a reference: a penalty contact closing in the first
/// Newton step can take ||F|| far above it, and Newton then converges from there. Once true it
/// stays true for the solve (the history only grows), so its remaining steps are all `l2`
/// steps rather than a return to the secant that stalled.
pub fn stalled(norms: &[f64]) -> bool {
    norms.get(1..).is_some_and(|n| n.windows(STALL_WINDOW + 1).any(|w| w[1..].iter().all(|&v| v > STALL_RATIO * w[0])))
}

/// PETSc's `l2` step (one iteration of its secant on d||F||^2/d lambda, as linesearchl2.c):
/// with ||F||^2 equal to `g0`, `gmid`, `g1` at 0, lambda / 2 and lambda, the parabola's
/// stationary point, taken downhill (a concave parabola turns the step round); a step below
/// `steptol` becomes lambda / 2. None keeps lambda (beyond `maxstep`, or not finite).
pub fn l2_step(g0: f64, gmid: f64, g1: f64, lambda: f64, tolerances: &Tolerances) -> Option<f64> {
    let slope = (3.0 * g1 - 4.0 * gmid + g0) / lambda;
    let curvature = 4.0 * (g1 - 2.0 * gmid + g0) / (lambda * lambda);
    let mut next = if curvature > 0.0 { lambda - slope / curvature } else { lambda + slope / curvature };
    if next < tolerances.steptol {
        next = 0.5 * lambda;
    }
    (next.is_finite() && next <= tolerances.maxstep).then_some(next)
}

/// The step length of one secant step on F.y from 0 (slope `fty0`) to `lambda` (slope `fty1`),
/// as PETSc's `cp` computes it (a wrong-signed secant is turned round; a step below `steptol`
/// is reflected), or None to keep `lambda`: where cp keeps it (F.y fell below `rtol` of its
/// start, or the secant is flat, not finite or beyond `maxstep`) and where the secant's step
/// is within the band of it.
pub fn secant_step(fty0: f64, fty1: f64, lambda: f64, tolerances: &Tolerances) -> Option<f64> {
    if (fty1 / fty0).abs() < tolerances.rtol {
        return None;
    }
    let steptol = tolerances.steptol;
    let mut slope = (fty1 - fty0) / lambda;
    if slope > 0.0 {
        slope = -slope;
    }
    let mut next = lambda - fty1 / slope;
    if next < steptol {
        next = lambda + fty1 / slope;
    }
    if !next.is_finite() || next > tolerances.maxstep || (next - lambda).abs() <= FULL_STEP_BAND * lambda {
        return None;
    }
    Some(next)
}

/// The line search's tolerances, as PETSc holds them (-snes_linesearch_minlambda, _maxstep,
/// _rtol, _atol).
#[derive(Clone, Copy, Debug)]
pub struct Tolerances {
    pub steptol: f64,
    pub maxstep: f64,
    pub rtol: f64,
    pub atol: f64,
}

/// Sets the shell line search on `ls` (PETSc's options may still replace it).
///
/// # Safety
/// `ls` must be a valid SNESLineSearch.
pub(super) unsafe fn install(ls: sys::SNESLineSearch) -> sys::PetscErrorCode {
    // SAFETY: `ls` is valid (the caller's contract); the type name is a static C string.
    let code = unsafe { sys::SNESLineSearchSetType(ls, c"shell".as_ptr()) };
    if code != 0 {
        return code;
    }
    // SAFETY: as above; `apply` has the signature PETSc calls, and takes no context.
    unsafe { sys::SNESLineSearchShellSetUserFunc(ls, Some(apply), std::ptr::null_mut()) }
}

/// Runs one PETSc call of [`apply`], returning early with its error code if it fails. Each
/// call site says why its call is sound in a `// SAFETY:` line above it.
macro_rules! petsc_try {
    ($call:expr) => {
        #[allow(clippy::macro_metavars_in_unsafe)]
        let code = unsafe { $call };
        if code != 0 {
            return code;
        }
    };
}

/// The shell's apply: X <- X - lambda Y and F <- F(X), as `cp` leaves them, with the norms.
unsafe extern "C" fn apply(ls: sys::SNESLineSearch, _ctx: *mut c_void) -> sys::PetscErrorCode {
    let null = std::ptr::null_mut;
    let (mut x, mut f, mut y, mut w, mut g) = (null(), null(), null(), null(), null());
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchGetVecs(ls, &mut x, &mut f, &mut y, &mut w, &mut g));
    let mut snes: sys::SNES = std::ptr::null_mut();
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchGetSNES(ls, &mut snes));
    let mut lambda = 0.0;
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchGetLambda(ls, &mut lambda));
    let (mut steptol, mut maxstep, mut rtol, mut atol, mut ltol, mut max_it) = (0.0, 0.0, 0.0, 0.0, 0.0, 0);
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchGetTolerances(ls, &mut steptol, &mut maxstep, &mut rtol, &mut atol, &mut ltol, &mut max_it));
    let tolerances = Tolerances { steptol, maxstep, rtol, atol };
    let (mut xnorm, mut fnorm, mut ynorm) = (0.0, 0.0, 0.0);
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchGetNorms(ls, &mut xnorm, &mut fnorm, &mut ynorm));
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchSetReason(ls, sys::SNESLineSearchReason_SNES_LINESEARCH_SUCCEEDED));
    let mut changed_y = sys::PetscBool_PETSC_FALSE;
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchPreCheck(ls, x, y, &mut changed_y));
    let mut fty0 = 0.0;
    // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
    petsc_try!(sys::VecDot(f, y, &mut fty0));
    // as cp: no slope left along the step means the potential is at its minimum (the
    // residual at round-off), and the solve has converged where it stands
    if fty0.abs() < tolerances.atol * ynorm {
        // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
        return unsafe { sys::SNESSetConvergedReason(snes, sys::SNESConvergedReason_SNES_CONVERGED_FNORM_ABS) };
    }

    // F at the full step (into F: F(X) is not needed again once F.y is known); where the full
    // step leaves the domain (an element inverted: a stiff penalty's first step can throw a
    // contact node through its neighbours), halved until it does not
    let mut domain = sys::PetscBool_PETSC_FALSE;
    for halving in 0..=DOMAIN_HALVINGS {
        // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
        petsc_try!(sys::VecWAXPY(w, -lambda, y, x));
        // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
        petsc_try!(sys::SNESComputeFunction(snes, w, f));
        // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
        petsc_try!(sys::SNESGetFunctionDomainError(snes, &mut domain));
        if domain == sys::PetscBool_PETSC_FALSE {
            break;
        }
        if halving == DOMAIN_HALVINGS {
            // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
            return unsafe { sys::SNESLineSearchSetReason(ls, sys::SNESLineSearchReason_SNES_LINESEARCH_FAILED_DOMAIN) };
        }
        // (SNESComputeFunction clears the flag before it evaluates, PETSc >= 3.17)
        lambda *= 0.5;
    }
    let mut evaluated_at_w = true;
    let (mut hist, mut hist_its, mut nhist): (*mut f64, *mut sys::PetscInt, sys::PetscInt) = (std::ptr::null_mut(), std::ptr::null_mut(), 0);
    // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
    petsc_try!(sys::SNESGetConvergenceHistory(snes, &mut hist, &mut hist_its, &mut nhist));
    // SAFETY: PETSc's history of this solve, `nhist` norms (the array slideline's Snes owns),
    // read before the next iterate is logged into it.
    let norms = if hist.is_null() || nhist <= 0 { &[][..] } else { unsafe { std::slice::from_raw_parts(hist, nhist as usize) } };
    let mut step = None;
    if stalled(norms) {
        // SAFETY: the line search's own vectors and SNES, got above, alive during this callback.
        petsc_try!(l2_trial(snes, [x, f, y, w, g], lambda, fnorm, &tolerances, &mut step));
    }
    let step = match step {
        Some(step) => step,
        None => {
            let mut fty1 = 0.0;
            // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
            petsc_try!(sys::VecDot(f, y, &mut fty1));
            secant_step(fty0, fty1, lambda, &tolerances)
        }
    };
    if let Some(next) = step {
        lambda = next;
        // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
        petsc_try!(sys::VecWAXPY(w, -lambda, y, x));
        evaluated_at_w = false;
    }

    let (mut changed_y, mut changed_w) = (sys::PetscBool_PETSC_FALSE, sys::PetscBool_PETSC_FALSE);
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchPostCheck(ls, x, y, w, &mut changed_y, &mut changed_w));
    if changed_y == sys::PetscBool_PETSC_TRUE {
        // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
        petsc_try!(sys::VecWAXPY(w, -lambda, y, x));
        evaluated_at_w = false;
    }
    if changed_w == sys::PetscBool_PETSC_TRUE {
        evaluated_at_w = false;
    }
    // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
    petsc_try!(sys::VecCopy(w, x));
    if !evaluated_at_w {
        // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
        petsc_try!(sys::SNESComputeFunction(snes, x, f));
        // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
        petsc_try!(sys::SNESGetFunctionDomainError(snes, &mut domain));
        if domain == sys::PetscBool_PETSC_TRUE {
            // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
            return unsafe { sys::SNESLineSearchSetReason(ls, sys::SNESLineSearchReason_SNES_LINESEARCH_FAILED_DOMAIN) };
        }
    }
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchComputeNorms(ls));
    // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
    petsc_try!(sys::SNESLineSearchSetLambda(ls, lambda));
    if lambda <= steptol {
        // SAFETY: `ls` is the line search PETSc is running (valid during this callback); the outs are locals.
        petsc_try!(sys::SNESLineSearchSetReason(ls, sys::SNESLineSearchReason_SNES_LINESEARCH_FAILED_REDUCT));
    }
    0
}

/// The L2 line search's step where Newton stalls (`stalled`): ||F||^2 at the full step (in F)
/// and at half of it (into G) give the parabola's minimum, into `step`; left None where the half
/// step leaves the domain (the secant then), with F evaluated at the full step again so that
/// the half step's domain flag is cleared rather than left for the SNES to read.
///
/// # Safety
/// `snes` and the vectors [X, F, Y, W, G] are those of the line search PETSc is running.
unsafe fn l2_trial(
    snes: sys::SNES,
    [x, f, y, w, g]: [sys::Vec; 5],
    lambda: f64,
    fnorm: f64,
    tolerances: &Tolerances,
    step: &mut Option<Option<f64>>,
) -> sys::PetscErrorCode {
    // ||F||^2 at the full step (in F) and at half of it (into G)
    let (mut full, mut mid, mut domain) = (0.0, 0.0, sys::PetscBool_PETSC_FALSE);
    // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
    petsc_try!(sys::VecNorm(f, sys::NormType_NORM_2, &mut full));
    // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
    petsc_try!(sys::VecWAXPY(w, -0.5 * lambda, y, x));
    // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
    petsc_try!(sys::SNESComputeFunction(snes, w, g));
    // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
    petsc_try!(sys::SNESGetFunctionDomainError(snes, &mut domain));
    // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
    petsc_try!(sys::VecWAXPY(w, -lambda, y, x));
    if domain == sys::PetscBool_PETSC_FALSE {
        // SAFETY: x, f, y, w, g are the line search's own vectors (SNESLineSearchGetVecs), alive while it runs.
        petsc_try!(sys::VecNorm(g, sys::NormType_NORM_2, &mut mid));
        *step = Some(l2_step(fnorm * fnorm, mid * mid, full * full, lambda, tolerances));
    } else {
        // the half step left the domain (the full one did not): back to the secant
        // SAFETY: `snes` owns this line search (SNESLineSearchGetSNES) and outlives the callback; the outs are locals.
        petsc_try!(sys::SNESComputeFunction(snes, w, f));
    }
    0
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: Tolerances = Tolerances { steptol: 1e-8, maxstep: 1e8, rtol: 1e-8, atol: 1e-15 };

    #[test]
    fn the_secant_keeps_a_near_full_step_and_moves_a_poor_one_as_cp_would() {
        // a quadratic potential with its minimum at 1.05: F.y falls linearly to 0 there
        let slope = |m: f64| (1.0, 1.0 - 1.0 / m); // (fty0, fty1) for a minimum at m
        let (a, b) = slope(1.05);
        assert_eq!(secant_step(a, b, 1.0, &T), None);
        // minimum at 0.4 (an overshooting Newton step) and at 2.5 (a timid one)
        for m in [0.4, 2.5] {
            let (a, b) = slope(m);
            let next = secant_step(a, b, 1.0, &T).unwrap();
            assert!((next - m).abs() < 1e-12, "{next} vs {m}");
        }
        // a wrong-signed secant (a concave stretch) is turned round, as cp does
        let next = secant_step(1.0, 3.0, 1.0, &T).unwrap();
        assert!((next - 2.5).abs() < 1e-12, "{next}");
        // beyond the maximum step, or no information: the full step
        let (a, b) = slope(2.5);
        assert_eq!(secant_step(a, b, 1.0, &Tolerances { maxstep: 2.0, ..T }), None);
        assert_eq!(secant_step(1.0, 1.0, 1.0, &T), None);
        assert_eq!(secant_step(f64::NAN, 0.5, 1.0, &T), None);
        // F.y gone below rtol of its start: cp keeps the step whatever the secant says
        assert_eq!(secant_step(1.0, -1e-9, 1.0, &T), None);
    }

    #[test]
    fn l2_step_is_the_minimum_of_the_parabola_through_the_three_norms() {
        // ||F||^2 = (lambda - m)^2 + c along the step: its minimum m whatever c
        for (m, c) in [(0.4, 1.0), (0.9, 0.0), (1.7, 3.0)] {
            let g = |l: f64| (l - m) * (l - m) + c;
            let next = l2_step(g(0.0), g(0.5), g(1.0), 1.0, &T).unwrap();
            assert!((next - m).abs() < 1e-12, "{next} vs {m}");
        }
        // a concave stretch goes downhill: from the top at 0.5 of -(lambda - 0.5)^2 PETSc's
        // rule moves on from the full step by its slope over the curvature (to 1.5)
        let g = |l: f64| 2.0 - (l - 0.5) * (l - 0.5);
        let next = l2_step(g(0.0), g(0.5), g(1.0), 1.0, &T).unwrap();
        assert!((next - 1.5).abs() < 1e-12, "{next}");
        // a minimum behind the start is not taken: half the step instead
        let g = |l: f64| (l + 0.3) * (l + 0.3);
        assert_eq!(l2_step(g(0.0), g(0.5), g(1.0), 1.0, &T), Some(0.5));
        // beyond the maximum step the full step is kept
        let g = |l: f64| (l - 3.0) * (l - 3.0);
        assert_eq!(l2_step(g(0.0), g(0.5), g(1.0), 1.0, &Tolerances { maxstep: 2.0, ..T }), None);
    }

    #[test]
    fn a_solve_has_stalled_when_its_residual_has_not_halved_over_six_iterations() {
        // Newton's quadratic phase, and a first iterate far above the predictor's
        assert!(!stalled(&[1e6, 2e5, 1e4, 3e1, 1e-3, 1e-9, 1e-12, 1e-14]));
        assert!(!stalled(&[1e3, 1e8, 1e7, 1e6, 1e5, 1e4, 1e3, 1e2]));
        // slow but steady: more than half gone within every six iterations
        let steady: Vec<f64> = (0..20).map(|k| 0.85f64.powi(k)).collect();
        assert!(!stalled(&steady));
        // the frictional heat increment of the default bellows' cycle, as logged: its
        // first iterate 1.9e5, then up and back to 2e5, where it stays
        let mut norms = vec![6.734e6, 1.949e5, 8.473e5, 4.170e5, 2.543e5, 2.090e5, 2.164e5];
        assert!(!stalled(&norms), "five iterations are not yet a stall");
        norms.push(2.008e5);
        assert!(stalled(&norms));
        // and it stays stalled for the rest of the solve, whatever follows
        norms.extend([1e3, 1e-2]);
        assert!(stalled(&norms));
        // the predictor's norm is not a reference, the first iterate's is
        assert!(!stalled(&[1.0, 5.0, 4.0, 3.0, 3.0, 2.8, 2.7]));
        assert!(stalled(&[1.0, 5.0, 4.0, 3.0, 3.0, 2.8, 2.7, 2.6]));
    }
}

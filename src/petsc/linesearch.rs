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

use super::sys;
use std::os::raw::c_void;

/// The full step is kept when the secant's step length is within this of 1.
pub const FULL_STEP_BAND: f64 = 0.1;

/// Halvings of a step that leaves the residual's domain before the line search gives up.
const DOMAIN_HALVINGS: usize = 5;

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
    let code = sys::SNESLineSearchSetType(ls, c"shell".as_ptr());
    if code != 0 {
        return code;
    }
    sys::SNESLineSearchShellSetUserFunc(ls, Some(apply), std::ptr::null_mut())
}

/// Returns early with PETSc's error code from a failed call.
macro_rules! petsc_try {
    ($call:expr) => {
        let code = $call;
        if code != 0 {
            return code;
        }
    };
}

/// The shell's apply: X <- X - lambda Y and F <- F(X), as `cp` leaves them, with the norms.
unsafe extern "C" fn apply(ls: sys::SNESLineSearch, _ctx: *mut c_void) -> sys::PetscErrorCode {
    let null = std::ptr::null_mut;
    let (mut x, mut f, mut y, mut w, mut g) = (null(), null(), null(), null(), null());
    petsc_try!(sys::SNESLineSearchGetVecs(ls, &mut x, &mut f, &mut y, &mut w, &mut g));
    let mut snes: sys::SNES = std::ptr::null_mut();
    petsc_try!(sys::SNESLineSearchGetSNES(ls, &mut snes));
    let mut lambda = 0.0;
    petsc_try!(sys::SNESLineSearchGetLambda(ls, &mut lambda));
    let (mut steptol, mut maxstep, mut rtol, mut atol, mut ltol, mut max_it) = (0.0, 0.0, 0.0, 0.0, 0.0, 0);
    petsc_try!(sys::SNESLineSearchGetTolerances(ls, &mut steptol, &mut maxstep, &mut rtol, &mut atol, &mut ltol, &mut max_it));
    let tolerances = Tolerances { steptol, maxstep, rtol, atol };
    let (mut xnorm, mut fnorm, mut ynorm) = (0.0, 0.0, 0.0);
    petsc_try!(sys::SNESLineSearchGetNorms(ls, &mut xnorm, &mut fnorm, &mut ynorm));
    petsc_try!(sys::SNESLineSearchSetReason(ls, sys::SNESLineSearchReason_SNES_LINESEARCH_SUCCEEDED));
    let mut changed_y = sys::PetscBool_PETSC_FALSE;
    petsc_try!(sys::SNESLineSearchPreCheck(ls, x, y, &mut changed_y));
    let mut fty0 = 0.0;
    petsc_try!(sys::VecDot(f, y, &mut fty0));
    // as cp: no slope left along the step means the potential is at its minimum (the
    // residual at round-off), and the solve has converged where it stands
    if fty0.abs() < tolerances.atol * ynorm {
        return sys::SNESSetConvergedReason(snes, sys::SNESConvergedReason_SNES_CONVERGED_FNORM_ABS);
    }

    // F at the full step (into F: F(X) is not needed again once F.y is known); where the full
    // step leaves the domain (an element inverted: a stiff penalty's first step can throw a
    // contact node through its neighbours), halved until it does not
    let mut domain = sys::PetscBool_PETSC_FALSE;
    for halving in 0..=DOMAIN_HALVINGS {
        petsc_try!(sys::VecWAXPY(w, -lambda, y, x));
        petsc_try!(sys::SNESComputeFunction(snes, w, f));
        petsc_try!(sys::SNESGetFunctionDomainError(snes, &mut domain));
        if domain == sys::PetscBool_PETSC_FALSE {
            break;
        }
        if halving == DOMAIN_HALVINGS {
            return sys::SNESLineSearchSetReason(ls, sys::SNESLineSearchReason_SNES_LINESEARCH_FAILED_DOMAIN);
        }
        // (SNESComputeFunction clears the flag before it evaluates, PETSc >= 3.17)
        lambda *= 0.5;
    }
    let mut fty1 = 0.0;
    petsc_try!(sys::VecDot(f, y, &mut fty1));
    let mut evaluated_at_w = true;
    if let Some(next) = secant_step(fty0, fty1, lambda, &tolerances) {
        lambda = next;
        petsc_try!(sys::VecWAXPY(w, -lambda, y, x));
        evaluated_at_w = false;
    }

    let (mut changed_y, mut changed_w) = (sys::PetscBool_PETSC_FALSE, sys::PetscBool_PETSC_FALSE);
    petsc_try!(sys::SNESLineSearchPostCheck(ls, x, y, w, &mut changed_y, &mut changed_w));
    if changed_y == sys::PetscBool_PETSC_TRUE {
        petsc_try!(sys::VecWAXPY(w, -lambda, y, x));
        evaluated_at_w = false;
    }
    if changed_w == sys::PetscBool_PETSC_TRUE {
        evaluated_at_w = false;
    }
    petsc_try!(sys::VecCopy(w, x));
    if !evaluated_at_w {
        petsc_try!(sys::SNESComputeFunction(snes, x, f));
        petsc_try!(sys::SNESGetFunctionDomainError(snes, &mut domain));
        if domain == sys::PetscBool_PETSC_TRUE {
            return sys::SNESLineSearchSetReason(ls, sys::SNESLineSearchReason_SNES_LINESEARCH_FAILED_DOMAIN);
        }
    }
    petsc_try!(sys::SNESLineSearchComputeNorms(ls));
    petsc_try!(sys::SNESLineSearchSetLambda(ls, lambda));
    if lambda <= steptol {
        petsc_try!(sys::SNESLineSearchSetReason(ls, sys::SNESLineSearchReason_SNES_LINESEARCH_FAILED_REDUCT));
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
}

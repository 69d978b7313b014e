//! The PETSc binding on its own: SNES through the trampolines on a toy problem
//! F_i(x) = x_i^3 - c_i, and the failure paths: an error or a panic inside a callback comes
//! back from `solve` as an `Error` (nothing unwinds into C, nothing aborts), a domain error
//! gives DIVERGED_FUNCTION_DOMAIN, and a PETSc error carries PETSc's own message.
//! One test function: MPI can be initialised once per process.

use slideline::petsc::{MatOps, MatrixView, NonlinearProblem, PetscSession, VecOps, Vector, VectorView};
use slideline::petsc::{Matrix, Snes};
use slideline::Error;

#[derive(Clone, Copy, PartialEq)]
enum Mode {
    Healthy,
    Fails,
    Panics,
    OutOfDomain,
}

struct Cubic {
    c: Vec<f64>,
    mode: Mode,
}

impl NonlinearProblem for Cubic {
    fn residual(&mut self, x: &VectorView<'_>, f: &mut VectorView<'_>) -> slideline::Result<()> {
        match self.mode {
            Mode::Fails => return Err(Error::input("deliberate failure in the residual")),
            Mode::Panics => panic!("deliberate panic in the residual"),
            Mode::OutOfDomain => return Err(Error::Domain("deliberately outside the domain".into())),
            Mode::Healthy => {}
        }
        let xv = x.read()?.to_vec();
        let mut fv = f.write()?;
        for i in 0..xv.len() {
            fv[i] = xv[i].powi(3) - self.c[i];
        }
        Ok(())
    }

    fn jacobian(&mut self, x: &VectorView<'_>, j: &mut MatrixView<'_>) -> slideline::Result<()> {
        let xv = x.read()?.to_vec();
        j.zero_entries()?;
        for (i, xi) in xv.iter().enumerate() {
            j.add_block(&[i as i32], &[i as i32], &[3.0 * xi * xi])?;
        }
        j.assemble()
    }
}

#[test]
fn snes_trampolines_and_error_paths() {
    let session = PetscSession::initialize(&["-snes_rtol".into(), "1e-12".into()]).expect("PETSc starts");
    let comm = session.comm();
    let n = 3;
    let mut x = Vector::mpi(&session, comm, n).unwrap();
    let mut r = x.duplicate().unwrap();
    let mut jac = Matrix::aij(&session, comm, n, &[1; 3], &[0; 3]).unwrap();
    let mut snes = Snes::new(&session).unwrap();
    let mut problem = Cubic { c: vec![8.0, 27.0, 1.0], mode: Mode::Healthy };

    // healthy: converges to the cube roots, quadratically at the end
    x.set_all(1.5).unwrap();
    let report = snes.solve(&mut problem, &mut x, &mut r, &mut jac).unwrap();
    assert!(report.converged(), "reason {}", report.reason_name());
    let sol = x.read().unwrap().to_vec();
    for (s, e) in sol.iter().zip([2.0, 3.0, 1.0]) {
        assert!((s - e).abs() < 1e-10, "{sol:?}");
    }
    let h = &report.residual_norms;
    let k = h.len() - 2;
    assert!(h[k + 1] <= 10.0 * h[k] * h[k], "not quadratic at the end: {h:?}");

    // an error inside a callback comes back as that error
    for (mode, expect) in [(Mode::Fails, "deliberate failure"), (Mode::Panics, "deliberate panic")] {
        problem.mode = mode;
        x.set_all(1.5).unwrap();
        let err = snes.solve(&mut problem, &mut x, &mut r, &mut jac).unwrap_err();
        assert!(err.to_string().contains(expect), "{err}");
    }
    problem.mode = Mode::Panics;
    assert!(matches!(snes.solve(&mut problem, &mut x, &mut r, &mut jac), Err(Error::Panic(_))));

    // a domain error is not an error: SNES reports DIVERGED_FUNCTION_DOMAIN
    problem.mode = Mode::OutOfDomain;
    let report = snes.solve(&mut problem, &mut x, &mut r, &mut jac).unwrap();
    assert_eq!(report.reason_name(), "DIVERGED_FUNCTION_DOMAIN");

    // the binding still works after all that
    problem.mode = Mode::Healthy;
    x.set_all(1.5).unwrap();
    assert!(snes.solve(&mut problem, &mut x, &mut r, &mut jac).unwrap().converged());

    // a PETSc error carries PETSc's message: a nonzero outside the preallocated pattern
    let mut tight = Matrix::aij(&session, comm, n, &[1; 3], &[0; 3]).unwrap();
    tight.add_block(&[0], &[0], &[1.0]).expect("fits the one preallocated slot");
    let err = tight.add_block(&[0], &[1], &[1.0]).unwrap_err();
    match err {
        Error::Petsc { call, message, .. } => {
            assert_eq!(call, "MatSetValues");
            assert!(message.to_lowercase().contains("nonzero"), "message: {message}");
        }
        other => panic!("expected a PETSc error, got {other}"),
    }
}

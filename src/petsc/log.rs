//! PETSc logging stages, so `-log_view` shows where slideline spends its time.

use super::{check, sys};
use crate::error::Result;
use std::ffi::CString;

/// A registered stage; `push`/`pop` bracket the work it measures.
#[derive(Clone, Copy, Debug)]
pub struct LogStage(sys::PetscLogStage);

impl LogStage {
    /// The stage called `name`, registered on first use (PETSc refuses a second registration
    /// of a name, and a process may run several analyses).
    pub fn named(name: &str) -> Result<Self> {
        let cname = CString::new(name).expect("stage names are static and NUL-free");
        let mut stage = -1;
        // SAFETY: PETSc reads the name and writes the id (or -1) to a local.
        check(unsafe { sys::PetscLogStageGetId(cname.as_ptr(), &mut stage) }, "PetscLogStageGetId")?;
        if stage < 0 {
            // SAFETY: PETSc copies the name.
            check(unsafe { sys::PetscLogStageRegister(cname.as_ptr(), &mut stage) }, "PetscLogStageRegister")?;
        }
        Ok(LogStage(stage))
    }

    /// Runs `work` inside this stage (directly, when logging is off and the id is -1).
    pub fn run<T>(self, work: impl FnOnce() -> T) -> Result<T> {
        if self.0 < 0 {
            return Ok(work());
        }
        // SAFETY: a registered stage id; push and pop are paired around `work`.
        check(unsafe { sys::PetscLogStagePush(self.0) }, "PetscLogStagePush")?;
        let out = work();
        check(unsafe { sys::PetscLogStagePop() }, "PetscLogStagePop")?;
        Ok(out)
    }
}

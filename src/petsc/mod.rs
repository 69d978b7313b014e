//! Safe owners over the PETSc objects slideline uses. This module tree is the only place with
//! `unsafe`; everything above it is safe Rust with `Result` errors.
//!
//! - [`PetscSession`] initialises PETSc (and SLEPc, for [`eigen`]) on the `mpi` crate's world
//!   and finalises them on drop;
//!   every owner borrows it (lifetime `'s`) so the compiler orders the drops.
//! - One owner per handle (`Drop` calls XDestroy and never panics), no `Clone`; borrowed views
//!   (`*View`) for the handles PETSc passes into callbacks.
//! - `check` turns a non-zero PetscErrorCode into [`Error::Petsc`] with PETSc's own message;
//!   PETSc's error handler is replaced by the returning one so no trace is printed.
#![allow(unsafe_code)]

pub mod sys;

pub mod eigen;
mod linesearch;
mod log;
mod matrix;
pub mod options;
mod partition;
mod snes;
mod vector;

pub use log::LogStage;
pub use matrix::{MatOps, Matrix, MatrixView, OwnedStructure};
pub use partition::partition_graph;
pub use snes::{FieldRatios, NonlinearProblem, Snes, SolveReport};
pub use vector::{IndexSet, Scatter, VecOps, Vector, VectorView};

use crate::error::{Error, Result};
use mpi::traits::AsRaw;
use std::ffi::{c_char, c_int, CStr, CString};
use std::marker::PhantomData;

pub type Comm = mpi::ffi::MPI_Comm;

/// Turns a PetscErrorCode into a `Result`, fetching the message PETSc recorded for it.
pub(crate) fn check(code: sys::PetscErrorCode, call: &'static str) -> Result<()> {
    if code == 0 {
        return Ok(());
    }
    let mut text: *const c_char = std::ptr::null();
    let mut specific: *mut c_char = std::ptr::null_mut();
    // SAFETY: PetscErrorMessage only writes two pointers to static strings owned by PETSc.
    unsafe { sys::PetscErrorMessage(code, &mut text, &mut specific) };
    let mut message = String::new();
    for p in [specific as *const c_char, text] {
        if !p.is_null() {
            // SAFETY: PETSc returns NUL-terminated static strings.
            let s = unsafe { CStr::from_ptr(p) }.to_string_lossy();
            if !s.trim().is_empty() {
                message = s.trim().to_string();
                break;
            }
        }
    }
    Err(Error::Petsc { call, code, message })
}

/// PETSc initialised on the world of the `mpi` crate, or on one group of it (a study's).
/// Drop finalises PETSc, then MPI.
pub struct PetscSession {
    // Declared before `universe` so PETSc is finalised (in Drop) before MPI is, and the
    // group's communicator freed before MPI is finalised.
    _args: Vec<CString>,
    _argv: Vec<*mut c_char>,
    options: Vec<String>,
    /// PETSc's world: every rank, or this rank's group in a study.
    world: mpi::topology::SimpleCommunicator,
    groups: Option<Groups>,
    universe: mpi::environment::Universe,
}

/// A study's split of MPI_COMM_WORLD into groups of equal size, each running one model at a
/// time on its own PETSc objects.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Groups {
    /// How many groups, and which this rank is in (ranks 0..G-1 are group 0, and so on).
    pub count: usize,
    pub index: usize,
    pub ranks_per_group: usize,
}

impl PetscSession {
    /// Initialises MPI (through the `mpi` crate) and PETSc, with `petsc_options` (e.g.
    /// `-snes_monitor -pc_type gamg`) put in the options database as if given on the command line.
    /// The PETSC_OPTIONS environment variable is honoured as well, as PETSc always does.
    pub fn initialize(petsc_options: &[String]) -> Result<Self> {
        options::check(petsc_options)?;
        quiet_threads();
        let universe = mpi::initialize().ok_or_else(|| Error::Mpi("MPI was already initialised".into()))?;
        Self::start(petsc_options, universe.world(), None, universe)
    }

    /// As [`Self::initialize`], for a study: MPI_COMM_WORLD split into groups of
    /// `ranks_per_group` consecutive ranks (MPI_Comm_split), PETSc's world set to this rank's
    /// group before PETSc starts (as the PETSC_COMM_WORLD manual page says), so every object a
    /// run makes lives on its group. MPI is started with MPI_THREAD_MULTIPLE: a study's
    /// coordinator answers the groups from a thread of rank 0.
    pub fn initialize_groups(petsc_options: &[String], ranks_per_group: usize) -> Result<Self> {
        use mpi::environment::Threading;
        use mpi::topology::Color;
        use mpi::traits::Communicator;
        options::check(petsc_options)?;
        quiet_threads();
        let (universe, threading) = mpi::initialize_with_threading(Threading::Multiple).ok_or_else(|| Error::Mpi("MPI was already initialised".into()))?;
        if threading != Threading::Multiple {
            return Err(Error::Mpi(format!("this MPI gives {threading:?} threading; a study's coordinator needs MPI_THREAD_MULTIPLE")));
        }
        let everyone = universe.world();
        let size = everyone.size() as usize;
        if ranks_per_group == 0 || !size.is_multiple_of(ranks_per_group) {
            return Err(Error::input(format!("--ranks-per-run {ranks_per_group}: it must divide the {size} ranks given (mpirun -n {size}) into whole groups")));
        }
        let index = everyone.rank() as usize / ranks_per_group;
        let group = everyone.split_by_color(Color::with_value(index as i32)).ok_or_else(|| Error::Mpi("MPI_Comm_split gave no communicator".into()))?;
        let groups = Groups { count: size / ranks_per_group, index, ranks_per_group };
        Self::start(petsc_options, group, Some(groups), universe)
    }

    /// PETSc and SLEPc started on `world`, with the stop signals trapped.
    fn start(petsc_options: &[String], world: mpi::topology::SimpleCommunicator, groups: Option<Groups>, universe: mpi::environment::Universe) -> Result<Self> {
        let mut args = vec![CString::new("slideline").expect("static name")];
        for o in petsc_options {
            args.push(CString::new(o.as_str()).map_err(|_| Error::input(format!("PETSc option {o:?} contains a NUL byte")))?);
        }
        let mut argv: Vec<*mut c_char> = args.iter().map(|a| a.as_ptr() as *mut c_char).collect();
        argv.push(std::ptr::null_mut());
        let mut argc = c_int::try_from(args.len()).expect("few arguments");
        let mut argv_ptr = argv.as_mut_ptr();
        // SAFETY: MPI is initialised and PETSc is not: PETSC_COMM_WORLD may be set now (its
        // manual page); `world` is kept in the session, freed only after PetscFinalize.
        unsafe { sys::PETSC_COMM_WORLD = world.as_raw() };
        // SAFETY: argc/argv describe NUL-terminated strings kept alive in `self` for the whole
        // session (PETSc keeps pointers to them); MPI is already initialised, so PETSc leaves
        // MPI_Finalize to the `mpi` crate.
        let code = unsafe { sys::PetscInitialize(&mut argc, &mut argv_ptr, std::ptr::null(), std::ptr::null()) };
        check(code, "PetscInitialize")?;
        // SAFETY: installs PETSc's own handler that returns the error code without printing.
        check(unsafe { sys::PetscPushErrorHandler(Some(sys::PetscReturnErrorHandler), std::ptr::null_mut()) }, "PetscPushErrorHandler")?;
        // SAFETY: PETSc is initialised, so SLEPc only registers its packages (it starts PETSc
        // only when nothing has, and then finalises it too); no arguments are needed for that.
        check(unsafe { sys::SlepcInitialize(std::ptr::null_mut(), std::ptr::null_mut(), std::ptr::null(), std::ptr::null()) }, "SlepcInitialize")?;
        trap_stop_signals()?;
        Ok(PetscSession { _args: args, _argv: argv, options: petsc_options.to_vec(), world, groups, universe })
    }

    /// PETSc's world: every rank of a run (MPI_COMM_WORLD), or this rank's group in a study.
    pub fn world(&self) -> &mpi::topology::SimpleCommunicator {
        &self.world
    }

    /// The raw communicator PETSc objects are created on (PETSC_COMM_WORLD).
    pub fn comm(&self) -> Comm {
        self.world.as_raw()
    }

    /// Every rank started (MPI_COMM_WORLD): a study's coordinator talks to the groups over it.
    pub fn everyone(&self) -> mpi::topology::SimpleCommunicator {
        self.universe.world()
    }

    /// A study's groups (None for a single run on every rank).
    pub fn groups(&self) -> Option<Groups> {
        self.groups
    }

    /// The PETSc options this session was started with.
    pub fn options(&self) -> &[String] {
        &self.options
    }

    /// The options given that nothing has read so far (a misspelt `-snes_monitr`), as
    /// `-name` or `-name value`.
    pub fn unused_options(&self) -> Vec<String> {
        let mut n: sys::PetscInt = 0;
        let mut names: *mut *mut c_char = std::ptr::null_mut();
        let mut values: *mut *mut c_char = std::ptr::null_mut();
        // SAFETY: NULL is the global database; the out-pointers are valid and the arrays are
        // handed back to PetscOptionsLeftRestore with the same count, as the manual asks.
        if unsafe { sys::PetscOptionsLeftGet(std::ptr::null_mut(), &mut n, &mut names, &mut values) } != 0 {
            return Vec::new();
        }
        let text = |p: *mut c_char| -> Option<String> {
            // SAFETY: PETSc returns NUL-terminated strings (or NULL for an option without value)
            (!p.is_null()).then(|| unsafe { std::ffi::CStr::from_ptr(p) }.to_string_lossy().into_owned())
        };
        let left = (0..usize::try_from(n).unwrap_or(0))
            .map(|k| {
                // SAFETY: both arrays hold n entries
                let (name, value) = unsafe { (*names.add(k), *values.add(k)) };
                let name = format!("-{}", text(name).unwrap_or_default());
                match text(value) {
                    Some(v) if !v.is_empty() => format!("{name} {v}"),
                    _ => name,
                }
            })
            .collect();
        // SAFETY: restores exactly what LeftGet returned
        unsafe { sys::PetscOptionsLeftRestore(std::ptr::null_mut(), &mut n, &mut names, &mut values) };
        left
    }

    /// Whether `name` (e.g. `-pc_type`) is set in the options database.
    pub fn has_option(&self, name: &str) -> bool {
        let Ok(cname) = CString::new(name) else {
            return false;
        };
        let mut set: sys::PetscBool = sys::PetscBool_PETSC_FALSE;
        // SAFETY: NULL options object means the global database; `set` is a valid out-pointer.
        let code = unsafe { sys::PetscOptionsHasName(std::ptr::null_mut(), std::ptr::null(), cname.as_ptr(), &mut set) };
        code == 0 && set == sys::PetscBool_PETSC_TRUE
    }
}

impl Drop for PetscSession {
    fn drop(&mut self) {
        // SAFETY: every PETSc object borrows the session, so all are destroyed by now.
        // Errors at finalisation cannot be reported anywhere useful; they are ignored.
        // SLEPc first: it did not start PETSc, so it leaves PETSc's finalisation to us.
        unsafe {
            sys::SlepcFinalize();
            sys::PetscPopErrorHandler();
            sys::PetscFinalize();
        }
    }
}

/// Scotch (the partitioner under ptscotch) runs several threads whose interleaving changes the
/// partition from run to run; with one thread repeated runs are identical. Set before MPI and
/// PETSc start any thread; a user's own setting is kept.
fn quiet_threads() {
    if std::env::var_os("SCOTCH_PTHREAD_NUMBER").is_none() {
        std::env::set_var("SCOTCH_PTHREAD_NUMBER", "1");
    }
}

/// SIGINT and SIGTERM ask the run to stop after its increment ([`crate::interrupt`]); a second
/// one ends the process at once (130 or 143, the shell's codes). PETSc 3.18 traps neither (its
/// handler takes SIGSEGV, SIGFPE, SIGBUS, ...), so signal-hook chains to no other handler.
fn trap_stop_signals() -> Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use std::sync::{atomic::AtomicBool, Arc};
    let hook = |e: std::io::Error| Error::Internal(format!("cannot trap SIGINT and SIGTERM: {e}"));
    for signal in [SIGINT, SIGTERM] {
        let twice = Arc::new(AtomicBool::new(false));
        signal_hook::flag::register_conditional_shutdown(signal, 128 + signal, Arc::clone(&twice)).map_err(hook)?;
        signal_hook::flag::register(signal, twice).map_err(hook)?;
        signal_hook::flag::register_usize(signal, crate::interrupt::flag(), signal as usize).map_err(hook)?;
    }
    Ok(())
}

/// Marker tying an owner to the session that must outlive it.
pub(crate) type SessionBorrow<'s> = PhantomData<&'s PetscSession>;

/// Converts a Rust index to PetscInt, failing loudly on overflow of the 32-bit index type.
pub(crate) fn to_petsc_int(i: usize) -> Result<sys::PetscInt> {
    sys::PetscInt::try_from(i).map_err(|_| Error::input(format!("index {i} exceeds PETSc's 32-bit PetscInt")))
}

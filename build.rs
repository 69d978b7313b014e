//! Generates the PETSc and SLEPc FFI (src/petsc/sys.rs includes it) from Debian's PETSc 3.18
//! and SLEPc 3.18, found through pkg-config, restricted to the calls the binding makes.

use std::env;
use std::path::PathBuf;

/// Every PETSc function the binding calls; nothing else is generated.
const FUNCTIONS: &[&str] = &[
    // SLEPc: eigenproblems (src/petsc/eigen.rs)
    "SlepcInitialize",
    "SlepcFinalize",
    "EPSCreate",
    "EPSDestroy",
    "EPSSetOperators",
    "EPSSetProblemType",
    "EPSSetType",
    "EPSSetDimensions",
    "EPSSetTarget",
    "EPSSetWhichEigenpairs",
    "EPSSetTolerances",
    "EPSGetST",
    "EPSSetFromOptions",
    "EPSSolve",
    "EPSGetConverged",
    "EPSGetConvergedReason",
    "EPSGetEigenpair",
    "EPSComputeError",
    "STSetType",
    "STGetKSP",
    // system, options, errors, logging
    "PetscInitialize",
    "PetscFinalize",
    "PetscInitialized",
    "PetscErrorMessage",
    "PetscPushErrorHandler",
    "PetscPopErrorHandler",
    "PetscReturnErrorHandler",
    "PetscMallocA",
    "PetscOptionsHasName",
    "PetscOptionsLeftGet",
    "PetscOptionsLeftRestore",
    "PetscLogStageRegister",
    "PetscLogStageGetId",
    "PetscLogStagePush",
    "PetscLogStagePop",
    // vectors, index sets, scatters
    "VecCreateMPI",
    "VecCreateSeq",
    "VecDuplicate",
    "VecDestroy",
    "VecSet",
    "VecCopy",
    "VecAXPY",
    "VecNorm",
    "VecDot",
    "VecWAXPY",
    "VecGetOwnershipRange",
    "VecGetLocalSize",
    "VecGetSize",
    "VecGetArray",
    "VecRestoreArray",
    "VecGetArrayRead",
    "VecRestoreArrayRead",
    "VecSetValues",
    "VecAssemblyBegin",
    "VecAssemblyEnd",
    "ISCreateGeneral",
    "ISDestroy",
    "ISGetLocalSize",
    "ISGetIndices",
    "ISRestoreIndices",
    "VecScatterCreate",
    "VecScatterBegin",
    "VecScatterEnd",
    "VecScatterDestroy",
    // matrices and partitioning
    "MatCreateAIJ",
    "MatDestroy",
    "MatSetOption",
    "MatSetValues",
    "MatSetPreallocationCOO",
    "MatSetValuesCOO",
    "MatZeroEntries",
    "MatMult",
    "MatGetType",
    "MatGetOwnershipRange",
    "MatMPIAIJGetSeqAIJ",
    "MatGetRowIJ",
    "MatRestoreRowIJ",
    "MatSeqAIJGetArray",
    "MatSeqAIJRestoreArray",
    "MatAssemblyBegin",
    "MatAssemblyEnd",
    "MatCreateMPIAdj",
    "MatPartitioningCreate",
    "MatPartitioningSetAdjacency",
    "MatPartitioningSetNParts",
    "MatPartitioningSetVertexWeights",
    "MatPartitioningSetType",
    "MatPartitioningSetFromOptions",
    "MatPartitioningApply",
    "MatPartitioningDestroy",
    // linear and nonlinear solvers
    "KSPSetType",
    "KSPGetPC",
    "PCReset",
    "KSPSetOperators",
    "KSPSolve",
    "KSPGetConvergedReason",
    "PCSetType",
    "PCFactorSetMatSolverType",
    "PCGetType",
    "PCFactorGetMatSolverType",
    "PCFactorGetMatrix",
    "MatMumpsGetInfog",
    "SNESCreate",
    "SNESDestroy",
    "SNESSetFunction",
    "SNESSetJacobian",
    "SNESGetKSP",
    "SNESGetType",
    "SNESGetLineSearch",
    "SNESLineSearchSetType",
    "SNESLineSearchShellSetUserFunc",
    "SNESLineSearchGetVecs",
    "SNESLineSearchGetSNES",
    "SNESLineSearchGetLambda",
    "SNESLineSearchSetLambda",
    "SNESLineSearchGetTolerances",
    "SNESLineSearchSetReason",
    "SNESLineSearchPreCheck",
    "SNESLineSearchPostCheck",
    "SNESLineSearchComputeNorms",
    "SNESLineSearchGetNorms",
    "SNESSetConvergedReason",
    "SNESComputeFunction",
    "SNESGetFunctionDomainError",
    "SNESSetFromOptions",
    "SNESSetConvergenceHistory",
    "SNESGetConvergenceHistory",
    "SNESSolve",
    "SNESGetConvergedReason",
    "SNESGetSolution",
    "SNESGetFunction",
    "SNESGetIterationNumber",
    "SNESGetLinearSolveIterations",
    "SNESSetFunctionDomainError",
    "SNESSetTolerances",
    "SNESSetConvergenceTest",
    "SNESConvergedDefault",
];

fn main() {
    let petsc = pkg_config::Config::new()
        .atleast_version("3.18")
        .probe("petsc")
        .expect("PETSc not found by pkg-config: run ./run.sh (it installs petsc-dev), or set PKG_CONFIG_PATH");
    let slepc = pkg_config::Config::new()
        .atleast_version("3.18")
        .probe("slepc")
        .expect("SLEPc not found by pkg-config: run ./run.sh (it installs libslepc-real3.18-dev), or set PKG_CONFIG_PATH");
    // PETSc's headers include <mpi.h>; Debian's petsc.pc does not name its directory.
    let mpi = pkg_config::Config::new()
        .cargo_metadata(false)
        .probe("ompi-c")
        .or_else(|_| pkg_config::Config::new().cargo_metadata(false).probe("mpi"))
        .expect("MPI headers not found by pkg-config: install libopenmpi-dev");

    let mut builder = bindgen::Builder::default()
        .header("src/petsc/wrapper.h")
        .parse_callbacks(Box::new(bindgen::CargoCallbacks::new()))
        // C enums become integer constants: a Rust enum holding a value C did not list is UB.
        .default_enum_style(bindgen::EnumVariation::Consts)
        // MPI handles come from the `mpi` crate so `comm.as_raw()` passes straight through.
        .blocklist_type("MPI_.*")
        .blocklist_type("ompi_.*")
        .raw_line("pub use mpi::ffi::MPI_Comm;")
        // set to a study's group before PetscInitialize (the manual page's way to run PETSc on a subset)
        .allowlist_var("PETSC_COMM_WORLD")
        .layout_tests(false)
        .generate_comments(false);
    for f in FUNCTIONS {
        builder = builder.allowlist_function(f);
    }
    for ty in [
        "PetscBool",
        "NormType",
        "InsertMode",
        "ScatterMode",
        "MatAssemblyType",
        "MatOption",
        "SNESConvergedReason",
        "KSPConvergedReason",
        "PetscErrorType",
        "SNESLineSearchReason",
        "EPSProblemType",
        "EPSWhich",
        "EPSConvergedReason",
        "EPSErrorType",
    ] {
        builder = builder.allowlist_type(ty);
    }
    for path in petsc.include_paths.iter().chain(slepc.include_paths.iter()).chain(mpi.include_paths.iter()) {
        builder = builder.clang_arg(format!("-I{}", path.display()));
    }
    let bindings = builder.generate().expect("bindgen failed on the PETSc headers");
    let out = PathBuf::from(env::var("OUT_DIR").unwrap()).join("petsc_sys.rs");
    bindings.write_to_file(&out).expect("cannot write petsc_sys.rs");
    println!("cargo:rerun-if-changed=src/petsc/wrapper.h");
    println!("cargo:rerun-if-changed=build.rs");
}

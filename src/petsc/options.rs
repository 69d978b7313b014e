//! PETSc options checked before PETSc starts, so that a bad one is refused the same way on every
//! rank (exit 2, the option named) before anything is written: values that must be numbers in a
//! range, files PETSc would open on one rank only (an options file, a log file), and choices
//! that would make a run's answers wrong without a word (a nonlinear solver that skips
//! slideline's convergence test, a matrix-free Jacobian that a direct solver cannot factor).

use crate::error::{Error, Result};
use std::path::Path;

/// What a numeric option takes.
#[derive(Clone, Copy)]
enum Takes {
    /// A tolerance: finite, >= 0; relative ones below 1.
    Tolerance { relative: bool },
    /// A count of at least 1.
    Count,
    /// Any finite number.
    Finite,
}

const NUMERIC: [(&str, Takes); 16] = [
    ("-snes_rtol", Takes::Tolerance { relative: true }),
    ("-snes_atol", Takes::Tolerance { relative: false }),
    ("-snes_stol", Takes::Tolerance { relative: true }),
    ("-snes_max_it", Takes::Count),
    ("-snes_max_funcs", Takes::Count),
    ("-ksp_rtol", Takes::Tolerance { relative: true }),
    ("-ksp_atol", Takes::Tolerance { relative: false }),
    ("-ksp_max_it", Takes::Count),
    ("-ksp_gmres_restart", Takes::Count),
    ("-snes_linesearch_max_it", Takes::Count),
    ("-eps_tol", Takes::Tolerance { relative: true }),
    ("-eps_max_it", Takes::Count),
    ("-eps_ncv", Takes::Count),
    ("-eps_mpd", Takes::Count),
    ("-eps_target", Takes::Finite),
    ("-st_shift", Takes::Finite),
];

/// The nonlinear solvers whose solves slideline's convergence test judges: Newton with a line
/// search. Any other (`ksponly` takes one linear solve and reports success; `newtontr`, `ngmres`,
/// ... converge by their own tests) would pass increments that are not in equilibrium.
pub const JUDGED_SNES_TYPES: [&str; 1] = ["newtonls"];

/// The value given after option `name`, if any.
fn value<'a>(options: &'a [String], name: &str) -> Option<&'a str> {
    let k = options.iter().rposition(|o| o == name)?;
    options.get(k + 1).map(String::as_str).filter(|v| !v.starts_with('-') || v.parse::<f64>().is_ok())
}

/// Checks the options given on the command line (see the module doc).
pub fn check(options: &[String]) -> Result<()> {
    for (name, takes) in NUMERIC {
        if !options.iter().any(|o| o == name) {
            continue;
        }
        let given = value(options, name).unwrap_or("");
        let ok = match takes {
            Takes::Tolerance { relative } => given.parse::<f64>().is_ok_and(|v| v.is_finite() && v >= 0.0 && (!relative || v < 1.0)),
            Takes::Count => given.parse::<i64>().is_ok_and(|v| v >= 1),
            Takes::Finite => given.parse::<f64>().is_ok_and(f64::is_finite),
        };
        if !ok {
            let wanted = match takes {
                Takes::Tolerance { relative: true } => "a number >= 0 and < 1",
                Takes::Tolerance { relative: false } => "a number >= 0",
                Takes::Count => "a whole number >= 1",
                Takes::Finite => "a finite number",
            };
            return Err(Error::input(format!("PETSc option {name} {given:?}: give {wanted}")));
        }
    }
    if let Some(kind) = value(options, "-snes_type").filter(|t| !JUDGED_SNES_TYPES.contains(t)) {
        return Err(snes_type_refused(kind));
    }
    if options.iter().any(|o| o == "-snes_mf") {
        return Err(Error::input(
            "PETSc option -snes_mf: a matrix-free Jacobian leaves the direct solver nothing to factor (slideline assembles the exact tangent; -snes_mf_operator keeps it as the preconditioner)",
        ));
    }
    if let Some(file) = value(options, "-options_file") {
        std::fs::File::open(file).map_err(|e| Error::input(format!("PETSc option -options_file {file}: {e}")))?;
    }
    // -log_view :FILE[:FORMAT] and the like: rank 0 writes the file at the end of the run
    for name in ["-log_view", "-log_view_memory", "-log_trace"] {
        if let Some(file) = value(options, name).and_then(|v| v.strip_prefix(':')).map(|v| v.split(':').next().unwrap_or("")).filter(|f| !f.is_empty()) {
            crate::output_path::check_output_path(Path::new(file), None).map_err(|e| Error::input(format!("PETSc option {name}: {e}")))?;
        }
    }
    Ok(())
}

/// PETSc 3.18's nonlinear solver types.
const SNES_TYPES: [&str; 19] = [
    "newtonls",
    "newtontr",
    "nrichardson",
    "ksponly",
    "ksptransposeonly",
    "vinewtonrsls",
    "vinewtonssls",
    "ngmres",
    "qn",
    "shell",
    "ngs",
    "ncg",
    "fas",
    "ms",
    "nasm",
    "anderson",
    "aspin",
    "composite",
    "patch",
];

/// The error for a nonlinear solver slideline cannot judge.
pub fn snes_type_refused(kind: &str) -> Error {
    if !SNES_TYPES.contains(&kind) {
        return Error::input(format!("PETSc option -snes_type {kind}: unknown SNES type (slideline runs {})", JUDGED_SNES_TYPES.join(", ")));
    }
    Error::input(format!(
        "PETSc option -snes_type {kind}: slideline judges every increment by its own convergence test inside Newton's method with a line search ({}); {kind} would skip or replace it",
        JUDGED_SNES_TYPES.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(options: &[&str]) -> String {
        let options: Vec<String> = options.iter().map(|s| s.to_string()).collect();
        check(&options).expect_err("refused").to_string()
    }

    #[test]
    fn numbers_out_of_range_and_solvers_that_skip_the_test_are_named() {
        assert!(refused(&["-snes_rtol", "-1"]).contains("-snes_rtol \"-1\""));
        assert!(refused(&["-snes_atol", "nan"]).contains("-snes_atol \"nan\""));
        assert!(refused(&["-snes_max_it", "abc"]).contains("whole number"));
        assert!(refused(&["-snes_max_it", "0"]).contains("-snes_max_it \"0\""));
        assert!(refused(&["-snes_max_it"]).contains("-snes_max_it \"\""));
        assert!(refused(&["-snes_type", "ksponly"]).contains("ksponly would skip"));
        assert!(refused(&["-snes_type", "bogus"]).contains("-snes_type bogus: unknown SNES type"));
        assert!(refused(&["-snes_mf"]).contains("-snes_mf"));
        assert!(refused(&["-options_file", "/nonexistent/opts"]).contains("-options_file /nonexistent/opts"));
        assert!(refused(&["-log_view", ":/nonexistent/dir/log.txt"]).contains("-log_view"));
        let fine: Vec<String> = ["-snes_rtol", "1e-8", "-snes_max_it", "40", "-snes_type", "newtonls", "-log_view", "-snes_monitor"].map(String::from).to_vec();
        assert!(check(&fine).is_ok());
    }
}

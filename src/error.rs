//! The one error type of slideline. Variants carry the offending item so a message names it;
//! `exit_code` maps them to the CLI's codes (2 bad input, 3 not converged, 1 other).

use std::fmt::Display;
use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad input of any kind: the message names the file, line, set, element or value at fault.
    #[error("{0}")]
    Input(String),

    #[error("cannot read {path}: {source}")]
    Read { path: PathBuf, source: std::io::Error },

    /// A PETSc call returned a non-zero PetscErrorCode; `message` is PETSc's own text.
    #[error("PETSc call {call} failed (error code {code}): {message}")]
    Petsc { call: &'static str, code: i32, message: String },

    /// The current iterate left the domain of the residual (inverted element, failed return map).
    /// SNES is told, the increment is cut back.
    #[error("{0}")]
    Domain(String),

    #[error("step {step} did not converge at load factor {load_factor:.6}: {reason}")]
    NotConverged { step: String, load_factor: f64, reason: String },

    /// SIGINT or SIGTERM stopped the run after a converged increment (its file complete).
    #[error("stopped by {signal} after {what}: every converged increment is in {}", path.display())]
    Interrupted { signal: &'static str, what: String, path: PathBuf },

    #[error("cannot write {path}: {message}")]
    Output { path: PathBuf, message: String },

    #[error("MPI: {0}")]
    Mpi(String),

    /// A broken assumption inside slideline (a bug), reported rather than panicking.
    #[error("internal error: {0}")]
    Internal(String),

    /// A Rust panic caught at the FFI boundary (a bug, reported rather than unwound through C).
    #[error("internal error (panic inside a PETSc callback): {0}")]
    Panic(String),
}

/// PETSc error codes that mean the options asked for something it cannot do:
/// PETSC_ERR_SUP (56), PETSC_ERR_ARG_UNKNOWN_TYPE (86), PETSC_ERR_MISSING_FACTOR (92).
const PETSC_OPTION_ERRORS: [i32; 3] = [56, 86, 92];

impl Error {
    pub fn input(message: impl Into<String>) -> Self {
        Error::Input(message.into())
    }

    /// Process exit code for the CLI.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Input(_) | Error::Read { .. } => 2,
            // PETSc refusing what its options ask for (an unsupported operation, an unknown
            // type, a factorisation the matrix type lacks) is bad input, as an unknown flag is
            Error::Petsc { code, .. } if PETSC_OPTION_ERRORS.contains(code) => 2,
            Error::NotConverged { .. } => 3,
            // the shell's convention for a process ended by a signal
            Error::Interrupted { signal: "SIGINT", .. } => 130,
            Error::Interrupted { .. } => 143,
            _ => 1,
        }
    }
}

pub type Result<T> = std::result::Result<T, Error>;

/// A number as a message shows it: to 10 significant digits (a sum's round-off is not the
/// user's number: 3 x 60.3 is 180.9, not 180.89999999999998), plainly, or in exponent form
/// where it is huge or tiny (1e300 is not 301 digits).
pub fn shown(v: f64) -> String {
    let v: f64 = if v.is_finite() { format!("{v:.9e}").parse().unwrap_or(v) } else { v };
    if v == 0.0 || !v.is_finite() || (1e-4..1e6).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// A list of items for a message: the first ten, comma-separated, then "and N more".
pub fn first_ten(items: &[impl Display]) -> String {
    let shown: Vec<String> = items.iter().take(10).map(|i| i.to_string()).collect();
    match items.len() {
        n if n > 10 => format!("{} and {} more", shown.join(", "), n - 10),
        _ => shown.join(", "),
    }
}

#[cfg(test)]
mod list_tests {
    use super::{first_ten, shown};

    /// A sum's round-off is not printed (seen before: "3 Db = 180.89999999999998 mm",
    /// "2.4000000000000004"), a huge value not in 301 digits.
    #[test]
    fn a_computed_number_is_shown_as_its_ten_digits_say() {
        assert_eq!(shown(3.0 * 60.3), "180.9");
        assert_eq!(shown(3.0 * 0.8), "2.4");
        assert_eq!(shown(1e300), "1e300");
        assert_eq!(shown(f64::NAN), "NaN");
        assert_eq!(shown(0.1234567891234), "0.1234567891");
    }

    #[test]
    fn a_long_list_shows_its_first_ten_and_counts_the_rest() {
        assert_eq!(first_ten(&[3, 1]), "3, 1");
        let many: Vec<u32> = (1..=13).collect();
        assert_eq!(first_ten(&many), "1, 2, 3, 4, 5, 6, 7, 8, 9, 10 and 3 more");
    }
}

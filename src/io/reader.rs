//! Reading a results file back (serially, after the run): the mesh, the increments' fields
//! and the history columns, for pictures, summaries and post-processing. Every failure names
//! the file and the group or dataset that is missing, so a wrong file gives a clear message.

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

pub struct ResultsReader {
    file: hdf5::File,
    path: PathBuf,
}

/// A group or dataset of the file that could not be read.
fn missing(path: &Path, what: &str, e: impl std::fmt::Display) -> Error {
    Error::input(format!("{}: cannot read {what}: {e}", path.display()))
}

impl ResultsReader {
    pub fn open(path: &Path) -> Result<Self> {
        if !path.exists() {
            return Err(Error::input(format!("{}: no such file", path.display())));
        }
        let file = hdf5::File::open(path).map_err(|e| Error::input(format!("{}: not an HDF5 file ({e})", path.display())))?;
        let reader = ResultsReader { file, path: path.to_path_buf() };
        for group in ["mesh", "increments", "history"] {
            if !reader.file.link_exists(group) {
                return Err(Error::input(format!("{}: not a slideline results file (no /{group} group)", path.display())));
            }
        }
        Ok(reader)
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    fn read_f64(&self, name: &str) -> Result<Vec<f64>> {
        let ds = self.file.dataset(name).map_err(|e| missing(&self.path, name, e))?;
        ds.read_raw::<f64>().map_err(|e| missing(&self.path, name, e))
    }

    fn read_i64(&self, name: &str) -> Result<Vec<i64>> {
        let ds = self.file.dataset(name).map_err(|e| missing(&self.path, name, e))?;
        ds.read_raw::<i64>().map_err(|e| missing(&self.path, name, e))
    }

    /// Reference coordinates (r, z) of the nodes, in file order.
    pub fn coordinates(&self) -> Result<Vec<[f64; 2]>> {
        Ok(self.read_f64("mesh/coordinates")?.chunks_exact(2).map(|c| [c[0], c[1]]).collect())
    }

    /// Q8 connectivity as rows of `coordinates`.
    pub fn connectivity(&self) -> Result<Vec<[usize; 8]>> {
        Ok(self.read_i64("mesh/connectivity")?.chunks_exact(8).map(|c| std::array::from_fn(|k| c[k] as usize)).collect())
    }

    /// Names of the element sets.
    pub fn element_set_names(&self) -> Result<Vec<String>> {
        let g = self.file.group("mesh/element_sets").map_err(|e| missing(&self.path, "mesh/element_sets", e))?;
        g.member_names().map_err(|e| missing(&self.path, "mesh/element_sets", e))
    }

    /// Positions (rows of the element datasets) of an element set's members.
    pub fn element_set(&self, name: &str) -> Result<Vec<usize>> {
        Ok(self.read_i64(&format!("mesh/element_sets/{name}"))?.into_iter().map(|k| k as usize).collect())
    }

    /// Names of the increments written (zero-padded, so sorted in order).
    pub fn increments(&self) -> Result<Vec<String>> {
        let g = self.file.group("increments").map_err(|e| missing(&self.path, "increments", e))?;
        let mut names = g.member_names().map_err(|e| missing(&self.path, "increments", e))?;
        names.sort();
        Ok(names)
    }

    /// Nodal displacement (u_r, u_z) at an increment.
    pub fn displacement(&self, increment: &str) -> Result<Vec<[f64; 2]>> {
        Ok(self.read_f64(&format!("increments/{increment}/displacement"))?.chunks_exact(2).map(|c| [c[0], c[1]]).collect())
    }

    /// Any field of an increment, flattened (row-major).
    pub fn field(&self, increment: &str, name: &str) -> Result<Vec<f64>> {
        self.read_f64(&format!("increments/{increment}/{name}"))
    }

    /// A numeric attribute of an increment (step, increment, load_factor, time).
    pub fn increment_attr(&self, increment: &str, name: &str) -> Result<f64> {
        let what = format!("increments/{increment} attribute {name}");
        let g = self.file.group(&format!("increments/{increment}")).map_err(|e| missing(&self.path, &what, e))?;
        g.attr(name).and_then(|a| a.read_scalar::<f64>()).map_err(|e| missing(&self.path, &what, e))
    }

    /// Names of the history columns.
    pub fn history_columns(&self) -> Result<Vec<String>> {
        let g = self.file.group("history").map_err(|e| missing(&self.path, "history", e))?;
        g.member_names().map_err(|e| missing(&self.path, "history", e))
    }

    /// One history column (a row per converged increment).
    pub fn history(&self, column: &str) -> Result<Vec<f64>> {
        self.read_f64(&format!("history/{column}"))
    }
}

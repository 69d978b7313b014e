//! A table of columns (a study's rows, a verdict's lines) in HDF5 and CSV, and the HDF5 file
//! of such tables (a study's file, a verdict's group) written and read back.

use crate::error::{Error, Result};
use hdf5::types::VarLenUnicode;
use std::path::{Path, PathBuf};

/// One column of a study's table.
pub enum Column {
    /// Numbers with their unit ("" for a count or a ratio).
    Numbers(Vec<f64>, String),
    Text(Vec<String>),
}

/// A study's table, its columns in the order they print.
#[derive(Default)]
pub struct Table {
    pub columns: Vec<(String, Column)>,
}

impl Table {
    pub fn numbers(&mut self, name: &str, unit: &str, values: Vec<f64>) {
        self.columns.push((name.to_string(), Column::Numbers(values, unit.to_string())));
    }

    pub fn text(&mut self, name: &str, values: Vec<String>) {
        self.columns.push((name.to_string(), Column::Text(values)));
    }

    /// Each column a dataset of `group` in `file` (numbers with a `units` attribute).
    pub fn write_group(&self, file: &hdf5::File, group: &str, path: &Path) -> Result<()> {
        let err = |e: hdf5::Error| Error::Output { path: path.to_path_buf(), message: e.to_string() };
        let text = |s: &str| s.parse::<hdf5::types::VarLenUnicode>().map_err(|_| Error::Output { path: path.to_path_buf(), message: format!("text {s:?}") });
        let g = file.create_group(group).map_err(err)?;
        for (name, column) in &self.columns {
            match column {
                Column::Numbers(values, unit) => {
                    let d = g.new_dataset_builder().with_data(values.as_slice()).create(name.as_str()).map_err(err)?;
                    d.new_attr::<hdf5::types::VarLenUnicode>().create("units").map_err(err)?.write_scalar(&text(unit)?).map_err(err)?;
                }
                Column::Text(values) => {
                    let values = values.iter().map(|v| text(v)).collect::<Result<Vec<_>>>()?;
                    g.new_dataset_builder().with_data(values.as_slice()).create(name.as_str()).map_err(err)?;
                }
            }
        }
        Ok(())
    }

    /// The table as CSV, each header `name [unit]` where the column has one.
    pub fn write_csv(&self, path: &Path) -> Result<()> {
        let err = |e: csv::Error| Error::Output { path: path.to_path_buf(), message: e.to_string() };
        let mut w = csv::Writer::from_path(path).map_err(err)?;
        let header: Vec<String> = self
            .columns
            .iter()
            .map(|(name, c)| match c {
                Column::Numbers(_, unit) if !unit.is_empty() => format!("{name} [{unit}]"),
                _ => name.clone(),
            })
            .collect();
        w.write_record(&header).map_err(err)?;
        let rows = self.columns.first().map_or(0, |(_, c)| match c {
            Column::Numbers(v, _) => v.len(),
            Column::Text(v) => v.len(),
        });
        for r in 0..rows {
            let record: Vec<String> = self
                .columns
                .iter()
                .map(|(_, c)| match c {
                    Column::Numbers(v, _) => format!("{}", v[r]),
                    Column::Text(v) => v[r].clone(),
                })
                .collect();
            w.write_record(&record).map_err(err)?;
        }
        w.flush().map_err(|e| Error::Output { path: path.to_path_buf(), message: e.to_string() })
    }
}

/// An HDF5 file of tables: each table a group of columns, text attributes on the file or on a
/// group, a run's history copied in beside them. Written errors are output errors; read ones
/// name the file and the group.
pub struct TableFile {
    file: hdf5::File,
    path: PathBuf,
}

impl TableFile {
    /// A new file at `path` (replacing one there).
    pub fn create(path: &Path) -> Result<Self> {
        let file = hdf5::File::create(path).map_err(|e| Error::Output { path: path.to_path_buf(), message: e.to_string() })?;
        Ok(TableFile { file, path: path.to_path_buf() })
    }

    /// The file at `path`, to read.
    pub fn open(path: &Path, group: &str) -> Result<Self> {
        let file = hdf5::File::open(path).map_err(|e| Error::input(format!("{}: /{group}: {e}", path.display())))?;
        Ok(TableFile { file, path: path.to_path_buf() })
    }

    fn output_error(&self) -> impl Fn(hdf5::Error) -> Error + '_ {
        |e| Error::Output { path: self.path.clone(), message: e.to_string() }
    }

    /// Text attribute `name` on the file (`group` None) or on `group`.
    pub fn text_attr(&self, group: Option<&str>, name: &str, value: &str) -> Result<()> {
        let err = self.output_error();
        let text = value.parse::<VarLenUnicode>().map_err(|_| Error::Output { path: self.path.clone(), message: format!("text {value:?}") })?;
        match group {
            None => self.file.new_attr::<VarLenUnicode>().create(name).map_err(err)?.write_scalar(&text).map_err(self.output_error()),
            Some(g) => {
                let g = self.file.group(g).map_err(self.output_error())?;
                g.new_attr::<VarLenUnicode>().create(name).map_err(err)?.write_scalar(&text).map_err(self.output_error())
            }
        }
    }

    /// Table `t` as group `group`.
    pub fn table(&self, group: &str, t: &Table) -> Result<()> {
        t.write_group(&self.file, group, &self.path)
    }

    /// Group `group` (and the groups above it that are missing).
    pub fn group(&self, group: &str) -> Result<()> {
        let mut at = String::new();
        for part in group.split('/') {
            at = if at.is_empty() { part.to_string() } else { format!("{at}/{part}") };
            if !self.file.link_exists(&at) {
                self.file.create_group(&at).map_err(self.output_error())?;
            }
        }
        Ok(())
    }

    /// Each history column of the results file `results` as a dataset of `group` (created).
    pub fn copy_history(&self, group: &str, results: &Path) -> Result<()> {
        self.group(group)?;
        // a run that failed before its first increment has no history to copy
        let Ok(r) = super::reader::ResultsReader::open(results) else { return Ok(()) };
        let g = self.file.group(group).map_err(self.output_error())?;
        for c in r.history_columns()? {
            g.new_dataset_builder().with_data(r.history(&c)?.as_slice()).create(c.as_str()).map_err(self.output_error())?;
        }
        Ok(())
    }

    /// Whether the file has group `group`.
    pub fn has_group(&self, group: &str) -> bool {
        self.file.group(group).is_ok()
    }

    fn input_error<'e>(&'e self, group: &'e str) -> impl Fn(hdf5::Error) -> Error + 'e {
        move |e| Error::input(format!("{}: /{group}: {e}", self.path.display()))
    }

    /// Text column `name` of table `group`.
    pub fn texts(&self, group: &str, name: &str) -> Result<Vec<String>> {
        let g = self.file.group(group).map_err(self.input_error(group))?;
        Ok(g.dataset(name).and_then(|d| d.read_raw::<VarLenUnicode>()).map_err(self.input_error(group))?.iter().map(|s| s.to_string()).collect())
    }

    /// Number column `name` of table `group`.
    pub fn numbers(&self, group: &str, name: &str) -> Result<Vec<f64>> {
        let g = self.file.group(group).map_err(self.input_error(group))?;
        g.dataset(name).and_then(|d| d.read_raw::<f64>()).map_err(self.input_error(group))
    }

    /// Text attribute `name` of group `group`.
    pub fn group_text_attr(&self, group: &str, name: &str) -> Result<String> {
        let g = self.file.group(group).map_err(self.input_error(group))?;
        Ok(g.attr(name).and_then(|a| a.read_scalar::<VarLenUnicode>()).map_err(self.input_error(group))?.to_string())
    }
}

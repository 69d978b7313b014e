//! A table of columns (a study's rows, a verdict's lines) in HDF5 and CSV.

use crate::error::{Error, Result};
use std::path::Path;

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

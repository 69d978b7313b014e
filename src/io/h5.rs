//! The HDF5 helpers every writer of the results file uses: the file's marker attributes, errors
//! mapped to the file's name, datasets described (units and description) and written by slabs,
//! groups got or created.

use crate::element::solid::QUADRATURE_POINTS;
use crate::error::{Error, Result};
use crate::model::Precision;
use hdf5::types::VarLenUnicode;
use ndarray::{ArrayView1, ArrayView2, ArrayView3};
use std::path::Path;

/// Attribute of an increment group written after everything else of the increment.
pub const COMPLETE: &str = "complete";
/// Root attribute: the fields of every N-th increment (and of each step's last) are written.
pub const OUTPUT_EVERY: &str = "output_every";
/// Root attribute of files whose increments carry [`COMPLETE`] (older files do not).
pub const COMPLETION_MARKED: &str = "increments_marked_complete";

/// The root `geometry` attribute of a model of plane sections only.
pub(super) const PLANE: &str = "plane";

pub(super) fn h5err(path: &Path) -> impl Fn(hdf5::Error) -> Error + '_ {
    move |e| Error::Output { path: path.to_path_buf(), message: e.to_string() }
}

/// Group `name` of `parent`, created if it is not there yet (collective, as HDF5's metadata
/// calls are).
pub(super) fn group_in(parent: &hdf5::Group, name: &str, path: &Path) -> Result<hdf5::Group> {
    match parent.link_exists(name) {
        true => parent.group(name),
        false => parent.create_group(name),
    }
    .map_err(h5err(path))
}

/// Per-element Gauss-slot values (`C` numbers per slot) flattened for a dataset, with NaN in
/// the slots that are no integration point of their element (`used`: 9, or a reduced Q8's 4).
pub(super) fn gauss_rows<const C: usize>(values: &[[[f64; C]; QUADRATURE_POINTS]], used: &[usize]) -> Vec<f64> {
    let mut out = Vec::with_capacity(values.len() * QUADRATURE_POINTS * C);
    for (element, &n) in values.iter().zip(used) {
        for (q, slot) in element.iter().enumerate() {
            out.extend(slot.iter().map(|&v| if q < n { v } else { f64::NAN }));
        }
    }
    out
}

/// Writes the `units` and `description` attributes of a dataset (collective).
/// A plane model's file (its root `geometry` attribute "plane") gets the plane units.
pub(super) fn describe_dataset(ds: &hdf5::Dataset, units: &'static str, description: &str, path: &Path) -> Result<()> {
    let err = h5err(path);
    let geometry = ds.file().and_then(|f| f.attr("geometry")).and_then(|a| a.read_scalar::<VarLenUnicode>());
    let units = if geometry.is_ok_and(|g| g.as_str() == PLANE) { super::describe::plane_units(units) } else { units };
    for (attr, text) in [("units", units), ("description", description)] {
        let value: VarLenUnicode = text.parse().map_err(|_| Error::Output { path: path.to_path_buf(), message: format!("attribute text {text:?}") })?;
        ds.new_attr::<VarLenUnicode>().create(attr).map_err(&err)?.write_scalar(&value).map_err(&err)?;
    }
    Ok(())
}

/// A visualisation field (f64 as computed), stored at the run's `precision` (collective over
/// `world`, the file's ranks, as [`write_rows`]).
#[allow(clippy::too_many_arguments)]
pub(super) fn write_field(
    group: &hdf5::Group,
    name: &str,
    shape: &[usize],
    slab: (usize, usize),
    data: &[f64],
    precision: Precision,
    world: &impl mpi::traits::Communicator,
    path: &Path,
) -> Result<()> {
    match precision {
        Precision::Double => write_rows(group, name, shape, slab, data, path),
        Precision::Single => write_rows(group, name, shape, slab, &data.iter().map(|&v| v as f32).collect::<Vec<f32>>(), path),
        Precision::Resolution => {
            use mpi::collective::{CommunicatorCollectives, SystemOperation};
            // the largest value over every rank, and whether every value is finite (NaN marks
            // an unused Gauss slot): the filter's parameters are the dataset's, alike on all
            let local = data.iter().fold(0.0f64, |m, v| if v.is_finite() { m.max(v.abs()) } else { f64::INFINITY });
            let mut largest = 0.0f64;
            world.all_reduce_into(&local, &mut largest, SystemOperation::max());
            let units = super::describe::describe(&group.name(), name).0;
            let storage = match resolution_digits(units, largest) {
                Some(digits) => Storage::Scaled(digits),
                None => Storage::Plain,
            };
            let ds = write_rows_as(group, name, shape, slab, data, storage, path)?;
            let said = match storage {
                Storage::Scaled(d) => format!("1e-{d} {units}"),
                _ => "full (64-bit: a value is not finite)".to_string(),
            };
            let text: VarLenUnicode = said.parse().map_err(|_| Error::Output { path: path.to_path_buf(), message: "resolution".into() })?;
            ds.new_attr::<VarLenUnicode>().create("resolution").and_then(|a| a.write_scalar(&text)).map_err(h5err(path))
        }
    }
}

/// The decimal digits a field of `units` is kept to, whose largest value is `largest`: the
/// finer of its unit's resolution (1e-3 MPa, 1e-6 mm, 1e-8 for a strain or another unitless
/// figure, 1e-3 N) and 1e-6 of `largest`; None where a value is not finite.
pub fn resolution_digits(units: &str, largest: f64) -> Option<u8> {
    if !largest.is_finite() {
        return None;
    }
    let unit = if units.starts_with("MPa") {
        1e-3
    } else if units.starts_with("mm") {
        1e-6
    } else if units.starts_with('N') {
        1e-3
    } else {
        1e-8
    };
    let relative = if largest > 0.0 { 1e-6 * largest } else { unit };
    let resolution = unit.min(relative);
    Some((-resolution.log10()).ceil().clamp(0.0, 15.0) as u8)
}

/// Whether dataset `name` is stored chunked, shuffled and deflated: the fields that are zero
/// or constant over most of the mesh (reactions off the supports, plastic strains off the
/// yielded zones, contact state off the contact surfaces, a uniform temperature) shrink 3 to
/// 200 times and cost little to compress. Stresses, strains and displacements, whose doubles'
/// low bits are noise, shrink by a sixth at most for several times the write's cost, and stay
/// contiguous (docs/performance.md).
fn deflated(name: &str) -> bool {
    name == "reaction_force"
        || name == "temperature"
        || name == "plastic_points"
        || name.starts_with("plastic_strain_")
        || name.starts_with("backstress")
        || name.starts_with("equivalent_plastic_strain")
        || name.starts_with("contact_")
        || name.starts_with("friction_")
}

/// Values of a deflated dataset's chunk, at most: whole fields of meshes up to some 100 000
/// nodes in one chunk (a chunk is the unit HDF5 compresses and reads).
const CHUNK_VALUES: usize = 1 << 20;

/// How a dataset's values are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Storage {
    Plain,
    /// Chunked, shuffled and deflated (lossless).
    Deflated,
    /// Chunked, kept to 10^-digits by the scale-offset filter, then deflated.
    Scaled(u8),
}

/// Dataset `name` of `shape`, this rank's rows `slab` from `data` (collective: every rank
/// calls it, those without rows with an empty slab). Deflated datasets (see [`deflated`]) are
/// written through a collective transfer, as parallel HDF5 requires of filtered data.
pub(super) fn write_rows<T: hdf5::H5Type + Copy>(
    group: &hdf5::Group,
    name: &str,
    shape: &[usize],
    slab: (usize, usize),
    data: &[T],
    path: &Path,
) -> Result<()> {
    let storage = if deflated(name) { Storage::Deflated } else { Storage::Plain };
    write_rows_as(group, name, shape, slab, data, storage, path).map(|_| ())
}

/// [`write_rows`] with the storage given (a small dataset is stored plain whatever is asked).
fn write_rows_as<T: hdf5::H5Type + Copy>(
    group: &hdf5::Group,
    name: &str,
    shape: &[usize],
    slab: (usize, usize),
    data: &[T],
    storage: Storage,
    path: &Path,
) -> Result<hdf5::Dataset> {
    let err = h5err(path);
    let values: usize = shape.iter().product();
    let storage = if values >= 256 { storage } else { Storage::Plain };
    let builder = group.new_dataset::<T>().shape(shape.to_vec());
    let row: usize = shape[1..].iter().product();
    let mut chunk = shape.to_vec();
    chunk[0] = (CHUNK_VALUES / row.max(1)).clamp(1, shape[0].max(1));
    let ds = match storage {
        Storage::Plain => builder.create(name),
        Storage::Deflated => builder.chunk(chunk).shuffle().deflate(1).create(name),
        Storage::Scaled(digits) => builder.chunk(chunk).scale_offset(hdf5::filters::ScaleOffset::FloatDScale(digits)).deflate(1).create(name),
    }
    .map_err(&err)?;
    let (units, description) = super::describe::describe(&group.name(), name);
    describe_dataset(&ds, units, &description, path)?;
    let rows = slab.1 - slab.0;
    if storage != Storage::Plain {
        super::h5ffi::write_rows_collective(&ds, slab.0, rows, data)
            .map_err(|message| Error::Output { path: path.to_path_buf(), message: format!("{}/{name}: {message}", group.name()) })?;
        return Ok(ds);
    }
    if rows == 0 {
        return Ok(ds);
    }
    let shape_err = |e: ndarray::ShapeError| Error::Output { path: path.to_path_buf(), message: e.to_string() };
    match shape.len() {
        1 => ds.write_slice(ArrayView1::from(data), slab.0..slab.1),
        2 => ds.write_slice(ArrayView2::from_shape((rows, shape[1]), data).map_err(shape_err)?, (slab.0..slab.1, ..)),
        3 => ds.write_slice(ArrayView3::from_shape((rows, shape[1], shape[2]), data).map_err(shape_err)?, (slab.0..slab.1, .., ..)),
        _ => unreachable!("datasets have at most 3 dimensions"),
    }
    .map_err(&err)?;
    Ok(ds)
}

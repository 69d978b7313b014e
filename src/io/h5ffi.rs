//! The raw HDF5 calls the `hdf5` crate does not offer: a collective write of one rank's rows of
//! a dataset (parallel HDF5 writes chunked, filtered (compressed) datasets only through
//! collective transfers, and the crate writes with the default, independent, transfer property
//! list), a file's stored end of allocation, and a group created with link-storage properties.
//! Like `src/petsc/`, this is an FFI module (the only other place `unsafe` is allowed): every
//! `unsafe` block says why it is sound.
#![allow(unsafe_code)]

use hdf5::H5Type;
use hdf5_sys::h5::hsize_t;
use hdf5_sys::h5d::{H5Dget_space, H5Dwrite};
use hdf5_sys::h5i::hid_t;
use hdf5_sys::h5p::{H5FD_mpio_xfer_t, H5Pclose, H5Pcreate, H5Pset_dxpl_mpio};
use hdf5_sys::h5s::{H5S_seloper_t, H5Sclose, H5Screate_simple, H5Sselect_hyperslab, H5Sselect_none};

/// Closes an HDF5 identifier when dropped.
struct Id(hid_t, unsafe extern "C" fn(hid_t) -> hdf5_sys::h5::herr_t);

impl Drop for Id {
    fn drop(&mut self) {
        if self.0 >= 0 {
            // SAFETY: the identifier was returned valid by the HDF5 call that created it and is
            // closed once, here, by the close function of its kind.
            unsafe { (self.1)(self.0) };
        }
    }
}

fn check(id: hid_t, what: &str) -> Result<hid_t, String> {
    if id < 0 {
        Err(format!("HDF5 {what} failed"))
    } else {
        Ok(id)
    }
}

/// Writes `data`, rows `first .. first + rows` of `dataset` (whose other dimensions give the
/// row length), with a collective transfer: every rank of the file's communicator must call
/// it for the dataset, those without rows with `rows` = 0.
pub fn write_rows_collective<T: H5Type>(dataset: &hdf5::Dataset, first: usize, rows: usize, data: &[T]) -> Result<(), String> {
    let shape = dataset.shape();
    let row: usize = shape[1..].iter().product();
    if data.len() != rows * row || first + rows > shape.first().copied().unwrap_or(0) {
        return Err(format!("{} values for rows {first}..{} of a dataset of shape {shape:?}", data.len(), first + rows));
    }
    let memory_type = hdf5::Datatype::from_type::<T>().map_err(|e| e.to_string())?;
    hdf5::sync::sync(|| {
        // The identifiers are valid for the block (the dataset and datatype held by their Rust
        // owners, the others by `Id` guards); start and count have the dataset's rank.
        // SAFETY: the buffer holds exactly the selected rows x row values of the memory type
        // (checked above) and is only read; the rest are plain calls on valid identifiers.
        unsafe {
            let transfer = Id(check(H5Pcreate(*hdf5::globals::H5P_DATASET_XFER), "H5Pcreate(dataset transfer)")?, H5Pclose);
            if H5Pset_dxpl_mpio(transfer.0, H5FD_mpio_xfer_t::H5FD_MPIO_COLLECTIVE) < 0 {
                return Err("HDF5 H5Pset_dxpl_mpio failed".into());
            }
            let file_space = Id(check(H5Dget_space(dataset.id()), "H5Dget_space")?, H5Sclose);
            let mut count: Vec<hsize_t> = shape.iter().map(|&d| d as hsize_t).collect();
            let mut start = vec![0 as hsize_t; count.len()];
            if !count.is_empty() {
                count[0] = rows as hsize_t;
                start[0] = first as hsize_t;
            }
            // a rank without rows still takes part, with empty selections
            let memory_dims: Vec<hsize_t> = count.iter().map(|&c| c.max(1)).collect();
            let memory_space = Id(check(H5Screate_simple(memory_dims.len() as i32, memory_dims.as_ptr(), std::ptr::null()), "H5Screate_simple")?, H5Sclose);
            let selected = if rows == 0 {
                H5Sselect_none(file_space.0).min(H5Sselect_none(memory_space.0))
            } else {
                H5Sselect_hyperslab(file_space.0, H5S_seloper_t::H5S_SELECT_SET, start.as_ptr(), std::ptr::null(), count.as_ptr(), std::ptr::null())
            };
            if selected < 0 {
                return Err("HDF5 selection failed".into());
            }
            let placeholder = [0u8; 16];
            let buffer = if rows == 0 { placeholder.as_ptr().cast() } else { data.as_ptr().cast() };
            if H5Dwrite(dataset.id(), memory_type.id(), memory_space.0, file_space.0, transfer.0, buffer) < 0 {
                return Err("HDF5 H5Dwrite (collective) failed".into());
            }
            Ok(())
        }
    })
}

extern "C" {
    // HDF5 >= 1.10.2 (H5Fpublic.h); not among hdf5-sys's bindings
    fn H5Fget_eoa(file_id: hid_t, eoa: *mut hdf5_sys::h5::haddr_t) -> hdf5_sys::h5::herr_t;
}

/// The end of allocation `file`'s superblock records: every object the file's metadata
/// addresses lies before it (HDF5 refuses one past it: "addr overflow").
pub fn end_of_allocation(file: &hdf5::File) -> Result<u64, String> {
    let mut eoa: hdf5_sys::h5::haddr_t = 0;
    // SAFETY: the file identifier is valid while `file` lives, and `eoa` is a valid place for
    // the one value the call writes.
    let status = hdf5::sync::sync(|| unsafe { H5Fget_eoa(file.id(), &mut eoa) });
    if status < 0 {
        return Err("HDF5 H5Fget_eoa failed".into());
    }
    Ok(eoa)
}

/// Creates group `name` of `parent` for up to `links` links held in one piece of metadata:
/// compact link storage (the links in the group's object header, with their creation order),
/// the header sized for `links` names of `name_length` characters at once. A group that gains
/// a link per increment otherwise keeps its names in a local heap and a B-tree of symbol nodes
/// that split and move as it grows: a writer killed while flushing such a change (SIGKILL, in
/// about 1 of 40 kills timed into the writes) left the heap's header and block from different
/// flushes ("bad heap free list") or a B-tree pointing at a node never written (the links of
/// five increments lost). One object header is written whole by each flush.
pub fn create_group_for_links(parent: &hdf5::Group, name: &str, links: u16, name_length: u16) -> Result<(), String> {
    use hdf5_sys::h5g::{H5Gclose, H5Gcreate2};
    use hdf5_sys::h5p::{H5Pset_est_link_info, H5Pset_link_creation_order, H5Pset_link_phase_change, H5P_CRT_ORDER_TRACKED};
    let name = std::ffi::CString::new(name).map_err(|_| format!("group name {name:?} holds a NUL"))?;
    hdf5::sync::sync(|| {
        // SAFETY: plain calls on identifiers valid for the block (the property list held by its
        // `Id` guard, `parent` by its Rust owner); `name` is a NUL-terminated string that
        // outlives the call; the new group's identifier is closed at once.
        unsafe {
            let create = Id(check(H5Pcreate(*hdf5::globals::H5P_GROUP_CREATE), "H5Pcreate(group creation)")?, H5Pclose);
            // tracking the creation order makes the group of the newer format (compact links)
            // whatever the file's format bounds
            if H5Pset_link_creation_order(create.0, H5P_CRT_ORDER_TRACKED) < 0
                || H5Pset_link_phase_change(create.0, u16::MAX as u32, u16::MAX as u32) < 0
                || H5Pset_est_link_info(create.0, links as u32, name_length as u32) < 0
            {
                return Err("HDF5 group creation properties refused".into());
            }
            let group = check(H5Gcreate2(parent.id(), name.as_ptr(), hdf5_sys::h5p::H5P_DEFAULT, create.0, hdf5_sys::h5p::H5P_DEFAULT), "H5Gcreate2")?;
            H5Gclose(group);
            Ok(())
        }
    })
}

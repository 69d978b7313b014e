//! Field output at a stated resolution (`--output-precision resolution`: HDF5's scale-offset
//! filter, decimal scaling): the quick joint written both ways on 1 rank, every field of
//! every increment read back with the hdf5 crate (as h5py would) agrees with the full-precision
//! file within the resolution its `resolution` attribute states, which is the finer of its
//! unit's (1e-3 MPa, 1e-8 strain, 1e-6 mm) and 1e-6 of its largest value; what is not a
//! visualisation field (the displacement, the restart state, the history, the mesh) is the
//! same bit for bit; meshio reads the file through its XDMF sidecar; and a restart from a
//! middle increment of such a file continues bit for bit on 1 rank. The default file's
//! 32-bit fields hold each value as the 32-bit float nearest it (2^-24 of itself).

mod common;
use common::{command_in, Results};
use std::path::Path;

/// The quick joint, 20 mm in 4 increments, into `dir/name` with `precision` on `ranks` ranks.
fn quick(dir: &Path, name: &str, precision: &str, ranks: usize, extra: &[&str]) {
    let out = command_in(dir, ranks)
        .current_dir(dir)
        .args(["bellows", "--quick", "--displacement", "20", "--increments", "4", "--quiet", "--output-precision", precision, "-o", name])
        .args(extra)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// Every dataset under `a`'s group, against `b`'s: within the stated resolution where `b`
/// states one, the 32-bit float nearest `a`'s value where `b` holds 32-bit floats, else bit
/// for bit. Returns how many fields had a resolution or 32 bits.
fn compare(a: &hdf5::Group, b: &hdf5::Group) -> usize {
    let mut stated = 0;
    for name in a.member_names().unwrap() {
        if let Ok(g) = a.group(&name) {
            stated += compare(&g, &b.group(&name).unwrap());
            continue;
        }
        let (x, y) = (a.dataset(&name).unwrap(), b.dataset(&name).unwrap());
        let what = format!("{}/{name}", a.name());
        assert_eq!(x.shape(), y.shape(), "{what}");
        if !matches!(x.dtype().unwrap().to_descriptor().unwrap(), hdf5::types::TypeDescriptor::Float(_)) {
            continue;
        }
        let (p, q) = (x.read_raw::<f64>().unwrap(), y.read_raw::<f64>().unwrap());
        if (x.dtype().unwrap().size(), y.dtype().unwrap().size()) == (8, 4) {
            let nearest = |u: f64| f64::from(u as f32);
            assert!(p.iter().zip(&q).all(|(&u, &v)| nearest(u).to_bits() == v.to_bits()), "{what}: not the nearest 32-bit floats");
            stated += 1;
            continue;
        }
        match y.attr("resolution").ok().map(|r| r.read_scalar::<hdf5::types::VarLenUnicode>().unwrap().to_string()) {
            Some(text) if !text.starts_with("full") => {
                let resolution: f64 = text.split(' ').next().unwrap().parse().unwrap_or_else(|_| panic!("{what}: {text}"));
                // at least as fine as 1e-6 of the largest value and as the coarsest unit's (1e-3)
                let largest = p.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(resolution <= 1e-3 && (largest == 0.0 || resolution <= 1e-6 * largest * (1.0 + 1e-12)), "{what}: {resolution} for largest {largest}");
                let worst = p.iter().zip(&q).map(|(u, v)| (u - v).abs()).fold(0.0f64, f64::max);
                assert!(worst <= resolution * (1.0 + 1e-9), "{what}: differs by {worst:e}, its resolution is {resolution:e}");
                stated += 1;
            }
            _ => assert!(p.iter().zip(&q).all(|(u, v)| u.to_bits() == v.to_bits()), "{what} differs"),
        }
    }
    stated
}

#[test]
fn every_field_agrees_within_its_stated_resolution() {
    let dir = tempfile::tempdir().unwrap();
    // on 1 rank: two runs on 2 are equal only to the direct solver's summation order
    quick(dir.path(), "full.h5", "full", 1, &[]);
    quick(dir.path(), "stated.h5", "resolution", 1, &[]);
    let (a, b) = (Results::open(&dir.path().join("full.h5")), Results::open(&dir.path().join("stated.h5")));
    let stated = compare(&a.file.group("increments").unwrap(), &b.file.group("increments").unwrap());
    assert!(stated > 100, "{stated} fields with a stated resolution");
    assert_eq!(a.f64s("mesh/coordinates"), b.f64s("mesh/coordinates"));
    for name in a.file.group("history").unwrap().member_names().unwrap().iter().filter(|n| *n != "wall_time") {
        let (x, y) = (a.history(name), b.history(name));
        assert!(x.len() == y.len() && x.iter().zip(&y).all(|(u, v)| u.to_bits() == v.to_bits()), "history/{name}");
    }
    let (full, small) = (std::fs::metadata(dir.path().join("full.h5")).unwrap().len(), std::fs::metadata(dir.path().join("stated.h5")).unwrap().len());
    assert!(small < full, "{small} bytes against {full}");
    // meshio reads the sidecar: each increment a step, the fields as h5py reads them, the
    // nodal stresses the Gauss values carried to the nodes within the stated resolutions
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/check_xdmf.py");
    let read = common::python().arg(&script).arg(dir.path().join("stated.xmf")).current_dir("/").output().expect("python3");
    let text = format!("{}{}", String::from_utf8_lossy(&read.stdout), String::from_utf8_lossy(&read.stderr));
    assert!(read.status.success() && text.trim_end().ends_with("ok"), "{text}");
}

/// The default precision: every visualisation field of every increment is the 32-bit float
/// nearest the value computed (the same run with `--output-precision double`), the rest bit
/// for bit.
#[test]
fn the_default_file_holds_the_32_bit_float_nearest_each_value() {
    let dir = tempfile::tempdir().unwrap();
    quick(dir.path(), "full.h5", "double", 1, &[]);
    let out = command_in(dir.path(), 1)
        .current_dir(dir.path())
        .args(["bellows", "--quick", "--displacement", "20", "--increments", "4", "--quiet", "-o", "default.h5"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (a, b) = (Results::open(&dir.path().join("full.h5")), Results::open(&dir.path().join("default.h5")));
    let single = compare(&a.file.group("increments").unwrap(), &b.file.group("increments").unwrap());
    assert!(single > 100, "{single} fields of 32 bits");
}

#[test]
fn a_restart_from_a_file_at_a_stated_resolution_continues_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    quick(dir.path(), "whole.h5", "resolution", 1, &[]);
    quick(dir.path(), "continued.h5", "resolution", 1, &["--restart", "whole.h5", "--increment", "3"]);
    common::assert_continues(&dir.path().join("whole.h5"), &dir.path().join("continued.h5"), 3);
}

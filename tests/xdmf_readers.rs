//! The XDMF sidecar opens in the tools engineers use: meshio's TimeSeriesReader (what many
//! Python post-processing scripts use; ParaView's Xdmf3 reader takes the same plain data items)
//! reads every increment of a 2-rank run of the quick bellows, from another working directory,
//! and what it reads equals the HDF5 file: times, mesh, displacement, element fields, and the
//! nodal stresses equal the Gauss-point stresses carried to the nodes, recomputed in Python
//! (scripts/check_xdmf.py; `./run.sh test` installs Debian's meshio, h5py and numpy).

mod common;
use common::command_in;

#[test]
fn meshio_reads_every_increment_and_the_fields_equal_the_results_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = command_in(dir.path(), 2)
        .current_dir(dir.path())
        .args(["bellows", "--quick", "--displacement", "20", "--increments", "4", "--quiet", "-o", "joint.h5"])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/check_xdmf.py");
    let check = common::python().arg(&script).arg(dir.path().join("joint.xmf")).current_dir("/").output().expect("python3");
    let text = format!("{}{}", String::from_utf8_lossy(&check.stdout), String::from_utf8_lossy(&check.stderr));
    assert!(check.status.success() && text.trim_end().ends_with("ok"), "{text}");
    assert!(text.contains("6 increment steps after the t = 0 frame"), "2 heat and 4 compression increments: {text}");
}

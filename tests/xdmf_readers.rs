//! The XDMF sidecar opens in the tools engineers use: meshio's TimeSeriesReader (what many
//! Python post-processing scripts use; ParaView's Xdmf3 reader takes the same plain data items)
//! reads every increment of a 2-rank run of the quick bellows, from another working directory,
//! and what it reads equals the HDF5 file: times, mesh, displacement, element fields, and the
//! nodal stresses equal the Gauss-point stresses carried to the nodes, recomputed in Python
//! (scripts/check_xdmf.py; `./run.sh test` installs Debian's meshio, h5py and numpy). The
//! same holds for a file of 64-bit visualisation fields (`--output-precision double`), and
//! the mostly-zero fields are stored deflated by the 2-rank collective write.

mod common;
use common::command_in;
use hdf5::filters::Filter;
use std::path::Path;

/// The Python check of the sidecar of `xmf`; its output.
fn check(xmf: &Path) -> String {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/check_xdmf.py");
    let check = common::python().arg(&script).arg(xmf).current_dir("/").output().expect("python3");
    let text = format!("{}{}", String::from_utf8_lossy(&check.stdout), String::from_utf8_lossy(&check.stderr));
    assert!(check.status.success() && text.trim_end().ends_with("ok"), "{text}");
    text
}

/// The quick joint, 20 mm in 4 increments on 2 ranks, into `dir/name`, then the XDMF check.
fn run_and_check(dir: &Path, name: &str, extra: &[&str]) {
    let out = command_in(dir, 2)
        .current_dir(dir)
        .args(["bellows", "--quick", "--displacement", "20", "--increments", "4", "--quiet", "-o", name])
        .args(extra)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = check(&dir.join(name).with_extension("xmf"));
    assert!(text.contains("6 increment steps after the t = 0 frame"), "2 heat and 4 compression increments: {text}");
}

/// A mesh of 6-node triangles, part yielded (the bore's elements copy their nearest Gauss
/// point, the others are fitted): meshio reads XDMF's Triangle_6 cells, and the nodal stresses
/// equal the Gauss values carried to the nodes as recomputed in Python.
#[test]
fn meshio_reads_a_triangle_mesh_and_its_nodal_stresses_are_the_recovered_ones() {
    let deck = format!(
        r#"nlgeom = false
[mesh]
rectangle = {{ r = [100.0, 130.0], z = [0.0, 3.0], divisions = [8, 2], triangles = true }}
{PLASTIC_STEEL}[[step]]
increments = 3
boundary = [ {{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = 0.0 }} ]
pressure = [ {{ surface = "inner", value = 80.0 }} ]
"#,
        PLASTIC_STEEL = common::PLASTIC_STEEL
    );
    let run = common::run_deck(&deck, &[], 2, &[]);
    run.assert_ok();
    let text = check(&run.h5.with_extension("xmf"));
    assert!(text.contains("mesh: ") && text.contains(" 32 triangle6 cells"), "{text}");
    let file = hdf5::File::open(&run.h5).unwrap();
    let ep = file.dataset("increments/000003/equivalent_plastic_strain").unwrap().read_raw::<f64>().unwrap();
    let yielded = ep.chunks(9).filter(|e| e.iter().any(|&v| v > 0.0)).count();
    assert!(yielded > 0 && yielded < 32, "{yielded} of 32 elements yielded: both recovery rules are checked");
}

#[test]
fn meshio_reads_every_increment_and_the_fields_equal_the_results_file() {
    let dir = tempfile::tempdir().unwrap();
    run_and_check(dir.path(), "double.h5", &["--output-precision", "double"]);
    run_and_check(dir.path(), "joint.h5", &[]);
    let (double, single) = (hdf5::File::open(dir.path().join("double.h5")).unwrap(), hdf5::File::open(dir.path().join("joint.h5")).unwrap());
    let width = |f: &hdf5::File, d: &str| f.dataset(&format!("increments/000006/{d}")).unwrap().dtype().unwrap().size();
    for d in ["nodal/stress_rr", "nodal/von_mises", "stress", "nodal/reaction_force", "nodal/contact_pressure"] {
        assert_eq!((width(&double, d), width(&single, d)), (8, 4), "{d}: 32-bit by default, 64-bit on request");
    }
    for d in ["nodal/displacement", "state/plastic_state"] {
        assert_eq!(width(&single, d), 8, "{d}: the restart reads it, always 64-bit");
    }
    // the fields zero over most of the mesh are deflated; the noise-like stresses are not
    let deflated = |d: &str| double.dataset(&format!("increments/000006/{d}")).unwrap().filters().iter().any(|f| matches!(f, Filter::Deflate(_)));
    for d in ["nodal/reaction_force", "nodal/plastic_strain_rr", "nodal/contact_gap", "nodal/temperature", "equivalent_plastic_strain"] {
        assert!(deflated(d), "{d} is stored deflated");
    }
    assert!(!deflated("stress"));
    let stored = |f: &hdf5::File, d: &str| f.dataset(&format!("increments/000006/{d}")).unwrap().storage_size();
    let raw = 8 * 3 * double.dataset("mesh/node_ids").unwrap().size() as u64;
    assert!(
        stored(&double, "nodal/reaction_force") * 20 < raw,
        "reactions (nonzero at the supports only) shrink: {} of {raw} bytes",
        stored(&double, "nodal/reaction_force")
    );
    // one number per increment for the uniform temperature
    let t = double.group("increments/000006").unwrap().attr("temperature").unwrap().read_scalar::<f64>().unwrap();
    assert_eq!(t, 200.0, "the bellows' operating temperature");
    let size = |f: &str| std::fs::metadata(dir.path().join(f)).unwrap().len() as f64;
    assert!(size("joint.h5") < 0.75 * size("double.h5"), "single precision: {} against {} bytes", size("joint.h5"), size("double.h5"));
}

/// Kinematic hardening's backstress is in the file (Gauss points, `backstress`) and at the
/// nodes (`backstress_rr` .. `backstress_von_mises`), which meshio reads at every increment of
/// a 2-rank run with the other fields (and zeros at t = 0). What is stored is the state the
/// solver had: at every Gauss point that flowed in the last increment the stress sits on the
/// moved yield surface, sqrt(3/2) |s - alpha| = sigma_y (300 MPa, no isotropic hardening),
/// within 1e-6, in a cylinder loaded past yield and then taken to suction (reverse yield).
#[test]
fn meshio_reads_the_backstress_and_flowing_points_sit_on_the_moved_surface() {
    let deck = r#"nlgeom = false
[mesh]
rectangle = { r = [100.0, 130.0], z = [0.0, 3.0], divisions = [8, 2] }
[[material]]
name = "steel"
model = "j2"
youngs_modulus = 200000.0
poissons_ratio = 0.3
yield_stress = 300.0
backstresses = [ { modulus = 20000.0, recall = 100.0 }, { modulus = 5000.0 } ]
[[step]]
increments = 4
boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 } ]
pressure = [ { surface = "inner", value = 84.0 } ]
[[step]]
increments = 4
pressure = [ { surface = "inner", value = -75.0 } ]
"#;
    let run = common::run_deck(deck, &[], 2, common::DOUBLE);
    run.assert_ok();
    let text = check(&run.h5.with_extension("xmf"));
    assert!(text.contains("8 increment steps after the t = 0 frame"), "{text}");
    let xmf = std::fs::read_to_string(run.h5.with_extension("xmf")).unwrap();
    assert!(xmf.contains("Name=\"backstress_von_mises\""), "the sidecar lists the nodal backstress");
    let file = hdf5::File::open(&run.h5).unwrap();
    let read = |inc: &str, name: &str| file.dataset(&format!("increments/{inc}/{name}")).unwrap().read_raw::<f64>().unwrap();
    let (stress, back) = (read("000008", "stress"), read("000008", "backstress"));
    let (ep, ep_before) = (read("000008", "equivalent_plastic_strain"), read("000007", "equivalent_plastic_strain"));
    let mut flowing = 0;
    for k in 0..ep.len() {
        if ep[k] > ep_before[k] {
            let relative: [f64; 4] = std::array::from_fn(|c| stress[4 * k + c] - back[4 * k + c]);
            let mean = (relative[0] + relative[1] + relative[2]) / 3.0;
            let s = [relative[0] - mean, relative[1] - mean, relative[2] - mean, relative[3]];
            let q = (1.5 * (s[0] * s[0] + s[1] * s[1] + s[2] * s[2] + 2.0 * s[3] * s[3])).sqrt();
            assert!((q / 300.0 - 1.0).abs() < 1e-6, "Gauss point {k}: sqrt(3/2) |s - alpha| = {q}");
            flowing += 1;
        }
    }
    assert!(flowing > 0, "some points yield in reverse in the last increment");
    // at the end of the loading the bore has a backstress of some MPa (C ep, ep ~ 5e-4)
    let nodal = read("000004", "nodal/backstress_von_mises");
    assert!(nodal.iter().all(|v| *v >= 0.0) && nodal.iter().any(|v| *v > 5.0), "{nodal:?}");
}

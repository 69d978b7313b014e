//! The same analysis on 1 rank and on 2 ranks (mpirun -n 2) gives the same displacements to
//! 1e-8 relative, and the 2-rank HDF5 file reads back (h5dump and the hdf5 crate) with its
//! history rows and fields.
//! Model: a 24 x 4 Q8 ring r in [100, 130], z in [0, 20], finite strain, J2 (sigma_y0 = 150,
//! H = 1000), internal pressure 20 MPa, heated by 50 degC, bottom held axially, top pushed down
//! 0.3 mm so the ring yields; two steps (heat+pressure, then push).

mod common;
use common::{displacement_difference, run_deck, run_serial_and_parallel, Results};
use std::process::Command;

const DECK: &str = r#"
[mesh]
rectangle = { r = [100.0, 130.0], z = [0.0, 20.0], divisions = [24, 4] }

[[material]]
name = "steel"
model = "j2"
youngs_modulus = 200000.0
poissons_ratio = 0.3
thermal_expansion = 1.2e-5
yield_stress = 150.0
hardening_modulus = 1000.0

[[step]]
name = "heat"
increments = 2
temperature = 70.0
boundary = [ { set = "bottom", uz = 0.0 } ]
pressure = [ { surface = "inner", value = 20.0 } ]

[[step]]
name = "push"
increments = 3
boundary = [ { set = "top", uz = -0.3 } ]
"#;

#[test]
fn two_ranks_match_one_rank_and_the_file_reads_back() {
    let (_serial, r1, parallel, r2) = run_serial_and_parallel(DECK, &[]);
    let (worst, scale) = displacement_difference(&r1, &r2);
    assert!(worst <= 1e-8 * scale, "1 vs 2 ranks differ by {worst:e} (scale {scale:e})");

    // the case is plastic
    let ep = r2.history("max_equivalent_plastic_strain");
    assert!(*ep.last().unwrap() > 1e-4, "not plastic: {ep:?}");
    let ep1 = r1.history("max_equivalent_plastic_strain");
    assert!((ep1.last().unwrap() - ep.last().unwrap()).abs() <= 1e-8 * ep.last().unwrap());

    // both ranks really assembled elements
    let ranks = r2.file.dataset("mesh/element_rank").unwrap().read_raw::<u32>().unwrap();
    assert!(ranks.contains(&0) && ranks.contains(&1), "partition used one rank only: {ranks:?}");
    assert_eq!(r2.file.attr("ranks").unwrap().read_scalar::<u32>().unwrap(), 2);

    // history: one row per increment (2 + 3), with the reaction of the set pushed in step 2
    let steps = r2.f64s("history/step");
    assert_eq!(steps, vec![1.0, 1.0, 2.0, 2.0, 2.0]);
    let top = r2.f64s("history/reaction_top_z");
    assert!(top[..2].iter().all(|v| v.is_nan()) && top[2..].iter().all(|v| v.is_finite() && *v < 0.0), "{top:?}");
    assert_eq!(r2.f64s("history/reaction_bottom_z").len(), 5);
    let n = r2.file.group("increments").unwrap().member_names().unwrap().len();
    assert_eq!(n, 5);

    // a plain HDF5 tool reads the same file
    let dump = Command::new("h5dump").args(["-d", "/history/load_factor"]).arg(&parallel.h5).output().expect("h5dump (hdf5-tools) installed");
    let text = String::from_utf8_lossy(&dump.stdout);
    assert!(dump.status.success() && text.contains("0.5, 1, 0.333333"), "h5dump output:\n{text}");
    // and the XDMF sidecar is well-formed and names every increment
    let xmf = std::fs::read_to_string(parallel.h5.with_extension("xmf")).expect("xmf sidecar");
    assert_eq!(xmf.matches("<Grid Name=\"increment").count(), 5);
}

#[test]
fn an_element_inverted_on_one_rank_cuts_the_increment_back_on_both() {
    // Full Newton steps (no line search) from the pushed end nodes alone (no predictor)
    // overshoot in the plastic push and invert elements on one rank: every rank must still
    // meet in the collective assembly, report the domain error together, and cut back; this
    // used to hang.
    let deck = format!("[stepping]\npredictor = false\n{DECK}");
    let run = run_deck(&deck, &[], 2, &["--", "-snes_linesearch_type", "basic"]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    assert!(res.history("cutbacks").iter().sum::<f64>() >= 1.0, "expected the push to need cutbacks");
    assert_eq!(*res.history("time").last().unwrap(), 2.0);
    // with the predictor (the default) the same full Newton steps need no cutback and fewer
    // iterations in the push
    let predicted = run_deck(DECK, &[], 2, &["--", "-snes_linesearch_type", "basic"]);
    predicted.assert_ok();
    let with = Results::open(&predicted.h5);
    assert_eq!(with.history("cutbacks").iter().sum::<f64>(), 0.0);
    let push_iterations = |r: &Results| r.history("newton_iterations")[2..].iter().sum::<f64>();
    assert!(push_iterations(&with) < push_iterations(&res), "{} vs {}", push_iterations(&with), push_iterations(&res));
}

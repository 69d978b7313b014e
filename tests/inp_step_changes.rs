//! What CalculiX users change from step to step: a block r 100..110, z 0..10 (elastic, two
//! CAX4 elements a side), held axially at its bottom (model data), is pressed 0.01 mm at its
//! top in step 1 (uniaxial: sigma_z = -E 0.01 / 10 = -200 MPa with the bore and outside free);
//! step 2's *BOUNDARY, OP=NEW restates only the bottom, so the top is let go and the elastic
//! block springs back to zero stress, and its top to u_z = 0; step 3 changes nothing and asks
//! for no field output (*NODE FILE, FREQUENCY=0): its increments are in the history only. A
//! restart from the end of step 1 continues through the release bit for bit.

mod common;
use common::{command_in, Results};
use std::path::Path;

const DECK: &str = "*NODE, NSET=NALL
1, 100., 0.
2, 105., 0.
3, 110., 0.
4, 100., 5.
5, 105., 5.
6, 110., 5.
7, 100., 10.
8, 105., 10.
9, 110., 10.
*ELEMENT, TYPE=CAX4, ELSET=BLOCK
1, 1, 2, 5, 4
2, 2, 3, 6, 5
3, 4, 5, 8, 7
4, 5, 6, 9, 8
*NSET, NSET=BOTTOM
1, 2, 3
*NSET, NSET=TOP
7, 8, 9
*MATERIAL, NAME=STEEL
*ELASTIC
200000., 0.3
*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL
*BOUNDARY
BOTTOM, 2, 2
*STEP
*STATIC
0.5, 1.
*BOUNDARY
TOP, 2, 2, -0.01
*END STEP
*STEP
*STATIC
0.5, 1.
*BOUNDARY, OP=NEW
BOTTOM, 2, 2
*END STEP
*STEP
*STATIC
0.5, 1.
*NODE FILE, FREQUENCY=0
U
*END STEP
";

fn run(dir: &Path, extra: &[&str], out: &str) -> std::process::Output {
    let deck = dir.join("block.inp");
    std::fs::write(&deck, DECK).unwrap();
    let output = command_in(dir, 2).arg("run").arg(&deck).arg("-o").arg(dir.join(out)).args(extra).output().unwrap();
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    output
}

fn top_uz_and_largest_stress(res: &Results, increment: &str) -> (f64, f64) {
    let x = res.f64s("mesh/coordinates");
    let u = res.displacement(increment);
    let top: Vec<f64> = x.chunks(2).zip(u.chunks(2)).filter(|(x, _)| x[1] == 10.0).map(|(_, u)| u[1]).collect();
    assert_eq!(top.len(), 5, "the top's corner and mid-side nodes");
    let stress = res.f64s(&format!("{increment}/stress"));
    (top.iter().sum::<f64>() / top.len() as f64, stress.iter().fold(0.0f64, |m, s| m.max(s.abs())))
}

#[test]
fn op_new_releases_the_top_and_frequency_zero_writes_no_fields() {
    let dir = tempfile::tempdir().unwrap();
    let out = run(dir.path(), &[], "full.h5");
    let text = String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(text.contains("OP=NEW releases TOP u_z"), "{text}");
    let res = Results::open(&dir.path().join("full.h5"));
    // two increments a step, three steps: six history rows, fields of the first four only
    assert_eq!(res.history("step"), vec![1.0, 1.0, 2.0, 2.0, 3.0, 3.0]);
    let increments = res.increments();
    assert_eq!(increments.len(), 4, "{increments:?}");
    // step 1: pressed, uniaxial -200 MPa
    let (uz, _) = top_uz_and_largest_stress(&res, &increments[1]);
    assert!((uz + 0.01).abs() < 1e-12, "pressed top {uz}");
    let stress = res.f64s(&format!("{}/stress", increments[1]));
    assert!(stress.chunks(4).all(|s| (s[1] + 200.0).abs() < 1e-6 && s[0].abs() < 1e-6), "{:?}", &stress[..8]);
    // step 2: released, back to zero
    let (uz, worst) = top_uz_and_largest_stress(&res, &increments[3]);
    assert!(uz.abs() < 1e-12 && worst < 1e-6, "released top at {uz}, stress {worst}");
    // the energy the sudden release frees is the audit's balance error (a static analysis has
    // nowhere else to put it): the elastic energy stored at the end of step 1
    let (elastic, balance) = (res.history("energy_elastic"), res.history("energy_balance_error"));
    assert!(balance[1].abs() < 1e-9 * elastic[1], "{balance:?}");
    assert!((balance[3] - elastic[1]).abs() < 1e-9 * elastic[1] && elastic[3] < 1e-12 * elastic[1], "{balance:?} {elastic:?}");
}

#[test]
fn a_restart_before_the_release_continues_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    run(dir.path(), &["--quiet", "--", "-ksp_type", "preonly", "-pc_type", "redundant", "-redundant_pc_type", "lu"], "full.h5");
    let full = dir.path().join("full.h5");
    run(
        dir.path(),
        &[
            "--quiet",
            "--restart",
            full.to_str().unwrap(),
            "--increment",
            "2",
            "--",
            "-ksp_type",
            "preonly",
            "-pc_type",
            "redundant",
            "-redundant_pc_type",
            "lu",
        ],
        "more.h5",
    );
    common::assert_continues(&full, &dir.path().join("more.h5"), 2);
}

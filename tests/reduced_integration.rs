//! CalculiX's reduced 8-node element (CAX8R: 2 x 2 Gauss points, no volumetric treatment)
//! from end to end: a thick cylinder a = 100, b = 150 mm of 8 CAX8R elements across the wall,
//! ends held axially (plane strain), E = 200 GPa, nu = 0.3, yield 300 MPa with H = 1000 MPa,
//! 60 then 120 MPa inside, on 2 ranks.
//!
//! At 60 MPa it is elastic, against Lame (Timoshenko & Goodier, Theory of Elasticity, 3rd ed.,
//! 1970, sect. 33): u_r(a) = (1 + nu) p a^2 / (E (b^2 - a^2)) ((1 - 2 nu) a + b^2 / a)
//! = 0.082680 mm (to 1e-6; it meets it to 1e-13), and the membrane hoop stress across the
//! wall, the integral of sigma_t over the thickness, is p a / (b - a) = 120 MPa exactly, which
//! `post --linearize` must print (1e-4; it prints 119.9996). At 120 MPa the bore has yielded (first yield at
//! 95.7 MPa: von Mises 3.134 p there) and the outside has not.
//!
//! What users see of the reduced element: `mesh/gauss_points` is 4 for each; the Gauss-point
//! datasets hold NaN in its 5 spare slots, and the XDMF check (scripts/check_xdmf.py, meshio and
//! h5py) recomputes the nodal stresses from the 2 x 2 points in Python (the bilinear field
//! where elastic, the nearest point where yielded); the element mean von Mises is the mean of
//! its 4 points; `post --field von_mises` reports finite extremes.

mod common;
use common::{cax8_wall, command_in, node_list, run_deck_file, Results};
use std::fmt::Write as _;

const A: f64 = 100.0;
const B: f64 = 150.0;
const E: f64 = 200_000.0;
const NU: f64 = 0.3;

fn deck() -> String {
    let (wall, nodes) = cax8_wall(A, B, 8, 5.0);
    let mut w = wall.replace("TYPE=CAX8,", "TYPE=CAX8R,");
    let _ = write!(
        w,
        "*NSET, NSET=BOTTOM\n{}\n*NSET, NSET=TOP\n{}\n*MATERIAL, NAME=STEEL\n*ELASTIC\n{E}, {NU}\n*PLASTIC\n300., 0.\n1300., 1.\n\
         *SOLID SECTION, ELSET=WALL, MATERIAL=STEEL\n*BOUNDARY\nBOTTOM, 2, 2\nTOP, 2, 2\n\
         *STEP\n*STATIC, DIRECT\n0.5, 1.\n*DLOAD\n1, P4, 120.\n*END STEP\n",
        node_list(&nodes, |_, z| z == 0.0),
        node_list(&nodes, |_, z| z == 5.0)
    );
    w
}

fn post(run: &common::Run, args: &[&str]) -> String {
    let out = command_in(run.dir.path(), 1).arg("post").arg(&run.h5).args(args).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(out.status.success(), "{text}{}", String::from_utf8_lossy(&out.stderr));
    text
}

#[test]
fn a_cylinder_of_reduced_elements_meets_lame_and_its_outputs_read_right() {
    let run = run_deck_file("cylinder.inp", &deck(), &[], 2, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    assert!(res.i64s("mesh/gauss_points").iter().all(|&n| n == 4));

    // increment 1, elastic: Lame
    let p = 60.0;
    let exact = (1.0 + NU) * p * A * A / (E * (B * B - A * A)) * ((1.0 - 2.0 * NU) * A + B * B / A);
    let increments = res.increments();
    let u1 = res.displacement(&increments[0]);
    let coords = res.f64s("mesh/coordinates");
    let bore_u: Vec<f64> = (0..coords.len() / 2).filter(|&n| (coords[2 * n] - A).abs() < 1e-9).map(|n| u1[2 * n]).collect();
    assert_eq!(bore_u.len(), 3);
    eprintln!("u_r(a): {bore_u:?} against Lame's {exact}");
    for u in &bore_u {
        assert!((u - exact).abs() < 1e-6 * exact, "u_r(a) {u} against Lame's {exact}");
    }
    let linearized = post(&run, &["--linearize", "100,2.5:150,2.5", "--increment", "1"]);
    let line = linearized.lines().find(|l| l.trim_start().starts_with("membrane")).unwrap_or_else(|| panic!("{linearized}"));
    let hoop: f64 = line.split_whitespace().nth(3).unwrap().parse().unwrap();
    eprintln!("membrane hoop {hoop} MPa against 120");
    assert!((hoop - p * A / (B - A)).abs() < 1e-4 * 120.0, "membrane hoop {hoop} against 120: {linearized}");

    // increment 2: the Gauss datasets and the element means
    let last = res.last_increment();
    let vm = res.f64s(&format!("{last}/von_mises"));
    let mean = res.f64s(&format!("{last}/von_mises_mean"));
    for (e, slots) in vm.chunks(9).enumerate() {
        assert!(slots[..4].iter().all(|v| v.is_finite()) && slots[4..].iter().all(|v| v.is_nan()), "element {e}: {slots:?}");
        let m = slots[..4].iter().sum::<f64>() / 4.0;
        assert!((mean[e] - m).abs() < 1e-9 * m, "element {e}: mean {} against {m}", mean[e]);
    }
    let ep = res.f64s(&format!("{last}/equivalent_plastic_strain"));
    let yielded = ep.chunks(9).filter(|e| e[..4].iter().any(|&v| v > 0.0)).count();
    assert!(yielded > 0 && yielded < 8, "{yielded} of 8 elements yielded: both recovery rules are checked");
    let largest = vm.iter().copied().filter(|v| !v.is_nan()).fold(f64::MIN, f64::max);
    let field = post(&run, &["--field", "von_mises", "--increment", "2"]);
    let max_line = field.lines().find(|l| l.contains(" max ")).unwrap_or_else(|| panic!("{field}"));
    let printed: f64 = max_line.split_whitespace().nth(2).unwrap().parse().unwrap();
    assert!((printed - largest).abs() < 1e-5 * largest && field.contains("a reduced element uses the first 4"), "{field}");

    // meshio and h5py: the NaN layout and the nodal stresses recomputed from the 2 x 2 points
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/check_xdmf.py");
    let check = common::python().arg(script).arg(run.h5.with_extension("xmf")).output().unwrap();
    let text = String::from_utf8_lossy(&check.stdout);
    assert!(check.status.success() && text.trim_end().ends_with("ok"), "{text}{}", String::from_utf8_lossy(&check.stderr));
}

//! Steady radial heat conduction through the wall of a long thick cylinder, against the
//! closed form (Carslaw & Jaeger, Conduction of Heat in Solids, 2nd ed., 1959, section 7.2;
//! Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, eq. 3.26-3.27): with the bore
//! r = a held at T_a and the outside r = b at T_b, the ends insulated,
//!
//!   T(r) = T_a + (T_b - T_a) ln(r / a) / ln(b / a),   q_r = k (T_a - T_b) / (r ln(b / a)),
//!   heat flow in at the bore Q = 2 pi k h (T_a - T_b) / ln(b / a).
//!
//! a = 100, b = 130, h = 10 mm; k = 16 mW/(mm K) (stainless steel, 16 W/(m K)); T_a = 200,
//! T_b = 20 degC. Then T(115) = 104.11 degC, q_r(a) = 109.77 mW/mm^2 and Q = 689.7 W
//! (6.897e5 mW) for the ring. A 12 x 2 Q8 mesh (and the same split into T6) must give every
//! node's temperature within 0.05 % of the 180 degC drop, every Gauss point's flux within
//! 0.5 % of q_r(a) and the ring's heat flow within 0.1 %, on 2 ranks; the outside takes
//! exactly the heat the bore lets in.

mod common;
use common::{run_deck, Results};
use std::f64::consts::TAU;

const A: f64 = 100.0;
const B: f64 = 130.0;
const H: f64 = 10.0;
const K: f64 = 16.0;
const TA: f64 = 200.0;
const TB: f64 = 20.0;

fn exact(r: f64) -> f64 {
    TA + (TB - TA) * (r / A).ln() / (B / A).ln()
}

fn deck(triangles: bool) -> String {
    format!(
        r#"reference_temperature = 20.0
[mesh]
rectangle = {{ r = [{A}, {B}], z = [0.0, {H}], divisions = [12, 2], triangles = {triangles} }}
[[material]]
name = "steel"
conductivity = {K}
[[step]]
name = "wall"
procedure = "heat"
temperature = [{{ set = "inner", value = {TA} }}, {{ set = "outer", value = {TB} }}]
"#
    )
}

#[test]
fn the_wall_of_a_thick_cylinder_conducts_the_logarithmic_profile() {
    for triangles in [false, true] {
        let run = run_deck(&deck(triangles), &[], 2, &[]);
        run.assert_ok();
        let res = Results::open(&run.h5);
        let coords = res.f64s("mesh/coordinates");
        let t = res.f64s("heat/wall/temperature");
        assert_eq!(t.len() * 2, coords.len());
        let worst = (0..t.len()).map(|n| (t[n] - exact(coords[2 * n])).abs()).fold(0.0f64, f64::max);
        assert!(worst < 5e-4 * (TA - TB), "triangles {triangles}: a node's temperature is {worst:.4} degC off the logarithmic profile");

        // the flux at the Gauss points: radial, k (T_a - T_b) / (r ln(b/a)); each point's radius
        // is not in the file, so compare the flux times the radius interpolated from the
        // element's mean (the flux varies as 1/r: compare q_r against its bounds in the wall)
        let q = res.f64s("heat/wall/flux");
        let peak = K * (TA - TB) / (A * (B / A).ln());
        let low = K * (TA - TB) / (B * (B / A).ln());
        for p in q.chunks(2) {
            assert!(p[0] > low * (1.0 - 5e-3) && p[0] < peak * (1.0 + 5e-3), "triangles {triangles}: q_r {} outside [{low}, {peak}]", p[0]);
            assert!(p[1].abs() < 5e-3 * peak, "triangles {triangles}: q_z {} in a radial flow", p[1]);
        }

        let flow = |set: &str| res.file.group(&format!("heat/wall/flows/{set}")).unwrap().attr("flow_ring").unwrap().read_scalar::<f64>().unwrap();
        let expected = TAU * K * H * (TA - TB) / (B / A).ln();
        let (inner, outer) = (flow("inner"), flow("outer"));
        assert!((inner - expected).abs() < 1e-3 * expected, "triangles {triangles}: heat flow in at the bore {inner:.6e} mW, expected {expected:.6e}");
        assert!((inner + outer).abs() < 1e-9 * expected, "the outside takes what the bore lets in: {inner} and {outer}");
        let stdout = run.stdout();
        assert!(stdout.contains("heat step 'wall'") && stdout.contains("inner"), "the summary names the step and its flows:\n{stdout}");
    }
}

/// The flux is exact pointwise too: compare each element's mean flux at its mean radius.
#[test]
fn the_heat_flux_falls_as_one_over_r() {
    let run = run_deck(&deck(false), &[], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let mean = res.f64s("heat/wall/element_flux");
    let coords = res.f64s("mesh/coordinates");
    let conn = res.u64s("mesh/connectivity");
    for (e, q) in mean.chunks(3).enumerate() {
        let r = conn[8 * e..8 * e + 4].iter().map(|&n| coords[2 * n as usize]).sum::<f64>() / 4.0;
        // the mean of 1/r over [r - d, r + d] differs from 1/r by (d/r)^2 / 3, < 1e-4 here
        let expected = K * (TA - TB) / (r * (B / A).ln());
        assert!((q[0] - expected).abs() < 2e-3 * expected, "element {e}: q_r {} against {expected} at r = {r}", q[0]);
    }
}

/// The same wall as a CalculiX deck: CAX8 elements without *ELASTIC, the bore held in the
/// model data and the outside in the *HEAT TRANSFER, STEADY STATE step (*BOUNDARY on degree of
/// freedom 11), on 2 ranks; and `slideline post` prints the step's range and flows.
#[test]
fn a_calculix_heat_transfer_deck_gives_the_same_profile() {
    use std::fmt::Write as _;
    let columns = 2 * 12 + 1;
    let dr = (B - A) / 12.0;
    let id = |row: usize, col: usize| row * columns + col + 1;
    let mut w = String::from("*NODE, NSET=NALL\n");
    for row in 0..3 {
        for col in (0..columns).filter(|c| row != 1 || c % 2 == 0) {
            let _ = writeln!(w, "{}, {:.12}, {:.12}", id(row, col), A + col as f64 * dr / 2.0, row as f64 * H / 2.0);
        }
    }
    w.push_str("*ELEMENT, TYPE=CAX8, ELSET=WALL\n");
    for e in 0..12 {
        let c = 2 * e;
        let _ = writeln!(
            w,
            "{}, {}, {}, {}, {}, {}, {}, {}, {}",
            e + 1,
            id(0, c),
            id(0, c + 2),
            id(2, c + 2),
            id(2, c),
            id(0, c + 1),
            id(1, c + 2),
            id(2, c + 1),
            id(1, c)
        );
    }
    let side = |col: usize| [id(0, col), id(1, col), id(2, col)].map(|n| n.to_string()).join(", ");
    let _ = write!(
        w,
        "*NSET, NSET=BORE\n{}\n*NSET, NSET=OUTSIDE\n{}\n*MATERIAL, NAME=STEEL\n*CONDUCTIVITY\n{K}\n*SOLID SECTION, ELSET=WALL, MATERIAL=STEEL\n\
         *INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 20.\n*BOUNDARY\nBORE, 11, 11, {TA}\n\
         *STEP\n*HEAT TRANSFER, STEADY STATE\n*BOUNDARY\nOUTSIDE, 11, 11, {TB}\n*NODE PRINT, NSET=NALL\nNT\n*END STEP\n",
        side(0),
        side(columns - 1)
    );
    let run = common::run_deck_file("wall.inp", &w, &[], 2, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let coords = res.f64s("mesh/coordinates");
    let t = res.f64s("heat/step-1/temperature");
    let worst = (0..t.len()).map(|n| (t[n] - exact(coords[2 * n])).abs()).fold(0.0f64, f64::max);
    assert!(worst < 5e-4 * (TA - TB), "a node's temperature is {worst:.4} degC off the logarithmic profile");
    let expected = TAU * K * H * (TA - TB) / (B / A).ln();
    let post = common::command_in(run.dir.path(), 1).arg("post").arg(&run.h5).output().unwrap();
    let text = String::from_utf8_lossy(&post.stdout);
    let line = text.lines().find(|l| l.trim_start().starts_with("BORE")).unwrap_or_else(|| panic!("post names the bore's flow:\n{text}"));
    let flow: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!((flow - expected).abs() < 1e-3 * expected, "post: the bore's heat flow {flow:.6e} mW, expected {expected:.6e}");
    assert!(text.contains("heat step 'step-1': temperatures 2.000000e1 to 2.000000e2 degC"), "{text}");
}

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
//! node's temperature within 0.05 % of the 180 degC drop, every Gauss point's q_r between its
//! values at b and a (0.5 % slack) and q_z zero, each element's mean flux within 0.2 % of
//! q_r at its mean radius, and the ring's heat flow within 0.1 %, on 2 ranks; the outside
//! takes exactly the heat the bore lets in.

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

        // the flux at the Gauss points: radial, k (T_a - T_b) / (r ln(b/a)), so between its
        // values at b and a (the element means are checked against 1/r below)
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
/// freedom 11), on 2 ranks; the run prints the flows per 2-degree segment as CalculiX's RFL, and
/// `slideline post` prints the step's range and flows.
#[test]
fn a_calculix_heat_transfer_deck_gives_the_same_profile() {
    use std::fmt::Write as _;
    let (mut w, nodes) = common::cax8_wall(A, B, 12, H);
    let _ = write!(
        w,
        "*NSET, NSET=BORE\n{}\n*NSET, NSET=OUTSIDE\n{}\n*MATERIAL, NAME=STEEL\n*CONDUCTIVITY\n{K}\n*SOLID SECTION, ELSET=WALL, MATERIAL=STEEL\n\
         *INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 20.\n*BOUNDARY\nBORE, 11, 11, {TA}\n\
         *STEP\n*HEAT TRANSFER, STEADY STATE\n*BOUNDARY\nOUTSIDE, 11, 11, {TB}\n*NODE PRINT, NSET=NALL\nNT\n*END STEP\n",
        common::node_list(&nodes, |r, _| r == A),
        common::node_list(&nodes, |r, _| (r - B).abs() < 1e-9)
    );
    let run = common::run_deck_file("wall.inp", &w, &[], 2, &[]);
    run.assert_ok();
    // the run prints the bore's flow per 2-degree segment too, as CalculiX's RFL
    let expected = TAU * K * H * (TA - TB) / (B / A).ln();
    let stdout = run.stdout();
    let tail = stdout.split("heat flowing in per 2-degree segment (as CalculiX prints RFL):").nth(1).unwrap_or_else(|| panic!("no RFL table:\n{stdout}"));
    let bore: f64 = tail.lines().find(|l| l.trim_start().starts_with("BORE")).and_then(|l| l.split_whitespace().nth(1)).unwrap().parse().unwrap();
    assert!((bore - expected / 180.0).abs() < 1e-3 * expected / 180.0, "the bore's flow per 2 degrees {bore:.6e}, expected {:.6e}", expected / 180.0);
    let res = Results::open(&run.h5);
    let coords = res.f64s("mesh/coordinates");
    let t = res.f64s("heat/step-1/temperature");
    let worst = (0..t.len()).map(|n| (t[n] - exact(coords[2 * n])).abs()).fold(0.0f64, f64::max);
    assert!(worst < 5e-4 * (TA - TB), "a node's temperature is {worst:.4} degC off the logarithmic profile");
    let post = common::command_in(run.dir.path(), 1).arg("post").arg(&run.h5).output().unwrap();
    let text = String::from_utf8_lossy(&post.stdout);
    let line = text.lines().find(|l| l.trim_start().starts_with("BORE")).unwrap_or_else(|| panic!("post names the bore's flow:\n{text}"));
    let flow: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!((flow - expected).abs() < 1e-3 * expected, "post: the bore's heat flow {flow:.6e} mW, expected {expected:.6e}");
    assert!(text.contains("heat step 'step-1': temperatures 2.000000e1 to 2.000000e2 degC"), "{text}");
}

/// The heat step's field carried into a static step, as CalculiX carries it: the same wall,
/// 120 degC at the bore and 20 outside from 20 everywhere, its ends held axially (plane
/// strain), against Timoshenko & Goodier, Theory of Elasticity (3rd ed., 1970), section 151,
/// for the temperature change T(r) = 100 ln(b/r) / ln(b/a):
///
///   sigma_r = alpha E / ((1 - nu) r^2) [ (r^2 - a^2) / (b^2 - a^2) I(b) - I(r) ]
///   sigma_t = alpha E / ((1 - nu) r^2) [ (r^2 + a^2) / (b^2 - a^2) I(b) + I(r) - T r^2 ]
///   sigma_z = nu (sigma_r + sigma_t) - alpha E T,   I(r) = int_a^r T r dr
///           = 100 / ln(b/a) [ r^2 ln(b/r) / 2 + r^2 / 4 - a^2 ln(b/a) / 2 - a^2 / 4 ].
///
/// E = 200 GPa, nu = 0.3, alpha = 1.2e-5 /degC: sigma_t = -186.35 MPa at the bore and +156.50 MPa
/// outside (the closed form for this profile, alpha E T_a / (2 (1 - nu) ln(b/a)) [1 - ln(b/a) -
/// (a^2 + b^2) / (b^2 - a^2) ln(b/a)] at the bore, gives the same), sigma_z = -295.9 MPa at the
/// bore. Every Gauss point's stress within 0.05 % of that largest stress, on 2 ranks.
#[test]
fn a_heat_steps_field_is_the_temperature_of_the_static_step_after_it() {
    const E: f64 = 200_000.0;
    const NU: f64 = 0.3;
    const ALPHA: f64 = 1.2e-5;
    let change = |r: f64| 100.0 * (B / r).ln() / (B / A).ln();
    let integral = |r: f64| 100.0 / (B / A).ln() * (r * r * (B / r).ln() / 2.0 + r * r / 4.0 - A * A * (B / A).ln() / 2.0 - A * A / 4.0);
    let exact = |r: f64| {
        let k = ALPHA * E / ((1.0 - NU) * r * r);
        let sr = k * ((r * r - A * A) / (B * B - A * A) * integral(B) - integral(r));
        let st = k * ((r * r + A * A) / (B * B - A * A) * integral(B) + integral(r) - change(r) * r * r);
        [sr, NU * (sr + st) - ALPHA * E * change(r), st]
    };
    let deck = format!(
        r#"reference_temperature = 20.0
nlgeom = false
[mesh]
rectangle = {{ r = [{A}, {B}], z = [0.0, 2.0], divisions = [24, 1] }}
[[material]]
name = "steel"
youngs_modulus = {E}
poissons_ratio = {NU}
thermal_expansion = {ALPHA}
conductivity = {K}
[[step]]
name = "warm"
procedure = "heat"
temperature = [{{ set = "inner", value = 120.0 }}, {{ set = "outer", value = 20.0 }}]
[[step]]
name = "stress"
boundary = [{{ set = "bottom", uz = 0.0 }}, {{ set = "top", uz = 0.0 }}]
"#
    );
    let run = run_deck(&deck, &[], 2, common::DOUBLE);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let last = res.last_increment();
    assert_eq!(res.f64s(&format!("{last}/nodal/temperature")), res.f64s("heat/warm/temperature"), "the static step ends at the heat step's field");
    let coords = res.f64s("mesh/coordinates");
    let conn = res.u64s("mesh/connectivity");
    let stress = res.f64s(&format!("{last}/stress"));
    let g = 0.6f64.sqrt();
    let (mut peak, mut worst) = ([0.0f64; 3], [0.0f64; 3]);
    for e in 0..conn.len() / 8 {
        let r = |slot: usize| coords[2 * conn[8 * e + slot] as usize];
        assert!(r(1) > r(0) && (r(3) - r(0)).abs() < 1e-9, "element {e}: its first side runs along r");
        for q in 0..9 {
            let x = r(0) + (1.0 + [-g, 0.0, g][q % 3]) * (r(1) - r(0)) / 2.0;
            let want = exact(x);
            for c in 0..3 {
                peak[c] = peak[c].max(want[c].abs());
                worst[c] = worst[c].max((stress[(e * 9 + q) * 4 + c] - want[c]).abs());
            }
        }
    }
    assert!((exact(A)[2] + 186.35).abs() < 0.01 && (exact(B)[2] - 156.50).abs() < 0.01, "the peaks quoted: {:?} {:?}", exact(A), exact(B));
    // (the field is the heat step's quadratic approximation of the logarithm, so each
    // component's error is measured against the largest stress, sigma_z at the bore)
    let largest = peak.iter().fold(0.0f64, |m, &p| m.max(p));
    for (c, name) in ["sigma_r", "sigma_z", "sigma_t"].iter().enumerate() {
        println!("{name}: peak {:.3} MPa, largest difference {:.4} MPa", peak[c], worst[c]);
        assert!(worst[c] < 5e-4 * largest, "{name}: {:.4} MPa off, {:.2e} of the largest stress {largest:.3}", worst[c], worst[c] / largest);
    }
}

//! Elastoplastic thick cylinder under internal pressure, plane strain (u_z = 0 on both faces):
//! inner radius a = 100, outer b = 130, E = 200 GPa, nu = 0.3, sigma_y0 = 300 MPa, H = 1000 MPa.
//! Mesh: one row of Q8 elements over r in [100, 130], z in [0, 1] (or [0, 2]).
//!
//! References:
//! - first yield at the bore (elastic Lame stresses, sigma_z = nu (sigma_r + sigma_t), von
//!   Mises): p_y = sigma_y0 / q(1), q(1) the von Mises stress per unit pressure = 70.06 MPa;
//! - residual hoop stress at the bore after loading to the mid-wall plastic front and
//!   unloading: a fine-mesh slideline run (100 elements across the wall) is the reference for
//!   the magnitude; Hill's closed form for an incompressible, perfectly plastic Tresca-Mises
//!   cylinder (The Mathematical Theory of Plasticity, ch. V) bounds it loosely (-75 MPa);
//! - limit pressure with H = 0: (2 / sqrt 3) sigma_y0 ln(b / a) = 90.89 MPa.

mod common;
use common::{run_deck, Results, TIGHT};

const A: f64 = 100.0;
const B: f64 = 130.0;
const SY: f64 = 300.0;

fn deck(nlgeom: bool, divisions: usize, hardening: f64, steps: &str) -> String {
    format!(
        r#"nlgeom = {nlgeom}
[mesh]
rectangle = {{ r = [{A}, {B}], z = [0.0, 1.0], divisions = [{divisions}, 1] }}
[[material]]
name = "steel"
model = "j2"
youngs_modulus = 200000.0
poissons_ratio = 0.3
yield_stress = {SY}
hardening_modulus = {hardening}
{steps}"#
    )
}

const HOLD: &str = r#"boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 } ]"#;

/// Pressure at which the bore first yields, from the elastic Lame solution.
fn first_yield_pressure() -> f64 {
    let nu = 0.3;
    let (sr, st) = (-1.0, (B * B + A * A) / (B * B - A * A));
    let sz = nu * (sr + st);
    let q = (0.5 * ((sr - st) * (sr - st) + (st - sz) * (st - sz) + (sz - sr) * (sz - sr))).sqrt();
    SY / q
}

#[test]
fn first_yield_pressure_within_half_a_percent() {
    let py = first_yield_pressure();
    assert!((py - 70.06).abs() < 0.01, "{py}");
    let steps = format!(
        "[[step]]\nname = \"below\"\n{HOLD}\npressure = [ {{ surface = \"inner\", value = {} }} ]\n[[step]]\nname = \"above\"\npressure = [ {{ surface = \"inner\", value = {} }} ]\n",
        0.995 * py,
        1.005 * py
    );
    let run = run_deck(&deck(false, 60, 1000.0, &steps), &[], 1, &[]);
    run.assert_ok();
    let ep = Results::open(&run.h5).history("max_equivalent_plastic_strain");
    assert_eq!(ep.len(), 2);
    assert_eq!(ep[0], 0.0, "yielded below 0.995 p_y");
    assert!(ep[1] > 0.0, "no yield at 1.005 p_y");
}

#[test]
fn newton_converges_quadratically_in_plastic_increments() {
    // 20 increments to 86 MPa: the last four (from 73 MPa, first yield being 70.06) are plastic
    let steps = format!("[[step]]\nincrements = 20\n{HOLD}\npressure = [ {{ surface = \"inner\", value = 86.0 }} ]\n");
    let run = run_deck(&deck(true, 30, 1000.0, &steps), &[], 1, TIGHT);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let ep = res.history("max_equivalent_plastic_strain");
    let mut checked = 0;
    for (k, inc) in res.increments().iter().enumerate() {
        if ep[k] == 0.0 {
            continue;
        }
        let r = res.f64s(&format!("{inc}/residual_norms"));
        let e: Vec<f64> = r.iter().map(|v| v / r[0]).collect();
        // asymptotic pairs: e_k small, e_(k+1) above the round-off floor (~1e-10 relative here)
        for w in e.windows(2).filter(|w| w[0] < 0.1 && w[1] > 1e-9) {
            assert!(w[1] <= 10.0 * w[0] * w[0], "increment {inc}: {} -> {} is not quadratic; norms {r:?}", w[0], w[1]);
            checked += 1;
        }
        assert!(r.len() <= 8, "increment {inc} took {} Newton iterations: {r:?}", r.len() - 1);
    }
    assert!(checked >= 2, "too few asymptotic iterations were checked");
}

/// Loads to `peak`, unloads, and returns (outermost plastic radius at peak, residual hoop
/// stress at the bore).
fn load_and_unload(divisions: usize, peak: f64) -> (f64, f64) {
    let steps = format!(
        "[[step]]\nname = \"load\"\nincrements = 10\n{HOLD}\npressure = [ {{ surface = \"inner\", value = {peak} }} ]\n[[step]]\nname = \"unload\"\nincrements = 2\npressure = [ {{ surface = \"inner\", value = 0.0 }} ]\n"
    );
    let run = run_deck(&deck(false, divisions, 1000.0, &steps), &[], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let incs = res.increments();
    let peak_inc = &incs[9];
    // plastic front: largest Gauss-point radius with ep > 0, from element centres
    let ep = res.f64s(&format!("{peak_inc}/equivalent_plastic_strain"));
    let conn = res.i64s("mesh/connectivity");
    let coords = res.f64s("mesh/coordinates");
    let mut front: f64 = A;
    for e in 0..conn.len() / 8 {
        if ep[9 * e..9 * e + 9].iter().any(|&v| v > 0.0) {
            let r_out = (0..4).map(|k| coords[2 * conn[8 * e + k] as usize]).fold(0.0f64, f64::max);
            front = front.max(r_out);
        }
    }
    (front, res.stress_at_inner_edge(incs.last().unwrap(), A, 2))
}

#[test]
fn unloading_from_a_mid_wall_plastic_front_leaves_compressive_bore_hoop_stress() {
    let peak = 86.0; // Hill's estimate of the pressure that puts the front at c = 115
    let (front, coarse) = load_and_unload(20, peak);
    let (_, fine) = load_and_unload(100, peak);
    eprintln!("plastic front at r = {front}, residual hoop stress at bore: coarse {coarse:.2} MPa, fine {fine:.2} MPa");
    assert!((112.0..=119.0).contains(&front), "plastic front at {front}, not mid-wall");
    assert!(fine < 0.0 && coarse < 0.0, "residual hoop stress must be compressive");
    assert!((coarse - fine).abs() <= 0.02 * fine.abs(), "coarse {coarse} vs fine-mesh reference {fine}");
    // Hill (incompressible, perfectly plastic, Tresca-Mises): sigma_t(a) = -p + 2 sy / sqrt3
    // minus the elastic Lame hoop stress at p.
    let hill = -peak + 2.0 * SY / 3f64.sqrt() - peak * (B * B + A * A) / (B * B - A * A);
    assert!((fine - hill).abs() <= 0.25 * hill.abs(), "fine {fine} far from Hill's {hill}");
}

#[test]
fn no_volumetric_locking_limit_pressure_plateau_and_smooth_pressure_field() {
    // Perfect plasticity, bore pushed out 1.2 mm (displacement control).
    let steps = "[[step]]\nincrements = 12\nboundary = [ { set = \"bottom\", uz = 0.0 }, { set = \"top\", uz = 0.0 }, { set = \"inner\", ur = 1.2 } ]\n";
    let run = run_deck(&deck(false, 30, 0.0, steps), &[], 1, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let height = 1.0;
    let pressure: Vec<f64> = res.history("reaction_inner_r").iter().map(|f| f / (A * height)).collect();
    let limit = 2.0 / 3f64.sqrt() * SY * (B / A).ln();
    let last = *pressure.last().unwrap();
    eprintln!("pressure history {pressure:.3?}, limit {limit:.3}");
    assert!((last - limit).abs() <= 0.01 * limit, "plateau {last} vs limit pressure {limit}");
    let before = pressure[pressure.len() - 3];
    assert!((last - before).abs() <= 0.002 * limit, "no plateau: {before} -> {last}");
    // Mean stress at every Gauss point against the fully plastic solution
    // sigma_m = sigma_r + sy / sqrt3, sigma_r = -p + (2 / sqrt3) sy ln(r / a): a checkerboard
    // would show as oscillations of order sy between neighbouring points.
    let stress = res.f64s(&format!("{}/stress", res.last_increment()));
    let conn = res.i64s("mesh/connectivity");
    let coords = res.f64s("mesh/coordinates");
    let mut worst = 0.0f64;
    for e in 0..conn.len() / 8 {
        let r0 = coords[2 * conn[8 * e] as usize];
        let r1 = coords[2 * conn[8 * e + 1] as usize];
        for (i, xi) in [-0.6f64.sqrt(), 0.0, 0.6f64.sqrt()].iter().enumerate() {
            let r = 0.5 * (r0 + r1) + 0.5 * (r1 - r0) * xi;
            let sr = -last + 2.0 / 3f64.sqrt() * SY * (r / A).ln();
            let expected = sr + SY / 3f64.sqrt();
            for row in 0..3 {
                let s = &stress[(e * 9 + 3 * row + i) * 4..(e * 9 + 3 * row + i) * 4 + 3];
                worst = worst.max(((s[0] + s[1] + s[2]) / 3.0 - expected).abs());
            }
        }
    }
    eprintln!("max deviation of the mean stress from the fully plastic solution: {worst:.3} MPa");
    assert!(worst <= 0.01 * SY, "mean stress deviates by {worst} MPa: checkerboard or locking");
    // The nodal fields a ParaView user sees (every element has yielded: each node takes its
    // nearest Gauss point's value, averaged) against the fully plastic solution at every node:
    // sigma_rr and the von Mises stress (the yield stress, H = 0) within 1 % of the limit
    // pressure, the equivalent plastic strain never below zero.
    let inc = res.last_increment();
    let nodal = |name: &str| res.f64s(&format!("{inc}/nodal/{name}"));
    let (rr, vm, ep) = (nodal("stress_rr"), nodal("von_mises"), nodal("equivalent_plastic_strain"));
    let mut worst = 0.0f64;
    for (k, (x, _)) in res.nodes().iter().enumerate() {
        let sr = -last + 2.0 / 3f64.sqrt() * SY * (x[0] / A).ln();
        worst = worst.max((rr[k] - sr).abs()).max((vm[k] - SY).abs());
    }
    eprintln!("largest nodal deviation from the fully plastic solution: {worst:.3} MPa ({:.2} % of the limit pressure)", 100.0 * worst / limit);
    assert!(worst <= 0.01 * limit, "nodal stresses off the fully plastic solution by {worst} MPa");
    assert!(ep.iter().all(|&e| e >= 0.0), "negative nodal plastic strain");
    // The fully plastic wall's linearised hoop membrane (`post --linearize` through the wall,
    // every element yielded) against the half cylinder's equilibrium, which holds at any
    // state: int_a^b sigma_t dr = p a, the membrane p a / (b - a) (small strain: reference
    // coordinates); and the membrane von Mises near the yield stress.
    let out = common::command_in(run.dir.path(), 1).args(["post"]).arg(&run.h5).args(["--linearize", &format!("{A},0.5:{B},0.5")]).output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let membrane: Vec<f64> =
        text.lines().find(|l| l.trim_start().starts_with("membrane ")).unwrap().split_whitespace().skip(1).map(|v| v.parse().unwrap()).collect();
    let hoop = last * A / (B - A);
    eprintln!("fully plastic wall: hoop membrane {:.3} MPa against p a / (b - a) = {hoop:.3}", membrane[2]);
    assert!((membrane[2] - hoop).abs() <= 0.005 * hoop, "hoop membrane {} against {hoop}\n{text}", membrane[2]);
}

/// `[output] fields = [..., "element_nodal"]` keeps each element's own nodal stresses before
/// averaging (for the jumps between elements): loaded past first yield (the bore's elements
/// yield, the outer ones stay elastic), the mean over the elements at each node of
/// `element_nodal_stress` is the averaged nodal stress ParaView shows, to round-off; a yielded
/// element's nodal values are its nearest Gauss points' (copied), and not written by default.
#[test]
fn element_nodal_stresses_are_kept_on_request_and_average_to_the_nodal_ones() {
    let steps = format!("[output]\nfields = [\"stress\", \"plastic_strain\", \"element_nodal\"]\n[[step]]\nincrements = 4\n{HOLD}\npressure = [ {{ surface = \"inner\", value = 80.0 }} ]\n");
    let run = run_deck(&deck(false, 12, 1000.0, &steps), &[], 2, common::DOUBLE);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let inc = res.last_increment();
    let element_nodal = res.f64s(&format!("{inc}/element_nodal_stress"));
    let gauss = res.f64s(&format!("{inc}/stress"));
    let ep = res.f64s(&format!("{inc}/equivalent_plastic_strain"));
    let conn = res.i64s("mesh/connectivity");
    let nodal = res.f64s(&format!("{inc}/nodal/stress_tt"));
    let nodes = nodal.len();
    let (mut sums, mut counts) = (vec![0.0; nodes], vec![0.0; nodes]);
    let (mut copied, mut extrapolated) = (0, 0);
    for e in 0..conn.len() / 8 {
        for a in 0..8 {
            sums[conn[8 * e + a] as usize] += element_nodal[(8 * e + a) * 4 + 2];
            counts[conn[8 * e + a] as usize] += 1.0;
        }
        if ep[9 * e..9 * e + 9].iter().any(|&v| v > 0.0) {
            // corner 1 (xi = -1, eta = -1) takes Gauss point 1 (the first)
            assert_eq!(element_nodal[8 * e * 4 + 2], gauss[9 * e * 4 + 2], "a yielded element copies its nearest Gauss point");
            copied += 1;
        } else {
            extrapolated += 1;
        }
    }
    assert!(copied > 0 && extrapolated > 0, "{copied} yielded and {extrapolated} elastic elements");
    for n in 0..nodes {
        let mean = sums[n] / counts[n];
        assert!((mean - nodal[n]).abs() <= 1e-12 * nodal[n].abs().max(1.0), "node {n}: {mean} against {}", nodal[n]);
    }
    let default = run_deck(&deck(false, 2, 1000.0, &format!("[[step]]\n{HOLD}\npressure = [ {{ surface = \"inner\", value = 10.0 }} ]\n")), &[], 1, &[]);
    default.assert_ok();
    let file = Results::open(&default.h5);
    assert!(file.file.dataset(&format!("{}/element_nodal_stress", file.last_increment())).is_err(), "not written by default");
}

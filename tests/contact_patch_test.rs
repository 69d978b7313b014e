//! Contact patch test: two stacked axisymmetric blocks with non-matching meshes, r in [0, 10],
//! lower z in [0, 5] (5 x 2 Q8), upper z in [5, 10] (7 x 2 Q8), the upper one resting on the
//! lower through contact only, 10 MPa on the upper face, lower face held axially, u_r = 0 on
//! the axis. Exact answer: uniform sigma_zz = -10 MPa and a uniform 10 MPa contact pressure.
//!
//!   z=10 +--+--+--+--+--+--+--+  <- 10 MPa
//!        |  |  |  |  |  |  |  |  upper (slave surface: its bottom)
//!   z=5  +--+--+--+--+--+--+--+
//!        +---+---+---+---+---+   lower (master surface: its top)
//!        |   |   |   |   |   |
//!   z=0  +---+---+---+---+---+   u_z = 0
//!       r=0 (axis)           r=10
//!
//! Surface-integrated enforcement transmits it to round-off at every slave node, the node on
//! the axis included, one-pass and two-pass. The paper's nodal collocation (node-to-segment)
//! cannot between non-matching quadratic meshes: its master reactions are a nodal quadrature
//! of the master's shape functions; the test states its deviation.

mod common;
use common::{patch_test_deck, run_deck, Results, TIGHT};

/// (r, pressure, traction) at every slave node of every pass, and the largest |sigma_zz + 10|.
fn run(integration: &str, two_pass: bool) -> (Vec<(f64, f64, f64)>, f64) {
    let run = run_deck(&patch_test_deck(integration, two_pass, false), &[], 1, TIGHT);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let coords = res.f64s("mesh/coordinates");
    let passes = if two_pass { 2 } else { 1 };
    let mut out = Vec::new();
    for k in 0..passes {
        let nodes = res.u64s(&format!("mesh/contact/interface/pass{k}/nodes"));
        let p = res.f64s(&format!("increments/000001/contact/interface/pass{k}/pressure"));
        let t = res.f64s(&format!("increments/000001/contact/interface/pass{k}/traction"));
        for i in 0..nodes.len() {
            out.push((coords[2 * nodes[i] as usize], p[i], t[i]));
        }
    }
    let szz = res.f64s("increments/000001/stress").chunks(4).map(|s| (s[1] + 10.0).abs()).fold(0.0, f64::max);
    (out, szz)
}

#[test]
fn surface_integrated_contact_transmits_the_uniform_pressure_at_every_node() {
    for two_pass in [false, true] {
        let (nodes, szz) = run("segment", two_pass);
        assert!(nodes.iter().any(|n| n.0 == 0.0), "the axis node is a slave node");
        for (r, p, t) in &nodes {
            assert!((p - 10.0).abs() <= 1e-6 * 10.0, "two_pass {two_pass}: pressure {p} at r = {r}");
            assert!((t - 10.0).abs() <= 1e-6 * 10.0, "two_pass {two_pass}: traction {t} at r = {r}");
        }
        assert!(szz <= 1e-6 * 10.0, "two_pass {two_pass}: sigma_zz off by {szz}");
    }
}

#[test]
fn node_to_segment_collocation_deviation_is_stated() {
    for two_pass in [false, true] {
        let (nodes, szz) = run("node-to-segment", two_pass);
        let worst = nodes.iter().map(|n| (n.2 - 10.0).abs() / 10.0).fold(0.0, f64::max);
        eprintln!("node-to-segment, two_pass = {two_pass}: traction off by up to {:.1} %, sigma_zz by up to {:.1} %", 100.0 * worst, 10.0 * szz);
        // what the collocated slide line does on this patch (a statement, bounded so a change
        // shows): about 13 % one-pass, about 50 % two-pass (nodes near the axis and ends)
        assert!(worst > 0.01, "unexpectedly exact: update the documentation");
        assert!(worst < if two_pass { 2.5 } else { 0.25 }, "worse than documented: {worst}");
    }
}

/// CalculiX's exponential pressure-overclosure law, p = p0 exp(-ln(100) g / c0), on the patch
/// with matching meshes (the upper block also 5 x 2), where the node-to-segment slide line
/// transmits a uniform pressure exactly. 10 MPa with p0 = 0.1 MPa is 100 p0, which the law
/// reaches at a penetration of exactly c0: every slave node must carry 10 MPa at a gap of
/// -c0 = -2e-3 mm, and sigma_zz = -10 MPa throughout (the law's definition, ccx 2.20 manual,
/// *SURFACE BEHAVIOR; the case's equilibrium).
#[test]
fn the_exponential_law_carries_the_patch_at_a_penetration_of_its_clearance() {
    let deck = patch_test_deck("node-to-segment", false, false)
        .replace("divisions = [7, 2]", "divisions = [5, 2]")
        .replace("penalty = 1.0e6", "exponential = { clearance = 2.0e-3, pressure = 0.1 }");
    let run = run_deck(&deck, &[], 1, TIGHT);
    run.assert_ok();
    let res = Results::open(&run.h5);
    // the first attempt at the whole load meets the law's soft start (0.1 MPa at touch) and
    // cuts back: the full load is the last increment
    let last = res.last_increment();
    let nodes = res.u64s("mesh/contact/interface/pass0/nodes");
    let p = res.f64s(&format!("{last}/contact/interface/pass0/pressure"));
    let gap = res.f64s(&format!("{last}/contact/interface/pass0/gap"));
    assert_eq!(nodes.len(), 11);
    for k in 0..nodes.len() {
        assert!((p[k] - 10.0).abs() <= 1e-6 * 10.0, "slave node {}: pressure {}", nodes[k], p[k]);
        assert!((gap[k] + 2.0e-3).abs() <= 1e-6 * 2.0e-3, "slave node {}: gap {}", nodes[k], gap[k]);
    }
    let szz = res.f64s(&format!("{last}/stress")).chunks(4).map(|s| (s[1] + 10.0).abs()).fold(0.0, f64::max);
    assert!(szz <= 1e-6 * 10.0, "sigma_zz off by {szz}");
}

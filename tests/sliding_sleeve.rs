//! Sliding sleeve: a tube (r in [90, 100], z in [0, 40], 4 x 20 Q8) inside another with zero
//! clearance (r in [100, 110], z in [-10, 70], 4 x 27 Q8: non-matching along the interface),
//! frictionless, the inner tube pressed out by 5 MPa on its bore and moved axially by 20 mm
//! (finite strain). The outer tube is held whole, so its bore stays a straight cylinder: with
//! an elastic outer tube the bore bulges near the ends of contact, a frictionless force normal
//! to a tilted surface has an axial part, and a small axial force is then physics (about 4e-7
//! of the contact force here), not error. Expected: the axial force needed to slide is zero to
//! round-off; the penetration is the penalty's p / eps; every slave node stays in contact as it
//! crosses the master's element boundaries.

mod common;
use common::{run_deck, Results, TIGHT};

const EPS: f64 = 1.0e5;

fn deck(integration: &str) -> String {
    format!(
        r#"[[mesh.block]]
name = "inner"
r = [90.0, 100.0]
z = [0.0, 40.0]
divisions = [4, 20]
[[mesh.block]]
name = "outer"
r = [100.0, 110.0]
z = [-10.0, 70.0]
divisions = [4, 27]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[contact]]
name = "sleeve"
slave = "inner_outer"
master = "outer_inner"
integration = "{integration}"
penalty = {EPS}
[[step]]
name = "pressurise"
boundary = [ {{ set = "outer", ur = 0.0, uz = 0.0 }}, {{ set = "inner_bottom", uz = 0.0 }} ]
pressure = [ {{ surface = "inner_inner", value = 5.0 }} ]
[[step]]
name = "slide"
increments = 20
boundary = [ {{ set = "inner_bottom", uz = 20.0 }} ]
"#
    )
}

#[test]
fn frictionless_sliding_needs_no_axial_force_and_keeps_every_node_in_contact() {
    for integration in ["segment", "node-to-segment"] {
        let run = run_deck(&deck(integration), &[], 1, TIGHT);
        run.assert_ok();
        let res = Results::open(&run.h5);
        let fz = res.history("reaction_inner_bottom_z");
        let active = res.history("contact_sleeve_active_nodes");
        let penetration = res.history("contact_sleeve_max_penetration");
        let force = res.history("contact_sleeve_force");
        let slaves = res.u64s("mesh/contact/sleeve/pass0/nodes").len() as f64;
        // the radial contact force per radian is ~ 5 MPa * 90 mm * 40 mm: the scale for round-off
        let scale = force.last().unwrap().abs();
        eprintln!(
            "{integration}: max |F_z| = {:.2e} N/rad against {scale:.3e}; active {active:?}; max penetration {:.3e}",
            fz.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            penetration.iter().cloned().fold(0.0, f64::max)
        );
        for (k, f) in fz.iter().enumerate() {
            assert!(f.abs() <= 1e-8 * scale, "{integration}, increment {k}: axial reaction {f}");
        }
        for a in &active {
            assert_eq!(*a, slaves, "{integration}: a slave node lost contact: {active:?}");
        }
        // the contact pressure is about 5 * 90/100 = 4.5 MPa; p / eps = 4.5e-5 mm
        let inc = res.last_increment();
        let p_max = res.f64s(&format!("{inc}/contact/sleeve/pass0/pressure")).into_iter().fold(0.0, f64::max);
        for pen in &penetration {
            assert!(*pen <= 1.05 * p_max / EPS, "{integration}: penetration {pen} beyond p/eps = {}", p_max / EPS);
        }
        // the tube did slide by 20 mm (plus a few micrometres of Poisson shortening)
        let coords = res.f64s("mesh/coordinates");
        let u = res.displacement(&inc);
        let top = (0..coords.len() / 2).find(|&n| coords[2 * n] == 95.0 && coords[2 * n + 1] == 40.0).unwrap();
        assert!((u[2 * top + 1] - 20.0).abs() < 0.01, "{}", u[2 * top + 1]);
    }
}

/// Count of a -log_view event's calls (the second column of its line).
fn event_count(log: &str, event: &str) -> usize {
    log.lines()
        .find_map(|l| l.strip_prefix(event).filter(|r| r.starts_with(' ')).and_then(|r| r.split_whitespace().next()).and_then(|c| c.parse().ok()))
        .unwrap_or_else(|| panic!("no {event} in -log_view:\n{log}"))
}

#[test]
fn the_jacobian_pattern_is_preallocated_and_mumps_reanalyses_only_when_it_changes() {
    // 2 ranks, the slide finding new master edges every increment. PETSc never has to
    // reallocate (-info reports no mallocs), and the symbolic analyses are exactly a step's new
    // matrix or a refit of the pattern in place for new couplings; every other factorisation
    // reuses the analysis.
    let run = run_deck(&deck("segment"), &[], 2, &["--", "-log_view", "-info", ":mat"]);
    run.assert_ok();
    let out = run.stdout();
    let steps = 2;
    let refits: usize = out
        .lines()
        .find_map(|l| l.split("refitted in place ").nth(1))
        .and_then(|r| r.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no pattern summary:\n{out}"));
    let mallocs = out.lines().filter(|l| l.contains("Number of mallocs during MatSetValues() is") && !l.ends_with(" is 0")).count();
    let symbolic = event_count(&out, "MatLUFactorSym");
    let numeric = event_count(&out, "MatLUFactorNum");
    eprintln!("{refits} refits, {mallocs} assemblies with mallocs, {symbolic} symbolic and {numeric} numeric factorisations");
    assert_eq!(mallocs, 0, "an assembly reallocated:\n{out}");
    assert!(refits >= 1, "the slide should have needed new couplings");
    // exactly: fewer would mean a factorisation reused the analysis of a replaced structure
    assert_eq!(symbolic, steps + refits, "{symbolic} symbolic analyses for {steps} steps and {refits} refits");
    assert!(numeric >= 4 * symbolic, "too little reuse: {numeric} numeric for {symbolic} symbolic factorisations");
}

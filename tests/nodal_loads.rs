//! Concentrated loads: *CLOAD, GRAV / CENTRIF on point masses (*MASS), and the TOML deck's
//! `force`.
//!
//! CalculiX takes an axisymmetric node's force, and a point mass, as the whole ring's
//! (measured with ccx 2.20: the bore loads below reproduce the pressure's displacements only so;
//! its reactions it prints per 2-degree segment). slideline keeps them per radian: F / (2 pi).
//!
//! 1. Lame's thick cylinder (tests/data/inp/lame.inp: a = 100, b = 150, p = 100 MPa, ends held
//!    axially) with its bore pressure replaced by the consistent nodal loads of the one loaded
//!    edge, p a L (1/6, 2/3, 1/6) per radian, given as *CLOAD ring totals (x 2 pi) on 2 ranks:
//!    the same displacements as the pressure (small strain: both are dead loads) to 1e-9, and
//!    Lame's u(a) = (1 + nu) a p / E ((1 - 2 nu) a^2 + b^2) / (b^2 - a^2) = 0.13780 mm
//!    (CalculiX's printed 0.1377930 for the pressure deck) within 0.1 %; the energy balance
//!    holds to 1e-9 of the elastic energy.
//! 2. A disc r 0.1..1, z 0..0.1 of two CAX8 elements with a point mass of 1e-8 t at its rim's
//!    mid-side node (r = 1), spun at omega^2 = 1e10 (CENTRIF on the mass only): the mass pulls
//!    its node out with m omega^2 r = 100 N around the ring. The same as a *CLOAD of 100 N there
//!    to round-off; u_r there 5.482124e-4 mm in ccx 2.20 (the same deck), slideline within
//!    0.5 % (0.19 %: the one-element-wide mesh under a point load).
//! 3. A TOML deck's `force` (N around the whole ring, on each node of a set): a block whose top
//!    nodes (5, corners and mid-sides) each take fz = -1000 N and fr = +200 N, held axially at its
//!    bottom: the full-ring axial reaction balances the 5 kN to 1e-9, ramped over two
//!    increments, and kept by a later step that does not restate the force; the radial forces
//!    push the top out.

mod common;
use common::{command_in, data, run_deck, Results, Run};
use std::f64::consts::TAU;

/// Runs the deck `text` in a directory of its own (with the Lame mesh it may include).
fn run_inp(text: &str, ranks: usize) -> Run {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(data("inp/lame_mesh.inc"), dir.path().join("lame_mesh.inc")).unwrap();
    let path = dir.path().join("deck.inp");
    std::fs::write(&path, text).unwrap();
    let h5 = dir.path().join("out.h5");
    let output = command_in(dir.path(), ranks).current_dir(dir.path()).arg("run").arg(&path).arg("-o").arg(&h5).arg("-q").output().expect("run slideline");
    Run { dir, output, h5 }
}

#[test]
fn cload_of_the_consistent_bore_loads_is_the_pressure_and_lames_cylinder() {
    let pressure = std::fs::read_to_string(data("inp/lame.inp")).unwrap();
    assert!(pressure.contains("*DLOAD\nINNER, P4, 100.\n"));
    // the bore edge of element 1: nodes 1 (z = 0), 18 (z = 5), 27 (z = 10)
    let (p, a, b, length) = (100.0, 100.0f64, 150.0f64, 10.0);
    let corner = TAU * p * a * length / 6.0;
    let cload = pressure.replace("*DLOAD\nINNER, P4, 100.\n", &format!("*CLOAD\n1, 1, {corner}\n27, 1, {corner}\n18, 1, {}\n", 4.0 * corner));
    let (with_pressure, with_cload) = (run_inp(&pressure, 2), run_inp(&cload, 2));
    with_pressure.assert_ok();
    with_cload.assert_ok();
    let (ours, theirs) = (Results::open(&with_cload.h5), Results::open(&with_pressure.h5));
    let (worst, scale) = common::displacement_difference(&theirs, &ours);
    assert!(worst <= 1e-9 * scale, "the nodal loads move the nodes as the pressure does: {worst:e} of {scale}");
    let (nu, e) = (0.3, 200000.0);
    let lame = (1.0 + nu) * a * p / e * ((1.0 - 2.0 * nu) * a * a + b * b) / (b * b - a * a);
    let u = ours.displacement_by_node_id()[&1][0];
    assert!((u / lame - 1.0).abs() < 1e-3, "u_r(a) = {u} against Lame's {lame}");
    // the nodal forces' work is in the energy audit's external work
    let (elastic, balance) = (ours.history("energy_elastic"), ours.history("energy_balance_error"));
    assert!(elastic[0] > 0.0 && balance[0].abs() < 1e-9 * elastic[0], "balance {balance:?} of {elastic:?}");
}

const DISC: &str = "*NODE, NSET=NALL
1, 0.1, 0.1
2, 0.1, 0.
3, 0.55, 0.
4, 0.55, 0.1
5, 0.1, 0.05
6, 0.325, 0.
7, 0.55, 0.05
8, 0.325, 0.1
9, 1., 0.
10, 1., 0.1
11, 0.775, 0.
12, 1., 0.05
13, 0.775, 0.1
*ELEMENT, TYPE=CAX8, ELSET=DISC
1, 1, 2, 3, 4, 5, 6, 7, 8
2, 4, 3, 9, 10, 7, 11, 12, 13
*ELEMENT, TYPE=MASS, ELSET=RIM
3, 12
*BOUNDARY
1, 2, 2
*MATERIAL, NAME=EL
*ELASTIC
210000., .3
*SOLID SECTION, ELSET=DISC, MATERIAL=EL
*MASS, ELSET=RIM
1.e-8
*STEP
*STATIC
*DLOAD
RIM, CENTRIF, 1.e10, 0., 0., 0., 0., 1., 0.
*NODE PRINT, NSET=NALL
U
*END STEP
";

#[test]
fn a_spinning_point_mass_pulls_its_node_as_calculix_has_it() {
    let spun = run_inp(DISC, 1);
    spun.assert_ok();
    let pulled = run_inp(&DISC.replace("*DLOAD\nRIM, CENTRIF, 1.e10, 0., 0., 0., 0., 1., 0.\n", "*CLOAD\n12, 1, 100.\n"), 1);
    pulled.assert_ok();
    let (spun, pulled) = (Results::open(&spun.h5), Results::open(&pulled.h5));
    let (worst, scale) = common::displacement_difference(&pulled, &spun);
    assert!(worst <= 1e-12 * scale, "m omega^2 r on the mass's node: {worst:e} of {scale}");
    let u = spun.displacement_by_node_id()[&12][0];
    let ccx = 5.482124e-4;
    assert!((u / ccx - 1.0).abs() < 5e-3, "u_r at the mass {u} against ccx's {ccx}");

    // refused: a load on masses without *MASS, and with NLGEOM (applied at the initial radius
    // only); a *CLOAD dof the axisymmetric node lacks
    for (edit, needle) in [
        (DISC.replace("*MASS, ELSET=RIM\n1.e-8\n", ""), "have no *MASS"),
        (DISC.replace("*STEP\n", "*STEP, NLGEOM\n"), "with NLGEOM"),
        (DISC.replace("*DLOAD\nRIM, CENTRIF, 1.e10, 0., 0., 0., 0., 1., 0.\n", "*CLOAD\n12, 3, 100.\n"), "degree of freedom 3"),
    ] {
        let run = run_inp(&edit, 1);
        assert_eq!(run.code(), 2, "{needle}: {}", run.stderr());
        assert!(run.stderr().contains(needle), "{needle}: {}", run.stderr());
    }
}

#[test]
fn a_toml_force_is_the_whole_rings_on_each_node_and_is_kept_by_later_steps() {
    let deck = r#"
[mesh.rectangle]
r = [100.0, 110.0]
z = [0.0, 10.0]
divisions = [2, 2]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[step]]
name = "load"
increments = 2
boundary = [ { set = "bottom", uz = 0.0 } ]
force = [ { set = "top", fz = -1000.0, fr = 200.0 } ]
[[step]]
name = "hold"
"#;
    let run = run_deck(deck, &[], 2, common::TIGHT);
    run.assert_ok();
    let r = Results::open(&run.h5);
    let fz = r.history("reaction_bottom_z_ring");
    let load = r.history("load_factor");
    for (k, (&f, &lambda)) in fz.iter().zip(&load).enumerate() {
        let expected = if k < 2 { 5000.0 * lambda } else { 5000.0 };
        assert!((f - expected).abs() < 1e-9 * 5000.0, "#{}: bottom reaction {f} N against {expected}", k + 1);
    }
    assert_eq!(fz.len(), 3);
    // the radial forces stretch the ring: the bottom carries no radial reaction (it is free
    // radially), the top moves out
    assert!(r.nodes().iter().filter(|(x, _)| x[1] == 10.0).all(|(_, u)| u[0] > 0.0), "the radial forces push the top out");
    let bad = run_deck(&deck.replace("fz = -1000.0, fr = 200.0", "fz = -1000.0").replace("set = \"top\"", "set = \"nowhere\""), &[], 1, &[]);
    assert_eq!(bad.code(), 2, "{}", bad.stderr());
    assert!(bad.stderr().contains("force on an unknown node set 'nowhere'"), "{}", bad.stderr());
}

//! Multi-point constraints, read from CalculiX decks (*PRE-TENSION SECTION, *EQUATION, *TIE)
//! and from the TOML deck (`[[tie]]`), each against the exact solution of a tube r 10..12 (or 0.1..1.1) pulled along its axis with
//! its lateral faces free: sigma_zz = E eps uniform, u_r = -nu eps r, u_z = eps z (Timoshenko &
//! Goodier, Theory of Elasticity, simple tension; the quadratic elements hold this linear field
//! exactly, so only the penalty's give of ~1e-6 separates the run from it).
//!
//! 1. CalculiX's pret2 deck (two CAX8 elements, r 0.1..1.1, z 0..2, cut at z = 1 by a
//!    pre-tension section) with its radial supports removed: the reference node's u_1 = 0.01
//!    shortens the section by 0.01, eps = 0.005, sigma_zz = 1050 MPa (E = 210000), and the
//!    reference node carries the pre-load sigma A = 1050 pi (1.1^2 - 0.1^2) = 3958.41 N around
//!    the ring (630.0 N per radian). ccx 2.20 gives the same 1050 MPa on this deck. Given as that
//!    force (*CLOAD) instead, the section shortens by 0.01. On 2 ranks.
//! 2. *EQUATION: one CAX8 element r 10..12, z 0..1, whose top nodes follow the u_z of its top
//!    mid-side node (two equations), a *CLOAD of 44 pi * 100 N there (A = pi (12^2 - 10^2) =
//!    44 pi mm^2): sigma_zz = 100 MPa, u_z(top) = 100 / E.
//! 3. *TIE: the same tube as two blocks meshed differently (one element below z = 1, two above,
//!    split at r = 10.8), the upper block's bottom tied to the lower block's top, pulled by 0.01
//!    at z = 2: sigma_zz = E 0.01 / 2 = 1050 MPa in every element to 1e-5, on 2 ranks.
//! 4. The same from a TOML deck (small strain): two `[[mesh.block]]`s of 2 x 1 and 3 x 2
//!    elements joined by a `[[tie]]`, on 2 ranks: 1050 MPa to 1e-5.

mod common;
use common::{run_deck, run_deck_file, Results};
use std::f64::consts::PI;

const PRET2: &str = "*NODE, NSET=Nall
1,0.1,2.
2,0.1,1.
3,1.1,1.
4,1.1,2.
5,0.1,1.5
6,0.6,1.
7,1.1,1.5
8,0.6,2.
9,0.1,0.
10,1.1,0.
11,0.1,0.5
12,0.6,0.
13,1.1,0.5
14,0.,0.
*ELEMENT, TYPE=CAX8, ELSET=Eall
1, 1, 2, 3, 4, 5, 6, 7, 8
2, 2, 9, 10, 3, 11, 12, 13, 6
*MATERIAL,NAME=EL
*ELASTIC
210000.,.3
*SOLID SECTION,ELSET=Eall,MATERIAL=EL
*NSET,NSET=N1
14
*BOUNDARY
1,2,2
8,2,2
4,2,2
9,2,2
12,2,2
10,2,2
*SURFACE,NAME=S1
1,S2
*PRE-TENSION SECTION,SURFACE=S1,NODE=14
*STEP
*STATIC
LOAD
*END STEP
";

/// Every element's stress at every point: [rr, zz, tt, rz].
fn stresses(results: &Results) -> Vec<[f64; 4]> {
    let s = results.f64s(&format!("{}/stress", results.last_increment()));
    s.chunks(4).map(|c| [c[0], c[1], c[2], c[3]]).collect()
}

fn assert_uniaxial(results: &Results, sigma: f64, eps: f64, what: &str) {
    for s in stresses(results) {
        assert!((s[1] - sigma).abs() < 1e-5 * sigma, "{what}: sigma_zz {} against {sigma}", s[1]);
        assert!(s[0].abs().max(s[2].abs()).max(s[3].abs()) < 1e-5 * sigma, "{what}: a lateral stress in {s:?}");
    }
    for ((x, u), id) in results.nodes().into_iter().zip(results.u64s("mesh/node_ids")) {
        if id != 14 || !what.starts_with("pre-tension") {
            assert!((u[0] + 0.3 * eps * x[0]).abs() < 1e-5 * eps * x[0].max(1.0), "{what}: node {id} at {x:?} u_r {} against {}", u[0], -0.3 * eps * x[0]);
        }
    }
}

#[test]
fn a_pretension_section_shortened_or_loaded_stretches_the_bolt_uniformly() {
    let shortened = run_deck_file("pret2.inp", &PRET2.replace("LOAD\n", "*BOUNDARY\n14,1,1,.01\n"), &[], 2, &[]);
    shortened.assert_ok();
    let results = Results::open(&shortened.h5);
    assert_uniaxial(&results, 1050.0, 0.005, "pre-tension shortened");
    // three nodes doubled at the cut: the partners are numbered on from the highest node
    let ids = results.u64s("mesh/node_ids");
    assert!([15, 16, 17].iter().all(|n| ids.contains(n)) && ids.len() == 17, "{ids:?}");
    // the upper half's cut face moved down by 0.005, the lower's up: the section overlaps 0.01
    let u = results.displacement_by_node_id();
    assert!((u[&2][1] - 0.005).abs() < 1e-8 && (u[&15][1] + 0.005).abs() < 1e-8, "{:?} {:?}", u[&2], u[&15]);
    // the pre-load is the reaction of the shortening, per radian
    let preload = results.history("reaction_N14_r");
    let expected = 1050.0 * (1.1f64.powi(2) - 0.1f64.powi(2)) / 2.0;
    assert!((preload.last().unwrap() - expected).abs() < 1e-5 * expected, "pre-load {preload:?} N/rad against {expected}");

    let force = 1050.0 * PI * (1.1f64.powi(2) - 0.1f64.powi(2));
    let loaded = run_deck_file("pret2.inp", &PRET2.replace("LOAD\n", &format!("*CLOAD\n14,1,{force}\n")), &[], 2, &[]);
    loaded.assert_ok();
    let results = Results::open(&loaded.h5);
    assert_uniaxial(&results, 1050.0, 0.005, "pre-tension loaded");
    let shortening = results.displacement_by_node_id()[&14][0];
    assert!((shortening - 0.01).abs() < 1e-7, "shortening {shortening}");
}

const BLOCK: &str = "*NODE
1,10.,0.
2,12.,0.
3,12.,1.
4,10.,1.
5,11.,0.
6,12.,0.5
7,11.,1.
8,10.,0.5
*ELEMENT, TYPE=CAX8, ELSET=LOW
1, 1, 2, 3, 4, 5, 6, 7, 8
*MATERIAL,NAME=STEEL
*ELASTIC
210000.,.3
*SOLID SECTION,ELSET=LOW,MATERIAL=STEEL
*NSET,NSET=BOTTOM
1, 2, 5
";

#[test]
fn equations_make_the_top_follow_one_loaded_node() {
    let force = 44.0 * PI * 100.0;
    let deck = format!("{BLOCK}*EQUATION\n2\n3,2,1.,7,2,-1.\n2\n4,2,1.,\n7,2,-1.\n*BOUNDARY\nBOTTOM,2,2\n*STEP\n*STATIC\n*CLOAD\n7,2,{force}\n*END STEP\n");
    let run = run_deck_file("block.inp", &deck, &[], 1, &[]);
    run.assert_ok();
    let results = Results::open(&run.h5);
    assert_uniaxial(&results, 100.0, 100.0 / 210000.0, "equation");
    let u = results.displacement_by_node_id();
    for n in [3, 4, 7] {
        assert!((u[&n][1] - 100.0 / 210000.0).abs() < 1e-5 * 100.0 / 210000.0, "node {n}: u_z {}", u[&n][1]);
    }
}

#[test]
fn a_tie_joins_two_differently_meshed_blocks_as_one() {
    let upper = "*NODE
11,10.,1.
12,10.8,1.
13,10.8,2.
14,10.,2.
15,10.4,1.
16,10.8,1.5
17,10.4,2.
18,10.,1.5
19,12.,1.
20,12.,2.
21,11.4,1.
22,12.,1.5
23,11.4,2.
*ELEMENT, TYPE=CAX8, ELSET=UP
2, 11, 12, 13, 14, 15, 16, 17, 18
3, 12, 19, 20, 13, 21, 22, 23, 16
*SOLID SECTION,ELSET=UP,MATERIAL=STEEL
*NSET,NSET=TOP
14, 13, 20, 17, 23
*SURFACE, NAME=LOWTOP
1, S3
*SURFACE, NAME=UPBOT
UP, S1
*TIE, NAME=GLUE, POSITION TOLERANCE=0.01
UPBOT, LOWTOP
*BOUNDARY
BOTTOM,2,2
*STEP
*STATIC
*BOUNDARY
TOP,2,2,0.01
*END STEP
";
    let run = run_deck_file("tied.inp", &format!("{BLOCK}{upper}"), &[], 2, &[]);
    run.assert_ok();
    let results = Results::open(&run.h5);
    assert_uniaxial(&results, 1050.0, 0.005, "tie");
    let u = results.displacement_by_node_id();
    // the slave node between the master's nodes follows the master face's quadratic field
    assert!((u[&15][1] - 0.005).abs() < 1e-8 && (u[&15][0] + 0.0015 * 10.4).abs() < 1e-7, "{:?}", u[&15]);
}

/// PETSc's check of the assembled Jacobian against finite differences of the assembled
/// residual (`-snes_test_jacobian`, as tests/snes_test_jacobian.rs) on 2 ranks, with the
/// pre-tension section's constraints, whose reference node is loaded: ||J - J_fd|| / ||J||
/// below 1e-6 at every Newton iterate.
#[test]
fn the_assembled_constraint_tangent_matches_finite_differences_on_two_ranks() {
    let deck = PRET2.replace("LOAD\n", "*CLOAD\n14,1,3958.4\n");
    let run = run_deck_file("pret2.inp", &deck, &[], 2, &["--", "-snes_test_jacobian"]);
    run.assert_ok();
    let ratios = common::jacobian_test_ratios(&run.stdout());
    assert!(!ratios.is_empty(), "PETSc printed no Jacobian test:\n{}", run.stdout());
    for r in &ratios {
        assert!(*r < 1e-6, "||J - Jfd|| / ||J|| = {r:e}\n{}", run.stdout());
    }
}

#[test]
fn a_toml_tie_joins_two_blocks_meshed_differently() {
    let deck = r#"
nlgeom = false
[mesh]
[[mesh.block]]
name = "low"
r = [10.0, 12.0]
z = [0.0, 1.0]
divisions = [2, 1]
[[mesh.block]]
name = "up"
r = [10.0, 12.0]
z = [1.0, 2.0]
divisions = [3, 2]

[[material]]
name = "steel"
youngs_modulus = 210000.0
poissons_ratio = 0.3

[[tie]]
slave = "up_bottom"
master = "low_top"

[[step]]
boundary = [ { set = "low_bottom", uz = 0.0 }, { set = "up_top", uz = 0.01 } ]
"#;
    let run = run_deck(deck, &[], 2, &[]);
    run.assert_ok();
    assert_uniaxial(&Results::open(&run.h5), 1050.0, 0.005, "TOML tie");
}

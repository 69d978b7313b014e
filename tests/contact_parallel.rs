//! Contact on 2 ranks equals 1 rank. Three nested tubes (r in [100, 110], [109.97, 120],
//! [119.98, 130], z in [0, 12]) shrunk onto each other (interferences 0.03 and 0.02 mm) and
//! pressurised inside by 20 MPa, finite strain: two contact pairs, one surface-integrated and
//! two-pass, one node-to-segment with augmented-Lagrangian updates. The elements are split by
//! index (`-mat_partitioning_type average`: a and the lower part of b on rank 0, the rest of b
//! and c on rank 1), so both interfaces are cut and slave and master nodes of each pair live on
//! different ranks; slideline's own partition would keep facing elements together.
//! Also: PETSc's finite-difference check of the assembled Jacobian (-snes_test_jacobian) on the
//! same two-body-pair model on 2 ranks.

mod common;
use common::{displacement_difference, jacobian_test_ratios, run_deck, run_serial_and_parallel};

const DECK: &str = r#"
[[mesh.block]]
name = "a"
r = [100.0, 110.0]
z = [0.0, 12.0]
divisions = [3, 4]
[[mesh.block]]
name = "b"
r = [109.97, 120.0]
z = [0.0, 12.0]
divisions = [3, 5]
[[mesh.block]]
name = "c"
r = [119.98, 130.0]
z = [0.0, 12.0]
divisions = [3, 3]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
[[contact]]
name = "ab"
slave = "b_inner"
master = "a_outer"
two_pass = true
penalty = 1.0e5
[[contact]]
name = "bc"
slave = "c_inner"
master = "b_outer"
integration = "node-to-segment"
penalty = 1.0e4
augmented_lagrangian = { penetration_tolerance = 1e-5 }
[[step]]
increments = 3
boundary = [ { set = "a_bottom", uz = 0.0 }, { set = "b_bottom", uz = 0.0 }, { set = "c_bottom", uz = 0.0 } ]
pressure = [ { surface = "a_inner", value = 20.0 } ]
"#;

/// PETSc options that split the elements by index, cutting both interfaces (see above).
const CUT_BY_INDEX: &[&str] = &["--", "-mat_partitioning_type", "average"];

#[test]
fn two_contact_pairs_across_the_partition_match_one_rank() {
    let (_serial, r1, _parallel, r2) = run_serial_and_parallel(DECK, CUT_BY_INDEX);
    let (worst, scale) = displacement_difference(&r1, &r2);
    assert!(worst <= 1e-8 * scale, "displacements differ by {worst:e} (scale {scale:e})");
    // both interfaces are cut: a on rank 0, b on both, c on rank 1
    let ranks = r2.file.dataset("mesh/element_rank").unwrap().read_raw::<u32>().unwrap();
    let ranks_of = |block: &str| {
        let mut r: Vec<u32> = r2.u64s(&format!("mesh/element_sets/{block}")).iter().map(|&position| ranks[position as usize]).collect();
        r.sort_unstable();
        r.dedup();
        r
    };
    assert_eq!((ranks_of("a"), ranks_of("b"), ranks_of("c")), (vec![0], vec![0, 1], vec![1]));
    for pair in ["ab", "bc"] {
        let f1 = r1.history(&format!("contact_{pair}_force"));
        let f2 = r2.history(&format!("contact_{pair}_force"));
        for (a, b) in f1.iter().zip(&f2) {
            assert!((a - b).abs() <= 1e-8 * a.abs(), "pair {pair}: contact force {a} vs {b}");
        }
        assert!(f1.last().unwrap() > &0.0);
        // the node lists of a pass hold each slave node once, whatever the partition
        let n1 = r1.u64s(&format!("mesh/contact/{pair}/pass0/nodes")).len();
        let n2 = r2.u64s(&format!("mesh/contact/{pair}/pass0/nodes")).len();
        assert_eq!(n1, n2);
    }
    assert_eq!(r1.history("augmentations"), r2.history("augmentations"));
}

#[test]
fn assembled_contact_jacobian_matches_finite_differences_on_two_ranks() {
    // one increment to a state with active contact, then PETSc's check at every Newton
    // iterate of a second increment (a finite-strain, two-body, two-pair state)
    let deck = DECK.replace("increments = 3", "increments = 2");
    let run = run_deck(&deck, &[], 2, &[CUT_BY_INDEX, &["-snes_test_jacobian"]].concat());
    run.assert_ok();
    let out = run.stdout();
    let ratios = jacobian_test_ratios(&out);
    assert!(ratios.len() >= 4, "PETSc printed too few Jacobian tests:\n{out}");
    for r in &ratios {
        assert!(*r < 1e-6, "||J - Jfd|| / ||J|| = {r:e}");
    }
}

//! The finite-element plies as formed, and the finite-element joint set beside the code's.
//!
//! An engineer's DN400 joint (tests/data/specs/dn400_rev_c.toml: 3 plies x 0.8 mm of 316L, w 28,
//! q 28, 10 convolutions, 1.6 MPa at 300 degC, Sy 125 MPa, H 1000 MPa) passes the code's
//! in-plane check, whose formulas take the plies as formed (cold-worked), while its annealed
//! finite-element plies yield under the design pressure alone (about 0.4 % plastic strain at
//! the roots on the engineer's mesh). The plies given 15 % cold work (the annealed curve from
//! there: yield 125 + 1000 x 0.15 = 275 MPa) do not. The quick mesh on 2 ranks, 25 mm stroke.

mod common;
use common::command_in;
use slideline::bellows::spec::DesignSpec;
use std::path::{Path, PathBuf};

fn dn400() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/specs/dn400_rev_c.toml")).unwrap()
}

/// The DN400 specification with `line` added to its [material] table.
fn with_material(line: &str) -> String {
    dn400().replace("hardening_modulus = 1000.0", &format!("hardening_modulus = 1000.0\n{line}"))
}

#[test]
fn the_plies_as_formed_are_a_material_of_their_own_and_bad_ones_are_named() {
    let spec = DesignSpec::from_text(&with_material("cold_work = 0.15"), &PathBuf::from("cw.toml")).unwrap();
    let model = slideline::bellows::joint::model(&spec).unwrap();
    assert_eq!(model.materials.len(), 2);
    let plastic = |k: usize| model.materials[k].plasticity.unwrap().initial_yield_stress();
    assert_eq!((plastic(0), plastic(1)), (125.0, 275.0));
    let plies: Vec<usize> = (1..=3).flat_map(|k| model.element_sets[&format!("ply{k}")].clone()).collect();
    assert!(plies.iter().all(|&e| model.element_material[e] == 1));
    assert_eq!(model.element_material.iter().filter(|&&m| m == 0).count(), model.mesh.elements.len() - plies.len(), "the tubes and sleeve stay annealed");
    let curve = DesignSpec::from_text(&with_material("formed_curve = [[0.0, 300.0], [0.1, 360.0]]"), &PathBuf::from("c.toml")).unwrap();
    let model = slideline::bellows::joint::model(&curve).unwrap();
    assert_eq!(model.materials[1].plasticity.unwrap().initial_yield_stress(), 300.0);
    // the seed joint, annealed: one material, as before
    assert_eq!(slideline::bellows::joint::model(&DesignSpec::seed()).unwrap().materials.len(), 1);
    for (line, needle) in [
        ("cold_work = 0.1\nformed_curve = [[0.0, 300.0]]", "material.cold_work: give one of formed_curve and cold_work"),
        ("formed_curve = [[0.01, 300.0]]", "material.formed_curve: the first point of a hardening table must be at plastic strain 0"),
        ("cold_work = -0.1", "material.cold_work: a plastic strain > 0, got -0.1"),
    ] {
        let e = DesignSpec::from_text(&with_material(line), &PathBuf::from("bad.toml")).unwrap_err().to_string();
        assert!(e.contains(needle), "{line}: {e}");
    }
    let e = DesignSpec::from_text(&with_material("cold_work = 0.1").replace("hardening_modulus = 1000.0", "hardening_modulus = 0.0"), &PathBuf::from("h.toml"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("cold work raises nothing"), "{e}");
}

/// The section after the closing table: the plies' material, the code's as-formed and thinned
/// plies beside them, yield under the pressure named with the pressures it falls between, and
/// each convolution's share of the stroke (in all the stroke with the pipes' thermal growth:
/// alpha 1.7e-5 x 280 degC over two tubes).
#[test]
fn the_fe_joint_is_set_beside_the_codes_and_yield_under_pressure_named() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, text: &str| {
        let spec = dir.path().join(format!("{name}.toml"));
        std::fs::write(&spec, text).unwrap();
        let out = command_in(dir.path(), 2)
            .args(["bellows", "--spec"])
            .arg(&spec)
            .args(["--quick", "--displacement", "25", "-q", "-o"])
            .arg(dir.path().join(format!("{name}.h5")))
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(out.status.success(), "{text}{}", String::from_utf8_lossy(&out.stderr));
        text[text.find("the finite-element joint beside the code's").expect("the section")..].to_string()
    };
    let shares = |section: &str| -> Vec<f64> {
        let line = section.lines().find(|l| l.trim_start().starts_with("1: ")).expect("the shares' line");
        line.split('(').skip(1).map(|s| s.split(" %").next().unwrap().parse::<f64>().unwrap()).collect()
    };
    let annealed = run("annealed", &dn400());
    assert!(annealed.contains("plies: annealed: yield 125 MPa, hardening 1000 MPa"), "{annealed}");
    assert!(annealed.contains("(tp 0.7717 mm; the finite-element plies 0.8 mm)"), "{annealed}");
    assert!(
        annealed.contains("the joint yields under the design pressure alone (more than 0.01 % plastic strain): first between 0.8 and 1.6 MPa\n"),
        "{annealed}"
    );
    let formed = run("formed", &with_material("cold_work = 0.15"));
    assert!(formed.contains("plies: as formed: the annealed curve from 15 % cold work on, yield 275 MPa"), "{formed}");
    assert!(!formed.contains("yields under the design pressure"), "{formed}");
    for section in [&annealed, &formed] {
        let s = shares(section);
        assert_eq!(s.len(), 10, "{section}");
        assert!((s.iter().sum::<f64>() - 100.0).abs() <= 5.0, "{s:?}");
        assert!(section.contains("26.5"), "the stroke with the pipes' growth: {section}");
    }
    // the formed plies share the stroke about evenly; the annealed ones leave the end
    // convolutions a third of the others' (the quick mesh: no localisation named)
    assert!(shares(&formed).iter().all(|&s| (7.0..=11.0).contains(&s)), "{formed}");
    assert!(shares(&annealed)[0] < 5.0 && !annealed.contains("localises"), "{annealed}");
    // and the quick mesh says what it cannot see
    assert!(annealed.contains("one element through each ply (the quick mesh) does not see a convolution collapse"), "{annealed}");
}

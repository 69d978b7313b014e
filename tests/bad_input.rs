//! Bad input gives one clear message naming the offending item and exit code 2 (no panic,
//! no PETSc trace).

mod common;
use common::{assert_rejected, command_in, data, run_deck, Run};

const MATERIAL: &str = "[[material]]\nname = \"steel\"\nyoungs_modulus = 200000.0\npoissons_ratio = 0.3\n";
const STEP: &str = "[[step]]\nboundary = [ { set = \"bottom\", uz = 0.0 } ]\n";
const RECT: &str = "[mesh]\nrectangle = { r = [1.0, 2.0], z = [0.0, 1.0], divisions = [2, 1] }\n";

#[test]
fn missing_deck_file() {
    let dir = tempfile::tempdir().unwrap();
    let output = command_in(dir.path(), 1).args(["run", "/nonexistent/deck.toml", "-q"]).output().unwrap();
    let missing = Run { h5: dir.path().join("none.h5"), dir, output };
    assert_rejected(&missing, &["/nonexistent/deck.toml", "No such file"]);
}

#[test]
fn missing_mesh_file() {
    let run = run_deck(&format!("[mesh]\nfile = \"nowhere.msh\"\n{MATERIAL}{STEP}"), &[], 1, &[]);
    assert_rejected(&run, &["nowhere.msh"]);
}

#[test]
fn malformed_toml() {
    let run = run_deck(&format!("{RECT}{MATERIAL}[[step]\n"), &[], 1, &[]);
    assert_rejected(&run, &["deck.toml", "line"]);
}

#[test]
fn unknown_key() {
    let run = run_deck(&format!("{RECT}{MATERIAL}youngs_modulus_typo = 1.0\n{STEP}"), &[], 1, &[]);
    assert_rejected(&run, &["youngs_modulus_typo"]);
}

#[test]
fn unknown_set_name() {
    let run = run_deck(&format!("{RECT}{MATERIAL}[[step]]\nboundary = [ {{ set = \"botom\", uz = 0.0 }} ]\n"), &[], 1, &[]);
    assert_rejected(&run, &["'botom'", "bottom"]);
}

#[test]
fn non_positive_youngs_modulus() {
    let run = run_deck(&format!("{RECT}[[material]]\nname = \"soft\"\nyoungs_modulus = 0.0\npoissons_ratio = 0.3\n{STEP}"), &[], 1, &[]);
    assert_rejected(&run, &["'soft'", "Young's modulus"]);
}

#[test]
fn poissons_ratio_out_of_range() {
    for nu in ["0.5", "-1.0", "0.7"] {
        let run = run_deck(&format!("{RECT}[[material]]\nname = \"rubber\"\nyoungs_modulus = 10.0\npoissons_ratio = {nu}\n{STEP}"), &[], 1, &[]);
        assert_rejected(&run, &["'rubber'", "Poisson's ratio"]);
    }
}

#[test]
fn inverted_element() {
    let run = run_deck(&format!("[mesh]\nfile = \"m.msh\"\n{MATERIAL}[[step]]\n"), &[("m.msh", &data("inverted.msh"))], 1, &[]);
    assert_rejected(&run, &["element 1", "non-positive Jacobian"]);
}

#[test]
fn degenerate_element() {
    let run = run_deck(&format!("[mesh]\nfile = \"m.msh\"\n{MATERIAL}[[step]]\n"), &[("m.msh", &data("degenerate.msh"))], 1, &[]);
    assert_rejected(&run, &["element 1", "degenerate"]);
}

#[test]
fn mesh_without_elements() {
    let run = run_deck(&format!("[mesh]\nfile = \"m.msh\"\n{MATERIAL}[[step]]\n"), &[("m.msh", &data("no_elements.msh"))], 1, &[]);
    assert_rejected(&run, &["no elements"]);
}

#[test]
fn four_node_quadrilaterals_are_refused_by_name() {
    let text = std::fs::read_to_string(data("inverted.msh")).unwrap().replace("2 1 16 1\n1 1 4 3 2 8 7 6 5", "2 1 3 1\n1 1 2 3 4");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("q4.msh");
    std::fs::write(&path, text).unwrap();
    let run = run_deck(&format!("[mesh]\nfile = \"q4.msh\"\n{MATERIAL}[[step]]\n"), &[("q4.msh", &path)], 1, &[]);
    assert_rejected(&run, &["q4.msh:", "element 1", "4-node quadrilateral"]);
}

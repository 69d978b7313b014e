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
    assert_rejected(&run, &["deck.toml:7:", "[[step]", "invalid table header"]);
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

/// Values that would run into a meaningless solve are refused while reading, each by name.
#[test]
fn non_finite_and_absurd_values_are_refused_when_read() {
    let step = |extra: &str| format!("[[step]]\nboundary = [ {{ set = \"bottom\", uz = 0.0 }} ]\n{extra}");
    for (deck, needles) in [
        (format!("{RECT}{MATERIAL}{}", step("pressure = [ { surface = \"inner\", value = nan } ]\n")), vec!["pressure on 'inner'", "finite"]),
        (format!("{RECT}{MATERIAL}{}", step("pressure = [ { surface = \"inner\", value = inf } ]\n")), vec!["pressure on 'inner'", "finite"]),
        (format!("{RECT}{MATERIAL}{}", step("temperature = inf\n")), vec!["temperature", "finite"]),
        (format!("reference_temperature = nan\n{RECT}{MATERIAL}{}", step("")), vec!["reference temperature", "finite"]),
        (format!("{RECT}[[material]]\nname = \"fog\"\nyoungs_modulus = 1e-300\npoissons_ratio = 0.3\n{}", step("")), vec!["'fog'", "Young's modulus"]),
        (format!("{RECT}{MATERIAL}{}", step("increments = 1000000000000\n")), vec!["increments", "1000000000000"]),
        (
            format!("{RECT}{MATERIAL}{}", step("pressure = [ { surface = \"inner\", value = 1.0 }, { surface = \"inner\", value = 2.0 } ]\n")),
            vec!["'inner'", "two pressures"],
        ),
        (
            format!("[mesh]\nrectangle = {{ r = [1.0, 2.0], z = [0.0, 1.0], divisions = [100000, 100000] }}\n{MATERIAL}{}", step("")),
            vec!["100000 x 100000", "elements"],
        ),
    ] {
        let run = run_deck(&deck, &[], 1, &[]);
        assert_rejected(&run, &needles);
    }
}

#[test]
fn two_values_on_one_degree_of_freedom_are_refused() {
    // the same set twice, and two sets sharing the corner node at (1, 0)
    for boundary in ["{ set = \"bottom\", uz = 0.0 }, { set = \"bottom\", uz = 0.1 }", "{ set = \"bottom\", uz = 0.0 }, { set = \"inner\", uz = 0.1 }"] {
        let run = run_deck(&format!("{RECT}{MATERIAL}[[step]]\nboundary = [ {boundary} ]\n"), &[], 1, &[]);
        assert_rejected(&run, &["uz", "0.1", "one degree of freedom takes one value"]);
    }
    // the same value twice is one constraint
    run_deck(&format!("{RECT}{MATERIAL}[[step]]\nboundary = [ {{ set = \"bottom\", uz = 0.0 }}, {{ set = \"inner\", uz = 0.0 }} ]\n"), &[], 1, &[]).assert_ok();
}

#[test]
fn a_body_free_to_move_axially_is_refused() {
    let run = run_deck(
        &format!("{RECT}{MATERIAL}[[step]]\nboundary = [ {{ set = \"inner\", ur = 0.0 }} ]\npressure = [ {{ surface = \"outer\", value = 1.0 }} ]\n"),
        &[],
        1,
        &[],
    );
    assert_rejected(&run, &["free to move along the axis", "prescribe uz"]);
}

#[test]
fn duplicate_contact_pair_names_are_refused_when_read() {
    let blocks = "[[mesh.block]]\nname = \"a\"\nr = [1.0, 2.0]\nz = [0.0, 1.0]\ndivisions = [1, 1]\n[[mesh.block]]\nname = \"b\"\nr = [2.0, 3.0]\nz = [0.0, 1.0]\ndivisions = [1, 1]\n";
    let pair = "[[contact]]\nname = \"fit\"\nslave = \"b_inner\"\nmaster = \"a_outer\"\npenalty = 1e4\n";
    let step = "[[step]]\nboundary = [ { set = \"a_bottom\", uz = 0.0 }, { set = \"b_bottom\", uz = 0.0 } ]\n";
    let run = run_deck(&format!("{blocks}{MATERIAL}{pair}{pair}{step}"), &[], 1, &[]);
    assert_rejected(&run, &["'fit'", "used twice"]);
}

#[test]
fn a_bad_adjust_is_named_with_its_pair() {
    let blocks = "[[mesh.block]]\nname = \"a\"\nr = [1.0, 2.0]\nz = [0.0, 1.0]\ndivisions = [1, 1]\n[[mesh.block]]\nname = \"b\"\nr = [2.0, 3.0]\nz = [0.0, 1.0]\ndivisions = [1, 1]\n";
    let step = "[[step]]\nboundary = [ { set = \"a_bottom\", uz = 0.0 }, { set = \"b_bottom\", uz = 0.0 } ]\n";
    for (pair, needles) in [
        ("slave = \"b_inner\"\nmaster = \"a_outer\"\nadjust = -0.1", &["contact 'fit'", "clearance >= 0", "-0.1"][..]),
        ("slave = \"b_inner\"\nmaster = \"a_outer\"\nadjust = \"nowhere\"", &["contact 'fit'", "unknown node set 'nowhere'"][..]),
        (
            "slave = \"b_inner\"\nmaster = \"a_outer\"\nadjust = \"a_bottom\"",
            &["contact 'fit'", "adjust set 'a_bottom'", "not on the slave surface 'b_inner'"][..],
        ),
        ("slave = \"b_inner\"\nmaster = \"b_inner\"\nadjust = 0.1", &["contact 'fit'", "not self-contact"][..]),
    ] {
        let contact = format!("[[contact]]\nname = \"fit\"\n{pair}\npenalty = 1e4\n");
        let run = run_deck(&format!("{blocks}{MATERIAL}{contact}{step}"), &[], 1, &[]);
        assert_rejected(&run, needles);
    }
}

#[test]
fn an_output_path_that_cannot_be_written_is_refused_before_the_solve() {
    let deck = format!("{RECT}{MATERIAL}{STEP}");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("deck.toml"), &deck).unwrap();
    for (output, needle) in [("missing/out.h5", "does not exist"), (".", "is a directory"), ("deck.toml", "input deck")] {
        let out = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "deck.toml", "-o", output]).output().unwrap();
        let run = Run { h5: dir.path().join(output), dir: tempfile::tempdir().unwrap(), output: out };
        assert_rejected(&run, &["cannot write", needle]);
    }
    assert_eq!(std::fs::read_to_string(dir.path().join("deck.toml")).unwrap(), deck, "the deck is untouched");
}

/// A results file being written by a live run is refused; a lock left by a process that is
/// gone is replaced with a note; the lock is removed when the run ends.
#[test]
fn a_results_file_in_use_is_refused_and_a_stale_lock_replaced() {
    let deck = format!("{RECT}{MATERIAL}{STEP}");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("deck.toml"), &deck).unwrap();
    let lock = dir.path().join("out.lock");
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    let run_to = |output: &str| command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "deck.toml", "-o", output]).output().unwrap();
    let run = || run_to("out.h5");
    // held by this test process: alive
    std::fs::write(&lock, format!("host {} pid {}\n", host.trim(), std::process::id())).unwrap();
    let out = run();
    let held = Run { h5: dir.path().join("out.h5"), dir: tempfile::tempdir().unwrap(), output: out };
    assert_rejected(&held, &["out.h5", "another run is writing it", "out.lock"]);
    assert!(!dir.path().join("out.h5").exists(), "nothing written");
    // the same files under other names: out.hdf5 would write the same out.xmf and out.sta, a
    // link leads to the same file (seen failing before: both ran, into the running run's files)
    std::os::unix::fs::symlink(dir.path().join("out.h5"), dir.path().join("link.h5")).unwrap();
    for other in ["out.hdf5", "link.h5"] {
        let held = Run { h5: dir.path().join(other), dir: tempfile::tempdir().unwrap(), output: run_to(other) };
        assert_rejected(&held, &["another run is writing it", "out.lock"]);
    }
    assert!(!dir.path().join("out.h5").exists() && !dir.path().join("out.xmf").exists(), "nothing written");
    // held by a process that is gone (pids stay below 2^22 on Linux)
    std::fs::write(&lock, format!("host {} pid 4194304\n", host.trim())).unwrap();
    let out = run();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains("replaced the stale lock"));
    assert!(!lock.exists(), "the lock is removed at the end of the run");
    // an empty lock, as a write onto a full disk left one, names no process: stale (seen
    // failing before: refused as "another run is writing it (unknown process)")
    std::fs::write(&lock, "").unwrap();
    let out = run();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains("replaced the stale lock") && String::from_utf8_lossy(&out.stdout).contains("empty"));
    assert!(!lock.exists(), "the lock is removed at the end of the run");
}

/// `check` takes the locks of every file it will write before its first analysis: a check
/// whose ratcheting file another live run holds writes nothing, not even its limit-load file
/// (seen failing before: the limit-load analysis ran and replaced the file of the same name,
/// and the check was refused only at the ratcheting file).
#[test]
fn a_check_writes_nothing_when_one_of_its_files_is_held() {
    let dir = tempfile::tempdir().unwrap();
    let deck = std::fs::read_to_string(common::data("dba/thick_cylinder.toml")).unwrap();
    std::fs::write(dir.path().join("deck.toml"), deck.replace("limit_load = {", "ratcheting = { cycle = [\"pressurise\"], cycles = 3 }\nlimit_load = {"))
        .unwrap();
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname").unwrap();
    std::fs::write(dir.path().join("out_ratcheting.lock"), format!("host {} pid {}\n", host.trim(), std::process::id())).unwrap();
    std::fs::write(dir.path().join("out_limit_load.h5"), "another check's finished file").unwrap();
    let out = command_in(dir.path(), 1).current_dir(dir.path()).args(["check", "deck.toml", "-o", "out.h5", "--quiet"]).output().unwrap();
    let held = Run { h5: dir.path().join("out.h5"), dir: tempfile::tempdir().unwrap(), output: out };
    assert_rejected(&held, &["out_ratcheting.h5", "another run is writing it"]);
    assert_eq!(std::fs::read_to_string(dir.path().join("out_limit_load.h5")).unwrap(), "another check's finished file", "the other file untouched");
    for lock in ["out.lock", "out_limit_load.lock", "out_buckling.lock", "out_fatigue.lock"] {
        assert!(!dir.path().join(lock).exists(), "{lock} taken and left");
    }
    assert!(dir.path().join("out_ratcheting.lock").exists(), "the other run's lock stays");
}

#[test]
fn a_misspelt_petsc_option_is_named_in_a_warning() {
    let run = run_deck(&format!("{RECT}{MATERIAL}{STEP}"), &[], 1, &["--", "-snes_monitr", "-ksp_type", "preonly"]);
    run.assert_ok();
    let err = run.stderr();
    assert!(err.contains("warning: PETSc option -snes_monitr was not used"), "{err}");
    assert!(!err.contains("-ksp_type"), "an option PETSc read is not reported: {err}");
}

#[test]
fn a_preconditioner_alone_is_refused_alike_on_one_and_two_ranks() {
    for ranks in [1, 2] {
        let run = run_deck(&format!("{RECT}{MATERIAL}{STEP}"), &[], ranks, &["--", "-pc_type", "ilu"]);
        assert_rejected(&run, &["-pc_type ilu", "-ksp_type preonly", "Krylov"]);
    }
}

#[test]
fn a_geometry_or_a_binary_file_given_as_the_mesh_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let geo = dir.path().join("m.geo");
    std::fs::write(&geo, "Point(1) = {0, 0, 0};\n").unwrap();
    let run = run_deck(&format!("[mesh]\nfile = \"m.geo\"\n{MATERIAL}{STEP}"), &[("m.geo", &geo)], 1, &[]);
    assert_rejected(&run, &["m.geo", "mesh it first", "gmsh -2 -order 2"]);
    let bin = dir.path().join("b.msh");
    std::fs::write(&bin, b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\xff\xfe\n$EndMeshFormat\n").unwrap();
    let run = run_deck(&format!("[mesh]\nfile = \"b.msh\"\n{MATERIAL}{STEP}"), &[("b.msh", &bin)], 1, &[]);
    assert_rejected(&run, &["b.msh", "binary"]);
}

/// PETSc options that cannot work or would make the answers wrong are refused on 2 ranks with
/// exit 2 and one line naming the option, before anything is written: a rerun with any of them
/// leaves the good results file it would replace as it was. Seen failing before: `-snes_type
/// bogus` and `-snes_max_it abc` exit 1 with PETSc's internals named, after the results file
/// was truncated; `-snes_max_it 0`, `-snes_mf`, `-ksp_type preonly -pc_type jacobi` exit 3;
/// `-snes_rtol -1`, `-snes_atol nan` and `-snes_type ksponly` ran (ksponly reporting success for
/// increments out of equilibrium); `-options_file` naming a missing file exit 1.
#[test]
fn bad_petsc_options_are_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let deck = dir.path().join("deck.toml");
    std::fs::write(&deck, format!("{RECT}{MATERIAL}{STEP}")).unwrap();
    let h5 = dir.path().join("out.h5");
    let good = command_in(dir.path(), 2).arg("run").arg(&deck).arg("-o").arg(&h5).arg("-q").output().unwrap();
    assert!(good.status.success(), "{}", String::from_utf8_lossy(&good.stderr));
    let before = std::fs::read(&h5).unwrap();
    for (options, needle) in [
        (&["-snes_type", "bogus"][..], "-snes_type bogus: unknown SNES type"),
        (&["-snes_type", "ksponly"], "-snes_type ksponly"),
        (&["-snes_max_it", "abc"], "-snes_max_it \"abc\""),
        (&["-snes_max_it", "0"], "-snes_max_it \"0\""),
        (&["-snes_rtol", "-1"], "-snes_rtol \"-1\""),
        (&["-snes_atol", "nan"], "-snes_atol \"nan\""),
        (&["-snes_mf"], "-snes_mf"),
        (&["-ksp_type", "preonly", "-pc_type", "jacobi"], "-pc_type jacobi"),
        (&["-ksp_type", "gmres", "-pc_type", "bogus"], "PC type bogus"),
        (&["-options_file", "/nonexistent/options"], "-options_file /nonexistent/options"),
    ] {
        let out = command_in(dir.path(), 2).arg("run").arg(&deck).arg("-o").arg(&h5).arg("-q").arg("--").args(options).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        let errors: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
        assert_eq!(out.status.code(), Some(2), "{options:?}: {err}");
        assert!(errors.len() == 1 && errors[0].contains(needle) && !err.contains("error code"), "{options:?}: {err}");
        assert!(!err.contains("warning: PETSc option"), "{options:?}: no warning beside the error: {err}");
        assert_eq!(std::fs::read(&h5).unwrap(), before, "{options:?}: the good results file was touched");
    }
}

/// A run never writes over what it reads, under whatever name: a TOML deck's mesh file, an .inp
/// deck's include, a hard link to the deck, and `bellows --export-inp` onto its `--params` file
/// are refused with exit 2 naming the input, and the input stays as it was. Seen failing
/// before: each of them was overwritten.
#[test]
fn outputs_never_overwrite_an_input_file() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    std::fs::copy(data("patch5.msh"), root.join("m.msh")).unwrap();
    let step = "[[step]]\nboundary = [ { set = \"b1\", ur = 0.0, uz = 0.0 }, { set = \"b2\", uz = 0.0 } ]\n";
    std::fs::write(root.join("deck.toml"), format!("[mesh]\nfile = \"m.msh\"\n{MATERIAL}{step}")).unwrap();
    std::fs::hard_link(root.join("deck.toml"), root.join("alias.h5")).unwrap();
    for name in ["lame.inp", "lame_mesh.inc"] {
        std::fs::copy(data(&format!("inp/{name}")), root.join(name)).unwrap();
    }
    std::fs::write(root.join("joint.toml"), "[bellows]\nplies = 2\n").unwrap();
    let inputs = ["m.msh", "deck.toml", "lame.inp", "lame_mesh.inc", "joint.toml"].map(|f| (f, std::fs::read(root.join(f)).unwrap()));
    for (args, needle) in [
        (&["run", "deck.toml", "-o", "m.msh"][..], "an input file of the model"),
        (&["run", "deck.toml", "-o", "alias.h5"], "the input deck"),
        (&["run", "lame.inp", "-o", "lame_mesh.inc"], "an input file of the model"),
        (&["bellows", "--params", "joint.toml", "--export-inp", "joint.toml"], "the --params file"),
        (&["bellows", "--params", "joint.toml", "-o", "joint.toml"], "the --params file"),
    ] {
        let out = command_in(root, 1).current_dir(root).args(args).output().unwrap();
        let run = Run { h5: root.join("none.h5"), dir: tempfile::tempdir().unwrap(), output: out };
        assert_rejected(&run, &["cannot write", needle]);
    }
    for (name, bytes) in inputs {
        assert_eq!(std::fs::read(root.join(name)).unwrap(), bytes, "{name} was written over");
    }
}

/// Rank 0 alone writes the XDMF sidecar and the status file; a directory where either goes is
/// refused by every rank before the run, exit 2 (seen failing before: rank 0 stopped and rank
/// 1 waited forever).
#[test]
fn a_directory_where_the_sidecar_or_status_file_goes_is_refused_on_two_ranks() {
    for side in ["out.xmf", "out.sta"] {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("deck.toml"), format!("{RECT}{MATERIAL}{STEP}")).unwrap();
        std::fs::create_dir(dir.path().join(side)).unwrap();
        let out = command_in(dir.path(), 2).current_dir(dir.path()).args(["run", "deck.toml", "-o", "out.h5"]).output().unwrap();
        let run = Run { h5: dir.path().join("out.h5"), dir: tempfile::tempdir().unwrap(), output: out };
        assert_rejected(&run, &["cannot write", side, "a directory"]);
    }
}

/// A Gmsh file that contradicts itself is refused with exit 2 and the line named, never read
/// as valid or allowed to exhaust memory. Seen failing before: each of these was accepted (a
/// header of 2^62 nodes in one block reserved memory for them).
#[test]
fn a_gmsh_file_that_contradicts_itself_is_refused() {
    let text = std::fs::read_to_string(data("patch5.msh")).unwrap();
    let nodes = &text[text.find("$Nodes").unwrap()..text.find("$Elements").unwrap()];
    let step = "[[step]]\nboundary = [ { set = \"b1\", ur = 0.0, uz = 0.0 }, { set = \"b2\", uz = 0.0 } ]\n";
    let dir = tempfile::tempdir().unwrap();
    for (what, bad, needle) in [
        ("2^62 nodes in a block", text.replace("$Nodes\n1 20 1 111\n2 1 0 20\n", "$Nodes\n1 4611686018427387904 1 111\n2 1 0 4611686018427387904\n"), "m.msh:"),
        (
            "10^15 nodes in the header",
            text.replace("$Nodes\n1 20 1 111\n", "$Nodes\n1 1000000000000000 1 111\n"),
            "gives 1000000000000000 nodes, its blocks hold 20",
        ),
        ("two $Nodes sections", text.replace("$Elements", &format!("{nodes}$Elements")), "a second $Nodes section"),
        ("a duplicate element id", text.replace("1001 1 2 6 5", "1000 1 2 6 5"), "element 1000 is given twice"),
        ("a wrong element count", text.replace("9 13 1000 2007", "9 14 1000 2007"), "gives 14 elements, its blocks hold 13"),
        ("a node tag twice, elsewhere", text.replace("8\n100\n101", "8\n1\n101"), "node 1 is given twice"),
    ] {
        std::fs::write(dir.path().join("m.msh"), &bad).unwrap();
        let run = run_deck(&format!("[mesh]\nfile = \"m.msh\"\n{MATERIAL}{step}"), &[("m.msh", &dir.path().join("m.msh"))], 1, &[]);
        assert_eq!(run.code(), 2, "{what}: {}", run.stderr());
        assert!(run.stderr().contains(needle), "{what}: {}", run.stderr());
        assert_rejected(&run, &[needle]);
    }
}

/// Step names are how a restart finds the steps done: two steps of one name or an empty name
/// are refused (both ran); a `[stepping]` value out of range is named with its key, not as a
/// Rust structure.
#[test]
fn step_names_and_stepping_values_are_checked_by_name() {
    let step = |name: &str| format!("[[step]]\nname = \"{name}\"\nboundary = [ {{ set = \"bottom\", uz = 0.0 }} ]\n");
    let twice = run_deck(&format!("{RECT}{MATERIAL}{}{}", step("load"), step("load")), &[], 1, &[]);
    assert_rejected(&twice, &["step 2", "\"load\" is used twice"]);
    let empty = run_deck(&format!("{RECT}{MATERIAL}{}", step("")), &[], 1, &[]);
    assert_rejected(&empty, &["step 1", "an empty name"]);
    let growth = run_deck(&format!("[stepping]\ngrowth_factor = 0.5\n{RECT}{MATERIAL}{STEP}"), &[], 1, &[]);
    assert_rejected(&growth, &["[stepping] growth_factor = 0.5", "growth_factor >= 1"]);
    assert!(!growth.stderr().contains("SteppingControls"), "{}", growth.stderr());
}

/// A TOML error is one line naming the file, the line and the key with its table (it was a
/// multi-line excerpt with a caret, and a missing [mesh] named no file section).
#[test]
fn toml_errors_name_the_line_and_the_key_on_one_line() {
    let cases = [
        (format!("nlgeo = true\n{RECT}{MATERIAL}{STEP}"), vec!["deck.toml:1: nlgeo: unknown field `nlgeo`"]),
        (format!("[stepping]\ncutback_factor = \"half\"\n{RECT}{MATERIAL}{STEP}"), vec!["deck.toml:2: [stepping] cutback_factor: invalid type"]),
        (format!("{RECT}{MATERIAL}{STEP}").replace("youngs_modulus", "youngs_modulu"), vec![":5: [[material]] youngs_modulu: unknown field"]),
        (format!("{MATERIAL}{STEP}"), vec!["deck.toml: missing field `mesh`"]),
        // an array left open at the end of the file: the empty last line is not quoted
        (format!("{RECT}{MATERIAL}{STEP}garbage = [\n"), vec!["deck.toml:", ": invalid array"]),
    ];
    for (deck, needles) in cases {
        let run = run_deck(&deck, &[], 1, &[]);
        assert_rejected(&run, &needles);
        assert_eq!(run.stderr().trim_end().lines().count(), 1, "{}", run.stderr());
        assert!(!run.stderr().contains(": :"), "{}", run.stderr());
    }
}

/// A contact pair whose surfaces can never face each other (the ring's outside listed against
/// the tube's outside) is named in a note before the run (it ran without a word, the fit never
/// closing); the walk-through's correct pair is not.
#[test]
fn a_contact_pair_whose_surfaces_never_face_is_named() {
    let fit = std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/shrink_fit.toml")).unwrap();
    let wrong = fit.replace("slave = \"ring_inner\"", "slave = \"ring_outer\"");
    assert_ne!(wrong, fit);
    let dir = tempfile::tempdir().unwrap();
    for (deck, noted) in [(wrong, true), (fit, false)] {
        std::fs::write(dir.path().join("fit.toml"), deck).unwrap();
        let out = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "fit.toml", "-o", "fit.h5"]).output().unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        assert_eq!(text.contains("note: contact 'fit': its surfaces 'ring_outer' and 'tube_outer' never face each other"), noted, "{text}");
    }
}

/// Output places that cannot take a file are refused before any work with exit 2 and "cannot
/// write": a device (`-o /dev/full` crashed with SIGSEGV), the export of the bellows deck to a
/// missing directory and a CSV into /proc (both exit 1 after the work).
#[test]
fn output_places_that_cannot_take_a_file_are_refused_first() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("deck.toml"), format!("{RECT}{MATERIAL}{STEP}")).unwrap();
    let good = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "deck.toml", "-o", "good.h5", "-q"]).output().unwrap();
    assert!(good.status.success());
    for args in [
        &["run", "deck.toml", "-o", "/dev/full"][..],
        &["bellows", "--quick", "--export-inp", "/nonexistent/dir/joint.inp"],
        &["post", "good.h5", "--csv", "/proc/history.csv"],
    ] {
        let out = command_in(dir.path(), 1).current_dir(dir.path()).args(args).output().unwrap();
        let run = Run { h5: dir.path().join("x.h5"), dir: tempfile::tempdir().unwrap(), output: out };
        assert_rejected(&run, &["cannot write"]);
    }
}

/// A `[[tie]]` names its unknown surface, a tolerance that is no distance, and surfaces too far
/// apart to tie.
#[test]
fn a_wrong_tie_is_named() {
    for (tie, needles) in [
        ("slave = \"top\"\nmaster = \"topp\"\n", ["tie 'top-topp'", "unknown surface 'topp'"]),
        ("slave = \"top\"\nmaster = \"bottom\"\ntolerance = -1.0\n", ["tie 'top-bottom'", "tolerance -1: give a distance > 0"]),
        ("name = \"far\"\nslave = \"top\"\nmaster = \"bottom\"\n", ["tie 'far'", "no node of 'top' lies within"]),
    ] {
        let run = run_deck(&format!("{RECT}{MATERIAL}[[tie]]\n{tie}{STEP}"), &[], 1, &[]);
        assert_rejected(&run, &needles);
    }
}

/// A heat step's mistakes: no conductivity, a mechanical entry in it, a uniform temperature
/// (it holds temperatures on sets), a general step before it or one with its own temperature
/// after it.
#[test]
fn a_wrong_heat_step_is_named() {
    let heat = "[[step]]\nname = \"h\"\nprocedure = \"heat\"\n";
    let held = "temperature = [{ set = \"inner\", value = 100.0 }]\n";
    let conductive = "[[material]]\nname = \"steel\"\nconductivity = 16.0\n";
    for (deck, needles) in [
        (format!("{RECT}{MATERIAL}{heat}{held}"), vec!["heat step 'h'", "material 'steel' has no conductivity"]),
        (format!("{RECT}{conductive}{heat}{held}boundary = [{{ set = \"bottom\", uz = 0.0 }}]\n"), vec!["step 'h'", "boundary has no meaning in a heat step"]),
        (format!("{RECT}{conductive}{heat}temperature = 100.0\n"), vec!["step 'h'", "holds temperatures on node sets"]),
        (format!("{RECT}{conductive}{heat}temperature = [{{ set = \"nowhere\", value = 1.0 }}]\n"), vec!["heat step 'h'", "unknown node set 'nowhere'"]),
        (
            format!("{RECT}{MATERIAL}conductivity = 16.0\n{STEP}{heat}{held}"),
            vec!["step 'h'", "a heat step after the general step 'step-1'", "heat steps first"],
        ),
        (
            format!("{RECT}{MATERIAL}conductivity = 16.0\n{heat}{held}{STEP}temperature = 50.0\n"),
            vec!["heat step 'h'", "general step 'step-2' gives its own temperature"],
        ),
        (format!("{RECT}{conductive}{STEP}"), vec!["material 'steel': missing youngs_modulus (MPa)"]),
    ] {
        let run = run_deck(&deck, &[], 1, &[]);
        assert_rejected(&run, &needles);
    }
}

/// The steps run in one order, heat, general, perturbation: a step out of it is named with the
/// step it follows.
#[test]
fn a_step_out_of_the_order_steps_run_in_is_named() {
    let frequency = "[[step]]\nname = \"modes\"\nprocedure = \"frequency\"\nmode = 2\neigenvalues = 2\n";
    let deck = format!("{RECT}{MATERIAL}density = 7.85e-9\n{STEP}{frequency}[[step]]\nname = \"more\"\nboundary = [ {{ set = \"bottom\", uz = 0.0 }} ]\n");
    let run = run_deck(&deck, &[], 1, &[]);
    assert_rejected(&run, &["step 'more': a general step after the perturbation step 'modes'", "then the perturbation steps"]);
}

/// Material data in other units than slideline's (E = 200 for 200 GPa: the run ended in "did
/// not converge at load factor 0.2") get a note naming slideline's units before the run; a
/// yield stress above E / 20 likewise; the walk-through's steel gets none.
#[test]
fn material_data_in_other_units_are_named() {
    let fit = std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/shrink_fit.toml")).unwrap();
    let gpa = fit.replacen("youngs_modulus = 200000.0", "youngs_modulus = 200.0", 1);
    assert_ne!(gpa, fit);
    let dir = tempfile::tempdir().unwrap();
    for (deck, noted) in [(gpa, true), (fit.clone(), false)] {
        std::fs::write(dir.path().join("fit.toml"), deck).unwrap();
        let out = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "fit.toml", "-o", "fit.h5"]).output().unwrap();
        let text = String::from_utf8_lossy(&out.stdout);
        let note = "Young's modulus 200 MPa is below 1000 MPa, softer than any metal or polymer: slideline's units are N, mm, MPa";
        assert_eq!(text.contains(note), noted, "{text}{}", String::from_utf8_lossy(&out.stderr));
    }
    // a yield stress of 300 over E = 2000 (a yield strain of 15 %)
    let m = slideline::model::Material {
        name: "soft".into(),
        youngs_modulus: 2000.0,
        poissons_ratio: 0.3,
        thermal_expansion: 0.0,
        plasticity: Some(slideline::material::Hardening::linear(300.0, 0.0)),
        kinematic: slideline::material::KinematicHardening::NONE,
        density: 0.0,
        conductivity: 0.0,
    };
    let deck = slideline::model::deck::parse(&fit, std::path::Path::new("fit.toml")).unwrap();
    let model = slideline::model::Model { materials: vec![m], ..deck };
    let notes = model.implausible_units();
    assert!(notes.len() == 1 && notes[0].contains("yield stress 300 MPa is more than a twentieth of its Young's modulus 2000 MPa"), "{notes:?}");
}

/// A rerun with a bad eigensolver option (an unknown type, a tolerance <= 0, a shift that is
/// no number) is refused with exit 2 naming it before the results file it would replace is
/// touched (`-eps_type bogus` had replaced `out.h5` before refusing; `-eps_tol -1` and
/// `-st_shift nan` exited 1).
#[test]
fn a_bad_eigensolver_option_leaves_the_results_file_alone() {
    let deck = r#"[mesh.rectangle]
r = [99.0, 101.0]
z = [0.0, 6.0]
divisions = [2, 4]
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
density = 7.85e-9
[[step]]
name = "rest"
boundary = [ { set = "bottom", uz = 0.0 } ]
[[step]]
name = "ovals"
procedure = "frequency"
mode = 2
eigenvalues = 2
"#;
    let run = common::run_deck(deck, &[], 1, &[]);
    run.assert_ok();
    let before = std::fs::read(&run.h5).unwrap();
    for (option, needle) in [
        (&["-eps_type", "bogus"][..], "SLEPc options: Unknown EPS type given: bogus"),
        (&["-eps_tol", "-1"], "PETSc option -eps_tol \"-1\": give a number >= 0 and < 1"),
        (&["-eps_tol", "0"], "SLEPc options: Illegal value of tol"),
        (&["-st_shift", "nan"], "PETSc option -st_shift \"nan\": give a finite number"),
        (&["-st_type", "bogus"], "SLEPc options: Unable to find requested ST type bogus"),
    ] {
        let out =
            command_in(run.dir.path(), 1).arg("run").arg(run.dir.path().join("deck.toml")).arg("-o").arg(&run.h5).arg("--").args(option).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{option:?}: {stderr}");
        assert!(stderr.contains(needle), "{option:?}: {stderr}");
        assert!(std::fs::read(&run.h5).unwrap() == before, "{option:?} touched the results file");
    }
}

/// `slideline coefficients` refuses what the codes' charts do not cover and meshes it cannot
/// make, naming the flag and its range, before any analysis: `--c2 1e6` aborted on a 3.5 to
/// 45 GB allocation, `--through 0` ended in "the mesh has no elements", `--per-thickness 0` in
/// exit 1 with a temporary file's path, C1 too small for C2 in a convolution wider than Dm.
/// And C1 = 1 (the tori meet, no sidewall) is on the charts and computes (it ended in "node
/// 934 at (NaN, NaN)").
#[test]
fn chart_coefficients_outside_the_charts_or_of_no_mesh_are_refused_by_flag() {
    let dir = tempfile::tempdir().unwrap();
    for (args, needle) in [
        (&["--c1", "0.5", "--c2", "1e6"][..], "--c2 1000000: the codes' charts (EJMA Figs. 4.16 to 4.18; ASME VIII-1 Appendix 26) cover 0.2 <= C2 <= 4"),
        (&["--c1", "0.5", "--c2", "0.1"], "--c2 0.1: the codes' charts"),
        (&["--c1", "1.5", "--c2", "1"], "--c1 1.5: the codes' charts (EJMA Figs. 4.16 to 4.18; ASME VIII-1 Appendix 26) cover 0 < C1 <= 1"),
        (&["--c1", "nan", "--c2", "1"], "--c1 NaN: the codes' charts"),
        (&["--c1", "0.5", "--c2", "0.5", "--through", "0"], "--through 0: give 1 to 16 elements through the ply"),
        (&["--c1", "0.5", "--c2", "0.5", "--per-thickness", "0"], "--per-thickness 0: give 0.5 to 16 elements per ply thickness along the meridian"),
        (&["--c1", "0.05", "--c2", "4"], "C1 = 0.05, C2 = 4: the convolution's height w = 2780.0 tp leaves no bore inside Dm"),
        (&["--c1", "0.01", "--c2", "0.2", "--through", "16", "--per-thickness", "16"], "178928 elements, more than 50000"),
    ] {
        let out = command_in(dir.path(), 1).arg("coefficients").args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(needle) && stderr.lines().count() == 1, "{args:?}: {stderr}");
        assert!(!String::from_utf8_lossy(&out.stdout).contains("Cp"), "{args:?}: a table was begun before the refusal");
    }
    let out = command_in(dir.path(), 1).args(["coefficients", "--c1", "1", "--c2", "0.5"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let row: Vec<f64> = String::from_utf8_lossy(&out.stdout).lines().last().unwrap().split_whitespace().map(|v| v.parse().unwrap()).collect();
    assert!(row.len() == 6 && row[2..].iter().all(|c| c.is_finite() && *c > 0.1 && *c < 10.0), "{row:?}");
}

/// Kinematic hardening's terms: each refused with the material and the term named.
#[test]
fn bad_backstresses_are_named_with_their_material() {
    let j2 = "[[material]]\nname = \"cyclic\"\nmodel = \"j2\"\nyoungs_modulus = 200000.0\npoissons_ratio = 0.3\nyield_stress = 200.0\n";
    for (terms, needles) in [
        ("backstresses = [ { modulus = 20000.0, recall = -5.0 } ]\n", vec!["'cyclic'", "backstress 1", "recall"]),
        ("backstresses = [ { modulus = 1e4 }, { modulus = 0.0 } ]\n", vec!["'cyclic'", "backstress 2", "modulus"]),
        ("backstresses = [ { modulus = 1e4 }, { modulus = 1e4 }, { modulus = 1e4 }, { modulus = 1e4 } ]\n", vec!["'cyclic'", "at most 3"]),
        ("backstresses = [ { modulus = 1e4, gamma = 10.0 } ]\n", vec!["gamma"]),
    ] {
        let run = run_deck(&format!("{RECT}{j2}{terms}{STEP}"), &[], 1, &[]);
        assert_rejected(&run, &needles);
    }
    // backstresses move a yield surface: an elastic material has none
    let run = run_deck(&format!("{RECT}{MATERIAL}backstresses = [ {{ modulus = 1e4 }} ]\n{STEP}"), &[], 1, &[]);
    assert_rejected(&run, &["'steel'", "backstresses need model = \"j2\""]);
}

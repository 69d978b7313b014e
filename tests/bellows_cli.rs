//! `slideline bellows`: bad flags are refused before any solve (exit 2, the value named), and
//! `--mesh-only` writes a Gmsh mesh of the seed joint that `slideline run` reads back, and the
//! same mesh as the /mesh group of an HDF5 results file.

mod common;
use common::command_in;

fn bellows(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    command_in(dir, 1).arg("bellows").args(args).arg("-o").arg(dir.join("b.h5")).output().expect("run slideline")
}

#[test]
fn bad_flags_are_refused_before_any_solve() {
    let dir = tempfile::tempdir().unwrap();
    for (args, needle) in [
        (vec!["--ply-thickness", "-1"], "ply thickness"),
        (vec!["--plies", "0"], "plies"),
        (vec!["--convolutions", "0"], "convolutions must be at least 1"),
        // a thicker pack on the same tori's inside radii needs a wider pitch, and is told why
        (vec!["--plies", "3"], "a pitch of 24 is less than 4 x the torus radius = 26"),
        (vec!["--plies", "3"], "its inside radius plus half the ply pack: 5 + 1.5 mm at the root"),
        (vec!["--torus-radius", "0.9", "--pitch", "3.6"], "torus radius"),
        (vec!["--height", "8"], "height"),
        (vec!["--friction-plies", "-0.1"], "friction between the plies"),
        (vec!["--tangential-penalty", "0"], "tangential penalty"),
        (vec!["--elastic-slip", "-0.01"], "elastic slip"),
        // seen failing before: a memory allocation failure aborted the first two, the next two ran
        (vec!["--ply-elements", "100000"], "the mesh would have about"),
        (vec!["--ply-element-length", "1e-6"], "the mesh would have about"),
        (vec!["--elastic-slip", "0.01"], "no pair has friction"),
        (vec!["--elastic-slip", "0.01", "--tangential-penalty", "100", "--friction-plies", "0.2"], "cannot be used with"),
        (vec!["--coefficients", "0.68,0,1.63"], "coefficient Cf must be > 0"),
        (vec!["--coefficients", "0.68,1.65"], "coefficients"),
        // a joint that is not U-shaped is not assessed
        (vec!["--assess", "--torus-radius", "11", "--pitch", "44"], "less than two torus radii"),
    ] {
        let out = bellows(dir.path(), &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?} should name {needle:?}: {err}");
        assert!(!dir.path().join("b.h5").exists(), "no analysis may start");
    }
}

/// The code check in the closing table takes the chart coefficients as given (`--coefficients`),
/// labelled so, and gives the stroke's stresses far above yield no note: the codes' formulas and
/// fatigue curves are pseudo-elastic, written for them.
/// The figures with Cp 0.68, Cf 1.65, Cd 1.63 (the joint: Db 320 (the tubes' outside), w 20,
/// 2 plies of 1 mm, Dm 342, tp 0.9673, N 6, 0.6 MPa, E 200 GPa): S4 = 0.6 / 4 (20 / 0.9673)^2
/// 0.68 = 43.6 MPa, the rate 1.7 x 342 x 200 000 x 0.9673^3 x 2 / (8000 x 1.65) / 6 = 2657.6
/// N/mm; a 10 mm stroke gives S5 + S6 = 836 MPa, 2.8 times the yield stress.
#[test]
fn the_code_check_takes_given_coefficients() {
    let dir = tempfile::tempdir().unwrap();
    let out = bellows(dir.path(), &["--quick", "--displacement", "10", "--increments", "4", "--quiet", "--coefficients", "0.68,1.65,1.63"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}{}", String::from_utf8_lossy(&out.stderr));
    assert!(text.contains("Cp 0.680, Cf 1.650, Cd 1.630 as given"), "{text}");
    let s4: f64 = text.lines().find(|l| l.contains("S3 / S4")).and_then(|l| l.split_whitespace().last()).unwrap().parse().unwrap();
    assert!((s4 - 43.6).abs() < 0.1, "{text}");
    let rate: f64 = text.lines().find(|l| l.contains("axial rate, N/mm full ring")).and_then(|l| l.split_whitespace().last()).unwrap().parse().unwrap();
    assert!((rate - 2657.6).abs() < 0.1, "{text}");
    // the same check in the results file, each value with its units and source, and read back
    let h5 = dir.path().join("b.h5");
    let file = hdf5::File::open(&h5).unwrap();
    let s4 = file.dataset("assessment/S4").unwrap();
    let attr = |name: &str| s4.attr(name).unwrap().read_scalar::<hdf5::types::VarLenUnicode>().unwrap().to_string();
    assert_eq!((attr("units").as_str(), attr("source").as_str()), ("MPa", "code (as given)"));
    assert!((s4.read_scalar::<f64>().unwrap() - 43.6).abs() < 0.05);
    let post = command_in(dir.path(), 1).args(["post", h5.to_str().unwrap(), "--assessment"]).output().unwrap();
    let printed = String::from_utf8_lossy(&post.stdout);
    // the code check's block, up to the section after it (the finite-element joint's)
    let section = &text[text.find("  code check").unwrap()..];
    let section = &section[..section.find("\n\n").unwrap_or(section.len())];
    assert!(
        post.status.success() && section.lines().filter(|l| l.starts_with("  ")).all(|l| printed.contains(l)),
        "post --assessment:\n{printed}\nthe run:\n{section}"
    );
    // the tables alone, not the history before them (seen failing before: every progress line)
    assert!(printed.starts_with("\n  code check") && !printed.contains("lambda"), "post --assessment:\n{printed}");
    assert!(!text.contains("far beyond the elastic range") && !text.contains("note: the stroke"), "{text}");
}

#[test]
fn mesh_only_writes_the_seed_joint_as_gmsh() {
    let dir = tempfile::tempdir().unwrap();
    let out = bellows(dir.path(), &["--quick", "--mesh-only"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (mesh, sets) = slideline::model::gmsh::read(&dir.path().join("b.msh")).unwrap();
    mesh.validate().unwrap();
    let rmax = mesh.coords.iter().map(|c| c[0]).fold(0.0, f64::max);
    assert!((rmax - 182.0).abs() < 1e-9, "crest outside surface at r = 182: {rmax}");
    for name in ["fixed_end", "moving_end"] {
        assert!(!sets.node_sets[name].is_empty(), "{name}");
    }
    for name in ["wetted", "ply1_outer", "ply2_inner", "sleeve_outer", "tube_b_inner"] {
        assert!(!sets.surfaces[name].is_empty(), "{name}");
    }
    // the picture of the wetted faces, beside it
    assert!(std::fs::metadata(dir.path().join("b_wetted.png")).is_ok_and(|m| m.len() > 10_000), "no picture of the wetted faces");
    // and as HDF5: the /mesh group of a results file, same nodes, no increments
    let file = hdf5::File::open(dir.path().join("b.h5")).unwrap();
    let shape = file.dataset("mesh/coordinates").unwrap().shape();
    assert_eq!(shape, vec![mesh.coords.len(), 2]);
    assert_eq!(file.dataset("mesh/connectivity").unwrap().shape(), vec![mesh.elements.len(), 8]);
    assert!(file.group("mesh/node_sets").unwrap().member_names().unwrap().contains(&"moving_end".to_string()));
    assert!(file.group("increments").unwrap().member_names().unwrap().is_empty());
}

#[test]
fn a_parameter_file_sets_the_joint_and_flags_override_it() {
    let dir = tempfile::tempdir().unwrap();
    // the example file is the seed case
    let example = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/bellows.toml");
    let mut read = slideline::bellows::spec::DesignSpec::joint_file(&example).unwrap();
    let seed = slideline::bellows::spec::DesignSpec::seed();
    assert_ne!(read, seed, "the file gives the tubes' and sleeve's dimensions the seed derives from Db");
    read.joint = slideline::bellows::spec::JointSpec { tube_thickness: None, tube_length: None, sleeve_thickness: None, sleeve_overlap: None, ..read.joint };
    assert_eq!(read, seed);
    let write = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let typo = write("typo.toml", "[bellows]\nplies = 2\npliess = 3\n");
    let zero = write("zero.toml", "[bellows]\nplies = 0\nconvolutions = 5\npitch = 26.0\n");
    let crown = write("crown.toml", "[joint]\nsleeve_crown = 5.0\n");
    for (args, needle) in [
        (vec!["--params", typo.as_str()], "unknown field `pliess`"),
        (vec!["--params", zero.as_str()], "plies"),
        (vec!["--params", crown.as_str()], "sleeve crown must be >= 0 and below half the sleeve thickness (5 mm), got 5"),
    ] {
        let out = bellows(dir.path(), &args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
    // the file's 5 convolutions of pitch 26 with the command line's 3 plies (the tori's inside
    // radii kept: their mid-surface radii 6.5 mm, 4 x 6.5 = 26)
    let out = bellows(dir.path(), &["--params", zero.as_str(), "--plies", "3", "--quick", "--mesh-only"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let (mesh, sets) = slideline::model::gmsh::read(&dir.path().join("b.msh")).unwrap();
    assert!(sets.element_sets.contains_key("ply3") && !sets.element_sets.contains_key("ply4"));
    let zmax_ply = sets.element_sets["ply1"].iter().flat_map(|&e| mesh.elements[e]).map(|n| mesh.coords[n][1]).fold(0.0, f64::max);
    // tangent B ends 20 past the convolutions: 128 + 5 x 26 + 20 = 278
    assert!((zmax_ply - 278.0).abs() < 1e-9, "{zmax_ply}");
}

#[test]
fn flags_given_explicitly_win_over_quick_and_are_validated() {
    let dir = tempfile::tempdir().unwrap();
    let out = command_in(dir.path(), 1).current_dir(dir.path()).args(["bellows", "--quick", "--ply-elements", "3", "--export-inp", "q.inp"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let quick_3 = std::fs::read_to_string(dir.path().join("q.inp")).unwrap();
    let out = command_in(dir.path(), 1).current_dir(dir.path()).args(["bellows", "--quick", "--export-inp", "q1.inp"]).output().unwrap();
    assert!(out.status.success());
    let quick_1 = std::fs::read_to_string(dir.path().join("q1.inp")).unwrap();
    let elements = |deck: &str| deck.lines().skip_while(|l| !l.starts_with("*ELEMENT")).skip(1).take_while(|l| !l.starts_with('*')).count();
    // three elements through each ply instead of --quick's one: more elements
    assert!(elements(&quick_3) > elements(&quick_1), "{} vs {}", elements(&quick_3), elements(&quick_1));
    for (flag, value, needle) in
        [("--ply-elements", "0", "ply elements"), ("--ply-element-length", "0", "ply element length"), ("--temperature", "inf", "temperature")]
    {
        let out = bellows(dir.path(), &["--quick", flag, value]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flag} {value}: {err}");
        assert!(err.contains(needle), "{flag} {value}: {err}");
    }
}

#[test]
fn a_command_line_error_is_printed_once_under_mpirun() {
    let dir = tempfile::tempdir().unwrap();
    let out = command_in(dir.path(), 2).args(["bellows", "--no-such-flag"]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.matches("unexpected argument").count(), 1, "{err}");
    let out = command_in(dir.path(), 2).args(["bellows", "--plies", "0"]).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.matches("plies must be").count(), 1, "{err}");
}

/// On a terminal the run draws a progress bar (step, increment, load factor, elapsed, ETA);
/// through a pipe it prints the plain line per increment.
#[test]
fn a_terminal_gets_a_progress_bar_and_a_pipe_plain_lines() {
    let dir = tempfile::tempdir().unwrap();
    let exe = env!("CARGO_BIN_EXE_slideline");
    let args = "bellows --quick --displacement 10 --increments 4 -o b.h5";
    // `script` runs the command on a pseudo-terminal
    let out = std::process::Command::new("script")
        .args(["-qec", &format!("{exe} {args}"), "/dev/null"])
        .current_dir(dir.path())
        .env("OMPI_ALLOW_RUN_AS_ROOT", "1")
        .env("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
        .output()
        .expect("script (util-linux)");
    let tty = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && tty.contains("ETA") && tty.contains("step 2/2 compress #6"), "{tty}");
    let out = command_in(dir.path(), 1).current_dir(dir.path()).args(args.split(' ')).output().unwrap();
    let piped = String::from_utf8_lossy(&out.stdout);
    assert!(!piped.contains("ETA") && piped.lines().any(|l| l.starts_with("step 2/2 compress   #6")), "{piped}");
}

#[test]
fn a_load_cycle_with_friction_between_the_plies_closes_its_loop() {
    // the quick joint compressed 20 mm in 10 increments and brought back, mu = 0.2 between the
    // plies: a third step, the reaction back at zero compression, the loop's area reported, the
    // plies' frictional tractions in the results
    let dir = tempfile::tempdir().unwrap();
    let out = command_in(dir.path(), 2)
        .args(["bellows", "--quick", "--displacement", "20", "--increments", "10", "--friction-plies", "0.2", "--cycle", "-q", "-o"])
        .arg(dir.path().join("b.h5"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{text}\n{}", String::from_utf8_lossy(&out.stderr));
    let r = common::Results::open(&dir.path().join("b.h5"));
    let steps = r.history("step");
    assert_eq!(steps.last().copied(), Some(3.0), "a return step");
    let line = text.lines().find(|l| l.contains("cycle: loop area")).unwrap_or_else(|| panic!("no loop area in:\n{text}"));
    let area: f64 = line.split_whitespace().rev().nth(1).unwrap().parse().unwrap();
    assert!(area > 0.0, "the cycle dissipates: {line}");
    assert!(text.contains("friction mu, plies / sleeve"), "{text}");
    // the pictures: the stroke and the cycle's end, each at its own compression
    for caption in ["at 10.0 mm compression, half the stroke)", "at 20.0 mm compression, the stroke)", "at 0.0 mm compression, the cycle's end)"] {
        assert!(text.lines().any(|l| l.starts_with("picture: ") && l.ends_with(caption)), "no picture {caption:?} in:\n{text}");
    }
    let last = r.last_increment();
    let shear = r.f64s(&format!("{last}/contact/ply1_ply2/pass0/shear"));
    assert!(shear.iter().any(|s| s.abs() > 0.0), "frictional tractions between the plies");
}

/// Flags of the newer analyses are a bad-input surface too: negative numbers in exponent form
/// reach their flag (`--density -8e-9` was taken for an unknown argument `-8` with a tip that
/// would hand it to PETSc), and movements and chart coefficients far off any joint or chart
/// are refused with their range (`--lateral 1e9`, `--angular 1e6` and `--coefficients
/// 1e300,..` ran with absurd figures); a negative offset is a movement like any other.
#[test]
fn absurd_movements_and_coefficients_are_refused_with_their_range() {
    let dir = tempfile::tempdir().unwrap();
    for (args, needle) in [
        (&["--density", "-8e-9"][..], "bellows: density must be > 0, got -8e-9"),
        (&["--lateral", "1e9"], "--lateral 1e9: give a nonzero movement of at most 144 mm in size"),
        (&["--angular", "1e6"], "--angular 1e6: give a nonzero movement of at most 45 degrees in size"),
        (&["--coefficients", "1e300,1e300,1e300"], "bellows: coefficient Cp 1e300 is off the codes' charts: give 0.1 to 10"),
        (&["--coefficients", "0.6,1.7,0.01"], "bellows: coefficient Cd 0.01 is off the codes' charts"),
    ] {
        let out = bellows(dir.path(), &[&["--quick", "--mesh-only"][..], args].concat());
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(needle) && stderr.lines().count() == 1, "{args:?}: {stderr}");
    }
    let out = bellows(dir.path(), &["--quick", "--mesh-only", "--lateral", "-5"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
}

/// `slideline post FILE` prints a bellows run's closing table and code check again, line for
/// line as the run printed them (it printed neither).
#[test]
fn post_prints_the_closing_table_as_the_run_did() {
    let dir = tempfile::tempdir().unwrap();
    let out = bellows(dir.path(), &["--quick", "--displacement", "10", "--increments", "4", "--quiet"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let table = |text: &str| -> Vec<String> {
        text.lines()
            .skip_while(|l| !(l.contains("slideline") && l.trim_end().ends_with("paper")))
            .take_while(|l| !l.starts_with("picture:"))
            .filter(|l| !l.trim().is_empty())
            .map(str::to_string)
            .collect()
    };
    let printed = table(&String::from_utf8_lossy(&out.stdout));
    assert!(printed.len() > 25 && printed.iter().any(|l| l.contains("code check")), "{printed:#?}");
    let post = command_in(dir.path(), 1).arg("post").arg(dir.path().join("b.h5")).output().unwrap();
    assert!(post.status.success(), "{}", String::from_utf8_lossy(&post.stderr));
    assert_eq!(table(&String::from_utf8_lossy(&post.stdout)), printed);
}

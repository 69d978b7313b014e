//! `slideline check DECK`: the design-by-analysis checks of ASME VIII-2 Part 5 a deck's
//! `[design_by_analysis]` table names, against closed forms the code did not produce.
//! - Limit load (5.2.3): a thick-walled cylinder, a = 100, b = 200 mm, plane strain (a slice
//!   with both faces held: in the fully plastic state plastic incompressibility gives the axial
//!   stress the mean of the other two, as in a closed-end tube), elastic-perfectly plastic at
//!   1.5 S = 150 MPa: Hill's limit pressure p_L = (2 / sqrt 3) sigma_y ln(b / a) = 120.06 MPa
//!   (R. Hill, The Mathematical Theory of Plasticity, 1950, ch. V), so 2.401 times a design
//!   pressure of 50 MPa (PASS: 1.5 is carried) and 1.334 times 90 MPa (FAIL); the collapse
//!   load factor within 1 %. A thin tube (a = 100, b = 102 mm) likewise, (2 / sqrt 3) 300
//!   ln 1.02 = 6.861 MPa against 3 MPa: 2.287.
//! - Limit load of a thick sphere (a = 100, b = 200 mm) under internal pressure, von Mises at
//!   1.5 S = 150 MPa: in spherical symmetry von Mises is Tresca, p_L = 2 sigma_y ln(b / a) =
//!   207.94 MPa (Hill, ch. V), 2.44640 times 85 MPa. The search must accept only increments
//!   whose residual has fallen (the field test once accepted one after 12 iterations with a
//!   residual of 888 N/rad and reported 2.4469): within 1e-4, and the supports (the equator)
//!   carry the figure's load, pi a^2 p, to 1e-4.
//! - Limit load of a simply supported circular plate (a = 100, h = 2 mm, solid elements, small
//!   displacements) under uniform pressure, von Mises at 150 MPa: 6.51 M0 / a^2 with
//!   M0 = sigma_y h^2 / 4 (H. G. Hopkins & A. J. Wang, J. Mech. Phys. Solids 3 (1954);
//!   Tresca's 6 M0 / a^2 is Hopkins & Prager's, 1953): 0.09765 MPa, 2.441 times 0.04 MPa,
//!   within 3 %.
//! - Buckling (5.4.1.3(a), type 1): a long tube (R = 101 mm mean, t = 2 mm, plane strain) under
//!   external pressure, its oval mode n = 2 at Levy's p_cr = E t^3 / (4 (1 - nu^2) R^3) =
//!   0.4267 MPa for a follower pressure (S. Timoshenko & J. Gere, Theory of Elastic Stability,
//!   1961, ch. 7): 3.2005 times a design pressure of 0.1333 MPa within 1 %, PASS against
//!   2 / 0.8 = 2.5; at 0.2 MPa 2.13, FAIL.
//! - Ratcheting (5.5.7): the thin tube (examples/pressurised_tube.toml) at a hoop stress of
//!   half the yield stress, its axial
//!   strain cycled between +-2 yield strains (Miller's problem: reversed plasticity under a
//!   constant hoop stress ratchets the diameter with every cycle, by normality) fails: no
//!   criterion holds; cycled by +-0.1 of a yield strain it stays elastic and passes by (a).
//! - Bad tables exit 2 naming the key.

mod common;
use common::{assert_rejected, command_in, Results, Run};

fn check(deck: &str) -> Run {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("deck.toml");
    std::fs::write(&path, deck).unwrap();
    let h5 = dir.path().join("out.h5");
    let output = command_in(dir.path(), 1).current_dir(dir.path()).arg("check").arg(&path).arg("-o").arg(&h5).arg("--quiet").output().expect("slideline");
    Run { dir, output, h5 }
}

fn texts(file: &Results, name: &str) -> Vec<String> {
    file.file.dataset(name).unwrap().read_raw::<hdf5::types::VarLenUnicode>().unwrap().iter().map(|s| s.to_string()).collect()
}

fn thick_cylinder(pressure: f64) -> String {
    std::fs::read_to_string(common::data("dba/thick_cylinder.toml")).unwrap().replace("value = 50.0", &format!("value = {pressure}"))
}

/// Hill's limit pressure of a tube a -> b at yield stress sy.
fn hill(a: f64, b: f64, sy: f64) -> f64 {
    2.0 / 3f64.sqrt() * sy * (b / a).ln()
}

#[test]
fn the_limit_load_of_a_thick_cylinder_is_hills() {
    for (pressure, passes) in [(50.0, true), (90.0, false)] {
        let run = check(&thick_cylinder(pressure));
        run.assert_ok();
        let f = Results::open(&run.h5);
        let figure = f.f64s("dba/figure")[0];
        let expected = hill(100.0, 200.0, 150.0) / pressure;
        eprintln!("p {pressure}: collapse load factor {figure:.4}, Hill {expected:.4} ({:+.3} %)", 100.0 * (figure / expected - 1.0));
        assert!((figure / expected - 1.0).abs() < 0.01, "collapse factor {figure} against {expected}\n{}", run.stdout());
        assert_eq!(texts(&f, "dba/verdict")[0], if passes { "PASS" } else { "FAIL" }, "{}", run.stdout());
        let out = run.stdout();
        assert!(out.contains("plastic collapse, limit load") && out.contains(if passes { "verdict: PASS" } else { "verdict: FAIL" }), "{out}");
        // the analysis is kept beside the verdict, readable
        assert!(run.dir.path().join("out_limit_load.h5").exists());
    }
}

#[test]
fn the_limit_load_of_a_thick_sphere_is_reached_by_converged_increments_only() {
    let dir = tempfile::tempdir().expect("temp dir");
    for f in ["thick_sphere.toml", "thick_sphere.msh"] {
        std::fs::copy(common::data(&format!("dba/{f}")), dir.path().join(f)).unwrap();
    }
    let h5 = dir.path().join("out.h5");
    let output =
        command_in(dir.path(), 1).current_dir(dir.path()).arg("check").arg("thick_sphere.toml").arg("-o").arg(&h5).arg("--quiet").output().expect("slideline");
    let run = Run { dir, output, h5 };
    run.assert_ok();
    let figure = Results::open(&run.h5).f64s("dba/figure")[0];
    let (a, b, sy, p) = (100.0, 200.0, 150.0, 85.0);
    let expected = 2.0 * sy * f64::ln(b / a) / p;
    eprintln!("sphere: collapse load factor {figure:.5}, closed form {expected:.5} ({:+.4} %)", 100.0 * (figure / expected - 1.0));
    assert!((figure / expected - 1.0).abs() < 1e-4, "collapse factor {figure} against {expected}\n{}", run.stdout());
    // the load the supports carry at the last increment the search kept: the equator's axial
    // reaction per radian against the pressure's resultant, a^2 p / 2 per radian
    let analysis = Results::open(&run.dir.path().join("out_collapse_search.h5"));
    let reaction = *analysis.history("reaction_bottom_z").last().expect("a converged increment");
    let carried = -2.0 * reaction / (a * a * p);
    eprintln!("the supports carry {carried:.5} times the design pressure's resultant");
    assert!((carried / figure - 1.0).abs() < 1e-4, "the supports carry {carried}, the figure says {figure}");
    // a search out of time stops, says so, and keeps the verdict
    let deck = std::fs::read_to_string(run.dir.path().join("thick_sphere.toml")).unwrap();
    std::fs::write(run.dir.path().join("thick_sphere.toml"), deck.replace("search_to = 3.0 }", "search_to = 3.0, search_seconds = 0.001 }")).unwrap();
    let h5 = run.dir.path().join("late.h5");
    let out = command_in(run.dir.path(), 1).current_dir(run.dir.path()).arg("check").arg("thick_sphere.toml").arg("-o").arg(&h5).output().expect("slideline");
    let late = Run { dir: run.dir, output: out, h5 };
    late.assert_ok();
    assert!(late.stdout().contains("the search stopped at the figure (the search stopped at its budget of 0.001 s)"), "{}", late.stdout());
    assert_eq!(texts(&Results::open(&late.h5), "dba/verdict")[0], "PASS");
}

#[test]
fn the_limit_load_of_a_simply_supported_plate_is_hopkins_and_wangs() {
    let deck = std::fs::read_to_string(common::data("dba/circular_plate.toml")).unwrap();
    let run = check(&deck);
    run.assert_ok();
    let figure = Results::open(&run.h5).f64s("dba/figure")[0];
    let expected = 6.51 * 150.0 * 2.0f64.powi(2) / 4.0 / 100.0f64.powi(2) / 0.04;
    eprintln!("plate: collapse load factor {figure:.4}, Hopkins & Wang {expected:.4} ({:+.2} %)", 100.0 * (figure / expected - 1.0));
    assert!((figure / expected - 1.0).abs() < 0.03, "collapse factor {figure} against {expected}\n{}", run.stdout());
}

#[test]
fn the_buckling_check_finds_levys_ring_pressure() {
    let deck = std::fs::read_to_string(common::data("dba/ring_buckling.toml")).unwrap();
    let p_cr = 200_000.0 * 8.0 / (4.0 * 0.91 * 101f64.powi(3));
    for (pressure, passes) in [(0.1333, true), (0.2, false)] {
        let run = check(&deck.replace("value = 0.1333", &format!("value = {pressure}")));
        run.assert_ok();
        let f = Results::open(&run.h5);
        let (figure, limit) = (f.f64s("dba/figure")[0], f.f64s("dba/limit")[0]);
        eprintln!("ring at {pressure} MPa: load factor {figure:.4}, Levy {:.4}", p_cr / pressure);
        assert!((figure * pressure / p_cr - 1.0).abs() < 0.01, "{figure} x {pressure} MPa against {p_cr}\n{}", run.stdout());
        assert_eq!(limit, 2.5);
        assert_eq!(texts(&f, "dba/verdict")[0], if passes { "PASS" } else { "FAIL" }, "{}", run.stdout());
    }
    assert_rejected(&check(&deck.replace("beta_cr = 0.8", "beta_cr = 1.5")), &["buckling.beta_cr"]);
    let without = deck[..deck.find("[[step]]\nname = \"oval\"").unwrap()].to_string() + "[design_by_analysis]\nbuckling = { beta_cr = 0.8 }\n";
    assert_rejected(&check(&without), &["buckling", "no buckle step"]);
}

/// The example's thin tube (examples/pressurised_tube.toml: 2 mm high, its top moved +-0.006 mm)
/// with its axial strain cycled by +-`strain` instead.
fn thin_tube(strain: f64) -> String {
    let deck = std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pressurised_tube.toml")).unwrap();
    assert!(deck.contains("uz = 0.006 }") && deck.contains("uz = -0.006 }"), "the example's cycle");
    // without its comments, so that the bad tables below can drop or change a line
    let bare: String = deck.lines().map(|l| l.split('#').next().unwrap_or_default().trim_end().to_string() + "\n").collect();
    bare.replace("uz = 0.006 }", &format!("uz = {} }}", 2.0 * strain)).replace("uz = -0.006 }", &format!("uz = {} }}", -2.0 * strain))
}

#[test]
fn a_thin_tube_ratchets_under_reversed_axial_plasticity_and_not_below_it() {
    let yield_strain = 300.0 / 200_000.0;
    for (strain, ratchets) in [(2.0 * yield_strain, true), (0.1 * yield_strain, false)] {
        let run = check(&thin_tube(strain));
        run.assert_ok();
        let out = run.stdout();
        let f = Results::open(&run.h5);
        let checks = texts(&f, "dba/check");
        let verdicts = texts(&f, "dba/verdict");
        let figures = f.f64s("dba/figure");
        let limits = f.f64s("dba/limit");
        // the limit load first: the factored pressure carried, Hill's collapse pressure found
        assert_eq!((checks[0].as_str(), verdicts[0].as_str()), ("plastic collapse, limit load", "PASS"), "{out}");
        let expected = hill(100.0, 102.0, 300.0) / 3.0;
        assert!((figures[0] / expected - 1.0).abs() < 0.01, "collapse factor {} against {expected}\n{out}", figures[0]);
        // then (a), (b), (c) and the ratcheting verdict
        assert_eq!(checks[1..].iter().filter(|c| *c == "ratcheting").count(), 4, "{out}");
        let [a, b, c] = [1, 2, 3].map(|k| figures[k] <= limits[k]);
        eprintln!("axial strain +-{strain}: (a) {} (b) {} (c) {} mm\n{out}", figures[1], figures[2], figures[3]);
        assert_eq!(verdicts[4], if ratchets { "FAIL" } else { "PASS" }, "{out}");
        if ratchets {
            assert!(!a && !b && !c, "every criterion fails when it ratchets:\n{out}");
            assert!(out.contains("verdict: FAIL"), "{out}");
        } else {
            assert!(a && figures[1] == 0.0, "no plastic strain at all below yield:\n{out}");
        }
    }
}

#[test]
fn bad_design_by_analysis_tables_are_named() {
    let base = thin_tube(0.001);
    let cases: Vec<(String, Vec<&str>)> = vec![
        (base.replace("limit_load = {}", "limit_load = { factor = 0.0 }"), vec!["limit_load.factor", "> 0"]),
        (base.replace("limit_load = {}", "limit_load = { factor = 2.0, search_to = 1.5 }"), vec!["limit_load.search_to"]),
        (base.replace("allowable_stress = 200.0\n", ""), vec!["allowable_stress"]),
        (base.replace("allowable_stress = 200.0", "allowable_stress = { iron = 200.0 }"), vec!["allowable_stress", "'steel'"]),
        (base.replace("cycles = 3", "cycles = 2"), vec!["ratcheting.cycles", "at least 3"]),
        (base.replace(r#"cycle = ["pull", "push"]"#, r#"cycle = ["pressurise"]"#), vec!["ratcheting.cycle", "last general steps"]),
        (base.replace("limit_load = {}", "limt_load = {}"), vec!["[design_by_analysis]", "limt_load"]),
        (
            base.replace("model = \"j2\"", "model = \"elastic\"")
                .replace("yield_stress = 300.0\n", "")
                .replace("hardening_modulus = 1000.0\n", "")
                .replace("limit_load = {}\n", ""),
            vec!["ratcheting", "'steel'", "yield"],
        ),
        (base[..base.find("[design_by_analysis]").unwrap()].to_string(), vec!["no [design_by_analysis] table"]),
    ];
    for (deck, needles) in cases {
        let run = check(&deck);
        assert_rejected(&run, &needles);
    }
}

/// `bellows --spec FILE --dba`: the seed joint's code verdict, then the design-by-analysis table
/// (quick mesh, 8 increments a stroke, 2 ranks): the limit load under the design pressure alone
/// (the ends held; 1.5 S = 172.5 MPa from the specification's S = 115) carries the factored
/// 0.9 MPa and collapses within the search (to 20 x); ratcheting over three strokes of 70 mm at
/// 16 times the yield strain and more is plastic action in every cycle (criterion a fails); the
/// verdict and both analyses' files are written; the design report (written by the run, and
/// again by `post` from the verdict file alone, the same) has the code's verdict and the
/// checks' table with the printed figures; without --spec it is refused, naming it.
#[test]
fn the_bellows_design_by_analysis_runs_the_joint_of_its_specification() {
    // the seed joint's specification with a cyclic curve for the fatigue check (illustrative
    // Armstrong-Frederick terms, not a fit of AISI 304)
    let seed = std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/seed_joint.toml")).unwrap();
    let marker = "hardening_modulus = 1000.0";
    assert!(seed.contains(marker));
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("seed_cyclic.toml");
    std::fs::write(
        &spec,
        seed.replacen(
            marker,
            "backstresses = [ { modulus = 60000.0, recall = 400.0 }, { modulus = 10000.0, recall = 60.0 }, { modulus = 1500.0 } ]\nhardening_modulus = 1000.0",
            1,
        ),
    )
    .unwrap();
    let run = command_in(dir.path(), 2)
        .current_dir(dir.path())
        .args(["bellows", "--spec", spec.to_str().unwrap(), "--quick", "--increments", "8", "--dba", "--quiet", "-o", "j.h5", "--report", "j.html"])
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&run.stdout).to_string();
    assert!(run.status.success(), "{out}{}", String::from_utf8_lossy(&run.stderr));
    let (code, dba) =
        (out.find("\nverdict: FAIL: fatigue").expect("the code's verdict"), out.find("design by analysis (ASME VIII-2 Part 5)").expect("the table"));
    assert!(code < dba, "the code's verdict first:\n{out}");
    let f = Results::open(&dir.path().join("j.h5"));
    let (checks, verdicts, figures) = (texts(&f, "dba/check"), texts(&f, "dba/verdict"), f.f64s("dba/figure"));
    assert_eq!(checks.len(), 8, "{out}");
    assert_eq!(verdicts[0], "PASS", "{out}");
    assert!(figures[0] > 1.5 && figures[0] < 20.0, "a collapse within the search: {}\n{out}", figures[0]);
    assert!(figures[1] > 1e-3, "plastic action in the last cycle of a 70 mm stroke:\n{out}");
    assert!(dir.path().join("j_limit_load.h5").exists() && dir.path().join("j_ratcheting.h5").exists());
    // fatigue over three strokes against the specification's 1000 cycles: a plastic strain
    // range of percents, far fewer cycles allowed (the code's check fails too), and the damage
    // is n / N of the S_alt = E x range / 2 printed beside it
    assert_eq!(&checks[5..], ["fatigue, elastic-plastic"; 3], "{out}");
    assert!(figures[5] > 0.01, "a 70 mm stroke's effective strain range: {}\n{out}", figures[5]);
    assert!((figures[6] - 200_000.0 * figures[5] / 2.0).abs() < 1e-9 * figures[6], "{out}");
    assert_eq!(verdicts[7], "FAIL", "{out}");
    assert!(figures[7] > 1.0 && dir.path().join("j_fatigue.h5").exists(), "{out}");
    // the report: the code's checks, then the design-by-analysis table as printed
    let html = std::fs::read_to_string(dir.path().join("j.html")).unwrap();
    assert!(html.contains("id=\"checks\"") && html.contains("id=\"dba\""), "{html}");
    assert_eq!(html.matches("class=\"dba-check\"").count(), 8, "{html}");
    let collapse = format!("{:.4}", figures[0]);
    assert!(out.contains(&collapse) && html.contains(&format!("<td class=\"n\">{collapse}</td>")), "{collapse}:\n{html}");
    let overall = if verdicts.iter().any(|v| v == "FAIL") { "FAIL" } else { "PASS: every check" };
    assert!(html.contains(&format!("id=\"dba-verdict\">Design by analysis: {overall}<")), "{overall}:\n{html}");
    let nodes = Results::open(&dir.path().join("j_limit_load.h5")).f64s("mesh/coordinates").len() / 2;
    assert!(html.contains(&format!("id=\"mesh\">{nodes} nodes")), "the mesh of the checks' analyses, {nodes} nodes:\n{html}");
    let post = command_in(dir.path(), 1).current_dir(dir.path()).args(["post", "j.h5", "--report", "again.html"]).output().unwrap();
    let printed = String::from_utf8_lossy(&post.stdout);
    assert!(post.status.success() && printed.contains(&format!("verdict: {overall}")), "{printed}{}", String::from_utf8_lossy(&post.stderr));
    assert_eq!(std::fs::read_to_string(dir.path().join("again.html")).unwrap(), html, "post writes the run's report again");
    let field = command_in(dir.path(), 1).current_dir(dir.path()).args(["post", "j.h5", "--field", "stress"]).output().unwrap();
    let said = String::from_utf8_lossy(&field.stderr);
    assert!(field.status.code() == Some(2) && said.contains("j_limit_load.h5"), "{said}");
    let refused = command_in(dir.path(), 1).current_dir(dir.path()).args(["bellows", "--quick", "--dba"]).output().unwrap();
    assert_eq!(refused.status.code(), Some(2), "{}", String::from_utf8_lossy(&refused.stderr));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("--spec"), "{}", String::from_utf8_lossy(&refused.stderr));
}

/// The limit-load and ratcheting checks are elastic-perfectly plastic whatever hardening the
/// deck's material has: the ratcheting tube with three backstresses added gets the very
/// figures it gets without them. Seen failing before: the ratcheting run kept the backstresses.
#[test]
fn the_elastic_perfectly_plastic_checks_drop_kinematic_hardening() {
    let plain = thin_tube(2.0 * 300.0 / 200_000.0);
    let marker = "yield_stress = 300.0\n";
    assert!(plain.contains(marker));
    let kinematic = plain.replace(marker, &format!("{marker}backstresses = [ {{ modulus = 50000.0, recall = 200.0 }}, {{ modulus = 5000.0 }} ]\n"));
    let figures = |deck: &str| {
        let run = check(deck);
        run.assert_ok();
        Results::open(&run.h5).f64s("dba/figure")
    };
    let (a, b) = (figures(&plain), figures(&kinematic));
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!(x.to_bits() == y.to_bits() || (x.is_nan() && y.is_nan()), "{a:?} against {b:?}");
    }
}

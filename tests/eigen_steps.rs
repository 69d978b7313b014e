//! Eigenvalue perturbation steps (`procedure = "frequency"` and `"buckle"`), through the whole
//! program, against closed forms:
//! - a free thin ring, mean radius R = 100 mm, 2 mm radial by 6 mm axial, steel (E 200 GPa,
//!   nu 0.3, rho 7.85e-9 t/mm^3): its in-plane flexural mode n = 2, omega^2 = E t^2 n^2 (n^2 -
//!   1)^2 / (12 rho R^4 (n^2 + 1)) = 124.45 Hz, and its breathing mode n = 0, omega^2 = E /
//!   (rho R^2) = 8033.4 Hz (Blevins, Formulas for Natural Frequency and Mode Shape, table 9-1,
//!   thin ring); within 0.5 % (measured -0.012 %, -0.002 %); 1 and 2 ranks agree to 1e-8;
//! - a cantilevered tube r 95..100, 4000 mm long: its first bending mode (n = 1) against
//!   Euler-Bernoulli's 1.8751^2 sqrt(E I / (rho A L^4)) within 1.5 % (the slender beam's
//!   shear and rotary inertia take off about (1.875 r_g / L)^2 (1 + E / (k G)) = 0.6 %), and
//!   its effective mass 0.6131 of the tube's (the same beam's) within 2 %;
//! - the same tube under an axial end load (a dead pressure on its end, small strain): the
//!   buckle step's load factor times the step's load is Euler's cantilever load pi^2 E I /
//!   (4 L^2) with Engesser's shear correction P / (1 + P / (k G A)) (Timoshenko & Gere 2.17):
//!   within 1 % from the unloaded tube, and from a base state already at half that load the
//!   factor is the remaining half (critical = base + factor x step), within 1 %;
//! - a pipe r 95..100, 8000 mm long, both ends clamped, under internal pressure (nlgeom: the
//!   pressure follows the wall): it bows sideways when the effective axial force p A_i (1 - 2
//!   nu) (the pressure's thrust less the wall's Poisson tension; Palmer & Baldry 1974, Lateral
//!   buckling of axially constrained pipelines) reaches the clamped column's 4 pi^2 E I / L^2,
//!   with Engesser's shear correction: within 1 % (measured +0.4 %; with nlgeom = false, no
//!   follower stiffness, the two factors nearest zero are -39.6 and -80.5: the wall's own
//!   stresses alone, no squirm);
//! - the tube r 95..100, 4000 mm long, both ends clamped (its top a ring held at rest, free to
//!   move along the axis under the load): 4 pi^2 E I / L^2 with Engesser's shear correction,
//!   within 1 %; 1 and 2 ranks agree to 1e-8;
//! - a thin cylinder R 100, t 1, 100 mm long, its ends held radially, under axial compression:
//!   the classical critical stress E t / (R sqrt(3 (1 - nu^2))) = 1210.4 MPa (Timoshenko &
//!   Gere, Theory of Elastic Stability, 11.4) within 5 % at the critical n among 0, 4, 8, 12
//!   (measured: n = 0 +0.4 %, n = 8 about -1.5 %; the ends' radial hold bends the wall in the
//!   prebuckling state, which takes a little off the higher n, Almroth 1966);
//! - the same tube clamped at its base, free at its top, twist held: its axial modes (2k - 1) c
//!   / (4 L), c = sqrt(E / rho), within 0.5 % for k = 1, 2, 3 (Love's lateral inertia takes
//!   off (nu k_k r)^2 / 2 <= 0.2 %);
//! - the same tube pinned at both ends (ur and ut held, free to turn) under an axial end load
//!   P = +-0.5 of its Euler load P_E = pi^2 E I / L^2 (with Engesser's correction): its first
//!   bending frequency changes by sqrt(1 + P / P_E) (a pinned beam-column, Blevins, Formulas
//!   for Natural Frequency and Mode Shape, 8.2), within 2 %.

mod common;
use common::{run_deck, Results};
use std::f64::consts::PI;

const E: f64 = 200_000.0;
const NU: f64 = 0.3;
const RHO: f64 = 7.85e-9;

/// Every deck's material: steel with its density.
fn steel() -> String {
    format!("[[material]]\nname = \"steel\"\nyoungs_modulus = {E}\npoissons_ratio = {NU}\ndensity = {RHO}")
}

fn f64s(r: &Results, path: &str) -> Vec<f64> {
    r.f64s(path)
}

#[test]
fn a_free_ring_rings_as_the_thin_ring_theory_says_on_one_and_two_ranks() {
    let deck = format!(
        r#"
[mesh.rectangle]
r = [99.0, 101.0]
z = [0.0, 6.0]
divisions = [2, 4]
{steel}
[[step]]
name = "rest"
boundary = [ {{ set = "bottom", uz = 0.0 }} ]
[[step]]
name = "ovals"
procedure = "frequency"
mode = 2
eigenvalues = 2
[[step]]
name = "breathing"
procedure = "frequency"
mode = 0
boundary = [ {{ set = "bottom", uz = 0.0, ut = 0.0 }} ]
"#,
        steel = steel()
    );
    let (r, t, n) = (100.0f64, 2.0f64, 2.0f64);
    let oval = (E * t * t * n * n * (n * n - 1.0).powi(2) / (12.0 * RHO * r.powi(4) * (n * n + 1.0))).sqrt() / (2.0 * PI);
    let breathing = (E / RHO).sqrt() / r / (2.0 * PI);
    let one = run_deck(&deck, &[], 1, &[]);
    one.assert_ok();
    let r1 = Results::open(&one.h5);
    let (f_oval, f_breathing) = (f64s(&r1, "perturbations/ovals/frequencies")[0], f64s(&r1, "perturbations/breathing/frequencies")[0]);
    eprintln!("ring: n = 2 {f_oval:.3} Hz against {oval:.3}; breathing {f_breathing:.2} Hz against {breathing:.2}");
    assert!((f_oval / oval - 1.0).abs() < 5e-3, "{f_oval} against {oval}");
    assert!((f_breathing / breathing - 1.0).abs() < 5e-3, "{f_breathing} against {breathing}");
    assert!(one.stdout().contains("perturbation step 'ovals': natural frequencies"), "{}", one.stdout());
    // the first mode's field, for ParaView, and `slideline post`
    assert_eq!(f64s(&r1, "perturbations/ovals/mode_1").len(), f64s(&r1, "perturbations/ovals/amplitudes").len());
    // the modes in the step's sidecar, as meshio (and ParaView) read it
    let sidecar = one.h5.with_file_name(format!("{}_ovals.xmf", one.h5.file_stem().unwrap().to_string_lossy()));
    let read = common::python().arg("-c").arg("import meshio, sys; print(sorted(meshio.read(sys.argv[1]).point_data))").arg(&sidecar).output().unwrap();
    let text = String::from_utf8_lossy(&read.stdout);
    assert!(text.contains("'mode_1', 'mode_2'"), "{text}{}", String::from_utf8_lossy(&read.stderr));
    let post = common::command_in(one.dir.path(), 1).args(["post", one.h5.to_str().unwrap()]).output().unwrap();
    let printed = String::from_utf8_lossy(&post.stdout);
    assert!(printed.contains(&format!("mode  1: {f_oval:.6e} Hz")), "{printed}");

    let two = run_deck(&deck, &[], 2, &[]);
    two.assert_ok();
    let r2 = Results::open(&two.h5);
    for step in ["ovals", "breathing"] {
        let (a, b) = (f64s(&r1, &format!("perturbations/{step}/frequencies")), f64s(&r2, &format!("perturbations/{step}/frequencies")));
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-8 * x, "{step}: {x} on one rank, {y} on two");
        }
    }
}

/// The tube r 95..100, `length` long, clamped at its base, with `steps` after a base step
/// carrying `base`.
fn tube(length: f64, base: &str, steps: &str) -> String {
    format!(
        r#"
nlgeom = false
[mesh.rectangle]
r = [95.0, 100.0]
z = [0.0, {length}]
divisions = [2, 120]
{steel}
[[step]]
name = "base"
boundary = [ {{ set = "bottom", ur = 0.0, uz = 0.0 }} ]
{base}
{steps}
"#,
        steel = steel()
    )
}

const HELD: &str = r#"boundary = [ { set = "bottom", ur = 0.0, uz = 0.0, ut = 0.0 } ]"#;

fn section() -> (f64, f64, f64) {
    let area = PI * (100f64.powi(2) - 95f64.powi(2));
    let inertia = PI / 4.0 * (100f64.powi(4) - 95f64.powi(4));
    // Cowper's shear coefficient of a thin-walled tube, m = 0.95
    let m2: f64 = 0.95 * 0.95;
    let kappa = 6.0 * (1.0 + NU) * (1.0 + m2).powi(2) / ((7.0 + 6.0 * NU) * (1.0 + m2).powi(2) + (20.0 + 12.0 * NU) * m2);
    (area, inertia, kappa * E / (2.0 * (1.0 + NU)) * area)
}

#[test]
fn a_cantilevered_tube_vibrates_as_a_beam() {
    let length = 4000.0;
    let steps = format!("[[step]]\nname = \"sway\"\nprocedure = \"frequency\"\nmode = 1\n{HELD}\n");
    let run = run_deck(&tube(length, "", &steps), &[], 1, &[]);
    run.assert_ok();
    let r = Results::open(&run.h5);
    let (area, inertia, _) = section();
    let beam = 1.8751f64.powi(2) * (E * inertia / (RHO * area * length.powi(4))).sqrt() / (2.0 * PI);
    let f = f64s(&r, "perturbations/sway/frequencies")[0];
    let mass = f64s(&r, "perturbations/sway/effective_mass_ring")[0];
    let total = RHO * area * length;
    eprintln!(
        "cantilever: {f:.4} Hz against Euler-Bernoulli's {beam:.4} ({:+.3} %); effective mass {:.4} of the tube's",
        100.0 * (f / beam - 1.0),
        mass / total
    );
    assert!(f < beam && (f / beam - 1.0).abs() < 0.015, "{f} against {beam}");
    assert!((mass / total / 0.6131 - 1.0).abs() < 0.02, "effective mass {mass} of {total}");
}

#[test]
fn a_compressed_tube_buckles_at_eulers_load_with_engesser_s_shear() {
    let length = 2000.0;
    let (area, inertia, shear) = section();
    let euler = PI * PI * E * inertia / (4.0 * length * length);
    let critical = euler / (1.0 + euler / shear);
    // the step's load: 1 MPa on the end
    let steps = format!(
        "[[step]]\nname = \"squash\"\nprocedure = \"buckle\"\nmode = 1\neigenvalues = 2\npressure = [ {{ surface = \"top\", value = 1.0 }} ]\n{HELD}\n"
    );
    let run = run_deck(&tube(length, "", &steps), &[], 1, &[]);
    run.assert_ok();
    let factor = f64s(&Results::open(&run.h5), "perturbations/squash/eigenvalues")[0];
    eprintln!("buckling: {:.1} N against {critical:.1} N ({:+.3} %)", factor * area, 100.0 * (factor * area / critical - 1.0));
    assert!((factor * area / critical - 1.0).abs() < 0.01, "{} against {critical}", factor * area);
    assert!(run.stdout().contains("buckling load factors"), "{}", run.stdout());
    // from a base already at half the critical load, the factor is the other half
    let half = format!("pressure = [ {{ surface = \"top\", value = {} }} ]", critical / 2.0 / area);
    let run = run_deck(&tube(length, &half, &steps), &[], 1, &[]);
    run.assert_ok();
    let r = Results::open(&run.h5);
    let rest = f64s(&r, "perturbations/squash/eigenvalues")[0];
    // the critical pressure the file and the run give: the base's plus the factor times 1 MPa
    let on_top = f64s(&r, "perturbations/squash/critical_pressure_top")[0];
    assert!((on_top - (critical / 2.0 / area + rest)).abs() < 1e-12 * on_top, "{on_top}");
    assert!(run.stdout().contains(&format!("critical pressure on 'top' {on_top:.6e} MPa")), "{}", run.stdout());
    eprintln!("from half the load: {:.1} N more against {:.1}", rest * area, critical / 2.0);
    assert!((rest * area / (critical / 2.0) - 1.0).abs() < 0.01, "{} against {}", rest * area, critical / 2.0);
}

#[test]
fn a_pipe_with_its_ends_held_bows_under_internal_pressure_at_the_effective_axial_force() {
    let length = 8000.0;
    let deck = format!(
        r#"
[mesh.rectangle]
r = [95.0, 100.0]
z = [0.0, {length}]
divisions = [2, 200]
{steel}
[[step]]
name = "base"
boundary = [ {{ set = "bottom", ur = 0.0, uz = 0.0 }}, {{ set = "top", ur = 0.0, uz = 0.0 }} ]
[[step]]
name = "squirm"
procedure = "buckle"
mode = 1
pressure = [ {{ surface = "inner", value = 1.0 }} ]
boundary = [ {{ set = "bottom", ur = 0.0, uz = 0.0, ut = 0.0 }}, {{ set = "top", ur = 0.0, uz = 0.0, ut = 0.0 }} ]
"#,
        steel = steel()
    );
    let (_, inertia, shear) = section();
    let euler = 4.0 * PI * PI * E * inertia / (length * length);
    let column = euler / (1.0 + euler / shear);
    let expected = column / (PI * 95.0 * 95.0 * (1.0 - 2.0 * NU));
    let run = run_deck(&deck, &[], 1, &[]);
    run.assert_ok();
    let p = f64s(&Results::open(&run.h5), "perturbations/squirm/critical_pressure_inner")[0];
    eprintln!("pipe squirm: {p:.2} MPa against {expected:.2} ({:+.3} %)", 100.0 * (p / expected - 1.0));
    assert!((p / expected - 1.0).abs() < 0.01, "{p} against {expected}");
}

#[test]
fn a_column_clamped_at_both_ends_buckles_at_four_times_the_pinned_load() {
    let length = 4000.0;
    let (area, inertia, shear) = section();
    let euler = 4.0 * PI * PI * E * inertia / (length * length);
    let critical = euler / (1.0 + euler / shear);
    // the top: a ring held at rest (no lateral motion, no rotation), free along the axis
    let steps = "[[step]]\nname = \"squash\"\nprocedure = \"buckle\"\nmode = 1\npressure = [ { surface = \"top\", value = 1.0 } ]\n\
                 boundary = [ { set = \"bottom\", ur = 0.0, uz = 0.0, ut = 0.0 }, { set = \"top\", lateral = 0.0, rotation = 0.0 } ]\n";
    let deck = tube(length, "", steps);
    let one = run_deck(&deck, &[], 1, &[]);
    one.assert_ok();
    let factor = f64s(&Results::open(&one.h5), "perturbations/squash/eigenvalues")[0];
    eprintln!("clamped column: {:.1} N against {critical:.1} N ({:+.3} %)", factor * area, 100.0 * (factor * area / critical - 1.0));
    assert!((factor * area / critical - 1.0).abs() < 0.01, "{} against {critical}", factor * area);
    let two = run_deck(&deck, &[], 2, &[]);
    two.assert_ok();
    let on_two = f64s(&Results::open(&two.h5), "perturbations/squash/eigenvalues")[0];
    assert!((on_two - factor).abs() < 1e-8 * factor, "{factor} on one rank, {on_two} on two");
}

#[test]
fn a_thin_cylinder_under_axial_compression_buckles_at_the_classical_stress() {
    let (radius, t) = (100.0f64, 1.0f64);
    let classical = E * t / (radius * (3.0 * (1.0 - NU * NU)).sqrt());
    let modes = [0u32, 4, 8, 12];
    let steps: String = modes
        .iter()
        .map(|n| {
            format!(
                "[[step]]\nname = \"n{n}\"\nprocedure = \"buckle\"\nmode = {n}\npressure = [ {{ surface = \"top\", value = 1.0 }} ]\n\
                 boundary = [ {{ set = \"bottom\", ur = 0.0, uz = 0.0, ut = 0.0 }}, {{ set = \"top\", ur = 0.0, ut = 0.0 }} ]\n"
            )
        })
        .collect();
    let deck = format!(
        "nlgeom = false\n[mesh.rectangle]\nr = [{}, {}]\nz = [0.0, 100.0]\ndivisions = [2, 100]\n{}\n[[step]]\nname = \"base\"\nboundary = [ {{ set = \"bottom\", uz = 0.0 }} ]\n{steps}",
        radius - t / 2.0,
        radius + t / 2.0,
        steel()
    );
    let run = run_deck(&deck, &[], 1, &[]);
    run.assert_ok();
    let r = Results::open(&run.h5);
    // the step's load is 1 MPa on the end: the load factor is the critical stress
    let stresses: Vec<f64> = modes.iter().map(|n| f64s(&r, &format!("perturbations/n{n}/eigenvalues"))[0]).collect();
    for (n, s) in modes.iter().zip(&stresses) {
        eprintln!("cylinder, n = {n}: {s:.1} MPa against {classical:.1} ({:+.2} %)", 100.0 * (s / classical - 1.0));
    }
    let lowest = stresses.iter().copied().fold(f64::INFINITY, f64::min);
    assert!((lowest / classical - 1.0).abs() < 0.05, "{lowest} against {classical}");
    // the axisymmetric mode is on the classical value itself, and high n climbs off it
    assert!((stresses[0] / classical - 1.0).abs() < 0.01, "n = 0: {} against {classical}", stresses[0]);
    assert!(stresses[3] > 1.05 * classical, "n = 12: {}", stresses[3]);
}

#[test]
fn a_clamped_free_rod_rings_axially_at_odd_quarter_waves() {
    let length = 4000.0;
    let steps = "[[step]]\nname = \"axial\"\nprocedure = \"frequency\"\nmode = 0\neigenvalues = 3\n\
                 boundary = [ { set = \"bottom\", ur = 0.0, uz = 0.0, ut = 0.0 }, { set = \"all\", ut = 0.0 } ]\n";
    let run = run_deck(&tube(length, "", steps), &[], 1, &[]);
    run.assert_ok();
    let f = f64s(&Results::open(&run.h5), "perturbations/axial/frequencies");
    let c = (E / RHO).sqrt();
    for (k, f) in f.iter().enumerate() {
        let rod = (2.0 * k as f64 + 1.0) * c / (4.0 * length);
        eprintln!("rod, axial mode {}: {f:.3} Hz against {rod:.3} ({:+.3} %)", k + 1, 100.0 * (f / rod - 1.0));
        assert!((f / rod - 1.0).abs() < 5e-3, "mode {}: {f} against {rod}", k + 1);
    }
}

#[test]
fn tension_raises_and_compression_lowers_the_bending_frequency_as_a_beam_column_s() {
    let length = 4000.0;
    let (area, inertia, shear) = section();
    let euler = PI * PI * E * inertia / (length * length);
    let buckling = euler / (1.0 + euler / shear);
    let pinned = "[[step]]\nname = \"sway\"\nprocedure = \"frequency\"\nmode = 1\n\
                  boundary = [ { set = \"bottom\", ur = 0.0, ut = 0.0 }, { set = \"top\", ur = 0.0, ut = 0.0 } ]\n";
    // the base step: the bottom held along the axis only (free to swell), the end load on top
    let frequency = |load: f64| {
        let deck = tube(length, &format!("pressure = [ {{ surface = \"top\", value = {} }} ]", -load / area), pinned)
            .replace("{ set = \"bottom\", ur = 0.0, uz = 0.0 }", "{ set = \"bottom\", uz = 0.0 }");
        let run = run_deck(&deck, &[], 1, &[]);
        run.assert_ok();
        f64s(&Results::open(&run.h5), "perturbations/sway/frequencies")[0]
    };
    let free = frequency(0.0);
    for share in [0.5, -0.5] {
        let f = frequency(share * buckling);
        let beam = (1.0 + share).sqrt();
        eprintln!("beam-column, P = {share:+} P_E: f / f0 = {:.4} against {beam:.4} ({:+.3} %)", f / free, 100.0 * (f / free / beam - 1.0));
        assert!((f / free / beam - 1.0).abs() < 0.02, "P = {share} P_E: {} against {beam}", f / free);
    }
}

/// Eigenvalue steps that cannot answer say so: a buckle step on a tube that nothing holds
/// laterally in its mode (n = 1) is refused naming the free rigid motions (it printed a
/// critical pressure of noise); a buckle step whose load is zero is refused (it printed "load
/// factor inf" and "critical pressure NaN" with exit 0); a frequency step on a body free along
/// the axis runs and names its rigid motions in a note; held, the same buckle step answers.
#[test]
fn eigenvalue_steps_with_free_rigid_motions_or_no_load_say_so() {
    let deck = |steps: &str| {
        format!(
            "[mesh.rectangle]\nr = [95.0, 100.0]\nz = [0.0, 400.0]\ndivisions = [1, 20]\n{steel}\n[[step]]\nname = \"rest\"\nboundary = [ {{ set = \"bottom\", uz = 0.0 }} ]\n{steps}",
            steel = steel()
        )
    };
    let buckle = |name: &str, boundary: &str, value: f64| {
        format!("[[step]]\nname = \"{name}\"\nprocedure = \"buckle\"\nmode = 1\n{boundary}pressure = [ {{ surface = \"top\", value = {value} }} ]\n")
    };
    let held = "boundary = [ { set = \"bottom\", ur = 0.0, uz = 0.0, ut = 0.0 } ]\n";
    let free = run_deck(&deck(&buckle("free", "", 1.0)), &[], 1, &[]);
    assert_eq!(free.code(), 2, "{}", free.stderr());
    assert!(
        free.stderr().contains("buckle step 'free' (mode 1): nothing holds the model across the axis (the lateral offset) nor the tilt about a diameter"),
        "{}",
        free.stderr()
    );
    let unloaded = run_deck(&deck(&buckle("unloaded", held, 0.0)), &[], 1, &[]);
    assert_eq!(unloaded.code(), 2, "{}", unloaded.stderr());
    assert!(unloaded.stderr().contains("perturbation step 'unloaded': no load"), "{}", unloaded.stderr());
    let ring = "[[step]]\nname = \"ring\"\nprocedure = \"frequency\"\nmode = 0\n";
    let ok = run_deck(&deck(&format!("{}{ring}", buckle("held", held, 1.0))), &[], 1, &[]);
    ok.assert_ok();
    assert!(ok.stdout().contains("step 'ring' (mode 0): nothing holds the model along the axis (uz) nor the twist about the axis (ut)"), "{}", ok.stdout());
    assert!(!ok.stdout().contains("step 'held' (mode 1): nothing holds"), "{}", ok.stdout());
    let r = Results::open(&ok.h5);
    let factor = f64s(&r, "perturbations/held/eigenvalues")[0];
    assert!(factor.is_finite() && factor > 0.0, "{factor}");
}

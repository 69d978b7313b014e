//! Body loads (`body_load = [{ elements, gravity | spin }]` in a step) through the whole program,
//! against closed forms:
//! - thin discs spinning about their axis, plane stress (Timoshenko & Goodier, Theory of
//!   Elasticity, 3rd ed., section 32): with C = (3 + nu) rho omega^2 / 8,
//!   sigma_r = C (a^2 + b^2 - a^2 b^2 / r^2 - r^2), sigma_t = C (a^2 + b^2 + a^2 b^2 / r^2 -
//!   (1 + 3 nu) / (3 + nu) r^2), u_r = r (sigma_t - nu sigma_r) / E (a = 0: the solid disc);
//!   a disc of b = 100, 2 mm thick (its half, z 0..1, on its mid-plane's symmetry), steel at
//!   omega = 3000 rad/s: u_r at every mid-plane node and the bore's hoop stress within 0.5 %
//!   (solid and annular a = 20); the same disc at nlgeom spins to the same u_r within 0.5 %
//!   (the spin softening then adds rho omega^2 / E ~ 3.5e-7 of stiffness loss: nothing here);
//! - a tube r 95..100, 1000 mm long, hanging from its top under gravity g = -9810 mm/s^2: the
//!   top's reaction is its weight rho g A L (1e-9) and its bottom sinks rho g L^2 / (2 E)
//!   (0.5 %).

mod common;
use common::{run_deck, Results};

const E: f64 = 200_000.0;
const NU: f64 = 0.3;
const RHO: f64 = 7.85e-9;
const OMEGA: f64 = 3000.0;

/// Every deck's material: steel with its density.
fn steel() -> String {
    format!("[[material]]\nname = \"steel\"\nyoungs_modulus = {E}\npoissons_ratio = {NU}\ndensity = {RHO}")
}

fn disc(inner: f64, nlgeom: bool) -> String {
    format!(
        r#"
nlgeom = {nlgeom}
[mesh.rectangle]
r = [{inner}, 100.0]
z = [0.0, 1.0]
divisions = [50, 1]
{steel}
[[step]]
name = "spin"
boundary = [ {{ set = "bottom", uz = 0.0 }} ]
body_load = [ {{ elements = "all", spin = {OMEGA} }} ]
"#,
        steel = steel()
    )
}

/// Timoshenko's plane-stress disc: (u_r, sigma_t) at radius r.
fn spinning(a: f64, r: f64) -> (f64, f64) {
    let b: f64 = 100.0;
    let c = (3.0 + NU) * RHO * OMEGA * OMEGA / 8.0;
    let hole = if a > 0.0 { a * a * b * b / (r * r) } else { 0.0 };
    let sr = c * (a * a + b * b - hole - r * r);
    let st = c * (a * a + b * b + hole - (1.0 + 3.0 * NU) / (3.0 + NU) * r * r);
    (r * (st - NU * sr) / E, st)
}

#[test]
fn spinning_discs_stretch_as_timoshenko_s_plane_stress_disc() {
    for (inner, nlgeom) in [(0.0, false), (20.0, false), (20.0, true)] {
        let run = run_deck(&disc(inner, nlgeom), &[], 1, &[]);
        run.assert_ok();
        let r = Results::open(&run.h5);
        let mut worst: f64 = 0.0;
        for (x, u) in r.nodes().iter().filter(|(x, _)| x[1] == 0.0 && x[0] > 0.0) {
            let (exact, _) = spinning(inner, x[0]);
            worst = worst.max((u[0] / exact - 1.0).abs());
        }
        let at_bore = if inner > 0.0 { r.stress_at_inner_edge(&r.last_increment(), inner, 2) } else { f64::NAN };
        eprintln!("disc a = {inner}, nlgeom {nlgeom}: u_r within {:.2e}; bore hoop stress {at_bore:.3} against {:.3}", worst, spinning(inner, inner).1);
        assert!(worst < 5e-3, "a = {inner}: u_r off by {worst}");
        if inner > 0.0 {
            let exact = spinning(inner, inner).1;
            assert!((at_bore / exact - 1.0).abs() < 5e-3, "bore hoop stress {at_bore} against {exact}");
        }
    }
}

#[test]
fn a_hanging_tube_carries_its_weight() {
    let (g, length) = (-9810.0, 1000.0);
    let deck = format!(
        r#"
nlgeom = false
[mesh.rectangle]
r = [95.0, 100.0]
z = [0.0, {length}]
divisions = [2, 40]
{steel}
[[step]]
name = "hang"
boundary = [ {{ set = "top", uz = 0.0 }} ]
body_load = [ {{ elements = "all", gravity = {g} }} ]
"#,
        steel = steel()
    );
    let run = run_deck(&deck, &[], 1, &[]);
    run.assert_ok();
    let r = Results::open(&run.h5);
    let weight = RHO * g * length * (100.0f64.powi(2) - 95.0f64.powi(2)) / 2.0;
    let reaction = *r.history("reaction_top_z").last().unwrap();
    eprintln!("hanging tube: reaction {reaction:.6e} N/rad against the weight {weight:.6e}");
    assert!((reaction + weight).abs() < 1e-9 * weight.abs(), "{reaction} against {weight}");
    let sink = RHO * g * length * length / (2.0 * E);
    let bottom = r.nodes().iter().filter(|(x, _)| x[1] == 0.0).map(|(_, u)| u[1]).sum::<f64>() / 5.0;
    assert!((bottom / sink - 1.0).abs() < 5e-3, "bottom {bottom} against {sink}");
}

/// Body loads it cannot apply are refused, one line, exit 2.
#[test]
fn bad_body_loads_are_refused() {
    let spin = disc(20.0, false);
    let cases = [
        (spin.replace("elements = \"all\", spin", "elements = \"rotor\", spin"), "unknown element set 'rotor'"),
        (spin.replace(&format!("density = {RHO}\n"), ""), "material 'steel' has no density"),
        (spin.replace("spin = 3000", "gravity = -9810.0, spin = 3000"), "give one of gravity (mm/s^2) or spin (rad/s)"),
        (
            format!("{spin}[[step]]\nname = \"sway\"\nprocedure = \"harmonic\"\nmode = 1\nboundary = [ {{ set = \"bottom\", ur = 1.0 }} ]\n"),
            "the base state spins",
        ),
    ];
    for (deck, needle) in cases {
        let run = run_deck(&deck, &[], 1, &[]);
        assert_eq!(run.code(), 2, "{needle}: {}", run.stderr());
        assert!(run.stderr().contains(needle) && run.stderr().lines().count() == 1, "{needle}: {}", run.stderr());
    }
    // a spin ramped back to 0 leaves a base state at rest: the perturbation step runs (it was
    // refused as "the base state spins")
    let stopped = format!(
        "{spin}[[step]]\nname = \"stop\"\nbody_load = [ {{ elements = \"all\", spin = 0.0 }} ]\n[[step]]\nname = \"sway\"\nprocedure = \"harmonic\"\nmode = 1\nboundary = [ {{ set = \"bottom\", ur = 1.0 }} ]\n"
    );
    run_deck(&stopped, &[], 1, &[]).assert_ok();
}

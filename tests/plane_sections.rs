//! Plane strain and plane stress (`geometry = "plane_strain"` / `"plane_stress"`, and the .inp
//! types CPE.. / CPS..) against analytical answers.
//!
//! - Kirsch's plate with a hole (Kirsch 1898; Timoshenko & Goodier, Theory of Elasticity,
//!   sec. 35): remote tension s along y gives sigma_yy = 3 s at the hole's edge on the x axis
//!   and sigma_xx = -s on the y axis, in plane stress and plane strain alike. The quarter plate
//!   (tests/data/plate_hole.geo) is 25 hole radii wide and long; the finite width raises the
//!   factor to 3.005 (Heywood's K_tn = 2 + (1 - d/W)^3 over the net section, d/W = 0.04; Pilkey,
//!   Peterson's Stress Concentration Factors, chart 4.1). The nodal sigma_yy at the edge is
//!   held to 1 % of 3 s (measured 3.016 plane stress, 3.012 plane strain), sigma_xx on the y
//!   axis to 2 % of -s; plane stress's thickness strain is -nu (s_xx + s_yy) / E and the
//!   reaction is s times the width times the thickness (2 mm).
//! - Hertz's cylinder on a flat block in plane strain (Johnson, Contact Mechanics, sec. 4.3):
//!   load P per unit length, E* = E / (2 (1 - nu^2)) for two equal bodies, half-width
//!   b = sqrt(4 P R / (pi E*)), peak pressure p0 = 2 P / (pi b). R = 10 mm, E = 200 GPa,
//!   nu = 0.3, pressed 0.06 mm on 2 ranks: P = 2492 N/mm, b = 0.537 mm, p0 = 2953 MPa. The
//!   contact pressure's fit p^2 = p0^2 (1 - x^2 / b^2) gives both within 2 % (measured b
//!   +0.4 %, p0 -0.7 %).
//! - NAFEMS's contact benchmark 1, the 2-D cylinder roller (Konter, Advanced Finite Element
//!   Contact Benchmarks, NAFEMS 2006; tests/data/nafems_roller.geo): a steel cylinder (E 210
//!   GPa, diameter 100) pressed by a point load of 35 kN per mm into an aluminium block (E 70
//!   GPa, 200 x 200), nu 0.3, plane strain. Hertz (the benchmark's analytical answer, Johnson
//!   sec. 4.3): 1 / E* = (1 - nu^2) (1 / E1 + 1 / E2), E* = 57692 MPa, b = sqrt(4 P R / (pi E*))
//!   = 6.215 mm, p0 = 2 P / (pi b) = 3585 MPa; the fit gives both within 2 % (measured b -0.7 %,
//!   p0 +0.6 %). With the benchmark's mu = 0.1 (its published values are codes' averages, not
//!   reproduced here) Coulomb's law holds at every node, the centre sticks and the edges slide,
//!   and b and p0 stay within 2 % of Hertz's (the materials' mismatch, Dundurs' beta = -0.14,
//!   couples the shear into the pressure by about 1 %). Against CalculiX 2.20 on the same mesh
//!   and increments (surface-to-surface, the same penalty and stick slope; stored in
//!   tests/data/nafems_roller_ccx.csv by scripts/nafems-roller-calculix.sh), node by node where
//!   both carry over a fifth of the peak: the pressure within 5 % of the peak (measured 3.7 %,
//!   at the contact's edge) and |shear| / (mu p) 0.1 rms apart (measured 0.058; CalculiX's own
//!   profile is jagged, 0.25 apart at most); the stick zone ends at 4.7 to 5.1 mm, CalculiX's
//!   at 4.4 to 4.7 mm.
//! - Spence's problem in plane strain (Spence 1975, "The Hertz contact problem with finite
//!   friction", J. Elasticity 5): a cylinder of 1000 times the block's stiffness (R = 500, a cap
//!   25 high; tests/data/spence_cylinder.geo) pressed into a block 3000 x 3000, nu = 0.3, to a
//!   half-width of 2 mm (a / R = 0.004) in 20 increments; Dundurs' beta = -0.2851. The central
//!   stick zone c / a against a boundary-element solution of two half-planes
//!   (`scripts/spence_bem_plane.py --beta -0.2851 --mu 0.4073 0.2851 0.1996`, 400 elements,
//!   120 steps): 0.872, 0.652, 0.362 for beta / mu = -0.7, -1, -1.43; slideline within 5 %
//!   (measured +0.2, +2.9 and +1.4 %; a node spacing is 2.5 % of a, and a mesh refined over a
//!   slightly wider zone gave +0.1, -0.9 and -1.1 %). At a / R = 0.05 the slope of the contact
//!   surface, which the linear theory leaves out, tilts the normal traction by up to 3 degrees
//!   and the stick zone came out 20 to 40 % wider. For the same reasons the NAFEMS roller
//!   (a / R = 0.12, a finite disc and block) is no Spence problem: its c / a is 0.82 against
//!   the half-planes' 0.39.
//! - A CPS8 strip from an .inp deck in uniaxial tension: u = s L / E, reaction s W t.
//! - A column under its own weight (gravity on a plane body; Timoshenko & Goodier, sec. 24).

mod common;
use common::{assert_rejected, command_in, data, run_deck, Results, Run};

const STEEL: &str = r#"
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
"#;

fn kirsch_deck(geometry: &str) -> String {
    format!(
        r#"nlgeom = false
geometry = "{geometry}"
thickness = 2.0
[mesh]
file = "plate_hole.msh"
{STEEL}
[[step]]
name = "pull"
boundary = [ {{ set = "left", ux = 0.0 }}, {{ set = "bottom", uy = 0.0 }} ]
pressure = [ {{ surface = "top", value = -100.0 }} ]
"#
    )
}

/// The nodal value of `field` at the node at (x, y).
fn nodal_at(res: &Results, field: &str, at: [f64; 2]) -> f64 {
    let x = res.f64s("mesh/coordinates");
    let k = x.chunks(2).position(|c| (c[0] - at[0]).hypot(c[1] - at[1]) < 1e-9).expect("a node there");
    res.f64s(&format!("{}/nodal/{field}", res.last_increment()))[k]
}

#[test]
fn kirsch_plate_concentrates_stress_threefold_in_plane_stress_and_plane_strain() {
    for (geometry, ranks) in [("plane_stress", 1), ("plane_strain", 2)] {
        let run = run_deck(&kirsch_deck(geometry), &[("plate_hole.msh", &data("plate_hole.msh"))], ranks, &[]);
        run.assert_ok();
        let res = Results::open(&run.h5);
        let peak = nodal_at(&res, "stress_zz", [1.0, 0.0]) / 100.0;
        let side = nodal_at(&res, "stress_rr", [0.0, 1.0]) / 100.0;
        eprintln!("{geometry}: sigma_yy / s at the hole's edge {peak:.4} (3.005 with the finite width), sigma_xx / s on the y axis {side:.4}");
        assert!((peak - 3.0).abs() < 0.03, "{geometry}: stress concentration {peak}");
        assert!((side + 1.0).abs() < 0.02, "{geometry}: sigma_xx / s on the y axis {side}");
        let reaction = res.history("reaction_bottom_z");
        assert!((reaction.last().unwrap() + 100.0 * 25.0 * 2.0).abs() < 1e-6 * 5000.0, "{geometry}: reaction {reaction:?}");
        let (sxx, syy, stt, ett) = (
            nodal_at(&res, "stress_rr", [1.0, 0.0]),
            nodal_at(&res, "stress_zz", [1.0, 0.0]),
            nodal_at(&res, "stress_tt", [1.0, 0.0]),
            nodal_at(&res, "strain_tt", [1.0, 0.0]),
        );
        if geometry == "plane_stress" {
            assert!(stt.abs() < 1e-6, "sigma_zz out of plane {stt}");
            let hooke = -0.3 * (sxx + syy) / 200e3;
            assert!((ett - hooke).abs() < 1e-6 * hooke.abs(), "thickness strain {ett} vs {hooke}");
        } else {
            assert!(ett == 0.0, "plane strain's strain_tt {ett}");
            assert!((stt - 0.3 * (sxx + syy)).abs() < 0.01 * stt, "sigma_zz {stt} vs nu (sxx + syy) {}", 0.3 * (sxx + syy));
        }
        assert!(!res.file.group("history").unwrap().member_names().unwrap().iter().any(|n| n.ends_with("_ring")), "a plane model has no ring columns");
    }
}

#[test]
fn hertz_cylinder_on_a_block_in_plane_strain() {
    let deck = format!(
        r#"nlgeom = false
geometry = "plane_strain"
[mesh]
file = "hertz_cylinder.msh"
{STEEL}
[[contact]]
slave = "cylinder_surface"
master = "block_top"
penalty = 1.0e7
[[step]]
name = "press"
increments = 4
boundary = [ {{ set = "cylinder_top", uy = -0.06 }}, {{ set = "cylinder_axis", ux = 0.0 }}, {{ set = "block_axis", ux = 0.0 }}, {{ set = "block_bottom", uy = 0.0 }} ]
"#
    );
    let run = run_deck(&deck, &[("hertz_cylinder.msh", &data("hertz_cylinder.msh"))], 2, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    // the half model carries half the load
    let load = -2.0 * res.history("reaction_cylinder_top_z").last().unwrap();
    let e_star = 200e3 / (2.0 * (1.0 - 0.3 * 0.3));
    let b = (4.0 * load * 10.0 / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * load / (std::f64::consts::PI * b);
    let (b_fit, p0_fit, points) = hertz_fit(&res, "cylinder_surface-block_top/pass0");
    eprintln!("Hertz: P = {load:.1} N/mm; b {b_fit:.4} vs {b:.4} mm, p0 {p0_fit:.1} vs {p0:.1} MPa ({points} points)");
    assert!(points >= 10, "{points} points in the contact");
    assert!((b_fit / b - 1.0).abs() < 0.02, "half-width {b_fit} vs Hertz {b}");
    assert!((p0_fit / p0 - 1.0).abs() < 0.02, "peak pressure {p0_fit} vs Hertz {p0}");
}

/// (half-width b, peak pressure p0, points) of the last increment's contact pressure along the
/// pass `pass`, from the least squares of p^2 = p0^2 (1 - x^2 / b^2) over the slave nodes above
/// a fifth of the peak.
fn hertz_fit(res: &Results, pass: &str) -> (f64, f64, usize) {
    let nodes = res.u64s(&format!("mesh/contact/{pass}/nodes"));
    let pressure = res.f64s(&format!("{}/contact/{pass}/pressure", res.last_increment()));
    let x = res.f64s("mesh/coordinates");
    let peak = pressure.iter().cloned().fold(0.0, f64::max);
    let points: Vec<(f64, f64)> = nodes.iter().zip(&pressure).filter(|(_, &p)| p > 0.2 * peak).map(|(&n, &p)| (x[2 * n as usize].powi(2), p * p)).collect();
    let n = points.len() as f64;
    let (sx, sy) = (points.iter().map(|p| p.0).sum::<f64>(), points.iter().map(|p| p.1).sum::<f64>());
    let (sxx, sxy) = (points.iter().map(|p| p.0 * p.0).sum::<f64>(), points.iter().map(|p| p.0 * p.1).sum::<f64>());
    let slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    let intercept = (sy - slope * sx) / n;
    ((-intercept / slope).sqrt(), intercept.sqrt(), points.len())
}

/// A plane-strain deck of a body `upper` (element set, its sets `{upper}_surface` and
/// `{upper}_axis`) pressed into `block` (`block_top`, `block_axis`, `block_bottom` held) of mesh
/// `mesh`: Young's moduli [upper, block], the contact pair `pair` with `friction`'s lines, and
/// the step's `increments` and load line.
fn two_body_deck(mesh: &str, upper: &str, [e_upper, e_block]: [f64; 2], nu: f64, friction: &str, increments: usize, load: &str) -> String {
    format!(
        r#"nlgeom = false
geometry = "plane_strain"
[mesh]
file = "{mesh}"
[[material]]
name = "{upper}"
youngs_modulus = {e_upper}
poissons_ratio = {nu}
[[material]]
name = "block"
youngs_modulus = {e_block}
poissons_ratio = {nu}
[[section]]
elements = "{upper}"
material = "{upper}"
[[section]]
elements = "block"
material = "block"
[[contact]]
name = "pair"
slave = "{upper}_surface"
master = "block_top"
penalty_factor = 10.0
{friction}
[[step]]
name = "press"
increments = {increments}
boundary = [ {{ set = "{upper}_axis", ux = 0.0 }}, {{ set = "block_axis", ux = 0.0 }}, {{ set = "block_bottom", ux = 0.0, uy = 0.0 }} ]
{load}
"#
    )
}

#[test]
fn nafems_cylinder_roller_matches_hertz_with_and_without_friction() {
    let (e_roller, e_block, nu, radius, load) = (210e3, 70e3, 0.3, 50.0, 35e3);
    let e_star = 1.0 / ((1.0 - nu * nu) * (1.0 / e_roller + 1.0 / e_block));
    let b = (4.0 * load * radius / (std::f64::consts::PI * e_star)).sqrt();
    let p0 = 2.0 * load / (std::f64::consts::PI * b);
    for mu in [0.0, 0.1] {
        let friction = if mu > 0.0 { format!("friction = {mu}") } else { String::new() };
        let force = format!("force = [ {{ set = \"cylinder_top\", fy = {} }} ]", -load / 2.0);
        // with friction the answer depends on the path: CalculiX's increments
        let increments = if mu > 0.0 { 20 } else { 5 };
        let deck = two_body_deck("nafems_roller.msh", "cylinder", [e_roller, e_block], nu, &friction, increments, &force);
        // the Coulomb bound is checked to 1e-9: the tractions as computed
        let run = run_deck(&deck, &[("nafems_roller.msh", &data("nafems_roller.msh"))], 2, common::DOUBLE);
        run.assert_ok();
        let res = Results::open(&run.h5);
        assert!((res.history("reaction_block_bottom_z").last().unwrap() - load / 2.0).abs() < 1e-6 * load, "the block carries the half load");
        let (b_fit, p0_fit, points) = hertz_fit(&res, "pair/pass0");
        eprintln!("NAFEMS roller, mu {mu}: b {b_fit:.4} vs Hertz {b:.4} mm, p0 {p0_fit:.1} vs {p0:.1} MPa ({points} points)");
        assert!(points >= 15, "mu {mu}: {points} points in the contact");
        assert!((b_fit / b - 1.0).abs() < 0.02, "mu {mu}: half-width {b_fit} vs Hertz {b}");
        assert!((p0_fit / p0 - 1.0).abs() < 0.02, "mu {mu}: peak pressure {p0_fit} vs Hertz {p0}");
        if mu > 0.0 {
            let last = res.last_increment();
            let (pressure, shear) = (res.f64s(&format!("{last}/contact/pair/pass0/pressure")), res.f64s(&format!("{last}/contact/pair/pass0/shear")));
            let sliding = res.u8s(&format!("{last}/contact/pair/pass0/sliding"));
            let x = res.f64s("mesh/coordinates");
            let nodes = res.u64s("mesh/contact/pair/pass0/nodes");
            let mut slid = 0;
            for k in 0..nodes.len() {
                assert!(shear[k].abs() <= mu * pressure[k] * (1.0 + 1e-9), "node {}: |shear| {} above mu p {}", nodes[k], shear[k], mu * pressure[k]);
                if pressure[k] > 0.0 && sliding[k] == 1 {
                    assert!((shear[k].abs() / (mu * pressure[k]) - 1.0).abs() < 1e-9, "node {}: slides below mu p", nodes[k]);
                    slid += 1;
                }
            }
            // the disc's upper half is in the slave surface too, never in contact
            let (_, c, one_zone) = stick_zone(&res, "pair/pass0", 10.0);
            assert!(slid >= 3 && c > 0.5 * b && one_zone, "mu {mu}: the centre sticks to {c} mm and {slid} nodes slide outside it");
            // CalculiX 2.20 on the same mesh (scripts/nafems-roller-calculix.sh): the pressure
            // and the shear's share of mu p, node by node where both carry over a fifth of the peak
            let ccx: Vec<[f64; 3]> = std::fs::read_to_string(data("nafems_roller_ccx.csv"))
                .unwrap()
                .lines()
                .filter(|l| !l.starts_with('#'))
                .map(|l| {
                    let v: Vec<f64> = l.split(',').map(|v| v.parse().unwrap()).collect();
                    [v[0], v[1], v[2]]
                })
                .collect();
            let peak = pressure.iter().cloned().fold(0.0, f64::max);
            let (mut compared, mut pressure_gap, mut share_squares) = (0, 0.0f64, 0.0);
            for k in 0..nodes.len() {
                let at = [x[2 * nodes[k] as usize], x[2 * nodes[k] as usize + 1]];
                let Some(&[_, p_ccx, q_ccx]) = ccx.iter().find(|c| (c[0] - at[0]).abs() < 1e-5 && at[1] < 10.0) else { continue };
                if pressure[k] > 0.2 * peak && p_ccx > 0.2 * peak {
                    compared += 1;
                    pressure_gap = pressure_gap.max((pressure[k] - p_ccx).abs() / peak);
                    share_squares += (shear[k].abs() / (mu * pressure[k]) - q_ccx.abs() / (mu * p_ccx)).powi(2);
                }
            }
            let share_rms = (share_squares / compared as f64).sqrt();
            eprintln!(
                "against CalculiX at {compared} nodes: pressure within {:.2} % of the peak, |shear| / (mu p) {share_rms:.3} rms apart",
                100.0 * pressure_gap
            );
            assert!(
                compared >= 30 && pressure_gap < 0.05 && share_rms < 0.1,
                "against CalculiX: {compared} nodes, pressure {pressure_gap}, shear share rms {share_rms}"
            );
        }
    }
}

/// A strip 10 mm long, 2 mm wide, of five 8-node plane elements of type `kind`, with
/// `thickness` on its *SOLID SECTION line, pulled by `stress` on its right edge (face P2 of
/// the last element, from its corner 2 to corner 3), held along x at its left edge.
fn strip_deck(kind: &str, thickness: &str, stress: f64) -> String {
    // nodes on a grid of 1 mm half-steps: i in 0..=10 along x, j in 0..=2 across
    let id = |i: usize, j: usize| 1 + i + 11 * j;
    let mut nodes = String::new();
    for j in 0..=2 {
        for i in (0..=10).filter(|i| j != 1 || i % 2 == 0) {
            nodes.push_str(&format!("{}, {}.0, {}.0\n", id(i, j), i, j));
        }
    }
    let mut elements = String::new();
    for e in 0..5 {
        let i = 2 * e;
        let n = [id(i, 0), id(i + 2, 0), id(i + 2, 2), id(i, 2), id(i + 1, 0), id(i + 2, 1), id(i + 1, 2), id(i, 1)];
        elements.push_str(&format!("{}, {}\n", e + 1, n.map(|k| k.to_string()).join(", ")));
    }
    format!(
        "*NODE, NSET=NALL\n{nodes}*ELEMENT, TYPE={kind}, ELSET=EALL\n{elements}*NSET, NSET=LEFT\n{}, {}, {}\n*NSET, NSET=CORNER\n{}\n\
*MATERIAL, NAME=STEEL\n*ELASTIC\n200000., 0.3\n*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n{thickness}\n\
*BOUNDARY\nLEFT, 1, 1\nCORNER, 2, 2\n*STEP\n*STATIC\n*DLOAD\n5, P2, {}\n*NODE FILE\nU\n*END STEP\n",
        id(0, 0),
        id(0, 1),
        id(0, 2),
        id(0, 0),
        -stress
    )
}

#[test]
fn a_plane_stress_strip_from_an_inp_deck_stretches_as_hookes_law_says() {
    for (kind, thickness, t) in [("CPS8", "0.5", 0.5), ("CPE8R", "", 1.0)] {
        // run without --quiet, for the reader's notes
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("strip.inp"), strip_deck(kind, thickness, 100.0)).unwrap();
        let h5 = dir.path().join("out.h5");
        let output = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "strip.inp", "-o"]).arg(&h5).output().unwrap();
        let run = Run { dir, output, h5 };
        run.assert_ok();
        let res = Results::open(&run.h5);
        // plane stress: u = s L / E; plane strain (free across the strip): u = s L (1 - nu^2) / E
        let expected = if kind == "CPS8" { 100.0 * 10.0 / 200e3 } else { 100.0 * 10.0 * (1.0 - 0.09) / 200e3 };
        let tip = res.nodes().iter().filter(|(x, _)| x[0] == 10.0).map(|(_, u)| u[0]).fold(f64::NAN, f64::max);
        assert!((tip - expected).abs() < 1e-9, "{kind}: u at the tip {tip} vs {expected}");
        let reaction = *res.history("reaction_LEFT_r").last().unwrap();
        assert!((reaction + 100.0 * 2.0 * t).abs() < 1e-8, "{kind}: reaction {reaction} vs {}", -100.0 * 2.0 * t);
        assert!(run.stdout().contains("note: a plane model: forces and reactions are those of the sections' thickness"), "{kind}:\n{}", run.stdout());
        let section = if kind == "CPS8" { "plane-stress" } else { "plane-strain" };
        let element = if kind == "CPS8" {
            format!("slideline's 8-node {section} quadrilateral")
        } else {
            format!("CalculiX's reduced 8-node {section} quadrilateral: 2 x 2 Gauss points")
        };
        assert!(run.stdout().contains(&format!("5 {kind} elements run as {element}")), "{}", run.stdout());
    }
}

#[test]
fn plane_input_errors_name_the_item() {
    let body = format!("[mesh]\nrectangle = {{ r = [0.0, 10.0], z = [0.0, 2.0], divisions = [2, 1] }}\n{STEEL}");
    // a thickness without a plane geometry
    let run = run_deck(&format!("thickness = 2.0\n{body}[[step]]\nboundary = [ {{ set = \"bottom\", uz = 0.0 }} ]\n"), &[], 1, &[]);
    assert_rejected(&run, &["thickness", "plane"]);
    // a plane body nothing holds along x
    let run = run_deck(&format!("geometry = \"plane_strain\"\n{body}[[step]]\nboundary = [ {{ set = \"bottom\", uy = 0.0 }} ]\n"), &[], 1, &[]);
    assert_rejected(&run, &["free to move along x", "ux"]);
    // a zero thickness
    let run = run_deck(
        &format!("geometry = \"plane_stress\"\nthickness = 0.0\n{body}[[step]]\nboundary = [ {{ set = \"inner\", ux = 0.0, uy = 0.0 }} ]\n"),
        &[],
        1,
        &[],
    );
    assert_rejected(&run, &["thickness = 0", "positive"]);
}

/// Gravity on a plane body: a column x 0..20, y 0..100, standing on rollers, its left edge a
/// symmetry plane, under its own weight (rho = 7.85e-9 t/mm^3, g = -9810 mm/s^2 along y). The
/// exact answer (Timoshenko & Goodier, Theory of Elasticity, sec. 24, the prism under its own
/// weight) is sigma_yy = rho g (L - y), sigma_xx = sigma_xy = 0. Its base stays flat on the
/// rollers only without Poisson's contraction (u_y has a term nu rho g x^2 / 2E), so nu = 0
/// here: then u_y = rho g (y^2 / 2 - L y) / E, quadratic, which the 8-node element holds
/// exactly. Checked: the nodal sigma_yy to 1e-7 of its largest value (the solve's tolerance), sigma_xx and the out-of-
/// plane stress zero, in plane stress and plane strain, and the base's reaction the weight
/// rho g L W t of the thickness t (2 mm), not a ring's.
#[test]
fn a_plane_column_under_its_own_weight_is_timoshenkos_prism() {
    let (rho, g, length, width, t): (f64, f64, f64, f64, f64) = (7.85e-9, -9810.0, 100.0, 20.0, 2.0);
    for geometry in ["plane_stress", "plane_strain"] {
        let deck = format!(
            r#"nlgeom = false
geometry = "{geometry}"
thickness = {t}
[mesh]
rectangle = {{ r = [0.0, {width}], z = [0.0, {length}], divisions = [2, 10] }}
{}density = {rho}
[[step]]
boundary = [ {{ set = "inner", ux = 0.0 }}, {{ set = "bottom", uy = 0.0 }} ]
body_load = [ {{ elements = "all", gravity = {g} }} ]
"#,
            STEEL.replace("0.3", "0.0")
        );
        let run = run_deck(&deck, &[], 1, &[]);
        run.assert_ok();
        let res = Results::open(&run.h5);
        let scale = (rho * g * length).abs();
        for y in [0.0, 25.0, 50.0, 90.0] {
            for x in [0.0, width] {
                let syy = nodal_at(&res, "stress_zz", [x, y]);
                assert!((syy - rho * g * (length - y)).abs() < 1e-7 * scale, "{geometry}: sigma_yy {syy} at ({x}, {y})");
                let sxx = nodal_at(&res, "stress_rr", [x, y]);
                assert!(sxx.abs() < 1e-7 * scale, "{geometry}: sigma_xx {sxx} at ({x}, {y})");
                let szz = nodal_at(&res, "stress_tt", [x, y]);
                assert!(szz.abs() < 1e-7 * scale, "{geometry}: sigma_zz {szz} at ({x}, {y})");
            }
        }
        let weight = rho * g * length * width * t;
        let reaction = *res.history("reaction_bottom_z").last().unwrap();
        assert!((reaction + weight).abs() < 1e-7 * weight.abs(), "{geometry}: reaction {reaction} against the weight {weight}");
        // the linearisation across the column at mid-height names a plane model's components
        // and finds the membrane stress rho g L / 2 across the section (printed to 4 places)
        let post = command_in(run.dir.path(), 1).args(["post", run.h5.to_str().unwrap(), "--linearize", "0,50:20,50"]).output().unwrap();
        let text = String::from_utf8_lossy(&post.stdout);
        assert!(post.status.success() && text.contains("in-plane across it, out-of-plane, shear") && !text.contains("hoop"), "{text}");
        let membrane: Vec<f64> =
            text.lines().find(|l| l.trim_start().starts_with("membrane ")).unwrap().split_whitespace().skip(1).map(|v| v.parse().unwrap()).collect();
        assert!((membrane[1] - rho * g * length / 2.0).abs() < 1e-4 && membrane[0].abs() < 1e-4, "{text}");
    }
}

/// The last increment's contact and stick half-widths (a, c) along pass `pass` over its slave
/// nodes below y = `below`, each halfway between the last node inside and the first outside,
/// and whether every node in contact sticks inside c and slides outside it.
fn stick_zone(res: &Results, pass: &str, below: f64) -> (f64, f64, bool) {
    let last = res.last_increment();
    let (pressure, sliding) = (res.f64s(&format!("{last}/contact/{pass}/pressure")), res.u8s(&format!("{last}/contact/{pass}/sliding")));
    let x = res.f64s("mesh/coordinates");
    let mut rows: Vec<(f64, f64, u8)> = res
        .u64s(&format!("mesh/contact/{pass}/nodes"))
        .iter()
        .zip(&pressure)
        .zip(&sliding)
        .filter(|((&n, _), _)| x[2 * n as usize + 1] < below)
        .map(|((&n, &p), &s)| (x[2 * n as usize], p, s))
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let edge = rows.iter().position(|r| r.1 <= 0.0).expect("the contact ends on the slave surface");
    let first = rows[..edge].iter().position(|r| r.2 == 1).expect("no node slides");
    assert!(first > 0, "no node sticks");
    let (a, c) = (0.5 * (rows[edge - 1].0 + rows[edge].0), 0.5 * (rows[first - 1].0 + rows[first].0));
    (a, c, rows[first..edge].iter().all(|r| r.2 == 1))
}

#[test]
fn plane_frictional_indentation_sticks_inside_the_half_planes_radius() {
    let (e_block, nu, radius, half_width) = (70e3, 0.3, 500.0, 2.0);
    let e_cap = 1000.0 * e_block;
    let e_star = 1.0 / ((1.0 - nu * nu) * (1.0 / e_cap + 1.0 / e_block));
    // the load that gives Hertz's half-width, as a pressure on the cap's flat top (half model)
    let load = half_width * half_width * std::f64::consts::PI * e_star / (4.0 * radius);
    let top = (radius * radius - (radius - 25.0f64).powi(2)).sqrt();
    let beta = (1.0 - 2.0 * nu) * (1.0 + nu) * (1.0 / e_cap - 1.0 / e_block) / (2.0 * (1.0 - nu * nu) * (1.0 / e_cap + 1.0 / e_block));
    assert!((beta + 0.2851).abs() < 5e-5, "Dundurs' beta {beta}");
    for (mu, reference) in [(0.4073, 0.872), (0.2851, 0.652), (0.1996, 0.362)] {
        let pressure = format!("pressure = [ {{ surface = \"cap_top\", value = {} }} ]", load / 2.0 / top);
        let deck = two_body_deck("spence_cylinder.msh", "cap", [e_cap, e_block], nu, &format!("friction = {mu}"), 20, &pressure);
        let run = run_deck(&deck, &[("spence_cylinder.msh", &data("spence_cylinder.msh"))], 2, &[]);
        run.assert_ok();
        let res = Results::open(&run.h5);
        let (a, c, one_zone) = stick_zone(&res, "pair/pass0", f64::INFINITY);
        eprintln!(
            "plane Spence, mu {mu} (beta / mu {:.3}): a {a:.4} mm, c/a {:.4} against {reference} ({:+.1} %)",
            beta / mu,
            c / a,
            100.0 * (c / a / reference - 1.0)
        );
        assert!(one_zone, "mu {mu}: a node sticks outside the central stick zone");
        assert!((c / a / reference - 1.0).abs() < 0.05, "mu {mu}: c/a {} against the half-planes' {reference}", c / a);
    }
}

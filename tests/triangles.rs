//! Six-node triangles (T6; CalculiX's CAX6, Gmsh's type 9) against the analytical answers the
//! Q8 tests use, on structured, unstructured (Gmsh) and mixed Q8/T6 meshes.
//!
//! - Lame's thick-walled cylinder (Timoshenko & Goodier, Theory of Elasticity, sec. 33): inner
//!   radius a = 100 mm, outer b = 130 mm, internal pressure p = 50 MPa, E = 200 GPa, nu = 0.3,
//!   axial ends held: u_r(a) = 0.098442 mm, u_r(b) = 0.085725 mm,
//!   sigma_tt(a) = p (b^2 + a^2) / (b^2 - a^2) = 194.93 MPa. u_r to 1e-4 at every node and the
//!   nodal hoop stress at the bore to 2e-3.
//! - The perfectly plastic thick cylinder (same radii, sigma_y 300 MPa, H = 0; Hill, The
//!   Mathematical Theory of Plasticity, ch. V): limit pressure (2 / sqrt 3) sigma_y ln(b / a) =
//!   90.89 MPa to 1e-3, and the mean stress at every Gauss point on the fully plastic solution
//!   sigma_m = -p + (2 / sqrt 3) sigma_y ln(r / a) + sigma_y / sqrt 3 to 1 % of sigma_y (a
//!   locking or checkerboarding element misses both).
//! - The clamped circular plate (Timoshenko & Woinowsky-Krieger, Theory of Plates and Shells,
//!   sec. 62): w(0) = p a^4 / (64 D) = 0.8531 mm for a = 100, t = 1, p = 0.01 MPa; to 0.5 %
//!   with 4 triangle pairs through the thickness (bending is what a volumetric treatment can
//!   spoil: projected onto the element's mean, this plate came out 3 % soft).
//! - The same plastic cylinder from a CalculiX deck of CAX6, which integrate as CalculiX's and
//!   Abaqus's (3 points, no volumetric treatment): the limit pressure to 1e-3 and the mean
//!   stress at every point to 1 % of sigma_y.
//! - The contact patch test on triangles: 10 MPa through non-matching triangle meshes, at
//!   every slave node to 1e-6.

mod common;
use common::{assert_rejected, data, patch_test_deck, run_deck, run_deck_file, Results, TIGHT};
use slideline::fe::quadrature::Integration;
use slideline::fe::shape::Shape;
use slideline::model::mesh::{rectangle, split_into_triangles};

const A: f64 = 100.0;
const B: f64 = 130.0;

fn lame_ur(r: f64) -> f64 {
    let (p, e, nu) = (50.0, 200e3, 0.3);
    let aa = p * A * A / (B * B - A * A);
    (1.0 + nu) / e * ((1.0 - 2.0 * nu) * aa * r + aa * B * B / r)
}

const STEEL: &str = r#"
[[material]]
name = "steel"
youngs_modulus = 200000.0
poissons_ratio = 0.3
"#;

const LAME_STEP: &str = r#"
[[step]]
boundary = [ { set = "bottom", uz = 0.0 }, { set = "top", uz = 0.0 } ]
pressure = [ { surface = "inner", value = 50.0 } ]
"#;

/// Checks a Lame run: u_r at every node, the nodal hoop stress at the bore; returns the
/// element count per shape (Q8, T6) from the results file.
fn check_lame(res: &Results, label: &str) -> (usize, usize) {
    let mut worst = 0.0f64;
    for (x, u) in res.nodes() {
        worst = worst.max((u[0] - lame_ur(x[0])).abs() / lame_ur(x[0]));
        assert!(u[1].abs() < 1e-6, "{label}: u_z {} at {x:?}", u[1]);
    }
    let hoop = res.f64s(&format!("{}/nodal/stress_tt", res.last_increment()));
    let exact = 50.0 * (B * B + A * A) / (B * B - A * A);
    let bore: Vec<f64> = res.nodes().iter().zip(&hoop).filter(|((x, _), _)| (x[0] - A).abs() < 1e-9).map(|(_, &s)| s).collect();
    let hoop_error = bore.iter().map(|s| (s - exact).abs() / exact).fold(0.0, f64::max);
    eprintln!("{label}: u_r within {worst:.2e} of Lame at every node; nodal hoop stress at the bore within {hoop_error:.2e} of {exact:.2} MPa");
    assert!(worst < 1e-4, "{label}: u_r off by {worst:e}");
    assert!(!bore.is_empty() && hoop_error < 2e-3, "{label}: bore hoop stress {bore:?} vs {exact}");
    let conn = res.i64s("mesh/connectivity");
    let tri = conn.chunks(8).filter(|c| c[6] == c[0]).count();
    (conn.len() / 8 - tri, tri)
}

#[test]
fn lame_on_structured_triangles_on_two_ranks() {
    let deck = format!("nlgeom = false\n[mesh]\nrectangle = {{ r = [{A}, {B}], z = [0.0, 10.0], divisions = [12, 2], triangles = true }}\n{STEEL}{LAME_STEP}");
    let run = run_deck(&deck, &[], 2, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    assert_eq!(check_lame(&res, "structured T6"), (0, 48));
    // the cells ParaView and meshio read: XDMF's Triangle_6 rows of the six nodes
    let xmf = std::fs::read_to_string(run.h5.with_extension("xmf")).unwrap();
    assert!(xmf.contains(r#"TopologyType="Triangle_6" NumberOfElements="48""#), "{}", &xmf[..600.min(xmf.len())]);
    let cells = res.i64s("mesh/topology");
    let conn = res.i64s("mesh/connectivity");
    assert_eq!(cells.len(), 48 * 6);
    for e in 0..48 {
        assert_eq!(cells[6 * e..6 * e + 6], conn[8 * e..8 * e + 6], "element row {e}");
    }
}

#[test]
fn lame_on_gmsh_unstructured_triangles_and_a_mixed_quadrilateral_triangle_mesh() {
    // tests/data/lame_tri6.geo and lame_mixed.geo, meshed with Gmsh 4.8 (-order 2)
    for (file, ranks) in [("lame_tri6.msh", 1), ("lame_mixed.msh", 2)] {
        let deck = format!("nlgeom = false\n[mesh]\nfile = \"m.msh\"\n{STEEL}{LAME_STEP}");
        let run = run_deck(&deck, &[("m.msh", &data(file))], ranks, &[]);
        run.assert_ok();
        let res = Results::open(&run.h5);
        let (quads, triangles) = check_lame(&res, file);
        let xmf = std::fs::read_to_string(run.h5.with_extension("xmf")).unwrap();
        if file == "lame_tri6.msh" {
            assert_eq!((quads, triangles), (0, 92));
        } else {
            assert_eq!((quads, triangles), (20, 44));
            // XDMF's mixed list: type 37 and 8 nodes per Q8, 36 and 6 per T6
            let cells = res.i64s("mesh/topology");
            assert_eq!(cells.len(), 20 * 9 + 44 * 7);
            assert!(xmf.contains(&format!(r#"TopologyType="Mixed" NumberOfElements="64"><DataItem Dimensions="{}""#, cells.len())), "{xmf:.600}");
            let (mut at, mut seen) = (0, [0, 0]);
            while at < cells.len() {
                let n = match cells[at] {
                    37 => 8,
                    36 => 6,
                    other => panic!("cell type {other} at {at}"),
                };
                seen[usize::from(n == 6)] += 1;
                at += 1 + n;
            }
            assert_eq!(seen, [20, 44]);
        }
    }
}

#[test]
fn plastic_limit_pressure_and_mean_stress_on_triangles() {
    let (sy, h) = (300.0, 1.0);
    let deck = format!(
        "nlgeom = false\n[mesh]\nrectangle = {{ r = [{A}, {B}], z = [0.0, {h}], divisions = [10, 3], triangles = true }}\n\
         [[material]]\nname = \"steel\"\nmodel = \"j2\"\nyoungs_modulus = 200000.0\npoissons_ratio = 0.3\nyield_stress = {sy}\nhardening_modulus = 0.0\n\
         [[step]]\nincrements = 12\nboundary = [ {{ set = \"bottom\", uz = 0.0 }}, {{ set = \"top\", uz = 0.0 }}, {{ set = \"inner\", ur = 1.2 }} ]\n"
    );
    let run = run_deck(&deck, &[], 2, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let pressure: Vec<f64> = res.history("reaction_inner_r").iter().map(|f| f / (A * h)).collect();
    let limit = 2.0 / 3f64.sqrt() * sy * (B / A).ln();
    let last = *pressure.last().unwrap();
    eprintln!("triangles: plateau {last:.4} MPa, limit pressure {limit:.4} (rel {:.1e})", (last - limit) / limit);
    assert!((last - limit).abs() <= 1e-3 * limit, "plateau {last} vs limit pressure {limit}");
    // mean stress at every Gauss point (the rule's points mapped with the T6 functions)
    let stress = res.f64s(&format!("{}/stress", res.last_increment()));
    let (conn, coords) = (res.i64s("mesh/connectivity"), res.f64s("mesh/coordinates"));
    let rule = Shape::Tri6.rule();
    let mut worst = 0.0f64;
    for (e, c) in conn.chunks(8).enumerate() {
        for (q, (p, _)) in rule.iter().enumerate() {
            let (n, _) = Shape::Tri6.functions(*p);
            let r: f64 = (0..6).map(|a| n[a] * coords[2 * c[a] as usize]).sum();
            let expected = -last + 2.0 / 3f64.sqrt() * sy * (r / A).ln() + sy / 3f64.sqrt();
            let s = &stress[(9 * e + q) * 4..(9 * e + q) * 4 + 3];
            worst = worst.max(((s[0] + s[1] + s[2]) / 3.0 - expected).abs());
        }
    }
    eprintln!("triangles: mean stress within {worst:.3} MPa of the fully plastic solution at every Gauss point");
    assert!(worst <= 0.01 * sy, "mean stress off by {worst} MPa");
}

#[test]
fn clamped_plate_bends_within_half_a_percent_on_triangles() {
    let deck = format!(
        "nlgeom = false\n[mesh]\nrectangle = {{ r = [0.0, 100.0], z = [0.0, 1.0], divisions = [100, 4], triangles = true }}\n{STEEL}\
         [[step]]\nboundary = [ {{ set = \"inner\", ur = 0.0 }}, {{ set = \"outer\", ur = 0.0, uz = 0.0 }} ]\npressure = [ {{ surface = \"top\", value = 0.01 }} ]\n"
    );
    let run = run_deck(&deck, &[], 2, &[]);
    run.assert_ok();
    let nodes = Results::open(&run.h5).nodes();
    let (_, u) = nodes.iter().find(|(x, _)| x[0] == 0.0 && (x[1] - 0.5).abs() < 1e-12).expect("mid-plane node on the axis");
    let d = 200e3 / (12.0 * (1.0 - 0.09));
    let exact = -0.01 * 100f64.powi(4) / (64.0 * d);
    let rel = (u[1] - exact).abs() / exact.abs();
    eprintln!("triangles: centre deflection {:.5} mm, Kirchhoff {exact:.5} (rel {rel:.2e})", u[1]);
    assert!(rel < 5e-3, "centre deflection {} vs {exact}", u[1]);
}

#[test]
fn contact_patch_test_on_triangles() {
    // the Q8 patch test's stacked blocks (tests/contact_patch_test.rs), both split into triangles
    let deck = patch_test_deck("segment", false, true);
    let run = run_deck(&deck, &[], 2, TIGHT);
    run.assert_ok();
    let res = Results::open(&run.h5);
    let p = res.f64s("increments/000001/contact/interface/pass0/pressure");
    assert_eq!(p.len(), 15, "the slave surface's 7 edges have 15 nodes");
    assert!(p.iter().all(|p| (p - 10.0).abs() <= 1e-6 * 10.0), "contact pressure {p:?}");
    let szz = res.f64s("increments/000001/stress").chunks(4).map(|s| (s[1] + 10.0).abs()).fold(0.0, f64::max);
    assert!(szz <= 1e-5 * 10.0, "sigma_zz off -10 MPa by {szz}");
}

/// A CalculiX deck of the cylinder r in [A, B], z in [0, `height`], on `divisions` cells each
/// split into two triangles: CAX6, or CAX3 (corners only, `linear`); node sets ENDS (top and
/// bottom) and BORE_NODES, the surface BORE (the inner faces, or `inner_face`); `material`'s
/// cards after *ELASTIC, then `step`.
fn calculix_triangle_deck(divisions: [usize; 2], height: f64, linear: bool, inner_face: &str, material: &str, step: &str) -> String {
    let (q, qs) = rectangle([A, B], [0.0, height], divisions).unwrap();
    let (mesh, sets) = split_into_triangles(&q, &qs);
    let mut s = String::from("*NODE, NSET=NALL\n");
    // CAX3 lists corners only: their mid-side nodes are added by the reader
    let used: std::collections::BTreeSet<usize> = (0..mesh.elements.len()).flat_map(|e| mesh.element_nodes(e)[..if linear { 3 } else { 6 }].to_vec()).collect();
    for &n in &used {
        s += &format!("{}, {}, {}\n", n + 1, mesh.coords[n][0], mesh.coords[n][1]);
    }
    s += &format!("*ELEMENT, TYPE={}, ELSET=EALL\n", if linear { "CAX3" } else { "CAX6" });
    for e in 0..mesh.elements.len() {
        let nodes: Vec<String> = mesh.element_nodes(e)[..if linear { 3 } else { 6 }].iter().map(|n| (n + 1).to_string()).collect();
        s += &format!("{}, {}\n", e + 1, nodes.join(", "));
    }
    let face = |name: &str| sets.surfaces[name].iter().map(|edge| format!("{}, S{}\n", edge.element + 1, edge.side + 1)).collect::<String>();
    let nodes_of = |names: &[&str]| -> String {
        let nodes: std::collections::BTreeSet<usize> =
            names.iter().flat_map(|n| sets.surfaces[*n].iter().flat_map(|e| mesh.edge_nodes(*e))).filter(|n| used.contains(n)).collect();
        nodes.iter().map(|n| (n + 1).to_string()).collect::<Vec<_>>().join(",\n")
    };
    let inner = if inner_face.is_empty() { face("inner") } else { format!("{inner_face}\n") };
    s += &format!("*NSET, NSET=ENDS\n{}\n*NSET, NSET=BORE_NODES\n{}\n*SURFACE, NAME=BORE\n{inner}", nodes_of(&["bottom", "top"]), nodes_of(&["inner"]));
    s += &format!("*MATERIAL, NAME=STEEL\n*ELASTIC\n200000., 0.3\n{material}*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL\n{step}");
    s
}

/// The reader of CalculiX decks: CAX6 elements (CalculiX's 3-point rule), CAX3 (given mid-side
/// nodes, as CAX4), and their faces S1 to S3; S4 of a triangle is refused with the element named.
#[test]
fn calculix_cax6_and_cax3_decks_run_lame() {
    let step = "*STEP\n*STATIC\n*BOUNDARY\nENDS, 2, 2\n*DLOAD\nBORE, P1, 50.\n*END STEP\n";
    let deck = |linear: bool, inner_face: &str| calculix_triangle_deck([6, 2], 10.0, linear, inner_face, "", step);
    // a CAX3 deck's ends list corners only; the added mid-side nodes join the set (as CAX4's)
    for linear in [false, true] {
        let run = run_deck_file("lame.inp", &deck(linear, ""), &[], 1, &[]);
        run.assert_ok();
        let label = if linear { "CAX3" } else { "CAX6" };
        assert_eq!(check_lame(&Results::open(&run.h5), label), (0, 24));
    }
    assert_rejected(&run_deck_file("s4.inp", &deck(false, "1, S4"), &[], 1, &[]), &["face 'S4' of element 1", "triangle has faces S1 to S3"]);
    let p4 = deck(false, "").replace("BORE, P1, 50.", "1, P4, 50.");
    assert_rejected(&run_deck_file("p4.inp", &p4, &[], 1, &[]), &["'P4' on element 1", "triangle has faces P1 to P3"]);
}

/// A CAX6 deck's triangles integrate as CalculiX's and Abaqus's: 3 points, no volumetric
/// treatment. In plastic flow that does not lock either: the perfectly plastic cylinder of
/// `plastic_limit_pressure_and_mean_stress_on_triangles`, meshed alike, meets the limit pressure
/// to 1e-3 and the fully plastic mean stress at every one of its 3 points per element to 1 % of
/// sigma_y (measured: 4e-6 and 0.24 %, as the 9-point rule's 4e-6 and 0.27 %).
#[test]
fn a_calculix_cax6_deck_reaches_the_limit_pressure_with_three_points_per_triangle() {
    let (sy, h) = (300.0, 1.0);
    let step = "*STEP\n*STATIC, DIRECT\n0.0833333333333333, 1.\n*BOUNDARY\nENDS, 2, 2\nBORE_NODES, 1, 1, 1.2\n*END STEP\n";
    let deck = calculix_triangle_deck([10, 3], h, false, "", &format!("*PLASTIC\n{sy}, 0.\n"), step);
    let run = run_deck_file("plastic.inp", &deck, &[], 2, &[]);
    run.assert_ok();
    let res = Results::open(&run.h5);
    assert!(res.i64s("mesh/gauss_points").iter().all(|&n| n == 3));
    let last = *res.history("reaction_BORE_NODES_r").last().unwrap() / (A * h);
    let limit = 2.0 / 3f64.sqrt() * sy * (B / A).ln();
    eprintln!("CAX6: plateau {last:.4} MPa, limit pressure {limit:.4} (rel {:.1e})", (last - limit) / limit);
    assert!((last - limit).abs() <= 1e-3 * limit, "plateau {last} vs limit pressure {limit}");
    let stress = res.f64s(&format!("{}/stress", res.last_increment()));
    let (conn, coords) = (res.i64s("mesh/connectivity"), res.f64s("mesh/coordinates"));
    let rule = Shape::Tri6.rule_for(Integration::Reduced);
    let mut worst = 0.0f64;
    for (e, c) in conn.chunks(8).enumerate() {
        for (q, (p, _)) in rule.iter().enumerate().take(3) {
            let (n, _) = Shape::Tri6.functions(*p);
            let r: f64 = (0..6).map(|a| n[a] * coords[2 * c[a] as usize]).sum();
            let expected = -last + 2.0 / 3f64.sqrt() * sy * (r / A).ln() + sy / 3f64.sqrt();
            let s = &stress[(9 * e + q) * 4..(9 * e + q) * 4 + 3];
            worst = worst.max(((s[0] + s[1] + s[2]) / 3.0 - expected).abs());
        }
        assert!(stress[(9 * e + 3) * 4..(9 * e + 9) * 4].iter().all(|v| v.is_nan()), "element {e}: its 6 spare slots");
    }
    eprintln!("CAX6: mean stress within {worst:.3} MPa of the fully plastic solution at every Gauss point");
    assert!(worst <= 0.01 * sy, "mean stress off by {worst} MPa");
    // meshio and h5py: the spare slots, and the nodal values copied from the 3 points
    let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/check_xdmf.py");
    let check = common::python().arg(script).arg(run.h5.with_extension("xmf")).output().unwrap();
    let text = String::from_utf8_lossy(&check.stdout);
    assert!(check.status.success() && text.trim_end().ends_with("ok"), "{text}{}", String::from_utf8_lossy(&check.stderr));
}

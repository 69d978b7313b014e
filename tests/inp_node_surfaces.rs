//! A node-based slave surface (`*SURFACE, TYPE=NODE`) in a CalculiX deck bears as in CalculiX:
//! each node of the set is a slave point carrying the area of the master face it meets (ccx
//! 2.20's springforc_n2f.f: a slave node without a face of its own takes the master face's area;
//! gen3dsurf.f keeps the 2-D node of the set as that slave node).
//!
//! Two plane-strain CPE8 blocks (unit thickness): the lower one x 0..2, y 0..1, one element
//! whose top face is the master; the upper one x 0.5..1.5, y 1..2, pressed down by 0.3 MPa on
//! its top, the node set of its bottom face (3 nodes, away from the master's ends) the slave,
//! under CalculiX's exponential law p = p0 exp(-ln(100) g / c0), c0 = 0.01 mm, p0 = 1 MPa.
//! The load, 0.3 x 1 = 0.3 N, is carried by 3 nodes each bearing with the master face's area
//! 2 mm^2: p = 0.05 MPa, so the gap is g = c0 ln(p0 / p) / ln(100) = 0.006505 mm. (With the
//! slave face's own shares, areas summing to 1 mm^2, it would be p = 0.3 and g = 0.00261
//! mm.) The blocks (E = 210000) shorten by about 1e-6 mm, so the gap holds to 1e-3.

mod common;
use common::{run_deck_file, Results};

const DECK: &str = "*NODE, NSET=NALL
1, 0., 0.
2, 2., 0.
3, 2., 1.
4, 0., 1.
5, 1., 0.
6, 2., 0.5
7, 1., 1.
8, 0., 0.5
11, 0.5, 1.
12, 1.5, 1.
13, 1.5, 2.
14, 0.5, 2.
15, 1., 1.
16, 1.5, 1.5
17, 1., 2.
18, 0.5, 1.5
*ELEMENT, TYPE=CPE8, ELSET=LOWER
1, 1, 2, 3, 4, 5, 6, 7, 8
*ELEMENT, TYPE=CPE8, ELSET=UPPER
2, 11, 12, 13, 14, 15, 16, 17, 18
*ELSET, ELSET=EALL
LOWER, UPPER
*MATERIAL, NAME=STEEL
*ELASTIC
210000., 0.3
*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL
1.
*NSET, NSET=BOTTOM_SET
11, 12, 15
*SURFACE, NAME=BOTTOM, TYPE=NODE
BOTTOM_SET
*SURFACE, NAME=TOP
1, S3
*CONTACT PAIR, INTERACTION=SOFT, TYPE=NODE TO SURFACE
BOTTOM, TOP
*SURFACE INTERACTION, NAME=SOFT
*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=EXPONENTIAL
0.01, 1.
*BOUNDARY
1, 1, 2
2, 2, 2
5, 2, 2
4, 1, 1
8, 1, 1
11, 1, 1
14, 1, 1
18, 1, 1
*STEP
*STATIC
0.25, 1.
*DLOAD
2, P3, 0.3
*NODE PRINT, NSET=NALL
U
*END STEP
";

#[test]
fn each_node_of_a_node_based_slave_bears_with_the_master_face_area() {
    let run = run_deck_file("deck.inp", DECK, &[], 2, &[]);
    run.assert_ok();
    let u = Results::open(&run.h5).displacement_by_node_id();
    let expected = 0.01 * 20f64.ln() / 100f64.ln();
    // the gap over the lower block's top (node 7, its middle; the top stays flat to 1e-7 mm)
    for slave in [11, 15, 12] {
        let gap = u[&slave][1] - u[&7][1];
        assert!((gap / expected - 1.0).abs() < 1e-3, "node {slave}: gap {gap:.6e} mm against {expected:.6e}");
    }
}

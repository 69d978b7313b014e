//! CAX4 decks run as CalculiX runs them: slideline gives each CAX4 edge a mid-side node, and
//! that node joins every node set holding both ends of its edge, so a *BOUNDARY on a set holds
//! the whole edge as it holds CalculiX's straight edge.
//!
//! Case: a shrink fit of CAX4 rings, tube r 50..60.05 (5 x 4 elements) in a ring r 60..80
//! (6 x 4), z 0..10, both faces of both rings held axially (plane strain), matched interface
//! stations, surface-to-surface penalty 1e6. With the faces held whole, the fit is uniform
//! along z: the contact pressure is the same at every slave node (to 1e-4), and the nodes on
//! the held faces, added mid-side nodes included, do not move axially.
//!
//! ```text
//!   z=10 +--+--+--+--+--+ +---+---+---+---+---+---+
//!        | tube (CAX4)  | |  ring (CAX4)          |   both faces held (uz = 0)
//!   z=0  +--+--+--+--+--+ +---+---+---+---+---+---+
//!       r=50       60.05 60                       80
//! ```

mod common;
use common::{command_in, Results};

/// The deck: nodes of a (ni + 1) x (nj + 1) grid per ring, CAX4 elements, sets, one step.
fn shrink_fit_cax4() -> String {
    let mut nodes = String::from("*NODE\n");
    let mut elements = String::new();
    let (mut bottom, mut top) = (Vec::new(), Vec::new());
    let mut next_node = 1;
    let mut next_element = 1;
    let mut faces = [Vec::new(), Vec::new()];
    for (k, (r0, r1, ni)) in [(50.0, 60.05, 5usize), (60.0, 80.0, 6usize)].into_iter().enumerate() {
        let nj = 4;
        let id = |i: usize, j: usize| next_node + j * (ni + 1) + i;
        for j in 0..=nj {
            for i in 0..=ni {
                let (r, z) = (r0 + (r1 - r0) * i as f64 / ni as f64, 10.0 * j as f64 / nj as f64);
                nodes += &format!("{}, {r}, {z}\n", id(i, j));
                if j == 0 {
                    bottom.push(id(i, j));
                }
                if j == nj {
                    top.push(id(i, j));
                }
            }
        }
        elements += &format!("*ELEMENT, TYPE=CAX4, ELSET={}\n", ["TUBE", "RING"][k]);
        for j in 0..nj {
            for i in 0..ni {
                elements += &format!("{next_element}, {}, {}, {}, {}\n", id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                // the tube's outside (S2 of its last column), the ring's bore (S4 of its first)
                if k == 0 && i == ni - 1 {
                    faces[0].push(format!("{next_element}, S2"));
                }
                if k == 1 && i == 0 {
                    faces[1].push(format!("{next_element}, S4"));
                }
                next_element += 1;
            }
        }
        next_node += (ni + 1) * (nj + 1);
    }
    let list = |v: &[usize]| v.iter().map(|n| n.to_string()).collect::<Vec<_>>().join(", ");
    format!(
        "*HEADING\nCAX4 shrink fit\n{nodes}{elements}*NSET, NSET=FACES\n{}\n{}\n*SURFACE, NAME=TUBE_OUT, TYPE=ELEMENT\n{}\n*SURFACE, NAME=RING_IN, TYPE=ELEMENT\n{}\n\
*MATERIAL, NAME=STEEL\n*ELASTIC\n200000., 0.3\n*SOLID SECTION, ELSET=TUBE, MATERIAL=STEEL\n*SOLID SECTION, ELSET=RING, MATERIAL=STEEL\n\
*SURFACE INTERACTION, NAME=FIT\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n1.e6\n*CONTACT PAIR, INTERACTION=FIT, TYPE=SURFACE TO SURFACE\nRING_IN, TUBE_OUT\n\
*BOUNDARY\nFACES, 2, 2\n*STEP\n*STATIC\n*END STEP\n",
        list(&bottom),
        list(&top),
        faces[0].join("\n"),
        faces[1].join("\n")
    )
}

#[test]
fn a_cax4_shrink_fit_held_on_its_faces_is_uniform_and_its_faces_stay_put() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("fit.inp"), shrink_fit_cax4()).unwrap();
    let out = command_in(dir.path(), 1).current_dir(dir.path()).args(["run", "fit.inp", "-o", "fit.h5", "--quiet"]).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let res = Results::open(&dir.path().join("fit.h5"));
    // every node on z = 0 or z = 10, the added mid-side ones included, is held
    let mut held = 0;
    for (x, u) in res.nodes() {
        if x[1] == 0.0 || x[1] == 10.0 {
            assert!(u[1] == 0.0, "node at ({}, {}) moved axially by {}", x[0], x[1], u[1]);
            held += 1;
        }
    }
    assert_eq!(held, 2 * (2 * 5 + 1 + 2 * 6 + 1), "corner and mid-side nodes of both faces of both rings");
    let p = res.f64s("increments/000001/contact/RING_IN-TUBE_OUT/pass0/pressure");
    assert_eq!(p.len(), 2 * 4 + 1, "the ring's bore: 4 edges, 9 nodes");
    let mean = p.iter().sum::<f64>() / p.len() as f64;
    let spread = p.iter().map(|v| (v - mean).abs()).fold(0.0, f64::max);
    assert!(mean > 1.0, "the fit carries pressure: {mean}");
    assert!(spread <= 1e-4 * mean, "contact pressure {p:?} varies by {spread} about {mean}");
}

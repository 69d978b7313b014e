//! Shape functions of the two element shapes, the 8-node serendipity quadrilateral (Q8) and
//! the 6-node triangle (T6), and of the 3-node edge.
//!
//! Q8 node order (Gmsh type 16, VTK/XDMF Quadrilateral_8, Abaqus CAX8): corners 0..3
//! counter-clockwise at (-1,-1), (1,-1), (1,1), (-1,1), then mid-side nodes 4 (edge 0-1),
//! 5 (1-2), 6 (2-3), 7 (3-0). Edge `s` runs from corner s to corner (s+1)%4 through node 4+s.
//!
//! T6 node order (Gmsh type 9, VTK/XDMF Triangle_6, Abaqus CAX6): corners 0..2
//! counter-clockwise at (0,0), (1,0), (0,1), then mid-side nodes 3 (edge 0-1), 4 (1-2),
//! 5 (2-0). Edge `s` runs from corner s to corner (s+1)%3 through node 3+s.
//!
//! Both shapes live in the same 8 node slots, so that one element kernel with fixed-size
//! arrays serves both (the Q8's speed is what the bellows runs on): a T6's last two slots
//! repeat its first node and carry shape functions that are identically zero, so whatever they
//! gather is multiplied by zero and whatever they scatter is zero. `Shape::of` reads the shape
//! back from the slots; code that walks an element's nodes for anything but an interpolation
//! (counts, outlines, output) takes `Shape::nodes` of them.

use super::quadrature::{square_2x2, square_3x3, triangle_3, triangle_9, Integration};

/// An element's shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    Quad8,
    Tri6,
}

impl Shape {
    /// The shape of an element from its 8 node slots (a T6's slots 6 and 7 repeat slot 0).
    #[inline]
    pub fn of(slots: &[usize; 8]) -> Shape {
        if slots[6] == slots[0] {
            Shape::Tri6
        } else {
            Shape::Quad8
        }
    }

    /// The 8 slots of a T6 with nodes `nodes` (CAX6 order).
    pub fn tri6_slots(nodes: [usize; 6]) -> [usize; 8] {
        [nodes[0], nodes[1], nodes[2], nodes[3], nodes[4], nodes[5], nodes[0], nodes[0]]
    }

    /// Number of nodes: 8 or 6.
    pub const fn nodes(self) -> usize {
        match self {
            Shape::Quad8 => 8,
            Shape::Tri6 => 6,
        }
    }

    /// Number of corners (and sides): 4 or 3.
    pub const fn corners(self) -> usize {
        match self {
            Shape::Quad8 => 4,
            Shape::Tri6 => 3,
        }
    }

    /// Local node numbers (start, end, middle) of side `side`, in the element's
    /// counter-clockwise direction.
    pub const fn edge_nodes(self, side: usize) -> [usize; 3] {
        let c = self.corners();
        [side, (side + 1) % c, c + side]
    }

    /// Shape functions and their derivatives d/d(xi, eta) at `p`, zero in a T6's unused slots.
    #[inline]
    pub fn functions(self, p: [f64; 2]) -> ([f64; 8], [[f64; 2]; 8]) {
        match self {
            Shape::Quad8 => q8(p),
            Shape::Tri6 => t6(p),
        }
    }

    /// Reference coordinates of the nodes (a T6's unused slots at its first node's).
    pub fn reference_nodes(self) -> [[f64; 2]; 8] {
        match self {
            Shape::Quad8 => q8_nodes(),
            Shape::Tri6 => {
                let n = T6_NODES;
                [n[0], n[1], n[2], n[3], n[4], n[5], n[0], n[0]]
            }
        }
    }

    /// The 9-point integration rule: ((xi, eta), weight). Both integrate the element fully
    /// (the Q8's 3 x 3 Gauss rule; the T6's conical product rule, exact to degree 5).
    pub fn rule(self) -> [([f64; 2], f64); 9] {
        match self {
            Shape::Quad8 => square_3x3(),
            Shape::Tri6 => triangle_9(),
        }
    }

    /// The rule of an element of this shape integrated as `integration`: the full rule, or
    /// the reduced one in the first of the 9 slots (a Q8's 2 x 2 points, a T6's 3).
    pub fn rule_for(self, integration: Integration) -> [([f64; 2], f64); 9] {
        match (self, integration) {
            (_, Integration::Full) => self.rule(),
            (Shape::Quad8, Integration::Reduced) => square_2x2(),
            (Shape::Tri6, Integration::Reduced) => triangle_3(),
        }
    }

    /// How many of the 9 Gauss slots of an element of this shape integrated as
    /// `integration` are integration points: 9, a reduced Q8's 4, a reduced T6's 3.
    pub const fn points(self, integration: Integration) -> usize {
        match (self, integration) {
            (_, Integration::Full) => 9,
            (Shape::Quad8, Integration::Reduced) => 4,
            (Shape::Tri6, Integration::Reduced) => 3,
        }
    }

    /// The local nodes around the element's outline, corner, mid-side, corner, ...
    pub const fn outline(self) -> &'static [usize] {
        match self {
            Shape::Quad8 => &[0, 4, 1, 5, 2, 6, 3, 7],
            Shape::Tri6 => &[0, 3, 1, 4, 2, 5],
        }
    }

    /// Whether reference point `p` lies in the element, up to `slack` (in reference units).
    pub fn contains(self, p: [f64; 2], slack: f64) -> bool {
        match self {
            Shape::Quad8 => p[0].abs() <= 1.0 + slack && p[1].abs() <= 1.0 + slack,
            Shape::Tri6 => p[0] >= -slack && p[1] >= -slack && p[0] + p[1] <= 1.0 + slack,
        }
    }

    /// The reference point at the element's centre.
    pub fn centre(self) -> [f64; 2] {
        match self {
            Shape::Quad8 => [0.0, 0.0],
            Shape::Tri6 => [1.0 / 3.0, 1.0 / 3.0],
        }
    }
}

/// Reference coordinates of the six T6 nodes.
pub const T6_NODES: [[f64; 2]; 6] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 0.0], [0.5, 0.5], [0.0, 0.5]];

/// T6 shape functions and their derivatives at `p = (xi, eta)`, in 8 slots (the last two zero):
/// with the area coordinates L0 = 1 - xi - eta, L1 = xi, L2 = eta, a corner's is
/// L_i (2 L_i - 1), a mid-side node's 4 L_i L_j.
pub fn t6(p: [f64; 2]) -> ([f64; 8], [[f64; 2]; 8]) {
    let [x, y] = p;
    let l = [1.0 - x - y, x, y];
    // dL_i / d(xi, eta)
    let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
    let mut n = [0.0; 8];
    let mut d = [[0.0; 2]; 8];
    for i in 0..3 {
        n[i] = l[i] * (2.0 * l[i] - 1.0);
        d[i] = dl[i].map(|g| g * (4.0 * l[i] - 1.0));
        let j = (i + 1) % 3;
        n[3 + i] = 4.0 * l[i] * l[j];
        d[3 + i] = [0, 1].map(|k| 4.0 * (dl[i][k] * l[j] + l[i] * dl[j][k]));
    }
    (n, d)
}

pub const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Q8 shape functions N_a and their derivatives dN_a/d(xi, eta) at `p = (xi, eta)`.
pub fn q8(p: [f64; 2]) -> ([f64; 8], [[f64; 2]; 8]) {
    let [x, y] = p;
    let mut n = [0.0; 8];
    let mut d = [[0.0; 2]; 8];
    for (a, &[xa, ya]) in CORNERS.iter().enumerate() {
        let (fx, fy) = (1.0 + xa * x, 1.0 + ya * y);
        let s = xa * x + ya * y - 1.0;
        n[a] = 0.25 * fx * fy * s;
        d[a] = [0.25 * xa * fy * (s + fx), 0.25 * ya * fx * (s + fy)];
    }
    // mid-side nodes on xi = 0 (4 at eta=-1, 6 at eta=+1) and eta = 0 (5 at xi=+1, 7 at xi=-1)
    for (a, ya) in [(4, -1.0), (6, 1.0)] {
        n[a] = 0.5 * (1.0 - x * x) * (1.0 + ya * y);
        d[a] = [-x * (1.0 + ya * y), 0.5 * ya * (1.0 - x * x)];
    }
    for (a, xa) in [(5, 1.0), (7, -1.0)] {
        n[a] = 0.5 * (1.0 + xa * x) * (1.0 - y * y);
        d[a] = [0.5 * xa * (1.0 - y * y), -y * (1.0 + xa * x)];
    }
    (n, d)
}

/// Quadratic 1D shape functions on [-1, 1] for nodes at -1 (start), +1 (end), 0 (middle),
/// and their derivatives.
pub fn line3(s: f64) -> ([f64; 3], [f64; 3]) {
    ([0.5 * s * (s - 1.0), 0.5 * s * (s + 1.0), 1.0 - s * s], [s - 0.5, s + 0.5, -2.0 * s])
}

/// Reference coordinates of the eight Q8 nodes.
pub const fn q8_nodes() -> [[f64; 2]; 8] {
    [CORNERS[0], CORNERS[1], CORNERS[2], CORNERS[3], [0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q8_is_interpolatory_and_a_partition_of_unity() {
        for (b, &pb) in q8_nodes().iter().enumerate() {
            let (n, _) = q8(pb);
            for (a, &na) in n.iter().enumerate() {
                assert!((na - if a == b { 1.0 } else { 0.0 }).abs() < 1e-14, "N_{a} at node {b} = {na}");
            }
        }
        let (n, d) = q8([0.3, -0.7]);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        assert!(d.iter().map(|g| g[0]).sum::<f64>().abs() < 1e-14);
        assert!(d.iter().map(|g| g[1]).sum::<f64>().abs() < 1e-14);
    }

    #[test]
    fn q8_derivatives_match_finite_differences() {
        let p = [0.37, -0.21];
        let h = 1e-6;
        let (_, d) = q8(p);
        for k in 0..2 {
            let (mut pp, mut pm) = (p, p);
            pp[k] += h;
            pm[k] -= h;
            let (np, _) = q8(pp);
            let (nm, _) = q8(pm);
            for a in 0..8 {
                let fd = (np[a] - nm[a]) / (2.0 * h);
                assert!((fd - d[a][k]).abs() < 1e-9, "dN{a}/dxi{k}: {fd} vs {}", d[a][k]);
            }
        }
    }

    #[test]
    fn line3_matches_q8_on_an_edge() {
        // On edge 0 (eta = -1), the Q8 functions of its nodes equal the line3 ones.
        for s in [-0.8, -0.1, 0.45] {
            let (n, _) = q8([s, -1.0]);
            let (l, _) = line3(s);
            let e = Shape::Quad8.edge_nodes(0);
            for k in 0..3 {
                assert!((n[e[k]] - l[k]).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn t6_is_interpolatory_a_partition_of_unity_and_matches_line3_on_its_edges() {
        let shape = Shape::Tri6;
        let nodes = shape.reference_nodes();
        for b in 0..6 {
            let (n, _) = t6(nodes[b]);
            for (a, &na) in n.iter().enumerate() {
                assert!((na - if a == b { 1.0 } else { 0.0 }).abs() < 1e-14, "N_{a} at node {b} = {na}");
            }
        }
        let (n, d) = t6([0.23, 0.41]);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        assert!(n[6] == 0.0 && n[7] == 0.0 && d[6] == [0.0; 2] && d[7] == [0.0; 2]);
        assert!(d.iter().map(|g| g[0]).sum::<f64>().abs() < 1e-14 && d.iter().map(|g| g[1]).sum::<f64>().abs() < 1e-14);
        // along each side, from its start corner (s = -1) to its end (s = +1), the side's three
        // functions are line3's and the third corner's is zero
        for side in 0..3 {
            let e = shape.edge_nodes(side);
            let (a, b) = (nodes[e[0]], nodes[e[1]]);
            for s in [-0.8, -0.1, 0.45] {
                let t = 0.5 * (s + 1.0);
                let (n, _) = t6([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
                let (l, _) = line3(s);
                for k in 0..3 {
                    assert!((n[e[k]] - l[k]).abs() < 1e-14, "side {side} s {s} node {k}");
                }
                assert!(n[(side + 2) % 3].abs() < 1e-14);
            }
        }
    }

    #[test]
    fn t6_derivatives_match_finite_differences() {
        let p = [0.21, 0.37];
        let h = 1e-6;
        let (_, d) = t6(p);
        for k in 0..2 {
            let (mut pp, mut pm) = (p, p);
            pp[k] += h;
            pm[k] -= h;
            let (np, _) = t6(pp);
            let (nm, _) = t6(pm);
            for a in 0..8 {
                let fd = (np[a] - nm[a]) / (2.0 * h);
                assert!((fd - d[a][k]).abs() < 1e-9, "dN{a}/dxi{k}: {fd} vs {}", d[a][k]);
            }
        }
    }

    #[test]
    fn the_shape_is_read_back_from_the_slots() {
        assert_eq!(Shape::of(&[0, 1, 2, 3, 4, 5, 6, 7]), Shape::Quad8);
        let t = Shape::tri6_slots([4, 9, 2, 7, 5, 3]);
        assert_eq!(Shape::of(&t), Shape::Tri6);
        assert_eq!(Shape::Tri6.edge_nodes(2), [2, 0, 5]);
        assert_eq!(Shape::Quad8.edge_nodes(3), [3, 0, 7]);
    }
}

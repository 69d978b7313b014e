//! Gauss-point values carried to the nodes for plots, the rule ANSYS applies by default
//! (its ERESX command, key DEFA): in an element that is wholly elastic, the 3 x 3 values are
//! fitted by the biquadratic Lagrange polynomial through the Gauss points and evaluated at the
//! Q8's nodes (a linear or quadratic stress comes back exactly; a T6's 9 values are fitted by
//! the complete quadratic in least squares, which also returns a quadratic exactly; a reduced
//! Q8's 2 x 2 values by the bilinear field through them); in an
//! element with plastic
//! strain anywhere, each node takes the value of its nearest Gauss point (copied). Plastic
//! quantities (the equivalent plastic strain, the plastic strain tensor) are always copied.
//!
//! Why not extrapolate everywhere, as CalculiX does: through a yielded ply the stress is a
//! saturating profile, and the parabola through its three Gauss values overshoots at the
//! surface (on the quick bellows the nodal von Mises reached +85 % of the Gauss maximum, and
//! extrapolated plastic strain went below zero). Copying keeps every nodal value inside the
//! range of the Gauss values around it.
//!
//! A node's value is then the mean over the elements around it, component by component;
//! invariants (von Mises, pressure, principal stresses) are computed afterwards from the
//! averaged components (`io::nodal`), never averaged as scalars, so they keep their sign.

use super::quadrature::{square_3x3, Integration, GAUSS2, GAUSS3};
use super::shape::{q8_nodes, Shape};
use nalgebra::{SMatrix, SVector};

/// How an element's Gauss values reach its nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rule {
    /// The biquadratic fit through the 9 Gauss points, evaluated at the node.
    Extrapolate,
    /// The value of the Gauss point nearest the node.
    Copy,
}

impl Rule {
    /// The rule for an element's stress and total strain: copied where any of its Gauss points
    /// has yielded (`plastic_strain` > 0), extrapolated where all are elastic.
    pub fn for_element(plastic_strain: &[f64; 9]) -> Rule {
        if plastic_strain.iter().any(|&ep| ep > 0.0) {
            Rule::Copy
        } else {
            Rule::Extrapolate
        }
    }
}

/// Weight of Gauss point `q` (the order of `square_3x3`) in the extrapolated value at node `a`.
fn weight(a: usize, q: usize) -> f64 {
    let points = GAUSS3.map(|g| g.0);
    // 1D Lagrange basis through the three Gauss abscissae, at x
    let lagrange = |k: usize, x: f64| -> f64 { (0..3).filter(|&m| m != k).map(|m| (x - points[m]) / (points[k] - points[m])).product() };
    let [xi, eta] = q8_nodes()[a];
    lagrange(q % 3, xi) * lagrange(q / 3, eta)
}

/// The 8 x 9 extrapolation matrix of a shape integrated as `integration`: row a gives node
/// a's value from the 9 Gauss slots (a T6's unused slots take its first node's row; a reduced
/// Q8's weightless slots have zero columns).
pub fn gauss_to_nodes(shape: Shape, integration: Integration) -> [[f64; 9]; 8] {
    match (shape, integration) {
        (Shape::Quad8, Integration::Reduced) => {
            // the bilinear field through the 2 x 2 points, at the node (x = +-1 lies at
            // +-sqrt(3) in the points' own coordinates)
            let lagrange = |k: usize, x: f64| 0.5 * (1.0 + (if k == 0 { -x } else { x }) / GAUSS2);
            std::array::from_fn(|a| {
                let [xi, eta] = q8_nodes()[a];
                std::array::from_fn(|q| if q < 4 { lagrange(q % 2, xi) * lagrange(q / 2, eta) } else { 0.0 })
            })
        }
        (Shape::Quad8, Integration::Full) => {
            debug_assert_eq!(square_3x3()[1].0, [GAUSS3[1].0, GAUSS3[0].0], "square_3x3 runs over xi first");
            std::array::from_fn(|a| std::array::from_fn(|q| weight(a, q)))
        }
        (Shape::Tri6, Integration::Reduced) => {
            // the linear field through the 3 points: in area coordinates, each point's value
            // weighs by the linear function that is 1 there and 0 at the other two
            let rule = Shape::Tri6.rule_for(Integration::Reduced);
            let m = nalgebra::Matrix3::from_fn(|q, k| [1.0, rule[q].0[0], rule[q].0[1]][k]);
            let inverse = m.try_inverse().unwrap_or_else(nalgebra::Matrix3::zeros);
            let nodes = Shape::Tri6.reference_nodes();
            std::array::from_fn(|n| {
                let row = nalgebra::RowVector3::new(1.0, nodes[n][0], nodes[n][1]) * inverse;
                std::array::from_fn(|q| if q < 3 { row[q] } else { 0.0 })
            })
        }
        (Shape::Tri6, Integration::Full) => {
            // least-squares fit of {1, xi, eta, xi^2, xi eta, eta^2} to the 9 values
            let monomials = |p: [f64; 2]| SVector::<f64, 6>::from([1.0, p[0], p[1], p[0] * p[0], p[0] * p[1], p[1] * p[1]]);
            let rule = Shape::Tri6.rule();
            let a = SMatrix::<f64, 9, 6>::from_fn(|q, k| monomials(rule[q].0)[k]);
            // the normal matrix of 9 interior points is well conditioned (a fixed rule)
            let fit = (a.transpose() * a).try_inverse().unwrap_or_else(SMatrix::zeros) * a.transpose();
            let nodes = Shape::Tri6.reference_nodes();
            std::array::from_fn(|n| {
                let row = monomials(nodes[n]).transpose() * fit;
                std::array::from_fn(|q| row[q])
            })
        }
    }
}

/// The copying matrix: row a gives node a the value of its nearest Gauss point, or the mean
/// of the points equally near it (a reduced Q8's mid-side node lies between two). For a full
/// Q8 a corner's is the corner point of the 3 x 3 grid, a mid-side node's the point at the
/// middle of that side.
pub fn nearest_gauss_points(shape: Shape, integration: Integration) -> [[f64; 9]; 8] {
    let (points, nodes) = (shape.rule_for(integration), shape.reference_nodes());
    let used = shape.points(integration);
    let distance = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    std::array::from_fn(|a| {
        let nearest = (0..used).map(|q| distance(nodes[a], points[q].0)).fold(f64::INFINITY, f64::min);
        let tied: Vec<usize> = (0..used).filter(|&q| distance(nodes[a], points[q].0) <= nearest * (1.0 + 1e-12)).collect();
        std::array::from_fn(|q| if tied.contains(&q) { 1.0 / tied.len() as f64 } else { 0.0 })
    })
}

/// The element kinds, in the order of [`Recovery`]'s tables.
const KINDS: [(Shape, Integration); 4] =
    [(Shape::Quad8, Integration::Full), (Shape::Tri6, Integration::Full), (Shape::Quad8, Integration::Reduced), (Shape::Tri6, Integration::Reduced)];

/// Carries Gauss values to an element's nodes, for each element kind.
#[derive(Clone, Debug)]
pub struct Recovery {
    extrapolate: [[[f64; 9]; 8]; 4],
    copy: [[[f64; 9]; 8]; 4],
}

impl Default for Recovery {
    fn default() -> Self {
        Recovery { extrapolate: KINDS.map(|(s, i)| gauss_to_nodes(s, i)), copy: KINDS.map(|(s, i)| nearest_gauss_points(s, i)) }
    }
}

impl Recovery {
    /// The values at the 8 node slots of an element of shape `shape` integrated as
    /// `integration` (a T6's unused slots repeat its first node's) of the `C` quantities given
    /// at its Gauss slots (a reduced element's weightless ones are not read).
    pub fn element_nodal<const C: usize>(&self, shape: Shape, integration: Integration, rule: Rule, gauss: &[[f64; C]; 9]) -> [[f64; C]; 8] {
        let k = KINDS.iter().position(|&kind| kind == (shape, integration)).unwrap_or(0);
        let m = match rule {
            Rule::Extrapolate => &self.extrapolate[k],
            Rule::Copy => &self.copy[k],
        };
        // zero weights skip their slots outright, so that a NaN there cannot leak in
        std::array::from_fn(|a| std::array::from_fn(|c| (0..9).filter(|&q| m[a][q] != 0.0).map(|q| m[a][q] * gauss[q][c]).sum()))
    }

    /// Adds an element's nodal values (`nodal[a][c]` for its node slots `nodes`) into `sums`
    /// (node-major, `C` per node) and 1 per node into `counts`.
    pub fn accumulate<const C: usize>(nodes: &[usize; 8], nodal: &[[f64; C]; 8], sums: &mut [f64], counts: &mut [f64]) {
        for (a, &n) in nodes.iter().enumerate().take(Shape::of(nodes).nodes()) {
            for c in 0..C {
                sums[n * C + c] += nodal[a][c];
            }
            counts[n] += 1.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::quadrature::square_2x2;

    #[test]
    fn a_biquadratic_field_is_carried_to_the_nodes_exactly() {
        let f = |p: [f64; 2]| 3.0 + 2.0 * p[0] - p[1] + 0.5 * p[0] * p[1] + 0.25 * p[0] * p[0] - 0.75 * p[1] * p[1] + 0.1 * p[0] * p[0] * p[1] * p[1];
        let m = gauss_to_nodes(Shape::Quad8, Integration::Full);
        let gauss = square_3x3().map(|(p, _)| f(p));
        for (a, node) in q8_nodes().iter().enumerate() {
            let value: f64 = (0..9).map(|q| m[a][q] * gauss[q]).sum();
            assert!((value - f(*node)).abs() < 1e-12, "node {a}: {value} vs {}", f(*node));
        }
        // each row sums to 1: a constant stays constant
        assert!(m.iter().all(|row| (row.iter().sum::<f64>() - 1.0).abs() < 1e-14));
    }

    #[test]
    fn copying_takes_each_nodes_nearest_gauss_point() {
        // q = i + 3 j with i along xi, j along eta, both from -sqrt(0.6) up
        let one = |q: usize| -> [f64; 9] { std::array::from_fn(|p| if p == q { 1.0 } else { 0.0 }) };
        assert_eq!(nearest_gauss_points(Shape::Quad8, Integration::Full), [0, 2, 8, 6, 1, 5, 7, 3].map(one));
        let gauss: [[f64; 1]; 9] = std::array::from_fn(|q| [q as f64]);
        let nodal = Recovery::default().element_nodal(Shape::Quad8, Integration::Full, Rule::Copy, &gauss);
        assert_eq!(nodal.map(|v| v[0]), [0.0, 2.0, 8.0, 6.0, 1.0, 5.0, 7.0, 3.0]);
    }

    #[test]
    fn a_saturated_plastic_profile_is_not_overshot_when_copied() {
        // through a yielded ply (xi across it) the stress saturates: -320, 0, 320 at the Gauss
        // points of a linear-elastic core with a yielded surface; extrapolated, the surface
        // value is 320 / sqrt(0.6) = 413; copied, 320
        let s = [-320.0, 0.0, 320.0];
        let gauss: [[f64; 1]; 9] = std::array::from_fn(|q| [s[q % 3]]);
        let plastic: [f64; 9] = std::array::from_fn(|q| if q % 3 == 1 { 0.0 } else { 0.01 });
        assert_eq!(Rule::for_element(&plastic), Rule::Copy);
        assert_eq!(Rule::for_element(&[0.0; 9]), Rule::Extrapolate);
        let r = Recovery::default();
        let extrapolated = r.element_nodal(Shape::Quad8, Integration::Full, Rule::Extrapolate, &gauss);
        assert!((extrapolated[1][0] - 320.0 / 0.6f64.sqrt()).abs() < 1e-9);
        let copied = r.element_nodal(Shape::Quad8, Integration::Full, Rule::Copy, &gauss);
        assert_eq!(copied[1][0], 320.0);
        assert!(copied.iter().all(|v| v[0].abs() <= 320.0));
    }

    #[test]
    fn a_quadratic_field_is_carried_to_a_triangles_nodes_exactly_and_its_spare_slots_repeat_node_0() {
        let f = |p: [f64; 2]| 3.0 + 2.0 * p[0] - p[1] + 0.5 * p[0] * p[1] + 0.25 * p[0] * p[0] - 0.75 * p[1] * p[1];
        let gauss: [[f64; 1]; 9] = Shape::Tri6.rule().map(|(p, _)| [f(p)]);
        let nodal = Recovery::default().element_nodal(Shape::Tri6, Integration::Full, Rule::Extrapolate, &gauss);
        for (a, node) in Shape::Tri6.reference_nodes().iter().enumerate() {
            assert!((nodal[a][0] - f(*node)).abs() < 1e-12, "node {a}: {} vs {}", nodal[a][0], f(*node));
        }
        // copying: each corner takes a point near it, and the spare slots are node 0's
        let copied = Recovery::default().element_nodal(Shape::Tri6, Integration::Full, Rule::Copy, &std::array::from_fn(|q| [q as f64]));
        let nearest = nearest_gauss_points(Shape::Tri6, Integration::Full).map(|row| row.iter().position(|&w| w == 1.0).unwrap());
        assert_eq!(copied.map(|v| v[0] as usize), nearest);
        assert_eq!((nearest[6], nearest[7]), (nearest[0], nearest[0]));
        // its corner 0 at (0, 0) is nearest the rule's first point (small s, small t)
        assert_eq!(nearest[0], 0);
        // a T6 adds to its six nodes only
        let (mut sums, mut counts) = (vec![0.0; 7], vec![0.0; 7]);
        Recovery::accumulate(&Shape::tri6_slots([1, 2, 3, 4, 5, 6]), &[[1.0]; 8], &mut sums, &mut counts);
        assert_eq!(counts, [0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0]);
    }

    #[test]
    fn a_reduced_quadrilateral_carries_a_bilinear_field_exactly_and_never_reads_its_weightless_slots() {
        let f = |p: [f64; 2]| 3.0 + 2.0 * p[0] - p[1] + 0.5 * p[0] * p[1];
        let mut gauss: [[f64; 1]; 9] = square_2x2().map(|(p, _)| [f(p)]);
        for slot in &mut gauss[4..] {
            *slot = [f64::NAN];
        }
        let r = Recovery::default();
        let nodal = r.element_nodal(Shape::Quad8, Integration::Reduced, Rule::Extrapolate, &gauss);
        for (a, node) in q8_nodes().iter().enumerate() {
            assert!((nodal[a][0] - f(*node)).abs() < 1e-12, "node {a}: {} vs {}", nodal[a][0], f(*node));
        }
        // copied: a corner takes its own point, a mid-side node the mean of the two beside it
        let gauss: [[f64; 1]; 9] = std::array::from_fn(|q| if q < 4 { [q as f64] } else { [f64::NAN] });
        let copied = r.element_nodal(Shape::Quad8, Integration::Reduced, Rule::Copy, &gauss);
        assert_eq!(copied.map(|v| v[0]), [0.0, 1.0, 3.0, 2.0, 0.5, 2.0, 2.5, 1.0]);
    }

    #[test]
    fn a_three_point_triangle_carries_a_linear_field_exactly() {
        let f = |p: [f64; 2]| 3.0 + 2.0 * p[0] - 5.0 * p[1];
        let rule = Shape::Tri6.rule_for(Integration::Reduced);
        let gauss: [[f64; 1]; 9] = std::array::from_fn(|q| if q < 3 { [f(rule[q].0)] } else { [f64::NAN] });
        let r = Recovery::default();
        let nodal = r.element_nodal(Shape::Tri6, Integration::Reduced, Rule::Extrapolate, &gauss);
        for (a, node) in Shape::Tri6.reference_nodes().iter().enumerate() {
            assert!((nodal[a][0] - f(*node)).abs() < 1e-12, "node {a}: {} vs {}", nodal[a][0], f(*node));
        }
        // copied: corners their own point, mid-side nodes 3 and 5 the point beside them, node
        // 4 (between points 1 and 2) their mean
        let copied = r.element_nodal(Shape::Tri6, Integration::Reduced, Rule::Copy, &std::array::from_fn(|q| if q < 3 { [q as f64] } else { [f64::NAN] }));
        assert_eq!(copied.map(|v| v[0])[..6], [0.0, 1.0, 2.0, 1.0, 1.5, 2.0]);
    }

    #[test]
    fn nodes_shared_by_elements_are_averaged() {
        // two elements sharing nodes 1, 2, 5: constant 1 in one, 3 in the other
        let conn = [[0, 1, 2, 3, 4, 5, 6, 7], [1, 8, 9, 2, 10, 11, 12, 5]];
        let values = [[[1.0]; 9], [[3.0]; 9]];
        let (mut sums, mut counts) = (vec![0.0; 13], vec![0.0; 13]);
        let r = Recovery::default();
        for (nodes, gauss) in conn.iter().zip(&values) {
            Recovery::accumulate(nodes, &r.element_nodal(Shape::Quad8, Integration::Full, Rule::Extrapolate, gauss), &mut sums, &mut counts);
        }
        let mean = |n: usize| sums[n] / counts[n];
        assert!((mean(0) - 1.0).abs() < 1e-12 && (mean(8) - 3.0).abs() < 1e-12);
        assert!((mean(1) - 2.0).abs() < 1e-12 && (mean(5) - 2.0).abs() < 1e-12 && (mean(2) - 2.0).abs() < 1e-12);
    }
}

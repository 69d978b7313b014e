//! Gauss-point values carried to the nodes, as CalculiX and Abaqus do for plots: the 3 x 3
//! values are fitted by the biquadratic Lagrange polynomial through the Gauss points, which is
//! evaluated at the Q8's nodes; a node's value is then the mean over the elements around it.
//! A field that is biquadratic over the element (so any linear or quadratic stress) comes back
//! exactly.

use super::quadrature::{square_3x3, GAUSS3};
use super::shape::CORNERS;

/// Natural coordinates of the Q8 nodes (corners, then mid-sides), the order of `fe::shape`.
const NODES: [[f64; 2]; 8] = [CORNERS[0], CORNERS[1], CORNERS[2], CORNERS[3], [0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];

/// Weight of Gauss point `q` (the order of `square_3x3`) in the value at node `a`.
fn weight(a: usize, q: usize) -> f64 {
    let points = GAUSS3.map(|g| g.0);
    // 1D Lagrange basis through the three Gauss abscissae, at x
    let lagrange = |k: usize, x: f64| -> f64 { (0..3).filter(|&m| m != k).map(|m| (x - points[m]) / (points[k] - points[m])).product() };
    let [xi, eta] = NODES[a];
    lagrange(q % 3, xi) * lagrange(q / 3, eta)
}

/// The 8 x 9 extrapolation matrix: row a gives node a's value from the 9 Gauss values.
pub fn gauss_to_nodes() -> [[f64; 9]; 8] {
    debug_assert_eq!(square_3x3()[1].0, [GAUSS3[1].0, GAUSS3[0].0], "square_3x3 runs over xi first");
    std::array::from_fn(|a| std::array::from_fn(|q| weight(a, q)))
}

/// Adds each element's extrapolated nodal values of `components` quantities into `sums`
/// (node-major, `components` per node) and 1 per element into `counts`, for the elements
/// `elements` with connectivity `conn` and Gauss values `values[e][q][c]`.
pub fn accumulate_nodal<const C: usize>(matrix: &[[f64; 9]; 8], conn: &[[usize; 8]], values: &[[[f64; C]; 9]], sums: &mut [f64], counts: &mut [f64]) {
    for (nodes, gauss) in conn.iter().zip(values) {
        for (a, &n) in nodes.iter().enumerate() {
            for c in 0..C {
                sums[n * C + c] += (0..9).map(|q| matrix[a][q] * gauss[q][c]).sum::<f64>();
            }
            counts[n] += 1.0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_biquadratic_field_is_carried_to_the_nodes_exactly() {
        let f = |p: [f64; 2]| 3.0 + 2.0 * p[0] - p[1] + 0.5 * p[0] * p[1] + 0.25 * p[0] * p[0] - 0.75 * p[1] * p[1] + 0.1 * p[0] * p[0] * p[1] * p[1];
        let m = gauss_to_nodes();
        let gauss = square_3x3().map(|(p, _)| f(p));
        for (a, node) in NODES.iter().enumerate() {
            let value: f64 = (0..9).map(|q| m[a][q] * gauss[q]).sum();
            assert!((value - f(*node)).abs() < 1e-12, "node {a}: {value} vs {}", f(*node));
        }
        // each row sums to 1: a constant stays constant
        assert!(m.iter().all(|row| (row.iter().sum::<f64>() - 1.0).abs() < 1e-14));
    }

    #[test]
    fn nodes_shared_by_elements_are_averaged() {
        // two elements sharing nodes 1, 2, 5: constant 1 in one, 3 in the other
        let conn = [[0, 1, 2, 3, 4, 5, 6, 7], [1, 8, 9, 2, 10, 11, 12, 5]];
        let values = [[[1.0]; 9], [[3.0]; 9]];
        let (mut sums, mut counts) = (vec![0.0; 13], vec![0.0; 13]);
        accumulate_nodal(&gauss_to_nodes(), &conn, &values, &mut sums, &mut counts);
        let mean = |n: usize| sums[n] / counts[n];
        assert!((mean(0) - 1.0).abs() < 1e-12 && (mean(8) - 3.0).abs() < 1e-12);
        assert!((mean(1) - 2.0).abs() < 1e-12 && (mean(5) - 2.0).abs() < 1e-12 && (mean(2) - 2.0).abs() < 1e-12);
    }
}

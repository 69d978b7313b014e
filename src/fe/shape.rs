//! Shape functions of the 8-node serendipity quadrilateral (Q8) and the 3-node edge.
//!
//! Node order (Gmsh type 16, VTK/XDMF Quadrilateral_8, Abaqus CAX8): corners 0..3
//! counter-clockwise at (-1,-1), (1,-1), (1,1), (-1,1), then mid-side nodes 4 (edge 0-1),
//! 5 (1-2), 6 (2-3), 7 (3-0). Edge `s` runs from corner s to corner (s+1)%4 through node 4+s.

pub const CORNERS: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Local node numbers (start, end, middle) of edge `side` of a Q8, in the element's
/// counter-clockwise direction.
pub const fn edge_nodes(side: usize) -> [usize; 3] {
    [side, (side + 1) % 4, 4 + side]
}

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
pub fn q8_nodes() -> [[f64; 2]; 8] {
    let mut out = [[0.0; 2]; 8];
    out[..4].copy_from_slice(&CORNERS);
    out[4] = [0.0, -1.0];
    out[5] = [1.0, 0.0];
    out[6] = [0.0, 1.0];
    out[7] = [-1.0, 0.0];
    out
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
            let e = edge_nodes(0);
            for k in 0..3 {
                assert!((n[e[k]] - l[k]).abs() < 1e-14);
            }
        }
    }
}

//! Contact surfaces: a model surface (quadratic element edges) seen as a polyline of straight
//! segments through all its nodes, each edge giving two segments (start -> middle -> end) in
//! the owning element's counter-clockwise direction, so every segment's outward normal is its
//! tangent turned clockwise.
//!
//! Each node carries its consistent axisymmetric tributary area per radian,
//! A_a = sum over its edges of integral N_a r ds (quadratic edge shape functions, reference
//! configuration): the nodal force of a unit pressure. Near the axis this is what makes the
//! contact force right: r_a times half the adjacent lengths would be zero at r = 0 and wrong
//! next to it. (A corner node on the axis does get zero area: the integral of N_a r vanishes
//! there, as it does for a pressure load.)

use crate::fe::quadrature::GAUSS3;
use crate::fe::shape::line3;
use crate::model::{Edge, Mesh};

#[derive(Clone, Debug)]
pub struct ContactSurface {
    /// Mesh nodes of the surface, sorted.
    pub nodes: Vec<usize>,
    /// Tributary area per radian of each node (same order as `nodes`).
    pub areas: Vec<f64>,
    /// Segments as (start, end) mesh nodes, counter-clockwise around their element.
    pub segments: Vec<[usize; 2]>,
    /// Length of the element edge each segment belongs to (the master element size h).
    pub edge_length: Vec<f64>,
    /// Element each segment belongs to.
    pub element: Vec<usize>,
    /// For each segment, the segments sharing its start and its end node (None at a chain end).
    pub neighbours: Vec<[Option<usize>; 2]>,
}

impl ContactSurface {
    pub fn new(mesh: &Mesh, edges: &[Edge]) -> Self {
        let mut nodes: Vec<usize> = edges.iter().flat_map(|&e| mesh.edge_nodes(e)).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let mut areas = vec![0.0; nodes.len()];
        let mut segments = Vec::with_capacity(2 * edges.len());
        let mut edge_length = Vec::with_capacity(2 * edges.len());
        let mut element = Vec::with_capacity(2 * edges.len());
        for &edge in edges {
            let [start, end, mid] = mesh.edge_nodes(edge);
            let x = [start, end, mid].map(|n| mesh.coords[n]);
            let mut length = 0.0;
            for &(s, w) in &GAUSS3 {
                let (n, dn) = line3(s);
                let r: f64 = (0..3).map(|a| n[a] * x[a][0]).sum();
                let t = [0, 1].map(|i| (0..3).map(|a| dn[a] * x[a][i]).sum::<f64>());
                let jac = t[0].hypot(t[1]);
                length += w * jac;
                for (a, node) in [start, end, mid].iter().enumerate() {
                    let k = nodes.binary_search(node).expect("edge node is a surface node");
                    areas[k] += w * n[a] * r * jac;
                }
            }
            for seg in [[start, mid], [mid, end]] {
                segments.push(seg);
                edge_length.push(length);
                element.push(edge.element);
            }
        }
        let neighbours = (0..segments.len())
            .map(|s| {
                let [a, b] = segments[s];
                let find = |node: usize, end: usize| (0..segments.len()).find(|&o| o != s && segments[o][end] == node);
                [find(a, 1), find(b, 0)]
            })
            .collect();
        ContactSurface { nodes, areas, segments, edge_length, element, neighbours }
    }

    /// Index of mesh node `node` in `nodes`.
    pub fn index_of(&self, node: usize) -> Option<usize> {
        self.nodes.binary_search(&node).ok()
    }

    /// Segments within `hops` segments of `node` along the surface (for self-contact: a node
    /// never contacts its own neighbourhood).
    pub fn neighbourhood(&self, node: usize, hops: usize) -> Vec<usize> {
        let mut near: Vec<usize> = (0..self.segments.len()).filter(|&s| self.segments[s].contains(&node)).collect();
        for _ in 1..hops {
            let grown: Vec<usize> = near.iter().flat_map(|&s| self.neighbours[s].iter().flatten().copied()).collect();
            near.extend(grown);
            near.sort_unstable();
            near.dedup();
        }
        near
    }

    /// Outward normal at surface node `k` (average of its segments' normals) for positions `x`.
    pub fn node_normal(&self, node: usize, x: impl Fn(usize) -> [f64; 2]) -> [f64; 2] {
        let mut n = [0.0; 2];
        for seg in self.segments.iter().filter(|s| s.contains(&node)) {
            let (a, b) = (x(seg[0]), x(seg[1]));
            let d = [b[0] - a[0], b[1] - a[1]];
            let l = d[0].hypot(d[1]).max(f64::MIN_POSITIVE);
            n[0] += d[1] / l;
            n[1] -= d[0] / l;
        }
        let l = n[0].hypot(n[1]).max(f64::MIN_POSITIVE);
        [n[0] / l, n[1] / l]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::mesh::rectangle;

    #[test]
    fn tributary_areas_sum_to_the_annulus_and_are_right_at_the_axis() {
        // top surface of a disc r in [0, 10]: total area per radian = 10^2 / 2
        let (mesh, sets) = rectangle([0.0, 10.0], [0.0, 1.0], [5, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        let total: f64 = s.areas.iter().sum();
        assert!((total - 50.0).abs() < 1e-12, "{total}");
        assert_eq!(s.segments.len(), 10);
        // the axis node: integral of N r over [0, 2] for the corner node at r = 0 is 0
        let axis = s.nodes.iter().position(|&n| mesh.coords[n][0] == 0.0).unwrap();
        assert!(s.areas[axis].abs() < 1e-12);
        // mid-side node of the first edge (r = 1): integral (1 - xi^2) r ds = h^2 / 3 = 4/3
        let mid = s.nodes.iter().position(|&n| mesh.coords[n][0] == 1.0).unwrap();
        assert!((s.areas[mid] - 4.0 / 3.0).abs() < 1e-12);
        // a uniform pressure p on these areas gives p * area, like the pressure load
        let far = s.nodes.iter().position(|&n| mesh.coords[n][0] == 6.0).unwrap();
        assert!((s.areas[far] - (2.0 * 6.0 * 2.0 / 6.0)).abs() < 1e-12, "{}", s.areas[far]);
    }

    #[test]
    fn segments_are_chained_and_oriented_outward() {
        let (mesh, sets) = rectangle([1.0, 3.0], [0.0, 1.0], [2, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        // top surface runs towards -r: outward normal +z
        let x = |n: usize| mesh.coords[n];
        for &node in &s.nodes {
            let n = s.node_normal(node, x);
            assert!((n[1] - 1.0).abs() < 1e-12, "{n:?}");
        }
        let ends = s.neighbours.iter().filter(|nb| nb.iter().any(|o| o.is_none())).count();
        assert_eq!(ends, 2, "one chain has two ends");
        assert_eq!(s.neighbourhood(s.segments[0][1], 1).len(), 2);
    }
}

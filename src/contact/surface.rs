//! Contact surfaces: a model surface (3-node element edges), its nodes with their consistent
//! axisymmetric tributary areas, its edges (oriented counter-clockwise around their element,
//! so the outward normal is the tangent turned clockwise) and their neighbours.
//!
//! In a plane section the measure r below is the section's thickness (`fe::section`).
//!
//! Tributary area per radian, A_a = sum over the node's edges of integral N_a r ds (reference
//! configuration): the nodal force of a unit pressure. Near the axis this is what makes the
//! contact force right: r_a times half the adjacent lengths would be zero at r = 0 and wrong
//! next to it. (A corner node on the axis gets zero area: the integral of N_a r vanishes
//! there, as it does for a pressure load; its pressure comes from the traction recovery.)

use crate::fe::edge_projection::EdgeProjection;
use crate::fe::quadrature::GAUSS3;
use crate::fe::section::Section;
use crate::fe::shape::line3;
use crate::model::{Edge, Mesh, Model};

#[derive(Clone, Debug)]
pub struct ContactSurface {
    /// Mesh nodes of the surface, sorted.
    pub nodes: Vec<usize>,
    /// Tributary area per radian of each node (same order as `nodes`): integral N_a r ds.
    pub areas: Vec<f64>,
    /// Integral psi_a r ds of the piecewise-linear hat psi_a on the polyline through the
    /// nodes: positive at every node, the axis included (the weights of segment integration).
    pub hat_areas: Vec<f64>,
    /// Edges as (start, end, middle) mesh nodes, counter-clockwise around their element.
    pub edges: Vec<[usize; 3]>,
    /// Reference length of each edge (the master element size h).
    pub edge_length: Vec<f64>,
    /// Reference thickness of the body behind each edge: from the edge's middle node along its
    /// inward normal to the nearest other boundary edge of its body (infinite where none). A
    /// point deeper than this has passed through the body, to its back (`reaches`).
    pub thickness: Vec<f64>,
    /// Element each edge belongs to.
    pub element: Vec<usize>,
    /// Section of each edge's element: its out-of-plane measure weights the edge.
    pub section: Vec<Section>,
    /// For each edge, the edges continuing it at its start and its end (None at a chain end).
    pub neighbours: Vec<[Option<usize>; 2]>,
    /// Consistent "mass" matrix M_ij = integral N_i N_j r ds as (i, j, value) triplets over
    /// `nodes` indices, for the traction recovery.
    mass: Vec<(usize, usize, f64)>,
    /// Edges touching each node (same order as `nodes`): keeps per-node lookups local.
    node_edges: Vec<Vec<usize>>,
}

impl ContactSurface {
    /// Contact surface `name` of `model` (`Model::contact_edges`), each edge weighted by its
    /// element's section.
    pub fn of_model(model: &Model, name: &str) -> Self {
        Self::with_sections(&model.mesh, &model.contact_edges(name), &model.element_section)
    }

    /// An axisymmetric surface.
    pub fn new(mesh: &Mesh, edges: &[Edge]) -> Self {
        Self::with_sections(mesh, edges, &vec![Section::Axisymmetric; mesh.elements.len()])
    }

    /// A surface whose edges' elements have sections `element_section` (per mesh element).
    pub fn with_sections(mesh: &Mesh, edges: &[Edge], element_section: &[Section]) -> Self {
        let mut nodes: Vec<usize> = edges.iter().flat_map(|&e| mesh.edge_nodes(e)).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let index = |n: usize| nodes.binary_search(&n).expect("edge node is a surface node");
        let mut areas = vec![0.0; nodes.len()];
        let mut hat_areas = vec![0.0; nodes.len()];
        let mut mass = Vec::new();
        let mut list = Vec::with_capacity(edges.len());
        let mut edge_length = Vec::with_capacity(edges.len());
        let mut thickness = Vec::with_capacity(edges.len());
        // each body's own boundary: another body overlapping it (an interference fit, a
        // sphere started into a block) is not its back
        let mut body = vec![usize::MAX; mesh.coords.len()];
        for (b, nodes) in mesh.bodies().iter().enumerate() {
            for &n in nodes {
                body[n] = b;
            }
        }
        let body_of = |element: usize| body[mesh.elements[element][0]];
        let mut boundaries: std::collections::HashMap<usize, Vec<Edge>> = std::collections::HashMap::new();
        for free in mesh.free_edges() {
            boundaries.entry(body_of(free.element)).or_default().push(free);
        }
        let boundaries: std::collections::HashMap<usize, Vec<[[f64; 2]; 2]>> =
            boundaries.into_iter().map(|(b, edges)| (b, mesh.edge_segments(&edges))).collect();
        let mut element = Vec::with_capacity(edges.len());
        let mut section = Vec::with_capacity(edges.len());
        for &edge in edges {
            let measure = |r: f64| element_section[edge.element].measure(r);
            let en = mesh.edge_nodes(edge);
            let x = en.map(|n| mesh.coords[n]);
            let k = en.map(index);
            let mut length = 0.0;
            let mut m = [[0.0; 3]; 3];
            for &(s, w) in &GAUSS3 {
                let (n, dn) = line3(s);
                let r = measure((0..3).map(|a| n[a] * x[a][0]).sum());
                let t = [0, 1].map(|i| (0..3).map(|a| dn[a] * x[a][i]).sum::<f64>());
                let jac = t[0].hypot(t[1]);
                length += w * jac;
                for a in 0..3 {
                    areas[k[a]] += w * n[a] * r * jac;
                    for b in 0..3 {
                        m[a][b] += w * n[a] * n[b] * r * jac;
                    }
                }
            }
            for a in 0..3 {
                for b in 0..3 {
                    mass.push((k[a], k[b], m[a][b]));
                }
            }
            // hats: integrate each half of the edge separately (they kink at the middle)
            for (lo, hi) in [(-1.0, 0.0), (0.0, 1.0)] {
                for &(s, w) in &GAUSS3 {
                    let xi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * s;
                    let (n, dn) = line3(xi);
                    let r = measure((0..3).map(|a| n[a] * x[a][0]).sum());
                    let t = [0, 1].map(|i| (0..3).map(|a| dn[a] * x[a][i]).sum::<f64>());
                    let ds = w * 0.5 * (hi - lo) * t[0].hypot(t[1]);
                    let psi = hats(xi);
                    for a in 0..3 {
                        hat_areas[k[a]] += psi[a] * r * ds;
                    }
                }
            }
            list.push(en);
            edge_length.push(length);
            thickness.push(boundaries.get(&body_of(edge.element)).map_or(f64::INFINITY, |b| thickness_behind(x, b)));
            element.push(edge.element);
            section.push(element_section[edge.element]);
        }
        let mut node_edges = vec![Vec::new(); nodes.len()];
        for (e, en) in list.iter().enumerate() {
            for &n in en {
                node_edges[index(n)].push(e);
            }
        }
        let neighbours = (0..list.len())
            .map(|e| {
                let [start, end, _] = list[e];
                let find = |node: usize, at: usize| node_edges[index(node)].iter().copied().find(|&o| o != e && list[o][at] == node);
                [find(start, 1), find(end, 0)]
            })
            .collect();
        ContactSurface { nodes, areas, hat_areas, edges: list, edge_length, thickness, element, section, neighbours, mass, node_edges }
    }

    /// Whether a point at normal gap `gap` from master edge `edge` may bear on it: within the
    /// pair's capture distance, and not deeper than the body behind the edge is thick. Deeper,
    /// the point has passed through the body: it is near the back of the wall, not its face. A
    /// self-contact surface on both sides of a wall (the fluid sides of a bellows' two
    /// sidewalls, back to back across their plies once the fold between them closes) would
    /// otherwise see its far side as a penetration of both walls' thickness.
    pub fn reaches(&self, edge: usize, gap: f64, capture: f64) -> bool {
        gap > -capture.min(self.thickness[edge])
    }

    /// Whether a slave node whose outward normal is `slave_normal` bears on master edge `edge`
    /// where it projects (`projection`): the surfaces face each other (never the back of a thin
    /// master) and the edge `reaches` it.
    pub fn bears(&self, edge: usize, projection: &EdgeProjection, slave_normal: [f64; 2], capture: f64) -> bool {
        slave_normal[0] * projection.normal[0] + slave_normal[1] * projection.normal[1] < 0.0 && self.reaches(edge, projection.gap, capture)
    }

    /// Index of mesh node `node` in `nodes`.
    pub fn index_of(&self, node: usize) -> Option<usize> {
        self.nodes.binary_search(&node).ok()
    }

    /// Edges touching mesh node `node` (empty if it is not on the surface).
    pub fn edges_of(&self, node: usize) -> &[usize] {
        self.index_of(node).map(|k| self.node_edges[k].as_slice()).unwrap_or(&[])
    }

    /// Edges within `hops` edges of `node` along the surface (self-contact: a node never
    /// bears on its own neighbourhood).
    pub fn neighbourhood(&self, node: usize, hops: usize) -> Vec<usize> {
        let mut near: Vec<usize> = self.edges_of(node).to_vec();
        for _ in 1..hops {
            let grown: Vec<usize> = near.iter().flat_map(|&e| self.neighbours[e].iter().flatten().copied()).collect();
            near.extend(grown);
            near.sort_unstable();
            near.dedup();
        }
        near
    }

    /// Outward unit normal at mesh node `node` (average over its edges) for positions `x`.
    pub fn node_normal(&self, node: usize, x: impl Fn(usize) -> [f64; 2]) -> [f64; 2] {
        let mut n = [0.0; 2];
        for e in self.edges_of(node).iter().map(|&k| &self.edges[k]) {
            let xi = [-1.0, 1.0, 0.0][e.iter().position(|&m| m == node).expect("contains")];
            let (_, dn) = line3(xi);
            let t = [0, 1].map(|i| (0..3).map(|a| dn[a] * x(e[a])[i]).sum::<f64>());
            let l = t[0].hypot(t[1]).max(f64::MIN_POSITIVE);
            n[0] += t[1] / l;
            n[1] -= t[0] / l;
        }
        let l = n[0].hypot(n[1]).max(f64::MIN_POSITIVE);
        [n[0] / l, n[1] / l]
    }

    /// Consistent traction recovery: the nodal pressures p whose consistent nodal forces
    /// (integral N_i p r ds) are `forces`, i.e. M p = f (Jacobi-preconditioned conjugate
    /// gradients; M is symmetric positive definite). Exact for a uniform traction, and
    /// defined at a corner node on the axis, whose tributary area is zero.
    pub fn recover_pressure(&self, forces: &[f64]) -> Vec<f64> {
        let n = self.nodes.len();
        let apply = |v: &[f64]| {
            let mut out = vec![0.0; n];
            for &(i, j, m) in &self.mass {
                out[i] += m * v[j];
            }
            out
        };
        let mut diag = vec![0.0; n];
        for &(i, j, m) in &self.mass {
            if i == j {
                diag[i] += m;
            }
        }
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut p = vec![0.0; n];
        let mut r = forces.to_vec();
        let mut z: Vec<f64> = r.iter().zip(&diag).map(|(r, d)| r / d).collect();
        let mut d = z.clone();
        let mut rz = dot(&r, &z);
        let target = 1e-28 * dot(forces, forces).max(f64::MIN_POSITIVE);
        for _ in 0..10 * n.max(10) {
            if dot(&r, &r) <= target {
                break;
            }
            let md = apply(&d);
            let alpha = rz / dot(&d, &md);
            for i in 0..n {
                p[i] += alpha * d[i];
                r[i] -= alpha * md[i];
                z[i] = r[i] / diag[i];
            }
            let rz_next = dot(&r, &z);
            let beta = rz_next / rz;
            rz = rz_next;
            for i in 0..n {
                d[i] = z[i] + beta * d[i];
            }
        }
        p
    }
}

/// The distance from the middle of edge `x` (start, end, middle) along its inward normal (the
/// chord turned anticlockwise) to the nearest of the straight `segments` it crosses, its own
/// two excepted; infinite if it crosses none.
fn thickness_behind(x: [[f64; 2]; 3], segments: &[[[f64; 2]; 2]]) -> f64 {
    let t = [x[1][0] - x[0][0], x[1][1] - x[0][1]];
    let l = t[0].hypot(t[1]).max(f64::MIN_POSITIVE);
    let inward = [-t[1] / l, t[0] / l];
    let origin = x[2];
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    segments
        .iter()
        .filter_map(|&[p, q]| {
            let along = [q[0] - p[0], q[1] - p[1]];
            let denominator = cross(inward, along);
            if denominator.abs() <= 1e-12 * along[0].hypot(along[1]) {
                return None;
            }
            let to = [p[0] - origin[0], p[1] - origin[1]];
            let (distance, s) = (cross(to, along) / denominator, cross(to, inward) / denominator);
            (distance > 1e-9 * l && (0.0..=1.0).contains(&s)).then_some(distance)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Piecewise-linear hats of an edge's (start, end, middle) nodes at edge coordinate `xi`:
/// positive, summing to one, kinked at the middle node.
pub fn hats(xi: f64) -> [f64; 3] {
    if xi <= 0.0 {
        [-xi, 0.0, 1.0 + xi]
    } else {
        [0.0, xi, 1.0 - xi]
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
        assert_eq!(s.edges.len(), 5);
        // the axis node: integral of N r over [0, 2] for the corner node at r = 0 is 0
        let at = |r: f64| s.nodes.iter().position(|&n| mesh.coords[n][0] == r).unwrap();
        assert!(s.areas[at(0.0)].abs() < 1e-12);
        // mid-side node of the first edge (r = 1): integral (1 - xi^2) r ds = h^2 / 3 = 4/3
        assert!((s.areas[at(1.0)] - 4.0 / 3.0).abs() < 1e-12);
        // an interior corner (r = 6): h r / 3 = 4
        assert!((s.areas[at(6.0)] - 4.0).abs() < 1e-12, "{}", s.areas[at(6.0)]);
        // hats: the axis node gets (h/2)^2 / 6 > 0; the total is unchanged
        assert!((s.hat_areas[at(0.0)] - 1.0 / 6.0).abs() < 1e-12, "{}", s.hat_areas[at(0.0)]);
        assert!((s.hat_areas.iter().sum::<f64>() - 50.0).abs() < 1e-12);
    }

    #[test]
    fn traction_recovery_is_exact_for_uniform_pressure_including_the_axis_node() {
        let (mesh, sets) = rectangle([0.0, 10.0], [0.0, 1.0], [5, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        let forces: Vec<f64> = s.areas.iter().map(|a| 7.5 * a).collect();
        let p = s.recover_pressure(&forces);
        assert!(p.iter().all(|v| (v - 7.5).abs() < 1e-9), "{p:?}");
    }

    #[test]
    fn edges_are_chained_and_oriented_outward() {
        let (mesh, sets) = rectangle([1.0, 3.0], [0.0, 1.0], [2, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        let x = |n: usize| mesh.coords[n];
        for &node in &s.nodes {
            let n = s.node_normal(node, x);
            assert!((n[1] - 1.0).abs() < 1e-12, "{n:?}");
        }
        let ends = s.neighbours.iter().filter(|nb| nb.iter().any(|o| o.is_none())).count();
        assert_eq!(ends, 2, "one chain has two ends");
        // the top face runs towards -r: edge 0 starts at the corner it shares with edge 1
        assert_eq!(s.neighbourhood(s.edges[0][0], 1).len(), 2);
    }
}

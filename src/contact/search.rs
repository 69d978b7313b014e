//! Closest-edge search: a uniform grid of master-edge bounding boxes (inflated by the capture
//! distance), rebuilt on the current configuration at every evaluation. Building is linear in
//! the number of edges and each query looks at one cell, so the search is linear, not
//! quadratic, in the surface sizes. The grid also keeps each edge's hull box, so the
//! candidates of a query that cannot win are ruled out from one contiguous array, without
//! fetching their nodes.

use super::node_to_edge::FREE_END_EXTENSION;
use super::surface::ContactSurface;
use crate::fe::edge_projection::{project_on_edge, EdgeProjection};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

pub struct EdgeGrid {
    cell: f64,
    /// Per occupied cell, the range of `edges` listing the edges whose inflated box meets it
    /// (one list for the whole grid rather than a vector per cell: the grid is rebuilt at every
    /// evaluation, and a thousand small allocations cost more than the counting below).
    cells: HashMap<(i64, i64), (u32, u32), BuildHasherDefault<CellHasher>>,
    edges: Vec<usize>,
    /// Per edge, the box (low, high corners) of its Bezier control points, which holds the
    /// curve: the distance to it is a lower bound on the distance to the edge.
    hulls: Vec<[[f64; 2]; 2]>,
}

/// A multiplicative hash for cell coordinates: the grid is rebuilt and queried at every
/// contact evaluation, and the default SipHash (built against adversarial keys, which cell
/// indices are not) cost as much as the lookups' other work.
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(b as u64);
        }
    }

    fn write_i64(&mut self, v: i64) {
        self.write_u64(v as u64);
    }

    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x517c_c1b7_2722_0a95);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

impl EdgeGrid {
    /// Grid over the edges of `surface` at positions `x`, boxes inflated by `capture`.
    pub fn new(surface: &ContactSurface, x: &impl Fn(usize) -> [f64; 2], capture: f64) -> Self {
        let n = surface.edges.len().max(1);
        let mean: f64 = surface.edges.iter().map(|e| dist(x(e[0]), x(e[1]))).sum::<f64>() / n as f64;
        let cell = (mean + 2.0 * capture).max(f64::MIN_POSITIVE);
        let mut cells: HashMap<(i64, i64), (u32, u32), BuildHasherDefault<CellHasher>> = HashMap::with_capacity_and_hasher(2 * n, Default::default());
        let mut hulls = Vec::with_capacity(surface.edges.len());
        // each edge's span of cells, counted per cell; then each cell's range of the list, and
        // the edges written into it in index order
        let mut spans = Vec::with_capacity(surface.edges.len());
        for e in &surface.edges {
            let p = e.map(&x);
            hulls.push(hull(&p));
            let lo = [0, 1].map(|i| cell_of(p.iter().map(|q| q[i]).fold(f64::INFINITY, f64::min) - capture, cell));
            let hi = [0, 1].map(|i| cell_of(p.iter().map(|q| q[i]).fold(f64::NEG_INFINITY, f64::max) + capture, cell));
            for i in lo[0]..=hi[0] {
                for j in lo[1]..=hi[1] {
                    cells.entry((i, j)).or_default().1 += 1;
                }
            }
            spans.push((lo, hi));
        }
        let mut total = 0;
        for range in cells.values_mut() {
            let count = range.1;
            *range = (total, total);
            total += count;
        }
        let mut edges = vec![0; total as usize];
        for (k, (lo, hi)) in spans.into_iter().enumerate() {
            for i in lo[0]..=hi[0] {
                for j in lo[1]..=hi[1] {
                    let range = cells.get_mut(&(i, j)).expect("counted in the first pass");
                    edges[range.1 as usize] = k;
                    range.1 += 1;
                }
            }
        }
        EdgeGrid { cell, cells, edges, hulls }
    }

    /// Edges whose inflated box may contain `p`.
    pub fn candidates(&self, p: [f64; 2]) -> &[usize] {
        self.cell_edges((cell_of(p[0], self.cell), cell_of(p[1], self.cell)))
    }

    /// Edges whose inflated box meets cell `key`.
    fn cell_edges(&self, key: (i64, i64)) -> &[usize] {
        self.cells.get(&key).map_or(&[], |&(start, end)| &self.edges[start as usize..end as usize])
    }

    /// Whether any edge (outside `excluded`) lies within `capture` of some point of the
    /// quadratic edge at `x`: if not, no point of that edge finds a master edge, and a caller
    /// can skip its points. Conservative with respect to [`Self::closest_edge`]: every point
    /// of the edge lies in its hull box, so its cell is one the box overlaps, and an edge found
    /// from it is within `capture` of the box.
    /// A box over more cells than the grid holds (an edge flung far by a diverging Newton
    /// iterate, whose box spanned some 1e12 cells and kept a run in this loop for minutes) is
    /// tested against every edge's box instead: the same answer, at the cost of one pass.
    pub fn may_reach(&self, x: &[[f64; 2]; 3], excluded: &[usize], capture: f64) -> bool {
        let b = hull(x);
        let span = |k: usize| cell_of(b[1][k], self.cell) as f64 - cell_of(b[0][k], self.cell) as f64 + 1.0;
        if span(0) * span(1) > self.cells.len() as f64 {
            return (0..self.hulls.len()).any(|k| box_gap(&b, &self.hulls[k]) <= capture && !excluded.contains(&k));
        }
        for i in cell_of(b[0][0], self.cell)..=cell_of(b[1][0], self.cell) {
            for j in cell_of(b[0][1], self.cell)..=cell_of(b[1][1], self.cell) {
                if self.cell_edges((i, j)).iter().any(|&k| box_gap(&b, &self.hulls[k]) <= capture && !excluded.contains(&k)) {
                    return true;
                }
            }
        }
        false
    }

    /// The master edge a slave node at `xs` bears on, among the candidates of its cell (minus
    /// `excluded`): the edge whose nearest point is closest, within `capture`. A projection
    /// beyond an edge end is kept only where a neighbouring edge continues the surface (the
    /// blind spot of a convex corner); beyond a free end of the surface (by more than
    /// FREE_END_EXTENSION) the node has slid off. At a concave corner the nearer edge wins, so
    /// a node is never counted twice. Ties go to the edge containing the projection, then to
    /// the lower index, so the choice is deterministic and does not depend on the order the
    /// candidates are tried in. `hint` (an edge likely to win, such as the previous
    /// query's on the same slave edge) is tried first: once it is the best so far, the others are
    /// mostly ruled out by their bounding boxes without a projection.
    pub fn closest_edge(
        &self,
        surface: &ContactSurface,
        x: &impl Fn(usize) -> [f64; 2],
        xs: [f64; 2],
        excluded: &[usize],
        capture: f64,
        hint: Option<usize>,
    ) -> Option<(usize, EdgeProjection)> {
        let candidates = self.candidates(xs);
        let inside = |p: &EdgeProjection| (-1.0..=1.0).contains(&p.xi);
        let mut best: Option<(usize, EdgeProjection)> = None;
        let tol = 1e-12 * capture;
        // the hint needs no membership test: an edge whose inflated box misses xs is farther than
        // the capture distance and falls to the bound below
        for k in hint.into_iter().chain(candidates.iter().copied().filter(|&k| Some(k) != hint)) {
            // a lower bound on the distance first: the curve lies in the hull of its Bezier
            // control points, so an edge whose hull's box is farther than the capture distance
            // or the best edge so far is skipped without the projection (same result, several
            // times fewer projections)
            let bound = box_distance(xs, &self.hulls[k]);
            if bound > capture || best.as_ref().is_some_and(|(_, bp)| bound > bp.distance + tol) {
                continue;
            }
            if excluded.contains(&k) {
                continue;
            }
            let Some(p) = project_on_edge(xs, &surface.edges[k].map(x)) else { continue };
            if p.distance > capture {
                continue;
            }
            let better = match &best {
                None => true,
                Some((bk, bp)) => {
                    p.distance < bp.distance - tol || (p.distance <= bp.distance + tol && (inside(&p) && !inside(bp) || (inside(&p) == inside(bp) && k < *bk)))
                }
            };
            if better {
                best = Some((k, p));
            }
        }
        let (k, p) = best?;
        let beyond = 1.0 + FREE_END_EXTENSION;
        if (p.xi < -beyond && surface.neighbours[k][0].is_none()) || (p.xi > beyond && surface.neighbours[k][1].is_none()) {
            return None;
        }
        Some((k, p))
    }
}

fn cell_of(v: f64, cell: f64) -> i64 {
    (v / cell).floor() as i64
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The box of the Bezier control points of the quadratic edge `x` (start, end, middle): the
/// end nodes and 2 x_mid - (x_start + x_end) / 2.
fn hull(x: &[[f64; 2]; 3]) -> [[f64; 2]; 2] {
    let control = [0, 1].map(|i| 2.0 * x[2][i] - 0.5 * (x[0][i] + x[1][i]));
    [[0, 1].map(|i| x[0][i].min(x[1][i]).min(control[i])), [0, 1].map(|i| x[0][i].max(x[1][i]).max(control[i]))]
}

/// Distance from `p` to the box `hull`: a lower bound on the distance to any point of the
/// edge inside it.
fn box_distance(p: [f64; 2], hull: &[[f64; 2]; 2]) -> f64 {
    let gap = |i: usize| (hull[0][i] - p[i]).max(p[i] - hull[1][i]).max(0.0);
    // sqrt of the squares, not hypot: this runs for every candidate edge of every query, and
    // libm's overflow-safe hypot is several times slower (lengths here are far from overflow)
    (gap(0) * gap(0) + gap(1) * gap(1)).sqrt()
}

/// Distance between the boxes `a` and `b` (zero where they overlap).
fn box_gap(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> f64 {
    let gap = |i: usize| (b[0][i] - a[1][i]).max(a[0][i] - b[1][i]).max(0.0);
    (gap(0) * gap(0) + gap(1) * gap(1)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::shape::line3;
    use crate::model::mesh::rectangle;
    use crate::model::Mesh;

    #[test]
    fn finds_the_edge_under_a_node_and_loses_it_past_the_free_end() {
        let (mesh, sets) = rectangle([1.0, 5.0], [0.0, 1.0], [4, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        let x = |n: usize| mesh.coords[n];
        let grid = EdgeGrid::new(&s, &x, 0.5);
        let xs = [2.3, 0.99];
        let (k, p) = grid.closest_edge(&s, &x, xs, &[], 0.5, None).unwrap();
        let e = s.edges[k];
        assert!(x(e[0])[0].min(x(e[1])[0]) <= 2.3 && 2.3 <= x(e[0])[0].max(x(e[1])[0]));
        assert!((p.gap + 0.01).abs() < 1e-12, "{p:?}");
        // on a shared corner (r = 3): exactly one edge
        let xs = [3.0, 0.99];
        assert!(grid.closest_edge(&s, &x, xs, &[], 0.5, None).is_some());
        // beyond the free end r = 5 (more than the 5 % extension of the 1 mm edge)
        let xs = [5.2, 0.99];
        assert!(grid.closest_edge(&s, &x, xs, &[], 0.5, None).is_none());
    }

    /// A surface made of straight 3-node edges through `points` (each pair of consecutive
    /// points one edge), in a throw-away mesh of degenerate-free elements.
    fn polyline(points: &[[f64; 2]]) -> (Mesh, ContactSurface) {
        use crate::model::Edge;
        let mut mesh = Mesh::default();
        let mut edges = Vec::new();
        for w in points.windows(2) {
            let (a, b) = (w[0], w[1]);
            // element whose side 0 is a -> b (counter-clockwise: the body lies to the left)
            let n = [a[1] - b[1], b[0] - a[0]];
            let c = [b[0] + n[0], b[1] + n[1]];
            let d = [a[0] + n[0], a[1] + n[1]];
            let mid = |p: [f64; 2], q: [f64; 2]| [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
            let base = mesh.coords.len();
            mesh.coords.extend([a, b, c, d, mid(a, b), mid(b, c), mid(c, d), mid(d, a)]);
            mesh.elements.push(std::array::from_fn(|k| base + k));
            edges.push(Edge { element: mesh.elements.len() - 1, side: 0 });
        }
        // merge coincident corner nodes so consecutive edges share them
        let n = mesh.coords.len();
        let mut canonical: Vec<usize> = (0..n).collect();
        for i in 0..n {
            for j in 0..i {
                if mesh.coords[i] == mesh.coords[j] {
                    canonical[i] = canonical[j];
                    break;
                }
            }
        }
        for e in mesh.elements.iter_mut() {
            for k in e.iter_mut() {
                *k = canonical[*k];
            }
        }
        mesh.node_ids = (1..=n as u64).collect();
        mesh.element_ids = (1..=mesh.elements.len() as u64).collect();
        let s = ContactSurface::new(&mesh, &edges);
        (mesh, s)
    }

    /// An edge flung 1e9 mm by a diverging iterate spans about 1e18 cells of a 1 mm grid: the
    /// question is answered against every edge's box at once, and alike (seen failing before:
    /// the loop over its cells ran for minutes, a DN400 joint's collapse search without output).
    #[test]
    fn an_edge_flung_far_is_answered_at_once_and_alike() {
        let (mesh, sets) = rectangle([1.0, 5.0], [0.0, 1.0], [4, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        let x = |n: usize| mesh.coords[n];
        let grid = EdgeGrid::new(&s, &x, 0.1);
        let flung = [[2.0, 1.05], [1.0e9, -1.0e9], [2.5, 1.05]];
        assert!(grid.may_reach(&flung, &[], 0.1), "its box holds the surface");
        let away = [[2.0e9, 1.0e9], [3.0e9, 2.0e9], [2.5e9, 1.5e9]];
        assert!(!grid.may_reach(&away, &[], 0.1));
        let all: Vec<usize> = (0..s.edges.len()).collect();
        assert!(!grid.may_reach(&flung, &all, 0.1), "every edge excluded");
    }

    #[test]
    fn convex_and_concave_corners_keep_a_node_once() {
        // the surface runs along +r, then up: the body (on its left) is the quadrant r < 2,
        // z > 0, whose corner at (2, 0) is convex; outward normals -z and +r
        let (mesh, s) = polyline(&[[0.0, 0.0], [2.0, 0.0], [2.0, 2.0]]);
        let x = |n: usize| mesh.coords[n];
        let grid = EdgeGrid::new(&s, &x, 0.5);
        // convex corner, outside: a point beyond both edge ends, in the blind spot, is found
        // on exactly one edge (the nearer one, here a tie broken towards the lower index)
        let xs = [2.1, -0.1];
        let found = grid.closest_edge(&s, &x, xs, &[], 0.5, None).expect("blind spot of a convex corner");
        assert!(found.1.gap > 0.0, "outside the body");
        // inside the body near the corner: it projects onto both edges; only the nearer counts
        let xs = [1.95, 0.02];
        let (k, p) = grid.closest_edge(&s, &x, xs, &[], 0.5, None).unwrap();
        assert_eq!(k, 0, "nearer to the first edge");
        assert!((p.gap + 0.02).abs() < 1e-12);
        let xs = [1.98, 0.5];
        let (k, _) = grid.closest_edge(&s, &x, xs, &[], 0.5, None).unwrap();
        assert_eq!(k, 1, "nearer to the second edge");
    }

    #[test]
    fn self_contact_skips_the_neighbourhood_and_finds_the_facing_side() {
        // a U whose inside (the surface) faces itself across a 0.2 gap: bottom leg along -r at
        // z = 0, turn, top leg along +r at z = 0.2 (the body is outside the U)
        let (mesh, s) = polyline(&[[4.0, 0.0], [3.0, 0.0], [2.0, 0.0], [2.0, 0.2], [3.0, 0.2], [4.0, 0.2]]);
        let x = |n: usize| mesh.coords[n];
        let grid = EdgeGrid::new(&s, &x, 0.5);
        let node = s.nodes.iter().copied().find(|&n| mesh.coords[n] == [3.0, 0.2]).unwrap();
        let xs = [3.0, 0.19]; // the node, moved 0.01 off its own leg towards the bottom leg
        let own = s.neighbourhood(node, 1);
        assert!(!own.is_empty());
        let (k, p) = grid.closest_edge(&s, &x, xs, &own, 0.5, None).unwrap();
        assert!(!own.contains(&k));
        let e = s.edges[k];
        assert!(mesh.coords[e[0]][1] == 0.0 && mesh.coords[e[1]][1] == 0.0, "found the bottom leg");
        assert!((p.gap - 0.19).abs() < 1e-12, "open by 0.19: {p:?}");
        // without the exclusion the node's own edge would be the nearest
        let (k, _) = grid.closest_edge(&s, &x, xs, &[], 0.5, None).unwrap();
        assert!(own.contains(&k));
    }

    #[test]
    fn an_edge_ruled_out_whole_has_no_point_that_finds_a_master() {
        // a U whose top leg bends away from the bottom one: the facing parts reach each other
        // across 0.2, the far end of the top leg reaches nothing but its own neighbourhood
        let (mesh, s) = polyline(&[[6.0, 0.0], [5.0, 0.0], [4.0, 0.0], [3.0, 0.0], [2.0, 0.0], [2.0, 0.2], [3.0, 0.2], [4.0, 1.5], [5.0, 3.0], [6.0, 4.5]]);
        let x = |n: usize| mesh.coords[n];
        let capture = 0.5;
        let grid = EdgeGrid::new(&s, &x, capture);
        let (mut reached, mut ruled_out) = (0, 0);
        for (e, nodes) in s.edges.iter().enumerate() {
            let mut own: Vec<usize> = [nodes[0], nodes[1]].iter().flat_map(|&n| s.neighbourhood(n, 1)).collect();
            own.sort_unstable();
            own.dedup();
            let xs = nodes.map(x);
            let found = (0..=40).any(|i| {
                let xi = -1.0 + i as f64 / 20.0;
                let (n, _) = line3(xi);
                let p = [0, 1].map(|c| (0..3).map(|a| n[a] * xs[a][c]).sum::<f64>());
                grid.closest_edge(&s, &x, p, &own, capture, None).is_some()
            });
            if grid.may_reach(&xs, &own, capture) {
                reached += 1;
            } else {
                assert!(!found, "edge {e} ruled out, but one of its points finds a master");
                ruled_out += 1;
            }
        }
        assert!(reached >= 4 && ruled_out >= 2, "reached {reached}, ruled out {ruled_out}");
    }

    #[test]
    fn the_grid_returns_every_edge_within_capture() {
        let (mesh, sets) = rectangle([0.0, 40.0], [0.0, 1.0], [40, 1]).unwrap();
        let s = ContactSurface::new(&mesh, &sets.surfaces["top"]);
        let x = |n: usize| mesh.coords[n];
        let grid = EdgeGrid::new(&s, &x, 0.3);
        for i in 0..400 {
            let p = [i as f64 * 0.1 + 0.05, 1.1];
            let c = grid.candidates(p);
            for k in 0..s.edges.len() {
                let e = s.edges[k];
                if x(e[0])[0].min(x(e[1])[0]) - 0.3 <= p[0] && p[0] <= x(e[0])[0].max(x(e[1])[0]) + 0.3 {
                    assert!(c.contains(&k), "edge {k} missing at {p:?}");
                }
            }
        }
    }
}

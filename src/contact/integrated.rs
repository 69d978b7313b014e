//! Surface-integrated slide line ("segment" integration): the pointwise gap of the slide line
//! is evaluated along the whole slave surface and averaged around each slave node with the
//! piecewise-linear hat psi_a of the polyline through the nodes, g_a = integral psi_a g r ds
//! (reference r ds), giving the nodal pressure p_a = max(0, lambda_a - eps g_a / A_a) with
//! A_a = integral psi_a r ds. The forces act through the quadratic interpolation of the slave
//! point, so for a uniform pressure every node receives p integral N_a r ds, its consistent
//! share. Hats rather than the quadratic N_a as weights: they are positive and sum to one
//! everywhere, and a corner node on the axis (where integral N_a r ds = 0) still has a
//! positive weight and so a pressure of its own. The
//! integral is split where the master's element boundaries project onto the slave edge and
//! taken piecewise with 3-point Gauss rules, so a uniform gap gives exactly consistent forces
//! on both sides: non-matching quadratic meshes pass the contact patch test, which nodal
//! collocation (node-to-segment) cannot, its master reactions being a nodal quadrature of the
//! master shape functions.
//!
//! Penalty energy per node A_a p_a^2 / (2 eps): residual f = -p_a dg_a, tangent
//! K = (eps / A_a) dg_a dg_a^T - p_a d2g_a, where dg and d2g are the integrals of the pointwise
//! gap's gradient and Hessian (from the node-to-edge kernel, with the slave point interpolated
//! from its edge's nodes). The integration points' positions are taken as fixed on the slave
//! edge: the integrand is continuous across the split points, so their motion adds nothing.
//!
//! The search and the gaps come first ([`weighted_gaps_into`], with each integration point kept as
//! a [`GapSample`]); the gradient of a sample is closed-form and cheap, its Hessian (dual
//! numbers) is asked for only where a tangent is wanted, so residual-only evaluations (the
//! line search's) skip it.

use super::node_to_edge::{edge_residual_and_tangent, project_on_edge, ContactLaw, EdgeProjection};
use super::search::EdgeGrid;
use super::surface::{hats, ContactSurface};
use crate::fe::quadrature::GAUSS3;
use crate::fe::shape::line3;
use nalgebra::{SMatrix, SVector};

pub type SampleVector = SVector<f64, 12>;
pub type SampleMatrix = SMatrix<f64, 12, 12>;

/// One integration point of a slave edge bearing on a master edge, as seen by one slave node.
#[derive(Clone, Copy, Debug)]
pub struct GapSample {
    /// The slave edge's three nodes, then the master edge's three (the 12 DOFs of the sample).
    pub nodes: [usize; 6],
    /// Quadratic shape functions of the slave edge at the point (the slave point is
    /// sum N_a x_a).
    pub shape: [f64; 3],
    /// The slave point's projection on the master edge.
    pub projection: EdgeProjection,
    /// psi_a w r ds: the sample's weight in the node's weighted gap.
    pub weight: f64,
    /// Index of the integration point among those of its `weighted_gaps_into` call: the samples
    /// of one point (one per slave node whose hat covers it) share it, and their Hessians
    /// differ only by the weight.
    pub point: usize,
}

impl GapSample {
    /// Weighted gradient of the pointwise gap over the sample's 12 DOFs:
    /// dg = n . (sum N_a dx_a - sum M_k(xi) dx_k), closed form at the closest point.
    pub fn gradient(&self) -> SampleVector {
        let n = self.projection.normal;
        let m = line3(self.projection.xi).0;
        let mut g = SampleVector::zeros();
        for a in 0..3 {
            for c in 0..2 {
                g[2 * a + c] = self.weight * self.shape[a] * n[c];
                g[6 + 2 * a + c] = -self.weight * m[a] * n[c];
            }
        }
        g
    }

    /// Hessian of the pointwise gap at the sample's point over its 12 DOFs at positions `x`
    /// (unweighted, the same for every sample of the point): the node-to-edge kernel's (8 DOFs:
    /// slave point and master edge) carried to the slave edge's nodes through x_s = sum N_a x_a.
    pub fn point_hessian(&self, x: &impl Fn(usize) -> [f64; 2]) -> SampleMatrix {
        let slave = [0, 1, 2].map(|a| x(self.nodes[a]));
        let master = [3, 4, 5].map(|a| x(self.nodes[a]));
        let p = [0, 1].map(|i| (0..3).map(|a| self.shape[a] * slave[a][i]).sum::<f64>());
        // the kernel with p = 1, A = 1, eps = 0 gives -dg and -d2g
        let unit = ContactLaw::linear(1.0, 0.0, 1.0, [false, false]);
        let (_, minus, _) = edge_residual_and_tangent(p, &master, &self.projection, &unit);
        // x_s = sum N_a x_a: slave DOF (a, c) is kernel DOF c scaled by N_a; master DOFs map
        // one to one (kernel DOFs 2..8)
        let of = |i: usize| if i < 6 { (i % 2, self.shape[i / 2]) } else { (i - 4, 1.0) };
        SampleMatrix::from_fn(|i, j| {
            let ((ri, fi), (rj, fj)) = (of(i), of(j));
            -fi * fj * minus[(ri, rj)]
        })
    }
}

/// The weighted gap of one slave node and the integration points it is made of.
pub struct WeightedGap {
    /// Index of the node in the slave surface.
    pub index: usize,
    /// g_a = integral psi_a g r ds over the parts of the node's edges facing a master.
    pub gap: f64,
    /// The integration points (weighted by psi_a w r ds) whose sums are g_a, dg_a and d2g_a.
    pub samples: Vec<GapSample>,
    /// Master edge under the node's heaviest integration point (its size sets a penalty
    /// factor).
    pub master_edge: usize,
}

/// Weighted gaps of the slave nodes `indices` (into `slave.nodes`) against `master`, at
/// positions `x` (current) and `x0` (reference, for the weights), into `out`: one entry per node
/// of `indices`, in its order, with no samples for a node none of whose integration points finds
/// a master. `excluded[edge]` lists the master edges a slave edge may not bear on (self-contact;
/// empty, or no entry, for none). The entries of the last call are refilled, their sample
/// vectors kept, so a contact evaluation does not allocate them again.
#[allow(clippy::too_many_arguments)]
pub fn weighted_gaps_into(
    slave: &ContactSurface,
    master: &ContactSurface,
    x: &impl Fn(usize) -> [f64; 2],
    x0: &impl Fn(usize) -> [f64; 2],
    indices: &[usize],
    excluded: &[Vec<usize>],
    capture: f64,
    out: &mut Vec<WeightedGap>,
) {
    let grid = EdgeGrid::new(master, x, capture);
    out.truncate(indices.len());
    for (k, &i) in indices.iter().enumerate() {
        match out.get_mut(k) {
            Some(g) => {
                g.samples.clear();
                (g.index, g.gap, g.master_edge) = (i, 0.0, usize::MAX);
            }
            None => out.push(WeightedGap { index: i, gap: 0.0, samples: Vec::new(), master_edge: usize::MAX }),
        }
    }
    let mut best_weight = vec![0.0f64; indices.len()];
    // requested node index (into slave.nodes) -> position in `indices`
    let mut lookup = vec![usize::MAX; slave.nodes.len()];
    for (k, &i) in indices.iter().enumerate() {
        lookup[i] = k;
    }
    let position = |i: usize| Some(lookup[i]).filter(|&k| k != usize::MAX);
    // the slave edges touching a requested node
    let mut edges: Vec<usize> = indices.iter().flat_map(|&i| slave.edges_of(slave.nodes[i]).iter().copied()).collect();
    edges.sort_unstable();
    edges.dedup();
    // the master edge of the last point found: consecutive points mostly share it
    let mut hint = None;
    let mut points = 0;
    // per-edge scratch, reused
    let (mut cuts, mut masters): (Vec<f64>, Vec<usize>) = (Vec::new(), Vec::new());
    for e in edges {
        let en = slave.edges[e];
        let xs = en.map(x);
        let xr = en.map(x0);
        let skip = excluded.get(e).map_or(&[][..], |v| v.as_slice());
        // most edges of a self-contact surface, and of a pair's ends, face nothing: ruled out
        // for the whole edge at once instead of at each of its points
        if !grid.may_reach(&xs, skip, capture) {
            continue;
        }
        split_points(&grid, master, x, &xs, skip, capture, &mut hint, &mut cuts, &mut masters);
        // the edge's nodes among the requested ones (looked up once, not per point)
        let requested = en.map(|n| slave.index_of(n).and_then(position));
        for piece in cuts.windows(2) {
            let (lo, hi) = (piece[0], piece[1]);
            for &(s, w) in &GAUSS3 {
                let xi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * s;
                let (n, dn) = line3(xi);
                let r0 = slave.section[e].measure((0..3).map(|a| n[a] * xr[a][0]).sum());
                let t0 = [0, 1].map(|i| (0..3).map(|a| dn[a] * xr[a][i]).sum::<f64>());
                let weight = w * 0.5 * (hi - lo) * r0 * (t0[0] * t0[0] + t0[1] * t0[1]).sqrt();
                let p = point(&xs, xi);
                let Some((m, proj)) = grid.closest_edge(master, x, p, skip, capture, hint) else { continue };
                hint = Some(m);
                // surfaces in contact face each other
                let ts = [0, 1].map(|i| (0..3).map(|a| dn[a] * xs[a][i]).sum::<f64>());
                if ts[1] * proj.normal[0] - ts[0] * proj.normal[1] >= 0.0 || !master.reaches(m, proj.gap, capture) {
                    continue;
                }
                let nodes = [en[0], en[1], en[2], master.edges[m][0], master.edges[m][1], master.edges[m][2]];
                let psi = hats(xi);
                let point = points;
                points += 1;
                for a in 0..3 {
                    let Some(k) = requested[a] else { continue };
                    let wa = weight * psi[a];
                    if wa == 0.0 {
                        continue;
                    }
                    let g = &mut out[k];
                    if g.samples.is_empty() {
                        // a node's hat covers two slave edges, each of two or more pieces of
                        // three points: room for the usual count at once
                        g.samples.reserve(12);
                    }
                    g.gap += wa * proj.gap;
                    g.samples.push(GapSample { nodes, shape: n, projection: proj, weight: wa, point });
                    if wa.abs() > best_weight[k] {
                        best_weight[k] = wa.abs();
                        g.master_edge = m;
                    }
                }
            }
        }
    }
}

/// Where slave edge `xs` is split for its integration, into `cuts` (in [-1, 1], sorted): its
/// middle node (the hats kink there) and the ends of the master edges it faces projected onto
/// it; `masters` gets those edges, `hint` the last one found.
#[allow(clippy::too_many_arguments)]
fn split_points(
    grid: &EdgeGrid,
    master: &ContactSurface,
    x: &impl Fn(usize) -> [f64; 2],
    xs: &[[f64; 2]; 3],
    skip: &[usize],
    capture: f64,
    hint: &mut Option<usize>,
    cuts: &mut Vec<f64>,
    masters: &mut Vec<usize>,
) {
    cuts.clear();
    cuts.extend([-1.0, 0.0, 1.0]);
    masters.clear();
    // the ends first: where both find the same master edge or two neighbours, the master
    // surface runs on under the slave edge from one to the other, and the probes between
    // would find those edges again; they are spared (a fifth of the bellows' searches).
    // Five probes could miss a short master edge too: a cut is for accuracy, not validity
    let mut probe = |xi: f64| {
        let found = grid.closest_edge(master, x, point(xs, xi), skip, capture, *hint).map(|(m, _)| m);
        if let Some(m) = found {
            *hint = Some(m);
            if !masters.contains(&m) {
                masters.push(m);
            }
        }
        found
    };
    let ends = [probe(-1.0), probe(1.0)];
    let continuous = match ends {
        [Some(a), Some(b)] => a == b || master.neighbours[a].contains(&Some(b)),
        _ => false,
    };
    if !continuous {
        for xi in [-0.5, 0.0, 0.5] {
            probe(xi);
        }
    }
    for &m in masters.iter() {
        for corner in [master.edges[m][0], master.edges[m][1]] {
            if let Some(p) = project_on_edge(x(corner), xs) {
                if p.xi > -1.0 + 1e-9 && p.xi < 1.0 - 1e-9 && p.distance <= capture {
                    cuts.push(p.xi);
                }
            }
        }
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
}

fn point(x: &[[f64; 2]; 3], xi: f64) -> [f64; 2] {
    let (n, _) = line3(xi);
    [0, 1].map(|i| (0..3).map(|a| n[a] * x[a][i]).sum::<f64>())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::mesh::{blocks, Block};

    #[test]
    fn a_uniform_gap_between_non_matching_faces_gives_consistent_weighted_gaps() {
        // upper block's bottom 0.01 below the lower block's top: a slave face finer than its
        // master (7 on 5 elements), and one so much coarser (2 on 7) that a slave edge's ends
        // find master edges that are not neighbours, whose corners the probes between must
        // find for the integration to be exact on the master side
        for (slave_divisions, master_divisions) in [(7, 5), (2, 7)] {
            uniform_gap_consistent(slave_divisions, master_divisions);
        }
    }

    /// Two walls 1 thick, 0.5 apart, and a surface on their far sides (as the fluid sides of a
    /// bellows' two sidewalls, back to back across the fold between them): a capture distance
    /// of 4 reaches across both walls, 2.5, but the far side lies beyond the wall behind the
    /// master face, so no point bears on it; a face penetrated by 0.1 still is.
    #[test]
    fn the_back_of_a_wall_is_no_penetration_of_its_face() {
        let wall = |name: &str, z: [f64; 2]| Block { name: name.into(), r: [0.0, 10.0], z, divisions: [5, 1], grading: [1.0, 1.0], triangles: false };
        let (mesh, sets) = blocks(&[wall("lower", [0.0, 1.0]), wall("upper", [1.5, 2.5])]).unwrap();
        let x = |n: usize| mesh.coords[n];
        let gaps = |slave: &str, master: &str, shift: f64| {
            let slave = ContactSurface::new(&mesh, &sets.surfaces[slave]);
            let master = ContactSurface::new(&mesh, &sets.surfaces[master]);
            assert!(master.thickness.iter().all(|&d| (d - 1.0).abs() < 1e-12), "{:?}", master.thickness);
            let moved = |n: usize| if slave.index_of(n).is_some() { [x(n)[0], x(n)[1] + shift] } else { x(n) };
            let all: Vec<usize> = (0..slave.nodes.len()).collect();
            let mut gaps = Vec::new();
            weighted_gaps_into(&slave, &master, &moved, &x, &all, &[], 4.0, &mut gaps);
            gaps
        };
        // the upper wall's top against the lower wall's bottom: 2.5 behind it
        assert!(gaps("upper_top", "lower_bottom", 0.0).iter().all(|g| g.samples.is_empty()));
        // the upper wall's bottom pushed 0.6 down, 0.1 into the lower wall's top
        for g in gaps("upper_bottom", "lower_top", -0.6) {
            assert!(!g.samples.is_empty());
            assert!((g.gap / g.samples.iter().map(|s| s.weight).sum::<f64>() + 0.1).abs() < 1e-9, "{}", g.gap);
        }
    }

    fn uniform_gap_consistent(slave_divisions: usize, master_divisions: usize) {
        let specs = [
            Block { name: "lower".into(), r: [0.0, 10.0], z: [0.0, 5.0], divisions: [master_divisions, 1], grading: [1.0, 1.0], triangles: false },
            Block { name: "upper".into(), r: [0.0, 10.0], z: [4.99, 10.0], divisions: [slave_divisions, 1], grading: [1.0, 1.0], triangles: false },
        ];
        let (mesh, sets) = blocks(&specs).unwrap();
        let slave = ContactSurface::new(&mesh, &sets.surfaces["upper_bottom"]);
        let master = ContactSurface::new(&mesh, &sets.surfaces["lower_top"]);
        let x = |n: usize| mesh.coords[n];
        let all: Vec<usize> = (0..slave.nodes.len()).collect();
        let mut gaps = Vec::new();
        weighted_gaps_into(&slave, &master, &x, &x, &all, &[], 0.5, &mut gaps);
        assert_eq!(gaps.len(), slave.nodes.len());
        assert!(gaps.iter().all(|g| !g.samples.is_empty()), "every slave node faces the master");
        for g in &gaps {
            let area = slave.hat_areas[g.index];
            assert!((g.gap - (-0.01) * area).abs() < 1e-12, "node {}: {} vs {}", g.index, g.gap, -0.01 * area);
        }
        // the master side of the gradient, summed over slave nodes, gives every master node its
        // consistent area (psi sums to one)
        let mut master_force = vec![0.0; mesh.coords.len()];
        for g in &gaps {
            for s in &g.samples {
                let grad = s.gradient();
                for k in 3..6 {
                    master_force[s.nodes[k]] += grad[2 * k + 1];
                }
            }
        }
        for (k, &node) in master.nodes.iter().enumerate() {
            // d g / d z_master = -n_z = -1 on a face whose outward normal is +z
            assert!((master_force[node] + master.areas[k]).abs() < 1e-10, "master node {node}: {} vs {}", master_force[node], -master.areas[k]);
        }
    }
}

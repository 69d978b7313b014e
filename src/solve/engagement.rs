//! One active slave node's contribution to the problem: its residual at once, its tangent on
//! demand. An evaluation finds the engagements with the residual (the line search asks for no
//! more); the Jacobian at the same iterate then forms their tangents from what each kept (its
//! recipe), without searching again.

use crate::contact::integrated::{GapSample, SampleMatrix};
use crate::contact::node_to_edge::{edge_residual_and_tangent, ContactLaw, EdgeProjection};

/// The contribution of one active slave node: residual and tangent over `nodes`.
pub struct Engagement {
    /// Mesh nodes the contribution couples (the slave node first).
    pub nodes: Vec<usize>,
    /// Two entries per node, (r, z).
    pub residual: Vec<f64>,
    /// Row-major, (2 nodes) x (2 nodes); empty until the tangent is formed (`form_tangent`).
    pub tangent: Vec<f64>,
    /// What the tangent is formed from.
    recipe: TangentRecipe,
}

enum TangentRecipe {
    /// Node-to-segment: the kernel's arguments.
    Nodal { xs: [f64; 2], master: [[f64; 2]; 3], projection: EdgeProjection, law: ContactLaw },
    /// Segment integration: K = stiffness dg dg^T - weighted_pressure d2g, with dg (`gradient`,
    /// over the engagement's nodes) and d2g the sums over the node's integration points.
    Integrated { samples: Vec<GapSample>, gradient: Vec<f64>, stiffness: f64, weighted_pressure: f64 },
}

impl Engagement {
    /// Node-to-segment: slave node `node` at `xs` on the master edge with nodes `edge` at
    /// `x_master`, projected at `projection`; `residual` is the kernel's over [node, edge...].
    pub(super) fn nodal(
        node: usize,
        edge: [usize; 3],
        residual: Vec<f64>,
        xs: [f64; 2],
        x_master: [[f64; 2]; 3],
        projection: EdgeProjection,
        law: ContactLaw,
    ) -> Self {
        let recipe = TangentRecipe::Nodal { xs, master: x_master, projection, law };
        Engagement { nodes: vec![node, edge[0], edge[1], edge[2]], residual, tangent: Vec::new(), recipe }
    }

    /// Segment integration: slave node `node`, its weighted gap made of `samples`, at the
    /// nodal pressure times the pass's weight `weighted_pressure`; `stiffness` is the pass's
    /// weight times eps / A. The residual is -weighted_pressure dg.
    pub(super) fn integrated(node: usize, samples: Vec<GapSample>, stiffness: f64, weighted_pressure: f64) -> Self {
        let nodes = sample_nodes(node, &samples);
        let mut gradient = vec![0.0; 2 * nodes.len()];
        for s in &samples {
            let sg = s.gradient();
            for (a, &n) in s.nodes.iter().enumerate() {
                let at = position_in(&nodes, n);
                gradient[2 * at] += sg[2 * a];
                gradient[2 * at + 1] += sg[2 * a + 1];
            }
        }
        let residual = gradient.iter().map(|v| -weighted_pressure * v).collect();
        Engagement { nodes, residual, tangent: Vec::new(), recipe: TangentRecipe::Integrated { samples, gradient, stiffness, weighted_pressure } }
    }

    /// Forms the tangent at positions `x` (those of the evaluation that found the engagement),
    /// the segment-integrated ones from `hessians` of the same evaluation.
    pub(super) fn form_tangent(&mut self, x: &impl Fn(usize) -> [f64; 2], hessians: &mut PointHessians) {
        self.tangent = match &self.recipe {
            TangentRecipe::Nodal { xs, master, projection, law } => {
                let (_, k, _) = edge_residual_and_tangent(*xs, master, projection, law);
                k.transpose().as_slice().to_vec()
            }
            TangentRecipe::Integrated { samples, gradient, stiffness, weighted_pressure } => {
                let m = gradient.len();
                let mut k = vec![0.0; m * m];
                for i in 0..m {
                    for j in 0..m {
                        k[i * m + j] = stiffness * gradient[i] * gradient[j];
                    }
                }
                // -p d2g
                for s in samples {
                    let h = hessians.at(s, x);
                    let f = weighted_pressure * s.weight;
                    let map = s.nodes.map(|n| 2 * position_in(&self.nodes, n));
                    for a in 0..12 {
                        let row = map[a / 2] + a % 2;
                        for b in 0..12 {
                            k[row * m + map[b / 2] + b % 2] -= f * h[(a, b)];
                        }
                    }
                }
                k
            }
        };
    }
}

/// The nodes the samples of a slave node couple, the node first.
fn sample_nodes(node: usize, samples: &[GapSample]) -> Vec<usize> {
    let mut nodes = vec![node];
    for s in samples {
        for &n in &s.nodes {
            if !nodes.contains(&n) {
                nodes.push(n);
            }
        }
    }
    nodes
}

fn position_in(nodes: &[usize], n: usize) -> usize {
    nodes.iter().position(|&q| q == n).expect("listed")
}

/// The Hessians of the pointwise gap at the integration points of one evaluation, computed
/// when a tangent first asks (each point serves the two slave nodes whose hats cover it).
#[derive(Default)]
pub(super) struct PointHessians {
    /// Per point, its index in `matrices` (u32::MAX until computed).
    slot: Vec<u32>,
    matrices: Vec<SampleMatrix>,
}

impl PointHessians {
    /// Forgets every Hessian; `points` points to come.
    pub(super) fn reset(&mut self, points: usize) {
        self.slot.clear();
        self.slot.resize(points, u32::MAX);
        self.matrices.clear();
    }

    /// The (unweighted) Hessian at `sample`'s point.
    fn at(&mut self, sample: &GapSample, x: &impl Fn(usize) -> [f64; 2]) -> &SampleMatrix {
        if self.slot[sample.point] == u32::MAX {
            self.slot[sample.point] = self.matrices.len() as u32;
            self.matrices.push(sample.point_hessian(x));
        }
        &self.matrices[self.slot[sample.point] as usize]
    }
}

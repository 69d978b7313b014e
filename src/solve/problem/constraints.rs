//! The linear multi-point constraints' share of the residual and the tangent. Each constraint
//! g(u) = sum_i a_i u_i = 0 (`model::Constraint`) is enforced by the penalty energy
//! k g^2 / 2: force k g a_i at each term's DOF, tangent k a_i a_j. The penalty is
//! `PENALTY_FACTOR` times the stiffness scale E * measure (E r per radian, E t in a plane
//! section) of the stiffest element at the constraint's nodes, so a constraint gives way by
//! about 1 / PENALTY_FACTOR of the deformation its force causes in those elements.
//!
//! A penalty keeps the unknowns and the Jacobian's structure those of the elements and
//! contact (CalculiX eliminates each constraint's dependent DOF instead; the difference is
//! the give above). Each constraint is evaluated by the rank that owns its first node.

use crate::decomposition::{DofMap, Partition};
use crate::fe::shape::Shape;
use crate::model::Model;
use crate::petsc::sys::PetscInt;

/// Constraint stiffness over the stiffness scale of the elements it joins: a constraint
/// gives way by ~1e-6 of the deformation it transmits, while the Jacobian's condition
/// number grows by the same factor at most (MUMPS's LU keeps ~1e-16 * 1e6 * cond(K_elements)).
pub const PENALTY_FACTOR: f64 = 1e6;

/// One constraint this rank evaluates: its terms as (node, component, coefficient), the
/// position of each term's DOF in the gathered free DOFs (None where prescribed), and its
/// penalty k (N/mm per radian, or per thickness in a plane section).
struct LocalConstraint {
    terms: Vec<(usize, usize, f64)>,
    slots: Vec<Option<usize>>,
    penalty: f64,
}

pub struct ConstraintAssembly {
    local: Vec<LocalConstraint>,
}

impl ConstraintAssembly {
    /// This rank's constraints with their penalties; None when the model has none.
    /// `slot_of` gives the position of a free DOF in the gathered vector.
    pub fn new(model: &Model, partition: &Partition, dofs: &DofMap, slot_of: impl Fn(PetscInt) -> usize) -> Option<Self> {
        if model.constraints.is_empty() {
            return None;
        }
        let scale = node_stiffness_scales(model);
        let largest = scale.iter().copied().fold(0.0, f64::max);
        let local = model
            .constraints
            .iter()
            .filter(|c| partition.node_owner[c.terms[0].node] == partition.rank)
            .map(|c| {
                // a constraint only between nodes of no element (reference nodes) takes the
                // model's stiffest scale
                let own = c.terms.iter().map(|t| scale[t.node]).fold(0.0, f64::max);
                let penalty = PENALTY_FACTOR * if own > 0.0 { own } else { largest };
                let terms: Vec<(usize, usize, f64)> = c.terms.iter().map(|t| (t.node, t.component as usize, t.coefficient)).collect();
                let slots = terms.iter().map(|&(n, k, _)| Some(dofs.dof[n][k]).filter(|&d| d >= 0).map(&slot_of)).collect();
                LocalConstraint { terms, slots, penalty }
            })
            .collect();
        Some(ConstraintAssembly { local })
    }

    /// The node pairs (a <= b) this rank's constraints couple in the Jacobian.
    pub fn pairs(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        self.local.iter().flat_map(|c| c.terms.iter().flat_map(move |&(a, _, _)| c.terms.iter().map(move |&(b, _, _)| (a.min(b), a.max(b)))))
    }

    /// The constraint forces k g a_i at the `gathered` free DOFs and the `prescribed` values
    /// (per node): `sink(node, component, force)` for each term. Returns the sum of their
    /// magnitudes, their count and the round-off scale (squared) of the sums g.
    pub fn residual(&self, gathered: &[f64], prescribed: &[[f64; 2]], mut sink: impl FnMut(usize, usize, f64)) -> ([f64; 2], f64) {
        let (mut forces, mut roundoff) = ([0.0, 0.0], 0.0);
        for c in &self.local {
            let u = |i: usize| c.slots[i].map_or_else(|| prescribed[c.terms[i].0][c.terms[i].1], |s| gathered[s]);
            let g: f64 = c.terms.iter().enumerate().map(|(i, t)| t.2 * u(i)).sum();
            let size: f64 = c.terms.iter().enumerate().map(|(i, t)| (t.2 * u(i)).abs()).sum();
            for &(n, k, a) in &c.terms {
                let f = c.penalty * g * a;
                sink(n, k, f);
                forces[0] += f.abs();
                forces[1] += 1.0;
                roundoff += (crate::solve::problem::roundoff::ROUNDOFF_ULPS * f64::EPSILON * c.penalty * size * a.abs()).powi(2);
            }
        }
        (forces, roundoff)
    }

    /// K_fp delta of the constraints (see `Problem::prescribed_coupling`): `add(node,
    /// component, force)` at each free term when the prescribed ones move by `delta`.
    pub fn prescribed_coupling(&self, delta: &[[f64; 2]], mut add: impl FnMut(usize, usize, f64)) {
        for c in &self.local {
            let moved: f64 = c.terms.iter().zip(&c.slots).filter(|(_, s)| s.is_none()).map(|(&(n, k, a), _)| a * delta[n][k]).sum();
            if moved != 0.0 {
                for (&(n, k, a), _) in c.terms.iter().zip(&c.slots).filter(|(_, s)| s.is_some()) {
                    add(n, k, c.penalty * a * moved);
                }
            }
        }
    }

    /// The tangent k a_i a_j: `add(node_i, component_i, node_j, component_j, value)`.
    pub fn tangent(&self, mut add: impl FnMut(usize, usize, usize, usize, f64)) {
        for c in &self.local {
            for &(a, ca, ka) in &c.terms {
                for &(b, cb, kb) in &c.terms {
                    add(a, ca, b, cb, c.penalty * ka * kb);
                }
            }
        }
    }
}

/// For each node, the largest E * measure(mean radius) of the elements holding it (0 for a
/// node of no element): the stiffness per unit strain an element gives its nodes.
fn node_stiffness_scales(model: &Model) -> Vec<f64> {
    let mut scale = vec![0.0f64; model.mesh.coords.len()];
    for (e, conn) in model.mesh.elements.iter().enumerate() {
        let nodes = &conn[..Shape::of(conn).nodes()];
        let mean_r = nodes.iter().map(|&n| model.mesh.coords[n][0]).sum::<f64>() / nodes.len() as f64;
        let s = model.materials[model.element_material[e]].youngs_modulus * model.element_section[e].measure(mean_r);
        for &n in nodes {
            scale[n] = scale[n].max(s);
        }
    }
    scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Component, Constraint, Term};

    /// A central-difference check of the tangent against the residual, at an arbitrary
    /// state, on a constraint with repeated and mixed-component terms.
    #[test]
    fn the_tangent_is_the_derivative_of_the_constraint_forces() {
        let terms = vec![(0, 0, 1.0), (1, 1, -1.73), (1, 0, 0.5), (2, 1, 2.0), (0, 0, 0.25)];
        let dof = |n: usize, c: usize| 2 * n + c;
        let slots = terms.iter().map(|&(n, c, _)| Some(dof(n, c))).collect();
        let assembly = ConstraintAssembly { local: vec![LocalConstraint { terms, slots, penalty: 3.5e4 }] };
        let x0 = [0.3, -0.2, 0.11, 0.07, -0.5, 0.9];
        let forces = |x: &[f64; 6]| {
            let mut r = [0.0; 6];
            assembly.residual(x, &[], |n, c, f| r[dof(n, c)] += f);
            r
        };
        let mut k = [[0.0; 6]; 6];
        assembly.tangent(|a, ca, b, cb, v| k[dof(a, ca)][dof(b, cb)] += v);
        let h = 1e-6;
        for j in 0..6 {
            let (mut plus, mut minus) = (x0, x0);
            plus[j] += h;
            minus[j] -= h;
            let (rp, rm) = (forces(&plus), forces(&minus));
            for i in 0..6 {
                let fd = (rp[i] - rm[i]) / (2.0 * h);
                assert!((fd - k[i][j]).abs() <= 1e-6 * k[i][j].abs().max(1.0), "({i}, {j}): fd {fd} tangent {}", k[i][j]);
            }
        }
        // the forces k g a are normal to every motion that keeps g: a . v = 0 here
        let r = forces(&x0);
        let keeps_g = [1.73, 0.0, 0.0, 1.25, 0.0, 0.0];
        let work: f64 = r.iter().zip(keeps_g).map(|(f, v)| f * v).sum();
        assert!(work.abs() < 1e-12 * r.iter().map(|v| v.abs()).sum::<f64>(), "work {work}");
    }

    /// The penalty follows the stiffest element at the constraint's nodes: E * r per radian.
    #[test]
    fn the_penalty_scales_with_the_elements_at_the_nodes() {
        let deck = "[mesh.rectangle]\nr = [10.0, 12.0]\nz = [0.0, 2.0]\ndivisions = [1, 1]\n[[material]]\nname = \"steel\"\nyoungs_modulus = 200000.0\npoissons_ratio = 0.3\n[[step]]\nname = \"s\"\nboundary = [ { set = \"bottom\", uz = 0.0 } ]\n";
        let mut model = crate::model::deck::parse(deck, std::path::Path::new("one.toml")).unwrap();
        let corner = model.mesh.elements[0][0];
        model.constraints = vec![Constraint { origin: "test".into(), terms: vec![Term { node: corner, component: Component::Z, coefficient: 1.0 }] }];
        let partition = Partition::from_element_ranks(&model.mesh, vec![0], 0, 1);
        let dofs = DofMap::new(&partition, &vec![[false; 2]; model.mesh.coords.len()]).unwrap();
        let a = ConstraintAssembly::new(&model, &partition, &dofs, |d| d as usize).unwrap();
        let e = model.materials[0].youngs_modulus;
        assert!((a.local[0].penalty - PENALTY_FACTOR * e * 11.0).abs() < 1e-9 * a.local[0].penalty, "{}", a.local[0].penalty);
    }
}

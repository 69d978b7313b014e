//! Linear multi-point constraints between displacement components: sum_i a_i u(n_i, c_i) = 0.
//! CalculiX's *EQUATION, *TIE and *PRE-TENSION SECTION all reduce to them (the reader builds
//! them); the solver enforces each by a penalty (`solve::constraints`).

use super::{Component, Model};
use crate::error::{Error, Result};

/// One term a u(node, component) of a constraint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Term {
    pub node: usize,
    pub component: Component,
    pub coefficient: f64,
}

/// sum of the terms = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Constraint {
    /// Where it comes from, for messages ("*EQUATION 3", "tie BOLT_FL, node 5836").
    pub origin: String,
    pub terms: Vec<Term>,
}

impl Constraint {
    /// The distinct nodes of its terms, in order of first appearance.
    pub fn nodes(&self) -> Vec<usize> {
        let mut nodes: Vec<usize> = Vec::with_capacity(self.terms.len());
        for t in &self.terms {
            if !nodes.contains(&t.node) {
                nodes.push(t.node);
            }
        }
        nodes
    }
}

impl Model {
    /// Refuses a constraint with no term, a node outside the mesh, a coefficient that is not
    /// finite, or only zero coefficients.
    pub(super) fn validate_constraints(&self) -> Result<()> {
        for c in &self.constraints {
            let at = |m: String| Error::input(format!("constraint {}: {m}", c.origin));
            if let Some(t) = c.terms.iter().find(|t| t.node >= self.mesh.coords.len()) {
                return Err(at(format!("node index {} is outside the mesh", t.node)));
            }
            if let Some(t) = c.terms.iter().find(|t| !t.coefficient.is_finite()) {
                return Err(at(format!("the coefficient of node {} is {}", self.mesh.node_ids[t.node], t.coefficient)));
            }
            if c.terms.iter().all(|t| t.coefficient == 0.0) {
                return Err(at("has no nonzero coefficient".into()));
            }
        }
        Ok(())
    }

    /// Whether each node appears in some constraint.
    pub fn constrained_nodes(&self) -> Vec<bool> {
        let mut on = vec![false; self.mesh.coords.len()];
        for t in self.constraints.iter().flat_map(|c| &c.terms) {
            on[t.node] = true;
        }
        on
    }

    /// The degrees of freedom that no element and no constraint touches (a pre-tension
    /// section's reference node has one): held at zero, since nothing determines them.
    pub fn unused_dofs(&self) -> Vec<[bool; 2]> {
        let mut unused = vec![[true; 2]; self.mesh.coords.len()];
        for e in 0..self.mesh.elements.len() {
            for &n in self.mesh.element_nodes(e) {
                unused[n] = [false; 2];
            }
        }
        for t in self.constraints.iter().flat_map(|c| &c.terms) {
            unused[t.node][t.component as usize] = false;
        }
        unused
    }
}

//! Linear multi-point constraints between displacement components: sum_i a_i u(n_i, c_i) = 0.
//! CalculiX's *EQUATION, *TIE and *PRE-TENSION SECTION all reduce to them (the reader builds
//! them); the solver enforces each by a penalty (`solve::problem::constraints`).

use super::{Component, Edge, Mesh, Model};
use crate::error::{Error, Result};
use crate::fe::edge_projection::project_on_edge;
use crate::fe::quadrature::GAUSS3;
use crate::fe::section::Section;
use crate::fe::shape::{line3, Shape};
use std::collections::BTreeMap;

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

/// The constraints of a tie (CalculiX's and Abaqus's *TIE; TOML's `[[tie]]`), integrated along
/// the slave surface as a mortar: for each slave node a and each component,
/// int N_a (u_slave - u_master(nearest point)) m dGamma = 0 over the part of the slave faces
/// within `tolerance` of a master face (m = r in axisymmetry, the thickness in a plane
/// section, by `sections` of the slave faces' elements), divided by int N_a m dGamma. Each
/// slave face is cut where a master corner projects on it, and each piece integrated with 3
/// Gauss points, so a uniform traction passes between non-matching quadratic meshes exactly
/// (the patch test; a tie node by node does not pass it). Also returns how many slave nodes
/// are tied and how many are farther away, left free.
pub fn tie(mesh: &Mesh, sections: &[Section], name: &str, slave: &[Edge], master: &[Edge], tolerance: f64) -> (Vec<Constraint>, usize, usize) {
    let master_nodes: Vec<[usize; 3]> = master.iter().map(|&e| mesh.edge_nodes(e)).collect();
    let nearest = |x: [f64; 2]| {
        master_nodes
            .iter()
            .filter_map(|ids| project_on_edge(x, &ids.map(|n| mesh.coords[n])).map(|p| (p.distance, p.xi.clamp(-1.0, 1.0), *ids)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .filter(|p| p.0 <= tolerance)
    };
    // per slave node: its weight int N_a m dGamma and its terms (node -> coefficient)
    let mut rows: BTreeMap<usize, (f64, BTreeMap<usize, f64>)> = BTreeMap::new();
    let mut seen: Vec<usize> = Vec::new();
    for &e in slave {
        let ids = mesh.edge_nodes(e);
        let x = ids.map(|n| mesh.coords[n]);
        seen.extend(ids);
        // where the master's corners project on this face
        let mut cuts: Vec<f64> = master_nodes
            .iter()
            .flat_map(|m| [m[0], m[1]])
            .filter_map(|n| project_on_edge(mesh.coords[n], &x).filter(|p| p.distance <= tolerance && p.xi.abs() < 1.0).map(|p| p.xi))
            .chain([-1.0, 1.0])
            .collect();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
        for piece in cuts.windows(2) {
            let half = 0.5 * (piece[1] - piece[0]);
            for (g, w) in GAUSS3 {
                let xi = 0.5 * (piece[0] + piece[1]) + half * g;
                let (n, dn) = line3(xi);
                let point = [0, 1].map(|c| (0..3).map(|k| n[k] * x[k][c]).sum::<f64>());
                let tangent = [0, 1].map(|c| (0..3).map(|k| dn[k] * x[k][c]).sum::<f64>());
                let Some((_, xi_m, m_ids)) = nearest(point) else { continue };
                let weight = w * half * tangent[0].hypot(tangent[1]) * sections[e.element].measure(point[0]);
                let n_m = line3(xi_m).0;
                for a in 0..3 {
                    let row = rows.entry(ids[a]).or_default();
                    row.0 += weight * n[a];
                    for b in 0..3 {
                        *row.1.entry(ids[b]).or_default() += weight * n[a] * n[b];
                        *row.1.entry(m_ids[b]).or_default() -= weight * n[a] * n_m[b];
                    }
                }
            }
        }
    }
    seen.sort_unstable();
    seen.dedup();
    let far = seen.iter().filter(|n| !rows.get(n).is_some_and(|r| r.0 > 0.0)).count();
    let mut constraints = Vec::new();
    for (&s, (area, terms)) in rows.iter().filter(|(_, r)| r.0 > 0.0) {
        for component in [Component::R, Component::Z] {
            let terms = terms.iter().filter(|(_, c)| c.abs() > 1e-12 * area).map(|(&node, c)| Term { node, component, coefficient: c / area }).collect();
            constraints.push(Constraint { origin: format!("tie {name}, node {}", mesh.node_ids[s]), terms });
        }
    }
    (constraints, seen.len() - far, far)
}

/// A pre-tension section built into the mesh: its constraints, each (node, partner) pair, and
/// its unit normal.
pub struct PretensionSection {
    pub constraints: Vec<Constraint>,
    pub partners: Vec<(usize, usize)>,
    pub normal: [f64; 2],
}

/// A bolt's pre-tension section across `faces` (CalculiX's *PRE-TENSION SECTION, read from its
/// pretensionsections.f; TOML's `[[pretension]]`): the faces' nodes are doubled, the partners
/// (numbered on from the highest node) taking the node's place in the faces' own elements; each
/// pair is tied across the section and opens along the normal by the same amount, the
/// `reference` node's u_1: n . (u_node - u_partner) + u_1 = 0 for the first pair, the others'
/// openings equal to the first's. A positive u_1 overlaps the two sides (the bolt shortens);
/// the force on u_1 is the pre-load. The normal is `normal`, else the faces' mean outward one.
pub fn pretension(mesh: &mut Mesh, name: &str, faces: &[Edge], reference: usize, normal: Option<[f64; 2]>) -> std::result::Result<PretensionSection, String> {
    let normal = normal.unwrap_or_else(|| faces.iter().map(|&e| outward_normal(mesh, e)).fold([0.0, 0.0], |s, n| [s[0] + n[0], s[1] + n[1]]));
    let length = normal[0].hypot(normal[1]);
    if length.is_nan() || length <= 0.0 {
        return Err(format!("pre-tension section {name}: the normal ({}, {}) has no direction", normal[0], normal[1]));
    }
    let n = [normal[0] / length, normal[1] / length];
    let t = [-n[1], n[0]];
    let along = |node: usize, v: [f64; 2], a: f64| {
        [Component::R, Component::Z].into_iter().filter(move |&c| v[c as usize].abs() > 1e-10).map(move |component| Term {
            node,
            component,
            coefficient: a * v[component as usize],
        })
    };
    let (mut constraints, mut partners) = (Vec::new(), Vec::<(usize, usize)>::new());
    for &e in faces {
        let conn = mesh.elements[e.element];
        for a in Shape::of(&conn).edge_nodes(e.side) {
            let node = conn[a];
            if let Some(&(_, p)) = partners.iter().find(|(n, _)| *n == node) {
                mesh.elements[e.element][a] = p;
                continue;
            }
            let origin = format!("pre-tension section {name}, node {}", mesh.node_ids[node]);
            let partner = mesh.coords.len();
            mesh.coords.push(mesh.coords[node]);
            mesh.node_ids.push(mesh.node_ids.iter().copied().max().unwrap_or(0) + 1);
            mesh.elements[e.element][a] = partner;
            constraints.push(Constraint { origin: origin.clone(), terms: along(node, t, 1.0).chain(along(partner, t, -1.0)).collect() });
            let opening = along(node, n, 1.0).chain(along(partner, n, -1.0));
            let terms = match partners.first() {
                None => opening.chain([Term { node: reference, component: Component::R, coefficient: 1.0 }]).collect(),
                Some(&(n0, p0)) => opening.chain(along(n0, n, -1.0)).chain(along(p0, n, 1.0)).collect(),
            };
            constraints.push(Constraint { origin, terms });
            partners.push((node, partner));
        }
    }
    Ok(PretensionSection { constraints, partners, normal: n })
}

/// The outward unit normal of an element face (elements run counter-clockwise).
fn outward_normal(mesh: &Mesh, e: Edge) -> [f64; 2] {
    let [a, b, _] = mesh.edge_nodes(e).map(|n| mesh.coords[n]);
    let (dr, dz) = (b[0] - a[0], b[1] - a[1]);
    let l = dr.hypot(dz);
    [dz / l, -dr / l]
}

/// A tie's default position tolerance: 5 % of its master faces' mean length.
pub fn default_tie_tolerance(mesh: &Mesh, master: &[Edge]) -> f64 {
    0.05 * master.iter().map(|&e| mesh.edge_length(e)).sum::<f64>() / master.len().max(1) as f64
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

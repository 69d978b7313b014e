//! The multi-point constraint cards: *EQUATION, *TIE and *PRE-TENSION SECTION, each read
//! into linear constraints between displacement components (`model::Constraint`), as
//! CalculiX builds them.

use super::cards::{error_at, Card, Location};
use super::Builder;
use crate::error::Result;
use crate::fe::shape::Shape;
use crate::model::constraint::{default_tie_tolerance, tie};
use crate::model::{Component, Constraint, Edge, Term};

/// A *TIE, resolved once the whole deck is read (its surfaces may follow it).
pub(super) struct TieDef {
    name: String,
    slave: String,
    master: String,
    tolerance: Option<f64>,
    at: Location,
}

/// A DOF number of a constraint card: 1 is u_r (u_x), 2 is u_z (u_y).
fn component(dof: f64, card: &Card, node: u64) -> Result<Component> {
    match dof {
        1.0 => Ok(Component::R),
        2.0 => Ok(Component::Z),
        _ => Err(card.error(format!("node {node}: degree of freedom {dof}: slideline's models have 1 (u_r, or u_x) and 2 (u_z, or u_y)"))),
    }
}

/// Terms of `sum a (n . u)` over the nonzero components of the in-plane vector `n`.
fn along(node: usize, n: [f64; 2], a: f64) -> impl Iterator<Item = Term> {
    [Component::R, Component::Z].into_iter().filter(move |&c| n[c as usize].abs() > 1e-10).map(move |component| Term {
        node,
        component,
        coefficient: a * n[component as usize],
    })
}

impl Builder {
    /// *EQUATION: each equation is a line with its number of terms, then the terms (node,
    /// DOF, coefficient), four to a line; sum a u = 0.
    pub(super) fn equation(&mut self, card: &Card) -> Result<()> {
        card.only(&[])?;
        let mut lines = card.data.iter();
        while let Some(head) = lines.next() {
            let count = head.number("EQUATION", 0, "number of terms", None)?;
            if !(count >= 1.0 && count.fract() == 0.0) {
                return Err(error_at(&head.at, "EQUATION", format!("number of terms {count}: a whole number >= 1")));
            }
            let origin = format!("*EQUATION ({})", head.at);
            let mut terms = Vec::with_capacity(count as usize);
            while terms.len() < count as usize {
                let Some(d) = lines.next() else {
                    return Err(error_at(&head.at, "EQUATION", format!("{count} terms announced, {} given", terms.len())));
                };
                for k in (0..d.fields.len()).step_by(3).filter(|&k| !d.fields[k].is_empty()) {
                    let node = self.node(d, "EQUATION", k)?;
                    let dof = d.number("EQUATION", k + 1, "degree of freedom", None)?;
                    let component = component(dof, card, self.mesh.node_ids[node])?;
                    let coefficient = d.number("EQUATION", k + 2, "coefficient", None)?;
                    terms.push(Term { node, component, coefficient });
                }
            }
            if terms.len() != count as usize {
                return Err(error_at(&head.at, "EQUATION", format!("{count} terms announced, {} given", terms.len())));
            }
            self.constraints.push(Constraint { origin, terms });
        }
        Ok(())
    }

    /// *TIE: kept until the deck's end (its surfaces may be defined after it).
    pub(super) fn tie(&mut self, card: &Card) -> Result<()> {
        card.only(&["NAME", "POSITION TOLERANCE", "ADJUST", "TYPE"])?;
        if let Some(t) = card.param("TYPE").filter(|t| !t.eq_ignore_ascii_case("SURFACE TO SURFACE")) {
            return Err(card.error(format!("TYPE={t}: slideline ties surfaces to surfaces (TYPE=SURFACE TO SURFACE), no cyclic symmetry or fluid ties")));
        }
        let name = card.required("NAME")?.to_uppercase();
        let tolerance = match card.param("POSITION TOLERANCE") {
            Some(t) => {
                Some(super::cards::parse_number(t).filter(|v| *v > 0.0).ok_or_else(|| card.error(format!("POSITION TOLERANCE={t}: a distance > 0 (mm)")))?)
            }
            None => None,
        };
        let [d] = card.data.as_slice() else {
            return Err(card.error("needs one line: the slave surface, the master surface"));
        };
        let surface = |k: usize| {
            d.fields
                .get(k)
                .filter(|s| !s.is_empty())
                .map(|s| s.to_uppercase())
                .ok_or_else(|| card.error("needs one line: the slave surface, the master surface"))
        };
        self.ties.push(TieDef { name, slave: surface(0)?, master: surface(1)?, tolerance, at: card.at.clone() });
        Ok(())
    }

    /// The ties' constraints (`model::constraint::tie`); the tolerance defaults to 5 % of the
    /// master faces' mean length.
    pub(super) fn resolve_ties(&mut self) -> Result<()> {
        for t in std::mem::take(&mut self.ties) {
            let faces = |name: &str| -> Result<&Vec<Edge>> {
                self.surfaces.get(name).ok_or_else(|| error_at(&t.at, "TIE", format!("tie {}: surface {name} is not defined", t.name)))
            };
            let (slave, master) = (faces(&t.slave)?, faces(&t.master)?);
            let tolerance = t.tolerance.unwrap_or_else(|| default_tie_tolerance(&self.mesh, master));
            let (constraints, tied, far) = tie(&self.mesh, &self.element_family, &t.name, slave, master, tolerance);
            if tied == 0 {
                return Err(error_at(&t.at, "TIE", format!("tie {}: no node of {} lies within {tolerance:.3e} mm of {}", t.name, t.slave, t.master)));
            }
            let beyond = if far > 0 { format!("; {far} farther than {tolerance:.3e} mm stay free") } else { String::new() };
            self.notes.push(format!("tie {} ({}): {tied} nodes of {} follow {}{beyond}", t.name, t.at, t.slave, t.master));
            self.constraints.extend(constraints);
        }
        Ok(())
    }

    /// *PRE-TENSION SECTION, SURFACE=S, NODE=N (CalculiX's `pretensionsections.f`): the
    /// section's nodes are doubled, the surface's own elements taking the new partner nodes;
    /// each pair moves together across the normal n (tangentially tied), and opens along n by
    /// the same amount, the reference node's u_1: n . (u_node - u_partner) + u_1 = 0 for the
    /// first pair, the others' openings equal to the first's. A positive u_1 overlaps the two
    /// sides: the bolt is shortened, its pre-load the force on u_1. The normal is the line
    /// after the card, else the mean outward normal of the surface's faces.
    pub(super) fn pretension_section(&mut self, card: &Card) -> Result<()> {
        card.only(&["SURFACE", "NODE", "ELEMENT"])?;
        if card.has("ELEMENT") {
            return Err(card.error("ELEMENT= (a beam's pre-tension): slideline has no beam elements; give SURFACE="));
        }
        let name = card.required("SURFACE")?.to_uppercase();
        let faces = self.surfaces.get(&name).cloned().ok_or_else(|| card.error(format!("surface {name} is not defined (define it before the card)")))?;
        let reference = {
            let id: u64 = card.required("NODE")?.trim().parse().map_err(|_| card.error("NODE=: a node number"))?;
            *self.node_index.get(&id).ok_or_else(|| card.error(format!("node {id} is not defined")))?
        };
        let normal = match card.data.first() {
            Some(d) => {
                let n: Vec<f64> = (0..3).map(|k| d.number("PRE-TENSION SECTION", k, "normal component", Some(0.0))).collect::<Result<_>>()?;
                if n[2] != 0.0 {
                    return Err(error_at(&d.at, "PRE-TENSION SECTION", "the normal has a third component: slideline's models lie in the r-z (x-y) plane"));
                }
                [n[0], n[1]]
            }
            None => faces.iter().map(|&e| self.outward_normal(e)).fold([0.0, 0.0], |s, n| [s[0] + n[0], s[1] + n[1]]),
        };
        let length = normal[0].hypot(normal[1]);
        if length.is_nan() || length <= 0.0 {
            return Err(card.error(format!("surface {name}: the normal ({}, {}) has no direction", normal[0], normal[1])));
        }
        let n = [normal[0] / length, normal[1] / length];
        let t = [-n[1], n[0]];
        let mut first: Option<(usize, usize)> = None;
        let mut partners: Vec<(usize, usize)> = Vec::new();
        for e in faces {
            let conn = self.mesh.elements[e.element];
            for a in Shape::of(&conn).edge_nodes(e.side) {
                let node = conn[a];
                if let Some(&(_, p)) = partners.iter().find(|(n, _)| *n == node) {
                    self.mesh.elements[e.element][a] = p;
                    continue;
                }
                let origin = format!("pre-tension section {name}, node {}", self.mesh.node_ids[node]);
                let partner = self.add_partner_node(node, card)?;
                self.mesh.elements[e.element][a] = partner;
                partners.push((node, partner));
                let tangential = along(node, t, 1.0).chain(along(partner, t, -1.0)).collect();
                self.constraints.push(Constraint { origin: origin.clone(), terms: tangential });
                let opening = along(node, n, 1.0).chain(along(partner, n, -1.0));
                let terms = match first {
                    None => opening.chain([Term { node: reference, component: Component::R, coefficient: 1.0 }]).collect(),
                    Some((n0, p0)) => opening.chain(along(n0, n, -1.0)).chain(along(p0, n, 1.0)).collect(),
                };
                first.get_or_insert((node, partner));
                self.constraints.push(Constraint { origin, terms });
            }
        }
        self.notes.push(format!(
            "pre-tension section {name} ({}): {} nodes doubled, normal ({:.4}, {:.4}); node {}'s u_1 is the shortening across it, its force the pre-load",
            card.at,
            partners.len(),
            n[0],
            n[1],
            self.mesh.node_ids[reference]
        ));
        self.section_partners.extend(partners);
        Ok(())
    }

    /// A new node at `node`'s place, numbered after the highest number so far (as CalculiX).
    fn add_partner_node(&mut self, node: usize, card: &Card) -> Result<usize> {
        let id = self.mesh.node_ids.iter().copied().max().unwrap_or(0) + 1;
        if self.node_index.contains_key(&id) {
            return Err(card.error(format!("node number {id} for a partner node is taken")));
        }
        let index = self.mesh.coords.len();
        self.node_index.insert(id, index);
        self.mesh.coords.push(self.mesh.coords[node]);
        self.mesh.node_ids.push(id);
        Ok(index)
    }

    /// The outward unit normal of an element face (elements run counter-clockwise).
    fn outward_normal(&self, e: Edge) -> [f64; 2] {
        let [a, b, _] = self.mesh.edge_nodes(e).map(|n| self.mesh.coords[n]);
        let (dr, dz) = (b[0] - a[0], b[1] - a[1]);
        let l = dr.hypot(dz);
        [dz / l, -dr / l]
    }
}

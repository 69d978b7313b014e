//! The multi-point constraint cards: *EQUATION, *TIE and *PRE-TENSION SECTION, each read
//! into linear constraints between displacement components (`model::Constraint`), as
//! CalculiX builds them.

use super::cards::{error_at, Card, Location};
use super::Builder;
use crate::error::Result;
use crate::model::constraint::{default_tie_tolerance, pretension, tie};
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

    /// *PRE-TENSION SECTION, SURFACE=S, NODE=N (`model::constraint::pretension`): the normal
    /// is the line after the card, else the surface's mean outward normal.
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
                Some([n[0], n[1]])
            }
            None => None,
        };
        let section = pretension(&mut self.mesh, &name, &faces, reference, normal).map_err(|m| card.error(m))?;
        for &(_, p) in &section.partners {
            self.node_index.insert(self.mesh.node_ids[p], p);
        }
        self.notes.push(format!(
            "pre-tension section {name} ({}): {} nodes doubled, normal ({:.4}, {:.4}); node {}'s u_1 is the shortening across it, its force the pre-load",
            card.at,
            section.partners.len(),
            section.normal[0],
            section.normal[1],
            self.mesh.node_ids[reference]
        ));
        self.constraints.extend(section.constraints);
        self.section_partners.extend(section.partners);
        Ok(())
    }
}

//! Material and contact cards: *ELASTIC, *PLASTIC, *EXPANSION and *DENSITY under
//! *MATERIAL, the *SURFACE INTERACTION properties, *CONTACT PAIR.

use super::cards::{error_at, normalise, Card};
use super::{single, Builder};
use crate::error::Result;
use crate::model::ContactIntegration;

impl Builder {
    pub(super) fn material_property(&mut self, card: &Card) -> Result<()> {
        let m = self.materials.last_mut().expect("checked by the caller");
        match card.keyword.as_str() {
            "ELASTIC" => {
                card.only(&["TYPE"])?;
                if card.param("TYPE").is_some_and(|t| !t.eq_ignore_ascii_case("ISO")) {
                    return Err(card.error("only TYPE=ISO (isotropic) is supported"));
                }
                let d = single(card)?;
                m.elastic = Some((d.number("ELASTIC", 0, "Young's modulus", None)?, d.number("ELASTIC", 1, "Poisson's ratio", None)?));
            }
            "EXPANSION" => {
                card.only(&["TYPE", "ZERO"])?;
                if card.param("TYPE").is_some_and(|t| !t.eq_ignore_ascii_case("ISO")) {
                    return Err(card.error("only TYPE=ISO (isotropic) is supported"));
                }
                m.expansion = single(card)?.number("EXPANSION", 0, "expansion coefficient", None)?;
                if card.has("ZERO") {
                    self.notes.push(format!(
                        "material {}: ZERO= of *EXPANSION ({}) has no effect with a constant coefficient: thermal strain alpha (T - T_initial), as in CalculiX and Abaqus",
                        m.name, card.at
                    ));
                }
            }
            "PLASTIC" => {
                card.only(&["HARDENING"])?;
                if card.param("HARDENING").is_some_and(|t| !t.eq_ignore_ascii_case("ISOTROPIC")) {
                    return Err(card.error("only HARDENING=ISOTROPIC is supported"));
                }
                m.plastic.clear();
                for d in &card.data {
                    if d.fields.len() > 2 && !d.fields[2].is_empty() {
                        return Err(error_at(&d.at, "PLASTIC", "temperature-dependent hardening is not supported"));
                    }
                    m.plastic.push((d.number("PLASTIC", 1, "plastic strain", None)?, d.number("PLASTIC", 0, "yield stress", None)?));
                }
                m.plastic_at = Some(card.at.clone());
            }
            _ => {
                card.only(&[])?;
                self.notes.push(format!("material {}: *DENSITY ({}) has no effect in a static analysis", m.name, card.at));
            }
        }
        Ok(())
    }

    pub(super) fn interaction_property(&mut self, card: &Card) -> Result<()> {
        let name = self.current_interaction.clone().expect("checked by the caller");
        if card.keyword == "FRICTION" {
            card.only(&[])?;
            let mu = card.data.first().map(|d| d.number("FRICTION", 0, "friction coefficient", None)).transpose()?.unwrap_or(0.0);
            if mu != 0.0 {
                return Err(card.error(format!("friction coefficient {mu}: slideline's contact is frictionless")));
            }
            return Ok(());
        }
        card.only(&["PRESSURE-OVERCLOSURE"])?;
        let law = card.required("PRESSURE-OVERCLOSURE")?.to_uppercase();
        if law != "LINEAR" {
            return Err(card.error(format!("PRESSURE-OVERCLOSURE={law}: slideline's penalty contact reads LINEAR (its slope is the penalty, N/mm^3)")));
        }
        let d = card.data.first().ok_or_else(|| card.error("needs the slope of the pressure-overclosure line"))?;
        let slope = d.number("SURFACE BEHAVIOR", 0, "slope (MPa/mm)", None)?;
        if d.fields.len() > 1 && d.fields.iter().skip(1).any(|f| !f.is_empty()) {
            self.notes.push(format!(
                "interaction {name}: the tension at large clearance and c0 of *SURFACE BEHAVIOR ({}) are not used: slideline's penalty gives zero pressure at any clearance",
                card.at
            ));
        }
        self.interactions.get_mut(&name).expect("registered").slope = Some(slope);
        Ok(())
    }

    pub(super) fn contact_pair(&mut self, card: &Card) -> Result<()> {
        card.only(&["INTERACTION", "TYPE", "SMALL SLIDING"])?;
        let interaction = card.required("INTERACTION")?.to_uppercase();
        if !self.interactions.contains_key(&interaction) {
            return Err(card.error(format!("surface interaction {interaction} is not defined")));
        }
        let integration = match card.param("TYPE").map(normalise).as_deref() {
            None | Some("NODE TO SURFACE") => ContactIntegration::NodeToSegment,
            Some("SURFACE TO SURFACE") => ContactIntegration::Segment,
            Some(other) => return Err(card.error(format!("TYPE={other} is not supported (NODE TO SURFACE or SURFACE TO SURFACE)"))),
        };
        if card.has("SMALL SLIDING") {
            self.notes.push(format!("*CONTACT PAIR ({}): SMALL SLIDING ignored, slideline searches for the closest segment at every iteration", card.at));
        }
        for d in &card.data {
            let name = |k: usize| -> Result<String> {
                let s = d.fields.get(k).map(|s| s.to_uppercase()).unwrap_or_default();
                if self.surfaces.contains_key(&s) {
                    Ok(s)
                } else {
                    Err(error_at(&d.at, "CONTACT PAIR", format!("surface '{s}' is not defined (define it before its use)")))
                }
            };
            self.contacts.push((name(0)?, name(1)?, interaction.clone(), integration, d.at.clone()));
        }
        Ok(())
    }
}

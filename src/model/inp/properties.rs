//! Material and contact cards: *ELASTIC, *PLASTIC, *EXPANSION and *DENSITY under
//! *MATERIAL (and the model's materials made from them), the *SURFACE INTERACTION properties,
//! *CONTACT PAIR.

use super::cards::{error_at, normalise, Card, Location};
use super::{single, Builder};
use crate::error::Result;
use crate::model::{
    default_capture_distance, Adjust, Backstress, ContactIntegration, ContactPair, Friction, KinematicHardening, Material, Penalty, Plasticity,
};

/// One data line of a *CONTACT PAIR card, as listed.
pub(super) struct ListedPair {
    pub slave: String,
    pub master: String,
    pub interaction: String,
    pub integration: ContactIntegration,
    pub adjust: Option<Adjust>,
    pub at: Location,
}

impl Builder {
    /// The deck's materials as the model's (`heat`: a heat deck's need no elastic constants).
    pub(super) fn material_list(&mut self, heat: bool) -> Result<Vec<Material>> {
        let mut materials = Vec::new();
        let mut notes = Vec::new();
        for m in &self.materials {
            let (youngs_modulus, poissons_ratio) = match (m.elastic, heat) {
                (Some(e), _) => e,
                (None, true) => (f64::NAN, f64::NAN),
                (None, false) => return Err(error_at(&m.at, "MATERIAL", format!("material {} has no *ELASTIC", m.name))),
            };
            // piecewise linear through the points, flat after the last (as Abaqus): two points
            // are linear hardening exactly up to the second
            let plasticity = match (m.plastic.as_slice(), &m.plastic_at) {
                ([], _) | (_, None) => None,
                (points, Some(at)) => Some(Plasticity::table(points).map_err(|e| error_at(at, "PLASTIC", e))?),
            };
            // HARDENING=KINEMATIC: the yield surface keeps the first point's size and moves
            // with the curve's slope (Prager), as CalculiX's linear kinematic hardening
            let (plasticity, kinematic) = match (plasticity, &m.plastic_at) {
                (Some(curve), Some(at)) if m.kinematic => {
                    let [(ep0, s0), (ep1, s1)] = m.plastic[..] else {
                        return Err(error_at(
                            at,
                            "PLASTIC",
                            format!("HARDENING=KINEMATIC takes a two-point curve (linear kinematic hardening), got {} points", m.plastic.len()),
                        ));
                    };
                    let slope = (s1 - s0) / (ep1 - ep0);
                    let terms = KinematicHardening::new(&[Backstress { modulus: slope, recall: 0.0 }]).map_err(|e| error_at(at, "PLASTIC", e))?;
                    notes.push(format!(
                        "material {}: linear kinematic hardening of slope {slope} MPa from *PLASTIC, HARDENING=KINEMATIC ({at}), continued past its last point ({ep1})",
                        m.name
                    ));
                    (Some(Plasticity::linear(curve.initial_yield_stress(), 0.0)), terms)
                }
                (p, _) => (p, KinematicHardening::NONE),
            };
            materials.push(Material {
                name: m.name.clone(),
                youngs_modulus,
                poissons_ratio,
                thermal_expansion: m.expansion,
                plasticity,
                kinematic,
                density: m.density,
                conductivity: m.conductivity,
            });
        }
        self.notes.extend(notes);
        Ok(materials)
    }

    pub(super) fn material_property(&mut self, card: &Card) -> Result<()> {
        let m = self.materials.last_mut().expect("checked by the caller");
        match card.keyword.as_str() {
            "ELASTIC" => {
                card.only(&["TYPE"])?;
                if card.param("TYPE").is_some_and(|t| !isotropic(t)) {
                    return Err(card.error("only TYPE=ISO (isotropic) is supported"));
                }
                let d = single(card)?;
                m.elastic = Some((d.number("ELASTIC", 0, "Young's modulus", None)?, d.number("ELASTIC", 1, "Poisson's ratio", None)?));
            }
            "EXPANSION" => {
                card.only(&["TYPE", "ZERO"])?;
                if card.param("TYPE").is_some_and(|t| !isotropic(t)) {
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
                m.kinematic = match card.param("HARDENING") {
                    Some(t) if t.eq_ignore_ascii_case("KINEMATIC") => true,
                    None => false,
                    Some(t) if t.eq_ignore_ascii_case("ISOTROPIC") => false,
                    Some(_) => return Err(card.error("HARDENING=ISOTROPIC or KINEMATIC (linear, a two-point curve) is supported")),
                };
                m.plastic.clear();
                for d in &card.data {
                    if d.fields.len() > 2 && !d.fields[2].is_empty() {
                        return Err(error_at(&d.at, "PLASTIC", "temperature-dependent hardening is not supported"));
                    }
                    m.plastic.push((d.number("PLASTIC", 1, "plastic strain", None)?, d.number("PLASTIC", 0, "yield stress", None)?));
                }
                m.plastic_at = Some(card.at.clone());
            }
            "CONDUCTIVITY" => {
                card.only(&["TYPE"])?;
                if card.param("TYPE").is_some_and(|t| !isotropic(t)) {
                    return Err(card.error("only TYPE=ISO (isotropic) is supported"));
                }
                if card.data.len() > 1 {
                    return Err(card.error("a conductivity that varies with temperature is not supported: give one line"));
                }
                m.conductivity = single(card)?.number("CONDUCTIVITY", 0, "conductivity", None)?;
                if !(m.conductivity > 0.0 && m.conductivity.is_finite()) {
                    return Err(card.error(format!("conductivity {} must be > 0", m.conductivity)));
                }
            }
            _ => {
                card.only(&[])?;
                m.density = single(card)?.number("DENSITY", 0, "density (t/mm^3)", None)?;
                if !(m.density >= 0.0 && m.density.is_finite()) {
                    return Err(card.error(format!("density {} must be >= 0 (t/mm^3)", m.density)));
                }
                m.density_at = Some(card.at.clone());
            }
        }
        Ok(())
    }

    pub(super) fn interaction_property(&mut self, card: &Card) -> Result<()> {
        let name = self.current_interaction.clone().expect("checked by the caller");
        if card.keyword == "FRICTION" {
            self.interactions.get_mut(&name).expect("registered").friction = friction_values(card)?;
            return Ok(());
        }
        card.only(&["PRESSURE-OVERCLOSURE"])?;
        let law = card.required("PRESSURE-OVERCLOSURE")?.to_uppercase();
        let data = || card.data.first().ok_or_else(|| card.error(format!("needs the data line of PRESSURE-OVERCLOSURE={law}")));
        let behaviour = match law.as_str() {
            "LINEAR" => {
                let d = data()?;
                let slope = d.number("SURFACE BEHAVIOR", 0, "slope (MPa/mm)", None)?;
                if d.fields.len() > 1 && d.fields.iter().skip(1).any(|f| !f.is_empty()) {
                    self.notes.push(format!(
                        "interaction {name}: the tension at large clearance and c0 of *SURFACE BEHAVIOR ({}) are not used: slideline's penalty gives zero pressure at any clearance",
                        card.at
                    ));
                }
                Penalty::Stiffness(slope)
            }
            "EXPONENTIAL" => {
                let d = data()?;
                let clearance = d.number("SURFACE BEHAVIOR", 0, "c0 (mm)", None)?;
                let pressure = d.number("SURFACE BEHAVIOR", 1, "p0 (MPa)", None)?;
                if !(clearance > 0.0 && clearance.is_finite() && pressure > 0.0 && pressure.is_finite()) {
                    return Err(card.error(format!("EXPONENTIAL needs c0 > 0 (mm) and p0 > 0 (MPa), got c0 = {clearance}, p0 = {pressure}")));
                }
                Penalty::Exponential { clearance, pressure }
            }
            _ => {
                return Err(
                    card.error(format!("PRESSURE-OVERCLOSURE={law}: slideline reads LINEAR (its slope is the penalty, N/mm^3) and EXPONENTIAL (c0, p0)"))
                )
            }
        };
        self.interactions.get_mut(&name).expect("registered").behaviour = Some(behaviour);
        Ok(())
    }

    pub(super) fn contact_pair(&mut self, card: &Card) -> Result<()> {
        card.only(&["INTERACTION", "TYPE", "SMALL SLIDING", "ADJUST"])?;
        // the interaction may be defined after the pair (CalculiX reads the deck whole)
        let interaction = card.required("INTERACTION")?.to_uppercase();
        let integration = match card.param("TYPE").map(normalise).as_deref() {
            None | Some("NODE TO SURFACE") => ContactIntegration::NodeToSegment,
            Some("SURFACE TO SURFACE") => ContactIntegration::Segment,
            Some(other) => return Err(card.error(format!("TYPE={other} is not supported (NODE TO SURFACE or SURFACE TO SURFACE)"))),
        };
        // ADJUST=clearance (mm) or ADJUST=node set
        let adjust = match card.param("ADJUST") {
            None => None,
            Some("") => return Err(card.error("ADJUST needs a value: a clearance (mm) or a node set")),
            Some(v) => Some(match v.parse::<f64>() {
                Ok(c) if c >= 0.0 && c.is_finite() => Adjust::Clearance(c),
                Ok(c) => return Err(card.error(format!("ADJUST={c}: a clearance must be >= 0"))),
                Err(_) => Adjust::NodeSet(v.to_uppercase()),
            }),
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
            self.contacts.push(ListedPair {
                slave: name(0)?,
                master: name(1)?,
                interaction: interaction.clone(),
                integration,
                adjust: adjust.clone(),
                at: d.at.clone(),
            });
        }
        Ok(())
    }

    /// The deck's contact pairs as slideline's: a pair listed both ways with one interaction
    /// is one two-pass pair (each direction carries half its force, so its penalty is twice
    /// the slope: the same forces as CalculiX's two pairs); a pair listed twice is refused.
    pub(super) fn contact_pairs(&mut self) -> Result<Vec<ListedContact>> {
        let mut contacts: Vec<ListedContact> = Vec::new();
        let mut merged = vec![false; self.contacts.len()];
        for (i, listed) in self.contacts.iter().enumerate() {
            if merged[i] {
                continue;
            }
            let ListedPair { slave, master, interaction, integration, adjust, at } = listed;
            // CalculiX's rule too: its node-based surfaces are slaves only
            if self.node_surfaces.contains_key(master) {
                return Err(error_at(at, "CONTACT PAIR", format!("surface {master} is node-based (TYPE=NODE): a master surface must be element faces")));
            }
            let found =
                self.interactions.get(interaction).ok_or_else(|| error_at(at, "CONTACT PAIR", format!("surface interaction {interaction} is not defined")))?;
            let behaviour = found.behaviour.ok_or_else(|| error_at(at, "CONTACT PAIR", format!("interaction {interaction} has no *SURFACE BEHAVIOR")))?;
            let friction = found.friction;
            if let Some(first) = self.contacts[..i].iter().find(|c| &c.slave == slave && &c.master == master) {
                return Err(error_at(at, "CONTACT PAIR", format!("the pair {slave}, {master} is already defined at {}", first.at)));
            }
            let reverse = (slave != master)
                .then(|| (i + 1..self.contacts.len()).find(|&j| !merged[j] && self.contacts[j].slave == *master && self.contacts[j].master == *slave))
                .flatten();
            let two_pass = match reverse.map(|j| (j, &self.contacts[j])) {
                // the first listing's slave is the one adjusted; CalculiX adjusting the reverse
                // listing's too would find nothing left to move
                Some((_, r)) if r.adjust.is_some() => {
                    return Err(error_at(
                        &r.at,
                        "CONTACT PAIR",
                        format!("{master}, {slave} reverses the pair at {at}: give ADJUST on the first listing of a pair listed both ways"),
                    ))
                }
                Some((j, r)) if r.interaction == *interaction && r.integration == *integration => {
                    merged[j] = true;
                    true
                }
                Some((_, r)) => {
                    return Err(error_at(
                        &r.at,
                        "CONTACT PAIR",
                        format!("{master}, {slave} reverses the pair at {at} with another interaction or type: slideline's two-pass pair takes one"),
                    ))
                }
                None => false,
            };
            let name = if slave == master { slave.clone() } else { format!("{slave}-{master}") };
            // two-pass: each direction carries half the force, so its stiffnesses are doubled
            let passes = if two_pass { 2.0 } else { 1.0 };
            let friction = pair_friction(friction, passes);
            // the stick slope CalculiX defaults to: the normal law's slope at touch
            let (law, slope) = match behaviour {
                Penalty::Exponential { clearance, pressure } => (
                    format!("exponential pressure-overclosure p = {pressure} MPa x exp(-ln(100) g / {clearance} mm) (EXPONENTIAL)"),
                    100f64.ln() * pressure / clearance,
                ),
                Penalty::Stiffness(slope) | Penalty::Factor(slope) => (format!("penalty {slope} N/mm^3 (the LINEAR slope)"), slope),
            };
            self.notes.push(format!(
                "contact {name}: {} {law}, {}{}",
                match friction {
                    None => "frictionless".to_string(),
                    Some(f) => format!(
                        "Coulomb friction mu = {} with a stick slope of {} MPa/mm,",
                        f.coefficient,
                        f.tangential_penalty.map_or(format!("{slope} (the normal slope; none given)"), |k| (k / passes).to_string())
                    ),
                },
                match integration {
                    ContactIntegration::Segment => "gap integrated along the slave surface (SURFACE TO SURFACE)",
                    ContactIntegration::NodeToSegment => "node-to-segment slide line (NODE TO SURFACE)",
                },
                if two_pass { "; listed both ways: one two-pass pair, each direction carrying half the force of a law twice as stiff" } else { "" }
            ));
            let pair = ContactPair {
                name,
                slave: slave.clone(),
                master: master.clone(),
                two_pass,
                integration: *integration,
                penalty: match behaviour {
                    Penalty::Exponential { clearance, pressure } => Penalty::Exponential { clearance, pressure: passes * pressure },
                    _ => Penalty::Stiffness(passes * slope),
                },
                capture_distance: default_capture_distance(&self.mesh, &self.surfaces[slave], &self.surfaces[master], two_pass),
                augmented_lagrangian: None,
                exclude_neighbours: 2,
                friction,
                adjust: adjust.clone(),
                slave_nodes: match integration {
                    ContactIntegration::NodeToSegment => self.node_surfaces.get(slave).map(|n| n.iter().copied().collect()),
                    ContactIntegration::Segment => None,
                },
            };
            contacts.push(ListedContact { pair, interaction: interaction.clone(), passes });
        }
        Ok(contacts)
    }
}

/// A contact pair of the deck, with its interaction's name and its number of passes (for a
/// *CHANGE FRICTION of the interaction).
pub(super) struct ListedContact {
    pub pair: ContactPair,
    pub interaction: String,
    pub passes: f64,
}

/// CalculiX's friction of an interaction: mu and the stick slope (MPa/mm) if given; None for
/// mu = 0.
pub(super) type CalculixFriction = Option<(f64, Option<f64>)>;

/// A *FRICTION card's mu and CalculiX's stick slope (MPa/mm, tangential stress per unit
/// slip), None for mu = 0; Abaqus' parameters (ELASTIC SLIP, SLIP TOLERANCE, EXPONENTIAL
/// DECAY, ...) are refused.
pub(super) fn friction_values(card: &Card) -> Result<CalculixFriction> {
    card.only(&[])?;
    let d = card.data.first().ok_or_else(|| card.error("needs the friction coefficient (mu[, stick slope])"))?;
    let mu = d.number("FRICTION", 0, "friction coefficient", None)?;
    let stick = (d.fields.len() > 1 && !d.fields[1].is_empty()).then(|| d.number("FRICTION", 1, "stick slope (MPa/mm)", None)).transpose()?;
    if !mu.is_finite() || mu < 0.0 {
        return Err(card.error(format!("friction coefficient {mu}: give mu >= 0")));
    }
    if let Some(k) = stick.filter(|k| !k.is_finite() || *k <= 0.0) {
        return Err(card.error(format!("stick slope {k}: give a positive stiffness (MPa/mm)")));
    }
    Ok((mu > 0.0).then_some((mu, stick)))
}

/// slideline's friction of a pair for CalculiX's mu and stick slope: a two-pass pair's
/// directions (`passes` = 2) each carry half the force, so its stiffness is doubled.
pub(super) fn pair_friction(friction: CalculixFriction, passes: f64) -> Option<Friction> {
    friction.map(|(mu, stick)| Friction { coefficient: mu, tangential_penalty: stick.map(|k| passes * k), elastic_slip: None })
}

/// TYPE=ISO, also spelt ISOTROPIC (both are Abaqus' and CalculiX's).
fn isotropic(t: &str) -> bool {
    t.eq_ignore_ascii_case("ISO") || t.eq_ignore_ascii_case("ISOTROPIC")
}

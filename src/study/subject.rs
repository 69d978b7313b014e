//! What a penalty study runs: the bellows or a deck, with each penalty given to every contact
//! pair, and what it measures the runs by (the node set whose axial reaction is compared, how
//! that reaction is printed, the length penetration is set against).

use crate::bellows::joint;
use crate::bellows::report::SECTOR_RADIANS;
use crate::bellows::spec::DesignSpec;
use crate::contact::surface::ContactSurface;
use crate::error::{Error, Result};
use crate::model::{Model, Penalty};

// one per study: the variants' sizes do not matter
#[allow(clippy::large_enum_variant)]
pub enum Subject {
    Bellows(DesignSpec),
    Deck(Model),
}

/// How a study's runs are compared.
pub struct Measures {
    /// History column of the compared reaction.
    pub reaction_column: String,
    /// Scale and unit for printing it (N per sector for the bellows, per ring otherwise).
    pub reaction_scale: f64,
    pub reaction_unit: &'static str,
    /// Length the penetration is compared with, and its name.
    pub length: f64,
    pub length_name: &'static str,
}

impl Subject {
    /// The model with `penalty` on every contact pair.
    pub fn model(&self, penalty: Penalty) -> Result<Model> {
        let mut m = match self {
            Subject::Bellows(p) => joint::model(p)?,
            Subject::Deck(m) => m.clone(),
        };
        for c in &mut m.contacts {
            c.penalty = penalty;
        }
        Ok(m)
    }

    /// The measures of a study comparing `reaction` (a node set; the bellows' default is its
    /// moving end, a deck must name one): the bellows' reaction per sector against the ply
    /// thickness, a deck's per ring against its shortest master edge.
    pub fn measures(&self, reaction: Option<String>) -> Result<Measures> {
        let (set, reaction_scale, reaction_unit, length, length_name) = match self {
            Subject::Bellows(p) => (reaction.unwrap_or_else(|| "moving_end".into()), -SECTOR_RADIANS, "N/sector", p.bellows.ply_thickness, "ply"),
            Subject::Deck(m) => {
                let set = reaction.ok_or_else(|| Error::input("penalty-study --deck: name the node set whose reaction to compare with --reaction SET"))?;
                if !m.node_sets.contains_key(&set) {
                    return Err(Error::input(format!("--reaction: no node set {set:?} in the deck")));
                }
                if m.contacts.is_empty() {
                    return Err(Error::input("penalty-study --deck: the deck has no contact pair"));
                }
                let shortest = |c: &crate::model::ContactPair| {
                    ContactSurface::new(&m.mesh, &m.surfaces[&c.master]).edge_length.iter().fold(f64::INFINITY, |a, &b| a.min(b))
                };
                let h = m.contacts.iter().map(shortest).fold(f64::INFINITY, f64::min);
                (set, 2.0 * std::f64::consts::PI, "N ring", h, "master edge")
            }
        };
        Ok(Measures { reaction_column: format!("reaction_{set}_z"), reaction_scale, reaction_unit, length, length_name })
    }
}

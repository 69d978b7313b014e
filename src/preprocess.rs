//! What runs between reading a deck and solving it, above both the plain model and the contact
//! kernels: the contact pairs' adjustments (slave nodes moved onto their master) and the notes on
//! what the model may not mean (pairs that never face, implausible units).

use crate::error::Result;
use crate::model::{read_deck, Model};
use std::path::Path;

/// Reads the deck at `path` ([`read_deck`]) and prepares it for the solver: the model and every
/// note, the reader's first.
pub fn prepared_deck(path: &Path) -> Result<(Model, Vec<String>)> {
    let (mut model, mut notes) = read_deck(path)?;
    notes.extend(crate::contact::adjust::adjust_slave_nodes(&mut model)?);
    notes.extend(model.never_facing_pairs());
    notes.extend(model.implausible_units());
    Ok((model, notes))
}

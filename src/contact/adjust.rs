//! A contact pair's ADJUST (CalculiX's and Abaqus's): before the analysis, slave nodes within a
//! clearance of the master surface, penetrating ones always, or the slave nodes of a node set,
//! are moved along the master's normal onto it. A change of the mesh, not a load: the adjusted
//! geometry starts stress-free, and the results file holds it. It removes the gaps and
//! overclosures of a mesh built from parts (CalculiX ccx 2.20 manual, *CONTACT PAIR).

use super::search::EdgeGrid;
use super::surface::ContactSurface;
use crate::error::{Error, Result};
use crate::model::{Adjust, Model};

/// Moves the slave nodes of every pair with an `adjust` onto its master (pairs in order, each
/// searching the mesh as the pairs before it left it); one note per such pair on what moved.
pub fn adjust_slave_nodes(model: &mut Model) -> Result<Vec<String>> {
    let mut notes = Vec::new();
    for p in 0..model.contacts.len() {
        let pair = &model.contacts[p];
        let Some(adjust) = pair.adjust.clone() else { continue };
        let name = pair.name.clone();
        if pair.slave == pair.master {
            return Err(Error::input(format!("contact '{name}': adjust is for two surfaces, not self-contact")));
        }
        let slave = ContactSurface::of_model(model, &pair.slave);
        let master = ContactSurface::of_model(model, &pair.master);
        let chosen: Vec<usize> = match &adjust {
            Adjust::Clearance(c) if !(*c >= 0.0 && c.is_finite()) => {
                return Err(Error::input(format!("contact '{name}': adjust must be a clearance >= 0 mm or a node set, got {c}")))
            }
            // a node-based slave's points are its set's nodes
            Adjust::Clearance(_) => pair.slave_nodes.clone().unwrap_or_else(|| slave.nodes.clone()),
            Adjust::NodeSet(set) => {
                let nodes = model.node_set(set).map_err(|e| Error::input(format!("contact '{name}': adjust: {e}")))?;
                if let Some(&n) = nodes.iter().find(|n| slave.index_of(**n).is_none()) {
                    return Err(Error::input(format!(
                        "contact '{name}': adjust set '{set}' holds node {}, which is not on the slave surface '{}'",
                        model.mesh.node_ids[n], pair.slave
                    )));
                }
                nodes.to_vec()
            }
        };
        // the search reaches as far as the clearance, and at least the pair's capture distance
        // (penetrating nodes are adjusted however deep, CalculiX's rule, within that reach)
        let reach = match adjust {
            Adjust::Clearance(c) => c.max(pair.capture_distance),
            Adjust::NodeSet(_) => pair.capture_distance,
        };
        let coords = &model.mesh.coords;
        let x = |n: usize| coords[n];
        let grid = EdgeGrid::new(&master, &x, reach);
        let moves: Vec<(usize, [f64; 2], f64)> = chosen
            .iter()
            .filter_map(|&n| {
                let ns = slave.node_normal(n, x);
                let (_, proj) = grid.closest_edge(&master, &x, x(n), &[], reach, None)?;
                let facing = ns[0] * proj.normal[0] + ns[1] * proj.normal[1] < 0.0;
                let within = match adjust {
                    Adjust::Clearance(c) => proj.gap <= c,
                    Adjust::NodeSet(_) => true,
                };
                (facing && within && proj.gap != 0.0).then(|| (n, [x(n)[0] - proj.gap * proj.normal[0], x(n)[1] - proj.gap * proj.normal[1]], proj.gap))
            })
            .collect();
        let largest = moves.iter().max_by(|a, b| a.2.abs().total_cmp(&b.2.abs()));
        let note = match (largest, &adjust) {
            (None, Adjust::Clearance(c)) => {
                format!("contact '{name}': adjust = {c} mm moved no slave node (none within {c} mm of the master or penetrating it)")
            }
            (None, Adjust::NodeSet(set)) => format!("contact '{name}': adjust set '{set}' moved no slave node (none facing the master within {reach} mm)"),
            (Some(&(n, _, gap)), _) => format!(
                "contact '{name}': adjust moved {} slave node(s) onto the master surface, by at most {} (node {}, {})",
                moves.len(),
                super::format_mm(gap.abs()),
                model.mesh.node_ids[n],
                if gap > 0.0 { "a gap" } else { "an overclosure" }
            ),
        };
        for &(n, to, _) in &moves {
            model.mesh.coords[n] = to;
        }
        model.mesh.validate().map_err(|e| Error::input(format!("contact '{name}': after adjust moved {} slave node(s): {e}", moves.len())))?;
        notes.push(note);
    }
    Ok(notes)
}

//! Bodies that only contact holds along the axis. While all of a body's contact is open,
//! nothing fixes its axial position: the tangent is singular there, and Newton answers that
//! with an arbitrary jump of the body. Named in a warning at a step's start and in the error
//! when a step gives up, so the user learns why instead of reading a cutback cascade.

use crate::contact::format_mm;
use crate::model::Model;
use crate::solve::problem::Problem;
use mpi::collective::SystemOperation;
use mpi::traits::*;

/// Collective: one sentence per body that has no prescribed uz in the step (`prescribed`, per
/// node and component) and whose contact pairs are all open at the problem's last evaluation.
pub fn open_holds(world: &impl Communicator, model: &Model, problem: &Problem<'_, '_>, prescribed: &[[bool; 2]]) -> Vec<String> {
    let Some(contact) = problem.contact.as_ref() else { return Vec::new() };
    let held_z: Vec<bool> = prescribed.iter().map(|m| m[1]).collect();
    let free = model.axially_free_bodies(&held_z);
    if free.is_empty() {
        return Vec::new();
    }
    let (closed, gaps): (Vec<f64>, Vec<f64>) = contact.pair_openings(model).into_iter().unzip();
    let (mut all_closed, mut all_gaps) = (vec![0.0f64; closed.len()], vec![0.0f64; gaps.len()]);
    world.all_reduce_into(&closed[..], &mut all_closed[..], SystemOperation::sum());
    world.all_reduce_into(&gaps[..], &mut all_gaps[..], SystemOperation::min());
    free.into_iter()
        .filter(|(_, pairs)| !pairs.is_empty() && pairs.iter().all(|&p| all_closed[p] == 0.0))
        .map(|(n, pairs)| {
            let open: Vec<String> = pairs
                .iter()
                .map(|&p| {
                    let gap = all_gaps[p];
                    let how = if gap.is_finite() {
                        format!("smallest gap {}", format_mm(gap))
                    } else {
                        format!("no slave node within its capture distance of {} mm", model.contacts[p].capture_distance)
                    };
                    format!("'{}' ({how})", model.contacts[p].name)
                })
                .collect();
            format!(
                "the body containing node {} (at r = {}, z = {}) has no prescribed uz and all its contact is open: {}; nothing holds it along the axis until the contact closes",
                model.mesh.node_ids[n],
                model.mesh.coords[n][0],
                model.mesh.coords[n][1],
                open.join(", ")
            )
        })
        .collect()
}

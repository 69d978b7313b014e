//! One attempt at an increment: the load predictor, then the Newton solve with its
//! augmented-Lagrangian updates.

use crate::error::Result;
use crate::material::SurfaceBranch;
use crate::model::Model;
use crate::petsc::{Matrix, NonlinearProblem, Snes, SolveReport, VecOps, Vector};
use crate::solve::problem::{LoadState, Problem};
use mpi::collective::SystemOperation;
use mpi::traits::*;

/// One attempt at an increment: a Newton solve and, for augmented-Lagrangian pairs, Uzawa
/// updates of the contact pressures followed by further solves until the penetration is
/// within tolerance (or the pair's update budget is spent). Returns the last solve's report
/// with the Newton and linear iterations of all solves, and the number of updates.
#[allow(clippy::too_many_arguments)]
pub(in crate::solve) fn solve_increment(
    world: &impl Communicator,
    model: &Model,
    snes: &mut Snes<'_>,
    problem: &mut Problem<'_, '_>,
    x: &mut Vector<'_>,
    residual: &mut Vector<'_>,
    jacobian: &mut Matrix<'_>,
) -> Result<(SolveReport, usize)> {
    let mut report = snes.solve(problem, x, residual, jacobian)?;
    let budget = model.contacts.iter().filter_map(|c| c.augmented_lagrangian).map(|a| a.max_augmentations).max().unwrap_or(0);
    let mut augmentations = 0;
    while report.converged() && augmentations < budget {
        problem.evaluate_fields(x)?; // contact states at the converged iterate
        let contact = problem.contact.as_mut().expect("augmented pairs imply contact");
        let local = contact.needs_augmentation(model) as i32;
        let mut global = 0;
        world.all_reduce_into(&local, &mut global, SystemOperation::max());
        if global == 0 {
            break;
        }
        contact.augment(model);
        augmentations += 1;
        let next = snes.solve(problem, x, residual, jacobian)?;
        report = SolveReport {
            newton_iterations: report.newton_iterations + next.newton_iterations,
            linear_iterations: report.linear_iterations + next.linear_iterations,
            ..next
        };
    }
    Ok((report, augmentations))
}

/// Load predictor for an increment whose prescribed displacements change (from `start`, the
/// converged state's loads, to the problem's current ones): the free DOFs move by the linear
/// response du = -K_ff^-1 K_fp delta, with the tangent at the converged state. Without it
/// Newton starts with the whole increment of a moved end in the row of elements next to it:
/// on the bellows a 0.2 mm step of tube B's end strains those 8 mm elements by 2.5 %, far past
/// yield, and Newton wanders between loading and unloading there. Collective; where anything
/// fails on any rank the predictor is skipped (Newton then starts from the converged state).
#[allow(clippy::too_many_arguments)]
pub(in crate::solve) fn predict(
    world: &impl Communicator,
    snes: &mut Snes<'_>,
    problem: &mut Problem<'_, '_>,
    start: LoadState,
    x: &mut Vector<'_>,
    work: &mut Vector<'_>,
    jacobian: &mut Matrix<'_>,
    correction: &mut Vector<'_>,
) -> Result<()> {
    let delta: Vec<[f64; 2]> = problem.load().prescribed.iter().zip(&start.prescribed).map(|(e, s)| [e[0] - s[0], e[1] - s[1]]).collect();
    // prescribed values are replicated: every rank takes the same branch
    if delta.iter().flatten().all(|&d| d == 0.0) {
        return Ok(());
    }
    let end = problem.set_load(start);
    // points that flowed keep flowing under a monotonic load: their elasto-plastic tangent
    // predicts the increment (the elastic one, too stiff, doubled the bellows' Newton iterations)
    let elastic = problem.set_surface_branch(SurfaceBranch::Flowing);
    // friction's tractions are held at their converged values: its tangent there is that of
    // the converged stick/slip status and slip direction, which the increment changes (a
    // reversal, nodes starting to slip), and its slip term mu dp/du then predicts a whole
    // sliding fit closed, deep (the quick bellows' sleeve with mu 0.1: 16 cutbacks in the
    // return stroke, 1 without it)
    let without = problem.set_without_friction(true);
    let coupling = problem.prescribed_coupling(x, &delta, work);
    let tangent = problem.assemble_jacobian(x, jacobian);
    problem.set_without_friction(without);
    problem.set_surface_branch(elastic);
    problem.set_load(end);
    // the refit is collective, so every rank resets
    if problem.take_structure_change() {
        snes.reset_factorisation()?;
    }
    let local = i32::from(coupling.is_ok() && tangent.is_ok());
    let mut everywhere = 0;
    world.all_reduce_into(&local, &mut everywhere, SystemOperation::min());
    if everywhere == 1 && snes.linear_solve(jacobian, work, correction)? {
        x.axpy(-1.0, correction)?;
    }
    Ok(())
}

//! The general (static) step's driver: a step's load ramped in adaptive increments, one SNES
//! solve per attempt, a failed attempt cut back and retried from the last converged state, each
//! converged increment recorded (history row, energy audit, fields and restart state).
//!
//! Each step asks for `increments` equal increments of its load factor (a step reversing the
//! previous one's prescribed motion starts at a quarter of one). An attempt that does not
//! converge (any negative SNES reason: divergence, line-search failure, NaN, an inverted element
//! or any other domain error; or a runaway, see `runaway`) is cut back by `cutback_factor` and
//! retried from the last converged state; after an easy increment the size grows by
//! `growth_factor`, never past the requested size. Below `min_increment` the run stops with
//! every converged increment in the results file.

mod attempt;
pub mod energy;
mod record;
pub(in crate::solve) mod resume;

use crate::decomposition::{DofMap, Partition};
use crate::error::{Error, Result};
use crate::model::{Convergence, GeneralStep, Predictor};
use crate::petsc::{FieldRatios, Matrix, Snes, SolveReport, VecOps, Vector};
use crate::records::last_increment::LastIncrement;
use crate::solve::context::RunContext;
use crate::solve::problem::held;
use crate::solve::problem::schedule::StepLoads;
use crate::solve::problem::{Problem, StepStart};
use crate::solve::procedures::perturbation::KeptBase;
use attempt::{predict, solve_increment};
use mpi::collective::SystemOperation;
use mpi::datatype::PartitionMut;
use mpi::traits::*;
use record::keep_base;
use resume::{Carried, ResumeAt};

/// A step reversing the previous one's prescribed motion starts at this fraction of a
/// requested increment (the joint's unloading: its first increments undo the plastic flow).
const REVERSAL_START: f64 = 0.25;

/// The general steps' own state: what one step hands the next (the state carried, the
/// perturbations' base) and the contact pattern's counts; what every procedure shares comes
/// with the run's context.
pub(in crate::solve) struct GeneralSteps {
    pub carried: Carried,
    /// The history rows a restart took over from the file it continues.
    pub continued: usize,
    pub reserved_couplings: usize,
    pub pattern_refits: usize,
    /// The perturbation steps' base state: the end of the last general step.
    pub base: Option<KeptBase>,
}

/// One step under way: its loads and unknowns, the solver's objects, where its load factor
/// stands and the next attempt's size.
struct StepState<'s, 'm> {
    s: usize,
    step: &'m GeneralStep,
    loads: StepLoads,
    prescribed: Vec<[bool; 2]>,
    dofs: DofMap,
    x: Vector<'s>,
    residual: Vector<'s>,
    correction: Vector<'s>,
    problem: Problem<'s, 'm>,
    jacobian: Matrix<'s>,
    snes: Snes<'s>,
    requested: f64,
    lambda: f64,
    size: f64,
    increment: usize,
    cutbacks: usize,
    /// Once an attempt has failed, the step's remaining solves search with `l2` (see
    /// Snes::search_after_failure); a restart finds that in the step's history.
    failed_in_step: bool,
    /// The step's last converged increment (the extrapolation's), and whether its displacement
    /// is in this file (a restart there reads it; otherwise the state keeps it).
    last: Option<LastIncrement>,
    last_in_file: bool,
}

impl GeneralSteps {
    /// The perturbation steps' base state: the end of the last general step, once converged.
    pub fn base_state(&self) -> Option<crate::solve::procedures::perturbation::BaseState<'_>> {
        let kept = self.base.as_ref()?;
        Some(crate::solve::procedures::perturbation::BaseState {
            displacement: &self.carried.displacement,
            stress: &kept.stress,
            plastic_strain: &kept.plastic_strain,
            pressures: &kept.pressures,
            contacts: &kept.contacts,
        })
    }

    /// Runs general step `s` to its end, from `resumed_here` for a restart inside it
    /// (collective).
    pub fn step<'a, 's>(&mut self, ctx: &mut RunContext<'a, 's>, s: usize, resumed_here: Option<ResumeAt>) -> Result<()> {
        let mut st = self.begin(ctx, s, resumed_here)?;
        let (model, partition, world) = (ctx.model, ctx.partition, ctx.session.world());
        let controls = model.stepping;
        let model_size = model.mesh.largest_extent();
        while st.lambda < 1.0 {
            if let Some(signal) = stop_requested(world) {
                if let Some(status) = ctx.status.as_mut() {
                    status.note(&format!("stopped by {} at lambda {:.6}", crate::interrupt::name(signal), st.lambda));
                }
                return Err(Error::Interrupted {
                    signal: crate::interrupt::name(signal),
                    what: format!("{} converged increments (step '{}' at load factor {:.6})", ctx.results.increments_written(), st.step.name, st.lambda),
                    path: ctx.options.output.clone(),
                });
            }
            // land exactly on 1 rather than leave a sliver
            let target = if st.lambda + st.size > 1.0 - 1e-9 * st.requested { 1.0 } else { st.lambda + st.size };
            st.problem.set_load(st.loads.at(model, target));
            // only where prescribed DOFs move, as the tangent predictor: under a constant load
            // the last increment's response need not go on (a shrink fit's is all in its first);
            // and not in a step that has failed an attempt (the tangent predictor follows a
            // changing contact better)
            let start_load = st.loads.at(model, st.lambda);
            let moving = st.problem.load().prescribed != start_load.prescribed;
            // a free DOF may follow the prescribed motion: the runaway check allows for it
            let prescribed_motion =
                st.problem.load().prescribed.iter().zip(&start_load.prescribed).flat_map(|(a, b)| [a[0] - b[0], a[1] - b[1]]).fold(0.0, |m, d| d.abs().max(m));
            let extrapolated = match (controls.predictor, &st.last) {
                (Predictor::Extrapolate, Some(last)) if moving && !st.failed_in_step => Some(last.extrapolate(&self.carried.displacement, target - st.lambda)),
                _ => None,
            };
            set_free_values(&mut st.x, &st.dofs, partition, extrapolated.as_deref().unwrap_or(&self.carried.displacement))?;
            st.snes.mark_increment_start(&st.x)?;
            if controls.predictor == Predictor::Tangent || (controls.predictor == Predictor::Extrapolate && extrapolated.is_none()) {
                predict(world, &mut st.snes, &mut st.problem, start_load, &mut st.x, &mut st.residual, &mut st.jacobian, &mut st.correction)?;
            }
            // rtol 1e-10: with quadratic convergence it costs at most one iteration more than
            // PETSc's 1e-8; where round-off stops the residual first (a small increment, large
            // displacements, a stiff penalty), the problem's round-off floor ends the solve
            // (see NonlinearProblem::roundoff_squares). -snes_rtol / -snes_atol override.
            st.snes.set_tolerances(None, Some(1e-10), Some(controls.max_newton_iterations))?;
            st.snes.search_after_failure(st.failed_in_step)?;
            let (mut report, augmentations) = solve_increment(world, model, &mut st.snes, &mut st.problem, &mut st.x, &mut st.residual, &mut st.jacobian)?;
            if report.converged() {
                if let Some(why) = runaway(&st.x, &mut st.correction, (&st.dofs, partition, &self.carried.displacement), model_size + prescribed_motion)? {
                    report.refuse(why);
                }
            }
            if !report.converged() {
                self.cut_back(ctx, &mut st, target, &report)?;
                continue;
            }
            self.record(ctx, &mut st, target, report, augmentations)?;
        }
        self.end(ctx, st)
    }

    /// Sets step `s` up: its loads, unknowns and solver, the load factor it starts from, and
    /// the contact at its start (an interference fit's overlap, bodies only open contact holds).
    fn begin<'a, 's>(&mut self, ctx: &mut RunContext<'a, 's>, s: usize, resumed_here: Option<ResumeAt>) -> Result<StepState<'s, 'a>> {
        let (session, model, partition) = (ctx.session, ctx.model, ctx.partition);
        let (world, comm) = (session.world(), session.comm());
        let root = world.rank() == 0;
        let controls = model.stepping;
        let step = model.general_step(s);
        let loads = StepLoads::new(model, s, self.carried.previous.as_ref(), resumed_here.as_ref().map_or(&self.carried.displacement, |r| &r.step_start));
        let prescribed = loads.prescribed_mask(model);
        // a constraint released at the step's start lets go of its reaction at once
        self.carried.audit.release(&prescribed);
        let dofs = DofMap::new(partition, &prescribed)?;
        let mut x = Vector::mpi(session, comm, dofs.local_len())?;
        let residual = x.duplicate()?;
        let correction = x.duplicate()?;
        // every contact coupling found so far is in the new step's pattern (each Jacobian
        // synchronises the pattern across ranks, so the carried one is complete)
        let mut problem = Problem::new(
            session,
            model,
            partition,
            &dofs,
            &x,
            StepStart { step: s, history: std::mem::take(&mut self.carried.history), contact: self.carried.carry.take() },
        )?;
        let jacobian = problem.jacobian_matrix()?;
        let mut snes = Snes::new(session)?;
        snes.set_field_test((controls.convergence == Convergence::Field).then(FieldRatios::default));
        snes.set_monitor(ctx.options.monitor);
        if resumed_here.is_some() {
            // the field test's time average over the step's increments before the restart
            snes.restore_force_average(self.carried.rows.iter().filter(|r| r.step == s + 1).map(|r| r.average_force));
        }
        let failed_before_restart = resumed_here.is_some() && self.carried.rows.iter().any(|r| r.step == s + 1 && r.cutbacks > 0);

        let requested = 1.0 / step.increments as f64;
        let (lambda, size, increment, cutbacks) = match &resumed_here {
            Some(r) => (r.load_factor, r.size.min(requested), r.increment, 0usize),
            None => (0.0f64, requested * if loads.reverses(self.carried.previous.as_ref()) { REVERSAL_START } else { 1.0 }, 0usize, 0usize),
        };
        if problem.contact.is_some() {
            // the contact at the step's start: overlaps in the undeformed mesh (a shrink fit)
            // are the energy audit's input, and a body only open contact holds is worth a warning
            problem.set_load(loads.at(model, lambda));
            set_free_values(&mut x, &dofs, partition, &self.carried.displacement)?;
            problem.evaluate_fields(&x)?;
            if s == 0 && resumed_here.is_none() {
                let local = problem.contact.as_ref().map_or(0.0, |c| {
                    let e = c.energies();
                    e[0] + e[1]
                });
                let mut total = 0.0;
                world.all_reduce_into(&local, &mut total, SystemOperation::sum());
                self.carried.audit.starts_overlapping = total > 0.0;
            }
            for hold in held::open_holds(world, model, &problem, &prescribed) {
                let text = format!(
                    "warning: step '{}': {hold}; close the gap in the mesh or with the pair's adjust, or prescribe its uz in an earlier step",
                    step.name
                );
                if root {
                    eprintln!("{text}");
                }
                if let Some(status) = ctx.status.as_mut() {
                    status.note(&text);
                }
            }
        }
        let failed_in_step = failed_before_restart;
        let last = resumed_here.as_ref().and_then(|r| r.last_increment.clone());
        // (a restart point always has its field: the restart reads it from the file continued)
        let last_in_file = resumed_here.is_some();
        Ok(StepState {
            s,
            step,
            loads,
            prescribed,
            dofs,
            x,
            residual,
            correction,
            problem,
            jacobian,
            snes,
            requested,
            lambda,
            size,
            increment,
            cutbacks,
            failed_in_step,
            last,
            last_in_file,
        })
    }

    /// After a failed attempt at `target`: the increment cut back (a note of it), or the run
    /// stopped with the reason when a smaller one cannot help.
    fn cut_back<'a, 's>(&mut self, ctx: &mut RunContext<'a, 's>, st: &mut StepState<'s, 'a>, target: f64, report: &SolveReport) -> Result<()> {
        let (model, partition, world) = (ctx.model, ctx.partition, ctx.session.world());
        let controls = model.stepping;
        let (s, step) = (st.s, st.step);
        st.problem.reset();
        st.failed_in_step = true;
        st.cutbacks += 1;
        st.size = (target - st.lambda) * controls.cutback_factor;
        ctx.progress.note(&format!(
            "step {}/{} {:<10} cutback at lambda {target:.6}: {}, {} Newton its; retry {:.3e}",
            s + 1,
            model.general_step_count(),
            step.name,
            report.describe(),
            report.newton_iterations,
            st.size
        ));
        if let Some(status) = ctx.status.as_mut() {
            status.note(&format!("step {} cutback at lambda {target:.6} ({} after {} Newton iterations)", s + 1, report.describe(), report.newton_iterations));
        }
        if st.size < controls.min_increment || !report.retry_may_help() {
            let stop = if report.retry_may_help() { "the increment would fall below min_increment" } else { "a smaller increment cannot help" };
            if let Some(status) = ctx.status.as_mut() {
                status.note(&format!("stopped: {stop}"));
            }
            let stop = if report.retry_may_help() { format!("{stop} = {:e}", controls.min_increment) } else { stop.to_string() };
            // why, where it is a body nothing holds at the last converged state
            st.problem.set_load(st.loads.at(model, st.lambda));
            set_free_values(&mut st.x, &st.dofs, partition, &self.carried.displacement)?;
            st.problem.evaluate_fields(&st.x)?;
            let why: String =
                held::open_holds(world, model, &st.problem, &st.prescribed).iter().map(|h| format!("; at the last converged state {h}")).collect();
            return Err(Error::NotConverged {
                step: step.name.clone(),
                load_factor: target,
                reason: format!(
                    "{} after {} Newton iterations, and {stop}{why}; the {} converged increments before are in {}",
                    report.describe(),
                    report.newton_iterations,
                    ctx.results.increments_written(),
                    ctx.options.output.display()
                ),
            });
        }
        Ok(())
    }

    /// The step's end: the perturbations' base where a restart converged no increment, and what
    /// the next step takes over.
    fn end<'a, 's>(&mut self, ctx: &mut RunContext<'a, 's>, mut st: StepState<'s, 'a>) -> Result<()> {
        let (model, partition, world) = (ctx.model, ctx.partition, ctx.session.world());
        let s = st.s;
        // a restart from the last step's end converges no increment: the state it resumes is
        // the perturbations' base
        if self.base.is_none() && model.perturbations().next().is_some() && s + 1 == model.general_step_count() && st.lambda >= 1.0 {
            st.problem.set_load(st.loads.at(model, st.lambda));
            set_free_values(&mut st.x, &st.dofs, partition, &self.carried.displacement)?;
            let fields = st.problem.evaluate_fields(&st.x)?;
            self.base = Some(keep_base(model, &mut st.problem, &fields));
        }
        (self.carried.history, self.carried.carry) = st.problem.into_history();
        // couplings are reserved per rank (each for its own engagements): report the sum
        let (local, refits) = self.carried.carry.as_ref().map_or((0, 0), |c| (c.pattern.len() as u64, c.pattern.refits));
        let mut total = 0u64;
        world.all_reduce_into(&local, &mut total, SystemOperation::sum());
        (self.reserved_couplings, self.pattern_refits) = (total as usize, refits);
        self.carried.previous = Some(st.loads);
        Ok(())
    }
}

/// Whether any rank of the run was asked to stop by a signal, and by which (collective: every
/// rank stops after the same increment).
fn stop_requested(world: &impl Communicator) -> Option<i32> {
    let mine = crate::interrupt::requested().unwrap_or(0);
    let mut any = 0;
    world.all_reduce_into(&mine, &mut any, SystemOperation::max());
    (any != 0).then_some(any)
}

/// All ranks' owned displacements into the replicated array (model node order).
pub(in crate::solve) fn gather_displacement(world: &impl Communicator, partition: &Partition, owned: &[[f64; 2]], displacement: &mut [[f64; 2]]) {
    let counts: Vec<i32> = (0..partition.size).map(|r| 2 * (partition.node_offsets[r + 1] - partition.node_offsets[r]) as i32).collect();
    let displs: Vec<i32> = partition.node_offsets[..partition.size].iter().map(|&o| 2 * o as i32).collect();
    let flat: Vec<f64> = owned.iter().flatten().copied().collect();
    let mut all = vec![0.0; 2 * displacement.len()];
    world.all_gather_varcount_into(&flat[..], &mut PartitionMut::new(&mut all[..], counts, displs));
    for (k, &n) in partition.node_order.iter().enumerate() {
        displacement[n] = [all[2 * k], all[2 * k + 1]];
    }
}

/// Displacement of this rank's owned nodes (partition order): solved values and prescribed ones.
pub(in crate::solve) fn owned_displacement(x: &Vector<'_>, dofs: &DofMap, partition: &Partition, prescribed: &[[f64; 2]]) -> Result<Vec<[f64; 2]>> {
    let first = dofs.first() as i32;
    let a = x.read()?;
    Ok(partition
        .owned_nodes()
        .iter()
        .map(|&n| std::array::from_fn(|c| if dofs.dof[n][c] >= 0 { a[(dofs.dof[n][c] - first) as usize] } else { prescribed[n][c] }))
        .collect())
}

/// Why a converged solve has run away, if it has: its free displacements moved further in the
/// increment than `size` (mm: the model's own size and the prescribed motion). Past a limit
/// load a perfectly plastic mechanism (or a body nothing holds) moves without bound at a
/// near-constant residual, and a relative convergence test can then pass at an absurd state
/// (3e9 mm, measured on a thick cylinder at its collapse pressure). `work` is overwritten.
/// Collective.
pub(in crate::solve) fn runaway(
    x: &Vector<'_>,
    work: &mut Vector<'_>,
    (dofs, partition, converged): (&DofMap, &Partition, &[[f64; 2]]),
    size: f64,
) -> Result<Option<String>> {
    set_free_values(work, dofs, partition, converged)?;
    work.axpy(-1.0, x)?;
    let moved = work.norm_max()?;
    Ok((moved > size).then(|| {
        format!("a runaway: the free displacements moved {moved:.3e} mm in the increment, more than the model's size and the prescribed motion ({size:.3e} mm)")
    }))
}

/// Puts the current displacement of this rank's free DOFs into `x` (the initial guess).
pub(in crate::solve) fn set_free_values(x: &mut Vector<'_>, dofs: &DofMap, partition: &Partition, displacement: &[[f64; 2]]) -> Result<()> {
    let first = dofs.first() as i32;
    let mut a = x.write()?;
    for &n in partition.owned_nodes() {
        for (c, &d) in dofs.dof[n].iter().enumerate() {
            if d >= 0 {
                a[(d - first) as usize] = displacement[n][c];
            }
        }
    }
    Ok(())
}

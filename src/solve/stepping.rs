//! The analysis loop: steps, adaptive increments, one SNES solve per attempt, output after
//! each converged increment.
//!
//! Each step asks for `increments` equal increments of its load factor (a step reversing the
//! previous one's prescribed motion starts at a quarter of one). An attempt that does not
//! converge (any negative SNES reason: divergence, line-search failure, NaN, an inverted element
//! or any other domain error; or a runaway, see `runaway`) is cut back by `cutback_factor` and
//! retried from the last converged state; after an easy increment the size grows by
//! `growth_factor`, never past the requested size. Below `min_increment` the run stops with
//! every converged increment in the results file.

use super::attempt::{predict, solve_increment};
use super::energy::EnergyAudit;
use super::held;
use super::problem::{LoadState, Problem, StepStart};
use super::resume::{restart_point, Carried};
use super::schedule::StepLoads;
use crate::dist::{DofMap, Partition};
use crate::element::solid::ElementEnergy;
use crate::error::{Error, Result};
use crate::io::lock::ResultsLock;
use crate::io::progress::Progress;
use crate::io::restart::{CommittedState, RestartFrom};
use crate::io::status::StatusFile;
use crate::io::{ContactSummary, HistoryRow, ResultsFile};
use crate::material::PointState;
use crate::model::perturbation::Analysis;
use crate::model::{Convergence, Model, Predictor};
use crate::petsc::{FieldRatios, PetscSession, Snes, VecOps, Vector};
use crate::records::energy::Energies;
use crate::records::increment_fields::IncrementFields;
use crate::records::last_increment::LastIncrement;
use mpi::collective::SystemOperation;
use mpi::datatype::PartitionMut;
use mpi::traits::*;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Clone, Debug)]
pub struct RunOptions {
    pub output: PathBuf,
    /// Print a line per increment (rank 0).
    pub progress: bool,
    /// The long line per increment, with every reaction and the contact.
    pub verbose: bool,
    /// A line per Newton iteration: the convergence test's measures against their bounds.
    pub monitor: bool,
    /// Continue the run that wrote this file from one of its increments.
    pub restart: Option<RestartFrom>,
}

#[derive(Clone, Debug)]
pub struct RunSummary {
    pub history: Vec<HistoryRow>,
    pub wall_time: f64,
    pub ranks: usize,
    /// Final nodal displacements (u_r, u_z) of every node, in model order.
    pub displacement: Vec<[f64; 2]>,
    /// Contact couplings (node pairs) the Jacobian's pattern held by the end, summed over the
    /// ranks that reserve them (each for its own engagements).
    pub reserved_couplings: usize,
    /// How many times a step's matrix was given room for new contact couplings in place.
    pub pattern_refits: usize,
    /// The increments a restart took over from the file it continues (0 for a fresh run):
    /// `history` holds them first, then this run's.
    pub continued: usize,
    /// Each perturbation step's name and answer, in order.
    pub perturbations: Vec<(String, crate::records::perturbation::PerturbationAnswer)>,
    /// Each heat step's name and answer, in order.
    pub heat: Vec<(String, crate::records::heat::HeatAnswer)>,
    /// Whether the model is plane (no axisymmetric element): its forces are over its
    /// thickness, not per radian.
    pub plane: bool,
}

impl RunSummary {
    /// The closing line: the whole history's increments, and for a restart how many of them
    /// this run added and how long the whole history took (its clock goes on from the file's).
    pub fn done_line(&self) -> String {
        let n = self.history.len();
        if self.continued == 0 {
            return format!("done: {n} increments in {:.2} s on {} rank(s)", self.wall_time, self.ranks);
        }
        let whole = self.history.last().map_or(self.wall_time, |r| r.wall_time);
        format!(
            "done: {n} increments, {} of them in this run ({:.2} s on {} rank(s)), continuing #{}; the whole history {:.2} s",
            n - self.continued,
            self.wall_time,
            self.ranks,
            self.continued,
            whole
        )
    }
}

/// Runs every step of `model` on the session's ranks, writing `options.output` as it goes.
/// What the perturbation steps need of the converged state `problem` is in, whose fields are
/// `fields`: this rank's stress and plastic strain, the pressures, the closed contact nodes.
fn keep_base(model: &Model, problem: &mut Problem<'_, '_>, fields: &super::kept::ElementFields) -> super::perturbation::KeptBase {
    super::perturbation::KeptBase {
        stress: fields.stress.clone(),
        plastic_strain: fields.plastic_strain.clone(),
        pressures: problem.load().pressures.clone(),
        contacts: problem.contact.as_mut().map(|c| c.base_contacts(model)).unwrap_or_default(),
    }
}

pub fn run(session: &PetscSession, model: &Model, options: &RunOptions) -> Result<RunSummary> {
    let start = Instant::now();
    let world = session.world();
    let comm = session.comm();
    let root = world.rank() == 0;
    let nodes = model.mesh.coords.len();
    let controls = model.stepping;
    let partition = Partition::new(session, &model.mesh, &super::affinity::partition_affinity(model))?;
    // the deck, its mesh and its includes are never written over, whatever name leads to them
    let written = [options.output.clone(), crate::io::xdmf::sidecar_path(&options.output), crate::io::status::status_path(&options.output)];
    for (output, input) in written.iter().flat_map(|w| model.source_files.iter().map(move |i| (w, i))) {
        crate::output_path::check_output_path(output, Some((input, "an input file of the model")))?;
    }
    // every rank sees the same file system: the sidecar and the status file, which rank 0
    // alone writes, are checked by all, so none waits for a rank that could not
    for output in &written {
        crate::output_path::check_output_path(output, None)?;
    }
    let resume = options.restart.as_ref().map(|from| restart_point(from, &options.output, model)).transpose()?;
    // PETSc's options are read (and a bad one refused) before anything is written: a rerun
    // with a misspelt type must not destroy the results file it would replace
    drop(Snes::new(session)?);
    if model.perturbations.iter().any(|p| p.analysis != crate::model::perturbation::Analysis::Response) {
        crate::petsc::eigen::check_options(session)?;
    }
    let (_lock, note) = ResultsLock::acquire(&options.output, &world)?;
    if let (true, Some(note)) = (root, note) {
        println!("note: {note}");
    }
    let mut results = ResultsFile::create(&options.output, session, model, &partition)?;
    let title = format!("{} nodes, {} elements on {} rank(s); results {}", nodes, model.mesh.elements.len(), partition.size, options.output.display());
    let mut status = if root { Some(StatusFile::create(&options.output, &title)?) } else { None };
    let progress = Progress::new(root && options.progress, options.verbose, model.steps.len());
    progress.note(&format!(
        "slideline: {} nodes, {} elements on {} rank(s); results -> {}",
        nodes,
        model.mesh.elements.len(),
        partition.size,
        options.output.display()
    ));
    // the heat steps, first: the last one's field is the general steps' temperature
    let mut heat = Vec::new();
    for h in &model.heat_steps {
        let answer = super::conduction::solve(session, model, &partition, h)?;
        stop_all_on_write_error(&world, &options.output, results.write_heat(h, &answer, &partition, model.is_axisymmetric()))?;
        progress.note(&format!("heat step '{}': solved", h.name));
        heat.push((h.name.clone(), answer));
    }
    let heated = heat.last().filter(|_| !model.steps.is_empty()).map(|(_, a)| model.with_heat_field(a.temperature.clone()));
    let model = heated.as_ref().unwrap_or(model);
    let (carried, mut resumed) = match resume {
        None => (Carried::fresh(model, &partition), None),
        Some(point) => {
            progress.note(&format!(
                "restart: continuing {} from increment #{} (step {}, load factor {})",
                point.file.display(),
                point.number,
                point.step + 1,
                point.load_factor
            ));
            let (carried, at) = Carried::restored(model, &partition, point, &mut results)?;
            (carried, Some(at))
        }
    };
    let Carried { mut displacement, mut history, mut carry, mut rows, mut previous, mut audit, wall_before } = carried;
    let continued = rows.len();
    let (mut reserved_couplings, mut pattern_refits) = (0usize, 0usize);
    let first_step = resumed.as_ref().map_or(0, |r| r.step);
    // the base state of the perturbation steps, if any: the end of the last general step
    let mut base: Option<super::perturbation::KeptBase> = None;
    let model_size = model.mesh.largest_extent();
    for (s, step) in model.steps.iter().enumerate().skip(first_step) {
        let resumed_here = resumed.take();
        let loads = StepLoads::new(model, s, previous.as_ref(), resumed_here.as_ref().map_or(&displacement, |r| &r.step_start));
        let prescribed = loads.prescribed_mask(model);
        // a constraint released at the step's start lets go of its reaction at once
        audit.release(&prescribed);
        let dofs = DofMap::new(&partition, &prescribed)?;
        let mut x = Vector::mpi(session, comm, dofs.local_len())?;
        let mut residual = x.duplicate()?;
        let mut correction = x.duplicate()?;
        // every contact coupling found so far is in the new step's pattern (each Jacobian
        // synchronises the pattern across ranks, so the carried one is complete)
        let mut problem = Problem::new(session, model, &partition, &dofs, &x, StepStart { step: s, history, contact: carry })?;
        let mut jacobian = problem.jacobian_matrix()?;
        let mut snes = Snes::new(session)?;
        snes.set_field_test((controls.convergence == Convergence::Field).then(FieldRatios::default));
        snes.set_monitor(options.monitor);
        if resumed_here.is_some() {
            // the field test's time average over the step's increments before the restart
            snes.restore_force_average(rows.iter().filter(|r| r.step == s + 1).map(|r| r.average_force));
        }
        let failed_before_restart = resumed_here.is_some() && rows.iter().any(|r| r.step == s + 1 && r.cutbacks > 0);

        let requested = 1.0 / step.increments as f64;
        let (mut lambda, mut size, mut increment, mut cutbacks) = match &resumed_here {
            Some(r) => (r.load_factor, r.size.min(requested), r.increment, 0usize),
            None => (0.0f64, requested * if loads.reverses(previous.as_ref()) { REVERSAL_START } else { 1.0 }, 0usize, 0usize),
        };
        if problem.contact.is_some() {
            // the contact at the step's start: overlaps in the undeformed mesh (a shrink fit)
            // are the energy audit's input, and a body only open contact holds is worth a warning
            problem.set_load(loads.at(model, lambda));
            set_free_values(&mut x, &dofs, &partition, &displacement)?;
            problem.evaluate_fields(&x)?;
            if s == 0 && resumed_here.is_none() {
                let local = problem.contact.as_ref().map_or(0.0, |c| {
                    let e = c.energies();
                    e[0] + e[1]
                });
                let mut total = 0.0;
                world.all_reduce_into(&local, &mut total, SystemOperation::sum());
                audit.starts_overlapping = total > 0.0;
            }
            for hold in held::open_holds(&world, model, &problem, &prescribed) {
                let text = format!(
                    "warning: step '{}': {hold}; close the gap in the mesh or with the pair's adjust, or prescribe its uz in an earlier step",
                    step.name
                );
                if root {
                    eprintln!("{text}");
                }
                if let Some(status) = status.as_mut() {
                    status.note(&text);
                }
            }
        }
        // once an attempt has failed, the step's remaining solves search with `l2` (see
        // Snes::search_after_failure); a restart finds that in the step's history
        let mut failed_in_step = failed_before_restart;
        // the step's last converged increment (the extrapolation's), and whether its
        // displacement is in this file (a restart there reads it; otherwise the state keeps it)
        let mut last = resumed_here.as_ref().and_then(|r| r.last_increment.clone());
        // (a restart point always has its field: the restart reads it from the file continued)
        let mut last_in_file = resumed_here.is_some();
        while lambda < 1.0 {
            // land exactly on 1 rather than leave a sliver
            let target = if lambda + size > 1.0 - 1e-9 * requested { 1.0 } else { lambda + size };
            problem.set_load(loads.at(model, target));
            // only where prescribed DOFs move, as the tangent predictor: under a constant load
            // the last increment's response need not go on (a shrink fit's is all in its first);
            // and not in a step that has failed an attempt (the tangent predictor follows a
            // changing contact better)
            let start_load = loads.at(model, lambda);
            let moving = problem.load().prescribed != start_load.prescribed;
            // a free DOF may follow the prescribed motion: the runaway check allows for it
            let prescribed_motion =
                problem.load().prescribed.iter().zip(&start_load.prescribed).flat_map(|(a, b)| [a[0] - b[0], a[1] - b[1]]).fold(0.0, |m, d| d.abs().max(m));
            let extrapolated = match (controls.predictor, &last) {
                (Predictor::Extrapolate, Some(last)) if moving && !failed_in_step => Some(last.extrapolate(&displacement, target - lambda)),
                _ => None,
            };
            set_free_values(&mut x, &dofs, &partition, extrapolated.as_deref().unwrap_or(&displacement))?;
            snes.mark_increment_start(&x)?;
            if controls.predictor == Predictor::Tangent || (controls.predictor == Predictor::Extrapolate && extrapolated.is_none()) {
                predict(&world, &mut snes, &mut problem, start_load, &mut x, &mut residual, &mut jacobian, &mut correction)?;
            }
            // rtol 1e-10: with quadratic convergence it costs at most one iteration more than
            // PETSc's 1e-8; where round-off stops the residual first (a small increment, large
            // displacements, a stiff penalty), the problem's round-off floor ends the solve
            // (see NonlinearProblem::roundoff_squares). -snes_rtol / -snes_atol override.
            snes.set_tolerances(None, Some(1e-10), Some(controls.max_newton_iterations))?;
            snes.search_after_failure(failed_in_step)?;
            let (mut report, augmentations) = solve_increment(&world, model, &mut snes, &mut problem, &mut x, &mut residual, &mut jacobian)?;
            if report.converged() {
                if let Some(why) = runaway(&x, &mut correction, (&dofs, &partition, &displacement), model_size + prescribed_motion)? {
                    report.refuse(why);
                }
            }
            if !report.converged() {
                problem.reset();
                failed_in_step = true;
                cutbacks += 1;
                size = (target - lambda) * controls.cutback_factor;
                progress.note(&format!(
                    "step {}/{} {:<10} cutback at lambda {target:.6}: {}, {} Newton its; retry {size:.3e}",
                    s + 1,
                    model.steps.len(),
                    step.name,
                    report.describe(),
                    report.newton_iterations
                ));
                if let Some(status) = status.as_mut() {
                    status.note(&format!(
                        "step {} cutback at lambda {target:.6} ({} after {} Newton iterations)",
                        s + 1,
                        report.describe(),
                        report.newton_iterations
                    ));
                }
                if size < controls.min_increment || !report.retry_may_help() {
                    let stop = if report.retry_may_help() { "the increment would fall below min_increment" } else { "a smaller increment cannot help" };
                    if let Some(status) = status.as_mut() {
                        status.note(&format!("stopped: {stop}"));
                    }
                    let stop = if report.retry_may_help() { format!("{stop} = {:e}", controls.min_increment) } else { stop.to_string() };
                    // why, where it is a body nothing holds at the last converged state
                    problem.set_load(loads.at(model, lambda));
                    set_free_values(&mut x, &dofs, &partition, &displacement)?;
                    problem.evaluate_fields(&x)?;
                    let why: String =
                        held::open_holds(&world, model, &problem, &prescribed).iter().map(|h| format!("; at the last converged state {h}")).collect();
                    return Err(Error::NotConverged {
                        step: step.name.clone(),
                        load_factor: target,
                        reason: format!(
                            "{} after {} Newton iterations, and {stop}{why}; the {} converged increments before are in {}",
                            report.describe(),
                            report.newton_iterations,
                            results.increments_written(),
                            options.output.display()
                        ),
                    });
                }
                continue;
            }
            let done = target - lambda;
            lambda = target;
            increment += 1;
            let output = problem.stages.output;
            let fields = output.run(|| problem.evaluate_fields(&x))??;
            problem.commit();
            let owned = owned_displacement(&x, &dofs, &partition, &problem.load().prescribed)?;
            // the extrapolating predictor's increment (kept only for it)
            let before = (controls.predictor == Predictor::Extrapolate).then(|| displacement.clone());
            gather_displacement(&world, &partition, &owned, &mut displacement);
            last = before.map(|before| LastIncrement::between(&before, &displacement, done));
            let mut force = vec![0.0; 2 * nodes];
            let local: Vec<f64> = fields.nodal_force.iter().flatten().copied().collect();
            world.all_reduce_into(&local[..], &mut force[..], SystemOperation::sum());
            let local_max_ep = fields.plastic_strain.iter().flatten().fold(0.0f64, |m, &v| m.max(v));
            let mut max_ep = 0.0;
            world.all_reduce_into(&local_max_ep, &mut max_ep, SystemOperation::max());
            if let Some(contact) = problem.contact.as_mut() {
                let local = contact.nodal_forces();
                let mut total = vec![0.0; local.len()];
                world.all_reduce_into(&local[..], &mut total[..], SystemOperation::sum());
                contact.recover_tractions(&total);
            }
            // only the end of the last general step is the perturbations' base (a run that stops
            // before it returns before them): no copy at every increment
            if !model.perturbations.is_empty() && s + 1 == model.steps.len() && lambda >= 1.0 {
                base = Some(keep_base(model, &mut problem, &fields));
            }
            let contacts = contact_summaries(&world, model, &problem);
            let load_now = loads.at(model, lambda);
            let energy = audit_increment(&world, model, &mut audit, &problem, &fields, &force, &prescribed, &displacement, &load_now);
            let reactions = loads
                .constrained_sets
                .iter()
                .map(|set| (set.clone(), model.node_sets[set].iter().fold([0.0; 2], |acc, &n| [acc[0] + force[2 * n], acc[1] + force[2 * n + 1]])))
                .collect();
            let set_displacements = loads
                .constrained_sets
                .iter()
                .map(|set| {
                    let nodes = &model.node_sets[set];
                    let sum = nodes.iter().fold([0.0; 2], |acc, &n| [acc[0] + displacement[n][0], acc[1] + displacement[n][1]]);
                    (set.clone(), sum.map(|s| s / nodes.len().max(1) as f64))
                })
                .collect();
            let row = HistoryRow {
                number: rows.len() + 1,
                step: s + 1,
                increment,
                load_factor: lambda,
                time: match step.time_span {
                    Some([start, end]) => start + lambda * (end - start),
                    None => s as f64 + lambda,
                },
                newton_iterations: report.newton_iterations,
                linear_iterations: report.linear_iterations,
                residual_norm: report.residual_norms.last().copied().unwrap_or(f64::NAN),
                residual_norms: report.residual_norms.clone(),
                average_force: snes.accept_increment(),
                cutbacks,
                augmentations,
                max_plastic_strain: max_ep,
                contacts,
                wall_time: wall_before + start.elapsed().as_secs_f64(),
                reactions,
                set_displacements,
                energy: Some(energy),
            };
            // the next attempt's size: kept after a hard increment, grown after an easy one
            size = if report.newton_iterations <= controls.easy_iterations { (done * controls.growth_factor).min(requested) } else { done };
            let with_fields = !step.without_field_output && model.output.writes_fields(row.number, lambda >= 1.0);
            let fresh_pattern = match (with_fields, problem.contact.as_mut()) {
                (true, Some(c)) => c.pattern_mut().take_fresh(),
                _ => Vec::new(),
            };
            let contact_output = problem.contact.as_ref().map(|c| c.pass_outputs()).unwrap_or_default();
            let (strain, plastic_strain_tensor) =
                if with_fields { problem.strain_fields(&displacement, &fields.thickness_stretch) } else { Default::default() };
            let reaction: Vec<[f64; 2]> =
                partition.owned_nodes().iter().map(|&n| std::array::from_fn(|c| if prescribed[n][c] { force[2 * n + c] } else { 0.0 })).collect();
            let increment_fields = IncrementFields {
                displacement: &owned,
                stress: &fields.stress,
                plastic_strain: &fields.plastic_strain,
                strain: &strain,
                plastic_strain_tensor: &plastic_strain_tensor,
                reaction: &reaction,
                temperature: &load_now.temperature,
                contact: &contact_output,
            };
            let state = with_fields.then(|| {
                let (multipliers, slip, refits) =
                    problem.contact.as_ref().map_or((Vec::new(), Vec::new(), 0), |c| (c.committed_by_node(), c.slip_by_node(), c.pattern().refits));
                CommittedState {
                    mesh: &model.mesh,
                    history: problem.committed_history(),
                    local_elements: partition.local_elements(),
                    initial: PointState::initial(model.kinematics),
                    multipliers,
                    slip,
                    fresh_pattern,
                    next_size: size,
                    // the extrapolation's increment, unless the previous increment's field has it
                    predictor_increment: (increment > 1 && !last_in_file).then(|| last.as_ref().map(|l| l.displacement.as_slice())).flatten(),
                    audit: &audit.last,
                    thermal_by_node: model.has_temperature_field(),
                    refits,
                }
            });
            let written = state.as_ref().map(|state| (&increment_fields, state));
            stop_all_on_write_error(&world, &options.output, output.run(|| results.write_increment(&step.name, &row, written, &partition))?)?;
            last_in_file = with_fields;
            if let Some(status) = status.as_mut() {
                status.record(&row);
            }
            progress.increment(&row, &step.name, model.steps.len(), !model.is_axisymmetric());
            rows.push(row);
            cutbacks = 0;
        }
        // a restart from the last step's end converges no increment: the state it resumes is
        // the perturbations' base
        if base.is_none() && !model.perturbations.is_empty() && s + 1 == model.steps.len() && lambda >= 1.0 {
            problem.set_load(loads.at(model, lambda));
            set_free_values(&mut x, &dofs, &partition, &displacement)?;
            let fields = problem.evaluate_fields(&x)?;
            base = Some(keep_base(model, &mut problem, &fields));
        }
        (history, carry) = problem.into_history();
        // couplings are reserved per rank (each for its own engagements): report the sum
        let (local, refits) = carry.as_ref().map_or((0, 0), |c| (c.pattern.len() as u64, c.pattern.refits));
        let mut total = 0u64;
        world.all_reduce_into(&local, &mut total, SystemOperation::sum());
        (reserved_couplings, pattern_refits) = (total as usize, refits);
        previous = Some(loads);
    }
    let mut perturbations = Vec::new();
    for p in &model.perturbations {
        let Some(kept) = base.as_ref() else {
            return Err(Error::input(format!("perturbation step '{}': this run converged no increment of a general step to be its base state", p.name)));
        };
        let state = super::perturbation::BaseState {
            displacement: &displacement,
            stress: &kept.stress,
            plastic_strain: &kept.plastic_strain,
            pressures: &kept.pressures,
            contacts: &kept.contacts,
        };
        // each procedure its own driver: a response (solve::perturbation) or an eigenproblem
        // (solve::modes)
        let answer = match p.analysis {
            Analysis::Response => super::perturbation::response(session, model, &partition, &state, p, false)?,
            Analysis::Frequency { eigenvalues } => super::modes::frequency(session, model, &partition, &state, p, eigenvalues)?,
            Analysis::Buckle { eigenvalues } => super::modes::buckle(session, model, &partition, &state, p, eigenvalues)?,
        };
        // notes on what an answer means belong with it, --quiet or not
        for note in answer.notes.iter().filter(|_| root) {
            match options.progress {
                true => progress.note(&format!("note: {note}")),
                false => println!("note: {note}"),
            }
        }
        // the base state's fields: the last increment's (always written: it ends its step)
        let base_group = rows.last().map(|r| format!("{:06}", r.number));
        stop_all_on_write_error(&world, &options.output, results.write_perturbation(p, &answer, &partition, base_group.as_deref()))?;
        perturbations.push((p.name.clone(), answer));
    }
    progress.finish();
    if let Some(status) = status.as_mut() {
        status.note(&format!("completed: {} increments ({} in this run) in {:.1} s", rows.len(), rows.len() - continued, start.elapsed().as_secs_f64()));
    }
    Ok(RunSummary {
        history: rows,
        wall_time: start.elapsed().as_secs_f64(),
        ranks: partition.size,
        displacement,
        reserved_couplings,
        pattern_refits,
        continued,
        perturbations,
        heat,
        plane: !model.is_axisymmetric(),
    })
}

/// The energy audit's record of a converged increment (collective: the element and contact
/// energies and the pressure loads are summed over the ranks).
#[allow(clippy::too_many_arguments)]
fn audit_increment(
    world: &impl Communicator,
    model: &Model,
    audit: &mut EnergyAudit,
    problem: &Problem<'_, '_>,
    fields: &super::problem::ElementFields,
    residual: &[f64],
    prescribed: &[[bool; 2]],
    displacement: &[[f64; 2]],
    load: &LoadState,
) -> Energies {
    let local: Vec<f64> = fields.pressure_force.iter().flatten().copied().collect();
    let mut pressure = vec![0.0; local.len()];
    world.all_reduce_into(&local[..], &mut pressure[..], SystemOperation::sum());
    let e = fields.energy;
    let contact = problem.contact.as_ref().map_or([0.0; 3], |c| c.energies());
    let local = [e.elastic, e.plastic_work, contact[0], contact[1], contact[2]];
    let mut total = [0.0; 5];
    world.all_reduce_into(&local[..], &mut total[..], SystemOperation::sum());
    let mut thermal_force = vec![0.0; fields.thermal_force.len()];
    world.all_reduce_into(&fields.thermal_force[..], &mut thermal_force[..], SystemOperation::sum());
    let elements = ElementEnergy { elastic: total[0], plastic_work: total[1] };
    let temperature = load.temperature.nodal(model.mesh.coords.len());
    audit.record(residual, prescribed, &pressure, displacement, elements, [total[2], total[3], total[4]], &thermal_force, &temperature)
}

/// Per pair, over all ranks: active slave nodes, largest penetration, total normal force.
fn contact_summaries(world: &impl Communicator, model: &Model, problem: &Problem<'_, '_>) -> Vec<ContactSummary> {
    let Some(contact) = problem.contact.as_ref() else { return Vec::new() };
    contact
        .pair_summaries(model)
        .into_iter()
        .zip(&model.contacts)
        .map(|((active, penetration, force), pair)| {
            let (mut a, mut p, mut f) = (0.0, 0.0, 0.0);
            world.all_reduce_into(&active, &mut a, SystemOperation::sum());
            world.all_reduce_into(&penetration, &mut p, SystemOperation::max());
            world.all_reduce_into(&force, &mut f, SystemOperation::sum());
            ContactSummary { name: pair.name.clone(), active_nodes: a as usize, max_penetration: p, normal_force: f }
        })
        .collect()
}

/// Why a converged solve has run away, if it has: its free displacements moved further in the
/// increment than `size` (mm: the model's own size and the prescribed motion). Past a limit
/// load a perfectly plastic mechanism (or a body nothing holds) moves without bound at a
/// near-constant residual, and a relative convergence test can then pass at an absurd state
/// (3e9 mm, measured on a thick cylinder at its collapse pressure). `work` is overwritten.
/// Collective.
fn runaway(x: &Vector<'_>, work: &mut Vector<'_>, (dofs, partition, converged): (&DofMap, &Partition, &[[f64; 2]]), size: f64) -> Result<Option<String>> {
    set_free_values(work, dofs, partition, converged)?;
    work.axpy(-1.0, x)?;
    let moved = work.norm_max()?;
    Ok((moved > size).then(|| {
        format!("a runaway: the free displacements moved {moved:.3e} mm in the increment, more than the model's size and the prescribed motion ({size:.3e} mm)")
    }))
}

/// Puts the current displacement of this rank's free DOFs into `x` (the initial guess).
fn set_free_values(x: &mut Vector<'_>, dofs: &DofMap, partition: &Partition, displacement: &[[f64; 2]]) -> Result<()> {
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

/// A write that failed on one rank (a full disk, a vanished directory) leaves the others
/// waiting inside HDF5's collective calls: the rank that met it prints the error and stops every
/// rank (MPI_Abort). The increments completed before are on disk, each flushed and marked.
fn stop_all_on_write_error<T>(world: &impl Communicator, output: &std::path::Path, result: Result<T>) -> Result<T> {
    match result {
        Err(e @ Error::Output { .. }) if world.size() > 1 => {
            eprintln!("error: {e}; every rank stops (the increments completed before are in the file)");
            // the abort runs no destructor: the lock goes first, whichever rank holds it (a
            // file that stays locked would refuse the next run into it)
            let _ = std::fs::remove_file(crate::io::lock::lock_path(output));
            world.abort(1)
        }
        other => other,
    }
}

/// Displacement of this rank's owned nodes (partition order): solved values and prescribed ones.
fn owned_displacement(x: &Vector<'_>, dofs: &DofMap, partition: &Partition, prescribed: &[[f64; 2]]) -> Result<Vec<[f64; 2]>> {
    let first = dofs.first() as i32;
    let a = x.read()?;
    Ok(partition
        .owned_nodes()
        .iter()
        .map(|&n| std::array::from_fn(|c| if dofs.dof[n][c] >= 0 { a[(dofs.dof[n][c] - first) as usize] } else { prescribed[n][c] }))
        .collect())
}

/// All ranks' owned displacements into the replicated array (model node order).
fn gather_displacement(world: &impl Communicator, partition: &Partition, owned: &[[f64; 2]], displacement: &mut [[f64; 2]]) {
    let counts: Vec<i32> = (0..partition.size).map(|r| 2 * (partition.node_offsets[r + 1] - partition.node_offsets[r]) as i32).collect();
    let displs: Vec<i32> = partition.node_offsets[..partition.size].iter().map(|&o| 2 * o as i32).collect();
    let flat: Vec<f64> = owned.iter().flatten().copied().collect();
    let mut all = vec![0.0; 2 * displacement.len()];
    world.all_gather_varcount_into(&flat[..], &mut PartitionMut::new(&mut all[..], counts, displs));
    for (k, &n) in partition.node_order.iter().enumerate() {
        displacement[n] = [all[2 * k], all[2 * k + 1]];
    }
}

/// The share of the requested increment a step starts with when it reverses the previous step's
/// prescribed motion (`StepLoads::reverses`); it grows back after easy increments as after a
/// cutback.
const REVERSAL_START: f64 = 0.25;

//! A run: its set-up (the output checked, locked and created, PETSc's options read, a restart
//! point read), then each step handed to its procedure's driver, in order, through one dispatch
//! with the run's context: the heat steps (`conduction`), the general steps (`general_step`),
//! the perturbation steps about the last one's end (`perturbation` for a response, `modes` for
//! an eigenproblem).

use crate::decomposition::Partition;
use crate::error::{Error, Result};
use crate::io::lock::ResultsLock;
use crate::io::progress::Progress;
use crate::io::restart::RestartPoint;
use crate::io::status::StatusFile;
use crate::io::{HistoryRow, ResultsFile};
use crate::model::perturbation::{Analysis, Perturbation};
use crate::model::{Model, Step};
use crate::petsc::{PetscSession, Snes};
use crate::records::perturbation::PerturbationAnswer;
use crate::solve::context::{stop_all_on_write_error, RunContext, RunOptions};
use crate::solve::procedures::general::resume::{restart_point, Carried, ResumeAt};
use crate::solve::procedures::general::GeneralSteps;
use mpi::traits::*;
use std::time::Instant;

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
    pub perturbations: Vec<(String, PerturbationAnswer)>,
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

pub fn run(session: &PetscSession, model: &Model, options: &RunOptions) -> Result<RunSummary> {
    let start = Instant::now();
    let world = session.world();
    let root = world.rank() == 0;
    let nodes = model.mesh.coords.len();
    let partition = Partition::new(session, &model.mesh, &crate::solve::contact::affinity::partition_affinity(model))?;
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
    if model.perturbations().any(|p| p.analysis != Analysis::Response) {
        crate::petsc::eigen::check_options(session)?;
    }
    let (_lock, note) = ResultsLock::acquire(&options.output, world)?;
    if let (true, Some(note)) = (root, note) {
        println!("note: {note}");
    }
    let results = ResultsFile::create(&options.output, session, model, &partition)?;
    let title = format!("{} nodes, {} elements on {} rank(s); results {}", nodes, model.mesh.elements.len(), partition.size, options.output.display());
    let status = if root { Some(StatusFile::create(&options.output, &title)?) } else { None };
    let progress = Progress::new(root && options.progress, options.verbose, model.steps.len());
    progress.note(&format!(
        "slideline: {} nodes, {} elements on {} rank(s); results -> {}",
        nodes,
        model.mesh.elements.len(),
        partition.size,
        options.output.display()
    ));
    // the model the general steps run on: with the last heat step's field as its temperature
    let heated = std::cell::OnceCell::new();
    let mut ctx = RunContext { session, model, partition: &partition, options, progress: &progress, status, results, start };
    // each step to its procedure's driver, in the list's order (validated: heat steps, general
    // steps, perturbation steps); the general steps are numbered among themselves (the results
    // file's steps), and a restart skips those before its own
    let mut heat: Vec<(String, crate::records::heat::HeatAnswer)> = Vec::new();
    let mut perturbations = Vec::new();
    let mut general: Option<(GeneralSteps, Option<ResumeAt>)> = None;
    let mut resume = resume;
    let mut general_index = 0;
    for step in &model.steps {
        if !matches!(step, Step::Heat(_)) && general.is_none() {
            if let Some((_, answer)) = heat.last().filter(|_| model.general_step_count() > 0) {
                ctx.model = heated.get_or_init(|| model.with_heat_field(answer.temperature.clone()));
            }
            general = Some(start_general(&mut ctx, resume.take())?);
        }
        match step {
            Step::Heat(h) => heat.push((h.name.clone(), heat_step(&mut ctx, h)?)),
            Step::General(_) => {
                let (steps, resumed) = general.as_mut().expect("started before the first general step");
                if general_index >= resumed.as_ref().map_or(0, |r| r.step) {
                    steps.step(&mut ctx, general_index, resumed.take())?;
                }
                general_index += 1;
            }
            Step::Perturbation(p) => {
                let (steps, _) = general.as_ref().expect("started before the first perturbation step");
                perturbations.push((p.name.clone(), perturbation(&mut ctx, steps, p)?));
            }
        }
    }
    let (general, _) = match general {
        Some(general) => general,
        None => start_general(&mut ctx, resume.take())?,
    };
    let GeneralSteps { carried: Carried { displacement, rows, .. }, continued, reserved_couplings, pattern_refits, .. } = general;
    progress.finish();
    if let Some(status) = ctx.status.as_mut() {
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

/// Heat step `h` solved and its answer written (collective).
fn heat_step(ctx: &mut RunContext<'_, '_>, h: &crate::model::heat::HeatStep) -> Result<crate::records::heat::HeatAnswer> {
    let answer = crate::solve::procedures::conduction::solve(ctx, h)?;
    let written = ctx.results.write_heat(h, &answer, ctx.partition, ctx.model.is_axisymmetric());
    stop_all_on_write_error(ctx.session.world(), &ctx.options.output, written)?;
    ctx.progress.note(&format!("heat step '{}': solved", h.name));
    Ok(answer)
}

/// The general steps' state at the first of them: fresh, or a restart point's (announced).
fn start_general(ctx: &mut RunContext<'_, '_>, resume: Option<RestartPoint>) -> Result<(GeneralSteps, Option<ResumeAt>)> {
    let (carried, resumed) = match resume {
        None => (Carried::fresh(ctx.model, ctx.partition), None),
        Some(point) => {
            ctx.progress.note(&format!(
                "restart: continuing {} from increment #{} (step {}, load factor {})",
                point.file.display(),
                point.number,
                point.step + 1,
                point.load_factor
            ));
            let (carried, at) = Carried::restored(ctx.model, ctx.partition, point, &mut ctx.results)?;
            (carried, Some(at))
        }
    };
    let continued = carried.rows.len();
    Ok((GeneralSteps { carried, continued, reserved_couplings: 0, pattern_refits: 0, base: None }, resumed))
}

/// Perturbation step `p` about the state the general steps ended in, by its procedure's
/// driver (`perturbation` for a response, `modes` for an eigenproblem), its answer written
/// (collective).
fn perturbation(ctx: &mut RunContext<'_, '_>, general: &GeneralSteps, p: &Perturbation) -> Result<PerturbationAnswer> {
    let (session, partition) = (ctx.session, ctx.partition);
    let Some(state) = general.base_state() else {
        return Err(Error::input(format!("perturbation step '{}': this run converged no increment of a general step to be its base state", p.name)));
    };
    let answer = match p.analysis {
        Analysis::Response => crate::solve::procedures::perturbation::response(ctx, &state, p, false)?,
        Analysis::Frequency { eigenvalues } => crate::solve::procedures::modes::frequency(ctx, &state, p, eigenvalues)?,
        Analysis::Buckle { eigenvalues } => crate::solve::procedures::modes::buckle(ctx, &state, p, eigenvalues)?,
    };
    // notes on what an answer means belong with it, --quiet or not
    for note in answer.notes.iter().filter(|_| session.world().rank() == 0) {
        match ctx.options.progress {
            true => ctx.progress.note(&format!("note: {note}")),
            false => println!("note: {note}"),
        }
    }
    // the base state's fields: the last increment's (always written: it ends its step)
    let base_group = general.carried.rows.last().map(|r| format!("{:06}", r.number));
    let written = ctx.results.write_perturbation(p, &answer, partition, base_group.as_deref());
    stop_all_on_write_error(session.world(), &ctx.options.output, written)?;
    Ok(answer)
}

//! A run: its set-up (the output checked, locked and created, PETSc's options read, a restart's
//! state restored), then each procedure's steps handed to its driver in order: the heat steps
//! (`conduction`), the general steps (`general_step`), the perturbation steps about the last
//! one's end (`perturbation` for a response, `modes` for an eigenproblem); and the helpers the
//! general steps' driver shares.

use super::general_step::{stop_all_on_write_error, GeneralSteps};
use super::resume::{restart_point, Carried};
use crate::dist::Partition;
use crate::error::{Error, Result};
use crate::io::lock::ResultsLock;
use crate::io::progress::Progress;
use crate::io::restart::RestartFrom;
use crate::io::status::StatusFile;
use crate::io::{HistoryRow, ResultsFile};
use crate::model::perturbation::{Analysis, Perturbation};
use crate::model::{Model, Step};
use crate::petsc::{PetscSession, Snes};
use crate::records::perturbation::PerturbationAnswer;
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
    if model.perturbations().any(|p| p.analysis != Analysis::Response) {
        crate::petsc::eigen::check_options(session)?;
    }
    let (_lock, note) = ResultsLock::acquire(&options.output, world)?;
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
    // the heat steps run first (validated: they lead the list): the last one's field is the
    // general steps' temperature, and so part of the model the rest runs on
    let mut heat = Vec::new();
    for h in model.heat_steps() {
        let answer = super::conduction::solve(session, model, &partition, h)?;
        stop_all_on_write_error(world, &options.output, results.write_heat(h, &answer, &partition, model.is_axisymmetric()))?;
        progress.note(&format!("heat step '{}': solved", h.name));
        heat.push((h.name.clone(), answer));
    }
    let heated = heat.last().filter(|_| model.general_step_count() > 0).map(|(_, a)| model.with_heat_field(a.temperature.clone()));
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
    let continued = carried.rows.len();
    let first_step = resumed.as_ref().map_or(0, |r| r.step);
    let mut general = GeneralSteps {
        session,
        model,
        partition: &partition,
        output: &options.output,
        monitor: options.monitor,
        progress: &progress,
        status: &mut status,
        results: &mut results,
        start,
        carried,
        reserved_couplings: 0,
        pattern_refits: 0,
        base: None,
    };
    // each step to its procedure's driver, in the list's order; the general steps are
    // numbered among themselves (the results file's steps), and a restart skips those before
    // its own
    let mut perturbations = Vec::new();
    let mut general_index = 0;
    for step in &model.steps {
        match step {
            Step::Heat(_) => {}
            Step::General(_) => {
                if general_index >= first_step {
                    general.step(general_index, resumed.take())?;
                }
                general_index += 1;
            }
            Step::Perturbation(p) => perturbations.push((p.name.clone(), perturbation(&mut general, p, options.progress)?)),
        }
    }
    let GeneralSteps { carried: Carried { displacement, rows, .. }, reserved_couplings, pattern_refits, .. } = general;
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

/// Perturbation step `p` about the state the general steps ended in, by its procedure's
/// driver (`perturbation` for a response, `modes` for an eigenproblem), its answer written
/// (collective).
fn perturbation(general: &mut GeneralSteps, p: &Perturbation, progress_lines: bool) -> Result<PerturbationAnswer> {
    let (session, model, partition) = (general.session, general.model, general.partition);
    let Some(kept) = general.base.as_ref() else {
        return Err(Error::input(format!("perturbation step '{}': this run converged no increment of a general step to be its base state", p.name)));
    };
    let state = super::perturbation::BaseState {
        displacement: &general.carried.displacement,
        stress: &kept.stress,
        plastic_strain: &kept.plastic_strain,
        pressures: &kept.pressures,
        contacts: &kept.contacts,
    };
    let answer = match p.analysis {
        Analysis::Response => super::perturbation::response(session, model, partition, &state, p, false)?,
        Analysis::Frequency { eigenvalues } => super::modes::frequency(session, model, partition, &state, p, eigenvalues)?,
        Analysis::Buckle { eigenvalues } => super::modes::buckle(session, model, partition, &state, p, eigenvalues)?,
    };
    // notes on what an answer means belong with it, --quiet or not
    for note in answer.notes.iter().filter(|_| session.world().rank() == 0) {
        match progress_lines {
            true => general.progress.note(&format!("note: {note}")),
            false => println!("note: {note}"),
        }
    }
    // the base state's fields: the last increment's (always written: it ends its step)
    let base_group = general.carried.rows.last().map(|r| format!("{:06}", r.number));
    let written = general.results.write_perturbation(p, &answer, partition, base_group.as_deref());
    stop_all_on_write_error(session.world(), general.output, written)?;
    Ok(answer)
}

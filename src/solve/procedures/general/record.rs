//! A converged increment recorded: committed, its history row and energy audit, its fields and
//! restart state written (when the output asks), the next attempt's size.

use super::energy::EnergyAudit;
use super::{gather_displacement, owned_displacement, GeneralSteps, StepState};
use crate::element::solid::ElementEnergy;
use crate::error::Result;
use crate::io::state::CommittedState;
use crate::io::{ContactSummary, HistoryRow};
use crate::material::PointState;
use crate::model::{Model, Predictor};
use crate::petsc::SolveReport;
use crate::records::energy::Energies;
use crate::records::increment_fields::IncrementFields;
use crate::records::last_increment::LastIncrement;
use crate::solve::context::{stop_all_on_write_error, RunContext};
use crate::solve::problem::{LoadState, Problem};
use mpi::collective::SystemOperation;
use mpi::traits::*;

impl GeneralSteps {
    /// The converged increment at `target`: committed, its history row and energy audit, its
    /// fields and restart state written (when the output asks), the next attempt's size.
    pub(super) fn record<'a, 's>(
        &mut self,
        ctx: &mut RunContext<'a, 's>,
        st: &mut StepState<'s, 'a>,
        target: f64,
        report: SolveReport,
        augmentations: usize,
    ) -> Result<()> {
        let (model, partition, world) = (ctx.model, ctx.partition, ctx.session.world());
        let controls = model.stepping;
        let nodes = model.mesh.coords.len();
        let (s, step) = (st.s, st.step);
        let done = target - st.lambda;
        st.lambda = target;
        st.increment += 1;
        let output = st.problem.stages.output;
        let fields = output.run(|| st.problem.evaluate_fields(&st.x))??;
        st.problem.commit();
        let owned = owned_displacement(&st.x, &st.dofs, partition, &st.problem.load().prescribed)?;
        // the extrapolating predictor's increment (kept only for it)
        let before = (controls.predictor == Predictor::Extrapolate).then(|| self.carried.displacement.clone());
        gather_displacement(world, partition, &owned, &mut self.carried.displacement);
        st.last = before.map(|before| LastIncrement::between(&before, &self.carried.displacement, done));
        let mut force = vec![0.0; 2 * nodes];
        let local: Vec<f64> = fields.nodal_force.iter().flatten().copied().collect();
        world.all_reduce_into(&local[..], &mut force[..], SystemOperation::sum());
        let local_max_ep = fields.plastic_strain.iter().flatten().fold(0.0f64, |m, &v| m.max(v));
        let mut max_ep = 0.0;
        world.all_reduce_into(&local_max_ep, &mut max_ep, SystemOperation::max());
        if let Some(contact) = st.problem.contact.as_mut() {
            let local = contact.nodal_forces();
            let mut total = vec![0.0; local.len()];
            world.all_reduce_into(&local[..], &mut total[..], SystemOperation::sum());
            contact.recover_tractions(&total);
        }
        // only the end of the last general step is the perturbations' base (a run that stops
        // before it returns before them): no copy at every increment
        if model.perturbations().next().is_some() && s + 1 == model.general_step_count() && st.lambda >= 1.0 {
            self.base = Some(keep_base(model, &mut st.problem, &fields));
        }
        let contacts = contact_summaries(world, model, &st.problem);
        let load_now = st.loads.at(model, st.lambda);
        let energy =
            audit_increment(world, model, &mut self.carried.audit, &st.problem, &fields, &force, &st.prescribed, &self.carried.displacement, &load_now);
        let (reactions, set_displacements) = set_totals(model, &st.loads.constrained_sets, &force, &self.carried.displacement);
        let row = HistoryRow {
            number: self.carried.rows.len() + 1,
            step: s + 1,
            increment: st.increment,
            load_factor: st.lambda,
            time: match step.time_span {
                Some([start, end]) => start + st.lambda * (end - start),
                None => s as f64 + st.lambda,
            },
            newton_iterations: report.newton_iterations,
            linear_iterations: report.linear_iterations,
            residual_norm: report.residual_norms.last().copied().unwrap_or(f64::NAN),
            residual_norms: report.residual_norms.clone(),
            average_force: st.snes.accept_increment(),
            cutbacks: st.cutbacks,
            augmentations,
            max_plastic_strain: max_ep,
            contacts,
            wall_time: self.carried.wall_before + ctx.start.elapsed().as_secs_f64(),
            reactions,
            set_displacements,
            energy: Some(energy),
        };
        // the next attempt's size: kept after a hard increment, grown after an easy one
        st.size = if report.newton_iterations <= controls.easy_iterations { (done * controls.growth_factor).min(st.requested) } else { done };
        let with_fields = !step.without_field_output && model.output.writes_fields(row.number, st.lambda >= 1.0);
        let fresh_pattern = match (with_fields, st.problem.contact.as_mut()) {
            (true, Some(c)) => c.pattern_mut().take_fresh(),
            _ => Vec::new(),
        };
        let contact_output = st.problem.contact.as_ref().map(|c| c.pass_outputs()).unwrap_or_default();
        let (strain, plastic_strain_tensor) =
            if with_fields { st.problem.strain_fields(&self.carried.displacement, &fields.thickness_stretch) } else { Default::default() };
        let backstress = (with_fields && model.has_kinematic_hardening()).then(|| st.problem.backstress_field());
        let reaction: Vec<[f64; 2]> =
            partition.owned_nodes().iter().map(|&n| std::array::from_fn(|c| if st.prescribed[n][c] { force[2 * n + c] } else { 0.0 })).collect();
        let increment_fields = IncrementFields {
            displacement: &owned,
            stress: &fields.stress,
            plastic_strain: &fields.plastic_strain,
            strain: &strain,
            plastic_strain_tensor: &plastic_strain_tensor,
            backstress: backstress.as_deref(),
            reaction: &reaction,
            temperature: &load_now.temperature,
            contact: &contact_output,
        };
        let state = with_fields.then(|| committed_state(model, partition, st, fresh_pattern, &self.carried.audit.last));
        let written = state.as_ref().map(|state| (&increment_fields, state));
        stop_all_on_write_error(world, &ctx.options.output, output.run(|| ctx.results.write_increment(&step.name, &row, written, partition))?)?;
        st.last_in_file = with_fields;
        if let Some(status) = ctx.status.as_mut() {
            status.record(&row);
        }
        ctx.progress.increment(&row, &step.name, model.general_step_count(), !model.is_axisymmetric());
        self.carried.rows.push(row);
        st.cutbacks = 0;
        Ok(())
    }
}

/// The energy audit's record of a converged increment (collective: the element and contact
/// energies and the pressure loads are summed over the ranks).
#[allow(clippy::too_many_arguments)]
pub(in crate::solve) fn audit_increment(
    world: &impl Communicator,
    model: &Model,
    audit: &mut EnergyAudit,
    problem: &Problem<'_, '_>,
    fields: &crate::solve::problem::ElementFields,
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
pub(in crate::solve) fn contact_summaries(world: &impl Communicator, model: &Model, problem: &Problem<'_, '_>) -> Vec<ContactSummary> {
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

/// Runs every step of `model` on the session's ranks, writing `options.output` as it goes.
/// What the perturbation steps need of the converged state `problem` is in, whose fields are
/// `fields`: this rank's stress and plastic strain, the pressures, the closed contact nodes.
pub(super) fn keep_base(
    model: &Model,
    problem: &mut Problem<'_, '_>,
    fields: &crate::solve::problem::kept::ElementFields,
) -> crate::solve::procedures::perturbation::KeptBase {
    crate::solve::procedures::perturbation::KeptBase {
        stress: fields.stress.clone(),
        plastic_strain: fields.plastic_strain.clone(),
        pressures: problem.load().pressures.clone(),
        contacts: problem.contact.as_mut().map(|c| c.base_contacts(model)).unwrap_or_default(),
    }
}

/// Each constrained set's reaction (the sum of its nodes' forces `force`, N per radian) and
/// mean displacement (mm): the history's force-displacement columns.
#[allow(clippy::type_complexity)]
fn set_totals(model: &Model, sets: &[String], force: &[f64], displacement: &[[f64; 2]]) -> (Vec<(String, [f64; 2])>, Vec<(String, [f64; 2])>) {
    let reactions = sets
        .iter()
        .map(|set| (set.clone(), model.node_sets[set].iter().fold([0.0; 2], |acc, &n| [acc[0] + force[2 * n], acc[1] + force[2 * n + 1]])))
        .collect();
    let set_displacements = sets
        .iter()
        .map(|set| {
            let nodes = &model.node_sets[set];
            let sum = nodes.iter().fold([0.0; 2], |acc, &n| [acc[0] + displacement[n][0], acc[1] + displacement[n][1]]);
            (set.clone(), sum.map(|s| s / nodes.len().max(1) as f64))
        })
        .collect();
    (reactions, set_displacements)
}

/// What a restart needs of the increment `st` has just converged: its Gauss points' and
/// contact's state, the pattern's fresh couplings, the next attempt's size, the predictor's
/// increment where the file will not hold it, the energy audit's starting point.
fn committed_state<'r>(
    model: &'r Model,
    partition: &'r crate::decomposition::Partition,
    st: &'r StepState<'_, '_>,
    fresh_pattern: Vec<(usize, usize)>,
    audit: &'r crate::records::energy::AuditPoint,
) -> CommittedState<'r> {
    let (multipliers, slip, refits) =
        st.problem.contact.as_ref().map_or((Vec::new(), Vec::new(), 0), |c| (c.committed_by_node(), c.slip_by_node(), c.pattern().refits));
    CommittedState {
        mesh: &model.mesh,
        history: st.problem.committed_history(),
        local_elements: partition.local_elements(),
        initial: PointState::initial(model.kinematics),
        kinematic: model.has_kinematic_hardening(),
        multipliers,
        slip,
        fresh_pattern,
        next_size: st.size,
        // the extrapolation's increment, unless the previous increment's field has it
        predictor_increment: (st.increment > 1 && !st.last_in_file).then(|| st.last.as_ref().map(|l| l.displacement.as_slice())).flatten(),
        audit,
        thermal_by_node: model.has_temperature_field(),
        refits,
    }
}

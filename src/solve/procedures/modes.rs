//! Eigenvalue perturbation steps about the base state (Abaqus's *FREQUENCY and *BUCKLE on CAXA
//! elements), one circumferential harmonic n at a time, on the harmonic element's system
//! (`solve::procedures::perturbation`) and SLEPc (`petsc::eigen`):
//! - **frequency**: K_T phi = omega^2 M phi, K_T the perturbation's stiffness about the base
//!   state (material, initial stress, follower pressure, contact), M the consistent mass, the
//!   ring factor in both; frequencies in Hz and each mode's effective mass along the mode's
//!   rigid motion (n = 0 axial, n = 1 lateral), full ring;
//! - **buckle**: (K_T + lambda K_D) phi = 0, K_D the initial-stress stiffness of the stress
//!   increment the step's axisymmetric load causes (a linear solve of that load about the base
//!   state, mode 0, twist held) plus that load's follower-pressure stiffness; the load factors
//!   lambda nearest zero, the critical load being the base's plus lambda times the step's.
//!
//! The amplitudes a step names are held at zero in the eigenproblem.

use crate::decomposition::Partition;
use crate::element::harmonic::{initial_stress_stiffness, ring_factor};
use crate::element::solid::{NODES, QUADRATURE_POINTS};
use crate::error::{Error, Result};
use crate::model::perturbation::{Analysis, HarmonicComponent, Perturbation};
use crate::model::Model;
use crate::petsc::eigen::{nearest, Pencil};
use crate::petsc::PetscSession;
use crate::records::perturbation::{EigenMode, PerturbationAnswer};
use crate::solve::context::RunContext;
use crate::solve::procedures::linear_system::{amplitudes_of, assemble, Amplitude, Block};
use crate::solve::procedures::perturbation::{
    current_positions, model_size, number, prescribed_amplitudes, pressure_stiffness_blocks, response, stiffness_blocks, BaseState,
};
use mpi::collective::SystemOperation;
use mpi::traits::*;
use std::f64::consts::PI;

/// The step's amplitudes held at zero, numbered for mode `mode`.
fn held_numbering(model: &Model, partition: &Partition, step: &Perturbation, current: &[[f64; 2]]) -> Result<(Vec<[Amplitude; 3]>, Vec<usize>)> {
    let (mut prescribed, _) = prescribed_amplitudes(model, step, current)?;
    for p in prescribed.iter_mut().flatten() {
        if p.is_some() {
            *p = Some(0.0);
        }
    }
    Ok(number(partition, &prescribed, current, step.mode, model_size(current)))
}

/// The consistent mass of this rank's elements for mode `mode` (per radian, the ring factor in).
fn mass_blocks(model: &Model, partition: &Partition, current: &[[f64; 2]], mode: u32) -> Result<Vec<Block>> {
    let factor = ring_factor(mode);
    partition
        .local_elements()
        .iter()
        .map(|&e| {
            let conn = model.mesh.elements[e];
            let geo = model.element_geometry(e, &conn.map(|n| current[n])).map_err(|m| Error::input(format!("element {}: {m}", model.mesh.element_ids[e])))?;
            let rho = model.materials[model.element_material[e]].density;
            let (points, weights) = geo.points();
            let size = 3 * NODES;
            let mut m = vec![0.0; size * size];
            for q in 0..QUADRATURE_POINTS {
                let n = &points[q].n;
                for a in 0..NODES {
                    for b in 0..NODES {
                        let v = factor * rho * weights[q] * n[a] * n[b];
                        for c in 0..3 {
                            m[(3 * b + c) * size + 3 * a + c] += v;
                        }
                    }
                }
            }
            Ok((conn.to_vec(), m))
        })
        .collect()
}

/// x^T (sum of `blocks`) y over every node (collective).
fn product(world: &impl Communicator, blocks: &[Block], x: &[[f64; 3]], y: &[[f64; 3]]) -> f64 {
    let mut local = 0.0;
    for (conn, k) in blocks {
        let size = 3 * conn.len();
        let at = |v: &[[f64; 3]], i: usize| v[conn[i / 3]][i % 3];
        for i in 0..size {
            for j in 0..size {
                local += at(x, i) * k[j * size + i] * at(y, j);
            }
        }
    }
    let mut total = 0.0;
    world.all_reduce_into(&local, &mut total, SystemOperation::sum());
    total
}

/// The rigid motions of harmonic `mode` that the step leaves free, by name: n = 0 along the
/// axis and the twist about it, n = 1 across it and the tilt (U = [z, -r, -z]); free where
/// the stiffness does not resist the motion with the step's held amplitudes zeroed (x^T K x
/// below 1e-9 of sum K_ii x_i^2: a held node makes it about 1 / nodes; collective).
fn free_rigid_motions(world: &impl Communicator, stiffness: &[Block], amplitude: &[[Amplitude; 3]], current: &[[f64; 2]], mode: u32) -> Vec<&'static str> {
    // each motion's amplitudes [U_r, U_z, U_t] at a node (r, z)
    type Motion = fn([f64; 2]) -> [f64; 3];
    let motions: Vec<(&'static str, Motion)> = match mode {
        0 => vec![("along the axis (uz)", |_| [0.0, 1.0, 0.0]), ("the twist about the axis (ut)", |x| [0.0, 0.0, x[0]])],
        1 => vec![("across the axis (the lateral offset)", |_| [1.0, 0.0, -1.0]), ("the tilt about a diameter", |x| [x[1], -x[0], -x[1]])],
        _ => Vec::new(),
    };
    motions
        .into_iter()
        .filter(|(_, motion)| {
            let x: Vec<[f64; 3]> = current
                .iter()
                .zip(amplitude)
                .map(|(&p, held)| {
                    let m = motion(p);
                    std::array::from_fn(|c| if matches!(held[c], Amplitude::Prescribed(_)) { 0.0 } else { m[c] })
                })
                .collect();
            let energy = product(world, stiffness, &x, &x);
            let mut local = 0.0;
            for (conn, k) in stiffness {
                let size = 3 * conn.len();
                local += (0..size).map(|i| k[i * size + i] * x[conn[i / 3]][i % 3].powi(2)).sum::<f64>();
            }
            let mut scale = 0.0;
            world.all_reduce_into(&local, &mut scale, SystemOperation::sum());
            energy.abs() <= 1e-9 * scale
        })
        .map(|(name, _)| name)
        .collect()
}

/// The modes of `pairs` as every node's amplitudes, scaled to a largest amplitude of 1.
fn modes_of(
    world: &impl Communicator,
    partition: &Partition,
    amplitude: &[[Amplitude; 3]],
    offsets: &[usize],
    pairs: Vec<crate::petsc::eigen::Eigenpair>,
) -> Vec<EigenMode> {
    pairs
        .into_iter()
        .map(|p| {
            let mut amplitudes = amplitudes_of(world, partition, amplitude, offsets, &p.vector);
            let largest = amplitudes.iter().flatten().fold(0.0f64, |m, &v| if v.abs() > m.abs() { v } else { m });
            if largest != 0.0 {
                amplitudes.iter_mut().flatten().for_each(|v| *v /= largest);
            }
            EigenMode { eigenvalue: p.value, amplitudes, effective_mass: None, error: p.error, critical_pressures: Vec::new() }
        })
        .collect()
}

/// The modes of A x = lambda B x nearest zero, A the sum of `a`, B of `b`, on the step's
/// numbering with its named amplitudes held (collective).
#[allow(clippy::too_many_arguments)]
fn pencil_modes(
    session: &PetscSession,
    model: &Model,
    partition: &Partition,
    step: &Perturbation,
    current: &[[f64; 2]],
    a: &[Block],
    b: &[Block],
    pencil: Pencil,
    count: usize,
) -> Result<Vec<EigenMode>> {
    let (amplitude, offsets) = held_numbering(model, partition, step, current)?;
    let local_len = offsets[partition.rank + 1] - offsets[partition.rank];
    let (a, _) = assemble(session, a, &amplitude, local_len)?;
    let (b, _) = assemble(session, b, &amplitude, local_len)?;
    let pairs = nearest(session, &a, &b, local_len, pencil, count, 0.0)?;
    Ok(modes_of(session.world(), partition, &amplitude, &offsets, pairs))
}

/// An eigenvalue step's answer, with a note where fewer modes converged than asked for.
fn answer(step: &Perturbation, modes: Vec<EigenMode>, count: usize) -> PerturbationAnswer {
    let notes =
        if modes.len() < count { vec![format!("step '{}': {} of the {count} eigenvalues asked for converged", step.name, modes.len())] } else { Vec::new() };
    PerturbationAnswer { amplitudes: Vec::new(), reactions: Vec::new(), stress: Vec::new(), modes, analysis: step.analysis, notes }
}

/// A frequency step (collective).
pub(in crate::solve) fn frequency(ctx: &RunContext<'_, '_>, base: &BaseState<'_>, step: &Perturbation, count: usize) -> Result<PerturbationAnswer> {
    let (session, model, partition) = (ctx.session, ctx.model, ctx.partition);
    let world = session.world();
    let current = current_positions(model, base);
    let (stiffness, _) = stiffness_blocks(model, partition, base, &current, step)?;
    let mass = mass_blocks(model, partition, &current, step.mode)?;
    // a follower pressure's load stiffness is unsymmetric
    let follower = model.kinematics == crate::material::Kinematics::Finite && base.pressures.iter().any(|(_, p)| *p != 0.0);
    let pencil = if follower { Pencil::General } else { Pencil::Hermitian };
    let mut modes = pencil_modes(session, model, partition, step, &current, &stiffness, &mass, pencil, count)?;
    // a free body's rigid motions are modes of (near) zero frequency: say which they are
    let (amplitude, _) = held_numbering(model, partition, step, &current)?;
    let free = free_rigid_motions(world, &stiffness, &amplitude, &current, step.mode);
    // the mode's rigid motion: n = 0 along the axis, n = 1 across it (U_r = -U_t)
    let rigid: Option<[f64; 3]> = match step.mode {
        0 => Some([0.0, 1.0, 0.0]),
        1 => Some([1.0, 0.0, -1.0]),
        _ => None,
    };
    if let Some(r) = rigid {
        let r = vec![r; current.len()];
        for mode in &mut modes {
            let generalised = product(world, &mass, &mode.amplitudes, &mode.amplitudes);
            let participation = product(world, &mass, &mode.amplitudes, &r);
            mode.effective_mass = Some(2.0 * PI * participation * participation / generalised);
        }
    }
    let mut answer = answer(step, modes, count);
    if !free.is_empty() {
        answer.notes.push(format!(
            "step '{}' (mode {}): nothing holds the model {}: its lowest frequencies (one per free motion) are rigid motions near 0 Hz, not vibrations",
            step.name,
            step.mode,
            free.join(" nor ")
        ));
    }
    Ok(answer)
}

/// A buckle step (collective).
pub(in crate::solve) fn buckle(ctx: &RunContext<'_, '_>, base: &BaseState<'_>, step: &Perturbation, count: usize) -> Result<PerturbationAnswer> {
    let (session, model, partition) = (ctx.session, ctx.model, ctx.partition);
    let current = current_positions(model, base);
    // the stress increment of the step's load: its axisymmetric response about the base state
    let load = Perturbation {
        name: step.name.clone(),
        mode: 0,
        displacements: step.displacements.iter().filter(|d| d.component != HarmonicComponent::T).cloned().collect(),
        rings: Vec::new(),
        pressures: step.pressures.clone(),
        without_contact: step.without_contact.clone(),
        analysis: Analysis::Response,
    };
    let increment = response(ctx, base, &load, true)?;
    let (stiffness, materials) = stiffness_blocks(model, partition, base, &current, step)?;
    // K_D: the stress increment's initial stress, and the step's pressures' load stiffness
    // where they follow the surface; B = -K_D
    let mut load_stiffness: Vec<Block> = materials
        .iter()
        .zip(&increment.stress)
        .zip(partition.local_elements())
        .map(|(((geo, _), stress), &e)| {
            let sigma: [[f64; 4]; QUADRATURE_POINTS] = stress.map(|s| [s[0], s[1], s[2], s[3]]);
            (model.mesh.elements[e].to_vec(), initial_stress_stiffness(geo, step.mode, &sigma).as_slice().to_vec())
        })
        .collect();
    if model.kinematics == crate::material::Kinematics::Finite {
        for p in &step.pressures {
            load_stiffness.extend(pressure_stiffness_blocks(model, partition, &current, &p.surface, p.value, step.mode));
        }
    }
    for (_, values) in &mut load_stiffness {
        values.iter_mut().for_each(|v| *v = -*v);
    }
    // a rigid motion left free makes the pencil singular: its "critical load" is noise
    let (amplitude, _) = held_numbering(model, partition, step, &current)?;
    let free = free_rigid_motions(session.world(), &stiffness, &amplitude, &current, step.mode);
    if !free.is_empty() {
        return Err(Error::input(format!(
            "buckle step '{}' (mode {}): nothing holds the model {} in this mode, so its buckling loads are not defined; hold the amplitude (a boundary entry with ur, uz or ut = 0, or a ring held at rest)",
            step.name,
            step.mode,
            free.join(" nor ")
        )));
    }
    let mut modes = pencil_modes(session, model, partition, step, &current, &stiffness, &load_stiffness, Pencil::General, count)?;
    for mode in &mut modes {
        let base_on = |surface: &str| base.pressures.iter().filter(|(s, _)| s == surface).map(|(_, p)| p).sum::<f64>();
        mode.critical_pressures = step.pressures.iter().map(|p| (p.surface.clone(), base_on(&p.surface) + mode.eigenvalue * p.value)).collect();
    }
    Ok(answer(step, modes, count))
}

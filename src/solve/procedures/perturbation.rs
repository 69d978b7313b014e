//! A linear perturbation step (`model::perturbation`) about the state the general steps end
//! in: the harmonic elements (`element::harmonic`) on the base state's current geometry, with
//! the material stiffness, the initial-stress stiffness of the base state's Cauchy stress (at
//! small strain too: the stress's work on the perturbation's rotations) and the load stiffness
//! of the pressures in force there where they follow the surface (finite kinematics),
//! assembled over the unknown
//! amplitudes [U_r, U_z, U_t] of every node and solved once with the SNES's linear solver
//! (MUMPS). The base state is read, never changed.
//!
//! The material tangent: elastic, and at the points on the yield surface at the base state J2's
//! elastic-plastic (loading) tangent with the hardening slope there (`element::harmonic::
//! elastoplastic`): the limit of the radial return's consistent tangent as the increment
//! vanishes, what a perturbation about a yielded state sees if it loads further.
//!
//! Contact: every contact node closed in the base state keeps its normal penalty stiffness (the
//! base state's axisymmetric contact tangent, geometric terms and all) on the meridional
//! amplitudes, and a node of a pair with friction sticks, along the meridian and around the
//! hoop (`contact::harmonic`); open nodes stay open. A step may leave named pairs out
//! (`without_contact`).
//!
//! On the axis (r = 0) the amplitudes obey regularity, applied to free amplitudes of nodes
//! there: n = 0, U_r = U_t = 0; n = 1, U_z = 0 and U_t = -U_r (one unknown, U_r); n >= 2, all
//! zero.

use crate::contact::harmonic::{normal_stiffness, sticking_stiffness};
use crate::decomposition::Partition;
use crate::element::harmonic::{
    elastoplastic, harmonic_strain, initial_stress_stiffness, isotropic, material_stiffness, ring_factor, HarmonicMatrix, Tangent6,
};
use crate::element::harmonic_pressure::harmonic_pressure_stiffness;
use crate::element::pressure::compute_pressure_load;
use crate::element::solid::{ElementGeometry, NODES, QUADRATURE_POINTS};
use crate::error::{Error, Result};
use crate::model::perturbation::Perturbation;
use crate::model::Model;
use crate::petsc::sys::PetscInt;
use crate::records::perturbation::{PerturbationAnswer, SetReaction};
use crate::solve::contact::BaseContact;
use crate::solve::context::RunContext;
use crate::solve::procedures::linear_system::{amplitudes_of, assemble, solve_once, Amplitude, Block};
use mpi::collective::SystemOperation;
use mpi::traits::*;
use std::f64::consts::PI;

/// The state a perturbation is about: every node's displacement, the Cauchy stress at the
/// Gauss points of this rank's elements (partition order), the pressures in force.
pub struct BaseState<'a> {
    pub displacement: &'a [[f64; 2]],
    pub stress: &'a [[[f64; 4]; QUADRATURE_POINTS]],
    /// The equivalent plastic strain at the same points.
    pub plastic_strain: &'a [[f64; QUADRATURE_POINTS]],
    pub pressures: &'a [(String, f64)],
    /// The closed contact nodes this rank owns, with their pair.
    pub contacts: &'a [(usize, BaseContact)],
}

/// What the general steps leave for the perturbation steps, kept at the end of the last one:
/// the stress and equivalent plastic strain of this rank's elements, the pressures in force.
#[derive(Clone, Debug, Default)]
pub struct KeptBase {
    pub stress: Vec<[[f64; 4]; QUADRATURE_POINTS]>,
    pub plastic_strain: Vec<[f64; QUADRATURE_POINTS]>,
    pub pressures: Vec<(String, f64)>,
    pub contacts: Vec<(usize, BaseContact)>,
}

/// A local element's geometry and the material tangent at its Gauss points.
pub(in crate::solve) type ElementMaterial = (ElementGeometry, [Tangent6; QUADRATURE_POINTS]);

/// The base state's current geometry: every node's position.
pub(in crate::solve) fn current_positions(model: &Model, base: &BaseState<'_>) -> Vec<[f64; 2]> {
    let mesh = &model.mesh;
    (0..mesh.coords.len()).map(|n| [mesh.coords[n][0] + base.displacement[n][0], mesh.coords[n][1] + base.displacement[n][1]]).collect()
}

/// The stiffness of `step`'s mode about `base` on this rank: its elements' material and
/// initial-stress matrices, the base pressures' load stiffness (finite kinematics), the closed
/// contact nodes of the pairs the step does not leave out; and each element's material tangent.
pub(in crate::solve) fn stiffness_blocks(
    model: &Model,
    partition: &Partition,
    base: &BaseState<'_>,
    current: &[[f64; 2]],
    step: &Perturbation,
) -> Result<(Vec<Block>, Vec<ElementMaterial>)> {
    let (mode, without_contact, step) = (step.mode, &step.without_contact, &step.name);
    let mesh = &model.mesh;
    let mut blocks: Vec<Block> = Vec::new();
    let mut materials: Vec<ElementMaterial> = Vec::new();
    for (k, &e) in partition.local_elements().iter().enumerate() {
        let conn = mesh.elements[e];
        let x: [[f64; 2]; NODES] = conn.map(|n| current[n]);
        let geo = model.element_geometry(e, &x).map_err(|m| Error::input(format!("perturbation step '{step}': element {}: {m}", mesh.element_ids[e])))?;
        let m = &model.materials[model.element_material[e]];
        let j2 = crate::solve::problem::material_kernel(m);
        // points on the yield surface take the elastic-plastic tangent (loading), the others
        // the elastic one
        let d: [Tangent6; QUADRATURE_POINTS] = std::array::from_fn(|q| {
            let (stress, ep) = (&base.stress[k][q], base.plastic_strain[k][q]);
            let on_surface = ep > 0.0 && crate::fe::axisymmetric::von_mises(stress) >= (1.0 - 1e-6) * j2.hardening.yield_stress(ep);
            match on_surface {
                true => elastoplastic(m.youngs_modulus, m.poissons_ratio, j2.hardening.segment(ep).0, stress),
                false => isotropic(m.youngs_modulus, m.poissons_ratio),
            }
        });
        let ke: HarmonicMatrix = material_stiffness(&geo, mode, &d) + initial_stress_stiffness(&geo, mode, &base.stress[k]);
        blocks.push((conn.to_vec(), ke.as_slice().to_vec()));
        materials.push((geo, d));
    }
    // the base's pressures follow the surface (a load stiffness) where the kinematics are finite;
    // at small strain they are dead loads, with none
    if model.kinematics == crate::material::Kinematics::Finite {
        for (surface, p) in base.pressures {
            blocks.extend(pressure_stiffness_blocks(model, partition, current, surface, *p, mode));
        }
    }
    // the closed contact nodes of the pairs the step keeps
    let left_out: Vec<usize> = without_contact.iter().filter_map(|name| model.contacts.iter().position(|c| &c.name == name)).collect();
    for (_, contact) in base.contacts.iter().filter(|(pair, _)| !left_out.contains(pair)) {
        match contact {
            BaseContact::Normal { nodes, tangent } => blocks.push((nodes.clone(), normal_stiffness(tangent, nodes.len(), mode))),
            BaseContact::Sticking { nodes, sticking } => blocks.push((nodes.to_vec(), sticking_stiffness(sticking, mode).as_slice().to_vec())),
        }
    }
    Ok((blocks, materials))
}

/// The load stiffness of pressure `p` following `surface` on this rank's edges, for mode
/// `mode` (d f_ext / dU enters the stiffness with a minus).
pub(in crate::solve) fn pressure_stiffness_blocks(model: &Model, partition: &Partition, current: &[[f64; 2]], surface: &str, p: f64, mode: u32) -> Vec<Block> {
    let local: std::collections::HashSet<usize> = partition.local_elements().iter().copied().collect();
    let edges = model.surfaces.get(surface).into_iter().flatten().filter(|edge| local.contains(&edge.element));
    edges
        .map(|edge| {
            let en = model.mesh.edge_nodes(*edge);
            let kp = harmonic_pressure_stiffness(&en.map(|n| current[n]), p, mode);
            // column-major, as nalgebra's: entry (i, j) at j * 9 + i
            (en.to_vec(), (0..9).flat_map(|j| (0..9).map(move |i| -kp[i][j])).collect())
        })
        .collect()
}

/// The material's stress amplitudes D : strain at the Gauss points of this rank's elements.
pub(in crate::solve) fn stresses(
    model: &Model,
    partition: &Partition,
    materials: &[ElementMaterial],
    mode: u32,
    amplitudes: &[[f64; 3]],
) -> Vec<[[f64; 6]; QUADRATURE_POINTS]> {
    partition
        .local_elements()
        .iter()
        .zip(materials)
        .map(|(&e, (geo, d))| {
            let strain = harmonic_strain(geo, mode, &model.mesh.elements[e].map(|n| amplitudes[n]));
            std::array::from_fn(|q| (d[q] * nalgebra::SVector::<f64, 6>::from(strain[q])).into())
        })
        .collect()
}

/// The response to the step's prescribed amplitudes and harmonic pressures; `hold_twist` holds
/// every U_t at zero (an axisymmetric load's solve, whose twist is decoupled).
pub(in crate::solve) fn response(ctx: &RunContext<'_, '_>, base: &BaseState<'_>, step: &Perturbation, hold_twist: bool) -> Result<PerturbationAnswer> {
    let (session, model, partition) = (ctx.session, ctx.model, ctx.partition);
    let world = session.world();
    let nodes = model.mesh.coords.len();
    let current = current_positions(model, base);
    let (mut prescribed, centres) = prescribed_amplitudes(model, step, &current)?;
    if hold_twist {
        prescribed.iter_mut().for_each(|p| p[2] = Some(0.0));
    }
    let (amplitude, offsets) = number(partition, &prescribed, &current, step.mode, model_size(&current));
    let local_len = offsets[partition.rank + 1] - offsets[partition.rank];
    let (blocks, materials) = stiffness_blocks(model, partition, base, &current, step)?;

    // the step's harmonic pressure: p cos n theta, weighed by cos n theta
    let factor = ring_factor(step.mode);
    let local: std::collections::HashSet<usize> = partition.local_elements().iter().copied().collect();
    let mut load = vec![[0.0f64; 3]; nodes];
    for q in &step.pressures {
        for edge in model.surfaces.get(&q.surface).into_iter().flatten().filter(|edge| local.contains(&edge.element)) {
            let en = model.mesh.edge_nodes(*edge);
            for (a, f) in compute_pressure_load(crate::fe::section::Section::Axisymmetric, &en.map(|n| current[n]), q.value).iter().enumerate() {
                load[en[a]][0] += factor * f[0];
                load[en[a]][1] += factor * f[1];
            }
        }
    }

    // the system: K_ff U_f = f_f - K_fp U_p
    let (matrix, mut rhs) = assemble(session, &blocks, &amplitude, local_len)?;
    // the harmonic pressure's load: each rank has its own edges' part; PETSc sums the rows
    for (n, l) in load.iter().enumerate() {
        for c in 0..3 {
            if let (Amplitude::Unknown(row, coef), true) = (amplitude[n][c], l[c] != 0.0) {
                rhs.push((row, coef * l[c]));
            }
        }
    }
    // every amplitude prescribed (a ring motion on every node): nothing to solve for
    let unknowns = offsets.last().copied().unwrap_or(0);
    let solved = if unknowns == 0 {
        Vec::new()
    } else {
        solve_once(session, &matrix, rhs, local_len)?.ok_or_else(|| Error::NotConverged {
            step: step.name.clone(),
            load_factor: 1.0,
            reason: "the linear solve failed: the perturbation's stiffness is singular (a rigid motion of its mode left free? hold it on a set)".into(),
        })?
    };
    let amplitudes = amplitudes_of(world, partition, &amplitude, &offsets, &solved);

    // reactions: K U - f at every node, summed over ranks
    let mut force = vec![0.0; 3 * nodes];
    for (conn, k) in &blocks {
        let ue: Vec<f64> = conn.iter().flat_map(|&n| amplitudes[n]).collect();
        let size = ue.len();
        for i in 0..size {
            let fi: f64 = (0..size).map(|j| k[j * size + i] * ue[j]).sum();
            force[3 * conn[i / 3] + i % 3] += fi;
        }
    }
    // minus this rank's part of the harmonic pressure's load
    for (f, l) in force.iter_mut().zip(load.iter().flatten()) {
        *f -= l;
    }
    let mut total = vec![0.0; 3 * nodes];
    world.all_reduce_into(&force[..], &mut total[..], SystemOperation::sum());
    let reactions = reactions(model, step, &current, &total, &centres);
    let stress = stresses(model, partition, &materials, step.mode, &amplitudes);
    Ok(PerturbationAnswer { amplitudes, reactions, stress, modes: Vec::new(), analysis: step.analysis, notes: Vec::new() })
}

/// The model's size, for the axis tolerance.
pub(in crate::solve) fn model_size(x: &[[f64; 2]]) -> f64 {
    let (rmax, zmin, zmax) = x.iter().fold((0.0f64, f64::INFINITY, f64::NEG_INFINITY), |(r, a, b), p| (r.max(p[0]), a.min(p[1]), b.max(p[1])));
    rmax.max(zmax - zmin)
}

/// Each node's prescribed amplitudes (None: free).
type Prescription = Vec<[Option<f64>; 3]>;

/// The amplitudes the step prescribes and each ring's (set, centre z_c).
pub(in crate::solve) fn prescribed_amplitudes(model: &Model, step: &Perturbation, x: &[[f64; 2]]) -> Result<(Prescription, Vec<(String, f64)>)> {
    let mut prescribed = vec![[None; 3]; x.len()];
    let mut set_value = |n: usize, c: usize, v: f64, set: &str| -> Result<()> {
        match prescribed[n][c] {
            Some(old) if old != v => Err(Error::input(format!(
                "perturbation step '{}': node {} gets two values of {} ({old} and {v}, the second from '{set}')",
                step.name,
                model.mesh.node_ids[n],
                ["ur", "uz", "ut"][c]
            ))),
            _ => {
                prescribed[n][c] = Some(v);
                Ok(())
            }
        }
    };
    for d in &step.displacements {
        for &n in model.node_set(&d.node_set)? {
            set_value(n, d.component.index(), d.value, &d.node_set)?;
        }
    }
    let mut centres = Vec::new();
    for ring in &step.rings {
        let set = model.node_set(&ring.node_set)?;
        let zc = ring.pivot.unwrap_or_else(|| set.iter().map(|&n| x[n][1]).sum::<f64>() / set.len().max(1) as f64);
        centres.push((ring.node_set.clone(), zc));
        for &n in set {
            let ur = ring.lateral + ring.rotation * (x[n][1] - zc);
            set_value(n, 0, ur, &ring.node_set)?;
            set_value(n, 2, -ur, &ring.node_set)?;
            set_value(n, 1, -ring.rotation * x[n][0], &ring.node_set)?;
        }
    }
    Ok((prescribed, centres))
}

/// Numbers the unknown amplitudes rank by rank in partition order, with the axis's regularity;
/// returns every node's amplitudes and the ranks' offsets.
pub(in crate::solve) fn number(
    partition: &Partition,
    prescribed: &[[Option<f64>; 3]],
    x: &[[f64; 2]],
    mode: u32,
    size: f64,
) -> (Vec<[Amplitude; 3]>, Vec<usize>) {
    let mut amplitude = vec![[Amplitude::Prescribed(0.0); 3]; x.len()];
    let mut offsets = vec![0; partition.size + 1];
    let mut next: PetscInt = 0;
    for r in 0..partition.size {
        for &n in &partition.node_order[partition.node_offsets[r]..partition.node_offsets[r + 1]] {
            let on_axis = x[n][0].abs() <= 1e-9 * size;
            // which free amplitudes regularity fixes at zero, and whether U_t follows U_r
            let (zero, follows) = match (on_axis, mode) {
                (false, _) => ([false; 3], false),
                (true, 0) => ([true, false, true], false),
                (true, 1) => ([false, true, false], true),
                (true, _) => ([true; 3], false),
            };
            for c in 0..3 {
                amplitude[n][c] = match prescribed[n][c] {
                    Some(v) => Amplitude::Prescribed(v),
                    None if zero[c] => Amplitude::Prescribed(0.0),
                    None if c == 2 && follows => match amplitude[n][0] {
                        Amplitude::Unknown(i, _) => Amplitude::Unknown(i, -1.0),
                        Amplitude::Prescribed(v) => Amplitude::Prescribed(-v),
                    },
                    None => {
                        next += 1;
                        Amplitude::Unknown(next - 1, 1.0)
                    }
                };
            }
        }
        offsets[r + 1] = next as usize;
    }
    (amplitude, offsets)
}

/// The reactions of every set the step prescribes amplitudes on.
fn reactions(model: &Model, step: &Perturbation, x: &[[f64; 2]], force: &[f64], centres: &[(String, f64)]) -> Vec<SetReaction> {
    let mut names: Vec<&str> = step.displacements.iter().map(|d| d.node_set.as_str()).chain(step.rings.iter().map(|r| r.node_set.as_str())).collect();
    let mut seen = std::collections::BTreeSet::new();
    names.retain(|n| seen.insert(*n));
    names
        .into_iter()
        .map(|name| {
            let set = model.node_sets.get(name).map(Vec::as_slice).unwrap_or(&[]);
            let f = |n: usize, c: usize| force[3 * n + c];
            let sum = |c: usize| set.iter().map(|&n| f(n, c)).sum::<f64>();
            let zc = centres.iter().find(|(s, _)| s == name).map_or_else(|| set.iter().map(|&n| x[n][1]).sum::<f64>() / set.len().max(1) as f64, |c| c.1);
            let resultants = match step.mode {
                0 => {
                    vec![("axial_force_ring", 2.0 * PI * sum(1), "N"), ("torque_ring", 2.0 * PI * set.iter().map(|&n| x[n][0] * f(n, 2)).sum::<f64>(), "N mm")]
                }
                1 => vec![
                    ("lateral_force_ring", 2.0 * PI * (sum(0) - sum(2)), "N"),
                    ("moment_ring", 2.0 * PI * set.iter().map(|&n| (x[n][1] - zc) * (f(n, 0) - f(n, 2)) - x[n][0] * f(n, 1)).sum::<f64>(), "N mm"),
                ],
                _ => Vec::new(),
            };
            SetReaction { set: name.to_string(), force: [sum(0), sum(1), sum(2)], resultants }
        })
        .collect()
}

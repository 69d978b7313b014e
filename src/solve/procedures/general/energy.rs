//! The energy audit: where the work done on the model went, after every converged increment,
//! as Abaqus' ALLWK / ALLSE / ALLPD / ALLFD (all per radian, N mm).
//!
//! - external work: the supports' reactions on the prescribed displacements and the pressure
//!   loads on the displacements they follow, integrated along the load path (trapezoids
//!   between converged increments);
//! - elastic energy, stored: the Hencky energy tau : C^-1 : tau / 2 of every Gauss point (a
//!   state function);
//! - plastic work: the integral of sigma_y over the equivalent plastic strain (a state
//!   function of ep for isotropic hardening);
//! - thermal work: the stress power of the thermal strain, alpha tr(tau) N_a per degree of
//!   each node's temperature, integrated along every node's temperature path (trapezoids);
//!   with no temperature change, zero;
//! - contact energy, stored: the normal penalty's eps g^2 A / 2 and the tangential penalty's
//!   tau^2 A / (2 eps_T) of every slave node;
//! - friction dissipation: each increment's A tau (slip beyond the elastic), summed.
//!
//! An interference fit starts out of equilibrium (its undeformed mesh overlaps): its first
//! increment's state is taken as the audit's start (`initial_contact`, counted as an input).
//!
//! The balance error, external work (and initial contact energy) minus the rest, measures the whole coupled solve at once:
//! the residual's convergence, the consistency of the stresses with the displacements, the
//! return maps. It is not zero: the trapezoids integrate the path to second order in the
//! increment (and a multiplier's part of augmented-Lagrangian contact is not counted).

use crate::element::solid::ElementEnergy;
use crate::records::energy::{AuditPoint, Energies};

/// The running audit.
#[derive(Clone, Debug)]
pub struct EnergyAudit {
    pub totals: Energies,
    pub last: AuditPoint,
    /// The undeformed mesh overlaps: the first increment sets `initial_contact`.
    pub starts_overlapping: bool,
}

impl EnergyAudit {
    /// Before the first increment: nothing loaded, at `temperature` (per node).
    pub fn new(temperature: Vec<f64>) -> Self {
        let nodes = temperature.len();
        EnergyAudit {
            totals: Energies::default(),
            last: AuditPoint { forces: vec![[0.0; 4]; nodes], displacement: vec![[0.0; 2]; nodes], thermal_force: vec![0.0; nodes], temperature },
            starts_overlapping: false,
        }
    }

    /// Forgets the reactions of the DOFs no longer `prescribed` (a released constraint's force
    /// vanishes at the release: it does no work on the motion that follows).
    pub fn release(&mut self, prescribed: &[[bool; 2]]) {
        for (force, held) in self.last.forces.iter_mut().zip(prescribed) {
            for c in 0..2 {
                if !held[c] {
                    force[c] = 0.0;
                }
            }
        }
    }

    /// Takes a converged increment: `residual` the nodal f_int - f_ext (+ contact) summed over
    /// ranks (the reactions at the prescribed DOFs `prescribed`), `pressure` the pressure loads,
    /// `displacement` every node's, `elements` and `contact` ([normal stored, tangential stored,
    /// dissipated in the increment]) and `thermal_force` summed over ranks, at `temperature`
    /// (per node).
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        residual: &[f64],
        prescribed: &[[bool; 2]],
        pressure: &[f64],
        displacement: &[[f64; 2]],
        elements: ElementEnergy,
        contact: [f64; 3],
        thermal_force: &[f64],
        temperature: &[f64],
    ) -> Energies {
        let mut work = 0.0;
        let mut forces = vec![[0.0; 4]; displacement.len()];
        for (n, u) in displacement.iter().enumerate() {
            for c in 0..2 {
                let reaction = if prescribed[n][c] { residual[2 * n + c] } else { 0.0 };
                forces[n][c] = reaction;
                forces[n][2 + c] = pressure[2 * n + c];
                let du = u[c] - self.last.displacement[n][c];
                let before = &self.last.forces[n];
                work += 0.5 * (before[c] + reaction + before[2 + c] + pressure[2 * n + c]) * du;
            }
        }
        let t = &mut self.totals;
        t.external_work += work;
        let uniform = |t: &[f64]| t.iter().all(|&x| x == t[0]);
        t.thermal_work += if uniform(temperature) && uniform(&self.last.temperature) {
            // one temperature change for every node: the sums' trapezoid (what a restart, which
            // keeps only the sum, continues bit for bit)
            let sum = |f: &[f64]| f.iter().sum::<f64>();
            0.5 * (sum(&self.last.thermal_force) + sum(thermal_force)) * (temperature[0] - self.last.temperature[0])
        } else {
            (0..temperature.len()).map(|n| 0.5 * (self.last.thermal_force[n] + thermal_force[n]) * (temperature[n] - self.last.temperature[n])).sum::<f64>()
        };
        t.elastic = elements.elastic;
        t.plastic_work = elements.plastic_work;
        t.contact_stored = contact[0] + contact[1];
        t.friction_dissipation += contact[2];
        if std::mem::take(&mut self.starts_overlapping) {
            t.initial_contact = 0.0;
            t.initial_contact = -t.balance_error();
        }
        self.last = AuditPoint { forces, displacement: displacement.to_vec(), thermal_force: thermal_force.to_vec(), temperature: temperature.to_vec() };
        self.totals
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_spring_loaded_in_steps_stores_what_was_done_on_it() {
        // one node pulled by a prescribed displacement against a spring k = 3: reaction k u; the
        // trapezoids integrate the linear path exactly, so W = k u^2 / 2 in any number of steps
        let k = 3.0;
        let mut audit = EnergyAudit::new(vec![20.0]);
        let mut last = Energies::default();
        for u in [0.1, 0.25, 0.7] {
            let elements = ElementEnergy { elastic: 0.5 * k * u * u, ..Default::default() };
            last = audit.record(&[0.0, k * u], &[[false, true]], &[0.0, 0.0], &[[0.0, u]], elements, [0.0; 3], &[0.0], &[20.0]);
        }
        assert!((last.external_work - 0.5 * k * 0.49).abs() < 1e-12, "{last:?}");
        assert!(last.balance_error().abs() < 1e-12);
        // a pressure load on a free DOF works too; heating under a stress power that grows
        // from 0 to 2 per degree does thermal work 2 x 10 / 2
        let mut audit = EnergyAudit::new(vec![20.0]);
        let e = audit.record(&[0.0, 0.0], &[[false, false]], &[5.0, 0.0], &[[0.2, 0.0]], ElementEnergy::default(), [0.0; 3], &[2.0], &[30.0]);
        assert!((e.external_work - 0.5 * 5.0 * 0.2).abs() < 1e-12 && (e.thermal_work - 0.5 * 2.0 * 10.0).abs() < 1e-12, "{e:?}");
        // two nodes heated differently: each node's trapezoid
        let mut audit = EnergyAudit::new(vec![20.0, 20.0]);
        let displacement = [[0.0; 2]; 2];
        let e = audit.record(&[0.0; 4], &[[false; 2]; 2], &[0.0; 4], &displacement, ElementEnergy::default(), [0.0; 3], &[1.0, 3.0], &[30.0, 25.0]);
        assert!((e.thermal_work - (0.5 * 1.0 * 10.0 + 0.5 * 3.0 * 5.0)).abs() < 1e-12, "{e:?}");
    }
}

//! The history's row: what one converged increment records beside its fields (the load
//! factor, Newton's work, the reactions, the contact and the energy), and the lines the run
//! prints and the status file keeps for it.

use crate::records::energy::Energies;

/// Contact state of one pair at an increment.
#[derive(Clone, Debug)]
pub struct ContactSummary {
    pub name: String,
    /// Slave nodes with a positive contact pressure.
    pub active_nodes: usize,
    /// Largest penetration, mm.
    pub max_penetration: f64,
    /// Total normal contact force, N per radian.
    pub normal_force: f64,
}

/// One row of the history table.
#[derive(Clone, Debug)]
pub struct HistoryRow {
    /// The increment's number over the whole run, 1-based: its group /increments/NNNNNN, post's
    /// --increment, the pictures' names.
    pub number: usize,
    pub step: usize,
    /// The increment's number within its step.
    pub increment: usize,
    /// Load factor within the step, in (0, 1].
    pub load_factor: f64,
    /// Step number minus one plus the load factor (Abaqus' total time).
    pub time: f64,
    pub newton_iterations: usize,
    pub linear_iterations: usize,
    pub residual_norm: f64,
    /// ||F|| at each Newton iterate of the converged attempt.
    pub residual_norms: Vec<f64>,
    /// The field convergence test's average force at the converged state (mean magnitude of
    /// the element and contact nodal forces), N per radian; 0 under the residual test. The
    /// step's time average of it is the test's reference force, restored on a restart.
    pub average_force: f64,
    /// Failed attempts (cutbacks) before this increment converged.
    pub cutbacks: usize,
    /// Augmented-Lagrangian multiplier updates in this increment.
    pub augmentations: usize,
    pub contacts: Vec<ContactSummary>,
    /// Largest equivalent plastic strain over the model.
    pub max_plastic_strain: f64,
    /// Wall time since the start of the analysis, s.
    pub wall_time: f64,
    /// (set name, [F_r, F_z] per radian), N/rad.
    pub reactions: Vec<(String, [f64; 2])>,
    /// (set name, [u_r, u_z] the mean over its nodes), mm: the displacement the reactions work
    /// on (the prescribed one, where it is the same at every node), for force-displacement curves.
    pub set_displacements: Vec<(String, [f64; 2])>,
    /// The energy audit after the increment (None: a file written before the audit existed).
    pub energy: Option<Energies>,
}

impl HistoryRow {
    /// The short line the run prints for this row (and `slideline post` prints again), at most
    /// 100 characters where the step and set names are short (they are never cut): the step, the run-wide increment number (#N) and the step's own, the
    /// load factor, the Newton iterations, the largest axial reaction (a `plane` model's largest
    /// y reaction, over its thickness) and the wall time. Of sets within 1 % of the largest the
    /// first is named, so that two ends bearing equal and opposite forces do not take turns.
    pub fn short_line(&self, step_name: &str, steps: usize, plane: bool) -> String {
        // names whole (a cut name can name another set); an axisymmetric force for the full
        // ring, as Abaqus and ANSYS report it (the file keeps both)
        let name = step_name;
        let largest = self.reactions.iter().map(|r| r.1[1].abs()).fold(0.0, f64::max);
        let reaction = self.reactions.iter().find(|r| r.1[1].abs() >= 0.99 * largest);
        let (label, unit, factor) = if plane { ("F_y", "N", 1.0) } else { ("F_z", "N ring", 2.0 * std::f64::consts::PI) };
        let force = reaction.map_or(String::new(), |(set, f)| format!(" {label} {set:<10} {:>9.3e} {unit}", factor * f[1]));
        format!(
            "step {}/{} {name:<10} #{:<4} inc {:>4} lambda {:.4} newton {:>2}{force} {:>5.1} s",
            self.step, steps, self.number, self.increment, self.load_factor, self.newton_iterations, self.wall_time
        )
    }

    /// The long line (`--verbose`) the run prints for this row (and `slideline post --verbose`):
    /// the run-wide increment number (#N), then the step's own; the reactions (per radian, or
    /// a `plane` model's over its thickness); the contact pairs summed in one field (active
    /// nodes, largest penetration).
    pub fn progress_line(&self, step_name: &str, steps: usize, plane: bool) -> String {
        let mut line = format!(
            "step {}/{} {:<10} #{:<4} inc {:>4} lambda {:.4}  newton {:>2}  ksp {:>3}  |F| {:.2e}  ep_max {:.3e}  {:>7.2} s",
            self.step,
            steps,
            step_name,
            self.number,
            self.increment,
            self.load_factor,
            self.newton_iterations,
            self.linear_iterations,
            self.residual_norm,
            self.max_plastic_strain,
            self.wall_time
        );
        for (set, f) in &self.reactions {
            if plane {
                line.push_str(&format!("  {set} Fx {:.3e} Fy {:.3e} N", f[0], f[1]));
            } else {
                // the full ring first, per radian beside it
                let ring = 2.0 * std::f64::consts::PI;
                line.push_str(&format!("  {set} Fr {:.3e} Fz {:.3e} N ring ({:.3e} {:.3e} N/rad)", ring * f[0], ring * f[1], f[0], f[1]));
            }
        }
        if !self.contacts.is_empty() {
            let active: usize = self.contacts.iter().map(|c| c.active_nodes).sum();
            let penetration = self.contacts.iter().map(|c| c.max_penetration).fold(0.0, f64::max);
            line.push_str(&format!("  contact {active} active, pen {penetration:.2e} mm"));
        }
        if self.augmentations > 0 {
            line.push_str(&format!("  AL x{}", self.augmentations));
        }
        line
    }

    /// The status file's header and one row per increment (`RESULTS.sta`, as Abaqus' .sta).
    pub const STATUS_HEADER: &'static str = "  number  step  inc  cutbacks  newton  load_factor        time   wall_s  max_penetration_mm  ep_max";

    pub fn status_line(&self) -> String {
        let penetration = self.contacts.iter().map(|c| c.max_penetration).fold(0.0, f64::max);
        format!(
            "{:>8}  {:>4}  {:>3}  {:>8}  {:>6}  {:>11.6}  {:>10.6}  {:>7.1}  {:>18.3e}  {:.3e}",
            self.number,
            self.step,
            self.increment,
            self.cutbacks,
            self.newton_iterations,
            self.load_factor,
            self.time,
            self.wall_time,
            penetration,
            self.max_plastic_strain
        )
    }
}

#[cfg(test)]
mod tests {
    use super::HistoryRow;

    fn row(reactions: &[(&str, f64)]) -> HistoryRow {
        HistoryRow {
            number: 8,
            step: 2,
            increment: 6,
            load_factor: 0.15,
            time: 1.15,
            newton_iterations: 2,
            linear_iterations: 2,
            residual_norm: 0.0,
            residual_norms: Vec::new(),
            average_force: 0.0,
            cutbacks: 0,
            augmentations: 0,
            contacts: Vec::new(),
            max_plastic_strain: 0.0,
            wall_time: 1.3,
            reactions: reactions.iter().map(|&(set, f)| (set.to_string(), [0.0, f])).collect(),
            set_displacements: Vec::new(),
            energy: None,
        }
    }

    #[test]
    fn the_short_line_names_the_largest_reaction_and_keeps_to_one_of_two_equal_ends() {
        // the quick joint's increments 7 and 8: its two ends within 0.3 % of each other
        for ends in [[("moving_end", -4.972e3), ("fixed_end", 4.960e3)], [("moving_end", -5.017e3), ("fixed_end", 5.030e3)]] {
            let line = row(&ends).short_line("compress", 3, false);
            assert!(line.contains(" F_z moving_end ") && line.contains(" N ring "), "{line}");
            // the full ring's force: 2 pi times the per-radian one
            let ring = format!("{:.3e}", 2.0 * std::f64::consts::PI * ends[0].1);
            assert!(line.contains(&ring), "{line} ({ring})");
        }
        // a step name longer than ten characters is printed whole
        assert!(row(&[("top", 1.0)]).short_line("compression_stroke", 3, false).contains(" compression_stroke "));
        let line = row(&[("inner", 1.0e2), ("top", -8.8e3)]).short_line("press", 1, true);
        assert!(line.contains(" F_y top ") && line.contains("-8.800e3 N "), "{line}");
    }
}

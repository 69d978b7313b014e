//! The field convergence test of CalculiX and Abaqus: the largest residual force against the
//! time-averaged force, and the largest correction against the increment's largest
//! displacement. CalculiX's manual (2.x, section "Convergence criteria", eqs. 380-386) states
//! it and its defaults, which are kept here; Abaqus's Analysis User's Manual ("Commonly used
//! control parameters") has the same ratios.

/// The ratios of the test (CalculiX's names and defaults).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldRatios {
    /// R_n: largest residual over the time-averaged force, iterations 1 .. I_p.
    pub residual: f64,
    /// R_p: the same from iteration I_p + 1 on.
    pub residual_late: f64,
    /// I_p.
    pub late_after: usize,
    /// C_n: largest correction over the increment's largest displacement.
    pub correction: f64,
    /// epsilon: an average force below this share of the time average is zero flux.
    pub zero_flux: f64,
    /// C_epsilon: the correction ratio under zero flux.
    pub zero_flux_correction: f64,
    /// R_l: a residual this small against the time average passes without the correction
    /// check (a linear increment).
    pub linear: f64,
    /// A correction below this share of the model's size passes whatever the increment moved:
    /// CalculiX's absolute floor (c_max < 1e-8) made relative to the model, whose units it
    /// does not know. A step that holds its loads moves nothing, and its corrections are then
    /// judged against round-off: the forming's `settle` with friction never converged, a die
    /// node chattering between stick and slip at 1e-7 mm against a bound of 7e-9 mm (25
    /// iterations, cut back to nothing); its model is 240 mm across, a floor of 2.4e-6 mm.
    pub size_floor: f64,
}

impl Default for FieldRatios {
    fn default() -> Self {
        FieldRatios {
            residual: 0.005,
            residual_late: 0.02,
            late_after: 9,
            correction: 0.02,
            zero_flux: 1e-5,
            zero_flux_correction: 1e-3,
            linear: 1e-8,
            size_floor: 1e-8,
        }
    }
}

/// What one iteration is judged on (all agreed across ranks).
#[derive(Clone, Copy, Debug)]
pub struct IterateMeasures {
    /// Largest residual force component, r_max.
    pub residual_max: f64,
    /// Largest change of an unknown in this iteration, c_max.
    pub correction_max: f64,
    /// Largest change of an unknown since the start of the increment, Delta u_max.
    pub increment_max: f64,
    /// The model's size (its largest distance from the origin), in the unknowns' unit.
    pub model_size: f64,
    /// Average magnitude of the element (and contact) nodal forces, q-bar.
    pub average_force: f64,
}

/// Time average of the average force over a step: the converged increments' averages.
#[derive(Clone, Copy, Debug, Default)]
pub struct ForceAverage {
    sum: f64,
    count: usize,
}

impl ForceAverage {
    /// The time average including the current iterate's average force (q-tilde).
    pub fn with(&self, current: f64) -> f64 {
        (self.sum + current) / (self.count + 1) as f64
    }

    /// Adds a converged increment's average force (one with zero flux adds nothing, as in
    /// CalculiX, so an unloaded increment does not dilute the average).
    pub fn add(&mut self, converged: f64) {
        if converged > 0.0 {
            self.sum += converged;
            self.count += 1;
        }
    }
}

/// The bounds iteration `iteration` is held to: (largest residual force, largest correction),
/// and whether the iterate has zero flux.
pub fn field_bounds(ratios: &FieldRatios, iteration: usize, m: &IterateMeasures, time_average: f64) -> (f64, f64, bool) {
    let zero_flux = m.average_force <= ratios.zero_flux * time_average;
    let (c1, c2) = if zero_flux {
        (ratios.zero_flux, ratios.zero_flux_correction)
    } else if iteration <= ratios.late_after {
        (ratios.residual, ratios.correction)
    } else {
        (ratios.residual_late, ratios.correction)
    };
    (c1 * time_average, c2 * m.increment_max, zero_flux)
}

/// Whether iteration `iteration` (1 for the first Newton step) has converged; `earlier` holds
/// r_max of the iterates before it in this solve (the initial one first).
pub fn field_converged(ratios: &FieldRatios, iteration: usize, m: &IterateMeasures, time_average: f64, earlier: &[f64]) -> bool {
    if iteration == 0 {
        return false;
    }
    let (residual_bound, correction_bound, zero_flux) = field_bounds(ratios, iteration, m, time_average);
    if m.residual_max > residual_bound {
        return false;
    }
    // the next correction, estimated from the residual's rate of decrease
    let previous = earlier.iter().rev().take(2).copied().fold(f64::INFINITY, f64::min);
    let estimate = if previous.is_finite() && previous > 0.0 { m.residual_max * m.correction_max / previous } else { f64::INFINITY };
    m.correction_max <= correction_bound
        || estimate < correction_bound
        || m.residual_max <= ratios.linear * time_average
        || zero_flux
        || m.correction_max < (ratios.size_floor * m.model_size).max(1e-8)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn measures(residual_max: f64, correction_max: f64) -> IterateMeasures {
        IterateMeasures { residual_max, correction_max, increment_max: 1.0, model_size: 1.0, average_force: 100.0 }
    }

    #[test]
    fn both_the_residual_and_the_correction_must_be_small() {
        let r = FieldRatios::default();
        // residual 0.004 of the average force, correction 0.01 of the increment: converged
        assert!(field_converged(&r, 1, &measures(0.4, 0.01), 100.0, &[50.0]));
        // residual too large
        assert!(!field_converged(&r, 1, &measures(0.6, 0.01), 100.0, &[50.0]));
        // correction too large, and the residual fell too slowly for the estimate to pass
        assert!(!field_converged(&r, 2, &measures(0.4, 0.05), 100.0, &[50.0, 0.5]));
        // the same correction, but the residual fell by 100: the next correction is tiny
        assert!(field_converged(&r, 2, &measures(0.4, 0.05), 100.0, &[50.0, 40.0]));
        // never at the initial iterate
        assert!(!field_converged(&r, 0, &measures(0.0, 0.0), 100.0, &[]));
    }

    #[test]
    fn late_iterations_zero_flux_and_linear_increments_relax_the_test() {
        let r = FieldRatios::default();
        // 0.01 of the average: too much early, enough after I_p iterations
        assert!(!field_converged(&r, 9, &measures(1.0, 0.001), 100.0, &[50.0]));
        assert!(field_converged(&r, 10, &measures(1.0, 0.001), 100.0, &[50.0]));
        // a residual at 1e-9 of the average passes whatever the correction
        assert!(field_converged(&r, 1, &measures(1e-7, 0.5), 100.0, &[1.0]));
        // zero flux: the residual must be below 1e-5 of the time average
        let idle = IterateMeasures { residual_max: 2e-3, correction_max: 0.5, increment_max: 1.0, model_size: 1.0, average_force: 1e-4 };
        assert!(!field_converged(&r, 1, &idle, 100.0, &[1.0]));
        assert!(field_converged(&r, 1, &IterateMeasures { residual_max: 5e-4, ..idle }, 100.0, &[1.0]));
    }

    #[test]
    fn a_correction_below_the_models_size_floor_passes() {
        let r = FieldRatios::default();
        // the forming's settle with friction: the increment 3e-7 mm, a stick-slip chatter of
        // 1e-7 mm, the model 240 mm across (floor 2.4e-6 mm): converged
        let settle = IterateMeasures { residual_max: 0.4, correction_max: 9.7e-8, increment_max: 3e-7, model_size: 240.0, average_force: 100.0 };
        assert!(field_converged(&r, 3, &settle, 100.0, &[0.5, 0.4]));
        // the same in a model of unit size: below CalculiX's floor only under 1e-8
        assert!(!field_converged(&r, 3, &IterateMeasures { model_size: 1.0, ..settle }, 100.0, &[0.5, 0.4]));
        // a correction of 1e-5 mm in that increment is not round-off
        assert!(!field_converged(&r, 3, &IterateMeasures { correction_max: 1e-5, ..settle }, 100.0, &[0.5, 0.4]));
    }

    #[test]
    fn the_time_average_counts_converged_increments_with_force() {
        let mut a = ForceAverage::default();
        assert_eq!(a.with(10.0), 10.0);
        a.add(10.0);
        a.add(0.0);
        a.add(30.0);
        assert_eq!(a.with(20.0), 20.0);
    }
}

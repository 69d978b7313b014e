//! The energy audit's totals after an increment and the loads its next trapezoids start from
//! (`solve::procedures::general::energy` keeps the audit; the history and the restart state write these).

/// The audit's totals after an increment (per radian, N mm).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energies {
    pub external_work: f64,
    /// An interference fit: its undeformed mesh overlaps, so it does not start in equilibrium
    /// and its first increment jumps to the fitted state rather than following a load path.
    /// That state's energy, less the work done in the increment, is counted as an input (the
    /// audit runs from there).
    pub initial_contact: f64,
    pub elastic: f64,
    pub plastic_work: f64,
    pub thermal_work: f64,
    pub contact_stored: f64,
    pub friction_dissipation: f64,
}

impl Energies {
    /// External work minus everything it went into.
    pub fn balance_error(&self) -> f64 {
        self.external_work + self.initial_contact - (self.elastic + self.plastic_work + self.thermal_work + self.contact_stored + self.friction_dissipation)
    }

    /// The history columns: (name, value).
    pub fn columns(&self) -> [(&'static str, f64); 8] {
        [
            ("energy_external_work", self.external_work),
            ("energy_initial_contact", self.initial_contact),
            ("energy_elastic", self.elastic),
            ("energy_plastic_work", self.plastic_work),
            ("energy_thermal_work", self.thermal_work),
            ("energy_contact_stored", self.contact_stored),
            ("energy_friction_dissipation", self.friction_dissipation),
            ("energy_balance_error", self.balance_error()),
        ]
    }
}

/// What the next increment's trapezoids start from: the loads of the last converged state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AuditPoint {
    /// Per node: the reaction (prescribed DOFs, 0 elsewhere) and the pressure load, (r, z) each.
    pub forces: Vec<[f64; 4]>,
    pub displacement: Vec<[f64; 2]>,
    /// Per node: the thermal strain's stress power per degree (`SolidResponse::thermal_force`)
    /// and the temperature, degC.
    pub thermal_force: Vec<f64>,
    pub temperature: Vec<f64>,
}

//! Steady heat-conduction steps (CalculiX's and Abaqus's `*HEAT TRANSFER, STEADY STATE`): the
//! temperature field that Fourier's law gives, -div(k grad T) = 0 in the body, with the
//! temperatures the step holds on node sets and insulated (zero-flux) surfaces elsewhere. It
//! is linear (a temperature-independent conductivity), so a step solves once
//! (`solve::procedures::conduction`, `element::conduction`). Heat steps come before the general steps;
//! the last one's field is then the temperature of the general steps, reached in the first of
//! them (ramped from the initial temperatures, as a step's own temperature is), as CalculiX
//! carries a *HEAT TRANSFER step's temperatures into the *STATIC step after it (measured with
//! ccx 2.20). A general step after a heat step gives no temperature of its own.
//!
//! Units, from slideline's mm, N, s: conductivity in mW/(mm K) = N/(s K) (numerically equal to
//! W/(m K): steel about 50), heat flux in mW/mm^2, heat flow in mW.

use super::Model;
use crate::error::{Error, Result};

/// A temperature held on every node of a set, degC.
#[derive(Clone, Debug, PartialEq)]
pub struct HeldTemperature {
    pub node_set: String,
    pub value: f64,
}

/// One steady heat-conduction step.
#[derive(Clone, Debug, PartialEq)]
pub struct HeatStep {
    pub name: String,
    /// In order: a later value wins on the nodes two sets share.
    pub temperatures: Vec<HeldTemperature>,
}

impl HeatStep {
    /// Checks the step against its model: known sets, finite values, a conductivity in every
    /// material, no general step with a temperature of its own.
    pub fn validate(&self, model: &Model) -> Result<()> {
        let at = |what: String| Error::input(format!("heat step '{}': {what}", self.name));
        if let Some(s) = model.general_steps().find(|s| s.temperature.is_some()) {
            return Err(at(format!(
                "general step '{}' gives its own temperature: after a heat step the temperatures are the heat step's field (leave the step's temperature out)",
                s.name
            )));
        }
        if self.temperatures.is_empty() {
            return Err(at("holds no temperature: give at least one node set's (without it the field is not determined)".into()));
        }
        for t in &self.temperatures {
            model.node_set(&t.node_set).map_err(|e| at(e.to_string()))?;
            if !t.value.is_finite() {
                return Err(at(format!("the temperature of '{}' must be finite", t.node_set)));
            }
        }
        if let Some(m) = model.materials.iter().find(|m| !(m.conductivity > 0.0 && m.conductivity.is_finite())) {
            return Err(at(format!("material '{}' has no conductivity (mW/(mm K), numerically W/(m K); steel about 50)", m.name)));
        }
        Ok(())
    }

    /// Every node's held temperature (None: free), a later set winning on shared nodes.
    pub fn held(&self, model: &Model) -> Vec<Option<f64>> {
        let mut held = vec![None; model.mesh.coords.len()];
        for t in &self.temperatures {
            for &n in model.node_sets.get(&t.node_set).map(Vec::as_slice).unwrap_or(&[]) {
                held[n] = Some(t.value);
            }
        }
        held
    }
}

impl Model {
    /// This model with a heat step's answer `field` (every node's temperature, degC) as the
    /// temperature of its general steps: reached in the first (ramped from the initial
    /// temperatures) and kept after.
    pub fn with_heat_field(&self, field: Vec<f64>) -> Model {
        let mut model = self.clone();
        if let Some(super::Step::General(first)) = model.steps.iter_mut().find(|s| matches!(s, super::Step::General(_))) {
            first.temperature = Some(super::Temperature::from_nodal(field));
        }
        model
    }
}

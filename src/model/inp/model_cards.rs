//! The cards of the model data the reader keeps on the builder as it goes: *MATERIAL, *MASS,
//! *SOLID SECTION, *INITIAL CONDITIONS, *CONTROLS; and of a step: *TEMPERATURE, *END STEP, the
//! output requests.

use super::cards::{error_at, Card};
use super::{single, Builder, MaterialDef, Target};
use crate::error::Result;

impl Builder {
    /// *MATERIAL: a new material, its properties to follow.
    pub(super) fn material(&mut self, card: &Card) -> Result<()> {
        card.only(&["NAME"])?;
        let name = card.required("NAME")?.to_uppercase();
        if self.materials.iter().any(|m| m.name == name) {
            return Err(card.error(format!("material {name} is defined twice")));
        }
        self.materials.push(MaterialDef {
            name,
            at: card.at.clone(),
            elastic: None,
            expansion: 0.0,
            density: 0.0,
            density_at: None,
            plastic: Vec::new(),
            plastic_at: None,
            kinematic: false,
            conductivity: 0.0,
        });
        Ok(())
    }

    /// *MASS: the mass of an element set of MASS elements (point masses for GRAV and CENTRIF).
    pub(super) fn mass(&mut self, card: &Card) -> Result<()> {
        card.only(&["ELSET"])?;
        let set = card.required("ELSET")?.to_uppercase();
        let mass = single(card)?.number("MASS", 0, "mass (t)", None)?;
        if !(mass > 0.0 && mass.is_finite()) {
            return Err(card.error(format!("mass {mass}: give a positive mass (t)")));
        }
        let Some(entry) = self.point_masses.get_mut(&set) else {
            return Err(card.error(format!("element set {set} holds no elements of type MASS")));
        };
        entry.1 = Some(mass);
        self.notes.push(format!("*MASS ({}): the point masses of {set} carry only the GRAV and CENTRIF loads given on them in a static step", card.at));
        Ok(())
    }

    /// *SOLID SECTION: an element set's material (and a plane section's thickness).
    pub(super) fn solid_section(&mut self, card: &Card) -> Result<()> {
        card.only(&["ELSET", "MATERIAL"])?;
        let elset = card.required("ELSET")?.to_uppercase();
        if !self.element_sets.contains_key(&elset) {
            return Err(card.error(format!("element set {elset} is not defined (define it before its use)")));
        }
        let thickness = match card.data.first().and_then(|d| d.fields.first()).filter(|f| !f.is_empty()) {
            Some(_) => Some(card.data[0].number("SOLID SECTION", 0, "thickness", None)?),
            None => None,
        };
        self.sections.push((elset, card.required("MATERIAL")?.to_uppercase(), thickness, card.at.clone()));
        Ok(())
    }

    /// *INITIAL CONDITIONS, TYPE=TEMPERATURE: the initial temperatures (lines accumulate).
    pub(super) fn initial_conditions(&mut self, card: &Card) -> Result<()> {
        card.only(&["TYPE"])?;
        if !card.param("TYPE").is_some_and(|t| t.eq_ignore_ascii_case("TEMPERATURE")) {
            return Err(card.error("only TYPE=TEMPERATURE is supported"));
        }
        let (mut lines, at) = self.initial_temperature.take().unwrap_or_else(|| (Vec::new(), card.at.clone()));
        lines.extend(self.node_temperatures(card)?);
        self.initial_temperature = Some((lines, at));
        Ok(())
    }

    /// *TEMPERATURE: the step's temperatures (OP=MOD), with their amplitude.
    pub(super) fn temperature(&mut self, card: &Card) -> Result<()> {
        self.step_mut(card)?;
        card.only(&["AMPLITUDE", "OP"])?;
        if card.param("OP").is_some_and(|o| !o.eq_ignore_ascii_case("MOD")) {
            return Err(card.error("only OP=MOD is supported"));
        }
        let lines = self.node_temperatures(card)?;
        let amplitude = self.amplitude_ref(card)?;
        let step = self.step_mut(card)?;
        step.temperature.extend(lines.into_iter().map(|(key, value)| Target { key, value, amplitude: amplitude.clone() }));
        Ok(())
    }

    /// *END STEP: the step must have had its procedure card.
    pub(super) fn end_step(&mut self, card: &Card) -> Result<()> {
        if !self.in_step {
            return Err(card.error("without a *STEP"));
        }
        let step = self.steps.last().expect("in a step");
        if !step.has_procedure {
            return Err(error_at(&step.at, "STEP", "has no procedure card: slideline runs *STATIC steps (add *STATIC after *STEP)"));
        }
        self.in_step = false;
        Ok(())
    }

    /// An output request: noted, its time points used, a file request's FREQUENCY kept.
    pub(super) fn output_request(&mut self, card: &Card, kw: &str) -> Result<()> {
        self.output_requests.insert(format!("*{kw}"));
        self.use_time_points(card)?;
        // the frequency of the results file's field output
        if kw == "NODE FILE" || kw == "EL FILE" || kw == "CONTACT FILE" {
            let every: usize = match card.param("FREQUENCY") {
                Some(f) => f.parse().map_err(|_| card.error(format!("FREQUENCY={f}: a whole number >= 0")))?,
                None => 1,
            };
            // FREQUENCY=0: none of this request in the step; slideline writes all
            // fields or none, so a step whose every file request says 0 has none
            self.step_mut(card)?.file_requests[usize::from(every > 0)] += 1;
            if every > 0 && card.param("FREQUENCY").is_some() {
                self.output_every = Some(self.output_every.map_or(every, |e: usize| e.min(every)));
            }
        }
        Ok(())
    }

    /// *CONTROLS: of CalculiX's time incrementation parameters, I_G (the sixth value: an
    /// increment grows after increments that converged within it) is slideline's
    /// easy_iterations; the rest, and the field test's ratios, are not used (a note says so).
    pub(super) fn controls(&mut self, card: &Card) -> Result<()> {
        let time = card.param("PARAMETERS").is_some_and(|p| p.eq_ignore_ascii_case("TIME INCREMENTATION"));
        let given = card.data.first().filter(|d| time && d.fields.get(5).is_some_and(|f| !f.is_empty()));
        match given {
            Some(d) => {
                let i_g = d.number("CONTROLS", 5, "I_G", None)?;
                if !(i_g >= 1.0 && i_g.fract() == 0.0) {
                    return Err(card.error(format!("I_G = {i_g}: give a whole number of iterations >= 1")));
                }
                self.easy_iterations = Some(i_g as usize);
                self.notes.push(format!(
                    "*CONTROLS ({}): I_G = {i_g}: an increment grows after one that converged within {i_g} iterations; its other values are not used (slideline judges convergence by CalculiX's field test with its default ratios)",
                    card.at
                ));
            }
            None => self.notes.push(format!("*CONTROLS ({}) ignored: slideline judges convergence by CalculiX's field test with its default ratios", card.at)),
        }
        Ok(())
    }
}

//! The history part of a deck: *AMPLITUDE, *INITIAL CONDITIONS / *TEMPERATURE, *STEP and
//! *STATIC, *BOUNDARY, *DLOAD, *CHANGE FRICTION (the steps they expand to: inp/expand.rs).

use super::cards::{error_at, normalise, Card};
use super::{Builder, StepDef, Target};
use crate::error::Result;
use crate::model::heat::{HeatStep, HeldTemperature};
use crate::model::{Component, Predictor, Temperature};
use std::collections::BTreeSet;

impl Builder {
    pub(super) fn amplitude(&mut self, card: &Card) -> Result<()> {
        card.only(&["NAME", "TIME", "DEFINITION"])?;
        if card.param("TIME").is_some_and(|t| normalise(t) != "STEP TIME") {
            return Err(card.error("only TIME=STEP TIME is supported"));
        }
        if card.param("DEFINITION").is_some_and(|t| !t.eq_ignore_ascii_case("TABULAR")) {
            return Err(card.error("only DEFINITION=TABULAR is supported"));
        }
        let name = card.required("NAME")?.to_uppercase();
        let mut values = Vec::new();
        for d in &card.data {
            let fields: Vec<usize> = (0..d.fields.len()).filter(|&k| !d.fields[k].is_empty()).collect();
            if !fields.len().is_multiple_of(2) {
                return Err(error_at(&d.at, "AMPLITUDE", "values come in (time, amplitude) pairs"));
            }
            for pair in fields.chunks(2) {
                values.push((d.number("AMPLITUDE", pair[0], "time", None)?, d.number("AMPLITUDE", pair[1], "amplitude", None)?));
            }
        }
        if values.is_empty() || values.windows(2).any(|w| w[1].0 <= w[0].0) {
            return Err(card.error(format!("amplitude {name} needs (time, value) pairs with increasing times")));
        }
        self.amplitudes.insert(name, values);
        Ok(())
    }

    pub(super) fn amplitude_ref(&self, card: &Card) -> Result<Option<String>> {
        match card.param("AMPLITUDE") {
            None => Ok(None),
            Some(a) => {
                let a = a.to_uppercase();
                if self.amplitudes.contains_key(&a) {
                    Ok(Some(a))
                } else {
                    Err(card.error(format!("amplitude {a} is not defined (define it before its use)")))
                }
            }
        }
    }

    /// The (nodes, temperature) of each data line of *TEMPERATURE or *INITIAL CONDITIONS,
    /// TYPE=TEMPERATURE: a node or a node set, then degC.
    pub(super) fn node_temperatures(&self, card: &Card) -> Result<Vec<(Vec<usize>, f64)>> {
        if card.data.is_empty() {
            return Err(card.error("needs a data line: node or node set, temperature"));
        }
        card.data.iter().map(|d| Ok((self.node_items(d, &card.keyword, 0)?, d.number(&card.keyword, 1, "temperature", None)?))).collect()
    }

    /// A nodal field from `before` (None: every node the deck names must be given) with the
    /// values in order; `Err` counts the nodes left without one.
    pub(super) fn temperature_field(&self, before: Option<&Temperature>, lines: &[(Vec<usize>, f64)]) -> std::result::Result<Temperature, usize> {
        // a pre-tension section's partner node takes its node's temperature
        let partner = |n: usize| self.section_partners.iter().filter(move |(a, _)| *a == n).map(|&(_, p)| p);
        let values = lines.iter().flat_map(|(set, t)| set.iter().flat_map(move |&n| std::iter::once(n).chain(partner(n))).map(move |n| (n, *t)));
        temperature_field(self.mesh.coords.len(), &self.added_midside, before, values)
    }

    pub(super) fn step_mut(&mut self, card: &Card) -> Result<&mut StepDef> {
        match self.steps.last_mut() {
            Some(s) if self.in_step => Ok(s),
            _ => Err(card.error("belongs inside a *STEP")),
        }
    }

    pub(super) fn step(&mut self, card: &Card) -> Result<()> {
        card.only(&["NLGEOM", "INC", "NAME", "AMPLITUDE", "EXTRAPOLATION"])?;
        if self.in_step {
            return Err(card.error("the previous *STEP has no *END STEP"));
        }
        // INC is the most increments the step may take (slideline's cutbacks are bounded by
        // the minimum increment instead): a count, at least 1
        if let Some(inc) = card.param("INC").filter(|v| v.trim().parse::<u64>().map_or(true, |n| n == 0)) {
            return Err(card.error(format!("INC={inc}: give the largest number of increments, a whole number >= 1")));
        }
        if card.param("AMPLITUDE").is_some_and(|a| !a.eq_ignore_ascii_case("RAMP")) {
            return Err(card.error("only AMPLITUDE=RAMP (loads ramped over the step) is supported; use an *AMPLITUDE for other histories"));
        }
        let nlgeom = match card.param("NLGEOM").map(|v| v.to_uppercase()) {
            None => None,
            Some(v) if v.is_empty() || v == "YES" => Some(true),
            Some(v) if v == "NO" => Some(false),
            Some(v) => return Err(card.error(format!("NLGEOM={v}: YES or NO"))),
        };
        if let Some(e) = card.param("EXTRAPOLATION") {
            let predictor = match e.trim().to_uppercase().as_str() {
                "LINEAR" => Predictor::Extrapolate,
                "NO" => Predictor::None,
                other => return Err(card.error(format!("EXTRAPOLATION={other}: LINEAR or NO (PARABOLIC is not supported)"))),
            };
            match &self.predictor {
                Some((p, at)) if *p != predictor => {
                    return Err(card.error(format!("EXTRAPOLATION={e} differs from the EXTRAPOLATION of {at}: slideline takes one predictor for all steps")))
                }
                _ => self.predictor = Some((predictor, card.at.clone())),
            }
        }
        let name = card.param("NAME").map(|s| s.to_string()).unwrap_or_else(|| format!("step-{}", self.steps.len() + 1));
        self.steps.push(StepDef {
            name,
            at: card.at.clone(),
            nlgeom,
            initial: 1.0,
            period: 1.0,
            minimum: None,
            boundaries: Vec::new(),
            pressures: Vec::new(),
            body: Vec::new(),
            temperature: Vec::new(),
            new_loads: false,
            new_boundaries: false,
            boundary_cards: 0,
            file_requests: [0, 0],
            has_procedure: false,
            time_points: Vec::new(),
            friction_changes: Vec::new(),
            cloads: Vec::new(),
            new_cloads: false,
            heat: false,
            held_temperatures: Vec::new(),
        });
        self.in_step = true;
        Ok(())
    }

    pub(super) fn static_procedure(&mut self, card: &Card) -> Result<()> {
        card.only(&["DIRECT", "SOLVER"])?;
        if card.has("SOLVER") {
            self.notes.push(format!("*STATIC ({}): SOLVER= ignored, the linear solver is PETSc's (options after `--`)", card.at));
        }
        let step = self.step_mut(card)?;
        if step.has_procedure {
            return Err(card.error("a step takes one procedure card"));
        }
        step.has_procedure = true;
        if let Some(d) = card.data.first() {
            let period = d.number("STATIC", 1, "time period", Some(1.0))?;
            let initial = d.number("STATIC", 0, "initial increment", Some(period))?;
            if !(period > 0.0 && initial > 0.0 && initial <= period * (1.0 + 1e-12)) {
                return Err(error_at(&d.at, "STATIC", format!("need 0 < initial increment ({initial}) <= time period ({period})")));
            }
            step.period = period;
            step.initial = initial;
            step.minimum = d.fields.get(2).filter(|f| !f.is_empty()).map(|_| d.number("STATIC", 2, "minimum increment", None)).transpose()?;
        }
        Ok(())
    }

    /// *HEAT TRANSFER, STEADY STATE: a steady heat-conduction step (`model::heat`); its data
    /// line (increments, period) has no use in a linear steady solve.
    pub(super) fn heat_transfer_procedure(&mut self, card: &Card) -> Result<()> {
        card.only(&["STEADY STATE", "SOLVER", "DIRECT"])?;
        if !card.has("STEADY STATE") {
            return Err(card.error("a transient heat transfer: slideline solves steady conduction only (add STEADY STATE)"));
        }
        let step = self.step_mut(card)?;
        if step.has_procedure {
            return Err(card.error("a step takes one procedure card"));
        }
        step.has_procedure = true;
        step.heat = true;
        Ok(())
    }

    /// The heat steps, taken out of the step list (the rest are static): each holds the model
    /// data's temperatures and its own; a mechanical load in one is refused, a displacement
    /// constraint noted (it has no effect on the temperatures).
    pub(super) fn heat_steps(&mut self) -> Result<Vec<HeatStep>> {
        if let Some(k) = self.steps.iter().position(|s| s.heat).filter(|&k| self.steps[..k].iter().any(|s| !s.heat)) {
            let s = &self.steps[k];
            return Err(error_at(&s.at, "STEP", format!("step {}: a *HEAT TRANSFER step after a *STATIC step: slideline solves the heat steps first", s.name)));
        }
        let (heat, general): (Vec<StepDef>, Vec<StepDef>) = std::mem::take(&mut self.steps).into_iter().partition(|s| s.heat);
        self.steps = general;
        let mut out = Vec::new();
        for s in heat {
            if !s.pressures.is_empty() || !s.body.is_empty() || !s.cloads.is_empty() || !s.temperature.is_empty() || !s.friction_changes.is_empty() {
                return Err(error_at(
                    &s.at,
                    "STEP",
                    format!(
                        "step {}: a *HEAT TRANSFER step holds temperatures (*BOUNDARY, 11); a mechanical load or *TEMPERATURE in it has no meaning",
                        s.name
                    ),
                ));
            }
            if !s.boundaries.is_empty() && !self.steps.is_empty() {
                return Err(error_at(
                    &s.at,
                    "STEP",
                    format!("step {}: displacement constraints in a *HEAT TRANSFER step: give them in the model data or the *STATIC step", s.name),
                ));
            }
            if !s.boundaries.is_empty() {
                self.notes.push(format!("step {}: its displacement constraints have no effect in a heat transfer step", s.name));
            }
            if s.nlgeom.is_some() {
                self.notes.push(format!("step {}: NLGEOM has no effect in a heat transfer step", s.name));
            }
            let temperatures = self
                .fixed_temperatures
                .iter()
                .chain(&s.held_temperatures)
                .map(|(set, value)| HeldTemperature { node_set: set.clone(), value: *value })
                .collect();
            out.push(HeatStep { name: s.name, temperatures });
        }
        if out.is_empty() && !self.fixed_temperatures.is_empty() {
            self.notes.push("temperatures held by *BOUNDARY, 11 in the model data have no effect without a *HEAT TRANSFER step".into());
        }
        if let Some(s) = self.steps.iter().find(|s| !s.held_temperatures.is_empty()) {
            return Err(error_at(
                &s.at,
                "STEP",
                format!("step {}: a temperature (*BOUNDARY, 11) outside a *HEAT TRANSFER step: give it with *TEMPERATURE", s.name),
            ));
        }
        Ok(out)
    }

    /// *TIME POINTS: the listed times (GENERATE: start, end, increment triples), in step time
    /// or, with TIME=TOTAL TIME, in total time; an output request naming them makes its step's
    /// increments end on them ([`Builder::use_time_points`]).
    pub(super) fn time_points(&mut self, card: &Card) -> Result<()> {
        card.only(&["NAME", "GENERATE", "TIME"])?;
        let name = card.required("NAME")?.to_uppercase();
        let total = match card.param("TIME").map(normalise).as_deref() {
            None | Some("STEP TIME") => false,
            Some("TOTAL TIME") => true,
            Some(other) => return Err(card.error(format!("TIME={other}: STEP TIME or TOTAL TIME"))),
        };
        let mut values = Vec::new();
        for d in &card.data {
            for k in (0..d.fields.len()).filter(|&k| !d.fields[k].is_empty()) {
                values.push(d.number("TIME POINTS", k, "time", None)?);
            }
        }
        let times = if card.has("GENERATE") {
            if values.len() % 3 != 0 {
                return Err(card.error("GENERATE takes (start, end, increment) triples"));
            }
            let mut times = Vec::new();
            for t in values.chunks(3) {
                let (start, end, step) = (t[0], t[1], t[2]);
                if !(step > 0.0 && end >= start) {
                    return Err(card.error(format!("GENERATE {start}, {end}, {step}: need end >= start and an increment > 0")));
                }
                let n = ((end - start) / step + 1e-9).floor() as usize;
                times.extend((0..=n).map(|k| start + k as f64 * step));
            }
            times
        } else {
            values
        };
        if times.is_empty() || times.windows(2).any(|w| w[1] <= w[0]) {
            return Err(card.error(format!("time points {name}: give increasing times")));
        }
        self.time_points.insert(name, (times, total));
        Ok(())
    }

    /// An output request's TIME POINTS=: its step's increments end on those times.
    pub(super) fn use_time_points(&mut self, card: &Card) -> Result<()> {
        let Some(name) = card.param("TIME POINTS").map(str::to_uppercase) else { return Ok(()) };
        let points =
            self.time_points.get(&name).cloned().ok_or_else(|| card.error(format!("time points {name} are not defined (define them before their use)")))?;
        self.step_mut(card)?.time_points.push(points);
        Ok(())
    }

    pub(super) fn boundary(&mut self, card: &Card) -> Result<()> {
        card.only(&["OP", "AMPLITUDE"])?;
        let new = match card.param("OP").map(|o| o.to_uppercase()).as_deref() {
            None | Some("MOD") => false,
            Some("NEW") if self.in_step => true,
            Some("NEW") => return Err(card.error("OP=NEW belongs in a *STEP (it releases the constraints of earlier steps)")),
            Some(o) => return Err(card.error(format!("OP={o}: MOD or NEW"))),
        };
        if self.in_step {
            // as CalculiX: OP counts on the step's first *BOUNDARY card only
            let step = self.steps.last_mut().expect("in a step");
            step.boundary_cards += 1;
            if step.boundary_cards == 1 {
                step.new_boundaries = new;
            } else if new {
                self.notes.push(format!("{}: OP=NEW on a step's later *BOUNDARY card has no effect (CalculiX reads it on the first only)", card.at));
            }
        }
        let amplitude = self.amplitude_ref(card)?;
        for d in &card.data {
            let target = d.fields.first().cloned().unwrap_or_default();
            let nodes = self.node_items(d, "BOUNDARY", 0)?;
            let set = if target.chars().all(|c| c.is_ascii_digit()) {
                // "N<number>", unless the deck names a set so (CalculiX's pret2 has both a
                // node 1 in *BOUNDARY and a set N1 of another node)
                let mut name = format!("N{target}");
                while self.deck_node_sets.contains(&name) {
                    name.push('_');
                }
                self.node_sets.insert(name.clone(), nodes);
                name
            } else {
                target.to_uppercase()
            };
            let word = d.fields.get(1).map(|s| s.to_uppercase()).unwrap_or_default();
            // degree of freedom 11: a temperature, which heat steps hold
            if d.fields.get(1).is_some_and(|f| f.trim() == "11") {
                if d.fields.get(2).is_some_and(|f| !f.trim().is_empty() && f.trim() != "11") {
                    return Err(error_at(&d.at, "BOUNDARY", "degree of freedom 11 (temperature) goes on a line of its own: 11, 11, value"));
                }
                let value = d.number("BOUNDARY", 3, "temperature", Some(0.0))?;
                match self.in_step {
                    true => self.steps.last_mut().expect("in a step").held_temperatures.push((set, value)),
                    false => self.fixed_temperatures.push((set, value)),
                }
                continue;
            }
            let (first, last, value) = match word.as_str() {
                "ENCASTRE" | "PINNED" => (1, 2, 0.0),
                "XSYMM" => (1, 1, 0.0),
                "YSYMM" => (2, 2, 0.0),
                _ => {
                    let first = d.id("BOUNDARY", 1, "first degree of freedom")?;
                    let last = if d.fields.get(2).is_some_and(|f| !f.is_empty()) { d.id("BOUNDARY", 2, "last degree of freedom")? } else { first };
                    (first, last, d.number("BOUNDARY", 3, "value", Some(0.0))?)
                }
            };
            if first > last || last > 2 {
                return Err(error_at(
                    &d.at,
                    "BOUNDARY",
                    format!("degrees of freedom {first} to {last}: axisymmetric nodes have 1 (ur), 2 (uz) and 11 (temperature)"),
                ));
            }
            for dof in first..=last {
                let component = if dof == 1 { Component::R } else { Component::Z };
                if self.in_step {
                    let step = self.steps.last_mut().expect("in a step");
                    step.boundaries.retain(|b| b.key != (set.clone(), component));
                    step.boundaries.push(Target { key: (set.clone(), component), value, amplitude: amplitude.clone() });
                } else {
                    if value != 0.0 || amplitude.is_some() {
                        return Err(error_at(&d.at, "BOUNDARY", "a prescribed (non-zero) value belongs inside a *STEP; model data only fixes"));
                    }
                    self.fixed.push((set.clone(), component));
                }
            }
        }
        Ok(())
    }
}

/// A load card's OP=: NEW (true) removes the earlier loads of its kind that it does not
/// restate, MOD (the default) keeps them.
pub(super) fn replaces_earlier_loads(card: &Card) -> Result<bool> {
    match card.param("OP").map(|o| o.to_uppercase()).as_deref() {
        None | Some("MOD") => Ok(false),
        Some("NEW") => Ok(true),
        Some(o) => Err(card.error(format!("OP={o}: MOD or NEW"))),
    }
}

/// A nodal field over `nodes` nodes from `before` with the values in order; the mid-side nodes
/// slideline added to CAX4 elements take their corners' mean, as a linear field along the edge
/// has. `Err` counts the nodes left without a value.
pub(super) fn temperature_field(
    nodes: usize,
    added_midside: &std::collections::HashMap<(usize, usize), usize>,
    before: Option<&Temperature>,
    values: impl IntoIterator<Item = (usize, f64)>,
) -> std::result::Result<Temperature, usize> {
    let mut field = crate::model::temperature::apply(nodes, before, values);
    for (&(a, b), &m) in added_midside {
        field[m] = field[a].zip(field[b]).map(|(x, y)| 0.5 * (x + y));
    }
    // counted among the deck's own nodes (an added one lacks a value only when a corner does)
    let added: BTreeSet<usize> = added_midside.values().copied().collect();
    let missing = field.iter().enumerate().filter(|(n, t)| t.is_none() && !added.contains(n)).count();
    if missing > 0 {
        return Err(missing);
    }
    Ok(Temperature::from_nodal(field.into_iter().flatten().collect()))
}

//! The model's one check before anything runs: the mesh, the materials, the sets, surfaces and
//! loads the steps name, the contact pairs, and the constraints (one value per degree of
//! freedom; no body free to move along the axis).

use super::{
    known, BodyLoad, Component, ContactIntegration, ContactPair, Edge, Material, Model, Penalty, Plasticity, Step, Temperature, MAX_INCREMENTS,
    MIN_YOUNGS_MODULUS,
};
use crate::error::{Error, Result};
use std::collections::BTreeMap;

impl Model {
    /// A contact pair's surfaces, penalty, capture distance and augmented Lagrangian settings.
    fn validate_contact(&self, c: &ContactPair) -> Result<()> {
        for surface in [&c.slave, &c.master] {
            self.surface(surface).map_err(|e| Error::input(format!("contact '{}': {e}", c.name)))?;
        }
        let eps = match c.penalty {
            Penalty::Stiffness(v) | Penalty::Factor(v) => v,
            Penalty::Exponential { clearance, pressure } => {
                if !(clearance > 0.0 && clearance.is_finite() && pressure > 0.0 && pressure.is_finite()) {
                    return Err(Error::input(format!(
                        "contact '{}': the exponential law needs c0 > 0 (mm) and p0 > 0 (MPa), got c0 = {clearance}, p0 = {pressure}",
                        c.name
                    )));
                }
                if c.integration != ContactIntegration::NodeToSegment || c.augmented_lagrangian.is_some() {
                    return Err(Error::input(format!(
                        "contact '{}': the exponential pressure-overclosure law is built for node-to-segment pairs without augmented Lagrangian iterations",
                        c.name
                    )));
                }
                pressure
            }
        };
        if !(eps > 0.0 && eps.is_finite()) {
            return Err(Error::input(format!("contact '{}': the penalty must be > 0, got {eps}", c.name)));
        }
        if !(c.capture_distance > 0.0 && c.capture_distance.is_finite()) {
            return Err(Error::input(format!("contact '{}': capture_distance must be > 0, got {}", c.name, c.capture_distance)));
        }
        if let Some(al) = c.augmented_lagrangian {
            if al.penetration_tolerance.is_nan() || al.penetration_tolerance <= 0.0 || al.max_augmentations == 0 {
                return Err(Error::input(format!("contact '{}': augmented_lagrangian needs penetration_tolerance > 0 and max_augmentations >= 1", c.name)));
            }
        }
        Ok(())
    }

    /// Checks everything the solver relies on; the first problem found is reported by name.
    pub fn validate(&self) -> Result<()> {
        if self.element_section.len() != self.mesh.elements.len() {
            return Err(Error::input("internal: element_section does not match the element count"));
        }
        self.mesh.validate_sections(&self.element_section)?;
        if self.perturbations().next().is_some() && self.element_section.iter().any(|s| !s.is_axisymmetric()) {
            return Err(Error::input(
                "perturbation steps (harmonic loads, buckling, natural frequencies) are built for axisymmetric models only; this model has plane-strain or plane-stress elements",
            ));
        }
        // a model of heat steps alone uses its materials' conductivity alone (`heat::HeatStep`)
        for m in self.materials.iter().filter(|_| self.general_step_count() > 0) {
            validate_material(m)?;
        }
        for p in self.perturbations() {
            p.validate(self)?;
        }
        for h in self.heat_steps() {
            h.validate(self)?;
        }
        if self.output.every == 0 {
            return Err(Error::input("[output]: every must be at least 1 (fields of every increment)"));
        }
        let c = &self.stepping;
        let ranges = [
            ("cutback_factor", c.cutback_factor, c.cutback_factor > 0.0 && c.cutback_factor < 1.0, "0 < cutback_factor < 1"),
            ("growth_factor", c.growth_factor, c.growth_factor >= 1.0 && c.growth_factor.is_finite(), "growth_factor >= 1"),
            ("min_increment", c.min_increment, c.min_increment > 0.0 && c.min_increment <= 1.0, "0 < min_increment <= 1"),
            ("max_newton_iterations", c.max_newton_iterations as f64, c.max_newton_iterations >= 1, "max_newton_iterations >= 1"),
        ];
        if let Some((key, value, _, need)) = ranges.into_iter().find(|r| !r.2) {
            return Err(Error::input(format!("[stepping] {key} = {value}: need {need}")));
        }
        self.validate_step_order()?;
        let mut seen: Vec<&str> = self.heat_steps().map(|h| h.name.as_str()).collect();
        for (k, step) in self.general_steps().enumerate() {
            if step.name.trim().is_empty() {
                return Err(Error::input(format!("step {}: an empty name (a restart finds steps by name)", k + 1)));
            }
            if seen.contains(&step.name.as_str()) {
                return Err(Error::input(format!("step {}: the name {:?} is used twice (a restart finds steps by name)", k + 1, step.name)));
            }
            seen.push(&step.name);
        }
        if self.element_material.len() != self.mesh.elements.len() {
            return Err(Error::input("internal: element_material does not match the element count"));
        }
        for c in &self.contacts {
            self.validate_contact(c)?;
        }
        let mut names: Vec<&str> = self.contacts.iter().map(|c| c.name.as_str()).collect();
        names.sort_unstable();
        if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
            return Err(Error::input(format!("contact pair name '{}' is used twice: give each pair its own name", w[0])));
        }
        if let Some(t) = self.reference_temperature.non_finite() {
            return Err(Error::input(format!("the reference temperature must be finite, got {t}")));
        }
        let fields = std::iter::once(&self.reference_temperature).chain(self.general_steps().filter_map(|s| s.temperature.as_ref()));
        if let Some(n) = fields
            .filter_map(|t| match t {
                Temperature::Nodal(v) => Some(v.len()),
                Temperature::Uniform(_) => None,
            })
            .find(|&n| n != self.mesh.coords.len())
        {
            return Err(Error::input(format!("a temperature field has {n} values for the mesh's {} nodes", self.mesh.coords.len())));
        }
        if self.general_step_count() == 0 && self.heat_steps().next().is_none() {
            return Err(Error::input("the model has no steps: add a [[step]]"));
        }
        for step in self.general_steps() {
            self.validate_general_step(step)?;
        }
        self.validate_constraints()?;
        self.check_constraints()?;
        Ok(())
    }

    /// A general step's loads: its increments, temperature, displacements, pressures, nodal
    /// forces, friction changes and body loads, each on what the model has.
    fn validate_general_step(&self, step: &super::GeneralStep) -> Result<()> {
        if step.increments == 0 || step.increments > MAX_INCREMENTS {
            return Err(Error::input(format!("step '{}': increments must lie in 1..={MAX_INCREMENTS}, got {}", step.name, step.increments)));
        }
        if let Some(t) = step.temperature.as_ref().and_then(Temperature::non_finite) {
            return Err(Error::input(format!("step '{}': temperature must be finite, got {t}", step.name)));
        }
        for d in &step.displacements {
            self.node_set(&d.node_set).map_err(|e| Error::input(format!("step '{}': {e}", step.name)))?;
            if !d.value.is_finite() {
                return Err(Error::input(format!("step '{}': displacement on '{}' is not finite", step.name, d.node_set)));
            }
        }
        for (k, p) in step.pressures.iter().enumerate() {
            self.surface(&p.surface).map_err(|e| Error::input(format!("step '{}': {e}", step.name)))?;
            if !p.value.is_finite() {
                return Err(Error::input(format!("step '{}': pressure on '{}' must be finite, got {}", step.name, p.surface, p.value)));
            }
            if step.pressures[..k].iter().any(|q| q.surface == p.surface) {
                return Err(Error::input(format!("step '{}': surface '{}' is given two pressures: give one (their sum, if both act)", step.name, p.surface)));
            }
        }
        for f in &step.nodal_forces {
            if f.node >= self.mesh.coords.len() || !f.value.is_finite() {
                return Err(Error::input(format!(
                    "step '{}': a nodal force of {} on node index {} (give a finite force on a mesh node)",
                    step.name, f.value, f.node
                )));
            }
        }
        for (k, change) in step.friction_changes.iter().enumerate() {
            if !self.contacts.iter().any(|c| c.name == change.pair) {
                return Err(Error::input(format!(
                    "step '{}': friction of an unknown contact pair '{}' (known: {})",
                    step.name,
                    change.pair,
                    known(self.contacts.iter().map(|c| &c.name))
                )));
            }
            if step.friction_changes[..k].iter().any(|c| c.pair == change.pair) {
                return Err(Error::input(format!("step '{}': the friction of pair '{}' is changed twice", step.name, change.pair)));
            }
        }
        for (k, b) in step.body_loads.iter().enumerate() {
            let at = |what: String| Error::input(format!("step '{}': body load on '{}': {what}", step.name, b.elements));
            let elements = self.element_sets.get(&b.elements).ok_or_else(|| at(format!("unknown element set '{}'", b.elements)))?;
            if !b.force.value().is_finite() {
                return Err(at(format!("{} must be finite", b.force.value())));
            }
            if let Some(m) = elements.iter().map(|&e| &self.materials[self.element_material[e]]).find(|m| !(m.density > 0.0 && m.density.is_finite())) {
                return Err(at(format!("material '{}' has no density (t/mm^3; steel 7.85e-9)", m.name)));
            }
            let same = |c: &BodyLoad| c.elements == b.elements && std::mem::discriminant(&c.force) == std::mem::discriminant(&b.force);
            if step.body_loads[..k].iter().any(same) {
                return Err(at("given twice: give one value (their sum, if both act)".into()));
            }
        }
        Ok(())
    }

    /// The steps run in one order: heat steps first (their field is the general steps'
    /// temperature), then the general steps, then the perturbation steps about their end.
    fn validate_step_order(&self) -> Result<()> {
        let rank = |s: &Step| match s {
            Step::Heat(_) => 0,
            Step::General(_) => 1,
            Step::Perturbation(_) => 2,
        };
        match self.steps.windows(2).find(|w| rank(&w[0]) > rank(&w[1])) {
            Some(w) => Err(Error::input(format!(
                "step '{}': a {} step after the {} step '{}': the steps run heat steps first, then the general steps, then the perturbation steps",
                w[1].name(),
                w[1].procedure(),
                w[0].procedure(),
                w[0].name()
            ))),
            None => Ok(()),
        }
    }

    /// Refuses two different values prescribed on one degree of freedom (by two entries of
    /// the constraints in force in a step: a step's own and those kept from earlier steps),
    /// and a body that no constraint holds axially (a rigid-body motion along z, which the
    /// solver would answer with an arbitrary offset). A body touching a contact surface is
    /// left to the contact to hold.
    fn check_constraints(&self) -> Result<()> {
        let mut in_force: BTreeMap<(String, Component), f64> = BTreeMap::new();
        let mut held_z = vec![false; self.mesh.coords.len()];
        let mut held_r = vec![false; self.mesh.coords.len()];
        for step in self.general_steps() {
            for (k, d) in step.displacements.iter().enumerate() {
                if let Some(e) = step.displacements[..k].iter().find(|e| e.node_set == d.node_set && e.component == d.component && e.value != d.value) {
                    return Err(Error::input(format!(
                        "step '{}': set '{}' is given {} = {} and {} = {}: one degree of freedom takes one value",
                        step.name,
                        d.node_set,
                        d.component.name(),
                        e.value,
                        d.component.name(),
                        d.value
                    )));
                }
                in_force.insert((d.node_set.clone(), d.component), d.value);
            }
            let mut by_dof: std::collections::HashMap<(usize, Component), (&str, f64)> = std::collections::HashMap::new();
            for ((set, component), value) in &in_force {
                for &n in self.node_set(set)? {
                    match component {
                        Component::Z => held_z[n] = true,
                        Component::R => held_r[n] = true,
                    }
                    match by_dof.insert((n, *component), (set.as_str(), *value)) {
                        Some((other, v)) if v != *value => {
                            return Err(Error::input(format!(
                                "step '{}': node {} has {} = {v} from set '{other}' and {} = {value} from set '{set}': one degree of freedom takes one value",
                                step.name,
                                self.mesh.node_ids[n],
                                component.name(),
                                component.name()
                            )))
                        }
                        _ => {}
                    }
                }
            }
        }
        // (a model of heat steps alone moves nothing)
        if let Some((n, _)) = self.axially_free_bodies(&held_z).into_iter().filter(|_| self.general_step_count() > 0).find(|(_, pairs)| pairs.is_empty()) {
            return Err(Error::input(format!(
                "the body containing node {} (at r = {}, z = {}) has no prescribed uz and no contact: it is free to move along the axis; prescribe uz on one of its nodes",
                self.mesh.node_ids[n], self.mesh.coords[n][0], self.mesh.coords[n][1]
            )));
        }
        // a plane body has no hoop stiffness to hold it in r either
        let plane_nodes: std::collections::HashSet<usize> =
            (0..self.mesh.elements.len()).filter(|&e| !self.element_section[e].is_axisymmetric()).flat_map(|e| self.mesh.element_nodes(e).to_vec()).collect();
        let held_r_or_axisymmetric: Vec<bool> = (0..held_r.len()).map(|n| held_r[n] || !plane_nodes.contains(&n)).collect();
        if let Some((n, _)) = self.axially_free_bodies(&held_r_or_axisymmetric).into_iter().find(|(_, pairs)| pairs.is_empty()) {
            return Err(Error::input(format!(
                "the plane body containing node {} (at x = {}, y = {}) has no prescribed ux and no contact: it is free to move along x; prescribe ux on one of its nodes",
                self.mesh.node_ids[n], self.mesh.coords[n][0], self.mesh.coords[n][1]
            )));
        }
        Ok(())
    }

    /// A note for each contact pair whose surfaces can never face each other: no slave edge's
    /// outward normal is against any master edge's (a ring's outside listed against a tube's
    /// outside, say). Such a pair never closes; the note names it, since the run itself cannot.
    /// A note for each material whose data look like another system of units than
    /// slideline's (N, mm, MPa): a Young's modulus below 1000 MPa (200 for steel in GPa), or a
    /// yield stress above a twentieth of it (a yield strain of 5 %: no metal; 300 MPa over
    /// E = 200 GPa given as 200).
    pub fn implausible_units(&self) -> Vec<String> {
        let units = "slideline's units are N, mm, MPa (N/mm^2), t/mm^3, s and degC: steel has E about 200000 MPa";
        let mut notes = Vec::new();
        for m in &self.materials {
            let e = m.youngs_modulus;
            if e < 1000.0 {
                notes.push(format!("material {}: Young's modulus {e} MPa is below 1000 MPa, softer than any metal or polymer: {units}", m.name));
            }
            let yield_stress = m.plasticity.as_ref().map_or(f64::INFINITY, |h| h.initial_yield_stress());
            if yield_stress.is_finite() && yield_stress > e / 20.0 {
                notes.push(format!(
                    "material {}: yield stress {yield_stress} MPa is more than a twentieth of its Young's modulus {e} MPa (a yield strain above 5 %): {units}",
                    m.name
                ));
            }
        }
        notes
    }

    pub fn never_facing_pairs(&self) -> Vec<String> {
        // the outward normal of a counter-clockwise element's side from its corner a to b
        let normal = |e: Edge| {
            let [a, b, _] = self.mesh.edge_nodes(e).map(|n| self.mesh.coords[n]);
            let (tr, tz) = (b[0] - a[0], b[1] - a[1]);
            let length = tr.hypot(tz).max(f64::MIN_POSITIVE);
            [tz / length, -tr / length]
        };
        let normals = |name: &str| self.surfaces.get(name).map_or(Vec::new(), |edges| edges.iter().map(|&e| normal(e)).collect::<Vec<_>>());
        self.contacts
            .iter()
            .filter(|c| c.slave != c.master)
            .filter(|c| {
                let (slave, master) = (normals(&c.slave), normals(&c.master));
                !slave.is_empty() && !master.is_empty() && !slave.iter().any(|s| master.iter().any(|m| s[0] * m[0] + s[1] * m[1] < 0.0))
            })
            .map(|c| {
                format!(
                    "contact '{}': its surfaces '{}' and '{}' never face each other (their outward normals point the same way everywhere), so the pair can never close: is a surface the wrong face of its body?",
                    c.name, c.slave, c.master
                )
            })
            .collect()
    }

    /// The bodies no node of which has a prescribed uz (`held_z` per node): per body, its first
    /// node and the contact pairs whose surfaces it lies on, the only things that can hold it
    /// along the axis (none: nothing does).
    pub fn axially_free_bodies(&self, held_z: &[bool]) -> Vec<(usize, Vec<usize>)> {
        let pair_nodes: Vec<std::collections::HashSet<usize>> = self
            .contacts
            .iter()
            .map(|c| {
                [&c.slave, &c.master]
                    .into_iter()
                    .filter_map(|s| self.surfaces.get(s))
                    .flat_map(|edges| edges.iter().flat_map(|&e| self.mesh.edge_nodes(e)))
                    .collect()
            })
            .collect();
        // a body a multi-point constraint touches is left to it, as one contact touches to the contact
        let constrained = self.constrained_nodes();
        self.mesh
            .bodies()
            .into_iter()
            .filter(|body| !body.iter().any(|&n| held_z[n] || constrained[n]))
            .map(|body| (body[0], (0..pair_nodes.len()).filter(|&p| body.iter().any(|n| pair_nodes[p].contains(n))).collect()))
            .collect()
    }
}

/// A material's elastic constants, expansion and plasticity, for the general steps.
fn validate_material(m: &Material) -> Result<()> {
    if m.youngs_modulus.is_nan() || m.poissons_ratio.is_nan() {
        return Err(Error::input(format!(
            "material '{}' has no elastic constants (Young's modulus, Poisson's ratio; *ELASTIC): the general steps need them",
            m.name
        )));
    }
    if !(m.youngs_modulus > 0.0 && m.youngs_modulus.is_finite()) {
        return Err(Error::input(format!("material '{}': Young's modulus must be > 0, got {}", m.name, m.youngs_modulus)));
    }
    if m.youngs_modulus < MIN_YOUNGS_MODULUS {
        return Err(Error::input(format!(
            "material '{}': Young's modulus {} MPa is below {MIN_YOUNGS_MODULUS} MPa (units are mm, N, MPa: steel is 2e5)",
            m.name, m.youngs_modulus
        )));
    }
    if !(m.poissons_ratio > -1.0 && m.poissons_ratio < 0.5) {
        return Err(Error::input(format!("material '{}': Poisson's ratio must lie in (-1, 0.5), got {}", m.name, m.poissons_ratio)));
    }
    if !m.thermal_expansion.is_finite() {
        return Err(Error::input(format!("material '{}': thermal expansion must be finite", m.name)));
    }
    if let Some(Plasticity::Linear { yield_stress, modulus }) = m.plasticity {
        if !(yield_stress > 0.0 && yield_stress.is_finite()) {
            return Err(Error::input(format!("material '{}': yield stress must be > 0, got {yield_stress}", m.name)));
        }
        if !(modulus >= 0.0 && modulus.is_finite()) {
            return Err(Error::input(format!("material '{}': hardening modulus must be >= 0, got {modulus}", m.name)));
        }
    }
    Ok(())
}

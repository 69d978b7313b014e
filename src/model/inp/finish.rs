//! The cards read made into a [`Model`]: the builder's last checks, its notes on how the deck
//! runs, the sections given their materials, the steps expanded.

use super::cards::error_at;
use super::{Builder, InpModel, CALCULIX_SEGMENT_DEGREES};
use crate::error::{Error, Result};
use crate::fe::section::Section;
use crate::model::{Kinematics, Model, Step, SteppingControls, Temperature};

impl Builder {
    /// The model of the cards read, with the notes on how it was read.
    pub(super) fn finish(mut self, source_text: String, source_files: Vec<std::path::PathBuf>) -> Result<InpModel> {
        if self.in_step {
            let at = &self.steps.last().expect("in a step").at;
            return Err(error_at(at, "STEP", "has no *END STEP"));
        }
        self.join_midside_nodes_to_sets();
        self.resolve_ties()?;
        // a heat deck's materials need no elastic constants, and its output is the heat group's
        let heat = self.steps.iter().any(|s| s.heat);
        self.note_elements_and_output(heat);

        let materials = self.material_list(heat)?;
        for m in materials.iter().filter(|m| !heat && m.conductivity > 0.0) {
            self.notes.push(format!("material {}: *CONDUCTIVITY has no effect in a static step (heat transfer steps use it)", m.name));
        }
        if materials.is_empty() {
            return Err(Error::input("the deck defines no *MATERIAL"));
        }
        let (element_material, element_section) = self.sections_of_elements(&materials)?;
        let axisymmetric = element_section.iter().any(|s| s.is_axisymmetric());
        if !axisymmetric {
            self.notes.push("a plane model: forces and reactions are those of the sections' thickness (no per radian, ring or segment values)".to_string());
        } else if element_section.iter().any(|s| !s.is_axisymmetric()) {
            self.notes.push(
                "plane elements beside axisymmetric ones: as in CalculiX, a plane slab's forces are the whole ring's, so per radian its *SOLID SECTION thickness is thickness / 2 pi"
                    .to_string(),
            );
        }
        if let Some(e) = element_material.iter().position(|&m| m == usize::MAX) {
            return Err(Error::input(format!("element {} has no *SOLID SECTION", self.mesh.element_ids[e])));
        }

        if self.steps.is_empty() {
            return Err(Error::input("the deck has no *STEP"));
        }
        let heat_steps = self.heat_steps()?;
        let kinematics = if self.steps.iter().any(|s| s.nlgeom == Some(true)) { Kinematics::Finite } else { Kinematics::Small };
        if let (Kinematics::Finite, Some(at)) = (kinematics, &self.mass_load_at) {
            return Err(error_at(
                at,
                "DLOAD",
                "a load on point masses with NLGEOM: slideline applies their force at the masses' initial position only (a dead load); run the deck without NLGEOM",
            ));
        }
        if kinematics == Kinematics::Finite && self.steps.first().is_some_and(|s| s.nlgeom != Some(true)) {
            self.notes.push("NLGEOM is set in a later step: slideline runs every step with finite strain".into());
        }
        let uses_temperature = self.steps.iter().any(|s| !s.temperature.is_empty());
        let reference_temperature = match &self.initial_temperature {
            Some((lines, at)) => self.temperature_field(None, lines).map_err(|missing| {
                let named = self.mesh.coords.len() - self.added_midside.len();
                error_at(
                    at,
                    "INITIAL CONDITIONS",
                    format!("TYPE=TEMPERATURE: {missing} of the {named} nodes have no temperature (give every node one: the stress-free state)"),
                )
            })?,
            None if uses_temperature => return Err(Error::input("*TEMPERATURE needs *INITIAL CONDITIONS, TYPE=TEMPERATURE (the stress-free temperature)")),
            None => Temperature::Uniform(0.0),
        };
        let contacts = self.contact_pairs()?;
        let steps = self.expand_steps(&reference_temperature, &contacts)?;
        if steps.iter().all(|s| s.body_loads.is_empty()) {
            for m in &self.materials {
                if let Some(at) = &m.density_at {
                    self.notes.push(format!("material {}: *DENSITY ({at}) has no effect: no step loads it (*DLOAD GRAV or CENTRIF)", m.name));
                }
            }
        }
        let contacts = contacts.into_iter().map(|c| c.pair).collect();
        let mut stepping = SteppingControls::default();
        stepping.easy_iterations = self.easy_iterations.unwrap_or(stepping.easy_iterations);
        stepping.predictor = self.predictor.as_ref().map_or(stepping.predictor, |p| p.0);
        if let Some(min) = self.steps.iter().filter_map(|s| s.minimum.map(|m| m / s.period)).reduce(f64::min) {
            stepping.min_increment = min.clamp(1e-12, 1.0);
        }
        if axisymmetric && !heat {
            self.notes.push(format!(
                "reactions are written per radian, per full ring (_ring) and per {CALCULIX_SEGMENT_DEGREES}-degree segment (_2deg, CalculiX's axisymmetric convention)"
            ));
        }
        let model = Model {
            mesh: self.mesh,
            node_sets: self.node_sets,
            element_sets: self.element_sets,
            surfaces: self.surfaces,
            materials,
            element_material,
            element_section,
            element_integration: self.element_integration,
            reference_temperature,
            kinematics,
            stepping,
            output: crate::model::OutputControls { every: self.output_every.unwrap_or(1), ..Default::default() },
            contacts,
            constraints: self.constraints,
            steps: heat_steps.into_iter().map(Step::Heat).chain(steps.into_iter().map(Step::General)).collect(),
            source_text,
            source_files,
            reaction_segment_degrees: axisymmetric.then_some(CALCULIX_SEGMENT_DEGREES),
        };
        model.validate()?;
        Ok(InpModel { model, notes: self.notes })
    }

    /// Notes on how the deck's element types run and how its output requests are answered.
    fn note_elements_and_output(&mut self, heat: bool) {
        for (kind, n) in &self.element_types {
            self.notes.push(format!("{n} {kind} elements run as {}", element_note(kind)));
        }
        if heat && !self.output_requests.is_empty() {
            let list: Vec<&str> = self.output_requests.iter().map(|s| s.as_str()).collect();
            self.notes.push(format!("output requests ({}) are answered by the results file: each heat step's temperatures and heat flux", list.join(", ")));
        } else if !self.output_requests.is_empty() {
            let list: Vec<&str> = self.output_requests.iter().map(|s| s.as_str()).collect();
            let every = match self.output_every {
                Some(n) if n > 1 => format!("every field at every {n}th increment and at the end of each step (FREQUENCY={n}), the history at every increment"),
                _ => "every field at every increment".to_string(),
            };
            self.notes.push(format!("output requests ({}) are answered by the results file: {every}", list.join(", ")));
        }
    }

    /// Each element's material (an index into `materials`) and section, from the *SOLID
    /// SECTION cards.
    fn sections_of_elements(&self, materials: &[crate::model::Material]) -> Result<(Vec<usize>, Vec<Section>)> {
        let mut element_material = vec![usize::MAX; self.mesh.elements.len()];
        let mut element_section = self.element_family.clone();
        let axisymmetric = element_section.iter().any(|s| s.is_axisymmetric());
        for (elset, material, thickness, at) in &self.sections {
            let k = materials
                .iter()
                .position(|m| &m.name == material)
                .ok_or_else(|| error_at(at, "SOLID SECTION", format!("material {material} is not defined")))?;
            for &e in &self.element_sets[elset] {
                element_material[e] = k;
                element_section[e] = plane_thickness(element_section[e], *thickness, axisymmetric)
                    .map_err(|m| error_at(at, "SOLID SECTION", format!("element {}: {m}", self.mesh.element_ids[e])))?;
            }
        }
        Ok((element_material, element_section))
    }
}

/// How an element type of the reader's (CAX.., CPE.., CPS.. with 8, 8R, 6, 4, 4R, 3) runs.
fn element_note(kind: &str) -> String {
    let (family, suffix) = kind.split_at(3);
    let (section, volumetric) = match family {
        "CPE" => ("plane-strain", "F-bar"),
        "CPS" => ("plane-stress", "the thickness stretch solved from sigma_33 = 0, no F-bar"),
        _ => ("axisymmetric", "F-bar"),
    };
    match suffix {
        "8" => format!("slideline's 8-node {section} quadrilateral (3 x 3 Gauss points, {volumetric})"),
        "8R" => format!("CalculiX's reduced 8-node {section} quadrilateral: 2 x 2 Gauss points, no F-bar (as ccx; a single element has one zero-energy mode, which its neighbours restrain)"),
        "6" => format!("CalculiX's 6-node {section} triangle: 3 Gauss points, no F-bar (as ccx and Abaqus)"),
        "3" => format!("{section} 6-node triangles with mid-side nodes added at the middle of each straight edge (quadratic displacements, 9 Gauss points, {volumetric})"),
        _ => format!("{section} 8-node quadrilaterals with mid-side nodes added at the middle of each straight edge (quadratic displacements, 3 x 3 Gauss points, {volumetric})"),
    }
}

/// The section of a plane element (`family`) of a *SOLID SECTION with `thickness` (1 when
/// not given), in a deck with axisymmetric elements (`axisymmetric`) or without. Beside
/// axisymmetric elements CalculiX takes the plane element's forces as the whole ring's (as
/// its *CLOAD): measured with ccx 2.20 on its axiplane deck, the ring's hoop stress is that
/// of the slab's force spread over 360 degrees. Per radian the slab is thickness / 2 pi.
fn plane_thickness(family: Section, thickness: Option<f64>, axisymmetric: bool) -> std::result::Result<Section, String> {
    let t = thickness.unwrap_or(1.0);
    let positive = t > 0.0 && t.is_finite();
    if !family.is_axisymmetric() && !positive {
        return Err(format!("the plane element's thickness {t} must be a positive length"));
    }
    let t = if axisymmetric { t / std::f64::consts::TAU } else { t };
    Ok(match family {
        Section::Axisymmetric => Section::Axisymmetric,
        Section::PlaneStrain { .. } => Section::PlaneStrain { thickness: t },
        Section::PlaneStress { .. } => Section::PlaneStress { thickness: t },
    })
}

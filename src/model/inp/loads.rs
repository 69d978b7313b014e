//! The load cards of a step: *CLOAD (nodal forces), *DLOAD (pressures, gravity, spin).

use super::cards::{error_at, Card, DataLine};
use super::steps::replaces_earlier_loads;
use super::{face_side, Builder, Target};
use crate::error::Result;
use crate::model::mesh::Edge;
use crate::model::Component;

impl Builder {
    /// *CLOAD: a force on each node of a node (set), dof 1 (r) or 2 (z), kept per radian.
    /// CalculiX takes an axisymmetric node's force as the whole ring's (measured with ccx 2.20:
    /// a bore's consistent nodal loads given so reproduce the pressure's displacements only
    /// when read as 360-degree totals; its reactions it prints per 2-degree segment).
    pub(super) fn cload(&mut self, card: &Card) -> Result<()> {
        card.only(&["OP", "AMPLITUDE"])?;
        let new = replaces_earlier_loads(card)?;
        let amplitude = self.amplitude_ref(card)?;
        self.step_mut(card)?;
        let mut loads: Vec<Target<(usize, Component)>> = Vec::new();
        for d in &card.data {
            let nodes = self.node_items(d, "CLOAD", 0)?;
            let component = match d.id("CLOAD", 1, "degree of freedom")? {
                1 => Component::R,
                2 => Component::Z,
                dof => return Err(error_at(&d.at, "CLOAD", format!("degree of freedom {dof}: axisymmetric nodes have 1 (r) and 2 (z)"))),
            };
            let value = d.number("CLOAD", 2, "magnitude", None)? / self.ring_measure();
            for node in nodes {
                loads.retain(|l| l.key != (node, component));
                loads.push(Target { key: (node, component), value, amplitude: amplitude.clone() });
            }
        }
        let step = self.step_mut(card)?;
        step.new_cloads |= new;
        for l in loads {
            step.cloads.retain(|c| c.key != l.key);
            step.cloads.push(l);
        }
        Ok(())
    }

    pub(super) fn dload(&mut self, card: &Card) -> Result<()> {
        card.only(&["OP", "AMPLITUDE"])?;
        let new = replaces_earlier_loads(card)?;
        let amplitude = self.amplitude_ref(card)?;
        self.step_mut(card)?;
        let mut loads = Vec::new();
        let mut body = Vec::new();
        let mut masses = Vec::new();
        for d in &card.data {
            let label = d.fields.get(1).map(|s| s.to_uppercase()).unwrap_or_default();
            if (label == "GRAV" || label == "CENTRIF") && self.point_masses.contains_key(&d.fields[0].to_uppercase()) {
                masses.extend(self.point_mass_load(d, &label, amplitude.clone())?);
                continue;
            }
            if label == "GRAV" || label == "CENTRIF" {
                body.push(self.body_load(d, &label, amplitude.clone())?);
                continue;
            }
            let side =
                face_side(&label, 'P').ok_or_else(|| error_at(&d.at, "DLOAD", format!("load type '{label}': slideline reads face pressures P1 to P4")))?;
            let value = d.number("DLOAD", 2, "magnitude", None)?;
            let target = d.fields[0].to_uppercase();
            // as CalculiX's dloads.f: an element (set) first, then an element-face surface,
            // whose own faces are loaded (the label's face number is then not used)
            let is_elements = target.chars().all(|c| c.is_ascii_digit()) || self.element_sets.contains_key(&target);
            let surface = if !is_elements && self.surfaces.contains_key(&target) {
                target
            } else {
                let elements = self.element_items(d, "DLOAD", 0)?;
                if let Some(&e) = elements.iter().find(|&&e| side >= self.mesh.shape(e).corners()) {
                    return Err(error_at(
                        &d.at,
                        "DLOAD",
                        format!("load type '{label}' on element {}: a triangle has faces P1 to P3", self.mesh.element_ids[e]),
                    ));
                }
                // the loaded faces as a surface named after the element set and face
                let surface = format!("DLOAD_{target}_{label}");
                self.surfaces.insert(surface.clone(), elements.into_iter().map(|element| Edge { element, side }).collect());
                surface
            };
            if loads.iter().any(|l: &Target<String>| l.key == surface) {
                return Err(error_at(&d.at, "DLOAD", format!("{surface} is loaded twice in one *DLOAD card: give one pressure per face")));
            }
            loads.push(Target { key: surface, value, amplitude: amplitude.clone() });
        }
        let step = self.step_mut(card)?;
        step.new_loads |= new;
        for l in loads {
            step.pressures.retain(|p| p.key != l.key);
            step.pressures.push(l);
        }
        for l in body {
            step.body.retain(|b| b.key != l.key);
            step.body.push(l);
        }
        for l in masses {
            step.cloads.retain(|c| c.key != l.key);
            step.cloads.push(l);
        }
        Ok(())
    }

    /// GRAV or CENTRIF on a set of point masses: each mass's force m g along the axis or
    /// m omega^2 r outward at its node's initial radius, as a nodal force per radian (the
    /// mass is the whole ring's). It then follows the rules of a *CLOAD.
    fn point_mass_load(&mut self, d: &DataLine, label: &str, amplitude: Option<String>) -> Result<Vec<Target<(usize, Component)>>> {
        let target = d.fields[0].to_uppercase();
        let (nodes, mass) = self.point_masses[&target].clone();
        let mass = mass.ok_or_else(|| error_at(&d.at, "DLOAD", format!("{label} on {target}: its point masses have no *MASS (define it before the step)")))?;
        let (spin, value) = self.body_load_value(d, label)?;
        self.mass_load_at.get_or_insert(d.at.clone());
        Ok(nodes
            .into_iter()
            .map(|n| {
                let (component, force) = if spin { (Component::R, mass * value * self.mesh.coords[n][0]) } else { (Component::Z, mass * value) };
                Target { key: (n, component), value: force / self.ring_measure(), amplitude: amplitude.clone() }
            })
            .collect())
    }

    /// A *DLOAD line of type GRAV (magnitude, direction) or CENTRIF (omega^2, a point of the
    /// axis, its direction), about slideline's axis: CalculiX's axisymmetric y (its x the
    /// radius). Its elements: a set, or one element (as a set of its own).
    fn body_load(&mut self, d: &DataLine, label: &str, amplitude: Option<String>) -> Result<Target<(String, bool)>> {
        let target = d.fields[0].to_uppercase();
        let elements = self.element_items(d, "DLOAD", 0)?;
        let set = if self.element_sets.contains_key(&target) {
            target
        } else {
            let name = format!("DLOAD_{target}");
            self.element_sets.insert(name.clone(), elements);
            name
        };
        let (spin, value) = self.body_load_value(d, label)?;
        Ok(Target { key: (set, spin), value, amplitude })
    }

    /// A GRAV or CENTRIF line's load about slideline's axis: (spin, g along the axis or
    /// omega^2).
    fn body_load_value(&self, d: &DataLine, label: &str) -> Result<(bool, f64)> {
        let magnitude = d.number("DLOAD", 2, "magnitude", None)?;
        let numbers = |from: usize| -> Result<[f64; 3]> {
            Ok([
                d.number("DLOAD", from, "coordinate", Some(0.0))?,
                d.number("DLOAD", from + 1, "coordinate", Some(0.0))?,
                d.number("DLOAD", from + 2, "coordinate", Some(0.0))?,
            ])
        };
        let along_axis = |v: [f64; 3]| -> Option<f64> {
            let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            (length > 0.0 && (v[0].abs() + v[2].abs()) <= 1e-9 * length).then(|| v[1] / length)
        };
        let spin = label == "CENTRIF";
        let value = if spin {
            let (point, direction) = (numbers(3)?, numbers(6)?);
            if point[0] != 0.0 || point[2] != 0.0 || along_axis(direction).is_none() {
                return Err(error_at(&d.at, "DLOAD", "CENTRIF: the rotation axis must be the model's axis (a point with x = z = 0, direction along y)"));
            }
            magnitude
        } else {
            let direction = along_axis(numbers(3)?).ok_or_else(|| error_at(&d.at, "DLOAD", "GRAV: the direction must be along the model's axis (y)"))?;
            magnitude * direction
        };
        Ok((spin, value))
    }
}

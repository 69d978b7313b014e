//! What a restart must find unchanged: a fingerprint of each part of the model (materials,
//! sections, contact, ...) and of each field of each step, written into the results file and
//! compared with the deck a restart reads. The model may not change, nor a step already begun;
//! steps after the restart point may be added or changed (Abaqus's rule for a restart).
//!
//! A fingerprint is the 64-bit FNV-1a hash of the part's `Debug` text: stable across builds
//! (unlike std's hasher), and short enough to keep every field of every step.

use super::{GeneralStep, Model};

/// One fingerprint: what it covers ("materials", "step 2 pressures") and its hash.
pub type Fingerprint = (String, u64);

fn fnv1a(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3))
}

fn print(what: &str, value: &impl std::fmt::Debug) -> Fingerprint {
    (what.to_string(), fnv1a(&format!("{value:?}")))
}

/// The fingerprints of the model's parts that no restart may change.
pub fn model_parts(model: &Model) -> Vec<Fingerprint> {
    vec![
        print("materials", &(&model.materials, &model.element_material)),
        print("sections", &(&model.element_section, &model.element_integration)),
        print("kinematics (nlgeom)", &model.kinematics),
        print("reference temperature", &model.reference_temperature),
        print("contact pairs", &model.contacts),
        print("constraints", &model.constraints),
    ]
}

/// The fingerprints of each field of step `k` (0-based), named "step K field".
pub fn step_fields(k: usize, step: &GeneralStep) -> Vec<Fingerprint> {
    // destructured so that a new field of Step cannot be left out unnoticed
    let GeneralStep {
        name,
        increments,
        displacements,
        pressures,
        nodal_forces,
        temperature,
        time_span,
        body_loads,
        release_constraints,
        without_field_output,
        friction_changes,
    } = step;
    let field = |what: &str, value: &dyn std::fmt::Debug| (format!("step {} {what}", k + 1), fnv1a(&format!("{value:?}")));
    vec![
        field("name", name),
        field("increments", increments),
        field("prescribed displacements", displacements),
        field("pressures", pressures),
        field("nodal forces", nodal_forces),
        field("temperature", temperature),
        field("time period", time_span),
        field("body loads", body_loads),
        field("release of earlier constraints (OP=NEW)", release_constraints),
        field("field output", without_field_output),
        field("friction changes", friction_changes),
    ]
}

/// Every fingerprint of `model` as the text stored in the results file: one "what hex" per line.
pub fn text(model: &Model) -> String {
    let steps = model.general_steps().enumerate().flat_map(|(k, s)| step_fields(k, s));
    model_parts(model).into_iter().chain(steps).map(|(what, h)| format!("{what}\t{h:016x}\n")).collect()
}

/// Compares the deck's model with the fingerprints `stored` (the file's text) up to and with
/// step `step` (0-based, the step of the restart increment): the parts that differ, by name.
pub fn changed(model: &Model, stored: &str, step: usize) -> Vec<String> {
    let stored: std::collections::HashMap<&str, &str> = stored.lines().filter_map(|l| l.split_once('\t')).collect();
    let steps = model.general_steps().enumerate().take(step + 1).flat_map(|(k, s)| step_fields(k, s));
    model_parts(model)
        .into_iter()
        .chain(steps)
        .filter(|(what, h)| stored.get(what.as_str()).is_some_and(|s| *s != format!("{h:016x}")))
        .map(|(what, _)| what)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hash_is_fnv1a() {
        // the published FNV-1a 64 test vectors (Fowler, Noll, Vo): "" and "a"
        assert_eq!(fnv1a(""), 0xcbf29ce484222325);
        assert_eq!(fnv1a("a"), 0xaf63dc4c8601ec8c);
    }
}

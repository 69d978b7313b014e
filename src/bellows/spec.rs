//! The joint, described once: a bellows expansion joint in an expansion-joint data sheet's terms
//! (the bellows' dimensions, its material's properties at the design temperature or tables of
//! them against temperature, the design conditions, the code's choices) and the finite-element
//! joint around it (`[joint]`: the pipes, the guide sleeve, contact, mesh, stepping, output).
//! The code's verdict ([`DesignSpec::verdict`]), the mesher (`bellows::joint`), the analyses
//! and the report all read this one type; the flags and `bellows-sweep --vary` change it by key
//! (`section.key`, [`keys`]). Every key is in docs/bellows-spec.md; an unknown key or an
//! impossible geometry is refused by name.
//!
//! `--spec FILE` reads a specification: the data sheet's keys are required. `--params FILE` and
//! the default run start from the seed paper's joint ([`DesignSpec::seed`]), each key given
//! replacing the seed's.

use crate::assessment::code::{CodeCheck, Duty, Source};
use crate::assessment::coefficients::Coefficients;
use crate::assessment::formulas::UBellows;
use crate::assessment::verdict::{self, Allowables, Conditions, FatigueCurve, Forming, Verdict};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

mod fe_joint;
pub mod forming;
pub mod keys;
mod rules;

pub use rules::off_the_charts;

/// The whole description of a joint.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DesignSpec {
    /// A line naming the joint (the report's title).
    #[serde(default)]
    pub title: String,
    /// The file's text, as read (kept with the results, hashed in the report).
    #[serde(skip)]
    pub text: String,
    pub bellows: BellowsSpec,
    pub material: MaterialSpec,
    pub design: DesignConditions,
    #[serde(default)]
    pub code: CodeChoices,
    #[serde(default)]
    pub joint: JointSpec,
    /// How the bellows is hydroformed (`--form`).
    #[serde(default, skip_serializing_if = "forming::FormingSpec::is_default")]
    pub forming: forming::FormingSpec,
}

/// The bellows' dimensions (mm), as a data sheet gives them.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BellowsSpec {
    /// Db, the inside diameter of the plies on the tangents (the pipes' outside).
    pub inside_diameter: f64,
    /// w, the convolution height: the ply pack's mid-surface from root bottom to crest top.
    pub convolution_height: f64,
    /// q, the pitch.
    pub pitch: f64,
    /// ric and rir, the inside radii of the crest and of the root (the pack's inside surface).
    pub crest_radius: f64,
    pub root_radius: f64,
    /// N, n, t.
    pub convolutions: usize,
    pub plies: usize,
    pub ply_thickness: f64,
    /// Lt, the length of each cylindrical tangent.
    pub tangent_length: f64,
    #[serde(default = "as_formed")]
    pub forming: Forming,
    /// tp, a ply's thickness as formed where it is known (measured on the bellows, or a
    /// forming's): the code's formulas take it for EJMA's t sqrt(Db / Dm); the finite-element
    /// joint keeps t (`--form` forms its own).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub formed_ply_thickness: Option<f64>,
    /// The chart coefficients [Cp, Cf, Cd] read off the code's charts; computed without them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coefficients: Option<[f64; 3]>,
}

fn as_formed() -> Forming {
    Forming::AsFormed
}

/// A material property: one value at the design temperature, or a table of [temperature (degC),
/// value] pairs interpolated linearly at it.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(untagged, expecting = "give a number in slideline's units (MPa, /degC, t/mm^3) or a table of [temperature (degC), value] pairs")]
pub enum Property {
    Value(f64),
    Table(Vec<[f64; 2]>),
}

impl Property {
    /// The value at `temperature`; `key` names the property in an error.
    pub fn at(&self, temperature: f64, key: &str) -> Result<f64> {
        let table = match self {
            Property::Value(v) => return Ok(*v),
            Property::Table(t) => t,
        };
        let bad = |what: String| Error::input(format!("spec: material.{key}: {what}"));
        if table.is_empty() {
            return Err(bad("an empty table: give [[temperature, value], ...]".into()));
        }
        if table.windows(2).any(|w| w[1][0].partial_cmp(&w[0][0]) != Some(std::cmp::Ordering::Greater)) {
            return Err(bad("the table's temperatures must rise from row to row".into()));
        }
        let (first, last) = (table[0][0], table[table.len() - 1][0]);
        if !(first..=last).contains(&temperature) {
            return Err(bad(format!("the design temperature {temperature} degC is outside the table ({first} to {last} degC)")));
        }
        let k = table.windows(2).position(|w| temperature <= w[1][0]).unwrap_or(0);
        let [t0, v0] = table[k];
        let [t1, v1] = *table.get(k + 1).unwrap_or(&table[k]);
        Ok(if t1 > t0 { v0 + (v1 - v0) * (temperature - t0) / (t1 - t0) } else { v0 })
    }
}

/// The bellows material: its name, where its data come from, and its properties at the design
/// temperature (MPa, /degC, t/mm^3).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub name: String,
    #[serde(default)]
    pub source: String,
    /// Eb, at the design temperature.
    pub youngs_modulus: Property,
    /// Eo, at room temperature: the fatigue curve's (Eb when not given).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub room_temperature_modulus: Option<f64>,
    #[serde(default = "poisson")]
    pub poissons_ratio: f64,
    /// Sy, at the design temperature.
    pub yield_stress: Property,
    /// S, the allowable stress at the design temperature: required of a specification (the
    /// seed joint has none, and gets the code check without a verdict).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub allowable_stress: Option<Property>,
    /// The finite-element joint's linear hardening (0: perfectly plastic): with `yield_stress`,
    /// the annealed curve, the tubes' and sleeve's, and the plies' unless they are given as formed.
    #[serde(default)]
    pub hardening_modulus: f64,
    /// The plies as formed (cold-worked), for the finite-element plies: their true stress (MPa)
    /// against plastic strain at the design temperature, `[[0.0, sigma_y], [ep, sigma], ...]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub formed_curve: Option<Vec<[f64; 2]>>,
    /// Or the plies' cold work: the plastic strain forming left in them, the annealed curve
    /// taken on from there (needs a hardening modulus).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cold_work: Option<f64>,
    /// The cyclic stress-strain curve as kinematic hardening (Armstrong-Frederick terms):
    /// `--dba`'s fatigue check runs with it (none: no fatigue check).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub backstresses: Vec<crate::material::Backstress>,
    #[serde(default = "no_expansion")]
    pub thermal_expansion: Property,
    /// The finite-element joint's mass density (default the seed's 8.0e-9 t/mm^3).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<f64>,
}

fn no_expansion() -> Property {
    Property::Value(0.0)
}

fn poisson() -> f64 {
    0.3
}

/// The design conditions: internal pressure (MPa), temperature (degC), the movements (mm,
/// degrees) and the cycles required of them.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DesignConditions {
    pub pressure: f64,
    pub temperature: f64,
    /// The axial movement: one of a compression or an extension (mm, the whole bellows).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial_compression: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axial_extension: Option<f64>,
    #[serde(default)]
    pub lateral: f64,
    #[serde(default)]
    pub angular: f64,
    /// Required of a specification (the seed joint has none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycles: Option<f64>,
}

/// The code's choices: the fatigue curve and its strength reduction factor Kg, the
/// longitudinal weld's factor Cwb, and Km (by the forming when not given); a key left out
/// takes its default.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct CodeChoices {
    pub fatigue_curve: FatigueCurve,
    pub fatigue_factor: f64,
    pub weld_factor: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub meridional_factor: Option<f64>,
}

impl Default for CodeChoices {
    fn default() -> Self {
        CodeChoices { fatigue_curve: FatigueCurve::Asme, fatigue_factor: 1.0, weld_factor: 1.0, meridional_factor: None }
    }
}

/// The finite-element joint around the bellows and its analysis: the pipes the tangents sit on,
/// the guide sleeve, contact and friction, the mesh, the stepping and the output. Every key is
/// optional, its default beside it; unset lengths are the seed joint's scaled with the bellows'
/// inside diameter (the seed's is 320 mm).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tube_thickness: Option<f64>,
    /// Axial length of each pipe (tube A; tube B is as long, at the other end).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tube_length: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sleeve_thickness: Option<f64>,
    /// The sleeve's overlap with tube A (bonded) and tube B (sliding), from the tube ends.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sleeve_overlap: Option<f64>,
    /// The sleeve's entry is crowned: its outside falls by this much (mm) over its last
    /// `sleeve_crown_length`, a parabola tangent to the cylinder (0: a sharp end). A sharp end
    /// presses into tube B's bore between two of its nodes, and the fit's force then alternates
    /// with the end's place between them: with sleeve friction the quick joint's end reaction
    /// zig-zagged by 0.26 % from increment to increment (0.03 % crowned; docs/performance.md).
    #[serde(default = "defaults::sleeve_crown")]
    pub sleeve_crown: f64,
    #[serde(default = "defaults::sleeve_crown_length")]
    pub sleeve_crown_length: f64,
    /// Contact penalty, N/mm^3.
    #[serde(default = "defaults::penalty")]
    pub penalty: f64,
    /// Coulomb friction coefficient between the plies (and of a ply's folds on each other).
    #[serde(default)]
    pub friction_plies: f64,
    /// Coulomb friction coefficient between the sleeve and tube B's bore.
    #[serde(default)]
    pub friction_sleeve: f64,
    /// Tangential penalty of the friction, MPa/mm of elastic slip. Measured on the quick
    /// joint's cycle with mu = 0.2 between the plies (cutbacks, against 4 frictionless): 1e4
    /// (the normal penalty) fails at 98 % of the stroke, 1000 takes 31, 300 takes 17, 100 takes
    /// 15. At 300 the elastic slip at the Coulomb limit, mu p / eps_T, is 0.7 % of the quick
    /// mesh's 2 mm ply elements at p = 10 MPa, about Abaqus' default allowance (0.5 %).
    #[serde(default = "defaults::tangential_penalty")]
    pub tangential_penalty: f64,
    /// Instead of the tangential penalty, the elastic slip (mm) at the Coulomb limit: eps_T =
    /// mu p / elastic_slip.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elastic_slip: Option<f64>,
    /// Increments of the heating step (pressure and temperature) and of the stroke.
    #[serde(default = "defaults::heat_increments")]
    pub heat_increments: usize,
    #[serde(default = "defaults::increments")]
    pub increments: usize,
    /// After the stroke, a further step takes tube B's end back to where it started.
    #[serde(default)]
    pub cycle: bool,
    /// How Newton's convergence is judged.
    #[serde(default)]
    pub convergence: crate::model::Convergence,
    /// Elements through each ply's thickness, and their length along the ply meridian (mm).
    #[serde(default = "defaults::ply_elements")]
    pub ply_elements: usize,
    #[serde(default = "defaults::one")]
    pub ply_element_length: f64,
    /// Elements through the tube and sleeve walls, and their length along them (mm).
    #[serde(default = "defaults::wall_elements")]
    pub wall_elements: usize,
    #[serde(default = "defaults::wall_element_length")]
    pub wall_element_length: f64,
    /// Fields of every N-th increment in the results file (and of the last of each step).
    #[serde(default = "defaults::output_every")]
    pub output_every: usize,
    /// The width of the visualisation fields' floats.
    #[serde(default)]
    pub output_precision: crate::model::Precision,
}

impl Default for JointSpec {
    /// Every key at its default (a specification without `[joint]`).
    fn default() -> Self {
        toml::Table::new().try_into().expect("every [joint] key has a default")
    }
}

/// The defaults of the keys that are not zero, false or none.
mod defaults {
    pub fn sleeve_crown() -> f64 {
        0.2
    }
    pub fn sleeve_crown_length() -> f64 {
        8.0
    }
    pub fn penalty() -> f64 {
        1.0e4
    }
    pub fn tangential_penalty() -> f64 {
        300.0
    }
    pub fn heat_increments() -> usize {
        2
    }
    pub fn increments() -> usize {
        240
    }
    pub fn ply_elements() -> usize {
        2
    }
    pub fn one() -> f64 {
        1.0
    }
    pub fn wall_elements() -> usize {
        3
    }
    pub fn wall_element_length() -> f64 {
        4.0
    }
    pub fn output_every() -> usize {
        1
    }
}

/// The seed paper's joint (DN300, two 1 mm plies of AISI 304 at 200 degC and 6 bar, compressed
/// 70 mm), its keys as a file gives them: every other key at its default.
const SEED_JOINT: &str = r#"
[bellows]
inside_diameter = 320.0
convolution_height = 20.0
pitch = 24.0
crest_radius = 5.0
root_radius = 5.0
convolutions = 6
plies = 2
ply_thickness = 1.0
tangent_length = 20.0

[material]
name = "AISI 304"
source = "the seed paper"
youngs_modulus = 200000.0
yield_stress = 300.0
hardening_modulus = 1000.0
thermal_expansion = 1.875e-5
density = 8.0e-9   # AISI 304: 8.00 g/cm^3 (ASM Handbook)

[design]
pressure = 0.6
temperature = 200.0
axial_compression = 70.0
"#;

impl DesignSpec {
    /// The seed paper's joint: what `slideline bellows` runs, and what `--params` and the flags
    /// change. It has no allowable stress and no cycles: the code check, no verdict.
    pub fn seed() -> Self {
        toml::from_str(SEED_JOINT).expect("the seed joint's keys are a joint (a unit test reads them)")
    }

    /// A design specification (`--spec`): the data sheet's keys required, the code's data
    /// (allowable stress, cycles) among them.
    pub fn from_file(path: &std::path::Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Read { path: path.to_path_buf(), source })?;
        Self::from_text(&text, path)
    }

    /// The specification in `text`, read from `path` (named in errors).
    pub fn from_text(text: &str, path: &std::path::Path) -> Result<Self> {
        let mut spec: DesignSpec = toml::from_str(text).map_err(|e| crate::model::deck::toml_error(path, text, &e, "docs/bellows-spec.md"))?;
        spec.text = text.to_string();
        for (key, missing) in [("material.allowable_stress", spec.material.allowable_stress.is_none()), ("design.cycles", spec.design.cycles.is_none())] {
            if missing {
                return Err(Error::input(format!("spec: {key}: missing: the code's verdict needs it (docs/bellows-spec.md)")));
            }
        }
        spec.validate()?;
        Ok(spec)
    }

    /// A joint file (`--params`): the seed joint with each key the file gives replaced.
    pub fn joint_file(path: &std::path::Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Read { path: path.to_path_buf(), source })?;
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| Error::input(format!("{}: {}", path.display(), e.message())))?;
        keys::over_seed(&table).map_err(|e| Error::input(format!("{}: {e}", path.display())))
    }

    /// The SHA-256 of the specification's text, in hex: what a report names its input by.
    pub fn sha256(&self) -> String {
        use sha2::Digest;
        sha2::Sha256::digest(self.text.as_bytes()).iter().map(|b| format!("{b:02x}")).collect()
    }

    /// Whether the joint has what the code's verdict needs beyond the code check: an allowable
    /// stress and the cycles required.
    pub fn has_design_data(&self) -> bool {
        self.material.allowable_stress.is_some() && self.design.cycles.is_some()
    }

    /// The mid-surface radii of the crest and the root (the inside radii plus half the pack).
    pub fn mid_surface_radii(&self) -> (f64, f64) {
        let half = self.pack_thickness() / 2.0;
        (self.bellows.crest_radius + half, self.bellows.root_radius + half)
    }

    /// Total thickness of the ply pack.
    pub fn pack_thickness(&self) -> f64 {
        self.bellows.plies as f64 * self.bellows.ply_thickness
    }

    /// The bellows as the code's formulas see it: rm the mean of the crest's and root's
    /// mid-surface radii.
    pub fn geometry(&self) -> UBellows {
        let b = &self.bellows;
        let (rc, rr) = self.mid_surface_radii();
        UBellows {
            inside_diameter: b.inside_diameter,
            height: b.convolution_height,
            pitch: b.pitch,
            ply_thickness: b.ply_thickness,
            plies: b.plies,
            convolutions: b.convolutions,
            torus_radius: (rc + rr) / 2.0,
            formed_ply_thickness: b.formed_ply_thickness,
        }
    }

    /// The axial movement, extension positive.
    pub fn axial(&self) -> f64 {
        self.design.axial_extension.unwrap_or(0.0) - self.design.axial_compression.unwrap_or(0.0)
    }

    pub fn conditions(&self) -> Conditions {
        let d = &self.design;
        Conditions { pressure: d.pressure, axial: self.axial(), lateral: d.lateral, angular: d.angular, cycles: d.cycles.unwrap_or(f64::NAN) }
    }

    /// The material's modulus, yield and allowable stresses at the design temperature (the
    /// allowable NaN where the joint has none).
    pub fn at_temperature(&self) -> Result<(f64, f64, f64)> {
        let (m, t) = (&self.material, self.design.temperature);
        let allowable = m.allowable_stress.as_ref().map_or(Ok(f64::NAN), |s| s.at(t, "allowable_stress"))?;
        Ok((m.youngs_modulus.at(t, "youngs_modulus")?, m.yield_stress.at(t, "yield_stress")?, allowable))
    }

    pub fn allowables(&self) -> Result<Allowables> {
        let (modulus, _, allowable_stress) = self.at_temperature()?;
        let c = &self.code;
        Ok(Allowables {
            allowable_stress,
            weld_factor: c.weld_factor,
            meridional_factor: c.meridional_factor.unwrap_or(self.bellows.forming.meridional_factor()),
            fatigue_curve: c.fatigue_curve,
            fatigue_factor: c.fatigue_factor,
            room_modulus: self.material.room_temperature_modulus.unwrap_or(modulus),
        })
    }

    /// The code check for the design pressure and the equivalent axial movement, with the chart
    /// coefficients given or `computed` (called only when none are given).
    pub fn code_check(&self, computed: impl FnOnce(&UBellows) -> Result<Coefficients>) -> Result<CodeCheck> {
        let b = self.geometry();
        let (coefficients, source) = match self.bellows.coefficients {
            Some([cp, cf, cd]) => (Coefficients { cp, cf, cd }, Source::Given),
            None => (computed(&b)?, Source::Computed),
        };
        let (modulus, yield_stress, _) = self.at_temperature()?;
        let stroke = verdict::movement_per_convolution(&b, &self.conditions()) * b.convolutions as f64;
        let duty =
            Duty { pressure: self.design.pressure, stroke, modulus, yield_stress, tangent_length: self.bellows.tangent_length, forming: self.bellows.forming };
        Ok(CodeCheck::new(&b, coefficients, source, duty))
    }

    /// The verdict of `check` (made by [`DesignSpec::code_check`]).
    pub fn verdict(&self, check: &CodeCheck) -> Result<Verdict> {
        let (modulus, _, _) = self.at_temperature()?;
        Ok(verdict::verdict(&self.geometry(), check, &self.conditions(), &self.allowables()?, modulus))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_is_interpolated_and_a_temperature_off_it_named() {
        let t = Property::Table(vec![[20.0, 195_000.0], [100.0, 189_000.0], [200.0, 183_000.0]]);
        assert_eq!(t.at(150.0, "youngs_modulus").unwrap(), 186_000.0);
        assert_eq!(t.at(20.0, "youngs_modulus").unwrap(), 195_000.0);
        assert_eq!(t.at(200.0, "youngs_modulus").unwrap(), 183_000.0);
        let e = t.at(250.0, "youngs_modulus").unwrap_err().to_string();
        assert!(e.contains("material.youngs_modulus") && e.contains("250 degC is outside the table (20 to 200 degC)"), "{e}");
        let e = Property::Table(vec![[100.0, 1.0], [20.0, 2.0]]).at(50.0, "yield_stress").unwrap_err().to_string();
        assert!(e.contains("must rise"), "{e}");
    }
}

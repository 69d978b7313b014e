//! A bellows design specification (`slideline bellows --spec FILE.toml`), in an expansion-joint
//! data sheet's terms: the bellows' dimensions, its material's properties at the design
//! temperature (or tables of them against temperature, interpolated), the design conditions and
//! the code's choices. It gives the code's verdict ([`DesignSpec::verdict`]) and the joint the
//! finite-element analyses run on ([`DesignSpec::joint_params`]). Every key is in
//! docs/bellows-spec.md; an unknown key or an impossible geometry is refused by name.

use super::joint::BellowsParams;
use crate::assessment::code::{CodeCheck, Duty, Source};
use crate::assessment::coefficients::Coefficients;
use crate::assessment::formulas::UBellows;
use crate::assessment::verdict::{self, Allowables, Conditions, FatigueCurve, Forming, Verdict};
use crate::error::{shown, Error, Result};
use serde::Deserialize;

/// The whole specification.
#[derive(Clone, Debug, Deserialize)]
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
}

/// The bellows' dimensions (mm), as a data sheet gives them.
#[derive(Clone, Debug, Deserialize)]
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
    /// The chart coefficients [Cp, Cf, Cd] read off the code's charts; computed without them.
    #[serde(default)]
    pub coefficients: Option<[f64; 3]>,
}

fn as_formed() -> Forming {
    Forming::AsFormed
}

/// A material property: one value at the design temperature, or a table of [temperature (degC),
/// value] pairs interpolated linearly at it.
#[derive(Clone, Debug, Deserialize)]
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
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub name: String,
    #[serde(default)]
    pub source: String,
    /// Eb, at the design temperature.
    pub youngs_modulus: Property,
    /// Eo, at room temperature: the fatigue curve's (Eb when not given).
    #[serde(default)]
    pub room_temperature_modulus: Option<f64>,
    #[serde(default = "poisson")]
    pub poissons_ratio: f64,
    /// Sy, at the design temperature.
    pub yield_stress: Property,
    /// S, the allowable stress at the design temperature.
    pub allowable_stress: Property,
    /// The finite-element plies' linear hardening (0: perfectly plastic).
    #[serde(default)]
    pub hardening_modulus: f64,
    /// The cyclic stress-strain curve as kinematic hardening (Armstrong-Frederick terms):
    /// `--dba`'s fatigue check runs with it (none: no fatigue check).
    #[serde(default)]
    pub backstresses: Vec<crate::material::Backstress>,
    #[serde(default = "no_expansion")]
    pub thermal_expansion: Property,
    #[serde(default)]
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
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignConditions {
    pub pressure: f64,
    pub temperature: f64,
    /// The axial movement: one of a compression or an extension (mm, the whole bellows).
    #[serde(default)]
    pub axial_compression: Option<f64>,
    #[serde(default)]
    pub axial_extension: Option<f64>,
    #[serde(default)]
    pub lateral: f64,
    #[serde(default)]
    pub angular: f64,
    pub cycles: f64,
}

/// The code's choices: the fatigue curve and its strength reduction factor Kg, the
/// longitudinal weld's factor Cwb, and Km (by the forming when not given); a key left out
/// takes its default.
#[derive(Clone, Debug, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CodeChoices {
    pub fatigue_curve: FatigueCurve,
    pub fatigue_factor: f64,
    pub weld_factor: f64,
    pub meridional_factor: Option<f64>,
}

impl Default for CodeChoices {
    fn default() -> Self {
        CodeChoices { fatigue_curve: FatigueCurve::Asme, fatigue_factor: 1.0, weld_factor: 1.0, meridional_factor: None }
    }
}

/// The finite-element joint around the bellows: the pipes the tangents sit on, the guide sleeve
/// and the analysis' mesh and stepping. Unset values are the seed joint's, lengths scaled with
/// the bellows' inside diameter (the seed's is 320 mm).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointSpec {
    pub tube_thickness: Option<f64>,
    pub tube_length: Option<f64>,
    pub sleeve_thickness: Option<f64>,
    pub sleeve_overlap: Option<f64>,
    pub increments: Option<usize>,
    pub penalty: Option<f64>,
}

impl DesignSpec {
    pub fn from_file(path: &std::path::Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Read { path: path.to_path_buf(), source })?;
        Self::from_text(&text, path)
    }

    /// The specification in `text`, read from `path` (named in errors).
    pub fn from_text(text: &str, path: &std::path::Path) -> Result<Self> {
        let mut spec: DesignSpec = toml::from_str(text).map_err(|e| crate::model::deck::toml_error(path, text, &e, "docs/bellows-spec.md"))?;
        spec.text = text.to_string();
        spec.validate()?;
        Ok(spec)
    }

    /// The SHA-256 of the specification's text, in hex: what a report names its input by.
    pub fn sha256(&self) -> String {
        use sha2::Digest;
        sha2::Sha256::digest(self.text.as_bytes()).iter().map(|b| format!("{b:02x}")).collect()
    }

    /// The mid-surface radii of the crest and the root (the inside radii plus half the pack).
    pub fn mid_surface_radii(&self) -> (f64, f64) {
        let half = self.bellows.plies as f64 * self.bellows.ply_thickness / 2.0;
        (self.bellows.crest_radius + half, self.bellows.root_radius + half)
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
        }
    }

    /// The axial movement, extension positive.
    pub fn axial(&self) -> f64 {
        self.design.axial_extension.unwrap_or(0.0) - self.design.axial_compression.unwrap_or(0.0)
    }

    pub fn conditions(&self) -> Conditions {
        let d = &self.design;
        Conditions { pressure: d.pressure, axial: self.axial(), lateral: d.lateral, angular: d.angular, cycles: d.cycles }
    }

    /// The material's modulus, yield and allowable stresses at the design temperature.
    pub fn at_temperature(&self) -> Result<(f64, f64, f64)> {
        let (m, t) = (&self.material, self.design.temperature);
        Ok((m.youngs_modulus.at(t, "youngs_modulus")?, m.yield_stress.at(t, "yield_stress")?, m.allowable_stress.at(t, "allowable_stress")?))
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

    /// Checks what the file says can be a bellows and a design: each value named with its rule.
    pub fn validate(&self) -> Result<()> {
        let b = &self.bellows;
        let bad = |key: &str, rule: String| Err(Error::input(format!("spec: {key}: {rule}")));
        let positive = [
            ("bellows.inside_diameter", b.inside_diameter),
            ("bellows.convolution_height", b.convolution_height),
            ("bellows.pitch", b.pitch),
            ("bellows.crest_radius", b.crest_radius),
            ("bellows.root_radius", b.root_radius),
            ("bellows.ply_thickness", b.ply_thickness),
            ("design.cycles", self.design.cycles),
            ("code.fatigue_factor", self.code.fatigue_factor),
            ("code.weld_factor", self.code.weld_factor),
        ];
        for (key, v) in positive.into_iter().chain(self.code.meridional_factor.map(|k| ("code.meridional_factor", k))) {
            if !(v > 0.0 && v.is_finite()) {
                return bad(key, format!("must be > 0, got {}", shown(v)));
            }
        }
        for (key, v) in [("bellows.tangent_length", b.tangent_length), ("design.lateral", self.design.lateral), ("design.angular", self.design.angular)] {
            if !(v >= 0.0 && v.is_finite()) {
                return bad(key, format!("must be >= 0, got {}", shown(v)));
            }
        }
        for (key, n) in [("bellows.convolutions", b.convolutions), ("bellows.plies", b.plies)] {
            if n == 0 {
                return bad(key, "must be at least 1".into());
            }
        }
        if let Some(rule) = b.coefficients.and_then(|c| super::joint::off_the_charts(&c)) {
            return bad("bellows.coefficients", rule);
        }
        // the movements the joint can take at all (as the --lateral and --angular flags): no
        // more than its convolved length sideways or axially, 45 degrees of rotation
        let length = b.convolutions as f64 * b.pitch;
        let movements = [
            ("design.lateral", self.design.lateral, length, "mm, the convolved length N q"),
            ("design.axial_compression", self.design.axial_compression.unwrap_or(0.0), length, "mm, the convolved length N q"),
            ("design.axial_extension", self.design.axial_extension.unwrap_or(0.0), length, "mm, the convolved length N q"),
            ("design.angular", self.design.angular, 45.0, "degrees"),
        ];
        for (key, v, most, what) in movements {
            if v.abs() > most {
                return bad(key, format!("{} is more than the joint can take: give at most {} {what}", shown(v), shown(most)));
            }
        }
        if !(self.design.pressure >= 0.0 && self.design.pressure.is_finite()) {
            return bad(
                "design.pressure",
                format!("{}: give the internal design pressure, >= 0 MPa (external pressure is not checked yet)", self.design.pressure),
            );
        }
        if !self.design.temperature.is_finite() {
            return bad("design.temperature", "must be a finite number (degC)".into());
        }
        match (self.design.axial_compression, self.design.axial_extension) {
            (Some(_), Some(_)) => return bad("design.axial_compression", "give one of axial_compression and axial_extension".into()),
            (Some(x), None) if !(x >= 0.0 && x.is_finite()) => {
                return bad("design.axial_compression", format!("a movement is given by its size, >= 0 mm; got {}", shown(x)))
            }
            (None, Some(x)) if !(x >= 0.0 && x.is_finite()) => {
                return bad("design.axial_extension", format!("a movement is given by its size, >= 0 mm; got {}", shown(x)))
            }
            _ => {}
        }
        let pack = b.plies as f64 * b.ply_thickness;
        let (rc, rr) = self.mid_surface_radii();
        // the U shape: two half tori and the sidewalls between them fit in the height and the pitch
        if rc + rr + pack > b.convolution_height {
            return bad(
                "bellows.convolution_height",
                format!(
                    "w = {} mm is less than the crest's and root's mid-surface radii and the ply pack ({} + {} + {} mm): the tori overlap",
                    shown(b.convolution_height),
                    shown(rc),
                    shown(rr),
                    shown(pack)
                ),
            );
        }
        if b.pitch < 2.0 * (rc + rr) - 1e-9 {
            return bad(
                "bellows.pitch",
                format!(
                    "q = {} mm is less than 2 (rc + rr) = {} mm (mid-surface radii): neighbouring convolutions overlap",
                    shown(b.pitch),
                    shown(2.0 * (rc + rr))
                ),
            );
        }
        if b.inside_diameter <= 2.0 * pack {
            return bad("bellows.inside_diameter", format!("Db = {} mm leaves no bore inside the ply pack", b.inside_diameter));
        }
        let (modulus, yield_stress, allowable) = self.at_temperature()?;
        for (key, v) in [("material.youngs_modulus", modulus), ("material.yield_stress", yield_stress), ("material.allowable_stress", allowable)] {
            if !(v > 0.0 && v.is_finite()) {
                return bad(key, format!("must be > 0 MPa at the design temperature, got {}", shown(v)));
            }
        }
        if !(self.material.poissons_ratio > -1.0 && self.material.poissons_ratio < 0.5) {
            return bad("material.poissons_ratio", format!("must lie in (-1, 0.5), got {}", self.material.poissons_ratio));
        }
        Ok(())
    }

    /// The finite-element joint of this specification: the bellows on pipes of the seed joint's
    /// proportions (scaled with Db, or as `[joint]` gives them), the design pressure and
    /// temperature, the axial movement as the stroke.
    pub fn joint_params(&self) -> Result<BellowsParams> {
        let b = &self.bellows;
        let (rc, rr) = self.mid_surface_radii();
        let (modulus, yield_stress, _) = self.at_temperature()?;
        let seed = BellowsParams::default();
        // the joint's other lengths scale with the seed's bellows inside diameter
        let scale = b.inside_diameter / (2.0 * seed.tube_outer_radius());
        let j = &self.joint;
        let tube_thickness = j.tube_thickness.unwrap_or(seed.tube_thickness * scale);
        let tube_length = j.tube_length.unwrap_or((seed.tube_length * scale).max(b.tangent_length + seed.sleeve_overlap * scale));
        let convolved = b.convolutions as f64 * b.pitch;
        let mut p = BellowsParams {
            tube_inner_radius: b.inside_diameter / 2.0 - tube_thickness,
            tube_thickness,
            tube_length,
            length: 2.0 * tube_length + convolved,
            convolutions: b.convolutions,
            pitch: b.pitch,
            height: b.convolution_height,
            torus_radius: rr,
            crest_radius: (rc != rr).then_some(rc),
            plies: b.plies,
            ply_thickness: b.ply_thickness,
            tangent_length: b.tangent_length,
            sleeve_thickness: j.sleeve_thickness.unwrap_or(seed.sleeve_thickness * scale),
            sleeve_overlap: j.sleeve_overlap.unwrap_or(seed.sleeve_overlap * scale),
            youngs_modulus: modulus,
            poissons_ratio: self.material.poissons_ratio,
            thermal_expansion: self.material.thermal_expansion.at(self.design.temperature, "thermal_expansion")?,
            yield_stress,
            hardening_modulus: self.material.hardening_modulus,
            density: self.material.density.unwrap_or(seed.density),
            temperature: self.design.temperature,
            pressure: self.design.pressure,
            displacement: -self.axial(),
            coefficients: b.coefficients,
            ..seed
        };
        if let Some(n) = j.increments {
            p.increments = n;
        }
        if let Some(k) = j.penalty {
            p.penalty = k;
        }
        p.validate().map_err(|e| Error::input(format!("spec: the finite-element joint: {e}")))?;
        Ok(p)
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

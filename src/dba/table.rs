//! A deck's `[design_by_analysis]` table: the checks of ASME VIII-2 Part 5 to run on its
//! model and the data they need beside the model's (docs/design-by-analysis.md).

use crate::error::{Error, Result};
use crate::model::Model;
use serde::Deserialize;
use std::collections::BTreeMap;

/// What `slideline check` runs on a deck.
#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct DbaTable {
    /// The allowable (design) stress S, MPa: one value for every material, or a table by
    /// material name. The limit-load check needs it.
    pub allowable_stress: Option<Allowable>,
    pub limit_load: Option<LimitLoadTable>,
    pub ratcheting: Option<RatchetingTable>,
    #[serde(default)]
    pub buckling: Option<BucklingTable>,
    pub fatigue: Option<FatigueTable>,
}

/// Fatigue by elastic-plastic analysis (VIII-2 5.5.4): the cycle's effective strain range
/// and the permissible cycles from the fatigue curve.
#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FatigueTable {
    /// The deck's steps that make one cycle of the loads: its last general steps, in order.
    pub cycle: Vec<String>,
    /// How many cycles are run; the last is evaluated (at least two: the first from the
    /// virgin state is no stabilised cycle).
    #[serde(default = "three")]
    pub cycles: usize,
    /// The cycles the design must endure, n: the damage is n / N.
    pub design_cycles: f64,
    /// The fatigue curve as [[cycles, S_a MPa], ...] at `curve_modulus` (default: the
    /// built-in curve of austenitic steels).
    pub curve: Option<Vec<[f64; 2]>>,
    /// E_FC, MPa: the modulus the curve's stresses belong to (with `curve`).
    pub curve_modulus: Option<f64>,
}

impl FatigueTable {
    /// The fatigue curve the check reads.
    pub fn curve(&self) -> Result<super::fatigue_curve::FatigueCurve> {
        let bad = |m: String| Error::input(format!("[design_by_analysis] fatigue.curve: {m}"));
        match (&self.curve, self.curve_modulus) {
            (None, None) => Ok(super::fatigue_curve::FatigueCurve::austenitic()),
            (Some(points), Some(modulus)) => super::fatigue_curve::FatigueCurve::table(points.iter().map(|p| (p[0], p[1])).collect(), modulus).map_err(bad),
            (Some(_), None) => Err(bad("a curve needs curve_modulus (E_FC, MPa: the modulus its stresses belong to)".into())),
            (None, Some(_)) => Err(bad("curve_modulus belongs to a curve: give curve = [[cycles, S_a], ...] too".into())),
        }
    }
}

/// Protection against collapse from buckling, type 1 (VIII-2 5.4.1.3(a)): the deck's buckle
/// steps about an elastic prestress of the design pressures.
#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BucklingTable {
    /// beta_cr, the capacity reduction factor of the shell's geometry and loading; the design
    /// factor is 2 / beta_cr.
    pub beta_cr: f64,
}

#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(untagged, expecting = "give a stress in MPa (a number) or a table of them by material name (`{ steel = 137.0 }`)")]
pub enum Allowable {
    Every(f64),
    ByMaterial(BTreeMap<String, f64>),
}

/// Protection against plastic collapse by the limit-load method (VIII-2 5.2.3).
#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct LimitLoadTable {
    /// The factor on the primary loads (Table 5.3: 1.5 on P + Ps + D).
    #[serde(default = "limit_load_factor")]
    pub factor: f64,
    /// Past the factor, the loads are raised to this multiple of the design loads to find the
    /// collapse load factor (the check's figure when it lies below).
    #[serde(default = "search_to")]
    pub search_to: f64,
    /// Increments of that search (each cut back down to the deck's min_increment).
    #[serde(default = "search_increments")]
    pub search_increments: usize,
    /// The search's time budget, s (none: until Newton fails at the smallest increment): past
    /// it the search stops after its increment under way, the figure "collapse above" the
    /// factor reached. The check's verdict is known before the search starts.
    #[serde(default)]
    pub search_seconds: Option<f64>,
    /// The general steps the analysis keeps, in the deck's order (default: every one): those
    /// that carry the primary loads, without a stroke that is a secondary load.
    pub steps: Option<Vec<String>>,
}

/// Protection against ratcheting by elastic-plastic analysis (VIII-2 5.5.7).
#[derive(Deserialize, Debug, Clone, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RatchetingTable {
    /// The deck's steps that make one cycle of the loads: its last general steps, in order.
    pub cycle: Vec<String>,
    /// How many cycles are run (Part 5: at least three).
    #[serde(default = "three")]
    pub cycles: usize,
    /// The primary-load-bearing section, `[[r1, z1], [r2, z2]]` through the wall, where an
    /// elastic core is looked for (criterion b); without it that criterion is not evaluated.
    pub section: Option<[[f64; 2]; 2]>,
}

fn limit_load_factor() -> f64 {
    1.5
}
fn search_to() -> f64 {
    4.0
}
fn search_increments() -> usize {
    40
}
fn three() -> usize {
    3
}

/// The least number of cycles a ratcheting check runs (VIII-2 5.5.7.2: at least three).
pub const LEAST_CYCLES: usize = 3;

impl DbaTable {
    /// The `[design_by_analysis]` table of the TOML deck the model was read from; None when
    /// it has none (or the model came from an .inp deck).
    pub fn of_model(model: &Model) -> Result<Option<Self>> {
        let Ok(table) = model.source_text.parse::<toml::Table>() else { return Ok(None) };
        let Some(value) = table.get("design_by_analysis") else { return Ok(None) };
        let spec: DbaTable = value.clone().try_into().map_err(|e: toml::de::Error| Error::input(format!("[design_by_analysis]: {}", e.message())))?;
        spec.validate(model)?;
        Ok(Some(spec))
    }

    /// Checks every value against the model; names the offending key.
    pub fn validate(&self, model: &Model) -> Result<()> {
        let bad = |m: String| Err(Error::input(format!("[design_by_analysis] {m}")));
        if self.limit_load.is_none() && self.ratcheting.is_none() && self.buckling.is_none() && self.fatigue.is_none() {
            return bad("names no check: give limit_load, ratcheting, buckling or fatigue".into());
        }
        if let Some(f) = &self.fatigue {
            if f.cycles < 2 {
                return bad(format!(
                    "fatigue.cycles must be at least 2 (the last cycle is evaluated, the first starts from the virgin state), got {}",
                    f.cycles
                ));
            }
            if !(f.design_cycles > 0.0 && f.design_cycles.is_finite()) {
                return bad(format!("fatigue.design_cycles must be a number of cycles > 0, got {}", f.design_cycles));
            }
            let general: Vec<&str> = model.general_steps().map(|s| s.name.as_str()).collect();
            let cycle: Vec<&str> = f.cycle.iter().map(String::as_str).collect();
            if cycle.is_empty() || !general.ends_with(&cycle) {
                return bad(format!("fatigue.cycle {:?} must name the deck's last general steps in order (they are {:?})", f.cycle, general));
            }
            f.curve()?;
        }
        if let Some(b) = &self.buckling {
            if !(b.beta_cr > 0.0 && b.beta_cr <= 1.0) {
                return bad(format!("buckling.beta_cr must be a capacity reduction factor in (0, 1], got {}", b.beta_cr));
            }
        }
        if let Some(l) = &self.limit_load {
            if !(l.factor > 0.0 && l.factor.is_finite()) {
                return bad(format!("limit_load.factor must be a load factor > 0, got {}", l.factor));
            }
            if !(l.search_to > l.factor && l.search_to.is_finite()) {
                return bad(format!("limit_load.search_to must exceed the factor {}, got {}", l.factor, l.search_to));
            }
            if l.search_increments == 0 {
                return bad("limit_load.search_increments must be at least 1".into());
            }
            if let Some(t) = l.search_seconds.filter(|t| !(*t > 0.0 && t.is_finite())) {
                return bad(format!("limit_load.search_seconds must be > 0 s, got {t}"));
            }
            if let Some(steps) = &l.steps {
                let general: Vec<&str> = model.general_steps().map(|s| s.name.as_str()).collect();
                if let Some(unknown) = steps.iter().find(|s| !general.contains(&s.as_str())) {
                    return bad(format!("limit_load.steps: '{unknown}' is not one of the deck's general steps {general:?}"));
                }
                if steps.is_empty() {
                    return bad("limit_load.steps is empty: name the steps that carry the primary loads".into());
                }
            }
            for m in &model.materials {
                self.allowable(&m.name)?;
            }
        }
        if let Some(r) = &self.ratcheting {
            if r.cycles < LEAST_CYCLES {
                return bad(format!("ratcheting.cycles must be at least {LEAST_CYCLES} (VIII-2 5.5.7.2), got {}", r.cycles));
            }
            let general: Vec<&str> = model.general_steps().map(|s| s.name.as_str()).collect();
            let cycle: Vec<&str> = r.cycle.iter().map(String::as_str).collect();
            if cycle.is_empty() || !general.ends_with(&cycle) {
                return bad(format!("ratcheting.cycle {:?} must name the deck's last general steps in order (they are {:?})", r.cycle, general));
            }
            if let Some(m) = model.materials.iter().find(|m| m.plasticity.is_none()) {
                return bad(format!("ratcheting: material '{}' has no yield stress (model = \"j2\"): the check is elastic-perfectly plastic at it", m.name));
            }
            if let Some(s) = r.section {
                if s.iter().flatten().any(|v| !v.is_finite()) || s[0] == s[1] {
                    return bad(format!("ratcheting.section {s:?} must be two distinct points"));
                }
            }
        }
        Ok(())
    }

    /// The allowable stress S of material `name`, MPa.
    pub fn allowable(&self, name: &str) -> Result<f64> {
        let s = match &self.allowable_stress {
            None => return Err(Error::input("[design_by_analysis] limit_load needs allowable_stress (S, MPa; one value or a table by material)")),
            Some(Allowable::Every(s)) => *s,
            Some(Allowable::ByMaterial(t)) => {
                *t.get(name).ok_or_else(|| Error::input(format!("[design_by_analysis] allowable_stress gives no value for material '{name}'")))?
            }
        };
        if !(s > 0.0 && s.is_finite()) {
            return Err(Error::input(format!("[design_by_analysis] allowable_stress of material '{name}' must be > 0 MPa, got {s}")));
        }
        Ok(s)
    }
}

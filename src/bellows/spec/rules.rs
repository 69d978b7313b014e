//! The data sheet's rules: what a joint must be to be a bellows and a design, each value
//! named with its rule (the finite-element joint's own rules are in `fe_joint`).

use super::DesignSpec;
use crate::error::{shown, Error, Result};

impl DesignSpec {
    /// Checks that the joint can be a bellows and a design, each value named with its rule: the
    /// data sheet's rules, then the finite-element joint's.
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
            ("code.fatigue_factor", self.code.fatigue_factor),
            ("code.weld_factor", self.code.weld_factor),
        ];
        let optional = self.code.meridional_factor.map(|k| ("code.meridional_factor", k)).into_iter().chain(self.design.cycles.map(|n| ("design.cycles", n)));
        for (key, v) in positive.into_iter().chain(optional) {
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
        if let Some(tp) = b.formed_ply_thickness {
            if !(tp > 0.0 && tp <= b.ply_thickness) {
                return bad(
                    "bellows.formed_ply_thickness",
                    format!("tp = {} mm: a ply thins as it is formed: give 0 < tp <= t = {} mm", shown(tp), shown(b.ply_thickness)),
                );
            }
        }
        if let Some(rule) = b.coefficients.and_then(|c| off_the_charts(&c)) {
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
        let allowable = self.material.allowable_stress.as_ref().map(|_| ("material.allowable_stress", allowable));
        for (key, v) in [("material.youngs_modulus", modulus), ("material.yield_stress", yield_stress)].into_iter().chain(allowable) {
            if !(v > 0.0 && v.is_finite()) {
                return bad(key, format!("must be > 0 MPa at the design temperature, got {}", shown(v)));
            }
        }
        if !(self.material.poissons_ratio > -1.0 && self.material.poissons_ratio < 0.5) {
            return bad("material.poissons_ratio", format!("must lie in (-1, 0.5), got {}", self.material.poissons_ratio));
        }
        self.validate_joint().map_err(|e| Error::input(format!("spec: the finite-element joint: {e}")))
    }
}

/// What is wrong with chart coefficients [Cp, Cf, Cd] off the codes' charts, whose
/// coefficients lie between about 0.3 and 3 (for the flags and the specification alike).
pub fn off_the_charts(c: &[f64; 3]) -> Option<String> {
    let (name, v) = [("Cp", c[0]), ("Cf", c[1]), ("Cd", c[2])].into_iter().find(|(_, v)| !(0.1..=10.0).contains(v))?;
    Some(format!(
        "coefficient {name} {} is off the codes' charts: give 0.1 to 10 (the charts' coefficients lie between about 0.3 and 3)",
        crate::error::shown(v)
    ))
}

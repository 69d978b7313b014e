//! The `[forming]` table: how the bellows is hydroformed from a straight tube of nested plies
//! (`bellows --form`, `bellows::forming`). Every key has a default that follows from the
//! target convolution; the defaults and the rules that refuse a forming by name live here.

use super::DesignSpec;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The forming pressure, by default, as a share of the pressure that yields the straight pack
/// in hoop (sigma_y n t / r): past it, so that plastic bulges seat the dies before they move
/// (at 0.6 the tube slid under the dies and one convolution took the whole closing; measured
/// on the seed joint, docs/bellows.md "Forming"), and held while the dies close.
pub const PRESSURE_SHARE: f64 = 1.1;

/// The developed length, by default, over the target's mid-surface meridian: the formed
/// sidewalls are not straight, and take more tube than the idealised U (on the seed joint the
/// meridian's 53.70 mm formed w 18.78 mm for 20; 56.10 mm formed 20.03).
pub const DEVELOPED_ALLOWANCE: f64 = 1.045;

/// How much closer than the pitch the dies close, by default, as a share of the pitch: the
/// formed convolutions spring open once the dies are out (on the seed joint closed to 24.00
/// mm they sprang to 25.13; closed to 22.90, to 23.82).
pub const OVERCLOSE_SHARE: f64 = 0.046;

/// The contact penalty of the forming, MPa/mm, by default: the plies on each other and on the
/// dies (a tenth of the joint's: on the seed joint it closed the dies in 0.56 of the time
/// 1e4 took, the penetration at most 0.1 mm while the dies press the sidewalls and 0.004 mm
/// once they are out).
pub const PENALTY: f64 = 1.0e3;

/// The room temperature at which the bellows is formed, degC (the material's tables are read
/// there).
pub const FORMING_TEMPERATURE: f64 = 20.0;

/// The plastic strain up to which a Swift curve is tabulated: past any forming's.
const SWIFT_TO: f64 = 2.0;

/// How a bellows is formed: every key optional.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FormingSpec {
    /// The forming pressure (MPa) held inside the tube while the dies close.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pressure: Option<f64>,
    /// The pressure (MPa) that first bulges the tube between the dies, so that they hold it
    /// as they close; default the forming pressure.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bulge_pressure: Option<f64>,
    /// The tube's developed length per convolution (mm): the length of straight tube the dies
    /// start apart; default the target convolution's mid-surface meridian.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub developed_length: Option<f64>,
    /// How much closer than the pitch the dies close (mm per convolution), for the springback
    /// that opens the formed convolutions again.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overclose: Option<f64>,
    /// The contact penalty (MPa/mm) of the plies on each other and on the dies (default
    /// [`PENALTY`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penalty: Option<f64>,
    /// Coulomb friction between the plies and on the dies (default none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub friction: Option<f64>,
    /// The annealed tube's true stress (MPa) against plastic strain at room temperature,
    /// `[[0.0, sigma_y], [ep, sigma], ...]`; default the `[material]`'s yield stress and
    /// hardening modulus (at 20 degC where they are tables).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curve: Option<Vec<[f64; 2]>>,
    /// Or Swift's law, sigma = K (e0 + ep)^n: `[K (MPa), e0, n]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub swift: Option<[f64; 3]>,
    /// Increments of the dies' closing (default 300).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub increments: Option<usize>,
}

impl FormingSpec {
    /// Whether no key is given (the table is then left out of the joint's text).
    pub fn is_default(&self) -> bool {
        *self == FormingSpec::default()
    }
}

fn bad(key: &str, why: String) -> Error {
    Error::input(format!("bellows --form: forming.{key}: {why}"))
}

impl DesignSpec {
    /// The plies' elastic modulus as formed and in the formed bellows' service: at the
    /// forming's temperature (MPa).
    pub fn forming_modulus(&self) -> Result<f64> {
        self.material.youngs_modulus.at(FORMING_TEMPERATURE, "youngs_modulus")
    }

    /// The annealed tube's hardening at room temperature: the forming's curve, Swift's law
    /// tabulated, or the `[material]`'s linear curve.
    pub fn forming_curve(&self) -> Result<crate::model::Plasticity> {
        let f = &self.forming;
        match (&f.curve, f.swift) {
            (Some(_), Some(_)) => Err(bad("swift", "give one of curve and swift".into())),
            (Some(curve), None) => {
                let points: Vec<(f64, f64)> = curve.iter().map(|&[ep, s]| (ep, s)).collect();
                crate::model::Plasticity::table(&points).map_err(|why| bad("curve", why))
            }
            (None, Some([k, e0, n])) => {
                if !(k > 0.0 && e0 > 0.0 && n > 0.0 && n < 1.0 && k.is_finite() && e0.is_finite()) {
                    return Err(bad("swift", format!("[K, e0, n] with K > 0 MPa, e0 > 0 and 0 < n < 1; got [{k}, {e0}, {n}]")));
                }
                // a geometric table: fine where the curve bends, to two strains
                let points: Vec<(f64, f64)> = std::iter::once(0.0)
                    .chain((0..=30).map(|i| 1e-4 * (SWIFT_TO / 1e-4_f64).powf(i as f64 / 30.0)))
                    .map(|ep| (ep, k * (e0 + ep).powf(n)))
                    .collect();
                crate::model::Plasticity::table(&points).map_err(|why| bad("swift", why))
            }
            (None, None) => {
                let sy = self.material.yield_stress.at(FORMING_TEMPERATURE, "yield_stress")?;
                Ok(crate::model::Plasticity::linear(sy, self.material.hardening_modulus))
            }
        }
    }

    /// The target convolution's mid-surface meridian length: one convolution from root bottom
    /// to root bottom.
    pub fn convolution_meridian(&self) -> f64 {
        let (rc, rr) = (self.crest(), self.torus_radius());
        // the tilt psi of the sidewalls' normal from the axis, as the mesher's mid-surface takes
        // it (0 radial, negative leaning open): each torus turns through pi + 2 psi
        let half = self.bellows.pitch / 2.0;
        let d = self.sidewall().hypot(half);
        let psi = self.sidewall().atan2(half) - ((rr + rc) / d).min(1.0).acos();
        2.0 * self.sidewall_length() + (rc + rr) * (std::f64::consts::PI + 2.0 * psi)
    }

    /// The forming pressure, MPa: given, or [`PRESSURE_SHARE`] of the pressure that yields the
    /// straight pack in hoop.
    pub fn forming_pressure(&self) -> Result<f64> {
        let yield_stress = self.forming_curve()?.initial_yield_stress();
        let r = self.tube_outer_radius() + self.pack_thickness() / 2.0;
        Ok(self.forming.pressure.unwrap_or(PRESSURE_SHARE * yield_stress * self.pack_thickness() / r))
    }

    /// The bulging pressure, MPa: given, or the forming pressure.
    pub fn bulge_pressure(&self) -> Result<f64> {
        self.forming.bulge_pressure.map_or_else(|| self.forming_pressure(), Ok)
    }

    pub fn forming_penalty(&self) -> f64 {
        self.forming.penalty.unwrap_or(PENALTY)
    }

    pub fn developed_length(&self) -> f64 {
        self.forming.developed_length.unwrap_or_else(|| DEVELOPED_ALLOWANCE * self.convolution_meridian())
    }

    pub fn overclose(&self) -> f64 {
        self.forming.overclose.unwrap_or(OVERCLOSE_SHARE * self.bellows.pitch)
    }

    /// The closing's increments: given, or 300 (asked in 120 the seed's closing, quick mesh, cut
    /// back 127 times and took 7500 Newton iterations with the failed ones; asked in 300, 59
    /// times and 5600).
    pub fn forming_increments(&self) -> usize {
        self.forming.increments.unwrap_or(300)
    }

    /// The forming's rules: a positive pressure, dies that can reach the pitch, a tube long
    /// enough to make the convolution; each refused naming its key.
    pub fn validate_forming(&self) -> Result<()> {
        self.validate_joint()?;
        let f = &self.forming;
        let p = self.forming_pressure()?;
        if !(p > 0.0 && p.is_finite()) {
            return Err(bad("pressure", format!("{} MPa: give a forming pressure > 0", crate::error::shown(p))));
        }
        let burst = 2.0 * self.forming_curve()?.initial_yield_stress() * self.pack_thickness() / self.tube_outer_radius();
        if p >= burst {
            return Err(bad(
                "pressure",
                format!(
                    "{p} MPa would bulge the tube freely between the dies, past twice the pressure that yields it in hoop (2 sigma_y n t / r = {burst:.3} MPa)"
                ),
            ));
        }
        if let Some(mu) = f.friction.filter(|mu| !(mu.is_finite() && *mu >= 0.0)) {
            return Err(bad("friction", format!("{mu}: give mu >= 0")));
        }
        if let Some(k) = f.penalty.filter(|k| !(k.is_finite() && *k > 0.0)) {
            return Err(bad("penalty", format!("{k}: give a contact penalty > 0 (MPa/mm)")));
        }
        match self.bulge_pressure()? {
            b if !(b > 0.0 && b.is_finite() && b < burst) => {
                return Err(bad("bulge_pressure", format!("{b} MPa: give a pressure > 0 and below {burst:.3} MPa (twice sigma_y n t / r)")));
            }
            _ => (),
        }
        if f.increments == Some(0) {
            return Err(bad("increments", "give at least 1".into()));
        }
        let die = 2.0 * self.bellows.root_radius;
        let closed = self.bellows.pitch - self.overclose();
        // the dies' plates (2 rir thick) leave the convolution its pack twice and the crest
        if !(self.overclose() >= 0.0 && closed - die >= 2.0 * self.pack_thickness()) {
            return Err(bad(
                "overclose",
                format!(
                    "{} mm: the dies (plates 2 rir = {die} mm thick) cannot close to a pitch of {closed} mm with the ply pack ({} mm) twice between them",
                    crate::error::shown(self.overclose()),
                    self.pack_thickness()
                ),
            ));
        }
        let length = self.developed_length();
        let meridian = self.convolution_meridian();
        if !(length.is_finite() && length > self.bellows.pitch) {
            return Err(bad("developed_length", format!("{length} mm: the tube between two dies must be longer than the pitch ({} mm)", self.bellows.pitch)));
        }
        // the tube barely stretches along its meridian: 20 % less than the target's meridian
        // cannot make it, whatever the pressure
        if length < 0.8 * meridian {
            return Err(bad(
                "developed_length",
                format!(
                    "{length} mm of tube cannot make a convolution whose mid-surface meridian is {meridian:.2} mm (w {}, q {})",
                    self.bellows.convolution_height, self.bellows.pitch
                ),
            ));
        }
        Ok(())
    }
}

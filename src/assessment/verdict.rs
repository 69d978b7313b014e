//! The code's verdict on an unreinforced U-shaped bellows: each design rule of ASME VIII-1
//! Mandatory Appendix 26 (2013 edition; EJMA writes the same forms) with its value, its limit,
//! the utilisation and PASS or FAIL, from the stresses and pressures of a [`CodeCheck`]; and
//! the figures a data sheet asks for beside them: the equivalent axial movement of combined
//! axial, lateral and angular movements, the effective area and the pressure thrust.
//!
//! The fatigue rule compares the required cycles with the allowable cycles of a design fatigue
//! curve: ASME VIII-2 Table 4.19.5 (the curve of VIII-1 Appendix 26 for austenitic bellows),
//! with its margins of 3 on cycles and 1.25 on stress already in it, or EJMA's as-formed
//! austenitic curve. Both are pseudo-elastic: they are written for the elastic stress range St
//! of the formulas, however far above yield it lies.

use super::code::CodeCheck;
pub use super::code::Forming;
use super::formulas::{cycles_as_formed_austenitic, UBellows, PSI_PER_MPA};
use std::f64::consts::PI;

/// The design fatigue curve the allowable cycles are read from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FatigueCurve {
    /// ASME VIII-2 Table 4.19.5, austenitic stainless steel (VIII-1 Appendix 26's).
    Asme,
    /// EJMA's as-formed austenitic curve, Nc = (1.86e6 / (St - 54 000))^3.4, St in psi.
    Ejma,
}

impl FatigueCurve {
    pub fn name(self) -> &'static str {
        match self {
            FatigueCurve::Asme => "ASME VIII-2 Table 4.19.5 (austenitic)",
            FatigueCurve::Ejma => "EJMA as-formed austenitic curve",
        }
    }

    /// What the curve's cycles are: a design curve's margins, or none stated.
    pub fn basis(self) -> &'static str {
        match self {
            FatigueCurve::Asme => "its margins, 3 on cycles and 1.25 on stress, are in the curve (Table 4.19.5, note 2): no further margin is applied",
            FatigueCurve::Ejma => "EJMA's design curve for as-formed austenitic bellows, as the worked reports use it",
        }
    }

    /// The factors the curve is entered with, as the verdict names them: Kg, and Eo / Eb
    /// where the curve takes the moduli (ASME's; EJMA's curve takes the stress as computed).
    pub fn factors(self, kg: f64, room_modulus: f64, modulus: f64) -> String {
        match self {
            FatigueCurve::Asme => format!("Kg {kg} and Eo / Eb {:.3}", room_modulus / modulus),
            FatigueCurve::Ejma => format!("Kg {kg}"),
        }
    }

    /// The allowable cycles at the stress range `st` (MPa) with the fatigue strength reduction
    /// factor `kg` and the moduli at room and design temperature; `f64::INFINITY` below the
    /// curve's endurance range (EJMA's), 1e6 at the foot of the table (ASME's).
    pub fn allowable_cycles(self, st: f64, kg: f64, room_modulus: f64, modulus: f64) -> f64 {
        match self {
            // X = Kg (Eo / Eb) St, MPa
            FatigueCurve::Asme => {
                let x = kg * room_modulus / modulus * st;
                if x >= 448.0 {
                    (35_850.0 / (x - 264.0)).powi(2)
                } else if x > 257.2 {
                    (46_200.0 / (x - 211.0)).powi(2)
                } else {
                    1.0e6
                }
            }
            FatigueCurve::Ejma => cycles_as_formed_austenitic(kg * st * PSI_PER_MPA).unwrap_or(f64::INFINITY),
        }
    }
}

/// The design conditions: internal pressure (MPa); the axial movement of the whole bellows
/// (mm, extension positive), the lateral offset of its ends held parallel (mm) and its angular
/// rotation (degrees); the cycles required of them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conditions {
    pub pressure: f64,
    pub axial: f64,
    pub lateral: f64,
    pub angular: f64,
    pub cycles: f64,
}

/// What the stresses are held to: the allowable stress S of the bellows material at design
/// temperature (MPa), the longitudinal weld's joint factor Cwb, the factor Km on S of the
/// meridional pressure stresses, the fatigue curve with its strength reduction factor Kg, and
/// the elastic modulus at room temperature (MPa, the fatigue curve's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Allowables {
    pub allowable_stress: f64,
    pub weld_factor: f64,
    pub meridional_factor: f64,
    pub fatigue_curve: FatigueCurve,
    pub fatigue_factor: f64,
    pub room_modulus: f64,
}

/// Whether a check's value may not exceed its limit (a stress) or may not fall below it (the
/// allowable cycles, an instability pressure).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sense {
    AtMost,
    AtLeast,
}

/// One rule: the figure checked and the limit it is held to.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// What is checked, for a table ("S2 convolution hoop membrane").
    pub name: String,
    /// The rule in symbols and where it is written ("S2 <= Cwb S; App. 26, 26-6.3.2").
    pub rule: String,
    pub value: f64,
    pub limit: f64,
    pub unit: String,
    pub sense: Sense,
}

impl Check {
    /// The utilisation: value / limit for an upper limit, limit / value for a lower one (the
    /// required cycles over the allowed, the pressure over the instability pressure).
    pub fn ratio(&self) -> f64 {
        match self.sense {
            Sense::AtMost => self.value / self.limit,
            Sense::AtLeast => self.limit / self.value,
        }
    }

    pub fn passes(&self) -> bool {
        self.ratio() <= 1.0
    }
}

/// The code's verdict: every check, and the data sheet's figures.
#[derive(Clone, Debug)]
pub struct Verdict {
    pub checks: Vec<Check>,
    /// The equivalent axial movement per convolution and of the whole bellows (mm).
    pub movement_per_convolution: f64,
    pub equivalent_movement: f64,
    /// Effective area pi Dm^2 / 4 (mm^2) and the pressure thrust P Ae on the anchors (N).
    pub effective_area: f64,
    pub pressure_thrust: f64,
    /// The allowable cycles of the fatigue check.
    pub allowable_cycles: f64,
    /// The conditions of applicability the bellows violates, each named: where one is, the
    /// rules are outside what they are written for and the verdict says so.
    pub outside: Vec<String>,
}

impl Verdict {
    /// The checks that fail, by name.
    pub fn failed(&self) -> Vec<&str> {
        self.checks.iter().filter(|c| !c.passes()).map(|c| c.name.as_str()).collect()
    }

    /// PASS, or FAIL with the failing checks named; a bellows outside the conditions of
    /// applicability has no code verdict.
    pub fn summary(&self) -> String {
        let failed = self.failed();
        match (self.outside.is_empty(), failed.is_empty()) {
            (false, _) => format!("NOT APPLICABLE: outside the code's conditions of applicability ({})", self.outside.join("; ")),
            (true, true) => "PASS: every check".to_string(),
            (true, false) => format!("FAIL: {}", failed.join(", ")),
        }
    }
}

/// The equivalent axial movement per convolution of `conditions`' movements (ASME VIII-1
/// App. 26 and EJMA: x / N + 3 Dm y / (N (Lb + x)) + Dm theta / (2 N), Lb = N q).
pub fn movement_per_convolution(b: &UBellows, conditions: &Conditions) -> f64 {
    b.equivalent_axial_movement(conditions.axial, conditions.lateral, conditions.angular.to_radians())
}

/// The verdict on bellows `b` whose code check `check` was made for `conditions`' pressure and
/// equivalent movement ([`movement_per_convolution`] times N), with the elastic modulus at
/// design temperature `modulus` (MPa).
pub fn verdict(b: &UBellows, check: &CodeCheck, conditions: &Conditions, allowables: &Allowables, modulus: f64) -> Verdict {
    let a = allowables;
    let s = a.allowable_stress;
    let e = movement_per_convolution(b, conditions);
    let allowable_cycles = a.fatigue_curve.allowable_cycles(check.stress_range, a.fatigue_factor, a.room_modulus, modulus);
    let p = conditions.pressure;
    let check_of = |name: &str, rule: &str, value: f64, limit: f64, unit: &str, sense: Sense| Check {
        name: name.into(),
        rule: rule.into(),
        value,
        limit,
        unit: unit.into(),
        sense,
    };
    let (most, least) = (Sense::AtMost, Sense::AtLeast);
    let checks = vec![
        check_of("S1 tangent hoop membrane", "S1 <= Cwb S (App. 26, 26-6.3.2)", check.s1, a.weld_factor * s, "MPa", most),
        check_of("S2 convolution hoop membrane", "S2 <= Cwb S (App. 26, 26-6.3.2; EJMA Eq. 4-29)", check.s2, a.weld_factor * s, "MPa", most),
        check_of(
            "S3 + S4 meridional, pressure",
            "S3 + S4 <= Km S (App. 26, 26-6.3.2; EJMA Eqs. 4-30, 4-31)",
            check.s3 + check.s4,
            a.meridional_factor * s,
            "MPa",
            most,
        ),
        check_of("column instability (squirm)", "P <= Psc = 0.34 pi Kb / (N q) (App. 26, 26-6.3.3)", p, check.column_instability, "MPa", most),
        check_of("in-plane instability", "P <= Psi (App. 26, 26-6.3.3)", p, check.in_plane_instability, "MPa", most),
        check_of("fatigue", "Nspe <= Nalw (App. 26, 26-6.5; St = 0.7 (S3 + S4) + S5 + S6)", allowable_cycles, conditions.cycles, "cycles", least),
    ];
    let effective_area = PI * b.mean_diameter().powi(2) / 4.0;
    Verdict {
        checks,
        movement_per_convolution: e,
        equivalent_movement: e * b.convolutions as f64,
        effective_area,
        pressure_thrust: p * effective_area,
        allowable_cycles,
        outside: b.conditions_of_applicability(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ASME VIII-2 Table 4.19.5 (2010, as stored): with X = Kg (Eo / Eb) St, N = (35 850 /
    /// (X - 264))^2 for X >= 448 MPa, (46 200 / (X - 211))^2 for 257.2 < X < 448, 10^6 below.
    /// The two branches meet within 0.1 % at 448 and the second reaches 10^6 at 257.2; Eo / Eb
    /// and Kg scale X.
    #[test]
    fn the_asme_curve_is_table_4_19_5() {
        let n = |x: f64| FatigueCurve::Asme.allowable_cycles(x, 1.0, 1.0, 1.0);
        assert!((n(448.0) - (35_850.0f64 / 184.0).powi(2)).abs() < 1e-6);
        assert!((n(447.999) / n(448.0) - 1.0).abs() < 2e-3, "{} {}", n(447.999), n(448.0));
        assert!((n(257.2001) - 1.0e6).abs() < 1e2 && n(200.0) == 1.0e6);
        assert!((n(1070.0) - (35_850.0f64 / 806.0).powi(2)).abs() < 1e-6, "1978 cycles at 1070 MPa");
        let scaled = FatigueCurve::Asme.allowable_cycles(500.0, 2.0, 200_000.0, 100_000.0);
        assert!((scaled - n(2000.0)).abs() < 1e-9);
    }

    /// The utilisation of an upper limit is value / limit, of a lower one limit / value.
    #[test]
    fn a_check_passes_at_a_ratio_of_one_or_less() {
        let c = |value, limit, sense| Check { name: "x".into(), rule: "x".into(), value, limit, unit: String::new(), sense };
        assert!(c(1.0, 1.0, Sense::AtMost).passes() && !c(1.01, 1.0, Sense::AtMost).passes());
        assert!(c(10_000.0, 9_000.0, Sense::AtLeast).passes() && !c(8_000.0, 9_000.0, Sense::AtLeast).passes());
        assert_eq!(c(20_000.0, 10_000.0, Sense::AtLeast).ratio(), 0.5);
    }
}

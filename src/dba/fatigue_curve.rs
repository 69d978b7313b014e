//! Design fatigue curves: the permissible cycles N of an alternating stress S_alt, by
//! logarithmic interpolation in a table of (N, S_a) points at the curve's own Young's modulus.
//!
//! The built-in curve is ASME's smooth-bar curve for austenitic steels (series 3xx, nickel-
//! chromium-iron and nickel-iron-chromium alloys, nickel-copper alloy; temperatures not above
//! 427 degC): ASME III Appendix I, Figure I-9.2 of the 2010 and later editions, the curve
//! VIII-2 Annex 3-F gives for these materials, E_FC = 195 123 MPa (28.3e6 psi), tabulated
//! from 10 to 1e11 cycles. An alternating stress computed with the material's modulus E_T is
//! read on it at S_alt E_FC / E_T (Annex 3-F), and between points log N is linear in log S_a
//! (the interpolation ASME prescribes for its tables).

/// A tabulated fatigue curve.
#[derive(Clone, Debug, PartialEq)]
pub struct FatigueCurve {
    /// What the curve is, for the verdict table.
    pub name: String,
    /// (N, S_a MPa), N increasing, S_a decreasing.
    pub points: Vec<(f64, f64)>,
    /// E_FC, the Young's modulus the curve's stresses belong to, MPa.
    pub modulus: f64,
}

/// ASME III Figure I-9.2 (2010): (cycles, S_a MPa).
const AUSTENITIC: [(f64, f64); 23] = [
    (1e1, 6000.0),
    (2e1, 4300.0),
    (5e1, 2748.0),
    (1e2, 1978.0),
    (2e2, 1440.0),
    (5e2, 974.0),
    (1e3, 745.0),
    (2e3, 590.0),
    (5e3, 450.0),
    (1e4, 368.0),
    (2e4, 300.0),
    (5e4, 235.0),
    (1e5, 196.0),
    (2e5, 168.0),
    (5e5, 142.0),
    (1e6, 126.0),
    (2e6, 113.0),
    (5e6, 102.0),
    (1e7, 99.0),
    (1e8, 97.1),
    (1e9, 95.8),
    (1e10, 94.4),
    (1e11, 93.7),
];

/// Permissible cycles read off a curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cycles {
    /// Within the table.
    Allowed(f64),
    /// Below the curve's lowest stress: more cycles than its last point.
    Beyond(f64),
    /// Above its highest stress: fewer cycles than its first point.
    Below(f64),
}

impl Cycles {
    /// The cycles as a number (the table's end where the stress lies off it).
    pub fn value(self) -> f64 {
        match self {
            Cycles::Allowed(n) | Cycles::Beyond(n) | Cycles::Below(n) => n,
        }
    }
}

impl FatigueCurve {
    /// The built-in austenitic-steel curve.
    pub fn austenitic() -> Self {
        FatigueCurve { name: "ASME austenitic, III Fig. I-9.2 (2010)".into(), points: AUSTENITIC.to_vec(), modulus: 195_123.0 }
    }

    /// A curve of the user's: at least two points, N increasing and S_a decreasing, all > 0.
    pub fn table(points: Vec<(f64, f64)>, modulus: f64) -> Result<Self, String> {
        if points.len() < 2 {
            return Err(format!("a fatigue curve needs at least two (cycles, stress) points, got {}", points.len()));
        }
        if !(modulus > 0.0 && modulus.is_finite()) {
            return Err(format!("the fatigue curve's modulus must be > 0 MPa, got {modulus}"));
        }
        for (k, w) in points.windows(2).enumerate() {
            if !(w[0].0 > 0.0 && w[0].1 > 0.0 && w[1].0 > w[0].0 && w[1].1 < w[0].1 && w[1].1 > 0.0 && w[1].0.is_finite() && w[0].1.is_finite()) {
                return Err(format!("fatigue curve point {}: cycles must increase and stresses decrease, all > 0; got {:?} after {:?}", k + 2, w[1], w[0]));
            }
        }
        Ok(FatigueCurve { name: "the deck's fatigue curve".into(), points, modulus })
    }

    /// Permissible cycles for the alternating stress `s_alt` (MPa) of a material of modulus
    /// `youngs_modulus`.
    pub fn cycles(&self, s_alt: f64, youngs_modulus: f64) -> Cycles {
        let s = s_alt * self.modulus / youngs_modulus;
        let (first, last) = (self.points[0], self.points[self.points.len() - 1]);
        if s > first.1 {
            return Cycles::Below(first.0);
        }
        if s < last.1 {
            return Cycles::Beyond(last.0);
        }
        let w = self.points.windows(2).find(|w| s >= w[1].1).expect("within the table");
        let t = (s.ln() - w[0].1.ln()) / (w[1].1.ln() - w[0].1.ln());
        Cycles::Allowed((w[0].0.ln() + t * (w[1].0.ln() - w[0].0.ln())).exp())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_points_are_read_back_and_between_them_log_n_is_linear_in_log_s() {
        let c = FatigueCurve::austenitic();
        for &(n, s) in &AUSTENITIC {
            let read = c.cycles(s, c.modulus).value();
            assert!((read / n - 1.0).abs() < 1e-12, "{s} MPa: {read} against {n}");
        }
        // halfway in log S between 745 (1e3) and 590 (2e3): N = sqrt(2) 1e3
        let s = (745.0f64 * 590.0).sqrt();
        assert!((c.cycles(s, c.modulus).value() / (2f64.sqrt() * 1e3) - 1.0).abs() < 1e-12);
        // a material twice as stiff reads the curve at half the stress
        assert_eq!(c.cycles(2.0 * 450.0, 2.0 * c.modulus), c.cycles(450.0, c.modulus));
        assert_eq!(c.cycles(7000.0, c.modulus), Cycles::Below(10.0));
        assert_eq!(c.cycles(50.0, c.modulus), Cycles::Beyond(1e11));
    }

    #[test]
    fn a_curve_that_does_not_fall_is_refused_naming_the_point() {
        assert!(FatigueCurve::table(vec![(10.0, 500.0), (100.0, 600.0)], 2e5).unwrap_err().contains("point 2"));
        assert!(FatigueCurve::table(vec![(10.0, 500.0)], 2e5).unwrap_err().contains("two"));
    }
}

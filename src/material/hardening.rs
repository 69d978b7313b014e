//! Isotropic hardening laws sigma_y(ep) for J2 plasticity: linear (sigma_y0 + H ep) or a
//! piecewise-linear table of (ep, sigma_y) points held constant past its last point (the
//! convention of Abaqus' and CalculiX's *PLASTIC). Both are non-decreasing, so the radial
//! return has exactly one root, found segment by segment.

/// Largest number of points in a hardening table (keeps the law `Copy`, no allocation in the
/// quadrature-point update).
pub const MAX_TABLE_POINTS: usize = 32;

// the table variant is large on purpose: a Copy law with no heap in the hot path
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Hardening {
    /// sigma_y(ep) = yield_stress + modulus * ep (MPa); elastic when yield_stress is infinite.
    Linear { yield_stress: f64, modulus: f64 },
    /// Piecewise linear through `points[..len]` = (ep, sigma_y), `ep[0] = 0`, constant after.
    Table { points: [(f64, f64); MAX_TABLE_POINTS], len: usize },
}

impl Hardening {
    pub fn linear(yield_stress: f64, modulus: f64) -> Self {
        Hardening::Linear { yield_stress, modulus }
    }

    /// A table of (ep, sigma_y) points: ep starts at 0 and increases, sigma_y > 0 does not
    /// decrease. The message names the offending point (1-based).
    pub fn table(points: &[(f64, f64)]) -> Result<Self, String> {
        if points.is_empty() || points.len() > MAX_TABLE_POINTS {
            return Err(format!("a hardening table needs 1 to {MAX_TABLE_POINTS} points, got {}", points.len()));
        }
        if points[0].0 != 0.0 {
            return Err(format!("the first point of a hardening table must be at plastic strain 0, got {}", points[0].0));
        }
        for (k, &(ep, s)) in points.iter().enumerate() {
            if !(s > 0.0 && s.is_finite() && ep.is_finite()) {
                return Err(format!("hardening point {}: yield stress {s} at plastic strain {ep} must be finite and > 0", k + 1));
            }
            if k > 0 && (ep <= points[k - 1].0 || s < points[k - 1].1) {
                return Err(format!(
                    "hardening point {}: plastic strain must increase and yield stress must not decrease (softening is not supported); got ({ep}, {s}) after ({}, {})",
                    k + 1,
                    points[k - 1].0,
                    points[k - 1].1
                ));
            }
        }
        let mut table = [(0.0, 0.0); MAX_TABLE_POINTS];
        table[..points.len()].copy_from_slice(points);
        Ok(Hardening::Table { points: table, len: points.len() })
    }

    /// Initial yield stress sigma_y(0).
    pub fn initial_yield_stress(&self) -> f64 {
        match self {
            Hardening::Linear { yield_stress, .. } => *yield_stress,
            Hardening::Table { points, .. } => points[0].1,
        }
    }

    /// Plastic work per unit volume to reach ep: the integral of sigma_y from 0 to ep (exact:
    /// the law is piecewise linear), MPa.
    pub fn plastic_work(&self, ep: f64) -> f64 {
        if ep <= 0.0 {
            return 0.0; // (an elastic law's yield stress is infinite)
        }
        match self {
            Hardening::Linear { yield_stress, modulus } => ep * (yield_stress + 0.5 * modulus * ep),
            Hardening::Table { points, len } => {
                let p = &points[..*len];
                let mut work = 0.0;
                for w in p.windows(2) {
                    if ep <= w[0].0 {
                        break;
                    }
                    let end = ep.min(w[1].0);
                    work += 0.5 * (w[0].1 + self.yield_stress(end)) * (end - w[0].0);
                }
                let last = p[p.len() - 1];
                if ep > last.0 {
                    work += last.1 * (ep - last.0);
                }
                work
            }
        }
    }

    /// sigma_y(ep), MPa.
    pub fn yield_stress(&self, ep: f64) -> f64 {
        match self {
            Hardening::Linear { yield_stress, modulus } => yield_stress + modulus * ep,
            Hardening::Table { .. } => {
                let (slope, start, s0, _) = self.segment(ep);
                s0 + slope * (ep - start)
            }
        }
    }

    /// The segment that continues from `ep`: (slope H, its start, sigma_y at its start, its
    /// end); the last segment is flat and endless.
    pub fn segment(&self, ep: f64) -> (f64, f64, f64, f64) {
        match self {
            Hardening::Linear { yield_stress, modulus } => (*modulus, 0.0, *yield_stress, f64::INFINITY),
            Hardening::Table { points, len } => {
                let p = &points[..*len];
                match p.windows(2).find(|w| ep < w[1].0) {
                    Some(w) => ((w[1].1 - w[0].1) / (w[1].0 - w[0].0), w[0].0, w[0].1, w[1].0),
                    None => (0.0, p[p.len() - 1].0, p[p.len() - 1].1, f64::INFINITY),
                }
            }
        }
    }

    /// Plastic multiplier of the radial return: the root dg >= 0 of
    /// q_trial - 3 G dg = sigma_y(ep_n + dg), given q_trial > sigma_y(ep_n). Returns
    /// (dg_before, ep_k, sigma_y(ep_k), H): the root lies on the segment from ep_k = ep_n +
    /// dg_before with slope H, where dg = dg_before + (q_trial - 3 G dg_before - sigma_y(ep_k)) / (3 G + H)
    /// (that form keeps the derivative of dg with respect to q_trial exact: 1 / (3 G + H)).
    pub fn return_segment(&self, q_trial: f64, shear_modulus: f64, ep_n: f64) -> (f64, f64, f64, f64) {
        let g3 = 3.0 * shear_modulus;
        let mut ep = ep_n;
        loop {
            let (h, start, s0, end) = self.segment(ep);
            let sy = s0 + h * (ep - start);
            let before = ep - ep_n;
            let dg = (q_trial - g3 * before - sy) / (g3 + h);
            if ep + dg <= end {
                return (before, ep, sy, h);
            }
            ep = end;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_two_point_table_is_linear_hardening_up_to_its_last_point_then_flat() {
        let t = Hardening::table(&[(0.0, 300.0), (0.1, 400.0)]).unwrap();
        let l = Hardening::linear(300.0, 1000.0);
        for ep in [0.0, 0.03, 0.0999] {
            assert!((t.yield_stress(ep) - l.yield_stress(ep)).abs() < 1e-9);
        }
        assert_eq!(t.yield_stress(0.5), 400.0);
    }

    #[test]
    fn the_return_crosses_table_segments_and_satisfies_the_consistency_condition() {
        let t = Hardening::table(&[(0.0, 200.0), (0.001, 250.0), (0.01, 300.0), (0.05, 320.0)]).unwrap();
        let g = 80000.0;
        for q in [210.0, 400.0, 1500.0, 5000.0, 50000.0] {
            let (before, ep_k, sy, h) = t.return_segment(q, g, 0.0);
            let dg = before + (q - 3.0 * g * before - sy) / (3.0 * g + h);
            assert!(ep_k >= 0.0 && dg >= before);
            let residual = q - 3.0 * g * dg - t.yield_stress(dg);
            assert!(residual.abs() < 1e-9 * q, "q {q}: residual {residual}");
        }
    }

    #[test]
    fn bad_tables_are_refused_naming_the_point() {
        assert!(Hardening::table(&[(0.01, 300.0)]).unwrap_err().contains("plastic strain 0"));
        assert!(Hardening::table(&[(0.0, 300.0), (0.1, 250.0)]).unwrap_err().contains("point 2"));
        assert!(Hardening::table(&[(0.0, 300.0), (0.0, 350.0)]).unwrap_err().contains("point 2"));
    }
}

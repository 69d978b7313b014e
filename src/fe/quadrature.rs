//! Gauss-Legendre rules on [-1, 1] and their tensor products on the square.

/// 3-point Gauss-Legendre abscissae and weights (exact for degree 5).
pub const GAUSS3: [(f64, f64); 3] = [(-0.774_596_669_241_483_4, 5.0 / 9.0), (0.0, 8.0 / 9.0), (0.774_596_669_241_483_4, 5.0 / 9.0)];

/// 3x3 Gauss rule on the reference square: ((xi, eta), weight). Full integration of the
/// 8-node quadrilateral: no spurious zero-energy modes.
pub fn square_3x3() -> [([f64; 2], f64); 9] {
    let mut out = [([0.0; 2], 0.0); 9];
    for (j, &(eta, wj)) in GAUSS3.iter().enumerate() {
        for (i, &(xi, wi)) in GAUSS3.iter().enumerate() {
            out[3 * j + i] = ([xi, eta], wi * wj);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rule_integrates_quintic_exactly() {
        let f = |x: f64| 3.0 * x.powi(4) - x.powi(5) + 2.0 * x * x + 1.0;
        let exact = 3.0 * 2.0 / 5.0 + 2.0 * 2.0 / 3.0 + 2.0;
        let q: f64 = GAUSS3.iter().map(|&(x, w)| w * f(x)).sum();
        assert!((q - exact).abs() < 1e-14);
        let area: f64 = square_3x3().iter().map(|p| p.1).sum();
        assert!((area - 4.0).abs() < 1e-14);
    }
}

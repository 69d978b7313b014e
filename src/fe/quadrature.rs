//! Gauss rules: Gauss-Legendre on [-1, 1] and its tensor product on the square; a conical
//! product rule on the triangle.

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

/// 3-point Gauss-Jacobi rule on [0, 1] for the weight (1 - t): abscissae and weights (exact
/// for (1 - t) times a polynomial of degree 5). The roots of the Jacobi polynomial
/// P_3^(1,0)(2t - 1), weights from the moments 1 / ((k + 1)(k + 2)).
const GAUSS_JACOBI3: [(f64, f64); 3] = [
    (0.088_587_959_512_704_25, 0.200_931_913_738_959_97),
    (0.409_466_864_440_734_8, 0.229_241_106_359_585_9),
    (0.787_659_461_760_847_3, 0.069_826_979_901_454_12),
];

/// The 9-point conical product rule on the reference triangle {xi, eta >= 0, xi + eta <= 1}
/// (Stroud, Approximate Calculation of Multiple Integrals, 1971, the rule T2: 5-? of 3 x 3
/// points): with xi = s (1 - t), eta = t the triangle is the unit square with the Jacobian
/// (1 - t), integrated by Gauss-Legendre in s and Gauss-Jacobi in t. Exact to degree 5 (as
/// the Q8's 3 x 3 rule in each direction), all weights positive, all points inside; s runs first.
pub fn triangle_9() -> [([f64; 2], f64); 9] {
    let mut out = [([0.0; 2], 0.0); 9];
    for (j, &(t, wt)) in GAUSS_JACOBI3.iter().enumerate() {
        for (i, &(x, wx)) in GAUSS3.iter().enumerate() {
            let s = 0.5 * (x + 1.0);
            out[3 * j + i] = ([s * (1.0 - t), t], 0.5 * wx * wt);
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

    #[test]
    fn triangle_rule_integrates_every_monomial_to_degree_5_exactly() {
        // int over the triangle of xi^a eta^b = a! b! / (a + b + 2)!
        let factorial = |n: u32| (1..=n).product::<u32>() as f64;
        let rule = triangle_9();
        for a in 0..=5u32 {
            for b in 0..=(5 - a) {
                let exact = factorial(a) * factorial(b) / factorial(a + b + 2);
                let q: f64 = rule.iter().map(|(p, w)| w * p[0].powi(a as i32) * p[1].powi(b as i32)).sum();
                assert!((q - exact).abs() < 1e-15, "xi^{a} eta^{b}: {q} vs {exact}");
            }
        }
        // degree 6 is not exact: the rule is what it says
        let q6: f64 = rule.iter().map(|(p, w)| w * p[1].powi(6)).sum();
        assert!((q6 - 1.0 / 56.0).abs() > 1e-6);
        assert!(rule.iter().all(|(p, w)| *w > 0.0 && p[0] > 0.0 && p[1] > 0.0 && p[0] + p[1] < 1.0));
    }
}

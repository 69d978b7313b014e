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

/// 2-point Gauss-Legendre abscissa (weights 1; exact for degree 3).
pub const GAUSS2: f64 = 0.577_350_269_189_625_8;

/// How an element is integrated. Full: a Q8's 3 x 3 Gauss points, a T6's 9-point rule, with
/// F-bar. Reduced: CalculiX's and Abaqus's rules with no volumetric treatment, a Q8's 2 x 2
/// points (their CAX8R/CPE8R/CPS8R) and a T6's 3 points (their CAX6/CPE6/CPS6), read so that
/// decks written for those elements give their answers.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Integration {
    #[default]
    Full,
    Reduced,
}

/// The 2 x 2 Gauss rule on the reference square in the first 4 of 9 slots (xi first), the
/// other 5 weightless at the centre, so that an element's fixed 9-slot arrays serve it and
/// every sum over the slots is the 2 x 2 rule's.
pub fn square_2x2() -> [([f64; 2], f64); 9] {
    let mut out = [([0.0; 2], 0.0); 9];
    for (q, slot) in out.iter_mut().take(4).enumerate() {
        let sign = |k: usize| if k == 0 { -GAUSS2 } else { GAUSS2 };
        *slot = ([sign(q % 2), sign(q / 2)], 1.0);
    }
    out
}

/// The 3-point rule on the reference triangle (points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3),
/// weights 1/6; exact for degree 2), CalculiX's for its 6-node triangles (gauss3d8's triangle
/// points) and Abaqus's, in the first 3 of 9 slots, the other 6 weightless at the centroid.
pub fn triangle_3() -> [([f64; 2], f64); 9] {
    let mut out = [([1.0 / 3.0; 2], 0.0); 9];
    let (a, b) = (1.0 / 6.0, 2.0 / 3.0);
    for (slot, p) in out.iter_mut().zip([[a, a], [b, a], [a, b]]) {
        *slot = (p, 1.0 / 6.0);
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
    fn the_reduced_rule_integrates_bicubics_exactly_in_its_first_four_slots() {
        let rule = square_2x2();
        assert!(rule[4..].iter().all(|(p, w)| *w == 0.0 && *p == [0.0, 0.0]));
        // int over the square of xi^a eta^b = (2 / (a + 1)) (2 / (b + 1)) for even a, b, else 0
        let moment = |a: i32| if a % 2 == 0 { 2.0 / f64::from(a + 1) } else { 0.0 };
        for a in 0..=3 {
            for b in 0..=3 {
                let q: f64 = rule.iter().map(|(p, w)| w * p[0].powi(a) * p[1].powi(b)).sum();
                assert!((q - moment(a) * moment(b)).abs() < 1e-14, "xi^{a} eta^{b}: {q}");
            }
        }
        let q4: f64 = rule.iter().map(|(p, w)| w * p[0].powi(4)).sum();
        assert!((q4 - 0.8).abs() > 0.1, "degree 4 is not exact: {q4}");
    }

    #[test]
    fn the_three_point_triangle_rule_is_exact_to_degree_2_only() {
        let factorial = |n: u32| (1..=n).product::<u32>() as f64;
        let rule = triangle_3();
        assert!(rule[3..].iter().all(|(_, w)| *w == 0.0));
        for a in 0..=2u32 {
            for b in 0..=(2 - a) {
                let exact = factorial(a) * factorial(b) / factorial(a + b + 2);
                let q: f64 = rule.iter().map(|(p, w)| w * p[0].powi(a as i32) * p[1].powi(b as i32)).sum();
                assert!((q - exact).abs() < 1e-15, "xi^{a} eta^{b}: {q} vs {exact}");
            }
        }
        let q3: f64 = rule.iter().map(|(p, w)| w * p[0].powi(3)).sum();
        assert!((q3 - 1.0 / 20.0).abs() > 1e-4, "degree 3 is not exact: {q3}");
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

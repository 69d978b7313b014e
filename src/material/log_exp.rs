//! Logarithm and exponential of a symmetric 2x2 matrix [[a, b], [b, c]], written as smooth
//! functions of its invariants so they stay exact and differentiable when the eigenvalues
//! coincide (as at the undeformed state).
//!
//! With m = (a + c) / 2 and s = ((a - c) / 2)^2 + b^2 (so the eigenvalues are m +- sqrt(s)),
//! any isotropic f satisfies f(A) = g0 I + g1 (A - m I), g0 = (f(m+d) + f(m-d)) / 2,
//! g1 = (f(m+d) - f(m-d)) / (2d), d = sqrt(s). Both g0 and g1 are even in d, hence smooth in
//! s; for small s they are summed as series in s, otherwise in closed form.

use crate::ad::Scalar;

/// Symmetric 2x2 matrix as (a, c, b) = (A11, A22, A12).
pub type Sym2<T> = [T; 3];

fn invariants<T: Scalar>(a: &Sym2<T>) -> (T, T) {
    let m = (a[0] + a[1]) * 0.5;
    let h = (a[0] - a[1]) * 0.5;
    (m, h * h + a[2] * a[2])
}

fn combine<T: Scalar>(a: &Sym2<T>, m: T, g0: T, g1: T) -> Sym2<T> {
    [g0 + g1 * (a[0] - m), g0 + g1 * (a[1] - m), g1 * a[2]]
}

/// Natural logarithm of a symmetric positive-definite 2x2 matrix.
pub fn log_sym2<T: Scalar>(a: &Sym2<T>) -> Sym2<T> {
    let (m, s) = invariants(a);
    let g0 = (m * m - s).ln() * 0.5;
    // g1 = atanh(d/m) / d = (1/m) * atanh(x)/x with x^2 = s / m^2
    let x2 = s / (m * m);
    let (ratio, slope) = atanh_ratio(x2.re());
    combine(a, m, g0, x2.lift(ratio, slope) / m)
}

/// atanh(x)/x and its derivative, as functions of y = x^2 in [0, 1).
fn atanh_ratio(y: f64) -> (f64, f64) {
    let (g, dg, _) = atanh_ratio_with_curvature(y);
    (g, dg)
}

/// atanh(x)/x and its first two derivatives in y = x^2 in [0, 1).
fn atanh_ratio_with_curvature(y: f64) -> (f64, f64, f64) {
    if y < 1e-2 {
        // sum y^k / (2k+1) and its derivatives; 10 terms: error < 1e-20 for y < 0.01
        let (mut g, mut dg, mut ddg) = (ATANH_SERIES[9], 0.0, 0.0);
        for k in (0..9).rev() {
            ddg = ddg * y + 2.0 * dg;
            dg = dg * y + g;
            g = g * y + ATANH_SERIES[k];
        }
        (g, dg, ddg)
    } else {
        // g' = (u - g) / (2 y) and g'' = (u' - 3 g') / (2 y), u = 1 / (1 - y)
        let x = y.sqrt();
        let g = ((1.0 + x) / (1.0 - x)).ln() * 0.5 / x;
        let u = 1.0 / (1.0 - y);
        let dg = (u - g) / (2.0 * y);
        (g, dg, (u * u - 3.0 * dg) / (2.0 * y))
    }
}

/// The stress conjugate to C of a stress `t` conjugate to ln C: S = t : d ln C / d C, for
/// symmetric positive-definite `c` (both as (11, 22, 12), tensor components). This is how a
/// stress work-conjugate to the Lagrangian log strain E = ln(C) / 2 becomes the second
/// Piola-Kirchhoff stress (S = 2 t_E : dE/dC with t_E = t). Written, like [`log_sym2`], on the
/// invariants m and s: ln C = g0 I + g1 (C - m I), so
/// S = tr t (dg0/dm I / 2 + dg0/ds D) + (t : D) (dg1/dm I / 2 + dg1/ds D) + g1 (t - tr t I / 2),
/// with D = C - m I = ds/dC; smooth (and differentiable) where the eigenvalues coincide.
pub fn log_gradient_contract<T: Scalar>(c: &Sym2<T>, t: &Sym2<T>) -> Sym2<T> {
    let (m, s) = invariants(c);
    let h = (c[0] - c[1]) * 0.5;
    let q = m * m - s;
    let (g0_m, g0_s) = (m / q, -(T::from_f64(0.5) / q));
    let y = s / (m * m);
    let (ratio, slope, curvature) = atanh_ratio_with_curvature(y.re());
    let (r, dr) = (y.lift(ratio, slope), y.lift(slope, curvature));
    let m2 = m * m;
    let g1 = r / m;
    let g1_s = dr / (m2 * m);
    let g1_m = -(r / m2) - s * dr * 2.0 / (m2 * m2);
    let trace = t[0] + t[1];
    let t_d = (t[0] - t[1]) * h + t[2] * c[2] * 2.0;
    let iso = trace * g0_m * 0.5 + t_d * g1_m * 0.5 - g1 * trace * 0.5;
    let dev = trace * g0_s + t_d * g1_s;
    [iso + dev * h + g1 * t[0], iso - dev * h + g1 * t[1], dev * c[2] + g1 * t[2]]
}

/// Exponential of a symmetric 2x2 matrix.
pub fn exp_sym2<T: Scalar>(a: &Sym2<T>) -> Sym2<T> {
    let (m, s) = invariants(a);
    let em = m.exp();
    let (cosh, sinhc) = if s.re() < 1.0 {
        // cosh d = sum s^k / (2k)!, sinh(d)/d = sum s^k / (2k+1)!; 12 terms: error < 1e-24
        let (mut c, mut sc) = (T::from_f64(0.0), T::from_f64(0.0));
        for k in (0..12).rev() {
            c = c * s + INVERSE_FACTORIALS[2 * k];
            sc = sc * s + INVERSE_FACTORIALS[2 * k + 1];
        }
        (c, sc)
    } else {
        let d = s.sqrt();
        let (ep, en) = (d.exp(), (-d).exp());
        ((ep + en) * 0.5, (ep - en) * 0.5 / d)
    };
    combine(a, m, em * cosh, em * sinhc)
}

/// 1 / (2k + 1), k = 0..9: the series of atanh(x)/x in x^2.
const ATANH_SERIES: [f64; 10] = {
    let mut t = [0.0; 10];
    let mut k = 0;
    while k < 10 {
        t[k] = 1.0 / (2 * k + 1) as f64;
        k += 1;
    }
    t
};

/// 1 / n!, n = 0..23: the series of cosh and sinh(d)/d in d^2 (constants, so the series cost
/// 24 multiply-adds and no factorials; they run at every Gauss point of every evaluation).
const INVERSE_FACTORIALS: [f64; 24] = {
    let mut t = [1.0; 24];
    let mut n = 1;
    while n < 24 {
        t[n] = t[n - 1] / n as f64;
        n += 1;
    }
    t
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ad::Dual;

    fn mul(a: &Sym2<f64>, b: &Sym2<f64>) -> [f64; 4] {
        [a[0] * b[0] + a[2] * b[2], a[0] * b[2] + a[2] * b[1], a[2] * b[0] + a[1] * b[2], a[2] * b[2] + a[1] * b[1]]
    }

    #[test]
    fn exp_inverts_log_on_both_branches() {
        for a in [[1.3, 0.8, 0.2], [1.0, 1.0, 0.0], [1.0 + 1e-9, 1.0, 1e-10], [5.0, 0.3, 1.1]] {
            let back = exp_sym2(&log_sym2(&a));
            for k in 0..3 {
                assert!((back[k] - a[k]).abs() < 1e-13 * a[0].abs().max(1.0), "{a:?} -> {back:?}");
            }
        }
    }

    #[test]
    fn log_of_a_product_of_commuting_matrices_adds() {
        // A and A^2 commute: log(A^2) = 2 log(A)
        let a = [1.7, 0.6, 0.4];
        let sq = mul(&a, &a);
        let l2 = log_sym2(&[sq[0], sq[3], sq[1]]);
        let l = log_sym2(&a);
        for k in 0..3 {
            assert!((l2[k] - 2.0 * l[k]).abs() < 1e-13);
        }
    }

    /// S = t : d ln C / d C against central differences of the scalar t : ln C (with the
    /// tensor convention: the 12 slot of the gradient is half the derivative by c[2], which
    /// enters the double contraction twice), on both sides of the series switch.
    #[test]
    fn the_log_gradient_contraction_is_the_gradient_of_t_double_dot_ln_c() {
        let t = [120.0, -45.0, 30.0];
        for c in [[1.0, 1.0, 0.0], [1.0 + 1e-3, 1.0, 2e-4], [1.2, 1.0, 0.0], [2.0, 0.7, 0.3], [0.5, 1.9, -0.6]] {
            let s = log_gradient_contract(&c, &t);
            let work = |c: &Sym2<f64>| {
                let l = log_sym2(c);
                t[0] * l[0] + t[1] * l[1] + 2.0 * t[2] * l[2]
            };
            let h = 1e-6;
            for j in 0..3 {
                let (mut p, mut q) = (c, c);
                p[j] += h;
                q[j] -= h;
                let fd = (work(&p) - work(&q)) / (2.0 * h) * if j == 2 { 0.5 } else { 1.0 };
                assert!((fd - s[j]).abs() < 1e-6 * 120.0, "c {c:?}, S[{j}]: {} against {fd}", s[j]);
            }
            // and it is differentiable there: Dual against differences of S itself
            let d = log_gradient_contract(&[Dual::<3>::variable(c[0], 0), Dual::variable(c[1], 1), Dual::variable(c[2], 2)], &t.map(Dual::constant));
            for j in 0..3 {
                let (mut p, mut q) = (c, c);
                p[j] += h;
                q[j] -= h;
                let (sp, sq) = (log_gradient_contract(&p, &t), log_gradient_contract(&q, &t));
                for i in 0..3 {
                    let fd = (sp[i] - sq[i]) / (2.0 * h);
                    assert!((fd - d[i].eps[j]).abs() < 1e-6 * 120.0, "c {c:?}, dS[{i}]/dc[{j}]: {} against {fd}", d[i].eps[j]);
                }
            }
        }
    }

    #[test]
    fn derivative_is_smooth_through_coincident_eigenvalues() {
        // d log(A) / d A at A = I is the identity map; then on either side of the series
        // switch (x^2 = 0.0083 and 0.0123) and well past it (x^2 = 0.15)
        for a in [[1.0, 1.0, 0.0], [1.0 + 0.2, 1.0, 0.0], [1.25, 1.0, 0.0], [2.0, 1.0, 0.3]] {
            let h = 1e-6;
            let d = log_sym2(&[Dual::<3>::variable(a[0], 0), Dual::variable(a[1], 1), Dual::variable(a[2], 2)]);
            for j in 0..3 {
                let (mut p, mut q) = (a, a);
                p[j] += h;
                q[j] -= h;
                let (lp, lq) = (log_sym2(&p), log_sym2(&q));
                for i in 0..3 {
                    let fd = (lp[i] - lq[i]) / (2.0 * h);
                    assert!((fd - d[i].eps[j]).abs() < 1e-8, "d log[{i}]/d a[{j}]: {fd} vs {}", d[i].eps[j]);
                }
            }
        }
    }
}

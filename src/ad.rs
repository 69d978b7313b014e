//! Forward-mode automatic differentiation: a number carrying its derivatives with respect to
//! `N` chosen inputs. Material updates are written once, generic over [`Scalar`]; run on `f64`
//! they give the stress, run on `Dual<N>` they give the stress and its exact derivative, i.e.
//! the consistent (algorithmic) tangent of the very algorithm that produced the stress.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// What the generic kernels need from a number.
pub trait Scalar:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    fn from_f64(v: f64) -> Self;
    /// The value without derivatives.
    fn re(self) -> f64;
    fn ln(self) -> Self;
    fn exp(self) -> Self;
    fn sqrt(self) -> Self;
    fn powf(self, p: f64) -> Self;
    /// Cube root (several times faster than `powf(1/3)`).
    fn cbrt(self) -> Self;
    /// A smooth function of this number, given its `value` and `derivative` at `self.re()`:
    /// a function evaluated on plain numbers (a series, say) then costs one chain rule on a
    /// dual number instead of every one of its operations.
    fn lift(self, value: f64, derivative: f64) -> Self;
}

impl Scalar for f64 {
    fn from_f64(v: f64) -> Self {
        v
    }
    fn re(self) -> f64 {
        self
    }
    fn ln(self) -> Self {
        f64::ln(self)
    }
    fn exp(self) -> Self {
        f64::exp(self)
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn powf(self, p: f64) -> Self {
        f64::powf(self, p)
    }
    fn cbrt(self) -> Self {
        f64::cbrt(self)
    }
    fn lift(self, value: f64, _derivative: f64) -> Self {
        value
    }
}

/// A value and its gradient with respect to `N` inputs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dual<const N: usize> {
    pub re: f64,
    pub eps: [f64; N],
}

impl<const N: usize> Dual<N> {
    pub fn constant(re: f64) -> Self {
        Dual { re, eps: [0.0; N] }
    }

    /// Input number `i`: value `re`, derivative 1 with respect to itself.
    pub fn variable(re: f64, i: usize) -> Self {
        let mut eps = [0.0; N];
        eps[i] = 1.0;
        Dual { re, eps }
    }

    /// Applies a scalar function with value `f` and derivative `df` at `self.re` (chain rule).
    #[inline]
    fn chain(self, f: f64, df: f64) -> Self {
        Dual { re: f, eps: self.eps.map(|e| e * df) }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Dual { re: self.re + o.re, eps: std::array::from_fn(|i| self.eps[i] + o.eps[i]) }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Dual { re: self.re - o.re, eps: std::array::from_fn(|i| self.eps[i] - o.eps[i]) }
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    #[inline]
    #[allow(clippy::suspicious_arithmetic_impl)] // the product rule
    fn mul(self, o: Self) -> Self {
        Dual { re: self.re * o.re, eps: std::array::from_fn(|i| self.eps[i] * o.re + self.re * o.eps[i]) }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    #[inline]
    #[allow(clippy::suspicious_arithmetic_impl)] // the quotient rule
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.re;
        let q = self.re * inv;
        Dual { re: q, eps: std::array::from_fn(|i| (self.eps[i] - q * o.eps[i]) * inv) }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Dual { re: -self.re, eps: self.eps.map(|e| -e) }
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: f64) -> Self {
        Dual { re: self.re + o, eps: self.eps }
    }
}

impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: f64) -> Self {
        Dual { re: self.re - o, eps: self.eps }
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: f64) -> Self {
        Dual { re: self.re * o, eps: self.eps.map(|e| e * o) }
    }
}

impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn div(self, o: f64) -> Self {
        self * (1.0 / o)
    }
}

impl<const N: usize> Scalar for Dual<N> {
    fn from_f64(v: f64) -> Self {
        Dual::constant(v)
    }
    fn re(self) -> f64 {
        self.re
    }
    fn ln(self) -> Self {
        self.chain(self.re.ln(), 1.0 / self.re)
    }
    fn exp(self) -> Self {
        let e = self.re.exp();
        self.chain(e, e)
    }
    fn sqrt(self) -> Self {
        let s = self.re.sqrt();
        self.chain(s, 0.5 / s)
    }
    fn powf(self, p: f64) -> Self {
        self.chain(self.re.powf(p), p * self.re.powf(p - 1.0))
    }
    fn cbrt(self) -> Self {
        let c = self.re.cbrt();
        self.chain(c, c / (3.0 * self.re))
    }
    fn lift(self, value: f64, derivative: f64) -> Self {
        self.chain(value, derivative)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f<T: Scalar>(x: T, y: T) -> T {
        (x * y + x.exp()).ln() / (y.sqrt() - 0.3) + x.powf(1.0 / 3.0) * 2.0 + (x * y).cbrt()
    }

    #[test]
    fn derivatives_match_central_differences() {
        let (x, y) = (0.7, 1.9);
        let d = f(Dual::<2>::variable(x, 0), Dual::<2>::variable(y, 1));
        let h = 1e-6;
        let fx = (f(x + h, y) - f(x - h, y)) / (2.0 * h);
        let fy = (f(x, y + h) - f(x, y - h)) / (2.0 * h);
        assert!((d.re - f(x, y)).abs() < 1e-15);
        assert!((d.eps[0] - fx).abs() < 1e-8 && (d.eps[1] - fy).abs() < 1e-8, "{d:?} vs {fx} {fy}");
    }
}

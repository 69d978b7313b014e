//! The linear extrapolation predictor (Abaqus's default, *STEP, EXTRAPOLATION=LINEAR): Newton
//! starts an increment from the last converged state plus the step's last displacement
//! increment scaled to the new increment's size. It costs no factorisation, where the tangent
//! predictor (`attempt::predict`) costs one per increment; the step's first increment, with
//! nothing to extrapolate, takes the tangent predictor (see `model::Predictor`).

/// The last converged increment of the current step: its displacement increment (every mesh
/// node) and its size in load factor.
#[derive(Clone, Debug, PartialEq)]
pub struct LastIncrement {
    pub displacement: Vec<[f64; 2]>,
    pub size: f64,
}

impl LastIncrement {
    /// The increment from `before` to `after`, of load-factor size `size`.
    pub fn between(before: &[[f64; 2]], after: &[[f64; 2]], size: f64) -> Self {
        LastIncrement { displacement: after.iter().zip(before).map(|(a, b)| [a[0] - b[0], a[1] - b[1]]).collect(), size }
    }

    /// The guess for an increment of `size` from the converged `displacement`.
    pub fn extrapolate(&self, displacement: &[[f64; 2]], size: f64) -> Vec<[f64; 2]> {
        let r = size / self.size;
        displacement.iter().zip(&self.displacement).map(|(u, d)| [u[0] + r * d[0], u[1] + r * d[1]]).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_path_is_extrapolated_exactly() {
        // u(lambda) = lambda * [2, -3]: from lambda 0.3 to 0.5, then a step of 0.1 from 0.5
        let u = |l: f64| [2.0 * l, -3.0 * l];
        let last = LastIncrement::between(&[u(0.3)], &[u(0.5)], 0.2);
        let guess = last.extrapolate(&[u(0.5)], 0.1);
        assert!((guess[0][0] - u(0.6)[0]).abs() < 1e-15 && (guess[0][1] - u(0.6)[1]).abs() < 1e-15, "{guess:?}");
    }
}

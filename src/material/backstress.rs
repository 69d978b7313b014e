//! A material's backstress terms, the data of its kinematic hardening: how many, their moduli
//! and recalls, and the slope they add. The return map that moves them is
//! [`super::kinematic`]; the isotropic kernel [`super::j2`] carries them in its point state.

use crate::ad::Scalar;

/// Largest number of Armstrong-Frederick backstresses.
pub const MAX_BACKSTRESSES: usize = 3;

/// One Armstrong-Frederick backstress term (a deck's `{ modulus = C, recall = gamma }`).
#[derive(Clone, Copy, Debug, PartialEq, Default, serde::Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct Backstress {
    /// C_k, MPa: the initial slope of the term's uniaxial stress-plastic strain curve.
    pub modulus: f64,
    /// gamma_k (dimensionless): the rate of its recall; C_k / gamma_k is its saturation
    /// stress. 0 (the default) is linear (Prager) hardening.
    #[serde(default)]
    pub recall: f64,
}

/// The backstress terms of a material; none for purely isotropic hardening.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct KinematicHardening {
    terms: [Backstress; MAX_BACKSTRESSES],
    len: usize,
}

impl KinematicHardening {
    /// No kinematic hardening.
    pub const NONE: KinematicHardening = KinematicHardening { terms: [Backstress { modulus: 0.0, recall: 0.0 }; MAX_BACKSTRESSES], len: 0 };

    /// Up to three terms, each with C_k > 0 and gamma_k >= 0 (finite); the message names the
    /// offending term (1-based).
    pub fn new(terms: &[Backstress]) -> Result<Self, String> {
        if terms.len() > MAX_BACKSTRESSES {
            return Err(format!("at most {MAX_BACKSTRESSES} backstress terms, got {}", terms.len()));
        }
        for (k, t) in terms.iter().enumerate() {
            if !(t.modulus > 0.0 && t.modulus.is_finite()) {
                return Err(format!("backstress {}: modulus C = {} must be finite and > 0 (MPa)", k + 1, t.modulus));
            }
            if !(t.recall >= 0.0 && t.recall.is_finite()) {
                return Err(format!("backstress {}: recall gamma = {} must be finite and >= 0", k + 1, t.recall));
            }
        }
        let mut all = KinematicHardening::NONE;
        all.terms[..terms.len()].copy_from_slice(terms);
        all.len = terms.len();
        Ok(all)
    }

    pub fn terms(&self) -> &[Backstress] {
        &self.terms[..self.len]
    }

    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The hardening slope of continued loading at the state whose relative-stress direction
    /// is `normal` (unit, [rr, zz, tt, rz], tensor shear): sum_k (C_k - sqrt(3/2) gamma_k
    /// alpha_k : N), the kinematic share of d sigma / d ep in uniaxial tension.
    pub fn slope(&self, back: &[[f64; 4]; MAX_BACKSTRESSES], normal: &[f64; 4]) -> f64 {
        let sq = (1.5f64).sqrt();
        self.terms().iter().zip(back).map(|(t, a)| t.modulus - sq * t.recall * dot(a, normal)).sum()
    }
}

/// Double contraction of two symmetric tensors [rr, zz, tt, rz].
pub(super) fn dot<T: Scalar>(a: &[T; 4], b: &[f64; 4]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * (2.0 * b[3])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_terms_are_refused_naming_the_term() {
        let ok = Backstress { modulus: 1e4, recall: 10.0 };
        assert!(KinematicHardening::new(&[ok, Backstress { modulus: 0.0, recall: 1.0 }]).unwrap_err().contains("backstress 2"));
        assert!(KinematicHardening::new(&[Backstress { modulus: 1e4, recall: -1.0 }]).unwrap_err().contains("backstress 1"));
        assert!(KinematicHardening::new(&[ok; 4]).unwrap_err().contains("at most 3"));
    }
}

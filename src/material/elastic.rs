//! Isotropic linear elasticity with isotropic thermal strain, in the Voigt order of
//! `fe::axisymmetric` (`[rr, zz, tt, rz]`, engineering shear).

use crate::model::MaterialModel;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastic {
    /// Lame's first parameter (MPa).
    pub lambda: f64,
    /// Shear modulus (MPa).
    pub mu: f64,
    /// Linear thermal expansion coefficient (1/degC).
    pub alpha: f64,
}

impl Elastic {
    pub fn new(youngs_modulus: f64, poissons_ratio: f64, thermal_expansion: f64) -> Self {
        let (e, nu) = (youngs_modulus, poissons_ratio);
        Elastic {
            lambda: e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            mu: e / (2.0 * (1.0 + nu)),
            alpha: thermal_expansion,
        }
    }

    pub fn from_model(model: &MaterialModel) -> Self {
        match *model {
            MaterialModel::Elastic {
                youngs_modulus,
                poissons_ratio,
                thermal_expansion,
            } => Elastic::new(youngs_modulus, poissons_ratio, thermal_expansion),
        }
    }

    /// Stress from total strain `e` and temperature change `dt` (thermal strain alpha*dt
    /// on the normal components is removed first).
    pub fn stress(&self, e: &[f64; 4], dt: f64) -> [f64; 4] {
        let th = self.alpha * dt;
        let (n0, n1, n2) = (e[0] - th, e[1] - th, e[2] - th);
        let tr = n0 + n1 + n2;
        let m2 = 2.0 * self.mu;
        [
            self.lambda * tr + m2 * n0,
            self.lambda * tr + m2 * n1,
            self.lambda * tr + m2 * n2,
            self.mu * e[3],
        ]
    }

    /// d(stress)/d(strain), constant.
    pub fn tangent(&self) -> [[f64; 4]; 4] {
        let (l, m) = (self.lambda, self.mu);
        [
            [l + 2.0 * m, l, l, 0.0],
            [l, l + 2.0 * m, l, 0.0],
            [l, l, l + 2.0 * m, 0.0],
            [0.0, 0.0, 0.0, m],
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_matches_finite_differences_of_stress() {
        let m = Elastic::new(200e3, 0.3, 1.2e-5);
        let e = [1e-3, -4e-4, 2e-4, 3e-4];
        let c = m.tangent();
        let h = 1e-7;
        for j in 0..4 {
            let (mut ep, mut em) = (e, e);
            ep[j] += h;
            em[j] -= h;
            let (sp, sm) = (m.stress(&ep, 50.0), m.stress(&em, 50.0));
            for i in 0..4 {
                let fd = (sp[i] - sm[i]) / (2.0 * h);
                assert!(
                    (fd - c[i][j]).abs() <= 1e-6 * c[0][0],
                    "C[{i}][{j}]: {fd} vs {}",
                    c[i][j]
                );
            }
        }
    }

    #[test]
    fn uniaxial_stress_recovers_youngs_modulus_and_free_heating_is_stress_free() {
        let (e, nu) = (200e3, 0.3);
        let m = Elastic::new(e, nu, 1e-5);
        let s = m.stress(&[1e-3, -nu * 1e-3, -nu * 1e-3, 0.0], 0.0);
        assert!((s[0] - e * 1e-3).abs() < 1e-9 && s[1].abs() < 1e-9 && s[2].abs() < 1e-9);
        let th = 1e-5 * 100.0;
        let s = m.stress(&[th, th, th, 0.0], 100.0);
        assert!(s.iter().all(|v| v.abs() < 1e-9));
    }
}

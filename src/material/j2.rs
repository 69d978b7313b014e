//! J2 (von Mises) elastoplasticity with linear isotropic hardening sigma_y(ep) = sigma_y0 + H ep,
//! and isotropic thermal strain; elasticity alone is the case sigma_y0 = infinity.
//!
//! Finite strain (Simo 1992; de Souza Neto, Peric & Owen, *Computational Methods for
//! Plasticity*, ch. 14): multiplicative split F = F_e F_theta F_p with the isotropic thermal
//! stretch F_theta = (1 + alpha dT) I, Hencky elasticity tau = K tr(eps_e) I + 2 G dev(eps_e) on
//! the logarithmic elastic strain eps_e = 1/2 ln b_e, and the exponential-map return: the trial
//! b_e = F C_p^-1 F^T / (1 + alpha dT)^2 is mapped back by the small-strain radial return in
//! log-strain space, which is exact for this model. History: C_p^-1 and ep.
//! Small strain: the same radial return on eps - eps_p - alpha dT I. History: eps_p and ep.
//! For small strains the finite update reduces to the small one.
//!
//! The update is generic over [`Scalar`]: with `Dual` inputs it returns the exact derivative of
//! the stress measure, which is the consistent algorithmic tangent.
//!
//! Interface with the element (F-bar, see `element::solid`): inputs are the axisymmetric
//! deformation gradient `f = [F_rR, F_rZ, F_zR, F_zZ, F_tT]` and the projected volume measure
//! `theta` (det F_bar at finite strain, tr eps_bar at small strain); the output stress measure
//! `phi` is the work conjugate of `f` that the element integrates over the reference volume:
//! `phi = J sigma(F_bar) F^-T` (finite; de Souza Neto's F-bar) or the small-strain stress in the
//! same slots `[s_rr, s_rz, s_rz, s_zz, s_tt]`.

use super::backstress::{KinematicHardening, MAX_BACKSTRESSES};
use super::hardening::Hardening;
use super::log_exp::{exp_sym2, log_sym2};
use crate::ad::Scalar;

/// Relative tolerance on the yield function below which a trial state counts as elastic.
pub const YIELD_TOLERANCE: f64 = 1e-10;

/// How far below the yield surface (relative) a trial state still counts as on it when
/// [`SurfaceBranch::Flowing`] asks: a point that flowed in the last increment is on the
/// surface to round-off at the converged state; one that unloaded lies below it by far more.
pub const SURFACE_TOLERANCE: f64 = 1e-6;

/// Which response a trial state on the yield surface (to round-off) takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SurfaceBranch {
    /// Elastic: Newton's first direction of an increment is never softer than the response.
    #[default]
    Elastic,
    /// Flowing (plastic loading, the continuum elasto-plastic tangent at a zero increment):
    /// the load predictor's tangent at a converged state, since a monotonic load keeps the
    /// points that flowed flowing. Measured on the default bellows: half the Newton iterations
    /// of the elastic predictor.
    Flowing,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kinematics {
    /// Geometrically linear: small strains and rotations, loads on the reference configuration.
    Small,
    /// Finite strains and rotations (NLGEOM), follower pressure.
    Finite,
}

/// History at one quadrature point. Tensor components in the order [rr, zz, tt, rz].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointState {
    /// Finite strain: C_p^-1, the inverse plastic right Cauchy-Green tensor (with kinematic
    /// hardening exp(-2 E_p) of the Lagrangian log plastic strain E_p).
    /// Small strain: the plastic strain eps_p.
    pub plastic: [f64; 4],
    /// Equivalent plastic strain.
    pub ep: f64,
    /// The backstresses alpha_k of kinematic hardening, MPa (tensor shear); zero without it.
    pub back: [[f64; 4]; MAX_BACKSTRESSES],
    /// The backstresses' share of the plastic work so far (what sigma_y(ep) does not give),
    /// MPa; zero without kinematic hardening.
    pub kinematic_work: f64,
}

impl PointState {
    pub fn initial(kinematics: Kinematics) -> Self {
        let plastic = match kinematics {
            Kinematics::Finite => [1.0, 1.0, 1.0, 0.0],
            Kinematics::Small => [0.0; 4],
        };
        PointState { plastic, ep: 0.0, back: [[0.0; 4]; MAX_BACKSTRESSES], kinematic_work: 0.0 }
    }

    /// The state with this plastic tensor and equivalent plastic strain, and no backstress.
    pub fn isotropic(plastic: [f64; 4], ep: f64) -> Self {
        PointState { plastic, ep, back: [[0.0; 4]; MAX_BACKSTRESSES], kinematic_work: 0.0 }
    }

    /// The plastic strain tensor [rr, zz, tt, rz] (tensor shear): eps_p in small strain; in
    /// finite strain the logarithmic plastic strain of the reference configuration,
    /// ln(C_p) / 2 = -ln(C_p^-1) / 2.
    pub fn plastic_strain_tensor(&self, kinematics: Kinematics) -> [f64; 4] {
        match kinematics {
            Kinematics::Small => self.plastic,
            Kinematics::Finite => {
                let c = self.plastic;
                let [rr, zz, rz] = log_sym2(&[c[0], c[1], c[3]]);
                [-0.5 * rr, -0.5 * zz, -0.5 * c[2].ln(), -0.5 * rz]
            }
        }
    }
}

/// Result of one update.
#[derive(Clone, Copy, Debug)]
pub struct Update<T> {
    /// Stress measure conjugate to `f` (see the module doc).
    pub phi: [T; 5],
    /// Cauchy stress [rr, zz, tt, rz], MPa.
    pub cauchy: [f64; 4],
    /// The trial history (committed only when the increment converges).
    pub state: PointState,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct J2 {
    pub bulk_modulus: f64,
    pub shear_modulus: f64,
    /// 1/degC.
    pub thermal_expansion: f64,
    /// Isotropic hardening sigma_y(ep); infinite yield stress for an elastic material.
    pub hardening: Hardening,
    /// Backstress terms (none: isotropic hardening alone); see [`super::kinematic`].
    pub kinematic: KinematicHardening,
}

impl J2 {
    pub fn elastic(youngs_modulus: f64, poissons_ratio: f64, thermal_expansion: f64) -> Self {
        Self::plastic(youngs_modulus, poissons_ratio, thermal_expansion, f64::INFINITY, 0.0)
    }

    pub fn plastic(youngs_modulus: f64, poissons_ratio: f64, thermal_expansion: f64, yield_stress: f64, hardening_modulus: f64) -> Self {
        Self::with_hardening(youngs_modulus, poissons_ratio, thermal_expansion, Hardening::linear(yield_stress, hardening_modulus))
    }

    pub fn with_hardening(youngs_modulus: f64, poissons_ratio: f64, thermal_expansion: f64, hardening: Hardening) -> Self {
        let (e, nu) = (youngs_modulus, poissons_ratio);
        J2 {
            bulk_modulus: e / (3.0 * (1.0 - 2.0 * nu)),
            shear_modulus: e / (2.0 * (1.0 + nu)),
            thermal_expansion,
            hardening,
            kinematic: KinematicHardening::NONE,
        }
    }

    /// Radial return on the elastic trial strain `e` ([11, 22, 33, 12], tensor shear).
    /// Returns the stress, the elastic strain after return, and ep.
    fn return_map<T: Scalar>(&self, branch: SurfaceBranch, e: [T; 4], ep_n: f64) -> ([T; 4], [T; 4], f64) {
        let (k, g) = (self.bulk_modulus, self.shear_modulus);
        let tr = e[0] + e[1] + e[2];
        let mean = tr / 3.0;
        let mut dev = [e[0] - mean, e[1] - mean, e[2] - mean, e[3]];
        let mut ep = ep_n;
        let norm2 = dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2] + dev[3] * dev[3] * 2.0;
        if norm2.re() > 0.0 {
            let q_trial = (norm2 * 6.0).sqrt() * g; // sqrt(3/2) |2 G dev|
            let yield_now = self.hardening.yield_stress(ep_n);
            let f = q_trial - yield_now;
            // Elastic predictor: a point on the yield surface to round-off (as every plastic
            // point is at the start of an increment) is elastic, so the first Newton direction
            // of an increment is never softer than the response it predicts.
            let threshold = match branch {
                SurfaceBranch::Elastic => YIELD_TOLERANCE,
                // ep_n > 0: only a point that has yielded can be on the surface
                SurfaceBranch::Flowing if ep_n > 0.0 => -SURFACE_TOLERANCE,
                SurfaceBranch::Flowing => YIELD_TOLERANCE,
            };
            if f.re() > threshold * yield_now {
                // the segment of sigma_y(ep) the return ends on (real parts), then dgamma
                // as an exact function of q_trial on it
                let (before, _, yield_k, h) = self.hardening.return_segment(q_trial.re(), g, ep_n);
                let dgamma = (q_trial - (3.0 * g * before + yield_k)) / (3.0 * g + h) + before;
                let factor = -(dgamma * (3.0 * g)) / q_trial + 1.0;
                dev = dev.map(|d| d * factor);
                ep = ep_n + dgamma.re();
            }
        }
        let p = tr * k;
        let stress = [p + dev[0] * (2.0 * g), p + dev[1] * (2.0 * g), p + dev[2] * (2.0 * g), dev[3] * (2.0 * g)];
        let elastic = [dev[0] + mean, dev[1] + mean, dev[2] + mean, dev[3]];
        (stress, elastic, ep)
    }

    /// Stored elastic energy per unit reference volume of the Kirchhoff stress `tau`
    /// ([rr, zz, tt, rz]; the Cauchy stress in small strain): tau : C^-1 : tau / 2, the
    /// Hencky energy of the log elastic strain (the small-strain one in small strain), MPa.
    pub fn elastic_energy(&self, tau: &[f64; 4]) -> f64 {
        let tr = tau[0] + tau[1] + tau[2];
        let mean = tr / 3.0;
        let dev2 = (tau[0] - mean).powi(2) + (tau[1] - mean).powi(2) + (tau[2] - mean).powi(2) + 2.0 * tau[3] * tau[3];
        dev2 / (4.0 * self.shear_modulus) + tr * tr / (18.0 * self.bulk_modulus)
    }

    /// The volume ratio det F and the thermal stretch 1 + alpha dT, or why the deformation
    /// is not admissible.
    pub(super) fn admissible<T: Scalar>(&self, f: &[T; 5], theta: T, dt: f64) -> Result<(T, f64), String> {
        let j = (f[0] * f[3] - f[1] * f[2]) * f[4];
        if j.re().is_nan() || j.re() <= 0.0 || theta.re().is_nan() || theta.re() <= 0.0 {
            return Err(format!("non-positive volume ratio (det F = {:.3e}, projected {:.3e}): element inverted", j.re(), theta.re()));
        }
        let stretch = 1.0 + self.thermal_expansion * dt;
        if stretch.is_nan() || stretch <= 0.0 {
            return Err(format!("thermal stretch 1 + alpha dT = {stretch} is not positive"));
        }
        Ok((j, stretch))
    }

    pub(super) fn update_small<T: Scalar>(&self, branch: SurfaceBranch, f: &[T; 5], theta: T, dt: f64, committed: &PointState) -> Update<T> {
        let e = [f[0] - 1.0, f[3] - 1.0, f[4] - 1.0, (f[1] + f[2]) * 0.5];
        // B-bar: the volumetric strain is replaced by the projected one.
        let shift = (theta - (e[0] + e[1] + e[2])) / 3.0;
        let th = self.thermal_expansion * dt;
        let ep_n = committed.plastic;
        let bar = [e[0] + shift, e[1] + shift, e[2] + shift, e[3]];
        let trial = [bar[0] - ep_n[0] - th, bar[1] - ep_n[1] - th, bar[2] - ep_n[2] - th, bar[3] - ep_n[3]];
        let (s, elastic, ep) = self.return_map(branch, trial, committed.ep);
        // unchanged where nothing flowed (bit for bit, so an elastic point's history stays as
        // committed instead of drifting by round-off)
        let plastic = if ep == committed.ep { ep_n } else { std::array::from_fn(|i| trial[i].re() - elastic[i].re() + ep_n[i]) };
        Update { phi: [s[0], s[3], s[3], s[1], s[2]], cauchy: s.map(|v| v.re()), state: PointState::isotropic(plastic, ep) }
    }

    pub(super) fn update_finite<T: Scalar>(&self, branch: SurfaceBranch, f: &[T; 5], theta: T, dt: f64, committed: &PointState) -> Result<Update<T>, String> {
        let (j, stretch) = self.admissible(f, theta, dt)?;
        // b_e trial = F_bar C_p^-1 F_bar^T / stretch^2 with F_bar = (theta / J)^(1/3) F, in-plane
        // block and hoop. The F-bar scaling multiplies b by (theta / J)^(2/3), which shifts
        // its logarithm by (2/3) ln(theta / J) I: it enters the log strain as one logarithm
        // on the diagonal instead of a cube root and a scaled copy of F.
        let c = committed.plastic;
        let s2 = 1.0 / (stretch * stretch);
        let (c11, c22, c33, c12) = (c[0], c[1], c[2], c[3]);
        let row = |a: T, b: T| (a * c11 + b * c12, a * c12 + b * c22); // [a b] C
        let (r1a, r1b) = row(f[0], f[1]);
        let (r2a, r2b) = row(f[2], f[3]);
        let b = [(r1a * f[0] + r1b * f[1]) * s2, (r2a * f[2] + r2b * f[3]) * s2, (r1a * f[2] + r1b * f[3]) * s2];
        let b33 = f[4] * f[4] * (c33 * s2);
        let log_b = log_sym2(&b);
        let shift = (theta / j).ln() * (1.0 / 3.0);
        let trial = [log_b[0] * 0.5 + shift, log_b[1] * 0.5 + shift, b33.ln() * 0.5 + shift, log_b[2] * 0.5];
        let (tau, elastic, ep) = self.return_map(branch, trial, committed.ep);

        let (phi, cauchy) = stress_measure(f, theta, &tau);
        if ep == committed.ep {
            // nothing flowed: C_p^-1 is the committed one (bit for bit, rather than recomputed
            // through exp and F_bar^-1 with round-off, so an elastic point's history is unchanged
            // and what was computed from it stays valid)
            return Ok(Update { phi, cauchy, state: *committed });
        }
        // history: C_p^-1 = stretch^2 F_bar^-1 b_e F_bar^-T, b_e = exp(2 eps_e)
        let re = |v: T| v.re();
        let be = exp_sym2(&[elastic[0].re() * 2.0, elastic[1].re() * 2.0, elastic[3].re() * 2.0]);
        let be33 = (elastic[2].re() * 2.0).exp();
        let scale = (theta.re() / j.re()).cbrt();
        let (f11, f12, f21, f22, f33) = (re(f[0]) * scale, re(f[1]) * scale, re(f[2]) * scale, re(f[3]) * scale, re(f[4]) * scale);
        let d = f11 * f22 - f12 * f21;
        let inv = [[f22 / d, -f12 / d], [-f21 / d, f11 / d]];
        let bm = [[be[0], be[2]], [be[2], be[1]]];
        let mut cp = [[0.0; 2]; 2];
        for i in 0..2 {
            for k in 0..2 {
                cp[i][k] = stretch * stretch * (0..2).map(|a| (0..2).map(|bb| inv[i][a] * bm[a][bb] * inv[k][bb]).sum::<f64>()).sum::<f64>();
            }
        }
        let plastic = [cp[0][0], cp[1][1], stretch * stretch * be33 / (f33 * f33), cp[0][1]];
        Ok(Update { phi, cauchy, state: PointState::isotropic(plastic, ep) })
    }
}

/// The element's stress measure phi = (J / theta) tau F^-T and the Cauchy stress tau / theta
/// of the Kirchhoff stress `tau` ([rr, zz, tt, rz]) at finite strain (see the module doc).
pub(super) fn stress_measure<T: Scalar>(f: &[T; 5], theta: T, tau: &[T; 4]) -> ([T; 5], [f64; 4]) {
    let cauchy = tau.map(|t| t.re() / theta.re());
    // in-plane J / det2 = F_tT, in the hoop J / F_tT = det2
    let det2 = f[0] * f[3] - f[1] * f[2];
    let inverse_theta = T::from_f64(1.0) / theta;
    let w = f[4] * inverse_theta;
    let (t11, t22, t33, t12) = (tau[0], tau[1], tau[2], tau[3]);
    let phi = [
        (t11 * f[3] - t12 * f[1]) * w,
        (t12 * f[0] - t11 * f[2]) * w,
        (t12 * f[3] - t22 * f[1]) * w,
        (t22 * f[0] - t12 * f[2]) * w,
        t33 * det2 * inverse_theta,
    ];
    (phi, cauchy)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::ad::Dual;

    /// AISI 304 of the seed paper, for kernel tests.
    pub(crate) const STEEL: J2 = J2 {
        bulk_modulus: 166_666.666_666_666_66,
        shear_modulus: 76_923.076_923_076_92,
        thermal_expansion: 1.875e-5,
        hardening: Hardening::Linear { yield_stress: 300.0, modulus: 1000.0 },
        kinematic: KinematicHardening::NONE,
    };

    /// Central-difference check of d phi / d (f, theta) against the Dual derivative.
    fn check_tangent(mat: &J2, kin: Kinematics, f: [f64; 5], theta: f64, dt: f64, state: &PointState) -> f64 {
        let vars: [Dual<6>; 6] = std::array::from_fn(|i| Dual::variable(if i < 5 { f[i] } else { theta }, i));
        let ad = mat.update(kin, &[vars[0], vars[1], vars[2], vars[3], vars[4]], vars[5], dt, state).unwrap();
        let scale = ad.phi.iter().flat_map(|p| p.eps).fold(0.0f64, |m, v| m.max(v.abs()));
        let mut worst = 0.0f64;
        for j in 0..6 {
            let h = 1e-7;
            let eval = |delta: f64| {
                let mut x = [f[0], f[1], f[2], f[3], f[4], theta];
                x[j] += delta;
                mat.update(kin, &[x[0], x[1], x[2], x[3], x[4]], x[5], dt, state).unwrap().phi
            };
            let (p, m) = (eval(h), eval(-h));
            for i in 0..5 {
                let fd = (p[i] - m[i]) / (2.0 * h);
                worst = worst.max((fd - ad.phi[i].eps[j]).abs() / scale);
            }
        }
        worst
    }

    fn det(f: &[f64; 5]) -> f64 {
        (f[0] * f[3] - f[1] * f[2]) * f[4]
    }

    #[test]
    fn tangent_matches_central_differences_elastic_just_yielded_and_large_plastic() {
        let state = PointState::initial(Kinematics::Finite);
        // elastic: small stretch and shear
        let f = [1.0005, 2e-4, -1e-4, 0.9998, 1.0003];
        let e = check_tangent(&STEEL, Kinematics::Finite, f, det(&f), 10.0, &state);
        assert!(e < 1e-6, "elastic: {e:e}");
        // just past yield: q_trial ~ 1.01 sigma_y in uniaxial stretch
        let s = 1.0 + 1.01 * 300.0 / 200e3;
        let l = 1.0 - 0.3 * (s - 1.0);
        let f = [l, 0.0, 0.0, s, l];
        let up = STEEL.update(Kinematics::Finite, &f, det(&f), 0.0, &state).unwrap();
        assert!(up.state.ep > 0.0 && up.state.ep < 1e-4, "should be just past yield: ep = {}", up.state.ep);
        let e = check_tangent(&STEEL, Kinematics::Finite, f, det(&f), 0.0, &state);
        assert!(e < 1e-6, "just yielded: {e:e}");
        // large rotation + plastic state with prior plastic history and heating
        let (c, sn) = (0.6f64.cos(), 0.6f64.sin());
        let u = [1.3, 0.2, 0.2, 0.8]; // stretch
        let f = [c * u[0] - sn * u[2], c * u[1] - sn * u[3], sn * u[0] + c * u[2], sn * u[1] + c * u[3], 1.1];
        let prior = PointState::isotropic([0.95, 1.04, 1.01, 0.02], 0.05);
        let e = check_tangent(&STEEL, Kinematics::Finite, f, det(&f) * 1.01, 150.0, &prior);
        assert!(e < 1e-6, "large plastic: {e:e}");
        let e =
            check_tangent(&STEEL, Kinematics::Small, [1.004, 0.002, 0.001, 0.997, 1.002], 0.003, 50.0, &PointState::isotropic([1e-3, -5e-4, 0.0, 1e-4], 1e-3));
        assert!(e < 1e-6, "small-strain plastic: {e:e}");
    }

    /// The load predictor's tangent at a converged plastic state: with the surface flowing it
    /// is the one-sided derivative of continued loading (forward differences of real updates
    /// from that state); the elastic choice is stiffer than that by far.
    #[test]
    fn a_flowing_surface_gives_the_tangent_of_continued_loading() {
        for kin in [Kinematics::Finite, Kinematics::Small] {
            // stretched past yield in z, then committed: the point is on its yield surface
            let s = 1.004;
            let l = 1.0 - 0.5 * (s - 1.0);
            let f = [l, 0.0, 0.0, s, l];
            let theta = if kin == Kinematics::Finite { det(&f) } else { f[0] + f[3] + f[4] - 3.0 };
            let state = STEEL.update(kin, &f, theta, 0.0, &PointState::initial(kin)).unwrap().state;
            assert!(state.ep > 5e-4, "{kin:?}: plastic expected, ep = {}", state.ep);
            let vars: [Dual<6>; 6] = std::array::from_fn(|i| Dual::variable(if i < 5 { f[i] } else { theta }, i));
            let tangent = |branch| STEEL.update_on(branch, kin, &[vars[0], vars[1], vars[2], vars[3], vars[4]], vars[5], 0.0, &state).unwrap().phi;
            let (flowing, elastic) = (tangent(SurfaceBranch::Flowing), tangent(SurfaceBranch::Elastic));
            // continued loading: f_zz and theta grow as in the stretch that yielded the point
            let h = 1e-7;
            let (dzz, dth) = if kin == Kinematics::Finite { (h, det(&[l, 0.0, 0.0, s + h, l]) - theta) } else { (h, h) };
            let mut g = f;
            g[3] += dzz;
            let ahead = STEEL.update(kin, &g, theta + dth, 0.0, &state).unwrap().phi;
            let here = STEEL.update(kin, &f, theta, 0.0, &state).unwrap().phi;
            let fd = (ahead[3] - here[3]) / h;
            let along = |phi: &[Dual<6>; 5]| phi[3].eps[3] + phi[3].eps[5] * dth / dzz;
            let scale = along(&elastic).abs();
            assert!((along(&flowing) - fd).abs() < 1e-4 * scale, "{kin:?}: flowing {} against continued loading {fd}", along(&flowing));
            assert!(along(&elastic) - fd > 0.3 * scale, "{kin:?}: elastic {} should be far stiffer than {fd}", along(&elastic));
        }
    }

    #[test]
    fn an_elastic_update_leaves_the_history_as_committed_bit_for_bit() {
        // What was computed from a history stays valid across a commit that did not change it
        // (the kept element tangents): an elastic step must not recompute C_p^-1 or eps_p with
        // round-off. A plastic step does change it.
        let relaxed = PointState::isotropic([1.0, 1.0, 1.0, 0.0], 0.05);
        let up = STEEL.update(Kinematics::Finite, &[1.0002, 0.0, 0.0, 0.9999, 1.0001], 1.0002, 0.0, &relaxed).unwrap();
        assert_eq!(up.state, relaxed, "finite strain, elastic");
        let small = PointState::isotropic([1e-3, -5e-4, -5e-4, 1e-4], 1e-3);
        let up = STEEL.update(Kinematics::Small, &[1.0012, 0.0001, 0.0001, 0.9996, 0.9996], 0.0004, 0.0, &small).unwrap();
        assert_eq!(up.state, small, "small strain, elastic");
        // the same machinery does move a history that flows
        let pulled = [1.02, 0.0, 0.0, 0.99, 0.99];
        let up = STEEL.update(Kinematics::Finite, &pulled, det(&pulled), 0.0, &relaxed).unwrap();
        assert!(up.state.ep > relaxed.ep && up.state.plastic != relaxed.plastic, "finite strain, plastic");
    }

    #[test]
    fn tangent_with_a_hardening_table_matches_central_differences_across_segments() {
        let table = Hardening::table(&[(0.0, 300.0), (0.002, 330.0), (0.02, 360.0), (0.1, 380.0)]).unwrap();
        let mat = J2::with_hardening(200e3, 0.3, 1.875e-5, table);
        // from virgin state into the second segment, and from a plastic state onto the flat tail
        let f = [1.0 - 0.3 * 0.006, 0.0, 0.0, 1.006, 1.0 - 0.3 * 0.006];
        let up = mat.update(Kinematics::Finite, &f, det(&f), 0.0, &PointState::initial(Kinematics::Finite)).unwrap();
        assert!(up.state.ep > 0.002 && up.state.ep < 0.02, "second segment expected: ep = {}", up.state.ep);
        let e = check_tangent(&mat, Kinematics::Finite, f, det(&f), 0.0, &PointState::initial(Kinematics::Finite));
        assert!(e < 1e-6, "table, second segment: {e:e}");
        let prior = PointState::isotropic([0.95, 1.04, 1.01, 0.02], 0.09);
        let f = [1.2, 0.1, 0.05, 0.85, 1.05];
        let up = mat.update(Kinematics::Finite, &f, det(&f), 0.0, &prior).unwrap();
        assert!(up.state.ep > 0.1, "flat tail expected: ep = {}", up.state.ep);
        let e = check_tangent(&mat, Kinematics::Finite, f, det(&f), 0.0, &prior);
        assert!(e < 1e-6, "table, flat tail: {e:e}");
    }

    #[test]
    fn uniaxial_kirchhoff_stress_follows_hardening_law_at_large_strain() {
        // Homogeneous uniaxial stress by iterating the lateral stretch to zero lateral stress.
        let eps = 0.5f64; // log strain
        let mut state = PointState::initial(Kinematics::Finite);
        let steps = 20;
        let mut lat = 1.0f64;
        for k in 1..=steps {
            let lz = (eps * k as f64 / steps as f64).exp();
            let mut up = None;
            for _ in 0..50 {
                let f = |l: f64| [l, 0.0, 0.0, lz, l];
                let g = |l: f64| {
                    let ff = f(l);
                    let u = STEEL.update(Kinematics::Finite, &ff, det(&ff), 0.0, &state).unwrap();
                    (u.cauchy[0], u)
                };
                let (s, u) = g(lat);
                let ds = (g(lat + 1e-8).0 - g(lat - 1e-8).0) / 2e-8;
                up = Some(u);
                if s.abs() < 1e-10 {
                    break;
                }
                lat -= s / ds;
            }
            state = up.unwrap().state;
        }
        let f = [lat, 0.0, 0.0, eps.exp(), lat];
        let up = STEEL.update(Kinematics::Finite, &f, det(&f), 0.0, &state).unwrap();
        let tau = up.cauchy[1] * det(&f);
        let e = 3.0 * STEEL.bulk_modulus * STEEL.shear_modulus * 3.0 / (3.0 * STEEL.bulk_modulus * 3.0 + STEEL.shear_modulus * 3.0) * 1.0;
        let youngs = 9.0 * STEEL.bulk_modulus * STEEL.shear_modulus / (3.0 * STEEL.bulk_modulus + STEEL.shear_modulus);
        let _ = e;
        let expected = (300.0 + 1000.0 * eps) / (1.0 + 1000.0 / youngs);
        assert!(((tau - expected) / expected).abs() < 1e-8, "tau {tau} vs {expected}");
        assert!((up.state.ep - (eps - tau / youngs)).abs() < 1e-8);
    }
}

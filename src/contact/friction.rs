//! Coulomb friction on the slide line: tangential penalty regularisation with a return map.
//!
//! A slave node in contact keeps, from the last converged increment, the master material point
//! it was at (an edge and its coordinate xi_n there) and the tangential traction tau_n (MPa,
//! along the master's unit tangent t, positive when it resists slip of the slave in +t). At
//! the current positions the slip since then is the slave's offset from that material point
//! along the current tangent,
//!   g_T = (x_s - sum_k N_k(xi_n) x_k^n) . t(xi),
//! the x_k^n being the current positions of the reference edge's nodes (the edge may be another
//! one than the edge the node now projects to: the measure holds across edges), and since
//! x_s - x(xi) is normal to t at the projection, g_T is also the tangential distance the
//! contact point has moved along the master. Backward Euler, as for plasticity:
//!   trial tau = tau_n + eps_T g_T;  stick if |trial| <= mu p, else slip with tau = mu p sign(trial),
//! p the contact pressure (the normal kernel's, with the free-end taper). The force on the slave
//! is -tau A t, the reaction +N_k(xi) tau A t on the nodes of the edge it projects to.
//!
//! The tangent is the exact derivative of this residual (dual numbers over the slave, the
//! current edge and the reference edge: 14 unknowns); in slip it holds mu dp/du, which makes the
//! matrix unsymmetric. DOF order: [s, e_1, e_2, e_3, r_1, r_2, r_3], (r, z) each.

use super::node_to_edge::{contact_point, ContactLaw};
use crate::ad::{Dual, Scalar};
use crate::fe::shape::line3;
use nalgebra::{SMatrix, SVector};

pub type FrictionVector = SVector<f64, 14>;
pub type FrictionMatrix = SMatrix<f64, 14, 14>;

/// Coulomb's law with its tangential penalty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionLaw {
    /// Friction coefficient mu.
    pub coefficient: f64,
    /// Tangential penalty eps_T: traction per unit slip in stick, MPa/mm.
    pub penalty: f64,
    /// Instead of `penalty`, the elastic slip gamma (mm) at the Coulomb limit: eps_T = mu p /
    /// gamma, a function of the pressure (its derivative is in the tangent).
    pub elastic_slip: Option<f64>,
}

impl FrictionLaw {
    /// eps_T at contact pressure `pressure`.
    pub(crate) fn stiffness<T: Scalar>(&self, pressure: T) -> T {
        match self.elastic_slip {
            Some(gamma) => pressure * (self.coefficient / gamma),
            None => T::from_f64(self.penalty),
        }
    }
}

/// Where a slave node's slip is measured from: the master edge's material point it was at
/// after the last converged increment, and the tangential traction it carried then.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipReference {
    /// Edge coordinate of the material point on the reference edge.
    pub xi: f64,
    /// Tangential traction tau_n, MPa.
    pub traction: f64,
}

/// What the return map gave at one slave node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionState {
    /// Tangential traction tau, MPa (along the master's tangent, resisting the slave's slip).
    pub traction: f64,
    /// Whether the node slips (|trial| > mu p).
    pub slipping: bool,
    /// Elastic energy of the tangential penalty, A tau^2 / (2 eps_T), N mm per radian.
    pub stored: f64,
    /// Energy dissipated by the slip since the reference (backward Euler: A tau times the slip
    /// beyond the elastic one, (trial - tau) / eps_T), N mm per radian.
    pub dissipated: f64,
}

/// The residual over [s, edge, reference edge] and the state; generic for the tangent.
fn residual<T: Scalar>(
    xs: &[T; 2],
    x: &[[T; 2]; 3],
    reference: &[[T; 2]; 3],
    xi: f64,
    from: &SlipReference,
    law: &ContactLaw,
    friction: &FrictionLaw,
) -> ([T; 14], FrictionState) {
    let point = contact_point(xs, x, xi, law);
    let n_ref = line3(from.xi).0;
    let material: [T; 2] = std::array::from_fn(|c| reference[0][c] * n_ref[0] + reference[1][c] * n_ref[1] + reference[2][c] * n_ref[2]);
    let t = point.tangent;
    let slip = (xs[0] - material[0]) * t[0] + (xs[1] - material[1]) * t[1];
    let stiffness = friction.stiffness(point.pressure);
    let trial = slip * stiffness + from.traction;
    let limit = point.pressure * friction.coefficient;
    let slipping = trial.re().abs() > limit.re();
    let tau = if slipping { limit * trial.re().signum() } else { trial };
    let c = tau * point.area;
    let mut f = [T::from_f64(0.0); 14];
    for k in 0..2 {
        f[k] = t[k] * c;
        for a in 0..3 {
            f[2 + 2 * a + k] = -(point.shape[a] * t[k] * c);
        }
    }
    let (t, a, k) = (tau.re(), point.area.re(), stiffness.re());
    // no stiffness (elastic slip at zero pressure): no traction, nothing stored or dissipated
    let per_stiffness = if k > 0.0 { a / k } else { 0.0 };
    (f, FrictionState { traction: t, slipping, stored: per_stiffness * t * t / 2.0, dissipated: per_stiffness * t * (trial.re() - t) })
}

/// The friction residual of a slave node at `xs` projecting at `xi` on the edge `x`, measured
/// from `from` on the reference edge `reference` (current positions; the same edge as `x` if
/// the node has stayed on it).
pub fn friction_residual(
    xs: [f64; 2],
    x: &[[f64; 2]; 3],
    reference: &[[f64; 2]; 3],
    xi: f64,
    from: &SlipReference,
    law: &ContactLaw,
    friction: &FrictionLaw,
) -> (FrictionVector, FrictionState) {
    let (f, state) = residual(&xs, x, reference, xi, from, law, friction);
    (FrictionVector::from(f), state)
}

/// [`friction_residual`] with its exact tangent (d residual_i / d u_j at (i, j)).
pub fn friction_residual_and_tangent(
    xs: [f64; 2],
    x: &[[f64; 2]; 3],
    reference: &[[f64; 2]; 3],
    xi: f64,
    from: &SlipReference,
    law: &ContactLaw,
    friction: &FrictionLaw,
) -> (FrictionVector, FrictionMatrix, FrictionState) {
    let v = |value: f64, i: usize| Dual::<14>::variable(value, i);
    let xs_d = [v(xs[0], 0), v(xs[1], 1)];
    let x_d = std::array::from_fn(|a| [v(x[a][0], 2 + 2 * a), v(x[a][1], 3 + 2 * a)]);
    let r_d = std::array::from_fn(|a| [v(reference[a][0], 8 + 2 * a), v(reference[a][1], 9 + 2 * a)]);
    let (f, state) = residual(&xs_d, &x_d, &r_d, xi, from, law, friction);
    (FrictionVector::from_fn(|i, _| f[i].re), FrictionMatrix::from_fn(|i, j| f[i].eps[j]), state)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::node_to_edge::project_on_edge;

    const FREE: [bool; 2] = [true, true];

    /// Residual of the 14 unknowns [s, edge, reference] (re-projecting s on the edge).
    fn eval(v: &[f64; 14], from: &SlipReference, friction: &FrictionLaw) -> (FrictionVector, FrictionMatrix, FrictionState) {
        let xs = [v[0], v[1]];
        let x = [[v[2], v[3]], [v[4], v[5]], [v[6], v[7]]];
        let reference = [[v[8], v[9]], [v[10], v[11]], [v[12], v[13]]];
        let p = project_on_edge(xs, &x).unwrap();
        let law = ContactLaw::linear(0.7, 2e4, 0.0, FREE);
        friction_residual_and_tangent(xs, &x, &reference, p.xi, from, &law, friction)
    }

    /// Largest difference between the tangent and central differences of the residual,
    /// relative to the tangent's largest entry.
    fn fd_error(v: [f64; 14], from: &SlipReference, friction: &FrictionLaw, expect_slip: bool) -> f64 {
        let (_, k, state) = eval(&v, from, friction);
        assert_eq!(state.slipping, expect_slip, "{state:?}");
        let scale = k.abs().max();
        let h = 1e-7;
        let mut worst = 0.0f64;
        for j in 0..14 {
            let (mut p, mut m) = (v, v);
            p[j] += h;
            m[j] -= h;
            let (fp, _, sp) = eval(&p, from, friction);
            let (fm, _, sm) = eval(&m, from, friction);
            assert_eq!((sp.slipping, sm.slipping), (expect_slip, expect_slip), "the perturbation crossed the slip limit");
            worst = worst.max(((fp - fm) / (2.0 * h) - k.column(j)).abs().max() / scale);
        }
        worst
    }

    /// A curved master edge, a slave node 0.02 inside it near xi = 0.3, and a reference edge.
    fn configuration(reference: [[f64; 2]; 3]) -> [f64; 14] {
        let x = [[20.0, 3.0], [22.0, 4.2], [21.05, 3.85]];
        let p = project_on_edge([21.3, 3.95], &x).unwrap();
        // the foot of the point on the curve, then 0.02 inside (against the outward normal)
        let xs = [0, 1].map(|c| [21.3, 3.95][c] - (p.gap + 0.02) * p.normal[c]);
        let mut v = [0.0; 14];
        v[..2].copy_from_slice(&xs);
        for a in 0..3 {
            v[2 + 2 * a..4 + 2 * a].copy_from_slice(&x[a]);
            v[8 + 2 * a..10 + 2 * a].copy_from_slice(&reference[a]);
        }
        v
    }

    #[test]
    fn tangent_matches_central_differences_in_stick_and_in_slip() {
        let same = [[20.0, 3.0], [22.0, 4.2], [21.05, 3.85]];
        // the neighbouring edge before this one (sharing its start node), curved too
        let before = [[18.1, 2.0], [20.0, 3.0], [19.0, 2.6]];
        for (reference, xi_ref, what) in [(same, 0.25, "on the same edge"), (before, 0.8, "from the edge before")] {
            let v = configuration(reference);
            // stick: a soft tangential penalty well inside the cone (p = 400 MPa, mu p the same);
            // slip: mu small
            let stick = FrictionLaw { coefficient: 1.0, penalty: 5.0, elastic_slip: None };
            let slip = FrictionLaw { coefficient: 0.1, penalty: 1e4, elastic_slip: None };
            for traction in [0.0, 30.0] {
                let from = SlipReference { xi: xi_ref, traction };
                let e = fd_error(v, &from, &stick, false);
                assert!(e <= 1e-6, "stick {what}, tau_n {traction}: {e:e}");
                let e = fd_error(v, &from, &slip, true);
                assert!(e <= 1e-6, "slip {what}, tau_n {traction}: {e:e}");
                // eps_T = mu p / gamma: its derivative through the pressure, in stick and slip
                let e = fd_error(v, &from, &FrictionLaw { elastic_slip: Some(20.0), ..stick }, false);
                assert!(e <= 1e-6, "stick with an elastic slip {what}, tau_n {traction}: {e:e}");
                let e = fd_error(v, &from, &FrictionLaw { elastic_slip: Some(1e-4), ..slip }, true);
                assert!(e <= 1e-6, "slip with an elastic slip {what}, tau_n {traction}: {e:e}");
            }
        }
    }

    #[test]
    fn the_return_map_sticks_below_the_cone_and_slides_on_it() {
        // straight master along r, its outward normal (t_z, -t_r) = -z: a slave 0.01 above it
        // at r = 1.3 penetrates, p = eps 0.01 = 200 MPa
        let x = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.0]];
        let xs = [1.3, 0.01];
        let law = ContactLaw::linear(1.0, 2e4, 0.0, FREE);
        let xi = project_on_edge(xs, &x).unwrap().xi;
        assert!((xi - 0.3).abs() < 1e-12);
        let friction = FrictionLaw { coefficient: 0.3, penalty: 1e3, elastic_slip: None };
        // reference material point at r = 1.25: slip 0.05, trial 50 MPa < mu p = 60: stick
        let from = SlipReference { xi: 0.25, traction: 0.0 };
        let (f, state) = friction_residual(xs, &x, &x, xi, &from, &law, &friction);
        assert!(!state.slipping && (state.traction - 50.0).abs() < 1e-9, "{state:?}");
        assert!((f[0] - 50.0).abs() < 1e-9 && f[1].abs() < 1e-12, "force on the slave -tau A t: residual +50 in r");
        assert!((f[2] + f[4] + f[6] + 50.0).abs() < 1e-9, "the reaction on the master balances it");
        // reference at r = 1.2: trial 100 > 60: slip at mu p, in the trial's direction
        let (_, state) = friction_residual(xs, &x, &x, xi, &SlipReference { xi: 0.2, traction: 0.0 }, &law, &friction);
        assert!(state.slipping && (state.traction - 60.0).abs() < 1e-9, "{state:?}");
        let (_, state) = friction_residual(xs, &x, &x, xi, &SlipReference { xi: 0.4, traction: 0.0 }, &law, &friction);
        assert!(state.slipping && (state.traction + 60.0).abs() < 1e-9, "{state:?}");
        // an elastic slip of 0.1: eps_T = mu p / 0.1 = 600 MPa/mm, so a slip of 0.05 sticks at
        // 30 MPa, half the limit, and one of 0.15 goes past it
        let elastic = FrictionLaw { elastic_slip: Some(0.1), ..friction };
        let (_, state) = friction_residual(xs, &x, &x, xi, &from, &law, &elastic);
        assert!(!state.slipping && (state.traction - 30.0).abs() < 1e-9, "{state:?}");
        let (_, state) = friction_residual(xs, &x, &x, xi, &SlipReference { xi: 0.15, traction: 0.0 }, &law, &elastic);
        assert!(state.slipping && (state.traction - 60.0).abs() < 1e-9, "{state:?}");
    }
}

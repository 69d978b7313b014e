//! The three-node slide-line element: slave node s against master segment (1, 2).
//!
//! Kinematics, eqs. (1)-(3): t = (x2 - x1) / l, a = (x_s - x1) . t / l, g_n = (x_s - x1) . n,
//! with n = (t_z, -t_r) the master's outward normal (the tangent turned clockwise; master
//! segments run counter-clockwise around their body). Penetration is g_n < 0.
//!
//! Penalty, eqs. (4)-(6), with the contact pressure p = max(0, lambda - eps g_n) (lambda the
//! augmented-Lagrangian multiplier, 0 for pure penalty) acting on the slave node's tributary
//! area A:
//!   residual  f = dPi/dx = -p A N_s,            N_s = [n, -(1 - a) n, -a n]
//!   tangent   K = A (eps N_s N_s^T - p H),      H = d^2 g_n / dx^2
//!             H = -(1/l) (T_s N^T + N T_s^T) - (g_n / l^2) N N^T,
//!             T_s = [t, -(1 - a) t, -a t],      N = [0, -n, n].
//! For pure penalty (p = -eps g_n) this is eq. (6):
//!   K = eps A [N_s N_s^T - (g_n / l) (T_s N^T + N T_s^T + (g_n / l) N N^T)].
//! DOF order: [s_r, s_z, 1_r, 1_z, 2_r, 2_z].

use nalgebra::{SMatrix, SVector};

pub type ContactVector = SVector<f64, 6>;
pub type ContactMatrix = SMatrix<f64, 6, 6>;

/// Geometry of a slave node against one master segment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Projection {
    /// Surface coordinate of the projection, eq. (2): 0 at node 1, 1 at node 2.
    pub a: f64,
    /// Normal gap, eq. (3): negative when penetrating.
    pub gap: f64,
    /// Current segment length.
    pub length: f64,
    pub tangent: [f64; 2],
    pub normal: [f64; 2],
}

/// Projects slave position `xs` onto the segment `x1 -> x2`. None for a degenerate segment.
pub fn project(xs: [f64; 2], x1: [f64; 2], x2: [f64; 2]) -> Option<Projection> {
    let d = [x2[0] - x1[0], x2[1] - x1[1]];
    let length = (d[0] * d[0] + d[1] * d[1]).sqrt();
    if length.is_nan() || length <= 0.0 || !length.is_finite() {
        return None;
    }
    let t = [d[0] / length, d[1] / length];
    let n = [t[1], -t[0]];
    let v = [xs[0] - x1[0], xs[1] - x1[1]];
    Some(Projection { a: (v[0] * t[0] + v[1] * t[1]) / length, gap: v[0] * n[0] + v[1] * n[1], length, tangent: t, normal: n })
}

/// Contact pressure p = max(0, lambda - eps g): the penalty (plus multiplier) pressure.
pub fn contact_pressure(gap: f64, penalty: f64, multiplier: f64) -> f64 {
    (multiplier - penalty * gap).max(0.0)
}

/// Residual and tangent of one slave node on one segment, for tributary area `area`, penalty
/// `penalty` (pressure per unit penetration) and multiplier `multiplier`. Both are zero when
/// the contact is open (lambda - eps g < 0).
pub fn residual_and_tangent(p: &Projection, area: f64, penalty: f64, multiplier: f64) -> (ContactVector, ContactMatrix, f64) {
    // Closed at zero gap: the tangent is on with zero force, so a body resting on contact
    // alone is supported from the first iteration.
    if multiplier - penalty * p.gap < 0.0 {
        return (ContactVector::zeros(), ContactMatrix::zeros(), 0.0);
    }
    let pressure = contact_pressure(p.gap, penalty, multiplier);
    let (n, t, a, l) = (p.normal, p.tangent, p.a, p.length);
    let ns = ContactVector::from([n[0], n[1], -(1.0 - a) * n[0], -(1.0 - a) * n[1], -a * n[0], -a * n[1]]);
    let ts = ContactVector::from([t[0], t[1], -(1.0 - a) * t[0], -(1.0 - a) * t[1], -a * t[0], -a * t[1]]);
    let nn = ContactVector::from([0.0, 0.0, -n[0], -n[1], n[0], n[1]]);
    let hessian = -(ts * nn.transpose() + nn * ts.transpose()) / l - nn * nn.transpose() * (p.gap / (l * l));
    let residual = ns * (-pressure * area);
    let tangent = (ns * ns.transpose() * penalty - hessian * pressure) * area;
    (residual, tangent, pressure)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Central-difference check of the tangent against the residual for positions `x`.
    fn fd_error(x: [f64; 6], area: f64, eps: f64, lambda: f64) -> f64 {
        let eval = |x: [f64; 6]| {
            let p = project([x[0], x[1]], [x[2], x[3]], [x[4], x[5]]).unwrap();
            residual_and_tangent(&p, area, eps, lambda)
        };
        let (_, k, pressure) = eval(x);
        assert!(pressure > 0.0, "the test state must be in contact");
        let scale = k.abs().max();
        let h = 1e-7;
        let mut worst = 0.0f64;
        for j in 0..6 {
            let (mut xp, mut xm) = (x, x);
            xp[j] += h;
            xm[j] -= h;
            let col = (eval(xp).0 - eval(xm).0) / (2.0 * h);
            worst = worst.max((col - k.column(j)).abs().max() / scale);
        }
        worst
    }

    #[test]
    fn geometry_of_a_rotated_segment() {
        // segment along +r: outward normal -z; a node 0.1 below it penetrates by 0.1
        let p = project([3.0, -0.1], [2.0, 0.0], [6.0, 0.0]).unwrap();
        assert!((p.a - 0.25).abs() < 1e-15 && (p.gap - 0.1).abs() < 1e-15);
        let p = project([3.0, 0.1], [2.0, 0.0], [6.0, 0.0]).unwrap();
        assert!((p.gap + 0.1).abs() < 1e-15, "above a +r segment is inside its body");
    }

    #[test]
    fn tangent_matches_central_differences_in_general_position_and_near_an_end() {
        // rotated segment, slave off-centre, moderate penetration (relative to length 2.2)
        let (x1, x2) = ([10.0, 4.0], [11.9, 5.1]);
        let p = project([10.5, 4.6], x1, x2).unwrap();
        assert!(p.gap < 0.0 && p.a > 0.1 && p.a < 0.6, "{p:?}");
        let x = [10.5, 4.6, x1[0], x1[1], x2[0], x2[1]];
        for lambda in [0.0, 35.0] {
            let e = fd_error(x, 0.7, 2.0e4, lambda);
            assert!(e <= 1e-6, "general position, lambda {lambda}: {e:e}");
        }
        // near the end: a close to 1
        // a = 0.995, penetration 0.02: x_s = x1 + 0.995 (x2 - x1) - 0.02 n
        let q = project(x1, x1, x2).unwrap();
        let xs = [x1[0] + 0.995 * (x2[0] - x1[0]) - 0.02 * q.normal[0], x1[1] + 0.995 * (x2[1] - x1[1]) - 0.02 * q.normal[1]];
        let p = project(xs, x1, x2).unwrap();
        assert!(p.gap < 0.0 && p.a > 0.99 && p.a < 1.0, "{p:?}");
        let e = fd_error([xs[0], xs[1], x1[0], x1[1], x2[0], x2[1]], 0.7, 2.0e4, 0.0);
        assert!(e <= 1e-6, "near the end: {e:e}");
    }

    #[test]
    fn pure_penalty_tangent_is_equation_6() {
        let (x1, x2, xs) = ([0.0, 0.0], [2.0, 1.0], [0.8, 0.7]);
        let p = project(xs, x1, x2).unwrap();
        let (eps, area) = (1e3, 1.3);
        let (_, k, _) = residual_and_tangent(&p, area, eps, 0.0);
        let (n, t, a, l, g) = (p.normal, p.tangent, p.a, p.length, p.gap);
        let ns = ContactVector::from([n[0], n[1], -(1.0 - a) * n[0], -(1.0 - a) * n[1], -a * n[0], -a * n[1]]);
        let ts = ContactVector::from([t[0], t[1], -(1.0 - a) * t[0], -(1.0 - a) * t[1], -a * t[0], -a * t[1]]);
        let nn = ContactVector::from([0.0, 0.0, -n[0], -n[1], n[0], n[1]]);
        let eq6 = (ns * ns.transpose() - (ts * nn.transpose() + nn * ts.transpose() + nn * nn.transpose() * (g / l)) * (g / l)) * (eps * area);
        assert!((k - eq6).abs().max() < 1e-12 * eq6.abs().max());
        // and the residual is eq. (5) times the area: G_n = -eps g N_s (as a force on the nodes)
        let (f, _, pressure) = residual_and_tangent(&p, area, eps, 0.0);
        assert!((pressure + eps * g).abs() < 1e-12);
        assert!((f - ns * (eps * g * area)).abs().max() < 1e-12);
    }

    #[test]
    fn open_contact_gives_nothing() {
        let p = project([1.0, -0.5], [0.0, 0.0], [2.0, 0.0]).unwrap();
        let (f, k, pressure) = residual_and_tangent(&p, 1.0, 1e4, 0.0);
        assert_eq!(pressure, 0.0);
        assert_eq!(f, ContactVector::zeros());
        assert_eq!(k, ContactMatrix::zeros());
    }
}

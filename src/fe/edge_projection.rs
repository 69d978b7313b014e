//! The closest point of a quadratic (three-node) edge to a point: contact's slave-node search
//! and a tie's projections both stand on it.

/// A slave node projected on a master edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeProjection {
    /// Edge coordinate of the closest point (-1 start, 1 end); may lie outside [-1, 1].
    pub xi: f64,
    /// Normal gap, negative when penetrating.
    pub gap: f64,
    pub normal: [f64; 2],
    /// Distance from the slave node to the nearest point of the edge (xi clamped to [-1, 1]).
    pub distance: f64,
}

/// Closest point of the edge curve to `xs` (Newton from the chord projection). None when the
/// edge is degenerate or the projection does not converge.
pub fn project_on_edge(xs: [f64; 2], x: &[[f64; 2]; 3]) -> Option<EdgeProjection> {
    let chord = [x[1][0] - x[0][0], x[1][1] - x[0][1]];
    let l2 = chord[0] * chord[0] + chord[1] * chord[1];
    if l2.is_nan() || l2 <= 0.0 || !l2.is_finite() {
        return None;
    }
    let mut xi = 2.0 * ((xs[0] - x[0][0]) * chord[0] + (xs[1] - x[0][1]) * chord[1]) / l2 - 1.0;
    // The curve as x_mid + b xi + c xi^2 seen from the slave point, d(xi) = d0 - b xi - c xi^2:
    // the projection equation r = d . x' is then the cubic k0 + k1 xi + k2 xi^2 + k3 xi^3,
    // a few operations per Newton step, and its coefficients are differences of nearby
    // points rather than of positions of size |x|.
    let (d0, b, c) = ([0, 1].map(|i| xs[i] - x[2][i]), [0, 1].map(|i| 0.5 * chord[i]), [0, 1].map(|i| 0.5 * (x[0][i] + x[1][i]) - x[2][i]));
    let dot = |u: [f64; 2], v: [f64; 2]| u[0] * v[0] + u[1] * v[1];
    let k = [dot(d0, b), 2.0 * dot(d0, c) - dot(b, b), -3.0 * dot(b, c), -2.0 * dot(c, c)];
    // r cannot be resolved below about eps |x| |x'| however well converged xi is (the slave
    // point and the edge are known to eps |x|; far from the origin that floor is 1e-13 and
    // more, above any fixed tolerance on the step)
    let size = xs[0].abs().max(xs[1].abs()) + x.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut converged = false;
    for _ in 0..30 {
        let r = k[0] + xi * (k[1] + xi * (k[2] + xi * k[3]));
        let dr = k[1] + xi * (2.0 * k[2] + xi * 3.0 * k[3]);
        if dr >= 0.0 || !dr.is_finite() {
            return None; // not a minimum of the distance: a badly curved edge
        }
        let step = r / dr;
        xi -= step;
        let floor = 64.0 * f64::EPSILON * size * dr.abs().sqrt();
        if step.abs() < 1e-14 * (1.0 + xi.abs()) || r.abs() <= floor {
            converged = true;
            break;
        }
    }
    if !converged || xi.abs() > 10.0 {
        return None;
    }
    let offset = |xi: f64| [0, 1].map(|i| d0[i] - xi * (b[i] + xi * c[i]));
    let t = [0, 1].map(|i| b[i] + 2.0 * xi * c[i]);
    let lt = dot(t, t).sqrt(); // not hypot: see search::box_distance
    let normal = [t[1] / lt, -t[0] / lt];
    let gap = dot(offset(xi), normal);
    let d = offset(xi.clamp(-1.0, 1.0));
    let distance = dot(d, d).sqrt();
    Some(EdgeProjection { xi, gap, normal, distance })
}

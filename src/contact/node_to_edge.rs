//! The slide line on quadratic element edges: a slave node s against a 3-node master edge
//! (start 1, end 2, middle 3), the edge being the curve x(xi) = sum N_k(xi) x_k, xi in [-1, 1].
//!
//! This is eqs. (1)-(6) of the seed paper generalised from straight two-node segments to the
//! edges of the quadratic elements: the projection xi is the closest point on the curve,
//! t = x'(xi) / |x'(xi)|, n = (t_z, -t_r) the outward normal, g_n = (x_s - x(xi)) . n, and since
//! x_s - x(xi) is parallel to n at the closest point,
//!   delta g_n = n . (delta x_s - sum N_k(xi) delta x_k),
//! so the penalty residual is f = -p A [n, -N_1 n, -N_2 n, -N_3 n] with p = p(g) the pair's
//! pressure-overclosure law (`Overclosure`: p = max(0, lambda - eps g), or exponential).
//! On a straight edge whose middle node sits at the chord midpoint, t, a = (1 + xi) / 2 and g_n
//! are exactly eqs. (1)-(3) on the chord; with the middle node tied to the midpoint the
//! residual and tangent reduce exactly to eqs. (5)-(6) (tested below against
//! `slideline::residual_and_tangent`). The difference is the reactions on the master: the
//! quadratic edge receives them with its own shape functions (1:4:1-consistent), which is what
//! lets two-pass contact between quadratic elements pass the patch test; straight segments
//! through corner and middle nodes hand them out linearly, and then cannot.
//!
//! The tangent is the exact derivative of this residual, computed with dual numbers; the
//! projection's dependence on the nodes enters through one Newton step of the projection
//! equation taken in dual arithmetic at the converged xi (the implicit function theorem).
//! DOF order: [s_r, s_z, 1_r, 1_z, 2_r, 2_z, 3_r, 3_z].

use crate::ad::{Dual, Scalar};
use crate::fe::section::Section;
use nalgebra::{SMatrix, SVector};

pub type EdgeVector = SVector<f64, 8>;
pub type EdgeMatrix = SMatrix<f64, 8, 8>;

/// How far (in edge coordinate; 0.1 = 5 % of the edge) a master surface reaches past its free
/// ends. Where slave and master end together (tubes of equal length), a slave end node sits
/// exactly on the master's end, and without this it would be lost and found again on
/// alternate Newton iterations as the bodies slide by round-off.
pub const FREE_END_EXTENSION: f64 = 0.1;

// the closest point of an edge is geometry, below contact (a tie's projections use it too)
pub use crate::fe::edge_projection::{project_on_edge, EdgeProjection};

fn curve<T: Scalar>(x: &[[T; 2]; 3], xi: T) -> ([T; 2], [T; 2], [T; 2]) {
    // line3 with a Scalar argument: N = [xi (xi - 1) / 2, xi (xi + 1) / 2, 1 - xi^2]
    let n = [xi * (xi - 1.0) * 0.5, xi * (xi + 1.0) * 0.5, -(xi * xi) + 1.0];
    let dn = [xi - 0.5, xi + 0.5, xi * -2.0];
    let ddn = [1.0, 1.0, -2.0];
    let pos = std::array::from_fn(|i| x[0][i] * n[0] + x[1][i] * n[1] + x[2][i] * n[2]);
    let tan = std::array::from_fn(|i| x[0][i] * dn[0] + x[1][i] * dn[1] + x[2][i] * dn[2]);
    let curv = std::array::from_fn(|i| x[0][i] * ddn[0] + x[1][i] * ddn[1] + x[2][i] * ddn[2]);
    (pos, tan, curv)
}

/// Projection equation r(xi) = (x_s - x(xi)) . x'(xi) and its xi-derivative.
fn projection_equation<T: Scalar>(xs: &[T; 2], x: &[[T; 2]; 3], xi: T) -> (T, T) {
    let (p, t, c) = curve(x, xi);
    let d = [xs[0] - p[0], xs[1] - p[1]];
    (d[0] * t[0] + d[1] * t[1], d[0] * c[0] + d[1] * c[1] - (t[0] * t[0] + t[1] * t[1]))
}

/// The contact point of the slave node at `xs` on the edge `x`: edge coordinate, master shape
/// functions there, unit tangent, outward normal and contact pressure
/// p = (lambda - eps g) w(xi) (w the free-end taper). Generic, so the dual version carries the
/// derivatives: the projection's dependence on the nodes enters through one Newton step of the
/// projection equation at the converged `xi_converged` (value unchanged, derivative
/// -r_x / r_xi by the implicit function theorem).
pub(crate) struct ContactPoint<T> {
    pub shape: [T; 3],
    pub tangent: [T; 2],
    pub normal: [T; 2],
    pub pressure: T,
    /// The area the pressure acts on (per radian, or over the thickness): the law's
    /// (`ContactLaw::area`), times the master face's at the point for a node of a node-based
    /// slave surface (`SlaveArea::MasterFace`).
    pub area: T,
}

pub(crate) fn contact_point<T: Scalar>(xs: &[T; 2], x: &[[T; 2]; 3], xi_converged: f64, law: &ContactLaw) -> ContactPoint<T> {
    let xi0 = T::from_f64(xi_converged);
    let (r, dr) = projection_equation(xs, x, xi0);
    let xi = xi0 - r / T::from_f64(dr.re());
    let (p, t, _) = curve(x, xi);
    let lt = (t[0] * t[0] + t[1] * t[1]).sqrt();
    let tangent = [t[0] / lt, t[1] / lt];
    let normal = [tangent[1], -tangent[0]];
    let gap = (xs[0] - p[0]) * normal[0] + (xs[1] - p[1]) * normal[1];
    let pressure = law.normal.pressure(gap) * end_taper(xi, law.free_ends); // the caller ensures >= 0
    let shape = [xi * (xi - 1.0) * 0.5, xi * (xi + 1.0) * 0.5, -(xi * xi) + 1.0];
    let area = match law.slave_area {
        SlaveArea::Tributary => T::from_f64(law.area),
        SlaveArea::MasterFace(section) => master_face_area(section, lt, p[0]) * law.area,
    };
    ContactPoint { shape, tangent, normal, pressure, area }
}

/// The area of the master face at a point of the edge where |dx/dxi| is `jacobian` and the
/// radius `r`: 2 |dx/dxi| times the section's measure there (per radian in axisymmetry, r; the
/// thickness in a plane section). It is the whole face's area on a straight edge with its
/// middle node at the middle, CalculiX's 4 |dx/dxi x dx/deta| of the face it expands the edge
/// to, per radian.
pub fn master_face_area<T: Scalar>(section: Section, jacobian: T, r: T) -> T {
    jacobian * 2.0 * (r * section.measure_slope() + section.measure(0.0))
}

/// Residual f = -p A [n, -N_k n] of the slave node at `xs` on the edge `x`, with `xi` the
/// converged projection; generic so the dual version gives the tangent.
fn residual<T: Scalar>(xs: &[T; 2], x: &[[T; 2]; 3], xi_converged: f64, law: &ContactLaw) -> [T; 8] {
    let ContactPoint { shape, normal: n, pressure, area, .. } = contact_point(xs, x, xi_converged, law);
    let c = -(pressure * area);
    [
        n[0] * c,
        n[1] * c,
        -(shape[0] * n[0] * c),
        -(shape[0] * n[1] * c),
        -(shape[1] * n[0] * c),
        -(shape[1] * n[1] * c),
        -(shape[2] * n[0] * c),
        -(shape[2] * n[1] * c),
    ]
}

/// Weight of the contact force of a slave node projecting past a free end of the master
/// surface (`free_ends` = [start free, end free]): 1 on the edge, falling smoothly to 0 at
/// FREE_END_EXTENSION past the end, so a node sliding off the surface lets go gradually
/// instead of dropping its force in one iteration (which makes Newton cycle). Generic: its
/// derivative enters the tangent.
pub(crate) fn end_taper<T: Scalar>(xi: T, free_ends: [bool; 2]) -> T {
    let over = if free_ends[0] && xi.re() < -1.0 {
        -xi - 1.0
    } else if free_ends[1] && xi.re() > 1.0 {
        xi - 1.0
    } else {
        return T::from_f64(1.0);
    };
    if over.re() >= FREE_END_EXTENSION {
        T::from_f64(0.0)
    } else {
        // smoothstep 1 - 3 s^2 + 2 s^3: no kink where the taper starts (slave end nodes of
        // equal-length bodies sit exactly there) or where it ends
        let s = over / FREE_END_EXTENSION;
        s * s * (s * 2.0 - 3.0) + 1.0
    }
}

/// The pressure-overclosure law: the contact pressure p (MPa) as a function of the normal gap
/// g (mm, negative when penetrating).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Overclosure {
    /// p = lambda - eps g: the penalty eps (MPa/mm) plus the augmented-Lagrangian multiplier
    /// lambda (0 for a pure penalty); open where that is negative.
    Linear { penalty: f64, multiplier: f64 },
    /// CalculiX's exponential law (ccx 2.20 manual, *SURFACE BEHAVIOR; springforc_n2f.f):
    /// p = p0 exp(-beta g) with beta = ln(100) / c0, so p0 at touch and p0 / 100 at the
    /// clearance c0, rising exponentially with penetration. Not Abaqus' law of the same name,
    /// which is zero at c0.
    Exponential { clearance: f64, pressure: f64 },
}

/// Past this clearance, in units of c0, the exponential law is open: p < 1e-6 p0 there, and
/// a node dropping that force is no jump Newton can see.
const EXPONENTIAL_REACH: f64 = 3.0;
/// Beyond an exponent of beta |g| = 30 (p = 1e13 p0, a penetration no converged state has)
/// the exponential continues along its tangent, so a wild Newton iterate cannot overflow.
const EXPONENT_CAP: f64 = 30.0;

impl Overclosure {
    /// beta = ln(100) / c0, the exponential law's decay rate (1/mm).
    fn decay(clearance: f64) -> f64 {
        100f64.ln() / clearance
    }

    /// The pressure at gap `g`, before the free-end taper; for the linear law negative where
    /// open. Generic: its derivative enters the tangent.
    pub fn pressure<T: Scalar>(&self, gap: T) -> T {
        match *self {
            Self::Linear { penalty, multiplier } => -(gap * penalty) + multiplier,
            Self::Exponential { clearance, pressure } => {
                let x = gap * -Self::decay(clearance);
                if x.re() <= EXPONENT_CAP {
                    x.exp() * pressure
                } else {
                    (x - (EXPONENT_CAP - 1.0)) * (pressure * EXPONENT_CAP.exp())
                }
            }
        }
    }

    /// Whether the law acts at gap `g` (closed at zero gap).
    pub fn is_closed(&self, gap: f64) -> bool {
        match *self {
            Self::Linear { .. } => self.pressure(gap) >= 0.0,
            Self::Exponential { clearance, .. } => gap < EXPONENTIAL_REACH * clearance,
        }
    }

    /// dp / d(-g) at gap `g`, MPa/mm: the normal stiffness per unit area (the scale of the
    /// round-off in the contact forces).
    pub fn stiffness(&self, gap: f64) -> f64 {
        match *self {
            Self::Linear { penalty, .. } => penalty,
            Self::Exponential { clearance, .. } => Self::decay(clearance) * self.pressure(gap.max(-EXPONENT_CAP / Self::decay(clearance))),
        }
    }

    /// Elastic energy stored per unit area (N/mm) at gap `g` under the (tapered) pressure
    /// `p`: -g p / 2 for the linear law (eps g^2 / 2 for a penalty), the integral of p from g
    /// to infinity, p / beta, for the exponential law.
    pub fn stored_energy(&self, gap: f64, pressure: f64) -> f64 {
        match *self {
            Self::Linear { .. } => -0.5 * gap * pressure,
            Self::Exponential { clearance, .. } => pressure / Self::decay(clearance),
        }
    }
}

/// The area a slave node's pressure acts on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SlaveArea {
    /// `ContactLaw::area`: the node's tributary area on its own surface.
    Tributary,
    /// The area of the master face it meets, times `ContactLaw::area`: CalculiX's rule for a
    /// node-based slave surface (springforc_n2f.f gives a slave node without a face of its own
    /// the master face's area). `section` is the master element's.
    MasterFace(Section),
}

/// The contact law of one slave node: its area, the pressure-overclosure law, and which ends
/// of the master surface are free (the force tapers off past them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactLaw {
    /// The tributary area, or the master face's multiplier (`slave_area`).
    pub area: f64,
    pub slave_area: SlaveArea,
    pub normal: Overclosure,
    pub free_ends: [bool; 2],
}

impl ContactLaw {
    /// The linear law p = lambda - eps g over tributary area `area`.
    pub fn linear(area: f64, penalty: f64, multiplier: f64, free_ends: [bool; 2]) -> Self {
        Self { area, slave_area: SlaveArea::Tributary, normal: Overclosure::Linear { penalty, multiplier }, free_ends }
    }

    /// The area the pressure acts on at edge coordinate `xi` of the master edge `x` (the
    /// value of [`ContactPoint::area`]).
    pub fn area_at(&self, x: &[[f64; 2]; 3], xi: f64) -> f64 {
        match self.slave_area {
            SlaveArea::Tributary => self.area,
            SlaveArea::MasterFace(section) => {
                let (p, t, _) = curve(x, xi);
                master_face_area(section, t[0].hypot(t[1]), p[0]) * self.area
            }
        }
    }

    /// The contact pressure at `proj`, None when the contact is open (closed at zero gap).
    fn pressure(&self, proj: &EdgeProjection) -> Option<f64> {
        self.normal.is_closed(proj.gap).then(|| self.normal.pressure(proj.gap) * end_taper(proj.xi, self.free_ends))
    }
}

/// Residual, tangent and contact pressure of one slave node on one master edge; all zero
/// when the contact is open.
pub fn edge_residual_and_tangent(xs: [f64; 2], x: &[[f64; 2]; 3], proj: &EdgeProjection, law: &ContactLaw) -> (EdgeVector, EdgeMatrix, f64) {
    let Some(pressure) = law.pressure(proj) else {
        return (EdgeVector::zeros(), EdgeMatrix::zeros(), 0.0);
    };
    let v = |k: usize, c: usize| Dual::<8>::variable(if k == 0 { xs[c] } else { x[k - 1][c] }, 2 * k + c);
    let xs_d = [v(0, 0), v(0, 1)];
    let x_d = [[v(1, 0), v(1, 1)], [v(2, 0), v(2, 1)], [v(3, 0), v(3, 1)]];
    let f = residual(&xs_d, &x_d, proj.xi, law);
    let force = EdgeVector::from_fn(|i, _| f[i].re);
    let tangent = EdgeMatrix::from_fn(|i, j| f[i].eps[j]);
    (force, tangent, pressure)
}

/// The residual and contact pressure of [`edge_residual_and_tangent`] without the tangent
/// (residual-only evaluations: the line search's).
pub fn edge_residual(xs: [f64; 2], x: &[[f64; 2]; 3], proj: &EdgeProjection, law: &ContactLaw) -> (EdgeVector, f64) {
    match law.pressure(proj) {
        Some(pressure) => (EdgeVector::from(residual(&xs, x, proj.xi, law)), pressure),
        None => (EdgeVector::zeros(), 0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::slideline;
    use crate::fe::shape::line3;

    fn flatten(xs: [f64; 2], x: &[[f64; 2]; 3]) -> [f64; 8] {
        [xs[0], xs[1], x[0][0], x[0][1], x[1][0], x[1][1], x[2][0], x[2][1]]
    }

    /// Both ends of the test edges are free (the taper acts past them).
    const FREE: [bool; 2] = [true, true];

    /// The slave node `depth` inside the edge `x` at `xi` (outside for a negative depth), with
    /// the edge, as the 8 unknowns.
    fn inside(x: &[[f64; 2]; 3], xi: f64, depth: f64) -> [f64; 8] {
        let (pos, t, _) = curve(x, xi);
        let l = t[0].hypot(t[1]);
        flatten([pos[0] - depth * t[1] / l, pos[1] + depth * t[0] / l], x)
    }

    /// The largest difference between a column of `law`'s tangent at `v` and its central
    /// difference, relative to the tangent's largest entry; and the contact pressure at `v`.
    fn law_fd_error(law: &ContactLaw, v: [f64; 8]) -> (f64, f64) {
        let at = |v: &[f64; 8]| {
            let xs = [v[0], v[1]];
            let x = [[v[2], v[3]], [v[4], v[5]], [v[6], v[7]]];
            let p = project_on_edge(xs, &x).unwrap();
            edge_residual_and_tangent(xs, &x, &p, law)
        };
        let (_, k, pressure) = at(&v);
        let h = 1e-7;
        let worst = (0..8)
            .map(|j| {
                let (mut a, mut b) = (v, v);
                a[j] += h;
                b[j] -= h;
                ((at(&a).0 - at(&b).0) / (2.0 * h) - k.column(j)).abs().max() / k.abs().max()
            })
            .fold(0.0, f64::max);
        (worst, pressure)
    }

    fn fd_error(v: [f64; 8], lambda: f64) -> f64 {
        let (worst, pressure) = law_fd_error(&ContactLaw::linear(0.8, 3e4, lambda, FREE), v);
        assert!(pressure > 0.0);
        worst
    }

    #[test]
    fn tangent_matches_central_differences_on_a_curved_rotated_edge_and_near_its_end() {
        // curved edge: middle node off the chord
        let x = [[20.0, 3.0], [22.0, 4.2], [21.05, 3.85]];
        // points penetrating by 0.03 below the curve at xi = 0.2 and xi = 0.97
        let inside = |xi: f64| {
            let (pos, t, _) = curve(&x, xi);
            let l = t[0].hypot(t[1]);
            [pos[0] - 0.03 * t[1] / l, pos[1] + 0.03 * t[0] / l]
        };
        for (xs, what) in [(inside(0.2), "general position"), (inside(0.97), "near the end"), (inside(1.04), "past a free end, tapered")] {
            let p = project_on_edge(xs, &x).unwrap();
            assert!(p.gap < 0.0, "{what}: {p:?}");
            for lambda in [0.0, 40.0] {
                let e = fd_error(flatten(xs, &x), lambda);
                assert!(e <= 1e-6, "{what}, lambda {lambda}: {e:e}");
            }
        }
    }

    #[test]
    fn the_residual_only_path_is_the_kernels_residual() {
        let x = [[20.0, 3.0], [22.0, 4.2], [21.05, 3.85]];
        // penetrating (above the curve), past the free end (tapered) and open (below)
        for xs in [[20.9, 3.8], [22.05, 4.35], [20.9, 3.4]] {
            let p = project_on_edge(xs, &x).unwrap();
            for lambda in [0.0, 40.0] {
                let law = ContactLaw::linear(0.8, 3e4, lambda, FREE);
                let (f, _, pressure) = edge_residual_and_tangent(xs, &x, &p, &law);
                let (g, q) = edge_residual(xs, &x, &p, &law);
                assert_eq!(pressure, q);
                assert!((f - g).abs().max() <= 1e-14 * f.abs().max().max(1.0), "{xs:?}: {f} vs {g}");
            }
        }
    }

    #[test]
    fn projection_is_the_closest_point_of_the_curve() {
        let x = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.3]];
        let xs = [0.7, 0.1];
        let p = project_on_edge(xs, &x).unwrap();
        let dist = |xi: f64| {
            let (n, _) = line3(xi);
            let q = [0, 1].map(|i| (0..3).map(|k| n[k] * x[k][i]).sum::<f64>());
            (xs[0] - q[0]).hypot(xs[1] - q[1])
        };
        for d in [-1e-4, 1e-4] {
            assert!(dist(p.xi + d) > dist(p.xi));
        }
        assert!((p.gap.abs() - dist(p.xi)).abs() < 1e-12);
    }

    #[test]
    fn a_point_on_a_curved_edge_far_from_the_origin_projects_onto_it() {
        // a bellows root torus (radius 6 about (167, 200)): every point of the curve, given
        // as a slave point, must project onto its own edge with zero gap. With a fixed
        // tolerance on the step, round-off in the projection equation (eps |x| ~ 4e-14 here)
        // kept Newton from "converging", the edge was rejected and a neighbour's extrapolated
        // curve taken instead, with a spurious gap of 0.07 mm.
        let arc = |a: f64| [167.0 + 6.0 * a.cos(), 200.0 + 6.0 * a.sin()];
        let x = [arc(3.3), arc(3.6), arc(3.45)];
        for k in 0..=20 {
            let xi = -1.0 + 0.1 * k as f64;
            let (n, _) = line3(xi);
            let xs = [0, 1].map(|i| (0..3).map(|a| n[a] * x[a][i]).sum::<f64>());
            let p = project_on_edge(xs, &x).unwrap_or_else(|| panic!("xi {xi}: no projection"));
            assert!((p.xi - xi).abs() < 1e-10 && p.gap.abs() < 1e-12, "xi {xi}: {p:?}");
        }
    }

    #[test]
    fn a_straight_edge_with_its_middle_node_tied_is_the_paper_slide_line() {
        // x3 = (x1 + x2) / 2: chain rule P maps the 6 DOFs of eqs. (1)-(6) to our 8.
        let (x1, x2, xs) = ([10.0, 4.0], [11.9, 5.1], [10.5, 4.6]);
        let x = [x1, x2, [(x1[0] + x2[0]) / 2.0, (x1[1] + x2[1]) / 2.0]];
        let p = project_on_edge(xs, &x).unwrap();
        let q = slideline::project(xs, x1, x2).unwrap();
        assert!((p.gap - q.gap).abs() < 1e-14 && ((1.0 + p.xi) / 2.0 - q.a).abs() < 1e-14);
        let (area, eps) = (0.7, 2e4);
        let (f8, k8, p8) = edge_residual_and_tangent(xs, &x, &p, &ContactLaw::linear(area, eps, 0.0, [false, false]));
        let (f6, k6, p6) = slideline::residual_and_tangent(&q, area, eps, 0.0);
        assert!((p8 - p6).abs() < 1e-12 * p6);
        let mut tie = SMatrix::<f64, 8, 6>::zeros();
        for i in 0..6 {
            tie[(i, i)] = 1.0;
        }
        for c in 0..2 {
            tie[(6 + c, 2 + c)] = 0.5;
            tie[(6 + c, 4 + c)] = 0.5;
        }
        let f = tie.transpose() * f8;
        let k = tie.transpose() * k8 * tie;
        assert!((f - f6).abs().max() < 1e-10 * f6.abs().max(), "{f} vs {f6}");
        assert!((k - k6).abs().max() < 1e-10 * k6.abs().max(), "{k} vs {k6}");
    }

    /// CalculiX's exponential law (ccx 2.20 manual, *SURFACE BEHAVIOR): p0 at touch, p0 / 100
    /// at the clearance c0, 100 p0 at a penetration of c0; open past 3 c0; continued along its
    /// tangent past the exponent cap, without a jump in value or slope there.
    #[test]
    fn the_exponential_law_is_calculix_s() {
        let law = Overclosure::Exponential { clearance: 1e-4, pressure: 0.1 };
        let p = |g: f64| law.pressure(g);
        assert!((p(0.0) - 0.1).abs() < 1e-15);
        assert!((p(1e-4) - 1e-3).abs() < 1e-15);
        assert!((p(-1e-4) - 10.0).abs() < 1e-12);
        assert!(law.is_closed(2.9e-4) && !law.is_closed(3.1e-4));
        let beta = 100f64.ln() / 1e-4;
        let cap = -EXPONENT_CAP / beta;
        let h = 1e-12;
        assert!((p(cap - h) / p(cap + h) - 1.0).abs() < 1e-6, "continuous at the cap");
        let slope = |g: f64| (p(g - h) - p(g + h)) / (2.0 * h);
        assert!((slope(cap - 2.0 * h) / slope(cap + 2.0 * h) - 1.0).abs() < 1e-5, "no kink at the cap");
        assert!(p(-1.0).is_finite(), "a penetration of 1 mm stays finite: {}", p(-1.0));
        for g in [-2e-4, 0.0, 1e-4] {
            assert!((law.stiffness(g) / slope(g) - 1.0).abs() < 1e-5, "stiffness at {g}");
        }
    }

    #[test]
    fn the_exponential_tangent_matches_central_differences() {
        let x = [[20.0, 3.0], [22.0, 4.2], [21.05, 3.85]];
        let normal = Overclosure::Exponential { clearance: 0.02, pressure: 5.0 };
        let law = ContactLaw { area: 0.8, slave_area: SlaveArea::Tributary, normal, free_ends: FREE };
        // penetrating, at a small clearance (the law acts there too), and past a free end
        for (xi, depth) in [(0.2, 0.01), (-0.5, -0.015), (1.03, 0.005)] {
            let (worst, pressure) = law_fd_error(&law, inside(&x, xi, depth));
            assert!(pressure > 0.0, "xi {xi}: pressure {pressure}");
            assert!(worst <= 1e-6, "xi {xi}, depth {depth}: {worst:e}");
        }
    }

    /// CalculiX's node-based slave (springforc_n2f.f): a node bears with the area of the master
    /// face it meets. On a straight edge of length L with its middle node at the middle that is
    /// L r per radian at the point's radius r (L times the thickness in a plane section), and
    /// the tangent, whose area now moves with the master's nodes, matches central differences.
    #[test]
    fn a_node_based_slave_bears_with_the_master_face_area_and_its_tangent_is_exact() {
        let straight = [[20.0, 3.0], [22.0, 3.0], [21.0, 3.0]];
        for (section, measure) in [(Section::Axisymmetric, 20.5), (Section::PlaneStrain { thickness: 4.0 }, 4.0)] {
            let law = ContactLaw::linear(1.0, 3e4, 0.0, FREE);
            let law = ContactLaw { slave_area: SlaveArea::MasterFace(section), ..law };
            // 0.01 into the edge at r = 20.5 (xi = -0.5); its outward normal points down
            let xs = [20.5, 3.01];
            let p = project_on_edge(xs, &straight).unwrap();
            let (f, _, pressure) = edge_residual_and_tangent(xs, &straight, &p, &law);
            assert!((pressure - 300.0).abs() < 1e-9, "{pressure}");
            assert!((law.area_at(&straight, p.xi) - 2.0 * measure).abs() < 1e-12);
            assert!((f[1].abs() - pressure * 2.0 * measure).abs() < 1e-9, "{section:?}: the slave's force {} against p L r {}", f[1], pressure * 2.0 * measure);
        }
        let curved = [[20.0, 3.0], [22.0, 4.2], [21.05, 3.85]];
        let law = ContactLaw { slave_area: SlaveArea::MasterFace(Section::Axisymmetric), ..ContactLaw::linear(0.5, 3e4, 0.0, FREE) };
        for xi in [0.2, -0.7, 1.03] {
            let (worst, pressure) = law_fd_error(&law, inside(&curved, xi, 0.01));
            assert!(pressure > 0.0);
            assert!(worst <= 1e-6, "xi {xi}: {worst:e}");
        }
    }
}

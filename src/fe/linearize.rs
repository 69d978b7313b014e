//! Stress linearisation along a straight section through a wall (ASME Section VIII Division 2,
//! Part 5, Annex 5-A, the stress classification line): the membrane part of each stress
//! component is its mean over the section, the bending part the linear distribution with the
//! same first moment,
//!   sigma_m = (1/t) int_0^t sigma dx,   sigma_b = (6/t^2) int_0^t sigma (t/2 - x) dx,
//! sigma_b being the value at the section's start (x = 0; minus it at the end). The components
//! are taken in the section's own axes: `normal` along the section (through the wall),
//! `meridional` across it in the r-z plane, `hoop`, and the in-plane `shear`. The plain
//! (unweighted) integrals of Annex 5-A, equations (5.A.1) and (5.A.3); the radius-weighted form
//! for thick axisymmetric sections is not used.

use super::axisymmetric::von_mises;
use super::quadrature::{Integration, GAUSS2, GAUSS3};
use super::recover::{Recovery, Rule};
use super::shape::Shape;

/// A stress tensor in the section's axes: [normal, meridional, hoop, shear].
pub type SectionComponents = [f64; 4];

/// The linearised stresses of one section.
#[derive(Clone, Debug, PartialEq)]
pub struct Linearized {
    /// Section length (the wall thickness it crosses), mm.
    pub thickness: f64,
    pub membrane: SectionComponents,
    /// Bending at the start (the end takes the opposite sign).
    pub bending: SectionComponents,
    /// Von Mises stress of the membrane tensor, and of membrane + bending at the start and at
    /// the end.
    pub membrane_equivalent: f64,
    pub membrane_plus_bending_equivalent: [f64; 2],
    /// Total stress (section axes) at the start and at the end.
    pub total: [SectionComponents; 2],
}

/// Rotates the stress [rr, zz, tt, rz] into the axes of a section running along `d` (unit).
pub fn section_components(s: &[f64; 4], d: [f64; 2]) -> SectionComponents {
    let m = [-d[1], d[0]];
    let along = |u: [f64; 2], v: [f64; 2]| u[0] * (s[0] * v[0] + s[3] * v[1]) + u[1] * (s[3] * v[0] + s[1] * v[1]);
    [along(d, d), along(m, m), s[2], along(d, m)]
}

/// Back to [rr-like, zz-like, tt, rz-like] in the section's axes (normal as rr, meridional as
/// zz), for the von Mises stress, which does not care about the axes.
fn as_tensor(c: &SectionComponents) -> [f64; 4] {
    [c[0], c[1], c[2], c[3]]
}

/// Linearises the stress along the section from `a` to `b` (r, z in mm), sampling `stress_at`
/// (the stress [rr, zz, tt, rz] at a point, None outside the model, given the unit direction
/// into the section there) at `intervals` + 1 points (Simpson's rule; `intervals` even). An
/// error names the first point outside the model.
///
/// The direction lets a sampler read, at a point on an interface (a section starting where one
/// ply lies on another), the body the section runs into rather than the one behind it
/// ([`StressSampler::entering`]).
pub fn linearize(a: [f64; 2], b: [f64; 2], intervals: usize, stress_at: impl Fn([f64; 2], [f64; 2]) -> Option<[f64; 4]>) -> Result<Linearized, String> {
    let t = (b[0] - a[0]).hypot(b[1] - a[1]);
    if !(t > 0.0 && t.is_finite()) {
        return Err(format!("the section's ends ({}, {}) and ({}, {}) must differ", a[0], a[1], b[0], b[1]));
    }
    let n = intervals.max(2) + intervals % 2;
    let d = [(b[0] - a[0]) / t, (b[1] - a[1]) / t];
    let mut membrane = [0.0; 4];
    let mut moment = [0.0; 4];
    let mut total = [[0.0; 4]; 2];
    for k in 0..=n {
        let x = t * k as f64 / n as f64;
        let p = [a[0] + x * d[0], a[1] + x * d[1]];
        let into = if k == n { [-d[0], -d[1]] } else { d };
        let s = stress_at(p, into).ok_or_else(|| format!("the section point ({:.6}, {:.6}) lies in no element", p[0], p[1]))?;
        let c = section_components(&s, d);
        let w = if k == 0 || k == n {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        } * (t / n as f64)
            / 3.0;
        for i in 0..4 {
            membrane[i] += w * c[i];
            moment[i] += w * c[i] * (0.5 * t - x);
        }
        if k == 0 {
            total[0] = c;
        }
        if k == n {
            total[1] = c;
        }
    }
    let membrane = membrane.map(|v| v / t);
    let bending = moment.map(|v| 6.0 * v / (t * t));
    let start: [f64; 4] = std::array::from_fn(|i| membrane[i] + bending[i]);
    let end: [f64; 4] = std::array::from_fn(|i| membrane[i] - bending[i]);
    Ok(Linearized {
        thickness: t,
        membrane,
        bending,
        membrane_equivalent: von_mises(&as_tensor(&membrane)),
        membrane_plus_bending_equivalent: [von_mises(&as_tensor(&start)), von_mises(&as_tensor(&end))],
        total,
    })
}

/// The stress anywhere in a mesh from its Gauss-point values, in the element holding the point
/// (reference coordinates), by the rule the nodal output uses:
/// - in an elastic element its Gauss values carried to its nodes (the biquadratic fit) and
///   interpolated there;
/// - in a yielded quadrilateral the tensor-product polynomial through its Gauss points, held at
///   the outer points' values beyond them: it passes through every Gauss value and never
///   extrapolates past one (a parabola through yielded points overshoots them), and at the
///   nodes it is the nearest point's value, the nodal output's rule there;
/// - in a yielded triangle its nearest Gauss point's value at each node, interpolated.
pub struct StressSampler<'a> {
    coords: &'a [[f64; 2]],
    elements: &'a [[usize; 8]],
    /// Per element, how its stress is read.
    fields: Vec<ElementField>,
    /// Per element, its bounding box (r0, z0, r1, z1).
    boxes: Vec<[f64; 4]>,
    /// Per element, each component's least and greatest Gauss value.
    ranges: Vec<[[f64; 2]; 4]>,
    /// How far outside an element (in its coordinates xi, eta) a point still counts as in it.
    slack: f64,
}

impl<'a> StressSampler<'a> {
    /// `stress` per element: [rr, zz, tt, rz] at the Gauss points of fully integrated elastic
    /// elements.
    pub fn new(coords: &'a [[f64; 2]], elements: &'a [[usize; 8]], stress: &[[[f64; 4]; 9]]) -> Self {
        Self::integrated(coords, elements, &vec![Integration::Full; elements.len()], &vec![Rule::Extrapolate; elements.len()], stress)
    }

    /// `stress` per element: [rr, zz, tt, rz] at the Gauss slots of elements integrated as
    /// `integration` (a reduced element's spare slots are not read), carried to the nodes by
    /// `rules` ([`Rule::for_element`] of each element's plastic strain).
    pub fn integrated(coords: &'a [[f64; 2]], elements: &'a [[usize; 8]], integration: &[Integration], rules: &[Rule], stress: &[[[f64; 4]; 9]]) -> Self {
        let recovery = Recovery::default();
        let fields = (elements.iter().zip(integration).zip(rules).zip(stress))
            .map(|(((e, &i), &rule), g)| match (Shape::of(e), rule) {
                (Shape::Quad8, Rule::Copy) => ElementField::Gauss(i, *g),
                (shape, rule) => ElementField::Nodal(recovery.element_nodal(shape, i, rule, g)),
            })
            .collect();
        let boxes = elements
            .iter()
            .map(|e| {
                e.iter().fold([f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY], |b, &n| {
                    let x = coords[n];
                    [b[0].min(x[0]), b[1].min(x[1]), b[2].max(x[0]), b[3].max(x[1])]
                })
            })
            .collect();
        let ranges = (elements.iter().zip(integration).zip(stress))
            .map(|((e, &i), g)| {
                std::array::from_fn(|c| g[..Shape::of(e).points(i)].iter().fold([f64::INFINITY, f64::NEG_INFINITY], |r, v| [r[0].min(v[c]), r[1].max(v[c])]))
            })
            .collect();
        StressSampler { coords, elements, fields, boxes, ranges, slack: 1e-9 }
    }

    /// Points up to `slack` outside an element (in its coordinates: 1e-2 is 0.5 % of its width)
    /// count as in it, the field extrapolated: for sections ending on a curved surface, which the
    /// quadratic edges follow only to about 1e-4 of an element. A sampler of one body only, so
    /// that no neighbour's element takes a point of its own.
    pub fn with_slack(mut self, slack: f64) -> Self {
        self.slack = slack;
        self
    }

    /// The stress at `p`, None outside every element.
    pub fn at(&self, p: [f64; 2]) -> Option<[f64; 4]> {
        self.holding(p).next().map(|(e, xi)| self.fields[e].at(Shape::of(&self.elements[e]), xi))
    }

    /// The element holding `p`, if any.
    pub fn element_at(&self, p: [f64; 2]) -> Option<usize> {
        self.holding(p).next().map(|(e, _)| e)
    }

    /// How many walls the section a -> b crosses: one more than the times it passes from an
    /// element to one that shares no node with it (an interface between bodies meshed apart,
    /// such as the plies of a pack in contact), read at the middles of 1000 equal pieces (a
    /// section that starts on an interface starts in the wall it runs into).
    pub fn walls_crossed(&self, a: [f64; 2], b: [f64; 2]) -> usize {
        const POINTS: usize = 1000;
        let along: Vec<usize> = (0..POINTS)
            .map(|k| (k as f64 + 0.5) / POINTS as f64)
            .filter_map(|t| self.element_at([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]))
            .collect();
        let nodes = |e: usize| &self.elements[e][..Shape::of(&self.elements[e]).nodes()];
        let apart = |e: usize, f: usize| !nodes(e).iter().any(|n| nodes(f).contains(n));
        1 + along.windows(2).filter(|w| w[0] != w[1] && apart(w[0], w[1])).count()
    }

    /// As [`Self::at`], each component held within the element's own Gauss values: for a field
    /// that is bounded pointwise (an equivalent plastic strain, or its growth, never below
    /// zero), where a polynomial through steep Gauss values would undershoot between them.
    pub fn within_gauss_values(&self, p: [f64; 2]) -> Option<[f64; 4]> {
        self.holding(p).next().map(|(e, xi)| {
            let v = self.fields[e].at(Shape::of(&self.elements[e]), xi);
            std::array::from_fn(|c| v[c].clamp(self.ranges[e][c][0], self.ranges[e][c][1]))
        })
    }

    /// The stress at `p` in the element that a line leaving `p` along `direction` (unit) runs
    /// into, where `p` lies on an interface between two; else as [`Self::at`].
    pub fn entering(&self, p: [f64; 2], direction: [f64; 2]) -> Option<[f64; 4]> {
        let ahead = |e: usize| {
            let bx = self.boxes[e];
            let step = 1e-6 * (bx[2] - bx[0]).max(bx[3] - bx[1]);
            let x: [[f64; 2]; 8] = self.elements[e].map(|n| self.coords[n]);
            inverse_map(Shape::of(&self.elements[e]), &x, [p[0] + step * direction[0], p[1] + step * direction[1]], self.slack).is_some()
        };
        let (e, xi) = self.holding(p).find(|&(e, _)| ahead(e)).or_else(|| self.holding(p).next())?;
        Some(self.fields[e].at(Shape::of(&self.elements[e]), xi))
    }

    /// The elements holding `p`, with its coordinates in each.
    fn holding(&self, p: [f64; 2]) -> impl Iterator<Item = (usize, [f64; 2])> + '_ {
        self.boxes.iter().enumerate().filter_map(move |(e, bx)| {
            let tol = self.slack.max(1e-9) * (bx[2] - bx[0]).max(bx[3] - bx[1]);
            if p[0] < bx[0] - tol || p[0] > bx[2] + tol || p[1] < bx[1] - tol || p[1] > bx[3] + tol {
                return None;
            }
            let x: [[f64; 2]; 8] = self.elements[e].map(|n| self.coords[n]);
            inverse_map(Shape::of(&self.elements[e]), &x, p, self.slack).map(|xi| (e, xi))
        })
    }
}

/// How one element's stress is read.
enum ElementField {
    /// [rr, zz, tt, rz] at its nodes, interpolated by its shape functions.
    Nodal([[f64; 4]; 8]),
    /// A yielded quadrilateral's Gauss values, integrated as given: the tensor-product
    /// Lagrange polynomial through them, its coordinates held within the outer points.
    Gauss(Integration, [[f64; 4]; 9]),
}

impl ElementField {
    fn at(&self, shape: Shape, xi: [f64; 2]) -> [f64; 4] {
        match self {
            ElementField::Nodal(nodal) => {
                let (n, _) = shape.functions(xi);
                std::array::from_fn(|c| (0..8).map(|a| n[a] * nodal[a][c]).sum())
            }
            ElementField::Gauss(integration, g) => {
                // the 1-D points of the rule (3 x 3: slot i + 3 j; 2 x 2: slot i + 2 j)
                let points: &[f64] = match integration {
                    Integration::Full => &[-GAUSS3[2].0, 0.0, GAUSS3[2].0],
                    Integration::Reduced => &[-GAUSS2, GAUSS2],
                };
                let m = points.len();
                let outer = points[m - 1];
                let lagrange = |k: usize, x: f64| -> f64 {
                    let x = x.clamp(-outer, outer);
                    (0..m).filter(|&j| j != k).map(|j| (x - points[j]) / (points[k] - points[j])).product()
                };
                let (li, lj): ([f64; 3], [f64; 3]) = (
                    std::array::from_fn(|k| if k < m { lagrange(k, xi[0]) } else { 0.0 }),
                    std::array::from_fn(|k| if k < m { lagrange(k, xi[1]) } else { 0.0 }),
                );
                std::array::from_fn(|c| (0..m * m).map(|q| li[q % m] * lj[q / m] * g[q][c]).sum())
            }
        }
    }
}

/// The element coordinates (xi, eta) of `p` in the element `x` of shape `shape`, if it lies
/// inside.
fn inverse_map(shape: Shape, x: &[[f64; 2]; 8], p: [f64; 2], slack: f64) -> Option<[f64; 2]> {
    let mut xi = shape.centre();
    for _ in 0..30 {
        let (n, d) = shape.functions(xi);
        let pos: [f64; 2] = std::array::from_fn(|c| (0..8).map(|a| n[a] * x[a][c]).sum());
        let r = [p[0] - pos[0], p[1] - pos[1]];
        // J[c][k] = d x_c / d xi_k
        let j: [[f64; 2]; 2] = std::array::from_fn(|c| std::array::from_fn(|k| (0..8).map(|a| d[a][k] * x[a][c]).sum()));
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det.abs() < 1e-300 {
            return None;
        }
        let step = [(j[1][1] * r[0] - j[0][1] * r[1]) / det, (-j[1][0] * r[0] + j[0][0] * r[1]) / det];
        xi = [xi[0] + step[0], xi[1] + step[1]];
        if xi[0].abs() > 3.0 || xi[1].abs() > 3.0 {
            return None;
        }
        // converged to 1e-10 of the element's size (xi is relative to it): Newton's last step
        // stalls at the round-off of the coordinates, about 1e-13 of the element in a thin ply
        // far from the axis, so a fixed 1e-13 failed there
        if step[0].abs().max(step[1].abs()) < 1e-10 {
            return shape.contains(xi, slack).then_some(xi);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::super::shape::q8;
    use super::*;

    #[test]
    fn a_linear_distribution_is_all_membrane_and_bending_and_rotates_with_the_section() {
        // sigma_zz = 10 + 4 (r - 2) across r in [2, 4], from 10 to 18: membrane 14, bending (its
        // linear part at the start) 10 - 14 = -4
        let field = |p: [f64; 2]| Some([1.0, 10.0 + 4.0 * (p[0] - 2.0), 3.0, 0.5]);
        let l = linearize([2.0, 1.0], [4.0, 1.0], 20, |p, _| field(p)).unwrap();
        assert!((l.thickness - 2.0).abs() < 1e-15);
        // along r: normal = rr, meridional = zz, shear = rz
        assert!((l.membrane[1] - 14.0).abs() < 1e-12 && (l.bending[1] + 4.0).abs() < 1e-12, "{l:?}");
        assert!((l.membrane[0] - 1.0).abs() < 1e-12 && l.bending[0].abs() < 1e-12 && (l.membrane[3] - 0.5).abs() < 1e-12);
        // the same section walked backwards: the bending flips sign at the (new) start
        let back = linearize([4.0, 1.0], [2.0, 1.0], 20, |p, _| field(p)).unwrap();
        assert!((back.bending[1] - 4.0).abs() < 1e-12 && (back.membrane[1] - 14.0).abs() < 1e-12);
        // a section along z: the normal is zz
        let c = section_components(&[1.0, 2.0, 3.0, 0.5], [0.0, 1.0]);
        assert_eq!(c, [2.0, 1.0, 3.0, -0.5]);
    }

    #[test]
    fn points_of_a_thin_curved_element_far_from_the_axis_are_found() {
        // a bellows ply's element: 1 mm across (r), 2 mm along a crest of radius 5 mm, at
        // r = 180; every point of a 9 x 9 grid inside it maps back to its element coordinates
        // (with a fixed tolerance of 1e-13 on the Newton step most failed: round-off stalls the
        // step near 1e-13 of the element at these coordinates)
        let arc = |rho: f64, s: f64| [175.0 + rho * (s / 5.0).cos(), 260.0 + rho * (s / 5.0).sin()];
        let x: [[f64; 2]; 8] = [arc(5.0, -1.0), arc(6.0, -1.0), arc(6.0, 1.0), arc(5.0, 1.0), arc(5.5, -1.0), arc(6.0, 0.0), arc(5.5, 1.0), arc(5.0, 0.0)];
        let mut found = 0;
        for i in 0..9 {
            for j in 0..9 {
                let xi = [-0.97 + 0.2425 * i as f64, -0.97 + 0.2425 * j as f64];
                let (n, _) = q8(xi);
                let p: [f64; 2] = std::array::from_fn(|c| (0..8).map(|a| n[a] * x[a][c]).sum());
                let back = inverse_map(Shape::Quad8, &x, p, 1e-9).unwrap_or_else(|| panic!("({}, {}) at xi {xi:?} not found", p[0], p[1]));
                assert!((back[0] - xi[0]).abs() < 1e-8 && (back[1] - xi[1]).abs() < 1e-8);
                found += 1;
            }
        }
        assert_eq!(found, 81);
    }

    #[test]
    fn the_sampler_interpolates_a_quadratic_field_exactly_and_says_when_outside() {
        // one Q8 over [1, 3] x [0, 2], Gauss values of s = r^2 (the biquadratic fit holds it)
        let coords = [[1.0, 0.0], [3.0, 0.0], [3.0, 2.0], [1.0, 2.0], [2.0, 0.0], [3.0, 1.0], [2.0, 2.0], [1.0, 1.0]];
        let elements = [[0, 1, 2, 3, 4, 5, 6, 7]];
        let g = 0.6f64.sqrt();
        let pts = [-g, 0.0, g];
        let stress: [[f64; 4]; 9] = std::array::from_fn(|q| {
            let (i, _) = (q % 3, q / 3);
            let r = 2.0 + pts[i];
            [r * r, 0.0, 0.0, 0.0]
        });
        let s = StressSampler::new(&coords, &elements, &[stress]);
        for r in [1.0, 1.7, 2.5, 3.0] {
            let v = s.at([r, 0.3]).unwrap();
            assert!((v[0] - r * r).abs() < 1e-12, "{r}: {v:?}");
        }
        assert!(s.at([3.5, 1.0]).is_none());
    }

    #[test]
    fn a_yielded_element_passes_through_its_gauss_values_and_holds_the_outer_ones_beyond() {
        // one Q8 over [1, 3] x [0, 2], yielded, Gauss values s = (r - 2)^3 (odd: no quadratic
        // holds it); a section starting on its left edge reads the element it runs into though
        // a neighbour over [0, 1] x [0, 2] also holds the starting point
        let coords = [
            [1.0, 0.0],
            [3.0, 0.0],
            [3.0, 2.0],
            [1.0, 2.0],
            [2.0, 0.0],
            [3.0, 1.0],
            [2.0, 2.0],
            [1.0, 1.0],
            [0.0, 0.0],
            [0.0, 2.0],
            [0.5, 0.0],
            [0.5, 2.0],
            [0.0, 1.0],
        ];
        let elements = [[8, 0, 3, 9, 10, 7, 11, 12], [0, 1, 2, 3, 4, 5, 6, 7]];
        let g = 0.6f64.sqrt();
        let gauss: [[f64; 4]; 9] = std::array::from_fn(|q| [(-g + g * (q % 3) as f64).powi(3), 0.0, 0.0, 0.0]);
        let neighbour = [[1e3, 0.0, 0.0, 0.0]; 9];
        let s = StressSampler::integrated(&coords, &elements, &[Integration::Full; 2], &[Rule::Extrapolate, Rule::Copy], &[neighbour, gauss]);
        for (k, r) in [2.0 - g, 2.0, 2.0 + g].into_iter().enumerate() {
            assert!((s.at([r, 0.7]).unwrap()[0] - gauss[k][0]).abs() < 1e-12);
        }
        // held beyond the outer points, where a parabola would reach +-(1.0) / extrapolate
        assert!((s.at([3.0, 1.0]).unwrap()[0] - g.powi(3)).abs() < 1e-12);
        assert!((s.at([1.0 + 1e-3, 1.0]).unwrap()[0] + g.powi(3)).abs() < 1e-12);
        let l = linearize([1.0, 1.0], [3.0, 1.0], 200, |p, d| s.entering(p, d)).unwrap();
        assert!((l.total[0][0] + g.powi(3)).abs() < 1e-9 && (l.total[1][0] - g.powi(3)).abs() < 1e-9, "{l:?}");
        // odd about the centre: no membrane
        assert!(l.membrane[0].abs() < 1e-6, "{l:?}");
    }
}

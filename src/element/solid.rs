//! The quadratic axisymmetric solid: the 8-node quadrilateral (Q8 serendipity, 3x3 Gauss
//! integration) and the 6-node triangle (T6, 9-point conical rule), total Lagrangian, with
//! F-bar on a projected dilatation.
//!
//! Why Q8: the bellows plies are 1 mm thick and bend. A quadratic element carries the linear
//! bending strain through the thickness exactly, so it neither shear-locks (as plain bilinear Q4
//! does) nor needs incompatible modes; with full 3x3 integration it has no hourglass modes.
//!
//! Why projected F-bar: plastic flow is isochoric, and a fully integrated Q8 then locks
//! (9 volume constraints per element). The volume measure v = det F (finite strain) or tr eps
//! (small strain) is replaced at each Gauss point by its L2 projection theta onto
//! {1, R - Rc, Z - Zc} over the element, F_bar = (theta / det F)^(1/3) F (de Souza Neto et al.
//! 1996, generalised from the centroid value to a linear field). That leaves 3 volume
//! constraints per element, the count of the Q8/P1 mixed element, which removes locking; unlike
//! a constant (centroid) value it keeps the linear through-thickness dilatation of bending
//! exact, so thin plies bend as with plain Q8 (the clamped-plate test). Deviatoric response
//! stays fully integrated.
//!
//! The T6 takes the same linear projection: 3 volume constraints per element, the count of
//! the P2/P1-discontinuous mixed triangle. Measured against the other choice, the constant
//! (P2/P0, inf-sup stable): the constant made elastic bending 3 % (4 elements through the
//! thickness) to 12 % (2) too soft in a clamped plate, where the linear one is within 0.3 %
//! and agrees with CalculiX's CAX6 on its own test deck to 0.03 %; in plastic flow the
//! linear one met the thick cylinder's limit pressure to 4e-6 and its mean stress to 0.3 % of
//! the yield stress at every Gauss point (the constant 2 %). Its price is near
//! incompressibility in elastic bending (nu = 0.4999: 2 % to 6 % too stiff, the Q8 0.5 % to
//! 1 %), outside what slideline's metals do; docs/deck.md (Element) has the figures.
//!
//! Total Lagrangian: dF/du is constant, so f_int = sum_q w_q G_q^T phi_q and the tangent is
//! exactly K = sum_q w_q G_q^T (A_q G_q + b_q (x) Theta_q), where A = d phi / d F and
//! b = d phi / d theta come from the material update on dual numbers and
//! Theta_q = d theta_q / d u = sum_p Pi_qp (dv/dF)_p G_p.
//! F components are ordered [F_rR, F_rZ, F_zR, F_zZ, F_tT] (t = hoop).
//!
//! The reduced rules of .inp decks (`Integration::Reduced`: CAX8R's 2 x 2 Gauss points, CAX6's
//! 3) have no projection, as CalculiX and Abaqus compute those elements: theta = v at each
//! point, its dependence on F folded into A, so the F-bar term vanishes. Their points fill the
//! first of the 9 slots; the others weigh nothing and keep zero stress.
//!
//! The evaluation is split in two so that the expensive part is done once per iterate: the
//! residual evaluation may keep the material tangents A, b (and dv/dF) of every point
//! ([`MaterialTangents`]), and [`solid_tangent`] turns them into K with products that use the
//! sparsity of G (per node: three nonzero rows on the radial DOF, two on the axial one).

use crate::ad::Dual;
use crate::fe::axisymmetric::{map_point, PointGeometry};
use crate::fe::quadrature::Integration;
use crate::fe::section::Section;
use crate::fe::shape::Shape;
use crate::material::log_exp::log_sym2;
use crate::material::{Kinematics, PointState, SurfaceBranch, J2};
use nalgebra::{Matrix3, SMatrix, SVector, Vector3};

pub const NODES: usize = 8;
pub const DOFS: usize = 16;
pub const QUADRATURE_POINTS: usize = 9;

pub type ElementVector = SVector<f64, DOFS>;
pub type ElementMatrix = SMatrix<f64, DOFS, DOFS>;

/// dF/du at one Gauss point, by its nonzeros: a radial DOF of node a moves F_rR, F_rZ, F_tT by
/// dN_a/dR, dN_a/dZ, N_a/R; an axial DOF moves F_zR, F_zZ by dN_a/dR, dN_a/dZ.
#[derive(Clone, Copy, Debug)]
struct GradientMap {
    dr: [f64; NODES],
    dz: [f64; NODES],
    hoop: [f64; NODES],
}

impl GradientMap {
    /// The map at a point; a plane section has no hoop term (F_33 is 1 in plane strain and
    /// solved from sigma_33 = 0 in plane stress, never moved by the displacements).
    fn new(g: &PointGeometry, section: Section) -> Self {
        let hoop = std::array::from_fn(|a| if section.is_axisymmetric() { g.n[a] / g.r } else { 0.0 });
        GradientMap { dr: g.grad.map(|d| d[0]), dz: g.grad.map(|d| d[1]), hoop }
    }

    /// G^T s for a 5-vector s over the F components (equally, the row s^T G).
    #[inline]
    fn contract(&self, s: &[f64; 5]) -> [f64; DOFS] {
        let mut out = [0.0; DOFS];
        for a in 0..NODES {
            out[2 * a] = s[0] * self.dr[a] + s[1] * self.dz[a] + s[4] * self.hoop[a];
            out[2 * a + 1] = s[2] * self.dr[a] + s[3] * self.dz[a];
        }
        out
    }
}

/// The material's consistent tangent at one Gauss point, weighted by the point's reference
/// volume: w d phi / d F, w d phi / d theta, and the volume measure's derivative dv/dF there.
#[derive(Clone, Copy, Debug, Default)]
pub struct PointTangent {
    stress_f: [[f64; 5]; 5],
    stress_theta: [f64; 5],
    volume_f: [f64; 5],
}

/// What [`solid_tangent`] needs of one evaluation.
pub type MaterialTangents = [PointTangent; QUADRATURE_POINTS];

/// Reference geometry of an element, computed once (it never changes in a total Lagrangian
/// formulation).
#[derive(Clone, Debug)]
pub struct ElementGeometry {
    section: Section,
    integration: Integration,
    /// How many of the slots are integration points.
    used: usize,
    points: [PointGeometry; QUADRATURE_POINTS],
    gradients: [GradientMap; QUADRATURE_POINTS],
    /// Reference volume of each Gauss point: w m det J, m the section's measure (R per radian
    /// in axisymmetry, the thickness in a plane section); zero in a reduced element's spare slots.
    weights: [f64; QUADRATURE_POINTS],
    /// The projection through its rank-3 basis: theta_q = basis[q] . sum_p coef[p] v_p, so the
    /// 9 rows Theta_q are combinations of 3 rows (sum_p coef[p][k] (dv/dF)_p G_p). Zero in a
    /// reduced element, which projects nothing.
    basis: [[f64; 3]; QUADRATURE_POINTS],
    coef: [[f64; 3]; QUADRATURE_POINTS],
}

/// The (basis, coef) of [`ElementGeometry`]'s volume projection.
type Projection = ([[f64; 3]; QUADRATURE_POINTS], [[f64; 3]; QUADRATURE_POINTS]);

/// The L2 projection (weighted by the points' reference volumes `weights`) onto
/// {1, R - Rc, Z - Zc}, the points at `pos`, through its rank-3 basis.
fn volume_projection(weights: &[f64; QUADRATURE_POINTS], pos: &[[f64; 2]; QUADRATURE_POINTS]) -> Result<Projection, String> {
    let vol: f64 = weights.iter().sum();
    let centre = [0, 1].map(|i| (0..QUADRATURE_POINTS).map(|q| weights[q] * pos[q][i]).sum::<f64>() / vol);
    let basis_vector = |q: usize| Vector3::new(1.0, pos[q][0] - centre[0], pos[q][1] - centre[1]);
    let mut m = Matrix3::zeros();
    for q in 0..QUADRATURE_POINTS {
        m += basis_vector(q) * basis_vector(q).transpose() * weights[q];
    }
    let m_inv = m.try_inverse().ok_or_else(|| "degenerate element: singular volume projection".to_string())?;
    let basis = std::array::from_fn(|q| basis_vector(q).into());
    let coef = std::array::from_fn(|p| (m_inv * basis_vector(p) * weights[p]).into());
    Ok((basis, coef))
}

impl ElementGeometry {
    /// The geometry of an element of shape `shape`, integrated as `integration`, of section
    /// `section`, with nodal coordinates `x`.
    pub fn new(shape: Shape, integration: Integration, section: Section, x: &[[f64; 2]; NODES]) -> Result<Self, String> {
        let rule = shape.rule_for(integration);
        let mut points = [map_point(shape, x, rule[0].0)?; QUADRATURE_POINTS];
        let mut weights = [0.0; QUADRATURE_POINTS];
        let mut pos = [[0.0; 2]; QUADRATURE_POINTS];
        for (q, (p, w)) in rule.into_iter().enumerate() {
            points[q] = map_point(shape, x, p)?;
            if section.is_axisymmetric() && points[q].r <= 0.0 {
                return Err(format!("radius {:.3e} <= 0 at an integration point: an axisymmetric mesh must lie at r >= 0", points[q].r));
            }
            weights[q] = w * section.measure(points[q].r) * points[q].det_j;
            pos[q] = [points[q].r, (0..NODES).map(|a| points[q].n[a] * x[a][1]).sum()];
        }
        let gradients = points.map(|g| GradientMap::new(&g, section));
        let (basis, coef) = match integration {
            Integration::Full => volume_projection(&weights, &pos)?,
            Integration::Reduced => ([[0.0; 3]; QUADRATURE_POINTS], [[0.0; 3]; QUADRATURE_POINTS]),
        };
        Ok(ElementGeometry { section, integration, used: shape.points(integration), points, gradients, weights, basis, coef })
    }

    /// How many of the 9 Gauss slots are integration points (the first 9, 4 or 3).
    pub fn points_used(&self) -> usize {
        self.used
    }

    /// The shape functions and gradients at each Gauss point, and its reference volume
    /// w m det J (for kernels beside this one on the same element: `element::harmonic`).
    pub(crate) fn points(&self) -> (&[PointGeometry; QUADRATURE_POINTS], &[f64; QUADRATURE_POINTS]) {
        (&self.points, &self.weights)
    }

    /// The projected volume measure theta at every Gauss point, from its values `v` there
    /// (`v` itself in a reduced element: no volumetric treatment).
    pub(crate) fn project(&self, v: &[f64; QUADRATURE_POINTS]) -> [f64; QUADRATURE_POINTS] {
        if self.integration == Integration::Reduced {
            return *v;
        }
        let mut c = [0.0; 3];
        for p in 0..QUADRATURE_POINTS {
            for k in 0..3 {
                c[k] += self.coef[p][k] * v[p];
            }
        }
        self.basis.map(|b| b[0] * c[0] + b[1] * c[1] + b[2] * c[2])
    }

    pub fn section(&self) -> Section {
        self.section
    }

    /// The element's volume (per radian in axisymmetry, over its thickness in a plane section):
    /// the sum of its points' measures.
    pub fn volume(&self) -> f64 {
        self.weights.iter().sum()
    }

    /// Mean out-of-plane measure of the element, its volume over its area in the (r, z)
    /// plane: the mean radius in axisymmetry, the thickness in a plane section.
    pub fn mean_measure(&self) -> f64 {
        let area: f64 = (0..QUADRATURE_POINTS).map(|q| self.weights[q] / self.points[q].r).sum();
        self.weights.iter().sum::<f64>() / area
    }

    /// The total strain [rr, zz, tt, rz] (tensor shear) at every Gauss point for nodal
    /// displacements `u`, for output: sym grad u in small strain; in finite strain the
    /// logarithmic (Hencky) strain of the current configuration, ln(F F^T) / 2, Abaqus's LE.
    /// In plane stress the thickness stretch F_33 of each point comes from the evaluation
    /// (`SolidResponse::thickness_stretch`).
    pub fn total_strain(
        &self,
        kinematics: Kinematics,
        u: &[[f64; 2]; NODES],
        thickness_stretch: Option<&[f64; QUADRATURE_POINTS]>,
    ) -> [[f64; 4]; QUADRATURE_POINTS] {
        std::array::from_fn(|q| {
            let mut f = self.deformation_gradient(q, u);
            if let Some(s) = thickness_stretch {
                f[4] = s[q];
            }
            match kinematics {
                Kinematics::Small => [f[0] - 1.0, f[3] - 1.0, f[4] - 1.0, 0.5 * (f[1] + f[2])],
                Kinematics::Finite => {
                    let b = [f[0] * f[0] + f[1] * f[1], f[2] * f[2] + f[3] * f[3], f[0] * f[2] + f[1] * f[3]];
                    let [rr, zz, rz] = log_sym2(&b);
                    [0.5 * rr, 0.5 * zz, f[4].ln(), 0.5 * rz]
                }
            }
        })
    }

    /// Deformation gradient at Gauss point q for nodal displacements u.
    fn deformation_gradient(&self, q: usize, u: &[[f64; 2]; NODES]) -> [f64; 5] {
        let g = &self.gradients[q];
        let mut f = [1.0, 0.0, 0.0, 1.0, 1.0];
        for a in 0..NODES {
            f[0] += g.dr[a] * u[a][0];
            f[1] += g.dz[a] * u[a][0];
            f[2] += g.dr[a] * u[a][1];
            f[3] += g.dz[a] * u[a][1];
            f[4] += g.hoop[a] * u[a][0];
        }
        f
    }
}

/// Volume measure v and its derivative dv/dF: det F, or tr eps at small strain.
fn volume_measure(kinematics: Kinematics, f: &[f64; 5]) -> (f64, [f64; 5]) {
    match kinematics {
        Kinematics::Finite => {
            let det2 = f[0] * f[3] - f[1] * f[2];
            (det2 * f[4], [f[3] * f[4], -f[2] * f[4], -f[1] * f[4], f[0] * f[4], det2])
        }
        Kinematics::Small => (f[0] + f[3] + f[4] - 3.0, [1.0, 0.0, 0.0, 1.0, 1.0]),
    }
}

/// What one element evaluation produces.
#[derive(Clone, Debug)]
pub struct SolidResponse {
    /// Internal force per radian.
    pub internal_force: ElementVector,
    /// Cauchy stress [rr, zz, tt, rz] at each Gauss point.
    pub stress: [[f64; 4]; QUADRATURE_POINTS],
    /// Trial history at each Gauss point.
    pub state: [PointState; QUADRATURE_POINTS],
    /// The element's energies at this state (per radian, N mm).
    pub energy: ElementEnergy,
    /// The thermal strain's stress power per degree at each node: sum over the points of
    /// alpha tr(tau) N_a dV_0 (N mm / degC per radian); the thermal work of a temperature
    /// change dT_a is its sum of products with dT_a.
    pub thermal_force: [f64; NODES],
    /// F_33 at each Gauss point: the hoop stretch in axisymmetry, 1 in plane strain, the
    /// solved thickness stretch in plane stress.
    pub thickness_stretch: [f64; QUADRATURE_POINTS],
}

/// Energies of one element at a state, per radian (N mm): the stored elastic energy and the
/// plastic work (the integral of sigma_y over the equivalent plastic strain).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ElementEnergy {
    pub elastic: f64,
    pub plastic_work: f64,
}

/// The element state an evaluation needs besides the displacements.
pub struct SolidInput<'a> {
    pub geometry: &'a ElementGeometry,
    pub material: &'a J2,
    pub kinematics: Kinematics,
    /// Temperature change from the reference temperature at each node, degC (interpolated
    /// to the Gauss points with the shape functions).
    pub temperature_change: [f64; NODES],
    /// History of the last converged increment (read, never written).
    pub committed: &'a [PointState; QUADRATURE_POINTS],
    /// The response of points on the yield surface (flowing for the load predictor).
    pub surface: SurfaceBranch,
}

/// Internal force for nodal displacements `u`, and the material tangents into `tangents` when
/// given (the update then runs on dual numbers, about 1.5 times the cost of the plain one;
/// written in place, as they are 2.5 kB per element).
pub fn compute_solid(input: &SolidInput<'_>, u: &[[f64; 2]; NODES], mut tangents: Option<&mut MaterialTangents>) -> Result<SolidResponse, String> {
    let geo = input.geometry;
    let kin = input.kinematics;
    let mut f = [[0.0; 5]; QUADRATURE_POINTS];
    let mut v = [0.0; QUADRATURE_POINTS];
    let mut dv = [[0.0; 5]; QUADRATURE_POINTS];
    for q in 0..QUADRATURE_POINTS {
        f[q] = geo.deformation_gradient(q, u);
        (v[q], dv[q]) = volume_measure(kin, &f[q]);
    }
    // plane stress: no projection (the free thickness strain takes up the plastic flow's
    // volume constraint); each point's theta is its own v, set with its F_33 below
    let plane_stress = matches!(geo.section, Section::PlaneStress { .. });
    let mut theta = if plane_stress { v } else { geo.project(&v) };
    // a reduced element's theta is each point's own v: its dependence on F joins d phi / d F
    let reduced = geo.integration == Integration::Reduced;

    let mut force = [0.0; DOFS];
    let mut stress = [[0.0; 4]; QUADRATURE_POINTS];
    let mut state = [PointState::initial(kin); QUADRATURE_POINTS];
    let mut energy = ElementEnergy::default();
    let mut thermal_force = [0.0; NODES];
    // a reduced element's spare slots keep zero stress and tangents and their committed history
    for q in geo.points_used()..QUADRATURE_POINTS {
        state[q] = input.committed[q];
        if let Some(tangents) = tangents.as_deref_mut() {
            tangents[q] = PointTangent::default();
        }
    }
    for q in 0..geo.points_used() {
        let w = geo.weights[q];
        let shape = &geo.points[q].n;
        let dt: f64 = (0..NODES).map(|a| shape[a] * input.temperature_change[a]).sum();
        let phi: [f64; 5] = if plane_stress {
            let (f33, up, dv33) = plane_stress_point(input.material, input.surface, kin, f[q], dt, &input.committed[q])?;
            f[q][4] = f33;
            theta[q] = volume_measure(kin, &f[q]).0;
            if let Some(tangents) = tangents.as_deref_mut() {
                // d phi / dF along theta = v(F), then F_33 condensed out by d phi_33 = 0
                let a: [[f64; 5]; 5] = std::array::from_fn(|i| std::array::from_fn(|j| up.phi[i].eps[j] + up.phi[i].eps[5] * dv33[j]));
                let condensed =
                    std::array::from_fn(|i| std::array::from_fn(|j| if i < 4 && j < 4 { (a[i][j] - a[i][4] * a[4][j] / a[4][4]) * w } else { 0.0 }));
                tangents[q] = PointTangent { stress_f: condensed, stress_theta: [0.0; 5], volume_f: [0.0; 5] };
            }
            stress[q] = up.cauchy;
            state[q] = up.state;
            up.phi.map(|p| p.re)
        } else if let Some(tangents) = tangents.as_deref_mut() {
            let fd: [Dual<6>; 5] = std::array::from_fn(|i| Dual::variable(f[q][i], i));
            let up = input.material.update_on(input.surface, kin, &fd, Dual::variable(theta[q], 5), dt, &input.committed[q])?;
            tangents[q] = if reduced {
                let along_v = |i: usize, j: usize| (up.phi[i].eps[j] + up.phi[i].eps[5] * dv[q][j]) * w;
                PointTangent { stress_f: std::array::from_fn(|i| std::array::from_fn(|j| along_v(i, j))), ..PointTangent::default() }
            } else {
                PointTangent {
                    stress_f: std::array::from_fn(|i| std::array::from_fn(|j| up.phi[i].eps[j] * w)),
                    stress_theta: std::array::from_fn(|i| up.phi[i].eps[5] * w),
                    volume_f: dv[q],
                }
            };
            stress[q] = up.cauchy;
            state[q] = up.state;
            up.phi.map(|p| p.re)
        } else {
            let up = input.material.update_on(input.surface, kin, &f[q], theta[q], dt, &input.committed[q])?;
            stress[q] = up.cauchy;
            state[q] = up.state;
            up.phi
        };
        // Kirchhoff stress: tau = theta sigma (F-bar's volume ratio); sigma in small strain
        let scale = if kin == Kinematics::Finite { theta[q] } else { 1.0 };
        let tau = stress[q].map(|s| s * scale);
        let material = input.material;
        energy.elastic += w * material.elastic_energy(&tau);
        energy.plastic_work += w * (material.hardening.plastic_work(state[q].ep) + state[q].kinematic_work);
        let thermal = w * material.thermal_expansion * (tau[0] + tau[1] + tau[2]);
        for a in 0..NODES {
            thermal_force[a] += thermal * shape[a];
        }
        let fq = geo.gradients[q].contract(&phi.map(|p| p * w));
        for i in 0..DOFS {
            force[i] += fq[i];
        }
    }
    let thickness_stretch = f.map(|fq| fq[4]);
    Ok(SolidResponse { internal_force: ElementVector::from(force), stress, state, energy, thermal_force, thickness_stretch })
}

/// Plane stress at one point of in-plane deformation gradient `f`: the thickness stretch
/// F_33 at which phi_33 (hence sigma_33) vanishes, found by Newton's method on the material
/// update itself, safeguarded by bisection (phi_33 rises with F_33; the yield kink can make
/// plain Newton cycle). Returns F_33, the update there on dual numbers over the 5 components
/// of F and theta (= v(F), no F-bar), and dv/dF there.
fn plane_stress_point(
    material: &J2,
    surface: SurfaceBranch,
    kin: Kinematics,
    f: [f64; 5],
    dt: f64,
    committed: &PointState,
) -> Result<(f64, crate::material::Update<Dual<6>>, [f64; 5]), String> {
    let (k, g) = (material.bulk_modulus, material.shear_modulus);
    // the elastic guess: eps_33 = -nu / (1 - nu) (eps_11 + eps_22) + (1 + nu) / (1 - nu) alpha dT
    let nu = (3.0 * k - 2.0 * g) / (2.0 * (3.0 * k + g));
    let mut f33 = 1.0 - nu / (1.0 - nu) * (f[0] + f[3] - 2.0) + (1.0 + nu) / (1.0 - nu) * material.thermal_expansion * dt;
    let (mut below, mut above) = (f64::NEG_INFINITY, f64::INFINITY);
    for _ in 0..60 {
        let mut fq = f;
        fq[4] = f33;
        let (v, dv) = volume_measure(kin, &fq);
        let fd: [Dual<6>; 5] = std::array::from_fn(|i| Dual::variable(fq[i], i));
        let up = material.update_on(surface, kin, &fd, Dual::variable(v, 5), dt, committed)?;
        let (r, slope) = (up.phi[4].re, up.phi[4].eps[4] + up.phi[4].eps[5] * dv[4]);
        if r < 0.0 {
            below = f33;
        } else if r > 0.0 {
            above = f33;
        }
        let mut next = f33 - r / slope;
        let inside = next > below && next < above && slope > 0.0;
        if !inside {
            next = if below.is_finite() && above.is_finite() { 0.5 * (below + above) } else { f33 * if r > 0.0 { 0.9 } else { 1.1 } };
        }
        if r == 0.0 || (next - f33).abs() <= 4.0 * f64::EPSILON * f33.abs() {
            return Ok((f33, up, dv));
        }
        f33 = next;
    }
    Err(format!("plane stress: the thickness stretch did not converge (F_33 = {f33:.6e})"))
}

/// The element tangent d f_int / d u from the material tangents of an evaluation:
/// K = sum_q G_q^T A_q G_q + sum_q G_q^T b_q (x) Theta_q, products written over G's nonzeros.
/// The F-bar part is of rank 3: with Theta_q = sum_k `basis[q][k]` psi_k it is
/// sum_k c_k (x) psi_k, c_k = sum_q `basis[q][k]` G_q^T b_q, three outer products for the whole
/// element instead of a term in every point's product.
pub fn solid_tangent(geo: &ElementGeometry, material: &MaterialTangents) -> ElementMatrix {
    // psi_k = sum_p coef[p][k] (dv/dF)_p G_p and c_k
    let mut psi = [[0.0; DOFS]; 3];
    let mut c = [[0.0; DOFS]; 3];
    for p in 0..QUADRATURE_POINTS {
        let g = &geo.gradients[p];
        let (volume, stress) = (g.contract(&material[p].volume_f), g.contract(&material[p].stress_theta));
        for k in 0..3 {
            let (a, b) = (geo.coef[p][k], geo.basis[p][k]);
            for j in 0..DOFS {
                psi[k][j] += a * volume[j];
                c[k][j] += b * stress[j];
            }
        }
    }
    // rows of K, row-major
    let mut k = [[0.0; DOFS]; DOFS];
    for i in 0..DOFS {
        for j in 0..DOFS {
            k[i][j] = c[0][i] * psi[0][j] + c[1][i] * psi[1][j] + c[2][i] * psi[2][j];
        }
    }
    for q in 0..geo.points_used() {
        let (g, t) = (&geo.gradients[q], &material[q]);
        // M = A G, row i over the element DOFs
        let mut m = [[0.0; DOFS]; 5];
        for (i, row) in m.iter_mut().enumerate() {
            let a = &t.stress_f[i];
            for n in 0..NODES {
                row[2 * n] = a[0] * g.dr[n] + a[1] * g.dz[n] + a[4] * g.hoop[n];
                row[2 * n + 1] = a[2] * g.dr[n] + a[3] * g.dz[n];
            }
        }
        // K += G^T M: the radial row of node n combines M's rows 0, 1, 4; the axial row 2, 3
        for n in 0..NODES {
            let (dr, dz, hoop) = (g.dr[n], g.dz[n], g.hoop[n]);
            for j in 0..DOFS {
                k[2 * n][j] += dr * m[0][j] + dz * m[1][j] + hoop * m[4][j];
                k[2 * n + 1][j] += dr * m[2][j] + dz * m[3][j];
            }
        }
    }
    ElementMatrix::from_fn(|i, j| k[i][j])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn element() -> [[f64; 2]; 8] {
        [[10.0, 0.0], [12.5, 0.3], [12.0, 2.2], [9.7, 2.0], [11.2, 0.1], [12.3, 1.3], [10.9, 2.15], [9.9, 1.0]]
    }

    use crate::material::j2::tests::STEEL;

    /// Max over columns of |K_fd - K| / max|K| with central differences of the internal force.
    fn tangent_error(input: &SolidInput<'_>, u: &[[f64; 2]; 8], h: f64) -> f64 {
        let mut material = MaterialTangents::default();
        compute_solid(input, u, Some(&mut material)).unwrap();
        let k = solid_tangent(input.geometry, &material);
        let scale = k.abs().max();
        let mut worst = 0.0f64;
        for j in 0..DOFS {
            let (mut up, mut um) = (*u, *u);
            up[j / 2][j % 2] += h;
            um[j / 2][j % 2] -= h;
            let fp = compute_solid(input, &up, None).unwrap().internal_force;
            let fm = compute_solid(input, &um, None).unwrap().internal_force;
            worst = worst.max(((fp - fm) / (2.0 * h) - k.column(j)).abs().max() / scale);
        }
        worst
    }

    /// Small-strain steel with no temperature change and a fresh history, on `geometry`.
    fn small_strain_input<'a>(geometry: &'a ElementGeometry, committed: &'a [PointState; 9]) -> SolidInput<'a> {
        SolidInput { geometry, material: &STEEL, kinematics: Kinematics::Small, temperature_change: [0.0; NODES], committed, surface: SurfaceBranch::Elastic }
    }

    /// A curved 6-node triangle in its 8 slots (the last two at its first node).
    fn triangle() -> [[f64; 2]; 8] {
        let x = [[10.0, 0.0], [12.5, 0.3], [10.4, 2.2], [11.3, 0.05], [11.5, 1.35], [10.1, 1.1]];
        [x[0], x[1], x[2], x[3], x[4], x[5], x[0], x[0]]
    }

    /// Both shapes, the three sections, full and reduced integration; a triangle's spare slots
    /// carry no force, and moving them changes nothing.
    #[test]
    fn tangent_matches_central_differences_small_and_large_plastic() {
        let (strain, stress) = (Section::PlaneStrain { thickness: 2.5 }, Section::PlaneStress { thickness: 2.5 });
        let (full, reduced) = (Integration::Full, Integration::Reduced);
        let cases = [
            (Shape::Quad8, full, Section::Axisymmetric, element()),
            (Shape::Tri6, full, Section::Axisymmetric, triangle()),
            (Shape::Quad8, full, strain, element()),
            (Shape::Quad8, full, stress, element()),
            (Shape::Tri6, full, stress, triangle()),
            (Shape::Quad8, reduced, Section::Axisymmetric, element()),
            (Shape::Quad8, reduced, strain, element()),
            (Shape::Quad8, reduced, stress, element()),
            (Shape::Tri6, reduced, Section::Axisymmetric, triangle()),
            (Shape::Tri6, reduced, stress, triangle()),
        ];
        for (shape, integration, section, x) in cases {
            let geometry = ElementGeometry::new(shape, integration, section, &x).unwrap();
            for (kin, amplitude) in [(Kinematics::Small, 2e-2), (Kinematics::Finite, 0.6)] {
                let committed = [PointState::initial(kin); 9];
                // a large rotation-stretch-shear field, plastic at every point
                let u: [[f64; 2]; 8] = std::array::from_fn(|a| {
                    let (r, z) = (x[a][0], x[a][1]);
                    [amplitude * (0.3 * r - 0.2 * z + 0.05 * z * z), amplitude * (0.5 * r + 0.1 * z - 0.02 * r * z)]
                });
                let input = SolidInput {
                    geometry: &geometry,
                    material: &STEEL,
                    kinematics: kin,
                    temperature_change: std::array::from_fn(|a| 40.0 + 5.0 * a as f64),
                    committed: &committed,
                    surface: SurfaceBranch::Elastic,
                };
                let out = compute_solid(&input, &u, None).unwrap();
                let used = geometry.points_used();
                assert!(out.state[..used].iter().all(|s| s.ep > 0.0), "{shape:?} {section:?} {kin:?}: every point should be plastic");
                if section == stress {
                    assert!(out.stress[..used].iter().all(|s| s[2].abs() < 1e-9), "{kin:?}: sigma_33 {:?}", out.stress);
                }
                // a reduced element's spare slots stay at rest
                assert!(out.state[used..].iter().all(|s| s.ep == 0.0) && out.stress[used..].iter().all(|s| *s == [0.0; 4]));
                let err = tangent_error(&input, &u, if kin == Kinematics::Small { 1e-8 } else { 1e-6 });
                assert!(err <= 1e-6, "{shape:?} {integration:?} {section:?} {kin:?}: tangent error {err:e}");
                if shape == Shape::Tri6 {
                    assert!((12..16).all(|i| out.internal_force[i] == 0.0));
                    let mut moved = u;
                    moved[6] = [5.0, -3.0];
                    moved[7] = [-2.0, 7.0];
                    assert_eq!(compute_solid(&input, &moved, None).unwrap().internal_force, out.internal_force);
                }
            }
        }
    }

    #[test]
    fn a_triangle_projects_a_linear_dilatation_onto_itself_and_holds_a_linear_field() {
        let x = triangle();
        let geometry = ElementGeometry::new(Shape::Tri6, Integration::Full, Section::Axisymmetric, &x).unwrap();
        let z = |q: usize| (0..NODES).map(|a| geometry.points[q].n[a] * x[a][1]).sum::<f64>();
        let v: [f64; 9] = std::array::from_fn(|q| 2.0 + 0.3 * geometry.points[q].r - 0.1 * z(q));
        let theta = geometry.project(&v);
        assert!((0..9).all(|q| (theta[q] - v[q]).abs() < 1e-12));
        // a linear displacement gives its exact (constant) small strain at every point
        let u: [[f64; 2]; 8] = std::array::from_fn(|a| [1e-3 * x[a][0], -5e-4 * x[a][1] + 2e-4 * x[a][0] + 0.3]);
        for e in geometry.total_strain(Kinematics::Small, &u, None) {
            let expected = [1e-3, -5e-4, 1e-3, 1e-4];
            assert!((0..4).all(|k| (e[k] - expected[k]).abs() < 1e-14), "{e:?}");
        }
    }

    #[test]
    fn rigid_rotation_and_translation_give_no_force_at_finite_strain() {
        let x = element();
        let geometry = ElementGeometry::new(Shape::Quad8, Integration::Full, Section::Axisymmetric, &x).unwrap();
        let committed = [PointState::initial(Kinematics::Finite); 9];
        let input = SolidInput {
            geometry: &geometry,
            material: &STEEL,
            kinematics: Kinematics::Finite,
            temperature_change: [0.0; NODES],
            committed: &committed,
            surface: SurfaceBranch::Elastic,
        };
        // axial translation only (a rotation in the (r, z) plane is not rigid in axisymmetry)
        let u = [[0.0, 3.7]; 8];
        let out = compute_solid(&input, &u, None).unwrap();
        // round-off only: |F - I| ~ 1e-15 times E ~ 1e5 over a ~10 mm^3 element
        assert!(out.internal_force.abs().max() < 1e-7, "{}", out.internal_force.abs().max());
    }

    /// Uniform elastic strain in the plane sections (Hooke's law, small strain): plane stress
    /// under eps_11 = e, eps_22 = -nu e gives sigma = (E e, 0, 0) and eps_33 = -nu e; plane
    /// strain under eps_11 = e gives sigma_11 = (lambda + 2 mu) e, sigma_22 = sigma_33 =
    /// lambda e; the uniform stress is in equilibrium (the nodal forces sum to zero).
    #[test]
    fn plane_sections_follow_hookes_law() {
        let (x, e) = (element(), 1e-4);
        let (k, g) = (STEEL.bulk_modulus, STEEL.shear_modulus);
        let (young, nu) = (9.0 * k * g / (3.0 * k + g), (3.0 * k - 2.0 * g) / (2.0 * (3.0 * k + g)));
        let lambda = k - 2.0 * g / 3.0;
        let committed = [PointState::initial(Kinematics::Small); 9];
        for (section, v, expected, stretch) in [
            (Section::PlaneStress { thickness: 3.0 }, -nu * e, [young * e, 0.0, 0.0], 1.0 - nu * e),
            (Section::PlaneStrain { thickness: 3.0 }, 0.0, [(lambda + 2.0 * g) * e, lambda * e, lambda * e], 1.0),
        ] {
            let geometry = ElementGeometry::new(Shape::Quad8, Integration::Full, section, &x).unwrap();
            let input = small_strain_input(&geometry, &committed);
            let u: [[f64; 2]; 8] = std::array::from_fn(|a| [e * x[a][0], v * x[a][1]]);
            let out = compute_solid(&input, &u, None).unwrap();
            for q in 0..9 {
                let s = out.stress[q];
                assert!((0..3).all(|i| (s[i] - expected[i]).abs() < 1e-9 * young * e) && s[3].abs() < 1e-9 * young * e, "{section:?}: {s:?}");
                assert!((out.thickness_stretch[q] - stretch).abs() < 1e-15, "{section:?}: F_33 {}", out.thickness_stretch[q]);
            }
            // a uniform stress in a plane section is in equilibrium: the nodal forces sum to zero
            // (in axisymmetry the hoop stress would pull the element inward)
            let f = out.internal_force;
            for c in 0..2 {
                let net: f64 = (0..8).map(|a| f[2 * a + c]).sum();
                assert!(net.abs() < 1e-9 * f.abs().max(), "{section:?}: net force {net} in component {c}");
            }
        }
    }

    /// The reduced Q8 is CalculiX's CPE8R/CAX8R: 2 x 2 Gauss points and no volumetric
    /// treatment. In plane strain its stiffness has, beside the three rigid motions, the one
    /// zero-energy mode of the 2 x 2 eight-node element (Cook, Malkus, Plesha and Witt,
    /// Concepts and Applications of Finite Element Analysis, 4th ed., 2002, sect. 6.8: 12
    /// strain samples for 13 deformation modes), which a mesh of more than one element
    /// restrains; fully integrated, only the three. A uniform strain stays exact either way.
    #[test]
    fn the_reduced_quadrilateral_has_the_one_spurious_mode_of_2x2_integration() {
        let x = element();
        let committed = [PointState::initial(Kinematics::Small); 9];
        let section = Section::PlaneStrain { thickness: 1.0 };
        let zero_modes = |integration: Integration| {
            let geometry = ElementGeometry::new(Shape::Quad8, integration, section, &x).unwrap();
            let input = small_strain_input(&geometry, &committed);
            let mut tangents = MaterialTangents::default();
            compute_solid(&input, &[[0.0; 2]; NODES], Some(&mut tangents)).unwrap();
            let k = solid_tangent(&geometry, &tangents);
            let eigen = k.symmetric_eigen().eigenvalues;
            let top = eigen.abs().max();
            // a uniform strain: e_rr = 1e-4 gives plane-strain Hooke at every point
            let u: [[f64; 2]; 8] = std::array::from_fn(|a| [1e-4 * x[a][0], 0.0]);
            let out = compute_solid(&input, &u, None).unwrap();
            let (k_mod, g) = (STEEL.bulk_modulus, STEEL.shear_modulus);
            let expected = (k_mod + 4.0 * g / 3.0) * 1e-4;
            assert!(out.stress[..geometry.points_used()].iter().all(|s| (s[0] - expected).abs() < 1e-9 * expected), "{integration:?}");
            eigen.iter().filter(|l| l.abs() < 1e-9 * top).count()
        };
        assert_eq!(zero_modes(Integration::Full), 3);
        assert_eq!(zero_modes(Integration::Reduced), 4);
    }

    #[test]
    fn projection_reproduces_linear_fields() {
        let geometry = ElementGeometry::new(Shape::Quad8, Integration::Full, Section::Axisymmetric, &element()).unwrap();
        let pos: Vec<[f64; 2]> = (0..9).map(|q| [geometry.points[q].r, 0.0]).collect();
        let v: [f64; 9] = std::array::from_fn(|q| 2.0 + 0.3 * pos[q][0]);
        let theta = geometry.project(&v);
        for q in 0..9 {
            assert!((theta[q] - v[q]).abs() < 1e-12);
        }
    }
}

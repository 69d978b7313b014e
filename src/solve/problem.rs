//! The discrete nonlinear problem F(u) = f_int(u) - f_ext(u) = 0 over the free DOFs: this
//! rank's elements, their history, the loads in force and contact. The loops that assemble
//! the residual and the Jacobian, and the implementation of SNES's `NonlinearProblem`, are in
//! `problem/assembly.rs`.
//!
//! History: a residual evaluation reads `committed` (the last converged increment) and writes
//! `trial`; [`Problem::commit`] copies trial to committed after a converged increment. A failed
//! attempt never touches `committed`, so a cutback has nothing to undo.

use crate::decomposition::{DofMap, Partition};
use crate::element::body_load::BodyForce;
use crate::element::solid::ElementMatrix;
use crate::element::solid::{compute_solid, solid_tangent, ElementGeometry, MaterialTangents, SolidInput, SolidResponse, DOFS, NODES, QUADRATURE_POINTS};
use crate::error::{Error, Result};
use crate::fe::section::Section;
use crate::fe::shape::Shape;
use crate::material::{Kinematics, PointState, SurfaceBranch, J2};
use crate::model::{Material, Model, Temperature};
use crate::petsc::sys::PetscInt;
use crate::petsc::{LogStage, Matrix, PetscSession, Scatter, VecOps, Vector};
use crate::solve::contact::surfaces::contact_nodes;
use crate::solve::contact::{ContactAssembly, ContactCarry, Need};
use crate::solve::jacobian::layout::JacobianLayout;
use crate::solve::problem::constraints::ConstraintAssembly;
use crate::solve::problem::kept::{KeptTangent, KeptTangents, LastEvaluation};
pub use kept::ElementFields;

mod assembly;
pub mod constraints;
pub(super) mod held;
pub(super) mod kept;
pub(super) mod roundoff;
pub mod schedule;

/// Loads and prescribed values at the current load factor.
#[derive(Clone, Debug)]
pub struct LoadState {
    /// Value of every prescribed DOF (node, component); entries of free DOFs are unused.
    pub prescribed: Vec<[f64; 2]>,
    /// The temperature, degC.
    pub temperature: Temperature,
    /// (surface name, pressure in MPa).
    pub pressures: Vec<(String, f64)>,
    /// (element set, body force per unit mass).
    pub body_loads: Vec<(String, BodyForce)>,
    /// (node, component, force per radian).
    pub nodal_forces: Vec<(usize, usize, f64)>,
}

/// PETSc log stages of the assembly, so `-log_view` splits a Newton iteration into residual,
/// Jacobian and contact (search and kernels) time; the linear solve stays in the main stage.
#[derive(Clone, Copy, Debug)]
pub struct Stages {
    pub residual: LogStage,
    pub jacobian: LogStage,
    pub contact: LogStage,
    pub output: LogStage,
}

impl Stages {
    pub fn new() -> Result<Self> {
        Ok(Stages {
            residual: LogStage::named("Residual")?,
            jacobian: LogStage::named("Jacobian")?,
            contact: LogStage::named("Contact")?,
            output: LogStage::named("Output")?,
        })
    }
}

/// History of every Gauss point of this rank's elements (in local element order).
pub type History = Vec<[PointState; QUADRATURE_POINTS]>;

/// A tensor [rr, zz, tt, rz] at each Gauss point of an element.
pub type PointTensors = [[f64; 4]; QUADRATURE_POINTS];

/// One element this rank assembles, with everything the loops need precomputed.
struct LocalElement {
    element: usize,
    geometry: ElementGeometry,
    coords: [[f64; 2]; NODES],
    /// Global unknown of each element DOF, -1 where prescribed (PETSc skips negative indices).
    dofs: [PetscInt; DOFS],
    /// Position of each free element DOF in the gathered vector.
    slots: [usize; DOFS],
    material: usize,
    /// E times the mean radius, and the element's size: its force is computed from F = I +
    /// grad u, so its round-off is about eps * E * r * (|u| + size) per radian (the size's
    /// share dominates in a stiff body that moves rigidly).
    roundoff_scale: f64,
    roundoff_length: f64,
}

pub struct Problem<'s, 'm> {
    model: &'m Model,
    materials: Vec<J2>,
    elements: Vec<LocalElement>,
    /// For each surface of the model: the (local element index, side) of its edges on this rank.
    surface_edges: Vec<(String, Vec<(usize, usize)>)>,
    /// For each element set a step's body load names: its local elements on this rank.
    loaded_elements: Vec<(String, Vec<usize>)>,
    /// The free DOFs this rank reads and writes (its elements' and every contact node's):
    /// gathered from the unknowns by `scatter`, and the residual added back through it.
    gathered: Vector<'s>,
    scatter: Scatter<'s>,
    /// Position in `gathered` of every (node, component) it holds, usize::MAX elsewhere.
    node_slots: Vec<[usize; 2]>,
    /// The nodes this rank owns: it alone adds their nodal forces.
    owns_node: Vec<bool>,
    /// This rank's residual contributions, in `gathered`'s order.
    local_residual: Vector<'s>,
    session: &'s PetscSession,
    /// The step's numbering: global unknown of every (node, component), -1 where prescribed.
    dofs: DofMap,
    committed: History,
    trial: History,
    /// Material tangents of the last residual evaluation (see [`KeptTangents`]).
    kept: KeptTangents,
    /// Its output fields (dropped at every commit, which changes the history).
    last: Option<LastEvaluation>,
    /// Where each Jacobian entry goes (elements and this rank's contact couplings).
    layout: JacobianLayout,
    /// Whether a Jacobian has replaced the matrix's structure since the solver last asked.
    structure_changed: bool,
    /// The mesh's largest distance from the origin (the field test's correction floor).
    model_size: f64,
    /// Round-off floor (squared, this rank) of the last residual.
    roundoff: f64,
    /// Sum of the magnitudes of the element and contact nodal forces of the last residual,
    /// and their number (this rank): the field convergence test's average force.
    force_sums: [f64; 2],
    /// How points on the yield surface respond (flowing while the load predictor's tangent
    /// is formed, elastic otherwise).
    surface: SurfaceBranch,
    pub contact: Option<ContactAssembly>,
    /// This rank's multi-point constraints.
    constraints: Option<ConstraintAssembly>,
    load: LoadState,
    /// Counts the loads set, so what was evaluated under a load can tell it is still in force.
    load_generation: u64,
    pub stages: Stages,
}

/// The Jacobian's layout: the local elements' entries and this rank's contact couplings.
fn jacobian_layout(elements: &[LocalElement], contact: Option<&ContactAssembly>, constraints: Option<&ConstraintAssembly>, dofs: &DofMap) -> JacobianLayout {
    let element_dofs: Vec<[PetscInt; DOFS]> = elements.iter().map(|el| el.dofs).collect();
    JacobianLayout::new(&element_dofs, coupled_pairs(contact, constraints), &dofs.dof)
}

/// The node pairs the Jacobian couples beyond the elements: contact's and the constraints'.
fn coupled_pairs(contact: Option<&ContactAssembly>, constraints: Option<&ConstraintAssembly>) -> Vec<(usize, usize)> {
    let contact = contact.into_iter().flat_map(|c| c.pattern().pairs());
    contact.chain(constraints.into_iter().flat_map(|c| c.pairs())).collect()
}

/// The material kernel of a model material.
pub fn material_kernel(m: &Material) -> J2 {
    match m.plasticity {
        None => J2::elastic(m.youngs_modulus, m.poissons_ratio, m.thermal_expansion),
        Some(h) => J2 { kinematic: m.kinematic, ..J2::with_hardening(m.youngs_modulus, m.poissons_ratio, m.thermal_expansion, h) },
    }
}

/// Initial history of this rank's elements.
pub fn initial_history(model: &Model, partition: &Partition) -> History {
    vec![[PointState::initial(model.kinematics); QUADRATURE_POINTS]; partition.local_elements().len()]
}

/// Where a step's problem starts: the step (its contact pairs' friction), the committed
/// history of this rank's elements, and what contact carries from the step before.
pub struct StepStart {
    pub step: usize,
    pub history: History,
    pub contact: Option<ContactCarry>,
}

impl<'s, 'm> Problem<'s, 'm> {
    /// The problem of a step; `layout` is any global vector with the layout of the unknowns.
    pub fn new(session: &'s PetscSession, model: &'m Model, partition: &Partition, dofs: &DofMap, layout: &Vector<'s>, start: StepStart) -> Result<Self> {
        let StepStart { step, history, contact } = start;
        let local = partition.local_elements();
        assert_eq!(history.len(), local.len(), "one history entry per local element");
        // Free DOFs this rank's elements touch and those of every contact and constraint node:
        // fetched by one scatter per evaluation, and the residual added back through the same
        // scatter
        let contact_nodes = contact_nodes(model);
        let constrained = model.constrained_nodes();
        let constraint_nodes = (0..constrained.len()).filter(|&n| constrained[n]);
        let mut needed: Vec<PetscInt> = local
            .iter()
            .flat_map(|&e| model.mesh.elements[e])
            .chain(contact_nodes.iter().copied())
            .chain(constraint_nodes)
            .flat_map(|n| dofs.dof[n])
            .filter(|&d| d >= 0)
            .collect();
        needed.sort_unstable();
        needed.dedup();
        let gathered = Vector::seq(session, needed.len())?;
        let scatter = Scatter::gather(session, layout, &gathered, &needed)?;
        let slot_of = |g: PetscInt| needed.binary_search(&g).expect("needed holds every local free DOF");
        let mut node_slots = vec![[usize::MAX; 2]; model.mesh.coords.len()];
        for (n, d) in dofs.dof.iter().enumerate() {
            for c in 0..2 {
                if d[c] >= 0 {
                    node_slots[n][c] = needed.binary_search(&d[c]).unwrap_or(usize::MAX);
                }
            }
        }
        let mut elements = Vec::with_capacity(local.len());
        for &e in local {
            let conn = model.mesh.elements[e];
            let mut d = [-1; DOFS];
            let mut slots = [usize::MAX; DOFS];
            // a T6's two unused slots keep DOF -1: their rows and columns are zero
            for a in 0..Shape::of(&conn).nodes() {
                for c in 0..2 {
                    let g = dofs.dof[conn[a]][c];
                    d[2 * a + c] = g;
                    if g >= 0 {
                        slots[2 * a + c] = slot_of(g);
                    }
                }
            }
            let coords = model.mesh.element_coords(e);
            let geometry = model.element_geometry(e, &coords).map_err(|m| Error::input(format!("element {}: {m}", model.mesh.element_ids[e])))?;
            let mat = &model.materials[model.element_material[e]];
            let roundoff_scale = mat.youngs_modulus * geometry.mean_measure();
            let extent = |c: usize| coords.iter().map(|x| x[c]).fold(f64::MIN, f64::max) - coords.iter().map(|x| x[c]).fold(f64::MAX, f64::min);
            let roundoff_length = extent(0).hypot(extent(1));
            elements.push(LocalElement { element: e, geometry, coords, dofs: d, slots, material: model.element_material[e], roundoff_scale, roundoff_length });
        }
        let mut position = vec![usize::MAX; model.mesh.elements.len()];
        for (k, el) in elements.iter().enumerate() {
            position[el.element] = k;
        }
        let surface_edges = model
            .surfaces
            .iter()
            .map(|(name, edges)| (name.clone(), edges.iter().filter(|e| position[e.element] != usize::MAX).map(|e| (position[e.element], e.side)).collect()))
            .collect();
        let loaded: std::collections::BTreeSet<&String> = model.general_steps().flat_map(|s| s.body_loads.iter().map(|b| &b.elements)).collect();
        let loaded_elements = loaded
            .into_iter()
            .map(|name| (name.clone(), model.element_sets[name].iter().filter(|&&e| position[e] != usize::MAX).map(|&e| position[e]).collect()))
            .collect();
        let materials = model.materials.iter().map(material_kernel).collect();
        let trial = history.clone();
        let contact = ContactAssembly::new(model, step, partition, dofs, slot_of, contact);
        let local_residual = gathered.duplicate()?;
        let constraints = ConstraintAssembly::new(model, partition, dofs, slot_of);
        let layout = jacobian_layout(&elements, contact.as_ref(), constraints.as_ref(), dofs);
        Ok(Problem {
            model,
            materials,
            elements,
            surface_edges,
            loaded_elements,
            gathered,
            scatter,
            node_slots,
            owns_node: partition.node_owner.iter().map(|&r| r == partition.rank).collect(),
            local_residual,
            session,
            dofs: dofs.clone(),
            committed: history,
            trial,
            kept: KeptTangents { elements: vec![KeptTangent::default(); local.len()] },
            last: None,
            layout,
            structure_changed: false,
            model_size: model.mesh.coords.iter().map(|x| x[0].hypot(x[1])).fold(0.0, f64::max),
            roundoff: 0.0,
            force_sums: [0.0, 0.0],
            surface: SurfaceBranch::Elastic,
            contact,
            constraints,
            load: LoadState {
                prescribed: Vec::new(),
                temperature: model.reference_temperature.clone(),
                pressures: Vec::new(),
                body_loads: Vec::new(),
                nodal_forces: Vec::new(),
            },
            load_generation: 0,
            stages: Stages::new()?,
        })
    }

    /// Sets how points on the yield surface respond in the tangents formed from now on;
    /// returns the previous choice.
    pub fn set_surface_branch(&mut self, surface: SurfaceBranch) -> SurfaceBranch {
        std::mem::replace(&mut self.surface, surface)
    }

    /// Leaves friction out of the evaluations (residual and tangent) from now on, or takes it
    /// back in; returns the previous choice.
    pub fn set_without_friction(&mut self, without: bool) -> bool {
        self.contact.as_mut().is_some_and(|c| c.set_without_friction(without))
    }

    /// Accepts the trial history and contact multipliers of the last evaluation (call after a
    /// converged increment).
    pub fn commit(&mut self) {
        // an element whose history did not change (no point flowed) keeps its tangents: the
        // next increment's predictor asks for the Jacobian at this very state
        for (k, (committed, trial)) in self.committed.iter_mut().zip(&self.trial).enumerate() {
            if committed != trial {
                self.kept.forget_element(k);
                *committed = *trial;
            }
        }
        self.last = None;
        if let Some(c) = self.contact.as_mut() {
            c.commit();
        }
    }

    /// Forgets what a failed attempt changed (contact multipliers; the trial history is
    /// overwritten by the next evaluation anyway).
    pub fn reset(&mut self) {
        if let Some(c) = self.contact.as_mut() {
            c.reset();
        }
    }

    /// The loads and prescribed values in force.
    pub fn load(&self) -> &LoadState {
        &self.load
    }

    /// Puts `load` in force and returns the one it replaces.
    pub fn set_load(&mut self, load: LoadState) -> LoadState {
        self.load_generation += 1;
        std::mem::replace(&mut self.load, load)
    }

    /// The committed history of this rank's elements.
    pub fn committed_history(&self) -> &History {
        &self.committed
    }

    /// For output, at the Gauss points of this rank's elements: the total strain at the whole
    /// mesh's `displacement` (with the plane-stress thickness stretches of its evaluation,
    /// `thickness_stretch`), and the plastic strain tensor of the committed history.
    pub fn strain_fields(&self, displacement: &[[f64; 2]], thickness_stretch: &[[f64; QUADRATURE_POINTS]]) -> (Vec<PointTensors>, Vec<PointTensors>) {
        let kinematics = self.model.kinematics;
        let total = self
            .elements
            .iter()
            .zip(thickness_stretch)
            .map(|(el, stretch)| {
                let plane_stress = matches!(el.geometry.section(), Section::PlaneStress { .. });
                el.geometry.total_strain(kinematics, &self.model.mesh.elements[el.element].map(|n| displacement[n]), plane_stress.then_some(stretch))
            })
            .collect();
        let plastic = self.committed.iter().map(|points| points.map(|p| p.plastic_strain_tensor(kinematics))).collect();
        (total, plastic)
    }

    /// The committed backstress at the Gauss points (the sum of its terms; kinematic hardening).
    pub fn backstress_field(&self) -> Vec<[[f64; 4]; QUADRATURE_POINTS]> {
        self.committed.iter().map(|points| points.map(|p| std::array::from_fn(|c| p.back.iter().map(|a| a[c]).sum()))).collect()
    }

    /// The committed history and what contact carries, for the next step's problem.
    pub fn into_history(self) -> (History, Option<ContactCarry>) {
        (self.committed, self.contact.map(|c| c.into_carry()))
    }

    /// A new matrix for this step's Jacobian, its structure the layout's: the elements and
    /// every contact coupling found so far (see `fit_pattern`).
    pub fn jacobian_matrix(&mut self) -> Result<Matrix<'s>> {
        self.layout.forget_storage();
        let (rows, cols) = self.layout.indices();
        Matrix::aij_coo(self.session, self.session.comm(), self.dofs.local_len(), rows, cols)
    }

    /// Whether Jacobians go straight into PETSc's storage of the matrix (from its second
    /// assembly on; see `JacobianLayout::hand_over`).
    pub fn writes_jacobian_storage(&self) -> bool {
        self.layout.writes_storage()
    }

    /// Fetches the free DOFs of this rank's elements (and the positions of all contact nodes)
    /// from the global vector `x`.
    fn gather(&mut self, x: &impl VecOps) -> Result<Vec<f64>> {
        self.scatter.forward(x, &mut self.gathered)?;
        let gathered = self.gathered.read()?.to_vec();
        if let Some(c) = self.contact.as_mut() {
            c.gather(self.model, &gathered, &self.load.prescribed);
        }
        Ok(gathered)
    }

    fn displacements(&self, el: &LocalElement, gathered: &[f64]) -> [[f64; 2]; NODES] {
        let conn = &self.model.mesh.elements[el.element];
        std::array::from_fn(|a| std::array::from_fn(|c| if el.dofs[2 * a + c] >= 0 { gathered[el.slots[2 * a + c]] } else { self.load.prescribed[conn[a]][c] }))
    }

    /// The temperature change from the reference at the nodes of local element `k`, degC.
    fn temperature_change(&self, k: usize) -> [f64; NODES] {
        let conn = &self.model.mesh.elements[self.elements[k].element];
        conn.map(|n| self.load.temperature.at(n) - self.model.reference_temperature.at(n))
    }

    fn solid(&self, k: usize, u: &[[f64; 2]; NODES], temperature_change: &[f64; NODES], tangents: Option<&mut MaterialTangents>) -> Result<SolidResponse> {
        let el = &self.elements[k];
        let input = SolidInput {
            geometry: &el.geometry,
            material: &self.materials[el.material],
            kinematics: self.model.kinematics,
            temperature_change: *temperature_change,
            committed: &self.committed[k],
            surface: self.surface,
        };
        compute_solid(&input, u, tangents).map_err(|m| Error::Domain(format!("element {}: {m}", self.model.mesh.element_ids[el.element])))
    }

    /// The tangent of local element `k` at displacements `u`, from the material tangents its
    /// last residual evaluation kept when that was at `u`, else by a new evaluation.
    fn element_tangent(&self, k: usize, u: &[[f64; 2]; NODES]) -> Result<ElementMatrix> {
        let geometry = &self.elements[k].geometry;
        // the kept tangents are the residual's, elastic on the yield surface
        let temperature_change = self.temperature_change(k);
        if self.surface == SurfaceBranch::Elastic {
            if let Some(material) = self.kept.get(k, u, &temperature_change) {
                return Ok(solid_tangent(geometry, material));
            }
        }
        let mut material = MaterialTangents::default();
        self.solid(k, u, &temperature_change, Some(&mut material))?;
        Ok(solid_tangent(geometry, &material))
    }

    /// Pressure edges on this rank: (local element, local node numbers, pressure).
    fn pressure_edges(&self) -> impl Iterator<Item = (usize, [usize; 3], f64)> + '_ {
        self.load.pressures.iter().flat_map(move |(surface, p)| {
            let edges = self.surface_edges.iter().find(|(n, _)| n == surface).map(|(_, e)| e.as_slice()).unwrap_or(&[]);
            edges.iter().map(move |&(k, side)| (k, Shape::of(&self.model.mesh.elements[self.elements[k].element]).edge_nodes(side), *p))
        })
    }

    /// Body-loaded elements on this rank: (local element, its density, the force per unit mass).
    fn body_loaded(&self) -> impl Iterator<Item = (usize, f64, BodyForce)> + '_ {
        self.load.body_loads.iter().flat_map(move |(set, force)| {
            let elements = self.loaded_elements.iter().find(|(n, _)| n == set).map(|(_, e)| e.as_slice()).unwrap_or(&[]);
            elements.iter().map(move |&k| (k, self.model.materials[self.elements[k].material].density, *force))
        })
    }

    /// Edge node positions the pressure acts on: current (finite strain) or reference.
    fn edge_positions(&self, k: usize, local: &[usize; 3], u: &[[f64; 2]; NODES]) -> [[f64; 2]; 3] {
        let x = &self.elements[k].coords;
        match self.model.kinematics {
            Kinematics::Finite => local.map(|a| [x[a][0] + u[a][0], x[a][1] + u[a][1]]),
            Kinematics::Small => local.map(|a| x[a]),
        }
    }

    /// Stresses, plastic strains and nodal forces at the state `x` (after convergence, for
    /// output and reactions); also leaves the trial history of `x` ready to commit.
    pub fn evaluate_fields(&mut self, x: &impl VecOps) -> Result<ElementFields> {
        let gathered = self.gather(x)?;
        let multipliers = self.contact.as_ref().map(|c| c.multipliers());
        if let Some(last) = self.last.as_ref().filter(|l| l.gathered == gathered && l.load == self.load_generation && l.multipliers.as_ref() == multipliers) {
            // the last residual was evaluated here: its trial history, fields and (cached)
            // contact states are those of x
            let fields = last.fields.clone();
            if let Some(c) = self.contact.as_mut() {
                c.evaluate(self.model, Need::Residual);
            }
            return Ok(fields);
        }
        let mut fields = ElementFields::zeros(self.elements.len(), self.model.mesh.coords.len());
        self.residual_entries(&gathered, false, &mut fields, |_, _, _| {})?;
        Ok(fields)
    }
}

//! The discrete nonlinear problem F(u) = f_int(u) - f_ext = 0 over the free DOFs, evaluated
//! by looping over this rank's elements and adding into PETSc (off-rank rows go through the
//! stash). Implements [`NonlinearProblem`] for SNES.

use crate::dist::{DofMap, Partition};
use crate::element::pressure::compute_pressure_load;
use crate::element::solid::{compute_solid, ElementMatrix, DOFS, NODES, QUADRATURE_POINTS};
use crate::error::{Error, Result};
use crate::fe::shape::edge_nodes;
use crate::material::elastic::Elastic;
use crate::model::Model;
use crate::petsc::sys::PetscInt;
use crate::petsc::{
    MatOps, MatrixView, NonlinearProblem, PetscSession, Scatter, VecOps, Vector, VectorView,
};

/// Loads and prescribed values at the current load factor.
#[derive(Clone, Debug, Default)]
pub struct LoadState {
    /// Value of every prescribed DOF (node, component); entries of free DOFs are unused.
    pub prescribed: Vec<[f64; 2]>,
    /// Uniform temperature minus the reference temperature (degC).
    pub temperature_change: f64,
    /// (surface name, pressure in MPa).
    pub pressures: Vec<(String, f64)>,
}

/// One element this rank assembles, with everything the loops need precomputed.
struct LocalElement {
    element: usize,
    coords: [[f64; 2]; NODES],
    /// Global unknown of each element DOF, -1 where prescribed (PETSc skips negative indices).
    dofs: [PetscInt; DOFS],
    /// Position of each free element DOF in the gathered vector.
    slots: [usize; DOFS],
    material: usize,
}

/// What an evaluation at a converged state gives for output.
pub struct ElementFields {
    /// Stress at the quadrature points of each local element (partition order).
    pub stress: Vec<[[f64; 4]; QUADRATURE_POINTS]>,
    /// This rank's part of f_int - f_ext at every node of the mesh (summed over ranks, it is
    /// the reaction at prescribed DOFs), per radian.
    pub nodal_force: Vec<[f64; 2]>,
}

pub struct Problem<'s, 'm> {
    model: &'m Model,
    materials: Vec<Elastic>,
    elements: Vec<LocalElement>,
    /// For each surface of the model: the (local element index, side) of its edges on this rank.
    surface_edges: Vec<(String, Vec<(usize, usize)>)>,
    gathered: Vector<'s>,
    scatter: Scatter<'s>,
    pub load: LoadState,
}

impl<'s, 'm> Problem<'s, 'm> {
    /// `layout` is any global vector with the layout of the unknowns.
    pub fn new(
        session: &'s PetscSession,
        model: &'m Model,
        partition: &Partition,
        dofs: &DofMap,
        layout: &Vector<'s>,
    ) -> Result<Self> {
        let local = partition.local_elements();
        // Free DOFs this rank's elements touch, fetched by one scatter per evaluation.
        let mut needed: Vec<PetscInt> = local
            .iter()
            .flat_map(|&e| model.mesh.elements[e])
            .flat_map(|n| dofs.dof[n])
            .filter(|&d| d >= 0)
            .collect();
        needed.sort_unstable();
        needed.dedup();
        let gathered = Vector::seq(session, needed.len())?;
        let scatter = Scatter::gather(session, layout, &gathered, &needed)?;
        let elements = local
            .iter()
            .map(|&e| {
                let conn = model.mesh.elements[e];
                let mut d = [-1; DOFS];
                let mut slots = [usize::MAX; DOFS];
                for a in 0..NODES {
                    for c in 0..2 {
                        let g = dofs.dof[conn[a]][c];
                        d[2 * a + c] = g;
                        if g >= 0 {
                            slots[2 * a + c] = needed
                                .binary_search(&g)
                                .expect("needed holds every local free DOF");
                        }
                    }
                }
                LocalElement {
                    element: e,
                    coords: model.mesh.element_coords(e),
                    dofs: d,
                    slots,
                    material: model.element_material[e],
                }
            })
            .collect::<Vec<_>>();
        let mut position = vec![usize::MAX; model.mesh.elements.len()];
        for (k, el) in elements.iter().enumerate() {
            position[el.element] = k;
        }
        let surface_edges = model
            .surfaces
            .iter()
            .map(|(name, edges)| {
                (
                    name.clone(),
                    edges
                        .iter()
                        .filter(|e| position[e.element] != usize::MAX)
                        .map(|e| (position[e.element], e.side))
                        .collect(),
                )
            })
            .collect();
        let materials = model
            .materials
            .iter()
            .map(|m| Elastic::from_model(&m.model))
            .collect();
        Ok(Problem {
            model,
            materials,
            elements,
            surface_edges,
            gathered,
            scatter,
            load: LoadState::default(),
        })
    }

    /// Fetches the free DOFs of this rank's elements from the global vector `x`.
    fn gather(&mut self, x: &impl VecOps) -> Result<()> {
        self.scatter.forward(x, &mut self.gathered)
    }

    fn displacements(&self, el: &LocalElement, gathered: &[f64]) -> [[f64; 2]; NODES] {
        let conn = &self.model.mesh.elements[el.element];
        std::array::from_fn(|a| {
            std::array::from_fn(|c| {
                if el.dofs[2 * a + c] >= 0 {
                    gathered[el.slots[2 * a + c]]
                } else {
                    self.load.prescribed[conn[a]][c]
                }
            })
        })
    }

    fn domain_error(&self, el: &LocalElement, msg: String) -> Error {
        Error::Domain(format!(
            "element {}: {msg}",
            self.model.mesh.element_ids[el.element]
        ))
    }

    /// Calls `sink(element, element DOF, node, component, value)` for every entry of
    /// f_int - f_ext of this rank's elements and pressure edges.
    fn residual_entries(
        &self,
        gathered: &[f64],
        mut on_stress: impl FnMut(usize, &[[f64; 4]; QUADRATURE_POINTS]),
        mut sink: impl FnMut(&LocalElement, usize, f64),
    ) -> Result<()> {
        for (k, el) in self.elements.iter().enumerate() {
            let u = self.displacements(el, gathered);
            let out = compute_solid(
                &el.coords,
                &u,
                self.load.temperature_change,
                &self.materials[el.material],
                false,
            )
            .map_err(|m| self.domain_error(el, m))?;
            on_stress(k, &out.stress);
            for i in 0..DOFS {
                sink(el, i, out.internal_force[i]);
            }
        }
        for (surface, p) in &self.load.pressures {
            let Some((_, edges)) = self.surface_edges.iter().find(|(n, _)| n == surface) else {
                continue;
            };
            for &(k, side) in edges {
                let el = &self.elements[k];
                let local = edge_nodes(side);
                let f = compute_pressure_load(&local.map(|a| el.coords[a]), *p);
                for (j, &a) in local.iter().enumerate() {
                    for c in 0..2 {
                        sink(el, 2 * a + c, -f[j][c]);
                    }
                }
            }
        }
        Ok(())
    }

    /// Stresses and nodal forces at the state `x` (after convergence, for output and reactions).
    pub fn evaluate_fields(&mut self, x: &impl VecOps) -> Result<ElementFields> {
        self.gather(x)?;
        let gathered = self.gathered.read()?.to_vec();
        let mut stress = vec![[[0.0; 4]; QUADRATURE_POINTS]; self.elements.len()];
        let mut nodal_force = vec![[0.0; 2]; self.model.mesh.coords.len()];
        let conn = |el: &LocalElement| self.model.mesh.elements[el.element];
        self.residual_entries(
            &gathered,
            |k, s| stress[k] = *s,
            |el, i, v| nodal_force[conn(el)[i / 2]][i % 2] += v,
        )?;
        Ok(ElementFields {
            stress,
            nodal_force,
        })
    }
}

impl NonlinearProblem for Problem<'_, '_> {
    fn residual(&mut self, x: &VectorView<'_>, f: &mut VectorView<'_>) -> Result<()> {
        self.gather(x)?;
        let gathered = self.gathered.read()?.to_vec();
        f.set_all(0.0)?;
        let mut rows: Vec<PetscInt> = Vec::with_capacity(DOFS);
        let mut values: Vec<f64> = Vec::with_capacity(DOFS);
        self.residual_entries(
            &gathered,
            |_, _| {},
            |el, i, v| {
                if el.dofs[i] >= 0 {
                    rows.push(el.dofs[i]);
                    values.push(v);
                }
            },
        )?;
        f.add_values(&rows, &values)?;
        f.assemble()
    }

    fn jacobian(&mut self, x: &VectorView<'_>, jacobian: &mut MatrixView<'_>) -> Result<()> {
        self.gather(x)?;
        let gathered = self.gathered.read()?.to_vec();
        jacobian.zero_entries()?;
        for el in &self.elements {
            let u = self.displacements(el, &gathered);
            let out = compute_solid(
                &el.coords,
                &u,
                self.load.temperature_change,
                &self.materials[el.material],
                true,
            )
            .map_err(|m| self.domain_error(el, m))?;
            let k: ElementMatrix = out.tangent.expect("tangent requested");
            // nalgebra is column-major; PETSc wants row-major: the transpose's storage is.
            jacobian.add_block(&el.dofs, &el.dofs, k.transpose().as_slice())?;
        }
        jacobian.assemble()
    }
}

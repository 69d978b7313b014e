//! Units and a description of every dataset of a results file, written as its `units` and
//! `description` attributes so that the file explains itself to any HDF5 reader.

/// Where a Gauss-point dataset's 9 slots of an element are.
const SLOTS: &str = "the 9 Gauss slots of each element (a Q8's 3 x 3 points, xi fastest; a T6's conical rule; a reduced Q8's 2 x 2 points, xi fastest, or a CAX6's 3 points, in the first slots and NaN in the rest: /mesh/gauss_points)";

/// (units, description) of dataset `name` in group `group` (an HDF5 path such as
/// `/increments/000001/contact/fit/pass0`).
pub fn describe(group: &str, name: &str) -> (&'static str, String) {
    let g = group.trim_start_matches('/');
    let top = g.split('/').next().unwrap_or("");
    if let Some(described) = describe_sets_state_and_side_results(g, top, name) {
        return described;
    }
    match (top, name) {
        ("mesh", "coordinates") => ("mm", "r, z of each node".into()),
        ("mesh", "connectivity") => (
            "-",
            "the 8 node slots of each element (rows of /mesh/coordinates), corners then mid-sides, counter-clockwise; a 6-node triangle's last two repeat its first".into(),
        ),
        ("mesh", "topology") => (
            "-",
            "the cells in XDMF's form: a mesh of triangles, the 6 nodes of each; a mixed mesh, each cell's type (36 a 6-node triangle, 37 an 8-node quadrilateral) then its nodes".into(),
        ),
        ("mesh", "node_ids") => ("-", "external node numbers (the input's)".into()),
        ("mesh", "element_ids") => ("-", "external element numbers (the input's)".into()),
        ("mesh", "element_rank") => ("-", "MPI rank that assembled the element".into()),
        ("mesh", "gauss_points") => ("-", "how many of each element's 9 Gauss slots are integration points: 9, or 4 in a reduced Q8 (CAX8R, CPE8R, CPS8R), 3 in an .inp deck's T6 (CAX6, CPE6, CPS6)".into()),
        ("mesh", "nodes") => ("-", "slave nodes of the contact pass (rows of /mesh/coordinates)".into()),
        ("mesh", "areas") => ("mm^2 per radian", "tributary area of each slave node of the contact pass (NaN for a node-based slave: its area is the increment's `area`)".into()),
        (_, "area") => ("mm^2 per radian", "a node-based slave's area: the master face's where each node projects (CalculiX's rule), 0 where none is within reach".into()),
        ("initial", "vector") => ("mm", "zero vectors at the nodes: the t = 0 frame's displacement and reaction force".into()),
        ("initial", "scalar") => ("-", "zeros at the nodes: the t = 0 frame's stresses and strains".into()),
        ("initial", "temperature") => ("degC", "the reference temperature at the nodes (the t = 0 frame)".into()),
        (_, "element_nodal_stress") => {
            ("MPa", "Cauchy stress [s_rr, s_zz, s_tt, s_rz] at each element's 8 nodes before averaging (extrapolated or copied as for the nodal fields)".into())
        }
        (_, "reaction_force") => ("N per radian", "reaction force r, z, 0 at the nodes with a prescribed displacement, 0 elsewhere".into()),
        (_, "pressure") if g.ends_with("nodal") => ("MPa", "hydrostatic pressure -(s_rr + s_zz + s_tt) / 3 of the nodal stress".into()),
        (_, "principal_stress_max") => ("MPa", "largest principal stress of the nodal stress (the hoop stress is principal)".into()),
        (_, "principal_stress_min") => ("MPa", "smallest principal stress of the nodal stress".into()),
        (_, n) if n.starts_with("strain_") => {
            ("-", format!("total strain {} at the nodes: logarithmic (finite strain) or small strain, tensor shear", n.trim_start_matches("strain_")))
        }
        (_, n) if n.starts_with("plastic_strain_") => (
            "-",
            format!(
                "plastic strain {} at the nodes: ln(C_p) / 2 (finite strain) or eps_p (small strain), tensor shear, copied from the nearest Gauss point",
                n.trim_start_matches("plastic_strain_")
            ),
        ),
        (_, "backstress") => ("MPa", format!("backstress of kinematic hardening, the sum of its terms [rr, zz, tt, rz] (tensor shear), at {SLOTS}")),
        (_, "backstress_von_mises") => ("MPa", "von Mises equivalent of the backstress at the nodes, copied from the nearest Gauss point".into()),
        (_, n) if n.starts_with("backstress_") => {
            ("MPa", format!("backstress {} at the nodes (kinematic hardening), copied from the nearest Gauss point", n.trim_start_matches("backstress_")))
        }
        (_, "friction_shear") => ("MPa", "frictional shear traction at the slave nodes (the largest in magnitude over their pairs), 0 elsewhere".into()),
        (_, "contact_sliding") => ("-", "1 where a slave node slides (friction at its Coulomb limit), 0 where it sticks, is open, or is no slave".into()),
        (_, "displacement") if g.ends_with("nodal") => ("mm", "u_r, u_z, 0 at each node (a 3-vector for ParaView)".into()),
        (_, "displacement") => ("mm", "u_r, u_z at each node".into()),
        (_, "stress") => ("MPa", format!("Cauchy stress [s_rr, s_zz, s_tt, s_rz] at {SLOTS}")),
        (_, "von_mises") if g.ends_with("nodal") => {
            ("MPa", "von Mises stress of the nodal stress components (Gauss values carried to the nodes and averaged; see docs/results.md)".into())
        }
        (_, "von_mises") => ("MPa", format!("von Mises stress at {SLOTS}")),
        (_, "von_mises_mean") => ("MPa", "element mean of the von Mises stress over its Gauss points".into()),
        (_, "equivalent_plastic_strain") if g.ends_with("nodal") => {
            ("-", "equivalent plastic strain at the nodes (copied from each element's nearest Gauss point, averaged)".into())
        }
        (_, "equivalent_plastic_strain") => ("-", format!("equivalent plastic strain at {SLOTS}")),
        (_, "equivalent_plastic_strain_max") => ("-", "largest equivalent plastic strain of each element".into()),
        (_, "temperature") => ("degC", "temperature at the nodes".into()),
        (_, "contact_pressure") => ("MPa", "contact pressure at the nodes: the largest over the pairs a node is a slave of, 0 elsewhere".into()),
        (_, "contact_status") => ("-", "1 where a node is in contact as a slave, 0 elsewhere".into()),
        (_, "contact_gap") => ("mm", "normal gap at the slave nodes (the smallest over their pairs), NaN elsewhere".into()),
        (_, "residual_norms") => ("N per radian", "||F|| at each Newton iterate of the increment".into()),
        (_, "gap") => ("mm", "normal gap at each slave node (negative: penetration)".into()),
        (_, "pressure") => ("MPa", "contact pressure at each slave node".into()),
        (_, "traction") => ("MPa", "contact traction recovered from the nodal contact forces".into()),
        (_, "active") => ("-", "1 where the slave node is in contact".into()),
        (_, "shear") => (
            "MPa",
            "frictional traction at each slave node, along the master's tangent (positive: resisting the slave's slip in the tangent's direction)".into(),
        ),
        (_, "sliding") => ("-", "1 where the slave node slides (friction at its Coulomb limit), 0 where it sticks or is open".into()),
        (_, n) if n.starts_with("stress_") => ("MPa", format!("{} at the nodes (Gauss values carried to the nodes, averaged)", n.replace('_', " "))),
        _ => ("-", name.replace('_', " ")),
    }
}

/// (units, description) of the node and element sets, the restart state's datasets and the
/// perturbation and heat steps' results; None for the increments' fields and the mesh.
fn describe_sets_state_and_side_results(g: &str, top: &str, name: &str) -> Option<(&'static str, String)> {
    Some(match (top, name) {
        ("mesh", _) if g.ends_with("node_sets") => ("-", format!("node set {name}: rows of /mesh/coordinates")),
        ("mesh", _) if g.ends_with("element_sets") => ("-", format!("element set {name}: rows of /mesh/connectivity")),
        ("restart", "pattern") => {
            ("-", "contact couplings the Jacobian reserved: [increment number, rank, node id, node id], as they were added (restart)".into())
        }
        (_, "plastic_points") => ("-", "[element id, Gauss point] of each Gauss point that has left its initial state (restart)".into()),
        (_, "plastic_state") => (
            "-",
            "committed plastic state of those points: C_p^-1 (finite strain) or eps_p (small strain) [rr, zz, tt, rz], equivalent plastic strain (restart)"
                .into(),
        ),
        (_, "backstress_state") => (
            "MPa",
            "backstresses of those points (kinematic hardening): three terms [rr, zz, tt, rz], then their share of the plastic work (restart)".into(),
        ),
        (_, n) if n.starts_with("multiplier_nodes_pass") => {
            ("-", "node ids of the slave nodes with a nonzero augmented-Lagrangian multiplier (restart)".into())
        }
        (_, n) if n.starts_with("slip_nodes_pass") => ("-", "node ids of the slave nodes with a slip reference (friction; restart)".into()),
        (_, n) if n.starts_with("slip_pass") => {
            ("-", "their slip reference: [master edge index, edge coordinate, tangential traction (MPa)] (friction; restart)".into())
        }
        (_, "audit_nodes") => ("-", "node ids with a reaction or a pressure load (energy audit; restart)".into()),
        (_, "audit_forces") => {
            ("N per radian", "their reaction (r, z) and pressure load (r, z), where the next increment's external work starts (restart)".into())
        }
        (_, n) if n.starts_with("multipliers_pass") => ("MPa", "their committed augmented-Lagrangian multipliers (restart)".into()),
        ("perturbations", "amplitudes") => (
            "mm",
            "harmonic amplitudes [U_r, U_z, U_t] of each node: u_r = U_r cos n theta, u_z = U_z cos n theta, u_theta = U_t sin n theta (n = 0: U_t)".into(),
        ),
        ("perturbations", "eigenvalues") => ("-", "omega^2 (rad^2/s^2; frequency steps) or the load factor (buckle steps) of each mode, nearest zero first".into()),
        ("perturbations", "frequencies") => ("Hz", "natural frequency of each mode (negative: the base state is unstable in it)".into()),
        ("perturbations", "effective_mass_ring") => ("t", "each mode's effective mass along its mode's rigid motion (n = 0 axial, n = 1 lateral), full ring".into()),
        ("perturbations", n) if n.starts_with("critical_pressure_") => ("MPa", "each mode's critical pressure on the surface: the base state's plus the load factor times the step's".into()),
        ("perturbations", n) if n.starts_with("mode_") => ("-", "the mode's amplitudes [U_r, U_z, U_t] of each node, largest 1".into()),
        ("perturbations", "stress") => (
            "MPa",
            format!("stress amplitudes [s_rr, s_zz, s_tt, s_rz, s_rt, s_zt] at {SLOTS}: the first four x cos n theta, the last two x sin n theta (n = 0: constant); D : strain"),
        ),
        ("perturbations", "displacement") => ("mm", "the perturbation's displacement at theta = 0 as a vector (u_r, u_z, u_theta) for ParaView's warp".into()),
        ("heat", "temperature") => ("degC", "the heat step's steady temperature at each node".into()),
        ("heat", "flux") => ("mW/mm^2", format!("heat flux q = -k grad T [q_r, q_z] at {SLOTS}")),
        ("heat", "element_flux") => ("mW/mm^2", "each element's mean heat flux [q_r, q_z, 0] over its Gauss points, a vector for ParaView".into()),
        _ => return None,
    })
}

/// The units of a plane model's dataset or column whose axisymmetric units are `units`: its
/// forces, energies and areas are over the sections' thickness, not per radian.
pub fn plane_units(units: &'static str) -> &'static str {
    match units {
        "N per radian" => "N",
        "N mm per radian" => "N mm",
        "mm^2 per radian" => "mm^2",
        other => other,
    }
}

/// (units, description) of history column `name`.
pub fn describe_column(name: &str) -> (&'static str, String) {
    let per_radian = "N per radian";
    match name {
        "step" => ("-", "step number".into()),
        "increment" => ("-", "increment number within the step".into()),
        "load_factor" => ("-", "load factor within the step".into()),
        "time" => ("-", "total time: step - 1 + load factor, or the input deck's time".into()),
        "newton_iterations" | "linear_iterations" => ("-", name.replace('_', " ")),
        "residual_norm" => (per_radian, "||F|| at convergence".into()),
        "average_force" => (
            per_radian,
            "mean magnitude of the element and contact nodal forces at convergence (the field convergence test's; 0 under the residual test)".into(),
        ),
        "cutbacks" => ("-", "failed attempts before the increment converged".into()),
        "augmentations" => ("-", "augmented-Lagrangian multiplier updates".into()),
        "max_equivalent_plastic_strain" => ("-", "largest equivalent plastic strain of the model".into()),
        "wall_time" => ("s", "wall time since the start of the run".into()),
        "energy_external_work" => {
            ("N mm per radian", "work of the reactions on the prescribed displacements and of the pressure loads, along the load path".into())
        }
        "energy_initial_contact" => (
            "N mm per radian",
            "penalty energy of the contact overlaps in the undeformed mesh (an interference fit), an input the first increments release".into(),
        ),
        "energy_elastic" => ("N mm per radian", "stored elastic energy (Hencky: tau : C^-1 : tau / 2 over the reference volume)".into()),
        "energy_plastic_work" => ("N mm per radian", "plastic work: the integral of the yield stress over the equivalent plastic strain".into()),
        "energy_thermal_work" => ("N mm per radian", "stress power of the thermal strain along the temperature path (alpha tr(tau) dT)".into()),
        "energy_contact_stored" => ("N mm per radian", "energy stored in the contact penalties (normal eps g^2 A / 2, tangential tau^2 A / (2 eps_T))".into()),
        "energy_friction_dissipation" => ("N mm per radian", "energy dissipated by frictional slip".into()),
        "energy_balance_error" => ("N mm per radian", "external work minus elastic, plastic, thermal, contact and friction energies".into()),
        n if n.ends_with("_2deg") => ("N per 2-degree segment", format!("{} (CalculiX's axisymmetric convention)", n.replace('_', " "))),
        n if n.ends_with("_ring") => ("N", format!("{} (full 360-degree ring)", n.replace('_', " "))),
        n if n.starts_with("reaction_") || n.ends_with("_force") => (per_radian, n.replace('_', " ")),
        n if n.ends_with("_max_penetration") => ("mm", n.replace('_', " ")),
        n if n.starts_with("displacement_") => {
            ("mm", format!("{}: the mean over the set's nodes (the prescribed displacement where it is uniform)", n.replace('_', " ")))
        }
        n => ("-", n.replace('_', " ")),
    }
}

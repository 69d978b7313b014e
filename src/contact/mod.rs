//! Penalty contact kernels: the node-to-segment ("slide line") kernel of eqs. (1)-(6) of the
//! seed paper (Wriggers) and the integrated (segment-to-segment) gap, Coulomb friction's return
//! map, the harmonic perturbation's contact stiffness, contact surfaces as polylines with
//! consistent axisymmetric tributary areas, the closest-segment search and the initial
//! adjustment. Pure: no PETSc, no MPI.

pub mod adjust;
pub mod friction;
pub mod harmonic;
pub mod integrated;
pub mod node_to_edge;
pub mod search;
pub mod slideline;
pub mod surface;

/// A gap or a distance for a message, in mm: four decimals from a micrometre up, else three
/// significant digits.
pub fn format_mm(v: f64) -> String {
    if v.abs() >= 1e-3 {
        format!("{v:.4} mm")
    } else {
        format!("{v:.3e} mm")
    }
}

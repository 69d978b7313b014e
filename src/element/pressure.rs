//! Uniform pressure on a 3-node element edge, as consistent nodal forces per radian.
//!
//! The edge runs from its start to its end node in the owning element's counter-clockwise
//! order, so the outward normal is the tangent rotated clockwise: n = (t_z, -t_r) / |t|.
//! Positive pressure pushes into the body: traction = -p n. Here the load acts on the
//! reference configuration (dead load).

use crate::fe::quadrature::GAUSS3;
use crate::fe::shape::line3;

/// Nodal forces `[f_r, f_z]` per radian on the edge nodes (start, end, middle) with
/// coordinates `x`, for pressure `p`: f_a = -p * integral of N_a (t_z, -t_r) r d(xi).
pub fn compute_pressure_load(x: &[[f64; 2]; 3], p: f64) -> [[f64; 2]; 3] {
    let mut f = [[0.0; 2]; 3];
    for &(s, w) in &GAUSS3 {
        let (n, dn) = line3(s);
        let (mut r, mut t) = (0.0, [0.0; 2]);
        for a in 0..3 {
            r += n[a] * x[a][0];
            t[0] += dn[a] * x[a][0];
            t[1] += dn[a] * x[a][1];
        }
        for a in 0..3 {
            f[a][0] -= p * w * n[a] * t[1] * r;
            f[a][1] += p * w * n[a] * t[0] * r;
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bore_pressure_gives_p_times_area_per_radian() {
        // Inner face r = 100 of a ring, traversed downward (z from 10 to 0) as the left edge of
        // a counter-clockwise element: the force is +r with total p * r * length.
        let x = [[100.0, 10.0], [100.0, 0.0], [100.0, 5.0]];
        let f = compute_pressure_load(&x, 50.0);
        let total: f64 = f.iter().map(|v| v[0]).sum();
        assert!((total - 50.0 * 100.0 * 10.0).abs() < 1e-8);
        assert!(f.iter().all(|v| v[1].abs() < 1e-12));
        // consistent 1:4:1 split on a straight edge at constant r
        assert!((f[2][0] / f[0][0] - 4.0).abs() < 1e-12);
    }

    #[test]
    fn top_face_pressure_on_a_disc_is_p_times_annulus_area() {
        // Top edge of a CCW element runs from larger to smaller r; load points down (-z).
        let x = [[30.0, 1.0], [10.0, 1.0], [20.0, 1.0]];
        let f = compute_pressure_load(&x, 2.0);
        let total: f64 = f.iter().map(|v| v[1]).sum();
        let exact = -2.0 * (30.0f64.powi(2) - 10.0f64.powi(2)) / 2.0;
        assert!((total - exact).abs() < 1e-9, "{total} vs {exact}");
    }
}

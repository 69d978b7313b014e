//! Uniform pressure on a 3-node element edge, as consistent nodal forces per radian, and the
//! load stiffness of a follower pressure.
//!
//! The edge runs from its start to its end node in the owning element's counter-clockwise
//! order, so the outward normal is the tangent rotated clockwise: n = (t_z, -t_r) / |t|.
//! Positive pressure pushes into the body: traction = -p n. With `x` the current nodal
//! positions the load follows the deformed surface (finite strain); with the reference
//! positions it is a dead load (small strain).

use crate::fe::quadrature::GAUSS3;
use crate::fe::section::Section;
use crate::fe::shape::line3;

/// External nodal forces `[f_r, f_z]` per radian on the edge nodes (start, end, middle) at
/// positions `x`, for pressure `p`: f_a = -p * integral of N_a (t_z, -t_r) m d(xi), m the
/// section's measure (r per radian in axisymmetry, the thickness in a plane section).
pub fn compute_pressure_load(section: Section, x: &[[f64; 2]; 3], p: f64) -> [[f64; 2]; 3] {
    let mut f = [[0.0; 2]; 3];
    for &(s, w) in &GAUSS3 {
        let (n, dn) = line3(s);
        let (r, t) = position_and_tangent(x, &n, &dn);
        let r = section.measure(r);
        for a in 0..3 {
            f[a][0] -= p * w * n[a] * t[1] * r;
            f[a][1] += p * w * n[a] * t[0] * r;
        }
    }
    f
}

/// d f_ext / d x of a follower pressure: entry [2a + i][2b + j] = d f_(a,i) / d x_(b,j).
/// Not symmetric. The residual f_int - f_ext takes it with a minus sign.
pub fn pressure_load_stiffness(section: Section, x: &[[f64; 2]; 3], p: f64) -> [[f64; 6]; 6] {
    let mut k = [[0.0; 6]; 6];
    let slope = section.measure_slope();
    for &(s, w) in &GAUSS3 {
        let (n, dn) = line3(s);
        let (r, t) = position_and_tangent(x, &n, &dn);
        let r = section.measure(r);
        for a in 0..3 {
            for b in 0..3 {
                let c = p * w * n[a];
                k[2 * a][2 * b] -= c * t[1] * n[b] * slope;
                k[2 * a][2 * b + 1] -= c * dn[b] * r;
                k[2 * a + 1][2 * b] += c * (dn[b] * r + t[0] * n[b] * slope);
            }
        }
    }
    k
}

fn position_and_tangent(x: &[[f64; 2]; 3], n: &[f64; 3], dn: &[f64; 3]) -> (f64, [f64; 2]) {
    let (mut r, mut t) = (0.0, [0.0; 2]);
    for a in 0..3 {
        r += n[a] * x[a][0];
        t[0] += dn[a] * x[a][0];
        t[1] += dn[a] * x[a][1];
    }
    (r, t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bore_pressure_gives_p_times_area_per_radian() {
        // Inner face r = 100 of a ring, traversed downward (z from 10 to 0) as the left edge of
        // a counter-clockwise element: the force is +r with total p * r * length.
        let x = [[100.0, 10.0], [100.0, 0.0], [100.0, 5.0]];
        let f = compute_pressure_load(Section::Axisymmetric, &x, 50.0);
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
        let f = compute_pressure_load(Section::Axisymmetric, &x, 2.0);
        let total: f64 = f.iter().map(|v| v[1]).sum();
        let exact = -2.0 * (30.0f64.powi(2) - 10.0f64.powi(2)) / 2.0;
        assert!((total - exact).abs() < 1e-9, "{total} vs {exact}");
        // the same face of a plate 4 mm thick: p t L, split 1:4:1
        let f = compute_pressure_load(Section::PlaneStress { thickness: 4.0 }, &x, 2.0);
        let total: f64 = f.iter().map(|v| v[1]).sum();
        assert!((total + 2.0 * 4.0 * 20.0).abs() < 1e-9 && (f[2][1] / f[0][1] - 4.0).abs() < 1e-12, "{f:?}");
    }

    #[test]
    fn follower_load_stiffness_matches_central_differences() {
        // a curved, inclined edge
        let x = [[40.0, 3.0], [46.0, 9.0], [42.5, 6.8]];
        let p = 7.0;
        for section in [Section::Axisymmetric, Section::PlaneStrain { thickness: 3.0 }] {
            let k = pressure_load_stiffness(section, &x, p);
            let scale = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            let h = 1e-6;
            for j in 0..6 {
                let (mut xp, mut xm) = (x, x);
                xp[j / 2][j % 2] += h;
                xm[j / 2][j % 2] -= h;
                let (fp, fm) = (compute_pressure_load(section, &xp, p), compute_pressure_load(section, &xm, p));
                for i in 0..6 {
                    let fd = (fp[i / 2][i % 2] - fm[i / 2][i % 2]) / (2.0 * h);
                    assert!((fd - k[i][j]).abs() <= 1e-6 * scale, "{section:?}: K[{i}][{j}] = {} vs fd {fd}", k[i][j]);
                }
            }
        }
    }
}

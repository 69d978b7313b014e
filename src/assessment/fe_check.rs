//! The finite-element figures of a bellows beside the code's (`bellows::finite_element` computes
//! them; the results file keeps them): each stress's peak and where it is, the strain-based life.

/// The largest value of a stress and where it is ("crest 1, ply 2").
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Peak {
    pub value: f64,
    pub at: String,
}

impl Peak {
    pub fn offer(&mut self, value: f64, at: impl FnOnce() -> String) {
        if value > self.value {
            *self = Peak { value, at: at() };
        }
    }
}

/// The finite-element figures beside the code's (MPa, N/mm full ring).
#[derive(Clone, Debug, PartialEq)]
pub struct FeCheck {
    /// Hoop membrane stress from pressure, averaged over a convolution's meridian (the code's
    /// S2 is that average: the hoop load over the convolution's metal), worst convolution.
    pub s2: Peak,
    /// The largest meridional membrane and bending stresses (magnitudes), from pressure (S3,
    /// S4) and from the stroke (S5, S6).
    pub s3: Peak,
    pub s4: Peak,
    pub s5: Peak,
    pub s6: Peak,
    /// The largest 0.7 (|S3| + |S4|) + |S5| + |S6| at one point.
    pub stress_range: Peak,
    pub cycles: Option<f64>,
    /// S3 .. S6 where the pack leaves the tubes (the quarter tori off the tangents): the codes'
    /// formulas are for the convolutions between, so these are reported apart from the peaks
    /// above; they sit at the corner of a bonded tangent and grow as the mesh is refined.
    pub ends: [Peak; 4],
    /// From the end reaction of the stroke analysis.
    pub axial_rate: f64,
    /// The instability pressures by buckling analyses of the joint at rest (`stability`):
    /// column (squirm, mode 1) and in-plane (mode 0), MPa; NaN where none was found.
    pub column_instability: f64,
    pub in_plane_instability: f64,
}

/// The effective (von Mises equivalent) range of a total strain change [rr, zz, tt, rz], tensor
/// shear: (sqrt 2 / 3) sqrt((d1 - d2)^2 + (d2 - d3)^2 + (d3 - d1)^2 + 6 d_rz^2), ASME VIII-2
/// Part 5's effective strain range; for a uniaxial plastic (incompressible) strain it is that
/// strain.
pub fn effective_strain_range(d: [f64; 4]) -> f64 {
    let [a, b, c, s] = d;
    2f64.sqrt() / 3.0 * ((a - b).powi(2) + (b - c).powi(2) + (c - a).powi(2) + 6.0 * s * s).sqrt()
}

/// The fatigue life of the stroke from the elastic-plastic run's own strains.
#[derive(Clone, Debug, PartialEq)]
pub struct StrainLife {
    /// The largest effective total strain range over the plies' nodes between the stroke's
    /// start and its end.
    pub strain_range: f64,
    /// Where, in the undeformed mesh (r, z mm).
    pub at: [f64; 2],
    /// The pseudo-elastic stress range E x strain range, MPa: the curve's St.
    pub pseudo_stress: f64,
    pub cycles: Option<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_effective_range_of_uniaxial_plastic_flow_is_its_axial_strain() {
        // plastic flow at constant volume: (-e/2, e, -e/2) in (rr, zz, tt); a volume change
        // adds nothing; pure shear gamma = 2 eps_rz gives gamma / sqrt 3
        let e = 3e-3;
        assert!((effective_strain_range([-e / 2.0, e, -e / 2.0, 0.0]) - e).abs() < 1e-18);
        assert!((effective_strain_range([-e / 2.0 + 1e-3, e + 1e-3, -e / 2.0 + 1e-3, 0.0]) - e).abs() < 1e-15);
        assert!((effective_strain_range([0.0, 0.0, 0.0, e / 2.0]) - e / 3f64.sqrt()).abs() < 1e-18);
    }
}

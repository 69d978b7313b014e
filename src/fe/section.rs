//! What an element's (r, z) plane stands for: a section of a body of revolution (per radian
//! about the axis), or a slice of a prismatic body, in plane strain (no strain along the
//! thickness) or plane stress (no stress along it), of a given thickness.
//!
//! Everything that integrates over an element or a face weights its points by the section's
//! out-of-plane measure: the radius r per radian in axisymmetry, the thickness t in a plane
//! model. Axisymmetry adds the hoop strain u_r / r; the plane sections do not, and plane stress
//! solves the thickness stretch from sigma_33 = 0 at each point (`element::solid`).

/// The kind of section of one element.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Section {
    /// A body of revolution about z; integrals per radian.
    #[default]
    Axisymmetric,
    /// A prismatic body in plane strain, `thickness` (mm) of it.
    PlaneStrain { thickness: f64 },
    /// A thin plate in plane stress, `thickness` (mm) of it.
    PlaneStress { thickness: f64 },
}

impl Section {
    /// The out-of-plane measure at radius `r`: r (per radian) or the thickness.
    #[inline]
    pub fn measure(self, r: f64) -> f64 {
        match self {
            Section::Axisymmetric => r,
            Section::PlaneStrain { thickness } | Section::PlaneStress { thickness } => thickness,
        }
    }

    /// d measure / d r: 1 in axisymmetry (a face's weight grows as it moves out), 0 in a plane.
    #[inline]
    pub fn measure_slope(self) -> f64 {
        match self {
            Section::Axisymmetric => 1.0,
            _ => 0.0,
        }
    }

    pub fn is_axisymmetric(self) -> bool {
        self == Section::Axisymmetric
    }

    /// The name users write: `axisymmetric`, `plane_strain`, `plane_stress`.
    pub fn name(self) -> &'static str {
        match self {
            Section::Axisymmetric => "axisymmetric",
            Section::PlaneStrain { .. } => "plane_strain",
            Section::PlaneStress { .. } => "plane_stress",
        }
    }
}

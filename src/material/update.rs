//! A quadrature point's update: J2 plasticity's isotropic kernel ([`super::j2`]) or, for a
//! material with backstresses, the kinematic one ([`super::kinematic`]), each beside the other.

use super::j2::{Kinematics, PointState, SurfaceBranch, Update, J2};
use super::kinematic;
use crate::ad::Scalar;

impl J2 {
    /// Stress and trial history at deformation `f`, projected volume measure `theta`,
    /// temperature change `dt`, from the `committed` history. Fails (a domain error for the
    /// solver) when the deformation is not admissible.
    pub fn update<T: Scalar>(&self, kinematics: Kinematics, f: &[T; 5], theta: T, dt: f64, committed: &PointState) -> Result<Update<T>, String> {
        self.update_on(SurfaceBranch::Elastic, kinematics, f, theta, dt, committed)
    }

    /// [`J2::update`] with the given treatment of trial states on the yield surface.
    pub fn update_on<T: Scalar>(
        &self,
        branch: SurfaceBranch,
        kinematics: Kinematics,
        f: &[T; 5],
        theta: T,
        dt: f64,
        committed: &PointState,
    ) -> Result<Update<T>, String> {
        match (kinematics, self.kinematic.is_empty()) {
            (Kinematics::Finite, true) => self.update_finite(branch, f, theta, dt, committed),
            (Kinematics::Small, true) => Ok(self.update_small(branch, f, theta, dt, committed)),
            (Kinematics::Finite, false) => kinematic::update_finite(self, branch, f, theta, dt, committed),
            (Kinematics::Small, false) => Ok(kinematic::update_small(self, branch, f, theta, dt, committed)),
        }
    }
}

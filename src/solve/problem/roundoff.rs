//! The residual's round-off floor: each assembled contribution (element, constraint, contact)
//! adds its size times this allowance to the floor below which Newton's residual is noise.

/// Round-off allowance per assembled contribution, in units in the last place: the floor
/// estimate ignores the linear solve's own error and the sums inside each kernel, so it is
/// generous; the accuracy tests (1e-8 MPa stresses, 1e-6 contact pressures) sit far above it.
pub const ROUNDOFF_ULPS: f64 = 100.0;

//! The bellows design assessment: the expansion joint codes' formulas beside the finite-element
//! answers. So far the formulas themselves ([`formulas`]), pure functions tested against
//! published worked calculations.

pub mod convolution;
pub mod formulas;

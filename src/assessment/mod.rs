//! The bellows design assessment: the expansion joint codes' formulas beside the finite-element
//! answers. The formulas themselves ([`formulas`]), pure functions tested against published
//! worked calculations; the chart coefficients computed from the idealised convolution
//! ([`convolution`]); the code check of a bellows with them ([`code`]).

pub mod code;
pub mod convolution;
pub mod formulas;

//! The expansion-joint codes' rules, pure: the formulas ([`formulas`]), tested against published
//! worked calculations; the chart coefficients ([`coefficients`]); the code check of a bellows
//! ([`code`]), its verdict against allowables ([`verdict`]); and the finite-element figures set
//! beside it ([`fe_check`]). The analyses that
//! compute the coefficients and the finite-element figures are the bellows area's.

pub mod code;
pub mod coefficients;
pub mod fe_check;
pub mod formulas;
pub mod verdict;

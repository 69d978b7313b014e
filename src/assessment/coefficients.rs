//! The chart coefficients of a U-shaped convolution (EJMA Figs. 4.16 to 4.18; ASME VIII-1
//! Appendix 26's Cp, Cf, Cd): read off the charts or computed (`bellows::convolution`).

/// The three coefficients.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients {
    pub cp: f64,
    pub cf: f64,
    pub cd: f64,
}

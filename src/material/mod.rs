//! Constitutive kernels: stress and consistent tangent at a quadrature point.

pub mod elastic;

//! Numbers: the crate's [`Scalar`](scalar::Scalar) trait over f64, intervals and Taylor types,
//! fast rigorous dot products of intervals, a branch-free interval product, directed rounding without mode switches, and
//! 3-vector helpers.

pub mod dot;
pub(crate) mod dyadic;
pub mod imul;
pub mod rounding;
pub mod scalar;
pub mod vec3;

//! Numbers: the crate's [`Scalar`](scalar::Scalar) trait over f64, intervals and Taylor types,
//! and fast rigorous dot products of intervals.

pub mod dot;
pub mod scalar;
pub mod vec3;

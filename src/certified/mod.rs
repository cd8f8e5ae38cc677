//! Certified curves: the intersection ODE on the validated engine.

pub mod field;
pub mod krawczyk;
pub mod tangential;

#[cfg(test)]
pub(crate) mod fixtures;

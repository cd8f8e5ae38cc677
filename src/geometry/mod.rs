//! Geometry: surfaces, rational Bézier patches, power-basis conversion, rigorous bounds.

pub mod analytic;
pub mod enclosing;
pub mod surface;

pub use enclosing::EnclosingSurface;
pub use surface::{Domain, ParametricSurface, SurfaceDerivs, Vec3};

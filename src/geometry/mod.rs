//! Geometry: surfaces, rational Bézier patches, power-basis conversion, rigorous bounds.

pub mod analytic;
pub(crate) mod bernstein;
pub mod bezier;
pub(crate) mod collapsed;
pub mod enclosure;
pub mod nurbs;
pub mod piece;
pub(crate) mod pole;
pub mod power;
pub mod surface;

pub use bezier::{PatchDerivs, RationalBezierPatch};
pub use power::PowerSurface;
pub use surface::{Domain, ParametricSurface, SurfaceDerivs, Vec3};

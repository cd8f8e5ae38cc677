//! # ssitrace
//!
//! Intersection curves of two parametric surfaces (rational Bézier patches), traced and certified.
//!
//! The layers, each importing only the ones before it:
//! [`numeric`] (the [`Scalar`] trait, rigorous dot products) → [`geometry`] (surfaces, Bézier
//! and power-basis patches, sub-patches, rigorous bounds) → [`pair`] (local geometry of `P ∩ Q`:
//! the field, Newton, Krawczyk, the contact quadratic, boundary directions, branch points) →
//! [`search`] (a start on every branch) → [`march`] (the fast circular-step marcher) →
//! [`topology`] (all branches, the arc graph, branch ends) → [`validated`] (the validated Taylor
//! ODE engine) → [`certify`] (certified branches and contacts) → [`check`] (straying and
//! looping) → [`pipeline`] (the whole job) → [`io`] (scene files, result JSON, SVG).

pub mod certify;
pub mod check;
pub mod error;
pub mod geometry;
pub mod io;
pub mod march;
pub mod numeric;
pub mod pair;
pub mod pipeline;
pub mod search;
pub mod topology;
pub mod validated;

pub use error::{Error, InputProblem, Result};
pub use numeric::scalar::Scalar;

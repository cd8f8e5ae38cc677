//! # ssitrace
//!
//! Intersection curves of two parametric surfaces (rational Bézier patches), traced and certified.
//!
//! The pipeline, one module each: [`geometry`] (surfaces and rigorous bounds) → [`marching`]
//! (fast circular-step tracing that finds the branches) → [`validated`] (the validated Taylor ODE
//! engine) → certified curves → [`io`] (scene files, result JSON, SVG).

pub mod certified;
pub mod error;
pub mod geometry;
pub mod intersection;
pub mod io;
pub mod marching;
pub mod pipeline;
pub mod scalar;
pub mod validated;

pub use error::{Error, InputProblem, Result};
pub use scalar::Scalar;

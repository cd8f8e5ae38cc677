//! The fast marching pre-pass: Newton refinement, circular / DQOC / tangent steps, branch tracing.

pub mod start_points;

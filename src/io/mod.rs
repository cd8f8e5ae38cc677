//! Input and output: the scene format, result JSON, SVG pictures.

pub mod scene;

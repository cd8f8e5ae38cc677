//! Input and output: the scene format, result JSON, SVG pictures.

pub mod result_json;
pub mod scene;
pub mod svg;
pub mod topology_json;

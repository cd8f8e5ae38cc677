//! Input and output: the scene format, STEP files, result JSON, SVG pictures (with the `svg`
//! feature).

pub mod edge_json;
pub mod intersection_json;
pub mod result_json;
pub mod scene;
pub mod step;
#[cfg(feature = "svg")]
pub mod svg;
pub mod topology_json;

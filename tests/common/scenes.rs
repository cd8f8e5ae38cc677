//! The repository's scene files.

use ssitrace::io::scene::Scene;
use std::path::{Path, PathBuf};

/// The path of the scene file `name` in the repository's `scenes/` folder.
pub(crate) fn scene_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
}

/// The scene file `name` of the repository's `scenes/` folder, parsed.
pub(crate) fn scene(name: &str) -> Scene {
    Scene::from_path(&scene_path(name)).expect("scene parses")
}

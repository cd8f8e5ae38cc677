use ssitrace::geometry::subdivision::SubPatch;
use ssitrace::io::scene::Scene;
use ssitrace::search::start_points::{find_start_points, SearchOptions};
fn main() {
    let s = Scene::from_path(std::path::Path::new("/tmp/tangent_scene.json")).unwrap();
    let [p, q] = &s.surfaces;
    println!(
        "{:?}\n{:?}",
        SubPatch::whole(p).bounds(),
        SubPatch::whole(q).bounds()
    );
    let r = find_start_points(p, q, &SearchOptions::default());
    println!(
        "{} {} {} {}",
        r.leaves,
        r.boundary.len(),
        r.interior.len(),
        r.undecided
    );
}

//! How close a chain comes to a pole a branch runs into: great circles through both poles of
//! the NURBS sphere of `scenes/nurbs_sphere_plane.json` (planes `y = k·x` holding its axis).
//!
//! Next to a pole the angle about it is fixed by a curve point only to rounding over the
//! distance to the pole; the chain's links there run along the distance and hold the angle
//! (`certify/chain/pole.rs`), and they reach the last marched point, a few 1e-12 from the
//! pole. Before, every chain stopped about 3e-9 from it (parameter; 4e-9 in the model).

mod common;

use common::shell_checks::{run, sphere_and_axis_plane};
use ssitrace::certify::CertifiedEnd;

/// Every branch ends unproven at a pole, and its end box (the last link's end slice) lies
/// within 1e-10 of the pole seen on the plane (an affine map of its parameters: its corners
/// bound the box's image), its centre within 1e-10: the chain reaches that close. The rest of
/// each branch meets the tolerance.
#[test]
fn chains_into_a_pole_end_within_1e10_of_it() {
    for axes in [[0, 1, 2], [2, 0, 1]] {
        for k in [0.3, -2.5] {
            for sphere_first in [true, false] {
                let what = format!("axes {axes:?}, y = {k}·x, sphere first: {sphere_first}");
                let (_, report) = run(sphere_and_axis_plane(axes, k, sphere_first));
                // The plane's coordinates in the end boxes, and its point in the sphere's axes.
                let side = if sphere_first { 2 } else { 0 };
                let on_plane = |u: f64, v: f64| [4.0 * u - 2.0, k * (4.0 * u - 2.0), 4.0 * v - 2.0];
                let mut at_poles = 0;
                for pair in &report.result.pairs {
                    for b in &pair.result.branches {
                        let cert = b.certified().expect("certified");
                        assert!(cert.certified_tolerance <= 1e-9, "{what}");
                        for end in &cert.ends {
                            let CertifiedEnd::Unproven { reason, near } = end else {
                                continue;
                            };
                            assert!(reason.contains("runs into the pole"), "{what}: {reason}");
                            at_poles += 1;
                            let (u, v) = (near[side], near[side + 1]);
                            let centre = on_plane(u.mid(), v.mid());
                            let pole = [0.0, 0.0, centre[2].signum()];
                            let dist = |x: [f64; 3]| {
                                (0..3).map(|i| (x[i] - pole[i]).powi(2)).sum::<f64>().sqrt()
                            };
                            let reach = dist(centre);
                            assert!(reach <= 1e-10, "{what}: the chain ends {reach:e} from it");
                            let corners = [u.inf(), u.sup()]
                                .iter()
                                .flat_map(|&a| [v.inf(), v.sup()].map(|b| on_plane(a, b)))
                                .map(dist)
                                .fold(0.0, f64::max);
                            assert!(corners <= 1e-9, "{what}: its box reaches {corners:e}");
                        }
                    }
                }
                assert_eq!(at_poles, 4, "{what}");
            }
        }
    }
}

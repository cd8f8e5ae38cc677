//! `Options::time_limit`: when it expires, every certified half still running ends unproven
//! ("time limit") and the certificate keeps what was proven up to there.

mod common;

use common::scenes::scene;
use ssitrace::certify::CertifiedEnd;
use ssitrace::{intersect, Method, Options};
use std::time::Duration;

#[test]
fn an_expired_time_limit_ends_halves_unproven_with_their_proven_boxes() {
    // Fig. 7 takes seconds to certify whole; 20 ms cannot be enough for all three loops.
    let s = scene("wu_andrade_fig7.json");
    let [p, q] = &s.surfaces;
    let opts = Options {
        method: Method::Validated,
        time_limit: Some(Duration::from_millis(20)),
        ..Options::default()
    };
    let r = intersect(p, q, &opts).expect("runs");
    assert_eq!(r.branches.len(), 3);
    let mut timed_out = 0;
    for b in &r.branches {
        let c = b
            .certified()
            .expect("the start is proven before the limit is looked at");
        for e in &c.ends {
            match e {
                CertifiedEnd::Unproven { reason, .. } if reason.starts_with("time limit") => {
                    timed_out += 1
                }
                CertifiedEnd::ClosedLoop => {}
                other => panic!("branch {}: unexpected end {other}", b.id()),
            }
        }
        // What is kept is still a gap-free chain of proven boxes.
        for w in c.boxes.windows(2) {
            assert!(
                w[0].overlaps(&w[1]),
                "branch {}: gap in the kept chain",
                b.id()
            );
        }
    }
    assert!(timed_out > 0, "the limit must have cut something");
    // Without a limit the same scene's loops close (checked in full by tests/certified_fig7.rs);
    // here a generous limit changes nothing on a fast scene.
    let s = scene("sphere_patch_plane.json");
    let [p, q] = &s.surfaces;
    let limited = Options {
        time_limit: Some(Duration::from_secs(3600)),
        ..Options::default()
    };
    let a = intersect(p, q, &limited).expect("runs");
    let b = intersect(p, q, &Options::default()).expect("runs");
    let ends = |r: &ssitrace::SurfaceIntersection| -> Vec<String> {
        r.branches
            .iter()
            .flat_map(|b| {
                b.certified()
                    .map(|c| format!("{} / {}", c.ends[0], c.ends[1]))
            })
            .collect()
    };
    assert_eq!(ends(&a), ends(&b));
}

//! Tests of the near matching of piece sides ([`near_edges`]).

use super::*;
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::surface::Domain;

/// A biquadratic patch over `[0, 1]²` with control point `(i, j)` at `(i/2, j/2, z(i, j))`
/// moved by `shift`, and weight `w(i, j)`.
fn patch(
    shift: [f64; 3],
    z: impl Fn(usize, usize) -> f64,
    w: impl Fn(usize, usize) -> f64,
) -> Face {
    let mut pts = Vec::new();
    let mut ws = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            pts.push([
                i as f64 / 2.0 + shift[0],
                j as f64 / 2.0 + shift[1],
                z(i, j) + shift[2],
            ]);
            ws.push(w(i, j));
        }
    }
    let d = Domain::new(0.0, 1.0, 0.0, 1.0);
    Face::from_patch(RationalBezierPatch::from_f64_points([2, 2], &pts, Some(&ws), d).unwrap())
}

fn bump(i: usize, j: usize) -> f64 {
    0.1 * ((i * 3 + j) % 4) as f64
}

/// The neighbour across `u = 1` of [`patch`]: its `u = 0` row is the first patch's `u = 1` row
/// moved by `delta` (and its rows run the other way when `flip`).
fn neighbour(delta: [f64; 3], flip: bool) -> Face {
    let mut pts = Vec::new();
    for i in 0..3 {
        for j in 0..3 {
            let jj = if flip { 2 - j } else { j };
            let (x, y, z) = (
                1.0 + i as f64 / 2.0,
                jj as f64 / 2.0,
                bump(2, jj) + 0.2 * i as f64,
            );
            let d = if i == 0 { delta } else { [0.0; 3] };
            pts.push([x + d[0], y + d[1], z + d[2]]);
        }
    }
    let d = Domain::new(0.0, 1.0, 0.0, 1.0);
    Face::from_patch(RationalBezierPatch::from_f64_points([2, 2], &pts, None, d).unwrap())
}

#[test]
fn sides_within_the_distance_are_matched_both_ways_with_a_bound_that_holds() {
    let a = patch([0.0; 3], bump, |_, _| 1.0);
    for flip in [false, true] {
        let delta = [3e-11, -2e-11, 4e-11];
        let faces = vec![a.clone(), neighbour(delta, flip)];
        let exact = shared_edges(&faces);
        assert!(exact.is_empty());
        let near = near_edges(&faces, &exact, 1e-9);
        assert_eq!(near.len(), 2, "flip {flip}: {near:?}");
        let l = &near[0];
        assert_eq!((l.link.from.face, l.link.from.side), (0, 1));
        assert_eq!((l.link.to.face, l.link.to.side), (1, 0));
        assert_eq!(l.link.reversed, flip);
        assert_eq!(l.link.kind, EdgeKind::NearEdge);
        // The bound holds between corresponding points, and is not far above the offset.
        let offset = delta.iter().map(|d| d * d).sum::<f64>().sqrt();
        assert!(
            l.mismatch >= offset && l.mismatch <= 1.01 * offset,
            "{}",
            l.mismatch
        );
        let (p, q) = (&faces[0].pieces()[0], &faces[1].pieces()[0]);
        for m in 0..=100 {
            let t = m as f64 / 100.0;
            let x = p.point_f64(1.0, t);
            let y = q.point_f64(0.0, if flip { 1.0 - t } else { t });
            let d = (0..3).map(|k| (x[k] - y[k]).powi(2)).sum::<f64>().sqrt();
            // The f64 evaluations round by a few ulps of the coordinates (about 2).
            assert!(
                d <= l.mismatch + 8.0 * f64::EPSILON,
                "{d:e} > {:e}",
                l.mismatch
            );
        }
        // Not within a smaller distance.
        assert!(near_edges(&faces, &exact, 1e-11).is_empty());
    }
}

#[test]
fn other_weights_exact_links_and_nothing_to_match_give_no_near_link() {
    // Equal rows: an exact link, and no near one.
    let a = patch([0.0; 3], bump, |_, _| 1.0);
    let faces = vec![a.clone(), neighbour([0.0; 3], false)];
    let exact = shared_edges(&faces);
    assert_eq!(exact.len(), 2);
    assert!(near_edges(&faces, &exact, 1e-9).is_empty());
    // Other weights on the shared row: not matched.
    let weighted = patch([0.0; 3], bump, |i, _| if i == 2 { 0.9 } else { 1.0 });
    let faces = vec![weighted, neighbour([1e-12, 0.0, 0.0], false)];
    assert!(near_edges(&faces, &shared_edges(&faces), 1e-9).is_empty());
    // No distance, or none at all: nothing.
    let faces = vec![a.clone(), neighbour([1e-12, 0.0, 0.0], false)];
    assert!(near_edges(&faces, &[], 0.0).is_empty());
    assert!(near_edges(&faces, &[], f64::NAN).is_empty());
    // Far apart: nothing.
    let faces = vec![a, patch([5.0, 0.0, 0.0], bump, |_, _| 1.0)];
    assert!(near_edges(&faces, &[], 1e-9).is_empty());
}

#[test]
fn rows_nearly_collapsed_to_a_point_are_not_near_edges() {
    // Two fans round a near-pole at the origin: their u = 0 rows are three points within
    // 1e-12 of it, rounded differently on each face.
    let fan = |eps: f64, y: f64| {
        let mut pts = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                let r = i as f64 / 2.0;
                let near = if i == 0 { eps * j as f64 } else { 0.0 };
                pts.push([r + near, y * r * j as f64 / 2.0, near]);
            }
        }
        let d = Domain::new(0.0, 1.0, 0.0, 1.0);
        Face::from_patch(RationalBezierPatch::from_f64_points([2, 2], &pts, None, d).unwrap())
    };
    let faces = vec![fan(1e-13, 1.0), fan(3e-13, -1.0)];
    assert!(near_edges(&faces, &shared_edges(&faces), 1e-9).is_empty());
}

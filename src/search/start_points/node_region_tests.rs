//! Tests of the node regions: saddle contacts settled (asymmetric domains, off and on the
//! subdivision lines), nodes on domain edges and corners, isolated contacts, `Piece::over`.

use super::super::{find_start_points, SearchOptions};
use super::*;
use crate::geometry::power::PowerTerm;
use crate::geometry::{Domain, PowerSurface};

/// The graph `z = Σ c·xⁱyʲ` over `domain`, as a Bézier patch.
fn graph(domain: Domain, terms: Vec<PowerTerm>) -> RationalBezierPatch {
    PowerSurface::graph(domain, terms).to_bezier().unwrap()
}

#[test]
fn a_saddle_contact_is_settled_and_its_four_arcs_found() {
    // z = x² + a·xy against z = b·y² − c·xy: tangent at the origin, where the height
    // difference x² + (a + c)·xy − b·y² has a saddle, so two lines of the intersection cross
    // there, y = m·x for both roots m of b·m² − (a + c)·m − 1 = 0. Asymmetric domains, the
    // node off every subdivision line and on one.
    for (a, b, c, dp, dq) in [
        (
            0.0,
            1.0,
            0.0,
            Domain::new(-1.0, 1.0, -1.0, 1.0),
            Domain::new(-1.0, 1.0, -1.0, 1.0),
        ),
        (
            0.3,
            0.5,
            0.2,
            Domain::new(-0.7, 1.3, -1.1, 0.6),
            Domain::new(-0.9, 0.8, -0.5, 1.2),
        ),
        (
            -0.4,
            2.0,
            0.1,
            Domain::new(-0.3, 1.0, -0.6, 0.4),
            Domain::new(-1.0, 0.35, -0.45, 0.9),
        ),
    ] {
        let p = graph(dp, vec![(2, 0, 1.0), (1, 1, a), (0, 0, 0.0), (0, 1, 0.0)]);
        let q = graph(dq, vec![(0, 2, b), (1, 1, -c), (0, 0, 0.0), (1, 0, 0.0)]);
        let r = find_start_points(&p, &q, &SearchOptions::default());
        assert!(r.complete, "{:?}", (a, b, c, r.undecided_regions.len()));
        assert!(r.node_regions >= 1, "{:?}", (a, b, c));
        let disc: f64 = ((a + c) * (a + c) + 4.0 * b).sqrt();
        let slopes = [((a + c) + disc) / (2.0 * b), ((a + c) - disc) / (2.0 * b)];
        // Every start point lies on one of the lines; each half-line from the node that
        // reaches a domain boundary has one (boundary or interior).
        let all: Vec<_> = r.boundary.iter().chain(&r.interior).collect();
        for s in &all {
            let [x, y, u, v] = s.params;
            assert!((x - u).abs() < 1e-9 && (y - v).abs() < 1e-9, "{s:?}");
            let off = slopes
                .iter()
                .map(|m| (y - m * x).abs())
                .fold(f64::MAX, f64::min);
            assert!(off < 1e-8, "{:?} {s:?}", (a, b, c));
        }
        for m in slopes {
            for sign in [1.0, -1.0] {
                // The half-line leaves the common domain; some start point lies on it.
                let hit = all.iter().any(|s| {
                    let [x, y, ..] = s.params;
                    x * sign > 1e-9 && (y - m * x).abs() < 1e-8
                });
                assert!(hit, "{:?} slope {m} side {sign}", (a, b, c));
            }
        }
    }
}

#[test]
fn a_saddle_contact_on_a_domain_edge_or_corner_is_found() {
    // z = x² against z = y² (lines y = ±x through the origin) with the origin on an edge of
    // both domains, and at a corner of both: no region is proven there (see the module
    // documentation) and the search reports undecided regions, but every start point lies
    // on a line and every half-line inside the domains is met.
    for (dp, dq) in [
        (
            Domain::new(0.0, 1.0, -1.0, 1.0),
            Domain::new(0.0, 1.0, -1.0, 1.0),
        ),
        (
            Domain::new(0.0, 1.0, 0.0, 1.0),
            Domain::new(0.0, 1.0, 0.0, 1.0),
        ),
        (
            Domain::new(-0.5, 0.0, -0.5, 0.7),
            Domain::new(-0.6, 0.0, -0.5, 0.5),
        ),
    ] {
        let p = graph(dp, vec![(2, 0, 1.0), (0, 0, 0.0), (0, 1, 0.0)]);
        let q = graph(dq, vec![(0, 2, 1.0), (0, 0, 0.0), (1, 0, 0.0)]);
        let r = find_start_points(&p, &q, &SearchOptions::default());
        let all: Vec<_> = r.boundary.iter().chain(&r.interior).collect();
        assert!(!all.is_empty(), "{dp:?}");
        // On a line, to 1e-6: where the surfaces touch, a point 1e-8 from the node is on
        // both to 1e-16 (the boundary search offers such Newton points from its undecided
        // leaves next to the node).
        for s in &all {
            let [x, y, ..] = s.params;
            assert!((x.abs() - y.abs()).abs() < 1e-6, "{dp:?} {s:?}");
        }
        for m in [1.0, -1.0] {
            for sign in [1.0, -1.0] {
                // A half-line that runs inside both domains has a start point on it.
                let (x, y) = (0.25 * sign, 0.25 * sign * m);
                let inside = dp.contains(x, y, 0.0) && dq.contains(x, y, 0.0);
                let hit = all.iter().any(|s| {
                    let [a, b, ..] = s.params;
                    a * sign > -1e-12 && (b - m * a).abs() < 1e-8
                });
                assert!(!inside || hit, "{dp:?} slope {m} side {sign}");
            }
        }
        println!(
            "{dp:?}: complete {}, {} regions, {} undecided",
            r.complete,
            r.node_regions,
            r.undecided_regions.len()
        );
    }
}

#[test]
fn an_isolated_contact_point_is_not_settled() {
    // z = x² + y² against z = 0: one contact point, where a tiny loop could hide; no region is
    // proven there and the search says it is not complete.
    let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
    let p = graph(d, vec![(2, 0, 1.0), (0, 2, 1.0), (0, 0, 0.0)]);
    let q = graph(d, vec![(0, 0, 0.0), (1, 0, 0.0)]);
    let r = find_start_points(&p, &q, &SearchOptions::default());
    assert_eq!(r.node_regions, 0);
    assert!(!r.complete);
}

#[test]
fn a_node_region_encloses_its_patch_piece() {
    // Piece::over a box not on the halving grid: the patch over that box lies in the
    // piece's bounds, and the piece's faces are the patch's boundary curves of the box.
    let d = Domain::new(-0.7, 1.3, -1.1, 0.6);
    let p = graph(d, vec![(2, 0, 1.0), (1, 1, 0.3), (0, 3, -0.5), (0, 0, 0.1)]);
    let (s, r) = ([0.3125, 0.71875], [0.125, 0.1875]);
    let piece = Piece::over(&p, s, r).unwrap();
    let bounds = piece.bounds();
    let at = |d: [f64; 2], x: f64| d[0] + x * (d[1] - d[0]);
    for i in 0..=8 {
        for j in 0..=8 {
            let (a, b) = (
                s[0] + (s[1] - s[0]) * i as f64 / 8.0,
                r[0] + (r[1] - r[0]) * j as f64 / 8.0,
            );
            let x = p.point(at(d.u, a), at(d.v, b));
            for (k, v) in [x.x, x.y, x.z].iter().enumerate() {
                assert!(bounds[k].inf() - 1e-12 <= *v && *v <= bounds[k].sup() + 1e-12);
            }
        }
    }
    // Tight: about the size of the box's image, not the whole patch's.
    assert!(bounds[0].wid() < 1.1 * (s[1] - s[0]) * 2.0);
    assert!(Piece::over(&p, [0.5, 0.5], r).is_none());
    assert!(Piece::over(&p, [0.5, 1.5], r).is_none());
}

/// The patch turned by the rotation with Euler angles `angles` (homogeneous net rotated in
/// interval arithmetic: the patch is the turned one up to rounding).
fn turned(p: &RationalBezierPatch, angles: [f64; 3]) -> RationalBezierPatch {
    let r = nalgebra::Rotation3::from_euler_angles(angles[0], angles[1], angles[2]);
    let m = r.matrix();
    let net = p
        .homogeneous()
        .iter()
        .map(|h| {
            let row = |i: usize| {
                point(m[(i, 0)]) * h[0] + point(m[(i, 1)]) * h[1] + point(m[(i, 2)]) * h[2]
            };
            [row(0), row(1), row(2), h[3]]
        })
        .collect();
    RationalBezierPatch::from_homogeneous(p.degree(), net, p.domain()).unwrap()
}

#[test]
fn an_isolated_contact_is_settled_above_below_and_round_a_tiny_loop() {
    // z = s·((x − a)² + 2(y − b)² + h) against z = 0, on asymmetric domains, both turned in
    // space (so no axis-aligned box separates them): an extremum of the height difference at
    // (a, b), a minimum for s = 1, a maximum for s = −1. With h > 0 the value there has the
    // extremum's own sign and no loop is possible; with h < 0 one ellipse
    // (x − a)² + 2(y − b)² = −h surrounds it, found by the ray from the extremum. Down to
    // h = 1e-14 above and a loop of radius 1e-5 below (a loop of radius 1e-7 is too tangent for
    // the ray's own search: its crossing is found but not proven there).
    let (a, b) = (0.1234, -0.0567);
    let dp = Domain::new(-0.7, 1.3, -1.1, 0.6);
    let dq = Domain::new(-0.9, 0.8, -0.5, 1.2);
    let angles = [0.3, -1.1, 2.2];
    for s in [1.0, -1.0] {
        for h in [1e-3, 1e-14, -1e-4, -1e-10] {
            let c0 = a * a + 2.0 * b * b + h;
            let p = graph(
                dp,
                vec![
                    (2, 0, s),
                    (0, 2, 2.0 * s),
                    (1, 0, -2.0 * a * s),
                    (0, 1, -4.0 * b * s),
                    (0, 0, c0 * s),
                ],
            );
            let q = graph(dq, vec![(0, 0, 0.0), (1, 0, 0.0)]);
            let (p, q) = (turned(&p, angles), turned(&q, angles));
            let r = find_start_points(&p, &q, &SearchOptions::default());
            let all: Vec<_> = r.boundary.iter().chain(&r.interior).collect();
            assert!(
                r.complete,
                "s {s} h {h}: {} undecided",
                r.undecided_regions.len()
            );
            assert!(r.node_regions >= 1, "s {s} h {h}");
            if h > 0.0 {
                assert!(all.is_empty(), "s {s} h {h}: {all:?}");
            } else {
                assert!(!all.is_empty(), "s {s} h {h}: the loop is missed");
                for st in &all {
                    let [x, y, ..] = st.params;
                    let e = (x - a).powi(2) + 2.0 * (y - b).powi(2) + h;
                    assert!(
                        e.abs() < 1e-12,
                        "s {s} h {h}: {st:?} off the ellipse ({e:e})"
                    );
                }
            }
            println!(
                "s {s} h {h:e}: complete, {} node regions, {} pairs, {} starts",
                r.node_regions,
                r.pairs,
                all.len()
            );
        }
    }
}

/// An empty enclosure (an evaluation divided by a weight exactly zero, possible past a domain)
/// has no sign and is no proof: its bounds (+∞, −∞) would pass every test.
#[test]
fn empty_enclosures_prove_nothing() {
    use crate::pair::contact_quadratic::{Proven, SignRule};
    assert_eq!(sign(Interval::EMPTY), None);
    assert!(proper([Interval::EMPTY, point(1.0)]).is_none());
    assert!(proper([point(1.0); 2]).is_some());
    let b = [point(1.0); 3];
    assert!(!Proven.positive(Interval::EMPTY, &b) && !Proven.negative(Interval::EMPTY, &b));
}

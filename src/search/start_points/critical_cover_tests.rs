//! Tests of the critical-set cover: rings of minima crossing a piece (settled), rings and loops
//! wholly inside a piece (never settled), and whole searches round concentric loops.

use super::super::{find_start_points, SearchOptions};
use super::*;
use crate::geometry::power::PowerTerm;
use crate::geometry::{Domain, ParametricSurface, PowerSurface};

/// The graph `z = Σ c·xⁱyʲ` over `domain`, as a Bézier patch.
fn graph(domain: Domain, terms: Vec<PowerTerm>) -> RationalBezierPatch {
    PowerSurface::graph(domain, terms).to_bezier().unwrap()
}

/// `z = (w − a)(w − a − d)` with `w = (x − cx)² + k·(y − cy)²`: against `z = 0` the two
/// (elliptical, for `k ≠ 1`) loops `w = a` and `w = a + d`, and between them a ring of minima
/// `w = a + d/2` where `z = −d²/4`.
fn rings(domain: Domain, a: f64, d: f64, c: [f64; 2], k: f64) -> RationalBezierPatch {
    let (cx, cy) = (c[0], c[1]);
    // w = x² + k y² − 2cx x − 2k cy y + w0.
    let w0 = cx * cx + k * cy * cy;
    let w: Vec<(u32, u32, f64)> = vec![
        (2, 0, 1.0),
        (0, 2, k),
        (1, 0, -2.0 * cx),
        (0, 1, -2.0 * k * cy),
        (0, 0, w0),
    ];
    // (w − a)(w − b) = w² − (a + b) w + a b, b = a + d.
    let b = a + d;
    let mut terms: std::collections::BTreeMap<(u32, u32), f64> = Default::default();
    for &(i, j, c1) in &w {
        for &(k2, l, c2) in &w {
            *terms.entry((i + k2, j + l)).or_default() += c1 * c2;
        }
        *terms.entry((i, j)).or_default() -= (a + b) * c1;
    }
    *terms.entry((0, 0)).or_default() += a * b;
    graph(
        domain,
        terms.into_iter().map(|((i, j), c)| (i, j, c)).collect(),
    )
}

fn plane(domain: Domain) -> RationalBezierPatch {
    graph(domain, vec![(0, 0, 0.0), (1, 0, 0.0)])
}

const SQUARE: Domain = Domain::new(-1.0, 1.0, -1.0, 1.0);

#[test]
fn a_ring_of_minima_crossing_the_piece_is_covered() {
    // Rings of radius 0.4 (a = 0.16) about the origin cross the piece x, y ∈ [0.25, 0.5]
    // (normalised [0.625, 0.75]²) from its lower-left edge... to its upper-right one: covered,
    // with the plane as P or as Q, for loops 0.05 down to 0.001 apart (in w) and an ellipse.
    for (d, k) in [(0.05, 1.0), (0.002, 1.0), (0.001, 1.0), (0.002, 1.7)] {
        let p = rings(SQUARE, 0.16, d, [0.0, 0.0], k);
        let q = plane(SQUARE);
        let a = Piece::over(&p, [0.625, 0.75], [0.5625, 0.6875]).unwrap();
        let b = Piece::whole(&q);
        assert!(prove_by_cover(&p, &a, &q, &b, MAX_CELLS), "d {d} k {k}");
        let a = Piece::over(&q, [0.625, 0.75], [0.5625, 0.6875]).unwrap();
        let b = Piece::whole(&p);
        assert!(
            prove_by_cover(&q, &a, &p, &b, MAX_CELLS),
            "plane first: d {d} k {k}"
        );
    }
}

#[test]
fn a_ring_or_a_loop_inside_the_piece_is_never_covered() {
    // The same rings of radius 0.1 lie wholly inside the piece x, y ∈ [−0.25, 0.25]: two loops
    // round the ring of minima, which no signed class joins to the boundary. Nor a single loop
    // round a minimum (a paraboloid cut below its rim), nor a ring of maxima between the loops
    // (the height difference negated).
    let q = plane(SQUARE);
    let b = Piece::whole(&q);
    for d in [0.05, 0.002] {
        let p = rings(SQUARE, 0.01, d, [0.0, 0.0], 1.0);
        let a = Piece::over(&p, [0.375, 0.625], [0.375, 0.625]).unwrap();
        assert!(!prove_by_cover(&p, &a, &q, &b, 100_000), "d {d}");
        assert!(!prove_by_cover(
            &q,
            &Piece::over(&q, a.s, a.r).unwrap(),
            &p,
            &Piece::whole(&p),
            100_000
        ));
        let neg = graph(
            SQUARE,
            vec![
                (4, 0, -1.0),
                (2, 2, -2.0),
                (0, 4, -1.0),
                (2, 0, 0.02 + d),
                (0, 2, 0.02 + d),
            ]
            .into_iter()
            .chain([(0, 0, -0.01 * (0.01 + d))])
            .collect(),
        );
        assert!(!prove_by_cover(&neg, &a, &q, &b, 100_000), "negated d {d}");
    }
    let bowl = graph(SQUARE, vec![(2, 0, 1.0), (0, 2, 1.0), (0, 0, -0.01)]);
    let a = Piece::over(&bowl, [0.375, 0.625], [0.375, 0.625]).unwrap();
    assert!(!prove_by_cover(&bowl, &a, &q, &b, 100_000));
}

#[test]
fn a_ring_above_the_plane_is_covered_whole() {
    // (w − a)(w − a − d) + c with c > d²/4: no intersection at all, the ring of minima inside
    // the piece but positive; every cell is signed and the class reaches the boundary.
    let q = plane(SQUARE);
    let (a0, d) = (0.01, 0.002);
    let c = d * d / 4.0 * 1.5;
    let p = graph(
        SQUARE,
        vec![
            (4, 0, 1.0),
            (2, 2, 2.0),
            (0, 4, 1.0),
            (2, 0, -(2.0 * a0 + d)),
            (0, 2, -(2.0 * a0 + d)),
            (0, 0, a0 * (a0 + d) + c),
        ],
    );
    let a = Piece::over(&p, [0.375, 0.625], [0.375, 0.625]).unwrap();
    assert!(prove_by_cover(&p, &a, &q, &Piece::whole(&q), MAX_CELLS));
}

#[test]
fn covered_pieces_never_hold_a_whole_loop() {
    // Every dyadic piece down to 1/16 of concentric loops (radii 0.3 and about 0.3033, a
    // centre off the grid) and of a small loop of radius 0.02: a piece holding either loop of
    // a pair, or the small loop, in its interior must not be covered.
    let c = [0.0371, -0.0213];
    let loops = rings(SQUARE, 0.09, 0.002, c, 1.0);
    let small = graph(
        SQUARE,
        vec![
            (2, 0, 1.0),
            (0, 2, 1.0),
            (1, 0, -2.0 * c[0]),
            (0, 1, -2.0 * c[1]),
            (0, 0, c[0] * c[0] + c[1] * c[1] - 0.0004),
        ],
    );
    let q = plane(SQUARE);
    let mut covered = 0;
    for (p, radius) in [(&loops, 0.3f64), (&small, 0.02)] {
        for level in 0..=4 {
            let n = 1u32 << level;
            for i in 0..n {
                for j in 0..n {
                    let w = 1.0 / f64::from(n);
                    let (s, r) = (
                        [f64::from(i) * w, f64::from(i + 1) * w],
                        [f64::from(j) * w, f64::from(j + 1) * w],
                    );
                    let a = Piece::over(p, s, r).unwrap();
                    if !prove_by_cover(p, &a, &q, &Piece::whole(&q), MAX_CELLS) {
                        continue;
                    }
                    covered += 1;
                    let x = [2.0 * s[0] - 1.0, 2.0 * s[1] - 1.0];
                    let y = [2.0 * r[0] - 1.0, 2.0 * r[1] - 1.0];
                    let inside = x[0] < c[0] - radius
                        && c[0] + radius < x[1]
                        && y[0] < c[1] - radius
                        && c[1] + radius < y[1];
                    assert!(!inside, "a covered piece holds a loop: {s:?} {r:?}");
                }
            }
        }
    }
    assert!(covered > 20, "{covered}");
}

/// Radius of the point `(x, y)` about `c` in the metric `(x − cx)² + k·(y − cy)²`.
fn radius(x: f64, y: f64, c: [f64; 2], k: f64) -> f64 {
    ((x - c[0]).powi(2) + k * (y - c[1]).powi(2)).sqrt()
}

#[test]
fn concentric_loops_are_searched_completely() {
    // Whole searches: two loops round a ring of minima, in w 0.002 to 0.05 apart, circles and
    // an ellipse, on the square and on an off-centre domain: complete, and start points on
    // both loops (every start on one of them).
    for (domain, c, a, d, k) in [
        (SQUARE, [0.0, 0.0], 0.16, 0.002, 1.0),
        (SQUARE, [0.0, 0.0], 0.16, 0.01, 1.0),
        // Radius 0.5: the inner circle touches the subdivision lines x, y = ±0.5, where the
        // face searches meet it tangentially (tangent_leaf.rs).
        (SQUARE, [0.0, 0.0], 0.25, 0.002, 1.0),
        (SQUARE, [0.0, 0.0], 0.25, 0.01, 1.0),
        (SQUARE, [0.0, 0.0], 0.25, 0.05, 1.0),
        (
            Domain::new(0.0, 3.0, 0.0, 2.0),
            [1.4, 0.9],
            0.25,
            0.002,
            1.0,
        ),
        (SQUARE, [0.1, -0.05], 0.2, 0.002, 1.7),
    ] {
        let p = rings(domain, a, d, c, k);
        let q = plane(domain);
        let r = find_start_points(&p, &q, &SearchOptions::default());
        assert!(
            r.complete,
            "{c:?} a {a} d {d} k {k}: {} undecided",
            r.undecided_regions.len()
        );
        let (r1, r2) = (a.sqrt(), (a + d).sqrt());
        let mut on = [false; 2];
        for st in r.boundary.iter().chain(&r.interior) {
            let [x, y, u, v] = st.params;
            assert!((x - u).abs() < 1e-9 && (y - v).abs() < 1e-9);
            assert!(p.point(x, y).z.abs() < 1e-9);
            let rho = radius(x, y, c, k);
            let near = [(rho - r1).abs() < 1e-9, (rho - r2).abs() < 1e-9];
            assert!(near[0] || near[1], "{st:?} on neither loop");
            on[0] |= near[0];
            on[1] |= near[1];
        }
        assert_eq!(on, [true, true], "{c:?} a {a} d {d} k {k}");
    }
}

//! Tests of the cuts at joins: the true crossings of a side, against a closed form.
use super::*;
use crate::geometry::Domain;
use crate::{intersect, Method, Options, SurfaceIntersection};

/// The plane `z = 0` and the paraboloid `z = (s − ½)² + (t − ½)² − ⅜`, both over the unit
/// square (every control point exact in `f64`), and their intersection: the circle of
/// radius `√⅜` round `(½, ½)`, at the same parameters on both, certified.
fn plane_and_bowl() -> (
    RationalBezierPatch,
    RationalBezierPatch,
    SurfaceIntersection,
) {
    let plane = RationalBezierPatch::from_f64_points(
        [1, 1],
        &[
            [0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
        ],
        None,
        Domain::UNIT,
    )
    .unwrap();
    let b = [0.25, -0.25, 0.25];
    let net: Vec<[f64; 3]> = (0..3)
        .flat_map(|i| (0..3).map(move |j| [i as f64 / 2.0, j as f64 / 2.0, b[i] + b[j] - 0.375]))
        .collect();
    let bowl = RationalBezierPatch::from_f64_points([2, 2], &net, None, Domain::UNIT).unwrap();
    let opts = Options {
        method: Method::Validated,
        ..Options::default()
    };
    let r = intersect(&plane, &bowl, &opts).expect("runs");
    (plane, bowl, r)
}

/// The plane `z = 0` and the paraboloid `z = (s − ½)² + (t − ½)² − ⅜`, both over the unit
/// square (every control point exact in `f64`): the circle of radius `√⅜` round `(½, ½)`
/// crosses every side of the square at `½ ± √⅛`. Every arc is cut at both sides it leaves
/// through; the cut's proven range (on the cut link, or the next one) must hold the true
/// crossing (enclosed in interval arithmetic). (These chains end with a link to a Newton
/// point just outside the square, so the ranges are at rounding level already and the
/// crossing's Krawczyk narrowing does not apply: the next test exercises it.)
#[test]
fn a_cut_holds_the_true_crossing_of_the_side() {
    let (plane, bowl, r) = plane_and_bowl();
    assert_eq!(r.branches.len(), 4, "four arcs inside the square");
    let off = point(0.125).sqrt();
    let (low, high) = (point(0.5) - off, point(0.5) + off);
    for (i, br) in r.branches.iter().enumerate() {
        let cert = br.certified().expect("certified");
        let mut segs = super::super::chain_segs(cert, false);
        let ends = [&cert.ends[0], &cert.ends[1]];
        let cuts = cut_ends(cert, &mut segs, ends, [&plane, &bowl], i, [None; 2])
            .expect("cut at both sides");
        assert_eq!(cuts.len(), 2);
        for c in &cuts {
            let t = &cert.tubes[c.tube];
            let j = t.along.expect("a cover chain").index;
            // The side the cut crosses (from the reported curve there), and the true
            // crossing on it; the plane's and the bowl's parameters agree along the curve.
            let end = t.coeffs.iter().rev().fold([0.0; 4], |acc, k| {
                std::array::from_fn(|d| acc[d] * c.gap.mid() + k[d])
            });
            let truth = |x: f64| if x < 0.5 { low } else { high };
            let crossing: [Interval; 4] = if (end[0] - 0.5).abs() > (end[1] - 0.5).abs() {
                let u = point(if end[0] < 0.5 { 0.0 } else { 1.0 });
                [u, truth(end[1]), u, truth(end[1])]
            } else {
                let v = point(if end[1] < 0.5 { 0.0 } else { 1.0 });
                [truth(end[0]), v, truth(end[0]), v]
            };
            // The parameter range a `τ` range of a piece covers: `x_j = from + dir·τ`.
            let covers = |piece: &crate::certify::TubePiece, tau: Interval| {
                point(piece.coeffs[0][j]) + point(piece.coeffs[1][j]) * tau
            };
            let on_cut = !covers(t, c.gap).disjoint(crossing[j]);
            let on_next = c.next.is_some_and(|(n, range)| {
                let nt = &cert.tubes[n];
                nt.along.map(|a| a.index) == Some(j) && !covers(nt, range).disjoint(crossing[j])
            });
            assert!(
                on_cut || on_next,
                "arc {i}: crossing {crossing:?} outside the cut {:?} / {:?}",
                c.gap,
                c.next
            );
        }
    }
}

/// The crossing's Krawczyk narrowing (`Side::crossing_slice`) on a side that the chain
/// crosses inside a link, not at a link's end: on the plane and the paraboloid's circle,
/// the side `x_b = c` through the middle of a link (`b` one of P's parameters other than
/// the link's along one, `c` the reported curve's value there). The narrowed range must
/// hold the true crossing (from the closed form, in interval arithmetic), and be far
/// narrower than the half link it was narrowed from.
#[test]
fn the_narrowed_crossing_of_a_side_holds_the_true_one() {
    let (plane, bowl, r) = plane_and_bowl();
    let mut checked = 0;
    for br in &r.branches {
        let cert = br.certified().expect("certified");
        let segs = super::super::chain_segs(cert, false);
        for seg in segs.iter().skip(1).step_by(3) {
            let t = &cert.tubes[seg.tube];
            let j = t.along.expect("a cover chain").index;
            let b = if j % 2 == 0 { 1 } else { 0 };
            let y = reparametrised(&t.coeffs, seg.ta, seg.tb);
            let (mid, ahead) = (eval_mid(&y, 0.5), eval_mid(&y, 0.6));
            let side = Side {
                cert,
                b,
                bound: mid[b],
                out_sign: (ahead[b] - mid[b]).signum(),
            };
            let gap = tau_range(seg, 0.25, 0.75);
            let Some(c) = side.crossing_slice([&plane, &bowl], (seg, &y, [0.25, 0.75]), None, gap)
            else {
                continue;
            };
            // The true crossing: x_b = c on the circle, the other parameter on the side of
            // ½ the reported curve is on; x_j is that one (j and b differ in parity).
            let off = (point(0.375) - (point(mid[b]) - point(0.5)).sqr()).sqrt();
            let other = if mid[1 - b] > 0.5 {
                point(0.5) + off
            } else {
                point(0.5) - off
            };
            let tau = (other - point(t.coeffs[0][j])) * point(t.coeffs[1][j]);
            assert!(
                !c.on_cut.disjoint(tau),
                "link {}: the narrowed range {:?} misses the crossing {tau:?}",
                seg.tube,
                c.on_cut
            );
            assert!(
                c.on_cut.wid() < 1e-6 * gap.wid(),
                "{:?} from {gap:?}",
                c.on_cut
            );
            checked += 1;
        }
    }
    assert!(checked >= 8, "only {checked} crossings narrowed");
}

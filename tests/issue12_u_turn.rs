//! Issue 12: a curve that turns within a micrometre on nearly tangent surfaces is one branch.
//!
//! The surface `z = x² − δ·y` meets the plane `z = 0` in the parabola `y = x²/δ`. At its vertex
//! the normals are only `δ` apart and the curve turns round with a radius of `δ/2`; elsewhere
//! it is plainly transversal. For `δ` between 1e-7 and 1e-6 the marcher used to stop on each
//! arm at the vertex and call it a singular point (there is none: the normals are never
//! parallel), and the chain's links graphed over `y`, which turns there, stayed wider than the
//! tolerance however short. Now the march goes round the turn, links there are graphed over a
//! coordinate that keeps moving (`x`), and the curve is one branch, certified from boundary to
//! boundary within the tolerance.
//!
//! Everything is moved to `(2.75, −1.375, 0.8125)`, where every coordinate below is exact: the
//! patches are exactly these surfaces, and the sampled curve points are exact, so the check of
//! the certified boxes against the closed form is exact too.

use inari::Interval;
use ssitrace::{intersect, Domain, Method, Options, RationalBezierPatch, SurfaceIntersection};

const SHIFT: [f64; 3] = [2.75, -1.375, 0.8125];
const TOL: f64 = 1e-9;

fn exact(v: f64) -> Interval {
    inari::interval!(v, v).unwrap()
}

fn patch(
    degree: [usize; 2],
    pts: &[[f64; 3]],
    map: &dyn Fn([f64; 3]) -> [f64; 3],
) -> RationalBezierPatch {
    let points = pts
        .iter()
        .map(|&p| {
            let m = map(p);
            std::array::from_fn(|k| exact(m[k] + SHIFT[k]))
        })
        .collect();
    RationalBezierPatch::new(degree, points, None, Domain::UNIT).expect("a valid patch")
}

/// `z = x² − δ·y` over `x, y ∈ [−1, 1]` (P) and the plane `z = 0` over `[−1.5, 1.5]²` (Q), each
/// control point mapped by `map` before the shift.
fn scene(delta: f64, map: &dyn Fn([f64; 3]) -> [f64; 3]) -> SurfaceIntersection {
    let p = patch(
        [2, 1],
        &[
            [-1.0, -1.0, 1.0 + delta],
            [-1.0, 1.0, 1.0 - delta],
            [0.0, -1.0, -1.0 + delta],
            [0.0, 1.0, -1.0 - delta],
            [1.0, -1.0, 1.0 + delta],
            [1.0, 1.0, 1.0 - delta],
        ],
        map,
    );
    let q = patch(
        [1, 1],
        &[
            [-1.5, -1.5, 0.0],
            [-1.5, 1.5, 0.0],
            [1.5, -1.5, 0.0],
            [1.5, 1.5, 0.0],
        ],
        map,
    );
    let opts = Options {
        method: Method::Both,
        required_tolerance: TOL,
        ..Options::default()
    };
    intersect(&p, &q, &opts).expect("runs")
}

/// One branch, marched and certified from P's side `y = 1` round the vertex back to it, within
/// the tolerance, and no singular point or contact reported.
fn assert_one_branch(r: &SurfaceIntersection, what: &str) {
    assert_eq!(r.branches.len(), 1, "{what}: one branch");
    assert!(r.nodes.is_empty(), "{what}: no singular point");
    assert!(r.contacts.is_empty(), "{what}: no contact");
    let b = &r.branches[0];
    let c = b.certified().expect("certified");
    let kinds: Vec<&str> = c.ends.iter().map(|e| e.kind()).collect();
    assert_eq!(kinds, ["boundary", "boundary"], "{what}");
    let t = b.certified_tolerance().expect("a tolerance");
    assert!(t <= TOL, "{what}: tolerance {t:e}");
}

#[test]
fn a_parabola_turning_within_a_micrometre_is_one_branch_within_the_tolerance() {
    // δ = 2⁻²¹ (normals 4.8e-7 apart at the vertex) and 2⁻²² (2.4e-7).
    for e in [21, 22] {
        let delta = 2f64.powi(-e);
        let r = scene(delta, &|p| p);
        assert_one_branch(&r, &format!("δ = 2^-{e}"));
        let c = r.branches[0].certified().expect("certified");
        // Curve points x = k·2⁻³⁰, y = x²/δ (exact), every one in a certified box, in model
        // space and in P's parameters (σ, t) = ((x + 1)/2, (y + 1)/2): densely through the turn
        // (radius δ/2, about 2⁸ steps of k) and across the arms.
        let reach = ((1u64 << (60 - e)) as f64).sqrt().floor() as i64; // y ≤ 1
        let ks = (-4096..=4096).chain((-reach..=reach).step_by(97));
        for k in ks {
            let x = k as f64 * 2f64.powi(-30);
            let y = x * x / delta;
            let (s, tt) = ((x + 1.0) / 2.0, (y + 1.0) / 2.0);
            let m = [x + SHIFT[0], y + SHIFT[1], SHIFT[2]];
            let inside = c.boxes.iter().any(|bx| {
                (0..3).all(|i| bx.xyz[i].contains(m[i]))
                    && bx.p[0].contains(s)
                    && bx.p[1].contains(tt)
            });
            assert!(inside, "δ = 2^-{e}: ({x:e}, {y:e}) in no certified box");
        }
        // And every box meets the curve: over the box's σ the curve's t (interval arithmetic,
        // rounded outward) overlaps the box's t.
        for bx in &c.boxes {
            let x = exact(2.0) * bx.p[0] - exact(1.0);
            let y = x.sqr() / exact(delta);
            let t_curve = (y + exact(1.0)) / exact(2.0);
            assert!(
                !t_curve.intersection(bx.p[1]).is_empty(),
                "δ = 2^-{e}: a box off the curve"
            );
        }
    }
}

#[test]
fn the_turn_is_one_branch_whatever_the_placement() {
    // Turned about z, then tilted about x (a rotation rounds the data, so only the topology
    // and the tolerance are checked here).
    for (a, b) in [(0.7f64, 0.4f64), (-2.1, 1.2), (2.9, -0.3)] {
        let map = move |p: [f64; 3]| {
            let (x, y) = (
                p[0] * a.cos() - p[1] * a.sin(),
                p[0] * a.sin() + p[1] * a.cos(),
            );
            [
                x,
                y * b.cos() - p[2] * b.sin(),
                y * b.sin() + p[2] * b.cos(),
            ]
        };
        for e in [21, 22] {
            let r = scene(2f64.powi(-e), &map);
            assert_one_branch(&r, &format!("turned by {a}, {b}; δ = 2^-{e}"));
        }
    }
}

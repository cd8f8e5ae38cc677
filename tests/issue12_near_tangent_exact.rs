//! Issue 12: certificates on nearly tangent surfaces are not held up by rounding.
//!
//! The parabolic cylinder `z = x²` and the plane `z = 2⁻⁴⁰` meet in the two lines
//! `x = ±2⁻²⁰`, along which the normals are only `2·2⁻²⁰ ≈ 1.9e-6` apart. Moved to
//! `(2.75, −1.375, 0.8125)` (exact: the patches are exactly these surfaces), every interval
//! evaluation of the residual rounds by a few ulps of 2.75, which over that sine is about 1e-10
//! to 1e-9 of a tube. Links there used to fail or stall: each line came back in pieces ending
//! in "singular boxes" (there is no singular point), 1 742 links for one of them. They are now
//! proven on the exact residual at exact points, with their nodes moved onto the curve by an
//! exact Newton step: each line is one branch, certified from boundary to boundary, far within
//! the tolerance. The lines are known in closed form; the certified boxes are checked against
//! them, sampled densely.

use ssitrace::{intersect, Domain, Method, Options, RationalBezierPatch};

const SHIFT: [f64; 3] = [2.75, -1.375, 0.8125];

fn patch(degree: [usize; 2], pts: &[[f64; 3]], domain: Domain) -> RationalBezierPatch {
    let points = pts
        .iter()
        .map(|p| {
            std::array::from_fn(|k| inari::interval!(p[k] + SHIFT[k], p[k] + SHIFT[k]).unwrap())
        })
        .collect();
    RationalBezierPatch::new(degree, points, None, domain).expect("a valid patch")
}

#[test]
fn two_lines_two_micrometres_apart_are_certified_whole_and_tight() {
    // z = x² over x, y ∈ [−1, 1]: Bernstein heights 1, −1, 1 in x (every sum below is exact).
    let cylinder = patch(
        [2, 1],
        &[
            [-1.0, -1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [0.0, -1.0, -1.0],
            [0.0, 1.0, -1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
        ],
        Domain::UNIT,
    );
    let h = 2f64.powi(-40);
    let plane = patch(
        [1, 1],
        &[
            [-1.5, -1.5, h],
            [-1.5, 1.5, h],
            [1.5, -1.5, h],
            [1.5, 1.5, h],
        ],
        Domain::UNIT,
    );
    let tol = 1e-9;
    let opts = Options {
        method: Method::Both,
        required_tolerance: tol,
        ..Options::default()
    };
    let r = intersect(&cylinder, &plane, &opts).expect("runs");
    assert_eq!(r.branches.len(), 2, "one branch per line");
    let x_line = [SHIFT[0] - 2f64.powi(-20), SHIFT[0] + 2f64.powi(-20)];
    let z_line = SHIFT[2] + h;
    let mut seen = [false; 2];
    for (k, b) in r.branches.iter().enumerate() {
        let c = b.certified().expect("certified");
        let kinds: Vec<&str> = c.ends.iter().map(|e| e.kind()).collect();
        assert_eq!(kinds, ["boundary", "boundary"], "branch {k}");
        let t = b.certified_tolerance().expect("a tolerance");
        assert!(t <= tol, "branch {k}: tolerance {t:e}");
        // Which line: the boxes' x.
        let x0 = c.boxes[0].xyz[0].mid();
        let line = if (x0 - x_line[0]).abs() < (x0 - x_line[1]).abs() {
            0
        } else {
            1
        };
        assert!(!seen[line], "line {line} certified twice");
        seen[line] = true;
        // Every point of the line (y over P's domain) lies in a box, in model space and in P's
        // parameters (σ = (x − 1.75)/2, y = 2t − 1.375 − 1; every value here is exact).
        let n = 4096;
        for i in 0..=n {
            let tt = i as f64 / n as f64;
            let y = 2.0 * tt - 1.0 + SHIFT[1];
            let (x, z) = (x_line[line], z_line);
            let s = (x - 1.75) / 2.0;
            let inside = c.boxes.iter().any(|bx| {
                bx.xyz[0].contains(x)
                    && bx.xyz[1].contains(y)
                    && bx.xyz[2].contains(z)
                    && bx.p[0].contains(s)
                    && bx.p[1].contains(tt)
            });
            assert!(inside, "line {line}: ({x}, {y}, {z}) in no certified box");
        }
        // And every box lies within the tolerance of its line.
        for bx in &c.boxes {
            let off = (bx.xyz[0] - inari::interval!(x_line[line], x_line[line]).unwrap()).mag();
            assert!(off <= tol, "line {line}: a box reaches {off:e} from it");
        }
    }
    assert_eq!(seen, [true, true]);
}

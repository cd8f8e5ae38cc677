//! NURBS surfaces: the Bézier pieces of the rigorous knot-insertion split enclose the surface
//! (checked against an independent de Boor evaluation in f64), an interval-weighted NURBS sphere
//! stays on the unit sphere, and bad input is rejected naming the field.

mod common;

use common::surfaces::UNIT_CIRCLE_NET;

use inari::Interval;
use ssitrace::error::{Error, InputProblem};
use ssitrace::geometry::nurbs::NurbsSurface;
use ssitrace::{RationalBezierPatch, Scalar};

fn pt(x: f64) -> Interval {
    Interval::from_f64(x)
}

/// A small deterministic generator (xorshift), values in [-1, 1).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// De Boor's algorithm on a homogeneous f64 curve: the point at `x` of degree `p` over `knots`.
fn de_boor(knots: &[f64], p: usize, pts: &[[f64; 4]], x: f64) -> [f64; 4] {
    let n = pts.len();
    // The span u_k ≤ x < u_{k+1} with p ≤ k ≤ n − 1 (the last non-empty one at the right end).
    let mut k = p;
    while k + 1 < n && knots[k + 1] <= x {
        k += 1;
    }
    let mut d: Vec<[f64; 4]> = (0..=p).map(|j| pts[j + k - p]).collect();
    for r in 1..=p {
        for j in (r..=p).rev() {
            let lo = knots[j + k - p];
            let hi = knots[j + 1 + k - r];
            let a = (x - lo) / (hi - lo);
            let prev = d[j - 1];
            for (x, y) in d[j].iter_mut().zip(prev) {
                *x = (1.0 - a) * y + a * *x;
            }
        }
    }
    d[p]
}

/// The NURBS point at `(u, v)` by de Boor in both directions, from the midpoints of the data.
fn nurbs_point(s: &NurbsSurface, u: f64, v: f64) -> [f64; 3] {
    let [p, q] = s.degree();
    let [nu, nv] = s.count();
    let row: Vec<[f64; 4]> = (0..nu)
        .map(|i| {
            let col: Vec<[f64; 4]> = (0..nv)
                .map(|j| {
                    let x = s.points()[i * nv + j].map(|c| c.mid());
                    let w = s.weights()[i * nv + j].mid();
                    [w * x[0], w * x[1], w * x[2], w]
                })
                .collect();
            de_boor(&s.knots()[1], q, &col, v)
        })
        .collect();
    let h = de_boor(&s.knots()[0], p, &row, u);
    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
}

/// The piece whose domain holds `(u, v)`.
fn piece_at(pieces: &[RationalBezierPatch], u: f64, v: f64) -> &RationalBezierPatch {
    pieces
        .iter()
        .find(|b| b.domain().contains(u, v, 0.0))
        .expect("a piece covers every domain point")
}

/// Every de Boor point of `s` on a grid lies in the interval evaluation of the piece there,
/// widened by `slack`.
fn check_enclosure(s: &NurbsSurface, slack: f64) {
    let pieces = s.to_bezier().unwrap();
    let spans = s.spans();
    assert_eq!(pieces.len(), spans[0].len() * spans[1].len());
    let d = s.domain();
    let n = 37;
    for a in 0..=n {
        for b in 0..=n {
            let u = d.u[0] + (d.u[1] - d.u[0]) * a as f64 / n as f64;
            let v = d.v[0] + (d.v[1] - d.v[0]) * b as f64 / n as f64;
            let exact = nurbs_point(s, u, v);
            let piece = piece_at(&pieces, u, v);
            let enc = piece.eval::<Interval>(pt(u), pt(v));
            for c in 0..3 {
                let x = enc[c];
                assert!(
                    x.inf() - slack <= exact[c] && exact[c] <= x.sup() + slack,
                    "({u}, {v}) coordinate {c}: de Boor {} outside {x:?}",
                    exact[c]
                );
                assert!(x.wid() < 1e-9, "({u}, {v}): enclosure too wide {x:?}");
            }
            // The fast f64 evaluation of the piece agrees too.
            let f = piece.point_f64(u, v);
            for c in 0..3 {
                assert!(
                    (f[c] - exact[c]).abs() < 1e-9,
                    "({u}, {v}): {f:?} vs {exact:?}"
                );
            }
        }
    }
}

fn random_surface(
    rng: &mut Rng,
    degree: [usize; 2],
    knots: [Vec<f64>; 2],
    rational: bool,
) -> NurbsSurface {
    let nu = knots[0].len() - degree[0] - 1;
    let nv = knots[1].len() - degree[1] - 1;
    let points: Vec<[Interval; 3]> = (0..nu * nv)
        .map(|k| {
            let (i, j) = (k / nv, k % nv);
            [
                pt(i as f64 + 0.3 * rng.next()),
                pt(j as f64 + 0.3 * rng.next()),
                pt(rng.next()),
            ]
        })
        .collect();
    let weights = rational.then(|| {
        (0..nu * nv)
            .map(|_| pt(1.0 + 0.8 * rng.next()))
            .collect::<Vec<_>>()
    });
    NurbsSurface::new(degree, knots, points, weights).unwrap()
}

#[test]
fn bezier_pieces_enclose_the_nurbs_clamped_and_unclamped() {
    let mut rng = Rng(0x9e3779b97f4a7c15);
    let cases: Vec<([usize; 2], [Vec<f64>; 2])> = vec![
        // Clamped, interior knots of multiplicity 1 and 2.
        (
            [2, 3],
            [
                vec![0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 1.0, 1.0, 1.0],
                vec![-1.0, -1.0, -1.0, -1.0, 0.25, 2.0, 2.0, 2.0, 2.0],
            ],
        ),
        // Unclamped uniform.
        (
            [3, 2],
            [
                (0..11).map(f64::from).collect(),
                (0..8).map(|k| 0.5 * k as f64).collect(),
            ],
        ),
        // Mixed: clamped at one end only, non-uniform, degree 1 in v.
        (
            [2, 1],
            [
                vec![0.0, 0.0, 0.0, 0.7, 1.1, 2.0, 2.5, 3.9],
                vec![0.0, 0.0, 0.4, 0.9, 1.0, 1.0],
            ],
        ),
    ];
    for (degree, knots) in cases {
        for rational in [false, true] {
            let s = random_surface(&mut rng, degree, knots.clone(), rational);
            check_enclosure(&s, 1e-13);
        }
    }
}

/// The standard NURBS unit sphere: a 9-point circle in u (degree 2, four quarter arcs) times a
/// 5-point half circle in v, with the weight √2/2 given as an interval enclosing it.
fn sphere() -> NurbsSurface {
    let r = std::f64::consts::FRAC_1_SQRT_2;
    let s = Interval::try_from((r.next_down(), r.next_up())).unwrap();
    let half = pt(0.5);
    assert!((s * s).inf() <= 0.5 && 0.5 <= (s * s).sup() && half.inf() == 0.5);
    let circle = UNIT_CIRCLE_NET;
    let meridian = [(0.0, -1.0), (1.0, -1.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let wc = |i: usize| if i % 2 == 1 { s } else { pt(1.0) };
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for (i, &(x, y)) in circle.iter().enumerate() {
        for (j, &(r, z)) in meridian.iter().enumerate() {
            points.push([pt(r * x), pt(r * y), pt(z)]);
            weights.push(wc(i) * wc(j));
        }
    }
    let ku = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
    NurbsSurface::new([2, 2], [ku, kv], points, Some(weights)).unwrap()
}

#[test]
fn nurbs_sphere_pieces_lie_on_the_unit_sphere() {
    let s = sphere();
    let pieces = s.to_bezier().unwrap();
    assert_eq!(pieces.len(), 8);
    let mut widest: f64 = 0.0;
    for b in &pieces {
        let d = b.domain();
        for a in 0..=20 {
            for c in 0..=20 {
                let u = d.u[0] + (d.u[1] - d.u[0]) * a as f64 / 20.0;
                let v = d.v[0] + (d.v[1] - d.v[0]) * c as f64 / 20.0;
                let x = b.eval::<Interval>(pt(u), pt(v));
                let r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
                assert!(r2.contains(1.0), "({u}, {v}): |S|² = {r2:?}");
                widest = widest.max(r2.wid());
            }
        }
    }
    // The weight interval is one ulp wide; the radius enclosure stays within a few of them.
    assert!(widest < 1e-14, "radius enclosure width {widest:e}");
    // Independent check with de Boor at the weight's midpoint.
    check_enclosure(&s, 1e-15);
}

fn field_of(e: Error) -> (String, InputProblem) {
    match e {
        Error::InvalidInput { field, problem, .. } => (field, problem),
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}

#[test]
fn bad_nurbs_input_names_the_field() {
    let grid = |n: usize| -> Vec<[Interval; 3]> {
        (0..n)
            .map(|k| [pt(k as f64), pt((k * k) as f64), pt(1.0)])
            .collect()
    };
    let k3 = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    let make = |ku: Vec<f64>, pts: Vec<[Interval; 3]>, w: Option<Vec<Interval>>| {
        NurbsSurface::new([2, 2], [ku, k3.clone()], pts, w).map(|_| ())
    };
    // Too short.
    let (f, _) = field_of(make(vec![0.0, 0.0, 1.0, 1.0], grid(3), None).unwrap_err());
    assert_eq!(f, "knots[0]");
    // Decreasing.
    let (f, _) =
        field_of(make(vec![0.0, 0.0, 0.0, 0.6, 0.4, 1.0, 1.0, 1.0], grid(15), None).unwrap_err());
    assert_eq!(f, "knots[0][4]");
    // Interior multiplicity above the degree.
    let (f, _) = field_of(
        make(
            vec![0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0],
            grid(18),
            None,
        )
        .unwrap_err(),
    );
    assert_eq!(f, "knots[0][3]");
    // End multiplicity above degree + 1.
    let (f, _) =
        field_of(make(vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0], grid(12), None).unwrap_err());
    assert_eq!(f, "knots[0][0]");
    // Non-finite knot.
    let (f, p) =
        field_of(make(vec![0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0, 1.0], grid(12), None).unwrap_err());
    assert_eq!((f.as_str(), p), ("knots[0][3]", InputProblem::NonFinite));
    // Wrong point count.
    let (f, p) = field_of(make(k3.clone(), grid(8), None).unwrap_err());
    assert_eq!(f, "points");
    assert_eq!(
        p,
        InputProblem::WrongCount {
            expected: 9,
            found: 8
        }
    );
    // Non-positive weight.
    let mut w = vec![pt(1.0); 9];
    w[4] = pt(0.0);
    let (f, p) = field_of(make(k3.clone(), grid(9), Some(w)).unwrap_err());
    assert_eq!(
        (f.as_str(), p),
        ("weights[4]", InputProblem::NonPositiveWeight)
    );
    // Wrong weight count.
    let (f, _) = field_of(make(k3.clone(), grid(9), Some(vec![pt(1.0); 3])).unwrap_err());
    assert_eq!(f, "weights");
    // Non-finite coordinate.
    let mut g = grid(9);
    g[2][1] = pt(f64::INFINITY);
    let (f, _) = field_of(make(k3.clone(), g, None).unwrap_err());
    assert_eq!(f, "points[2][1]");
    // Degree 0.
    let e = NurbsSurface::new([0, 2], [k3.clone(), k3.clone()], grid(9), None).unwrap_err();
    assert_eq!(field_of(e).0, "degree[0]");
}

mod mangled {
    use crate::common::mangle::replace_at;
    use proptest::prelude::*;
    use serde_json::Value;
    use ssitrace::error::Error;
    use ssitrace::io::scene::ShellScene;

    fn sphere_scene() -> Value {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/scenes/nurbs_sphere_plane.json"
        );
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    }

    fn arb_json() -> impl Strategy<Value = Value> {
        let leaf = prop_oneof![
            Just(Value::Null),
            any::<bool>().prop_map(Value::from),
            (-3i64..12).prop_map(Value::from),
            any::<i64>().prop_map(Value::from),
            any::<f64>()
                .prop_map(|x| serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)),
            prop_oneof![Just("nurbs"), Just("bezier"), Just("x")].prop_map(Value::from),
        ];
        leaf.prop_recursive(3, 24, 4, |inner| {
            prop::collection::vec(inner, 0..5).prop_map(Value::Array)
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]

        #[test]
        fn mangled_nurbs_never_panics_and_names_the_field(
            path in prop::collection::vec(any::<usize>(), 0..4),
            new in arb_json(),
        ) {
            let mut v = sphere_scene();
            replace_at(&mut v["surfaces"][0], &path, new);
            match ShellScene::from_json_value(&v) {
                Ok(s) => {
                    for f in &s.shells[0] {
                        prop_assert!(!f.pieces().is_empty());
                    }
                }
                Err(Error::InvalidInput { surface, field, .. }) => {
                    prop_assert_eq!(surface, Some(0));
                    prop_assert!(!field.is_empty());
                }
                Err(other) => prop_assert!(false, "unexpected error kind {other:?}"),
            }
        }
    }
}

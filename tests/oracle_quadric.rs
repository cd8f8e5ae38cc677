//! Random pieces of spheres, cylinders, cones and tori against random planes, against an
//! independent reference intersection.
//!
//! The second family of the random oracle (the first, `tests/oracle_random.rs`, has height
//! fields). P is a piece of a surface of revolution, as a rational biquadratic Bézier patch: an
//! arc of a circle in `u` (weights `1, cos(α/2), 1`) swept along a meridian in `v` — a circular
//! arc (sphere, torus) or a segment (cylinder, cone) — then moved by a random rotation and
//! translation, its control points rounded to `f64`. Q is a parallelogram whose corners are
//! dyadic, so the bilinear patch is exactly planar; it is large enough to hold the whole
//! intersection. Two kinds of pairs:
//! - **crossing**: the plane passes through a random point of P in a random direction;
//! - **near-tangent**: the plane is P's tangent plane at a random point, moved by `δ` (1e-2 down
//!   to 1e-8 of a unit model) into P or away from it. Into a sphere, a cone's or torus's outer
//!   side it cuts a tiny loop of radius about `√(2δ/κ)`; into a cylinder two lines `2√(2Rδ)`
//!   apart; on a torus's inner (saddle) side two near-crossing arcs; away from P, nothing there.
//!
//! **The reference** is computed without the code under test, from P's control data as given:
//! on grid lines `u = c` and `v = c` of P's parameters, and on the two lines through the
//! tangent point of a near-tangent pair, the sign of `n·S − d` (the plane `n·x = d` held in
//! intervals, `S` P's homogeneous point by de Casteljau in `inari`, divided by nothing since the
//! weight is positive) is sampled, and each sign change is bisected on proven signs. Every
//! bracket holds a point of the true intersection; the checks are those of
//! `tests/common/oracle.rs` (soundness against boxes and tubes, completeness, each arc once,
//! tolerance).
//!
//! A third kind, **polar** ([`polar_pair`]): a sphere piece whose meridian ends exactly at the
//! pole (its last row of control points one exact point, so the piece knows the side collapses
//! there), against a plane through a point `10^−k` (k uniform in [1, 7]) of the meridian's
//! parameter from the pole, in a random direction; 60 fixed seeds run in CI, and
//! `polar_soak` by hand (seeds from 3 000 000).
//!
//! A fourth, **edge** ([`edge_pair`]): a piece whose boundary meridian or parallel lies
//! exactly in a coordinate plane, against that plane or the plane moved by 1e-12 to 1e-6: the
//! curve runs along P's boundary or beside it; 48 fixed seeds in CI, `edge_soak` by hand (from 4 000 000).
//!
//! `cargo test --release --test oracle_quadric -- --nocapture` prints the figures; the soak is
//! `SSITRACE_ORACLE_PAIRS=10000 cargo test --release --test oracle_quadric soak -- --ignored
//! --nocapture` (same options as the height-field soak).

mod common;

use common::oracle::{
    assert_clean, assert_sound, compare, engine, env_parse, fresh_base, point, run_with_progress,
    sign_change_brackets, sign_change_brackets_at, sign_of, Comparison, Figures, RefPoint,
};
use common::rng::Rng;
use inari::Interval;
use ssitrace::geometry::{Domain, RationalBezierPatch};
use ssitrace::{intersect, Method, Options, SurfaceIntersection};
use std::f64::consts::{FRAC_PI_2, TAU};
use std::time::Instant;

/// The homogeneous 3×3 net of P (index `3i + j`, `i` along `u`), in intervals.
struct Net {
    h: Vec<[Interval; 4]>,
}

impl Net {
    fn new(points: &[[f64; 3]], weights: &[f64]) -> Self {
        let h = points
            .iter()
            .zip(weights)
            .map(|(p, &w)| {
                let w = point(w);
                [point(p[0]) * w, point(p[1]) * w, point(p[2]) * w, w]
            })
            .collect();
        Net { h }
    }

    /// The homogeneous point at `(u, v)` (de Casteljau along `v`, then `u`).
    fn eval(&self, u: Interval, v: Interval) -> [Interval; 4] {
        let one = point(1.0);
        let quad = |a: [Interval; 4], b: [Interval; 4], c: [Interval; 4], t: Interval| {
            let s = one - t;
            std::array::from_fn(|k| {
                let ab = s * a[k] + t * b[k];
                let bc = s * b[k] + t * c[k];
                s * ab + t * bc
            })
        };
        let rows: Vec<[Interval; 4]> = (0..3)
            .map(|i| quad(self.h[3 * i], self.h[3 * i + 1], self.h[3 * i + 2], v))
            .collect();
        quad(rows[0], rows[1], rows[2], u)
    }

    /// The Cartesian point in `f64` (midpoints; only to place the plane).
    fn point_f64(&self, u: f64, v: f64) -> [f64; 3] {
        let h = self.eval(point(u), point(v));
        std::array::from_fn(|k| h[k].mid() / h[3].mid())
    }
}

/// The plane `n·x = d`, `n` and `d` enclosed in intervals.
struct Plane {
    n: [Interval; 3],
    d: Interval,
}

impl Plane {
    /// The proven sign of `n·S − d` at P's parameters `(u, v)` (`0` when undecided).
    fn side(&self, net: &Net, u: f64, v: f64) -> i32 {
        let h = net.eval(point(u), point(v));
        let nx = self.n[0] * h[0] + self.n[1] * h[1] + self.n[2] * h[2];
        sign_of(nx - self.d * h[3])
    }
}

/// What P is a piece of.
#[derive(Clone, Copy, Debug)]
enum Kind {
    Sphere,
    Cylinder,
    Cone,
    Torus,
}

/// A meridian `(r, z)` as a rational quadratic: three control points and weights.
type Meridian = ([[f64; 2]; 3], [f64; 3]);

/// The arc of the circle of centre `(rc, 0)` and radius `a` from angle `f0` through `beta`.
fn circle_arc(rc: f64, a: f64, f0: f64, beta: f64) -> Meridian {
    let (f1, fm) = (f0 + beta, f0 + 0.5 * beta);
    let c = (0.5 * beta).cos();
    (
        [
            [rc + a * f0.cos(), a * f0.sin()],
            [rc + a * fm.cos() / c, a * fm.sin() / c],
            [rc + a * f1.cos(), a * f1.sin()],
        ],
        [1.0, c, 1.0],
    )
}

fn segment(a: [f64; 2], b: [f64; 2]) -> Meridian {
    ([a, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])], b], [1.0; 3])
}

fn random_meridian(rng: &mut Rng, kind: Kind) -> Meridian {
    match kind {
        Kind::Sphere => {
            let r = rng.uniform(0.5, 2.0);
            let f0 = rng.uniform(-1.3, 0.6);
            let beta = rng.uniform(0.4, (1.4 - f0).min(2.0));
            circle_arc(0.0, r, f0, beta)
        }
        Kind::Cylinder => {
            let r = rng.uniform(0.3, 1.5);
            segment([r, 0.0], [r, rng.uniform(0.5, 2.0)])
        }
        Kind::Cone => segment(
            [rng.uniform(0.3, 1.2), 0.0],
            [rng.uniform(0.3, 1.2), rng.uniform(0.5, 1.5)],
        ),
        Kind::Torus => {
            let big = rng.uniform(1.0, 2.0);
            let a = rng.uniform(0.2, 0.8) * big;
            circle_arc(big, a, rng.uniform(0.0, TAU), rng.uniform(0.4, 2.5))
        }
    }
}

/// A piece of a surface of revolution of `kind`, moved by a random rotation and translation:
/// its control points and weights (index `3i + j`).
fn random_piece(rng: &mut Rng, kind: Kind) -> (Vec<[f64; 3]>, Vec<f64>) {
    let mer = random_meridian(rng, kind);
    swept(rng, mer)
}

/// The meridian swept along a random arc in `u`, moved by a random rotation and translation.
fn swept(rng: &mut Rng, (mer, mw): Meridian) -> (Vec<[f64; 3]>, Vec<f64>) {
    let (t0, alpha) = (rng.uniform(0.0, TAU), rng.uniform(0.4, 2.5));
    let c = (0.5 * alpha).cos();
    let arc = [
        ([t0.cos(), t0.sin()], 1.0),
        (
            [(t0 + 0.5 * alpha).cos() / c, (t0 + 0.5 * alpha).sin() / c],
            c,
        ),
        ([(t0 + alpha).cos(), (t0 + alpha).sin()], 1.0),
    ];
    let rot = rng.rotation();
    let shift: [f64; 3] = std::array::from_fn(|_| rng.uniform(-2.0, 2.0));
    let mut points = Vec::with_capacity(9);
    let mut weights = Vec::with_capacity(9);
    for (xy, wu) in arc {
        for (rz, wv) in mer.iter().zip(mw) {
            let x = [rz[0] * xy[0], rz[0] * xy[1], rz[1]];
            points.push(std::array::from_fn(|i| {
                (0..3).map(|k| rot[i][k] * x[k]).sum::<f64>() + shift[i]
            }));
            weights.push(wu * wv);
        }
    }
    (points, weights)
}

/// Rounds to a multiple of 2⁻²⁰ (so sums of a few such numbers below 2⁸ are exact).
fn dyadic(x: f64) -> f64 {
    (x * (1u64 << 20) as f64).round() / (1u64 << 20) as f64
}

/// The parallelogram `c ± a/2 ± b/2` (dyadic data, so exactly planar) as a bilinear patch, and
/// its plane in intervals.
fn plane_patch(
    c: [f64; 3],
    a: [f64; 3],
    b: [f64; 3],
) -> (RationalBezierPatch, Plane, [[f64; 3]; 4]) {
    let (c, a, b) = (c.map(dyadic), a.map(dyadic), b.map(dyadic));
    let q00: [f64; 3] = std::array::from_fn(|k| c[k] - 0.5 * a[k] - 0.5 * b[k]);
    let corners = [
        q00,
        std::array::from_fn(|k| q00[k] + b[k]),
        std::array::from_fn(|k| q00[k] + a[k]),
        std::array::from_fn(|k| q00[k] + a[k] + b[k]),
    ];
    let patch = RationalBezierPatch::from_f64_points(
        [1, 1],
        &corners,
        None,
        Domain::new(0.0, 1.0, 0.0, 1.0),
    )
    .expect("a parallelogram");
    let (ai, bi) = (a.map(point), b.map(point));
    let n = [
        ai[1] * bi[2] - ai[2] * bi[1],
        ai[2] * bi[0] - ai[0] * bi[2],
        ai[0] * bi[1] - ai[1] * bi[0],
    ];
    let d = n[0] * point(q00[0]) + n[1] * point(q00[1]) + n[2] * point(q00[2]);
    (patch, Plane { n, d }, corners)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|k| a[k] - b[k])
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit(a: [f64; 3]) -> [f64; 3] {
    let n = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    a.map(|x| x / n)
}

/// One random pair and what the reference needs: P, Q, P's net, the plane, the extra reference
/// lines through the tangent point (near-tangent pairs) and the nearness scale of the check.
struct Pair {
    /// Both patches' control data, as a scene file (`SSITRACE_ORACLE_SCENE_DIR` writes it).
    scene: String,
    p: RationalBezierPatch,
    q: RationalBezierPatch,
    net: Net,
    plane: Plane,
    /// P's parameters of the tangent point of a near-tangent pair.
    tangent_point: Option<[f64; 2]>,
    /// For an [`edge_pair`], `ε` and the parameter held on the boundary curve (0: `u = 0`, the
    /// meridian; 1: `v = 0`, the parallel): the reference then also samples the lines across
    /// that side from it outward (geometrically), and for `ε = 0` holds the boundary curve's
    /// points themselves (exactly in the plane: the boundary row's coordinate is the plane's).
    along_boundary: Option<(f64, usize)>,
    near: f64,
    label: String,
}

fn random_pair(seed: u64) -> Pair {
    let mut rng = Rng::new(seed);
    let kind = [Kind::Sphere, Kind::Cylinder, Kind::Cone, Kind::Torus][(seed % 4) as usize];
    let near_tangent = (seed / 4) % 2 == 1;
    let (points, weights) = random_piece(&mut rng, kind);
    pair_of(seed, rng, kind, near_tangent, points, weights)
}

/// A sphere piece reaching the pole (its last row of control points the pole itself, one
/// exact point, so the piece knows the side collapses there) against a plane through a point
/// of the piece `10^−k` (k uniform in [1, 7]) of its meridian's parameter from the pole, in a
/// random direction: the curve passes the pole at about that distance times the meridian's
/// length.
fn polar_pair(seed: u64) -> Pair {
    let mut rng = Rng::new(seed);
    let r = rng.uniform(0.5, 2.0);
    let f0 = rng.uniform(0.2, 1.2);
    let (mut mer, mw) = circle_arc(0.0, r, f0, FRAC_PI_2 - f0);
    mer[2] = [0.0, r];
    let (points, weights) = swept(&mut rng, (mer, mw));
    let net = Net::new(&points, &weights);
    let (u0, t) = (rng.uniform(0.0, 1.0), 10f64.powf(-rng.uniform(1.0, 7.0)));
    let n = unit(std::array::from_fn(|_| rng.uniform(-1.0, 1.0)));
    let mut pair = pair_through(seed, &points, &weights, (n, net.point_f64(u0, 1.0 - t)));
    assert!(
        pair.p.collapsed_sides()[3].is_some(),
        "seed {seed}: the pole's side is one exact point"
    );
    pair.label = format!("polar crossing {t:.1e} from the pole");
    pair
}

/// A piece whose boundary meridian `u = 0` (or, every other 24 seeds, boundary parallel
/// `v = 0`) lies in a coordinate plane, against that plane moved by `ε` (0, ±1e-12, ±1e-9 or
/// 1e-6): the curve runs *along* P's boundary (`ε = 0`), or beside it inside or outside the
/// domain. The piece is swept from angle 0 (its first row of control points has `y = 0`
/// exactly; along the parallel, its meridian starts at `z = 0` exactly) and moved exactly (a
/// permutation of the axes, signs, and a dyadic shift), and the plane's corners are exact, so
/// `ε = 0` is exactly along.
fn edge_pair(seed: u64) -> Pair {
    let mut rng = Rng::new(seed);
    let kind = [Kind::Sphere, Kind::Cylinder, Kind::Cone, Kind::Torus][(seed % 4) as usize];
    let eps = [0.0, 1e-12, -1e-12, 1e-9, -1e-9, 1e-6][((seed / 4) % 6) as usize];
    // Along the meridian `u = 0` (in y = 0) or the parallel `v = 0` (in z = 0: the meridian
    // starts at z = 0 exactly, on the equator of a sphere or torus).
    let parallel = (seed / 24) % 2 == 1;
    let (mer, mw) = match (parallel, kind) {
        (true, Kind::Sphere) => circle_arc(0.0, rng.uniform(0.5, 2.0), 0.0, rng.uniform(0.4, 1.4)),
        (true, Kind::Torus) => {
            let big = rng.uniform(1.0, 2.0);
            let a = rng.uniform(0.2, 0.8) * big;
            circle_arc(big, a, 0.0, rng.uniform(0.4, 2.5))
        }
        _ => random_meridian(&mut rng, kind),
    };
    let alpha = rng.uniform(0.4, 2.5);
    let c = (0.5 * alpha).cos();
    let arc = [
        ([1.0, 0.0], 1.0),
        ([(0.5 * alpha).cos() / c, (0.5 * alpha).sin() / c], c),
        ([alpha.cos(), alpha.sin()], 1.0),
    ];
    let perm = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ][rng.below(6)];
    let sign: [f64; 3] = std::array::from_fn(|_| if rng.below(2) == 0 { 1.0 } else { -1.0 });
    let shift: [f64; 3] = std::array::from_fn(|_| dyadic(rng.uniform(-2.0, 2.0)));
    let moved =
        |x: [f64; 3]| -> [f64; 3] { std::array::from_fn(|k| sign[k] * x[perm[k]] + shift[k]) };
    let (mut points, mut weights) = (Vec::with_capacity(9), Vec::with_capacity(9));
    for (xy, wu) in arc {
        for (rz, wv) in mer.iter().zip(mw) {
            points.push(moved([rz[0] * xy[0], rz[0] * xy[1], rz[1]]));
            weights.push(wu * wv);
        }
    }
    let p = RationalBezierPatch::from_f64_points([2, 2], &points, Some(&weights), Domain::UNIT)
        .expect("a valid piece");
    let net = Net::new(&points, &weights);
    // The plane: coordinate `k` (the image of y, or of z along the parallel) at the boundary
    // curve's value moved by ε.
    let held = if parallel { 2 } else { 1 };
    let k = (0..3).find(|&k| perm[k] == held).expect("a permutation");
    let value = shift[k] + sign[k] * eps;
    let (a, b) = ((k + 1) % 3, (k + 2) % 3);
    let lo = |i: usize| dyadic(points.iter().map(|x| x[i]).fold(f64::INFINITY, f64::min) - 1.0);
    let hi = |i: usize| {
        dyadic(
            points
                .iter()
                .map(|x| x[i])
                .fold(f64::NEG_INFINITY, f64::max)
                + 1.0,
        )
    };
    let corner = |ua: f64, ub: f64| {
        let mut x = [0.0; 3];
        x[k] = value;
        x[a] = ua;
        x[b] = ub;
        x
    };
    let corners = [
        corner(lo(a), lo(b)),
        corner(lo(a), hi(b)),
        corner(hi(a), lo(b)),
        corner(hi(a), hi(b)),
    ];
    let q = RationalBezierPatch::from_f64_points([1, 1], &corners, None, Domain::UNIT)
        .expect("a rectangle");
    let mut n = [point(0.0); 3];
    n[k] = point(1.0);
    let scene = format!(
        "{{\"surfaces\": [{{\"kind\": \"bezier\", \"degree\": [2, 2], \"points\": {points:?}, \"weights\": {weights:?}}}, {{\"kind\": \"bezier\", \"degree\": [1, 1], \"points\": {corners:?}}}], \"options\": {{\"name\": \"oracle-quadric-edge-{seed}\", \"method\": \"validated\"}}}}\n"
    );
    Pair {
        scene,
        p,
        q,
        net,
        plane: Plane { n, d: point(value) },
        tangent_point: None,
        along_boundary: Some((eps, usize::from(parallel))),
        near: 0.02,
        label: format!(
            "{kind:?} along its boundary {}, ε = {eps:e}",
            if parallel { "parallel" } else { "meridian" }
        ),
    }
}

/// The pair of the piece `points`, `weights` and a plane chosen by `rng` (see [`random_pair`]).
fn pair_of(
    seed: u64,
    mut rng: Rng,
    kind: Kind,
    near_tangent: bool,
    points: Vec<[f64; 3]>,
    weights: Vec<f64>,
) -> Pair {
    let net = Net::new(&points, &weights);
    let (u0, v0) = (rng.uniform(0.1, 0.9), rng.uniform(0.1, 0.9));
    let x0 = net.point_f64(u0, v0);
    let (normal, tangent_point, near, label) = if near_tangent {
        let h = 1e-6;
        let du = sub(net.point_f64(u0 + h, v0), net.point_f64(u0 - h, v0));
        let dv = sub(net.point_f64(u0, v0 + h), net.point_f64(u0, v0 - h));
        let n = unit(cross(du, dv));
        let delta = [1e-2, 1e-4, 1e-6, 1e-8][rng.below(4)];
        let into = rng.uniform(0.0, 1.0) < 0.75;
        // Moving the plane by ±δ along n; which side is "into" P depends on its curvature, so
        // both happen: the label says which way it went.
        let s = if into { 1.0 } else { -1.0 };
        let shifted: [f64; 3] = std::array::from_fn(|k| x0[k] + s * delta * n[k]);
        (
            (n, shifted),
            Some([u0, v0]),
            0.25 * delta.sqrt(),
            format!("{kind:?} near-tangent δ = {:e}", s * delta),
        )
    } else {
        let n = unit(std::array::from_fn(|_| rng.uniform(-1.0, 1.0)));
        ((n, x0), None, 0.02, format!("{kind:?} crossing"))
    };
    let mut pair = pair_through(seed, &points, &weights, normal);
    pair.tangent_point = tangent_point;
    pair.near = near;
    pair.label = label;
    pair
}

/// The pair of the piece `points`, `weights` and the plane through `centre` with normal `n`
/// (a square 2.5 times P's control-net diameter across); no tangent point, a crossing's `near`.
fn pair_through(
    seed: u64,
    points: &[[f64; 3]],
    weights: &[f64],
    (n, centre): ([f64; 3], [f64; 3]),
) -> Pair {
    let p = RationalBezierPatch::from_f64_points(
        [2, 2],
        points,
        Some(weights),
        Domain::new(0.0, 1.0, 0.0, 1.0),
    )
    .expect("a valid piece");
    let net = Net::new(points, weights);
    let diam = points
        .iter()
        .flat_map(|a| points.iter().map(move |b| sub(*a, *b)))
        .map(|d| d.iter().map(|x| x * x).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    let e1 = unit(cross(
        n,
        if n[0].abs() < 0.6 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        },
    ));
    let e2 = cross(n, e1);
    let side = 2.5 * diam;
    let (q, plane, corners) = plane_patch(centre, e1.map(|x| side * x), e2.map(|x| side * x));
    let scene = format!(
        "{{\"surfaces\": [{{\"kind\": \"bezier\", \"degree\": [2, 2], \"points\": {points:?}, \"weights\": {weights:?}}}, {{\"kind\": \"bezier\", \"degree\": [1, 1], \"points\": {corners:?}}}], \"options\": {{\"name\": \"oracle-quadric-{seed}\", \"method\": \"validated\"}}}}\n"
    );
    Pair {
        scene,
        p,
        q,
        net,
        plane,
        tangent_point: None,
        along_boundary: None,
        near: 0.02,
        label: String::new(),
    }
}

/// Reference points on the grid lines `u, v = k/16`, away from P's boundary by `margin`, and for
/// a near-tangent pair on the lines `u = u₀` and `v = v₀` through its tangent point, sampled
/// geometrically outward from it (a loop round it may be far smaller than the grid).
fn reference(pair: &Pair, margin: f64) -> Vec<RefPoint> {
    let side = |u: f64, v: f64| pair.plane.side(&pair.net, u, v);
    let (lo, hi) = (margin, 1.0 - margin);
    let mut out = Vec::new();
    for c in (1..16).map(|k| k as f64 / 16.0) {
        for x in sign_change_brackets(|s| side(s, c), lo, hi, 400) {
            out.push(RefPoint { x, y: [c, c] });
        }
        for y in sign_change_brackets(|s| side(c, s), lo, hi, 400) {
            out.push(RefPoint { x: [c, c], y });
        }
    }
    if let Some((eps, held)) = pair.along_boundary {
        let from_edge = || {
            std::iter::once(0.0).chain(
                (0..200)
                    .map(|k| 1e-16 * 1.25f64.powi(k))
                    .take_while(|d| *d < 0.1),
            )
        };
        for c in (1..16).map(|k| k as f64 / 16.0) {
            let at = |x: [f64; 2]| {
                if held == 0 {
                    RefPoint { x, y: [c, c] }
                } else {
                    RefPoint { x: [c, c], y: x }
                }
            };
            if eps == 0.0 {
                out.push(at([0.0, 0.0]));
            } else {
                let across = |s: f64| if held == 0 { side(s, c) } else { side(c, s) };
                out.extend(
                    sign_change_brackets_at(across, from_edge())
                        .into_iter()
                        .map(at),
                );
            }
        }
    }
    if let Some(&[u0, v0]) = pair.tangent_point.as_ref() {
        // Offsets 1e-9·1.25^k on both sides of the tangent point, inside the margin.
        let around = |c: f64| {
            let steps: Vec<f64> = (0..100)
                .map(|k| 1e-9 * 1.25f64.powi(k))
                .take_while(|d| *d < 1.0)
                .collect();
            let mut at: Vec<f64> = steps.iter().rev().map(|d| c - d).collect();
            at.push(c);
            at.extend(steps.iter().map(|d| c + d));
            at.retain(|s| lo <= *s && *s <= hi);
            at
        };
        for x in sign_change_brackets_at(|s| side(s, v0), around(u0).into_iter()) {
            out.push(RefPoint { x, y: [v0, v0] });
        }
        for y in sign_change_brackets_at(|s| side(u0, s), around(v0).into_iter()) {
            out.push(RefPoint { x: [u0, u0], y });
        }
    }
    out
}

fn check_pair(seed: u64, fig: &mut Figures) {
    check(seed, random_pair(seed), fig);
}

fn check_polar_pair(seed: u64, fig: &mut Figures) {
    check(seed, polar_pair(seed), fig);
}

fn check_edge_pair(seed: u64, fig: &mut Figures) {
    check(seed, edge_pair(seed), fig);
}

fn check(seed: u64, pair: Pair, fig: &mut Figures) {
    if let Ok(dir) = std::env::var("SSITRACE_ORACLE_SCENE_DIR") {
        let path = format!("{dir}/oracle_quadric_{seed}.json");
        std::fs::write(&path, &pair.scene).expect("scene written");
    }
    let opts = Options {
        method: Method::Validated,
        engine: engine(),
        ..Options::default()
    };
    let clock = Instant::now();
    let result: SurfaceIntersection = intersect(&pair.p, &pair.q, &opts).expect("valid options");
    fig.times.push(clock.elapsed().as_secs_f64());
    let refs = reference(&pair, 1e-3);
    let before = fig.notes.len();
    let cmp = Comparison {
        seed,
        domains: [[0.0, 1.0, 0.0, 1.0]; 2],
        result: &result,
        refs: &refs,
        widen: 0.0,
        required: opts.required_tolerance,
        near: pair.near,
        p: Some(&pair.p),
    };
    compare(&cmp, fig);
    for n in &mut fig.notes[before..] {
        n.push_str(&format!(" ({})", pair.label));
    }
}

fn run(seeds: impl Iterator<Item = u64>) -> Figures {
    run_with_progress(seeds, 0, check_pair)
}

#[test]
fn quadric_pieces_against_planes_fixed_seeds_0() {
    assert_clean(&run(0..80));
}

#[test]
fn quadric_pieces_against_planes_fixed_seeds_1() {
    assert_clean(&run(80..160));
}

/// Fresh pairs on every run (the seed is printed; replay with `SSITRACE_ORACLE_SEED`).
#[test]
fn quadric_pieces_against_planes_fresh_seeds() {
    let base = fresh_base();
    assert_sound(&run((0..16).map(|k| base.wrapping_add(k))));
}

/// Sphere pieces reaching a pole against planes passing it at 1e-1 to 1e-7 of the meridian
/// ([`polar_pair`]): the pole's side collapses to one point, where the normal vanishes.
#[test]
fn polar_sphere_pieces_against_planes() {
    let fig = run_with_progress(0..60, 0, check_polar_pair);
    assert_clean(&fig);
}

/// Polar pairs the soaks found wanting, each now clean: 3 010 292, a plane passing about 1e-6
/// from the pole that leaves the piece by its side `u = 1` next to the pole (its chain's links
/// there did not contract on the net as given, the half stopped with "close branches", and the
/// arc was traced again twice with finer steps: three copies; the links now fall back on the
/// patches moved so that the pole is the origin), and 3 010 134, which a first form of that
/// fallback had ended with a singular box beside the pole.
#[test]
fn polar_pairs_the_soaks_found() {
    let fig = run_with_progress([3_010_292, 3_010_134].into_iter(), 0, check_polar_pair);
    assert_clean(&fig);
}

/// Pieces whose boundary meridian lies in the plane or within 1e-12 to 1e-6 of it
/// ([`edge_pair`]): the curve runs along P's boundary, or beside it.
#[test]
fn pieces_along_their_boundary_against_planes() {
    let fig = run_with_progress(0..48, 0, check_edge_pair);
    assert_clean(&fig);
}

/// The soak of [`edge_pair`]s: as [`soak`], from `SSITRACE_ORACLE_FIRST` (default 4 000 000).
#[test]
#[ignore = "soak: run by hand, see the module doc"]
fn edge_soak() {
    let n = env_parse("SSITRACE_ORACLE_PAIRS").unwrap_or(10_000u64);
    let first = env_parse("SSITRACE_ORACLE_FIRST").unwrap_or(4_000_000u64);
    let every = env_parse("SSITRACE_ORACLE_PROGRESS").unwrap_or(0usize);
    assert_sound(&run_with_progress(first..first + n, every, check_edge_pair));
}

/// The soak of [`polar_pair`]s: as [`soak`], from `SSITRACE_ORACLE_FIRST` (default 3 000 000).
#[test]
#[ignore = "soak: run by hand, see the module doc"]
fn polar_soak() {
    let n = env_parse("SSITRACE_ORACLE_PAIRS").unwrap_or(10_000u64);
    let first = env_parse("SSITRACE_ORACLE_FIRST").unwrap_or(3_000_000u64);
    let every = env_parse("SSITRACE_ORACLE_PROGRESS").unwrap_or(0usize);
    assert_sound(&run_with_progress(
        first..first + n,
        every,
        check_polar_pair,
    ));
}

/// The soak: `SSITRACE_ORACLE_PAIRS` pairs (default 10 000) from `SSITRACE_ORACLE_FIRST`
/// (default 1 000 000); `SSITRACE_ORACLE_PROGRESS=k` prints the figures every `k` pairs.
#[test]
#[ignore = "soak: run by hand, see the module doc"]
fn soak() {
    let n = env_parse("SSITRACE_ORACLE_PAIRS").unwrap_or(10_000u64);
    let first = env_parse("SSITRACE_ORACLE_FIRST").unwrap_or(1_000_000u64);
    let every = env_parse("SSITRACE_ORACLE_PROGRESS").unwrap_or(0usize);
    assert_sound(&run_with_progress(first..first + n, every, check_pair));
}

/// Pairs the soak found where the marcher jumped at a near-crossing on a torus's saddle side
/// (a plane within 1e-8 and 1e-6 of tangent): one arm was certified twice and another by no
/// branch. The stretch a jump leaves uncertified is now traced again with a finer step and the
/// jumping branches are dropped as duplicates: two curves, each certified from boundary to
/// boundary, each arc once.
///
/// Seed 8 514 911 (1e-8 from tangency): the marcher ends four arcs at a "singular point" where
/// the two curves pass closest; the chains of two of them now go on through it along their
/// true curves to the boundary (no point with parallel normals lies there), and the other two
/// arcs, whose marched points but the one at the "node" (on neither curve) lie in those
/// chains, are dropped as copies: two curves, each certified once from boundary to boundary
/// (each was certified twice).
#[test]
fn near_crossings_on_a_torus_are_traced_once_each() {
    let fig = run([1_000_103, 1_000_559, 8_514_911].into_iter());
    assert_clean(&fig);
    assert_eq!(fig.unproven_ends, 0, "{:?}", fig.notes);
    assert_eq!(fig.branches, 6, "two curves per pair");
}

/// Tiny loops of a torus's outer side against a plane 1e-8 from tangent (radius about 1e-3,
/// normals 1e-4 to 7e-4 apart): the march used to crawl at 1e-7 a step (the cap of the
/// approach to a singular point, a length, was taken for the step angle and shrunk again by the
/// loop's radius) and stopped at the point limit in five pieces a third of the way round. Each
/// is now one closed loop, certified closed.
///
/// Seed 8 400 735 (a loop of radius 7e-5, normals 1e-4 apart): the tubes of the links on one
/// side of the loop stayed at 5.4e-10–6.4e-10 however short the links, just above the chain's
/// aim of half the tolerance; the normals' cross product holds zero on a box 1e-4 round them,
/// so both halves stopped there with a "singular box", the loop's closure was not proven, and
/// the march round it three times gave three branches (an arc certified three times). No point
/// with parallel normals lies near (Gauss–Newton), so those links are now kept: one loop,
/// closed, within the tolerance.
#[test]
fn tiny_near_tangent_loops_on_a_torus_close_once() {
    let fig = run([2_000_111, 2_000_591, 8_400_735].into_iter());
    assert_clean(&fig);
    assert_eq!(fig.unproven_ends, 0, "{:?}", fig.notes);
    assert_eq!(fig.branches, 3, "one loop per pair");
}

/// A tiny loop 1e-8 from tangency whose normals are only 7e-5 apart where it is worst (seed
/// 8 402 951). It used to stop at both ends with a "singular box" (there is no singular point)
/// and be marched and certified three times; then it was one closed loop whose certificate
/// missed the tolerance (1.4e-9: no link was narrower than the interval residual's rounding
/// over that sine). Its links there are now proven on the exact residual at exact points, with
/// nodes moved onto the curve by an exact Newton step: one loop, closed, within the tolerance.
#[test]
fn a_near_tangent_loop_closes_once_within_the_tolerance() {
    let fig = run([8_402_951].into_iter());
    assert_clean(&fig);
    assert_eq!(fig.unproven_ends, 0, "{:?}", fig.notes);
    assert_eq!(fig.branches, 1, "one loop");
}

/// Curves that turn round more tightly than an `f64` march resolves: a cone or a cylinder
/// against a plane 1e-8 from tangent and slightly tilted, whose normals come within 1e-7 of
/// each other at the turn (seeds 8 700 238, 8 700 646 and 8 700 765). The marcher stops on both
/// arms there and reports a "singular point"; both arms used to end there unproven or with a
/// singular box, one at a tolerance of 8.6e-8. The two arms are now joined and the chain
/// proves the curve through the turn (which shows it is no singular point): one branch per
/// pair, from boundary to boundary, within the tolerance.
#[test]
fn turns_too_tight_to_march_are_certified_through() {
    let fig = run([8_700_238, 8_700_646, 8_700_765].into_iter());
    assert_clean_sparse(&fig);
    assert_eq!(fig.above_tolerance, 0, "{:?}", fig.notes);
    assert_eq!(fig.above_tolerance_stated, 0, "{:?}", fig.notes);
    assert_eq!(fig.unproven_ends, 0, "{:?}", fig.notes);
    assert_eq!(fig.branches, 3, "one branch per pair");
}

/// A curve that turns round on nearly tangent surfaces with its normals 1e-7 to 1e-6 apart at
/// the turn (seed 8 700 965, a cylinder against a plane 1e-8 from tangent): the marcher goes
/// round it. Without a check, its step out of the turn landed on the other arm, which runs the
/// other way along `N^P × N^Q`, and traced that arm again (thirteen branches, two arcs twice,
/// four uncertified); such a step is refused and halved: one branch, from boundary to boundary,
/// within the tolerance.
#[test]
fn a_march_out_of_a_tight_turn_stays_on_its_arm() {
    let fig = run([8_700_965].into_iter());
    assert_clean(&fig);
    assert_eq!(fig.unproven_ends, 0, "{:?}", fig.notes);
    assert_eq!(fig.branches, 1, "one branch");
}

/// A trace that stops with a Newton failure next to a tight turn (seed 8 702 966, a cone against
/// a plane 1e-8 from tangent; normals 1.4e-7 apart at the turn), beside a branch that goes round
/// the turn from boundary to boundary. Its points there are off the curve by the residual's
/// rounding over that sine (up to 7e-9), and the other branch's tubes there are graphed over a
/// coordinate that moves 450 times slower than the curve's fastest one, so the points were in
/// none of them and the arc was reported twice. It is now dropped as the copy it is: one branch.
#[test]
fn a_trace_stopped_beside_a_tight_turn_is_no_second_copy() {
    let fig = run([8_702_966].into_iter());
    assert_clean_sparse(&fig);
    assert_eq!(fig.branches, 1, "one branch");
}

/// Near-tangent pairs whose search used to end incomplete (20 of the 3 000 soak pairs from
/// 8 700 000 did). Two crossings of a piece's edge 6e-5 apart at a grazing angle (8 700 341,
/// 8 700 830) stayed undecided at the deepest leaves, 1/1024 of the leaf size; leaves are now
/// refined to 1/65536. A cylinder against a plane within 1e-8 of tangent along a ruling and
/// tilted along it (8 700 981, 8 701 069, 8 701 869) cuts a curve that turns round: no model
/// direction is monotone near the turn, and 1 000 to 2 000 pairs along the band between the arms
/// were left undecided at the level cap. The angle round the axis is monotone along the curve
/// (the ruling's component along the plane's normal is the tilt, everywhere): the whole pair is
/// now proven loop-free at once. Every search complete, each curve once.
#[test]
fn near_tangent_searches_that_gave_up_are_complete() {
    let seeds = [8_700_341, 8_700_830, 8_700_981, 8_701_069, 8_701_869];
    let fig = run(seeds.into_iter());
    assert_clean_sparse(&fig);
    assert_eq!(fig.incomplete_searches, 0, "{:?}", fig.notes);
    assert_eq!(fig.unproven_ends, 0, "{:?}", fig.notes);
    assert_eq!(
        fig.branches, 7,
        "two curves on 8 700 341 and 8 700 830, one on the others"
    );
}

/// Near-tangent pairs whose certificate came out above the tolerance with a stated reason
/// (seeds 8 700 191, a torus, and 8 701 854, a cone, each against a plane 1e-8 from tangent,
/// normals 5e-4 and 7e-7 apart there): a short link that halving had not narrowed was kept
/// at 2.0e-9 and 1.2e-9, although a longer link from the same node had been proven narrower
/// over another coordinate (the halving switched the along coordinate between two nearly
/// equal speeds). A link about to be kept wide is now tried over every other monotone
/// coordinate, and a narrower split link from its node is kept instead: both within 1e-9.
#[test]
fn a_link_kept_wide_is_the_narrowest_the_node_had() {
    let fig = run([8_700_191, 8_701_854].into_iter());
    assert_clean(&fig);
    assert_eq!(fig.unproven_ends, 0, "{:?}", fig.notes);
    assert_eq!(fig.branches, 3, "two curves on 8 700 191, one on 8 701 854");
}

/// `assert_clean` but for the tolerance and the count of reference points: on pairs with a
/// tight turn the reference holds few points (its grid misses the thin region between the
/// arms).
fn assert_clean_sparse(fig: &Figures) {
    assert_eq!(fig.soundness_violations, 0, "{:?}", fig.notes);
    assert_eq!(fig.missed_points, 0, "{:?}", fig.notes);
    assert_eq!(fig.twice, 0, "{:?}", fig.notes);
    assert_eq!(fig.inconsistent_ends, 0, "{:?}", fig.notes);
}

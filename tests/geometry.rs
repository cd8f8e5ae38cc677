//! Rational Bézier patches, enclosures and power-basis conversion against closed forms.

use inari::Interval;
use proptest::prelude::*;
use ssitrace::geometry::{
    Domain, ParametricSurface, PatchDerivs, PowerSurface, RationalBezierPatch,
};
use ssitrace::numeric::scalar::{interval, point};
use ssitrace::{Error, InputProblem};

const W45: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Quarter cylinder of radius `r` and height `h`: degree (2, 1), u runs along the quarter circle
/// from (r, 0) to (0, r), v along the axis from z = 0 to z = h.
fn quarter_cylinder(r: f64, h: f64, domain: Domain) -> RationalBezierPatch {
    let circle = [[r, 0.0], [r, r], [0.0, r]];
    let wc = [1.0, W45, 1.0];
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..3 {
        for z in [0.0, h] {
            points.push([circle[i][0], circle[i][1], z]);
            weights.push(wc[i]);
        }
    }
    RationalBezierPatch::from_f64_points([2, 1], &points, Some(&weights), domain).unwrap()
}

/// Part of the unit sphere by inverse stereographic projection:
/// `(2u, 2v, u² + v² − 1) / (1 + u² + v²)`.
fn sphere_power(domain: Domain) -> PowerSurface {
    PowerSurface {
        domain,
        x: vec![(1, 0, 2.0)],
        y: vec![(0, 1, 2.0)],
        z: vec![(2, 0, 1.0), (0, 2, 1.0), (0, 0, -1.0)],
        w: Some(vec![(0, 0, 1.0), (2, 0, 1.0), (0, 2, 1.0)]),
    }
}

/// A non-trivial bicubic-by-quadratic patch with varied positive weights.
fn wavy_patch(domain: Domain) -> RationalBezierPatch {
    let (m, n) = (3, 2);
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for i in 0..=m {
        for j in 0..=n {
            let (x, y) = (i as f64, j as f64);
            points.push([x, y, (x * 1.3 + y * 0.7).sin() + 0.2 * x * y]);
            weights.push(1.0 + 0.4 * ((i + 2 * j) % 3) as f64);
        }
    }
    RationalBezierPatch::from_f64_points([m, n], &points, Some(&weights), domain).unwrap()
}

fn contains(i: Interval, x: f64) -> bool {
    i.inf() <= x && x <= i.sup()
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|c| (a[c] - b[c]).abs() <= tol)
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// Central finite differences of the point map, for comparison with analytic derivatives.
fn finite_differences(s: &RationalBezierPatch, u: f64, v: f64, h: f64) -> PatchDerivs<f64> {
    let p = |du: f64, dv: f64| s.point_f64(u + du, v + dv);
    let comb = |f: &dyn Fn(usize) -> f64| [f(0), f(1), f(2)];
    let (c, pu, mu, pv, mv) = (p(0., 0.), p(h, 0.), p(-h, 0.), p(0., h), p(0., -h));
    let (pp, pm, mp, mm) = (p(h, h), p(h, -h), p(-h, h), p(-h, -h));
    PatchDerivs {
        p: c,
        su: comb(&|k| (pu[k] - mu[k]) / (2.0 * h)),
        sv: comb(&|k| (pv[k] - mv[k]) / (2.0 * h)),
        suu: comb(&|k| (pu[k] - 2.0 * c[k] + mu[k]) / (h * h)),
        suv: comb(&|k| (pp[k] - pm[k] - mp[k] + mm[k]) / (4.0 * h * h)),
        svv: comb(&|k| (pv[k] - 2.0 * c[k] + mv[k]) / (h * h)),
    }
}

fn assert_derivs_match_fd(s: &RationalBezierPatch, u: f64, v: f64) {
    let d = s.derivs_f64(u, v);
    let fd = finite_differences(s, u, v, 1e-4);
    let pairs = [
        ("su", d.su, fd.su),
        ("sv", d.sv, fd.sv),
        ("suu", d.suu, fd.suu),
        ("suv", d.suv, fd.suv),
        ("svv", d.svv, fd.svv),
    ];
    for (name, a, b) in pairs {
        let scale = 1.0 + norm(a);
        assert!(
            close(a, b, 2e-6 * scale),
            "{name} at ({u}, {v}): analytic {a:?}, finite differences {b:?}"
        );
    }
}

#[test]
fn quarter_cylinder_points_lie_on_the_cylinder() {
    let r = 2.5;
    for domain in [Domain::UNIT, Domain::new(1.0, 3.0, -1.0, 2.0)] {
        let s = quarter_cylinder(r, 4.0, domain);
        let mut worst: f64 = 0.0;
        for a in 0..=40 {
            for b in 0..=10 {
                let u = domain.u[0] + (domain.u[1] - domain.u[0]) * a as f64 / 40.0;
                let v = domain.v[0] + (domain.v[1] - domain.v[0]) * b as f64 / 10.0;
                let p = s.point_f64(u, v);
                worst = worst.max(((p[0] * p[0] + p[1] * p[1]).sqrt() - r).abs() / r);
                assert!((0.0..=4.0 + 1e-14).contains(&p[2]));
                // The generic path and the fast path agree.
                let g = s.eval(u, v);
                assert!(close(p, g, 1e-14));
            }
        }
        println!("quarter cylinder on {domain:?}: max relative radius error {worst:e}");
        assert!(worst < 1e-14);
        // Corners: the declared domain is what maps to the ends of the arc and the axis.
        let (u0, u1, v0, v1) = (domain.u[0], domain.u[1], domain.v[0], domain.v[1]);
        assert!(close(s.point_f64(u0, v0), [r, 0.0, 0.0], 1e-14));
        assert!(close(s.point_f64(u1, v0), [0.0, r, 0.0], 1e-14));
        assert!(close(s.point_f64(u1, v1), [0.0, r, 4.0], 1e-14));
        let mid = s.point_f64(0.5 * (u0 + u1), v0);
        assert!(close(mid, [r * W45, r * W45, 0.0], 1e-14));
    }
}

/// Closed form of the rational quadratic arc with weights (1, w, 1) and control points
/// (r,0), (r,r), (0,r): numerators Nx = r((1−t)² + 2wt(1−t)), Ny = r(2wt(1−t) + t²),
/// denominator D = (1−t)² + 2wt(1−t) + t², differentiated by hand.
fn arc_closed_form(r: f64, w: f64, t: f64) -> ([f64; 2], [f64; 2], [f64; 2]) {
    let nx = [
        r * ((1.0 - t).powi(2) + 2.0 * w * t * (1.0 - t)),
        r * (-2.0 * (1.0 - t) + 2.0 * w * (1.0 - 2.0 * t)),
        r * (2.0 - 4.0 * w),
    ];
    let ny = [
        r * (2.0 * w * t * (1.0 - t) + t * t),
        r * (2.0 * w * (1.0 - 2.0 * t) + 2.0 * t),
        r * (2.0 - 4.0 * w),
    ];
    let d = [
        (1.0 - t).powi(2) + 2.0 * w * t * (1.0 - t) + t * t,
        -2.0 * (1.0 - t) + 2.0 * w * (1.0 - 2.0 * t) + 2.0 * t,
        4.0 - 4.0 * w,
    ];
    let q = |n: [f64; 3]| {
        let x = n[0] / d[0];
        let x1 = (n[1] - x * d[1]) / d[0];
        let x2 = (n[2] - 2.0 * x1 * d[1] - x * d[2]) / d[0];
        (x, x1, x2)
    };
    let (x, x1, x2) = q(nx);
    let (y, y1, y2) = q(ny);
    ([x, y], [x1, y1], [x2, y2])
}

#[test]
fn quarter_cylinder_derivatives_match_closed_form_and_finite_differences() {
    let r = 1.5;
    let domain = Domain::new(1.0, 3.0, -1.0, 2.0);
    let (hu, hv) = (2.0, 3.0);
    let s = quarter_cylinder(r, 4.0, domain);
    for a in 0..=8 {
        for b in 0..=4 {
            let u = 1.0 + 2.0 * a as f64 / 8.0;
            let v = -1.0 + 3.0 * b as f64 / 4.0;
            let t = (u - 1.0) / hu;
            let d = s.derivs_f64(u, v);
            let (p, p1, p2) = arc_closed_form(r, W45, t);
            let h = 4.0 * (v + 1.0) / hv;
            assert!(close(d.p, [p[0], p[1], h], 1e-13));
            assert!(close(d.su, [p1[0] / hu, p1[1] / hu, 0.0], 1e-13));
            assert!(close(d.sv, [0.0, 0.0, 4.0 / hv], 1e-13));
            assert!(close(
                d.suu,
                [p2[0] / (hu * hu), p2[1] / (hu * hu), 0.0],
                1e-12
            ));
            assert!(close(d.suv, [0.0; 3], 1e-13));
            assert!(close(d.svv, [0.0; 3], 1e-13));
            // Geometric invariants of a circle of radius r: tangent ⟂ radius, curvature 1/r.
            let radial = [d.p[0], d.p[1], 0.0];
            let dot: f64 = (0..3).map(|k| radial[k] * d.su[k]).sum();
            assert!(dot.abs() < 1e-13);
            let kappa = norm(cross(d.su, d.suu)) / norm(d.su).powi(3);
            assert!((kappa - 1.0 / r).abs() < 1e-12, "curvature {kappa}");
            assert_derivs_match_fd(&s, u, v);
        }
    }
}

#[test]
fn sphere_patch_from_power_form_lies_on_the_unit_sphere() {
    for domain in [Domain::UNIT, Domain::new(-0.5, 1.5, 0.2, 0.9)] {
        let s = sphere_power(domain).to_bezier().unwrap();
        assert_eq!(s.degree(), [2, 2]);
        let mut worst: f64 = 0.0;
        for a in 0..=20 {
            for b in 0..=20 {
                let u = domain.u[0] + (domain.u[1] - domain.u[0]) * a as f64 / 20.0;
                let v = domain.v[0] + (domain.v[1] - domain.v[0]) * b as f64 / 20.0;
                let p = s.point_f64(u, v);
                worst = worst.max((norm(p) - 1.0).abs());
                let expected = sphere_power(domain).eval(u, v);
                assert!(close(p, expected, 1e-14));
                // Rigorous: the exact point has norm 1, so |P|² over the interval point encloses 1.
                let pi = s.eval(point(u), point(v));
                let r2 = pi[0].sqr() + pi[1].sqr() + pi[2].sqr();
                assert!(
                    contains(r2, 1.0),
                    "{u} {v}: |P|² in [{}, {}]",
                    r2.inf(),
                    r2.sup()
                );
            }
        }
        println!("sphere patch on {domain:?}: max | |P| − 1 | = {worst:e}");
        assert!(worst < 1e-14);
        assert_derivs_match_fd(&s, 0.3 * domain.u[0] + 0.7 * domain.u[1], domain.v[0] + 0.1);
        // Normal of a unit sphere is parallel to the position vector.
        let d = s.derivs_f64(domain.u[0] + 0.3, domain.v[0] + 0.4);
        let n = cross(d.su, d.sv);
        let c = cross(n, d.p);
        assert!(norm(c) < 1e-13 * norm(n));
    }
}

#[test]
fn f64_evaluation_lies_inside_interval_evaluation() {
    let patches = [
        quarter_cylinder(2.0, 1.0, Domain::new(-1.0, 1.0, 0.0, 5.0)),
        wavy_patch(Domain::UNIT),
        wavy_patch(Domain::new(0.5, 0.75, 10.0, 20.0)),
        sphere_power(Domain::new(-0.4, 1.0, -0.4, 1.0))
            .to_bezier()
            .unwrap(),
    ];
    for s in &patches {
        let d = s.domain();
        for a in 0..=13 {
            for b in 0..=11 {
                let u = d.u[0] + (d.u[1] - d.u[0]) * a as f64 / 13.0;
                let v = d.v[0] + (d.v[1] - d.v[0]) * b as f64 / 11.0;
                let f = s.derivs_f64(u, v);
                let i = s.enclose_derivs(point(u), point(v));
                for (fv, iv) in [
                    (f.p, i.p),
                    (f.su, i.su),
                    (f.sv, i.sv),
                    (f.suu, i.suu),
                    (f.suv, i.suv),
                    (f.svv, i.svv),
                ] {
                    for c in 0..3 {
                        assert!(contains(iv[c], fv[c]), "{fv:?} not in {iv:?}");
                        assert!(iv[c].wid() < 1e-9 * (1.0 + fv[c].abs()));
                    }
                }
            }
        }
    }
}

#[test]
fn subpatch_reproduces_the_patch_on_its_box() {
    let s = wavy_patch(Domain::new(-2.0, 2.0, 1.0, 3.0));
    let (u, v) = (interval(-0.5, 1.25).unwrap(), interval(1.5, 1.75).unwrap());
    let sub = s.subpatch(u, v).unwrap();
    assert_eq!(sub.domain(), Domain::new(-0.5, 1.25, 1.5, 1.75));
    for a in 0..=10 {
        for b in 0..=10 {
            let (x, y) = (-0.5 + 1.75 * a as f64 / 10.0, 1.5 + 0.25 * b as f64 / 10.0);
            assert!(close(sub.point_f64(x, y), s.point_f64(x, y), 1e-12));
        }
    }
    // A range of zero width is not a patch domain.
    assert!(s.subpatch(point(0.0), v).is_err());
}

/// Largest component width of a box.
fn width(b: &[Interval; 3]) -> f64 {
    b.iter().map(|x| x.wid()).fold(0.0, f64::max)
}

#[test]
fn convex_hull_versus_naive_interval_widths() {
    let patches = [
        ("quarter cylinder", quarter_cylinder(1.0, 1.0, Domain::UNIT)),
        ("wavy (3,2)", wavy_patch(Domain::UNIT)),
        (
            "sphere (2,2)",
            sphere_power(Domain::UNIT).to_bezier().unwrap(),
        ),
    ];
    println!(
        "{:<18} {:>8} {:>12} {:>12} {:>8}",
        "patch", "box", "hull", "naive", "ratio"
    );
    for (name, s) in &patches {
        for size in [1.0, 0.5, 0.1, 0.01, 0.001] {
            let (mut hull_w, mut naive_w, mut enc_w) = (0.0, 0.0, 0.0);
            for k in 0..5 {
                let lo = (1.0 - size) * k as f64 / 4.0;
                let (u, v) = (
                    interval(lo, lo + size).unwrap(),
                    interval(lo, lo + size).unwrap(),
                );
                let hull = s.hull_bound(u, v).unwrap();
                let naive = s.naive_bound(u, v);
                let enc = s.enclose(u, v);
                for c in 0..3 {
                    assert!(enc[c].subset(hull[c]) && enc[c].subset(naive[c]));
                }
                hull_w += width(&hull);
                naive_w += width(&naive);
                enc_w += width(&enc);
            }
            println!(
                "{name:<18} {size:>8} {:>12.3e} {:>12.3e} {:>8.3}",
                hull_w / 5.0,
                naive_w / 5.0,
                hull_w / naive_w
            );
            assert!(enc_w <= hull_w.min(naive_w) + 1e-15);
            if size <= 0.1 {
                // Subdivision converges quadratically, naive evaluation only linearly with a
                // large constant: the hull must win on small boxes.
                assert!(hull_w < naive_w, "{name} at {size}");
            }
        }
    }
}

#[test]
fn bounding_box_contains_samples_and_control_points() {
    let s = wavy_patch(Domain::new(3.0, 4.0, 0.0, 2.0));
    let b = s.bounding_box();
    for a in 0..=30 {
        for c in 0..=30 {
            let p = s.point_f64(3.0 + a as f64 / 30.0, 2.0 * c as f64 / 30.0);
            assert!((0..3).all(|k| contains(b[k], p[k])));
        }
    }
    // The corner control points are on the surface, so the box reaches them.
    let net = s.cartesian();
    for k in 0..3 {
        assert!(contains(b[k], net[0][k].mid()));
    }
    let whole = s.enclose(interval(3.0, 4.0).unwrap(), interval(0.0, 2.0).unwrap());
    for k in 0..3 {
        assert!(whole[k].subset(b[k]));
    }
}

#[test]
fn interval_control_points_are_enclosed() {
    // A bilinear patch whose corner z is uncertain in [−0.1, 0.1]: every member lies in the bound.
    let z = interval(-0.1, 0.1).unwrap();
    let pts = vec![
        [point(0.0), point(0.0), z],
        [point(0.0), point(1.0), point(0.0)],
        [point(1.0), point(0.0), point(0.0)],
        [point(1.0), point(1.0), point(1.0)],
    ];
    let s = RationalBezierPatch::new([1, 1], pts, None, Domain::UNIT).unwrap();
    for corner in [-0.1, 0.0, 0.1] {
        let member = RationalBezierPatch::from_f64_points(
            [1, 1],
            &[
                [0.0, 0.0, corner],
                [0.0, 1.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 1.0],
            ],
            None,
            Domain::UNIT,
        )
        .unwrap();
        for a in 0..=10 {
            let (u, v) = (a as f64 / 10.0, 0.3);
            let b = s.enclose(
                interval(u - 0.05, u + 0.05)
                    .unwrap()
                    .intersection(interval(0.0, 1.0).unwrap()),
                point(v),
            );
            // The member's exact point (enclosed by a point evaluation) lies in the bound; an f64
            // evaluation may be an ulp off, so compare rigorous sets.
            let p = member.eval(point(u), point(v));
            assert!(
                (0..3).all(|k| !p[k].intersection(b[k]).is_empty()),
                "{corner} {u}: {p:?} {b:?}"
            );
            // And the bound is not vacuous: its z width stays below the data uncertainty + slope.
            assert!(b[2].wid() < 0.3);
        }
    }
}

fn random_patch() -> impl Strategy<Value = RationalBezierPatch> {
    (
        1usize..5,
        1usize..5,
        -5.0f64..5.0,
        0.01f64..10.0,
        -5.0f64..5.0,
        0.01f64..10.0,
    )
        .prop_flat_map(|(m, n, u0, du, v0, dv)| {
            let count = (m + 1) * (n + 1);
            (
                prop::collection::vec(prop::array::uniform3(-10.0f64..10.0), count),
                prop::collection::vec(0.1f64..5.0, count),
            )
                .prop_map(move |(pts, ws)| {
                    RationalBezierPatch::from_f64_points(
                        [m, n],
                        &pts,
                        Some(&ws),
                        Domain::new(u0, u0 + du, v0, v0 + dv),
                    )
                    .unwrap()
                })
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn enclosure_contains_sampled_points(
        s in random_patch(),
        a in 0.0f64..1.0, b in 0.0f64..1.0, wa in 0.0f64..1.0, wb in 0.0f64..1.0,
    ) {
        let d = s.domain();
        let (hu, hv) = (d.u[1] - d.u[0], d.v[1] - d.v[0]);
        let u0 = d.u[0] + a * hu;
        let u1 = (u0 + wa * wa * hu).min(d.u[1]);
        let v0 = d.v[0] + b * hv;
        let v1 = (v0 + wb * wb * hv).min(d.v[1]);
        let (ui, vi) = (interval(u0, u1).unwrap(), interval(v0, v1).unwrap());
        let enc = s.enclose(ui, vi);
        let hull = s.hull_bound(ui, vi).unwrap();
        for p in 0..=12 {
            for q in 0..=12 {
                // Clamped: `v0 + (v1 − v0)·1` can round past `v1`, outside the box.
                let u = (u0 + (u1 - u0) * p as f64 / 12.0).min(u1);
                let v = (v0 + (v1 - v0) * q as f64 / 12.0).min(v1);
                // The exact point is in both rigorous sets, so they must overlap.
                let exact = s.eval(point(u), point(v));
                for k in 0..3 {
                    prop_assert!(!exact[k].intersection(enc[k]).is_empty(),
                        "({u}, {v}) component {k}: [{}, {}] vs enclosure [{}, {}]",
                        exact[k].inf(), exact[k].sup(), enc[k].inf(), enc[k].sup());
                    prop_assert!(!exact[k].intersection(hull[k]).is_empty());
                }
            }
        }
    }

    #[test]
    fn derivative_enclosure_contains_sampled_derivatives(
        s in random_patch(), a in 0.0f64..0.9, b in 0.0f64..0.9,
    ) {
        let d = s.domain();
        let (hu, hv) = (d.u[1] - d.u[0], d.v[1] - d.v[0]);
        let (u0, v0) = (d.u[0] + a * hu, d.v[0] + b * hv);
        let (u1, v1) = (u0 + 0.1 * hu, v0 + 0.1 * hv);
        let enc = s.enclose_derivs(interval(u0, u1).unwrap(), interval(v0, v1).unwrap());
        for p in 0..=4 {
            for q in 0..=4 {
                // Clamped: `v0 + (v1 − v0)·1` can round past `v1`, outside the box.
                let u = (u0 + (u1 - u0) * p as f64 / 4.0).min(u1);
                let v = (v0 + (v1 - v0) * q as f64 / 4.0).min(v1);
                let e = s.enclose_derivs(point(u), point(v));
                for (x, y) in [(e.p, enc.p), (e.su, enc.su), (e.sv, enc.sv),
                               (e.suu, enc.suu), (e.suv, enc.suv), (e.svv, enc.svv)] {
                    for k in 0..3 {
                        prop_assert!(!x[k].intersection(y[k]).is_empty());
                    }
                }
            }
        }
    }
}

/// Random power-basis polynomial: up to 6 terms with exponents up to 6.
fn terms() -> impl Strategy<Value = Vec<(u32, u32, f64)>> {
    prop::collection::vec((0u32..=6, 0u32..=6, -10.0f64..10.0), 1..7)
}

fn check_conversion(surface: &PowerSurface) -> std::result::Result<(), TestCaseError> {
    let s = surface
        .to_bezier()
        .map_err(|e| TestCaseError::fail(format!("{e}")))?;
    let d = surface.domain;
    let grid = |a: usize, b: usize| {
        (
            d.u[0] + (d.u[1] - d.u[0]) * a as f64 / 6.0,
            d.v[0] + (d.v[1] - d.v[0]) * b as f64 / 6.0,
        )
    };
    // Errors are measured relative to the size of each component over the domain: the largest
    // sum of absolute term values (divided by w) on the sample grid.
    let term_sum = |terms: &[(u32, u32, f64)], u: f64, v: f64| {
        terms
            .iter()
            .map(|&(i, j, c)| (c * u.powi(i as i32) * v.powi(j as i32)).abs())
            .sum::<f64>()
    };
    let mut scale = [0.0f64; 3];
    for a in 0..=6 {
        for b in 0..=6 {
            let (u, v) = grid(a, b);
            let w = surface
                .w
                .as_ref()
                .map(|w| surface_w(w, u, v))
                .unwrap_or(1.0);
            for (k, t) in [&surface.x, &surface.y, &surface.z].into_iter().enumerate() {
                scale[k] = scale[k].max(term_sum(t, u, v) / w.abs());
            }
        }
    }
    for a in 0..=6 {
        for b in 0..=6 {
            let (u, v) = grid(a, b);
            let bez = s.point_f64(u, v);
            let pow = surface.eval(u, v);
            for k in 0..3 {
                let tol = 1e-12 * (1.0 + scale[k]);
                prop_assert!(
                    (bez[k] - pow[k]).abs() <= tol,
                    "component {k} at ({u}, {v}): bezier {} power {}",
                    bez[k],
                    pow[k]
                );
            }
            // Both interval evaluations enclose the exact value, so they overlap.
            let bi = s.eval(point(u), point(v));
            let pi = surface.eval(point(u), point(v));
            for k in 0..3 {
                // The interval conversion is tight, not vacuous.
                prop_assert!(
                    bi[k].wid() <= 1e-11 * (1.0 + scale[k]),
                    "width {} scale {}",
                    bi[k].wid(),
                    scale[k]
                );
                prop_assert!(
                    !bi[k].intersection(pi[k]).is_empty(),
                    "component {k}: bezier [{}, {}], power [{}, {}]",
                    bi[k].inf(),
                    bi[k].sup(),
                    pi[k].inf(),
                    pi[k].sup()
                );
            }
        }
    }
    Ok(())
}

fn surface_w(w: &[(u32, u32, f64)], u: f64, v: f64) -> f64 {
    w.iter()
        .map(|&(i, j, c)| c * u.powi(i as i32) * v.powi(j as i32))
        .sum()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn power_to_bezier_matches_polynomials(
        x in terms(), y in terms(), z in terms(),
        u0 in -3.0f64..3.0, du in 0.1f64..3.0, v0 in -3.0f64..3.0, dv in 0.1f64..3.0,
    ) {
        // Make the surface non-constant whatever the random terms are.
        let mut x = x;
        x.push((1, 0, 1.0));
        let surface = PowerSurface { domain: Domain::new(u0, u0 + du, v0, v0 + dv), x, y, z, w: None };
        check_conversion(&surface)?;
    }

    #[test]
    fn rational_power_to_bezier_matches(
        x in terms(), y in terms(), z in terms(),
        w in prop::collection::vec((0u32..=6, 0u32..=6, 0.01f64..5.0), 0..5),
        u0 in 0.0f64..2.0, du in 0.1f64..2.0, v0 in 0.0f64..2.0, dv in 0.1f64..2.0,
    ) {
        // A denominator with positive coefficients on a domain in the positive quadrant has
        // positive Bernstein coefficients, so the conversion must accept it.
        let mut w = w;
        w.push((0, 0, 0.5));
        let mut y = y;
        y.push((0, 1, 1.0));
        let surface = PowerSurface {
            domain: Domain::new(u0, u0 + du, v0, v0 + dv), x, y, z, w: Some(w),
        };
        check_conversion(&surface)?;
    }
}

#[test]
fn power_degree_is_the_largest_exponent() {
    let s = PowerSurface {
        domain: Domain::UNIT,
        x: vec![(3, 0, 1.0)],
        y: vec![(0, 1, 1.0)],
        z: vec![],
        w: None,
    };
    assert_eq!(s.to_bezier().unwrap().degree(), [3, 1]);
    // x = u, y = v, z = 0 is the bilinear unit square with control points at the corners
    // (in the declared domain [2,4]×[1,2], x = u runs from 2 to 4).
    let plane = PowerSurface {
        domain: Domain::new(2.0, 4.0, 1.0, 2.0),
        x: vec![(1, 0, 1.0)],
        y: vec![(0, 1, 1.0)],
        z: vec![],
        w: None,
    };
    let b = plane.to_bezier().unwrap();
    assert_eq!(b.degree(), [1, 1]);
    let net = b.cartesian();
    let expected = [[2.0, 1.0], [2.0, 2.0], [4.0, 1.0], [4.0, 2.0]];
    for (h, e) in net.iter().zip(expected) {
        assert!(contains(h[0], e[0]) && contains(h[1], e[1]) && h[0].wid() < 1e-14);
    }
}

fn input_error(e: Error) -> (String, InputProblem) {
    match e {
        Error::InvalidInput {
            surface: None,
            field,
            problem,
        } => (field, problem),
        other => panic!("expected an input error, got {other:?}"),
    }
}

#[test]
fn power_conversion_rejects_bad_input() {
    let base = || sphere_power(Domain::UNIT);
    // w = u − 0.5 changes sign on [0, 1].
    let mut s = base();
    s.w = Some(vec![(1, 0, 1.0), (0, 0, -0.5)]);
    let (f, p) = input_error(s.to_bezier().unwrap_err());
    assert_eq!((f.as_str(), p), ("w", InputProblem::NonPositiveWeight));
    // 1 + u² is positive on [−1, 1] but its degree-2 Bernstein coefficients (2, 0, 2) are not
    // provably so; in degree 3 they are (2, 2/3, 2/3, 2) > 0, so the conversion elevates to it.
    let mut s = base();
    s.domain = Domain::new(-1.0, 1.0, 0.0, 1.0);
    s.w = Some(vec![(0, 0, 1.0), (2, 0, 1.0)]);
    let elevated = s.to_bezier().unwrap();
    assert_eq!(elevated.degree()[0], 3);
    assert!(elevated.homogeneous().iter().all(|h| h[3].inf() > 0.0));
    let mut s = base();
    s.y[0].2 = f64::NAN;
    assert_eq!(
        input_error(s.to_bezier().unwrap_err()),
        ("y[0][2]".into(), InputProblem::NonFinite)
    );
    let mut s = base();
    s.domain = Domain::new(0.0, 1.0, 2.0, 2.0);
    assert_eq!(
        input_error(s.to_bezier().unwrap_err()),
        (
            "domain[1]".into(),
            InputProblem::EmptyDomain { lo: 2.0, hi: 2.0 }
        )
    );
    let mut s = base();
    s.x.push((1000, 0, 1.0));
    assert_eq!(input_error(s.to_bezier().unwrap_err()).0, "x[1][0]");
    let constant = PowerSurface {
        domain: Domain::UNIT,
        x: vec![(0, 0, 1.0)],
        y: vec![],
        z: vec![],
        w: None,
    };
    assert_eq!(
        input_error(constant.to_bezier().unwrap_err()).1,
        InputProblem::Degenerate
    );
}

#[test]
fn patch_constructor_rejects_bad_input() {
    let pts = [
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 1.0],
    ];
    let make = |deg, pts: &[[f64; 3]], w: Option<&[f64]>, d| {
        input_error(RationalBezierPatch::from_f64_points(deg, pts, w, d).unwrap_err())
    };
    assert_eq!(
        make([0, 1], &pts, None, Domain::UNIT),
        ("degree[0]".into(), InputProblem::BadDegree(0))
    );
    assert_eq!(
        make([1, 2], &pts, None, Domain::UNIT),
        (
            "points".into(),
            InputProblem::WrongCount {
                expected: 6,
                found: 4
            }
        )
    );
    let mut bad = pts;
    bad[3][1] = f64::INFINITY;
    assert_eq!(
        make([1, 1], &bad, None, Domain::UNIT),
        ("points[3][1]".into(), InputProblem::NonFinite)
    );
    assert_eq!(
        make([1, 1], &pts, Some(&[1.0, 1.0, 0.0, 1.0]), Domain::UNIT),
        ("weights[2]".into(), InputProblem::NonPositiveWeight)
    );
    assert_eq!(
        make([1, 1], &pts, Some(&[1.0, 1.0]), Domain::UNIT),
        (
            "weights".into(),
            InputProblem::WrongCount {
                expected: 4,
                found: 2
            }
        )
    );
    assert_eq!(
        make([1, 1], &pts, None, Domain::new(1.0, 0.0, 0.0, 1.0)),
        (
            "domain[0]".into(),
            InputProblem::EmptyDomain { lo: 1.0, hi: 0.0 }
        )
    );
    assert_eq!(
        make([1, 1], &pts, None, Domain::new(0.0, 1.0, 0.0, f64::NAN)),
        ("domain[1]".into(), InputProblem::NonFinite)
    );
    assert_eq!(
        make([1, 1], &[[2.0, 3.0, 4.0]; 4], None, Domain::UNIT),
        ("points".into(), InputProblem::Degenerate)
    );
    // An interval weight reaching zero is not positive.
    let p: Vec<[Interval; 3]> = pts
        .iter()
        .map(|q| [point(q[0]), point(q[1]), point(q[2])])
        .collect();
    let w = vec![
        point(1.0),
        interval(0.0, 1.0).unwrap(),
        point(1.0),
        point(1.0),
    ];
    assert_eq!(
        input_error(
            RationalBezierPatch::new([1, 1], p.clone(), Some(w), Domain::UNIT).unwrap_err()
        ),
        ("weights[1]".into(), InputProblem::NonPositiveWeight)
    );
    let mut h: Vec<[Interval; 4]> = p.iter().map(|q| [q[0], q[1], q[2], point(1.0)]).collect();
    h[0][3] = point(-1.0);
    assert_eq!(
        input_error(RationalBezierPatch::from_homogeneous([1, 1], h, Domain::UNIT).unwrap_err()),
        ("weights[0]".into(), InputProblem::NonPositiveWeight)
    );
}

#[test]
fn parametric_surface_impl_uses_declared_parameters() {
    let domain = Domain::new(1.0, 3.0, -1.0, 2.0);
    let s = quarter_cylinder(1.0, 3.0, domain);
    assert_eq!(ParametricSurface::domain(&s), domain);
    let d = s.derivs(2.0, 0.5);
    let g = s.derivs_f64(2.0, 0.5);
    assert_eq!([d.p.x, d.p.y, d.p.z], g.p);
    assert_eq!([d.suu.x, d.suu.y, d.suu.z], g.suu);
    // v = 0.5 is 1.5 of the 3 units from v0 = −1: halfway up a cylinder of height 3.
    assert!((d.p.z - 1.5).abs() < 1e-15);
    assert!((d.sv.z - 1.0).abs() < 1e-15);
    let n = d.normal();
    assert!((n.norm() - d.su.norm() * d.sv.norm()).abs() < 1e-12);
}

#[test]
fn enclosures_extend_rigorously_beyond_the_domain() {
    // The quarter-circle weights (1, 1/√2, 1) keep the denominator positive for every t, so the
    // extrapolated net stays valid; samples of the polynomial extension must be enclosed.
    let s = quarter_cylinder(1.0, 1.0, Domain::UNIT);
    let (u, v) = (interval(0.8, 1.3).unwrap(), interval(-0.2, 0.1).unwrap());
    let enc = s.enclose(u, v);
    assert!(s.hull_bound(u, v).is_some());
    for a in 0..=10 {
        for b in 0..=10 {
            let (x, y) = (0.8 + 0.05 * a as f64, -0.2 + 0.03 * b as f64);
            let p = s.eval(point(x), point(y));
            // Still on the cylinder: the rational arc continues around the circle.
            let q = s.point_f64(x, y);
            assert!((q[0].hypot(q[1]) - 1.0).abs() < 1e-14);
            assert!((0..3).all(|k| !p[k].intersection(enc[k]).is_empty()));
        }
    }
    // The sub-patch over the extrapolated box evaluates like the patch.
    let sub = s.subpatch(u, v).unwrap();
    assert!(close(sub.point_f64(1.2, 0.0), s.point_f64(1.2, 0.0), 1e-13));
}

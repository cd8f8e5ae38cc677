use super::*;
use crate::geometry::{Domain, PowerSurface};
use crate::numeric::scalar::interval;
use crate::validated::SeriesN;

fn sextic() -> RationalBezierPatch {
    // Fig. 7's height field (degree 6), over a domain that is not the unit square.
    let d = Domain::new(-1.0, 1.0, -0.5, 2.0);
    PowerSurface::graph(
        d,
        vec![
            (0, 0, 0.21),
            (2, 0, -3.21),
            (0, 2, -1.07),
            (4, 0, 16.2),
            (2, 2, 10.8),
            (0, 4, 1.8),
            (6, 0, -27.0),
            (4, 2, -27.0),
            (2, 4, -9.0),
            (0, 6, -1.0),
        ],
    )
    .to_bezier()
    .unwrap()
}

/// The lean form of `p` against the patch's own at points, over boxes and along series,
/// at 20 points across the domain (centres a little off them).
fn check_lean_form(p: &RationalBezierPatch) {
    let lean = LeanPatch::new(p);
    let d = p.domain();
    let (wu, wv) = (d.u[1] - d.u[0], d.v[1] - d.v[0]);
    for k in 0..20 {
        let f = 0.05 + 0.045 * k as f64;
        let (u, v) = (d.u[0] + f * wu, d.v[1] - f * wv);
        let c = lean.centred(u + 0.005 * wu, v - 0.01 * wv);
        let want = p.first_derivs(u, v);
        let [gu, gv] = c.partials(point(u), point(v));
        let got = [c.eval(point(u), point(v)), gu, gv];
        for (a, b) in want.iter().zip(&got) {
            for x in 0..3 {
                assert!(
                    b[x].inf() - 1e-11 <= a[x] && a[x] <= b[x].sup() + 1e-11,
                    "{a:?} vs {b:?}"
                );
                assert!(b[x].wid() < 1e-11, "{b:?}");
            }
        }
        // Over a box: encloses sampled values; along a series: its constant term is the
        // value at the series' constant term.
        let (bu, bv) = (
            interval(u, u + 0.01 * wu).unwrap(),
            interval(v, v + 0.012 * wv).unwrap(),
        );
        let e = c.eval(bu, bv);
        let [eu, ev] = c.partials(bu, bv);
        for a in 0..=4 {
            for b in 0..=4 {
                let (su, sv) = (u + 0.0025 * wu * a as f64, v + 0.003 * wv * b as f64);
                let y = p.first_derivs(su, sv);
                for (want, got) in y.iter().zip([e, eu, ev]) {
                    for x in 0..3 {
                        assert!(got[x].inf() - 1e-12 <= want[x] && want[x] <= got[x].sup() + 1e-12);
                    }
                }
            }
        }
        let want2 = p.eval_derivs(u, v);
        let got2 = c.second_partials(point(u), point(v));
        for (a, b) in [want2.suu, want2.suv, want2.svv].iter().zip(&got2) {
            for x in 0..3 {
                assert!(
                    b[x].inf() - 1e-9 <= a[x] && a[x] <= b[x].sup() + 1e-9,
                    "{a:?} vs {b:?}"
                );
                assert!(b[x].wid() < 1e-9, "{b:?}");
            }
        }
        let box2 = c.second_partials(bu, bv);
        for a in 0..=4 {
            for b in 0..=4 {
                let (su, sv) = (u + 0.0025 * wu * a as f64, v + 0.003 * wv * b as f64);
                let dd = p.eval_derivs(su, sv);
                for (k, y) in [dd.suu, dd.suv, dd.svv].iter().enumerate() {
                    for x in 0..3 {
                        assert!(box2[k][x].inf() - 1e-9 <= y[x] && y[x] <= box2[k][x].sup() + 1e-9);
                    }
                }
            }
        }
        // Series of one length (the truncation order; a product keeps the longer operand's
        // length), one of them affine.
        type S = SeriesN<6>;
        let (long_u, long_v) = (
            S::new(&[point(u), point(0.3 * wu), point(-0.1 * wu)]),
            S::new(&[point(v), point(-0.2 * wv), point(0.05 * wv)]),
        );
        let (short_u, short_v) = (
            S::new(&[point(u), point(0.3 * wu), point(0.0)]),
            S::new(&[point(v), point(-0.2 * wv), point(0.0)]),
        );
        for (su, sv) in [(long_u, short_v), (short_u, long_v)] {
            let lean_series = c.eval(su, sv);
            let patch_series = p.eval(su, sv);
            let [lu, lv] = c.partials(su, sv);
            let lean_d = [lean_series, lu, lv];
            let patch_d = p.first_derivs(su, sv);
            for x in 0..3 {
                for i in 0..6 {
                    let mut pairs = vec![(lean_series[x].coeff(i), patch_series[x].coeff(i))];
                    pairs.extend((0..3).map(|d| (lean_d[d][x].coeff(i), patch_d[d][x].coeff(i))));
                    for (z, (a, b)) in pairs.into_iter().enumerate() {
                        assert!(
                            (a.mid() - b.mid()).abs() < 1e-9 * (1.0 + b.mag()),
                            "{x} {i} {z}: {a:?} vs {b:?}"
                        );
                    }
                }
            }
        }
    }
}

/// A form truncated to a window encloses the patch's point and first and second partials
/// (sampled, and over sub-boxes) everywhere inside the window, whatever the window's size
/// and its distance from the centre; it covers exactly the boxes inside its window; and on
/// a height field it drops the rounding-only terms of `x = u` and `y = v`.
#[test]
fn truncated_forms_enclose_the_patch_inside_their_window() {
    let p = sextic();
    let lean = LeanPatch::new(&p);
    let d = p.domain();
    let (wu, wv) = (d.u[1] - d.u[0], d.v[1] - d.v[0]);
    for (k, half) in [1e-6, 1e-4, 3e-3, 0.02, 0.07, 0.3].into_iter().enumerate() {
        // A window off the centre (as when a form is reused for a later link).
        let (cu, cv) = (d.u[0] + 0.37 * wu, d.v[0] + 0.61 * wv);
        let (lo_u, lo_v) = (cu + 0.2 * half * wu, cv - 0.9 * half * wv);
        let window = [
            interval(lo_u, lo_u + half * wu).unwrap(),
            interval(lo_v, lo_v + half * wv).unwrap(),
        ];
        let c = lean.centred_within(cu, cv, Some(window));
        assert!(c.covers(window[0], window[1]), "{k}");
        let outside = interval(cu + 2.1 * wu, cu + 2.2 * wu).unwrap();
        assert!(!c.covers(outside, window[1]), "{k}");
        if k == 3 {
            // x = u and y = v: the constant and the linear term only.
            let (t, tr) = c.taylor.as_ref().unwrap();
            assert_eq!(t.coeffs.len(), 3);
            for x in 0..2 {
                let kept = tr.forms[x][0].c.iter();
                let kept = kept.filter(|v| !(v.inf() == 0.0 && v.sup() == 0.0)).count();
                assert!(kept <= 2, "coordinate {x}: {kept} terms kept");
            }
        }
        for a in 0..=6 {
            for b in 0..=6 {
                let u = window[0].inf() + window[0].wid() * a as f64 / 6.0;
                let v = window[1].inf() + window[1].wid() * b as f64 / 6.0;
                let (iu, iv) = (
                    interval(u, (u + 1e-3 * half * wu).min(window[0].sup())).unwrap(),
                    interval(v, (v + 1e-3 * half * wv).min(window[1].sup())).unwrap(),
                );
                // Every dropped term's derivative, summed, lies in the form's bound.
                let (t, tr) = c.taylor.as_ref().unwrap();
                let (ds, dr) = t.offsets(point(u), point(v));
                for (x, forms) in tr.forms.iter().enumerate() {
                    for (&(oa, ob), form) in ORDERS.iter().zip(forms) {
                        let Some(rest) = form.rest else { continue };
                        let mut dropped = point(0.0);
                        for i in 0..=form.km {
                            for j in 0..=form.ln {
                                let full = t.coeffs[x][(i + oa) * (t.n + 1) + j + ob];
                                if form.c[i * (form.ln + 1) + j] != point(0.0) || full == point(0.0)
                                {
                                    continue;
                                }
                                let f = (i + 1..=i + oa).product::<usize>()
                                    * (j + 1..=j + ob).product::<usize>();
                                let mut term = full * point(f as f64);
                                term *= t.inv[0].powi(oa as i32) * t.inv[1].powi(ob as i32);
                                dropped += term * ds.powi(i as i32) * dr.powi(j as i32);
                            }
                        }
                        assert!(
                            dropped.subset(rest),
                            "{k} {x} {oa}{ob}: {dropped:?} {rest:?}"
                        );
                    }
                }
                let want = p.eval_derivs(u, v);
                let [su, sv] = c.partials(iu, iv);
                let got = [c.eval(iu, iv), su, sv];
                let second = c.second_partials(iu, iv);
                let pairs = [want.p, want.su, want.sv, want.suu, want.suv, want.svv]
                    .into_iter()
                    .zip(got.into_iter().chain(second));
                for (w, g) in pairs {
                    for x in 0..3 {
                        // The reference is the patch's own f64 evaluation: a few ulps.
                        let slack = 1e-12 * (1.0 + w[x].abs());
                        assert!(
                            g[x].inf() - slack <= w[x] && w[x] <= g[x].sup() + slack,
                            "{k} {a} {b}: {w:?} vs {g:?}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn lean_form_equals_and_encloses_the_patch() {
    check_lean_form(&sextic());
    check_lean_form(&crate::pair::fixtures::wavy_patch(false));
}

#[test]
fn rational_lean_form_equals_and_encloses_the_patch() {
    let p = crate::pair::fixtures::wavy_patch(true);
    assert!(PowerNet::of(&p).is_none());
    check_lean_form(&p);
    check_lean_form(&crate::pair::fixtures::quarter_cylinder());
    // On the cylinder x² + y² = 1 the lean point encloses the closed form's points.
    let cyl = crate::pair::fixtures::quarter_cylinder();
    let lean = LeanPatch::new(&cyl);
    let c = lean.centred(0.4, 0.5);
    for k in 0..=10 {
        let u = 0.1 * k as f64;
        let e = c.eval(interval(u, u + 1e-9).unwrap(), interval(0.2, 0.3).unwrap());
        let r = (e[0].sqr() + e[1].sqr()).sqrt();
        assert!(r.contains(1.0) && r.wid() < 1e-8, "{r:?}");
    }
}

/// Moved so that its pole is the origin, a sphere piece's form encloses the piece's points less
/// the pole, and next to the pole its second partial in the angle over a box is far tighter
/// than the form's as given (there its terms are each near the pole's height and as wide as
/// the box's range in the angle; moved, they are as small as the distance to the pole).
#[test]
fn a_moved_form_encloses_the_moved_patch_and_is_tight_at_a_pole() {
    let pieces = crate::geometry::pole::tests::nurbs_sphere()
        .to_bezier()
        .unwrap();
    for p in &pieces {
        let (side, x) = (2..4)
            .find_map(|s| p.collapsed_sides()[s].map(|x| (s, x)))
            .unwrap();
        let d = p.domain();
        let pole_v = if side == 2 { d.v[0] } else { d.v[1] };
        let inward = if side == 2 { 1.0 } else { -1.0 };
        let (given, moved) = (LeanPatch::new(p), LeanPatch::moved(p, x).unwrap());
        assert_eq!(moved.shift(), x);
        for gap in [1e-3, 1e-6, 1e-9] {
            let (u, v) = (d.u[0] + 0.37 * (d.u[1] - d.u[0]), pole_v + inward * gap);
            let (fg, fm) = (given.centred(u, v), moved.centred(u, v));
            // Points: the moved form at a point is the patch's point less the pole.
            let at = p.point_f64(u, v);
            let e = fm.eval(point(u), point(v));
            for c in 0..3 {
                let want = at[c] - x[c];
                let off = (e[c].inf() - want).max(want - e[c].sup()).max(0.0);
                assert!(off <= 1e-15, "gap {gap}: {e:?} against {want}");
            }
            // The second partial in the angle over a box 1e-5 wide in it: the same values
            // (the two enclosures meet), far tighter moved.
            let bu = interval(u - 5e-6, u + 5e-6).unwrap();
            let (hg, hm) = (
                fg.second_partials(bu, point(v))[0],
                fm.second_partials(bu, point(v))[0],
            );
            assert!(
                hg.iter().zip(&hm).all(|(a, b)| !a.disjoint(*b)),
                "{hg:?} {hm:?}"
            );
            let width = |h: [Interval; 3]| h.iter().map(|x| x.wid()).fold(0.0, f64::max);
            let (wg, wm) = (width(hg), width(hm));
            assert!(wm < 1e-2 * wg, "gap {gap}: {wm:e} moved against {wg:e}");
        }
    }
}

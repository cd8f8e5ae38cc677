use super::*;
use crate::geometry::nurbs::NurbsSurface;
use crate::geometry::RationalBezierPatch;

/// The unit sphere as the standard degree 2×2 NURBS (9×5 net, u round the z axis, v from the
/// south pole to the north pole).
pub(crate) fn nurbs_sphere() -> NurbsSurface {
    let h = Interval::try_from((
        std::f64::consts::FRAC_1_SQRT_2,
        std::f64::consts::FRAC_1_SQRT_2.next_up(),
    ))
    .unwrap();
    let one = point(1.0);
    let meridian = [(0.0, -1.0), (1.0, -1.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let (mut pts, mut ws) = (Vec::new(), Vec::new());
    // The unit circle's net: the square's corners and edge midpoints, round from (1, 0).
    let c = [1.0, 1.0, 0.0, -1.0, -1.0, -1.0, 0.0, 1.0, 1.0];
    for i in 0..9 {
        let (cx, cy) = (c[i], c[(i + 6) % 8]);
        for (j, &(r, z)) in meridian.iter().enumerate() {
            pts.push([point(cx * r), point(cy * r), point(z)]);
            let wi = if i % 2 == 1 { h } else { one };
            let wj = if j % 2 == 1 { h } else { one };
            ws.push(wi * wj);
        }
    }
    let ku = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
    NurbsSurface::new([2, 2], [ku, kv], pts, Some(ws)).unwrap()
}

fn pieces() -> Vec<RationalBezierPatch> {
    nurbs_sphere().to_bezier().unwrap()
}

#[test]
fn the_sphere_pieces_know_their_poles() {
    for (k, p) in pieces().iter().enumerate() {
        let c = p.collapsed_sides();
        assert_eq!(c[0], None, "piece {k}");
        assert_eq!(c[1], None, "piece {k}");
        // v-span 0 starts at the south pole, v-span 1 ends at the north pole.
        let south = (k % 2 == 0).then_some([0.0, 0.0, -1.0]);
        let north = (k % 2 == 1).then_some([0.0, 0.0, 1.0]);
        assert_eq!((c[2], c[3]), (south, north), "piece {k}");
    }
}

/// The enclosure holds the exact normal direction, scaled as the module derives it, at points
/// of sub-pieces touching the pole, down to 1e-12 from it, on every piece and both poles.
#[test]
fn the_collapsed_normal_holds_the_normal_near_the_pole() {
    for p in pieces() {
        let d = p.domain();
        let side = if p.collapsed_sides()[2].is_some() {
            2
        } else {
            3
        };
        let x = p.collapsed_sides()[side].unwrap();
        for (s, r) in [
            ([0.0, 0.0625], [0.0, 0.125]),
            ([0.25, 0.3125], [0.0, 0.125]),
            ([0.5, 0.53125], [0.9375, 1.0]),
        ] {
            // The ranges are written for a pole at r = 0; mirrored for one at r = 1.
            let toward = (side == 2) == (r[0] == 0.0);
            let r = if toward || r == [0.0, 1.0] {
                r
            } else {
                [1.0 - r[1], 1.0 - r[0]]
            };
            let piece = Piece::over(&p, s, r).unwrap();
            let e = collapsed_normal(&piece, side, x).unwrap();
            let mag = e.iter().map(|c| c.mag()).fold(0.0, f64::max);
            assert!(e.iter().all(|c| c.wid() < mag), "{e:?}");
            let (du, dv) = (
                (s[1] - s[0]) * (d.u[1] - d.u[0]),
                (r[1] - r[0]) * (d.v[1] - d.v[0]),
            );
            for &fs in &[0.0, 0.3, 0.77, 1.0] {
                for &b in &[1e-12, 1e-6, 0.01, 0.5, 1.0] {
                    let rn = if side == 2 { b } else { 1.0 - b };
                    let u = d.u[0] + (s[0] + fs * (s[1] - s[0])) * (d.u[1] - d.u[0]);
                    let v = d.v[0] + (r[0] + rn * (r[1] - r[0])) * (d.v[1] - d.v[0]);
                    let g = p.derivs_f64(u, v);
                    let n = cross(&g.su, &g.sv).map(|c| c * du * dv / b);
                    for c in 0..3 {
                        let slack = 1e-6 * (1.0 + n[c].abs());
                        assert!(
                            e[c].inf() - slack <= n[c] && n[c] <= e[c].sup() + slack,
                            "side {side} s {s:?} r {r:?} at ({fs}, {b}): {n:?} not in {e:?}"
                        );
                    }
                }
            }
        }
    }
}

/// At the pole the normal is the axis: every narrow sub-piece at the pole, all round it, has
/// its enclosure along ±z, away from zero, with the sign of the patch's own normal nearby
/// (the same at every piece of one pole: the orientation is consistent).
#[test]
fn the_collapsed_normal_at_the_pole_is_the_axis() {
    for p in pieces() {
        let side = if p.collapsed_sides()[2].is_some() {
            2
        } else {
            3
        };
        let x = p.collapsed_sides()[side].unwrap();
        let r = if side == 2 {
            [0.0, 1.0 / 64.0]
        } else {
            [63.0 / 64.0, 1.0]
        };
        let d = p.domain();
        for k in 0..32 {
            let s = [k as f64 / 32.0, (k + 1) as f64 / 32.0];
            let piece = Piece::over(&p, s, r).unwrap();
            let e = collapsed_normal(&piece, side, x).unwrap();
            let z = e[2];
            assert!(z.inf() > 0.0 || z.sup() < 0.0, "{e:?}");
            for c in 0..2 {
                assert!(e[c].mag() < 0.2 * z.mig(), "{e:?}");
            }
            let u = d.u[0] + 0.5 * (s[0] + s[1]) * (d.u[1] - d.u[0]);
            let v = d.v[0] + 0.5 * (r[0] + r[1]) * (d.v[1] - d.v[0]);
            let g = p.derivs_f64(u, v);
            let n = cross(&g.su, &g.sv);
            assert_eq!(z.inf() > 0.0, n[2] > 0.0, "{e:?} against {n:?}");
        }
    }
}

/// The sphere with its parameters swapped (`u` along the meridians, `v` round the axis): the
/// poles are then on the sides `u = u0` and `u = u1`.
fn transposed_sphere() -> NurbsSurface {
    let s = nurbs_sphere();
    let (nu, nv) = (9, 5);
    let pts = s.points();
    let ws = s.weights();
    let mut tp = Vec::new();
    let mut tw = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            tp.push(pts[i * nv + j]);
            tw.push(ws[i * nv + j]);
        }
    }
    let ku = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0];
    let kv = vec![0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 2.0];
    NurbsSurface::new([2, 2], [kv, ku], tp, Some(tw)).unwrap()
}

/// On both spheres, at every collapsed side of every piece (the `v` sides of the standard one,
/// the `u` sides of the transposed one), the enclosure holds the exact normal scaled as the
/// module derives it, down to 1e-12 from the pole: the sign of every side's orientation.
#[test]
fn the_collapsed_normal_holds_the_normal_on_every_side() {
    let mut sides_seen = [0usize; 4];
    for sphere in [nurbs_sphere(), transposed_sphere()] {
        for p in sphere.to_bezier().unwrap() {
            let d = p.domain();
            for (side, x) in p.collapsed_sides().into_iter().enumerate() {
                let Some(x) = x else { continue };
                sides_seen[side] += 1;
                let lower = side % 2 == 0;
                let across = if lower { [0.0, 0.125] } else { [0.875, 1.0] };
                let along = [0.25, 0.3125];
                let (s, r) = if side < 2 {
                    (across, along)
                } else {
                    (along, across)
                };
                let piece = Piece::over(&p, s, r).unwrap();
                let e = collapsed_normal(&piece, side, x).unwrap();
                let (du, dv) = (
                    (s[1] - s[0]) * (d.u[1] - d.u[0]),
                    (r[1] - r[0]) * (d.v[1] - d.v[0]),
                );
                for &fa in &[0.0, 0.4, 1.0] {
                    for &b in &[1e-12, 1e-5, 0.2, 1.0] {
                        let c = if lower {
                            across[0] + b * (across[1] - across[0])
                        } else {
                            across[1] - b * (across[1] - across[0])
                        };
                        let a = along[0] + fa * (along[1] - along[0]);
                        let (ns, nr) = if side < 2 { (c, a) } else { (a, c) };
                        let u = d.u[0] + ns * (d.u[1] - d.u[0]);
                        let v = d.v[0] + nr * (d.v[1] - d.v[0]);
                        let g = p.derivs_f64(u, v);
                        let n = cross(&g.su, &g.sv).map(|c| c * du * dv / b);
                        for k in 0..3 {
                            let slack = 1e-6 * (1.0 + n[k].abs());
                            assert!(
                                e[k].inf() - slack <= n[k] && n[k] <= e[k].sup() + slack,
                                "side {side} at ({fa}, {b}): {n:?} not in {e:?}"
                            );
                        }
                    }
                }
            }
        }
    }
    assert!(sides_seen.iter().all(|&k| k == 4), "{sides_seen:?}");
}

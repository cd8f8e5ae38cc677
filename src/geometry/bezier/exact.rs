//! A patch's homogeneous point at an `f64` parameter point, exactly (dyadic rationals).

use super::RationalBezierPatch;
use crate::geometry::bernstein::binomial;
use crate::numeric::dyadic::Dyadic;

impl RationalBezierPatch {
    /// The homogeneous point `(w·x, w·y, w·z, w)` at `(u, v)` times `Δu^m·Δv^n` (the domain's
    /// widths: a positive factor, common to all four, so `x = H₀/H₃` and so on), exactly:
    /// `Σ C(m,i)·C(n,j)·aⁱ·b^(m−i)·cʲ·d^(n−j)·h_ij` with `a = u − u₀`, `b = u₁ − u`,
    /// `c = v − v₀`, `d = v₁ − v`, every product and sum without rounding.
    ///
    /// From the Cartesian data as given (`w·x` formed exactly) or, for a patch built from a
    /// homogeneous net, from that net. `None` if any of those numbers is an interval wider than
    /// a point (the patch is then not one exact surface) or `u`, `v` are not finite.
    pub(crate) fn homogeneous_exact(&self, u: f64, v: f64) -> Option<[Dyadic; 4]> {
        // The four numbers of a control point as exact values (`None` unless all are points).
        let exact = |c: &[inari::Interval; 4]| -> Option<[Dyadic; 4]> {
            let x = c.map(|x| {
                (x.inf() == x.sup())
                    .then(|| Dyadic::from_f64(x.inf()))
                    .flatten()
            });
            let [a, b, c, d] = x;
            Some([a?, b?, c?, d?])
        };
        let net: Vec<[Dyadic; 4]> = match &self.cartesian {
            // (x, y, z, w) → (w·x, w·y, w·z, w), exactly.
            Some(cart) => cart
                .iter()
                .map(|c| exact(c).map(|[x, y, z, w]| [&x * &w, &y * &w, &z * &w, w]))
                .collect::<Option<_>>()?,
            None => self.homogeneous.iter().map(exact).collect::<Option<_>>()?,
        };
        let zero4 = || std::array::from_fn::<Dyadic, 4, _>(|_| Dyadic::zero());
        let [m, n] = self.degree;
        let d = self.domain;
        let bu = basis(m, u, d.u)?;
        let bv = basis(n, v, d.v)?;
        let mut out = zero4();
        for (i, bi) in bu.iter().enumerate() {
            let mut row = zero4();
            for (j, bj) in bv.iter().enumerate() {
                let h = &net[i * (n + 1) + j];
                for k in 0..4 {
                    row[k] = &row[k] + &(bj * &h[k]);
                }
            }
            for k in 0..4 {
                out[k] = &out[k] + &(bi * &row[k]);
            }
        }
        Some(out)
    }
}

/// `C(deg,i)·aⁱ·b^(deg−i)` for `i ≤ deg`, with `a = x − lo`, `b = hi − x` (the Bernstein basis
/// times `(hi − lo)^deg`), exactly.
fn basis(deg: usize, x: f64, [lo, hi]: [f64; 2]) -> Option<Vec<Dyadic>> {
    let x = Dyadic::from_f64(x)?;
    let a = &x - &Dyadic::from_f64(lo)?;
    let b = &Dyadic::from_f64(hi)? - &x;
    let mut pa = vec![Dyadic::from_f64(1.0)?];
    let mut pb = vec![Dyadic::from_f64(1.0)?];
    for k in 1..=deg {
        pa.push(&pa[k - 1] * &a);
        pb.push(&pb[k - 1] * &b);
    }
    (0..=deg)
        .map(|i| Some(&(&Dyadic::from_f64(binomial(deg, i))? * &pa[i]) * &pb[deg - i]))
        .collect()
}

#[cfg(test)]
mod tests {
    use crate::geometry::RationalBezierPatch;
    use crate::numeric::scalar::point;
    use crate::Domain;

    fn quarter_cylinder() -> RationalBezierPatch {
        crate::geometry::bezier::quarter_cylinder_over(Domain {
            u: [0.25, 2.0],
            v: [-1.0, 3.0],
        })
    }

    #[test]
    fn exact_points_lie_in_the_interval_evaluation() {
        let p = quarter_cylinder();
        for k in 0..=20 {
            let (u, v) = (0.25 + 1.75 * k as f64 / 20.0, -1.0 + 0.2 * k as f64);
            let h = p.homogeneous_exact(u, v).unwrap();
            let e = p.eval(point(u), point(v));
            let w = h[3].enclosure().unwrap();
            assert!(w.inf() > 0.0);
            for r in 0..3 {
                let x = h[r].enclosure().unwrap() / w;
                assert!(e[r].contains(x.mid()), "{r}: {x:?} outside {:?}", e[r]);
                assert!(x.wid() <= 1e-15 * x.mag(), "{x:?}");
            }
            // On the unit cylinder x² + y² = 1 (the input weight is rounded, so to the
            // rounding of that weight only).
            let (x, y) = (h[0].enclosure().unwrap() / w, h[1].enclosure().unwrap() / w);
            let r2 = x.sqr() + y.sqr();
            assert!((r2.mid() - 1.0).abs() < 1e-15, "{r2:?}");
        }
    }

    #[test]
    fn interval_data_have_no_exact_point() {
        let wide = RationalBezierPatch::new(
            [1, 1],
            vec![
                [
                    point(0.0),
                    point(0.0),
                    inari::interval!(0.0, 1e-12).unwrap(),
                ],
                [0.0, 1.0, 0.0].map(point),
                [1.0, 0.0, 0.0].map(point),
                [1.0, 1.0, 0.0].map(point),
            ],
            None,
            Domain::UNIT,
        )
        .unwrap();
        assert!(wide.homogeneous_exact(0.5, 0.5).is_none());
        assert!(quarter_cylinder()
            .homogeneous_exact(f64::NAN, 0.0)
            .is_none());
    }
}

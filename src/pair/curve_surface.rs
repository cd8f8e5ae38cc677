//! Rigorous settling of one box of a curve/surface intersection problem.
//!
//! The problem is `A(σ, t) − B(u, v) = 0` with one parameter of `A` held at an exact value (a
//! boundary curve or a face of a sub-patch of `A`): three equations in three unknowns. A box of
//! the unknowns is settled by one Krawczyk step
//!
//! ```text
//! K(X) = x̃ − C·F(x̃) + (I − C·J(X))·(X − x̃),     C ≈ (mid J)⁻¹
//! ```
//!
//! `K(X) ⊂ int X` proves exactly one zero in `X`; `K(X) ∩ X = ∅` proves none (every zero in `X`
//! lies in `K(X)`); the operator is [`krawczyk_operator`], shared with the curve tracer's
//! [`krawczyk`](crate::pair::krawczyk::krawczyk). The caller supplies the Jacobian enclosure
//! `J(X)`; the search takes it from the interval Bernstein nets of the pieces
//! ([`Piece::partials`](crate::geometry::piece::Piece::partials)), not from naive interval
//! evaluation of the Bernstein sums, which wraps so badly on high degrees that the test would
//! never pass on reasonably sized boxes.
//!
//! The fixed coordinate may be an interval (the declared parameter of a face, rounded outward):
//! then `F(x̃)` is enclosed over it, and for the exact face value inside it — the one for which the
//! caller's `J(X)` holds — the usual conclusions follow (parametric Krawczyk).

use crate::pair::krawczyk::{krawczyk_operator, preconditioner};
use inari::Interval;

/// What one Krawczyk step proved about a box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BoxVerdict {
    /// Exactly one zero in the box; it lies in this sub-box (`(σ, t, u, v)`, the fixed
    /// coordinate a point interval).
    One([Interval; 4]),
    /// No zero in the box.
    None,
    /// Not decided (box too large, or a near-tangency).
    Unknown,
}

/// One Krawczyk step on `F = A(σ, t) − B(u, v) = 0` over the box `x = (σ, t, u, v)`
/// (parameters of `a` then `b`), coordinate `fixed` (0 or 1: a parameter of `a`) held in its
/// interval `x[fixed]`. `xm` encloses a point of `x` (its fixed coordinate equal to `x[fixed]`),
/// `f` encloses `F` there, and `jac` encloses over `x` the free partial of `A` and `B_u`, `B_v`
/// (in that order). Rigorous (see the module documentation).
pub fn settle_box(
    x: [Interval; 4],
    xm: [Interval; 4],
    f: [Interval; 3],
    fixed: usize,
    jac: [[Interval; 3]; 3],
) -> BoxVerdict {
    if fixed > 1 || x.iter().any(|c| c.is_empty() || !c.wid().is_finite()) {
        return BoxVerdict::Unknown;
    }
    let free: [usize; 3] = if fixed == 0 { [1, 2, 3] } else { [0, 2, 3] };
    let cols = [jac[0], jac[1].map(|c| -c), jac[2].map(|c| -c)];
    let Some(cinv) = preconditioner(&cols) else {
        return BoxVerdict::Unknown;
    };
    if !cinv.iter().all(|c| c.is_finite()) {
        return BoxVerdict::Unknown;
    }
    let image = krawczyk_operator(&x, &xm, &f, &free, &cols, &cinv);
    let mut out = x;
    let mut inside = true;
    for (r, acc) in image.into_iter().enumerate() {
        if acc.is_empty() {
            return BoxVerdict::Unknown;
        }
        if acc.disjoint(x[free[r]]) {
            return BoxVerdict::None;
        }
        inside &= acc.interior(x[free[r]]);
        out[free[r]] = acc;
    }
    if inside {
        BoxVerdict::One(out)
    } else {
        BoxVerdict::Unknown
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Domain, PowerSurface};
    use crate::numeric::scalar::{interval, point};

    fn iv(a: f64, b: f64) -> Interval {
        interval(a, b).unwrap()
    }

    #[test]
    fn krawczyk_step_finds_excludes_and_declines() {
        // Edge σ = 0.3 of the paraboloid z = σ² + t² − 0.25 against the plane z = 0: the zeros
        // are t = ±√(0.25 − 0.09) = ±0.4, at (u, v) = (0.3, ±0.4). Exact Jacobian enclosures:
        // P_t = (0, 1, 2t), Q_u = (1, 0, 0), Q_v = (0, 1, 0).
        let d = Domain::new(-1.0, 1.0, -1.0, 1.0);
        let bowl = PowerSurface::graph(d, vec![(2, 0, 1.0), (0, 2, 1.0), (0, 0, -0.25)])
            .to_bezier()
            .unwrap();
        let plane = PowerSurface::graph(d, vec![(0, 0, 0.0), (1, 1, 0.0)])
            .to_bezier()
            .unwrap();
        let jac = |t: Interval| {
            [
                [point(0.0), point(1.0), point(2.0) * t],
                [point(1.0), point(0.0), point(0.0)],
                [point(0.0), point(1.0), point(0.0)],
            ]
        };
        let settle = |x: [Interval; 4]| {
            let xm = x.map(|c| point(c.mid()));
            let (fa, fb) = (
                bowl.eval::<Interval>(xm[0], xm[1]),
                plane.eval::<Interval>(xm[2], xm[3]),
            );
            let f = std::array::from_fn(|r| fa[r] - fb[r]);
            settle_box(x, xm, f, 0, jac(x[1]))
        };
        let x = [point(0.3), iv(0.35, 0.45), iv(0.28, 0.33), iv(0.36, 0.43)];
        match settle(x) {
            BoxVerdict::One(e) => {
                assert!(e[1].contains(0.4) && e[2].contains(0.3) && e[3].contains(0.4));
            }
            other => panic!("{other:?}"),
        }
        let away = [point(0.3), iv(0.1, 0.2), iv(0.28, 0.33), iv(0.1, 0.2)];
        assert_eq!(settle(away), BoxVerdict::None);
        // Both zeros in one box: never "one".
        let both = [point(0.3), iv(-0.5, 0.5), iv(0.2, 0.4), iv(-0.5, 0.5)];
        assert!(!matches!(settle(both), BoxVerdict::One(_)));
    }
}

//! Certified points of the intersection: the parametric Krawczyk test on P(σ,t) − Q(u,v) = 0.
//!
//! One of the four parameters is held in an interval (the *fixed* coordinate); the other three
//! are the unknowns of three equations. With X the box of unknowns, x̃ = mid X, C ≈ (mid J)⁻¹,
//!
//! ```text
//! K(X) = x̃ − C·F(x̃, [p]) + (I − C·J(X, [p]))·(X − x̃)
//! ```
//!
//! If K(X) ⊂ int X then for every value of the fixed coordinate in its interval there is exactly
//! one zero in X, and it lies in K(X) ∩ X (Krawczyk 1969; Moore's proof carries over to interval
//! parameters because F and J are enclosed over the parameter interval). Iterating X ← K(X) ∩ X
//! contracts the box onto the curve: this is how enclosures are pulled back onto P = Q.

use crate::numeric::scalar::{interval, point};
use crate::pair::field::ScalarSurface;
use inari::Interval;
use nalgebra::Matrix3;

/// A box in `(σ, t, u, v)`.
pub type ParamBox = [Interval; 4];

/// A surface the Krawczyk test can use: `[S, S_u, S_v]` enclosed over a parameter box, for
/// every point of the box. Every [`ScalarSurface`] is one (its interval evaluation); a surface
/// stitched from pieces across a knot line or seam is another (continuous, with the pieces'
/// enclosures hulled: the mean-value inclusion the test rests on holds for a continuous,
/// piecewise continuously differentiable map with its derivatives enclosed on every piece).
pub trait BoxSurface {
    /// `[S, S_u, S_v]` enclosed over `u × v`.
    fn box_first_order(&self, u: Interval, v: Interval) -> [[Interval; 3]; 3];
}

impl<S: ScalarSurface + ?Sized> BoxSurface for S {
    fn box_first_order(&self, u: Interval, v: Interval) -> [[Interval; 3]; 3] {
        self.first_order(u, v)
    }
}

/// Outcome of [`krawczyk`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KrawczykResult {
    /// Proven: for every value of the fixed coordinate in its interval the curve meets the box
    /// in exactly one point, and all those points lie in `enclosure` (a sub-box of the input).
    Proven {
        /// The contracted box.
        enclosure: ParamBox,
        /// Krawczyk iterations used.
        iterations: usize,
    },
    /// Not proven (the box may or may not contain a curve point): the reason.
    NotProven(&'static str),
}

/// Runs the parametric Krawczyk test and contraction on `y`, holding coordinate `fixed` (0..4)
/// in its interval. At most `max_iter` iterations; stops early when the widths stop shrinking.
pub fn krawczyk<P, Q>(p: &P, q: &Q, y: ParamBox, fixed: usize, max_iter: usize) -> KrawczykResult
where
    P: BoxSurface + ?Sized,
    Q: BoxSurface + ?Sized,
{
    if fixed > 3 || y.iter().any(|c| c.is_empty()) {
        return KrawczykResult::NotProven("invalid box or fixed coordinate");
    }
    let mut y = y;
    let mut proven = false;
    for it in 0..max_iter.max(1) {
        let (next, inside) = match krawczyk_image(p, q, &y, fixed) {
            None => {
                return KrawczykResult::NotProven(
                    "singular Jacobian (tangential or singular point)",
                )
            }
            Some(Image::Empty) => {
                return KrawczykResult::NotProven(
                    "the box holds no curve point (Krawczyk image disjoint)",
                )
            }
            Some(Image::Box { next, inside }) => (next, inside),
        };
        proven |= inside;
        let shrink = (0..4).all(|i| i == fixed || next[i].wid() >= 0.9 * y[i].wid());
        y = next;
        if proven && (shrink || it + 1 == max_iter.max(1)) {
            return KrawczykResult::Proven {
                enclosure: y,
                iterations: it + 1,
            };
        }
    }
    if proven {
        KrawczykResult::Proven {
            enclosure: y,
            iterations: max_iter,
        }
    } else {
        KrawczykResult::NotProven(
            "Krawczyk image not inside the box (box too large or near-singular)",
        )
    }
}

/// One Krawczyk image, intersected with the box.
enum Image {
    /// The image misses the box in some coordinate: no zero in the box.
    Empty,
    /// `next = K(y) ∩ y`; `inside`: `K(y) ⊂ int y` in the three free coordinates.
    Box { next: ParamBox, inside: bool },
}

/// `K(y) ∩ y` holding coordinate `fixed`; `None` if the midpoint Jacobian is singular.
fn krawczyk_image<P, Q>(p: &P, q: &Q, y: &ParamBox, fixed: usize) -> Option<Image>
where
    P: BoxSurface + ?Sized,
    Q: BoxSurface + ?Sized,
{
    let free: [usize; 3] = match fixed {
        0 => [1, 2, 3],
        1 => [0, 2, 3],
        2 => [0, 1, 3],
        _ => [0, 1, 2],
    };
    // Interval Jacobian over the whole box (columns: the free unknowns).
    let [_, ps, pt] = p.box_first_order(y[0], y[1]);
    let [_, qu, qv] = q.box_first_order(y[2], y[3]);
    let neg = |a: [Interval; 3]| a.map(|x| -x);
    let cols_all = [ps, pt, neg(qu), neg(qv)];
    let jac: [[Interval; 3]; 3] = free.map(|k| cols_all[k]); // jac[col][row]
    let cinv = preconditioner(&jac)?;
    // F at the midpoint of the free coordinates, the fixed one kept as its interval: directly,
    // and in mean-value form around the fixed coordinate's midpoint c,
    // F(x̃, [p]) ⊂ F(x̃, c) + J_fixed(y)·([p] − c) (the segment lies in y). Both enclose it; the
    // second is far tighter on a thin box, where the direct patch evaluation over [p] wraps.
    let mut ymid = *y;
    for &k in &free {
        ymid[k] = point(y[k].mid());
    }
    let [pm, ..] = p.box_first_order(ymid[0], ymid[1]);
    let [qm, ..] = q.box_first_order(ymid[2], ymid[3]);
    let mut f: [Interval; 3] = std::array::from_fn(|r| pm[r] - qm[r]);
    if y[fixed].wid() > 0.0 {
        let c = point(y[fixed].mid());
        let mut ycen = ymid;
        ycen[fixed] = c;
        let [pc, ..] = p.box_first_order(ycen[0], ycen[1]);
        let [qc, ..] = q.box_first_order(ycen[2], ycen[3]);
        let dk = y[fixed] - c;
        for r in 0..3 {
            let mv = pc[r] - qc[r] + cols_all[fixed][r] * dk;
            let both = f[r].intersection(mv);
            if !both.is_empty() {
                f[r] = both;
            }
        }
    }
    let kx = krawczyk_operator(y, &ymid, &f, &free, &jac, &cinv);
    let inside = (0..3).all(|r| kx[r].interior(y[free[r]]));
    let mut next = *y;
    for r in 0..3 {
        next[free[r]] = kx[r].intersection(y[free[r]]);
    }
    if next.iter().any(|c| c.is_empty()) {
        return Some(Image::Empty);
    }
    Some(Image::Box { next, inside })
}

/// The preconditioner `C = (mid J)⁻¹` of the Krawczyk operator (any `C` gives a rigorous
/// operator; a good one makes the test succeed), from the interval Jacobian columns
/// `cols[col][row]`; `None` if the midpoint matrix is singular.
pub fn preconditioner(cols: &[[Interval; 3]; 3]) -> Option<Matrix3<f64>> {
    Matrix3::from_fn(|r, c| cols[c][r].mid()).try_inverse()
}

/// The Krawczyk operator on the three free coordinates `free` of the box `x`:
///
/// ```text
/// K(X)ᵣ = x̃ᵣ − (C·F(x̃))ᵣ + Σ_col (I − C·J(X))ᵣ,col · (X − x̃)_col
/// ```
///
/// with `xm` the point `x̃` (its free coordinates point intervals inside `x`, the others as in
/// `x`), `f` an enclosure of `F` at `xm`, `cols[col][row]` the interval Jacobian of the free
/// unknowns over `x` and `c` the preconditioner (see [`preconditioner`]). Entry `r` of the
/// result is the image of coordinate `free[r]`. Rigorous whatever `c` is: every zero of `F` in
/// `x` lies in the image, and an image inside the interior of `x` proves exactly one.
pub fn krawczyk_operator(
    x: &ParamBox,
    xm: &ParamBox,
    f: &[Interval; 3],
    free: &[usize; 3],
    cols: &[[Interval; 3]; 3],
    c: &Matrix3<f64>,
) -> [Interval; 3] {
    let jac: [[Interval; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|k| cols[k][r]));
    let c: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|k| c[(r, k)]));
    krawczyk_image_n(&free.map(|k| x[k]), &free.map(|k| xm[k]), f, &jac, &c)
}

/// The Krawczyk operator in `N` unknowns, the one formula every Krawczyk test of the crate
/// evaluates:
///
/// ```text
/// K(X)ᵣ = x̃ᵣ − (C·F(x̃))ᵣ + Σ_k (I − C·J(X))ᵣₖ · (X − x̃)ₖ
/// ```
///
/// with `x` the box, `xm` the point `x̃` (point intervals, or thin enclosures, inside `x`), `f`
/// an enclosure of `F` at `x̃` (for a parametric problem: over all parameter values), `jac[r][k]`
/// the interval Jacobian `∂Fᵣ/∂xₖ` over the box (and the parameters) and `c` any preconditioner
/// (rows). Rigorous whatever `c` is: every zero of `F` in `x` lies in the image; an image inside
/// the interior of `x` proves exactly one (for each parameter value); an image disjoint from `x`
/// proves none.
pub fn krawczyk_image_n<const N: usize>(
    x: &[Interval; N],
    xm: &[Interval; N],
    f: &[Interval; N],
    jac: &[[Interval; N]; N],
    c: &[[f64; N]; N],
) -> [Interval; N] {
    let c: [[Interval; N]; N] = c.map(|row| row.map(point));
    std::array::from_fn(|r| {
        let mut cf = point(0.0);
        for (ci, fi) in c[r].iter().zip(f) {
            cf += *ci * *fi;
        }
        let mut acc = xm[r] - cf;
        for k in 0..N {
            // (I − C·J)[r][k]
            let mut cj = point(0.0);
            for (i, ci) in c[r].iter().enumerate() {
                cj += *ci * jac[i][k];
            }
            let ident = if r == k { point(1.0) } else { point(0.0) };
            acc += (ident - cj) * (x[k] - xm[k]);
        }
        acc
    })
}

/// Contracts `y` with the Krawczyk operator, holding coordinate `fixed` in its interval, without
/// the strict-interior test: every zero of `P − Q` in `y` (for the fixed coordinate in its
/// interval) lies in the result, whether or not there is one. `None` if the box provably holds no
/// zero (an image is disjoint from it) or the Jacobian is singular.
///
/// Use it when existence and uniqueness are known from elsewhere (e.g. a proven [`krawczyk`] on a
/// larger box); the result is then a tighter box around the same points.
pub fn contract_box<P, Q>(
    p: &P,
    q: &Q,
    y: ParamBox,
    fixed: usize,
    iterations: usize,
) -> Option<ParamBox>
where
    P: ScalarSurface + ?Sized,
    Q: ScalarSurface + ?Sized,
{
    if fixed > 3 || y.iter().any(|c| c.is_empty()) {
        return None;
    }
    let mut y = y;
    for _ in 0..iterations {
        match krawczyk_image(p, q, &y, fixed)? {
            Image::Empty => return None,
            Image::Box { next, .. } => {
                let shrunk = (0..4).any(|i| next[i].wid() < 0.9 * y[i].wid());
                y = next;
                if !shrunk {
                    break;
                }
            }
        }
    }
    Some(y)
}

/// The coordinate to hold fixed at a curve point with parameter velocity `velocity`: the one
/// moving fastest relative to `scales` (so the remaining 3×3 Jacobian is best conditioned).
pub fn best_fixed_coordinate(velocity: &[f64; 4], scales: &[f64; 4]) -> usize {
    (0..4)
        .max_by(|&a, &b| {
            let ra = (velocity[a] / scales[a]).abs();
            let rb = (velocity[b] / scales[b]).abs();
            ra.total_cmp(&rb)
        })
        .unwrap_or(0)
}

/// A certified box around an approximate curve point `approx`: coordinate `fixed` is held at
/// exactly its value, the others get radius `radius`; `None` if the proof fails.
pub fn certify_point<P, Q>(
    p: &P,
    q: &Q,
    approx: [f64; 4],
    fixed: usize,
    radius: f64,
) -> Option<ParamBox>
where
    P: ScalarSurface + ?Sized,
    Q: ScalarSurface + ?Sized,
{
    let mut y = [Interval::EMPTY; 4];
    for k in 0..4 {
        y[k] = if k == fixed {
            point(approx[k])
        } else {
            interval(approx[k] - radius, approx[k] + radius)?
        };
    }
    match krawczyk(p, q, y, fixed, 8) {
        KrawczykResult::Proven { enclosure, .. } => Some(enclosure),
        KrawczykResult::NotProven(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pair::fixtures::Bowl;

    #[test]
    fn certified_box_contains_the_true_curve_point_and_is_tight() {
        // Circle of radius 0.5 in the plane z = 0 (P a bowl, Q the plane).
        let p = Bowl::new(1.0, -0.25);
        let q = Bowl::new(0.0, 0.0);
        for k in 0..40 {
            let th = 0.05 + 0.15 * k as f64;
            let (x, y) = (0.5 * th.cos(), 0.5 * th.sin());
            let approx = [x + 1e-7, y - 1e-7, x, y];
            let fixed = best_fixed_coordinate(&[-y, x, -y, x], &[1.0; 4]);
            let b = certify_point(&p, &q, approx, fixed, 1e-4).expect("proof");
            // The true point with the fixed coordinate's value: (σ,t) on the circle, (u,v) = (σ,t).
            let fv = approx[fixed];
            let other = (0.25 - fv * fv)
                .sqrt()
                .copysign(if fixed.is_multiple_of(2) { y } else { x });
            let truth = if fixed.is_multiple_of(2) {
                [fv, other]
            } else {
                [other, fv]
            };
            for (i, t) in [truth[0], truth[1], truth[0], truth[1]].iter().enumerate() {
                assert!(
                    b[i].inf() <= *t + 1e-15 && *t - 1e-15 <= b[i].sup(),
                    "coord {i}"
                );
                assert!(b[i].wid() < 1e-12, "coord {i} width {}", b[i].wid());
            }
        }
    }

    #[test]
    fn interval_fixed_coordinate_encloses_the_curve_piece_and_contract_box_keeps_its_point() {
        // Circle of radius 0.5 (bowl against plane); σ held in a thin interval X around 0.3:
        // the curve piece over X (t = +√(0.25 − σ²), u = σ, v = t) must lie in the enclosure.
        let p = Bowl::new(1.0, -0.25);
        let q = Bowl::new(0.0, 0.0);
        let (s0, w) = (0.3, 1e-12);
        let t0 = (0.25f64 - s0 * s0).sqrt();
        let x = interval(s0 - w, s0 + w).unwrap();
        let r = 1e-10;
        let y = [
            x,
            interval(t0 - r, t0 + r).unwrap(),
            interval(s0 - r, s0 + r).unwrap(),
            interval(t0 - r, t0 + r).unwrap(),
        ];
        let KrawczykResult::Proven { enclosure, .. } = krawczyk(&p, &q, y, 0, 4) else {
            panic!("not proven on a thin interval of the fixed coordinate");
        };
        for sigma in [s0 - w, s0, s0 + w] {
            let t = (0.25f64 - sigma * sigma).sqrt();
            for (i, v) in [sigma, t, sigma, t].iter().enumerate() {
                assert!(
                    enclosure[i].inf() <= v + 1e-15 && v - 1e-15 <= enclosure[i].sup(),
                    "coord {i}"
                );
            }
        }
        // The mean-value form keeps the free widths near the curve's own spread over X.
        assert!(enclosure[1].wid() < 1e-11, "{}", enclosure[1].wid());
        // contract_box with σ = s0 exactly: tight and still holding the point.
        let mut thin = enclosure;
        thin[0] = point(s0);
        let c = contract_box(&p, &q, thin, 0, 3).expect("contracts");
        for (i, v) in [s0, t0, s0, t0].iter().enumerate() {
            assert!(
                c[i].inf() <= v + 1e-15 && v - 1e-15 <= c[i].sup(),
                "coord {i}"
            );
            assert!(c[i].wid() <= thin[i].wid());
        }
        assert!(c[1].wid() < 1e-14, "{}", c[1].wid());
        // A box without the curve is emptied.
        let mut off = thin;
        off[1] = interval(t0 + 1e-3, t0 + 2e-3).unwrap();
        off[3] = off[1];
        assert!(contract_box(&p, &q, off, 0, 3).is_none());
    }

    #[test]
    fn box_off_the_curve_is_not_proven() {
        let p = Bowl::new(1.0, -0.25);
        let q = Bowl::new(0.0, 0.0);
        assert!(certify_point(&p, &q, [0.0, 0.0, 0.0, 0.0], 0, 1e-3).is_none());
    }

    #[test]
    fn tangential_point_is_not_proven() {
        // Bowl z = u² + v² touches the plane z = 0 at the origin only.
        let p = Bowl::new(1.0, 0.0);
        let q = Bowl::new(0.0, 0.0);
        assert!(certify_point(&p, &q, [0.0, 0.0, 0.0, 0.0], 0, 1e-3).is_none());
    }
}

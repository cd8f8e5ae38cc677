//! A leaf of a curve/surface search where the intersection curve touches the searched edge (a
//! double root: no Krawczyk test settles it), settled by proving that every curve point in the
//! leaf lies on the one arc through the Newton point offered from it.
//!
//! **The argument.** Let the edge be `A(·)` with the parameter of index `k` fixed at `c`, and
//! `x*` the Newton point of the leaf. Take the box `B = S × Y`: `S` the free edge parameter over
//! the hull of the leaf's range and `x*`'s widened by `h` (the leaf's width), `Y` the fixed
//! parameter over `c ± 4h` and the other surface's `(u, v)` over the hull of the leaf's box and
//! `x*`'s widened by `4h`. A parametric Krawczyk test on the three equations `A − B = 0` in the unknowns
//! `Y`, for all values of the free parameter in `S` at once, whose image lies inside `Y`, proves
//! that for each `s ∈ S` exactly one point of `Y` solves them: `C ∩ B` is one arc, a graph over
//! `s` (where the curve touches the edge it runs along it, so the free parameter is the good
//! one). Where the curve crosses the edge but the surfaces meet at too small an angle for the
//! leaf's own test, the roles swap: the arc is proven a graph over the fixed parameter, over
//! `c ± h`, the free one among the unknowns. Every curve point on the edge inside the leaf lies in `B`, so on that arc, and so does
//! `x*` (to the Newton tolerance, as every start point): the component through the leaf has a
//! start point, and the leaf is settled.

use super::project_onto_intersection;
use crate::geometry::piece::Piece;
use crate::geometry::RationalBezierPatch;
use crate::numeric::scalar::point;
use crate::pair::field::ScalarSurface;
use crate::pair::krawczyk::krawczyk_image_n;
use crate::pair::newton::{refine, Constraint};
use inari::{interval, Interval};
use nalgebra::Matrix3;

/// The leaf's parameter boxes `(a's two, b's two)` and the index (0 or 1) of `a`'s parameter
/// the edge holds fixed.
fn leaf_box(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    edge: &Piece,
    other: &Piece,
) -> (usize, [Interval; 4]) {
    let index = if edge.degree()[0] == 0 { 0 } else { 1 };
    let [xa, ya] = edge.declared(&a.domain(), 0.0);
    let [xb, yb] = other.declared(&b.domain(), 0.0);
    (index, [xa, ya, xb, yb])
}

/// Whether every intersection point of the edge piece `edge` of `a` with the piece `other` of
/// `b` lies on the arc of the intersection through `x` (parameters `(a, b)`), see the module
/// documentation.
pub(super) fn arc_through(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    edge: &Piece,
    other: &Piece,
    x: &[f64; 4],
) -> bool {
    let (index, leaf) = leaf_box(a, b, edge, other);
    let free = 1 - index;
    let h = leaf.iter().map(|i| i.wid()).fold(0.0, f64::max);
    if !(h.is_finite() && h > 0.0) {
        return false;
    }
    // The unknowns' boxes wider than the parameter's: the curve's (u, v) move with it. The
    // fixed parameter barely moves along an arc that touches the edge, and where the surfaces
    // meet at a small angle its wide box would keep Krawczyk from contracting: narrower boxes
    // are tried too.
    let grow = |i: Interval, v: f64, h: f64| interval!(i.inf().min(v) - h, i.sup().max(v) + h).ok();
    // The arc as a graph over the edge's free parameter (where it touches or runs along the
    // edge), or over the fixed one (where it crosses the edge, at an angle too small for the
    // leaf's own test).
    [(index, free), (free, index)]
        .into_iter()
        .any(|(unknown, along)| {
            let Some(s) = grow(leaf[along], x[along], h) else {
                return false;
            };
            // Over `S` the unknowns move by their slopes times its width (along an edge the
            // other surface's parameters may move faster than the edge's): their boxes allow
            // twice that.
            let slope = slopes(a, b, unknown, along, x).unwrap_or([0.0; 3]);
            let moved = |k: usize| 2.0 * slope[k].abs() * s.wid();
            let (Some(u), Some(v)) = (
                grow(leaf[2], x[2], 4.0 * h + moved(1)),
                grow(leaf[3], x[3], 4.0 * h + moved(2)),
            ) else {
                return false;
            };
            [4.0, 0.25, 1.0 / 64.0].into_iter().any(|pad| {
                grow(leaf[unknown], x[unknown], pad * h + moved(0))
                    .is_some_and(|w| settles(a, b, unknown, s, [w, u, v], [x[unknown], x[2], x[3]]))
            })
        })
}

/// The derivatives of the unknowns (`a`'s parameter `unknown`, then `b`'s `u`, `v`) along the
/// curve with respect to `a`'s parameter `along`, at the curve point `x` (`f64`: they only size
/// the boxes, which the Krawczyk test then proves or not).
fn slopes(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    unknown: usize,
    along: usize,
    x: &[f64; 4],
) -> Option<[f64; 3]> {
    let da = a.derivs_f64(x[0], x[1]);
    let db = b.derivs_f64(x[2], x[3]);
    let col = |k: usize| if k == 0 { da.su } else { da.sv };
    let (a_unknown, a_along) = (col(unknown), col(along));
    let m = Matrix3::from_fn(|r, c| match c {
        0 => a_unknown[r],
        1 => -db.su[r],
        _ => -db.sv[r],
    });
    let rhs = nalgebra::Vector3::from_fn(|r, _| -a_along[r]);
    let y = m.try_inverse()? * rhs;
    y.iter().all(|c| c.is_finite()).then(|| [y[0], y[1], y[2]])
}

/// The Krawczyk iterations of [`arc_through`] over `S × Y`, `x*` at `xy` in `Y`; `index` is the
/// parameter of `a` among the unknowns, the other one runs over `S`.
fn settles(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    index: usize,
    s: Interval,
    mut y: [Interval; 3],
    xy: [f64; 3],
) -> bool {
    // Every solution in `Y` lies in the image, so `Y ∩ image` keeps them.
    for _ in 0..MAX_ITERATIONS {
        let Some(image) = image(a, b, index, s, &y) else {
            return false;
        };
        if image.iter().zip(&y).any(|(k, y)| k.disjoint(*y)) {
            // No curve point in B at all: none in the leaf.
            return true;
        }
        if image
            .iter()
            .zip(&y)
            .all(|(k, y)| y.inf() < k.inf() && k.sup() < y.sup())
        {
            // Unique per s: the arc. x* must lie in the box it is proven in.
            return y.iter().zip(&xy).all(|(y, v)| y.contains(*v));
        }
        y = std::array::from_fn(|r| image[r].intersection(y[r]));
    }
    false
}

/// Krawczyk iterations tried per leaf.
const MAX_ITERATIONS: usize = 4;

/// The parametric Krawczyk image of `A − B = 0` over the unknowns `y` (the fixed parameter of
/// `a` of index `index`, then `(u, v)`) for all values `s` of the free parameter at once.
fn image(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    index: usize,
    s: Interval,
    y: &[Interval; 3],
) -> Option<[Interval; 3]> {
    let sm = point(s.mid());
    let ym: [Interval; 3] = y.map(|i| point(i.mid()));
    let at = |v: Interval, sv: Interval| -> [Interval; 2] {
        if index == 0 {
            [v, sv]
        } else {
            [sv, v]
        }
    };
    let pm = at(ym[0], sm);
    let [ma, ..] = a.first_order(pm[0], pm[1]);
    let [mb, ..] = b.first_order(ym[1], ym[2]);
    let f: [Interval; 3] = std::array::from_fn(|c| ma[c] - mb[c]);
    let pa = at(y[0], s);
    // Centred forms: the partials' terms cancel where the surfaces meet at a small angle, and
    // natural interval evaluation would lose that.
    let [_, au, av] = a.first_order_centred(pa[0], pa[1], pm[0], pm[1]);
    let [_, bu, bv] = b.first_order_centred(y[1], y[2], ym[1], ym[2]);
    let (a_fixed, a_free) = if index == 0 { (au, av) } else { (av, au) };
    let jac: [[Interval; 3]; 3] = std::array::from_fn(|r| [a_fixed[r], -bu[r], -bv[r]]);
    let c = Matrix3::from_fn(|r, k| jac[r][k].mid()).try_inverse()?;
    let c: [[f64; 3]; 3] = std::array::from_fn(|r| std::array::from_fn(|k| c[(r, k)]));
    let k = krawczyk_image_n(y, &ym, &f, &jac, &c);
    // The parameter's term: −C·A_s·(s − s_m), over all s in S.
    Some(std::array::from_fn(|r| {
        let ca = (0..3).fold(point(0.0), |acc, i| acc + point(c[r][i]) * a_free[i]);
        k[r] - ca * (s - sm)
    }))
}

/// The point offered from an undecided leaf: Newton on the edge from its centre, or (inside a
/// face search, `interior`) where that fails, as it may at a double root, a projection onto the
/// curve from the centre.
pub(super) fn leaf_point(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    edge: &Piece,
    other: &Piece,
    tol: f64,
    interior: bool,
) -> Option<[f64; 4]> {
    leaf_newton(a, b, edge, other, tol).or_else(|| {
        let centre = leaf_box(a, b, edge, other).1.map(|i| i.mid());
        interior
            .then(|| project_onto_intersection(a, b, centre, tol))
            .flatten()
    })
}

/// [`edge_newton`]; where that fails, [`along_edge_point`].
fn leaf_newton(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    edge: &Piece,
    other: &Piece,
    tol: f64,
) -> Option<[f64; 4]> {
    edge_newton(a, b, edge, other, tol).or_else(|| along_edge_point(a, b, edge, other, tol))
}

/// Newton on `A(edge) − B(u, v) = 0` from the centre of a leaf, the edge parameter held fixed:
/// a curve point exactly on the edge.
pub(super) fn edge_newton(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    edge: &Piece,
    other: &Piece,
    tol: f64,
) -> Option<[f64; 4]> {
    let (index, leaf) = leaf_box(a, b, edge, other);
    let x = leaf.map(|i| i.mid());
    let constraint = Constraint::Fixed {
        index,
        value: x[index],
    };
    refine(a, b, x, constraint, tol, 40).ok().map(|r| r.x)
}

/// A curve point on the edge of a leaf where the curve runs *along* the edge (a section along
/// a knot line or a patch's boundary curve, where the edge's own three equations have no
/// isolated root): Newton with the edge's free parameter held at the leaf's centre, its quarter
/// points and its ends must land on the edge at all five (the edge parameter within [`ALONG`] of
/// its domain width, which a curve that only touches or crosses the edge misses by its
/// curvature times the spacing squared), and the first of them inside both domains is the
/// point. Not proven; [`arc_through`] proves what it needs.
pub(super) fn along_edge_point(
    a: &RationalBezierPatch,
    b: &RationalBezierPatch,
    edge: &Piece,
    other: &Piece,
    tol: f64,
) -> Option<[f64; 4]> {
    let (index, leaf) = leaf_box(a, b, edge, other);
    let free = 1 - index;
    let (da, db) = (a.domain(), b.domain());
    let centre = leaf.map(|i| i.mid());
    let width = if index == 0 {
        da.u[1] - da.u[0]
    } else {
        da.v[1] - da.v[0]
    };
    let s = leaf[free];
    let mut found = None;
    let probes = [
        s.mid(),
        s.inf() + 0.25 * s.wid(),
        s.sup() - 0.25 * s.wid(),
        s.inf(),
        s.sup(),
    ];
    for at in probes {
        let mut x = centre;
        x[free] = at;
        let constraint = Constraint::Fixed {
            index: free,
            value: at,
        };
        let y = refine(a, b, x, constraint, tol, 40).ok()?.x;
        if (y[index] - centre[index]).abs() > ALONG * width {
            return None;
        }
        if found.is_none() && da.contains(y[0], y[1], 1e-12) && db.contains(y[2], y[3], 1e-12) {
            found = Some(y);
        }
    }
    found
}

/// How far (relative to the edge coordinate's domain width) a curve point may be off the edge
/// and still count as running along it.
const ALONG: f64 = 1e-9;

#[cfg(test)]
mod tests {
    use super::*;

    use crate::pair::fixtures::square_graph as graph;

    /// The face `t = 0.5` (normalised 0.75) of P over normalised `s` round `x`, and Q's piece
    /// round `(x, 0.5)`, each `w` wide (normalised).
    fn leaf(
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        c: [f64; 2],
        w: f64,
    ) -> (Piece, Piece) {
        let face = Piece::over(p, [c[0] - w, c[0] + w], [0.75 - w, 0.75])
            .unwrap()
            .face(1, true);
        let other = Piece::over(q, [c[0] - w, c[0] + w], [c[1] - w, c[1] + w]).unwrap();
        (face, other)
    }

    #[test]
    fn a_circle_touching_the_edge_is_one_arc() {
        // z = x² + y² − 0.25 against z = 0: the circle of radius 0.5 touches the line y = 0.5
        // at x = 0, from below, the surfaces meeting at slopes 1 and, scaled by k, k.
        for k in [1.0, 0.01] {
            let p = graph(vec![(2, 0, k), (0, 2, k), (0, 0, -0.25 * k)]);
            let q = graph(vec![(0, 0, 0.0), (1, 0, 0.0)]);
            let (face, other) = leaf(&p, &q, [0.5, 0.75], 1.0 / 4096.0);
            let x = [0.0, 0.5, 0.0, 0.5];
            assert!(arc_through(&p, &q, &face, &other, &x), "k {k}");
        }
    }

    #[test]
    fn two_lines_crossing_on_the_edge_are_not_one_arc() {
        // z = x² − (y − 0.5)² against z = 0: the lines y − 0.5 = ±x cross on the edge y = 0.5.
        let p = graph(vec![(2, 0, 1.0), (0, 2, -1.0), (0, 1, 1.0), (0, 0, -0.25)]);
        let q = graph(vec![(0, 0, 0.0), (1, 0, 0.0)]);
        let (face, other) = leaf(&p, &q, [0.5, 0.75], 1.0 / 4096.0);
        assert!(!arc_through(&p, &q, &face, &other, &[0.0, 0.5, 0.0, 0.5]));
    }
}

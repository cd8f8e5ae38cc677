//! Normals near a pole: a side of a patch that the patch maps to one point `X` (the pole of a
//! sphere or of any surface of revolution meeting its axis, written as a NURBS with a
//! collapsed row of control points).
//!
//! There `S_u × S_v` vanishes along the whole side, so no enclosure of it over a piece touching
//! the side excludes zero, and every test built on normals (the loop-free test of the search)
//! fails near the pole. But the normal *direction* has a limit there, and it is the direction
//! of a polynomial that does not vanish. In the piece's normalised parameters, with `a` along
//! the collapsed side and `b` away from it (`b = 0` on it), the homogeneous net translated to
//! the pole, `X̃ = H − X·W`, has its side row exactly zero (the side is `X` exactly, and so is
//! every sub-net's row on it), so
//!
//! ```text
//! S − X = X̃ / W = b · D,    D = K / W,    K = Σ_{j ≥ 1} (n / j) X̃_{i j} Bᵢ(a) B_{j−1}^{n−1}(b)
//! ```
//!
//! (`K` degree-elevated back to degree `n` so that `D` is a rational patch with `W`'s weights).
//! Then `S_a = b·D_a`, `S_b = D + b·D_b`, and `S_a × S_b = b·(D_a × D + b·D_a × D_b)`: for
//! `b > 0` the normal is a positive multiple of `Ñ = D_a × D + b·D_a × D_b`, which is enclosed
//! from `D`'s net like any patch's partials. The sign of the multiple depends on which side
//! is collapsed (the orientation of `(a, b)` against `(u, v)`) and is folded in.

use crate::geometry::piece::Piece;
use crate::geometry::{Domain, RationalBezierPatch};
use crate::numeric::scalar::point;
use crate::numeric::vec3::cross;
use inari::Interval;

/// An enclosure of a positive multiple of the normal `S_u × S_v` of the patch over the part of
/// `piece` off its side `side` (`u = u0`, `u = u1`, `v = v0`, `v = v1`), which must lie on a side
/// of the patch collapsed to the exact point `x`; the enclosure also holds the normal's limit
/// directions on that side. `None` if the weights are not provably positive or the piece has
/// a degree 0 direction (a face).
pub(crate) fn collapsed_normal(piece: &Piece, side: usize, x: [f64; 3]) -> Option<[Interval; 3]> {
    let [m, n] = piece.degree();
    if m == 0 || n == 0 {
        return None;
    }
    let net = piece.net();
    let at = |i: usize, j: usize| net[i * (n + 1) + j];
    // The canonical net C[a][b] (degrees da along the side, db away from it) and the sign of
    // S_a × S_b against S_u × S_v.
    let (da, db, sign) = match side {
        0 => (n, m, -1.0),
        1 => (n, m, 1.0),
        2 => (m, n, 1.0),
        _ => (m, n, -1.0),
    };
    let canon = |a: usize, b: usize| match side {
        0 => at(b, a),
        1 => at(m - b, a),
        2 => at(a, b),
        _ => at(a, n - b),
    };
    let xp = x.map(point);
    let mut d_net = Vec::with_capacity((da + 1) * (db + 1));
    for a in 0..=da {
        // K[b − 1] = (db / b)·X̃[b] for b ≥ 1 (the row b = 0 is exactly zero).
        let k: Vec<[Interval; 3]> = (1..=db)
            .map(|b| {
                let h = canon(a, b);
                let f = point(db as f64) / point(b as f64);
                std::array::from_fn(|c| (h[c] - xp[c] * h[3]) * f)
            })
            .collect();
        for b in 0..=db {
            // Degree elevation from db − 1 to db.
            let t = point(b as f64) / point(db as f64);
            let mut e = [point(0.0); 3];
            for (c, ec) in e.iter_mut().enumerate() {
                if b >= 1 {
                    *ec += t * k[b - 1][c];
                }
                if b < db {
                    *ec += (point(1.0) - t) * k[b][c];
                }
            }
            d_net.push([e[0], e[1], e[2], canon(a, b)[3]]);
        }
    }
    let d_piece = Piece::new([0.0, 1.0], [0.0, 1.0], [da, db], d_net, false);
    let unit = Domain {
        u: [0.0, 1.0],
        v: [0.0, 1.0],
    };
    let d = d_piece.bounds();
    let origin = d.map(|c| c.mid());
    let [Some(da_), Some(db_)] = d_piece.partials(&unit, None, &origin, 0.0)? else {
        return None;
    };
    let first = cross(&da_, &d);
    let second = cross(&da_, &db_);
    let b = Interval::try_from((0.0, 1.0)).ok()?;
    let s = point(sign);
    Some(std::array::from_fn(|c| s * (first[c] + b * second[c])))
}

/// For the parameter box `u × v` of `patch` near one side the patch collapses to a point
/// (closer to it than four times its own extent across): an enclosure of a positive multiple
/// of `S_u × S_v` over the part of the box in the domain ([`collapsed_normal`] over that part
/// stretched to the side), which excludes zero where the normal's own enclosure cannot. `None`
/// when the box is not near such a side, misses the domain, or the enclosure cannot be
/// formed. (Beyond the domain the patch's polynomial is not the surface: the part of a box
/// there is left out.)
pub(crate) fn pole_scaled_normal(
    patch: &RationalBezierPatch,
    u: Interval,
    v: Interval,
) -> Option<[Interval; 3]> {
    let poles = patch.collapsed_sides();
    if poles.iter().all(Option::is_none) {
        return None;
    }
    let d = patch.domain();
    let normalised = |x: Interval, r: [f64; 2]| -> Option<[f64; 2]> {
        let t = (x - point(r[0])) / (point(r[1]) - point(r[0]));
        let (lo, hi) = (t.inf().max(0.0), t.sup().min(1.0));
        (lo < hi).then_some([lo, hi])
    };
    let (mut s, mut r) = (normalised(u, d.u)?, normalised(v, d.v)?);
    let near: Vec<usize> = (0..4)
        .filter(|&k| poles[k].is_some())
        .filter(|&k| {
            let (x, w) = if k < 2 {
                (s, s[1] - s[0])
            } else {
                (r, r[1] - r[0])
            };
            let gap = if k % 2 == 0 { x[0] } else { 1.0 - x[1] };
            gap <= 4.0 * w
        })
        .collect();
    let [side] = near.as_slice() else {
        return None;
    };
    match side {
        0 => s[0] = 0.0,
        1 => s[1] = 1.0,
        2 => r[0] = 0.0,
        _ => r[1] = 1.0,
    }
    let piece = Piece::over(patch, s, r)?;
    collapsed_normal(&piece, *side, poles[*side]?)
}

/// The one pole of the two patches (the point of their collapsed sides), if they have one and
/// no other. The link proofs write both patches moved so that it is the origin
/// (`LeanPatch::moved`): there `P(σ, t) − X = t·G(σ, t)`, and the second partials in `σ` over a link's tube, which on the net as given
/// are differences of terms near `X` (each as wide as the tube's `σ` range), are `t` times
/// smaller. A link next to the pole then contracts although the rounding of the other
/// surface's point there leaves the curve's `σ` known only to about `1e-15/t`.
pub(crate) fn common_pole(p: &RationalBezierPatch, q: &RationalBezierPatch) -> Option<[f64; 3]> {
    let mut poles = p
        .collapsed_sides()
        .into_iter()
        .chain(q.collapsed_sides())
        .flatten();
    let x = poles.next()?;
    poles.all(|y| y == x).then_some(x)
}

/// `s` moved so that its (first) pole is the origin ([`RationalBezierPatch::translated`]),
/// if it has one: the same derivatives, enclosed far tighter next to the pole.
pub(crate) fn moved_to_pole(s: &RationalBezierPatch) -> Option<RationalBezierPatch> {
    s.translated(s.collapsed_sides().into_iter().flatten().next()?)
}

#[cfg(test)]
#[path = "pole/tests.rs"]
pub(crate) mod tests;

//! A pair of pieces whose height difference has critical points that are not isolated (a ring
//! of minima between two concentric loops, a line of contact), proven free of closed components
//! by covering its critical set.
//!
//! **The setting.** As for a node region ([`super::node_region`]): a parametric Krawczyk test
//! proves that for every `(σ, t)` of the piece `a` of P exactly one `(u, v)` of the piece `b` of
//! Q solves `G = (e₁·(P − Q), e₂·(P − Q)) = 0`, strictly inside `b`. Then `C ∩ (a × b)` is the
//! zero set of the smooth `f(σ, t) = n·(P − Q)` over the rectangle `a`, and the critical points of
//! `f` are the zeros of `Φ` (the points of parallel normals).
//!
//! **The cover.** The rectangle `a` is cut into cells (halving), each either *free* (the
//! Krawczyk image of `Φ` over the cell and its `(u, v)` box is disjoint from that box: no
//! critical point in the closed cell) or *signed* (`f` enclosed away from 0 on the closed cell).
//! Two signed cells are joined when the closed cells meet; every class of joined cells (a
//! connected set on which `f ≠ 0`) must hold a cell touching the boundary of `a`.
//!
//! **Why no closed component is left.** Every critical point lies in a signed cell, so `f ≠ 0`
//! there and `0` is a regular value of `f`: a component `K` of `{f = 0}` that does not reach
//! `∂a` is a smooth closed curve in the interior of `a`, bounding a disc `D` with `D̄` inside the
//! interior of `a`. `f` vanishes on `∂D = K` and not on all of `D` (an open set of zeros would
//! hold critical points with `f = 0`), so it has an extremum at a point `c` inside `D`, a
//! critical point. The class of signed cells holding `c` is connected, holds `c ∈ D` and a point
//! of `∂a` outside `D̄`, so it meets `∂D = K`, where `f = 0`: impossible, `f ≠ 0` on it. So
//! **every component of `C ∩ (a × b)` reaches `∂a × int b`**, which is what a loop-free pair of
//! the pair search asserts (its faces are searched next). A ring of critical points lying wholly
//! inside `a` leaves a class of signed cells away from `∂a`: the test fails there, as it must (a
//! loop round it is possible).
//!
//! A signed class need not follow a curve of critical points exactly: any connected set with
//! `f ≠ 0` from each critical point to `∂a` will do, so cells far from the critical set that are
//! signed anyway merely join the classes.

use super::node_region::{frame_at, graph_image, sign, Frame};
use crate::geometry::piece::{declared_range, Piece};
use crate::geometry::RationalBezierPatch;
use crate::numeric::rounding::dot_point;
use crate::numeric::scalar::point;
use crate::numeric::vec3::cross;
use crate::pair::field::ScalarSurface;
use crate::pair::krawczyk::krawczyk_image_n;
use inari::Interval;
use nalgebra::Matrix2;

/// Most cells examined per pair (each a few interval evaluations of both patches).
pub(super) const MAX_CELLS: usize = 5000;

/// Cells are not halved below this fraction of the piece's normalised width.
const MIN_CELL: f64 = 1.0 / (1u64 << 16) as f64;

/// Proves that every component of the intersection inside `a × b` (`a` a piece of `p`, `b` of
/// `q`) reaches `∂a × int b` (see the module documentation), examining at most `max_cells`
/// cells; false when not proven.
pub(super) fn prove_by_cover(
    p: &RationalBezierPatch,
    a: &Piece,
    q: &RationalBezierPatch,
    b: &Piece,
    max_cells: usize,
) -> bool {
    let (dp, dq) = (p.domain(), q.domain());
    let (xp, xq) = (a.declared(&dp, 0.0), b.declared(&dq, 0.0));
    let x0 = [xp[0].mid(), xp[1].mid(), xq[0].mid(), xq[1].mid()];
    let Some(e) = frame_at(p, &x0) else {
        return false;
    };
    let Some(uv) = graph_image(p, q, &e, &xp, &xq) else {
        return false;
    };
    // The graph: a unique (u, v) per (σ, t), kept a rounding margin inside b.
    let inside = uv.iter().zip(&xq).all(|(k, x)| {
        let margin = 1e-12 * (1.0 + x.mag());
        k.inf() > x.inf() + margin && k.sup() < x.sup() - margin
    });
    if !inside {
        return false;
    }
    let Some(signed) = cover(p, q, &e, a, uv, max_cells) else {
        return false;
    };
    classes_reach_boundary(&signed, a)
}

/// A cell of the cover: its normalised box.
#[derive(Clone, Copy, Debug)]
struct Cell {
    s: [f64; 2],
    r: [f64; 2],
}

/// Cuts `a` into free and signed cells (module documentation); the signed ones, or `None` when
/// a cell is neither at the smallest size or the cell budget is spent. `uv` encloses the
/// `(u, v)` of every point of `a`.
fn cover(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    e: &Frame,
    a: &Piece,
    uv: [Interval; 2],
    max_cells: usize,
) -> Option<Vec<(Cell, bool)>> {
    let dp = p.domain();
    let min = [MIN_CELL * (a.s[1] - a.s[0]), MIN_CELL * (a.r[1] - a.r[0])];
    let mut stack = vec![(Cell { s: a.s, r: a.r }, uv)];
    let mut signed: Vec<(Cell, bool)> = Vec::new();
    let mut examined = 0;
    while let Some((cell, parent)) = stack.pop() {
        examined += 1;
        if examined > max_cells {
            return None;
        }
        let xc = [
            declared_range(dp.u, cell.s, 0.0),
            declared_range(dp.v, cell.r, 0.0),
        ];
        let (verdict, uv) = examine(p, q, e, &xc, &parent)?;
        match verdict {
            Verdict { signed: true, free } => {
                signed.push((cell, !free));
                continue;
            }
            Verdict { free: true, .. } => continue,
            _ => {}
        }
        let (ws, wr) = (cell.s[1] - cell.s[0], cell.r[1] - cell.r[0]);
        if ws <= min[0] && wr <= min[1] {
            return None;
        }
        // Halve the side that is longer in declared parameters.
        let split_s = wr <= min[1] || (ws > min[0] && xc[0].wid() >= xc[1].wid());
        let halves = if split_s {
            let m = 0.5 * (cell.s[0] + cell.s[1]);
            [[cell.s[0], m], [m, cell.s[1]]].map(|s| Cell { s, r: cell.r })
        } else {
            let m = 0.5 * (cell.r[0] + cell.r[1]);
            [[cell.r[0], m], [m, cell.r[1]]].map(|r| Cell { s: cell.s, r })
        };
        stack.extend(halves.map(|c| (c, uv)));
    }
    Some(signed)
}

/// What is proven of one cell.
struct Verdict {
    /// No point of the intersection over the cell: `f ≠ 0` on it.
    signed: bool,
    /// The normals are nowhere parallel over the cell: no critical point of `f`.
    free: bool,
}

/// Examines the cell `xc` (declared parameters of P) whose points have their `(u, v)` in
/// `parent`: its verdict and a (tighter) box of those `(u, v)`; `None` when the enclosures fail.
///
/// The `(u, v)` box is the parametric Krawczyk image of `G = 0` (as in
/// [`graph_image`](super::node_region::graph_image), with first-order enclosures over the
/// boxes). *Signed*: a point of `C` over the cell has its `(u, v)` in that box, so a direction
/// `m` with `m·(P(x) − Q(y)) ≠ 0` for all `x` in the cell and `y` in the box proves there is none
/// (mean-value form about the box centre; `m` the mean of the two unit normals there, along
/// which the two surfaces are nearly level). *Free*: a critical point of `f` has parallel
/// normals, so a component of `N_P × N_Q` enclosed away from zero proves there is none.
fn examine(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    e: &Frame,
    xc: &[Interval; 2],
    parent: &[Interval; 2],
) -> Option<(Verdict, [Interval; 2])> {
    let mp = xc.map(|i| point(i.mid()));
    let cq = parent.map(|i| point(i.mid()));
    let [pm, pms, pmt] = p.first_order(mp[0], mp[1]);
    let [qc, ..] = q.first_order(cq[0], cq[1]);
    // P's first and second partials over the cell, once for the graph's and the signs' tests.
    let sp = p.second_order(xc[0], xc[1]);
    let [_, ps, pt, ..] = sp;
    let [_, qu, qv] = q.first_order(parent[0], parent[1]);
    // Krawczyk image of G(σ, t, ·) over `parent`, for all (σ, t) in the cell.
    let gap: [Interval; 3] = std::array::from_fn(|k| pm[k] - qc[k]);
    let g: [Interval; 2] = std::array::from_fn(|i| dot_point(&e[i], &gap));
    let jp: [[Interval; 2]; 2] =
        std::array::from_fn(|i| [dot_point(&e[i], &ps), dot_point(&e[i], &pt)]);
    let jq: [[Interval; 2]; 2] =
        std::array::from_fn(|i| [-dot_point(&e[i], &qu), -dot_point(&e[i], &qv)]);
    let c = Matrix2::from_fn(|r, k| jq[r][k].mid()).try_inverse()?;
    let c = [[c[(0, 0)], c[(0, 1)]], [c[(1, 0)], c[(1, 1)]]];
    let k = krawczyk_image_n(parent, &cq, &g, &jq, &c);
    let mut uv: [Interval; 2] = std::array::from_fn(|r| {
        let mut acc = k[r];
        for col in 0..2 {
            let cj = point(c[r][0]) * jp[0][col] + point(c[r][1]) * jp[1][col];
            acc -= cj * (xc[col] - mp[col]);
        }
        acc
    });
    // First-order enclosures over a wide box wrap: where the image is not clearly narrower
    // than the box in either direction (a halved cell halves one), the centred forms of
    // `graph_image` (dearer) are used instead.
    let shrinks = |k: &[Interval; 2]| k.iter().zip(parent).any(|(k, x)| k.wid() <= 0.75 * x.wid());
    if !shrinks(&uv) {
        uv = graph_image(p, q, e, xc, parent)?;
    }
    let uv: [Interval; 2] = std::array::from_fn(|r| uv[r].intersection(parent[r]));
    if uv.iter().any(|x| x.is_empty()) {
        // No (u, v) in `parent` for some point: impossible once the graph is proven.
        return None;
    }
    // Signed: m·(P − Q) over the cell × uv, about the centre (Q's partials over `parent`).
    let cu = uv.map(|i| point(i.mid()));
    let [qm, qmu, qmv] = q.first_order(cu[0], cu[1]);
    let unit = |a: &[Interval; 3], b: &[Interval; 3]| {
        let n = cross(&a.map(|x| x.mid()), &b.map(|x| x.mid()));
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        n.map(|x| x / l)
    };
    let (np, nq) = (unit(&pms, &pmt), unit(&qmu, &qmv));
    let flip = if np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2] < 0.0 {
        -1.0
    } else {
        1.0
    };
    let m: [f64; 3] = std::array::from_fn(|k| np[k] + flip * nq[k]);
    let sq = q.second_order(uv[0], uv[1]);
    let mut signed = false;
    if m.iter().all(|x| x.is_finite()) && m.iter().any(|&x| x != 0.0) {
        // Second-order Taylor form with the Hessian enclosed over the boxes.
        let gap: [Interval; 3] = std::array::from_fn(|k| pm[k] - qm[k]);
        let (ds, dt) = (xc[0] - mp[0], xc[1] - mp[1]);
        let (du, dv) = (uv[0] - cu[0], uv[1] - cu[1]);
        let half = point(0.5);
        let along = |x: &[Interval; 3]| dot_point(&m, x);
        let value =
            along(&gap) + along(&pms) * ds + along(&pmt) * dt - along(&qmu) * du - along(&qmv) * dv
                + half * (along(&sp[3]) * ds.sqr() + along(&sp[5]) * dt.sqr())
                + along(&sp[4]) * (ds * dt)
                - half * (along(&sq[3]) * du.sqr() + along(&sq[5]) * dv.sqr())
                - along(&sq[4]) * (du * dv);
        signed = sign(value).is_some();
    }
    // Free: N_P × N_Q away from zero over the cell × uv, by the mean-value form about the
    // centre (normals and their partials enclosed over the boxes).
    let t = normals_cross(
        [&pms, &pmt, &qmu, &qmv],
        &sp,
        &sq,
        [ds0(xc, &mp), ds0(&uv, &cu)],
    );
    let free = t.iter().any(|x| sign(*x).is_some());
    Some((Verdict { signed, free }, uv))
}

/// The offsets `x − m` of a box from its centre.
fn ds0(x: &[Interval; 2], m: &[Interval; 2]) -> [Interval; 2] {
    [x[0] - m[0], x[1] - m[1]]
}

/// An enclosure of `N_P × N_Q` over a box of `(σ, t, u, v)` by the mean-value form about its
/// centre: `centre` the partials `P_σ, P_t, Q_u, Q_v` there, `sp`, `sq` the second-order data
/// of P and Q over the box, `off` the offsets of the box from the centre.
fn normals_cross(
    centre: [&[Interval; 3]; 4],
    sp: &[[Interval; 3]; 6],
    sq: &[[Interval; 3]; 6],
    off: [[Interval; 2]; 2],
) -> [Interval; 3] {
    let [ps, pt, qu, qv] = centre;
    let centre = cross(&cross(ps, pt), &cross(qu, qv));
    let [_, ps, pt, pss, pst, ptt] = sp;
    let [_, qu, qv, quu, quv, qvv] = sq;
    let add = |a: [Interval; 3], b: [Interval; 3]| -> [Interval; 3] {
        std::array::from_fn(|k| a[k] + b[k])
    };
    let (np, nq) = (cross(ps, pt), cross(qu, qv));
    let parts = [
        (cross(&add(cross(pss, pt), cross(ps, pst)), &nq), off[0][0]),
        (cross(&add(cross(pst, pt), cross(ps, ptt)), &nq), off[0][1]),
        (cross(&np, &add(cross(quu, qv), cross(qu, quv))), off[1][0]),
        (cross(&np, &add(cross(quv, qv), cross(qu, qvv))), off[1][1]),
    ];
    std::array::from_fn(|k| {
        parts
            .iter()
            .fold(centre[k], |acc, (d, off)| acc + d[k] * *off)
    })
}

/// Whether every class of signed cells joined by meeting (closed) cells holds a cell on the
/// boundary of `a`.
fn classes_reach_boundary(cells: &[(Cell, bool)], a: &Piece) -> bool {
    let mut order: Vec<usize> = (0..cells.len()).collect();
    let critical: Vec<bool> = cells.iter().map(|c| c.1).collect();
    let cells: Vec<Cell> = cells.iter().map(|c| c.0).collect();
    order.sort_by(|&i, &j| cells[i].s[0].total_cmp(&cells[j].s[0]));
    let mut parent: Vec<usize> = (0..cells.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if cells[j].s[0] > cells[i].s[1] {
                break;
            }
            let meet = cells[j].r[0] <= cells[i].r[1] && cells[i].r[0] <= cells[j].r[1];
            if meet {
                let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                parent[ri] = rj;
            }
        }
    }
    let on_boundary =
        |c: &Cell| c.s[0] == a.s[0] || c.s[1] == a.s[1] || c.r[0] == a.r[0] || c.r[1] == a.r[1];
    let mut reaches = vec![false; cells.len()];
    for (i, c) in cells.iter().enumerate() {
        if on_boundary(c) {
            let r = root(&mut parent, i);
            reaches[r] = true;
        }
    }
    (0..cells.len()).all(|i| {
        let r = root(&mut parent, i);
        reaches[r] || !critical[i]
    })
}

#[cfg(test)]
#[path = "critical_cover_tests.rs"]
mod tests;

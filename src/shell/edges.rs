//! Which Bézier pieces of a shell share an edge.
//!
//! Two kinds of shared edge are recognised:
//!
//! - **knot lines**: two pieces of one face whose knot spans touch (the same span in one
//!   direction, neighbouring spans in the other). Both pieces are the same NURBS surface on the
//!   knot line and use the face's own parameters, so the edge parameter is the same on both
//!   sides.
//! - **matched edges**: a boundary row of one piece's control net equal to another boundary row
//!   of the same or another piece (the same degree; every homogeneous control interval equal,
//!   in the same or the reverse order). This finds periodic seams (a closed NURBS surface whose
//!   first and last control rows coincide, or one closed Bézier piece) and edges shared by two
//!   faces. Rows are bucketed by their two end points, so the search is near linear. The two edges are then the same
//!   rational Bézier curve, and the edge parameters correspond affinely (each edge's parameter
//!   normalised to `[0, 1]`, reversed when the rows are). Rows whose points all coincide (a
//!   pole) are not edges and are never matched. For interval control data, equal intervals
//!   are read as the same data on both sides (the scene's topology); nothing else is inferred.
//!
//! The side of a piece is `0` for `u = u0`, `1` for `u = u1`, `2` for `v = v0`, `3` for
//! `v = v1`.

use std::collections::{HashMap, HashSet};

use inari::Interval;

use super::Face;
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::surface::Domain;
use crate::numeric::scalar::point;

/// How two pieces came to share an edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeKind {
    /// A knot line inside one NURBS face.
    KnotLine,
    /// Equal boundary control rows in one face (a periodic seam).
    Seam,
    /// Equal boundary control rows in two faces.
    FaceEdge,
    /// Sides of two pieces whose control rows agree only to within a small distance (faces whose
    /// corners were computed apart and rounded differently): not the same curve, so a curve
    /// crossing there passes from one piece to the other with a gap, which its join proves
    /// small and counts in the joined curve's tolerance ([`near_edges`]).
    NearEdge,
    /// Two sides collapsed to the same pole (of one face, or of faces of one shell sharing it):
    /// not an edge, but where a curve through the pole passes from one piece to another (such
    /// a join is proven on a cap round the pole, `shell/pole_cap.rs`).
    Pole,
}

impl EdgeKind {
    /// `"knot_line"`, `"seam"`, `"face_edge"`, `"near_edge"` or `"pole"`.
    pub fn name(self) -> &'static str {
        match self {
            EdgeKind::KnotLine => "knot_line",
            EdgeKind::Seam => "seam",
            EdgeKind::FaceEdge => "face_edge",
            EdgeKind::NearEdge => "near_edge",
            EdgeKind::Pole => "pole",
        }
    }
}

/// One side of one piece of a shell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PieceSide {
    /// The face.
    pub face: usize,
    /// The piece of that face.
    pub piece: usize,
    /// The side: 0 `u = u0`, 1 `u = u1`, 2 `v = v0`, 3 `v = v1`.
    pub side: usize,
}

/// A shared edge seen from one of its two sides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeLink {
    /// The side this link starts from.
    pub from: PieceSide,
    /// The side of the neighbouring piece across the edge.
    pub to: PieceSide,
    /// Whether the edge parameter runs the other way on `to`.
    pub reversed: bool,
    /// How the edge was recognised.
    pub kind: EdgeKind,
}

/// The parameter index (0 for u, 1 for v) held fixed on `side`, and its value.
pub fn side_coordinate(d: &Domain, side: usize) -> (usize, f64) {
    match side {
        0 => (0, d.u[0]),
        1 => (0, d.u[1]),
        2 => (1, d.v[0]),
        _ => (1, d.v[1]),
    }
}

/// The range `[lo, hi]` of the parameter that runs along `side`.
pub fn along_range(d: &Domain, side: usize) -> [f64; 2] {
    if side < 2 {
        d.v
    } else {
        d.u
    }
}

/// The side of `d` that the parameter point `x` lies on, within `tol` (the nearest one when
/// several are that close); `None` when it is on none.
pub fn side_of(d: &Domain, x: [f64; 2], tol: f64) -> Option<usize> {
    side_of_where(d, x, tol, |_| true)
}

/// As [`side_of`], among the sides `keep` accepts.
pub(crate) fn side_of_where(
    d: &Domain,
    x: [f64; 2],
    tol: f64,
    keep: impl Fn(usize) -> bool,
) -> Option<usize> {
    (0..4)
        .filter(|&side| keep(side))
        .map(|side| {
            let (k, value) = side_coordinate(d, side);
            (side, (x[k] - value).abs())
        })
        .filter(|&(_, gap)| gap <= tol)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(side, _)| side)
}

impl EdgeLink {
    /// The parameter along `to` of the parameter `t` along `from` (as an interval, rounded
    /// outward), given the two pieces' domains.
    pub fn map_along(&self, t: Interval, from: &Domain, to: &Domain) -> Interval {
        let [a0, a1] = along_range(from, self.from.side);
        let [b0, b1] = along_range(to, self.to.side);
        if self.kind == EdgeKind::KnotLine {
            return t;
        }
        let pt = point;
        let lambda = (t - pt(a0)) / (pt(a1) - pt(a0));
        let lambda = if self.reversed {
            pt(1.0) - lambda
        } else {
            lambda
        };
        pt(b0) + lambda * (pt(b1) - pt(b0))
    }
}

/// The homogeneous control points of `side` of `p`, in the order of increasing edge parameter.
fn side_row(p: &RationalBezierPatch, side: usize) -> Vec<[Interval; 4]> {
    let [m, n] = p.degree();
    let h = p.homogeneous();
    match side {
        0 => (0..=n).map(|j| h[j]).collect(),
        1 => (0..=n).map(|j| h[m * (n + 1) + j]).collect(),
        2 => (0..=m).map(|i| h[i * (n + 1)]).collect(),
        _ => (0..=m).map(|i| h[i * (n + 1) + n]).collect(),
    }
}

/// Whether two homogeneous control intervals are the same set.
fn same(a: &[Interval; 4], b: &[Interval; 4]) -> bool {
    a.iter()
        .zip(b)
        .all(|(x, y)| x.inf() == y.inf() && x.sup() == y.sup())
}

/// The bits of a homogeneous control interval (its bounds), for hashing.
type PointKey = [u64; 8];

fn point_key(h: &[Interval; 4]) -> PointKey {
    std::array::from_fn(|k| {
        let x = h[k / 2];
        if k % 2 == 0 {
            x.inf().to_bits()
        } else {
            x.sup().to_bits()
        }
    })
}

/// Both links of a shared edge between `a` and `b`.
fn link_both(
    links: &mut Vec<EdgeLink>,
    a: PieceSide,
    b: PieceSide,
    reversed: bool,
    kind: EdgeKind,
) {
    for (from, to) in [(a, b), (b, a)] {
        links.push(EdgeLink {
            from,
            to,
            reversed,
            kind,
        });
    }
}

/// Every shared edge of the shell `faces`, from both of its sides, sorted by `from`.
pub fn shared_edges(faces: &[Face]) -> Vec<EdgeLink> {
    let mut links = Vec::new();
    // Knot lines: pieces of one face whose spans touch (found by their domains' exact bounds).
    for (f, face) in faces.iter().enumerate() {
        let side = |piece, side| PieceSide {
            face: f,
            piece,
            side,
        };
        let bits = |x: [f64; 2]| x.map(f64::to_bits);
        let mut left = HashMap::new();
        let mut below = HashMap::new();
        for (j, b) in face.pieces().iter().enumerate() {
            let d = b.domain();
            left.insert((d.u[0].to_bits(), bits(d.v)), j);
            below.insert((d.v[0].to_bits(), bits(d.u)), j);
        }
        for (i, a) in face.pieces().iter().enumerate() {
            let d = a.domain();
            if let Some(&j) = left.get(&(d.u[1].to_bits(), bits(d.v))) {
                link_both(
                    &mut links,
                    side(i, 1),
                    side(j, 0),
                    false,
                    EdgeKind::KnotLine,
                );
            }
            if let Some(&j) = below.get(&(d.v[1].to_bits(), bits(d.u))) {
                link_both(
                    &mut links,
                    side(i, 3),
                    side(j, 2),
                    false,
                    EdgeKind::KnotLine,
                );
            }
        }
    }
    let knot_lines: HashSet<(PieceSide, PieceSide)> =
        links.iter().map(|l| (l.from, l.to)).collect();
    // Matched edges: equal boundary rows (not poles), bucketed by their two end points.
    let mut rows = Vec::new();
    let mut buckets: HashMap<(usize, PointKey, PointKey), Vec<usize>> = HashMap::new();
    for (f, face) in faces.iter().enumerate() {
        for (k, p) in face.pieces().iter().enumerate() {
            for side in 0..4 {
                let row = side_row(p, side);
                // A side known to collapse (`collapsed_sides`: exact equal rows of Cartesian
                // points, whatever the weights' rounding), or whose homogeneous points agree.
                let pole = p.collapsed_sides()[side].is_some()
                    || row.windows(2).all(|w| {
                        (0..3).all(|c| {
                            // The Cartesian points coincide when w·x/w agree as intervals.
                            let a = w[0][c] / w[0][3];
                            let b = w[1][c] / w[1][3];
                            a.inf() == b.inf() && a.sup() == b.sup()
                        })
                    });
                if pole {
                    continue;
                }
                let (first, last) = (point_key(&row[0]), point_key(&row[row.len() - 1]));
                let key = (row.len(), first.min(last), first.max(last));
                buckets.entry(key).or_default().push(rows.len());
                rows.push((
                    PieceSide {
                        face: f,
                        piece: k,
                        side,
                    },
                    row,
                ));
            }
        }
    }
    let mut keys: Vec<_> = buckets.keys().copied().collect();
    keys.sort_unstable();
    for key in keys {
        let bucket = &buckets[&key];
        for (x, &i) in bucket.iter().enumerate() {
            for &j in &bucket[x + 1..] {
                let ((a, ra), (b, rb)) = (&rows[i], &rows[j]);
                if knot_lines.contains(&(*a, *b)) {
                    continue;
                }
                let direct = ra.iter().zip(rb).all(|(p, q)| same(p, q));
                let reversed = !direct && ra.iter().zip(rb.iter().rev()).all(|(p, q)| same(p, q));
                if !(direct || reversed) {
                    continue;
                }
                let kind = if a.face == b.face {
                    EdgeKind::Seam
                } else {
                    EdgeKind::FaceEdge
                };
                link_both(&mut links, *a, *b, reversed, kind);
            }
        }
    }
    links.sort_by_key(|l| (l.from, l.to));
    links
}

/// A side matched to another only to within a distance ([`near_edges`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearLink {
    /// The link, of kind [`EdgeKind::NearEdge`].
    pub link: EdgeLink,
    /// A proven bound on the model distance between the two sides' points at corresponding
    /// edge parameters.
    pub mismatch: f64,
}

/// Most boundary rows compared for near matches (more: none are looked for).
const MAX_NEAR_ROWS: usize = 1 << 16;

/// Sides of pieces of `faces` that no exact link joins ([`shared_edges`]: `exact`) whose boundary
/// rows have the same length and the same weights, and whose Cartesian control points lie
/// pairwise within `within` (in the same or the reverse order), from both sides, sorted by
/// `from`. With equal weights every point of the one side is the same convex combination of
/// its control points as the matching point of the other, so the two sides are within the
/// largest control-point distance (`mismatch`, rounded up) at corresponding edge parameters.
/// Poles (and rows whose points lie within `within` of each other) are never matched;
/// `within` ≤ 0 matches nothing.
pub fn near_edges(faces: &[Face], exact: &[EdgeLink], within: f64) -> Vec<NearLink> {
    let mut out = Vec::new();
    if within.is_nan() || within <= 0.0 {
        return out;
    }
    let linked: HashSet<PieceSide> = exact.iter().map(|l| l.from).collect();
    let mut rows: Vec<(PieceSide, Vec<[Interval; 4]>)> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        for (k, p) in face.pieces().iter().enumerate() {
            for (side, pole) in p.collapsed_sides().iter().enumerate() {
                let at = PieceSide {
                    face: f,
                    piece: k,
                    side,
                };
                let row = side_row(p, side);
                // A row whose points all lie within the distance of its first is a pole, or
                // nearly one: not an edge.
                let degenerate = row_distance(row.iter(), std::iter::repeat_n(&row[0], row.len()))
                    .is_some_and(|d| d <= within);
                if pole.is_none() && !degenerate && !linked.contains(&at) {
                    rows.push((at, row));
                }
            }
        }
    }
    if rows.len() > MAX_NEAR_ROWS {
        return out;
    }
    // Rows by the grid cells (of twice `within`) of both end points: a near match's first end
    // point lies in a cell next to one of the other row's.
    let cell_size = 2.0 * within;
    let cell = |h: &[Interval; 4]| -> Option<[i64; 3]> {
        let c: [f64; 3] = std::array::from_fn(|k| (h[k] / h[3]).mid() / cell_size);
        c.iter()
            .all(|x| x.is_finite() && x.abs() < 1e15)
            .then(|| c.map(|x| x.floor() as i64))
    };
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (i, (_, row)) in rows.iter().enumerate() {
        for end in [&row[0], &row[row.len() - 1]] {
            if let Some(c) = cell(end) {
                grid.entry(c).or_default().push(i);
            }
        }
    }
    for (i, (a, ra)) in rows.iter().enumerate() {
        let Some(c) = cell(&ra[0]) else {
            continue;
        };
        let mut near: Vec<usize> = (0..27)
            .filter_map(|n| {
                let d = [n % 3, (n / 3) % 3, n / 9].map(|x| x as i64 - 1);
                grid.get(&std::array::from_fn(|k| c[k] + d[k]))
            })
            .flatten()
            .copied()
            .filter(|&j| j > i)
            .collect();
        near.sort_unstable();
        near.dedup();
        for j in near {
            let (b, rb) = &rows[j];
            if ra.len() != rb.len() || (a.face == b.face && a.piece == b.piece) {
                continue;
            }
            let direct = row_distance(ra.iter(), rb.iter());
            let reversed = row_distance(ra.iter(), rb.iter().rev());
            let (mismatch, rev) = match (direct, reversed) {
                (Some(d), Some(r)) if r < d => (r, true),
                (Some(d), _) => (d, false),
                (None, Some(r)) => (r, true),
                (None, None) => continue,
            };
            if mismatch > within {
                continue;
            }
            for (from, to) in [(*a, *b), (*b, *a)] {
                out.push(NearLink {
                    link: EdgeLink {
                        from,
                        to,
                        reversed: rev,
                        kind: EdgeKind::NearEdge,
                    },
                    mismatch,
                });
            }
        }
    }
    out.sort_by_key(|l| (l.link.from, l.link.to));
    out
}

/// The largest Euclidean distance between corresponding Cartesian control points of two rows
/// (rounded up), or `None` when a weight differs or a point is not finite.
fn row_distance<'a>(
    a: impl Iterator<Item = &'a [Interval; 4]>,
    b: impl Iterator<Item = &'a [Interval; 4]>,
) -> Option<f64> {
    let mut worst = 0.0f64;
    for (x, y) in a.zip(b) {
        if x[3].inf() != y[3].inf() || x[3].sup() != y[3].sup() {
            return None;
        }
        let d: [Interval; 3] = std::array::from_fn(|k| x[k] / x[3] - y[k] / y[3]);
        let sq = d.iter().fold(point(0.0), |acc, v| acc + v.sqr());
        let dist = sq.sup().sqrt();
        if !dist.is_finite() {
            return None;
        }
        // The square root rounded up by an ulp.
        worst = worst.max(dist.next_up());
    }
    Some(worst)
}

#[cfg(test)]
#[path = "edges_tests.rs"]
mod tests;

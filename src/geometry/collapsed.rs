//! Sides of a control net that are one exact point: where a patch collapses a whole side to a
//! pole (see [`crate::geometry::pole`] for what the rest of the crate does there).

use crate::geometry::Vec3;
use inari::Interval;

/// The net indices `i*(n+1)+j` of side `side` of a net of degree `[m, n]` (`u = u0`, `u = u1`,
/// `v = v0`, `v = v1`), in order along it.
fn side_indices(degree: [usize; 2], side: usize) -> Vec<usize> {
    let [m, n] = degree;
    match side {
        0 => (0..=n).collect(),
        1 => (0..=n).map(|j| m * (n + 1) + j).collect(),
        2 => (0..=m).map(|i| i * (n + 1)).collect(),
        _ => (0..=m).map(|i| i * (n + 1) + n).collect(),
    }
}

/// The sides of a net of degree `degree` with Cartesian control points `points` whose row is
/// one exact point, with that point (indexed `u = u0`, `u = u1`, `v = v0`, `v = v1`): the patch
/// maps such a side to the point, whatever its weights.
pub(crate) fn collapsed_rows(
    degree: [usize; 2],
    points: &[[Interval; 3]],
) -> [Option<[f64; 3]>; 4] {
    std::array::from_fn(|side| {
        let row = side_indices(degree, side);
        let first = &points[row[0]];
        let exact = |p: &[Interval; 3]| p.iter().all(|x| x.inf() == x.sup());
        (row.iter()
            .all(|&k| exact(&points[k]) && points[k] == *first))
        .then(|| first.map(|x| x.inf()))
    })
}

/// The distinct points of `collapsed` (a patch's collapsed sides), as vectors.
pub(crate) fn distinct_poles(collapsed: &[Option<[f64; 3]>; 4]) -> Vec<Vec3> {
    let mut out: Vec<Vec3> = Vec::new();
    for x in collapsed.iter().flatten() {
        let x = Vec3::new(x[0], x[1], x[2]);
        if !out.contains(&x) {
            out.push(x);
        }
    }
    out
}

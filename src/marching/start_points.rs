//! Start points for every branch of the intersection of two patches.
//!
//! Two searches, both subdivision with rigorous bounding-box exclusion followed by Newton:
//! - **boundary points**: each of the four boundary curves of each patch against the other patch
//!   (a curve/surface problem: 3 equations in 3 unknowns), which gives both ends of every open
//!   branch;
//! - **interior candidates**: pairs of sub-patches whose enclosures overlap, refined down to a
//!   leaf size, then projected onto the intersection by Gauss–Newton. Closed loops lying wholly
//!   inside both domains are found here.
//!
//! A box pair is discarded only when its interval enclosures are disjoint, which proves it holds
//! no intersection. Leaves where Newton fails are counted as *undecided* and reported, never
//! silently dropped.

use crate::geometry::enclosing::{boxes_disjoint, EnclosingSurface};
use crate::geometry::{Domain, Vec3};
use crate::scalar::interval;
use inari::Interval;
use nalgebra::{Matrix3, Matrix3x4, Vector3};

/// Tuning of the start-point search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchOptions {
    /// Leaf size as a fraction of the larger model extent of the two patches.
    pub leaf_fraction: f64,
    /// Upper bound on leaves examined per search (protects against tangential surfaces, where
    /// exclusion never succeeds); hitting it is reported in [`SearchReport::truncated`].
    pub max_leaves: usize,
    /// Newton converges when the model-space residual is below this (relative to model size).
    pub residual_tol: f64,
}

impl Default for SearchOptions {
    fn default() -> Self {
        SearchOptions {
            leaf_fraction: 1.0 / 64.0,
            max_leaves: 200_000,
            residual_tol: 1e-12,
        }
    }
}

/// Where a start point came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StartKind {
    /// On the boundary of surface `surface` (0 = P, 1 = Q).
    Boundary {
        /// 0 for P, 1 for Q.
        surface: usize,
    },
    /// Inside both domains (a candidate for a closed loop or a missed branch).
    Interior,
}

/// A point on the intersection: parameters `(σ, t, u, v)`, refined by Newton.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartPoint {
    /// `(σ, t)` on P then `(u, v)` on Q.
    pub params: [f64; 4],
    /// Where it came from.
    pub kind: StartKind,
}

/// Result of the start-point search.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SearchReport {
    /// Points on a boundary of either patch, deduplicated.
    pub boundary: Vec<StartPoint>,
    /// Interior points, one or more per surviving leaf pair (not deduplicated against branches).
    pub interior: Vec<StartPoint>,
    /// Leaf boxes examined.
    pub leaves: usize,
    /// Leaf boxes whose enclosures overlapped but where Newton found no point (undecided).
    pub undecided: usize,
    /// The leaf budget ran out: some regions were not examined.
    pub truncated: bool,
}

/// Finds boundary start points and interior candidates for the intersection of `p` and `q`.
pub fn find_start_points<P, Q>(p: &P, q: &Q, opts: &SearchOptions) -> SearchReport
where
    P: EnclosingSurface,
    Q: EnclosingSurface,
{
    let (dp, dq) = (p.domain(), q.domain());
    let size = diameter(&p.enclose(range(dp.u), range(dp.v)))
        .max(diameter(&q.enclose(range(dq.u), range(dq.v))))
        .max(f64::MIN_POSITIVE);
    let ctx = Ctx {
        leaf: size * opts.leaf_fraction,
        tol: opts.residual_tol * size.max(1.0),
        max_leaves: opts.max_leaves,
    };
    let mut report = SearchReport::default();
    for edge in edges(dp) {
        search_edge(&ctx, p, q, edge, false, &mut report);
    }
    for edge in edges(dq) {
        search_edge(&ctx, q, p, edge, true, &mut report);
    }
    dedup(&mut report.boundary, dp, dq);
    search_interior(&ctx, p, q, &mut report);
    report
}

struct Ctx {
    leaf: f64,
    tol: f64,
    max_leaves: usize,
}

/// A boundary curve of a domain: parameter `fixed_index` (0 = first, 1 = second) held at `value`,
/// the other running over `run`.
#[derive(Debug, Clone, Copy)]
struct Edge {
    fixed_index: usize,
    value: f64,
    run: [f64; 2],
}

fn edges(d: Domain) -> [Edge; 4] {
    [
        Edge {
            fixed_index: 0,
            value: d.u[0],
            run: d.v,
        },
        Edge {
            fixed_index: 0,
            value: d.u[1],
            run: d.v,
        },
        Edge {
            fixed_index: 1,
            value: d.v[0],
            run: d.u,
        },
        Edge {
            fixed_index: 1,
            value: d.v[1],
            run: d.u,
        },
    ]
}

impl Edge {
    fn params(&self, s: f64) -> (f64, f64) {
        if self.fixed_index == 0 {
            (self.value, s)
        } else {
            (s, self.value)
        }
    }
    fn params_box(&self, s: Interval) -> (Interval, Interval) {
        let fixed = interval(self.value, self.value).unwrap_or(Interval::ENTIRE);
        if self.fixed_index == 0 {
            (fixed, s)
        } else {
            (s, fixed)
        }
    }
}

fn range(r: [f64; 2]) -> Interval {
    interval(r[0], r[1]).unwrap_or(Interval::ENTIRE)
}

fn diameter(b: &[Interval; 3]) -> f64 {
    b.iter().map(|x| x.wid()).fold(0.0, f64::max)
}

fn mid(r: [f64; 2]) -> f64 {
    0.5 * (r[0] + r[1])
}

fn halves(r: [f64; 2]) -> [[f64; 2]; 2] {
    let m = mid(r);
    [[r[0], m], [m, r[1]]]
}

/// Searches one boundary curve of `a` against surface `b`. `swapped` says `a` is Q.
fn search_edge<A, B>(ctx: &Ctx, a: &A, b: &B, edge: Edge, swapped: bool, report: &mut SearchReport)
where
    A: EnclosingSurface,
    B: EnclosingSurface,
{
    let db = b.domain();
    let mut stack = vec![(edge.run, db.u, db.v)];
    while let Some((s, bu, bv)) = stack.pop() {
        let (au, av) = edge.params_box(range(s));
        let ea = a.enclose(au, av);
        let eb = b.enclose(range(bu), range(bv));
        if boxes_disjoint(&ea, &eb) {
            continue;
        }
        let (wa, wb) = (diameter(&ea), diameter(&eb));
        if wa <= ctx.leaf && wb <= ctx.leaf {
            report.leaves += 1;
            if report.leaves > ctx.max_leaves {
                report.truncated = true;
                return;
            }
            match edge_newton(a, b, edge, [mid(s), mid(bu), mid(bv)], ctx.tol) {
                Some([s0, u0, v0]) if inside(s0, edge.run) && db.contains(u0, v0, 1e-12) => {
                    let (a0, a1) = edge.params(s0.clamp(edge.run[0], edge.run[1]));
                    let params = if swapped {
                        [u0, v0, a0, a1]
                    } else {
                        [a0, a1, u0, v0]
                    };
                    report.boundary.push(StartPoint {
                        params,
                        kind: StartKind::Boundary {
                            surface: usize::from(swapped),
                        },
                    });
                }
                Some(_) => {}
                None => report.undecided += 1,
            }
            continue;
        }
        if wa >= wb {
            for h in halves(s) {
                stack.push((h, bu, bv));
            }
        } else {
            for hu in halves(bu) {
                for hv in halves(bv) {
                    stack.push((s, hu, hv));
                }
            }
        }
    }
}

fn inside(x: f64, r: [f64; 2]) -> bool {
    let tol = 1e-12 * (r[1] - r[0]).abs().max(1.0);
    x >= r[0] - tol && x <= r[1] + tol
}

/// Newton on `A(edge(s)) − B(u, v) = 0` in the unknowns `(s, u, v)`.
fn edge_newton<A, B>(a: &A, b: &B, edge: Edge, mut x: [f64; 3], tol: f64) -> Option<[f64; 3]>
where
    A: EnclosingSurface,
    B: EnclosingSurface,
{
    for _ in 0..40 {
        let (au, av) = edge.params(x[0]);
        let da = a.derivs(au, av);
        let db = b.derivs(x[1], x[2]);
        let f: Vec3 = da.p - db.p;
        let ds = if edge.fixed_index == 0 { da.sv } else { da.su };
        let jac = Matrix3::from_columns(&[ds, -db.su, -db.sv]);
        let step = jac.lu().solve(&f)?;
        for (xi, si) in x.iter_mut().zip(step.iter()) {
            *xi -= si;
        }
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        if f.norm() <= tol && step.norm() <= 1e-10 {
            return Some(x);
        }
        if step.norm() <= 1e-15 * (1.0 + x.iter().map(|v| v.abs()).fold(0.0, f64::max)) {
            let (au, av) = edge.params(x[0]);
            let r = (a.point(au, av) - b.point(x[1], x[2])).norm();
            return (r <= tol).then_some(x);
        }
    }
    None
}

/// Pair subdivision of both patches; a Gauss–Newton projection at every surviving leaf pair.
fn search_interior<P, Q>(ctx: &Ctx, p: &P, q: &Q, report: &mut SearchReport)
where
    P: EnclosingSurface,
    Q: EnclosingSurface,
{
    let (dp, dq) = (p.domain(), q.domain());
    let mut stack = vec![(dp.u, dp.v, dq.u, dq.v)];
    let budget = report.leaves + ctx.max_leaves;
    while let Some((pu, pv, qu, qv)) = stack.pop() {
        let ep = p.enclose(range(pu), range(pv));
        let eq = q.enclose(range(qu), range(qv));
        if boxes_disjoint(&ep, &eq) {
            continue;
        }
        let (wp, wq) = (diameter(&ep), diameter(&eq));
        if wp <= ctx.leaf && wq <= ctx.leaf {
            report.leaves += 1;
            if report.leaves > budget {
                report.truncated = true;
                return;
            }
            let x0 = [mid(pu), mid(pv), mid(qu), mid(qv)];
            match project_onto_intersection(p, q, x0, ctx.tol) {
                Some(x) if dp.contains(x[0], x[1], 1e-12) && dq.contains(x[2], x[3], 1e-12) => {
                    report.interior.push(StartPoint {
                        params: x,
                        kind: StartKind::Interior,
                    })
                }
                Some(_) => {}
                None => report.undecided += 1,
            }
            continue;
        }
        if wp >= wq {
            for hu in halves(pu) {
                for hv in halves(pv) {
                    stack.push((hu, hv, qu, qv));
                }
            }
        } else {
            for hu in halves(qu) {
                for hv in halves(qv) {
                    stack.push((pu, pv, hu, hv));
                }
            }
        }
    }
}

/// Gauss–Newton (minimum-norm steps) from `x` onto `P(σ,t) = Q(u,v)`; `None` if it does not
/// converge to a residual below `tol`.
pub fn project_onto_intersection<P, Q>(p: &P, q: &Q, mut x: [f64; 4], tol: f64) -> Option<[f64; 4]>
where
    P: crate::geometry::ParametricSurface,
    Q: crate::geometry::ParametricSurface,
{
    for _ in 0..40 {
        let a = p.derivs(x[0], x[1]);
        let b = q.derivs(x[2], x[3]);
        let f: Vector3<f64> = a.p - b.p;
        let j = Matrix3x4::from_columns(&[a.su, a.sv, -b.su, -b.sv]);
        let jjt = j * j.transpose();
        let y = jjt.lu().solve(&f)?;
        let step = j.transpose() * y;
        for (xi, si) in x.iter_mut().zip(step.iter()) {
            *xi -= si;
        }
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        if f.norm() <= tol && step.norm() <= 1e-10 {
            return Some(x);
        }
        if step.norm() <= 1e-15 * (1.0 + x.iter().map(|v| v.abs()).fold(0.0, f64::max)) {
            let r = (p.point(x[0], x[1]) - q.point(x[2], x[3])).norm();
            return (r <= tol).then_some(x);
        }
    }
    None
}

/// Removes boundary points that are the same point found twice (e.g. at a corner, or from two
/// neighbouring leaves), comparing parameters relative to the domain sizes.
fn dedup(points: &mut Vec<StartPoint>, dp: Domain, dq: Domain) {
    let scale = [
        dp.u[1] - dp.u[0],
        dp.v[1] - dp.v[0],
        dq.u[1] - dq.u[0],
        dq.v[1] - dq.v[0],
    ];
    let mut kept: Vec<StartPoint> = Vec::with_capacity(points.len());
    for pt in points.drain(..) {
        let dup = kept
            .iter()
            .any(|k| (0..4).all(|i| (k.params[i] - pt.params[i]).abs() <= 1e-7 * scale[i]));
        if !dup {
            kept.push(pt);
        }
    }
    *points = kept;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{ParametricSurface, SurfaceDerivs};
    use crate::Scalar;

    /// The graph z = a·(u² + v²) + c·u + d over a domain, with exact interval bounds.
    struct Graph {
        a: f64,
        c: f64,
        d: f64,
        domain: Domain,
    }

    impl Graph {
        fn z<S: Scalar>(&self, u: S, v: S) -> S {
            S::from_f64(self.a) * (u.sqr() + v.sqr())
                + S::from_f64(self.c) * u
                + S::from_f64(self.d)
        }
    }

    impl ParametricSurface for Graph {
        fn domain(&self) -> Domain {
            self.domain
        }
        fn derivs(&self, u: f64, v: f64) -> SurfaceDerivs {
            let z = self.z(u, v);
            SurfaceDerivs {
                p: Vec3::new(u, v, z),
                su: Vec3::new(1.0, 0.0, 2.0 * self.a * u + self.c),
                sv: Vec3::new(0.0, 1.0, 2.0 * self.a * v),
                suu: Vec3::new(0.0, 0.0, 2.0 * self.a),
                suv: Vec3::zeros(),
                svv: Vec3::new(0.0, 0.0, 2.0 * self.a),
            }
        }
    }

    impl EnclosingSurface for Graph {
        fn enclose(&self, u: Interval, v: Interval) -> [Interval; 3] {
            [u, v, self.z(u, v)]
        }
    }

    fn square() -> Domain {
        Domain::new(-1.0, 1.0, -1.0, 1.0)
    }

    #[test]
    fn interior_loop_is_found_and_lies_on_the_circle() {
        // Paraboloid z = u² + v² − 0.25 against the plane z = 0: the circle of radius 0.5.
        let p = Graph {
            a: 1.0,
            c: 0.0,
            d: -0.25,
            domain: square(),
        };
        let q = Graph {
            a: 0.0,
            c: 0.0,
            d: 0.0,
            domain: square(),
        };
        let r = find_start_points(&p, &q, &SearchOptions::default());
        assert!(r.boundary.is_empty(), "{:?}", r.boundary);
        assert!(!r.interior.is_empty());
        assert!(!r.truncated);
        for s in &r.interior {
            let [x, y, ..] = s.params;
            assert!((x.hypot(y) - 0.5).abs() < 1e-10, "{:?}", s.params);
        }
    }

    #[test]
    fn tiny_loop_is_found() {
        // Circle of radius 1e-3: far below the leaf size, still found.
        let p = Graph {
            a: 1.0,
            c: 0.0,
            d: -1e-6,
            domain: square(),
        };
        let q = Graph {
            a: 0.0,
            c: 0.0,
            d: 0.0,
            domain: square(),
        };
        let r = find_start_points(&p, &q, &SearchOptions::default());
        assert!(r
            .interior
            .iter()
            .any(|s| (s.params[0].hypot(s.params[1]) - 1e-3).abs() < 1e-9));
    }

    #[test]
    fn open_branch_ends_are_found_on_the_boundaries() {
        // Tilted plane z = 0.5·u + 0.1 against z = 0: the line u = −0.2 crossing v = ±1.
        let p = Graph {
            a: 0.0,
            c: 0.5,
            d: 0.1,
            domain: square(),
        };
        let q = Graph {
            a: 0.0,
            c: 0.0,
            d: 0.0,
            domain: square(),
        };
        let r = find_start_points(&p, &q, &SearchOptions::default());
        assert_eq!(r.boundary.len(), 2, "{:?}", r.boundary);
        for s in &r.boundary {
            assert!((s.params[0] + 0.2).abs() < 1e-12);
            assert!((s.params[1].abs() - 1.0).abs() < 1e-12);
        }
        // Disjoint surfaces: nothing, and no leaf is even reached.
        let far = Graph {
            a: 0.0,
            c: 0.0,
            d: 5.0,
            domain: square(),
        };
        let r = find_start_points(&far, &q, &SearchOptions::default());
        assert!(r.boundary.is_empty() && r.interior.is_empty() && r.leaves == 0);
    }
}

//! The intersection as a graph: singular points are nodes, arcs between them (or to the domain
//! boundary) are edges, closed curves without nodes are loops. Every arc is traced exactly once.
//!
//! [`trace_graph`] first traces from each regular start point (skipping starts on a branch already
//! traced); a trace that stops at a singular point attaches to its node (found by
//! [`locate_singular_point`], analysed once by [`analyse_node`]), and the exit through which it
//! arrived is marked used. Then, while some node has an unused exit, the arc leaving through it
//! is traced ([`trace_from_node`]) and its far end, if it is a node, marks the exit it arrives
//! through. An arc reached from its other end is therefore never traced again, and a closed curve
//! through a node (a figure eight) becomes two arcs from the node back to it.
//!
//! A trace that ended with a Newton failure right beside a singular point (nearly parallel
//! normals, a point with parallel normals within a node radius) is attached to that node as if it
//! had stopped on it, and a node exit lying on a trace that stopped short (incomplete) is not
//! traced again: either way the arc is traced once.

use crate::geometry::surface::pair_widths;
use crate::geometry::ParametricSurface;
use crate::march::branch::{Branch, BranchStatus, CurvePoint, EndReason, Event, EventKind};
use crate::march::covers::covers;
use crate::march::trace::{refine_start, trace_branch, trace_from_node, TracedBranch};
use crate::march::MarchOptions;
use crate::numeric::vec3::{dist3, norm3};
use crate::pair::branch_point::{analyse_node, locate_singular_point, SingularNode};
use crate::pair::contact_quadratic::ContactCase;
use crate::pair::tangent::curve_frame;

/// Counts of one [`trace_graph`] run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GraphStats {
    /// Start points skipped because a traced branch or a node already covers them.
    pub skipped_covered: usize,
    /// Start points (or node exits) from which tracing failed.
    pub failed_starts: usize,
    /// Arcs traced from node exits.
    pub node_arcs: usize,
    /// Arrivals at a node whose nearest exit had already been used (a sign of a double trace or
    /// of exits the node analysis missed); 0 when every arc was traced once.
    pub unmatched_arrivals: usize,
    /// Node exits left untraced because [`MAX_NODE_ARCS`] arcs had been traced from nodes
    /// (a safety net against degenerate input such as a tangential contact curve that yields
    /// node after node).
    pub untraced_exits: usize,
}

/// At most this many arcs are traced from node exits in one [`trace_graph`] run.
pub const MAX_NODE_ARCS: usize = 1024;

/// Branches, events, nodes and counts of one [`trace_graph`] run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GraphOutcome {
    /// The arcs and loops, numbered in order.
    pub branches: Vec<Branch>,
    /// One `Singular` event per node, and the boundary ends (duplicates removed).
    pub events: Vec<Event>,
    /// The singular points met, with their classification and exits.
    pub nodes: Vec<SingularNode>,
    /// For each node, which exits have been traced (all, unless a trace failed).
    pub exits_used: Vec<Vec<bool>>,
    /// Counts.
    pub stats: GraphStats,
}

struct Graph<'a> {
    opts: &'a MarchOptions,
    out: GraphOutcome,
}

impl Graph<'_> {
    fn radius(&self) -> f64 {
        self.opts.node_radius * self.opts.step
    }

    /// The node at the singular point where a trace stopped (`x`), created on first arrival.
    fn node_for<S1, S2>(&mut self, p: &S1, q: &S2, x: [f64; 4]) -> usize
    where
        S1: ParametricSurface + ?Sized,
        S2: ParametricSurface + ?Sized,
    {
        let scale = 1.0 + p.point(x[0], x[1]).norm();
        let tol = (100.0 * self.opts.newton_tolerance).max(1e-9 * scale);
        let located = locate_singular_point(p, q, x, tol, self.opts.singular_sine);
        let at = located.unwrap_or(x);
        let here = p.point(at[0], at[1]);
        let here = [here.x, here.y, here.z];
        let r = self.radius();
        if let Some(i) = self
            .out
            .nodes
            .iter()
            .position(|n| dist3(&n.xyz, &here) < 0.25 * r)
        {
            return i;
        }
        let node = analyse_node(
            p,
            q,
            at,
            located.is_some(),
            r,
            self.opts.newton_tolerance,
            self.opts.max_newton_iterations,
        );
        self.out.events.push(Event {
            kind: EventKind::Singular,
            p: [at[0], at[1]],
            q: [at[2], at[3]],
            xyz: node.xyz,
        });
        self.out.exits_used.push(vec![false; node.exits.len()]);
        self.out.nodes.push(node);
        self.out.nodes.len() - 1
    }

    /// Attaches the end of `points` (ordered from the node outwards) to its node: marks the exit
    /// the arc passes through and returns the node's curve point (to be joined to the arc).
    fn attach<S1, S2>(&mut self, p: &S1, q: &S2, outward: &[CurvePoint]) -> CurvePoint
    where
        S1: ParametricSurface + ?Sized,
        S2: ParametricSurface + ?Sized,
    {
        let first = &outward[0];
        let i = self.node_for(p, q, [first.p[0], first.p[1], first.q[0], first.q[1]]);
        let node = &self.out.nodes[i];
        let centre = node.xyz;
        // Where the arc crosses the sphere of radius r round the node.
        let r = node.radius;
        let crossing = outward
            .windows(2)
            .find(|w| dist3(&w[1].xyz, &centre) >= r)
            .map(|w| {
                let (da, db) = (dist3(&w[0].xyz, &centre), dist3(&w[1].xyz, &centre));
                let s = if db > da {
                    ((r - da) / (db - da)).clamp(0.0, 1.0)
                } else {
                    1.0
                };
                std::array::from_fn(|k| w[0].xyz[k] + s * (w[1].xyz[k] - w[0].xyz[k]))
            })
            .unwrap_or(outward[outward.len() - 1].xyz);
        let nearest = node
            .exit_xyz
            .iter()
            .enumerate()
            .map(|(k, e)| (k, dist3(e, &crossing)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match nearest {
            Some((k, _)) if !self.out.exits_used[i][k] => self.out.exits_used[i][k] = true,
            _ => self.out.stats.unmatched_arrivals += 1,
        }
        CurvePoint {
            p: [node.x[0], node.x[1]],
            q: [node.x[2], node.x[3]],
            xyz: node.xyz,
        }
    }

    /// Adds a traced branch: its singular ends are attached to nodes (the node point becomes the
    /// end point), its boundary events kept.
    /// Keeps the boundary events of a trace that are not already known.
    fn add_events(&mut self, events: Vec<Event>) {
        for e in events {
            if e.kind == EventKind::BoundaryEnd {
                let dup = self.out.events.iter().any(|f| {
                    f.kind == e.kind && dist3(&f.xyz, &e.xyz) <= 1e-6 * (1.0 + norm3(&e.xyz))
                });
                if !dup {
                    self.out.events.push(e);
                }
            }
        }
    }

    fn add<S1, S2>(&mut self, p: &S1, q: &S2, traced: TracedBranch, from_node: Option<usize>)
    where
        S1: ParametricSurface + ?Sized,
        S2: ParametricSurface + ?Sized,
    {
        let mut branch = traced.branch;
        self.add_events(traced.events);
        for end in 0..2 {
            if branch.ends[end] == EndReason::NewtonFailed && self.ends_at_node(p, q, &branch, end)
            {
                branch.ends[end] = EndReason::Singular;
            }
        }
        if branch.status == BranchStatus::Incomplete
            && branch.ends.iter().all(EndReason::is_regular)
        {
            branch.status = BranchStatus::Open;
        }
        if branch.ends[0] == EndReason::Singular && from_node.is_none() {
            let node_pt = self.attach(p, q, &branch.points);
            if branch.points[0] != node_pt {
                branch.points.insert(0, node_pt);
            }
        }
        if branch.ends[1] == EndReason::Singular && branch.points.len() > 1 {
            let outward: Vec<CurvePoint> = branch.points.iter().rev().copied().collect();
            let node_pt = self.attach(p, q, &outward);
            if branch.points.last() != Some(&node_pt) {
                branch.points.push(node_pt);
            }
        }
        branch.id = self.out.branches.len();
        self.out.branches.push(branch);
    }

    /// Whether the march that ended with a Newton failure at end `end` of `branch` stopped next
    /// to a singular point: the normals there are nearly parallel and Gauss–Newton finds a
    /// point with parallel normals within a node radius, ahead in the direction of travel. (Beside a branch point the sheets of the
    /// curve are closer than the Newton tolerance resolves; the arc ends at the node.)
    fn ends_at_node<S1, S2>(&self, p: &S1, q: &S2, branch: &Branch, end: usize) -> bool
    where
        S1: ParametricSurface + ?Sized,
        S2: ParametricSurface + ?Sized,
    {
        let Some(c) = (if end == 0 {
            branch.points.first()
        } else {
            branch.points.last()
        }) else {
            return false;
        };
        let x = [c.p[0], c.p[1], c.q[0], c.q[1]];
        if curve_frame(p, q, x).sine >= self.opts.watch_sine {
            return false;
        }
        let scale = 1.0 + norm3(&c.xyz);
        let tol = (100.0 * self.opts.newton_tolerance).max(1e-9 * scale);
        // The direction of travel into that end.
        let pts = &branch.points;
        let (from, to) = match (end, pts.len()) {
            (_, 0 | 1) => return false,
            (0, _) => (&pts[1], &pts[0]),
            (_, n) => (&pts[n - 2], &pts[n - 1]),
        };
        let travel: [f64; 3] = std::array::from_fn(|i| to.xyz[i] - from.xyz[i]);
        locate_singular_point(p, q, x, tol, self.opts.singular_sine).is_some_and(|at| {
            let here = p.point(at[0], at[1]);
            let off: [f64; 3] = std::array::from_fn(|i| here[i] - c.xyz[i]);
            let d = norm3(&off);
            let ahead = off.iter().zip(&travel).map(|(a, b)| a * b).sum::<f64>()
                >= 0.5 * d * norm3(&travel);
            // Ahead (within 60°), not beside the curve as the centre of a tiny loop is.
            d <= self.radius() && (ahead || d <= tol)
        })
    }

    /// The nodes within reach of their exits of `xyz`.
    fn nodes_near<'a>(&'a self, xyz: &'a [f64; 3]) -> impl Iterator<Item = &'a SingularNode> {
        self.out
            .nodes
            .iter()
            .filter(|n| dist3(&n.xyz, xyz) <= 1.5 * n.radius.max(self.opts.step / 3.0))
    }
}

/// Traces every arc and loop of `P ∩ Q` reachable from `starts` (guesses near the curve),
/// each exactly once (see the module docs).
///
/// Guarantees: every branch point satisfies the marcher's Newton tolerance except the node points
/// (located singular points, `|P − Q|` within 100 × tolerance); an arc that ends at a singular
/// point ends exactly on its node with `EndReason::Singular`; each node is reported once as a
/// `Singular` event and in [`GraphOutcome::nodes`] with its exits; isolated contact points and
/// nodes whose exits could not be found are reported without arcs.
pub fn trace_graph<S1, S2>(p: &S1, q: &S2, starts: &[[f64; 4]], opts: &MarchOptions) -> GraphOutcome
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let opts = MarchOptions {
        cross_singular: 0,
        ..*opts
    };
    let mut g = Graph {
        opts: &opts,
        out: GraphOutcome::default(),
    };
    let scales = pair_widths(&p.domain(), &q.domain());
    // Points are accurate to the Newton tolerance (a hundredfold margin for the start's own
    // refinement and the chords' end points).
    let floor = 100.0 * opts.newton_tolerance;
    // Starts near a located crossing wait until its exits are traced: they are usually on
    // those arcs, but an arc shorter than the exits' distance from the node (a node just inside
    // a domain side) has no exit and is reached from its start only.
    let mut near_nodes = Vec::new();
    for start in starts {
        // Tested on the curve: the start refined by Newton (the raw guess if that fails).
        let on_curve = refine_start(p, q, *start, &opts).map_or(*start, |n| n.x);
        if g.out
            .branches
            .iter()
            .any(|b| covers(b, &on_curve, p, floor, &scales))
        {
            g.out.stats.skipped_covered += 1;
            continue;
        }
        let here = p.point(start[0], start[1]);
        let here = [here.x, here.y, here.z];
        // Near a node: whether all the nodes near are located crossings. Only those have arms
        // to miss; a start near a point where the marcher merely stopped (a pole, a contact)
        // is skipped.
        let crossings = {
            let mut near = g.nodes_near(&here).peekable();
            near.peek()
                .is_some()
                .then(|| near.all(|n| n.located && has_arcs(n)))
        };
        match crossings {
            Some(true) => near_nodes.push(on_curve),
            Some(false) => g.out.stats.skipped_covered += 1,
            None => trace_start(&mut g, p, q, start),
        }
    }
    trace_node_exits(&mut g, p, q, floor, &scales);
    for start in &near_nodes {
        if g.out
            .branches
            .iter()
            .any(|b| covers(b, start, p, floor, &scales))
        {
            g.out.stats.skipped_covered += 1;
            continue;
        }
        trace_start(&mut g, p, q, start);
    }
    // The arcs traced from those starts may end at nodes with exits of their own.
    trace_node_exits(&mut g, p, q, floor, &scales);
    g.out
}

/// Traces the branch through `start` and adds it to the graph (or its node, or its event).
fn trace_start<S1, S2>(g: &mut Graph, p: &S1, q: &S2, start: &[f64; 4])
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    let Ok(traced) = trace_branch(p, q, *start, g.opts) else {
        g.out.stats.failed_starts += 1;
        return;
    };
    let single = traced.branch.points.len() == 1
        && traced.branch.ends == [EndReason::Singular, EndReason::Singular];
    if traced.branch.points.len() == 1 {
        // A curve touching a face from outside: its event only, no branch.
        if matches!(traced.branch.ends[0], EndReason::Boundary { .. }) {
            g.add_events(traced.events);
            return;
        }
    }
    if !single && is_contact_excursion(g, p, q, &traced.branch) {
        // A start beside a curve of tangency marches off it and straight back: the contact
        // (its node, no arcs) is all there is.
        return;
    }
    if single {
        // The start is itself a singular point: make it a node, its arcs come later.
        let cp = traced.branch.points[0];
        g.node_for(p, q, [cp.p[0], cp.p[1], cp.q[0], cp.q[1]]);
        return;
    }
    g.add(p, q, traced, None);
}

/// Traces the arcs from node exits not yet reached (at most [`MAX_NODE_ARCS`] in all).
fn trace_node_exits<S1, S2>(g: &mut Graph, p: &S1, q: &S2, floor: f64, scales: &[f64; 4])
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    while let Some((i, k)) = g
        .out
        .exits_used
        .iter()
        .enumerate()
        .find_map(|(i, used)| used.iter().position(|u| !u).map(|k| (i, k)))
    {
        if g.out.stats.node_arcs + g.out.stats.failed_starts >= MAX_NODE_ARCS {
            g.out.stats.untraced_exits = g.out.exits_used.iter().flatten().filter(|u| !**u).count();
            break;
        }
        g.out.exits_used[i][k] = true;
        let (x, exit) = (g.out.nodes[i].x, g.out.nodes[i].exits[k]);
        // An exit on an arc already traced that stopped short of its ends (so it never reached
        // the node to mark the exit) leads along that arc: not traced again.
        if g.out
            .branches
            .iter()
            .any(|b| b.status == BranchStatus::Incomplete && covers(b, &exit, p, floor, scales))
        {
            g.out.stats.skipped_covered += 1;
            continue;
        }
        match trace_from_node(p, q, x, exit, g.opts) {
            Ok(traced) => {
                g.out.stats.node_arcs += 1;
                g.add(p, q, traced, Some(i));
            }
            Err(_) => g.out.stats.failed_starts += 1,
        }
    }
}

/// Whether `branch` runs from a singular point to a singular point over less than a step and
/// both are contact nodes without arcs (a start beside a curve of tangency that marched off it
/// and straight back); the nodes are recorded either way.
fn is_contact_excursion<S1, S2>(g: &mut Graph, p: &S1, q: &S2, branch: &Branch) -> bool
where
    S1: ParametricSurface + ?Sized,
    S2: ParametricSurface + ?Sized,
{
    if branch.ends != [EndReason::Singular; 2] || branch.points.len() < 2 {
        return false;
    }
    if branch.length() >= g.opts.step {
        return false;
    }
    let params = |c: &CurvePoint| [c.p[0], c.p[1], c.q[0], c.q[1]];
    let ends = [&branch.points[0], &branch.points[branch.points.len() - 1]];
    ends.iter().all(|c| {
        let i = g.node_for(p, q, params(c));
        !has_arcs(&g.out.nodes[i])
    })
}

/// Whether a node is a crossing of branches (arcs leave it) rather than an isolated contact.
pub fn has_arcs(node: &SingularNode) -> bool {
    node.case != ContactCase::IsolatedPoint && !node.exits.is_empty()
}

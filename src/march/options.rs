//! Options of the marcher.

/// How the next point is predicted before Newton refinement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepMethod {
    /// Wu–Andrade circular step on the approximate osculating circle (matrix form).
    Circular,
    /// The same circular step as one unit dual quaternion (Bulut's DQOC, general 3D axis).
    Dqoc,
    /// Straight step of length `L` along the tangent (the baseline).
    Tangent,
}

/// Parameters of [`trace_branch`](super::trace_branch).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarchOptions {
    /// The step `L`: the central angle of a circular step (arc `L·R` when the radius `R ≤ 1`,
    /// arc `L` otherwise) or the length of a tangent step.
    pub step: f64,
    /// The predictor.
    pub method: StepMethod,
    /// At most this many points per branch (the start counts); reaching it ends with `PointLimit`.
    pub max_points: usize,
    /// Newton's tolerance: Newton stops when a correction moves the point by at most this and
    /// `|P − Q|` and the constraint residual are below it (model units).
    pub newton_tolerance: f64,
    /// Newton gives up after this many corrections.
    pub max_newton_iterations: usize,
    /// A point is singular when `|N^P × N^Q| < singular_sine · |N^P| |N^Q|` (default 1e-7).
    ///
    /// Below about that the curve cannot be told from a singular one in `f64`: a Newton point
    /// is off the curve by the residual's rounding over the sine (1e-9 at a sine of 1e-7 on a
    /// model of size 1), and where nearly tangent surfaces make the curve turn round, its
    /// radius there is about the sine over the normals' relative curvature. Above it the march
    /// goes round such a turn (at 1e-6, the former default, it stopped there and the curve came
    /// back as two branches ending at a "singular point" that is none).
    pub singular_sine: f64,
    /// Below this sine of the normal angle, while it decreases, the step is limited to half the
    /// distance at which it would reach zero, so the marcher approaches a singular point
    /// geometrically instead of jumping over it.
    pub watch_sine: f64,
    /// Consecutive unit tangents with `|t₀ · t₁| > 1 − parallel_tolerance` are treated as
    /// parallel and a tangent step replaces the circular one.
    pub parallel_tolerance: f64,
    /// The first step of each half-branch is `first_step_fraction · L` along the tangent.
    pub first_step_fraction: f64,
    /// Closing a loop needs `|Σ turning − 2πk| < rotation_tolerance` for an integer `k ≠ 0`
    /// (turning of the tangent in the parameter domain of P or of Q, radians).
    pub rotation_tolerance: f64,
    /// Parameter tolerance for "on the domain boundary" / "inside the domain".
    pub domain_tolerance: f64,
    /// At a singular point (branch point, tacnode, triple point) report it, then continue straight
    /// through it: the point is located, its exits found (see
    /// [`analyse_node`](crate::pair::branch_point::analyse_node)), the exit of arrival marked used and the
    /// march continued through the unused exit nearest to the straight continuation; a node
    /// reached again through a used exit ends the march there, so no arc is traced twice and the
    /// budget is never spent going round. A loop through crossings may close with rotation index
    /// 0 (a figure eight). At most this many crossings per half branch; 0 (the default, kept so
    /// that single traces stop at singular points as before) stops at the first one.
    /// `topology::intersect::intersect` traces through singular points regardless,
    /// as a graph of arcs.
    pub cross_singular: usize,
    /// At a singular point met by `topology::intersect::intersect` (graph tracing), the
    /// arcs leave through curve points at distance `node_radius · step` from it.
    pub node_radius: f64,
}

impl Default for MarchOptions {
    fn default() -> Self {
        MarchOptions {
            step: 0.05,
            method: StepMethod::Circular,
            max_points: 20_000,
            newton_tolerance: 1e-10,
            max_newton_iterations: 12,
            singular_sine: 1e-7,
            watch_sine: 0.05,
            parallel_tolerance: 1e-9,
            first_step_fraction: 0.01,
            rotation_tolerance: 0.5,
            domain_tolerance: 1e-9,
            cross_singular: 0,
            node_radius: 0.5,
        }
    }
}

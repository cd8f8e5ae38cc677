//! The crate's one error type.

use thiserror::Error;

/// What is wrong with one input field.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum InputProblem {
    /// A number that is NaN or infinite.
    #[error("a non-finite number")]
    NonFinite,
    /// A rational weight that is zero or negative (or an interval weight reaching ≤ 0).
    #[error("a weight that is not positive")]
    NonPositiveWeight,
    /// A list of the wrong length.
    #[error("{found} entries where {expected} are needed")]
    WrongCount {
        /// How many entries the field needs.
        expected: usize,
        /// How many it has.
        found: usize,
    },
    /// An interval `[lo, hi]` with `lo > hi`.
    #[error("an inverted interval [{lo}, {hi}]")]
    InvertedInterval {
        /// Lower bound given.
        lo: f64,
        /// Upper bound given.
        hi: f64,
    },
    /// A parameter domain of zero or negative width.
    #[error("an empty parameter domain [{lo}, {hi}]")]
    EmptyDomain {
        /// Lower bound given.
        lo: f64,
        /// Upper bound given.
        hi: f64,
    },
    /// A degree of zero (or a negative exponent) where at least one is needed.
    #[error("degree {0} (at least 1 is needed in each direction)")]
    BadDegree(i64),
    /// A surface kind the scene format does not know.
    #[error("unknown surface kind `{0}`")]
    UnknownKind(String),
    /// A field the scene format does not know.
    #[error("unknown field `{0}`")]
    UnknownField(String),
    /// A required field is missing.
    #[error("missing field")]
    Missing,
    /// A value of the wrong JSON type or shape.
    #[error("wrong shape: {0}")]
    WrongShape(String),
    /// A patch whose control net is degenerate (all control points coincide, so it has no normal).
    #[error("a degenerate patch (control points span no surface)")]
    Degenerate,
    /// A rational denominator whose Bernstein coefficients stayed not provably positive up to
    /// the largest degree tried (it may touch or nearly touch zero on the domain).
    #[error("a weight polynomial not proven positive after degree elevation to {max_degree}")]
    WeightNotProvenPositive {
        /// The largest degree (per parameter direction) that was tried.
        max_degree: usize,
    },
}

/// Every error `ssitrace` reports. Variants carry the data needed to locate the problem.
#[derive(Debug, Error)]
pub enum Error {
    /// Bad input: names the surface (0-based index in the scene, if known) and the field.
    #[error("surface {}: field `{field}`: {problem}", surface.map(|s| s.to_string()).unwrap_or_else(|| "?".into()))]
    InvalidInput {
        /// Index of the surface in the scene, when the input came from a scene.
        surface: Option<usize>,
        /// Name of the offending field (e.g. `points[3][1]`, `weights`, `domain`).
        field: String,
        /// What is wrong with it.
        problem: InputProblem,
    },
    /// The scene file is not valid JSON or not of the documented shape.
    #[error("scene is not valid: {0}")]
    Scene(String),
    /// A STEP file that cannot be read (or curves that cannot be written as STEP): names the
    /// instance `#n` when the problem is in one, else says where (a line, the file).
    #[error("STEP{}: {message}", entity.map(|e| format!(" entity #{e}")).unwrap_or_default())]
    Step {
        /// The instance number, when the problem is in one instance.
        entity: Option<u64>,
        /// What is wrong.
        message: String,
    },
    /// Reading or writing a file failed.
    #[error("i/o error on {path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// Newton refinement onto the intersection did not converge.
    #[error("Newton refinement did not converge after {iterations} iterations (residual {residual:e}) near {near:?}")]
    NewtonFailed {
        /// Iterations done.
        iterations: usize,
        /// Last residual |P − Q|.
        residual: f64,
        /// Parameters (σ, t, u, v) where it stopped.
        near: [f64; 4],
    },
    /// A result JSON document that is not of the documented `ssitrace-result` shape.
    #[error("result JSON is not valid: {0}")]
    ResultFormat(String),
    /// Drawing a picture failed.
    #[error("rendering failed: {0}")]
    Render(String),
    /// The validated ODE integrator could not prove the next step; carries the time and the
    /// enclosure of the state it had reached (everything before it is proven).
    #[error(
        "validated integration stopped at t = {time} (last step tried h = {step:e}): {reason}"
    )]
    StepFailed {
        /// Time reached (start of the step that failed).
        time: f64,
        /// The last step size tried.
        step: f64,
        /// Enclosure of the state at `time`.
        state: Vec<inari::Interval>,
        /// Why the step failed.
        reason: StepFailure,
    },
    /// A certified trace could not start, or an internal consistency check of the certificate
    /// failed (e.g. two consecutive boxes of a chain that do not overlap); nothing is claimed.
    #[error("certification failed near (σ,t,u,v) = {near:?}: {reason}")]
    Certification {
        /// What failed.
        reason: String,
        /// Approximate parameters where it failed.
        near: [f64; 4],
    },
    /// Invalid options or ODE system given to the validated integrator.
    #[error("validated integrator setup: {0}")]
    BadIntegratorSetup(String),
    /// A point given as lying on a face of the parameter box is not on it.
    #[error("point {near:?} is not on the face where coordinate {coordinate} = {bound} (off by {distance:e})")]
    NotOnBoundary {
        /// The face's coordinate (0 = σ, 1 = t, 2 = u, 3 = v).
        coordinate: usize,
        /// The face's value of that coordinate.
        bound: f64,
        /// How far the point is from the face (parameter units).
        distance: f64,
        /// The point given.
        near: [f64; 4],
    },
    /// A point given as a point of P ∩ Q is not on it.
    #[error("point {near:?} is not on the intersection (|P − Q| = {residual:e})")]
    NotOnIntersection {
        /// `|P(σ,t) − Q(u,v)|` at the point.
        residual: f64,
        /// The point given.
        near: [f64; 4],
    },
}

impl Error {
    /// Shorthand for an [`Error::InvalidInput`] with no surface index yet.
    pub fn input(field: impl Into<String>, problem: InputProblem) -> Self {
        Error::InvalidInput {
            surface: None,
            field: field.into(),
            problem,
        }
    }

    /// The same error attributed to surface `index` of a scene (input errors only).
    pub fn in_surface(self, index: usize) -> Self {
        match self {
            Error::InvalidInput { field, problem, .. } => Error::InvalidInput {
                surface: Some(index),
                field,
                problem,
            },
            other => other,
        }
    }
}

/// Result with the crate's [`Error`](enum@Error).
pub type Result<T> = std::result::Result<T, Error>;

/// Why a validated step could not be proven.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
pub enum StepFailure {
    /// Phase I failed for every step size down to `h_min`.
    #[error("no a-priori enclosure found for any step size down to h_min = {h_min:e}")]
    BelowMinimumStep {
        /// The minimum step size of the options.
        h_min: f64,
    },
    /// The field cannot be evaluated (smoothly) on the current set.
    #[error("the field is not defined on the current set ({0:?})")]
    Domain(DomainError),
    /// The options' step budget is spent.
    #[error("more than {0} steps")]
    TooManySteps(usize),
}

/// The expansion hit a point where the field is not (smoothly) defined on the given box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DomainError {
    /// A divisor whose enclosure contains zero.
    DivisionByZero,
    /// A square root whose argument's enclosure reaches zero or below.
    SqrtOfNonPositive,
    /// An interval that is empty or unbounded (overflow).
    Unbounded,
    /// An initial box whose length is not the field's dimension.
    WrongDimension,
}

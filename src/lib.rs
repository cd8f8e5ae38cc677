//! # ssitrace
//!
//! Intersection curves of two parametric surfaces (rational Bézier patches), traced and certified.
//!
//! One call does the whole job: [`intersect`] finds every branch of `P ∩ Q`, marches it, and
//! (with [`Method::Validated`] or [`Method::Both`], the default) certifies it: a chain of
//! parameter boxes proven to contain the curve, with a model-space tolerance.
//!
//! ```
//! use ssitrace::{intersect, Domain, Options, RationalBezierPatch};
//!
//! # fn main() -> ssitrace::Result<()> {
//! // P: the paraboloid z = x² + y² over [-1, 1]², a biquadratic patch (x² on [-1, 1] has the
//! // Bernstein coefficients 1, -1, 1). Control point (i, j) is at index 3·i + j.
//! let a = [1.0, -1.0, 1.0];
//! let mut net = Vec::new();
//! for i in 0..3 {
//!     for j in 0..3 {
//!         net.push([i as f64 - 1.0, j as f64 - 1.0, a[i] + a[j]]);
//!     }
//! }
//! let p = RationalBezierPatch::from_f64_points([2, 2], &net, None, Domain::UNIT)?;
//! // Q: the plane z = 1/2, a bilinear patch.
//! let plane = [[-1.0, -1.0, 0.5], [-1.0, 1.0, 0.5], [1.0, -1.0, 0.5], [1.0, 1.0, 0.5]];
//! let q = RationalBezierPatch::from_f64_points([1, 1], &plane, None, Domain::UNIT)?;
//!
//! let r = intersect(&p, &q, &Options::default())?;
//! assert!(r.is_complete(), "the search settled every region");
//! assert_eq!(r.branches.len(), 1, "one curve: the circle x² + y² = 1/2");
//! let b = &r.branches[0];
//! let certified = b.certified().expect("certified");
//! println!(
//!     "{} marched points; certified in {} steps to within {:.1e}; ends: {}, {}",
//!     b.marched.points.len(),
//!     certified.steps(),
//!     certified.certified_tolerance,
//!     certified.ends[0],
//!     certified.ends[1],
//! );
//! assert!(b.certified_tolerance().unwrap() <= r.options.required_tolerance);
//! # Ok(())
//! # }
//! ```
//!
//! The layers, each importing only the ones before it:
//! [`numeric`] (the [`Scalar`] trait, rigorous dot products) → [`geometry`] (surfaces, Bézier
//! and power-basis patches, sub-patches, rigorous bounds) → [`pair`] (local geometry of `P ∩ Q`:
//! the field, Newton, Krawczyk, the contact quadratic, boundary directions, branch points) →
//! [`search`] (a start on every branch) → [`march`] (the fast circular-step marcher) →
//! [`topology`] (all branches, the arc graph, branch ends) → [`validated`] (the validated Taylor
//! ODE engine) → [`certify`] (certified branches and contacts) → [`check`] (straying and
//! looping) → [`solve`] (the typed entry point [`intersect`]) → [`shell`] (many faces against
//! many, NURBS faces by their Bézier pieces, in parallel) → [`edge`] (certified curves as B-spline
//! edges with p-curves and one proven tolerance) → [`io`] (scene files, result
//! JSON, SVG) → [`pipeline`] (scene in, result document out, for the command line).

pub mod certify;
pub mod check;
pub mod edge;
pub mod error;
pub mod geometry;
pub mod io;
pub mod march;
pub mod numeric;
pub mod pair;
pub mod pipeline;
pub mod search;
pub mod shell;
pub mod solve;
pub mod topology;
pub mod validated;

pub use error::{Error, InputProblem, Result};
pub use geometry::{Domain, PowerSurface, RationalBezierPatch};
pub use numeric::scalar::Scalar;
pub use solve::{
    intersect, BranchCertificate, Engine, Method, Options, Stats, SurfaceIntersection, TracedBranch,
};

//! The library's entry point: [`intersect`] two rational Bézier patches with [`Options`] and get
//! a typed [`SurfaceIntersection`] back.
//!
//! This is the whole job above the layers: the start-point search ([`crate::search`]), the
//! marcher ([`crate::march`], [`crate::topology`]), the certified tracer ([`crate::certify`]) and
//! the straying check ([`crate::check`]). Nothing here reads or writes files: the `io` layer above
//! turns a [`SurfaceIntersection`] into the result JSON and pictures.

mod duplicates;
mod options;
mod repair;
mod result;
mod run;
mod turns;

pub use options::{
    Engine, Method, Options, COVER_EVALUATIONS, COVER_LEAF, DEFAULT_MAX_STEPS, LENGTH_BUDGET_FACTOR,
};
pub use result::{BranchCertificate, CertifyStats, Stats, SurfaceIntersection, TracedBranch};
pub use run::{certify_marched_branch, intersect};

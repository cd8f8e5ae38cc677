//! Certified curves: the intersection ODE on the validated engine, gap-free boxes, tight tubes.
//!
//! [`field`] writes the intersection ODE once over [`crate::Scalar`]; [`ode`] hands it to the
//! validated engine; [`krawczyk`] proves curve points and contracts boxes onto `P = Q`;
//! [`tangential`] classifies tangential contacts; [`trace`] certifies a branch; [`curve`] is what
//! a certified branch reports.

mod anchor;
pub mod curve;
pub mod field;
pub mod krawczyk;
pub mod ode;
pub mod tangential;
pub mod trace;

pub use curve::{CertifiedBranch, CertifiedEnd, EnclosureBox, TubePiece};
pub use trace::{certify_branch, certify_branch_profiled, CertifyOptions, TraceProfile};

#[cfg(test)]
pub(crate) mod fixtures;

//! Certified curves: gap-free boxes and tight tubes, by two engines.
//!
//! [`chain`] (the default) certifies a marched branch as a chain of links, each one parametric
//! Krawczyk test on a thin tube around a polynomial predictor (`segment.rs`); its arc lengths are
//! nominal. The Taylor engine: [`ode`] hands the intersection field ([`crate::pair::field`]) to the validated engine;
//! [`trace`] certifies a branch (its start and re-anchoring proven by
//! [`crate::pair::krawczyk`]); [`curve`] is what a certified branch reports. Tangential
//! contacts: [`tangential_ode`] (the tangential field, classified by
//! [`crate::pair::contact_quadratic`]), [`contact_cover`] (proven covers) and [`contact`] (the
//! entry point [`certify_contact`]).

mod anchor;
pub mod budget;
pub mod chain;
mod closing;
pub mod contact;
pub mod contact_cover;
mod contact_net;
pub mod contact_patch;
pub mod curve;
mod exact_residual;
mod jet;
mod lean_patch;
pub mod ode;
mod segment;
pub mod tangential_ode;
mod term_target;
pub mod trace;

pub use budget::StepBudget;
pub use chain::{certify_chain, ChainOptions};
pub use contact::{certify_contact, certify_contact_events, CertifiedContact, ContactOptions};
pub use curve::{
    AlongParameter, CertifiedBranch, CertifiedEnd, EnclosureBox, ToleranceLimit, TubePiece,
};
pub(crate) use segment::PREDICTOR_DEGREE;
pub use trace::{certify_branch, certify_branch_profiled, CertifyOptions, TraceProfile};

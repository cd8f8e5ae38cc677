//! Certified curves: the intersection ODE on the validated engine, gap-free boxes, tight tubes.
//!
//! [`field`] writes the intersection ODE once over [`crate::Scalar`]; [`ode`] hands it to the
//! validated engine; [`krawczyk`] proves curve points and contracts boxes onto `P = Q`;
//! [`tangential`] classifies tangential contacts; [`trace`] certifies a branch; [`curve`] is what
//! a certified branch reports. Tangential contacts: [`tangential_ode`] (the tangential field),
//! [`centred_second_order`] (tight second derivatives for it), [`contact_cover`] (proven covers)
//! and [`contact`] (the entry point [`certify_contact`]).

mod anchor;
pub mod contact;
pub mod contact_cover;
pub mod curve;
pub mod ode;
pub mod tangential_ode;
pub mod trace;

pub use contact::{certify_contact, certify_contact_events, CertifiedContact, ContactOptions};
pub use curve::{CertifiedBranch, CertifiedEnd, EnclosureBox, TubePiece};
pub use trace::{certify_branch, certify_branch_profiled, CertifyOptions, TraceProfile};

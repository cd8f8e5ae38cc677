//! The local geometry of a surface pair `P ∩ Q`: the intersection field and its tangent, Newton
//! refinement onto the curve, Krawczyk proofs of curve points, the contact quadratic of
//! tangential points, boundary directions and singular points (branch-point nodes).
//!
//! Everything here is about one point or one small box of the pair; the search, the marcher,
//! the topology and the certifier above all build on it.

pub mod boundary_direction;
pub mod branch_point;
pub mod centred_second_order;
pub mod contact_quadratic;
pub mod curve_surface;
pub mod field;
pub mod krawczyk;
pub mod newton;
pub mod tangent;

pub use boundary_direction::{
    classify_boundary_point, classify_on_faces, Bound, BoundaryClassification, BoundaryDirection,
    BoundaryOptions, BoundarySide,
};

#[cfg(test)]
pub(crate) mod fixtures;

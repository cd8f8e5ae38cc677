//! The rigorous branch search: a start point on every branch of `P ∩ Q`, or an explicit region
//! left undecided. Sub-patch pairs are proven disjoint or free of closed loops.

pub mod loop_exclusion;
mod point_exclusion;
pub mod start_points;

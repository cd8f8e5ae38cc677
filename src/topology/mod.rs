//! The topology of the intersection: all branches of a patch pair (search, then one march per
//! branch), singular points as graph nodes whose arcs are each traced once, and the boundary
//! ends of each branch checked by the boundary-direction test.

pub mod branch_ends;
pub mod graph;
pub mod intersect;

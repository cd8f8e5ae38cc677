//! Surfaces that can bound themselves rigorously over a parameter box.

use super::ParametricSurface;
use inari::Interval;

/// A surface with a rigorous model-space enclosure over any parameter box.
///
/// Guarantee: for every `(u, v)` in the box (intersected with the domain's extension by the
/// surface's formula), the point S(u, v) lies in the returned interval box.
pub trait EnclosingSurface: ParametricSurface {
    /// An interval box containing S(u, v) for all `u ∈ u_box`, `v ∈ v_box`.
    fn enclose(&self, u_box: Interval, v_box: Interval) -> [Interval; 3];
}

impl<T: EnclosingSurface + ?Sized> EnclosingSurface for &T {
    fn enclose(&self, u_box: Interval, v_box: Interval) -> [Interval; 3] {
        (**self).enclose(u_box, v_box)
    }
}

/// Whether two interval boxes are disjoint in some coordinate (a proof that they do not meet).
pub fn boxes_disjoint(a: &[Interval; 3], b: &[Interval; 3]) -> bool {
    a.iter().zip(b).any(|(x, y)| x.disjoint(*y))
}

impl EnclosingSurface for super::RationalBezierPatch {
    /// The intersection of the convex-hull bound of the sub-patch and the naive interval bound.
    fn enclose(&self, u_box: Interval, v_box: Interval) -> [Interval; 3] {
        super::RationalBezierPatch::enclose(self, u_box, v_box)
    }
}

//! 3-vectors as arrays: the one home of the cross and dot products, norms and distances.
//!
//! The generic functions work in any [`Scalar`] (plain `f64`, intervals, Taylor series), so the
//! floating-point marcher and the certified code share the same formulas; for intervals each
//! result encloses the exact one.

use crate::numeric::scalar::Scalar;

/// Cross product `a × b`.
pub fn cross<T: Scalar>(a: &[T; 3], b: &[T; 3]) -> [T; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Dot product `a·b`.
pub fn dot<T: Scalar>(a: &[T; 3], b: &[T; 3]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Sum of squares `a·a` (with `sqr`, so intervals stay non-negative).
pub fn norm_sqr<T: Scalar>(a: &[T; 3]) -> T {
    a[0].sqr() + a[1].sqr() + a[2].sqr()
}

/// Determinant `det(a, b, c) = a·(b×c)`.
pub fn det<T: Scalar>(a: &[T; 3], b: &[T; 3], c: &[T; 3]) -> T {
    dot(a, &cross(b, c))
}

/// Euclidean length of `a`.
pub fn norm3(a: &[f64; 3]) -> f64 {
    norm_sqr(a).sqrt()
}

/// Euclidean distance between two points.
pub fn dist3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::point;

    #[test]
    fn products_and_lengths() {
        let (a, b) = ([1.0, 2.0, 3.0], [-2.0, 0.5, 4.0]);
        assert_eq!(cross(&a, &b), [6.5, -10.0, 4.5]);
        assert_eq!(dot(&a, &b), 11.0);
        assert_eq!(det(&a, &b, &cross(&a, &b)), norm_sqr(&cross(&a, &b)));
        assert_eq!(norm3(&[3.0, 4.0, 12.0]), 13.0);
        assert_eq!(dist3(&[1.0, 1.0, 1.0], &[4.0, 5.0, 13.0]), 13.0);
        // The interval products enclose the f64 ones.
        let (ai, bi) = (a.map(point), b.map(point));
        let c = cross(&ai, &bi);
        assert!((0..3).all(|k| c[k].contains(cross(&a, &b)[k])));
        assert!(dot(&ai, &bi).contains(11.0));
    }
}

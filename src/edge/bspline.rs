//! Clamped B-spline curves as an edge reports them: degree, knots, control points.

/// A clamped, non-rational B-spline curve in `D` dimensions.
#[derive(Debug, Clone, PartialEq)]
pub struct BSpline<const D: usize> {
    /// The degree `p`.
    pub degree: usize,
    /// The knot vector, non-decreasing, `points.len() + degree + 1` long, the first and last
    /// knots repeated `degree + 1` times.
    pub knots: Vec<f64>,
    /// The control points.
    pub points: Vec<[f64; D]>,
}

impl<const D: usize> BSpline<D> {
    /// The parameter range `[first knot, last knot]`.
    pub fn range(&self) -> [f64; 2] {
        [
            self.knots.first().copied().unwrap_or(0.0),
            self.knots.last().copied().unwrap_or(0.0),
        ]
    }

    /// The point at parameter `s` (de Boor's algorithm in `f64`; `s` is clamped into the range).
    /// For checking and drawing, not a bound.
    pub fn eval(&self, s: f64) -> [f64; D] {
        let p = self.degree;
        let n = self.points.len();
        if n == 0 {
            return [0.0; D];
        }
        let [lo, hi] = self.range();
        let s = s.clamp(lo, hi);
        // The span k with knots[k] <= s < knots[k + 1], p <= k < n.
        let mut k = p;
        while k + 1 < n && self.knots[k + 1] <= s {
            k += 1;
        }
        let mut d: Vec<[f64; D]> = (0..=p).map(|j| self.points[j + k - p]).collect();
        for r in 1..=p {
            for j in (r..=p).rev() {
                let i = j + k - p;
                let den = self.knots[i + p + 1 - r] - self.knots[i];
                let a = if den == 0.0 {
                    0.0
                } else {
                    (s - self.knots[i]) / den
                };
                let prev = d[j - 1];
                for (v, w) in d[j].iter_mut().zip(prev) {
                    *v = (1.0 - a) * w + a * *v;
                }
            }
        }
        d[p]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bezier_segment_evaluates_like_bernstein() {
        let b = BSpline::<1> {
            degree: 2,
            knots: vec![0.0, 0.0, 0.0, 2.0, 2.0, 2.0],
            points: vec![[0.0], [1.0], [0.0]],
        };
        assert!((b.eval(1.0)[0] - 0.5).abs() < 1e-15);
        assert_eq!(b.eval(2.0)[0], 0.0);
        let two = BSpline::<1> {
            degree: 1,
            knots: vec![0.0, 0.0, 1.0, 3.0, 3.0],
            points: vec![[0.0], [2.0], [0.0]],
        };
        assert!((two.eval(2.0)[0] - 1.0).abs() < 1e-15);
    }
}

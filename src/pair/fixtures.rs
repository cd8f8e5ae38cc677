//! Small closed-form surfaces shared by the unit tests of this module, and a wavy rational
//! patch shared by the unit tests of the layers above.

use crate::pair::field::ScalarSurface;
use crate::Scalar;

/// The graph z = a·(u² + v²) + b·u·v + d (exact in every scalar type).
pub(crate) struct Bowl {
    pub a: f64,
    pub b: f64,
    pub d: f64,
}

impl Bowl {
    pub(crate) fn new(a: f64, d: f64) -> Self {
        Bowl { a, b: 0.0, d }
    }
}

impl ScalarSurface for Bowl {
    fn first_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 3] {
        let [p, su, sv, ..] = self.second_order(u, v);
        [p, su, sv]
    }
    fn second_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 6] {
        let (o, z) = (T::one(), T::zero());
        let (a, b) = (T::from_f64(self.a), T::from_f64(self.b));
        let two_a = T::from_f64(2.0 * self.a);
        [
            [
                u,
                v,
                a * (u.sqr() + v.sqr()) + b * u * v + T::from_f64(self.d),
            ],
            [o, z, two_a * u + b * v],
            [z, o, two_a * v + b * u],
            [z, z, two_a],
            [z, z, b],
            [z, z, two_a],
        ]
    }
}

/// A bilinear patch over the unit square with one uneven weight: the smallest rational patch,
/// which the contact patch's lean polynomial form must leave in the patch's own form.
#[cfg(test)]
pub(crate) fn rational_bilinear() -> crate::geometry::RationalBezierPatch {
    let pts = [
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.2],
        [1.0, 0.0, 0.1],
        [1.0, 1.0, 0.5],
    ];
    crate::geometry::RationalBezierPatch::from_f64_points(
        [1, 1],
        &pts,
        Some(&[1.0, 2.0, 1.0, 1.0]),
        crate::geometry::Domain::UNIT,
    )
    .unwrap()
}

/// A wavy bicubic × biquadratic patch over `[−1, 2] × [0.5, 1.5]`, rational (uneven weights) or
/// polynomial.
#[cfg(test)]
pub(crate) fn wavy_patch(weights: bool) -> crate::geometry::RationalBezierPatch {
    let (m, n) = (3, 2);
    let mut pts = Vec::new();
    let mut ws = Vec::new();
    for i in 0..=m {
        for j in 0..=n {
            let (x, y) = (i as f64, j as f64);
            pts.push([x + 0.1 * y, y - 0.2 * x, (x * 1.3 + y * 0.7).sin()]);
            ws.push(1.0 + 0.4 * ((i + 2 * j) % 3) as f64);
        }
    }
    let w = weights.then_some(ws.as_slice());
    let domain = crate::geometry::Domain::new(-1.0, 2.0, 0.5, 1.5);
    crate::geometry::RationalBezierPatch::from_f64_points([m, n], &pts, w, domain).unwrap()
}

/// The cubic height field `z = 2v² + 0.75u² − 0.7uv + 0.3uv² − 0.3u²v + 0.075u³` of the
/// contact-cover unit tests (`PowerSurface::graph` terms), shared by the cover and the lean
/// contact patches.
pub(crate) const TANGENTIAL_CUBIC: [crate::geometry::power::PowerTerm; 6] = [
    (0, 2, 2.0),
    (2, 0, 0.75),
    (1, 1, -0.7),
    (1, 2, 0.3),
    (2, 1, -0.3),
    (3, 0, 0.075),
];

/// The height field `z = Σ c·uᵃ·vᵇ` over `[−1, 1]²` (terms `(a, b, c)`), as a Bézier patch.
pub(crate) fn square_graph(terms: Vec<(u32, u32, f64)>) -> crate::geometry::RationalBezierPatch {
    crate::geometry::PowerSurface::graph(crate::geometry::Domain::new(-1.0, 1.0, -1.0, 1.0), terms)
        .to_bezier()
        .unwrap()
}

/// A quarter of the unit cylinder `x² + y² = 1`, `0 ≤ z ≤ 1` (rational, degree 2 × 1, weights
/// `cos 45°` on the middle row), over the unit square.
pub(crate) fn quarter_cylinder() -> crate::geometry::RationalBezierPatch {
    crate::geometry::bezier::quarter_cylinder_over(crate::geometry::Domain::UNIT)
}

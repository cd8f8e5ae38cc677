//! Test surfaces: height fields as Bézier patches, and analytic surfaces of the seed papers.

use ssitrace::geometry::analytic::{AnalyticSurface, Jet2};
use ssitrace::geometry::{Domain, PowerSurface, RationalBezierPatch};

/// The Bézier height field of degree `m × m` over `[0, 1]²` whose control point `(i, j)` is
/// `(i/m, j/m, z[i·(m+1) + j])`.
pub(crate) fn unit_height_patch(m: usize, z: &[f64]) -> RationalBezierPatch {
    let points = (0..=m)
        .flat_map(|i| (0..=m).map(move |j| (i, j)))
        .map(|(i, j)| {
            [i as f64 / m as f64, j as f64 / m as f64, z[i * (m + 1) + j]]
                .map(ssitrace::numeric::scalar::point)
        })
        .collect();
    RationalBezierPatch::new([m, m], points, None, Domain::new(0.0, 1.0, 0.0, 1.0)).unwrap()
}

/// The square `[−1, 1]²`.
pub(crate) const SQUARE: Domain = Domain::new(-1.0, 1.0, -1.0, 1.0);

/// The height field `z = Σ c·uⁱvʲ` over `domain`, terms `(i, j, c)`, as a Bézier patch.
pub(crate) fn height_field(domain: Domain, z: Vec<(u32, u32, f64)>) -> RationalBezierPatch {
    PowerSurface::graph(domain, z)
        .to_bezier()
        .expect("valid height field")
}

/// An analytic surface given by a plain function.
pub(crate) type Analytic = AnalyticSurface<fn(Jet2, Jet2) -> [Jet2; 3]>;

/// The plane `z = 0` over `domain`, parametrised by `(x, y)`.
pub(crate) fn plane_z0(domain: Domain) -> Analytic {
    AnalyticSurface::new(domain, |r, s| [r, s, Jet2::constant(0.0)])
}

/// The S11/S12 pair of seed 000 over `domain`: `z = 0.2u⁴ + 0.1v⁴` and
/// `z = 0.3s²w − 0.1w² + 0.2w³`, meeting in a loop through a branch point and a tangential point.
pub(crate) fn s11_s12(domain: Domain) -> (Analytic, Analytic) {
    (
        AnalyticSurface::new(domain, |u, v| [u, v, 0.2 * u.powi(4) + 0.1 * v.powi(4)]),
        AnalyticSurface::new(domain, |s, w| {
            [s, w, 0.3 * s * s * w - 0.1 * w * w + 0.2 * w.powi(3)]
        }),
    )
}

/// Fig. 8 of the marching paper (the S11/S12 curve, written with a common factor 1/10) over
/// `[−1.8, 1.8] × [−0.3, 2.3]`: `z = (2u⁴ + v⁴)/10` and `z = (3r²s − s² + 2s³)/10`, tangent at
/// the origin.
pub(crate) fn fig8() -> (Analytic, Analytic) {
    let d = Domain::new(-1.8, 1.8, -0.3, 2.3);
    (
        AnalyticSurface::new(d, |u, v| [u, v, (2.0 * u.powi(4) + v.powi(4)) / 10.0]),
        AnalyticSurface::new(d, |r, s| {
            [r, s, (3.0 * r * r * s - s * s + 2.0 * s.powi(3)) / 10.0]
        }),
    )
}

/// The standard nine-point control polygon of the unit circle as four rational quadratic
/// quarters (the square's corners carry the weight √2/2, the rest 1), starting and ending at
/// `(1, 0)`.
pub(crate) const UNIT_CIRCLE_NET: [(f64, f64); 9] = [
    (1.0, 0.0),
    (1.0, 1.0),
    (0.0, 1.0),
    (-1.0, 1.0),
    (-1.0, 0.0),
    (-1.0, -1.0),
    (0.0, -1.0),
    (1.0, -1.0),
    (1.0, 0.0),
];

//! The jet of the intersection curve at a point, graphed over one parameter: the other three
//! parameters' first, second and third derivatives (`f64`, guidance for the cover chain's
//! predictor; nothing about them is claimed).

use crate::geometry::RationalBezierPatch;
use nalgebra::Matrix3;

/// The three coordinates other than `j`, ascending.
pub(crate) fn others(j: usize) -> [usize; 3] {
    match j {
        0 => [1, 2, 3],
        1 => [0, 2, 3],
        2 => [0, 1, 3],
        _ => [0, 1, 2],
    }
}

/// A curve point seen as a point of the graph over coordinate `along`: the other coordinates'
/// values and first, second and third derivatives with respect to `x_along` (`f64`, guidance
/// only).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Jet {
    /// The point `(σ, t, u, v)`.
    pub(crate) x: [f64; 4],
    /// `d x_o / d x_along` for the three others.
    pub(crate) d1: [f64; 3],
    /// `d² x_o / d x_along²` for the three others.
    pub(crate) d2: [f64; 3],
    /// `d³ x_o / d x_along³` for the three others.
    pub(crate) d3: [f64; 3],
}

impl Jet {
    /// The jet of the curve through `x` with parameter velocity `t`, graphed over `along`:
    /// `o' = t_o / t_j`, and `o'' = −F_o⁻¹·F''[d, d]` with `d = (1, o')` (implicit
    /// differentiation of `F(x_j, o(x_j)) = 0`), `o'''` by [`third_derivative`]. `None` if
    /// `t_j = 0` or `F_o` is singular.
    pub(crate) fn new(
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        x: &[f64; 4],
        t: &[f64; 4],
        along: usize,
    ) -> Option<Jet> {
        Self::build(p, q, x, t, along, None)
    }

    /// [`Self::new`] with the coordinate `pin` (not `along`) held: its derivatives are zero,
    /// and the others' come from the curve's equations with `d x_pin = 0`. For an angular parameter
    /// next to a pole, which the point determines only to rounding over the distance to the
    /// pole: the velocity there is that of the field at a point off the curve by that much,
    /// and its angular part and every derivative built on it grow like the inverse of the
    /// distance (and its powers). Guidance only, as any jet.
    pub(crate) fn pinned(
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        x: &[f64; 4],
        t: &[f64; 4],
        along: usize,
        pin: usize,
    ) -> Option<Jet> {
        Self::build(p, q, x, t, along, Some(pin).filter(|&k| k != along))
    }

    /// [`Self::new`] or, with `pin`, [`Self::pinned`].
    fn build(
        p: &RationalBezierPatch,
        q: &RationalBezierPatch,
        x: &[f64; 4],
        t: &[f64; 4],
        along: usize,
        pin: Option<usize>,
    ) -> Option<Jet> {
        if t[along] == 0.0 {
            return None;
        }
        let o = others(along);
        let mut d: [f64; 4] = std::array::from_fn(|i| t[i] / t[along]);
        // The pinned coordinate's place among the others.
        let pinned = pin.and_then(|k| o.iter().position(|&i| i == k));
        if let Some(k) = pin {
            d[k] = 0.0;
        }
        let dp = p.derivs_f64(x[0], x[1]);
        let dq = q.derivs_f64(x[2], x[3]);
        let cols = [dp.su, dp.sv, dq.su.map(|v| -v), dq.sv.map(|v| -v)];
        let fo = Matrix3::from_fn(|r, c| cols[o[c]][r]);
        let second: [f64; 3] = std::array::from_fn(|r| {
            dp.suu[r] * d[0] * d[0] + 2.0 * dp.suv[r] * d[0] * d[1] + dp.svv[r] * d[1] * d[1]
                - (dq.suu[r] * d[2] * d[2]
                    + 2.0 * dq.suv[r] * d[2] * d[3]
                    + dq.svv[r] * d[3] * d[3])
        });
        let inv = fo.try_inverse()?;
        let d2v = -(inv * nalgebra::Vector3::from(second));
        let mut jet = Jet {
            x: *x,
            d1: o.map(|i| d[i]),
            d2: [d2v[0], d2v[1], d2v[2]],
            d3: [0.0; 3],
        };
        if let Some(r) = pinned {
            jet.d2[r] = 0.0;
        }
        jet.d3 = third_derivative(p, q, x, &d, &jet.d2, along, &inv);
        if let Some(r) = pinned {
            jet.d3[r] = 0.0;
        }
        jet.d1
            .iter()
            .chain(&jet.d2)
            .all(|v| v.is_finite())
            .then_some(jet.with_finite_d3())
    }

    /// The jet with `d3` zeroed where it is not finite (the predictor is then guessed with a
    /// zero third derivative there; it is guidance only).
    fn with_finite_d3(mut self) -> Jet {
        if !self.d3.iter().all(|v| v.is_finite()) {
            self.d3 = [0.0; 3];
        }
        self
    }
}

/// `d³ x_o / d x_along³` of the curve through `x` (guidance only, `f64`): along the quadratic
/// graph `y(ξ) = x + d·ξ + e·ξ²` (`e` the others' `d2 / 2`, zero along), `g(ξ) = F(y(ξ))` has
/// `g''(ξ) = F''(y)[y', y'] + F'(y)·y''`; its derivative at 0 comes from a central difference
/// of `g''` at `±h`, and the curve's third coefficient is `c₃ = −F_o⁻¹·g'''(0)/6`. The step
/// `h` is `10⁻³` of the smaller of the along coordinate's domain and the graph's bending
/// length `max|d1| / max|d2|` (truncation error about `(h/ℓ)²` relative, rounding about
/// `ε·ℓ/h`).
fn third_derivative(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    x: &[f64; 4],
    d: &[f64; 4],
    d2: &[f64; 3],
    along: usize,
    inv: &Matrix3<f64>,
) -> [f64; 3] {
    let o = others(along);
    let mut e = [0.0; 4];
    for (r, &i) in o.iter().enumerate() {
        e[i] = 0.5 * d2[r];
    }
    let dom = if along < 2 { p.domain() } else { q.domain() };
    let side = if along.is_multiple_of(2) {
        dom.u
    } else {
        dom.v
    };
    // The length over which the graph's slope changes by about its size: a tight loop (a
    // near-tangent torus, radius 1e-4) needs a step well inside it.
    let slope = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let bend = d2.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let scale = (side[1] - side[0]).min(slope / bend.max(f64::MIN_POSITIVE));
    let h = 1e-3 * scale;
    let g2 = |xi: f64| -> [f64; 3] {
        let y: [f64; 4] = std::array::from_fn(|i| x[i] + (d[i] + e[i] * xi) * xi);
        let dy: [f64; 4] = std::array::from_fn(|i| d[i] + 2.0 * e[i] * xi);
        let dp = p.derivs_f64(y[0], y[1]);
        let dq = q.derivs_f64(y[2], y[3]);
        std::array::from_fn(|r| {
            let quad = |s: &crate::geometry::PatchDerivs<f64>, a: f64, b: f64, ea: f64, eb: f64| {
                s.suu[r] * a * a
                    + 2.0 * s.suv[r] * a * b
                    + s.svv[r] * b * b
                    + 2.0 * (s.su[r] * ea + s.sv[r] * eb)
            };
            quad(&dp, dy[0], dy[1], e[0], e[1]) - quad(&dq, dy[2], dy[3], e[2], e[3])
        })
    };
    let (hi, lo) = (g2(h), g2(-h));
    let g3 = nalgebra::Vector3::from_fn(|r, _| (hi[r] - lo[r]) / (12.0 * h));
    let c3 = -(inv * g3);
    [6.0 * c3[0], 6.0 * c3[1], 6.0 * c3[2]]
}

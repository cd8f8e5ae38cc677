//! The random pair of soak seed 1 005 497 (without its rotation): two bicubic height fields
//! whose intersection has two curves that nearly cross near `(σ, t) ≈ (0.631, 0.680)`.

use inari::{interval, Interval};
use ssitrace::geometry::RationalBezierPatch;

/// Heights of P (bicubic, row `i` for `σ = i/3`).
pub(crate) const F: [f64; 16] = [
    -0.15508506196974167,
    -0.23859780711928655,
    -0.28015772179560555,
    0.2540426435672631,
    0.13808578799750737,
    -0.09488688252111602,
    -0.10499270602065844,
    0.2864442249019779,
    -0.2778684719332966,
    0.12077925209189444,
    0.07551622685773807,
    0.09824896593714516,
    0.08082110293703099,
    -0.05174394139229191,
    0.15187937015288316,
    -0.18028144937220153,
];

/// Heights of Q (bicubic).
pub(crate) const G: [f64; 16] = [
    0.07392655611752857,
    -0.10783668076099179,
    -0.003995702505873389,
    -0.17867774666638914,
    0.28556229901688907,
    0.10956565997194923,
    -0.14581992773512623,
    0.08584199449860519,
    0.04288993518996126,
    0.014209406668136526,
    0.07911441792246243,
    0.23329262893614694,
    -0.11496530533119895,
    -0.005637415291305348,
    -0.08255162307743522,
    0.056983838910329876,
];

pub(crate) fn point(x: f64) -> Interval {
    interval!(x, x).unwrap()
}

/// The bicubic height field with heights `z` over `[0, 1]²`.
pub(crate) fn patch(z: &[f64; 16]) -> RationalBezierPatch {
    super::surfaces::unit_height_patch(3, z)
}

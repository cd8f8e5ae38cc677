//! Phase I: the a-priori enclosure `[ỹ]` of every solution over a whole step `[0, h]`.
//!
//! Two validations, both proving existence and uniqueness on `[0, h]` for every initial value in
//! the box `[y]` (the field is smooth wherever the AD's domain guard let it be evaluated):
//!
//! * **High order** (Corliss & Rihm, "Validating an a priori enclosure using high-order Taylor
//!   series", 1996; also Nedialkov, Jackson & Pryce 2001): with `T = [0, h]`, if
//!   `P + Tᵏ·y_k(Z) ⊆ int Z` where `P = Σ_{i<k} Tⁱ·yᵢ([y])` and `y_k(Z)` encloses the `k`-th
//!   normalised Taylor coefficient of solutions through `Z`, then every solution stays in
//!   `P + Tᵏ·y_k(Z)` on `[0, h]`. `Z` is `P` plus a guessed remainder box, widened a few times.
//! * **First order** (Picard–Lindelöf in interval form, as in Lohner's AWA): if
//!   `[y] + T·f(Z) ⊆ int Z` then every solution stays in `[y] + T·f(Z)`; tried when the
//!   high-order test fails (it tolerates a poorer guess, at the price of a wider box).
//!
//! The remainder coefficient reported is `y_k(Z)` for the high-order test (valid: the solutions
//! stay in `Y ⊆ Z`). After the first-order test, whose `Y` is usually wide, the box is tightened
//! by Taylor's theorem with the Lagrange remainder over `Y`: `y(t) ∈ P(t) + Tᵏ·y_k(Y)`, ∩ `Y`.

use crate::numeric::scalar::interval;
use crate::validated::ad::{DomainError, Expansion, TaylorAd};
use inari::Interval;

/// Which validation proved the a-priori enclosure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EnclosureMethod {
    /// The high-order test (Taylor polynomial plus validated remainder).
    HighOrder,
    /// The first-order (constant-derivative) test.
    FirstOrder,
}

/// A proven a-priori enclosure over `[0, h]`.
#[derive(Clone, Debug)]
pub struct Apriori {
    /// Encloses `y(t)` for all `t ∈ [0, h]` and all initial values in the box.
    pub boxed: Vec<Interval>,
    /// Encloses the `k`-th Taylor coefficient `y_k` of solutions through `boxed` (the remainder
    /// coefficient: `y(t) − Σ_{i<k} yᵢ tⁱ ∈ y_k·tᵏ`).
    pub remainder_coeff: Vec<Interval>,
    /// Which test succeeded.
    pub method: EnclosureMethod,
}

/// Why phase I failed at one step size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EnclosureFailure {
    /// The containment test failed for both methods.
    NotContained,
    /// The field could not be evaluated on a candidate box.
    Domain(DomainError),
    /// Inconsistent arguments (order 0, or an expansion of the wrong order or dimension).
    InvalidArguments,
}

/// `Σ_{i<k} tⁱ cᵢ + tᵏ·rem` per component, by Horner in intervals (`t` may be an interval);
/// `1 ≤ k ≤ exp.order`.
pub(crate) fn taylor_poly(
    exp: &Expansion,
    k: usize,
    t: Interval,
    rem: Option<&[Interval]>,
) -> Vec<Interval> {
    let n = exp.dim;
    let mut acc: Vec<Interval> = match rem {
        Some(r) => r.to_vec(),
        None => exp.coeff(k - 1).to_vec(),
    };
    let start = if rem.is_some() { k } else { k - 1 };
    for i in (0..start).rev() {
        let c = exp.coeff(i);
        for j in 0..n {
            acc[j] = acc[j] * t + c[j];
        }
    }
    acc
}

/// Tries to prove an a-priori enclosure over `[0, h]` for the box `y` whose expansion to order `k`
/// (coefficients only needed) is `exp_box`. `scratch` is reused for further expansions.
pub fn prove_apriori(
    ad: &mut TaylorAd,
    y: &[Interval],
    exp_box: &Expansion,
    k: usize,
    h: f64,
    scratch: &mut Expansion,
) -> Result<Apriori, EnclosureFailure> {
    prove_apriori_with_guess(ad, y, exp_box, k, h, DEFAULT_GUESS_FACTOR, scratch)
}

/// The factor by which the first remainder guess of the high-order test exceeds the remainder
/// term of the initial box's own expansion.
pub const DEFAULT_GUESS_FACTOR: f64 = 1e3;

/// [`prove_apriori`] with the first remainder guess `guess_factor·|y_k([y])·hᵏ|` (plus a small
/// absolute term) instead of `1e3·|…|`. The remainder over the a-priori box usually exceeds the
/// initial box's by a ratio that changes slowly along a trajectory; a caller that remembers it
/// ([`remainder_ratio`]) saves the second expansion of a failed first guess. Any factor is sound.
pub fn prove_apriori_with_guess(
    ad: &mut TaylorAd,
    y: &[Interval],
    exp_box: &Expansion,
    k: usize,
    h: f64,
    guess_factor: f64,
    scratch: &mut Expansion,
) -> Result<Apriori, EnclosureFailure> {
    if k == 0
        || exp_box.order < k
        || exp_box.dim != y.len()
        || exp_box.dim != ad.dim()
        || h.is_nan()
        || h <= 0.0
    {
        return Err(EnclosureFailure::InvalidArguments);
    }
    let t = interval(0.0, h).unwrap_or(Interval::ENTIRE);
    let tk = crate::Scalar::powi(t, k as i32);
    let poly = taylor_poly(exp_box, k, t, None);
    let mut last_domain = None;

    // High order: guess the remainder from the k-th coefficient over the initial box.
    let mut guess: Vec<Interval> = exp_box
        .coeff(k)
        .iter()
        .zip(&poly)
        .map(|(c, p)| {
            // Generous on purpose: Z is dominated by the polynomial part (width ≈ h·|f|), so a
            // large guess costs nothing in tightness (the remainder is recomputed over the proven
            // box afterwards) and usually passes the test at the first evaluation.
            let r = (*c * tk).mag() * guess_factor + 1e-12 * (p.mag() + 1e-3) * h.min(1.0);
            symmetric(r)
        })
        .collect();
    for _ in 0..4 {
        let z: Vec<Interval> = poly.iter().zip(&guess).map(|(p, g)| *p + *g).collect();
        match ad.expand(&z, k, false, scratch) {
            Err(e) => {
                last_domain = Some(e);
                break;
            }
            Ok(()) => {
                let rem: Vec<Interval> = scratch.coeff(k).iter().map(|c| *c * tk).collect();
                if rem.iter().zip(&guess).all(|(r, g)| r.interior(*g)) {
                    let boxed: Vec<Interval> =
                        poly.iter().zip(&rem).map(|(p, r)| *p + *r).collect();
                    // The solutions stay in `boxed ⊆ Z`, so `y_k(Z)` is a valid remainder
                    // coefficient; Z exceeds `boxed` only by the small guessed remainder, so
                    // re-expanding over `boxed` would gain little.
                    return Ok(Apriori {
                        boxed,
                        remainder_coeff: scratch.coeff(k).to_vec(),
                        method: EnclosureMethod::HighOrder,
                    });
                }
                guess = rem
                    .iter()
                    .zip(&guess)
                    .map(|(r, g)| symmetric(r.mag().max(g.mag()) * 1.5 + f64::MIN_POSITIVE))
                    .collect();
            }
        }
    }

    // First order: Z = [y] + [-0.2, 1.2]·h·f([y]) + ε, then Y = [y] + [0,h]·f(Z) ⊂ int Z.
    let f0 = exp_box.coeff(1);
    let spread = interval(-0.2 * h, 1.2 * h).unwrap_or(Interval::ENTIRE);
    let mut z: Vec<Interval> = y
        .iter()
        .zip(f0)
        .map(|(yj, fj)| *yj + spread * *fj + symmetric(1e-12 * (yj.mag() + 1.0)))
        .collect();
    for _ in 0..6 {
        match ad.expand(&z, 1, false, scratch) {
            Err(e) => {
                last_domain = Some(e);
                break;
            }
            Ok(()) => {
                let w: Vec<Interval> = y
                    .iter()
                    .zip(scratch.coeff(1))
                    .map(|(yj, fj)| *yj + t * *fj)
                    .collect();
                if w.iter().zip(&z).all(|(wj, zj)| wj.interior(*zj)) {
                    return tighten(ad, exp_box, k, t, w, EnclosureMethod::FirstOrder, scratch);
                }
                z = w
                    .iter()
                    .zip(&z)
                    .map(|(wj, zj)| {
                        let hull = wj.convex_hull(*zj);
                        hull + symmetric(0.1 * hull.rad() + 1e-12 * (hull.mag() + 1.0))
                    })
                    .collect();
            }
        }
    }
    Err(match last_domain {
        Some(e) => EnclosureFailure::Domain(e),
        None => EnclosureFailure::NotContained,
    })
}

/// The largest ratio, over the components, of the proven remainder coefficient `a` to the
/// initial box's own order-`k` coefficient (what [`prove_apriori_with_guess`]'s factor had to
/// exceed); `None` where undefined (a zero or unbounded coefficient).
pub fn remainder_ratio(a: &Apriori, exp_box: &Expansion, k: usize) -> Option<f64> {
    let mut ratio: Option<f64> = None;
    for (r, c) in a.remainder_coeff.iter().zip(exp_box.coeff(k)) {
        let (rm, cm) = (r.mag(), c.mag());
        if cm > 0.0 && rm.is_finite() && cm.is_finite() {
            ratio = Some(ratio.map_or(rm / cm, |x| x.max(rm / cm)));
        }
    }
    ratio
}

/// Given a proven enclosure `boxed`, encloses the remainder coefficient over it and intersects
/// `boxed` with the Taylor polynomial plus remainder over `[0, h]`.
fn tighten(
    ad: &mut TaylorAd,
    exp_box: &Expansion,
    k: usize,
    t: Interval,
    boxed: Vec<Interval>,
    method: EnclosureMethod,
    scratch: &mut Expansion,
) -> Result<Apriori, EnclosureFailure> {
    ad.expand(&boxed, k, false, scratch)
        .map_err(EnclosureFailure::Domain)?;
    let remainder_coeff = scratch.coeff(k).to_vec();
    let poly = taylor_poly(exp_box, k, t, Some(&remainder_coeff));
    let tight: Vec<Interval> = boxed
        .iter()
        .zip(&poly)
        .map(|(b, p)| {
            let c = b.intersection(*p);
            // Both enclose the solution set, so the intersection is non-empty in exact arithmetic;
            // guard anyway.
            if c.is_empty() {
                *b
            } else {
                c
            }
        })
        .collect();
    Ok(Apriori {
        boxed: tight,
        remainder_coeff,
        method,
    })
}

/// Tightens the remainder coefficient of a proven a-priori enclosure: the solutions visit, over
/// the piece `[tₘ, tₘ₊₁]` of `[0, h]`, only `Zₘ = (Σ_{i<k} yᵢ([y]) tⁱ + y_k([ỹ]) tᵏ) ∩ [ỹ]`, so the
/// Lagrange remainder `y_k(y(ξ))`, `ξ ∈ [0, h]`, lies in the hull of the `y_k(Zₘ)` (and in
/// `y_k([ỹ])`; the result is the intersection). Interval Taylor coefficients over a box grow much
/// faster than linearly with its size, so `pieces` boxes a `pieces`-th of the length give a far
/// smaller remainder, hence longer steps. Falls back to the given coefficient where an expansion
/// fails.
pub(crate) fn refine_remainder(
    ad: &mut TaylorAd,
    exp_box: &Expansion,
    k: usize,
    h: f64,
    apriori: &Apriori,
    pieces: usize,
    scratch: &mut Expansion,
) -> Vec<Interval> {
    let rem = &apriori.remainder_coeff;
    let bounds: Vec<f64> = (0..=pieces)
        .map(|m| {
            if m == pieces {
                h
            } else {
                h * m as f64 / pieces as f64
            }
        })
        .collect();
    let mut hull: Option<Vec<Interval>> = None;
    for m in 0..pieces {
        let Some(t) = interval(bounds[m], bounds[m + 1]) else {
            return rem.clone();
        };
        let z: Vec<Interval> = taylor_poly(exp_box, k, t, Some(rem))
            .iter()
            .zip(&apriori.boxed)
            .map(|(p, b)| {
                let c = p.intersection(*b);
                if c.is_empty() {
                    *b
                } else {
                    c
                }
            })
            .collect();
        if ad.expand(&z, k, false, scratch).is_err() {
            return rem.clone();
        }
        let c = scratch.coeff(k);
        hull = Some(match hull {
            None => c.to_vec(),
            Some(hv) => hv.iter().zip(c).map(|(a, b)| a.convex_hull(*b)).collect(),
        });
    }
    match hull {
        Some(hv) => hv
            .iter()
            .zip(rem)
            .map(|(a, r)| {
                let c = a.intersection(*r);
                if c.is_empty() {
                    *r
                } else {
                    c
                }
            })
            .collect(),
        None => rem.clone(),
    }
}

/// The interval `[−r, r]` (r ≥ 0; non-finite r gives the whole line).
pub fn symmetric(r: f64) -> Interval {
    if r.is_finite() {
        interval(-r, r).unwrap_or(Interval::ENTIRE)
    } else {
        Interval::ENTIRE
    }
}

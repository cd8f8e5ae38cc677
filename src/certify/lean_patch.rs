//! A patch as a link proof of the cover chain sees it: the point and its first partials along a
//! link, written around a centre near the link in the power basis.
//!
//! A link proof ([`crate::certify::segment`]) evaluates both patches along the link's predictor
//! in truncated series arithmetic, where every product of two series costs `O(N²)`. The
//! Bernstein form of a degree-`(m, n)` patch spends most of its products on the basis functions
//! (about `m² + n²`) and on all four homogeneous coordinates, even where a coordinate is affine
//! (the `x` and `y` of a height field) and the weight is one. For a polynomial patch (all weights
//! equal and exact, [`PowerNet`]) this form instead encloses, once per link, the Taylor
//! coefficients `T_kl` of each coordinate at a centre `c` (intervals, outward rounded), and
//! evaluates `S = Σ T_kl dsᵏ drˡ` with `ds = (u − c_u)/Δu`, `dr = (v − c_v)/Δv` by Horner's rule,
//! skipping the coefficients that are exactly zero: a height field's `x` and `y` cost no series
//! product at all, its height one per monomial. The function is the patch's (a polynomial equals
//! its Taylor expansion at any point); every coefficient is an enclosure, so every value is too,
//! and near the centre the form is a centred one (tight).
//!
//! A rational patch is written the same way in its homogeneous coordinates `H = (w·x, w·y, w·z,
//! w)`, each a polynomial, and divided once: `S = H_xyz / H_w`, `S_u = (H_xyz,u − S·H_w,u) / H_w`
//! (the quotient rule; every step an enclosure, the weight's range positive). The Bernstein
//! form it replaces spends a series product on every basis function and row sum (on the
//! cylinders 40 % of a chain's time was there); its second partials, formed once per link over
//! a box, stay the patch's own.

use crate::certify::contact_patch::PowerNet;
use crate::geometry::bernstein::{bernstein_products as bernstein, binomial};
use crate::geometry::RationalBezierPatch;
use crate::numeric::imul::mul as imul;
use crate::numeric::rounding::mul_dir;
use crate::numeric::scalar::point;
use crate::Scalar;
use inari::Interval;
use std::borrow::Cow;
use std::cell::RefCell;
use std::rc::Rc;

/// A patch with its forward differences prepared: of its Cartesian net when it is polynomial,
/// of its homogeneous net otherwise.
#[derive(Debug, Clone)]
pub(crate) struct LeanPatch<'a> {
    patch: Cow<'a, RationalBezierPatch>,
    /// The patch as given (before any move: the moved net is an interval one).
    source: &'a RationalBezierPatch,
    /// The patch is moved by `−shift` ([`LeanPatch::moved`]): every value is `P − shift`.
    shift: [f64; 3],
    power: PowerNet,
    /// The last centred form, reused for centres near its own ([`REUSE`]).
    last: RefCell<Option<Rc<Taylor>>>,
}

/// A centred form is reused for a new centre within this part of the domain's width from its
/// own in both parameters: the form is the patch's exactly wherever it is evaluated, only a
/// little less tight away from its centre, and forming it costs a tenth of a link proof.
const REUSE: f64 = 0.05;

impl<'a> LeanPatch<'a> {
    /// The patch with its differences: Cartesian if all its weights are equal and exact,
    /// homogeneous otherwise.
    pub(crate) fn new(patch: &'a RationalBezierPatch) -> Self {
        Self::of(Cow::Borrowed(patch), patch, [0.0; 3])
    }

    /// The patch moved by `−by` ([`RationalBezierPatch::translated`]): its values are
    /// `P − by`, its derivatives `P`'s. The differences of two patches moved alike are theirs;
    /// next to a point `by` where the numerators of a rational patch's terms nearly cancel (a
    /// pole), its second partials are far tighter. `None` if the moved net overflows.
    pub(crate) fn moved(patch: &'a RationalBezierPatch, by: [f64; 3]) -> Option<Self> {
        Some(Self::of(Cow::Owned(patch.translated(by)?), patch, by))
    }

    fn of(
        patch: Cow<'a, RationalBezierPatch>,
        source: &'a RationalBezierPatch,
        shift: [f64; 3],
    ) -> Self {
        let power = PowerNet::of(&patch).unwrap_or_else(|| PowerNet::homogeneous(&patch));
        LeanPatch {
            patch,
            source,
            shift,
            power,
            last: RefCell::new(None),
        }
    }

    /// What every value of the patch is moved by (subtracted): zero unless [`Self::moved`].
    pub(crate) fn shift(&self) -> [f64; 3] {
        self.shift
    }

    /// The patch as given, not moved (its differences are the lean form's).
    pub(crate) fn source(&self) -> &'a RationalBezierPatch {
        self.source
    }

    /// The relative cost of an evaluation: coefficients per coordinate times the coordinates
    /// (four for the homogeneous form of a rational patch).
    fn eval_cost(&self) -> usize {
        let [m, n] = self.patch.degree();
        let coords = self.power.diffs.first().map_or(3, |d| d.len());
        (m + 1) * (n + 1) * coords
    }

    /// The patch written around `(cu, cv)` (any finite point; the lean form is tightest near
    /// it), with every term kept: valid wherever it is evaluated.
    #[cfg(test)]
    pub(crate) fn centred(&self, cu: f64, cv: f64) -> Centred<'_> {
        self.centred_within(cu, cv, None)
    }

    /// The patch written around `(cu, cv)` for evaluations inside `window` (a parameter box
    /// `[u, v]`; `None`: anywhere): the terms that are negligible over the window
    /// ([`DROPPED`]) are replaced by a bound on their sum, which saves their series products.
    /// The form is valid only inside its window: check [`Centred::covers`] for every box it
    /// is evaluated on.
    pub(crate) fn centred_within(
        &self,
        cu: f64,
        cv: f64,
        window: Option<[Interval; 2]>,
    ) -> Centred<'_> {
        let net = &self.power;
        let taylor = (cu.is_finite() && cv.is_finite()).then(|| {
            let d = self.patch.domain();
            let near = |t: &Taylor| {
                (t.centre[0] - cu).abs() <= REUSE * (d.u[1] - d.u[0])
                    && (t.centre[1] - cv).abs() <= REUSE * (d.v[1] - d.v[0])
            };
            let mut last = self.last.borrow_mut();
            match last.as_ref().filter(|t| near(t)) {
                Some(t) => Rc::clone(t),
                None => {
                    let t = Rc::new(Taylor::at(&self.patch, net, cu, cv));
                    *last = Some(Rc::clone(&t));
                    t
                }
            }
        });
        Centred {
            patch: &self.patch,
            taylor: taylor.map(|t| {
                let tr = t.truncated(window);
                (t, tr)
            }),
        }
    }
}

/// The first coordinate (0 for the first patch, 2 for the second) of the patch whose
/// evaluation costs at least four times the other's ([`LeanPatch::eval_cost`]), if one does.
pub(crate) fn costlier_side(lean: &[LeanPatch<'_>; 2]) -> Option<usize> {
    let (cp, cq) = (lean[0].eval_cost(), lean[1].eval_cost());
    if cp >= 4 * cq {
        Some(0)
    } else if cq >= 4 * cp {
        Some(2)
    } else {
        None
    }
}

/// A patch written around a centre ([`LeanPatch::centred`]).
#[derive(Debug, Clone)]
pub(crate) struct Centred<'a> {
    patch: &'a RationalBezierPatch,
    /// The Taylor form (polynomial patches and homogeneous forms) and its truncation for the
    /// window.
    taylor: Option<(Rc<Taylor>, Rc<Truncated>)>,
}

/// The derivative orders `(a, b)` (of `∂^(a+b)/∂uᵃ∂vᵇ`) a centred form provides: the point,
/// the first and the second partials.
const ORDERS: [(usize, usize); 6] = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];

/// A term is dropped from a truncated form when its size over the window, `|T_kl|·ρ_uᵏ·ρ_vˡ`,
/// is at most this part (`2⁻⁶⁰`) of the largest term's of its coordinate: below the rounding of
/// the coordinate's value. The terms a polynomial patch's Taylor form holds only by rounding
/// (a height field's `x = u` written in degree 6 has 44 coefficients that are intervals of width
/// 1e-16 around zero) and the terms above a polynomial's total degree are all such terms.
const DROPPED: f64 = 8.673_617_379_884_035e-19;

/// A term whose coefficient holds zero (its sign unknown: a rounding artefact, or an
/// uncertain input) is dropped when its size is at most this part (`2⁻⁴⁰`) of the largest
/// term's: its contribution to the value's width is then its size anyway.
const UNSIGNED: f64 = 9.094_947_017_729_282e-13;

/// Forms of fewer terms per coordinate than this (below bicubic) are not truncated.
const FEW_TERMS: usize = 16;

/// `2⁻¹⁰⁰⁰`: more than the underflow error of any truncated form's bound.
const UNDERFLOW_PAD: f64 = 9.332_636_185_032_189e-302;

/// Smallest window radius (in offsets normalised by the domain's width): below it the dropped
/// terms' bounds stop shrinking.
const MIN_RADIUS: f64 = 9.5367431640625e-7;

/// A Taylor form with its negligible terms replaced by bounds, valid over a window of offsets.
#[derive(Debug, Clone)]
struct Truncated {
    /// The window's half-widths `ρ` in normalised offsets (powers of two); `None`: no window,
    /// every term kept.
    radius: Option<[f64; 2]>,
    /// Per coordinate, per entry of [`ORDERS`], the derivative's form.
    forms: Vec<[DerivativeForm; 6]>,
}

/// One derivative `∂^(a+b)/∂uᵃ∂vᵇ` of one coordinate, as a polynomial in the normalised
/// offsets: `Σ c_kl·dsᵏ·drˡ + rest`.
#[derive(Debug, Clone)]
struct DerivativeForm {
    /// Degrees of the kept polynomial (`m − a`, `n − b`).
    km: usize,
    ln: usize,
    /// `c_kl = T_{k+a,l+b}·(k+a)!/k!·(l+b)!/l!·Δu⁻ᵃ·Δv⁻ᵇ` at `k·(ln+1) + l`, zero where
    /// dropped.
    c: Vec<Interval>,
    /// `[−ε, ε]`: the dropped terms' derivative over the window is within it (exactly 0 if
    /// none was dropped); `None` if the derivative vanishes (`a > m` or `b > n`).
    rest: Option<Interval>,
}

/// The Taylor coefficients of a polynomial patch at a centre, in the normalised offsets.
#[derive(Debug, Clone)]
struct Taylor {
    m: usize,
    n: usize,
    centre: [f64; 2],
    /// `1/Δu`, `1/Δv` (enclosures).
    inv: [Interval; 2],
    /// Per coordinate (`x, y, z`, and `w` for a rational patch's homogeneous form), `T_kl` at
    /// index `k·(n+1) + l`.
    coeffs: Vec<Vec<Interval>>,
    /// The last truncated form made from it (links in a row share their window's size).
    last_truncated: RefCell<Option<Rc<Truncated>>>,
}

impl Taylor {
    fn at(patch: &RationalBezierPatch, net: &PowerNet, cu: f64, cv: f64) -> Taylor {
        let (m, n) = (net.m, net.n);
        let d = patch.domain();
        let du = point(d.u[1]) - point(d.u[0]);
        let dv = point(d.v[1]) - point(d.v[0]);
        let cs = (point(cu) - point(d.u[0])) / du;
        let cr = (point(cv) - point(d.v[0])) / dv;
        let bs: Vec<Vec<Interval>> = (0..=m).map(|k| bernstein(m - k, cs)).collect();
        let br: Vec<Vec<Interval>> = (0..=n).map(|l| bernstein(n - l, cr)).collect();
        let coords = net.diffs.first().map_or(0, |d| d.len());
        let coeffs = (0..coords)
            .map(|x| {
                let mut out = vec![point(0.0); (m + 1) * (n + 1)];
                for k in 0..=m {
                    for l in 0..=n {
                        let Some(diffs) = net.diffs[k * (n + 1) + l][x].as_ref() else {
                            continue;
                        };
                        // Σ_i bs_i·(Σ_j Δ_ij·br_j), with the branch-free product.
                        let mut acc = point(0.0);
                        for i in 0..=m - k {
                            let row = &diffs[i * (n - l + 1)..(i + 1) * (n - l + 1)];
                            let mut inner = point(0.0);
                            for (d, b) in row.iter().zip(&br[l]) {
                                inner += imul(*d, *b);
                            }
                            acc += imul(inner, bs[k][i]);
                        }
                        out[k * (n + 1) + l] = imul(acc, point(binomial(m, k) * binomial(n, l)));
                    }
                }
                out
            })
            .collect();
        Taylor {
            m,
            n,
            centre: [cu, cv],
            inv: [point(1.0) / du, point(1.0) / dv],
            coeffs,
            last_truncated: RefCell::new(None),
        }
    }

    /// The window's radius in normalised offsets, per parameter: the smallest power of two
    /// (at least [`MIN_RADIUS`]) that holds every offset of the box, or `None` if none does.
    fn radius_of(&self, window: [Interval; 2]) -> Option<[f64; 2]> {
        let mut out = [0.0; 2];
        for p in 0..2 {
            let reach = imul(window[p] - point(self.centre[p]), self.inv[p]).mag();
            if !reach.is_finite() {
                return None;
            }
            let mut r = MIN_RADIUS;
            while r < reach {
                r *= 2.0;
            }
            out[p] = r;
        }
        Some(out)
    }

    /// The form truncated for `window` (made, or the last one if its radius is the same).
    fn truncated(&self, window: Option<[Interval; 2]>) -> Rc<Truncated> {
        // Low degrees have few terms to drop: their whole forms are cheaper than truncating.
        let few = (self.m + 1) * (self.n + 1) < FEW_TERMS;
        let radius = window.filter(|_| !few).and_then(|w| self.radius_of(w));
        let mut last = self.last_truncated.borrow_mut();
        // A form made for a window up to four times as wide serves too (valid on any part of
        // its window, the dropped terms' bounds a little wider).
        let serves = |t: &Truncated| match (t.radius, radius) {
            (Some(have), Some(need)) => {
                (0..2).all(|p| need[p] <= have[p] && have[p] <= 4.0 * need[p])
            }
            (have, need) => have == need,
        };
        if let Some(t) = last.as_ref().filter(|t| serves(t)) {
            return Rc::clone(t);
        }
        // Made for twice the window, so that the next links, a little further from the centre,
        // find it too.
        let radius = radius.map(|r| r.map(|x| 2.0 * x));
        let t = Rc::new(Truncated {
            radius,
            forms: (0..self.coeffs.len())
                .map(|x| self.derivative_forms(x, radius))
                .collect(),
        });
        *last = Some(Rc::clone(&t));
        t
    }

    /// The forms of the derivatives [`ORDERS`] of coordinate `x`, without the terms that are
    /// negligible over `radius` ([`DROPPED`], [`UNSIGNED`]) but with a bound on them.
    fn derivative_forms(&self, x: usize, radius: Option<[f64; 2]>) -> [DerivativeForm; 6] {
        let (m, n, t) = (self.m, self.n, &self.coeffs[x]);
        // ρᵏ rounded upward (exact powers of two unless they underflow): upper bounds, so the
        // products below only err by their own rounding.
        let [rs, rr] = radius.unwrap_or([1.0; 2]);
        let powers = |r: f64, d: usize| {
            let mut p = vec![1.0; d + 1];
            for k in 1..=d {
                p[k] = mul_dir(p[k - 1], r, true);
            }
            p
        };
        let (ps, pr) = (powers(rs, m), powers(rr, n));
        // Whether term (k, l) is dropped: a choice only, so f64 is fine.
        let size = |i: usize| t[i].mag() * ps[i / (n + 1)] * pr[i % (n + 1)];
        let dropped: Vec<bool> = match radius {
            None => vec![false; t.len()],
            Some(_) => {
                let largest = (0..t.len()).map(size).fold(0.0, f64::max);
                (0..t.len())
                    .map(|i| {
                        let sz = size(i);
                        sz <= DROPPED * largest || (t[i].contains(0.0) && sz <= UNSIGNED * largest)
                    })
                    .collect()
            }
        };
        let falling = |top: usize, k: usize| ((top - k + 1)..=top).product::<usize>() as f64;
        ORDERS.map(|(a, b)| {
            if a > m || b > n {
                return DerivativeForm {
                    km: 0,
                    ln: 0,
                    c: vec![point(0.0)],
                    rest: None,
                };
            }
            let (km, ln) = (m - a, n - b);
            let mut c = vec![point(0.0); (km + 1) * (ln + 1)];
            // Σ over the dropped terms of |T|·falling·ρ_uᵏ·ρ_vˡ (non-negative terms, the powers
            // upper bounds) in round-to-nearest, then enlarged by the relative error of N such
            // sums and products ((N + 2)·2⁻⁵³, with room to spare) and a pad for the absolute
            // error of products that underflow (each below 2⁻¹⁰⁷⁵), as `DotAcc` bounds its sums.
            let (mut rest, mut terms) = (0.0, 0.0);
            for k in 0..=km {
                for l in 0..=ln {
                    let i = (k + a) * (n + 1) + l + b;
                    let f = falling(k + a, a) * falling(l + b, b);
                    if dropped[i] {
                        rest += t[i].mag() * f * ps[k] * pr[l];
                        terms += 1.0;
                    } else {
                        c[k * (ln + 1) + l] = if f == 1.0 { t[i] } else { imul(t[i], point(f)) };
                    }
                }
            }
            let e = if terms == 0.0 {
                0.0
            } else {
                (rest * (1.0 + (terms + 4.0) * f64::EPSILON) + UNDERFLOW_PAD).next_up()
            };
            // The chain rule's factors 1/Δuᵃ·1/Δvᵇ, once here rather than at every evaluation.
            let mut scale = point(1.0);
            for _ in 0..a {
                scale = imul(scale, self.inv[0]);
            }
            for _ in 0..b {
                scale = imul(scale, self.inv[1]);
            }
            let nonzero = |x: &Interval| !(x.inf() == 0.0 && x.sup() == 0.0);
            if a + b > 0 {
                for x in c.iter_mut().filter(|x| nonzero(x)) {
                    *x = imul(*x, scale);
                }
            }
            let rest = inari::interval!(-e, e).unwrap_or(Interval::ENTIRE);
            DerivativeForm {
                km,
                ln,
                c,
                rest: Some(if a + b > 0 { imul(rest, scale) } else { rest }),
            }
        })
    }

    /// Whether the coefficients are of the homogeneous form (a rational patch).
    fn rational(&self) -> bool {
        self.coeffs.len() == 4
    }

    /// The normalised offsets `(ds, dr)` of `(u, v)`.
    fn offsets<S: Scalar>(&self, u: S, v: S) -> (S, S) {
        (
            (u - S::from_f64(self.centre[0])) * S::from_interval(self.inv[0]),
            (v - S::from_f64(self.centre[1])) * S::from_interval(self.inv[1]),
        )
    }

    /// `Σ_{k,l} c(k, l)·dsᵏ·drˡ` over `k ≤ km`, `l ≤ ln` by Horner's rule in `dr`, then in `ds`,
    /// without the terms whose coefficient is exactly zero. The inner rule runs `(km + 1)·ln`
    /// products and the outer `km`, so the variable with fewer stored terms (a link's along
    /// coordinate is an affine series) goes inside; the value is the same polynomial either way.
    fn horner<S: Scalar>(
        km: usize,
        ln: usize,
        c: impl Fn(usize, usize) -> Interval,
        ds: S,
        dr: S,
    ) -> S {
        if ds.terms() < dr.terms() {
            return Self::horner_in(ln, km, |l, k| c(k, l), dr, ds);
        }
        Self::horner_in(km, ln, c, ds, dr)
    }

    /// Horner's rule in `dr` inside, `ds` outside (see [`Self::horner`]).
    fn horner_in<S: Scalar>(
        km: usize,
        ln: usize,
        c: impl Fn(usize, usize) -> Interval,
        ds: S,
        dr: S,
    ) -> S {
        // The accumulators stay unset (`*_set` false) until their first nonzero term, which
        // saves the products of zero with the argument.
        let nonzero = |x: Interval| !(x.inf() == 0.0 && x.sup() == 0.0);
        let (mut outer, mut outer_set) = (S::zero(), false);
        for k in (0..=km).rev() {
            let (mut inner, mut inner_set) = (S::zero(), false);
            for l in (0..=ln).rev() {
                let a = c(k, l);
                if inner_set {
                    inner = inner * dr;
                }
                if nonzero(a) {
                    let a = S::from_interval(a);
                    inner = if inner_set { inner + a } else { a };
                    inner_set = true;
                }
            }
            if outer_set {
                outer = outer * ds;
            }
            if inner_set {
                outer = if outer_set { outer + inner } else { inner };
                outer_set = true;
            }
        }
        outer
    }

    /// The partial derivative `∂^(a+b) / ∂uᵃ ∂vᵇ` of coordinate `x` (the point for `(0, 0)`)
    /// from the truncated form `tr` (for offsets inside its window): Horner's rule on the kept
    /// coefficients, plus the dropped terms' bound.
    fn derivative<S: Scalar>(
        &self,
        tr: &Truncated,
        x: usize,
        a: usize,
        b: usize,
        ds: S,
        dr: S,
    ) -> S {
        let k = ORDERS
            .iter()
            .position(|&o| o == (a, b))
            .expect("a derivative order the form provides");
        let form = &tr.forms[x][k];
        let Some(rest) = form.rest else {
            return S::zero();
        };
        let ln = form.ln;
        let d = Self::horner(form.km, ln, |k, l| form.c[k * (ln + 1) + l], ds, dr);
        if rest.sup() > 0.0 {
            d + S::from_interval(rest)
        } else {
            d
        }
    }
}

impl Centred<'_> {
    /// Whether the box `[u, v]` lies inside the form's window (always, without a window or a
    /// Taylor form): every evaluation of a truncated form must be.
    pub(crate) fn covers(&self, u: Interval, v: Interval) -> bool {
        let Some((t, tr)) = &self.taylor else {
            return true;
        };
        let Some(radius) = tr.radius else {
            return true;
        };
        [u, v]
            .iter()
            .enumerate()
            .all(|(p, x)| imul(*x - point(t.centre[p]), t.inv[p]).mag() <= radius[p])
    }

    /// The second partials `[S_uu, S_uv, S_vv]` at `(u, v)` (as the fields of
    /// [`RationalBezierPatch::eval_derivs`]).
    pub(crate) fn second_partials<S: Scalar>(&self, u: S, v: S) -> [[S; 3]; 3] {
        let Some((t, tr)) = self.taylor.as_ref().filter(|(t, _)| !t.rational()) else {
            let d = self.patch.eval_derivs(u, v);
            return [d.suu, d.suv, d.svv];
        };
        let (ds, dr) = t.offsets(u, v);
        let per: [[S; 3]; 3] = std::array::from_fn(|x| {
            [(2, 0), (1, 1), (0, 2)].map(|(a, b)| t.derivative(tr, x, a, b, ds, dr))
        });
        std::array::from_fn(|d| std::array::from_fn(|x| per[x][d]))
    }

    /// The point at `(u, v)` (as [`RationalBezierPatch::eval`]).
    pub(crate) fn eval<S: Scalar>(&self, u: S, v: S) -> [S; 3] {
        let Some((t, tr)) = &self.taylor else {
            return self.patch.eval(u, v);
        };
        let (ds, dr) = t.offsets(u, v);
        if t.rational() {
            let w = t.derivative(tr, 3, 0, 0, ds, dr);
            return std::array::from_fn(|x| t.derivative(tr, x, 0, 0, ds, dr) / w);
        }
        std::array::from_fn(|x| t.derivative(tr, x, 0, 0, ds, dr))
    }

    /// The first partials `[S_u, S_v]` at `(u, v)` (as the last two of
    /// [`RationalBezierPatch::first_derivs`]; the point is not formed).
    pub(crate) fn partials<S: Scalar>(&self, u: S, v: S) -> [[S; 3]; 2] {
        let Some((t, tr)) = &self.taylor else {
            let [_, su, sv] = self.patch.first_derivs(u, v);
            return [su, sv];
        };
        let (ds, dr) = t.offsets(u, v);
        if t.rational() {
            let w = t.derivative(tr, 3, 0, 0, ds, dr);
            let (wu, wv) = (
                t.derivative(tr, 3, 1, 0, ds, dr),
                t.derivative(tr, 3, 0, 1, ds, dr),
            );
            let point: [S; 3] = std::array::from_fn(|x| t.derivative(tr, x, 0, 0, ds, dr) / w);
            return [(1, 0, wu), (0, 1, wv)].map(|(a, b, wd)| {
                std::array::from_fn(|x| (t.derivative(tr, x, a, b, ds, dr) - point[x] * wd) / w)
            });
        }
        [
            std::array::from_fn(|x| t.derivative(tr, x, 1, 0, ds, dr)),
            std::array::from_fn(|x| t.derivative(tr, x, 0, 1, ds, dr)),
        ]
    }
}

#[cfg(test)]
#[path = "lean_patch/tests.rs"]
mod tests;

//! Taylor-mode automatic differentiation over intervals, with Jacobians ∂yᵢ/∂y₀.
//!
//! Given a recorded field ([`Tape`]) and an initial box `[y₀]`, [`TaylorAd::expand`] computes the
//! normalised Taylor coefficients `yᵢ = y⁽ⁱ⁾(0)/i!` of the solution of `y' = f(y)`, `y(0) = y₀`,
//! enclosing them for every `y₀` in the box. It uses the classical recurrences: the series of `y`
//! is known to order `i`, every operation of the tape then yields its own coefficient `i` from the
//! coefficients `0..=i` of its operands (a product needs a convolution, a quotient and a square
//! root solve the convolution for the new coefficient), and `y_{i+1} = f_i/(i+1)`. Cost: `O(k²)`
//! interval operations per tape operation for order `k`.
//!
//! **Jacobians (choice and why).** Phase II needs `Jᵢ = ∂yᵢ/∂y₀` enclosed over the whole box. We
//! differentiate the same recurrences in forward mode: every tape operation carries, next to its
//! coefficient series, `n` series of partial derivatives (one per initial coordinate), updated by
//! the product rule applied to each recurrence (e.g. `d(ab)ᵢ = Σ daₘ b_{i−m} + aₘ db_{i−m}`). This
//! is exactly "Taylor series over forward-mode duals", but done in one pass over a flat buffer
//! instead of through a nested generic type: it reuses the coefficients already computed, costs
//! `O(n k²)` per operation (the variational equation integrated with the same machinery costs the
//! same but needs a second, larger tape), and keeps everything in plain interval arithmetic.
//!
//! Domain guard: a quotient whose divisor's value may be zero, or a square root whose argument may
//! be ≤ 0, makes the expansion fail with [`DomainError`] instead of producing a silently restricted
//! or empty interval (an empty interval would pass every containment test).

use crate::numeric::dot::{DotAcc, InariDot, IntervalDot};
use crate::numeric::imul::mul as imul;
use crate::numeric::scalar::point;
use crate::validated::tape::{Op, Tape};
use inari::{const_interval, Interval};

/// Orders computed with `inari`'s one-operation-at-a-time rounding by [`TaylorAd::expand_tight`].
pub const TIGHT_ORDERS: usize = 8;

const ZERO: Interval = const_interval!(0.0, 0.0);

pub use crate::error::DomainError;

/// Taylor coefficients of the solution (and optionally their Jacobians) for one initial box.
#[derive(Clone, Debug, Default)]
pub struct Expansion {
    /// Dimension `n`.
    pub dim: usize,
    /// Highest order `k` computed: `coeffs` holds `y₀ … y_k`.
    pub order: usize,
    /// `coeffs[i*n + j]` encloses the `j`-th component of `yᵢ`.
    pub coeffs: Vec<Interval>,
    /// Number of orders with Jacobians (0 if none were asked for): `Jᵢ` for `i < jac_orders`.
    pub jac_orders: usize,
    /// `jac[(i*n + j)*n + l]` encloses `∂y_{i,j}/∂y_{0,l}` over the box.
    pub jac: Vec<Interval>,
}

impl Expansion {
    /// The coefficient vector `yᵢ` (`i ≤ order`).
    pub fn coeff(&self, i: usize) -> &[Interval] {
        &self.coeffs[i * self.dim..(i + 1) * self.dim]
    }
    /// The Jacobian `Jᵢ` row-major (`i < jac_orders`).
    pub fn jacobian(&self, i: usize) -> &[Interval] {
        let nn = self.dim * self.dim;
        &self.jac[i * nn..(i + 1) * nn]
    }
}

/// Work done by a [`TaylorAd`] since it was created (for profiling; counts only).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct AdWork {
    /// Number of expansions.
    pub expansions: usize,
    /// Σ (order + 1)² over the expansions: the coefficient recurrences' cost, in units of one
    /// order-0 pass over the tape.
    pub coefficient_units: f64,
    /// Σ n·(order + 1)² over the expansions with Jacobians: their extra cost, same unit.
    pub jacobian_units: f64,
}

/// Taylor-mode AD engine for one recorded field, with reusable work buffers.
#[derive(Clone, Debug)]
pub struct TaylorAd {
    tape: Tape,
    coef: Vec<Interval>,
    dcoef: Vec<Interval>,
    work: AdWork,
}

impl TaylorAd {
    /// An engine for the recorded field `tape`.
    pub fn new(tape: Tape) -> Self {
        TaylorAd {
            tape,
            coef: Vec::new(),
            dcoef: Vec::new(),
            work: AdWork::default(),
        }
    }

    /// The work done so far (counts of expansions and their recurrence costs).
    pub fn work(&self) -> AdWork {
        self.work
    }

    /// The dimension of the field.
    pub fn dim(&self) -> usize {
        self.tape.dim
    }

    /// Number of recorded operations (a measure of the cost of one expansion).
    pub fn tape_len(&self) -> usize {
        self.tape.ops.len()
    }

    /// Encloses the Taylor coefficients `y₀ … y_order` of the solution through every point of the
    /// box `y0` (`y0.len() == dim`), and, if `with_jacobian`, the Jacobians `Jᵢ = ∂yᵢ/∂y₀` for
    /// `i < order`. Every returned interval is bounded and non-empty.
    ///
    /// Convolutions use the fast a-posteriori-bounded sums of [`DotAcc`] (a few ulps wider per
    /// coefficient than one-operation-at-a-time outward rounding); [`expand_tight`](Self::expand_tight)
    /// uses plain `inari` operations where those last ulps matter. With AVX-512 every order takes
    /// the outward-rounded operations ([`TIGHT_IS_FASTER`]).
    pub fn expand(
        &mut self,
        y0: &[Interval],
        order: usize,
        with_jacobian: bool,
        out: &mut Expansion,
    ) -> Result<(), DomainError> {
        self.expand_with(y0, order, with_jacobian, 0, out)
    }

    /// As [`expand`](Self::expand), but orders below [`TIGHT_ORDERS`] are computed with every
    /// operation outward-rounded by `inari` (tightest). Used for the expansion at the centre of the
    /// set, whose rounding widths feed the set: the low orders carry almost all of the Taylor
    /// polynomial's value, while the terms `yᵢhⁱ` of higher orders are so small that the few extra
    /// ulps of the fast sums are negligible.
    pub fn expand_tight(
        &mut self,
        y0: &[Interval],
        order: usize,
        with_jacobian: bool,
        out: &mut Expansion,
    ) -> Result<(), DomainError> {
        self.expand_with(y0, order, with_jacobian, TIGHT_ORDERS, out)
    }

    fn expand_with(
        &mut self,
        y0: &[Interval],
        order: usize,
        with_jacobian: bool,
        tight_below: usize,
        out: &mut Expansion,
    ) -> Result<(), DomainError> {
        let n = self.tape.dim;
        if y0.len() != n {
            return Err(DomainError::WrongDimension);
        }
        let nodes = self.tape.ops.len();
        let s = order + 1;
        self.work.expansions += 1;
        self.work.coefficient_units += (s * s) as f64;
        if with_jacobian {
            self.work.jacobian_units += (n * s * s) as f64;
        }
        self.coef.clear();
        self.coef.resize(nodes * s, ZERO);
        let nd = if with_jacobian { n } else { 0 };
        self.dcoef.clear();
        self.dcoef.resize(nodes * nd * s, ZERO);
        for (v, op) in self.tape.ops.iter().enumerate() {
            match *op {
                Op::Input(j) => {
                    self.coef[v * s] = y0[j];
                    if with_jacobian {
                        self.dcoef[(v * n + j) * s] = point(1.0);
                    }
                }
                Op::Const(c) => self.coef[v * s] = c,
                // The centre is the box's midpoint, an exact double: a thin constant.
                Op::Centre(j) => self.coef[v * s] = point(y0[j].mid()),
                _ => {}
            }
        }
        let ops = &self.tape.ops;
        let tc = &self.tape.time_constant;
        let tight_everywhere = TIGHT_IS_FASTER;
        for i in 0..order {
            for (v, op) in ops.iter().enumerate() {
                // Time-constant operations have only their value (coefficient 0).
                if tc[v] && i > 0 {
                    continue;
                }
                if tight_everywhere || i < tight_below {
                    coef_step::<InariDot>(tc, &mut self.coef, s, v, *op, i)?;
                } else {
                    coef_step::<DotAcc>(tc, &mut self.coef, s, v, *op, i)?;
                }
            }
            let jac_here = with_jacobian && i + 1 < order;
            if jac_here {
                for (v, op) in ops.iter().enumerate() {
                    // Neither constants nor the centre depend on the initial value.
                    if tc[v] {
                        continue;
                    }
                    if tight_everywhere || i < tight_below {
                        deriv_step::<InariDot>(tc, &self.coef, &mut self.dcoef, s, n, v, *op, i);
                    } else {
                        deriv_step::<DotAcc>(tc, &self.coef, &mut self.dcoef, s, n, v, *op, i);
                    }
                }
            }
            // y_{i+1} = f_i / (i+1), and its derivatives.
            let div = point((i + 1) as f64);
            for (j, &o) in self.tape.outputs.iter().enumerate() {
                let input = j; // Input(j) is operation j.
                let c = self.coef[o * s + i] / div;
                if !c.is_common_interval() {
                    return Err(DomainError::Unbounded);
                }
                self.coef[input * s + i + 1] = c;
                if jac_here {
                    for l in 0..n {
                        self.dcoef[(input * n + l) * s + i + 1] =
                            self.dcoef[(o * n + l) * s + i] / div;
                    }
                }
            }
        }
        out.dim = n;
        out.order = order;
        out.coeffs.clear();
        for i in 0..=order {
            for j in 0..n {
                out.coeffs.push(self.coef[j * s + i]);
            }
        }
        out.jac.clear();
        out.jac_orders = if with_jacobian { order } else { 0 };
        if with_jacobian {
            for i in 0..order {
                for j in 0..n {
                    for l in 0..n {
                        let d = self.dcoef[(j * n + l) * s + i];
                        if !d.is_common_interval() {
                            return Err(DomainError::Unbounded);
                        }
                        out.jac.push(d);
                    }
                }
            }
        }
        if out.coeffs.iter().any(|c| !c.is_common_interval()) {
            return Err(DomainError::Unbounded);
        }
        Ok(())
    }
}

/// Whether the outward-rounded sums ([`InariDot`], products by [`imul`](crate::numeric::imul))
/// are used at every order: with AVX-512 they are both tighter and faster than [`DotAcc`]
/// (tangential contact scene, whose contact trace runs this engine: task-clock 229 -> 184 ms,
/// tube 1.008e-11 -> 1.006e-11); elsewhere `inari`'s product branches on signs and [`DotAcc`]
/// stays the faster above the first orders.
pub const TIGHT_IS_FASTER: bool = cfg!(all(target_arch = "x86_64", target_feature = "avx512f"));

/// Whether operand `a` is constant in time (all its coefficients above the 0-th vanish).
fn is_const(tc: &[bool], a: u32) -> bool {
    tc[a as usize]
}

/// Computes coefficient `i` of operation `v` from coefficients `0..=i` of its operands.
fn coef_step<D: IntervalDot>(
    ops: &[bool],
    coef: &mut [Interval],
    s: usize,
    v: usize,
    op: Op,
    i: usize,
) -> Result<(), DomainError> {
    let (done, rest) = coef.split_at_mut(v * s);
    let c = &mut rest[..s];
    let ser = |a: u32| &done[a as usize * s..a as usize * s + s];
    match op {
        Op::Input(_) | Op::Const(_) | Op::Centre(_) => {}
        Op::Add(a, b) => c[i] = ser(a)[i] + ser(b)[i],
        Op::Sub(a, b) => c[i] = ser(a)[i] - ser(b)[i],
        Op::Neg(a) => c[i] = -ser(a)[i],
        Op::Mul(a, b) => {
            let (x, y) = (ser(a), ser(b));
            c[i] = if is_const(ops, a) {
                imul(x[0], y[i])
            } else if is_const(ops, b) {
                imul(x[i], y[0])
            } else {
                let mut acc = D::start();
                for m in 0..=i {
                    acc.add(x[m], y[i - m]);
                }
                acc.total()
            };
        }
        Op::Div(a, b) => {
            let (x, y) = (ser(a), ser(b));
            if i == 0 && y[0].contains(0.0) {
                return Err(DomainError::DivisionByZero);
            }
            c[i] = if is_const(ops, b) {
                x[i] / y[0]
            } else {
                let mut acc = D::start();
                for m in 1..=i {
                    acc.add(y[m], c[i - m]);
                }
                (x[i] - acc.total()) / y[0]
            };
        }
        Op::Sqr(a) => {
            let x = ser(a);
            c[i] = square_coefficient::<D>(x, 0, i);
        }
        Op::Sqrt(a) => {
            let x = ser(a);
            if i == 0 {
                if x[0].inf() <= 0.0 {
                    return Err(DomainError::SqrtOfNonPositive);
                }
                c[0] = x[0].sqrt();
            } else {
                let acc = square_coefficient::<D>(c, 1, i);
                c[i] = (x[i] - acc) / (c[0] + c[0]);
            }
        }
    }
    Ok(())
}

/// Computes the `n` partial derivatives of coefficient `i` of operation `v`.
#[allow(clippy::too_many_arguments)]
fn deriv_step<D: IntervalDot>(
    ops: &[bool],
    coef: &[Interval],
    dcoef: &mut [Interval],
    s: usize,
    n: usize,
    v: usize,
    op: Op,
    i: usize,
) {
    let (done, rest) = dcoef.split_at_mut(v * n * s);
    let ser = |a: u32| &coef[a as usize * s..a as usize * s + s];
    let c = ser(v as u32);
    for l in 0..n {
        let d = |a: u32| &done[(a as usize * n + l) * s..(a as usize * n + l) * s + s];
        let dc = &mut rest[l * s..l * s + s];
        match op {
            Op::Input(_) | Op::Const(_) | Op::Centre(_) => {}
            Op::Add(a, b) => dc[i] = d(a)[i] + d(b)[i],
            Op::Sub(a, b) => dc[i] = d(a)[i] - d(b)[i],
            Op::Neg(a) => dc[i] = -d(a)[i],
            Op::Mul(a, b) => {
                dc[i] = if is_const(ops, a) {
                    imul(ser(a)[0], d(b)[i])
                } else if is_const(ops, b) {
                    imul(d(a)[i], ser(b)[0])
                } else {
                    let (x, y, dx, dy) = (ser(a), ser(b), d(a), d(b));
                    let mut acc = D::start();
                    for m in 0..=i {
                        acc.add(dx[m], y[i - m]);
                        acc.add(x[m], dy[i - m]);
                    }
                    acc.total()
                };
            }
            Op::Div(a, b) => {
                let y = ser(b);
                dc[i] = if is_const(ops, b) {
                    d(a)[i] / y[0]
                } else {
                    let dy = d(b);
                    let mut acc = D::start();
                    for m in 0..i {
                        acc.add(dc[m], y[i - m]);
                    }
                    for m in 0..=i {
                        acc.add(c[m], dy[i - m]);
                    }
                    (d(a)[i] - acc.total()) / y[0]
                };
            }
            Op::Sqr(a) => {
                let (x, dx) = (ser(a), d(a));
                let mut acc = D::start();
                for m in 0..=i {
                    acc.add(dx[m], x[i - m]);
                }
                let acc = acc.total();
                dc[i] = acc + acc;
            }
            Op::Sqrt(a) => {
                let mut acc = D::start();
                for m in 0..i {
                    acc.add(dc[m], c[i - m]);
                }
                let acc = acc.total();
                dc[i] = (d(a)[i] - (acc + acc)) / (c[0] + c[0]);
            }
        }
    }
}

/// `Σ_{m=from}^{i−from} a_m·a_{i−m}`, the order-`i` coefficient of a square with the terms below
/// `from` (and their mirror images) left out, summed once per symmetric pair.
fn square_coefficient<D: IntervalDot>(a: &[Interval], from: usize, i: usize) -> Interval {
    let mut dot = D::start();
    for m in from..i.div_ceil(2) {
        dot.add(a[m], a[i - m]);
    }
    let mut acc = dot.total();
    acc = acc + acc;
    if i.is_multiple_of(2) {
        acc += a[i / 2].sqr();
    }
    acc
}

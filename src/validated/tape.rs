//! Recording the right-hand side once as a straight-line program (a "tape").
//!
//! [`Var`] is a `Copy` scalar that, instead of computing, appends the operation it stands for to a
//! thread-local list. Evaluating an [`OdeSystem`] once on `Var` inputs ([`Tape::record`]) therefore
//! yields the field as a list of elementary operations (`+ − × ÷`, negation, square, square root;
//! integer powers are lowered to products and one quotient). Sub-expressions that involve only
//! constants are folded at recording time, in interval arithmetic, so constants stay rigorous.
//!
//! Why a tape: the Taylor coefficients of the solution are then computed *incrementally*, one
//! order at a time for every operation (see [`crate::validated::ad`]), which costs `O(k²)` per
//! operation for order `k`. Evaluating `f` on truncated series of growing length (the naive
//! scheme, [`crate::validated::series`]) costs `O(k³)`; the benchmark `validated` measures both.

use crate::error::{Error, Result};
use crate::numeric::scalar::point;
use crate::validated::system::OdeSystem;
use crate::Scalar;
use inari::Interval;
use std::cell::RefCell;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// One elementary operation of a recorded program; operands are indices of earlier operations.
#[derive(Clone, Copy, Debug)]
pub enum Op {
    /// The `j`-th component of the state.
    Input(usize),
    /// The `j`-th component of the expansion's centre (the midpoint of the box being expanded):
    /// a value constant in time that does not depend on the initial value.
    Centre(usize),
    /// A constant, enclosed by an interval.
    Const(Interval),
    /// `a + b`.
    Add(u32, u32),
    /// `a − b`.
    Sub(u32, u32),
    /// `a × b`.
    Mul(u32, u32),
    /// `a ÷ b`.
    Div(u32, u32),
    /// `−a`.
    Neg(u32),
    /// `a²`.
    Sqr(u32),
    /// `√a` (the engine rejects arguments that may be negative).
    Sqrt(u32),
}

thread_local! {
    static RECORDING: RefCell<Vec<Op>> = const { RefCell::new(Vec::new()) };
}

fn push(op: Op) -> Var {
    RECORDING.with(|t| {
        let mut t = t.borrow_mut();
        t.push(op);
        Var((t.len() - 1) as u32)
    })
}

fn constant_of(v: Var) -> Option<Interval> {
    RECORDING.with(|t| match t.borrow().get(v.0 as usize) {
        Some(Op::Const(c)) => Some(*c),
        _ => None,
    })
}

/// A recording scalar: a handle to one operation of the program being recorded on this thread.
///
/// Only meaningful inside [`Tape::record`]; values created elsewhere are harmless but unused.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Var(u32);

impl Var {
    /// Index of the operation this variable stands for.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

fn binary(a: Var, b: Var, fold: fn(Interval, Interval) -> Interval, op: fn(u32, u32) -> Op) -> Var {
    match (constant_of(a), constant_of(b)) {
        (Some(x), Some(y)) => push(Op::Const(fold(x, y))),
        _ => push(op(a.0, b.0)),
    }
}

fn unary(a: Var, fold: fn(Interval) -> Interval, op: fn(u32) -> Op) -> Var {
    match constant_of(a) {
        Some(x) => push(Op::Const(fold(x))),
        None => push(op(a.0)),
    }
}

impl Add for Var {
    type Output = Var;
    fn add(self, rhs: Var) -> Var {
        binary(self, rhs, |x, y| x + y, Op::Add)
    }
}
impl Sub for Var {
    type Output = Var;
    fn sub(self, rhs: Var) -> Var {
        binary(self, rhs, |x, y| x - y, Op::Sub)
    }
}
impl Mul for Var {
    type Output = Var;
    fn mul(self, rhs: Var) -> Var {
        binary(self, rhs, |x, y| x * y, Op::Mul)
    }
}
impl Div for Var {
    type Output = Var;
    fn div(self, rhs: Var) -> Var {
        binary(self, rhs, |x, y| x / y, Op::Div)
    }
}
impl Neg for Var {
    type Output = Var;
    fn neg(self) -> Var {
        unary(self, |x| -x, Op::Neg)
    }
}

impl Scalar for Var {
    fn from_f64(x: f64) -> Self {
        push(Op::Const(point(x)))
    }
    fn from_interval(x: Interval) -> Self {
        push(Op::Const(x))
    }
    fn sqr(self) -> Self {
        unary(self, Interval::sqr, Op::Sqr)
    }
    fn sqrt(self) -> Self {
        // A constant whose interval reaches below zero is not folded (inari would silently drop
        // the negative part); the engine's domain check then rejects it.
        match constant_of(self) {
            Some(x) if x.inf() >= 0.0 => push(Op::Const(x.sqrt())),
            _ => push(Op::Sqrt(self.0)),
        }
    }
    fn powi(self, n: i32) -> Self {
        if n == 0 {
            return Var::one();
        }
        // Square-and-multiply on |n|, then one reciprocal for negative n.
        let mut e = n.unsigned_abs();
        let mut base = self;
        let mut acc: Option<Var> = None;
        while e > 0 {
            if e & 1 == 1 {
                acc = Some(match acc {
                    None => base,
                    Some(a) => a * base,
                });
            }
            e >>= 1;
            if e > 0 {
                base = base.sqr();
            }
        }
        let p = acc.unwrap_or_else(Var::one);
        if n < 0 {
            Var::one() / p
        } else {
            p
        }
    }
}

/// A recorded right-hand side: `n` inputs, a list of operations, and the `n` outputs `f_j`.
#[derive(Clone, Debug)]
pub struct Tape {
    /// The operations; the first `dim` are the inputs `Input(0..dim)`.
    pub ops: Vec<Op>,
    /// Index of the operation giving each component `f_j`.
    pub outputs: Vec<usize>,
    /// Whether operation `v` is constant in time (built from constants and the centre only).
    pub time_constant: Vec<bool>,
    /// The dimension `n`.
    pub dim: usize,
}

impl Tape {
    /// Records `system.eval` once. Errors if the system has dimension 0 or returns a vector of the
    /// wrong length. Recording is re-entrant: a recording in progress on this thread is restored.
    pub fn record<F: OdeSystem>(system: &F) -> Result<Tape> {
        let dim = system.dim();
        if dim == 0 {
            return Err(Error::BadIntegratorSetup(
                "the ODE system has dimension 0".into(),
            ));
        }
        let saved = RECORDING.with(|t| std::mem::take(&mut *t.borrow_mut()));
        let inputs: Vec<Var> = (0..dim).map(|j| push(Op::Input(j))).collect();
        let out = if system.uses_centre() {
            let centre: Vec<Var> = (0..dim).map(|j| push(Op::Centre(j))).collect();
            system.eval_centred(&inputs, &centre)
        } else {
            system.eval(&inputs)
        };
        let ops = RECORDING.with(|t| std::mem::replace(&mut *t.borrow_mut(), saved));
        if out.len() != dim {
            return Err(Error::BadIntegratorSetup(format!(
                "the ODE system has dimension {dim} but its field returned {} components",
                out.len()
            )));
        }
        let outputs: Vec<usize> = out.iter().map(|v| v.index()).collect();
        Ok(Tape::new(ops, outputs, dim).simplified())
    }

    /// The same program without dead operations (not needed by any output) and with repeated
    /// operations (same kind, same operands, or equal constants) merged. Inputs keep their
    /// positions `0..dim`; the outputs' values are unchanged (the same operations on the same
    /// operands, so the same enclosures).
    pub fn simplified(&self) -> Tape {
        let n = self.ops.len();
        let mut live = vec![false; n];
        for &o in &self.outputs {
            live[o] = true;
        }
        for v in (0..n).rev() {
            if !live[v] {
                continue;
            }
            match self.ops[v] {
                Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => {
                    live[a as usize] = true;
                    live[b as usize] = true;
                }
                Op::Neg(a) | Op::Sqr(a) | Op::Sqrt(a) => live[a as usize] = true,
                Op::Input(_) | Op::Centre(_) | Op::Const(_) => {}
            }
        }
        let mut map = vec![u32::MAX; n];
        let mut ops: Vec<Op> = Vec::new();
        let mut seen: std::collections::HashMap<(u8, u64, u64), u32> =
            std::collections::HashMap::new();
        for v in 0..n {
            let is_input = matches!(self.ops[v], Op::Input(_));
            if !live[v] && !is_input {
                continue;
            }
            let r = |a: u32| map[a as usize];
            let op = match self.ops[v] {
                Op::Add(a, b) => Op::Add(r(a), r(b)),
                Op::Sub(a, b) => Op::Sub(r(a), r(b)),
                Op::Mul(a, b) => Op::Mul(r(a), r(b)),
                Op::Div(a, b) => Op::Div(r(a), r(b)),
                Op::Neg(a) => Op::Neg(r(a)),
                Op::Sqr(a) => Op::Sqr(r(a)),
                Op::Sqrt(a) => Op::Sqrt(r(a)),
                other => other,
            };
            let key = match op {
                Op::Input(j) => (0, j as u64, 0),
                Op::Const(c) => (1, c.inf().to_bits(), c.sup().to_bits()),
                Op::Add(a, b) => (2, a.min(b) as u64, a.max(b) as u64),
                Op::Sub(a, b) => (3, a as u64, b as u64),
                Op::Mul(a, b) => (4, a.min(b) as u64, a.max(b) as u64),
                Op::Div(a, b) => (5, a as u64, b as u64),
                Op::Neg(a) => (6, a as u64, 0),
                Op::Sqr(a) => (7, a as u64, 0),
                Op::Sqrt(a) => (8, a as u64, 0),
                Op::Centre(j) => (9, j as u64, 0),
            };
            map[v] = *seen.entry(key).or_insert_with(|| {
                ops.push(op);
                (ops.len() - 1) as u32
            });
        }
        Tape::new(
            ops,
            self.outputs.iter().map(|&o| map[o] as usize).collect(),
            self.dim,
        )
    }

    /// A tape from its parts (inputs first), with the time-constant flags derived.
    pub fn new(ops: Vec<Op>, outputs: Vec<usize>, dim: usize) -> Tape {
        let mut tc: Vec<bool> = Vec::with_capacity(ops.len());
        for op in &ops {
            let c = |a: u32| tc[a as usize];
            let flag = match *op {
                Op::Input(_) => false,
                Op::Const(_) | Op::Centre(_) => true,
                Op::Add(a, b) | Op::Sub(a, b) | Op::Mul(a, b) | Op::Div(a, b) => c(a) && c(b),
                Op::Neg(a) | Op::Sqr(a) | Op::Sqrt(a) => c(a),
            };
            tc.push(flag);
        }
        Tape {
            ops,
            outputs,
            dim,
            time_constant: tc,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Sample;
    impl OdeSystem for Sample {
        fn dim(&self) -> usize {
            2
        }
        fn eval<S: Scalar>(&self, y: &[S]) -> Vec<S> {
            let c = S::from_f64(2.0) * S::from_f64(3.0);
            vec![y[0] * c + y[1].powi(-3), y[0].sqrt()]
        }
    }

    #[test]
    fn constants_fold_and_powers_lower() {
        let t = Tape::record(&Sample).unwrap();
        assert_eq!(t.dim, 2);
        // 2·3 folds to one constant 6.
        assert!(t
            .ops
            .iter()
            .any(|op| matches!(op, Op::Const(c) if c.inf() == 6.0 && c.sup() == 6.0)));
        assert!(!t.ops.iter().any(|op| matches!(op, Op::Mul(a, b)
            if matches!(t.ops[*a as usize], Op::Const(_)) && matches!(t.ops[*b as usize], Op::Const(_)))));
        assert!(t.ops.iter().any(|op| matches!(op, Op::Div(_, _))));
        assert_eq!(t.outputs.len(), 2);
    }
}

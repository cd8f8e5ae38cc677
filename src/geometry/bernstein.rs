//! The Bernstein basis toolbox of the patch evaluators: basis values with their first and second
//! derivatives, binomial coefficients and forward differences of a net, over any [`Scalar`].

use crate::numeric::scalar::Scalar;

/// Bernstein basis values `B_i^deg(t)` and their first and second derivatives in `t`.
///
/// Writes `deg + 1` entries into each of `b`, `d1`, `d2` (which must be at least that long).
pub(crate) fn bernstein<S: Scalar>(deg: usize, t: S, b: &mut [S], d1: &mut [S], d2: &mut [S]) {
    let one_minus = S::one() - t;
    for x in b[..=deg]
        .iter_mut()
        .chain(&mut d1[..=deg])
        .chain(&mut d2[..=deg])
    {
        *x = S::zero();
    }
    b[0] = S::one();
    // Raise the basis from level k to k + 1; entries above the current level stay zero, so the
    // derivative formulas below can read them as zeros.
    for k in 0..deg {
        if deg >= 2 && k == deg - 2 {
            // B''_i = deg(deg−1)(B_{i−2} − 2B_{i−1} + B_i), basis of level deg − 2.
            let c = S::from_f64((deg * (deg - 1)) as f64);
            let two = S::from_f64(2.0);
            for i in 0..=deg {
                let a = if i >= 2 { b[i - 2] } else { S::zero() };
                let m = if i >= 1 { b[i - 1] } else { S::zero() };
                d2[i] = c * (a - two * m + b[i]);
            }
        }
        if k == deg - 1 {
            // B'_i = deg(B_{i−1} − B_i), basis of level deg − 1.
            let c = S::from_f64(deg as f64);
            for i in 0..=deg {
                let a = if i >= 1 { b[i - 1] } else { S::zero() };
                d1[i] = c * (a - b[i]);
            }
        }
        b[k + 1] = t * b[k];
        for i in (1..=k).rev() {
            b[i] = one_minus * b[i] + t * b[i - 1];
        }
        b[0] = one_minus * b[0];
    }
}

/// Bernstein basis values only.
pub(crate) fn bernstein_values<S: Scalar>(deg: usize, t: S, b: &mut [S]) {
    let one_minus = S::one() - t;
    b[0] = S::one();
    for k in 1..=deg {
        b[k] = t * b[k - 1];
        for i in (1..k).rev() {
            b[i] = one_minus * b[i] + t * b[i - 1];
        }
        b[0] = one_minus * b[0];
    }
}

/// The binomial coefficient `C(n, k)` (exact in `f64` for the degrees of a patch).
pub(crate) const fn binomial(n: usize, k: usize) -> f64 {
    let mut acc = 1.0;
    let mut i = 0;
    while i < k {
        acc = acc * (n - i) as f64 / (i + 1) as f64;
        i += 1;
    }
    acc
}

/// The Bernstein values `B_i^d(t) = C(d, i)·tⁱ·(1 − t)^{d−i}`, `i = 0..=d`, each formed as that
/// product (the power form's centred coefficients are built from these; the in-place recurrence
/// of [`bernstein_values`] gives the same values with other interval widths).
pub(crate) fn bernstein_products<T: Scalar>(d: usize, t: T) -> Vec<T> {
    let mut a = vec![T::one(); d + 1];
    let mut b = vec![T::one(); d + 1];
    let one_minus = T::one() - t;
    for i in 1..=d {
        a[i] = a[i - 1] * t;
        b[i] = b[i - 1] * one_minus;
    }
    (0..=d)
        .map(|i| T::from_f64(binomial(d, i)) * a[i] * b[d - i])
        .collect()
}

/// The forward difference `Δₛᵏ Δᵣˡ` of a net at `(i, j)`: `Σ (−1)^{k−a+l−b} C(k,a) C(l,b) net(i+a, j+b)`.
pub(crate) fn forward_difference<S: Scalar>(
    net: &impl Fn(usize, usize) -> [S; 4],
    i: usize,
    j: usize,
    k: usize,
    l: usize,
) -> [S; 4] {
    let z = S::zero();
    let mut out = [z; 4];
    for a in 0..=k {
        for b in 0..=l {
            let c = binomial(k, a) * binomial(l, b);
            let sign = if (k - a + l - b).is_multiple_of(2) {
                c
            } else {
                -c
            };
            let p = net(i + a, j + b);
            let f = S::from_f64(sign);
            for x in 0..4 {
                out[x] = out[x] + f * p[x];
            }
        }
    }
    out
}

/// Bernstein basis values `B_i^deg(t)` and their first derivatives in `t`.
pub(crate) fn bernstein_first<S: Scalar>(deg: usize, t: S, b: &mut [S], d1: &mut [S]) {
    // Basis of level deg − 1, then B'_i = deg(B_{i−1} − B_i) on it, then raise once more.
    bernstein_values(deg - 1, t, b);
    b[deg] = S::zero();
    let c = S::from_f64(deg as f64);
    for i in 0..=deg {
        let a = if i >= 1 { b[i - 1] } else { S::zero() };
        d1[i] = c * (a - b[i]);
    }
    let one_minus = S::one() - t;
    b[deg] = t * b[deg - 1];
    for i in (1..deg).rev() {
        b[i] = one_minus * b[i] + t * b[i - 1];
    }
    b[0] = one_minus * b[0];
}

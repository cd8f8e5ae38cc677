//! Helpers shared by the benchmarks that print ratios of their own timings.

use std::time::Instant;

/// Seconds of the median of `n` wall-clock runs of `f`.
#[allow(dead_code)]
pub(crate) fn median(n: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..n)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[n / 2]
}

/// Seconds of the fastest of `n` wall-clock runs of `f` (what the code costs when nothing else
/// competes for the core: the estimate least disturbed by other processes).
#[allow(dead_code)]
pub(crate) fn fastest(n: usize, mut f: impl FnMut()) -> f64 {
    (0..n)
        .map(|_| {
            let s = Instant::now();
            f();
            s.elapsed().as_secs_f64()
        })
        .fold(f64::INFINITY, f64::min)
}

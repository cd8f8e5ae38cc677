//! Helpers shared by the benchmarks that print ratios of their own timings.

use std::time::Instant;

/// Seconds of the median of `n` wall-clock runs of `f`.
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

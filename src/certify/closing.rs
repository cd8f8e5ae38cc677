//! The loop-closing proof of a certified half branch (moved from `trace.rs`): the fixed
//! coordinate crosses its start value inside the start's uniqueness box.

use crate::error::Result;
use crate::validated::StepRecord;
use inari::Interval;

fn to4(v: &[Interval]) -> [Interval; 4] {
    [v[0], v[1], v[2], v[3]]
}

/// Data of the loop-closing test: the start's fixed coordinate, its value, the uniqueness box
/// and the fixed coordinate's velocity at the start (its sign says on which side the curve
/// comes back from).
pub(crate) type Closure<'a> = (usize, f64, &'a [Interval; 4], f64);

/// Progress of the loop-closing test along the forward half.
#[derive(Debug, Default)]
pub(crate) struct Crossing {
    /// The curve has been wholly outside the start's uniqueness box for a step.
    left: bool,
    /// The enclosure since the curve was last strictly on the returning side (may span steps).
    hull: Option<[Interval; 4]>,
}

/// The loop-closing proof for one step: the fixed coordinate `k` crosses its start value `c`,
/// from the side it returns from to the side it left to, inside the uniqueness box (in the other
/// coordinates). Then the crossing point is the start point. `state.hull` carries the enclosure since
/// the curve was last strictly on the returning side (it may span steps).
pub(crate) fn closes(
    rec: &StepRecord,
    apriori: &[Interval; 4],
    bridge: &[Interval; 4],
    c: Closure,
    state: &mut Crossing,
) -> Result<bool> {
    let (k, value, uniq, speed) = c;
    let free = |y: &[Interval; 4], f: &dyn Fn(Interval, Interval) -> bool| {
        (0..4).filter(|&i| i != k).all(|i| f(y[i], uniq[i]))
    };
    if !free(apriori, &|a, u| !a.disjoint(u)) {
        state.left = true;
        state.hull = None;
        return Ok(false);
    }
    // No loop lies wholly inside the uniqueness box (it would meet the start value twice), so
    // nothing can close before the curve has been outside it once: skip the costly test.
    if !state.left {
        return Ok(false);
    }
    let hull = &mut state.hull;
    // The curve piece from the last step's end to this step's start.
    if let Some(h) = hull.as_mut() {
        for i in 0..4 {
            h[i] = h[i].convex_hull(bridge[i]);
        }
    }
    let before = |x: Interval| {
        if speed > 0.0 {
            x.sup() < value
        } else {
            x.inf() > value
        }
    };
    let after = |x: Interval| {
        if speed > 0.0 {
            x.inf() > value
        } else {
            x.sup() < value
        }
    };
    // Pieces short enough that the curve moves (in parameters) at most a quarter of the
    // uniqueness box's narrowest free width over one piece, so a crossing fits inside it.
    let speed = rec
        .coeffs
        .get(1)
        .map_or(1.0, |c| c.iter().map(|x| x.mag()).fold(0.0, f64::max));
    let narrowest = (0..4)
        .filter(|&i| i != k)
        .map(|i| uniq[i].wid())
        .fold(f64::INFINITY, f64::min);
    let pieces = ((4.0 * speed * rec.h / narrowest).ceil() as usize).clamp(8, 4096);
    for m in 0..pieces {
        let a = rec.h * m as f64 / pieces as f64;
        let b = if m + 1 == pieces {
            rec.h
        } else {
            rec.h * (m + 1) as f64 / pieces as f64
        };
        let at_a = to4(&rec.enclose_on(a, a)?);
        let piece = to4(&rec.enclose_on(a, b)?);
        if before(at_a[k]) {
            *hull = Some(piece);
        } else if let Some(h) = hull.as_mut() {
            for i in 0..4 {
                h[i] = h[i].convex_hull(piece[i]);
            }
        }
        let at_b = to4(&rec.enclose_on(b, b)?);
        if let Some(h) = hull {
            if after(at_b[k]) && free(h, &|x, u| x.subset(u)) {
                return Ok(true);
            }
        }
    }
    Ok(false)
}

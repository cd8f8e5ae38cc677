//! Interval checks.

use inari::Interval;

/// Whether the intervals share a point. With `a` a tight enclosure of a true value (a few ulps
/// wide, or a stated margin), a sound claimed enclosure `b` must meet it: disjoint, `b` misses
/// the true value.
pub(crate) fn meets(a: Interval, b: Interval) -> bool {
    !a.intersection(b).is_empty()
}

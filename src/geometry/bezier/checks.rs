//! The checks of a patch's input data: intervals, domains, control data and degrees, each
//! failing with a typed error that names the field.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::surface::Domain;
use crate::numeric::scalar::Scalar;
use inari::Interval;

/// Whether `x` is a non-empty interval with finite bounds; the typed problem otherwise.
pub(crate) fn check_interval(x: Interval) -> std::result::Result<(), InputProblem> {
    if x.is_empty() {
        return Err(InputProblem::InvertedInterval {
            lo: f64::NAN,
            hi: f64::NAN,
        });
    }
    if !x.inf().is_finite() || !x.sup().is_finite() {
        return Err(InputProblem::NonFinite);
    }
    Ok(())
}

/// Validate a domain: finite bounds and positive width in both directions.
pub(crate) fn check_domain(domain: &Domain) -> Result<()> {
    for (k, [lo, hi]) in [domain.u, domain.v].into_iter().enumerate() {
        if !lo.is_finite() || !hi.is_finite() {
            return Err(Error::input(
                format!("domain[{k}]"),
                InputProblem::NonFinite,
            ));
        }
        if lo >= hi {
            return Err(Error::input(
                format!("domain[{k}]"),
                InputProblem::EmptyDomain { lo, hi },
            ));
        }
    }
    Ok(())
}

/// Checks Cartesian control data of `count` points: the point count, every coordinate finite
/// and non-empty, and the weights (all 1 when `None`) of the right count, finite and positive.
/// Errors name `points`, `points[k][c]`, `weights` or `weights[k]`.
pub(crate) fn check_control_data(
    points: &[[Interval; 3]],
    weights: Option<Vec<Interval>>,
    count: usize,
) -> Result<Vec<Interval>> {
    if points.len() != count {
        return Err(Error::input(
            "points",
            InputProblem::WrongCount {
                expected: count,
                found: points.len(),
            },
        ));
    }
    for (k, p) in points.iter().enumerate() {
        for (c, x) in p.iter().enumerate() {
            check_interval(*x).map_err(|e| Error::input(format!("points[{k}][{c}]"), e))?;
        }
    }
    let weights = match weights {
        Some(w) => {
            if w.len() != count {
                return Err(Error::input(
                    "weights",
                    InputProblem::WrongCount {
                        expected: count,
                        found: w.len(),
                    },
                ));
            }
            for (k, x) in w.iter().enumerate() {
                check_interval(*x).map_err(|e| Error::input(format!("weights[{k}]"), e))?;
                if x.inf() <= 0.0 {
                    return Err(Error::input(
                        format!("weights[{k}]"),
                        InputProblem::NonPositiveWeight,
                    ));
                }
            }
            w
        }
        None => vec![Interval::from_f64(1.0); count],
    };
    Ok(weights)
}

/// Validate a degree and return the number of control points it needs.
pub(super) fn check_degree(degree: [usize; 2]) -> Result<usize> {
    for (k, d) in degree.into_iter().enumerate() {
        if d == 0 {
            return Err(Error::input(
                format!("degree[{k}]"),
                InputProblem::BadDegree(0),
            ));
        }
    }
    let [m, n] = degree.map(|d| d.checked_add(1));
    m.zip(n)
        .and_then(|(m, n)| m.checked_mul(n))
        .filter(|&c| c < (1 << 24))
        .ok_or_else(|| {
            Error::input(
                "degree",
                InputProblem::WrongShape("degree too large".into()),
            )
        })
}

//! Typed access to the instances of a Part 21 file: records by number, parameters by position,
//! every failure an [`Error::Step`] naming the instance.

use super::part21::{Instance, Param, Part21, Record};
use crate::error::{Error, Result};

/// An error about instance `#id`.
pub(super) fn step_error(id: u64, message: impl Into<String>) -> Error {
    Error::Step {
        entity: Some(id),
        message: message.into(),
    }
}

/// The instances of a file, looked up with errors that name the instance.
pub(super) struct Entities<'a> {
    pub(super) file: &'a Part21,
}

impl<'a> Entities<'a> {
    /// Instance `#id`.
    pub(super) fn get(&self, id: u64) -> Result<&'a Instance> {
        self.file
            .instances
            .get(&id)
            .ok_or_else(|| step_error(id, "is referenced but not defined"))
    }

    /// The record of instance `#id` with one of the names `names` (simple, or a partial record
    /// of a complex instance), and the name found.
    pub(super) fn record(&self, id: u64, names: &[&str]) -> Result<Args<'a>> {
        let inst = self.get(id)?;
        for n in names {
            if let Some(r) = inst.record(n) {
                return Ok(Args { id, record: r });
            }
        }
        Err(step_error(
            id,
            format!(
                "is a {} where {} is needed",
                inst.name(),
                names.join(" or ")
            ),
        ))
    }
}

/// The parameters of one record of instance `id`.
#[derive(Clone, Copy)]
pub(super) struct Args<'a> {
    pub(super) id: u64,
    pub(super) record: &'a Record,
}

impl<'a> Args<'a> {
    /// The record's entity name.
    pub(super) fn name(&self) -> &'a str {
        &self.record.name
    }

    fn err(&self, k: usize, what: &str) -> Error {
        step_error(
            self.id,
            format!("{} parameter {k}: {what}", self.record.name),
        )
    }

    /// Parameter `k`.
    pub(super) fn at(&self, k: usize) -> Result<&'a Param> {
        self.record
            .params
            .get(k)
            .ok_or_else(|| self.err(k, "missing"))
    }

    /// Parameter `k` as a finite number.
    pub(super) fn real(&self, k: usize) -> Result<f64> {
        number(self.at(k)?).ok_or_else(|| self.err(k, "not a finite number"))
    }

    /// Parameter `k` as an integer in `lo..=hi`.
    pub(super) fn int(&self, k: usize, lo: i64, hi: i64) -> Result<i64> {
        match self.at(k)? {
            Param::Int(n) if (lo..=hi).contains(n) => Ok(*n),
            _ => Err(self.err(k, &format!("not an integer in {lo}..={hi}"))),
        }
    }

    /// Parameter `k` as a reference, or `None` if it is `$`.
    pub(super) fn opt_ref(&self, k: usize) -> Result<Option<u64>> {
        match self.at(k)? {
            Param::Ref(n) => Ok(Some(*n)),
            Param::Unset => Ok(None),
            _ => Err(self.err(k, "not a reference")),
        }
    }

    /// Parameter `k` as a reference.
    pub(super) fn reference(&self, k: usize) -> Result<u64> {
        self.opt_ref(k)?
            .ok_or_else(|| self.err(k, "not given (`$`)"))
    }

    /// Parameter `k` as a list.
    pub(super) fn list(&self, k: usize) -> Result<&'a [Param]> {
        match self.at(k)? {
            Param::List(v) => Ok(v),
            _ => Err(self.err(k, "not a list")),
        }
    }

    /// Parameter `k` as a list of references.
    pub(super) fn refs(&self, k: usize) -> Result<Vec<u64>> {
        self.list(k)?
            .iter()
            .map(|p| match p {
                Param::Ref(n) => Ok(*n),
                _ => Err(self.err(k, "a list entry that is not a reference")),
            })
            .collect()
    }

    /// Parameter `k` as a list of finite numbers.
    pub(super) fn reals(&self, k: usize) -> Result<Vec<f64>> {
        reals_of(self.list(k)?).ok_or_else(|| self.err(k, "not a list of finite numbers"))
    }

    /// Parameter `k` as a list of lists of finite numbers, each inner list `inner` long.
    pub(super) fn real_rows(&self, k: usize) -> Result<Vec<Vec<f64>>> {
        self.list(k)?
            .iter()
            .map(|row| match row {
                Param::List(v) => reals_of(v),
                _ => None,
            })
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| self.err(k, "not a list of lists of finite numbers"))
    }

    /// Parameter `k` as a list of lists of references.
    pub(super) fn ref_rows(&self, k: usize) -> Result<Vec<Vec<u64>>> {
        self.list(k)?
            .iter()
            .map(|row| match row {
                Param::List(v) => v
                    .iter()
                    .map(|p| match p {
                        Param::Ref(n) => Some(*n),
                        _ => None,
                    })
                    .collect(),
                _ => None,
            })
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| self.err(k, "not a list of lists of references"))
    }

    /// Parameter `k` as a list of integers in `lo..=hi`.
    pub(super) fn ints(&self, k: usize, lo: i64, hi: i64) -> Result<Vec<usize>> {
        self.list(k)?
            .iter()
            .map(|p| match p {
                Param::Int(n) if (lo..=hi).contains(n) => usize::try_from(*n).ok(),
                _ => None,
            })
            .collect::<Option<Vec<_>>>()
            .ok_or_else(|| self.err(k, &format!("not a list of integers in {lo}..={hi}")))
    }
}

/// A finite number (an integer or a real, possibly typed as a measure).
pub(super) fn number(p: &Param) -> Option<f64> {
    match p {
        Param::Real(x) if x.is_finite() => Some(*x),
        Param::Int(n) => Some(*n as f64).filter(|x| x.abs() < 9.0e15),
        Param::Typed(_, inner) => number(inner),
        _ => None,
    }
}

fn reals_of(v: &[Param]) -> Option<Vec<f64>> {
    v.iter().map(number).collect()
}

//! Where the faces of an assembly are: the placements of each face, following the file's
//! representations up to the roots.
//!
//! A face belongs to the shape representation whose items reach it (through solids, shells and
//! surface models). A representation is placed in another by a `REPRESENTATION_RELATIONSHIP`
//! with an `ITEM_DEFINED_TRANSFORMATION(…, item_1, item_2)` (the rigid motion taking the frame
//! `item_1` of the child onto the frame `item_2` of the parent, as OpenCASCADE reads it), or by
//! a `MAPPED_ITEM` (its map's origin onto its target); relationships without a transformation
//! join two representations of the same shape. Each path from a face's representation to a
//! representation placed nowhere is one placement, hence one face instance; a part used twice
//! gives its faces twice. The motions are applied to the control points in interval arithmetic
//! (the frames are intervals), so the placed surface encloses the exact one.

use super::entities::{step_error, Args, Entities};
use super::surfaces::{placement, Frame, IVec};
use crate::error::Result;
use crate::geometry::nurbs::NurbsSurface;
use std::collections::{HashMap, HashSet};

/// The most face instances an assembly may expand to.
pub const MAX_INSTANCES: usize = 100_000;
/// The deepest nesting of placements followed.
const MAX_DEPTH: usize = 32;
/// The most representation items visited (a file whose representations share items many times
/// over is refused rather than walked for long).
pub const MAX_VISITS: usize = 10_000_000;

/// A rigid motion: frame `from` onto frame `to`.
pub(super) type Motion = (Frame, Frame);

/// The motions placing one face instance, applied first to last.
pub(super) type Placement = Vec<Motion>;

fn apply(m: &Motion, p: &IVec) -> IVec {
    let (f, t) = m;
    let d = [0, 1, 2].map(|k| p[k] - f.origin[k]);
    let c = [f.x, f.y, f.z].map(|e| d[0] * e[0] + d[1] * e[1] + d[2] * e[2]);
    [0, 1, 2].map(|k| t.origin[k] + c[0] * t.x[k] + c[1] * t.y[k] + c[2] * t.z[k])
}

/// The surface moved by a placement (`id` names the face for errors).
pub(super) fn place(s: &NurbsSurface, p: &Placement, id: u64) -> Result<NurbsSurface> {
    if p.is_empty() {
        return Ok(s.clone());
    }
    let points = s
        .points()
        .iter()
        .map(|q| p.iter().fold(*q, |q, m| apply(m, &q)))
        .collect();
    NurbsSurface::new(
        s.degree(),
        s.knots().clone(),
        points,
        Some(s.weights().to_vec()),
    )
    .map_err(|e| step_error(id, format!("its placed surface is not valid: {e}")))
}

/// A link from a child representation up to a parent.
struct Up {
    parent: u64,
    motion: Option<Motion>,
}

/// The faces of the file with their placements: `(face, placement)` pairs in file order of
/// the faces; a face reached by no representation is placed once, where it is.
pub(super) fn face_placements(e: &Entities<'_>, faces: &[u64]) -> Result<Vec<(u64, Placement)>> {
    let mut owner: HashMap<u64, Vec<u64>> = HashMap::new();
    let mut ups: HashMap<u64, Vec<Up>> = HashMap::new();
    let mut same: HashMap<u64, Vec<u64>> = HashMap::new();
    let mut visits = 0usize;
    for &id in &e.file.order {
        let inst = e.get(id)?;
        if let Some(r) = inst.record("REPRESENTATION_RELATIONSHIP").or_else(|| {
            inst.record("SHAPE_REPRESENTATION_RELATIONSHIP")
                .filter(|r| r.params.len() >= 4)
        }) {
            let a = Args { id, record: r };
            let (child, parent) = (a.reference(2)?, a.reference(3)?);
            match inst.record("REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION") {
                Some(t) => {
                    let t = Args { id, record: t }.reference(0)?;
                    let idt = e.record(t, &["ITEM_DEFINED_TRANSFORMATION"])?;
                    let motion = (
                        placement(e, idt.reference(2)?)?,
                        placement(e, idt.reference(3)?)?,
                    );
                    ups.entry(child).or_default().push(Up {
                        parent,
                        motion: Some(motion),
                    });
                }
                None => {
                    same.entry(child).or_default().push(parent);
                    same.entry(parent).or_default().push(child);
                }
            }
            continue;
        }
        let Some(rep) = representation(inst) else {
            continue;
        };
        let a = Args { id, record: rep };
        let Ok(items) = a.refs(1) else {
            continue;
        };
        for item in items {
            collect(e, item, id, &mut owner, &mut ups, &mut visits, 0)?;
        }
    }
    let mut out = Vec::new();
    for &f in faces {
        let before = out.len();
        if let Some(reps) = owner.get(&f) {
            // Once per group of representations of the same shape.
            let mut seen = HashSet::new();
            for &r in reps {
                let g = group(r, &same);
                if seen.insert(g.iter().copied().min().unwrap_or(r)) {
                    paths(r, &ups, &same, Vec::new(), &mut out, f, 0)?;
                }
            }
        }
        if out.len() == before {
            out.push((f, Vec::new()));
        }
        if out.len() > MAX_INSTANCES {
            return Err(step_error(
                f,
                format!("more than {MAX_INSTANCES} placed faces"),
            ));
        }
    }
    Ok(out)
}

/// The record of a shape representation (`…SHAPE_REPRESENTATION`, simple).
fn representation(inst: &super::part21::Instance) -> Option<&super::part21::Record> {
    match inst {
        super::part21::Instance::Simple(r) if r.name.ends_with("SHAPE_REPRESENTATION") => Some(r),
        _ => None,
    }
}

/// Walks representation item `item` of representation `rep` down to its faces.
fn collect(
    e: &Entities<'_>,
    item: u64,
    rep: u64,
    owner: &mut HashMap<u64, Vec<u64>>,
    ups: &mut HashMap<u64, Vec<Up>>,
    visits: &mut usize,
    depth: usize,
) -> Result<()> {
    if depth > MAX_DEPTH {
        return Err(step_error(item, "representation items nested too deeply"));
    }
    *visits += 1;
    if *visits > MAX_VISITS {
        return Err(step_error(
            item,
            format!("more than {MAX_VISITS} representation items visited"),
        ));
    }
    let inst = e.get(item)?;
    if inst.record("ADVANCED_FACE").is_some() || inst.record("FACE_SURFACE").is_some() {
        owner.entry(item).or_default().push(rep);
        return Ok(());
    }
    let Some(r) = [
        "MANIFOLD_SOLID_BREP",
        "BREP_WITH_VOIDS",
        "SHELL_BASED_SURFACE_MODEL",
        "OPEN_SHELL",
        "CLOSED_SHELL",
        "ORIENTED_CLOSED_SHELL",
        "ORIENTED_OPEN_SHELL",
        "MAPPED_ITEM",
    ]
    .iter()
    .find_map(|n| inst.record(n)) else {
        // Placements, curves, points and other items hold no faces.
        return Ok(());
    };
    let a = Args {
        id: item,
        record: r,
    };
    let children: Vec<u64> = match r.name.as_str() {
        "MANIFOLD_SOLID_BREP" => vec![a.reference(1)?],
        "BREP_WITH_VOIDS" => {
            let mut v = vec![a.reference(1)?];
            v.extend(a.refs(2)?);
            v
        }
        "ORIENTED_CLOSED_SHELL" | "ORIENTED_OPEN_SHELL" => vec![a.reference(2)?],
        "MAPPED_ITEM" => {
            let map = e.record(a.reference(1)?, &["REPRESENTATION_MAP"])?;
            let origin = placement(e, map.reference(0)?)?;
            let target = placement(e, a.reference(2)?)?;
            ups.entry(map.reference(1)?).or_default().push(Up {
                parent: rep,
                motion: Some((origin, target)),
            });
            return Ok(());
        }
        _ => a.refs(1)?,
    };
    for c in children {
        collect(e, c, rep, owner, ups, visits, depth + 1)?;
    }
    Ok(())
}

/// The representations of the same shape as `rep` (joined without a transformation; at most
/// 64 followed).
fn group(rep: u64, same: &HashMap<u64, Vec<u64>>) -> Vec<u64> {
    let mut group = vec![rep];
    let mut k = 0;
    while k < group.len() && group.len() <= 64 {
        for &s in same.get(&group[k]).map(Vec::as_slice).unwrap_or(&[]) {
            if !group.contains(&s) {
                group.push(s);
            }
        }
        k += 1;
    }
    group
}

/// Every placement of representation `rep` (reached with `acc` so far), pushed as face `f`'s.
fn paths(
    rep: u64,
    ups: &HashMap<u64, Vec<Up>>,
    same: &HashMap<u64, Vec<u64>>,
    acc: Placement,
    out: &mut Vec<(u64, Placement)>,
    f: u64,
    depth: usize,
) -> Result<()> {
    if depth > MAX_DEPTH {
        return Err(step_error(
            rep,
            "placements nested too deeply (or in a cycle)",
        ));
    }
    if out.len() > MAX_INSTANCES {
        return Err(step_error(
            f,
            format!("more than {MAX_INSTANCES} placed faces"),
        ));
    }
    let links: Vec<&Up> = group(rep, same)
        .iter()
        .flat_map(|g| ups.get(g).map(Vec::as_slice).unwrap_or(&[]))
        .collect();
    if links.is_empty() {
        out.push((f, acc));
        return Ok(());
    }
    for up in links {
        let mut next = acc.clone();
        if let Some(m) = up.motion {
            next.push(m);
        }
        paths(up.parent, ups, same, next, out, f, depth + 1)?;
    }
    Ok(())
}

//! STEP (ISO 10303-21, AP203/AP214) input and output.
//!
//! **Reading** ([`StepModel`]): every `ADVANCED_FACE` / `FACE_SURFACE` of the file, in the
//! order written, becomes one face of a shell ([`StepModel::shell`]), its surface a
//! [`NurbsSurface`]:
//!
//! - `B_SPLINE_SURFACE_WITH_KNOTS`, simple or as the complex instance with
//!   `RATIONAL_B_SPLINE_SURFACE`: as written, on its knot domain (periodic surfaces as their
//!   unclamped knot vectors);
//! - `PLANE`, `CYLINDRICAL_SURFACE`, `CONICAL_SURFACE`, `SPHERICAL_SURFACE`,
//!   `TOROIDAL_SURFACE`: converted exactly, with interval control data, to rational NURBS
//!   ([`surfaces`] says how and in which parameters). Spheres and tori are taken whole;
//!   cylinders and cones whole around their axis over the face's height range; planes over the
//!   rectangle (in the plane's own axes) that holds the face's boundary.
//!
//! A face is its whole surface patch (the box above): the face's trimming curves are not
//! applied. [`StepFace::trimmed`] says whether the face may be smaller than that patch: it is
//! `false` only when the face has no bounds or every bound is a vertex loop or made of seam
//! edges (and, on a cylinder or cone, of circles about its axis), i.e. when the patch is the
//! face; planes are always `true`. The result document carries it per face pair.
//!
//! Faces of assemblies are placed where the assembly puts them (`ITEM_DEFINED_TRANSFORMATION`,
//! `MAPPED_ITEM`; see [`assembly`]); a part used twice gives its faces twice. The file's
//! numbers are taken as they are (lengths in the file's unit, [`StepModel::length_unit`]);
//! plane angles in radians unless the file declares a conversion-based plane angle unit, whose
//! factor is applied. Other surface types (`SURFACE_OF_REVOLUTION`, `OFFSET_SURFACE`, ...) are
//! refused.
//!
//! **Errors.** A file that cannot be read gives [`Error::Step`], naming the instance `#n` where
//! the problem is in one, or the line of a syntax error; never a panic.
//!
//! **Why a reader of our own.** `ruststep` 0.4 (whose Part 21 parser `truck-stepio` builds on)
//! panics on integers beyond `i64` (`expect` in its tokenizer) and parses nested lists by
//! unbounded recursion (a stack overflow, not an error, on deep nesting); `truck-stepio` 0.3
//! unwraps knot-vector construction and turns elementary surfaces into its own `f64` types, not
//! exact NURBS with enclosed control data. The subset needed here (Part 21 syntax, a dozen
//! entity types) is short enough to write with the limits above ([`part21`]).
//!
//! **Writing** ([`mod@write`]): certified curves as `B_SPLINE_CURVE_WITH_KNOTS` in a
//! `GEOMETRIC_CURVE_SET` of a `GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION`, as
//! OpenCASCADE writes free curves; with p-curves on request, as `SURFACE_CURVE`s (see
//! [`mod@write`]).

pub mod assembly;
mod bounds;
mod entities;
pub mod part21;
pub mod surfaces;
pub mod write;

use crate::error::{Error, Result};
use crate::geometry::nurbs::NurbsSurface;
use crate::shell::Face;
use entities::{step_error, Entities};
use std::path::Path;

/// The largest STEP file read (bytes).
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// One face of a STEP file.
#[derive(Debug, Clone, PartialEq)]
pub struct StepFace {
    /// The face's instance number (`#n`).
    pub entity: u64,
    /// Its surface's instance number.
    pub surface_entity: u64,
    /// The surface's entity name (`SPHERICAL_SURFACE`, `B_SPLINE_SURFACE_WITH_KNOTS`,
    /// `RATIONAL_B_SPLINE_SURFACE`, ...).
    pub surface_kind: String,
    /// Whether the face may be smaller than [`StepFace::surface`] (see the module
    /// documentation): the intersection is computed on the whole surface patch.
    pub trimmed: bool,
    /// The surface patch the face is intersected on, placed where the assembly puts it.
    pub surface: NurbsSurface,
    /// Which placement of the face this is: 0, or more when its part is used several times in
    /// the assembly (each use is one face here).
    pub placement: usize,
}

/// The faces of a STEP file.
#[derive(Debug, Clone, PartialEq)]
pub struct StepModel {
    /// The faces, in the order the file lists them.
    pub faces: Vec<StepFace>,
    /// The length unit: `"METRE"` with its SI prefix if any (e.g. `"MILLI METRE"`), the name of a
    /// conversion-based unit, or `None` when the file declares none.
    pub length_unit: Option<String>,
}

impl StepModel {
    /// Reads the faces of a STEP file's text (see the module documentation).
    ///
    /// Errors: [`Error::Step`] for a file that is not Part 21, an instance that is missing or
    /// malformed or of an unsupported type, a file without faces.
    pub fn from_text(text: &str) -> Result<StepModel> {
        let file = part21::parse(text)?;
        let e = Entities { file: &file };
        let angle = surfaces::angle_factor(&e)?;
        let mut read = std::collections::HashMap::new();
        let mut ids = Vec::new();
        for &id in &file.order {
            let inst = e.get(id)?;
            let rec = ["ADVANCED_FACE", "FACE_SURFACE"]
                .iter()
                .find_map(|n| inst.record(n));
            if let Some(r) = rec {
                let a = entities::Args { id, record: r };
                read.insert(id, read_face(&e, a, angle)?);
                ids.push(id);
            }
        }
        let mut faces: Vec<StepFace> = Vec::new();
        for (id, place) in assembly::face_placements(&e, &ids)? {
            let Some(f) = read.get(&id) else { continue };
            let placement = faces.iter().filter(|g| g.entity == id).count();
            faces.push(StepFace {
                surface: assembly::place(&f.surface, &place, id)?,
                placement,
                ..f.clone()
            });
        }
        if faces.is_empty() {
            return Err(Error::Step {
                entity: None,
                message: "no ADVANCED_FACE or FACE_SURFACE in the file".into(),
            });
        }
        Ok(StepModel {
            faces,
            length_unit: length_unit(&e)?,
        })
    }

    /// Reads and parses a STEP file; read failures give [`Error::Io`], files above
    /// [`MAX_FILE_BYTES`] and unreadable contents [`Error::Step`] (the message starts with the
    /// path).
    pub fn from_path(path: &Path) -> Result<StepModel> {
        let io = |e: std::io::Error| Error::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        };
        let size = std::fs::metadata(path).map_err(io)?.len();
        if size > MAX_FILE_BYTES {
            return Err(Error::Step {
                entity: None,
                message: format!(
                    "{}: {size} bytes, more than {MAX_FILE_BYTES}",
                    path.display()
                ),
            });
        }
        let bytes = std::fs::read(path).map_err(io)?;
        let text = String::from_utf8_lossy(&bytes);
        Self::from_text(&text).map_err(|e| match e {
            Error::Step { entity, message } => Error::Step {
                entity,
                message: format!("{}: {message}", path.display()),
            },
            other => other,
        })
    }

    /// The faces as a shell, each split into its Bézier pieces ([`Face::from_nurbs`]).
    ///
    /// Errors: [`Error::Step`] naming the face's surface when its split fails.
    pub fn shell(&self) -> Result<Vec<Face>> {
        self.faces
            .iter()
            .map(|f| {
                Face::from_nurbs(&f.surface)
                    .map_err(|e| step_error(f.surface_entity, format!("cannot be split: {e}")))
            })
            .collect()
    }
}

/// Reads one face: its surface as a NURBS on the patch the face is intersected on.
fn read_face(
    e: &Entities<'_>,
    face: entities::Args<'_>,
    angle: inari::Interval,
) -> Result<StepFace> {
    let bounds = face.refs(1)?;
    let sid = face.reference(2)?;
    let inst = e.get(sid)?;
    let name = inst.name();
    let kind = |s: &str| inst.record(s).is_some();
    let simple = |names: &[&str]| e.record(sid, names);
    let (surface, kind_name, trimmed) = if kind("B_SPLINE_SURFACE_WITH_KNOTS") {
        let b = bounds::boundary(e, &bounds, None)?;
        let k = if kind("RATIONAL_B_SPLINE_SURFACE") {
            "RATIONAL_B_SPLINE_SURFACE"
        } else {
            "B_SPLINE_SURFACE_WITH_KNOTS"
        };
        (surfaces::bspline(e, sid)?, k, !b.natural)
    } else if kind("SPHERICAL_SURFACE") || kind("TOROIDAL_SURFACE") {
        let b = bounds::boundary(e, &bounds, None)?;
        let s = if kind("SPHERICAL_SURFACE") {
            surfaces::sphere(e, simple(&["SPHERICAL_SURFACE"])?)?
        } else {
            surfaces::torus(e, simple(&["TOROIDAL_SURFACE"])?)?
        };
        let k = if kind("SPHERICAL_SURFACE") {
            "SPHERICAL_SURFACE"
        } else {
            "TOROIDAL_SURFACE"
        };
        (s, k, !b.natural)
    } else if kind("CYLINDRICAL_SURFACE") || kind("CONICAL_SURFACE") {
        let a = simple(&["CYLINDRICAL_SURFACE", "CONICAL_SURFACE"])?;
        let f = surfaces::placement(e, a.reference(1)?)?;
        let axis = surfaces::mid(&f.z);
        let b = bounds::boundary(e, &bounds, Some(axis))?;
        unknown_edge(&b)?;
        let v = b
            .range(surfaces::mid(&f.origin), axis)
            .filter(|[lo, hi]| lo < hi)
            .ok_or_else(|| step_error(face.id, "a face of no height on its cylinder or cone"))?;
        (
            surfaces::cylinder_or_cone(e, a, v, angle)?,
            if a.name() == "CONICAL_SURFACE" {
                "CONICAL_SURFACE"
            } else {
                "CYLINDRICAL_SURFACE"
            },
            !b.natural,
        )
    } else if kind("PLANE") {
        let a = simple(&["PLANE"])?;
        let f = surfaces::placement(e, a.reference(1)?)?;
        let b = bounds::boundary(e, &bounds, None)?;
        unknown_edge(&b)?;
        let o = surfaces::mid(&f.origin);
        let (u, v) = match (
            b.range(o, surfaces::mid(&f.x)),
            b.range(o, surfaces::mid(&f.y)),
        ) {
            (Some(u), Some(v)) if u[0] < u[1] && v[0] < v[1] => (u, v),
            _ => {
                return Err(step_error(
                    face.id,
                    "a plane face whose bounds enclose no area (or no bounds)",
                ))
            }
        };
        (surfaces::plane(e, a, u, v)?, "PLANE", true)
    } else {
        return Err(step_error(
            sid,
            format!("surface type {name} is not supported"),
        ));
    };
    Ok(StepFace {
        entity: face.id,
        surface_entity: sid,
        surface_kind: kind_name.to_string(),
        trimmed,
        surface,
        placement: 0,
    })
}

/// An error naming the first edge curve whose reach is unknown, where the box depends on it
/// (planes, cylinders, cones; elsewhere such an edge only makes the face trimmed).
fn unknown_edge(b: &bounds::Boundary) -> Result<()> {
    match &b.unknown {
        Some((id, name)) => Err(step_error(
            *id,
            format!("edge curve {name} is not supported on a plane, cylinder or cone face"),
        )),
        None => Ok(()),
    }
}

/// The length unit the file declares (see [`StepModel::length_unit`]).
fn length_unit(e: &Entities<'_>) -> Result<Option<String>> {
    for &id in &e.file.order {
        let inst = e.get(id)?;
        if inst.record("LENGTH_UNIT").is_none() {
            continue;
        }
        if let Some(r) = inst.record("SI_UNIT") {
            let a = entities::Args { id, record: r };
            let enum_of = |p: &part21::Param| match p {
                part21::Param::Enum(s) => Some(s.clone()),
                _ => None,
            };
            let prefix = a.at(0).ok().and_then(enum_of);
            let name = a
                .at(1)
                .ok()
                .and_then(enum_of)
                .unwrap_or_else(|| "METRE".into());
            return Ok(Some(match prefix {
                Some(p) => format!("{p} {name}"),
                None => name,
            }));
        }
        if let Some(r) = inst.record("CONVERSION_BASED_UNIT") {
            if let Ok(part21::Param::Str(s)) = (entities::Args { id, record: r }).at(0) {
                return Ok(Some(s.clone()));
            }
        }
    }
    Ok(None)
}

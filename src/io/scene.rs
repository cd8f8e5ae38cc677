//! The scene file: two surfaces (or two shells of surfaces) and optional run options, as JSON.
//!
//! ```json
//! {"surfaces": [A, B], "options": {"step": 0.05, "method": "march", "tolerance": 1e-9, "name": "x"}}
//! ```
//!
//! with `A` and `B` each one surface `S` or a non-empty array of surfaces (a shell; every face
//! of A is intersected with every face of B, see [`crate::shell`]), and each `S` one of
//!
//! * `{"kind": "bezier", "degree": [m, n], "points": [[x,y,z], …], "weights": […],
//!   "domain": [[u0,u1],[v0,v1]]}`: `(m+1)(n+1)` points, index `i·(n+1)+j`; `weights` (default
//!   all 1) and `domain` (default the unit square) optional; every coordinate and weight is a
//!   number or an interval `[lo, hi]`;
//! * `{"kind": "polynomial", "domain": [[u0,u1],[v0,v1]], "x": [[i,j,c], …], "y": […],
//!   "z": […], "w": […]}`: each component the sum of `c·uⁱ·vʲ`, the surface `(x/w, y/w, z/w)`;
//!   `w` (default 1) and `domain` (default the unit square) optional;
//! * `{"kind": "nurbs", "degree": [p, q], "knots": [[u_0, …, u_{nu+p}], [v_0, …, v_{nv+q}]],
//!   "points": [[x,y,z], …], "weights": […]}`: `nu·nv` Cartesian control points with
//!   `nu = len(knots[0]) − p − 1`, point `(i, j)` at index `i·nv + j`; `weights` optional (all
//!   1); knots non-decreasing, clamped or not; domain `[u_p, u_nu] × [v_q, v_nv]`; coordinates
//!   and weights may be intervals (see [`NurbsSurface`]).
//!
//! [`ShellScene`] reads every scene; [`Scene`] reads those of two single Bézier patches (a
//! NURBS surface of one knot span counts as one).
//!
//! The parser walks the [`serde_json::Value`] by hand so every problem is reported as an
//! [`Error::InvalidInput`] naming the surface index and the field path (top-level and option
//! problems have no surface index), or as [`Error::Scene`] when the text is not a JSON object.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::nurbs::NurbsSurface;
use crate::geometry::power::{PowerSurface, PowerTerm};
use crate::geometry::surface::Domain;
use crate::numeric::scalar::{interval, point};
use crate::shell::Face;
use inari::Interval;
use serde_json::{json, Map, Value};
use std::path::Path;

pub use crate::solve::Method;

/// Run options of a scene; every field has a documented default.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneOptions {
    /// Marching step length L (> 0, finite; default 0.05).
    pub step: f64,
    /// Tracing method (default [`Method::Both`]: march, certify, and check the marched points
    /// against the certificates).
    pub method: Method,
    /// The required tolerance a certified branch should meet (model units; > 0, finite; default
    /// 1e-9; `"tolerance"` in the scene file).
    pub required_tolerance: f64,
    /// An optional name for the scene.
    pub name: Option<String>,
}

impl Default for SceneOptions {
    fn default() -> Self {
        SceneOptions {
            step: 0.05,
            method: Method::Both,
            required_tolerance: 1e-9,
            name: None,
        }
    }
}

/// A parsed scene: two validated patches and the run options.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The two surfaces, in file order (surface 0 is P, surface 1 is Q).
    pub surfaces: [RationalBezierPatch; 2],
    /// The run options.
    pub options: SceneOptions,
}

/// A parsed scene in its general form: two shells (each a list of faces) and the run options.
#[derive(Debug, Clone, PartialEq)]
pub struct ShellScene {
    /// Shell A (the first entry of `"surfaces"`) and shell B (the second), faces in file order.
    pub shells: [Vec<Face>; 2],
    /// The run options.
    pub options: SceneOptions,
}

fn shape(field: &str, what: &str) -> Error {
    Error::input(field, InputProblem::WrongShape(what.to_string()))
}

fn object<'a>(v: &'a Value, field: &str) -> Result<&'a Map<String, Value>> {
    v.as_object()
        .ok_or_else(|| shape(field, "expected an object"))
}

fn array<'a>(v: &'a Value, field: &str) -> Result<&'a Vec<Value>> {
    v.as_array()
        .ok_or_else(|| shape(field, "expected an array"))
}

/// Reject keys outside `allowed`; the error names `prefix` + key.
fn only_fields(map: &Map<String, Value>, allowed: &[&str], prefix: &str) -> Result<()> {
    match map.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(k) => Err(Error::input(
            format!("{prefix}{k}"),
            InputProblem::UnknownField(k.clone()),
        )),
        None => Ok(()),
    }
}

fn required<'a>(map: &'a Map<String, Value>, key: &str, field: &str) -> Result<&'a Value> {
    map.get(key)
        .ok_or_else(|| Error::input(field, InputProblem::Missing))
}

/// A finite JSON number.
fn number(v: &Value, field: &str) -> Result<f64> {
    let x = v
        .as_f64()
        .ok_or_else(|| shape(field, "expected a number"))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(Error::input(field, InputProblem::NonFinite))
    }
}

/// A number (point interval) or an interval `[lo, hi]` with finite `lo ≤ hi`.
fn interval_value(v: &Value, field: &str) -> Result<Interval> {
    if v.is_number() {
        return Ok(point(number(v, field)?));
    }
    let a = v
        .as_array()
        .ok_or_else(|| shape(field, "expected a number or an interval [lo, hi]"))?;
    if a.len() != 2 {
        return Err(shape(
            field,
            "an interval needs exactly two bounds [lo, hi]",
        ));
    }
    let lo = number(&a[0], field)?;
    let hi = number(&a[1], field)?;
    interval(lo, hi).ok_or_else(|| Error::input(field, InputProblem::InvertedInterval { lo, hi }))
}

/// A non-negative integer (degrees and exponents; integral floats such as `2.0` are accepted);
/// negative integers are [`InputProblem::BadDegree`].
fn count(v: &Value, field: &str) -> Result<usize> {
    if let Some(n) = v.as_u64() {
        return usize::try_from(n).map_err(|_| shape(field, "integer too large"));
    }
    if let Some(n) = v.as_i64() {
        return Err(Error::input(field, InputProblem::BadDegree(n)));
    }
    match v.as_f64() {
        Some(x) if x.fract() == 0.0 && x.abs() < 1e15 => {
            if x < 0.0 {
                Err(Error::input(field, InputProblem::BadDegree(x as i64)))
            } else {
                Ok(x as usize)
            }
        }
        _ => Err(shape(field, "expected a non-negative integer")),
    }
}

/// `[[u0,u1],[v0,v1]]` with finite bounds and `u0 < u1`, `v0 < v1`.
fn domain(v: Option<&Value>) -> Result<Domain> {
    let Some(v) = v else {
        return Ok(Domain::UNIT);
    };
    let a = array(v, "domain")?;
    if a.len() != 2 {
        return Err(Error::input(
            "domain",
            InputProblem::WrongCount {
                expected: 2,
                found: a.len(),
            },
        ));
    }
    let mut sides = [[0.0; 2]; 2];
    for (k, side) in a.iter().enumerate() {
        let field = format!("domain[{k}]");
        let b = array(side, &field)?;
        if b.len() != 2 {
            return Err(Error::input(
                field,
                InputProblem::WrongCount {
                    expected: 2,
                    found: b.len(),
                },
            ));
        }
        let lo = number(&b[0], &format!("{field}[0]"))?;
        let hi = number(&b[1], &format!("{field}[1]"))?;
        if lo >= hi {
            return Err(Error::input(field, InputProblem::EmptyDomain { lo, hi }));
        }
        sides[k] = [lo, hi];
    }
    Ok(Domain {
        u: sides[0],
        v: sides[1],
    })
}

fn degree_pair(map: &Map<String, Value>) -> Result<[usize; 2]> {
    let deg = array(required(map, "degree", "degree")?, "degree")?;
    if deg.len() != 2 {
        return Err(Error::input(
            "degree",
            InputProblem::WrongCount {
                expected: 2,
                found: deg.len(),
            },
        ));
    }
    let mut degree = [0; 2];
    for (k, d) in deg.iter().enumerate() {
        let field = format!("degree[{k}]");
        degree[k] = count(d, &field)?;
        if degree[k] == 0 {
            return Err(Error::input(field, InputProblem::BadDegree(0)));
        }
    }
    Ok(degree)
}

fn control_points(map: &Map<String, Value>) -> Result<Vec<[Interval; 3]>> {
    let pts = array(required(map, "points", "points")?, "points")?;
    let mut points = Vec::with_capacity(pts.len());
    for (k, p) in pts.iter().enumerate() {
        let field = format!("points[{k}]");
        let xyz = array(p, &field)?;
        if xyz.len() != 3 {
            return Err(Error::input(
                field,
                InputProblem::WrongCount {
                    expected: 3,
                    found: xyz.len(),
                },
            ));
        }
        let mut q = [point(0.0); 3];
        for c in 0..3 {
            q[c] = interval_value(&xyz[c], &format!("points[{k}][{c}]"))?;
        }
        points.push(q);
    }
    Ok(points)
}

fn weights(map: &Map<String, Value>) -> Result<Option<Vec<Interval>>> {
    let Some(w) = map.get("weights") else {
        return Ok(None);
    };
    let w = array(w, "weights")?;
    let mut out = Vec::with_capacity(w.len());
    for (k, x) in w.iter().enumerate() {
        let field = format!("weights[{k}]");
        let x = interval_value(x, &field)?;
        if x.inf() <= 0.0 {
            return Err(Error::input(field, InputProblem::NonPositiveWeight));
        }
        out.push(x);
    }
    Ok(Some(out))
}

fn bezier(map: &Map<String, Value>) -> Result<RationalBezierPatch> {
    only_fields(map, &["kind", "degree", "points", "weights", "domain"], "")?;
    let degree = degree_pair(map)?;
    let points = control_points(map)?;
    let weights = weights(map)?;
    RationalBezierPatch::new(degree, points, weights, domain(map.get("domain"))?)
}

fn terms(v: &Value, name: &str) -> Result<Vec<PowerTerm>> {
    let a = array(v, name)?;
    let mut out = Vec::with_capacity(a.len());
    for (k, t) in a.iter().enumerate() {
        let field = format!("{name}[{k}]");
        let t = array(t, &field)?;
        if t.len() != 3 {
            return Err(Error::input(
                field,
                InputProblem::WrongCount {
                    expected: 3,
                    found: t.len(),
                },
            ));
        }
        let i = count(&t[0], &format!("{field}[0]"))?;
        let j = count(&t[1], &format!("{field}[1]"))?;
        let c = number(&t[2], &format!("{field}[2]"))?;
        let exponent = |e: usize, idx: usize| {
            u32::try_from(e).map_err(|_| shape(&format!("{field}[{idx}]"), "exponent too large"))
        };
        out.push((exponent(i, 0)?, exponent(j, 1)?, c));
    }
    Ok(out)
}

fn polynomial(map: &Map<String, Value>) -> Result<RationalBezierPatch> {
    only_fields(map, &["kind", "domain", "x", "y", "z", "w"], "")?;
    let surface = PowerSurface {
        domain: domain(map.get("domain"))?,
        x: terms(required(map, "x", "x")?, "x")?,
        y: terms(required(map, "y", "y")?, "y")?,
        z: terms(required(map, "z", "z")?, "z")?,
        w: map.get("w").map(|w| terms(w, "w")).transpose()?,
    };
    surface.to_bezier()
}

fn knot_vector(v: &Value, field: &str) -> Result<Vec<f64>> {
    array(v, field)?
        .iter()
        .enumerate()
        .map(|(i, t)| number(t, &format!("{field}[{i}]")))
        .collect()
}

fn nurbs(map: &Map<String, Value>) -> Result<NurbsSurface> {
    only_fields(map, &["kind", "degree", "knots", "points", "weights"], "")?;
    let degree = degree_pair(map)?;
    let knots = array(required(map, "knots", "knots")?, "knots")?;
    if knots.len() != 2 {
        return Err(Error::input(
            "knots",
            InputProblem::WrongCount {
                expected: 2,
                found: knots.len(),
            },
        ));
    }
    let knots = [
        knot_vector(&knots[0], "knots[0]")?,
        knot_vector(&knots[1], "knots[1]")?,
    ];
    NurbsSurface::new(degree, knots, control_points(map)?, weights(map)?)
}

/// One surface object as a face (errors not yet attributed to a surface index).
fn face(v: &Value) -> Result<Face> {
    let map = object(v, "surface")?;
    let kind = required(map, "kind", "kind")?
        .as_str()
        .ok_or_else(|| shape("kind", "expected a string"))?;
    match kind {
        "bezier" => bezier(map).map(Face::from_patch),
        "polynomial" => polynomial(map).map(Face::from_patch),
        "nurbs" => Face::from_nurbs(&nurbs(map)?),
        other => Err(Error::input(
            "kind",
            InputProblem::UnknownKind(other.to_string()),
        )),
    }
}

/// The same input error with its field prefixed by `face[k].`.
fn in_face(e: Error, k: usize) -> Error {
    match e {
        Error::InvalidInput {
            surface,
            field,
            problem,
        } => Error::InvalidInput {
            surface,
            field: format!("face[{k}].{field}"),
            problem,
        },
        other => other,
    }
}

/// One side of a scene: a surface object (one face) or a non-empty array of them.
fn side(v: &Value) -> Result<Vec<Face>> {
    match v.as_array() {
        None => Ok(vec![face(v)?]),
        Some(list) if list.is_empty() => Err(shape("surface", "an empty list of faces")),
        Some(list) => list
            .iter()
            .enumerate()
            .map(|(k, f)| face(f).map_err(|e| in_face(e, k)))
            .collect(),
    }
}

fn positive(v: &Value, field: &str) -> Result<f64> {
    let x = number(v, field)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(shape(field, "expected a number > 0"))
    }
}

fn options(v: Option<&Value>) -> Result<SceneOptions> {
    let mut out = SceneOptions::default();
    let Some(v) = v else {
        return Ok(out);
    };
    let map = object(v, "options")?;
    only_fields(map, &["step", "method", "tolerance", "name"], "options.")?;
    if let Some(s) = map.get("step") {
        out.step = positive(s, "options.step")?;
    }
    if let Some(t) = map.get("tolerance") {
        out.required_tolerance = positive(t, "options.tolerance")?;
    }
    if let Some(m) = map.get("method") {
        let m = m
            .as_str()
            .ok_or_else(|| shape("options.method", "expected a string"))?;
        out.method = match m {
            "march" => Method::March,
            "validated" => Method::Validated,
            "both" => Method::Both,
            _ => {
                return Err(shape(
                    "options.method",
                    "expected \"march\", \"validated\" or \"both\"",
                ))
            }
        };
    }
    if let Some(n) = map.get("name") {
        let n = n
            .as_str()
            .ok_or_else(|| shape("options.name", "expected a string"))?;
        out.name = Some(n.to_string());
    }
    Ok(out)
}

/// A JSON number for a point interval, `[lo, hi]` otherwise.
fn interval_json(x: Interval) -> Value {
    if x.inf() == x.sup() {
        json!(x.inf())
    } else {
        json!([x.inf(), x.sup()])
    }
}

fn patch_json(p: &RationalBezierPatch) -> Value {
    let net = p.cartesian();
    let points: Vec<Value> = net
        .iter()
        .map(|c| {
            json!([
                interval_json(c[0]),
                interval_json(c[1]),
                interval_json(c[2])
            ])
        })
        .collect();
    let d = p.domain();
    let mut out = json!({
        "kind": "bezier",
        "degree": p.degree(),
        "points": points,
        "domain": [d.u, d.v],
    });
    if net.iter().any(|c| c[3] != point(1.0)) {
        out["weights"] = net.iter().map(|c| interval_json(c[3])).collect();
    }
    out
}

/// Read a file's text; read failures give [`Error::Io`].
fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|e| Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// Text to JSON; text that is not JSON gives [`Error::Scene`].
fn parse_text(text: &str) -> Result<Value> {
    serde_json::from_str(text).map_err(|e| Error::Scene(format!("invalid JSON: {e}")))
}

impl ShellScene {
    /// Parse a scene from a JSON value: each entry of `"surfaces"` one surface object or a
    /// non-empty array of them (see the module documentation). Errors in face `k` of a list
    /// name the field `face[k].…`.
    pub fn from_json_value(v: &Value) -> Result<ShellScene> {
        let map = v
            .as_object()
            .ok_or_else(|| Error::Scene("the scene must be a JSON object".into()))?;
        only_fields(map, &["surfaces", "options"], "")?;
        let list = array(required(map, "surfaces", "surfaces")?, "surfaces")?;
        if list.len() != 2 {
            return Err(Error::input(
                "surfaces",
                InputProblem::WrongCount {
                    expected: 2,
                    found: list.len(),
                },
            ));
        }
        let first = side(&list[0]).map_err(|e| e.in_surface(0))?;
        let second = side(&list[1]).map_err(|e| e.in_surface(1))?;
        Ok(ShellScene {
            shells: [first, second],
            options: options(map.get("options"))?,
        })
    }

    /// Parse a scene from JSON text; text that is not JSON gives [`Error::Scene`].
    pub fn from_json_str(text: &str) -> Result<ShellScene> {
        Self::from_json_value(&parse_text(text)?)
    }

    /// Read and parse a scene file; read failures give [`Error::Io`].
    pub fn from_path(path: &Path) -> Result<ShellScene> {
        Self::from_json_str(&read_text(path)?)
    }

    /// The two-patch [`Scene`] when each shell is one face of one Bézier piece.
    pub fn as_pair(&self) -> Option<Scene> {
        match &self.shells {
            [a, b] if a.len() == 1 && b.len() == 1 => Some(Scene {
                surfaces: [a[0].as_patch()?.clone(), b[0].as_patch()?.clone()],
                options: self.options.clone(),
            }),
            _ => None,
        }
    }
}

impl Scene {
    /// Parse a scene of two single patches from a JSON value (see the module documentation for
    /// the format). A scene of several faces, or with a NURBS surface of several knot spans, is
    /// an [`Error::InvalidInput`] on `surfaces`: read it as a [`ShellScene`].
    pub fn from_json_value(v: &Value) -> Result<Scene> {
        ShellScene::from_json_value(v)?.as_pair().ok_or_else(|| {
            shape(
                "surfaces",
                "a shell scene (several faces or Bézier pieces); read it as a ShellScene",
            )
        })
    }

    /// Parse a scene from JSON text; text that is not JSON gives [`Error::Scene`].
    pub fn from_json_str(text: &str) -> Result<Scene> {
        Self::from_json_value(&parse_text(text)?)
    }

    /// Read and parse a scene file; read failures give [`Error::Io`].
    pub fn from_path(path: &Path) -> Result<Scene> {
        Self::from_json_str(&read_text(path)?)
    }

    /// The scene as JSON, both surfaces in Bézier form. Patches built from Cartesian data are
    /// written exactly as given; others (e.g. converted polynomials) as the rigorous interval
    /// projection of their homogeneous net, so parsing the output gives patches that enclose
    /// the originals.
    pub fn to_json(&self) -> Value {
        let o = &self.options;
        let mut options = json!({
            "step": o.step,
            "method": o.method.name(),
            "tolerance": o.required_tolerance,
        });
        if let Some(n) = &o.name {
            options["name"] = json!(n);
        }
        json!({
            "surfaces": [patch_json(&self.surfaces[0]), patch_json(&self.surfaces[1])],
            "options": options,
        })
    }
}

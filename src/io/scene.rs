//! The scene file: two surfaces and optional run options, as JSON.
//!
//! ```json
//! {"surfaces": [S, S], "options": {"step": 0.05, "method": "march", "tolerance": 1e-9, "name": "x"}}
//! ```
//!
//! with each `S` one of
//!
//! * `{"kind": "bezier", "degree": [m, n], "points": [[x,y,z], …], "weights": […],
//!   "domain": [[u0,u1],[v0,v1]]}`: `(m+1)(n+1)` points, index `i·(n+1)+j`; `weights` (default
//!   all 1) and `domain` (default the unit square) optional; every coordinate and weight is a
//!   number or an interval `[lo, hi]`;
//! * `{"kind": "polynomial", "domain": [[u0,u1],[v0,v1]], "x": [[i,j,c], …], "y": […],
//!   "z": […], "w": […]}`: each component the sum of `c·uⁱ·vʲ`, the surface `(x/w, y/w, z/w)`;
//!   `w` (default 1) and `domain` (default the unit square) optional.
//!
//! The parser walks the [`serde_json::Value`] by hand so every problem is reported as an
//! [`Error::InvalidInput`] naming the surface index and the field path (top-level and option
//! problems have no surface index), or as [`Error::Scene`] when the text is not a JSON object.

use crate::error::{Error, InputProblem, Result};
use crate::geometry::bezier::RationalBezierPatch;
use crate::geometry::power::{PowerSurface, PowerTerm};
use crate::geometry::surface::Domain;
use crate::numeric::scalar::{interval, point};
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

fn bezier(map: &Map<String, Value>) -> Result<RationalBezierPatch> {
    only_fields(map, &["kind", "degree", "points", "weights", "domain"], "")?;
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
    let weights = match map.get("weights") {
        None => None,
        Some(w) => {
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
            Some(out)
        }
    };
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

/// One surface object (errors not yet attributed to a surface index).
fn surface(v: &Value) -> Result<RationalBezierPatch> {
    let map = object(v, "surface")?;
    let kind = required(map, "kind", "kind")?
        .as_str()
        .ok_or_else(|| shape("kind", "expected a string"))?;
    match kind {
        "bezier" => bezier(map),
        "polynomial" => polynomial(map),
        other => Err(Error::input(
            "kind",
            InputProblem::UnknownKind(other.to_string()),
        )),
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

impl Scene {
    /// Parse a scene from a JSON value (see the module documentation for the format).
    pub fn from_json_value(v: &Value) -> Result<Scene> {
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
        let first = surface(&list[0]).map_err(|e| e.in_surface(0))?;
        let second = surface(&list[1]).map_err(|e| e.in_surface(1))?;
        Ok(Scene {
            surfaces: [first, second],
            options: options(map.get("options"))?,
        })
    }

    /// Parse a scene from JSON text; text that is not JSON gives [`Error::Scene`].
    pub fn from_json_str(text: &str) -> Result<Scene> {
        let v: Value =
            serde_json::from_str(text).map_err(|e| Error::Scene(format!("invalid JSON: {e}")))?;
        Self::from_json_value(&v)
    }

    /// Read and parse a scene file; read failures give [`Error::Io`].
    pub fn from_path(path: &Path) -> Result<Scene> {
        let text = std::fs::read_to_string(path).map_err(|e| Error::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        Self::from_json_str(&text)
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

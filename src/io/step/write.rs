//! Certified curves as a STEP file (AP214): each curve a `B_SPLINE_CURVE_WITH_KNOTS` (degree,
//! control points, distinct knots with their multiplicities, as [`BSpline`] holds them), all in
//! one `GEOMETRIC_CURVE_SET` of a `GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION` under
//! one product, which is how OpenCASCADE writes free curves and reads them back as edges. Each
//! curve's name records its proven tolerance, e.g. `'curve 0 tolerance 3.1e-10'`.
//!
//! P-curves are not written: in STEP a p-curve (`PCURVE` with a `DEFINITIONAL_REPRESENTATION`)
//! refers to its surface entity and must be in that surface's parameters. An edge's p-curves are
//! in the parameters of the NURBS faces it was traced on, which are the STEP parameters for
//! B-spline surfaces and planes but not for cylinders, cones, spheres and tori (their STEP
//! parameters are angles, ours rational); and writing them would mean writing the faces too.
//! The result's `--edges` JSON carries the p-curves.

use crate::edge::BSpline;
use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::Path;

/// One curve to write.
#[derive(Debug, Clone)]
pub struct StepCurve<'a> {
    /// Its label (written as the curve's name).
    pub label: String,
    /// The curve.
    pub curve: &'a BSpline<3>,
}

/// A real in Part 21 syntax (a decimal point always, `E` for the exponent), exact to the last
/// bit (the shortest text that reads back as the same `f64`).
pub fn real(x: f64) -> String {
    if !x.is_finite() {
        return "0.".into();
    }
    let s = format!("{x:?}");
    let (mantissa, exp) = match s.split_once(['e', 'E']) {
        Some((m, e)) => (m.to_string(), Some(e.to_string())),
        None => (s, None),
    };
    let mantissa = if mantissa.contains('.') {
        mantissa
    } else {
        format!("{mantissa}.")
    };
    match exp {
        Some(e) => format!("{mantissa}E{e}"),
        None => mantissa,
    }
}

/// The SI prefix (e.g. `.MILLI.` or `$`) of a length unit named as [`super::StepModel::length_unit`]
/// names it; `None` for units that are not a metre.
fn si_prefix(unit: &str) -> Option<String> {
    let mut words = unit.split_whitespace();
    match (words.next(), words.next(), words.next()) {
        (Some("METRE"), None, None) => Some("$".into()),
        (Some(p), Some("METRE"), None) if p.chars().all(|c| c.is_ascii_uppercase()) => {
            Some(format!(".{p}."))
        }
        _ => None,
    }
}

/// Escapes a string for Part 21 (apostrophes doubled; non-ASCII replaced).
fn string(s: &str) -> String {
    s.chars()
        .map(|c| match c {
            '\'' => "''".to_string(),
            c if c.is_ascii() && !c.is_ascii_control() => c.to_string(),
            _ => "?".to_string(),
        })
        .collect()
}

/// The text of a STEP file holding `curves`; lengths in `length_unit` (`"MILLI METRE"`,
/// `"METRE"`, ...; millimetres if `None`); `uncertainty` the file's distance accuracy.
///
/// Errors: [`Error::Step`] for a length unit that is not a metre with an SI prefix, or a curve
/// with fewer than two control points or knots that do not fit them.
pub fn step_text(
    name: &str,
    curves: &[StepCurve<'_>],
    length_unit: Option<&str>,
    uncertainty: f64,
) -> Result<String> {
    let unit = length_unit.unwrap_or("MILLI METRE");
    let prefix = si_prefix(unit).ok_or_else(|| Error::Step {
        entity: None,
        message: format!("cannot write curves in the length unit `{unit}`"),
    })?;
    let mut d = String::new();
    let mut next = 1u64;
    let mut add = |d: &mut String, body: String| -> u64 {
        let id = next;
        next += 1;
        let _ = writeln!(d, "#{id} = {body};");
        id
    };
    let app = add(
        &mut d,
        "APPLICATION_CONTEXT('core data for automotive mechanical design processes')".into(),
    );
    add(
        &mut d,
        format!("APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"),
    );
    let pc = add(&mut d, format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let product = add(
        &mut d,
        format!("PRODUCT('{0}','{0}','',(#{pc}))", string(name)),
    );
    let pdf = add(
        &mut d,
        format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"),
    );
    let pdc = add(
        &mut d,
        format!("PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"),
    );
    let pd = add(
        &mut d,
        format!("PRODUCT_DEFINITION('design','',#{pdf},#{pdc})"),
    );
    let pds = add(&mut d, format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"));
    let length = add(
        &mut d,
        format!("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT({prefix},.METRE.) )"),
    );
    let angle = add(
        &mut d,
        "( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )".into(),
    );
    let solid = add(
        &mut d,
        "( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )".into(),
    );
    let unc = add(
        &mut d,
        format!(
            "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{length},'distance_accuracy_value','confusion accuracy')",
            real(uncertainty)
        ),
    );
    let ctx = add(
        &mut d,
        format!(
            "( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid})) REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY') )"
        ),
    );
    let mut ids = Vec::new();
    for (k, c) in curves.iter().enumerate() {
        let b = c.curve;
        let n = b.points.len();
        if n < 2 || b.degree == 0 || b.knots.len() != n + b.degree + 1 {
            return Err(Error::Step {
                entity: None,
                message: format!("curve {k} ({}) is not a valid B-spline", c.label),
            });
        }
        let pts: Vec<String> = b
            .points
            .iter()
            .map(|p| {
                format!(
                    "#{}",
                    add(
                        &mut d,
                        format!(
                            "CARTESIAN_POINT('',({},{},{}))",
                            real(p[0]),
                            real(p[1]),
                            real(p[2])
                        )
                    )
                )
            })
            .collect();
        let mut knots: Vec<f64> = Vec::new();
        let mut mults: Vec<usize> = Vec::new();
        for &t in &b.knots {
            match knots.last() {
                Some(&last) if last == t => *mults.last_mut().unwrap_or(&mut 0) += 1,
                _ => {
                    knots.push(t);
                    mults.push(1);
                }
            }
        }
        let id = add(
            &mut d,
            format!(
                "B_SPLINE_CURVE_WITH_KNOTS('{}',{},({}),.UNSPECIFIED.,.F.,.F.,({}),({}),.UNSPECIFIED.)",
                string(&c.label),
                b.degree,
                pts.join(","),
                mults.iter().map(|m| m.to_string()).collect::<Vec<_>>().join(","),
                knots.iter().map(|&t| real(t)).collect::<Vec<_>>().join(",")
            ),
        );
        ids.push(format!("#{id}"));
    }
    let set = add(
        &mut d,
        format!("GEOMETRIC_CURVE_SET('',({}))", ids.join(",")),
    );
    let rep = add(
        &mut d,
        format!("GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('',(#{set}),#{ctx})"),
    );
    add(
        &mut d,
        format!("SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep})"),
    );
    add(
        &mut d,
        format!("PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"),
    );
    Ok(format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ssitrace certified intersection curves'),'2;1');\nFILE_NAME('{}','',(''),(''),'ssitrace','ssitrace','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));\nENDSEC;\nDATA;\n{d}ENDSEC;\nEND-ISO-10303-21;\n",
        string(name)
    ))
}

/// Writes [`step_text`] to `path`.
///
/// Errors: as [`step_text`]; [`Error::Io`] when the file cannot be written.
pub fn write_step_curves(
    path: &Path,
    name: &str,
    curves: &[StepCurve<'_>],
    length_unit: Option<&str>,
    uncertainty: f64,
) -> Result<()> {
    let text = step_text(name, curves, length_unit, uncertainty)?;
    std::fs::write(path, text).map_err(|e| Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// The `B_SPLINE_CURVE_WITH_KNOTS` curves of a STEP file's text, in the order written, with
/// their names (non-rational, simple instances only: what [`step_text`] writes).
///
/// Errors: [`Error::Step`] as [`super::part21::parse`], or naming a curve that is malformed.
pub fn read_step_curves(text: &str) -> Result<Vec<(String, BSpline<3>)>> {
    use super::entities::{step_error, Entities};
    let file = super::part21::parse(text)?;
    let e = Entities { file: &file };
    let mut out = Vec::new();
    for &id in &file.order {
        if e.get(id)?.record("B_SPLINE_CURVE_WITH_KNOTS").is_none() {
            continue;
        }
        let a = e.record(id, &["B_SPLINE_CURVE_WITH_KNOTS"])?;
        let label = match a.at(0)? {
            super::part21::Param::Str(s) => s.clone(),
            _ => String::new(),
        };
        let degree = a.int(1, 1, 64)? as usize;
        let points = a
            .refs(2)?
            .into_iter()
            .map(|p| super::surfaces::cartesian_point(&e, p))
            .collect::<Result<Vec<_>>>()?;
        let mults = a.ints(6, 1, 65)?;
        let ks = a.reals(7)?;
        let total: usize = mults.iter().sum();
        if mults.len() != ks.len() || total != points.len() + degree + 1 {
            return Err(step_error(id, "knots do not fit the control points"));
        }
        let knots = ks
            .iter()
            .zip(&mults)
            .flat_map(|(&t, &m)| std::iter::repeat_n(t, m))
            .collect();
        out.push((
            label,
            BSpline {
                degree,
                knots,
                points,
            },
        ));
    }
    Ok(out)
}

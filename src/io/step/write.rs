//! Certified curves as a STEP file (AP214): each curve a `B_SPLINE_CURVE_WITH_KNOTS` (degree,
//! control points, distinct knots with their multiplicities, as [`BSpline`] holds them), all in
//! one `GEOMETRIC_CURVE_SET` of a `GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION` under
//! one product, which is how OpenCASCADE writes free curves and reads them back as edges. Each
//! curve's name records its proven tolerance, e.g. `'curve 0 tolerance 3.1e-10'`.
//!
//! With p-curves ([`StepCurve::pcurves`], `--step-pcurves`), a curve is written as a
//! `SURFACE_CURVE` of its 3D curve and one `PCURVE` per surface: a 2D
//! `B_SPLINE_CURVE_WITH_KNOTS` in a `DEFINITIONAL_REPRESENTATION` (2D parametric context) on
//! the Bézier piece it lies on, written once per file as a rational `B_SPLINE_SURFACE_WITH_KNOTS`
//! on the piece's domain (the surface's own parameters), its control points and weights at the
//! midpoints of their interval enclosures. A STEP p-curve must lie in the parameters of the
//! surface entity it names, so the pieces are written rather than referring back to the input
//! files' surfaces: for converted cylinders, cones, spheres and tori the input's parameters are
//! angles, not the rational parameters the p-curves are in. A curve is split where it passes
//! from one pair of pieces to the next (one `SURFACE_CURVE` per part); OpenCASCADE reads each as
//! an edge with its 3D curve.

use crate::edge::BSpline;
use crate::error::{Error, Result};
use crate::geometry::RationalBezierPatch;
use std::fmt::Write as _;
use std::path::Path;

/// One curve to write.
#[derive(Debug, Clone)]
pub struct StepCurve<'a> {
    /// Its label (written as the curve's name).
    pub label: String,
    /// The curve.
    pub curve: &'a BSpline<3>,
    /// Its p-curves, if any: then it is written as a `SURFACE_CURVE` of the 3D curve and one
    /// `PCURVE` per entry.
    pub pcurves: Vec<StepPCurve<'a>>,
}

/// A p-curve to write: a 2D B-spline in the parameters of a Bézier piece, on the same knots as
/// its 3D curve.
#[derive(Debug, Clone)]
pub struct StepPCurve<'a> {
    /// The piece (written once per file as a rational B-spline surface on its domain).
    pub piece: &'a RationalBezierPatch,
    /// The curve in the piece's parameters.
    pub curve: &'a BSpline<2>,
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

/// The data section being written: instances numbered from 1.
struct Out {
    d: String,
    next: u64,
}

impl Out {
    fn add(&mut self, body: impl AsRef<str>) -> u64 {
        let id = self.next;
        self.next += 1;
        let _ = writeln!(self.d, "#{id} = {};", body.as_ref());
        id
    }

    /// Distinct knots and their multiplicities.
    fn knots(knots: &[f64]) -> (String, String) {
        let mut ks: Vec<f64> = Vec::new();
        let mut ms: Vec<usize> = Vec::new();
        for &t in knots {
            match (ks.last(), ms.last_mut()) {
                (Some(&last), Some(m)) if last == t => *m += 1,
                _ => {
                    ks.push(t);
                    ms.push(1);
                }
            }
        }
        let ms: Vec<String> = ms.iter().map(|m| m.to_string()).collect();
        let ks: Vec<String> = ks.iter().map(|&t| real(t)).collect();
        (ms.join(","), ks.join(","))
    }

    fn point(&mut self, p: &[f64]) -> String {
        let c: Vec<String> = p.iter().map(|&x| real(x)).collect();
        format!(
            "#{}",
            self.add(format!("CARTESIAN_POINT('',({}))", c.join(",")))
        )
    }

    /// A `B_SPLINE_CURVE_WITH_KNOTS` (3D or 2D).
    fn curve<const D: usize>(&mut self, label: &str, b: &BSpline<D>) -> Result<u64> {
        let n = b.points.len();
        if n < 2 || b.degree == 0 || b.knots.len() != n + b.degree + 1 {
            return Err(Error::Step {
                entity: None,
                message: format!("curve `{label}` is not a valid B-spline"),
            });
        }
        let pts: Vec<String> = b.points.iter().map(|p| self.point(p)).collect();
        let (mults, knots) = Self::knots(&b.knots);
        Ok(self.add(format!(
            "B_SPLINE_CURVE_WITH_KNOTS('{}',{},({}),.UNSPECIFIED.,.F.,.F.,({mults}),({knots}),.UNSPECIFIED.)",
            string(label),
            b.degree,
            pts.join(",")
        )))
    }

    /// A rational Bézier patch as a rational B-spline surface on its domain (control points and
    /// weights at the midpoints of their enclosures).
    fn patch(&mut self, p: &RationalBezierPatch) -> u64 {
        let [m, n] = p.degree();
        let net = p.cartesian();
        let mut rows = Vec::new();
        let mut weights = Vec::new();
        for i in 0..=m {
            let mut row = Vec::new();
            let mut wrow = Vec::new();
            for j in 0..=n {
                let c = net[i * (n + 1) + j];
                row.push(self.point(&[c[0].mid(), c[1].mid(), c[2].mid()]));
                wrow.push(real(c[3].mid()));
            }
            rows.push(format!("({})", row.join(",")));
            weights.push(format!("({})", wrow.join(",")));
        }
        let d = p.domain();
        self.add(format!(
            "( BOUNDED_SURFACE() B_SPLINE_SURFACE({m},{n},({}),.UNSPECIFIED.,.F.,.F.,.F.) \
             B_SPLINE_SURFACE_WITH_KNOTS(({},{}),({},{}),({},{}),({},{}),.PIECEWISE_BEZIER_KNOTS.) \
             GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(({})) \
             REPRESENTATION_ITEM('') SURFACE() )",
            rows.join(","),
            m + 1,
            m + 1,
            n + 1,
            n + 1,
            real(d.u[0]),
            real(d.u[1]),
            real(d.v[0]),
            real(d.v[1]),
            weights.join(",")
        ))
    }
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
    let mut o = Out {
        d: String::new(),
        next: 1,
    };
    let app = o.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
    o.add(format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ));
    let pc = o.add(format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let product = o.add(format!("PRODUCT('{0}','{0}','',(#{pc}))", string(name)));
    let pdf = o.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let pdc = o.add(format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ));
    let pd = o.add(format!("PRODUCT_DEFINITION('design','',#{pdf},#{pdc})"));
    let pds = o.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"));
    let length = o.add(format!(
        "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT({prefix},.METRE.) )"
    ));
    let angle = o.add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )");
    let solid = o.add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )");
    let unc = o.add(format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{length},'distance_accuracy_value','confusion accuracy')",
        real(uncertainty)
    ));
    let ctx = o.add(format!(
        "( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc})) GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid})) REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY') )"
    ));
    let mut ctx2 = None;
    let mut surfaces: Vec<(*const RationalBezierPatch, u64)> = Vec::new();
    let mut ids = Vec::new();
    for c in curves {
        if c.pcurves.is_empty() {
            ids.push(format!("#{}", o.curve(&c.label, c.curve)?));
            continue;
        }
        let c3 = o.curve(&c.label, c.curve)?;
        let ctx2 = *ctx2.get_or_insert_with(|| {
            o.add("( GEOMETRIC_REPRESENTATION_CONTEXT(2) PARAMETRIC_REPRESENTATION_CONTEXT() REPRESENTATION_CONTEXT('2D SPACE','') )")
        });
        let mut pcs = Vec::new();
        for pc in &c.pcurves {
            let key: *const RationalBezierPatch = pc.piece;
            let surf = match surfaces.iter().find(|(k, _)| *k == key) {
                Some(&(_, id)) => id,
                None => {
                    let id = o.patch(pc.piece);
                    surfaces.push((key, id));
                    id
                }
            };
            let b2 = o.curve("", pc.curve)?;
            let rep = o.add(format!("DEFINITIONAL_REPRESENTATION('',(#{b2}),#{ctx2})"));
            pcs.push(format!("#{}", o.add(format!("PCURVE('',#{surf},#{rep})"))));
        }
        let sc = o.add(format!(
            "SURFACE_CURVE('{}',#{c3},({}),.CURVE_3D.)",
            string(&c.label),
            pcs.join(",")
        ));
        ids.push(format!("#{sc}"));
    }
    let set = o.add(format!("GEOMETRIC_CURVE_SET('',({}))", ids.join(",")));
    let rep = o.add(format!(
        "GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('',(#{set}),#{ctx})"
    ));
    o.add(format!("SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep})"));
    o.add(format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"
    ));
    Ok(format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ssitrace certified intersection curves'),'2;1');\nFILE_NAME('{}','',(''),(''),'ssitrace','ssitrace','');\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));\nENDSEC;\nDATA;\n{}ENDSEC;\nEND-ISO-10303-21;\n",
        string(name),
        o.d
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

/// The 3D `B_SPLINE_CURVE_WITH_KNOTS` curves of a STEP file's text, in the order written, with
/// their names (non-rational, simple instances only: what [`step_text`] writes; 2D curves, the
/// p-curves, are skipped).
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
        let refs = a.refs(2)?;
        let is_2d = match refs.first() {
            Some(&p) => e.record(p, &["CARTESIAN_POINT"])?.reals(1)?.len() == 2,
            None => false,
        };
        if is_2d {
            continue;
        }
        let points = refs
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

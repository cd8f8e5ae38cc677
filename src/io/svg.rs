//! An SVG picture of an intersection result: three panels side by side.
//!
//! Left: the parameter domain of P `(σ, t)` with each branch's pre-image; middle: the parameter
//! domain of Q `(u, v)`; right: a fixed isometric projection of the model-space curves. Each
//! branch has its own colour and is labelled `b<id>` in every panel. Markers at branch ends:
//! filled circle = boundary end, cross = singular end, hollow square = incomplete end (Newton
//! failure or point budget), hollow circle = the seam of a closed loop (closed loops are also
//! drawn as closed polylines). Events are black: triangle = singular point, diamond = boundary
//! event. A legend below the panels lists every branch with its status and ends.
//!
//! Extension point for certified enclosures: [`Overlay`] carries boxes per panel, drawn as
//! translucent rectangles (parameter panels) or projected box edges (model panel).

use std::path::Path;

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::certify::contact::CertifiedContact;
use crate::certify::{CertifiedBranch, CertifiedEnd, EnclosureBox};
use crate::geometry::surface::Domain;
use crate::march::branch::{Branch, BranchStatus, EndReason, EventKind, Intersection};
use crate::{Error, Result};

/// Picture width in pixels.
pub const WIDTH: u32 = 1500;
/// Picture height in pixels.
pub const HEIGHT: u32 = 620;

const PANEL_HEIGHT: u32 = 470;
const MARGIN: u32 = 12;
const X_LABELS: u32 = 34;
const Y_LABELS: u32 = 48;
const CAPTION: u32 = 26;

/// Branch colours (Tableau 10); branch `k` gets `BRANCH_COLOURS[k % 10]`.
pub const BRANCH_COLOURS: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// An axis-aligned box in one parameter domain: `[[lo, hi], [lo, hi]]`.
pub type ParamBox = [[f64; 2]; 2];
/// An axis-aligned box in model space: `[[x_lo, y_lo, z_lo], [x_hi, y_hi, z_hi]]`.
pub type ModelBox = [[f64; 3]; 2];

/// Extra boxes drawn under the curves (e.g. certified enclosures), one list per panel.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overlay {
    /// Boxes in P's parameter domain `(σ, t)`.
    pub p_boxes: Vec<ParamBox>,
    /// Boxes in Q's parameter domain `(u, v)`.
    pub q_boxes: Vec<ParamBox>,
    /// Model-space boxes as `[min corner, max corner]`.
    pub xyz_boxes: Vec<ModelBox>,
}

/// Outline colour of certified boxes (drawn translucent, over the curves).
const BOX_COLOUR: RGBColor = RGBColor(0, 0, 0);
/// Outline width of certified boxes in pixels.
const BOX_STROKE: u32 = 4;

/// How many boxes per certified branch [`certified_overlay`] draws by default.
pub const DEFAULT_OVERLAY_BOXES: usize = 400;

/// The hull of a run of consecutive enclosure boxes (it holds everything each of them holds).
fn hull(run: &[EnclosureBox]) -> ([ParamBox; 2], ModelBox) {
    let mut pb = [[[f64::INFINITY, f64::NEG_INFINITY]; 2]; 2];
    let mut mb = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for b in run {
        for k in 0..2 {
            let (src, dst) = if k == 0 {
                (&b.p, &mut pb[0])
            } else {
                (&b.q, &mut pb[1])
            };
            for i in 0..2 {
                dst[i][0] = dst[i][0].min(src[i].inf());
                dst[i][1] = dst[i][1].max(src[i].sup());
            }
        }
        for (i, x) in b.xyz.iter().enumerate() {
            mb[0][i] = mb[0][i].min(x.inf());
            mb[1][i] = mb[1][i].max(x.sup());
        }
    }
    (pb, mb)
}

fn finite_box<const N: usize>(b: &[[f64; N]; 2]) -> bool {
    b.iter().flatten().all(|x| x.is_finite())
}

/// The overlay of certified branches: each branch's chain of enclosure boxes, consecutive
/// boxes merged into their hulls so that at most `max_boxes` are drawn per branch (a hull holds
/// the curve wherever its boxes do), plus the boxes of singular and close-branch ends.
/// Boxes with a non-finite bound are left out.
pub fn certified_overlay(branches: &[&CertifiedBranch], max_boxes: usize) -> Overlay {
    let mut overlay = Overlay::default();
    for c in branches {
        let n = c.boxes.len();
        let per = n.div_ceil(max_boxes.max(1)).max(1);
        for run in c.boxes.chunks(per) {
            let (pb, mb) = hull(run);
            if finite_box(&pb[0]) && finite_box(&pb[1]) && finite_box(&mb) {
                overlay.p_boxes.push(pb[0]);
                overlay.q_boxes.push(pb[1]);
                overlay.xyz_boxes.push(mb);
            }
        }
        for end in &c.ends {
            if let CertifiedEnd::Singular { near } | CertifiedEnd::CloseBranches { near, .. } = end
            {
                let pb = [
                    [near[0].inf(), near[0].sup()],
                    [near[1].inf(), near[1].sup()],
                ];
                let qb = [
                    [near[2].inf(), near[2].sup()],
                    [near[3].inf(), near[3].sup()],
                ];
                if finite_box(&pb) && finite_box(&qb) {
                    overlay.p_boxes.push(pb);
                    overlay.q_boxes.push(qb);
                }
            }
        }
    }
    overlay
}

/// Adds the step boxes of certified tangential contacts to `overlay` (consecutive boxes merged
/// into their hulls so that at most `max_boxes` are drawn per contact; boxes with a non-finite
/// bound are left out).
pub fn add_contact_boxes(overlay: &mut Overlay, contacts: &[CertifiedContact], max_boxes: usize) {
    for c in contacts {
        let n = c.steps.len();
        let per = n.div_ceil(max_boxes.max(1)).max(1);
        for run in c.steps.chunks(per) {
            let boxes: Vec<EnclosureBox> = run
                .iter()
                .map(|st| EnclosureBox {
                    s: st.s,
                    p: [st.apriori[0], st.apriori[1]],
                    q: [st.apriori[2], st.apriori[3]],
                    xyz: st.xyz,
                })
                .collect();
            let (pb, mb) = hull(&boxes);
            if finite_box(&pb[0]) && finite_box(&pb[1]) && finite_box(&mb) {
                overlay.p_boxes.push(pb[0]);
                overlay.q_boxes.push(pb[1]);
                overlay.xyz_boxes.push(mb);
            }
        }
    }
}

/// The colour of branch number `index` (its position in the result).
pub fn branch_colour(index: usize) -> RGBColor {
    BRANCH_COLOURS[index % BRANCH_COLOURS.len()]
}

/// Projects a model-space point to the picture plane of the model panel: x points down-left,
/// y down-right, z up (an isometric view).
pub fn isometric(xyz: [f64; 3]) -> (f64, f64) {
    let c = 3f64.sqrt() / 2.0;
    ((xyz[1] - xyz[0]) * c, xyz[2] - 0.5 * (xyz[0] + xyz[1]))
}

/// The SVG text for `result` over the declared domains `[P's, Q's]`, with no overlay.
pub fn render_svg(result: &Intersection, domains: [Domain; 2], title: &str) -> Result<String> {
    render_svg_with_overlay(result, domains, title, &Overlay::default())
}

/// Writes [`render_svg`]'s picture to `path` (I/O failures become [`Error::Io`]).
pub fn write_svg(
    path: &Path,
    result: &Intersection,
    domains: [Domain; 2],
    title: &str,
) -> Result<()> {
    let text = render_svg(result, domains, title)?;
    std::fs::write(path, text).map_err(|e| Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// Writes [`render_svg_with_overlay`]'s picture to `path` (I/O failures become [`Error::Io`]).
pub fn write_svg_with_overlay(
    path: &Path,
    result: &Intersection,
    domains: [Domain; 2],
    title: &str,
    overlay: &Overlay,
) -> Result<()> {
    let text = render_svg_with_overlay(result, domains, title, overlay)?;
    std::fs::write(path, text).map_err(|e| Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

/// The SVG text for `result` with the boxes of `overlay` drawn under the curves.
///
/// Never panics on odd data: non-finite coordinates are skipped, empty results and
/// degenerate domains still give a picture.
pub fn render_svg_with_overlay(
    result: &Intersection,
    domains: [Domain; 2],
    title: &str,
    overlay: &Overlay,
) -> Result<String> {
    let mut buf = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(render_err)?;
        let root = root.titled(title, ("sans-serif", 22)).map_err(render_err)?;
        let (panels_area, legend_area) = root.split_vertically(PANEL_HEIGHT);
        let panels = panels_area.split_evenly((1, 3));
        let p_points = |b: &Branch| b.points.iter().map(|c| (c.p[0], c.p[1])).collect();
        let q_points = |b: &Branch| b.points.iter().map(|c| (c.q[0], c.q[1])).collect();
        draw_param_panel(
            &panels[0],
            result,
            domains[0],
            "surface P: (σ, t)",
            ("σ", "t"),
            &p_points,
            &|e| (e.p[0], e.p[1]),
            &overlay.p_boxes,
        )?;
        draw_param_panel(
            &panels[1],
            result,
            domains[1],
            "surface Q: (u, v)",
            ("u", "v"),
            &q_points,
            &|e| (e.q[0], e.q[1]),
            &overlay.q_boxes,
        )?;
        draw_model_panel(&panels[2], result, &overlay.xyz_boxes)?;
        draw_legend(&legend_area, result, overlay.p_boxes.len())?;
        root.present().map_err(render_err)?;
    }
    Ok(buf)
}

fn render_err<E: std::fmt::Debug>(e: E) -> Error {
    Error::Render(format!("{e:?}"))
}

type Pt = (f64, f64);

/// A padded plotting range around `[lo, hi]`, never of zero or non-finite width.
fn padded(lo: f64, hi: f64) -> std::ops::Range<f64> {
    if !(lo.is_finite() && hi.is_finite()) || hi < lo {
        return -1.0..1.0;
    }
    let w = hi - lo;
    let pad = if w > 0.0 { 0.06 * w } else { 0.5 };
    (lo - pad)..(hi + pad)
}

fn finite(p: &Pt) -> bool {
    p.0.is_finite() && p.1.is_finite()
}

/// The branch polyline in one panel: closed loops are closed by repeating the first point.
fn branch_path(b: &Branch, pts: Vec<Pt>) -> Vec<Pt> {
    let mut pts: Vec<Pt> = pts.into_iter().filter(finite).collect();
    if b.status == BranchStatus::Closed {
        if let Some(first) = pts.first().copied() {
            pts.push(first);
        }
    }
    pts
}

/// A point of `path` for the branch label: of a dozen candidates along the path, the one
/// farthest (in pixels) from the labels already placed in this panel, which it joins.
fn label_position(chart: &Chart<'_, '_>, path: &[Pt], placed: &mut Vec<(i32, i32)>) -> Pt {
    let n = path.len();
    let candidates = (0..12).map(|k| path[(k * n / 12 + n / 24).min(n - 1)]);
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let score = |p: &Pt| {
        let (x, y) = chart.backend_coord(p);
        // The label runs about 80 px right of and 20 px above its point: keep it inside.
        if x + 80 > xs.end || y - 20 < ys.start {
            return -1.0;
        }
        placed
            .iter()
            .map(|(a, b)| {
                let (dx, dy) = (f64::from(x - a), f64::from(y - b));
                dx * dx + dy * dy
            })
            .fold(f64::INFINITY, f64::min)
    };
    let mut best = path[n / 2];
    let mut best_score = score(&best);
    for c in candidates {
        let sc = score(&c);
        if sc > best_score {
            best = c;
            best_score = sc;
        }
    }
    placed.push(chart.backend_coord(&best));
    best
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draws one branch (line, end markers, label) into a chart.
fn draw_branch(
    chart: &mut Chart<'_, '_>,
    index: usize,
    b: &Branch,
    pts: Vec<Pt>,
    placed_labels: &mut Vec<(i32, i32)>,
) -> Result<()> {
    let colour = branch_colour(index);
    let closed = b.status == BranchStatus::Closed;
    let path = branch_path(b, pts);
    if path.is_empty() {
        return Ok(());
    }
    chart
        .draw_series(std::iter::once(PathElement::new(
            path.clone(),
            colour.stroke_width(2),
        )))
        .map_err(render_err)?;
    let start = path[0];
    let last = if closed {
        path[path.len().saturating_sub(2)]
    } else {
        path[path.len() - 1]
    };
    if closed {
        chart
            .draw_series(std::iter::once(Circle::new(
                start,
                6,
                colour.stroke_width(2),
            )))
            .map_err(render_err)?;
    } else {
        for (end, at) in b.ends.iter().zip([start, last]) {
            draw_end_marker(chart, *end, at, colour)?;
        }
    }
    let label_at = label_position(chart, &path, placed_labels);
    let label = if closed {
        format!("b{} (loop)", b.id)
    } else {
        format!("b{}", b.id)
    };
    chart
        .draw_series(std::iter::once(
            EmptyElement::at(label_at)
                + Text::new(
                    label,
                    (7, -18),
                    ("sans-serif", 16).into_font().color(&colour),
                ),
        ))
        .map_err(render_err)?;
    Ok(())
}

fn draw_end_marker(
    chart: &mut Chart<'_, '_>,
    end: EndReason,
    at: Pt,
    colour: RGBColor,
) -> Result<()> {
    let res = match end {
        EndReason::Boundary { .. } => {
            chart.draw_series(std::iter::once(Circle::new(at, 5, colour.filled())))
        }
        EndReason::Singular => {
            chart.draw_series(std::iter::once(Cross::new(at, 6, colour.stroke_width(3))))
        }
        EndReason::ClosedLoop => {
            chart.draw_series(std::iter::once(Circle::new(at, 6, colour.stroke_width(2))))
        }
        EndReason::NewtonFailed | EndReason::PointLimit | EndReason::OwnPath => {
            chart.draw_series(std::iter::once(
                EmptyElement::at(at) + Rectangle::new([(-5, -5), (5, 5)], colour.stroke_width(2)),
            ))
        }
    };
    res.map(|_| ()).map_err(render_err)
}

fn draw_event_marker(chart: &mut Chart<'_, '_>, kind: EventKind, at: Pt) -> Result<()> {
    if !finite(&at) {
        return Ok(());
    }
    let res = match kind {
        EventKind::Singular => {
            chart.draw_series(std::iter::once(TriangleMarker::new(at, 7, BLACK.filled())))
        }
        EventKind::BoundaryEnd => chart.draw_series(std::iter::once(
            EmptyElement::at(at)
                + Polygon::new(vec![(0, -6), (6, 0), (0, 6), (-6, 0)], BLACK.filled()),
        )),
    };
    res.map(|_| ()).map_err(render_err)
}

#[allow(clippy::too_many_arguments)]
fn draw_param_panel(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    result: &Intersection,
    domain: Domain,
    caption: &str,
    axis_names: (&str, &str),
    points_of: &dyn Fn(&Branch) -> Vec<Pt>,
    event_at: &dyn Fn(&crate::march::branch::Event) -> Pt,
    boxes: &[ParamBox],
) -> Result<()> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 18))
        .margin(MARGIN)
        .x_label_area_size(X_LABELS)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(
            padded(domain.u[0], domain.u[1]),
            padded(domain.v[0], domain.v[1]),
        )
        .map_err(render_err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(axis_names.0)
        .y_desc(axis_names.1)
        .x_labels(6)
        .y_labels(6)
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 16))
        .draw()
        .map_err(render_err)?;
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(domain.u[0], domain.v[0]), (domain.u[1], domain.v[1])],
            BLACK.stroke_width(2),
        )))
        .map_err(render_err)?;
    let mut labels = Vec::new();
    for (k, b) in result.branches.iter().enumerate() {
        draw_branch(&mut chart, k, b, points_of(b), &mut labels)?;
    }
    // Certified boxes on top of the curves: a translucent band (boxes thinner than a pixel still
    // show as their outline) marks the certified stretch.
    chart
        .draw_series(boxes.iter().map(|b| {
            let ([u0, u1], [v0, v1]) = (b[0], b[1]);
            PathElement::new(
                vec![(u0, v0), (u1, v0), (u1, v1), (u0, v1), (u0, v0)],
                BOX_COLOUR.mix(0.45).stroke_width(BOX_STROKE),
            )
        }))
        .map_err(render_err)?;
    for e in &result.events {
        draw_event_marker(&mut chart, e.kind, event_at(e))?;
    }
    Ok(())
}

/// The 12 edges of a model box, projected.
fn box_edges(b: &ModelBox) -> Vec<[Pt; 2]> {
    let corner = |i: usize| isometric([b[i & 1][0], b[(i >> 1) & 1][1], b[(i >> 2) & 1][2]]);
    let mut edges = Vec::with_capacity(12);
    for i in 0..8usize {
        for bit in [1usize, 2, 4] {
            if i & bit == 0 {
                edges.push([corner(i), corner(i | bit)]);
            }
        }
    }
    edges
}

fn draw_model_panel(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    result: &Intersection,
    boxes: &[ModelBox],
) -> Result<()> {
    // Everything that will be drawn, projected, to fix an equal-scale view.
    let mut all: Vec<Pt> = result
        .branches
        .iter()
        .flat_map(|b| b.points.iter().map(|c| isometric(c.xyz)))
        .chain(result.events.iter().map(|e| isometric(e.xyz)))
        .chain(
            boxes
                .iter()
                .flat_map(|b| box_edges(b).into_iter().flatten()),
        )
        .filter(finite)
        .collect();
    if all.is_empty() {
        all.push((0.0, 0.0));
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in &all {
        x0 = x0.min(*x);
        x1 = x1.max(*x);
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    // Same scale on both axes: stretch the shorter side to the plot area's aspect ratio.
    let (w_px, h_px) = area.dim_in_pixel();
    let plot_w = w_px.saturating_sub(2 * MARGIN + Y_LABELS).max(1) as f64;
    let plot_h = h_px.saturating_sub(2 * MARGIN + X_LABELS + CAPTION).max(1) as f64;
    let span = ((x1 - x0) / plot_w).max((y1 - y0) / plot_h).max(1e-12) * 1.15;
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let xr = (cx - 0.5 * span * plot_w)..(cx + 0.5 * span * plot_w);
    let yr = (cy - 0.5 * span * plot_h)..(cy + 0.5 * span * plot_h);
    let mut chart = ChartBuilder::on(area)
        .caption("model space (isometric view)", ("sans-serif", 18))
        .margin(MARGIN)
        .x_label_area_size(X_LABELS)
        .y_label_area_size(Y_LABELS)
        .build_cartesian_2d(xr.clone(), yr.clone())
        .map_err(render_err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .disable_y_axis()
        .draw()
        .map_err(render_err)?;
    // Axis triad in the lower-left corner.
    let len = 0.12 * span * plot_w.min(plot_h);
    let origin = (
        xr.start + 0.14 * (xr.end - xr.start),
        yr.start + 0.14 * (yr.end - yr.start),
    );
    for (name, dir) in [
        ("x", [1.0, 0.0, 0.0]),
        ("y", [0.0, 1.0, 0.0]),
        ("z", [0.0, 0.0, 1.0]),
    ] {
        let d = isometric(dir);
        let tip = (origin.0 + len * d.0, origin.1 + len * d.1);
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![origin, tip],
                BLACK.stroke_width(1),
            )))
            .map_err(render_err)?;
        chart
            .draw_series(std::iter::once(Text::new(name, tip, ("sans-serif", 13))))
            .map_err(render_err)?;
    }
    let mut labels = Vec::new();
    for (k, b) in result.branches.iter().enumerate() {
        let pts = b.points.iter().map(|c| isometric(c.xyz)).collect();
        draw_branch(&mut chart, k, b, pts, &mut labels)?;
    }
    for b in boxes {
        chart
            .draw_series(box_edges(b).into_iter().map(|e| {
                PathElement::new(e.to_vec(), BOX_COLOUR.mix(0.45).stroke_width(BOX_STROKE))
            }))
            .map_err(render_err)?;
    }
    for e in &result.events {
        draw_event_marker(&mut chart, e.kind, isometric(e.xyz))?;
    }
    Ok(())
}

fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    result: &Intersection,
    certified_boxes: usize,
) -> Result<()> {
    let font = ("sans-serif", 14).into_font();
    let (w, _) = area.dim_in_pixel();
    let x0 = 30i32;
    let mut y = 18i32;
    let summary = format!(
        "{} branch(es), {} closed loop(s), {} event(s)",
        result.branches.len(),
        result
            .branches
            .iter()
            .filter(|b| b.status == BranchStatus::Closed)
            .count(),
        result.events.len()
    );
    let summary = if certified_boxes > 0 {
        format!("{summary}, {certified_boxes} certified box(es)")
    } else {
        summary
    };
    area.draw(&Text::new(summary, (x0, y), font.clone()))
        .map_err(render_err)?;
    // Marker key.
    let kx = (w as i32 / 2).max(400) - if certified_boxes > 0 { 140 } else { 0 };
    let key_y = y + 6;
    let mut kx_at = kx;
    let mut key = |label: &str, draw: &dyn Fn((i32, i32)) -> Result<()>| -> Result<()> {
        draw((kx_at, key_y))?;
        area.draw(&Text::new(
            label.to_string(),
            (kx_at + 10, key_y - 8),
            font.clone(),
        ))
        .map_err(render_err)?;
        kx_at += 22 + 8 * label.len() as i32;
        Ok(())
    };
    key("boundary end", &|p| {
        area.draw(&Circle::new(p, 5, BLACK.filled()))
            .map_err(render_err)
    })?;
    key("singular end", &|p| {
        area.draw(&Cross::new(p, 6, BLACK.stroke_width(3)))
            .map_err(render_err)
    })?;
    key("incomplete end", &|p| {
        area.draw(&Rectangle::new(
            [(p.0 - 5, p.1 - 5), (p.0 + 5, p.1 + 5)],
            BLACK.stroke_width(2),
        ))
        .map_err(render_err)
    })?;
    key("loop seam", &|p| {
        area.draw(&Circle::new(p, 6, BLACK.stroke_width(2)))
            .map_err(render_err)
    })?;
    key("singular event", &|p| {
        area.draw(&TriangleMarker::new(p, 7, BLACK.filled()))
            .map_err(render_err)
    })?;
    key("boundary event", &|p| {
        area.draw(&Polygon::new(
            vec![
                (p.0, p.1 - 6),
                (p.0 + 6, p.1),
                (p.0, p.1 + 6),
                (p.0 - 6, p.1),
            ],
            BLACK.filled(),
        ))
        .map_err(render_err)
    })?;
    if certified_boxes > 0 {
        key("certified box", &|p| {
            area.draw(&PathElement::new(
                vec![(p.0 - 6, p.1), (p.0 + 6, p.1)],
                BOX_COLOUR.mix(0.45).stroke_width(BOX_STROKE),
            ))
            .map_err(render_err)
        })?;
    }
    y += 24;
    // One line per branch, in up to three columns.
    let rows = 5usize;
    let shown = 15usize;
    for (k, b) in result.branches.iter().take(shown).enumerate() {
        let colour = branch_colour(k);
        let (col, row) = (k / rows, k % rows);
        let x = x0 + col as i32 * 480;
        let yy = y + row as i32 * 18;
        area.draw(&Rectangle::new(
            [(x, yy + 2), (x + 22, yy + 6)],
            colour.filled(),
        ))
        .map_err(render_err)?;
        let status = match b.status {
            BranchStatus::Closed => "closed loop".to_string(),
            BranchStatus::Open => {
                format!("open: {} → {}", b.ends[0], b.ends[1])
            }
            BranchStatus::Incomplete => format!("INCOMPLETE: {} → {}", b.ends[0], b.ends[1]),
        };
        let text = format!("b{}: {}, {} points", b.id, status, b.points.len());
        area.draw(&Text::new(
            text,
            (x + 28, yy - 4),
            font.clone().color(&colour),
        ))
        .map_err(render_err)?;
    }
    if result.branches.len() > shown {
        let text = format!("… and {} more branch(es)", result.branches.len() - shown);
        area.draw(&Text::new(text, (x0, y + rows as i32 * 18), font.clone()))
            .map_err(render_err)?;
    }
    Ok(())
}

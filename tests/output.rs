//! Result JSON and SVG output on synthetic results.

use serde_json::{json, Value};
use ssitrace::geometry::surface::Domain;
use ssitrace::io::result_json::{
    interval_from_json, interval_to_json, result_from_json, result_to_json, write_result,
    ResultMeta,
};
use ssitrace::io::svg::{branch_colour, render_svg, render_svg_with_overlay, write_svg, Overlay};
use ssitrace::march::branch::{
    Branch, BranchStatus, CurvePoint, EndReason, Event, EventKind, Intersection,
};
use ssitrace::numeric::scalar::{interval, point};
use ssitrace::Error;

/// P is the plane z = 0 over [0,1]², Q the same plane over [-1,1]² (q = 2p − 1).
fn curve_point(s: f64, t: f64) -> CurvePoint {
    CurvePoint {
        p: [s, t],
        q: [2.0 * s - 1.0, 2.0 * t - 1.0],
        xyz: [s, t, 0.0],
    }
}

/// An open branch t = s² from the boundary s = 0 to a singular end at s = 0.8, a closed
/// circle of radius 0.15 around (0.7, 0.3), and a singular event at the open branch's end.
fn synthetic() -> Intersection {
    let open: Vec<CurvePoint> = (0..=40)
        .map(|k| {
            let s = 0.8 * k as f64 / 40.0;
            curve_point(s, s * s)
        })
        .collect();
    let circle: Vec<CurvePoint> = (0..60)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 60.0;
            curve_point(0.7 + 0.15 * a.cos(), 0.3 + 0.15 * a.sin())
        })
        .collect();
    let end = curve_point(0.8, 0.64);
    Intersection {
        branches: vec![
            Branch {
                id: 0,
                status: BranchStatus::Open,
                ends: [EndReason::Boundary { surface: 0 }, EndReason::Singular],
                points: open,
            },
            Branch {
                id: 1,
                status: BranchStatus::Closed,
                ends: [EndReason::ClosedLoop, EndReason::ClosedLoop],
                points: circle,
            },
        ],
        events: vec![Event {
            kind: EventKind::Singular,
            p: end.p,
            q: end.q,
            xyz: end.xyz,
        }],
    }
}

fn domains() -> [Domain; 2] {
    [Domain::UNIT, Domain::new(-1.0, 1.0, -1.0, 1.0)]
}

fn meta() -> ResultMeta {
    let mut m = ResultMeta::new(Some("synthetic".into()), "march");
    m.stats.insert("points".into(), json!(101));
    m.stats.insert("seconds".into(), json!(0.125));
    m.certified
        .insert(1, json!({"boxes": [[[0.5, 0.6], [0.1, 0.2]]]}));
    m
}

#[test]
fn result_json_round_trips_through_text() {
    let result = synthetic();
    let meta = meta();
    let text = serde_json::to_string(&result_to_json(&result, &meta)).unwrap();
    let back = result_from_json(&serde_json::from_str(&text).unwrap()).unwrap();
    assert_eq!(back.intersection, result);
    assert_eq!(back.meta, meta);
}

#[test]
fn result_json_has_every_documented_field() {
    let doc = result_to_json(&synthetic(), &meta());
    assert_eq!(doc["format"], "ssitrace-result");
    assert_eq!(doc["version"], 1);
    assert_eq!(doc["scene"], "synthetic");
    assert_eq!(doc["method"], "march");
    assert_eq!(doc["stats"]["points"], 101);
    let b = &doc["branches"];
    assert_eq!(b.as_array().unwrap().len(), 2);
    assert_eq!(b[0]["id"], 0);
    assert_eq!(b[0]["status"], "open");
    assert_eq!(
        b[0]["ends"],
        json!([{"kind": "boundary", "surface": 0}, {"kind": "singular"}])
    );
    assert_eq!(b[1]["status"], "closed");
    assert_eq!(
        b[1]["ends"],
        json!([{"kind": "closed_loop"}, {"kind": "closed_loop"}])
    );
    // Points in all three coordinate systems, in order.
    let src = &synthetic().branches[0].points[20];
    assert_eq!(
        b[0]["points"][20],
        json!({"p": [src.p[0], src.p[1]], "q": [src.q[0], src.q[1]], "xyz": [src.xyz[0], src.xyz[1], src.xyz[2]]})
    );
    assert_eq!(b[0]["points"][20]["p"][0], 0.4);
    assert_eq!(b[0]["points"].as_array().unwrap().len(), 41);
    assert!(b[0].get("certified").is_none());
    assert_eq!(b[1]["certified"]["boxes"][0][0], json!([0.5, 0.6]));
    let e = &doc["events"][0];
    assert_eq!(e["kind"], "singular");
    assert_eq!(e["p"][0], 0.8);
    assert_eq!(e["xyz"].as_array().unwrap().len(), 3);
    // Without a scene name the member is present and null.
    let anon = result_to_json(&Intersection::default(), &ResultMeta::new(None, "march"));
    assert!(anon.get("scene").unwrap().is_null());
    assert_eq!(anon["branches"], json!([]));
    assert_eq!(anon["events"], json!([]));
    assert_eq!(anon["stats"], json!({}));
}

#[test]
fn result_json_file_round_trip_and_io_error() {
    let dir = std::env::temp_dir().join(format!("ssitrace-output-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("result.json");
    write_result(&path, &synthetic(), &meta()).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let back = result_from_json(&serde_json::from_str(&text).unwrap()).unwrap();
    assert_eq!(back.intersection, synthetic());
    let missing = dir.join("no/such/dir/result.json");
    match write_result(&missing, &synthetic(), &meta()) {
        Err(Error::Io { path, .. }) => assert!(path.contains("no/such/dir")),
        other => panic!("expected Error::Io, got {other:?}"),
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn result_json_rejects_malformed_documents() {
    let good = result_to_json(&synthetic(), &meta());
    let mutate = |f: &dyn Fn(&mut Value)| {
        let mut d = good.clone();
        f(&mut d);
        result_from_json(&d)
    };
    type Mutation = Box<dyn Fn(&mut Value)>;
    let cases: Vec<(&str, Mutation)> = vec![
        ("format", Box::new(|d| d["format"] = json!("other"))),
        ("version", Box::new(|d| d["version"] = json!(2))),
        ("method", Box::new(|d| d["method"] = json!(3))),
        (
            "status",
            Box::new(|d| d["branches"][0]["status"] = json!("weird")),
        ),
        (
            "end kind",
            Box::new(|d| d["branches"][0]["ends"][1]["kind"] = json!("x")),
        ),
        (
            "surface 2",
            Box::new(|d| d["branches"][0]["ends"][0]["surface"] = json!(2)),
        ),
        (
            "one end",
            Box::new(|d| d["branches"][0]["ends"] = json!([{"kind": "singular"}])),
        ),
        (
            "p arity",
            Box::new(|d| d["branches"][0]["points"][3]["p"] = json!([1.0])),
        ),
        (
            "null xyz",
            Box::new(|d| d["branches"][1]["points"][0]["xyz"][2] = Value::Null),
        ),
        (
            "event kind",
            Box::new(|d| d["events"][0]["kind"] = json!("tangent")),
        ),
        ("no branches", Box::new(|d| d["branches"] = Value::Null)),
    ];
    for (what, f) in cases {
        match mutate(&*f) {
            Err(Error::ResultFormat(_)) => {}
            other => panic!("{what}: expected Error::ResultFormat, got {other:?}"),
        }
    }
    assert!(result_from_json(&json!([1, 2])).is_err());
}

#[test]
fn interval_json_keeps_exact_outward_bounds() {
    // The f64 sum 0.1 + 0.2 rounds up; the outward-rounded enclosure has a lower bound one
    // ulp below it, so its two bounds differ and both must survive the text round trip.
    let sum = point(0.1) + point(0.2);
    assert!(sum.inf() < 0.1 + 0.2 && 0.1 + 0.2 <= sum.sup());
    let v = interval_to_json(sum).unwrap();
    let text = serde_json::to_string(&v).unwrap();
    let back: Value = serde_json::from_str(&text).unwrap();
    let lo = back[0].as_f64().unwrap();
    let hi = back[1].as_f64().unwrap();
    assert_eq!(lo.to_bits(), sum.inf().to_bits());
    assert_eq!(hi.to_bits(), sum.sup().to_bits());
    let again = interval_from_json(&back).unwrap();
    assert_eq!(again.inf().to_bits(), sum.inf().to_bits());
    assert_eq!(again.sup().to_bits(), sum.sup().to_bits());
    assert!(interval_to_json(inari::Interval::EMPTY).is_err());
    assert!(interval_to_json(inari::Interval::ENTIRE).is_err());
    assert!(interval_to_json(interval(0.0, f64::INFINITY).unwrap()).is_err());
    assert!(interval_from_json(&json!([1.0, 0.0])).is_err());
    assert!(interval_from_json(&json!([1.0])).is_err());
}

/// The `points` attributes of the polylines stroked in `colour` (`#RRGGBB`).
fn polylines_in(svg: &str, colour: &str) -> Vec<Vec<(f64, f64)>> {
    svg.split("<polyline")
        .skip(1)
        .filter(|tag| {
            let tag = &tag[..tag.find("/>").unwrap_or(tag.len())];
            tag.contains(&format!("stroke=\"{colour}\""))
        })
        .map(|tag| {
            let start = tag.find("points=\"").unwrap() + 8;
            let end = start + tag[start..].find('"').unwrap();
            tag[start..end]
                .split_whitespace()
                .map(|xy| {
                    let (x, y) = xy.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect()
}

fn hex(c: plotters::style::RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// Outlined (unfilled) black rectangles larger than a marker: the two domain frames.
fn domain_frames(svg: &str) -> Vec<(f64, f64)> {
    svg.split("<rect")
        .skip(1)
        .map(|t| &t[..t.find("/>").unwrap_or(t.len())])
        .filter(|t| t.contains("fill=\"none\"") && t.contains("stroke=\"#000000\""))
        .map(|t| {
            let attr = |name: &str| -> f64 {
                let s = t.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
                let e = s + t[s..].find('"').unwrap();
                t[s..e].parse().unwrap()
            };
            (attr("width"), attr("height"))
        })
        .filter(|(w, h)| *w > 50.0 && *h > 50.0)
        .collect()
}

/// Filled black polygons (event markers and the legend's marker keys).
fn black_polygons(svg: &str) -> usize {
    svg.split("<polygon")
        .skip(1)
        .filter(|t| t[..t.find("/>").unwrap_or(t.len())].contains("fill=\"#000000\""))
        .count()
}

fn assert_xml_ish(svg: &str) {
    assert!(
        svg.trim_start().starts_with("<svg"),
        "does not start with <svg"
    );
    assert!(
        svg.trim_end().ends_with("</svg>"),
        "does not end with </svg>"
    );
    assert_eq!(svg.matches("<text").count(), svg.matches("</text>").count());
    assert_eq!(svg.matches('<').count(), svg.matches('>').count());
}

#[test]
fn svg_shows_each_branch_in_each_panel() {
    let result = synthetic();
    let svg = render_svg(&result, domains(), "synthetic: open branch, loop, event").unwrap();
    if let Ok(dir) = std::env::var("SSITRACE_SVG_DIR") {
        write_svg(
            &std::path::Path::new(&dir).join("synthetic.svg"),
            &result,
            domains(),
            "synthetic: open branch, loop, event",
        )
        .unwrap();
    }
    assert_xml_ish(&svg);
    let open = polylines_in(&svg, &hex(branch_colour(0)));
    let loop_ = polylines_in(&svg, &hex(branch_colour(1)));
    assert_eq!(open.len(), 3, "open branch: one polyline per panel");
    assert_eq!(loop_.len(), 3, "closed loop: one polyline per panel");
    for line in &open {
        assert_eq!(line.len(), 41);
        assert_ne!(line[0], line[40], "open branch drawn closed");
    }
    for line in &loop_ {
        assert_eq!(
            line.len(),
            61,
            "closed loop not closed by repeating its start"
        );
        assert_eq!(line[0], line[60]);
    }
    // The three panels sit side by side: the polylines' x ranges do not overlap.
    let mut xs: Vec<(f64, f64)> = open
        .iter()
        .map(|l| {
            let min = l.iter().map(|p| p.0).fold(f64::MAX, f64::min);
            let max = l.iter().map(|p| p.0).fold(f64::MIN, f64::max);
            (min, max)
        })
        .collect();
    xs.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert!(xs[0].1 < xs[1].0 && xs[1].1 < xs[2].0, "{xs:?}");
    // Both domain frames; the domains are squares, so the frames are about as tall as wide
    // (the panels are a little taller than wide: allow 30 %).
    let frames = domain_frames(&svg);
    assert_eq!(frames.len(), 2, "{frames:?}");
    for (w, h) in frames {
        assert!(w > 200.0 && (h / w - 1.0).abs() < 0.3, "frame {w}×{h}");
    }
    // Labels: once per panel.
    assert_eq!(svg.matches(">\nb0\n</text>").count(), 3);
    assert_eq!(svg.matches(">\nb1 (loop)\n</text>").count(), 3);
    // The singular event: one black filled marker per panel, beyond the legend's keys
    // (which an empty result also has).
    let empty = render_svg(&Intersection::default(), domains(), "empty").unwrap();
    assert_eq!(
        black_polygons(&svg),
        black_polygons(&empty) + 3,
        "event markers"
    );
    assert!(svg.contains("2 branch(es), 1 closed loop(s), 1 event(s)"));
    assert!(svg.contains("b0: open: boundary of P → singular point, 41 points"));
}

#[test]
fn svg_of_empty_result_still_has_frames() {
    let svg = render_svg(&Intersection::default(), domains(), "empty").unwrap();
    assert_xml_ish(&svg);
    assert_eq!(domain_frames(&svg).len(), 2);
    for k in 0..3 {
        assert!(polylines_in(&svg, &hex(branch_colour(k))).is_empty());
    }
    assert!(svg.contains("0 branch(es), 0 closed loop(s), 0 event(s)"));
}

#[test]
fn svg_draws_overlay_boxes_and_survives_bad_numbers() {
    let mut result = synthetic();
    result.branches[0].points[5].xyz[0] = f64::NAN;
    result.branches[1].points[7].p[1] = f64::INFINITY;
    let overlay = Overlay {
        p_boxes: vec![[[0.1, 0.2], [0.1, 0.2]], [[0.5, 0.6], [0.2, 0.3]]],
        q_boxes: vec![[[-0.5, 0.0], [0.0, 0.5]]],
        xyz_boxes: vec![[[0.0, 0.0, -0.1], [0.2, 0.2, 0.1]]],
    };
    let svg = render_svg_with_overlay(&result, domains(), "overlay", &overlay).unwrap();
    assert_xml_ish(&svg);
    // Certified boxes are translucent wide outlines over the curves: closed 5-point outlines in
    // the parameter panels, 12 projected edges per model box, one key line in the legend.
    let outlines: Vec<usize> = svg
        .split("<polyline")
        .skip(1)
        .map(|t| &t[..t.find("/>").unwrap_or(t.len())])
        .filter(|t| t.contains("opacity=\"0.45\"") && t.contains("stroke-width=\"4\""))
        .map(|t| t.matches(',').count())
        .collect();
    assert_eq!(outlines.iter().filter(|&&n| n == 5).count(), 3);
    assert_eq!(
        outlines.iter().filter(|&&n| n == 2).count(),
        12 + 1,
        "one polyline per box edge, and the legend's key"
    );
    assert_eq!(outlines.len(), 16);
    assert!(svg.contains("certified box"));
    // The loop lost one point in P's panel only.
    let loop_ = polylines_in(&svg, &hex(branch_colour(1)));
    let mut lens: Vec<usize> = loop_.iter().map(Vec::len).collect();
    lens.sort();
    assert_eq!(lens, vec![60, 61, 61]);
}

/// Closed forms of two example scenes (see the README): the three Fig. 7 ellipses
/// `3u² + v² = 0.5, 0.6, 0.7` on z = 0, and the bicubic pair's branch σ = 1/2.
fn closed_form_examples() -> Intersection {
    let mut branches: Vec<Branch> = [0.5f64, 0.6, 0.7]
        .iter()
        .enumerate()
        .map(|(k, w)| Branch {
            id: k,
            status: BranchStatus::Closed,
            ends: [EndReason::ClosedLoop, EndReason::ClosedLoop],
            points: (0..80)
                .map(|i| {
                    let a = std::f64::consts::TAU * i as f64 / 80.0;
                    let (u, v) = ((w / 3.0).sqrt() * a.cos(), w.sqrt() * a.sin());
                    CurvePoint {
                        p: [u, v],
                        q: [u, v],
                        xyz: [u, v, 0.0],
                    }
                })
                .collect(),
        })
        .collect();
    // z(t): the cubic Bézier with values (3/32, 3/8, 13/64, 9/64).
    let c = [3.0 / 32.0, 3.0 / 8.0, 13.0 / 64.0, 9.0 / 64.0];
    let z = |t: f64| {
        let s = 1.0 - t;
        c[0] * s * s * s + 3.0 * c[1] * s * s * t + 3.0 * c[2] * s * t * t + c[3] * t * t * t
    };
    branches.push(Branch {
        id: 3,
        status: BranchStatus::Open,
        ends: [
            EndReason::Boundary { surface: 0 },
            EndReason::Boundary { surface: 0 },
        ],
        points: (0..=50)
            .map(|i| {
                let t = i as f64 / 50.0;
                CurvePoint {
                    p: [0.5, t],
                    q: [(t + 0.25) / 1.5, (z(t) + 1.0) / 2.0],
                    xyz: [0.5, t, z(t)],
                }
            })
            .collect(),
    });
    Intersection {
        branches,
        events: vec![],
    }
}

#[test]
fn svg_of_several_loops_and_a_branch() {
    let result = closed_form_examples();
    let doms = [
        Domain::new(-1.0, 1.0, -1.0, 1.0),
        Domain::new(-1.0, 1.0, -1.0, 1.0),
    ];
    let svg = render_svg(&result, doms, "three ellipses and a bicubic branch").unwrap();
    if let Ok(dir) = std::env::var("SSITRACE_SVG_DIR") {
        std::fs::write(std::path::Path::new(&dir).join("closed_forms.svg"), &svg).unwrap();
    }
    assert_xml_ish(&svg);
    for k in 0..3 {
        let lines = polylines_in(&svg, &hex(branch_colour(k)));
        assert_eq!(lines.len(), 3, "loop {k}");
        assert!(lines.iter().all(|l| l.len() == 81 && l[0] == l[80]));
    }
    // The ellipses are nested: in P's panel, loop k's horizontal extent grows with k.
    let widths: Vec<f64> = (0..3)
        .map(|k| {
            let l = &polylines_in(&svg, &hex(branch_colour(k)))[0];
            let xs = l.iter().map(|p| p.0);
            xs.clone().fold(f64::MIN, f64::max) - xs.fold(f64::MAX, f64::min)
        })
        .collect();
    assert!(widths[0] < widths[1] && widths[1] < widths[2], "{widths:?}");
    assert_eq!(polylines_in(&svg, &hex(branch_colour(3))).len(), 3);
    assert!(svg.contains("4 branch(es), 3 closed loop(s), 0 event(s)"));
}

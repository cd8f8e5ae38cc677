//! STEP files that cannot be read give the typed error `Error::Step`, naming the instance where
//! the problem is in one; never a panic, hang or unbounded allocation, also on mutated and
//! truncated copies of the OCCT-written files of tests/data/ (a property test).

use proptest::prelude::*;
use ssitrace::io::step::StepModel;
use ssitrace::Error;
use std::path::Path;

fn text(name: &str) -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(name),
    )
    .expect("test data")
}

/// `text(name)` with `from` (which must occur) replaced by `to`.
fn edited(name: &str, from: &str, to: &str) -> String {
    let t = text(name);
    assert!(t.contains(from), "{from} not in {name}");
    t.replacen(from, to, 1)
}

/// Reads `t`, expects `Error::Step` about `entity` whose message contains `words`.
fn refused(t: &str, entity: Option<u64>, words: &str) {
    match StepModel::from_text(t) {
        Err(Error::Step { entity: e, message }) => {
            assert_eq!(e, entity, "entity of: {message}");
            assert!(message.contains(words), "`{words}` not in: {message}");
        }
        Err(other) => panic!("not a STEP error: {other}"),
        Ok(_) => panic!("read a file that should be refused ({words})"),
    }
}

#[test]
fn good_files_read() {
    for f in [
        "occt_sphere.step",
        "occt_sphere_nurbs.step",
        "occt_plane.step",
        "occt_torus.step",
        "occt_cylinder.step",
        "occt_cone.step",
        "occt_box.step",
        "occt_two_spheres.step",
    ] {
        let m = StepModel::from_text(&text(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
        assert!(!m.faces.is_empty(), "{f}");
        m.shell().unwrap_or_else(|e| panic!("{f}: {e}"));
    }
}

#[test]
fn syntax_errors_name_the_line() {
    refused("", None, "not a STEP file");
    refused("hello", None, "not a STEP file");
    let t = text("occt_sphere.step");
    refused(&t[..t.len() / 2], None, "line");
    refused(
        &t.replacen(
            "GEOMETRIC_REPRESENTATION_CONTEXT(3)",
            "GEOMETRIC_REPRESENTATION_CONTEXT(99999999999999999999999)",
            1,
        ),
        None,
        "out of range",
    );
    let deep = format!("{}1.{}", "(".repeat(200), ")".repeat(200));
    refused(
        &t.replacen(
            "SPHERICAL_SURFACE('',#23,1.)",
            &format!("SPHERICAL_SURFACE('',#23,{deep})"),
            1,
        ),
        None,
        "nested deeper",
    );
    refused(
        &t.replacen("#22 = ", "#21 = ", 1),
        Some(21),
        "defined twice",
    );
    refused(&t.replacen("ENDSEC;\nEND-ISO", "END-ISO", 1), None, "line");
    refused(&t.replacen("'',#23,1.", "'',#23,1.E", 1), None, "exponent");
}

#[test]
fn entity_errors_name_the_entity() {
    let s = "occt_sphere.step";
    refused(&edited(s, "#23,1.)", "#23,-1.)"), Some(22), "not positive");
    refused(
        &edited(
            s,
            "#22 = SPHERICAL_SURFACE('',#23,1.)",
            "#22 = OFFSET_SURFACE('',#23,1.,.F.)",
        ),
        Some(22),
        "OFFSET_SURFACE is not supported",
    );
    refused(
        &edited(s, "#24 = CARTESIAN_POINT('',(0.,0.,0.));", ""),
        Some(24),
        "not defined",
    );
    refused(
        &edited(
            s,
            "#24 = CARTESIAN_POINT('',(0.,0.,0.))",
            "#24 = CARTESIAN_POINT('',(0.,0.))",
        ),
        Some(24),
        "2 coordinates",
    );
    refused(
        &edited(
            s,
            "#25 = DIRECTION('',(0.,0.,1.))",
            "#25 = DIRECTION('',(0.,0.,0.))",
        ),
        Some(23),
        "zero length",
    );
    refused(
        &edited(
            s,
            "#22 = SPHERICAL_SURFACE('',#23,1.)",
            "#22 = SPHERICAL_SURFACE('',#24,1.)",
        ),
        Some(24),
        "AXIS2_PLACEMENT_3D",
    );
    refused(
        &edited(s, "#17 = ADVANCED_FACE('',(#18),#22,.T.);", ""),
        Some(17),
        "not defined",
    );
    refused(
        &edited(
            s,
            "#17 = ADVANCED_FACE('',(#18),#22,.T.);",
            "#17 = FACE_BOUND('',#19,.T.);",
        ),
        None,
        "no ADVANCED_FACE",
    );
    // A placement whose transformation is not one.
    let a = "occt_two_spheres.step";
    let t = text(a);
    let idt = t
        .lines()
        .find(|l| l.contains("ITEM_DEFINED_TRANSFORMATION"))
        .unwrap();
    let id: u64 = idt[1..idt.find(' ').unwrap()].parse().unwrap();
    let bad = format!("#{id} = ITEM_DEFINED_TRANSFORMATION('','',#11,#12);");
    refused(&t.replacen(idt, &bad, 1), Some(12), "AXIS2_PLACEMENT_3D");
    let n = "occt_sphere_nurbs.step";
    refused(
        &edited(n, "(1,2,2,2,2,1)", "(1,2,2,2,2,9)"),
        Some(22),
        "add up",
    );
    // A huge multiplicity is refused before anything is allocated.
    refused(
        &edited(n, "(1,2,2,2,2,1)", "(1,2,2,2,2,4000000000000)"),
        Some(22),
        "integers in",
    );
    refused(
        &edited(n, "B_SPLINE_SURFACE(2,2,", "B_SPLINE_SURFACE(0,2,"),
        Some(22),
        "parameter 0",
    );
    refused(
        &edited(
            n,
            "(1.,0.707106781187,1.,0.707106781187,1.)",
            "(-1.,0.707106781187,1.,0.707106781187,1.)",
        ),
        Some(22),
        "weight",
    );
    refused(
        &edited(n, "(3,2,3)", "(3,3,3)"),
        Some(22),
        "multiplicities add up",
    );
    // An edge curve of a type the reader does not place: refused on a plane face (its box
    // depends on it); on a torus face it only makes the face trimmed.
    let p = "occt_plane.step";
    refused(
        &edited(
            p,
            "#27 = LINE('',#28,#29);",
            "#27 = OFFSET_CURVE_3D('',#28,1.,.F.,#29);",
        ),
        Some(27),
        "OFFSET_CURVE_3D is not supported",
    );
    let torus = edited(
        "occt_torus.step",
        "#24 = SEAM_CURVE('',#25,",
        "#24 = SURFACE_CURVE('',#25,",
    );
    let torus = torus.replacen(
        "#25 = CIRCLE('',#26,2.5);",
        "#25 = CLOTHOID('',#26,2.5);",
        1,
    );
    let m = StepModel::from_text(&torus).expect("reads");
    assert!(m.faces[0].trimmed, "an edge that is not a seam");
    let t = text(p);
    let face = t.lines().find(|l| l.contains("ADVANCED_FACE")).unwrap();
    let id: u64 = face[1..face.find(' ').unwrap()].parse().unwrap();
    let open = face.find("(#").unwrap();
    let close = face[open..].find(')').unwrap() + open;
    let unbounded = format!("{}(){}", &face[..open], &face[close + 1..]);
    refused(&t.replacen(face, &unbounded, 1), Some(id), "no area");
}

/// A B-spline surface of a few kilobytes that would split into 64 × 64 Bézier pieces of degree
/// 64 × 64 (17 million control points) is refused before it is split; a small one is read.
#[test]
fn bspline_too_large_to_split_is_refused() {
    let file = |degree: usize, spans: usize| {
        let n = degree + spans;
        let row = format!("({})", vec!["#3"; n].join(","));
        let rows = vec![row; n].join(",");
        let mut mults = vec![degree + 1];
        mults.extend(std::iter::repeat_n(1, spans - 1));
        mults.push(degree + 1);
        let mults = mults
            .iter()
            .map(|m| m.to_string())
            .collect::<Vec<_>>()
            .join(",");
        let knots = (0..=spans)
            .map(|k| format!("{k}."))
            .collect::<Vec<_>>()
            .join(",");
        format!(
            "ISO-10303-21;HEADER;ENDSEC;DATA;\n#1=ADVANCED_FACE('',(),#2,.T.);\n\
             #2=B_SPLINE_SURFACE_WITH_KNOTS('',{degree},{degree},({rows}),.UNSPECIFIED.,.F.,.F.,.F.,\
             ({mults}),({mults}),({knots}),({knots}),.UNSPECIFIED.);\n\
             #3=CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;END-ISO-10303-21;\n"
        )
    };
    refused(&file(64, 64), Some(2), "too many to split");
    let m = StepModel::from_text(&file(2, 3)).expect("a small one reads");
    assert!(!m.faces[0].trimmed, "no bounds: the whole surface");
}

/// One mutation of a text: truncate, replace a byte, delete or duplicate a range.
#[derive(Debug, Clone)]
enum Mutation {
    Truncate(usize),
    Replace(usize, char),
    Delete(usize, usize),
    Duplicate(usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let chars = prop::sample::select(vec![
        '(', ')', '#', ',', ';', '\'', '.', '$', '*', '=', '0', '1', '9', 'E', '-', '+', ' ', 'A',
        '/',
    ]);
    prop_oneof![
        any::<usize>().prop_map(Mutation::Truncate),
        (any::<usize>(), chars).prop_map(|(a, c)| Mutation::Replace(a, c)),
        (any::<usize>(), 1usize..40).prop_map(|(a, n)| Mutation::Delete(a, n)),
        (any::<usize>(), 1usize..200).prop_map(|(a, n)| Mutation::Duplicate(a, n)),
    ]
}

fn apply(t: &mut Vec<u8>, m: &Mutation) {
    if t.is_empty() {
        return;
    }
    let n = t.len();
    match *m {
        Mutation::Truncate(a) => t.truncate(a % n),
        Mutation::Replace(a, c) => t[a % n] = c as u8,
        Mutation::Delete(a, len) => {
            let a = a % n;
            t.drain(a..(a + len).min(n));
        }
        Mutation::Duplicate(a, len) => {
            let a = a % n;
            let piece: Vec<u8> = t[a..(a + len).min(n)].to_vec();
            t.splice(a..a, piece);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    /// Mutated and truncated STEP files are read or refused with a typed error, never a panic.
    #[test]
    fn mutated_files_never_panic(
        file in prop::sample::select(vec![
            "occt_sphere.step", "occt_sphere_nurbs.step", "occt_plane.step", "occt_torus.step",
            "occt_cylinder.step", "occt_cone.step", "occt_box.step", "occt_two_spheres.step",
        ]),
        ms in prop::collection::vec(mutation(), 1..4),
    ) {
        let mut t = text(file).into_bytes();
        for m in &ms {
            apply(&mut t, m);
        }
        let t = String::from_utf8_lossy(&t);
        match StepModel::from_text(&t) {
            Ok(model) => {
                // Whatever was read splits or is refused with a typed error too.
                if let Err(e) = model.shell() {
                    prop_assert!(matches!(e, Error::Step { .. }), "{e}");
                }
            }
            Err(e) => prop_assert!(matches!(e, Error::Step { .. }), "{e}"),
        }
    }
}

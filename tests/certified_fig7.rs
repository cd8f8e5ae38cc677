//! Seed 000 Fig. 7 certified: a degree-6 surface against a plane cut in three nested ellipses
//! 3u² + v² = 0.5, 0.6, 0.7 whose minimal distances are about 0.036 and 0.039. Each must be
//! certified as a closed loop, every box must meet its own ellipse (and only it), and the tubes of
//! different loops must be disjoint — a certificate that strays onto a neighbour fails here.

use ssitrace::certified::{CertifiedBranch, CertifiedEnd};
use ssitrace::io::scene::{Method, Scene};
use ssitrace::pipeline::{run, RunOptions};
use ssitrace::scalar::point;

#[test]
fn three_nested_loops_are_certified_with_disjoint_tubes() {
    let path = format!("{}/scenes/wu_andrade_fig7.json", env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::from_path(std::path::Path::new(&path)).unwrap();
    let mut opts = RunOptions::from_scene(&scene);
    opts.method = Method::Validated;
    let report = run(&scene, &opts).expect("runs");
    let loops: Vec<&CertifiedBranch> = report
        .certificates
        .iter()
        .map(|c| c.result.as_ref().expect("certified"))
        .collect();
    assert_eq!(loops.len(), 3);
    let mut levels = Vec::new();
    for c in &loops {
        assert_eq!(c.ends, [CertifiedEnd::ClosedLoop, CertifiedEnd::ClosedLoop]);
        // The level 3σ² + t² of this loop: every box meets exactly that ellipse.
        let level =
            |b: &ssitrace::certified::EnclosureBox| point(3.0) * b.p[0].sqr() + b.p[1].sqr();
        let first = level(&c.boxes[0]);
        let own = [0.5, 0.6, 0.7]
            .into_iter()
            .find(|w| first.contains(*w))
            .expect("on an ellipse");
        for b in &c.boxes {
            let l = level(b);
            assert!(l.contains(own), "a box leaves its ellipse {own}");
            for other in [0.5, 0.6, 0.7] {
                if other != own {
                    assert!(
                        !l.contains(other),
                        "a box meets the neighbouring ellipse {other}"
                    );
                }
            }
            assert!(b.xyz[2].contains(0.0));
        }
        levels.push(own);
        println!(
            "loop 3σ²+t² = {own}: {} steps, tolerance {:.2e}, max transversal width {:.2e}",
            c.steps(),
            c.tolerance,
            c.widths.iter().cloned().fold(0.0, f64::max)
        );
    }
    levels.sort_by(f64::total_cmp);
    assert_eq!(levels, [0.5, 0.6, 0.7]);
    // Disjoint tubes: no model-space box of one loop meets a box of another.
    for i in 0..3 {
        for j in i + 1..3 {
            for a in &loops[i].boxes {
                for b in &loops[j].boxes {
                    assert!(
                        a.xyz.iter().zip(&b.xyz).any(|(x, y)| x.disjoint(*y)),
                        "tubes {i} and {j} meet"
                    );
                }
            }
        }
    }
}

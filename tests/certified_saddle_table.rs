//! The seed paper's Table 1 experiment (Mukundan et al. 2004): the saddle z = u·v against the
//! planes z = δ. For δ ≠ 0 the intersection is two hyperbola branches u·v = δ, which approach
//! each other as δ → 0; at δ = 0 they cross at a singular point. The paper reports the steps its
//! validated tracer needed (845, 989, 1139, singular, 1303, 1153, 1007 for δ = 0.03 … −0.03);
//! ours are printed next to them. Checked: every box meets the hyperbola (δ ∈ [σ]·[t] and
//! δ ∈ [z]), the steps grow as |δ| shrinks, and δ = 0 is reported as singular with a box that
//! holds the crossing.

mod common;

use common::surfaces::{height_field, SQUARE};
use ssitrace::certify::{certify_branch, CertifiedEnd, CertifyOptions};

#[test]
fn saddle_against_planes_steps_grow_near_the_singularity() {
    let p = height_field(SQUARE, vec![(1, 1, 1.0)]);
    let paper = ["845", "989", "1139", "singular", "1303", "1153", "1007"];
    let deltas = [0.03, 3e-4, 3e-6, 0.0, -3e-6, -3e-4, -0.03];
    let mut steps = Vec::new();
    println!(
        "{:>10} {:>10} {:>14} {:>12}",
        "delta", "paper", "ours (steps)", "tolerance"
    );
    for (delta, paper_steps) in deltas.iter().zip(paper) {
        let q = height_field(SQUARE, vec![(0, 0, *delta)]);
        let (u, v) = (0.9, delta / 0.9);
        let c =
            certify_branch(&p, &q, [u, v, u, v], &CertifyOptions::default()).expect("certified");
        for b in &c.boxes {
            let uv = b.p[0] * b.p[1];
            assert!(
                uv.contains(*delta) && b.xyz[2].contains(*delta),
                "a box misses u·v = {delta}"
            );
        }
        let singular = c.ends.iter().find_map(|e| match e {
            CertifiedEnd::Singular { near } => Some(*near),
            _ => None,
        });
        if *delta == 0.0 {
            let near = singular.expect("the crossing is reported");
            assert!(
                near.iter().all(|x| x.contains(0.0)),
                "the reported box holds the origin"
            );
        } else {
            assert!(singular.is_none());
            assert!(
                c.ends
                    .iter()
                    .all(|e| matches!(e, CertifiedEnd::Boundary { .. })),
                "{:?}",
                c.ends
            );
        }
        let ours = if *delta == 0.0 {
            format!("{} + singular", c.steps())
        } else {
            c.steps().to_string()
        };
        println!(
            "{delta:>10.0e} {paper_steps:>10} {ours:>14} {:>12.1e}",
            c.certified_tolerance
        );
        steps.push(c.steps());
    }
    // More steps as the branches come closer, on both sides.
    assert!(steps[0] < steps[1] && steps[1] < steps[2]);
    assert!(steps[6] < steps[5] && steps[5] < steps[4]);
}

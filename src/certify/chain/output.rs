//! What a cover chain reports: its links as boxes and tube pieces, in order along the curve.

use super::slice::tight_slice;
use super::*;
use crate::certify::curve::ToleranceLimit;
use walker::Link;

/// The certificate from the backward half's links (walked outwards from the start) and the
/// forward half's.
pub(super) fn assemble(
    p: &RationalBezierPatch,
    q: &RationalBezierPatch,
    bwd: &[Link],
    fwd: &[Link],
    ends: [CertifiedEnd; 2],
) -> Option<CertifiedBranch> {
    let first = fwd.first().or(bwd.first())?;
    let fixed = first.proof.pred.along;
    let start = tight_slice(p, q, &first.proof, first.from);
    let start_uniqueness = first.proof.tube_over(first.from, first.from);
    let (mut boxes, mut tubes) = (Vec::new(), Vec::new());
    // Backward half: outwards from the start at negative nominal arc lengths, then reversed.
    let (bb, bt) = half_output(p, bwd, -1.0);
    boxes.extend(bb.into_iter().rev());
    tubes.extend(bt.into_iter().rev());
    let (fb, ft) = half_output(p, fwd, 1.0);
    boxes.extend(fb);
    tubes.extend(ft);
    let all = bwd.iter().chain(fwd);
    let certified_tolerance = all.clone().map(|l| l.radius_xyz).fold(0.0, f64::max);
    // The widest link kept above the aim, with why.
    let tolerance_limit = all
        .clone()
        .filter_map(|l| l.limit.as_ref().map(|r| (l, r)))
        .max_by(|a, b| a.0.radius_xyz.total_cmp(&b.0.radius_xyz))
        .map(|(l, reason)| ToleranceLimit {
            reason: reason.describe(l.radius_xyz),
            near: l
                .proof
                .box_over(l.cover_from.min(l.to), l.cover_from.max(l.to)),
            width: l.radius_xyz,
        });
    let widths = all
        .map(|l| l.proof.k.iter().map(|k| k.wid()).fold(0.0, f64::max))
        .collect();
    Some(CertifiedBranch {
        start,
        fixed,
        start_uniqueness,
        boxes,
        tubes,
        certified_tolerance,
        ends,
        widths,
        tolerance_limit,
    })
}

/// Boxes and tube pieces of one half, in walking order, with nominal arc lengths `sign·s`.
fn half_output(
    p: &RationalBezierPatch,
    links: &[Link],
    sign: f64,
) -> (Vec<EnclosureBox>, Vec<TubePiece>) {
    let (mut boxes, mut tubes) = (Vec::new(), Vec::new());
    let mut s = 0.0;
    for l in links {
        let pred = &l.proof.pred;
        let j = pred.along;
        let dir = (l.to - l.from).signum();
        let model = |xj: f64| {
            let y = pred.eval(xj - pred.x0);
            p.point_f64(y[0], y[1])
        };
        // One box from cover_from to to: its parameters from the segment's enclosure, its
        // model-space box from the proof's (the curve over the whole segment, a superset).
        let s_link = s;
        let ds = dist3(&model(l.cover_from), &model(l.to));
        let y = l
            .proof
            .box_over(l.cover_from.min(l.to), l.cover_from.max(l.to));
        let range = [s, s + ds];
        s += ds;
        boxes.push(EnclosureBox {
            s: if sign > 0.0 {
                range
            } else {
                [-range[1], -range[0]]
            },
            p: [y[0], y[1]],
            q: [y[2], y[3]],
            xyz: l.proof.model,
        });
        let mut coeffs = vec![[0.0; 4]; PREDICTOR_DEGREE + 1];
        coeffs[0][j] = l.from;
        coeffs[1][j] = dir;
        for (r, &i) in others(j).iter().enumerate() {
            for (k, c) in coeffs.iter_mut().enumerate() {
                c[i] = pred.c[k][r] * dir.powi(k as i32);
            }
        }
        tubes.push(TubePiece {
            s0: sign * s_link,
            direction: sign,
            h: (l.to - l.from).abs(),
            coeffs,
            radius_param: l.radius_param,
            radius_xyz: l.radius_xyz,
            s0_error: 0.0,
            along: Some(AlongParameter {
                index: j,
                arc_length: s - s_link,
            }),
        });
    }
    (boxes, tubes)
}

fn dist3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

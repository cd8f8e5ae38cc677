//! The intersection ODE: the curve P(σ,t) = Q(u,v) parametrised by model-space arc length.
//!
//! For transversal intersections (N^P × N^Q ≠ 0), with c the unit tangent
//! c = (N^P × N^Q)/|N^P × N^Q|, the parameter velocities are
//!
//! ```text
//! σ' = det(c, P_t, N^P)/|N^P|²    t' = det(P_σ, c, N^P)/|N^P|²
//! u' = det(c, Q_v, N^Q)/|N^Q|²    v' = det(Q_u, c, N^Q)/|N^Q|²
//! ```
//!
//! which follow from c = P_σ σ' + P_t t' = Q_u u' + Q_v v'. The field is written once over
//! [`Scalar`], so it runs in `f64`, in intervals and in Taylor series. Along it P − Q is constant
//! (a first integral): a solution that starts on the intersection stays on it.
//!
//! **Evaluated form.** With m = N^P × N^Q, the Lagrange identity
//! `(a×b)·(c×d) = (a·c)(b·d) − (a·d)(b·c)` and `N^P·P_σ = N^P·P_t = 0` turn the determinants into
//!
//! ```text
//! σ' = −(N^Q·P_t)/|m|    t' = (N^Q·P_σ)/|m|    u' = (N^P·Q_v)/|m|    v' = −(N^P·Q_u)/|m|
//! ```
//!
//! (e.g. `det(c, P_t, N^P)·|m| = (N^P × N^Q)·(P_t × N^P) = −|N^P|²(N^Q·P_t)`). This form has no
//! division by `|N^P|²`, `|N^Q|²` and none of the identically vanishing products `N^P·P_t` that
//! interval and Taylor arithmetic cannot cancel, so its interval Taylor coefficients are far
//! tighter. The partials may moreover be scaled by any positive factor per surface
//! ([`ScalarSurface::scaled_first_order`]): with `S_u = a/g`, `S_v = b/g`, `g > 0`, and
//! `ñ = a × b`, `m̃ = ñ^P × ñ^Q`,
//!
//! ```text
//! σ' = −g_P (ñ^Q·b_P)/|m̃|   t' = g_P (ñ^Q·a_P)/|m̃|   u' = g_Q (ñ^P·b_Q)/|m̃|   v' = −g_Q (ñ^P·a_Q)/|m̃|
//! ```
//!
//! which lets a rational patch skip its quotient rule (`g = w²`).

use crate::numeric::vec3::{cross, dot, norm_sqr};
use crate::Scalar;

/// A surface whose point and partial derivatives can be evaluated in any [`Scalar`].
pub trait ScalarSurface {
    /// `[S(u,v), ∂S/∂u, ∂S/∂v]` evaluated in the scalar type `T` (rigorous when `T` is).
    fn first_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 3];
    /// `[S, S_u, S_v, S_uu, S_uv, S_vv]` evaluated in `T` (rigorous when `T` is).
    fn second_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 6];
    /// `(a, b, g)` with `S_u = a/g`, `S_v = b/g` and `g > 0` on the domain (rigorous when `T`
    /// is). The default is `(S_u, S_v, 1)`; a rational surface can return its homogeneous
    /// numerators and save the quotient rule.
    fn scaled_first_order<T: Scalar>(&self, u: T, v: T) -> ([T; 3], [T; 3], T) {
        let [_, a, b] = self.first_order(u, v);
        (a, b, T::one())
    }
    /// The same quantities as [`scaled_first_order`](Self::scaled_first_order), possibly written
    /// around the centre `(cu, cv)` for tighter interval and Taylor enclosures (the default
    /// ignores the centre).
    fn scaled_first_order_centred<T: Scalar>(
        &self,
        u: T,
        v: T,
        cu: T,
        cv: T,
    ) -> ([T; 3], [T; 3], T) {
        let _ = (cu, cv);
        self.scaled_first_order(u, v)
    }
}

impl ScalarSurface for crate::geometry::RationalBezierPatch {
    fn first_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 3] {
        self.first_derivs(u, v)
    }
    fn second_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 6] {
        let d = self.eval_derivs(u, v);
        [d.p, d.su, d.sv, d.suu, d.suv, d.svv]
    }
    fn scaled_first_order<T: Scalar>(&self, u: T, v: T) -> ([T; 3], [T; 3], T) {
        self.scaled_partials(u, v)
    }
    fn scaled_first_order_centred<T: Scalar>(
        &self,
        u: T,
        v: T,
        cu: T,
        cv: T,
    ) -> ([T; 3], [T; 3], T) {
        self.scaled_partials_centred(u, v, cu, cv)
    }
}

/// The transversal parameter velocity times `|m|`, `m = N^P × N^Q` (the evaluated form of the
/// module documentation):
///
/// ```text
/// (σ', t', u', v')·|m| = (−N^Q·P_t, N^Q·P_σ, N^P·Q_v, −N^P·Q_u)
/// ```
///
/// from the partials `ps = P_σ`, `pt = P_t`, `qu = Q_u`, `qv = Q_v` and the normals
/// `np = P_σ × P_t`, `nq = Q_u × Q_v`. The one formula for the curve's parameter velocity: the
/// field, the boundary classification and the marcher's frames all scale it. Partials scaled by
/// a positive factor per surface (with their normals) scale the entries accordingly.
pub fn velocity_numerators<T: Scalar>(
    ps: &[T; 3],
    pt: &[T; 3],
    qu: &[T; 3],
    qv: &[T; 3],
    np: &[T; 3],
    nq: &[T; 3],
) -> [T; 4] {
    [-dot(nq, pt), dot(nq, ps), dot(np, qv), -dot(np, qu)]
}

/// Quantities of the transversal field at one point, for callers that need more than y'.
#[derive(Debug, Clone, Copy)]
pub struct FieldPoint<T> {
    /// `(σ', t', u', v')`.
    pub velocity: [T; 4],
    /// The unit model-space tangent c.
    pub tangent: [T; 3],
    /// `|N^P × N^Q|²` (zero at tangential / singular points).
    pub cross_norm_sqr: T,
}

/// The transversal intersection field at `y = (σ, t, u, v)`, with direction `orientation` = ±1
/// (the sign applied to c). All four outputs are enclosures when `T` is rigorous.
pub fn transversal_field<T, P, Q>(p: &P, q: &Q, y: &[T; 4], orientation: f64) -> FieldPoint<T>
where
    T: Scalar,
    P: ScalarSurface + ?Sized,
    Q: ScalarSurface + ?Sized,
{
    let f = ScaledField::new(p, q, y, orientation);
    let inv_len = T::one() / f.m2.sqrt();
    let sign = T::from_f64(orientation);
    let gg = (f.gp * f.gq).sqr();
    FieldPoint {
        velocity: f.velocity(),
        tangent: f.m.map(|x| sign * x * inv_len),
        cross_norm_sqr: f.m2 / gg.sqr(),
    }
}

/// Only the velocity `(σ', t', u', v')` of [`transversal_field`] (what the ODE integrates).
pub fn transversal_velocity<T, P, Q>(p: &P, q: &Q, y: &[T; 4], orientation: f64) -> [T; 4]
where
    T: Scalar,
    P: ScalarSurface + ?Sized,
    Q: ScalarSurface + ?Sized,
{
    ScaledField::new(p, q, y, orientation).velocity()
}

/// [`transversal_velocity`] with both surfaces written around the centre `c` (same function; the
/// centre only changes interval widths, see [`ScalarSurface::scaled_first_order_centred`]).
pub fn transversal_velocity_centred<T, P, Q>(
    p: &P,
    q: &Q,
    y: &[T; 4],
    c: &[T; 4],
    orientation: f64,
) -> [T; 4]
where
    T: Scalar,
    P: ScalarSurface + ?Sized,
    Q: ScalarSurface + ?Sized,
{
    let pp = p.scaled_first_order_centred(y[0], y[1], c[0], c[1]);
    let qq = q.scaled_first_order_centred(y[2], y[3], c[2], c[3]);
    ScaledField::from_parts(pp, qq, orientation).velocity()
}

/// The scaled quantities of the evaluated form (see the module documentation).
struct ScaledField<T> {
    ap: [T; 3],
    bp: [T; 3],
    gp: T,
    aq: [T; 3],
    bq: [T; 3],
    gq: T,
    np: [T; 3],
    nq: [T; 3],
    m: [T; 3],
    m2: T,
    orientation: f64,
}

impl<T: Scalar> ScaledField<T> {
    fn new<P, Q>(p: &P, q: &Q, y: &[T; 4], orientation: f64) -> Self
    where
        P: ScalarSurface + ?Sized,
        Q: ScalarSurface + ?Sized,
    {
        let pp = p.scaled_first_order(y[0], y[1]);
        let qq = q.scaled_first_order(y[2], y[3]);
        Self::from_parts(pp, qq, orientation)
    }

    fn from_parts(
        (ap, bp, gp): ([T; 3], [T; 3], T),
        (aq, bq, gq): ([T; 3], [T; 3], T),
        orientation: f64,
    ) -> Self {
        let np = cross(&ap, &bp);
        let nq = cross(&aq, &bq);
        let m = cross(&np, &nq);
        let m2 = norm_sqr(&m);
        ScaledField {
            ap,
            bp,
            gp,
            aq,
            bq,
            gq,
            np,
            nq,
            m,
            m2,
            orientation,
        }
    }

    fn velocity(&self) -> [T; 4] {
        let scale = T::from_f64(self.orientation) / self.m2.sqrt();
        let sp = self.gp * scale;
        let sq = self.gq * scale;
        let [s, t, u, v] =
            velocity_numerators(&self.ap, &self.bp, &self.aq, &self.bq, &self.np, &self.nq);
        [s * sp, t * sp, u * sq, v * sq]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numeric::scalar::point;
    use crate::pair::fixtures::Bowl;
    use inari::Interval;

    fn rk4(p: &Bowl, q: &Bowl, y: [f64; 4], h: f64) -> [f64; 4] {
        let f = |y: &[f64; 4]| transversal_field(p, q, y, 1.0).velocity;
        let add = |y: &[f64; 4], k: &[f64; 4], s: f64| std::array::from_fn(|i| y[i] + s * k[i]);
        let k1 = f(&y);
        let k2 = f(&add(&y, &k1, h / 2.0));
        let k3 = f(&add(&y, &k2, h / 2.0));
        let k4 = f(&add(&y, &k3, h));
        std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
    }

    #[test]
    fn circle_is_traced_at_unit_speed_and_closes_after_its_length() {
        // Paraboloid z = u² + v² − 0.25 against the plane z = 0: circle of radius 0.5.
        let p = Bowl::new(1.0, -0.25);
        let q = Bowl::new(0.0, 0.0);
        let mut y = [0.5, 0.0, 0.5, 0.0];
        let n = 2000;
        let h = std::f64::consts::PI / n as f64; // 2πr / n with r = 0.5
        for _ in 0..n {
            let f = transversal_field(&p, &q, &y, 1.0);
            // unit speed in model space: |c| = 1 and |P_σ σ' + P_t t'| = 1 on the plane of P
            let speed = (f.velocity[0].powi(2) + f.velocity[1].powi(2)).sqrt();
            assert!(speed <= 1.0 + 1e-12);
            y = rk4(&p, &q, y, h);
            assert!((y[0].hypot(y[1]) - 0.5).abs() < 1e-9);
            assert!((y[0] - y[2]).abs() < 1e-9 && (y[1] - y[3]).abs() < 1e-9);
        }
        assert!((y[0] - 0.5).abs() < 1e-9 && y[1].abs() < 1e-9, "{y:?}");
    }

    #[test]
    fn interval_field_encloses_f64_field() {
        let p = Bowl::new(1.0, -0.25);
        let q = Bowl::new(-0.5, 0.1);
        for k in 0..50 {
            let s = -0.7 + 0.03 * k as f64;
            let y = [s, 0.3, 0.2, s * 0.5];
            let f = transversal_field(&p, &q, &y, -1.0).velocity;
            let yi: [Interval; 4] = y.map(point);
            let fi = transversal_field(&p, &q, &yi, -1.0).velocity;
            for i in 0..4 {
                assert!(
                    fi[i].contains(f[i]),
                    "{i}: {} not in [{}, {}]",
                    f[i],
                    fi[i].inf(),
                    fi[i].sup()
                );
            }
        }
    }
}

//! Small closed-form surfaces shared by the unit tests of this module.

use crate::pair::field::ScalarSurface;
use crate::Scalar;

/// The graph z = a·(u² + v²) + b·u·v + d (exact in every scalar type).
pub(crate) struct Bowl {
    pub a: f64,
    pub b: f64,
    pub d: f64,
}

impl Bowl {
    pub(crate) fn new(a: f64, d: f64) -> Self {
        Bowl { a, b: 0.0, d }
    }
}

impl ScalarSurface for Bowl {
    fn first_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 3] {
        let [p, su, sv, ..] = self.second_order(u, v);
        [p, su, sv]
    }
    fn second_order<T: Scalar>(&self, u: T, v: T) -> [[T; 3]; 6] {
        let (o, z) = (T::one(), T::zero());
        let (a, b) = (T::from_f64(self.a), T::from_f64(self.b));
        let two_a = T::from_f64(2.0 * self.a);
        [
            [
                u,
                v,
                a * (u.sqr() + v.sqr()) + b * u * v + T::from_f64(self.d),
            ],
            [o, z, two_a * u + b * v],
            [z, o, two_a * v + b * u],
            [z, z, two_a],
            [z, z, b],
            [z, z, two_a],
        ]
    }
}

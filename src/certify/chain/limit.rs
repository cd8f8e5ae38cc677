//! Why a link of a chain was kept although wider than the chain's aim.

/// Why a link was kept although wider than the chain's aim (`Walker::limit_at`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum LinkLimit {
    /// The tube is at the rounding level of the coordinates.
    Rounding,
    /// The crossing is ill-conditioned there, usually nearly tangent surfaces (`sine` of the
    /// angle between the normals), and no singular point is near: the residual's rounding over
    /// that sine sets the width.
    Conditioning {
        /// The sine at the link's start (an estimate).
        sine: f64,
    },
    /// The link passes close to a pole of a surface (a side its patch maps to one point, where
    /// the parameters degenerate): the residual's rounding over the speed of the parameter
    /// along the pole's side sets the width.
    Pole {
        /// Which surface (0 for P, 1 for Q).
        surface: usize,
        /// The model distance from the link's start to the pole (an estimate).
        distance: f64,
    },
}

impl LinkLimit {
    /// The reason reported for a link of model width `width`.
    pub(super) fn describe(&self, width: f64) -> String {
        match self {
            LinkLimit::Rounding => {
                format!("the tube ({width:.1e}) is at the rounding level of the coordinates")
            }
            LinkLimit::Conditioning { sine } => format!(
                "{} (sine of the angle between the normals {sine:.1e}, no singular point \
                 near): shorter links did not narrow the tube below {width:.1e}, the rounding \
                 of the residual over that sine",
                if *sine < 1e-2 {
                    "nearly tangent surfaces"
                } else {
                    "an ill-conditioned crossing"
                }
            ),
            LinkLimit::Pole { surface, distance } => format!(
                "a link starting {distance:.1e} from a pole of {} (a side its patch maps to one \
                 point, where the parameters degenerate): shorter links did not narrow the \
                 tube below {width:.1e}, the rounding of the residual over the parameters' \
                 speed there",
                ["P", "Q"][*surface]
            ),
        }
    }
}

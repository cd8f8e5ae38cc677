//! The baseline predictor: a straight step along the tangent.

use crate::geometry::Vec3;
use crate::march::StepPrediction;

/// `current + length · tangent` (tangent unit); the predicted tangent is the current one.
pub fn tangent_step(current: &Vec3, tangent: &Vec3, length: f64) -> StepPrediction {
    StepPrediction {
        point: current + tangent * length,
        tangent: *tangent,
        arc: length,
    }
}

//! Moving the stitch: the tissue (and with it the wound, the stitch and the task's start condition,
//! which the scene places in the tissue frame) shifted, turned about its normal and tilted about the
//! wound.

use knotlab_sim::scene::SceneConfig;
use nalgebra::Vector3;

/// A displacement of the stitch site.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StitchMove {
    /// Shift of the tissue centre, world frame, m.
    pub offset_m: Vector3<f64>,
    /// Turn about the tissue's normal, rad.
    pub rotate_rad: f64,
    /// Tilt about the wound, rad (added to the scene's `tissue.tilt_rad`).
    pub tilt_rad: f64,
}

impl StitchMove {
    /// Applies the move to a scene.
    pub fn apply(&self, scene: &mut SceneConfig) {
        for (c, d) in scene.tissue.centre_m.iter_mut().zip(self.offset_m.iter()) {
            *c += d;
        }
        scene.tissue.yaw_rad += self.rotate_rad;
        scene.tissue.tilt_rad += self.tilt_rad;
    }

    /// How far the stitch moved, m.
    pub fn distance_m(&self) -> f64 {
        self.offset_m.norm()
    }
}

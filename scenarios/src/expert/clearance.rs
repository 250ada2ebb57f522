//! The right's winding kept clear of the left's wrist. The left's jaws point at the right's trocar,
//! so its wrist bends them far off its shaft, and the wrist link and shaft lean out from the jaws'
//! base towards the left's trocar. A circle about the jaws close to their base passes through them:
//! wound 6 mm behind the jaw centre (the second throw of `two-throws-cinched.toml`), the thread held
//! in the right's jaws was driven 2.1 mm into the left's wrist, 58-250 N on the left's gauge for
//! seconds at a time. The plan moves such a circle along the jaws, towards their tips,
//! until that thread keeps clear of the wrist: there 2.5 mm, and the gauge reads under 0.3 N through
//! the winding (seeds 0 and 2). The first throw's circle, 3 mm behind, keeps 0.8 mm clear
//! (seed 0) and is not moved.

use knotlab_hw::geometry::segment_distance;
use nalgebra::{Rotation3, UnitVector3, Vector3};

/// How far the circle is moved along the jaws at a time, m.
const STEP_M: f64 = 0.0005;

/// Points on each turn at which the clearance is measured.
const POINTS_PER_TURN: usize = 72;

/// A winding circle: the right's jaw centre goes round `axis` through `centre_m` from `start_m`,
/// `turns` times, advancing `pitch_m` along the axis per turn (as [`super::motion::Path::Around`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circle {
    /// A point on the axis, m.
    pub centre_m: Vector3<f64>,
    /// The axis (its sense is the turns').
    pub axis: UnitVector3<f64>,
    /// Where the right's jaw centre starts, m.
    pub start_m: Vector3<f64>,
    /// How many turns.
    pub turns: f64,
    /// Advance along the axis per turn, m.
    pub pitch_m: f64,
}

impl Circle {
    /// The right's jaw centre `s` of the way round (0 to 1).
    fn at(&self, s: f64) -> Vector3<f64> {
        let rotation = Rotation3::from_axis_angle(&self.axis, std::f64::consts::TAU * self.turns * s);
        self.centre_m
            + rotation * (self.start_m - self.centre_m)
            + self.axis.into_inner() * self.pitch_m * self.turns * s
    }

    /// The same circle moved by `offset_m`.
    fn moved(&self, offset_m: Vector3<f64>) -> Self {
        Self { centre_m: self.centre_m + offset_m, start_m: self.start_m + offset_m, ..*self }
    }
}

/// The left's wrist as the thread in the right's jaws must keep clear of it: its wrist link (from
/// the pitch axis to the yaw axis) and its shaft (from the pitch axis to the trocar), capsules of
/// `radius_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wrist {
    /// Where the shaft ends (the wrist's pitch axis), m.
    pub pitch_m: Vector3<f64>,
    /// Where the jaws hinge (the yaw axis), m.
    pub yaw_m: Vector3<f64>,
    /// The trocar the shaft passes through, m.
    pub trocar_m: Vector3<f64>,
    /// The wrist's and shaft's radius, m.
    pub radius_m: f64,
}

impl Wrist {
    /// Distance from the wrist's and shaft's axes, m.
    fn distance_m(&self, point_m: &Vector3<f64>) -> f64 {
        let wrist = segment_distance(point_m, point_m, &self.pitch_m, &self.yaw_m);
        wrist.min(segment_distance(point_m, point_m, &self.pitch_m, &self.trocar_m))
    }
}

/// The least gap between the thread the right holds (at its jaw centre, `thread_radius_m` round)
/// going round `circle` and the left's wrist, m (negative: it is driven into the wrist). The
/// instruments do not touch each other in the simulator; the thread in the right's jaws does, held
/// where it is by the grasp.
pub fn clearance_m(circle: &Circle, wrist: &Wrist, thread_radius_m: f64) -> f64 {
    let points = (POINTS_PER_TURN as f64 * circle.turns.abs()).ceil().max(1.0) as usize;
    let least = (0..=points)
        .map(|i| wrist.distance_m(&circle.at(i as f64 / points as f64)))
        .fold(f64::INFINITY, f64::min);
    least - wrist.radius_m - thread_radius_m
}

/// `circle`, moved along the left's jaws (`towards_tips`) in small steps until the thread the right
/// holds keeps clear of the wrist, but no further than `max_m`; with how far it was moved, m.
pub fn clear_of_wrist(
    circle: &Circle,
    wrist: &Wrist,
    thread_radius_m: f64,
    towards_tips: &UnitVector3<f64>,
    max_m: f64,
) -> (Circle, f64) {
    let mut moved_m = 0.0;
    while clearance_m(&circle.moved(towards_tips.into_inner() * moved_m), wrist, thread_radius_m) < 0.0
        && moved_m + STEP_M <= max_m + 1e-12
    {
        moved_m += STEP_M;
    }
    (circle.moved(towards_tips.into_inner() * moved_m), moved_m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wrist leaning out from the jaws' base (along +x) at 70 degrees, its shaft to a trocar above.
    fn wrist() -> Wrist {
        let yaw_m = Vector3::new(-0.005, 0.0, 0.0);
        let lean = Vector3::new(-(70f64.to_radians().cos()), 0.0, 70f64.to_radians().sin());
        let pitch_m = yaw_m + lean * 0.0091;
        Wrist { pitch_m, yaw_m, trocar_m: pitch_m + lean * 0.2, radius_m: 0.004 }
    }

    fn circle(behind_m: f64) -> Circle {
        let centre_m = Vector3::new(-behind_m, 0.0, 0.0);
        // Starting on the wrist's side, as the second throw's one turn did.
        Circle {
            centre_m,
            axis: Vector3::x_axis(),
            start_m: centre_m + Vector3::z() * 0.011,
            turns: 1.0,
            pitch_m: 0.0,
        }
    }

    const THREAD_RADIUS_M: f64 = 0.0004;

    /// The clearance check finds a circle round the jaws' base driving the thread into the leaning wrist, and
    /// one round the jaws' front half clear of it.
    #[test]
    fn a_circle_round_the_jaws_base_passes_through_the_leaning_wrist() {
        assert!(clearance_m(&circle(0.006), &wrist(), THREAD_RADIUS_M) < 0.0);
        // Round the jaws' front half, the right's jaws pass the wrist clear.
        assert!(clearance_m(&circle(-0.004), &wrist(), THREAD_RADIUS_M) > 0.0);
    }

    /// A winding circle moves towards the jaws' tips just far enough to clear the wrist, not at all when
    /// already clear, and never past the limit.
    #[test]
    fn the_circle_moves_towards_the_tips_until_clear_and_no_further() {
        let (moved, by_m) =
            clear_of_wrist(&circle(0.006), &wrist(), THREAD_RADIUS_M, &Vector3::x_axis(), 0.012);
        assert!(by_m > 0.0 && by_m < 0.010, "{by_m}");
        assert!(clearance_m(&moved, &wrist(), THREAD_RADIUS_M) >= 0.0);
        let back = circle(0.006).moved(Vector3::x() * (by_m - STEP_M));
        assert!(clearance_m(&back, &wrist(), THREAD_RADIUS_M) < 0.0, "one step less would touch");
        // Clear already: not moved.
        let (_, none_m) =
            clear_of_wrist(&circle(-0.004), &wrist(), THREAD_RADIUS_M, &Vector3::x_axis(), 0.006);
        assert_eq!(none_m, 0.0);
        // Not moved past the limit.
        let (_, capped_m) =
            clear_of_wrist(&circle(0.006), &wrist(), THREAD_RADIUS_M, &Vector3::x_axis(), 0.001);
        assert!(capped_m <= 0.001 + 1e-12);
    }
}

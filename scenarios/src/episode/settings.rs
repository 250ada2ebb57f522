//! What an episode's steps may do: the control rate, the time limit and the bounds of a command.

/// An episode's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EpisodeSettings {
    /// Steps per second. Each step is a whole number of the scene's control cycles (1 kHz in the
    /// shipped scene), so the rate divides the cycle rate.
    pub control_hz: f64,
    /// The episode is cut off here, s of simulated time (then the knot is judged as it lies).
    pub time_limit_s: f64,
    /// The fastest a tip may be commanded to move along each world axis, m/s.
    pub max_speed_mps: f64,
    /// The fastest a tip may be commanded to turn about each world axis, rad/s.
    pub max_turn_rad_s: f64,
    /// The widest a jaw may be commanded to open, rad.
    pub max_jaw_rad: f64,
    /// The thread's centreline in an observation: this many points, evenly spaced along it.
    pub thread_points: usize,
}

impl Default for EpisodeSettings {
    /// 20 steps a second, 60 s, 15 cm/s and 4 rad/s along and about each axis, jaws up to 0.8 rad,
    /// 32 points of thread.
    ///
    /// 20 Hz: between steps the target moves in a straight line, and the task's finest motions are
    /// resolved at that rate: a jaw closing takes 0.3 s (6 steps) and the winding, the fastest curve,
    /// turns 1 cm circles in about 2 s, whose 50 ms chords lie within 0.03 mm of the arc; the
    /// controller runs its inverse kinematics and limits at every 1 ms cycle in between. Over 50 ms
    /// the shipped demonstration's tips move at most 0.11 m/s and turn at most 2.9 rad/s (the left
    /// turning its jaws towards the tail), within the bounds along any axis.
    fn default() -> Self {
        Self {
            control_hz: 20.0,
            time_limit_s: 60.0,
            max_speed_mps: 0.15,
            max_turn_rad_s: 4.0,
            max_jaw_rad: 0.8,
            thread_points: 32,
        }
    }
}

impl EpisodeSettings {
    /// Each field that is out of range, with why.
    pub fn problems(&self, cycle_hz: f64) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        let cycles = cycle_hz / self.control_hz;
        if !(self.control_hz.is_finite() && self.control_hz > 0.0)
            || (cycles - cycles.round()).abs() > 1e-9 * cycles
            || cycles.round() < 1.0
        {
            out.push((
                "control_hz",
                format!(
                    "{}: must divide the control cycle's rate, {cycle_hz} Hz (20, 50, 100 ...)",
                    self.control_hz
                ),
            ));
        }
        let positive = [
            ("time_limit_s", self.time_limit_s),
            ("max_speed_mps", self.max_speed_mps),
            ("max_turn_rad_s", self.max_turn_rad_s),
            ("max_jaw_rad", self.max_jaw_rad),
        ];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                out.push((name, format!("{value}: must be a positive number")));
            }
        }
        if self.time_limit_s > 3600.0 {
            out.push(("time_limit_s", format!("{}: at most 3600 s", self.time_limit_s)));
        }
        if !(2..=4096).contains(&self.thread_points) {
            out.push(("thread_points", format!("{}: 2 to 4096", self.thread_points)));
        }
        out
    }
}

//! A joint servo: how a link follows its command. The command is offset by a calibration error, the
//! motor approaches it with a first-order lag under velocity and acceleration limits, and the link
//! follows the motor through a backlash dead band ("play"), inside the joint's position limits.
//! The paper blames its failures on play and calibration: these are the knobs Monte Carlo turns.

use knotlab_hw::kinematics::JointLimit;

/// How one joint follows commands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ServoModel {
    /// Position and speed limits.
    pub limit: JointLimit,
    /// First-order lag time constant, s (0: as fast as the limits allow).
    pub time_constant_s: f64,
    /// Largest acceleration, rad/s^2.
    pub max_acceleration_rad_s2: f64,
    /// Width of the backlash dead band, rad.
    pub play_rad: f64,
    /// The link settles at command + offset, rad.
    pub calibration_offset_rad: f64,
}

/// The moving state of one servo.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ServoState {
    /// Motor side position, rad.
    pub motor_rad: f64,
    /// Motor speed, rad/s.
    pub motor_velocity_rad_s: f64,
    /// Link side position, rad: what the kinematics sees.
    pub link_rad: f64,
}

impl ServoState {
    /// At rest with motor and link at `q_rad`.
    pub fn at(q_rad: f64) -> Self {
        Self { motor_rad: q_rad, motor_velocity_rad_s: 0.0, link_rad: q_rad }
    }
}

impl ServoModel {
    /// Advances `state` by `dt_s` towards `command_rad`; returns the link position.
    pub fn step(&self, state: &mut ServoState, command_rad: f64, dt_s: f64) -> f64 {
        let target =
            (command_rad + self.calibration_offset_rad).clamp(self.limit.lower_rad, self.limit.upper_rad);
        let error = target - state.motor_rad;
        let v_max = self.limit.max_velocity_rad_s;
        // First-order lag: the speed that closes the error with the time constant; never faster than
        // reaching the target within this step (no overshoot), nor than the speed limit.
        let wanted = if self.time_constant_s > dt_s { error / self.time_constant_s } else { error / dt_s };
        let mut wanted = wanted.clamp(-v_max, v_max);
        // No faster than what can still stop at the target under the acceleration limit.
        let brake = (2.0 * self.max_acceleration_rad_s2 * error.abs()).sqrt();
        if wanted.abs() > brake {
            wanted = brake.copysign(error);
        }
        let dv = self.max_acceleration_rad_s2 * dt_s;
        let v = state.motor_velocity_rad_s;
        let mut next_v = wanted.clamp(v - dv, v + dv);
        let mut next_motor = state.motor_rad + next_v * dt_s;
        // Never step past the target.
        if (target - next_motor).signum() != error.signum() && error != 0.0 {
            next_motor = target;
            next_v = 0.0;
        }
        state.motor_rad = next_motor;
        state.motor_velocity_rad_s = next_v;
        // Backlash: the link moves only when the motor pushes it from one side of the dead band.
        let half = 0.5 * self.play_rad;
        if state.motor_rad - state.link_rad > half {
            state.link_rad = state.motor_rad - half;
        } else if state.link_rad - state.motor_rad > half {
            state.link_rad = state.motor_rad + half;
        }
        state.link_rad = state.link_rad.clamp(self.limit.lower_rad, self.limit.upper_rad);
        state.link_rad
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn servo(play_rad: f64, calibration_offset_rad: f64) -> ServoModel {
        ServoModel {
            limit: JointLimit::new(-3.0, 3.0, 2.0),
            time_constant_s: 0.02,
            max_acceleration_rad_s2: 20.0,
            play_rad,
            calibration_offset_rad,
        }
    }

    /// A step command is reached exactly, the motor never exceeding its speed or acceleration limit.
    #[test]
    fn a_step_command_is_reached_within_limits() {
        let s = servo(0.0, 0.0);
        let mut state = ServoState::at(0.0);
        let dt = 1e-3;
        let mut last_v = 0.0;
        for _ in 0..2000 {
            s.step(&mut state, 1.0, dt);
            assert!(state.motor_velocity_rad_s.abs() <= 2.0 + 1e-12, "speed {}", state.motor_velocity_rad_s);
            let accel = (state.motor_velocity_rad_s - last_v) / dt;
            // Braking may exceed nothing: decelerations come from the same limit or from stopping at
            // the target in one step.
            assert!(accel.abs() <= 20.0 + 1e-6 || state.motor_velocity_rad_s == 0.0, "accel {accel}");
            last_v = state.motor_velocity_rad_s;
        }
        assert!((state.link_rad - 1.0).abs() < 1e-9, "{state:?}");
    }

    /// With a calibration offset the link settles at the command plus the offset, not at the command.
    #[test]
    fn the_link_settles_at_command_plus_calibration_offset() {
        let s = servo(0.0, 0.05);
        let mut state = ServoState::at(0.0);
        for _ in 0..3000 {
            s.step(&mut state, 0.5, 1e-3);
        }
        assert!((state.link_rad - 0.55).abs() < 1e-9, "{state:?}");
    }

    /// Driven forward the link lags the motor by half the play; backed off by less than the play it stays
    /// still, and backed off further it follows, leading the motor by half the play.
    #[test]
    fn reversing_direction_crosses_the_play_before_the_link_moves() {
        let s = servo(0.02, 0.0);
        let mut state = ServoState::at(0.0);
        for _ in 0..3000 {
            s.step(&mut state, 0.5, 1e-3);
        }
        // Pushed forward: the link lags the motor by half the play.
        assert!((state.motor_rad - state.link_rad - 0.01).abs() < 1e-9, "{state:?}");
        let held = state.link_rad;
        // Back off by less than the play: the link does not move.
        for _ in 0..3000 {
            s.step(&mut state, 0.485, 1e-3);
        }
        assert!((state.link_rad - held).abs() < 1e-12, "{state:?}");
        // Back off further: it follows, now leading the motor by half the play.
        for _ in 0..3000 {
            s.step(&mut state, 0.3, 1e-3);
        }
        assert!((state.link_rad - state.motor_rad - 0.01).abs() < 1e-9, "{state:?}");
    }

    /// A command beyond the joint's position limit stops the link at the limit, not past it.
    #[test]
    fn commands_beyond_the_limits_stop_at_the_limit() {
        let s = servo(0.0, 0.0);
        let mut state = ServoState::at(2.9);
        for _ in 0..2000 {
            s.step(&mut state, 5.0, 1e-3);
        }
        assert!((state.link_rad - 3.0).abs() < 1e-12);
    }
}

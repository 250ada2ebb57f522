//! The arm a MELFA controller emulator moves: each command checked against the joint limits and the
//! over-speed limit (the real controller faults on both), then followed through the controller's
//! command filter, modelled as a first-order lag with the MXT instruction's filter time.

use nalgebra::IsometryMatrix3;

use crate::kinematics::{JointLimit, Rv6slGeometry};

/// Slack on the checks, rad: set-points travel as f32 (about 2e-7 rad of rounding at 3 rad).
const CHECK_SLACK_RAD: f64 = 1e-5;

/// Why the emulated controller stopped the robot.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ArmFault {
    /// A joint command outside the joint's range.
    #[error("J{joint} command {value_rad:.6} rad is outside its range {lower_rad:.6}..{upper_rad:.6} rad")]
    OutOfRange {
        /// Axis 1..=6.
        joint: u8,
        /// The command, rad.
        value_rad: f64,
        /// Lower limit, rad.
        lower_rad: f64,
        /// Upper limit, rad.
        upper_rad: f64,
    },
    /// A joint command further from the previous one than the axis may move in one cycle.
    #[error(
        "J{joint} over speed: the command steps {step_rad:.6} rad in one cycle, more than {max_step_rad:.6} rad"
    )]
    OverSpeed {
        /// Axis 1..=6.
        joint: u8,
        /// The step, rad.
        step_rad: f64,
        /// The largest step, rad.
        max_step_rad: f64,
    },
}

/// The emulated arm.
#[derive(Clone, Debug, PartialEq)]
pub struct EmulatedArm {
    limits: [JointLimit; 6],
    cycle_s: f64,
    /// Fraction of the remaining distance the filter covers per cycle.
    alpha: f64,
    command_rad: [f64; 6],
    filtered_rad: [f64; 6],
}

impl EmulatedArm {
    /// Standing at `joints_rad`, with a filter time constant `filter_s` (0: no filter).
    pub fn new(joints_rad: [f64; 6], limits: [JointLimit; 6], cycle_s: f64, filter_s: f64) -> Self {
        let alpha = if filter_s > 0.0 { 1.0 - (-cycle_s / filter_s).exp() } else { 1.0 };
        Self { limits, cycle_s, alpha, command_rad: joints_rad, filtered_rad: joints_rad }
    }

    /// Takes a joint command (checked against the range and over-speed limits).
    pub fn command(&mut self, joints_rad: [f64; 6]) -> Result<(), ArmFault> {
        for (i, (&q, limit)) in joints_rad.iter().zip(&self.limits).enumerate() {
            let joint = i as u8 + 1;
            if !(q >= limit.lower_rad - CHECK_SLACK_RAD && q <= limit.upper_rad + CHECK_SLACK_RAD) {
                return Err(ArmFault::OutOfRange {
                    joint,
                    value_rad: q,
                    lower_rad: limit.lower_rad,
                    upper_rad: limit.upper_rad,
                });
            }
            let step_rad = (q - self.command_rad[i]).abs();
            let max_step_rad = limit.max_velocity_rad_s * self.cycle_s;
            if step_rad > max_step_rad + CHECK_SLACK_RAD {
                return Err(ArmFault::OverSpeed { joint, step_rad, max_step_rad });
            }
        }
        self.command_rad = joints_rad;
        Ok(())
    }

    /// Runs the filter for `cycles` cycles towards the last command.
    pub fn advance(&mut self, cycles: u32) {
        for _ in 0..cycles {
            for (f, c) in self.filtered_rad.iter_mut().zip(&self.command_rad) {
                *f += self.alpha * (c - *f);
            }
        }
    }

    /// The last command (JOINT), rad.
    pub fn command_rad(&self) -> [f64; 6] {
        self.command_rad
    }

    /// The joints after the filter (FJOINT; also the encoder feedback, FB_JOINT: the servo is taken as
    /// ideal), rad.
    pub fn filtered_rad(&self) -> [f64; 6] {
        self.filtered_rad
    }

    /// The flange in the arm's base frame at the filtered joints (knotlab's RV-6SL model).
    pub fn base_from_flange(&self) -> IsometryMatrix3<f64> {
        Rv6slGeometry::RV6SL.base_from_flange(&self.filtered_rad)
    }
}

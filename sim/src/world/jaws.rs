//! The instruments' jaws on the suture: each arm's [`JawState`] stepped from its jaw command and
//! opening (take what the closing jaws squeeze or the closed jaws hold between them, let go when
//! told to open, slip when pulled harder than the grip).

use knotlab_hw::rig::{ArmName, Rig};
use nalgebra::IsometryMatrix3;

use super::SimWorld;
use super::arm::{JawState, SimArm};
use crate::grasp::GraspEvent;
use crate::suture::{HoldCheck, JawsNow, Suture};

impl SimWorld {
    /// Steps each instrument's jaw state from its command and opening (links at `poses`).
    pub(super) fn update_grasps(&mut self, poses: &[IsometryMatrix3<f64>]) {
        for a in 0..self.arms.len() {
            let name = self.arms[a].name;
            if !name.carries_instrument() {
                continue;
            }
            let actual_rad = self.arms[a].actual().tool.jaw_rad;
            let command_rad = self.arms[a].command.tool.jaw_rad;
            let closed = actual_rad < self.jaw_closed_rad;
            // Told to close, or closing now (the command ramps down ahead of the jaws).
            let closing = command_rad < actual_rad - 1e-3;
            // A hold lasts until the jaws are told to open past where they took it (at least to
            // the closed threshold).
            let let_go_rad = match &self.arms[a].jaws {
                JawState::Holding { at_jaw_rad, .. } => self.jaw_closed_rad.max(at_jaw_rad + 1e-3),
                _ => self.jaw_closed_rad,
            };
            if command_rad >= let_go_rad && !closing {
                if let JawState::Holding { hold, .. } =
                    std::mem::replace(&mut self.arms[a].jaws, JawState::Free)
                {
                    self.suture.release(a, hold, &mut self.physics, true);
                    self.events.push(GraspEvent::Released { arm: name, time_s: self.time_s });
                }
                continue;
            }
            if self.arms[a].jaws != JawState::Free {
                continue;
            }
            if !closed {
                // Closing: the jaws clamp the thread once their faces squeeze it.
                if closing && self.jaws_squeeze_thread(a, poses) && self.try_grasp(name, poses) {
                    self.taken_at(a, command_rad);
                }
                continue;
            }
            if self.try_grasp(name, poses) {
                self.taken_at(a, command_rad);
            } else {
                self.arms[a].jaws = JawState::ClosedEmpty;
            }
        }
    }

    fn taken_at(&mut self, a: usize, command_rad: f64) {
        if let JawState::Holding { at_jaw_rad, .. } = &mut self.arms[a].jaws {
            *at_jaw_rad = command_rad;
        }
    }

    /// Whether arm `a`'s closing jaws squeeze the thread between them ([`Suture::squeezed`]).
    fn jaws_squeeze_thread(&self, a: usize, poses: &[IsometryMatrix3<f64>]) -> bool {
        let name = self.arms[a].name;
        let Some(jaw_radius_m) = jaw_radius_m(&self.rig, name) else { return false };
        let tip = &poses[self.rig.arm(name).tip_link];
        self.suture.squeezed(&self.physics, tip, self.arms[a].actual().tool.jaw_rad, jaw_radius_m)
    }

    /// Closes `arm`'s jaws on the thread or needle between them, if any; true when they hold it.
    pub(super) fn try_grasp(&mut self, arm: ArmName, poses: &[IsometryMatrix3<f64>]) -> bool {
        let Some(a) = self.arms.iter().position(|x| x.name == arm) else { return false };
        let rig_arm = self.rig.arm(arm);
        // The jaws' carrier: the link the tip frame hangs from.
        let clevis = self.rig.tree.links[rig_arm.tip_link]
            .parent_joint
            .and_then(|j| self.link_bodies[self.rig.tree.joints[j].parent]);
        let Some(clevis) = clevis else { return false };
        let tip = poses[rig_arm.tip_link];
        let radius_m = jaw_radius_m(&self.rig, arm);
        let Some(hold) = self.suture.try_grasp(&mut self.physics, clevis, &tip, radius_m, self.grip_force_n)
        else {
            return false;
        };
        self.events.push(GraspEvent::Grasped { arm, segment: hold.at(), time_s: self.time_s });
        self.arms[a].jaws = JawState::Holding { hold, at_jaw_rad: 0.0 };
        true
    }

    /// Gives the rope's needle to the jaws that hold it, or to the rope when none do.
    pub(super) fn hand_over_needle(&mut self) {
        let held = self.arms.iter().any(|a| a.holds_needle());
        self.suture.hand_over_needle(&mut self.physics, held);
    }

    /// Holds pulled harder than their grip slip out of the jaws; the rope, pulled along itself,
    /// slides through them first. Grips are checked before joints.
    pub(super) fn check_slip(&mut self) {
        let dt = self.config.solver.dt_s;
        for a in 0..self.arms.len() {
            let JawState::Holding { hold, .. } = &mut self.arms[a].jaws else { continue };
            let Some(check) = self.suture.check_grip(hold, &self.physics, dt, self.grip_force_n) else {
                continue;
            };
            self.after_check(a, check);
        }
        let needle_grip_force_n = self.config.sensor.needle_grip_force_n;
        for a in 0..self.arms.len() {
            let JawState::Holding { hold, .. } = &self.arms[a].jaws else { continue };
            let Some(check) =
                Suture::check_joint(hold, &self.physics, self.grip_force_n, needle_grip_force_n)
            else {
                continue;
            };
            self.after_check(a, check);
        }
    }

    fn after_check(&mut self, a: usize, check: HoldCheck) {
        let (arm, time_s) = (self.arms[a].name, self.time_s);
        match check {
            HoldCheck::Held => {}
            HoldCheck::Slid { force_n } => self.events.push(GraspEvent::Slid { arm, force_n, time_s }),
            HoldCheck::SlippedOut { force_n } => {
                if let JawState::Holding { hold, .. } =
                    std::mem::replace(&mut self.arms[a].jaws, JawState::Slipped)
                {
                    self.suture.release(a, hold, &mut self.physics, true);
                }
                self.events.push(GraspEvent::Slipped { arm, force_n, time_s });
            }
        }
    }
}

/// The radius of `arm`'s jaws: their capsules', from the robot model (`None` without jaws).
fn jaw_radius_m(rig: &Rig, arm: ArmName) -> Option<f64> {
    rig.link_radius_m(arm, "jaw_1")
}

/// What the suture needs of each of `arms`' jaws this step, the links at `poses`, jaws below
/// `jaw_closed_rad` closed.
pub(super) fn jaws_now<'a>(
    arms: &'a [SimArm],
    rig: &Rig,
    jaw_closed_rad: f64,
    poses: &[IsometryMatrix3<f64>],
) -> Vec<JawsNow<'a>> {
    arms.iter()
        .map(|arm| {
            let actual_rad = arm.actual().tool.jaw_rad;
            let command_rad = arm.command.tool.jaw_rad;
            JawsNow {
                colliders: &arm.jaw_colliders,
                hold: arm.hold(),
                world_from_tip: poses[rig.arm(arm.name).tip_link],
                radius_m: jaw_radius_m(rig, arm.name),
                closing: command_rad < jaw_closed_rad || command_rad < actual_rad - 1e-3,
                slipped: arm.slipped(),
                closed_empty: arm.closed_empty(),
                open: actual_rad.partial_cmp(&(0.5 * SimWorld::JAW_OPEN_RAD))
                    != Some(std::cmp::Ordering::Less),
            }
        })
        .collect()
}

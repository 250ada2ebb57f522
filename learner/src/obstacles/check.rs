//! One subcell, done plainly: the tip at its point, trocar IK from the arm's current joints, the boxes
//! posed by forward kinematics, then every box pair tested (bounding spheres first). The CPU backend
//! does the same work faster; tests hold it to this reference.

use nalgebra::{Matrix3, Rotation3, Vector3};

use knotlab_hw::kinematics::tool::MIN_TROCAR_DISTANCE_M;
use knotlab_hw::kinematics::{ArmJoints, TipOrientation, TipTarget};

use super::obb::Obb;
use super::prepare::{EnvBox, MovingBox, PreparedGrid};

/// What a subcell is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum SubcellVerdict {
    /// The arm reaches it without hitting anything.
    Free = 0,
    /// The arm reaches it but some box collides.
    Collides = 1,
    /// The inverse kinematics has no solution (out of reach, joint limits, too deep, ...).
    Unreachable = 2,
}

impl SubcellVerdict {
    /// Whether the subcell blocks its cell.
    pub fn blocks(self) -> bool {
        self != SubcellVerdict::Free
    }

    /// From the GPU's code (0, 1, 2); anything else reads as unreachable.
    pub fn from_code(code: u32) -> Self {
        match code {
            0 => SubcellVerdict::Free,
            1 => SubcellVerdict::Collides,
            _ => SubcellVerdict::Unreachable,
        }
    }
}

/// A unit vector perpendicular to unit `v` (as `hw`'s trocar IK picks one).
fn any_perpendicular(v: &Vector3<f64>) -> Vector3<f64> {
    let helper = if v.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
    v.cross(&helper).normalize()
}

/// Whether two spheres (centre, radius) overlap.
#[inline]
pub(crate) fn spheres_meet(a: &Vector3<f64>, ra: f64, b: &Vector3<f64>, rb: f64) -> bool {
    (a - b).norm_squared() <= (ra + rb) * (ra + rb)
}

/// Whether a moving box and an environment box collide (the patient exemption applied).
#[inline]
pub(crate) fn moving_hits_env(m: &MovingBox, obb: &Obb, e: &EnvBox) -> bool {
    !(m.inserted && e.patient)
        && spheres_meet(&obb.centre_m, m.radius_m, &e.obb.centre_m, e.radius_m)
        && obb.intersects(&e.obb)
}

impl PreparedGrid {
    /// The tip position of the subcell at fine-grid column `x`, row `y`.
    pub fn subcell_tip_m(&self, x: usize, y: usize) -> Vector3<f64> {
        self.request.plane.subcell_centre_m(x, y)
    }

    /// The moving arm's joints with its tip at `tip_m`, or `None` when unreachable: `hw`'s
    /// [`ArmModel::solve_tip`](knotlab_hw::kinematics::ArmModel::solve_tip) from the current joints.
    ///
    /// An instrument held along its shaft is handed over as the full tip frame that `solve_tip` would
    /// derive itself (jaws along trocar-to-tip, yaw axis the current tip's made perpendicular to them):
    /// the same solution, without a forward-kinematics call per subcell for the current yaw axis.
    pub fn solve(&self, tip_m: &Vector3<f64>) -> Option<ArmJoints> {
        let orientation = match self.current_yaw_axis {
            Some(y_now) => {
                let to_tip = tip_m - self.trocar_m;
                let distance_m = to_tip.norm();
                if distance_m < MIN_TROCAR_DISTANCE_M {
                    return None;
                }
                let jaw = to_tip / distance_m;
                let perp = y_now - jaw * jaw.dot(&y_now);
                let n = perp.norm();
                let yaw = if n > 1e-6 { perp / n } else { any_perpendicular(&jaw) };
                TipOrientation::Frame(Rotation3::from_matrix_unchecked(Matrix3::from_columns(&[
                    yaw.cross(&jaw),
                    yaw,
                    jaw,
                ])))
            }
            None => self.orientation,
        };
        let target = TipTarget { world_position_m: *tip_m, orientation };
        self.model.solve_tip(&target, &self.trocar_m, &self.current).ok()
    }

    /// The moving arm's boxes in the world at `joints`, written to `out` (as long as `moving`).
    pub fn pose_moving(&self, joints: &ArmJoints, out: &mut [Obb]) {
        let anchors = self.kinematics.world_from_anchors(joints);
        for (m, slot) in self.moving.iter().zip(out.iter_mut()) {
            *slot = Obb::new(&(anchors[m.anchor] * m.anchor_from_box), m.half_extents_m);
        }
    }

    /// Whether the posed moving boxes hit the environment or each other (every pair, group spheres as
    /// the only broad phase).
    pub fn collides(&self, posed: &[Obb]) -> bool {
        for (m, obb) in self.moving.iter().zip(posed) {
            if !m.tests_environment {
                continue;
            }
            for g in &self.groups {
                if !spheres_meet(&obb.centre_m, m.radius_m, &g.centre_m, g.radius_m) {
                    continue;
                }
                if self.environment[g.start..g.end].iter().any(|e| moving_hits_env(m, obb, e)) {
                    return true;
                }
            }
        }
        self.self_pairs.iter().any(|&(a, b)| {
            let (ma, mb) = (&self.moving[a], &self.moving[b]);
            spheres_meet(&posed[a].centre_m, ma.radius_m, &posed[b].centre_m, mb.radius_m)
                && posed[a].intersects(&posed[b])
        })
    }

    /// The verdict for the tip at `tip_m`.
    pub fn verdict_at(&self, tip_m: &Vector3<f64>) -> SubcellVerdict {
        let Some(joints) = self.solve(tip_m) else {
            return SubcellVerdict::Unreachable;
        };
        let mut posed =
            vec![Obb::new(&nalgebra::IsometryMatrix3::identity(), Vector3::zeros()); self.moving.len()];
        self.pose_moving(&joints, &mut posed);
        if self.collides(&posed) { SubcellVerdict::Collides } else { SubcellVerdict::Free }
    }

    /// Whether the verdict changes when the tip moves by `distance_m` along either in-plane axis or the
    /// plane's normal, either way: the subcell lies within that distance of a collision or reachability
    /// boundary, where the GPU's f32 arithmetic may decide differently from the CPU's f64.
    pub fn near_boundary(&self, tip_m: &Vector3<f64>, distance_m: f64) -> bool {
        let here = self.verdict_at(tip_m);
        let plane = &self.request.plane;
        [plane.axis_u, plane.axis_v, plane.normal()]
            .iter()
            .flat_map(|axis| [*axis, -*axis])
            .any(|step| self.verdict_at(&(tip_m + step * distance_m)) != here)
    }
}

//! The URDF as a validated joint tree, and forward kinematics by walking it. This is the second,
//! independent description of the robots that the closed-form kinematics is checked against.

use std::collections::HashMap;

use nalgebra::{IsometryMatrix3, Rotation3, Translation3, Unit, Vector3};

use super::error::Problem;
use crate::kinematics::JointLimit;

/// What a joint does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// Rigid.
    Fixed,
    /// Turns about its axis, within limits.
    Revolute,
    /// Turns about its axis without limits.
    Continuous,
    /// Slides along its axis, within limits.
    Prismatic,
}

/// A collision primitive; these become the oriented boxes of the collision tests.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A box with these half extents, m.
    Box {
        /// Half sizes along x, y, z, m.
        half_extents_m: Vector3<f64>,
    },
    /// A capsule along z: a cylinder of `length_m` with hemispherical caps.
    Capsule {
        /// Radius, m.
        radius_m: f64,
        /// Length of the cylindrical part, m.
        length_m: f64,
    },
    /// A sphere.
    Sphere {
        /// Radius, m.
        radius_m: f64,
    },
}

/// A collision primitive placed in its link.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CollisionShape {
    /// The shape's frame in the link.
    pub link_from_shape: IsometryMatrix3<f64>,
    /// The shape.
    pub shape: Shape,
}

/// A link of the tree.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeLink {
    /// Its URDF name.
    pub name: String,
    /// The joint that carries it; `None` for the root.
    pub parent_joint: Option<usize>,
    /// Its collision geometry.
    pub collisions: Vec<CollisionShape>,
}

/// A joint of the tree.
#[derive(Clone, Debug, PartialEq)]
pub struct TreeJoint {
    /// Its URDF name.
    pub name: String,
    /// What it does.
    pub kind: JointKind,
    /// Parent link index.
    pub parent: usize,
    /// Child link index.
    pub child: usize,
    /// The joint frame in the parent link (the URDF origin).
    pub parent_from_joint: IsometryMatrix3<f64>,
    /// Unit axis in the joint frame.
    pub axis: Unit<Vector3<f64>>,
    /// Limits of revolute and prismatic joints.
    pub limit: Option<JointLimit>,
}

/// A validated URDF: one root, every link reached once, joints in an order where parents come first.
#[derive(Clone, Debug, PartialEq)]
pub struct JointTree {
    /// The robot's name.
    pub name: String,
    /// Links, in document order.
    pub links: Vec<TreeLink>,
    /// Joints, in document order.
    pub joints: Vec<TreeJoint>,
    /// Index of the root link.
    pub root: usize,
    /// Joint indices, parents before children.
    order: Vec<usize>,
    link_index: HashMap<String, usize>,
    joint_index: HashMap<String, usize>,
}

fn finite3(v: &[f64; 3]) -> bool {
    v.iter().all(|x| x.is_finite())
}

fn pose_of(origin: &urdf_rs::Pose) -> IsometryMatrix3<f64> {
    let [x, y, z] = *origin.xyz;
    let [roll, pitch, yaw] = *origin.rpy;
    // URDF: R = Rz(yaw) Ry(pitch) Rx(roll), which is nalgebra's Euler-angle convention.
    IsometryMatrix3::from_parts(Translation3::new(x, y, z), Rotation3::from_euler_angles(roll, pitch, yaw))
}

fn check_origin(element: &str, origin: &urdf_rs::Pose, problems: &mut Vec<Problem>) {
    if !finite3(&origin.xyz) {
        problems.push(Problem::new(element, "origin.xyz", format!("not finite: {:?}", *origin.xyz)));
    }
    if !finite3(&origin.rpy) {
        problems.push(Problem::new(element, "origin.rpy", format!("not finite: {:?}", *origin.rpy)));
    }
}

fn shape_of(element: &str, geometry: &urdf_rs::Geometry, problems: &mut Vec<Problem>) -> Option<Shape> {
    let positive = |v: f64| v.is_finite() && v > 0.0;
    match geometry {
        urdf_rs::Geometry::Box { size } => {
            if size.iter().all(|s| positive(*s)) {
                Some(Shape::Box { half_extents_m: Vector3::new(size[0], size[1], size[2]) * 0.5 })
            } else {
                problems.push(Problem::new(
                    element,
                    "geometry.box.size",
                    format!("sizes must be finite and positive, got {:?}", **size),
                ));
                None
            }
        }
        urdf_rs::Geometry::Capsule { radius, length } => {
            if positive(*radius) && length.is_finite() && *length >= 0.0 {
                Some(Shape::Capsule { radius_m: *radius, length_m: *length })
            } else {
                problems.push(Problem::new(
                    element,
                    "geometry.capsule",
                    format!("radius must be positive and length not negative, got {radius} and {length}"),
                ));
                None
            }
        }
        urdf_rs::Geometry::Sphere { radius } => {
            if positive(*radius) {
                Some(Shape::Sphere { radius_m: *radius })
            } else {
                problems.push(Problem::new(
                    element,
                    "geometry.sphere.radius",
                    format!("must be positive, got {radius}"),
                ));
                None
            }
        }
        urdf_rs::Geometry::Cylinder { .. } | urdf_rs::Geometry::Mesh { .. } => {
            problems.push(Problem::new(
                element,
                "geometry",
                "only boxes, capsules and spheres are supported for collision (they become oriented boxes)",
            ));
            None
        }
    }
}

fn limit_of(element: &str, joint: &urdf_rs::Joint, problems: &mut Vec<Problem>) -> Option<JointLimit> {
    let l = &joint.limit;
    let before = problems.len();
    for (field, value) in [("limit.lower", l.lower), ("limit.upper", l.upper), ("limit.velocity", l.velocity)]
    {
        if !value.is_finite() {
            problems.push(Problem::new(element, field, format!("not finite: {value}")));
        }
    }
    if problems.len() == before {
        if l.lower >= l.upper {
            problems.push(Problem::new(
                element,
                "limit",
                format!("lower {} must be below upper {}", l.lower, l.upper),
            ));
        }
        if l.velocity <= 0.0 {
            problems.push(Problem::new(
                element,
                "limit.velocity",
                format!("must be positive, got {}", l.velocity),
            ));
        }
    }
    (problems.len() == before).then(|| JointLimit::new(l.lower, l.upper, l.velocity))
}

impl JointTree {
    /// Validates a parsed URDF; on failure returns every problem found.
    pub fn from_urdf(robot: &urdf_rs::Robot) -> Result<Self, Vec<Problem>> {
        let mut problems = Vec::new();
        let mut link_index = HashMap::new();
        let mut links = Vec::with_capacity(robot.links.len());
        for link in &robot.links {
            let element = format!("link '{}'", link.name);
            if link_index.insert(link.name.clone(), links.len()).is_some() {
                problems.push(Problem::new(&element, "name", "another link has the same name"));
            }
            let mut collisions = Vec::new();
            for (i, c) in link.collision.iter().enumerate() {
                let element = format!("{element} collision {i}");
                check_origin(&element, &c.origin, &mut problems);
                if let Some(shape) = shape_of(&element, &c.geometry, &mut problems) {
                    collisions.push(CollisionShape { link_from_shape: pose_of(&c.origin), shape });
                }
            }
            links.push(TreeLink { name: link.name.clone(), parent_joint: None, collisions });
        }

        let mut joint_index = HashMap::new();
        let mut joints = Vec::with_capacity(robot.joints.len());
        for joint in &robot.joints {
            let element = format!("joint '{}'", joint.name);
            if joint_index.insert(joint.name.clone(), joints.len()).is_some() {
                problems.push(Problem::new(&element, "name", "another joint has the same name"));
            }
            let mut endpoint = |field: &str, name: &str| match link_index.get(name) {
                Some(&i) => Some(i),
                None => {
                    problems.push(Problem::new(
                        &element,
                        field,
                        format!("names link '{name}', which does not exist"),
                    ));
                    None
                }
            };
            let parent = endpoint("parent", &joint.parent.link);
            let child = endpoint("child", &joint.child.link);
            check_origin(&element, &joint.origin, &mut problems);
            let kind = match joint.joint_type {
                urdf_rs::JointType::Fixed => Some(JointKind::Fixed),
                urdf_rs::JointType::Revolute => Some(JointKind::Revolute),
                urdf_rs::JointType::Continuous => Some(JointKind::Continuous),
                urdf_rs::JointType::Prismatic => Some(JointKind::Prismatic),
                ref other => {
                    problems.push(Problem::new(
                        &element,
                        "type",
                        format!("{other:?} joints are not supported"),
                    ));
                    None
                }
            };
            let axis_xyz = Vector3::from(*joint.axis.xyz);
            let axis = if kind == Some(JointKind::Fixed) {
                Some(Vector3::z_axis())
            } else if !axis_xyz.iter().all(|x| x.is_finite()) || axis_xyz.norm() < 1e-9 {
                problems.push(Problem::new(
                    &element,
                    "axis.xyz",
                    format!("must be finite and non-zero, got {:?}", *joint.axis.xyz),
                ));
                None
            } else {
                Some(Unit::new_normalize(axis_xyz))
            };
            let limit = match kind {
                Some(JointKind::Revolute | JointKind::Prismatic) => limit_of(&element, joint, &mut problems),
                _ => None,
            };
            if let (Some(parent), Some(child), Some(kind), Some(axis)) = (parent, child, kind, axis) {
                if links[child].parent_joint.is_some() {
                    problems.push(Problem::new(
                        &element,
                        "child",
                        format!("link '{}' already has a parent joint", joint.child.link),
                    ));
                }
                links[child].parent_joint = Some(joints.len());
                joints.push(TreeJoint {
                    name: joint.name.clone(),
                    kind,
                    parent,
                    child,
                    parent_from_joint: pose_of(&joint.origin),
                    axis,
                    limit,
                });
            }
        }
        if !problems.is_empty() {
            return Err(problems);
        }

        let roots: Vec<usize> = (0..links.len()).filter(|&i| links[i].parent_joint.is_none()).collect();
        let root = match roots.as_slice() {
            [r] => *r,
            [] => {
                return Err(vec![Problem::new(
                    format!("robot '{}'", robot.name),
                    "links",
                    "no root link: the joints form a cycle",
                )]);
            }
            many => {
                let names: Vec<&str> = many.iter().map(|&i| links[i].name.as_str()).collect();
                return Err(vec![Problem::new(
                    format!("robot '{}'", robot.name),
                    "links",
                    format!("more than one root link (unconnected): {}", names.join(", ")),
                )]);
            }
        };
        // Parents before children: breadth-first from the root; links never reached sit on a cycle.
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); links.len()];
        for (j, joint) in joints.iter().enumerate() {
            children[joint.parent].push(j);
        }
        let mut order = Vec::with_capacity(joints.len());
        let mut frontier = vec![root];
        while let Some(link) = frontier.pop() {
            for &j in &children[link] {
                order.push(j);
                frontier.push(joints[j].child);
            }
        }
        if order.len() != joints.len() {
            let reached: std::collections::HashSet<usize> = order.iter().copied().collect();
            let stray: Vec<&str> =
                (0..joints.len()).filter(|j| !reached.contains(j)).map(|j| joints[j].name.as_str()).collect();
            return Err(vec![Problem::new(
                format!("robot '{}'", robot.name),
                "joints",
                format!(
                    "joints on a cycle, unreachable from root '{}': {}",
                    links[root].name,
                    stray.join(", ")
                ),
            )]);
        }
        Ok(Self { name: robot.name.clone(), links, joints, root, order, link_index, joint_index })
    }

    /// Index of a link by name.
    pub fn link(&self, name: &str) -> Option<usize> {
        self.link_index.get(name).copied()
    }

    /// Index of a joint by name.
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.joint_index.get(name).copied()
    }

    /// Every link's pose in the root frame, for joint positions indexed like [`JointTree::joints`]
    /// (values of fixed joints are ignored).
    pub fn root_from_links(&self, positions: &[f64]) -> Vec<IsometryMatrix3<f64>> {
        let mut poses = vec![IsometryMatrix3::identity(); self.links.len()];
        for &j in &self.order {
            let joint = &self.joints[j];
            let q = positions.get(j).copied().unwrap_or(0.0);
            let motion = match joint.kind {
                JointKind::Fixed => IsometryMatrix3::identity(),
                JointKind::Revolute | JointKind::Continuous => IsometryMatrix3::from_parts(
                    Translation3::identity(),
                    Rotation3::from_axis_angle(&joint.axis, q),
                ),
                JointKind::Prismatic => IsometryMatrix3::from_parts(
                    Translation3::from(joint.axis.into_inner() * q),
                    Rotation3::identity(),
                ),
            };
            poses[joint.child] = poses[joint.parent] * joint.parent_from_joint * motion;
        }
        poses
    }

    /// The joints from the root down to `link`, root first.
    pub fn path_to(&self, link: usize) -> Vec<usize> {
        let mut path = Vec::new();
        let mut at = link;
        while let Some(j) = self.links[at].parent_joint {
            path.push(j);
            at = self.joints[j].parent;
        }
        path.reverse();
        path
    }
}

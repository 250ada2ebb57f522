//! A skill from the knowledge base's primitives at a new stitch (the fluid and DMP methods), by the
//! rules of each primitive type:
//! - linear: from where the instrument is to the moved end, straight, with the demonstrated speed
//!   profile (stretched to the new length, the demonstrated duration kept);
//! - force-controlled: the demonstrated movement, moved, up to where it came to rest, then at once on
//!   along its line (start to there) until the line is elongated by
//!   [`PrimitiveSettings::force_elongation`] or, short of that, as far as the instrument reaches
//!   ([`Site::reach`]), there until the slot's end, then back to the line's end; once the recorded
//!   maximum force is reached the tip stops there and holds, and the jaws open when the
//!   demonstration's opened (the primitive's span on), at once if the force comes later (two force
//!   events; the paper opens them at once, and a knot let go at once by the long end was left
//!   beside the stitch where the demonstrated hold laid it on it), at the slot's end if it never
//!   comes;
//! - 2D: regenerated through the fluid around obstacles ([`Method::Fluid`]) or by a DMP from where the
//!   instrument is ([`Method::Dmp`]); one that another instrument follows (a winding round its jaws)
//!   turned about that instrument's tip as its wrist can hold its jaws ([`super::winding`]);
//! - synchronized: the stored offsets from the reference applied to every point of the reference's new
//!   path, at the same progress along it.
//!
//! Between primitives the instrument does what it did in the demonstration (the knowledge base's path
//! of each instrument, moved to the new stitch), on the [`Schedule`]'s clock (after its last
//! primitive going no further than it reaches, [`Site::reach`], as a force-controlled pull does),
//! except that an instrument that waited before its first primitive (within [`WAITED_M`] and
//! [`WAITED_RAD`]) waits where it is;
//! a primitive that starts elsewhere is reached by a straight minimum-jerk move (at
//! [`PrimitiveSettings::gap_speed_mps`]). The
//! jaws move as the demonstration's did. The tip keeps the demonstrated frame ([`Aim::Frame`]): a
//! moved path key its own, a 2D path's point the frame the demonstration had as far along its path, a
//! synchronized point its sample's, a straight line turning from the frame it starts with to its end
//! pose's as the demonstration turned along its path.

use nalgebra::{Isometry3, UnitQuaternion, Vector2, Vector3};

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::{ForceAction, ForceEvent, JawKey, Skill};

use super::dmp::Dmp;
use super::orientation::Aim;
use super::schedule::Schedule;
use super::site::{Reach, pose_isometry};
use super::track::TrackKeys;
use super::winding::winding_aim;
use super::{Method, StartPose, SynthesisError, Trocars};
use crate::fluid::{
    ArcPath, GridRegion, InstantiateSettings, Instantiation, ObstacleMask, PlaneFrame, instantiate,
};
use crate::primitive::{
    ForcePrimitive, KnowledgeBase, LinearPrimitive, PathKey, Pose, Primitive, ProfilePoint,
    SynchronizedPrimitive, TwoDPrimitive,
};

/// How primitives are instantiated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrimitiveSettings {
    /// A force-controlled primitive's line is elongated by this factor (the paper: 1.25).
    pub force_elongation: f64,
    /// Its return from the elongated end to the line's end takes at least this long, s.
    pub force_return_s: f64,
    /// Moves between primitives go at this mean speed, m/s.
    pub gap_speed_mps: f64,
    /// The fluid's grid: cells per side.
    pub fluid_cells: usize,
    /// Free margin of the fluid's grid around the demonstrated path, m.
    pub fluid_margin_m: f64,
    /// The fluid solver's settings.
    pub fluid: InstantiateSettings,
    /// Basis functions per DMP.
    pub dmp_basis: usize,
    /// Pose keys of generated paths every this many seconds.
    pub key_period_s: f64,
}

impl Default for PrimitiveSettings {
    /// Elongation 1.25 and a return of at least 0.5 s, gaps at 1 cm/s, a 50 x 50 fluid grid with 1 cm
    /// margin, 100 DMP basis functions, keys every 50 ms.
    fn default() -> Self {
        Self {
            force_elongation: 1.25,
            force_return_s: 0.5,
            gap_speed_mps: 0.01,
            fluid_cells: 50,
            fluid_margin_m: 0.01,
            fluid: InstantiateSettings::default(),
            dmp_basis: 100,
            key_period_s: 0.05,
        }
    }
}

/// The site a skill is made for.
#[derive(Clone, Debug)]
pub struct Site<'a> {
    /// The new stitch frame.
    pub new_world_from_stitch: Isometry3<f64>,
    /// The trocars.
    pub trocars: &'a Trocars,
    /// Where the instruments are.
    pub starts: &'a [StartPose],
    /// Which tip targets each instrument can take; `None`: every one.
    pub reach: Option<Reach<'a>>,
}

/// How far short of the farthest reachable point a force-controlled pull stops, m: the arm's own
/// margin against play and rounding.
pub const REACH_MARGIN_M: f64 = 0.002;

/// Real and virtual obstacles in a 2D primitive's plane: given the primitive, its instrument, the
/// moved plane and the grid region, the blocked cells.
pub type ObstacleSource<'a> =
    dyn FnMut(&str, ArmName, &PlaneFrame, &GridRegion) -> Result<ObstacleMask, SynthesisError> + 'a;

/// A synthesized skill with what it was made of.
#[derive(Clone, Debug)]
pub struct Synthesis {
    /// The skill.
    pub skill: Skill,
    /// Its clock.
    pub schedule: Schedule,
    /// The fluid's regenerations of the 2D primitives (method fluid), by primitive name.
    pub fluid: Vec<(String, Instantiation)>,
}

fn invalid(field: impl Into<String>, reason: impl Into<String>) -> SynthesisError {
    SynthesisError::Invalid { field: field.into(), reason: reason.into() }
}

/// Where a knowledge-base pose lands in the world, and its frame.
fn placed(world_from_stitch: &Isometry3<f64>, pose: &Pose) -> (Vector3<f64>, Aim) {
    let world_from_tip = world_from_stitch * pose_isometry(pose);
    (world_from_tip.translation.vector, Aim::Frame(world_from_tip.rotation))
}

/// How a demonstrated path key aims the tip at the new stitch: its frame, or (a knowledge base before
/// format version 3) its jaws' direction.
fn key_aim(world_from_stitch: &Isometry3<f64>, key: &PathKey) -> Aim {
    match key.quaternion_xyzw {
        Some([x, y, z, w]) => Aim::Frame(
            world_from_stitch.rotation
                * UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)),
        ),
        None => Aim::Jaws(world_from_stitch.rotation * Vector3::from(key.jaw_direction)),
    }
}

/// Fractions of time at the profile's points, from 0 to 1, moving at its speeds (floored at 5 % of the
/// largest, where the hand was at rest).
fn profile_times(profile: &[ProfilePoint]) -> Vec<f64> {
    let v_max = profile.iter().map(|p| p.speed_mps).fold(0.0, f64::max);
    let floor = (0.05 * v_max).max(1e-6);
    let mut t = vec![0.0];
    for w in profile.windows(2) {
        let ds = (w[1].s_m - w[0].s_m).max(0.0);
        let v = 0.5 * (w[0].speed_mps.max(floor) + w[1].speed_mps.max(floor));
        t.push(t[t.len() - 1] + ds / v);
    }
    let total = t[t.len() - 1];
    if total > 0.0 {
        t.iter().map(|x| x / total).collect()
    } else {
        (0..profile.len()).map(|k| k as f64 / (profile.len() - 1).max(1) as f64).collect()
    }
}

/// The demonstrated turn of the tip over `start_s..=end_s`: `(fraction of the path's length covered,
/// fraction of the turn made)` at each path key, the turn's fraction measured between the frames at
/// the two ends (and never going back). Empty where the keys have no frames (a knowledge base before
/// format version 3) or the tip turned less than a degree.
fn demonstrated_turn(path: &[PathKey], start_s: f64, end_s: f64) -> Vec<(f64, f64)> {
    let keys: Vec<(Vector3<f64>, UnitQuaternion<f64>)> = path
        .iter()
        .filter(|k| k.time_s >= start_s - 1e-9 && k.time_s <= end_s + 1e-9)
        .filter_map(|k| {
            let [x, y, z, w] = k.quaternion_xyzw?;
            Some((
                Vector3::from(k.position_m),
                UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)),
            ))
        })
        .collect();
    let (Some(first), Some(last)) = (keys.first(), keys.last()) else {
        return Vec::new();
    };
    if keys.len() < 2 || first.1.angle_to(&last.1) < 1f64.to_radians() {
        return Vec::new();
    }
    let length: f64 = keys.windows(2).map(|w| (w[1].0 - w[0].0).norm()).sum();
    let (mut covered, mut turned) = (0.0, 0.0f64);
    let mut out = Vec::with_capacity(keys.len());
    for (k, (p, q)) in keys.iter().enumerate() {
        if k > 0 {
            covered += (p - keys[k - 1].0).norm();
        }
        let (from_start, to_end) = (first.1.angle_to(q), q.angle_to(&last.1));
        turned = turned.max(from_start / (from_start + to_end).max(1e-12));
        let u = if length > 0.0 { covered / length } else { k as f64 / (keys.len() - 1) as f64 };
        out.push((u, turned));
    }
    out
}

/// The turn's fraction at `u` of the path's length (linear between the points of
/// [`demonstrated_turn`]; `u` itself where there are none).
fn turn_at(turn: &[(f64, f64)], u: f64) -> f64 {
    let k = turn.partition_point(|(v, _)| *v < u);
    match (k.checked_sub(1).and_then(|i| turn.get(i)), turn.get(k)) {
        (_, None) if turn.is_empty() => u,
        (Some(a), Some(b)) if b.0 > a.0 => a.1 + (b.1 - a.1) * (u - a.0) / (b.0 - a.0),
        (_, Some(b)) => b.1,
        (Some(a), None) => a.1,
        (None, None) => u,
    }
}

/// Keys along the straight line `from -> to` from `t0` over `duration_s`, progressing by the profile
/// and turning the tip as the demonstration did along its path (`turn`, see [`demonstrated_turn`]).
fn line(
    track: &mut TrackKeys,
    profile: &[ProfilePoint],
    turn: &[(f64, f64)],
    t0: f64,
    duration_s: f64,
    to: Vector3<f64>,
    to_aim: Aim,
) {
    let (from, from_aim) = (track.position_m, track.aim);
    let total_s = profile.last().map_or(0.0, |p| p.s_m);
    if profile.len() < 2 || total_s <= 0.0 {
        track.move_to(t0 + duration_s, to, to_aim, 20);
        return;
    }
    for (p, tau) in profile.iter().zip(profile_times(profile)) {
        let u = (p.s_m / total_s).clamp(0.0, 1.0);
        track.key(t0 + tau * duration_s, from.lerp(&to, u), from_aim.towards(&to_aim, turn_at(turn, u)));
    }
}

fn gap_move(track: &mut TrackKeys, until_s: f64, to: Vector3<f64>, to_aim: Aim, speed_mps: f64) {
    let distance = (to - track.position_m).norm();
    let available = until_s - track.time_s;
    if available <= 0.0 {
        track.key(track.time_s, to, to_aim);
        return;
    }
    let wanted = (distance / speed_mps).max(0.3);
    track.move_to(track.time_s + wanted.min(available), to, to_aim, 10);
    track.hold_until(until_s);
}

fn duration_of(p: &Primitive, settings: &PrimitiveSettings) -> f64 {
    let (a, b) = p.span_s();
    match p {
        Primitive::Force(_) => settings.force_elongation * (b - a) + return_s(b - a, settings),
        _ => b - a,
    }
}

fn return_s(demo_duration_s: f64, settings: &PrimitiveSettings) -> f64 {
    (0.1 * demo_duration_s).max(settings.force_return_s)
}

fn linear_keys(
    track: &mut TrackKeys,
    p: &LinearPrimitive,
    path: &[PathKey],
    slot: (f64, f64),
    world_from_stitch: &Isometry3<f64>,
) {
    let (to, to_aim) = placed(world_from_stitch, &p.end_pose);
    track.hold_until(slot.0);
    let turn = demonstrated_turn(path, p.start_s, p.end_s);
    line(track, &p.speed_profile, &turn, slot.0, slot.1 - slot.0, to, to_aim);
}

/// Keys from the demonstrated path between the demonstration's times `from_s` and `to_s` (open
/// interval), placed at `map(t)` on the new clock and moved to the new stitch.
fn transfer(
    track: &mut TrackKeys,
    path: &[PathKey],
    (from_s, to_s): (f64, f64),
    map: impl Fn(f64) -> f64,
    world_from_stitch: &Isometry3<f64>,
) {
    for key in path.iter().filter(|k| k.time_s > from_s && k.time_s < to_s) {
        let t = map(key.time_s);
        if t <= track.time_s {
            continue;
        }
        let p = world_from_stitch.transform_point(&Vector3::from(key.position_m).into()).coords;
        track.key(t, p, key_aim(world_from_stitch, key));
    }
}

/// Farthest an instrument's tip may have moved before its first primitive for it to have waited, m.
pub const WAITED_M: f64 = 0.002;
/// Most an instrument's tip may have turned before its first primitive for it to have waited, rad: a
/// hand at rest wanders a few degrees (the synthetic demonstrations' assist turns 0.08 rad while it
/// holds the tail; the scripted expert's 0.0007 rad).
pub const WAITED_RAD: f64 = 0.15;

/// Whether the demonstrated instrument stayed where it started (within [`WAITED_M`] and
/// [`WAITED_RAD`]) until `until_s`.
fn waited(path: &[PathKey], until_s: f64) -> bool {
    let Some(first) = path.first() else { return true };
    let frame = |k: &PathKey| {
        k.quaternion_xyzw
            .map(|[x, y, z, w]| UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z)))
    };
    let p0 = Vector3::from(first.position_m);
    path.iter().take_while(|k| k.time_s < until_s).all(|k| {
        let turned = match (frame(first), frame(k)) {
            (Some(a), Some(b)) => a.angle_to(&b),
            _ => Vector3::from(first.jaw_direction).angle(&Vector3::from(k.jaw_direction)),
        };
        (Vector3::from(k.position_m) - p0).norm() <= WAITED_M && turned <= WAITED_RAD
    })
}

fn force_keys(
    track: &mut TrackKeys,
    p: &ForcePrimitive,
    path: &[PathKey],
    slot: (f64, f64),
    world_from_stitch: &Isometry3<f64>,
    settings: &PrimitiveSettings,
    reach: Option<Reach<'_>>,
) {
    let (start, start_aim) = placed(world_from_stitch, &p.start_pose);
    let (_, end_aim) = placed(world_from_stitch, &p.end_pose);
    let line_end = world_from_stitch.transform_point(&Vector3::from(p.line_end_m).into()).coords;
    gap_move(track, slot.0, start, start_aim, settings.gap_speed_mps);
    let d = p.end_s - p.start_s;
    // The demonstrated movement up to where it came to rest, moved; the line from its start to there
    // gives the direction it goes on in, at once (not after whatever the demonstration did at rest): a
    // pull that has not brought its force goes on while the other instruments still hold what they
    // held as it came to rest.
    let rest_s = came_to_rest_s(path, p);
    let pulled_s = rest_s - p.start_s;
    let shift = slot.0 - p.start_s;
    transfer(track, path, (p.start_s, rest_s), |t| t + shift, world_from_stitch);
    track.key(slot.0 + pulled_s, line_end, end_aim);
    let elongation = pull_within_reach(track, reach, start, line_end, end_aim, settings.force_elongation);
    let far = start + (line_end - start) * elongation;
    track.move_to(slot.0 + settings.force_elongation * pulled_s, far, end_aim, 20);
    track.hold_until(slot.0 + settings.force_elongation * d);
    track.move_to(slot.1, line_end, end_aim, 20);
    let (from_rad, to_rad) = (p.jaw.from_rad, p.jaw.to_rad);
    track.jaw.push(JawKey { time_s: slot.0, jaw_rad: from_rad });
    track.jaw.push(JawKey { time_s: slot.1 - 0.01, jaw_rad: from_rad });
    track.jaw.push(JawKey { time_s: slot.1, jaw_rad: to_rad });
    // At the recorded force the tip stops and holds, wherever that is ...
    track.events.push(ForceEvent {
        name: p.name.clone(),
        from_s: slot.0,
        until_s: slot.1,
        threshold_n: p.max_force_n,
        sustain_s: 0.0,
        fires_with: None,
        action: ForceAction::Hold,
    });
    // ... and the jaws let go as long after the pull's start as the demonstration's did (the
    // demonstrated hold at the snug lays the knot down), or at the force if it comes later (the
    // paper's rule).
    track.events.push(ForceEvent {
        name: format!("{} lets go", p.name),
        from_s: (slot.0 + p.jaw.at_s).min(slot.1),
        until_s: slot.1,
        threshold_n: p.max_force_n,
        sustain_s: 0.0,
        fires_with: Some(p.name.clone()),
        action: ForceAction::OpenJaw { jaw_rad: to_rad },
    });
}

/// How far from the line's end a demonstrated tip may be for its pull to have come to rest there, m.
pub const AT_REST_M: f64 = 0.001;

/// When the demonstrated force-controlled movement came to rest at its line's end: the first time of
/// the primitive's span from which the path stays within [`AT_REST_M`] of it (the span's end if it
/// never does).
fn came_to_rest_s(path: &[PathKey], p: &ForcePrimitive) -> f64 {
    let line_end = Vector3::from(p.line_end_m);
    let mut rest_s = p.end_s;
    for key in path.iter().rev().filter(|k| k.time_s >= p.start_s && k.time_s <= p.end_s) {
        if (Vector3::from(key.position_m) - line_end).norm() > AT_REST_M {
            break;
        }
        rest_s = key.time_s;
    }
    rest_s
}

/// How far along the line from `start` through `line_end` a force-controlled pull goes on, as a
/// multiple of the line: `elongation`, or less where the instrument would not reach that far (the
/// farthest multiple from 1 up whose point, [`REACH_MARGIN_M`] further on, it reaches, by bisection;
/// 1 where it reaches no further than the line's end).
fn pull_within_reach(
    track: &TrackKeys,
    reach: Option<Reach<'_>>,
    start: Vector3<f64>,
    line_end: Vector3<f64>,
    aim: Aim,
    elongation: f64,
) -> f64 {
    let Some(Reach(reaches)) = reach else { return elongation };
    let line = line_end - start;
    let length_m = line.norm();
    if length_m < 1e-9 || elongation <= 1.0 {
        return elongation;
    }
    let fits = |f: f64| {
        let at = start + line * (f + REACH_MARGIN_M / length_m);
        reaches(track.arm, &track.target(at, aim))
    };
    if fits(elongation) {
        return elongation;
    }
    let (mut lo, mut hi) = (1.0, elongation);
    if !fits(lo) {
        return 1.0;
    }
    for _ in 0..20 {
        let mid = 0.5 * (lo + hi);
        if fits(mid) { lo = mid } else { hi = mid }
    }
    lo
}

/// The reference path of a synchronized primitive: times and world points of a 2D primitive's new path.
#[derive(Clone, Debug)]
struct NewPath {
    name: String,
    plane: PlaneFrame,
    times_s: Vec<f64>,
    points_m: Vec<Vector3<f64>>,
    /// How each point aims the tip.
    aims: Vec<Aim>,
    /// The stitch frame it was made at (turned with it where it was aimed round another
    /// instrument's jaws: [`winding_aim`]), which its followers' frames are given in.
    world_from_stitch: Isometry3<f64>,
}

impl NewPath {
    /// The time at which the path has covered `phase` of its length.
    fn time_at_phase(&self, phase: f64) -> (f64, Vector3<f64>) {
        let mut s = vec![0.0];
        for w in self.points_m.windows(2) {
            s.push(s[s.len() - 1] + (w[1] - w[0]).norm());
        }
        let total = s[s.len() - 1];
        if total <= 0.0 {
            return (self.times_s[0], self.points_m[0]);
        }
        let target = phase.clamp(0.0, 1.0) * total;
        let k = s.partition_point(|x| *x <= target).saturating_sub(1).min(s.len() - 2);
        let f = if s[k + 1] > s[k] { (target - s[k]) / (s[k + 1] - s[k]) } else { 0.0 };
        (
            self.times_s[k] + f * (self.times_s[k + 1] - self.times_s[k]),
            self.points_m[k].lerp(&self.points_m[k + 1], f),
        )
    }
}

#[allow(clippy::too_many_arguments)]
fn two_d_path(
    arm: ArmName,
    track: &TrackKeys,
    p: &TwoDPrimitive,
    slot: (f64, f64),
    method: Method,
    demo_world_from_stitch: &Isometry3<f64>,
    new_world_from_stitch: &Isometry3<f64>,
    settings: &PrimitiveSettings,
    demo_path: &[PathKey],
    obstacles: &mut ObstacleSource<'_>,
) -> Result<(NewPath, Option<Instantiation>), SynthesisError> {
    let demo = p
        .planar_demonstration(demo_world_from_stitch)
        .map_err(|e| invalid(format!("{}.path", p.name), e.to_string()))?;
    let moved = new_world_from_stitch * demo_world_from_stitch.inverse();
    let plane = demo.plane.moved(&moved);
    let duration = slot.1 - slot.0;
    let (native, points_m, inst): (Vec<f64>, Vec<Vector3<f64>>, Option<Instantiation>) = match method {
        Method::Fluid => {
            let region =
                GridRegion::around(&demo.path.points_m, settings.fluid_cells, settings.fluid_margin_m)
                    .map_err(|e| invalid(format!("{}.fluid", p.name), e.to_string()))?;
            let mask = obstacles(&p.name, arm, &plane, &region)?;
            let inst = instantiate(&demo, &moved, &region, &mask, &settings.fluid)
                .map_err(|e| invalid(format!("{}.fluid", p.name), e.to_string()))?;
            let times = inst.points.iter().map(|q| q.t_s).collect();
            let points = inst.points.iter().map(|q| q.world_m).collect();
            (times, points, Some(inst))
        }
        Method::Dmp | Method::Replay => {
            let arc = ArcPath::new(&demo.path);
            let n = 400;
            let dt = arc.duration_s() / n as f64;
            let samples: Vec<Vector2<f64>> = (0..=n).map(|k| arc.at_time(k as f64 * dt).point_m).collect();
            let start = plane.to_plane(&track.position_m);
            let goal = samples[n];
            let mut coords = Vec::new();
            for axis in 0..2 {
                let y: Vec<f64> = samples.iter().map(|q| q[axis]).collect();
                let dmp = Dmp::fit(&y, dt, settings.dmp_basis)
                    .ok_or_else(|| invalid(format!("{}.path", p.name), "too short for a DMP"))?;
                coords.push(dmp.rollout(start[axis], goal[axis], arc.duration_s(), dt));
            }
            let times = (0..coords[0].len()).map(|k| k as f64 * dt).collect();
            let points = (0..coords[0].len())
                .map(|k| plane.to_world(&Vector2::new(coords[0][k], coords[1][k])))
                .collect();
            (times, points, None)
        }
    };
    let native_end = native.last().copied().unwrap_or(0.0).max(1e-9);
    let times_s: Vec<f64> = native.iter().map(|t| slot.0 + t / native_end * duration).collect();
    let (_, from_aim) = placed(new_world_from_stitch, &p.start_pose);
    let (_, to_aim) = placed(new_world_from_stitch, &p.end_pose);
    let aims = native.iter().map(|t| from_aim.towards(&to_aim, t / native_end)).collect();
    let regenerated = NewPath {
        name: p.name.clone(),
        plane,
        times_s,
        points_m,
        aims,
        world_from_stitch: *new_world_from_stitch,
    };
    // The demonstration's own pace along the path: how far along it the hand was at each moment (the
    // speeds the solver stirs with are floored where the hand was at rest, which shifts the timing).
    let progress = demonstrated_progress(demo_path, p);
    if progress.len() < 2 {
        return Ok((regenerated, inst));
    }
    let scale = duration / (p.end_s - p.start_s).max(1e-9);
    let times_s = progress.iter().map(|(key, _)| slot.0 + (key.time_s - p.start_s) * scale).collect();
    let points_m = progress.iter().map(|(_, phase)| regenerated.time_at_phase(*phase).1).collect();
    let aims = progress.iter().map(|(key, _)| key_aim(new_world_from_stitch, key)).collect();
    Ok((NewPath { times_s, points_m, aims, ..regenerated }, inst))
}

/// `(demonstrated key, fraction of the path's length covered)` over the primitive's span: each
/// demonstrated path key projected onto the primitive's tremor-free path (searching forward from the
/// previous one, so loops that pass near themselves are told apart).
fn demonstrated_progress(path: &[PathKey], p: &TwoDPrimitive) -> Vec<(PathKey, f64)> {
    let n = p.path_m.len();
    if n < 2 {
        return Vec::new();
    }
    let mut s = vec![0.0];
    for w in p.path_m.windows(2) {
        s.push(s[s.len() - 1] + (Vector2::from(w[1]) - Vector2::from(w[0])).norm());
    }
    let total = s[n - 1];
    if total <= 0.0 {
        return Vec::new();
    }
    let origin = Vector3::from(p.plane.origin_m);
    let (ax, ay) = (Vector3::from(p.plane.axis_x), Vector3::from(p.plane.axis_y));
    // Look ahead at most 2 cm of path from the last match.
    let window = ((0.02 / p.step_m.max(1e-6)).ceil() as usize).max(2);
    let mut at = 0usize;
    let mut out = Vec::new();
    for key in path.iter().filter(|k| k.time_s >= p.start_s && k.time_s <= p.end_s) {
        let d = Vector3::from(key.position_m) - origin;
        let q = Vector2::new(d.dot(&ax), d.dot(&ay));
        let best = (at..(at + window).min(n))
            .min_by(|&i, &j| {
                (Vector2::from(p.path_m[i]) - q).norm().total_cmp(&(Vector2::from(p.path_m[j]) - q).norm())
            })
            .unwrap_or(at);
        at = best;
        out.push((*key, s[best] / total));
    }
    if let Some(last) = out.last_mut() {
        last.1 = 1.0;
    }
    if let Some(first) = out.first_mut() {
        first.1 = 0.0;
    }
    out
}

fn path_keys(track: &mut TrackKeys, path: &NewPath, period_s: f64, gap_speed_mps: f64) {
    let t0 = path.times_s[0];
    gap_move(track, t0, path.points_m[0], path.aims[0], gap_speed_mps);
    let mut next = t0;
    for (k, ((t, q), aim)) in path.times_s.iter().zip(&path.points_m).zip(&path.aims).enumerate() {
        if *t + 1e-9 < next && k + 1 != path.times_s.len() {
            continue;
        }
        next = t + period_s;
        track.key(*t, *q, *aim);
    }
}

fn sync_keys(
    track: &mut TrackKeys,
    p: &SynchronizedPrimitive,
    reference: &NewPath,
    gap_speed_mps: f64,
) -> Result<(), SynthesisError> {
    let axes = [reference.plane.axis_x, reference.plane.axis_y, reference.plane.normal()];
    let mut points = Vec::with_capacity(p.mapping.len());
    for sample in &p.mapping {
        let (t, r) = reference.time_at_phase(sample.phase);
        let offset =
            axes[0] * sample.offset_m[0] + axes[1] * sample.offset_m[1] + axes[2] * sample.offset_m[2];
        let aim = Aim::Frame(
            reference.world_from_stitch.rotation
                * pose_isometry(&Pose { position_m: [0.0; 3], quaternion_xyzw: sample.quaternion_xyzw })
                    .rotation,
        );
        points.push((t, r + offset, aim));
    }
    let Some(&(t0, first, first_aim)) = points.first() else {
        return Err(invalid(format!("{}.mapping", p.name), "empty"));
    };
    gap_move(track, t0, first, first_aim, gap_speed_mps);
    for (t, q, aim) in points {
        track.key(t, q, aim);
    }
    Ok(())
}

/// Synthesizes the skill of `kb` at `site` by `method` (fluid or DMP; the replay baseline is
/// [`super::replay()`]).
pub fn synthesize(
    kb: &KnowledgeBase,
    method: Method,
    site: &Site<'_>,
    settings: &PrimitiveSettings,
    obstacles: &mut ObstacleSource<'_>,
) -> Result<Synthesis, SynthesisError> {
    let schedule = Schedule::plan(kb, |p| duration_of(p, settings))?;
    let demo_world_from_stitch = pose_isometry(&kb.world_from_stitch);
    let world_from_stitch = site.new_world_from_stitch;
    let mut tracks: Vec<TrackKeys> = Vec::new();
    for (i, ip) in kb.instruments.iter().enumerate() {
        let arm: ArmName = ip
            .instrument
            .parse()
            .map_err(|e| invalid(format!("instruments[{i}].instrument"), format!("{e}")))?;
        let start = site
            .starts
            .iter()
            .find(|s| s.arm == arm)
            .ok_or_else(|| invalid("starts", format!("no start pose of the {arm} instrument")))?;
        let mut track = TrackKeys::new(
            arm,
            site.trocars.of(arm)?,
            start.world_from_tip.translation.vector,
            Aim::Frame(start.world_from_tip.rotation),
        );
        // The jaws as the demonstration moved them, outside force-controlled primitives (which open
        // them by their event).
        let force_spans: Vec<(f64, f64)> = ip
            .primitives
            .iter()
            .filter(|p| matches!(p, Primitive::Force(_)))
            .map(Primitive::span_s)
            .collect();
        for point in &ip.jaw {
            if force_spans.iter().any(|(a, b)| point.time_s > *a && point.time_s < *b) {
                continue;
            }
            track.jaw.push(JawKey {
                time_s: schedule.map_time(arm, point.time_s).max(0.0),
                jaw_rad: point.jaw_rad,
            });
        }
        tracks.push(track);
    }
    let mut order: Vec<&Primitive> = kb.instruments.iter().flat_map(|ip| &ip.primitives).collect();
    order.sort_by(|a, b| {
        let sa = schedule.slot(a.name()).map_or(0.0, |s| s.new_s.0);
        let sb = schedule.slot(b.name()).map_or(0.0, |s| s.new_s.0);
        let sync = |p: &Primitive| matches!(p, Primitive::Synchronized(_));
        sa.total_cmp(&sb).then(sync(a).cmp(&sync(b)))
    });
    let mut paths: Vec<NewPath> = Vec::new();
    let mut fluid = Vec::new();
    // Per track, the demonstration's time up to which it has been built.
    let mut cursor: Vec<f64> = vec![f64::NEG_INFINITY; tracks.len()];
    for p in order {
        let slot = schedule.slot(p.name()).ok_or_else(|| invalid(p.name(), "not scheduled"))?;
        let t = tracks
            .iter()
            .position(|t| t.arm == slot.instrument)
            .ok_or_else(|| invalid(p.name(), "no track for its instrument"))?;
        let track = &mut tracks[t];
        let path = &kb.instruments[t].path;
        // An instrument that waited in the demonstration until its first primitive waits where it is:
        // the scene put it there (the assist on the tail's end), and the demonstration's pose moved to
        // the new stitch is another one at a turned or tilted site (the trocar turns the shaft), where
        // going would drag what it holds.
        let waits = cursor[t] == f64::NEG_INFINITY && waited(path, slot.demo_s.0);
        if !waits {
            if cursor[t] == f64::NEG_INFINITY
                && let Some(first) = path.first()
            {
                // The track starts where the tip is, turned as the demonstration's first key, moved,
                // turns it: the way in (`super::prepend_approach`) makes that turn at its own pace
                // before the skill starts. Left to the skill's first keys, a turned or tilted site's
                // turn of tens of degrees would come within a tenth of a second, which the arm follows
                // joint by joint at full speed, its tip swinging centimetres out and back (enough to
                // tear the needle from the right's jaws).
                track.key(0.0, track.position_m, key_aim(&world_from_stitch, first));
            }
            transfer(
                track,
                path,
                (cursor[t], slot.demo_s.0),
                |x| schedule.map_time(slot.instrument, x),
                &world_from_stitch,
            );
        }
        cursor[t] = cursor[t].max(slot.demo_s.1);
        match p {
            Primitive::Linear(l) => linear_keys(track, l, path, slot.new_s, &world_from_stitch),
            Primitive::Force(f) => {
                force_keys(track, f, path, slot.new_s, &world_from_stitch, settings, site.reach)
            }
            Primitive::TwoD(t) => {
                // A winding goes round the jaws as the instrument that follows it can hold them.
                let aimed = winding_aim(kb, t, &world_from_stitch, site.trocars)? * world_from_stitch;
                let (path, inst) = two_d_path(
                    slot.instrument,
                    track,
                    t,
                    slot.new_s,
                    method,
                    &demo_world_from_stitch,
                    &aimed,
                    settings,
                    path,
                    obstacles,
                )?;
                path_keys(track, &path, settings.key_period_s, settings.gap_speed_mps);
                if let Some(inst) = inst {
                    fluid.push((t.name.clone(), inst));
                }
                paths.push(path);
            }
            Primitive::Synchronized(s) => {
                let reference = paths.iter().find(|q| q.name == s.reference).ok_or_else(|| {
                    invalid(format!("{}.reference", s.name), format!("'{}' was not made", s.reference))
                })?;
                sync_keys(track, s, reference, settings.gap_speed_mps)?;
            }
        }
    }
    // After its last primitive each instrument does what it did in the demonstration (the pulls
    // that cinch the knot, the release), going no further than it reaches.
    for (t, track) in tracks.iter_mut().enumerate() {
        let arm = track.arm;
        let start = track.poses_len();
        transfer(
            track,
            &kb.instruments[t].path,
            (cursor[t], f64::INFINITY),
            |x| schedule.map_time(arm, x),
            &world_from_stitch,
        );
        track.keep_within_reach(start, site.reach, REACH_MARGIN_M);
    }
    let skill = Skill {
        name: format!("{} ({}, from {})", kb.task, method, kb.demonstration.description),
        tracks: tracks.into_iter().map(TrackKeys::build).collect(),
    };
    skill.check().map_err(|e| invalid("skill", e.to_string()))?;
    Ok(Synthesis { skill, schedule, fluid })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Keys 10 cm along x, the tip turned about y by `turn(u)` of 90 degrees at `u` of the way.
    fn keys(turn: impl Fn(f64) -> f64) -> Vec<PathKey> {
        (0..=10)
            .map(|k| {
                let u = k as f64 / 10.0;
                let q = UnitQuaternion::from_axis_angle(
                    &Vector3::y_axis(),
                    turn(u) * std::f64::consts::FRAC_PI_2,
                );
                let c = q.quaternion();
                PathKey {
                    time_s: u,
                    position_m: [0.1 * u, 0.0, 0.0],
                    jaw_direction: (q * Vector3::z()).into(),
                    quaternion_xyzw: Some([c.i, c.j, c.k, c.w]),
                }
            })
            .collect()
    }

    /// A line turns the tip as the demonstration turned along its path (a fifth of the turn halfway when it
    /// turned late), and turns by length for keys without frames or with hardly a turn.
    #[test]
    fn a_line_turns_the_tip_as_the_demonstration_did_along_its_path() {
        // The demonstration turned late: a fifth of the turn over the first half of the way.
        let late = |u: f64| if u <= 0.5 { 0.4 * u } else { 0.2 + 1.6 * (u - 0.5) };
        let turn = demonstrated_turn(&keys(late), 0.0, 1.0);
        assert_eq!(turn.len(), 11);
        for (u, f) in &turn {
            assert!((f - late(*u)).abs() < 1e-9, "{u}: {f} against {}", late(*u));
        }
        assert!((turn_at(&turn, 0.25) - 0.1).abs() < 1e-9);
        // A line made with it: halfway along, a fifth of the turn (a turn by length would be half).
        let trocar = Vector3::new(0.0, 0.0, 1.0);
        let from = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 2.8);
        let to = from * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 1.0);
        let mut track = TrackKeys::new(ArmName::Left, trocar, Vector3::zeros(), Aim::Frame(from));
        let profile: Vec<ProfilePoint> =
            (0..=4).map(|k| ProfilePoint { s_m: 0.025 * k as f64, speed_mps: 0.1 }).collect();
        line(&mut track, &profile, &turn, 1.0, 1.0, Vector3::new(0.1, 0.0, 0.0), Aim::Frame(to));
        let built = track.build();
        let half =
            built.poses.iter().find(|k| (k.world_position_m[0] - 0.05).abs() < 1e-9).expect("a key halfway");
        let expected = from.try_slerp(&to, 0.2, 1e-9).unwrap();
        let knotlab_hw::skill::Orientation::Frame { quaternion_xyzw: [x, y, z, w] } = half.orientation else {
            panic!("a frame: {:?}", half.orientation)
        };
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        assert!(q.angle_to(&expected) < 1e-9, "{q:?}");
        // Keys without frames (a knowledge base before version 3), or hardly a turn: turned by length.
        let mut old = keys(late);
        old.iter_mut().for_each(|k| k.quaternion_xyzw = None);
        assert!(demonstrated_turn(&old, 0.0, 1.0).is_empty());
        assert!(demonstrated_turn(&keys(|u| 0.005 * u), 0.0, 1.0).is_empty());
        assert_eq!(turn_at(&[], 0.3), 0.3);
    }
}

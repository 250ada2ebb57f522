//! A scripted stress sequence for the scene, run headless by `knotlab sim`: from the task's start
//! condition the assist pulls the tail so that the thread slides through the stitch, the right
//! instrument drags the long end across the left instrument's shaft, then the assist lays the tail
//! across the long end. Meanwhile it
//! measures what can go wrong with a thread: stretch, tunnelling (through itself or a shaft), and
//! non-finite or exploding bodies.

use std::time::Instant;

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::profile::min_jerk;
use nalgebra::{Point3, Vector3};
use serde::Serialize;

use knotlab_sim::convert::to_na;
use knotlab_sim::tissue::Flap;
use knotlab_sim::tunnelling::{Capsule, TunnellingMonitor};
use knotlab_sim::world::SimWorld;

/// What the stress sequence measured.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StressReport {
    /// The largest gap of a thread joint seen, as a fraction of the segment length.
    pub max_stretch_ratio: f64,
    /// When it was seen, s.
    pub max_stretch_at_s: f64,
    /// Thread segments passing through another segment or an instrument shaft.
    pub tunnelling_events: usize,
    /// Of which through an instrument shaft.
    pub shaft_tunnelling_events: usize,
    /// When the first tunnelling event was seen, s.
    pub first_tunnelling_at_s: Option<f64>,
    /// Steps in which the thread touched an instrument (shaft, wrist or jaws).
    pub instrument_contact_steps: usize,
    /// Non-finite or exploding bodies (the run stops at the first).
    pub nan_events: usize,
    /// The health failure, if any.
    pub failure: Option<String>,
    /// Simulated seconds per wall-clock second of stepping.
    pub realtime_factor: f64,
    /// Steps taken.
    pub steps: u64,
    /// Rigid bodies in the scene.
    pub bodies: usize,
    /// Simulated time, s.
    pub simulated_s: f64,
    /// Wall-clock time of the stepping, s.
    pub wall_s: f64,
    /// Thread pulled through the stitch towards the tail's side, m.
    pub pulled_through_m: f64,
    /// Wound gap at the start and at the end, m.
    pub wound_gap_m: [f64; 2],
    /// Grasp slips.
    pub slips: usize,
    /// Grasp and stitch events, in order.
    pub events: Vec<String>,
    /// Targets the instruments could not reach (their step was skipped).
    pub unreachable_targets: usize,
    /// Why the first unreachable target was refused.
    pub first_unreachable: Option<String>,
}

/// One scripted move: from `at_s` to `until_s`, `arm`'s jaw centre goes (minimum jerk) from where it
/// is to `to_m` (tissue frame), with the jaw opening `jaw_rad` from the start of the move.
#[derive(Clone, Copy, Debug)]
struct Move {
    arm: ArmName,
    at_s: f64,
    until_s: f64,
    to_m: [f64; 3],
    jaw_rad: f64,
}

fn script(seconds: f64, world: &SimWorld) -> Vec<Move> {
    let t = |f: f64| f * seconds;
    let open = SimWorld::JAW_OPEN_RAD;
    let tail = world.config().start.tail_m;
    let mv =
        |arm, from: f64, to: f64, to_m, jaw_rad| Move { arm, at_s: t(from), until_s: t(to), to_m, jaw_rad };
    use ArmName::{Assist, Left, Right};
    vec![
        // The assist pulls the tail out and up: the thread slides through the stitch.
        mv(Assist, 0.0, 0.25, [tail[0], 0.05, 0.03], 0.0),
        // The left instrument comes down beside the long end, its shaft low over the pad.
        mv(Left, 0.0, 0.15, [0.03, -0.04, 0.03], open),
        mv(Left, 0.15, 0.25, [0.03, -0.04, -0.002], open),
        // The right instrument drags the long end across the left shaft, then the left leaves.
        mv(Right, 0.28, 0.55, [0.05, -0.015, 0.025], 0.0),
        mv(Left, 0.55, 0.65, [-0.03, 0.0, 0.05], open),
        // Then the assist lays the tail across the long end near the wound.
        mv(Assist, 0.70, 0.95, [0.02, -0.02, 0.012], 0.0),
    ]
}

/// Thread capsules and the instrument shafts as capsules (shafts last).
fn capsules(world: &SimWorld, shafts: &[rapier3d::prelude::ColliderHandle]) -> Vec<Capsule> {
    let mut caps = world.suture().capsules(world.physics(), world.config().thread.radius_m);
    for h in shafts {
        let collider = &world.physics().colliders[*h];
        if let Some(capsule) = collider.shape().as_capsule() {
            let pose = collider.position();
            caps.push(Capsule {
                a_m: to_na(pose.transform_point(capsule.segment.a)),
                b_m: to_na(pose.transform_point(capsule.segment.b)),
                radius_m: capsule.radius,
            });
        }
    }
    caps
}

/// The colliders of the three instrument shafts.
fn shaft_colliders(world: &SimWorld) -> Vec<rapier3d::prelude::ColliderHandle> {
    let mut out = Vec::new();
    for (i, link) in world.rig().tree.links.iter().enumerate() {
        if !link.name.ends_with("_shaft") || link.name.starts_with("camera") {
            continue;
        }
        if let Some(body) = world.link_body(i) {
            out.extend(world.physics().bodies[body].colliders().iter().copied());
        }
    }
    out
}

/// Runs the stress sequence for `seconds` of simulated time. `at_times_s` and `on_time` let the caller
/// take pictures as it goes.
pub fn run_stress(
    world: &mut SimWorld,
    seconds: f64,
    at_times_s: &[f64],
    on_time: &mut dyn FnMut(f64, &SimWorld),
) -> StressReport {
    let moves = script(seconds, world);
    let frame = world.tissue().world_from_tissue;
    let shafts = shaft_colliders(world);
    // The instruments' links, by name (what the suture touches is reported by link).
    let instrument_bodies: Vec<rapier3d::prelude::RigidBodyHandle> = world
        .arms()
        .iter()
        .filter(|a| a.name.carries_instrument())
        .flat_map(|a| a.instrument_bodies.iter().copied())
        .collect();
    let instrument_links: Vec<String> = (0..world.rig().tree.links.len())
        .filter(|&i| world.link_body(i).is_some_and(|b| instrument_bodies.contains(&b)))
        .map(|i| world.rig().tree.links[i].name.clone())
        .collect();
    let n_thread = world.suture().capsules(world.physics(), 0.0).len();
    let mut monitor = TunnellingMonitor::new(0.002);
    let mut shaft_monitor = TunnellingMonitor::new(0.004);
    let thread_pairs: Vec<(usize, usize)> =
        (0..n_thread).flat_map(|i| (i + 2..n_thread).map(move |j| (i, j))).collect();
    let shaft_pairs: Vec<(usize, usize)> =
        (0..n_thread).flat_map(|i| (0..shafts.len()).map(move |k| (i, n_thread + k))).collect();
    let mut starts: Vec<Option<Vector3<f64>>> = vec![None; moves.len()];
    let gap_start = world.wound_gap_m();
    let tail_side_start = world.stitch_arc_at_m(Flap::B);
    let mut pending: Vec<f64> = at_times_s.to_vec();
    pending.sort_by(f64::total_cmp);
    let mut pending = pending.into_iter().peekable();
    let mut report = StressReport {
        max_stretch_ratio: 0.0,
        max_stretch_at_s: 0.0,
        tunnelling_events: 0,
        shaft_tunnelling_events: 0,
        first_tunnelling_at_s: None,
        instrument_contact_steps: 0,
        nan_events: 0,
        failure: None,
        realtime_factor: 0.0,
        steps: 0,
        bodies: world.body_count(),
        simulated_s: 0.0,
        wall_s: 0.0,
        pulled_through_m: 0.0,
        wound_gap_m: [gap_start, gap_start],
        slips: 0,
        unreachable_targets: 0,
        first_unreachable: None,
        events: Vec::new(),
    };
    let dt = world.config().solver.dt_s;
    let steps = (seconds / dt).round() as u64;
    let clock = Instant::now();
    for _ in 0..steps {
        while let Some(at) = pending.peek() {
            if *at > world.time_s() + 0.5 * dt {
                break;
            }
            on_time(world.time_s(), world);
            pending.next();
        }
        let now = world.time_s();
        for (k, m) in moves.iter().enumerate() {
            if now < m.at_s || now > m.until_s + dt {
                continue;
            }
            // From where the jaws were last told to be (the links may lag behind).
            let commanded = world.rig().arm(m.arm).model.world_from_tip(&world.arm(m.arm).command);
            let here = (commanded * Point3::new(0.0, 0.0, -knotlab_sim::world::JAW_CENTRE_OFFSET_M)).coords;
            let from = *starts[k].get_or_insert(here);
            let to = (frame * Point3::from(Vector3::from(m.to_m))).coords;
            let s = min_jerk((now - m.at_s) / (m.until_s - m.at_s).max(dt));
            let target = from + (to - from) * s;
            match world.joints_for_jaw_centre(m.arm, &target) {
                Ok(mut joints) => {
                    joints.tool.jaw_rad = m.jaw_rad;
                    world.command(m.arm, joints);
                }
                Err(e) => {
                    report.unreachable_targets += 1;
                    report.first_unreachable.get_or_insert_with(|| format!("{} at {now:.3} s: {e}", m.arm));
                }
            }
        }
        match world.step() {
            Ok(()) => {}
            Err(e) => {
                report.nan_events += 1;
                report.failure = Some(e.to_string());
                break;
            }
        }
        report.steps += 1;
        let stretch = world.suture().max_stretch_ratio(world.physics());
        if stretch > report.max_stretch_ratio {
            report.max_stretch_ratio = stretch;
            report.max_stretch_at_s = world.time_s();
        }
        let caps = capsules(world, &shafts);
        report.tunnelling_events += monitor.update(&caps, thread_pairs.iter().copied());
        let through_shaft = shaft_monitor.update(&caps, shaft_pairs.iter().copied());
        report.tunnelling_events += through_shaft;
        report.shaft_tunnelling_events += through_shaft;
        if report.tunnelling_events > 0 && report.first_tunnelling_at_s.is_none() {
            report.first_tunnelling_at_s = Some(world.time_s());
        }
        let touching = world.thread_contacts().iter().any(|(_, link)| instrument_links.contains(link));
        report.instrument_contact_steps += usize::from(touching);
    }
    report.wall_s = clock.elapsed().as_secs_f64();
    report.simulated_s = report.steps as f64 * dt;
    report.realtime_factor = if report.wall_s > 0.0 { report.simulated_s / report.wall_s } else { 0.0 };
    report.wound_gap_m[1] = world.wound_gap_m();
    let tail_side_end = world.stitch_arc_at_m(Flap::B);
    if let (Some(a), Some(b)) = (tail_side_start, tail_side_end) {
        report.pulled_through_m = a - b;
    }
    report.slips =
        world.events().iter().filter(|e| matches!(e, knotlab_sim::grasp::GraspEvent::Slipped { .. })).count();
    report.events = world.events().iter().map(|e| format!("{e:?}")).collect();
    report.events.extend(world.suture().stitch_events().iter().map(|e| format!("{e:?}")));
    for at in pending {
        if at <= world.time_s() + 0.5 * dt {
            on_time(world.time_s(), world);
        }
    }
    report
}

//! The scripted expert's plan: the instrument tie of a surgeon's knot, as one Skill for the controller.
//!
//! Everything is placed in the stitch (tissue) frame of the scene (x along the wound, y across it
//! towards the tail's flap, z out of the tissue) and turned into world-frame keys, so the same plan
//! ties at any stitch. The sequence is the canonical task of `scenarios/patterns/knot_tying.toml`:
//! L1 to the winding point (the right takes up the long end meanwhile), the left's jaws close; R2 winds
//! the long end twice around them; the assist presents the tail in front of the left's jaws, which
//! open; L3 to the tail (over it and, when the left looks, L4 down onto it), close; the assist lets go
//! and retreats (A1); the left draws the tail up and back over its flap (L5, L6) with the right going
//! along (R3, R4), running the knot down onto the wound; then the ends are pulled apart until the set
//! force (R5 the right's pull) and let go.

use knotlab_hw::rig::ArmName;
use knotlab_hw::skill::{ForceAction, ForceEvent, Skill};
use knotlab_sim::tissue::Flap;
use knotlab_sim::world::{JAW_CENTRE_OFFSET_M, SimWorld, trocar_of};
use nalgebra::{Isometry3, Point3, Unit, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::clearance::{Circle, Wrist, clear_of_wrist};
use super::geometry::{LeftFetch, SecondThrow, TieGeometry};
use super::motion::{Follow, Path, TrackBuilder, Tremor};
use super::tail::{tail_ahead_of_jaws, tail_between_knot_and_left, tail_from_its_end, tail_length_to};
use super::turn_thread::along_within_long_end;

/// How a human performance varies from run to run.
#[derive(Clone, Debug, PartialEq)]
pub struct Variation {
    /// Every duration is multiplied by this.
    pub slowness: f64,
    /// The pauses between primitives, s.
    pub pauses_s: [f64; 6],
    /// Tremor of each instrument (left, right, assist).
    pub tremor: [Tremor; 3],
    /// Where the expert puts the winding point, off the nominal one, m.
    pub winding_offset_m: Vector3<f64>,
}

impl Variation {
    /// A machine-like performance: nominal speed, 0.25 s pauses, no tremor.
    pub fn none() -> Self {
        Self {
            slowness: 1.0,
            pauses_s: [0.25; 6],
            tremor: [Tremor::none(), Tremor::none(), Tremor::none()],
            winding_offset_m: Vector3::zeros(),
        }
    }

    /// A human one drawn from `seed`: speed within +-15 %, pauses of 0.15-0.4 s, a 0.1 mm tremor,
    /// the winding point within 1 mm.
    pub fn human(seed: u64) -> Self {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let slowness = rng.random_range(0.85..1.15);
        let pauses_s = std::array::from_fn(|_| rng.random_range(0.15..0.4));
        let mut tremor = || Tremor {
            amplitude_m: 1e-4,
            sines: std::array::from_fn(|_| {
                std::array::from_fn(|_| {
                    (rng.random_range(8.0..12.0), rng.random_range(0.0..std::f64::consts::TAU))
                })
            }),
        };
        let tremor = [tremor(), tremor(), tremor()];
        let winding_offset_m = Vector3::from_fn(|_, _| rng.random_range(-0.001..0.001));
        Self { slowness, pauses_s, tremor, winding_offset_m }
    }
}

/// The assist's last stretch onto the tail it takes for the second throw, along its jaws, m.
const TAKE_APPROACH_M: f64 = 0.012;

/// How far the left rises from where it let go of the tail before it goes to take it back, m.
const RETAKE_CLEARANCE_M: f64 = 0.025;

/// `track` takes the tail at `tail_m`, its jaws along its shaft and its hinge along the tail
/// (`tail_dir`), so the tail runs between them.
fn take_tail(
    track: &mut TrackBuilder,
    world: &SimWorld,
    tail_m: Vector3<f64>,
    tail_dir: Vector3<f64>,
    d: &impl Fn(f64) -> f64,
    pause: &[f64],
) {
    let jaws = (tail_m - trocar_of(world.config(), track.arm())).normalize();
    let hinge = Unit::new_normalize(tail_dir - jaws * tail_dir.dot(&jaws));
    let frame = nalgebra::Rotation3::from_basis_unchecked(&[hinge.cross(&jaws), hinge.into_inner(), jaws]);
    track.go_framing(Path::To(tail_m - jaws * TAKE_APPROACH_M), d(1.5), frame);
    track.go(Path::To(tail_m), d(0.8));
    track.wait_until(track.time_s() + pause[3]);
    track.jaw(0.0, d(0.3));
    track.wait_until(track.time_s() + d(0.3) + 0.1);
}

/// The jaw centre of an arm as its links stand (world frame, m).
fn jaw_centre_m(world: &SimWorld, arm: ArmName) -> Vector3<f64> {
    (world.world_from_tip(arm) * Point3::new(0.0, 0.0, -JAW_CENTRE_OFFSET_M)).coords
}

/// The radius of the left's wrist link, m (`None` if the robot model has no capsule for it).
fn wrist_radius_m(world: &SimWorld) -> Option<f64> {
    world.rig().link_radius_m(ArmName::Left, "wrist")
}

/// Which throw a plan ties, and what the instruments hold when it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stage {
    /// The first, from the task's start condition; `keep_hold`: the pulls hold at the end instead of
    /// letting go (a second throw follows).
    First { keep_hold: bool },
    /// Before a second throw wound on the assist's jaws: the assist takes the tail this far from its
    /// free end (then draws it to `to_m`, stitch frame, if set), and the left lets go and rises clear
    /// ([`plan_tail_hand_over`]).
    HandOver { from_end_m: f64, to_m: Option<[f64; 3]> },
    /// The rest of a throw, planned from the world once the left's jaws are over the tail (a fetch
    /// that [`LeftFetch::looks`]): the left closes on the tail where it lies, and the throw goes on
    /// as [`Stage::First`] with `keep_hold`, or, with `second` set, as that [`Stage::Second`].
    Take { keep_hold: bool, second: Option<SecondStart> },
    /// The second, after the first: the left holds the tail and the right the long end, pulled apart
    /// (or, after a [`Stage::HandOver`], the assist holds the tail).
    Second { start: SecondStart },
}

/// How the second throw begins.
#[derive(Clone, Copy, Debug, PartialEq)]
enum SecondStart {
    /// The left keeps the tail it holds; the long end is wound round its closed jaws.
    LeftKeepsTail,
    /// The assist takes the tail from the left, which lets go.
    AssistTakes(TailHold),
    /// The assist holds the tail by its end: the left takes it back this far (along the thread) from
    /// its end, the assist lets go, and the two swap parts for the rest of the throw
    /// ([`SecondThrow::left_retakes_from_end_m`]).
    LeftRetakes { from_end_m: f64 },
}

/// Where the assist takes the tail from the left before the second throw.
#[derive(Clone, Copy, Debug, PartialEq)]
enum TailHold {
    /// This fraction of the way from the knot to the left's jaws.
    Along(f64),
    /// This far from the tail's free end, then drawn to `to_m` (stitch frame) once the left has let
    /// go, if `taut` is set no further from the entry point than that share of the tail it holds.
    FromEnd { from_end_m: f64, to_m: Option<[f64; 3]>, taut: Option<f64> },
}

/// The plan as a skill, for the world as it stands (its start condition): the first throw, and all
/// of the knot unless `geometry` asks for a second throw ([`plan_second_throw`]).
pub fn plan_instrument_tie(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Skill {
    plan_throw(world, geometry, variation, Stage::First { keep_hold: geometry.second_throw.is_some() })
}

/// How far off the jaws' line the tail they look at may lie for them to go straight onto it, m.
const OFF_LINE_M: f64 = 0.002;

/// A plan of part of the knot, from the world as it stands (`None`: the geometry asks for none).
pub type Planner = fn(&SimWorld, &TieGeometry, &Variation) -> Option<Skill>;

/// The rest of the first throw once the left's jaws are over the tail (`None` unless the left
/// fetches the tail and [`LeftFetch::looks`]): it closes on the tail where it lies now.
pub fn plan_tail_take(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Option<Skill> {
    geometry.fetch().filter(|f| f.looks)?;
    let stage = Stage::Take { keep_hold: geometry.second_throw.is_some(), second: None };
    Some(plan_throw(world, geometry, variation, stage))
}

/// The second throw, planned from the world the first throw left (`None` if `geometry` asks for
/// none). If its fetch [`LeftFetch::looks`], the plan stops with the left's jaws over the tail and
/// [`plan_second_tail_take`] plans the rest.
pub fn plan_second_throw(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Option<Skill> {
    let second = geometry.second_throw.as_ref()?;
    let stage = Stage::Second { start: second_start(second) };
    Some(plan_throw(world, &second.applied_to(geometry), variation, stage))
}

/// The rest of the second throw once the left's jaws are over the tail (`None` unless its fetch
/// [`LeftFetch::looks`]): it closes on the tail where it lies now.
pub fn plan_second_tail_take(
    world: &SimWorld,
    geometry: &TieGeometry,
    variation: &Variation,
) -> Option<Skill> {
    let second = geometry.second_throw.as_ref()?;
    let throw = second.applied_to(geometry);
    throw.fetch().filter(|f| f.looks)?;
    let start = second_start(second);
    looks_at_take(Stage::Second { start }).then_some(())?;
    let stage = Stage::Take { keep_hold: false, second: Some(start) };
    Some(plan_throw(world, &throw, variation, stage))
}

/// Whether a fetch that looks stops this stage's plan over the tail: the first throw's, and a
/// second throw's where the left takes the tail from the assist as in the first (where the left
/// and the assist swap parts, the left presents the tail rather than fetching it).
fn looks_at_take(stage: Stage) -> bool {
    matches!(stage, Stage::First { .. } | Stage::Second { start: SecondStart::AssistTakes(_) })
}

/// How `second` begins: who holds the tail, and who takes it.
fn second_start(second: &SecondThrow) -> SecondStart {
    match (second.left_keeps_tail, second.tail_hold_from_end_m, second.left_retakes_from_end_m) {
        (true, _, _) => SecondStart::LeftKeepsTail,
        (false, _, Some(from_end_m)) => SecondStart::LeftRetakes { from_end_m },
        (false, Some(from_end_m), None) => SecondStart::AssistTakes(TailHold::FromEnd {
            from_end_m,
            to_m: second.tail_held_to_m,
            taut: second.tail_held_taut,
        }),
        (false, None, None) => SecondStart::AssistTakes(TailHold::Along(second.tail_hold_along)),
    }
}

/// Before a second throw wound on the assist's jaws (`left_retakes_from_end_m` set; `None`
/// otherwise): the assist takes the tail by its end from the left, which lets go and rises clear.
/// [`plan_second_throw`] then goes on from the world this leaves, as a surgeon looks where the tail
/// lies before taking it back.
pub fn plan_tail_hand_over(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Option<Skill> {
    let second = geometry.second_throw.as_ref()?;
    second.left_retakes_from_end_m?;
    let from_end_m = second.tail_hold_from_end_m?;
    let stage = Stage::HandOver { from_end_m, to_m: second.tail_held_to_m };
    Some(plan_throw(world, &second.applied_to(geometry), variation, stage))
}

fn plan_throw(world: &SimWorld, geometry: &TieGeometry, variation: &Variation, stage: Stage) -> Skill {
    let world_from_stitch: Isometry3<f64> = world.tissue().world_from_tissue;
    let at = |p: [f64; 3]| (world_from_stitch * Point3::from(Vector3::from(p))).coords;
    let dir = |d: [f64; 3]| world_from_stitch.rotation * Vector3::from(d);
    let open = SimWorld::JAW_OPEN_RAD;
    let key_period_s = 0.01;
    let d = |s: f64| s * variation.slowness;
    let builder = |arm: ArmName, jaw: f64, tremor: &Tremor| {
        let trocar_m = trocar_of(world.config(), arm);
        let mut b =
            TrackBuilder::new(arm, jaw_centre_m(world, arm), jaw, key_period_s, tremor.clone(), trocar_m);
        b.follow(Follow {
            model: world.rig().arm(arm).model,
            trocar_m,
            joints: world.arm(arm).command,
            speed_fraction: geometry.speed_fraction,
        });
        b
    };
    let second = matches!(stage, Stage::Second { .. });
    let left_keeps_tail = matches!(stage, Stage::Second { start: SecondStart::LeftKeepsTail });
    // Who holds the tail as the plan starts: the left after the first throw, the assist after a
    // hand-over.
    let assist_holds = matches!(stage, Stage::Second { start: SecondStart::LeftRetakes { .. } });
    let left_holds = matches!(stage, Stage::HandOver { .. }) || (second && !assist_holds);
    let jaw = |holds: bool| if holds { 0.0 } else { open };
    let left_jaw =
        if matches!(stage, Stage::Take { .. }) { geometry.take_tail_jaw_rad } else { jaw(left_holds) };
    let mut left = builder(ArmName::Left, left_jaw, &variation.tremor[0]);
    let mut right = builder(ArmName::Right, 0.0, &variation.tremor[1]);
    let first = matches!(stage, Stage::First { .. } | Stage::Take { .. });
    let assist_jaw = if first { 0.0 } else { jaw(assist_holds) };
    let mut assist = builder(ArmName::Assist, assist_jaw, &variation.tremor[2]);
    let pause = &variation.pauses_s;
    let up = world_from_stitch.rotation * Vector3::z();
    if !matches!(stage, Stage::First { .. }) {
        // Every instrument goes on as it stands (the first throw left the jaws pointing their ways).
        for track in [&mut left, &mut right, &mut assist] {
            track.hold_as_it_stands();
        }
    }
    if let Stage::Take { keep_hold, second } = stage {
        // Onto the tail's point nearest the line of the jaws, ahead of them, as it lies now.
        let jaws_to = left.jaw_direction();
        let from = left.position_m();
        let stop_short_m = geometry.fetch().map_or(0.0, |f| f.stop_short_m);
        if let Some((tail_m, tail_dir)) = tail_ahead_of_jaws(world, &from, &jaws_to) {
            let framed = geometry.fetch().is_some_and(LeftFetch::holds_frame);
            let square = geometry.fetch().is_some_and(|f| f.hinge_along_tail);
            // Taking the tail square to it, a tail found well off the jaws' line (the part under
            // them lying low) is gone over first and come onto along the jaws, not sideways through
            // it (session 45); without `hinge_along_tail`, the straight descent.
            let off_line_m = (tail_m - from - jaws_to * (tail_m - from).dot(&jaws_to)).norm();
            let approach_m = geometry.fetch().map_or(0.0, |f| f.approach_m);
            let mut ways = vec![];
            if square && off_line_m > OFF_LINE_M {
                ways.push(tail_m - jaws_to * (stop_short_m + approach_m));
            }
            ways.push(tail_m - jaws_to * stop_short_m);
            let beside = geometry.fetch().and_then(|f| f.right_beside_m).map(dir);
            let follows = geometry.fetch().map_or(0.0, |f| f.right_follows);
            for to_m in ways {
                let (to, from_s, left_from) = (Path::To(to_m), left.time_s(), left.position_m());
                match left.held_frame().filter(|_| framed) {
                    // The jaws roll on the way, their hinge along the tail where it lies, so that it
                    // runs between them: aimed at the line from the entry to the assist, the hinge lay
                    // across a slack tail and the jaws closed beside it (session 45).
                    Some(held) => {
                        let hinge_now = held * Vector3::y();
                        let hinge = Unit::try_new(tail_dir - jaws_to * tail_dir.dot(&jaws_to), 1e-9)
                            .map(|h| if h.dot(&hinge_now) >= 0.0 { h } else { -h })
                            .unwrap_or_else(|| Unit::new_normalize(hinge_now));
                        let frame = nalgebra::Rotation3::from_basis_unchecked(&[
                            hinge.cross(&jaws_to),
                            hinge.into_inner(),
                            jaws_to,
                        ]);
                        left.go_framing(to, d(0.8), frame);
                    }
                    None => left.go(to, d(0.8)),
                }
                // The right keeps beside the left's jaws (the turn's thread), if told; or follows
                // their descent by the fetch's share, as it followed them to the tail. The turns lie
                // round both instruments' jaws: left standing (or stopped 8 mm over the tissue), the
                // right drew them taut as the left went down (seeds 0 and 19: both gauges 100-530 N,
                // equal and opposite; on seed 19 the assist's grip on the tail tore; session 49).
                if let Some(offset_m) = beside {
                    right.wait_until(from_s);
                    right.go(Path::To(to_m + offset_m), left.time_s() - from_s);
                } else if follows > 0.0 {
                    right.wait_until(from_s);
                    right.go(
                        Path::To(right.position_m() + (to_m - left_from) * follows),
                        left.time_s() - from_s,
                    );
                }
            }
        }
        left.wait_until(left.time_s() + pause[4]);
        left.jaw(0.0, d(0.3));
        left.wait_until(left.time_s() + d(0.3) + 0.1);
        let stage = match second {
            Some(start) => Stage::Second { start },
            None => Stage::First { keep_hold },
        };
        return finish_throw(world, geometry, variation, stage, [left, right, assist]);
    }
    if let Stage::HandOver { from_end_m, to_m } = stage {
        // The assist takes the tail near its end, the left lets go and rises clear, and the assist
        // draws the tail by its end to `to_m`.
        if let Some((tail_m, tail_dir)) = tail_from_its_end(world, from_end_m) {
            take_tail(&mut assist, world, tail_m, tail_dir, &d, pause);
        }
        left.wait_until(assist.time_s() + pause[5]);
        left.jaw(open, d(0.2));
        left.wait_until(left.time_s() + d(0.2) + pause[0]);
        left.go(Path::To(left.position_m() + up * RETAKE_CLEARANCE_M), d(0.8));
        if let Some(to_m) = to_m {
            assist.wait_until(left.time_s());
            assist.go(Path::To(at(to_m)), d(1.5));
        }
        let end_s = left.time_s().max(assist.time_s()) + pause[5];
        for track in [&mut left, &mut right, &mut assist] {
            track.wait_until(end_s);
        }
        return Skill {
            name: "instrument tie: surgeon's knot, the tail handed to the assist".into(),
            tracks: vec![left.build(), right.build(), assist.build()],
        };
    }
    if let Stage::Second { start } = stage {
        match start {
            SecondStart::LeftKeepsTail => left.wait_until(assist.time_s() + pause[5]),
            SecondStart::AssistTakes(tail_hold) => {
                // The assist takes the tail between the knot and the left's jaws, or near its free
                // end (the tail between its open jaws, along their hinge), then the left lets go.
                let taken = match tail_hold {
                    TailHold::Along(along) => tail_between_knot_and_left(world, along),
                    TailHold::FromEnd { from_end_m, .. } => tail_from_its_end(world, from_end_m),
                };
                if let Some((tail_m, tail_dir)) = taken {
                    take_tail(&mut assist, world, tail_m, tail_dir, &d, pause);
                }
                left.wait_until(assist.time_s() + pause[5]);
                left.jaw(open, d(0.2));
                left.wait_until(left.time_s() + d(0.2) + pause[0]);
                if let TailHold::FromEnd { to_m: Some(to_m), from_end_m, taut } = tail_hold {
                    // The assist draws the tail by its end to where the left will take it, while the
                    // left goes to the winding point; with `tail_held_taut`, no further from the entry
                    // point than that share of the tail it holds (the first throw leaves more or
                    // less of it: drawn to a fixed point, a short tail tore the assist's grip).
                    let mut to = at(to_m);
                    if let Some(share) = taut {
                        let entry = world.tissue().hole_m(world.physics(), Flap::A);
                        if let Some(length_m) = tail_length_to(world, from_end_m) {
                            let out = to - entry;
                            to = entry + out * (share * length_m / out.norm()).min(1.0);
                        }
                    }
                    assist.wait_until(left.time_s());
                    assist.go(Path::To(to), d(1.5));
                }
            }
            SecondStart::LeftRetakes { from_end_m } => {
                // The assist holds the tail by its end: the left takes it back `from_end_m` from its
                // end, where it lies now, its jaws square to the tail (along its shaft they would
                // come down the tail onto the assist's jaws) and its hinge along it; the assist lets
                // go; and from here on the assist winds and takes the tail, the left presents it.
                if let Some((retake, along)) = tail_from_its_end(world, from_end_m) {
                    let shaft = (retake - trocar_of(world.config(), left.arm())).normalize();
                    let jaws = (shaft - along * shaft.dot(&along)).try_normalize(1e-6).unwrap_or(-up);
                    let hinge = Unit::try_new(along - jaws * along.dot(&jaws), 1e-9)
                        .unwrap_or_else(|| Unit::new_normalize(world_from_stitch.rotation * Vector3::x()));
                    let frame = nalgebra::Rotation3::from_basis_unchecked(&[
                        hinge.cross(&jaws),
                        hinge.into_inner(),
                        jaws,
                    ]);
                    left.go_framing(Path::To(retake - jaws * TAKE_APPROACH_M), d(1.5), frame);
                    left.go(Path::To(retake), d(0.8));
                    left.wait_until(left.time_s() + pause[3]);
                    left.jaw(0.0, d(0.3));
                    left.wait_until(left.time_s() + d(0.3) + 0.1);
                }
                assist.wait_until(left.time_s());
                assist.jaw(open, d(0.2));
                assist.wait_until(assist.time_s() + d(0.2) + pause[5]);
                std::mem::swap(&mut left, &mut assist);
                left.wait_until(assist.time_s());
            }
        }
        right.wait_until(left.time_s());
        assist.wait_until(left.time_s());
    }

    // L1: the left to the winding point; the right takes up the long end meanwhile, to where the
    // winding starts: the long end then runs from the stitch past the left's jaws.
    let winding_point = at(geometry.winding_point_m) + variation.winding_offset_m;
    // The left's jaws point at the right's trocar: the right's shaft then circles them at a distance.
    let jaws = match geometry.left_jaw_direction {
        Some(d) => Unit::new_normalize(dir(d)),
        None => Unit::new_normalize(trocar_of(world.config(), ArmName::Right) - winding_point),
    };
    let axis = jaws;
    let across = |d: Vector3<f64>| Unit::try_new(d - axis.into_inner() * d.dot(&axis), 1e-9);
    // The winding starts opposite the exit point, so that the long end already lies across the
    // left's jaws, a little before the point where it would run straight over them.
    let exit = world.tissue().hole_m(world.physics(), Flap::B);
    // (With the exit on the jaw axis, any side will do: the one at right angles to `towards`.)
    let towards = across(dir(geometry.winding_towards))
        .or_else(|| across(Vector3::x()))
        .unwrap_or_else(|| Unit::new_normalize(Vector3::y()));
    let over = across(winding_point - exit).unwrap_or_else(|| Unit::new_normalize(axis.cross(&towards)));
    // The turns' sense: right-handed about the axis that moves `over` towards `towards`.
    let axis = if axis.cross(&over).dot(&towards) >= 0.0 { axis } else { -axis };
    let start_dir =
        nalgebra::Rotation3::from_axis_angle(&axis, -geometry.winding_lead_rad) * over.into_inner();
    let start_dir = Unit::new_normalize(start_dir);
    let centre = winding_point - jaws.into_inner() * geometry.winding_behind_m;
    // The jaws' hinge lies across the line from the entry point to where the tail will be held, so
    // that the tail then runs between the open jaws.
    let entry = world.tissue().hole_m(world.physics(), Flap::A);
    let tail_point = winding_point + jaws.into_inner() * geometry.tail_ahead_m;
    let hinge = across(tail_point - entry).unwrap_or(towards);
    let left_frame = nalgebra::Rotation3::from_basis_unchecked(&[
        hinge.cross(&jaws),
        hinge.into_inner(),
        jaws.into_inner(),
    ]);
    let l1_s = left.time_s();
    left.go_framing(Path::To(winding_point), d(2.0), left_frame);
    right.wait_until(l1_s);
    let winding_start = centre + start_dir.into_inner() * geometry.winding_radius_m;
    // The circle moved towards the jaws' tips until the thread in the right's jaws, going round it,
    // keeps clear of the left's wrist (at most to the jaw centre).
    // `axis` is the jaws' or their reverse (the turns' sense): the advance is along the jaws.
    let advance_m = geometry.winding_pitch_m * axis.dot(&jaws).signum();
    let turns = geometry.winding_turns;
    let planned = Circle { centre_m: centre, axis, start_m: winding_start, turns, pitch_m: advance_m };
    let circle = match (left.wrist_m(), wrist_radius_m(world)) {
        (Some((pitch_m, yaw_m)), Some(radius_m)) => {
            let trocar_m = trocar_of(world.config(), ArmName::Left);
            let wrist = Wrist { pitch_m, yaw_m, trocar_m, radius_m };
            let thread_m = world.config().thread.radius_m;
            clear_of_wrist(&planned, &wrist, thread_m, &jaws, geometry.winding_behind_m.max(0.0)).0
        }
        _ => planned,
    };
    let (centre, winding_start) = (circle.centre_m, circle.start_m);
    let shaft = (centre - trocar_of(world.config(), ArmName::Right)).normalize();
    match across(shaft).filter(|_| geometry.right_jaws_across_winding > 0.0) {
        Some(jaws_across) => {
            let jaws = shaft.lerp(&jaws_across, geometry.right_jaws_across_winding);
            right.go_turning(Path::To(winding_start), d(2.0), jaws)
        }
        None => right.go(Path::To(winding_start), d(2.0)),
    }
    left.wait_until(left.time_s() + pause[0]);
    if left_keeps_tail {
        left.wait_until(left.time_s() + pause[1]);
    } else {
        left.jaw(geometry.winding_jaw_rad, d(0.3));
        left.wait_until(left.time_s() + d(0.3) + pause[1]);
    }

    // R2: the right winds the long end around the left's jaws, after the left is there.
    right.wait_until(left.time_s() + pause[2]);
    right.go(
        Path::Around { centre_m: centre, axis, turns: geometry.winding_turns, pitch_m: advance_m },
        d(geometry.winding_s),
    );
    // Then it gives a little thread back, so the coils loosen enough to slide along the jaws.
    right.wait_until(right.time_s() + pause[2]);
    let slack_dir = (centre - right.position_m()).normalize();
    // ... and draws the coils back along the left's jaws, towards their hinge.
    let back = -jaws.into_inner() * geometry.coils_back_m;
    right.go(Path::To(right.position_m() + slack_dir * geometry.loosen_m + back), d(0.5));
    let wound_s = right.time_s();
    // Meanwhile the assist gives the winding thread, moving the tail towards the entry point.
    let tail_now = assist.position_m();
    assist.wait_until(left.time_s() + pause[2]);
    assist
        .go(Path::To(tail_now + (entry - tail_now) * geometry.tail_give_fraction), wound_s - assist.time_s());
    if let Some(to_m) = geometry.tail_brought_to_m {
        // Its wrist straightening on the way (held as they took the tail far out, the jaws needed
        // the wrist at its limits on the way back: the move slowed and jerked, and the tail was lost).
        let to = at(to_m);
        assist.go_pointing(Path::To(to), d(1.5), to - trocar_of(world.config(), ArmName::Assist));
    }

    if left_keeps_tail {
        // The left holds the tail already: the turn lies round its jaws behind the tail.
        left.wait_until(wound_s + pause[3]);
    } else if let Some(fetch) = geometry.fetch() {
        // The left takes its coils to the tail where the assist holds it (the right follows, so the
        // coils stay as they are): to a point behind the tail along the new jaw direction, then onto
        // the tail, jaws open.
        let tail_hold = assist.position_m();
        let jaws_to = dir(fetch.jaw_direction).normalize();
        // No further out than the long end reaches with the turns round the jaws.
        let (left_from, right_from) = (left.position_m(), right.position_m());
        let right_at = |jaws_m: &Vector3<f64>| match fetch.right_beside_m {
            Some(offset) => jaws_m + dir(offset),
            None => right_from + (jaws_m - jaws_to * fetch.approach_m - left_from) * fetch.right_follows,
        };
        let along = match world.stitch_arc_at_m(Flap::B) {
            Some(long_end_m) => along_within_long_end(
                fetch.along_tail,
                long_end_m,
                geometry.winding_turns,
                &exit,
                &entry,
                &tail_hold,
                right_at,
            ),
            None => fetch.along_tail,
        };
        let on_tail = entry + (tail_hold - entry) * along;
        let behind = on_tail - jaws_to * fetch.approach_m;
        left.wait_until(wound_s.max(assist.time_s()) + pause[3]);
        left.jaw(geometry.take_tail_jaw_rad, d(0.3));
        left.wait_until(left.time_s() + d(0.3));
        let shift = behind - left.position_m();
        // Where the right goes meanwhile: beside the left's jaws, or a share of their shift.
        let right_fetching = |from: Vector3<f64>| match fetch.right_beside_m {
            Some(offset) => behind + dir(offset),
            None => from + shift * fetch.right_follows,
        };
        let relocate_from = left.time_s();
        if fetch.holds_frame() {
            // The whole tip frame turns (the hinge along the tail, so that it runs between the open
            // jaws; no roll left to the solver, which may flip it half way and jerk the coils), and
            // the right turns with it about the left's jaws: the coils keep their shape.
            // (A tail along the new jaw direction leaves the hinge free: any side across them.)
            let across_to = |d: Vector3<f64>| Unit::try_new(d - jaws_to * d.dot(&jaws_to), 1e-9);
            let hinge = across_to(tail_hold - entry)
                .or_else(|| across_to(Vector3::x()))
                .unwrap_or_else(|| Unit::new_normalize(Vector3::y()));
            let (left_from, frame_from, jaws_from) =
                (left.position_m(), left.held_frame(), left.jaw_direction());
            let y_now = frame_from.map_or_else(Vector3::y, |q| q * Vector3::y());
            // Of the two hinge senses the one nearer the present, unless the wrist cannot turn so.
            let hinge = if hinge.dot(&y_now) >= 0.0 { hinge } else { -hinge };
            let frame_with = |hinge: Unit<Vector3<f64>>| {
                nalgebra::Rotation3::from_basis_unchecked(&[
                    hinge.cross(&jaws_to),
                    hinge.into_inner(),
                    jaws_to,
                ])
            };
            let frame = [frame_with(hinge), frame_with(-hinge)]
                .into_iter()
                .find(|f| left.reaches_framing(behind, *f))
                .unwrap_or_else(|| frame_with(hinge));
            left.go_framing(Path::To(behind), d(1.5), frame);
            right.wait_until(relocate_from);
            if fetch.as_one_body {
                // The right turns with the jaws' direction only: turned about the jaws as well, it
                // would go round them and wind or unwind the coils.
                let rotation = nalgebra::UnitQuaternion::rotation_between(&jaws_from, &jaws_to)
                    .unwrap_or_else(nalgebra::UnitQuaternion::identity);
                let carried = Path::Carried { pivot_from_m: left_from, pivot_to_m: behind, rotation };
                right.go(carried, left.time_s() - relocate_from);
            } else {
                right.go(Path::To(right_fetching(right.position_m())), left.time_s() - relocate_from);
            }
        } else {
            left.go_pointing(Path::To(behind), d(1.5), jaws_to);
            right.wait_until(relocate_from);
            right.go(Path::To(right_fetching(right.position_m())), left.time_s() - relocate_from);
        }
        left.wait_until(left.time_s() + pause[4]);
        if fetch.looks && looks_at_take(stage) {
            // The left looks where the tail lies before it closes on it: the rest from there
            // ([`plan_tail_take`]).
            let end_s = left.time_s().max(right.time_s()).max(assist.time_s());
            for track in [&mut left, &mut right, &mut assist] {
                track.wait_until(end_s);
            }
            let name = if second {
                "instrument tie: surgeon's knot, second throw, the turn to the tail"
            } else {
                "instrument tie: surgeon's knot, the coils to the tail"
            };
            return Skill { name: name.into(), tracks: vec![left.build(), right.build(), assist.build()] };
        }
        // The jaws' centre stops short of the tail, so the tail lies towards their tips, ahead of
        // the coils: every coil then passes over it when the jaws draw back.
        let (onto, onto_s) = (on_tail - jaws_to * fetch.stop_short_m, left.time_s());
        left.go(Path::To(onto), d(0.8));
        if let Some(offset) = fetch.right_beside_m {
            right.wait_until(onto_s);
            right.go(Path::To(onto + dir(offset)), left.time_s() - onto_s);
        }
        left.wait_until(left.time_s() + pause[4]);
        left.jaw(0.0, d(0.3));
        left.wait_until(left.time_s() + d(0.3) + 0.1);
    } else {
        // The assist presents the tail ahead of the left's jaws; the left opens, goes there, closes.
        assist.wait_until(wound_s + pause[3]);
        // The tail swung taut about the entry point (so it neither sags onto the tissue nor catches on
        // the flap) until it runs straight through the point ahead of the left's jaws; the assist holds it
        // there, beyond that point (at least `tail_beyond_m`).
        let radius = ((assist.position_m() - entry).norm() + geometry.tail_tension_m)
            .max((tail_point - entry).norm() + geometry.tail_beyond_m);
        let outward = (assist.position_m() - entry).normalize();
        let towards = (tail_point - entry).normalize();
        if let Some(offered_m) = geometry.tail_end_offered_m {
            // Beside the point ahead of the left's jaws along their hinge, on the side away from the
            // knot; the assist's hinge along the left's, towards the tail's end (it took the tail with
            // its hinge that way), so the rest of the tail runs from its jaws through the left's.
            let side = if (tail_point + hinge.into_inner() * offered_m - entry).norm()
                >= (tail_point - hinge.into_inner() * offered_m - entry).norm()
            {
                hinge.into_inner()
            } else {
                -hinge.into_inner()
            };
            let offer_m = tail_point + side * offered_m;
            let shaft = (offer_m - trocar_of(world.config(), assist.arm())).normalize();
            let assist_jaws = (shaft - side * shaft.dot(&side)).try_normalize(1e-9).unwrap_or(shaft);
            let frame =
                nalgebra::Rotation3::from_basis_unchecked(&[side.cross(&assist_jaws), side, assist_jaws]);
            assist.go_framing(Path::To(offer_m - assist_jaws * TAKE_APPROACH_M), d(1.5), frame);
            assist.go(Path::To(offer_m), d(0.8));
        } else if !geometry.tail_via_m.is_empty() {
            // A route given in the stitch frame, then up to the hold.
            for p in &geometry.tail_via_m {
                match geometry.assist_jaw_direction {
                    Some(j) => assist.go_pointing(Path::To(at(*p)), d(0.8), dir(j)),
                    None => assist.go(Path::To(at(*p)), d(0.8)),
                }
            }
            assist.go(Path::To(entry + towards * radius), d(0.8));
        } else {
            assist.go(Path::To(entry + outward * radius), d(0.4));
            // Through a direction leaning off the shortest arc, where the assist's wrist is far from its
            // singular pose.
            let via = (outward + towards).normalize() + dir(geometry.tail_swing_lean);
            for (from, to) in [(outward, via.normalize()), (via.normalize(), towards)] {
                if let Some(axis) = Unit::try_new(from.cross(&to), 1e-9) {
                    let turns = from.dot(&to).clamp(-1.0, 1.0).acos() / std::f64::consts::TAU;
                    assist.go(Path::Around { centre_m: entry, axis, turns, pitch_m: 0.0 }, d(0.8));
                }
            }
        }
        left.wait_until(wound_s + pause[3]);
        left.jaw(geometry.take_tail_jaw_rad, d(0.3));
        left.wait_until(assist.time_s());
        left.go(Path::To(tail_point - jaws.into_inner() * geometry.tail_take_short_m), d(1.0));
        left.wait_until(left.time_s() + pause[4]);
        left.jaw(0.0, d(0.3));
        left.wait_until(left.time_s() + d(0.3) + 0.1);
    }
    finish_throw(world, geometry, variation, stage, [left, right, assist])
}

/// The name of the pulls' force events (each pull's `fires_with` names the other's).
const SET_FORCE: &str = "set force";

/// The rest of a throw once the left has closed on the tail: the assist lets go and retreats, the
/// left draws the tail out of its coils, both run the knot down and pull to the set force.
fn finish_throw(
    world: &SimWorld,
    geometry: &TieGeometry,
    variation: &Variation,
    stage: Stage,
    [mut left, mut right, mut assist]: [TrackBuilder; 3],
) -> Skill {
    let world_from_stitch: Isometry3<f64> = world.tissue().world_from_tissue;
    let at = |p: [f64; 3]| (world_from_stitch * Point3::from(Vector3::from(p))).coords;
    let open = SimWorld::JAW_OPEN_RAD;
    let d = |s: f64| s * variation.slowness;
    let pause = &variation.pauses_s;
    let second = matches!(stage, Stage::Second { .. });
    let grasped_s = left.time_s();

    // The assist lets go and retreats (A1).
    assist.wait_until(grasped_s);
    assist.jaw(open, d(0.2));
    assist.wait_until(grasped_s + d(0.2) + pause[5]);
    assist.go(Path::To(at(geometry.assist_retreat_m)), d(1.2));

    // The pulls (L5, L6 and R3-R5 of the shipped pattern). First the left draws the tail back out of
    // its coils, along its jaws, while the right follows a little so that the coils stay loose and
    // slide off the jaws onto the tail; then both run the knot down onto the wound and pull the ends
    // apart until the set force, and let go.
    let mut draw_s = assist.time_s().max(grasped_s + d(0.4));
    if !geometry.right_before_draw_m.is_empty() {
        right.wait_until(draw_s);
        for p in &geometry.right_before_draw_m {
            right.go(Path::To(at(*p)), d(0.8));
        }
        draw_s = right.time_s() + pause[4];
    }
    left.wait_until(draw_s);
    right.wait_until(draw_s);
    let first_s = left.time_s();
    let draw = -left.jaw_direction() * geometry.draw_back_m;
    // The wrist straightens a little on the way (a bent wrist drawn back runs into its limit).
    let drawn_to = left.position_m() + draw;
    let shaft = (drawn_to - trocar_of(world.config(), left.arm())).normalize();
    let relaxed = left.jaw_direction().lerp(&shaft, geometry.draw_relax);
    if geometry.fetch().is_some_and(LeftFetch::holds_frame) {
        // The left holds a whole frame since the fetch: it turns that frame, the roll going with it
        // (handed to the solver, the roll flipped: the jaws jumped at 400-530 mm/s and tore the
        // needle out of the right's jaws).
        left.go_turning(Path::To(drawn_to), d(geometry.draw_s), relaxed);
    } else {
        left.go_pointing(Path::To(drawn_to), d(geometry.draw_s), relaxed);
    }
    let right_to = match geometry.right_draws_to_m {
        Some(p) => at(p),
        None => right.position_m() + draw * geometry.right_follows_draw,
    };
    right.go(Path::To(right_to), left.time_s() - first_s);
    // The run-down: the knot onto the wound.
    let run_down_s = left.time_s() + pause[4];
    left.wait_until(run_down_s);
    for via in &geometry.left_run_down_via_m {
        left.go(Path::To(at(*via)), d(geometry.run_down_s));
    }
    right.wait_until(run_down_s);
    for via in &geometry.right_run_down_via_m {
        right.go(Path::To(at(*via)), d(geometry.run_down_s));
    }
    for (track, to) in [(&mut left, geometry.left_run_down_to_m), (&mut right, geometry.right_run_down_to_m)]
    {
        track.wait_until(run_down_s);
        track.go(Path::To(at(to)), d(geometry.run_down_s));
    }
    // A run-down stopped at its force holds there to the end: going on to the pulls from the
    // run-down's end would drag what stopped it.
    let hold_from_run_down = |track: &mut TrackBuilder| {
        if let Some(threshold_n) = geometry.run_down_force_n {
            track.event(ForceEvent {
                name: "run-down force".into(),
                from_s: run_down_s,
                until_s: track.time_s(),
                threshold_n,
                sustain_s: 0.0,
                fires_with: None,
                action: ForceAction::Hold,
            });
        }
    };
    let pull_s = left.time_s().max(right.time_s()) + 0.3;
    let tail_pull_force_n = geometry.tail_pull_force_n.unwrap_or(geometry.pull_force_n);
    // Each pull to its target, or on past it within reach (`pull_on_m`), at the same speed.
    let pull = |track: &mut TrackBuilder, to: [f64; 3]| {
        track.wait_until(pull_s);
        let (from, to) = (track.position_m(), at(to));
        // On level with the tissue: the pulls come down to it, and going on down they pressed the
        // instrument into it (7 N, read as the set force).
        let normal = world_from_stitch.rotation * Vector3::z();
        let way = (to - from) - normal * normal.dot(&(to - from));
        let beyond = to + way.try_normalize(1e-12).unwrap_or_default() * geometry.pull_on_m;
        let end = track.reach_towards(beyond);
        let to_target_m = (to - from).norm();
        let stretch = if to_target_m > 1e-9 { (end - from).norm() / to_target_m } else { 1.0 };
        // The jaws keep pointing as they do: turning them along the shaft on the way passes the
        // straight wrist, where the arm crawls and the pull never reaches its force.
        track.go(Path::To(end), d(geometry.pull_s) * stretch.max(0.1));
    };
    let fires_with = geometry.pulls_stop_together.then(|| SET_FORCE.to_owned());
    if let Stage::First { keep_hold: true } = stage {
        // The pulls hold the knot cinched until the second throw: both stop at the set force (or
        // where they were going) and hold there together to the end of this plan; or the left then
        // lets go of the tail where it stopped, its hold lasting until its jaws are open, and the
        // right holds on to the needle and the long end.
        let left_lets_go = geometry.second_throw.as_ref().is_some_and(|s| s.left_lets_go_first);
        pull(&mut left, geometry.left_pull_to_m);
        pull(&mut right, geometry.right_pull_to_m);
        let held_s = left.time_s().max(right.time_s()) + 1.0;
        let end_s = if left_lets_go { held_s + d(0.2) + 0.3 } else { held_s };
        for (track, threshold_n) in [(&mut left, tail_pull_force_n), (&mut right, geometry.pull_force_n)] {
            track.event(ForceEvent {
                name: SET_FORCE.into(),
                from_s: pull_s + d(0.5),
                until_s: end_s,
                threshold_n,
                sustain_s: geometry.pull_force_sustain_s,
                fires_with: fires_with.clone(),
                action: ForceAction::Hold,
            });
            track.wait_until(held_s);
            hold_from_run_down(track);
        }
        if left_lets_go {
            left.jaw(open.max(geometry.take_tail_jaw_rad), d(0.2));
        }
        for track in [&mut left, &mut right, &mut assist] {
            track.wait_until(end_s);
        }
        return Skill {
            name: "instrument tie: surgeon's knot, first throw".into(),
            tracks: vec![left.build(), right.build(), assist.build()],
        };
    }
    // The left lets go of the tail past the angle its jaws took it at (which may be as wide as they
    // were opened to take it: jaws opened less still squeeze it, and the grip held through the
    // holding test; session 44).
    let left_let_go = open.max(geometry.take_tail_jaw_rad);
    let pulls = [
        (geometry.left_pull_to_m, tail_pull_force_n, left_let_go),
        (geometry.right_pull_to_m, geometry.pull_force_n, open),
    ];
    pull(&mut left, pulls[0].0);
    pull(&mut right, pulls[1].0);
    // Both let go together, a second after the later pull's end, whether or not the set force was
    // reached: a pull sent on within reach may run longer than the other (ended at its own time, the
    // left let go of the tail while the right was still drawing the long end's slack, session 48).
    let release_s = left.time_s().max(right.time_s()) + 1.0;
    for (track, (_, threshold_n, let_go)) in [&mut left, &mut right].into_iter().zip(pulls) {
        // The hold ends as the jaws start to open, or, with `hold_through_release`, once they are
        // open: ended before, the arm goes on towards where the pull was headed as it lets go.
        let hold_until_s = if geometry.hold_through_release { release_s + d(0.2) + 0.3 } else { release_s };
        track.event(ForceEvent {
            name: SET_FORCE.into(),
            from_s: pull_s + d(0.5),
            until_s: hold_until_s,
            threshold_n,
            sustain_s: geometry.pull_force_sustain_s,
            fires_with: fires_with.clone(),
            action: if geometry.hold_at_force {
                ForceAction::Hold
            } else {
                ForceAction::OpenJaw { jaw_rad: let_go }
            },
        });
        track.wait_until(release_s);
        track.jaw(let_go, d(0.2));
        track.wait_until(track.time_s() + d(0.2) + 0.3);
        hold_from_run_down(track);
    }
    assist.wait_until(left.time_s());
    let name = if second {
        "instrument tie: surgeon's knot, second throw"
    } else {
        "instrument tie: surgeon's knot"
    };
    Skill { name: name.into(), tracks: vec![left.build(), right.build(), assist.build()] }
}

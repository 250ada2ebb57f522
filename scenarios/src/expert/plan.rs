//! The scripted expert's plan: the instrument tie of a surgeon's knot, as Skills for the controller.
//!
//! Everything is placed in the stitch (tissue) frame of the scene (x along the wound, y across it
//! towards the tail's flap, z out of the tissue) and turned into world-frame keys, so the same plan
//! ties at any stitch. A throw is a sequence of phases (`expert/phases/`), the canonical task of
//! `scenarios/patterns/knot_tying.toml`: L1 to the winding point (the right takes up the long end
//! meanwhile), the left's jaws close; R2 winds the long end twice around them; the assist presents
//! the tail in front of the left's jaws, which open; L3 to the tail (over it and, when the left looks,
//! L4 down onto it), close; the assist lets go and retreats (A1); the left draws the tail up and back
//! over its flap (L5, L6) with the right going along (R3, R4), running the knot down onto the wound;
//! then the ends are pulled apart until the set force (R5 the right's pull) and let go. Which phases
//! a plan holds depends on its stage: where in the knot it starts and what the instruments hold.

use knotlab_hw::skill::Skill;
use knotlab_sim::world::SimWorld;

use super::geometry::{SecondThrow, TieGeometry};
use super::phases::approach::Winding;
use super::phases::approach::approach;
use super::phases::assist_lets_go::assist_lets_go;
use super::phases::draw::draw;
use super::phases::fetch::{close_on_tail, fetch};
use super::phases::hand_over::hand_over;
use super::phases::present::present;
use super::phases::pull::{pull_and_hold, pull_and_let_go};
use super::phases::run_down::run_down;
use super::phases::second_start::{SecondStart, second_start};
use super::phases::take_as_it_lies::take_as_it_lies;
use super::phases::wind::{Wound, wind};
use super::phases::{Hands, Setting};
use super::variation::Variation;

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
    /// The rest of the first throw once the right has wound the long end keeping its tension
    /// ([`TieGeometry::winding_give_force_n`]), planned from the world as the wind left it: the right's
    /// tip is where it gave to, not on its circle. The left fetches the tail (to the look, if it
    /// looks: [`Stage::Take`] follows), and the throw goes on as [`Stage::First`] with `keep_hold`.
    Wound { keep_hold: bool },
    /// The rest of a throw, planned from the world once the left's jaws are over the tail (a fetch
    /// that [`super::LeftFetch::looks`]): the left closes on the tail where it lies, and the throw
    /// goes on as [`Stage::First`] with `keep_hold`, or, with `second` set, as that [`Stage::Second`].
    Take { keep_hold: bool, second: Option<SecondStart> },
    /// The second, after the first: the left holds the tail and the right the long end, pulled apart
    /// (or, after a [`Stage::HandOver`], the assist holds the tail).
    Second { start: SecondStart },
}

impl Stage {
    /// The jaws (left, right, assist) as the plan starts, rad: closed on what each holds, open
    /// otherwise; the left's as they were opened to take the tail in [`Stage::Take`].
    fn jaws_at_start(self, geometry: &TieGeometry) -> [f64; 3] {
        let open = SimWorld::JAW_OPEN_RAD;
        let second = matches!(self, Stage::Second { .. });
        // Who holds the tail as the plan starts: the left after the first throw, the assist after
        // a hand-over.
        let assist_holds = matches!(self, Stage::Second { start: SecondStart::LeftRetakes { .. } });
        let left_holds = matches!(self, Stage::HandOver { .. }) || (second && !assist_holds);
        let jaw = |holds: bool| if holds { 0.0 } else { open };
        let left = match self {
            Stage::Take { .. } => geometry.take_tail_jaw_rad,
            Stage::Wound { .. } => geometry.winding_jaw_rad,
            _ => jaw(left_holds),
        };
        let first = matches!(self, Stage::First { .. } | Stage::Take { .. } | Stage::Wound { .. });
        let assist = if first { 0.0 } else { jaw(assist_holds) };
        [left, 0.0, assist]
    }

    /// Whether a fetch that looks stops this stage's plan over the tail: the first throw's, and a
    /// second throw's where the left takes the tail from the assist as in the first (where the left
    /// and the assist swap parts, the left presents the tail rather than fetching it).
    fn looks_at_take(self) -> bool {
        matches!(
            self,
            Stage::First { .. } | Stage::Wound { .. } | Stage::Second { start: SecondStart::AssistTakes(_) }
        )
    }
}

/// The plan as a skill, for the world as it stands (its start condition): the first throw, and all
/// of the knot unless `geometry` asks for a second throw ([`plan_second_throw`]).
pub fn plan_instrument_tie(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Skill {
    plan_throw(world, geometry, variation, Stage::First { keep_hold: geometry.second_throw.is_some() })
}

/// A plan of part of the knot, from the world as it stands (`None`: the geometry asks for none).
pub type Planner = fn(&SimWorld, &TieGeometry, &Variation) -> Option<Skill>;

/// The rest of the first throw once the right has wound the long end keeping its tension (`None`
/// unless [`TieGeometry::winding_give_force_n`] is set and the left fetches the tail): from the
/// world the wind left.
pub fn plan_after_wind(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Option<Skill> {
    geometry.winding_give_force_n?;
    geometry.fetch()?;
    let stage = Stage::Wound { keep_hold: geometry.second_throw.is_some() };
    Some(plan_throw(world, geometry, variation, stage))
}

/// The rest of the first throw once the left's jaws are over the tail (`None` unless the left
/// fetches the tail and [`super::LeftFetch::looks`]): it closes on the tail where it lies now.
pub fn plan_tail_take(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Option<Skill> {
    geometry.fetch().filter(|f| f.looks)?;
    let stage = Stage::Take { keep_hold: geometry.second_throw.is_some(), second: None };
    Some(plan_throw(world, geometry, variation, stage))
}

/// The second throw, planned from the world the first throw left (`None` if `geometry` asks for
/// none). If its fetch [`super::LeftFetch::looks`], the plan stops with the left's jaws over the
/// tail and [`plan_second_tail_take`] plans the rest.
pub fn plan_second_throw(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Option<Skill> {
    let second = geometry.second_throw.as_ref()?;
    let stage = Stage::Second { start: SecondStart::of(second) };
    Some(plan_throw(world, &second.applied_to(geometry), variation, stage))
}

/// The rest of the second throw once the left's jaws are over the tail (`None` unless its fetch
/// [`super::LeftFetch::looks`]): it closes on the tail where it lies now.
pub fn plan_second_tail_take(
    world: &SimWorld,
    geometry: &TieGeometry,
    variation: &Variation,
) -> Option<Skill> {
    let second = geometry.second_throw.as_ref()?;
    let throw = second.applied_to(geometry);
    throw.fetch().filter(|f| f.looks)?;
    let start = SecondStart::of(second);
    Stage::Second { start }.looks_at_take().then_some(())?;
    let stage = Stage::Take { keep_hold: false, second: Some(start) };
    Some(plan_throw(world, &throw, variation, stage))
}

/// Before a second throw wound on the assist's jaws (`left_retakes_from_end_m` set; `None`
/// otherwise): the assist takes the tail by its end from the left, which lets go and rises clear.
/// [`plan_second_throw`] then goes on from the world this leaves, as a surgeon looks where the tail
/// lies before taking it back.
pub fn plan_tail_hand_over(world: &SimWorld, geometry: &TieGeometry, variation: &Variation) -> Option<Skill> {
    let second: &SecondThrow = geometry.second_throw.as_ref()?;
    second.left_retakes_from_end_m?;
    let from_end_m = second.tail_hold_from_end_m?;
    let stage = Stage::HandOver { from_end_m, to_m: second.tail_held_to_m };
    Some(plan_throw(world, &second.applied_to(geometry), variation, stage))
}

/// A stage's plan: its phases, one after another.
fn plan_throw(world: &SimWorld, geometry: &TieGeometry, variation: &Variation, stage: Stage) -> Skill {
    let s = Setting::new(world, geometry, variation);
    // Every instrument goes on as it stands after the first plan (the first throw left the jaws
    // pointing their ways).
    let mut hands = Hands::start(&s, stage.jaws_at_start(geometry), !matches!(stage, Stage::First { .. }));
    let start = match stage {
        Stage::Take { keep_hold, second } => {
            take_as_it_lies(&s, &mut hands);
            let stage = match second {
                Some(start) => Stage::Second { start },
                None => Stage::First { keep_hold },
            };
            return finish_throw(&s, hands, stage);
        }
        Stage::HandOver { from_end_m, to_m } => {
            hand_over(&s, &mut hands, from_end_m, to_m);
            return hands.skill("instrument tie: surgeon's knot, the tail handed to the assist");
        }
        Stage::Wound { keep_hold } => {
            // The tension was kept to the wind's end only: kept on while the left fetches the tail,
            // the right drew the coils off its jaws.
            return fetch_or_present(&s, hands, &Wound::done(), None, Stage::First { keep_hold }, stage);
        }
        Stage::First { .. } => None,
        Stage::Second { start } => Some(start),
    };
    if let Some(start) = start {
        second_start(&s, &mut hands, start);
    }
    let left_keeps_tail = start == Some(SecondStart::LeftKeepsTail);
    let winding = approach(&s, &mut hands, (!left_keeps_tail).then_some(geometry.winding_jaw_rad));
    let wound = wind(&s, &mut hands, &winding);
    if left_keeps_tail {
        // The left holds the tail already: the turn lies round its jaws behind the tail.
        hands.left.wait_until(wound.wound_s + s.pause(3));
        wound.keep_tension(&s, &mut hands, wound.wound_s + geometry.winding_give_after_s);
        return finish_throw(&s, hands, stage);
    }
    if geometry.winding_give_force_n.is_some()
        && geometry.fetch().is_some()
        && matches!(stage, Stage::First { .. })
    {
        // The right's tip is where it gave to: the rest is planned from there ([`Stage::Wound`]).
        hands.wait_until(hands.latest_s());
        let end_s = hands.latest_s();
        wound.keep_tension(&s, &mut hands, end_s);
        return hands.skill("instrument tie: surgeon's knot, the long end wound");
    }
    fetch_or_present(&s, hands, &wound, Some(&winding), stage, stage)
}

/// Once the coils are wound (at `wound_s`): the left fetches the tail (stopping over it, if it
/// looks, where `looking` [`Stage::looks_at_take`]) or the assist presents it at the `winding`
/// (needs the winding as the approach placed it); then the rest of the throw as `stage`. Where the
/// right keeps the long end's tension while it winds ([`wind::Wound::keep_tension`]), it does so
/// to the plan's end if it stops at the look, or for `winding_give_after_s` after the wind.
fn fetch_or_present(
    s: &Setting,
    mut hands: Hands,
    wound: &Wound,
    winding: Option<&Winding>,
    stage: Stage,
    looking: Stage,
) -> Skill {
    let (geometry, wound_s) = (s.geometry, wound.wound_s);
    if let Some(left_fetch) = geometry.fetch() {
        let on_tail = fetch(s, &mut hands, wound_s, left_fetch);
        if left_fetch.looks && looking.looks_at_take() {
            // The left looks where the tail lies before it closes on it: the rest from there
            // ([`plan_tail_take`]).
            hands.wait_until(hands.latest_s());
            let end_s = hands.latest_s();
            wound.keep_tension(s, &mut hands, end_s);
            return hands.skill(if matches!(stage, Stage::Second { .. }) {
                "instrument tie: surgeon's knot, second throw, the turn to the tail"
            } else {
                "instrument tie: surgeon's knot, the coils to the tail"
            });
        }
        close_on_tail(s, &mut hands, on_tail, left_fetch);
    } else if let Some(winding) = winding {
        present(s, &mut hands, winding, wound_s);
    }
    wound.keep_tension(s, &mut hands, wound_s + geometry.winding_give_after_s);
    finish_throw(s, hands, stage)
}

/// The rest of a throw once the left has closed on the tail: the assist lets go and retreats, the
/// left draws the tail out of its coils, both run the knot down and pull to the set force, and hold
/// there (a second throw follows) or let go.
fn finish_throw(s: &Setting, mut hands: Hands, stage: Stage) -> Skill {
    let grasped_s = assist_lets_go(s, &mut hands);
    draw(s, &mut hands, grasped_s);
    let run_down_s = run_down(s, &mut hands);
    match stage {
        Stage::First { keep_hold: true } => {
            pull_and_hold(s, &mut hands, run_down_s);
            hands.skill("instrument tie: surgeon's knot, first throw")
        }
        Stage::Second { .. } => {
            pull_and_let_go(s, &mut hands, run_down_s);
            hands.skill("instrument tie: surgeon's knot, second throw")
        }
        _ => {
            pull_and_let_go(s, &mut hands, run_down_s);
            hands.skill("instrument tie: surgeon's knot")
        }
    }
}

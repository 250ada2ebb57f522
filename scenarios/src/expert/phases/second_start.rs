//! How a second throw begins: who holds the tail as it starts, and who takes it.

use knotlab_sim::tissue::Flap;
use nalgebra::{Unit, Vector3};

use super::take_tail::take_tail;
use super::{Hands, Setting, TAKE_APPROACH_M};
use crate::expert::geometry::SecondThrow;
use crate::expert::motion::Path;
use crate::expert::tail::{tail_between_knot_and_left, tail_from_its_end, tail_length_to};

/// How the second throw begins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum SecondStart {
    /// The left keeps the tail it holds; the long end is wound round its closed jaws.
    LeftKeepsTail,
    /// The assist takes the tail from the left, which lets go.
    AssistTakes(TailHold),
    /// The assist holds the tail by its end: the left takes it back this far (along the thread) from
    /// its end, the assist lets go, and the two swap parts for the rest of the throw
    /// ([`SecondThrow::left_retakes_from_end_m`]).
    LeftRetakes { from_end_m: f64 },
}

impl SecondStart {
    /// How `second` begins.
    pub fn of(second: &SecondThrow) -> Self {
        match (second.left_keeps_tail, second.tail_hold_from_end_m, second.left_retakes_from_end_m) {
            (true, _, _) => Self::LeftKeepsTail,
            (false, _, Some(from_end_m)) => Self::LeftRetakes { from_end_m },
            (false, Some(from_end_m), None) => Self::AssistTakes(TailHold::FromEnd {
                from_end_m,
                to_m: second.tail_held_to_m,
                taut: second.tail_held_taut,
            }),
            (false, None, None) => Self::AssistTakes(TailHold::Along(second.tail_hold_along)),
        }
    }
}

/// Where the assist takes the tail from the left before the second throw.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum TailHold {
    /// This fraction of the way from the knot to the left's jaws.
    Along(f64),
    /// This far from the tail's free end, then drawn to `to_m` (stitch frame) once the left has let
    /// go, if `taut` is set no further from the entry point than that share of the tail it holds.
    FromEnd { from_end_m: f64, to_m: Option<[f64; 3]>, taut: Option<f64> },
}

/// The second throw's first moves, as `start` says, ending with every instrument waiting for the
/// left (after [`SecondStart::LeftRetakes`], the instrument that now plays the left).
pub(crate) fn second_start(s: &Setting, hands: &mut Hands, start: SecondStart) {
    match start {
        SecondStart::LeftKeepsTail => {
            let assist_s = hands.assist.time_s();
            hands.left.wait_until(assist_s + s.pause(5));
        }
        SecondStart::AssistTakes(tail_hold) => assist_takes(s, hands, tail_hold),
        SecondStart::LeftRetakes { from_end_m } => left_retakes(s, hands, from_end_m),
    }
    let left_s = hands.left.time_s();
    hands.right.wait_until(left_s);
    hands.assist.wait_until(left_s);
}

/// The assist takes the tail between the knot and the left's jaws, or near its free end (the tail
/// between its open jaws, along their hinge), then the left lets go.
fn assist_takes(s: &Setting, hands: &mut Hands, tail_hold: TailHold) {
    let Hands { left, assist, .. } = hands;
    let taken = match tail_hold {
        TailHold::Along(along) => tail_between_knot_and_left(s.world, along),
        TailHold::FromEnd { from_end_m, .. } => tail_from_its_end(s.world, from_end_m),
    };
    if let Some((tail_m, tail_dir)) = taken {
        take_tail(assist, s, tail_m, tail_dir);
    }
    left.wait_until(assist.time_s() + s.pause(5));
    left.jaw(s.open(), s.d(0.2));
    left.wait_until(left.time_s() + s.d(0.2) + s.pause(0));
    if let TailHold::FromEnd { to_m: Some(to_m), from_end_m, taut } = tail_hold {
        // The assist draws the tail by its end to where the left will take it, while the left goes
        // to the winding point; with `tail_held_taut`, no further from the entry point than that
        // share of the tail it holds (the first throw leaves more or less of it: drawn to a fixed
        // point, a short tail tore the assist's grip).
        let mut to = s.at(to_m);
        if let Some(share) = taut {
            let entry = s.world.tissue().hole_m(s.world.physics(), Flap::A);
            if let Some(length_m) = tail_length_to(s.world, from_end_m) {
                let out = to - entry;
                to = entry + out * (share * length_m / out.norm()).min(1.0);
            }
        }
        assist.wait_until(left.time_s());
        assist.go(Path::To(to), s.d(1.5));
    }
}

/// The assist holds the tail by its end: the left takes it back `from_end_m` from its end, where it
/// lies now, its jaws square to the tail (along its shaft they would come down the tail onto the
/// assist's jaws) and its hinge along it; the assist lets go; and from here on the assist winds and
/// takes the tail, the left presents it.
fn left_retakes(s: &Setting, hands: &mut Hands, from_end_m: f64) {
    let Hands { left, assist, .. } = hands;
    if let Some((retake, along)) = tail_from_its_end(s.world, from_end_m) {
        let shaft = (retake - s.trocar_m(left.arm())).normalize();
        let jaws = (shaft - along * shaft.dot(&along)).try_normalize(1e-6).unwrap_or(-s.up());
        let hinge = Unit::try_new(along - jaws * along.dot(&jaws), 1e-9)
            .unwrap_or_else(|| Unit::new_normalize(s.world_from_stitch.rotation * Vector3::x()));
        let frame =
            nalgebra::Rotation3::from_basis_unchecked(&[hinge.cross(&jaws), hinge.into_inner(), jaws]);
        left.go_framing(Path::To(retake - jaws * TAKE_APPROACH_M), s.d(1.5), frame);
        left.go(Path::To(retake), s.d(0.8));
        left.wait_until(left.time_s() + s.pause(3));
        left.jaw(0.0, s.d(0.3));
        left.wait_until(left.time_s() + s.d(0.3) + 0.1);
    }
    assist.wait_until(left.time_s());
    assist.jaw(s.open(), s.d(0.2));
    assist.wait_until(assist.time_s() + s.d(0.2) + s.pause(5));
    std::mem::swap(left, assist);
    left.wait_until(assist.time_s());
}

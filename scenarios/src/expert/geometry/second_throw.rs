//! The second throw of the surgeon's knot: one turn the other way, laid on the first. A first throw
//! alone cannot hold once the instruments let go (`lab/tests/integration/throw_holds_the_loop_only_while_its_ends_are_held.rs`);
//! two throws can (`lab/tests/integration/square_knot_holds_its_free_ends_let_go.rs`). The expert plans it from
//! the world the first throw left, as a surgeon looks before the next move: the assist takes the tail
//! between the knot and the left's jaws, the left lets go of it, and the throw goes as the first
//! ([`super::super::plan`]) with its own winding and pulls; or, with `left_retakes_from_end_m`, it is wound
//! on the assist's jaws instead, the left presenting the tail.

use super::{LeftFetch, TieGeometry};

/// Where the second throw differs from the first (stitch frame, m; the rest as the first throw).
#[derive(Clone, Debug, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct SecondThrow {
    /// The assist takes the tail this fraction of the way from the knot to the left's jaws.
    pub tail_hold_along: f64,
    /// ... or, if set, this far (along the thread) from the tail's free end, m: the left then takes
    /// the tail next to the assist's jaws, near its end, so that only a short free end has to pass
    /// through the turn as the left draws back (taken mid-tail, the turn closes round a bight of it).
    pub tail_hold_from_end_m: Option<f64>,
    /// Once the left has let go, the assist draws the tail it holds to here (stitch frame); `None`:
    /// it stays where it took it.
    pub tail_held_to_m: Option<[f64; 3]>,
    /// ... but no further from the entry point than this share of the thread between the entry and
    /// the assist's jaws (the first throw leaves a longer or shorter tail: drawn to a fixed point, a
    /// short one tore the assist's grip, 34 N); `None`: to `tail_held_to_m` itself.
    pub tail_held_taut: Option<f64>,
    /// Once the right has wound, the assist brings the tail here (stitch frame) before the left
    /// fetches it ([`TieGeometry::tail_brought_to_m`]); `None`: as the first throw.
    pub tail_brought_to_m: Option<[f64; 3]>,
    /// The left lets go of the tail once the first throw's pulls are done, the right holding on: the
    /// double throw, cinched, holds by itself, and the assist then takes the tail where it lies (held
    /// taut by the left through the hand-over, the tail tore out of the left's jaws or the assist's,
    /// 15-78 N).
    pub left_lets_go_first: bool,
    /// If set, the assist and the left swap parts for the rest of the throw: once the assist holds
    /// the tail by its end (`tail_hold_from_end_m`; drawn to `tail_held_to_m` if set), the left
    /// takes it back this far (along the thread) from its free end and the assist lets go; then the
    /// long end is wound round the assist's jaws, the left presents the tail and the assist takes
    /// it and draws it through, m.
    /// The assist's jaws can point where the left's cannot (along -x, from its trocar on the other
    /// side), so the turn can be wound as the mirror image of one wound on the left's jaws. (That
    /// does not make the throw's mirror image, the other hand: the first knot, where both legs
    /// start, is not mirrored.)
    pub left_retakes_from_end_m: Option<f64>,
    /// The left's jaw centre while the long end is wound round them.
    pub winding_point_m: [f64; 3],
    /// Where the left's jaws point while the long end is wound round them (stitch frame); `None`: as
    /// in the first throw.
    pub left_jaw_direction: Option<[f64; 3]>,
    /// How the left takes its turn to the tail; `None`: as in the first throw.
    pub left_fetches: Option<LeftFetch>,
    /// The left keeps the tail it holds from the first throw and the long end is wound round its
    /// closed jaws: no hand-over, no fetch. Drawn off the jaws' tips (the left drawing back, or the
    /// right going to `right_draws_to_m`), the turn is meant to pass over the tail's free end beyond
    /// them, as if the left had taken the tail there.
    pub left_keeps_tail: bool,
    /// The assist presents the tail ahead of the left's jaws instead of the left fetching it (a
    /// fetch turns the jaws, and the turn slid off their tips on the way). Not with
    /// `left_keeps_tail`.
    pub assist_presents: bool,
    /// The tail is presented this far ahead of the left's jaw centre ([`TieGeometry::tail_ahead_m`]),
    /// m; `None`: as the first throw. Inside the jaws' reach (with `tail_take_short_m` as far), the
    /// left closes on the tail where it is presented without moving.
    pub tail_ahead_m: Option<f64>,
    /// The left's jaw centre stops this far short of the presented tail, m; `None`: as the first
    /// throw.
    pub tail_take_short_m: Option<f64>,
    /// With `assist_presents`: the assist offers the tail's end across the left's jaws, its jaw
    /// centre this far beside them ([`TieGeometry::tail_end_offered_m`]), m; `None`: as the first
    /// throw.
    pub tail_end_offered_m: Option<f64>,
    /// The left opens its jaws this far to take the tail, rad; `None`: as the first throw. Wider, the
    /// jaws' tips take a tail presented further off their line (the tips of jaws opened 0.6 rad
    /// stand 3 mm either side of it).
    pub take_tail_jaw_rad: Option<f64>,
    /// After winding, the right gives this much thread back towards the left's jaws, m; `None`: as
    /// the first throw.
    pub loosen_m: Option<f64>,
    /// Before the pulls, the left draws the tail back this far along its jaws, m; `None`: as the
    /// first throw.
    pub draw_back_m: Option<f64>,
    /// ... while the right moves this fraction of the same way; `None`: as the first throw.
    pub right_follows_draw: Option<f64>,
    /// ... or goes here (stitch frame); `None`: as the first throw.
    pub right_draws_to_m: Option<[f64; 3]>,
    /// Before the draw, the right carries the long end through these points (stitch frame; see
    /// [`TieGeometry::right_before_draw_m`]); empty: none.
    pub right_before_draw_m: Vec<[f64; 3]>,
    /// How long the draw takes, s; `None`: as the first throw.
    pub draw_s: Option<f64>,
    /// Whether the pulls' hold lasts until the jaws have opened
    /// ([`TieGeometry::hold_through_release`]); `None`: as the first throw.
    pub hold_through_release: Option<bool>,
    /// The run-down's stopping force, N; `None`: as the first throw.
    pub run_down_force_n: Option<f64>,
    /// How long each pull takes to its target, s; `None`: as the first throw.
    pub pull_s: Option<f64>,
    /// The right's set force in the pulls, N; `None`: as the first throw.
    pub pull_force_n: Option<f64>,
    /// The left's set force on the tail in the pulls, N; `None`: as the first throw.
    pub tail_pull_force_n: Option<f64>,
    /// The winding's first move (picks the sense of the turn).
    pub winding_towards: [f64; 3],
    /// The right's jaws' distance from the left's jaw axis while winding, m; `None`: as the first
    /// throw. The long end left between the knot and the needle must reach round the circle.
    pub winding_radius_m: Option<f64>,
    /// The winding circles this far behind the left's jaw centre, m; `None`: as the first throw.
    pub winding_behind_m: Option<f64>,
    /// The winding advances this far along the jaws per turn ([`TieGeometry::winding_pitch_m`]), m;
    /// `None`: as the first throw.
    pub winding_pitch_m: Option<f64>,
    /// Where the winding starts (see [`TieGeometry::winding_lead_rad`]); `None`: as the first throw.
    pub winding_lead_rad: Option<f64>,
    /// Turns of the winding.
    pub winding_turns: f64,
    /// The run-down: the left draws the tail to here ...
    pub left_run_down_to_m: [f64; 3],
    /// ... while the right takes its jaws to here.
    pub right_run_down_to_m: [f64; 3],
    /// The left's way to its run-down's end ([`TieGeometry::left_run_down_via_m`]); empty: straight.
    pub left_run_down_via_m: Vec<[f64; 3]>,
    /// The right's way to its run-down's end ([`TieGeometry::right_run_down_via_m`]); empty: straight.
    pub right_run_down_via_m: Vec<[f64; 3]>,
    /// Then the pulls until the set force: the left towards here ...
    pub left_pull_to_m: [f64; 3],
    /// ... the right towards here.
    pub right_pull_to_m: [f64; 3],
}

impl Default for SecondThrow {
    fn default() -> Self {
        let first = TieGeometry::default();
        Self {
            tail_hold_along: 0.6,
            tail_hold_from_end_m: None,
            tail_held_to_m: None,
            tail_held_taut: None,
            tail_brought_to_m: None,
            left_lets_go_first: false,
            left_retakes_from_end_m: None,
            winding_point_m: first.winding_point_m,
            left_jaw_direction: None,
            left_fetches: None,
            assist_presents: false,
            left_keeps_tail: false,
            tail_ahead_m: None,
            tail_take_short_m: None,
            tail_end_offered_m: None,
            take_tail_jaw_rad: None,
            loosen_m: None,
            draw_back_m: None,
            right_follows_draw: None,
            right_draws_to_m: None,
            right_before_draw_m: Vec::new(),
            draw_s: None,
            hold_through_release: None,
            run_down_force_n: None,
            pull_s: None,
            pull_force_n: None,
            tail_pull_force_n: None,
            winding_towards: [0.0, 0.0, -1.0],
            winding_radius_m: None,
            winding_behind_m: None,
            winding_pitch_m: None,
            winding_lead_rad: None,
            winding_turns: 1.0,
            left_run_down_to_m: first.left_run_down_to_m,
            right_run_down_to_m: first.right_run_down_to_m,
            left_run_down_via_m: Vec::new(),
            right_run_down_via_m: Vec::new(),
            left_pull_to_m: first.left_pull_to_m,
            right_pull_to_m: first.right_pull_to_m,
        }
    }
}

impl SecondThrow {
    /// The first throw's geometry with this throw's differences.
    pub fn applied_to(&self, first: &TieGeometry) -> TieGeometry {
        TieGeometry {
            winding_point_m: self.winding_point_m,
            left_jaw_direction: self.left_jaw_direction.or(first.left_jaw_direction),
            left_fetches: if self.assist_presents || self.left_keeps_tail {
                None
            } else {
                self.left_fetches.clone().or_else(|| first.left_fetches.clone())
            },
            // The second throw's own keys decide who brings the tail, not the first's.
            assist_presents: self.assist_presents,
            tail_ahead_m: self.tail_ahead_m.unwrap_or(first.tail_ahead_m),
            tail_take_short_m: self.tail_take_short_m.unwrap_or(first.tail_take_short_m),
            take_tail_jaw_rad: self.take_tail_jaw_rad.unwrap_or(first.take_tail_jaw_rad),
            tail_end_offered_m: self.tail_end_offered_m.or(first.tail_end_offered_m),
            loosen_m: self.loosen_m.unwrap_or(first.loosen_m),
            draw_back_m: self.draw_back_m.unwrap_or(first.draw_back_m),
            right_follows_draw: self.right_follows_draw.unwrap_or(first.right_follows_draw),
            right_draws_to_m: self.right_draws_to_m.or(first.right_draws_to_m),
            right_before_draw_m: self.right_before_draw_m.clone(),
            draw_s: self.draw_s.unwrap_or(first.draw_s),
            hold_through_release: self.hold_through_release.unwrap_or(first.hold_through_release),
            run_down_force_n: self.run_down_force_n.or(first.run_down_force_n),
            pull_s: self.pull_s.unwrap_or(first.pull_s),
            pull_force_n: self.pull_force_n.unwrap_or(first.pull_force_n),
            tail_pull_force_n: self.tail_pull_force_n.or(first.tail_pull_force_n),
            winding_towards: self.winding_towards,
            winding_radius_m: self.winding_radius_m.unwrap_or(first.winding_radius_m),
            winding_behind_m: self.winding_behind_m.unwrap_or(first.winding_behind_m),
            winding_pitch_m: self.winding_pitch_m.unwrap_or(first.winding_pitch_m),
            winding_lead_rad: self.winding_lead_rad.unwrap_or(first.winding_lead_rad),
            winding_turns: self.winding_turns,
            tail_brought_to_m: self.tail_brought_to_m.or(first.tail_brought_to_m),
            left_run_down_to_m: self.left_run_down_to_m,
            right_run_down_to_m: self.right_run_down_to_m,
            left_run_down_via_m: self.left_run_down_via_m.clone(),
            right_run_down_via_m: self.right_run_down_via_m.clone(),
            left_pull_to_m: self.left_pull_to_m,
            right_pull_to_m: self.right_pull_to_m,
            second_throw: None,
            ..first.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The second throw points the left's jaws and fetches as the first unless given its own, fetches nothing
    /// when the assist presents the tail or the left keeps it, and plans no further throw.
    #[test]
    fn the_second_throw_points_the_left_jaws_as_the_first_unless_told() {
        let first = TieGeometry { left_jaw_direction: Some([0.0, -1.0, 1.0]), ..TieGeometry::default() };
        let same = SecondThrow::default().applied_to(&first);
        assert_eq!(same.left_jaw_direction, Some([0.0, -1.0, 1.0]));
        let own = SecondThrow { left_jaw_direction: Some([1.0, 0.0, 0.0]), ..SecondThrow::default() };
        assert_eq!(own.applied_to(&first).left_jaw_direction, Some([1.0, 0.0, 0.0]));
        assert_eq!(own.applied_to(&first).second_throw, None, "a throw, not another knot");
        assert_eq!(own.applied_to(&first).left_fetches, first.left_fetches, "fetching as the first");
        let level =
            LeftFetch { jaw_direction: [1.0, 0.0, 0.0], ..first.left_fetches.clone().expect("a fetch") };
        let fetching = SecondThrow { left_fetches: Some(level.clone()), ..SecondThrow::default() };
        assert_eq!(fetching.applied_to(&first).left_fetches, Some(level));
        let presented = SecondThrow { assist_presents: true, ..fetching };
        assert_eq!(presented.applied_to(&first).left_fetches, None, "the assist brings the tail");
        let kept = SecondThrow { left_keeps_tail: true, ..SecondThrow::default() };
        assert_eq!(kept.applied_to(&first).left_fetches, None, "the left holds the tail already");
    }

    /// The second throw's draw, run-down, pulls and hold take the first throw's settings unless it gives its
    /// own, and then take exactly those.
    #[test]
    fn the_draw_and_run_down_are_the_first_throws_unless_told() {
        let first = TieGeometry { right_follows_draw: -0.6, ..TieGeometry::default() };
        let same = SecondThrow::default().applied_to(&first);
        assert_eq!(
            (same.draw_back_m, same.right_follows_draw, same.right_draws_to_m, same.draw_s),
            (first.draw_back_m, first.right_follows_draw, first.right_draws_to_m, first.draw_s)
        );
        assert_eq!(
            (same.run_down_force_n, same.winding_lead_rad),
            (first.run_down_force_n, first.winding_lead_rad)
        );
        let own = SecondThrow {
            loosen_m: Some(0.006),
            tail_take_short_m: Some(0.0045),
            draw_back_m: Some(0.008),
            right_follows_draw: Some(0.0),
            right_draws_to_m: Some([0.005, -0.015, 0.01]),
            draw_s: Some(4.0),
            run_down_force_n: Some(2.5),
            winding_lead_rad: Some(-1.5),
            ..SecondThrow::default()
        }
        .applied_to(&first);
        assert_eq!(
            (own.draw_back_m, own.right_follows_draw, own.right_draws_to_m, own.draw_s),
            (0.008, 0.0, Some([0.005, -0.015, 0.01]), 4.0)
        );
        assert_eq!((own.run_down_force_n, own.winding_lead_rad), (Some(2.5), -1.5));
        assert_eq!((same.loosen_m, own.loosen_m), (first.loosen_m, 0.006));
        let brought = SecondThrow { tail_brought_to_m: Some([0.0, 0.02, 0.03]), ..SecondThrow::default() }
            .applied_to(&first);
        assert_eq!((same.tail_brought_to_m, brought.tail_brought_to_m), (None, Some([0.0, 0.02, 0.03])));
        let held =
            SecondThrow { hold_through_release: Some(true), ..SecondThrow::default() }.applied_to(&first);
        assert_eq!((same.hold_through_release, held.hold_through_release), (false, true));
        let pulled = SecondThrow {
            pull_s: Some(6.0),
            pull_force_n: Some(1.5),
            tail_pull_force_n: Some(1.2),
            left_run_down_via_m: vec![[0.0, 0.01, 0.03]],
            right_run_down_via_m: vec![[0.0, -0.01, 0.04]],
            ..SecondThrow::default()
        }
        .applied_to(&first);
        assert_eq!(
            (same.pull_force_n, same.tail_pull_force_n),
            (first.pull_force_n, first.tail_pull_force_n)
        );
        assert_eq!((pulled.pull_force_n, pulled.tail_pull_force_n), (1.5, Some(1.2)));
        assert_eq!((same.pull_s, pulled.pull_s), (first.pull_s, 6.0));
        assert_eq!(
            (same.left_run_down_via_m.len(), pulled.left_run_down_via_m),
            (0, vec![[0.0, 0.01, 0.03]])
        );
        assert_eq!(
            (same.right_run_down_via_m.len(), pulled.right_run_down_via_m),
            (0, vec![[0.0, -0.01, 0.04]])
        );
        assert_eq!((same.tail_take_short_m, own.tail_take_short_m), (first.tail_take_short_m, 0.0045));
        let small = SecondThrow {
            winding_radius_m: Some(0.01),
            winding_behind_m: Some(0.003),
            take_tail_jaw_rad: Some(0.9),
            tail_end_offered_m: Some(0.008),
            ..SecondThrow::default()
        }
        .applied_to(&first);
        assert_eq!(
            (same.winding_radius_m, same.winding_behind_m),
            (first.winding_radius_m, first.winding_behind_m)
        );
        assert_eq!((small.winding_radius_m, small.winding_behind_m), (0.01, 0.003));
        assert_eq!((same.take_tail_jaw_rad, small.take_tail_jaw_rad), (first.take_tail_jaw_rad, 0.9));
        assert_eq!(
            (same.tail_end_offered_m, small.tail_end_offered_m),
            (first.tail_end_offered_m, Some(0.008))
        );
    }
}

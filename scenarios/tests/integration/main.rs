//! The scenarios crate's integration tests, one binary (one link, and the tests of every topic run side
//! by side): each module guards what its doc comment says.
//!
//! - The scripted expert: [`expert_ties_a_knot`], [`expert_recording`], [`expert_looks_where_the_tail_lies`],
//!   [`expert_winds_keeping_the_tension`], [`every_expert_file_loads`],
//!   [`jaws_turned_the_opposite_way_gave_poses_with_nan`].
//! - Its second throw: [`expert_second_throw_goes_on_from_the_first`], [`expert_second_throw_keeps_the_tail`],
//!   [`expert_second_throw_of_the_other_hand`], [`expert_second_throw_on_the_assists_jaws`],
//!   [`expert_second_throw_takes_the_tail_by_its_end`], [`draw_through_sees_the_first_throw`].
//! - The shipped scenes: [`scene_variants_differ_from_the_nominal_only_in_the_suture`],
//!   [`short_suture_scene_is_the_chain_one_with_less_thread`].
//! - The lab's workflow: [`lab_session`].
//! - The step-wise episode of the Gymnasium environment: [`episode_steps`].
//! - The stress sequence, the same twice: [`scene_determinism`]; the suture's stretch watch against it:
//!   [`suture_stretch_watch`].
//! - A trial's preview verdicts: [`trial_preview_verdicts`]; its take aimed where the thread lies:
//!   [`trial_take_aims_at_the_thread`]; the left's wrist past its reach at a turned site:
//!   [`trial_wrist_follows_its_reach`]; the winding round the left's jaws as they are held there:
//!   [`trial_winding_round_the_jaws`].
//! - [`common`]: the expert runs the second-throw tests share, and the skill learned from the shipped
//!   demonstration.

mod common;

mod draw_through_sees_the_first_throw;
mod episode_steps;
mod every_expert_file_loads;
mod expert_looks_where_the_tail_lies;
mod expert_recording;
mod expert_second_throw_goes_on_from_the_first;
mod expert_second_throw_keeps_the_tail;
mod expert_second_throw_of_the_other_hand;
mod expert_second_throw_on_the_assists_jaws;
mod expert_second_throw_takes_the_tail_by_its_end;
mod expert_ties_a_knot;
mod expert_winds_keeping_the_tension;
mod jaws_turned_the_opposite_way_gave_poses_with_nan;
mod lab_session;
mod scene_determinism;
mod scene_variants_differ_from_the_nominal_only_in_the_suture;
mod short_suture_scene_is_the_chain_one_with_less_thread;
mod suture_stretch_watch;
mod trial_preview_verdicts;
mod trial_take_aims_at_the_thread;
mod trial_winding_round_the_jaws;
mod trial_wrist_follows_its_reach;

//! The sim crate's integration tests, one binary: one link, and the tests of every file run side by side. Each module
//! guards what its doc comment says.

mod common;

mod backend_rig;
mod closed_empty_jaws_grasped_later;
mod closing_jaws_squeezed_the_thread_along_them;
mod coils_cinched_round_the_suture_across_the_wound;
mod grasp_slip;
mod grasp_took_coils_around_the_jaws;
mod holding_test_kept_a_grip_taken_wide;
mod holding_test_passed_an_untied_stitch;
mod jaws_took_a_coil_lying_beside_them;
mod kinematic_link_spun_when_its_quaternion_flipped_sign;
mod knot_classify;
mod knot_crept_along_its_rope_under_equal_pulls;
mod needle_gauge_missed_the_ropes_pull;
mod released_needle_flew_off_the_rope;
mod rope_among_rigid_bodies;
mod rope_held_in_jaws;
mod rope_held_on_the_tissue_tore_the_grip;
mod rope_jammed_in_a_gap_narrower_than_its_knots;
mod rope_scene_holds_its_start_condition;
mod rope_scene_poses_the_links_outside_rapiers_solver;
mod rope_slides_through_jaws_pulled_past_their_grip;
mod rope_stitch_hands_the_flaps_back_to_their_joints;
mod rope_stitch_ignored_its_slide_friction;
mod rope_stitch_stays_calm_through_a_cinch;
mod scene_file;
mod scene_reference;
mod thread_drag;
mod thread_laid_along_a_bent_path_starts_untwisted;
mod thread_physics;
mod thread_watch;
mod tissue_stitch;
mod wound_shut_on_thread_lying_in_it;

//! The lab crate's integration tests, one binary: each module guards what its doc comment says, on
//! an experiment rig of `knotlab-lab`.

mod common;

mod capsized_square_knot_slides_where_the_flat_one_holds;
mod laid_knot_lays_its_knot_through_the_stitch;
mod lone_double_throw_comes_undone_under_the_holding_load;
mod rope_holds_a_wrap_and_a_square_knot;
mod rope_knot_in_the_scenes_own_tissue;
mod rope_laid_surgeons_knot_in_the_wound;
mod square_knot_holds_its_free_ends_let_go;
mod stitch_point_slid_past_its_segment_into_empty_space;
mod strand_passed_through_a_double_wrap_at_0_7_n;
mod string_surgeons_knot_gave_the_wound_its_gap_back;
mod throw_holds_the_loop_only_while_its_ends_are_held;
mod wrapped_strand_rolled_off_whatever_the_friction;

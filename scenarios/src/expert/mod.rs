//! The scripted expert: a surgeon played by a program. It plans the knot-tying task as a Skill
//! ([`plan`]), each throw a sequence of phases (`phases/`, one file each: the approach, the wind,
//! the fetch or the presented tail, the draw, the run-down, the pull...), with human-like motion
//! ([`motion`]) varied from run to run ([`variation`]): the controller runs it on the simulated devices,
//! and what the devices read meanwhile is the demonstration ([`record`]); [`diagnose`] measures what a run
//! did to the thread.

pub mod clearance;
pub mod diagnose;
pub mod geometry;
pub mod geometry_file;
pub mod motion;
mod phases;
pub mod plan;
pub mod record;
pub mod tail;
pub mod turn_thread;
pub mod variation;

pub use geometry::{LeftFetch, SecondThrow, TieGeometry};
pub use geometry_file::{GeometryFileError, load_tie_geometry, parse_tie_geometry};
pub use plan::{
    Planner, plan_after_wind, plan_instrument_tie, plan_second_tail_take, plan_second_throw,
    plan_tail_hand_over, plan_tail_take,
};
pub use record::{DemoRun, ExpertError, RecordOptions, demonstrate, demonstrate_with, record_demonstration};
pub use variation::Variation;

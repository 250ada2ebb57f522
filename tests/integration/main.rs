//! The knotlab command's and the end-to-end tests, one binary: one link, and the tests of every file run side by side. Each module
//! guards what its doc comment says.

mod common;

mod backend_melfa_agreement;
mod cli_anywhere;
mod cli_canopen;
mod cli_demo;
mod cli_fluid;
mod cli_knot;
mod cli_learn;
mod cli_mc;
mod cli_melfa;
mod cli_netft;
mod cli_obstacles;
mod cli_report;
mod cli_rig;
mod cli_run;
mod cli_session;
mod cli_sim;
mod fuzz;
mod lab_rig_emulators;
mod readme_commands;
mod rerun_recording;

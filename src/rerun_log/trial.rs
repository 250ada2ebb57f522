//! A simulated trial as it runs: every few control cycles the instruments' tips and measured forces,
//! the suture, the grasp events, less often the robots' links; at the end the demonstration's tip paths,
//! the scene after the holding test, the knot's crossings and the verdict.

use knotlab_hw::controller::CycleRecord;
use knotlab_hw::rig::ArmName;
use knotlab_sim::evaluate::KnotEvaluation;
use knotlab_sim::shapes::{SceneShapes, scene_shapes};
use knotlab_sim::world::SimWorld;

use super::Recording;
use super::convert::{arm_color, v3};
use super::scene::{log_robots, log_suture};
use super::sdk;

/// Metres of arrow per newton of measured force.
const ARROW_M_PER_N: f64 = 0.01;

/// Logs a trial cycle by cycle. Errors while observing are kept and reported once, by [`TrialLogger::end`].
pub struct TrialLogger<'a> {
    recording: &'a Recording,
    /// Tips, forces, suture and events every this many cycles.
    every: u64,
    /// Robot links every this many cycles.
    robots_every: u64,
    events_logged: usize,
    error: Option<anyhow::Error>,
}

impl<'a> TrialLogger<'a> {
    /// Tips, forces, suture and events every `every` cycles; robots every `robots_every`.
    pub fn new(recording: &'a Recording, every: u64, robots_every: u64) -> Self {
        Self {
            recording,
            every: every.max(1),
            robots_every: robots_every.max(1),
            events_logged: 0,
            error: None,
        }
    }

    /// Sees one control cycle and the scene after it.
    pub fn observe(&mut self, record: &CycleRecord, world: &SimWorld) {
        if self.error.is_some() || !record.cycle.is_multiple_of(self.every) {
            return;
        }
        if let Err(e) = self.log_cycle(record, world) {
            self.error = Some(e);
        }
    }

    fn log_cycle(&mut self, record: &CycleRecord, world: &SimWorld) -> anyhow::Result<()> {
        let rec = self.recording;
        rec.set_duration_secs("sim_time", record.time_s);
        rec.set_time_sequence("step", record.cycle as i64);
        for arm in &record.arms {
            if arm.arm == ArmName::Camera {
                continue;
            }
            let name = arm.arm.to_string();
            let tip = arm.world_from_tip.translation.vector;
            let color = arm_color(&name);
            rec.log(
                format!("instruments/{name}/tip"),
                &sdk::Points3D::new([v3(&tip)]).with_radii([0.0008_f32]).with_colors([color]),
            )?;
            rec.log(
                format!("instruments/{name}/force"),
                &sdk::Arrows3D::from_vectors([v3(&(arm.world_force_n * ARROW_M_PER_N))])
                    .with_origins([v3(&tip)])
                    .with_colors([color]),
            )?;
            rec.log(format!("plots/force_n/{name}"), &sdk::Scalars::single(arm.world_force_n.norm()))?;
            rec.log(format!("plots/jaw_rad/{name}"), &sdk::Scalars::single(arm.measured.tool.jaw_rad))?;
        }
        let scene = scene_shapes(world);
        log_suture(rec, &scene)?;
        if record.cycle.is_multiple_of(self.robots_every) {
            log_robots(rec, &scene)?;
        }
        for event in &world.events()[self.events_logged.min(world.events().len())..] {
            rec.log("events", &sdk::TextLog::new(format!("{event:?}")))?;
        }
        self.events_logged = world.events().len();
        Ok(())
    }

    /// Ends the trial: the scene after the holding test (at `end_time_s`), the recorded tip paths
    /// (`(arm, points)`), and the verdict. Reports the first error met while observing, if any.
    pub fn end(
        self,
        end_time_s: f64,
        final_scene: &SceneShapes,
        tip_paths: &[(String, Vec<nalgebra::Vector3<f64>>)],
        evaluation: &KnotEvaluation,
    ) -> anyhow::Result<()> {
        if let Some(e) = self.error {
            return Err(e.context("recording the trial for Rerun"));
        }
        let rec = self.recording;
        rec.set_duration_secs("sim_time", end_time_s);
        log_suture(rec, final_scene)?;
        log_robots(rec, final_scene)?;
        for (arm, points) in tip_paths {
            rec.log_static(
                format!("instruments/{arm}/path"),
                &sdk::LineStrips3D::new([points.iter().map(v3).collect::<Vec<_>>()])
                    .with_radii([0.0002_f32])
                    .with_colors([arm_color(arm)]),
            )?;
        }
        let e = evaluation;
        let mm = |m: Option<f64>| m.map_or("-".to_owned(), |m| format!("{:.2} mm", m * 1e3));
        let text = format!(
            "# Verdict: {}\n\n| | |\n|---|---|\n| knot before release | {} |\n| knot after the holding test | {} |\n\
             | height above the tissue | {} |\n| distance from the stitch | {} |\n\
             | thread between the stitch and the knot | {} |\n| wound gap before release | {} |\n\
             | wound gap after the holding test | {} |\n",
            e.verdict.label(),
            e.knot_before.map_or("-", |k| k.name()),
            e.knot_after.map_or("-", |k| k.name()),
            mm(e.height_m),
            mm(e.stitch_distance_m),
            mm(e.loop_outside_m),
            mm(Some(e.gap_before_m)),
            mm(e.gap_after_m),
        );
        // The knot the thread holds at the end, and where its crossings lie.
        let text = match knotlab_sim::knot::classify(&final_scene.thread_m) {
            Ok(c) => {
                if let Some(span) = &c.span {
                    rec.log(
                        "knot/crossings",
                        &sdk::Points3D::new(span.points_m.iter().map(v3))
                            .with_radii([0.0004_f32])
                            .with_colors([sdk::Color::from_rgb(250, 140, 20)]),
                    )?;
                }
                format!(
                    "{text}| knot at the end | {} |\n| crossings (reduced) | {} |\n| determinant | {} |\n\
                     | writhe | {} |\n| directions agreeing | {:.0} % |\n",
                    c.knot.name(),
                    c.crossings,
                    c.determinant.map_or("-".to_owned(), |d| d.to_string()),
                    c.writhe,
                    100.0 * c.agreement
                )
            }
            Err(e) => format!("{text}| knot at the end | not classified: {e} |\n"),
        };
        rec.log("verdict", &sdk::TextDocument::from_markdown(text))?;
        rec.log("events", &sdk::TextLog::new(format!("verdict: {}", e.verdict.label())))?;
        Ok(())
    }
}

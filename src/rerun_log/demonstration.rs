//! A demonstration as the learner sees it: the instruments' tips, jaws and forces over its time, their
//! paths, the detected features, and the primitives it was cut into as labelled spans of the paths.

use knotlab_learner::demonstration::Demonstration;
use knotlab_learner::features::FeatureSet;
use knotlab_learner::segment::Decomposition;

use super::Recording;
use super::convert::{arm_color, v3};
use super::sdk;

/// Logs the demonstration's samples on `sim_time` (its own clock) and `step` (sample index), and each
/// instrument's whole path (`demonstration/<arm>/...`).
pub fn log_demonstration(recording: &Recording, demo: &Demonstration) -> anyhow::Result<()> {
    for record in &demo.instruments {
        let arm = record.instrument.to_string();
        let color = arm_color(&arm);
        for (k, sample) in record.samples.iter().enumerate() {
            recording.set_duration_secs("sim_time", sample.time_s);
            recording.set_time_sequence("step", k as i64);
            recording.log(
                format!("demonstration/{arm}/tip"),
                &sdk::Points3D::new([v3(&sample.position_m)]).with_radii([0.0008_f32]).with_colors([color]),
            )?;
            recording.log(
                format!("plots/demonstration/force_n/{arm}"),
                &sdk::Scalars::single(sample.force_n.norm()),
            )?;
            recording
                .log(format!("plots/demonstration/jaw_rad/{arm}"), &sdk::Scalars::single(sample.jaw_rad))?;
        }
        let path: Vec<[f32; 3]> = record.samples.iter().map(|s| v3(&s.position_m)).collect();
        recording.log_static(
            format!("demonstration/{arm}/path"),
            &sdk::LineStrips3D::new([path]).with_radii([0.0002_f32]).with_colors([color]),
        )?;
    }
    Ok(())
}

/// Logs the detected features (`features/<arm>`: labelled points, and a text line at each one's time)
/// and, if the demonstration was cut, the primitives (`primitives/<arm>/<name>`: the stretch of the path each covers, labelled with its
/// name and type, and a text line where each starts and ends).
pub fn log_decomposition(
    recording: &Recording,
    demo: &Demonstration,
    features: &FeatureSet,
    decomposition: Option<&Decomposition>,
) -> anyhow::Result<()> {
    for analysis in &features.instruments {
        let arm = analysis.instrument.to_string();
        let labels: Vec<String> = analysis.features.iter().map(|f| f.kind.as_str().to_owned()).collect();
        recording.log_static(
            format!("features/{arm}"),
            &sdk::Points3D::new(analysis.features.iter().map(|f| v3(&f.position_m)))
                .with_radii([0.0006_f32])
                .with_labels(labels)
                .with_colors([arm_color(&arm)]),
        )?;
        for feature in &analysis.features {
            recording.set_duration_secs("sim_time", feature.time_s);
            recording.log(
                format!("features/{arm}/log"),
                &sdk::TextLog::new(format!("{} ({:.4})", feature.kind.as_str(), feature.magnitude)),
            )?;
        }
    }
    for segment in decomposition.iter().flat_map(|d| &d.segments) {
        let arm = segment.instrument.to_string();
        let Some(record) = demo.instruments.iter().find(|r| r.instrument == segment.instrument) else {
            continue;
        };
        let stretch: Vec<[f32; 3]> = record
            .samples
            .iter()
            .filter(|s| s.time_s >= segment.start_s && s.time_s <= segment.end_s)
            .map(|s| v3(&s.position_m))
            .collect();
        let label = format!("{} ({})", segment.name, segment.kind.as_str());
        recording.log_static(
            format!("primitives/{arm}/{}", segment.name),
            &sdk::LineStrips3D::new([stretch])
                .with_radii([0.0005_f32])
                .with_labels([label.clone()])
                .with_colors([arm_color(&arm)]),
        )?;
        recording.set_duration_secs("sim_time", segment.start_s);
        recording.log(format!("primitives/{arm}/log"), &sdk::TextLog::new(format!("start {label}")))?;
        recording.set_duration_secs("sim_time", segment.end_s);
        recording.log(format!("primitives/{arm}/log"), &sdk::TextLog::new(format!("end {label}")))?;
    }
    Ok(())
}

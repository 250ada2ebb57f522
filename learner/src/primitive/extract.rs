//! Extraction of the primitives of a decomposed demonstration into a knowledge base, everything
//! carried into the stitch frame: positions from the smoothed path (tremor removed), orientations and
//! jaw angles from the recorded samples, forces smoothed as the force detector smooths them.

use knotlab_hw::geometry::arc_lengths;
use nalgebra::{Isometry3, Matrix3, SymmetricEigen, UnitQuaternion, Vector3};
use thiserror::Error;

use super::timing::{dependencies, jaw_points, path_keys};
use super::{
    DemonstrationInfo, ForcePrimitive, InstrumentPrimitives, JawAction, JawActionKind, KB_FORMAT,
    KB_FORMAT_VERSION, KnowledgeBase, LinearPrimitive, Plane, Pose, Primitive, ProfilePoint, SyncSample,
    SynchronizedPrimitive, TwoDPrimitive,
};
use crate::demonstration::{Demonstration, InstrumentRecord};
use crate::features::signal::{gaussian_smooth, index_at};
use crate::features::{FeatureKind, FeatureSet, InstrumentAnalysis};
use crate::pattern::{PrimitiveType, TaskPattern};
use crate::segment::{Decomposition, Segment};

/// Points of a speed profile.
pub const PROFILE_POINTS: usize = 50;

/// Spacing of a 2D primitive's path, m.
pub const PATH_STEP_M: f64 = 0.0005;

/// Samples of a synchronized primitive's mapping.
pub const SYNC_SAMPLES: usize = 50;

/// Why a primitive could not be extracted.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("primitive {primitive}: {reason}")]
pub struct ExtractError {
    /// The primitive.
    pub primitive: String,
    /// Why.
    pub reason: String,
}

/// What one primitive's extraction needs of its instrument.
struct Source<'a> {
    record: &'a InstrumentRecord,
    analysis: &'a InstrumentAnalysis,
    stitch_from_world: Isometry3<f64>,
}

impl Source<'_> {
    fn position(&self, t: f64) -> Vector3<f64> {
        self.stitch_from_world.transform_point(&self.analysis.position_at(t).into()).coords
    }

    fn rotation(&self, t: f64) -> UnitQuaternion<f64> {
        let k = index_at(&self.analysis.times_s, t);
        self.stitch_from_world.rotation * self.record.samples[k].world_from_tip()
    }

    fn jaw(&self, t: f64) -> f64 {
        self.record.samples[index_at(&self.analysis.times_s, t)].jaw_rad
    }

    fn pose(&self, t: f64) -> Pose {
        let p = self.position(t);
        let q = self.rotation(t);
        let q = q.quaternion();
        Pose { position_m: [p.x, p.y, p.z], quaternion_xyzw: [q.i, q.j, q.k, q.w] }
    }

    /// Sample indices of a span, and the smoothed positions (stitch frame) and speeds there.
    fn span(
        &self,
        name: &str,
        start_s: f64,
        end_s: f64,
    ) -> Result<(Vec<Vector3<f64>>, Vec<f64>), ExtractError> {
        let times = &self.analysis.times_s;
        if !(start_s.is_finite() && end_s.is_finite() && end_s > start_s) {
            return Err(ExtractError {
                primitive: name.to_owned(),
                reason: format!("empty span [{start_s}, {end_s}] s"),
            });
        }
        let (k0, k1) = (index_at(times, start_s), index_at(times, end_s));
        if k1 < k0 + 2 {
            return Err(ExtractError {
                primitive: name.to_owned(),
                reason: format!("[{start_s:.3}, {end_s:.3}] s holds fewer than 3 samples"),
            });
        }
        let points = (k0..=k1)
            .map(|k| self.stitch_from_world.transform_point(&self.analysis.positions_m[k].into()).coords)
            .collect();
        Ok((points, self.analysis.speed_mps[k0..=k1].to_vec()))
    }
}

/// Linear interpolation of `values` (at arc lengths `arc`) at arc length `s`.
fn at_arc(arc: &[f64], values: &[f64], s: f64) -> f64 {
    let k = arc.partition_point(|a| *a <= s);
    if k == 0 {
        return values[0];
    }
    if k >= arc.len() {
        return values[values.len() - 1];
    }
    let f = if arc[k] > arc[k - 1] { (s - arc[k - 1]) / (arc[k] - arc[k - 1]) } else { 0.0 };
    values[k - 1] + (values[k] - values[k - 1]) * f
}

/// The speed at `PROFILE_POINTS` equal steps of arc length.
fn speed_profile(points: &[Vector3<f64>], speeds: &[f64]) -> Vec<ProfilePoint> {
    let arc = arc_lengths(points);
    let total = arc[arc.len() - 1];
    (0..PROFILE_POINTS)
        .map(|k| {
            let s = total * k as f64 / (PROFILE_POINTS - 1) as f64;
            ProfilePoint { s_m: s, speed_mps: at_arc(&arc, speeds, s) }
        })
        .collect()
}

fn array(v: Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

fn linear(src: &Source, seg: &Segment) -> Result<LinearPrimitive, ExtractError> {
    let (points, speeds) = src.span(&seg.name, seg.start_s, seg.end_s)?;
    let (a, b) = (points[0], points[points.len() - 1]);
    let line = b - a;
    let deviation = |p: &Vector3<f64>| {
        let d = p - a;
        if line.norm() > 1e-12 { (d - line * (d.dot(&line) / line.norm_squared())).norm() } else { d.norm() }
    };
    Ok(LinearPrimitive {
        name: seg.name.clone(),
        start_s: seg.start_s,
        end_s: seg.end_s,
        start_pose: src.pose(seg.start_s),
        end_pose: src.pose(seg.end_s),
        path_length_m: arc_lengths(&points).last().copied().unwrap_or(0.0),
        max_deviation_m: points.iter().map(deviation).fold(0.0, f64::max),
        speed_profile: speed_profile(&points, &speeds),
        jaw_rad: [src.jaw(seg.start_s), src.jaw(seg.end_s)],
    })
}

fn two_d(src: &Source, seg: &Segment) -> Result<TwoDPrimitive, ExtractError> {
    let (points, speeds) = src.span(&seg.name, seg.start_s, seg.end_s)?;
    let n = points.len() as f64;
    let centroid = points.iter().sum::<Vector3<f64>>() / n;
    let cov = points.iter().map(|p| (p - centroid) * (p - centroid).transpose()).sum::<Matrix3<f64>>() / n;
    let eig = SymmetricEigen::new(cov);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let mut normal = eig.eigenvectors.column(order[0]).into_owned();
    if normal.z < 0.0 || (normal.z == 0.0 && normal.x + normal.y < 0.0) {
        normal = -normal;
    }
    let axis_x = eig.eigenvectors.column(order[2]).into_owned().normalize();
    let axis_y = normal.cross(&axis_x).normalize();
    let plane_points: Vec<[f64; 2]> =
        points.iter().map(|p| [(p - centroid).dot(&axis_x), (p - centroid).dot(&axis_y)]).collect();
    let rms = (points.iter().map(|p| (p - centroid).dot(&normal).powi(2)).sum::<f64>() / n).sqrt();
    // Resample at equal arc length in the plane.
    let flat: Vec<Vector3<f64>> = plane_points.iter().map(|q| Vector3::new(q[0], q[1], 0.0)).collect();
    let arc = arc_lengths(&flat);
    let total = arc[arc.len() - 1];
    if total < 2.0 * PATH_STEP_M {
        return Err(ExtractError {
            primitive: seg.name.clone(),
            reason: format!("its path in the plane is only {total:.5} m long"),
        });
    }
    let xs: Vec<f64> = plane_points.iter().map(|q| q[0]).collect();
    let ys: Vec<f64> = plane_points.iter().map(|q| q[1]).collect();
    let mut stations: Vec<f64> = (0..).map(|k| k as f64 * PATH_STEP_M).take_while(|s| *s < total).collect();
    if total - stations[stations.len() - 1] > 1e-9 {
        stations.push(total);
    }
    let path_m: Vec<[f64; 2]> =
        stations.iter().map(|&s| [at_arc(&arc, &xs, s), at_arc(&arc, &ys, s)]).collect();
    let speed_mps: Vec<f64> = stations.iter().map(|&s| at_arc(&arc, &speeds, s)).collect();
    // Signed turning of the resampled path's direction.
    let mut turning = 0.0;
    for w in path_m.windows(3) {
        let (u, v) = ([w[1][0] - w[0][0], w[1][1] - w[0][1]], [w[2][0] - w[1][0], w[2][1] - w[1][1]]);
        turning += (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1]);
    }
    let times = &src.analysis.times_s;
    let (k0, k1) = (index_at(times, seg.start_s), index_at(times, seg.end_s));
    let mut jaws: Vec<f64> = src.record.samples[k0..=k1].iter().map(|s| s.jaw_rad).collect();
    jaws.sort_by(f64::total_cmp);
    Ok(TwoDPrimitive {
        name: seg.name.clone(),
        start_s: seg.start_s,
        end_s: seg.end_s,
        plane: Plane { origin_m: array(centroid), axis_x: array(axis_x), axis_y: array(axis_y) },
        rms_out_of_plane_m: rms,
        step_m: PATH_STEP_M,
        path_m,
        speed_mps,
        turns: turning / std::f64::consts::TAU,
        start_pose: src.pose(seg.start_s),
        end_pose: src.pose(seg.end_s),
        jaw_rad: jaws[jaws.len() / 2],
    })
}

fn force(src: &Source, seg: &Segment, smoothing_s: f64) -> Result<ForcePrimitive, ExtractError> {
    let (points, speeds) = src.span(&seg.name, seg.start_s, seg.end_s)?;
    let times = &src.analysis.times_s;
    let (k0, k1) = (index_at(times, seg.start_s), index_at(times, seg.end_s));
    // The force smoothed as the detector smooths it, over the span and a little beyond.
    let (w0, w1) = (k0.saturating_sub(50), (k1 + 50).min(times.len() - 1));
    let raw: Vec<Vector3<f64>> = src.record.samples[w0..=w1].iter().map(|s| s.force_n).collect();
    let smooth = gaussian_smooth(&times[w0..=w1], &raw, smoothing_s);
    let (peak_k, peak) = smooth[k0 - w0..=k1 - w0]
        .iter()
        .enumerate()
        .map(|(k, f)| (k, f.norm()))
        .fold((0, 0.0f64), |best, (k, f)| if f > best.1 { (k, f) } else { best });
    let direction = src.stitch_from_world.rotation * smooth[k0 - w0 + peak_k];
    let direction = direction.try_normalize(1e-12).unwrap_or_else(Vector3::zeros);
    // The jaw action: a jaw opening at the span's end (within 0.2 s), else the jaws hold.
    let opening =
        src.analysis.features.iter().rev().find(|f| {
            f.kind == FeatureKind::JawOpen && f.time_s >= seg.start_s && f.time_s <= seg.end_s + 0.2
        });
    let jaw = match opening {
        Some(f) => JawAction {
            action: JawActionKind::Open,
            from_rad: src.jaw(f.time_s),
            to_rad: f.magnitude,
            at_s: f.time_s - seg.start_s,
        },
        None => JawAction {
            action: JawActionKind::Hold,
            from_rad: src.jaw(seg.end_s),
            to_rad: src.jaw(seg.end_s),
            at_s: seg.end_s - seg.start_s,
        },
    };
    // The line's end: where the motion that carries the pull came to rest.
    let rest_s = src
        .analysis
        .motions
        .iter()
        .find(|m| m.start_s <= seg.end_s && m.end_s >= seg.end_s)
        .map_or(seg.end_s, |m| m.end_s);
    Ok(ForcePrimitive {
        name: seg.name.clone(),
        start_s: seg.start_s,
        end_s: seg.end_s,
        start_pose: src.pose(seg.start_s),
        end_pose: src.pose(seg.end_s),
        line_end_m: array(src.position(rest_s)),
        max_force_n: peak,
        force_direction: array(direction),
        jaw,
        speed_profile: speed_profile(&points, &speeds),
    })
}

fn synchronized(
    src: &Source,
    seg: &Segment,
    reference: &Source,
    plane: &TwoDPrimitive,
) -> Result<SynchronizedPrimitive, ExtractError> {
    let reference_name = seg.reference.clone().unwrap_or_default();
    let (ref_points, _) = reference.span(&reference_name, plane.start_s, plane.end_s)?;
    src.span(&seg.name, seg.start_s, seg.end_s)?;
    let arc = arc_lengths(&ref_points);
    let total = arc[arc.len() - 1].max(1e-12);
    let ref_times = &reference.analysis.times_s;
    let k0 = index_at(ref_times, plane.start_s);
    let origin = Vector3::from(plane.plane.origin_m);
    let (x, y, normal) =
        (Vector3::from(plane.plane.axis_x), Vector3::from(plane.plane.axis_y), plane.plane.normal());
    let in_plane = |v: Vector3<f64>| [v.dot(&x), v.dot(&y), v.dot(&normal)];
    let mapping = (0..SYNC_SAMPLES)
        .map(|k| {
            let t = seg.start_s + (seg.end_s - seg.start_s) * k as f64 / (SYNC_SAMPLES - 1) as f64;
            let kr = index_at(ref_times, t).clamp(k0, k0 + ref_points.len() - 1) - k0;
            let p = src.position(t);
            let r = reference.position(t);
            let q = src.rotation(t);
            let q = q.quaternion();
            SyncSample {
                phase: arc[kr] / total,
                position_plane_m: in_plane(p - origin),
                offset_m: in_plane(p - r),
                quaternion_xyzw: [q.i, q.j, q.k, q.w],
                jaw_rad: src.jaw(t),
            }
        })
        .collect();
    Ok(SynchronizedPrimitive {
        name: seg.name.clone(),
        start_s: seg.start_s,
        end_s: seg.end_s,
        reference: reference_name,
        mapping,
    })
}

/// Extracts every primitive of `decomposition` from `demo` (whose features are `features`, detected
/// with `pattern`'s detector parameters) into a knowledge base.
pub fn extract(
    demo: &Demonstration,
    pattern: &TaskPattern,
    features: &FeatureSet,
    decomposition: &Decomposition,
) -> Result<KnowledgeBase, ExtractError> {
    let world_from_stitch = demo.metadata.stitch.world_from_stitch();
    let stitch_from_world = world_from_stitch.inverse();
    let source = |seg: &Segment| -> Result<Source<'_>, ExtractError> {
        let missing = |what: &str| ExtractError {
            primitive: seg.name.clone(),
            reason: format!("the demonstration has no {what} of {}", seg.instrument),
        };
        Ok(Source {
            record: demo.instrument(seg.instrument).ok_or_else(|| missing("record"))?,
            analysis: features.instrument(seg.instrument).ok_or_else(|| missing("features"))?,
            stitch_from_world,
        })
    };
    // 2D, linear and force-controlled primitives first: synchronized ones refer to a 2D primitive.
    let mut extracted: Vec<(usize, Primitive)> = Vec::new();
    for (k, seg) in decomposition.segments.iter().enumerate() {
        let src = source(seg)?;
        let primitive = match seg.kind {
            PrimitiveType::TwoD => Primitive::TwoD(two_d(&src, seg)?),
            PrimitiveType::Linear => Primitive::Linear(linear(&src, seg)?),
            PrimitiveType::Force => Primitive::Force(force(&src, seg, pattern.detector.force_smoothing_s)?),
            PrimitiveType::Synchronized => continue,
        };
        extracted.push((k, primitive));
    }
    for (k, seg) in decomposition.segments.iter().enumerate() {
        if seg.kind != PrimitiveType::Synchronized {
            continue;
        }
        let reference = seg.reference.as_deref().unwrap_or_default();
        let (plane, ref_seg) = extracted
            .iter()
            .find_map(|(j, p)| match p {
                Primitive::TwoD(t) if t.name == reference => Some((t.clone(), &decomposition.segments[*j])),
                _ => None,
            })
            .ok_or_else(|| ExtractError {
                primitive: seg.name.clone(),
                reason: format!("its reference '{reference}' is no extracted 2D primitive"),
            })?;
        let primitive = synchronized(&source(seg)?, seg, &source(ref_seg)?, &plane)?;
        extracted.push((k, Primitive::Synchronized(primitive)));
    }
    extracted.sort_by_key(|(k, _)| *k);
    let mut instruments: Vec<InstrumentPrimitives> = Vec::new();
    for (k, primitive) in extracted {
        let name = decomposition.segments[k].instrument.as_str().to_owned();
        match instruments.iter_mut().find(|i| i.instrument == name) {
            Some(i) => i.primitives.push(primitive),
            None => {
                let record = demo.instrument(decomposition.segments[k].instrument);
                let jaw = record.map(jaw_points).unwrap_or_default();
                let path = record.map(|r| path_keys(r, &stitch_from_world)).unwrap_or_default();
                instruments.push(InstrumentPrimitives {
                    instrument: name,
                    primitives: vec![primitive],
                    jaw,
                    path,
                });
            }
        }
    }
    let m = &demo.metadata;
    Ok(KnowledgeBase {
        format: KB_FORMAT.to_owned(),
        format_version: KB_FORMAT_VERSION,
        task: pattern.name.clone(),
        demonstration: DemonstrationInfo {
            source: m.source.clone(),
            scene: m.scene.clone(),
            seed: m.seed,
            sample_rate_hz: m.sample_rate_hz,
            description: m.description.clone(),
        },
        frame: "stitch".to_owned(),
        world_from_stitch: Pose {
            position_m: m.stitch.position_m,
            quaternion_xyzw: m.stitch.quaternion_xyzw,
        },
        instruments,
        dependencies: dependencies(pattern, decomposition),
    })
}

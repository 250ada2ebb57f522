//! What a knowledge base must hold beyond its schema: finite values in their physical ranges, unit
//! quaternions and axes, non-empty and ordered paths and profiles, instruments and dependencies that
//! resolve. Every problem is listed with the path of its field.

use super::{
    InstrumentPrimitives, KnowledgeBase, LinearPrimitive, Pose, Primitive, ProfilePoint, TwoDPrimitive,
};
use crate::demonstration::csv::{MAX_POSITION_M, MAX_TIP_SPEED_M_S};

/// How far a quaternion's or an axis's norm may be from 1.
pub const UNIT_TOLERANCE: f64 = 1e-6;
/// Most points one path, profile or mapping may hold (a demonstration of 100 s at 10 kHz).
pub const MAX_LIST_POINTS: usize = 1_000_000;
/// Spacing of a 2D primitive's path points, m: the detector's shape steps.
pub const STEP_RANGE_M: (f64, f64) = (1e-4, 0.01);
/// Largest force a force-controlled primitive may record, N.
pub const MAX_FORCE_N: f64 = 1000.0;
/// The instruments a skill can drive.
pub const INSTRUMENTS: [&str; 3] = ["left", "right", "assist"];

/// Every problem of `kb`, as (field path, reason).
pub fn problems(kb: &KnowledgeBase) -> Vec<(String, String)> {
    let mut p = Problems::default();
    p.pose("world_from_stitch", &kb.world_from_stitch);
    if kb.instruments.is_empty() {
        p.add("instruments", "is empty: a skill drives at least one instrument");
    }
    for (i, ip) in kb.instruments.iter().enumerate() {
        let at = format!("instruments[{i}]");
        if !INSTRUMENTS.contains(&ip.instrument.as_str()) {
            p.add(
                &format!("{at}.instrument"),
                format!("\"{}\" is not one of {INSTRUMENTS:?}", ip.instrument),
            );
        }
        if kb.instruments[..i].iter().any(|o| o.instrument == ip.instrument) {
            p.add(&format!("{at}.instrument"), format!("\"{}\" is given twice", ip.instrument));
        }
        p.instrument(&at, ip, kb);
    }
    let mut names: Vec<&str> = kb.instruments.iter().flat_map(|i| &i.primitives).map(|q| q.name()).collect();
    names.sort_unstable();
    for pair in names.windows(2).filter(|w| w[0] == w[1]) {
        p.add("instruments", format!("two primitives are named \"{}\"", pair[0]));
    }
    for (k, d) in kb.dependencies.iter().enumerate() {
        let at = format!("dependencies[{k}]");
        let (primitive, after) = (kb.primitive(&d.primitive), kb.primitive(&d.after));
        if primitive.is_none() {
            p.add(&format!("{at}.primitive"), format!("\"{}\" is no primitive of this skill", d.primitive));
        }
        if after.is_none() {
            p.add(&format!("{at}.after"), format!("\"{}\" is no primitive of this skill", d.after));
        }
        if let (Some(q), Some(a)) = (primitive, after) {
            // The pause is where the demonstration started the primitive after the end of `after`.
            let want = q.span_s().0 - a.span_s().1;
            if !(d.pause_s - want).abs().le(&1e-9) {
                p.add(
                    &format!("{at}.pause_s"),
                    format!("{} s, but the primitives' times give {want} s", d.pause_s),
                );
            }
        }
    }
    p.0
}

#[derive(Default)]
struct Problems(Vec<(String, String)>);

impl Problems {
    fn add(&mut self, field: &str, reason: impl Into<String>) {
        self.0.push((field.to_owned(), reason.into()));
    }

    fn within(&mut self, field: &str, value: f64, (lo, hi): (f64, f64), unit: &str) {
        if !(lo..=hi).contains(&value) {
            self.add(field, format!("{value} is not within {lo} to {hi} {unit}"));
        }
    }

    fn position(&mut self, field: &str, p: &[f64; 3]) {
        if p.iter().any(|x| !(-MAX_POSITION_M..=MAX_POSITION_M).contains(x)) {
            self.add(field, format!("{p:?} is not within ±{MAX_POSITION_M} m on every axis"));
        }
    }

    fn unit<const N: usize>(&mut self, field: &str, v: &[f64; N], what: &str) {
        let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(norm - 1.0).abs().le(&UNIT_TOLERANCE) {
            self.add(field, format!("{v:?} is not a unit {what} (norm {norm})"));
        }
    }

    fn pose(&mut self, field: &str, pose: &Pose) {
        self.position(&format!("{field}.position_m"), &pose.position_m);
        self.unit(&format!("{field}.quaternion_xyzw"), &pose.quaternion_xyzw, "quaternion");
    }

    fn span(&mut self, field: &str, (start, end): (f64, f64)) {
        if !(start.is_finite() && end.is_finite() && start <= end) {
            self.add(
                field,
                format!("start_s {start} and end_s {end}: both finite, the start not after the end"),
            );
        }
    }

    fn count(&mut self, field: &str, len: usize, least: usize) -> bool {
        if len < least || len > MAX_LIST_POINTS {
            self.add(field, format!("{len} points; {least} to {MAX_LIST_POINTS} are allowed"));
            return false;
        }
        true
    }

    /// Non-decreasing and finite, by `key`.
    fn ordered<T>(&mut self, field: &str, items: &[T], key: impl Fn(&T) -> f64, name: &str) {
        if let Some(k) = (0..items.len()).find(|&k| {
            let v = key(&items[k]);
            !v.is_finite() || (k > 0 && v < key(&items[k - 1]))
        }) {
            self.add(
                &format!("{field}[{k}].{name}"),
                format!("{} where finite values not below the one before are allowed", key(&items[k])),
            );
        }
    }

    fn jaw(&mut self, field: &str, rad: f64) {
        self.within(field, rad, (-std::f64::consts::PI, std::f64::consts::PI), "rad");
    }

    fn profile(&mut self, field: &str, profile: &[ProfilePoint]) {
        if self.count(field, profile.len(), 1) {
            self.ordered(field, profile, |q| q.s_m, "s_m");
            for (k, q) in profile.iter().enumerate() {
                self.within(&format!("{field}[{k}].speed_mps"), q.speed_mps, (0.0, MAX_TIP_SPEED_M_S), "m/s");
            }
        }
    }

    fn instrument(&mut self, at: &str, ip: &InstrumentPrimitives, kb: &KnowledgeBase) {
        for (j, q) in ip.primitives.iter().enumerate() {
            let at = format!("{at}.primitives[{j}]");
            self.span(&at, q.span_s());
            match q {
                Primitive::TwoD(t) => self.two_d(&at, t),
                Primitive::Linear(l) => self.linear(&at, l),
                Primitive::Force(f) => {
                    self.pose(&format!("{at}.start_pose"), &f.start_pose);
                    self.pose(&format!("{at}.end_pose"), &f.end_pose);
                    self.position(&format!("{at}.line_end_m"), &f.line_end_m);
                    self.within(&format!("{at}.max_force_n"), f.max_force_n, (0.0, MAX_FORCE_N), "N");
                    self.unit(&format!("{at}.force_direction"), &f.force_direction, "vector");
                    self.jaw(&format!("{at}.jaw.from_rad"), f.jaw.from_rad);
                    self.jaw(&format!("{at}.jaw.to_rad"), f.jaw.to_rad);
                    let duration = q.span_s().1 - q.span_s().0;
                    self.within(&format!("{at}.jaw.at_s"), f.jaw.at_s, (0.0, duration.max(0.0)), "s");
                    self.profile(&format!("{at}.speed_profile"), &f.speed_profile);
                }
                Primitive::Synchronized(s) => {
                    if !matches!(kb.primitive(&s.reference), Some(Primitive::TwoD(_))) {
                        self.add(
                            &format!("{at}.reference"),
                            format!("\"{}\" is no 2D primitive of this skill", s.reference),
                        );
                    }
                    let field = format!("{at}.mapping");
                    if self.count(&field, s.mapping.len(), 1) {
                        self.ordered(&field, &s.mapping, |m| m.phase, "phase");
                        for (k, m) in s.mapping.iter().enumerate() {
                            let at = format!("{field}[{k}]");
                            self.within(&format!("{at}.phase"), m.phase, (0.0, 1.0), "");
                            self.position(&format!("{at}.position_plane_m"), &m.position_plane_m);
                            self.position(&format!("{at}.offset_m"), &m.offset_m);
                            self.unit(&format!("{at}.quaternion_xyzw"), &m.quaternion_xyzw, "quaternion");
                            self.jaw(&format!("{at}.jaw_rad"), m.jaw_rad);
                        }
                    }
                }
            }
        }
        let field = format!("{at}.jaw");
        if self.count(&field, ip.jaw.len(), 0) {
            self.ordered(&field, &ip.jaw, |j| j.time_s, "time_s");
            for (k, j) in ip.jaw.iter().enumerate() {
                self.jaw(&format!("{field}[{k}].jaw_rad"), j.jaw_rad);
            }
        }
        let field = format!("{at}.path");
        if self.count(&field, ip.path.len(), 0) {
            self.ordered(&field, &ip.path, |k| k.time_s, "time_s");
            for (k, key) in ip.path.iter().enumerate() {
                let at = format!("{field}[{k}]");
                self.position(&format!("{at}.position_m"), &key.position_m);
                self.unit(&format!("{at}.jaw_direction"), &key.jaw_direction, "vector");
                if let Some(q) = &key.quaternion_xyzw {
                    self.unit(&format!("{at}.quaternion_xyzw"), q, "quaternion");
                }
            }
        }
    }

    fn two_d(&mut self, at: &str, t: &TwoDPrimitive) {
        self.position(&format!("{at}.plane.origin_m"), &t.plane.origin_m);
        self.unit(&format!("{at}.plane.axis_x"), &t.plane.axis_x, "vector");
        self.unit(&format!("{at}.plane.axis_y"), &t.plane.axis_y, "vector");
        let dot: f64 = t.plane.axis_x.iter().zip(&t.plane.axis_y).map(|(a, b)| a * b).sum();
        if !dot.abs().le(&UNIT_TOLERANCE) {
            self.add(&format!("{at}.plane.axis_y"), format!("is not perpendicular to axis_x (dot {dot})"));
        }
        self.within(&format!("{at}.step_m"), t.step_m, STEP_RANGE_M, "m");
        self.within(&format!("{at}.rms_out_of_plane_m"), t.rms_out_of_plane_m, (0.0, MAX_POSITION_M), "m");
        self.within(&format!("{at}.turns"), t.turns, (-1e3, 1e3), "turns");
        self.jaw(&format!("{at}.jaw_rad"), t.jaw_rad);
        self.pose(&format!("{at}.start_pose"), &t.start_pose);
        self.pose(&format!("{at}.end_pose"), &t.end_pose);
        let field = format!("{at}.path_m");
        if self.count(&field, t.path_m.len(), 2) {
            if let Some(k) = t
                .path_m
                .iter()
                .position(|q| q.iter().any(|x| !(-MAX_POSITION_M..=MAX_POSITION_M).contains(x)))
            {
                self.add(
                    &format!("{field}[{k}]"),
                    format!("{:?} is not within ±{MAX_POSITION_M} m", t.path_m[k]),
                );
            }
            if t.speed_mps.len() != t.path_m.len() {
                self.add(
                    &format!("{at}.speed_mps"),
                    format!("{} speeds for {} path points: one per point", t.speed_mps.len(), t.path_m.len()),
                );
            }
        }
        if let Some(k) = t.speed_mps.iter().position(|v| !(0.0..=MAX_TIP_SPEED_M_S).contains(v)) {
            self.add(
                &format!("{at}.speed_mps[{k}]"),
                format!("{} is not within 0 to {MAX_TIP_SPEED_M_S} m/s", t.speed_mps[k]),
            );
        }
    }

    fn linear(&mut self, at: &str, l: &LinearPrimitive) {
        self.pose(&format!("{at}.start_pose"), &l.start_pose);
        self.pose(&format!("{at}.end_pose"), &l.end_pose);
        self.within(&format!("{at}.path_length_m"), l.path_length_m, (0.0, MAX_POSITION_M), "m");
        self.within(&format!("{at}.max_deviation_m"), l.max_deviation_m, (0.0, MAX_POSITION_M), "m");
        self.jaw(&format!("{at}.jaw_rad[0]"), l.jaw_rad[0]);
        self.jaw(&format!("{at}.jaw_rad[1]"), l.jaw_rad[1]);
        self.profile(&format!("{at}.speed_profile"), &l.speed_profile);
    }
}

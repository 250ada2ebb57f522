//! The scripted expert's tie geometry from a TOML file (`knotlab demo --expert FILE`), so that a
//! researcher can move the winding point or the pulls without touching code. Only the keys given
//! change the base plan ([`TieGeometry::default`]); an unknown key, a wrong type or a value out of
//! range is refused, naming the file, the key (and line) and why. `scenarios/experts/base.toml` lists
//! every key with its base value; `scenarios/experts/instrument-tie.toml` is the shipped plan, the one
//! `knotlab demo` runs unless told otherwise.

use std::path::Path;

use super::geometry::{LeftFetch, TieGeometry};

/// Why a tie geometry file was refused (`Invalid`: every value out of range, with its key).
pub type GeometryFileError = knotlab_hw::toml_file::TomlFileError;

/// Parses a tie geometry; `file` names it in errors.
pub fn parse_tie_geometry(text: &str, file: &str) -> Result<TieGeometry, GeometryFileError> {
    knotlab_hw::toml_file::parse_checked(text, file, range_problems)
}

/// Reads and parses a tie geometry file.
pub fn load_tie_geometry(path: &Path) -> Result<TieGeometry, GeometryFileError> {
    knotlab_hw::toml_file::load_checked(path, range_problems)
}

/// Collects every value out of its range.
struct Check(Vec<(String, String)>);

impl Check {
    fn range(&mut self, key: &str, value: f64, lo: f64, hi: f64) {
        if !(value.is_finite() && value >= lo && value <= hi) {
            self.0.push((key.to_owned(), format!("must be within {lo}..{hi}, got {value}")));
        }
    }

    /// A point of the stitch frame, within 0.2 m of the stitch.
    fn point(&mut self, key: &str, p: &[f64; 3]) {
        for (axis, v) in ["x", "y", "z"].iter().zip(p) {
            self.range(&format!("{key}.{axis}"), *v, -0.2, 0.2);
        }
    }

    /// A direction: finite, not zero.
    fn direction(&mut self, key: &str, d: &[f64; 3]) {
        let norm = d.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm.is_finite() && norm > 1e-9) {
            self.0.push((key.to_owned(), format!("must be a direction (finite, not zero), got {d:?}")));
        }
    }

    /// How the left fetches the tail, its keys under `table`.
    fn fetch(&mut self, table: &str, f: &LeftFetch) {
        self.range(&format!("{table}.along_tail"), f.along_tail, 0.0, 1.0);
        self.direction(&format!("{table}.jaw_direction"), &f.jaw_direction);
        self.range(&format!("{table}.approach_m"), f.approach_m, 0.0, 0.1);
        self.range(&format!("{table}.stop_short_m"), f.stop_short_m, -0.05, 0.05);
        self.range(&format!("{table}.right_follows"), f.right_follows, 0.0, 1.0);
        if let Some(offset) = &f.right_beside_m {
            self.point(&format!("{table}.right_beside_m"), offset);
        }
    }
}

fn range_problems(g: &TieGeometry) -> Vec<(String, String)> {
    let mut c = Check(Vec::new());
    for (key, p) in [
        ("winding_point_m", &g.winding_point_m),
        ("left_run_down_to_m", &g.left_run_down_to_m),
        ("right_run_down_to_m", &g.right_run_down_to_m),
        ("left_pull_to_m", &g.left_pull_to_m),
        ("right_pull_to_m", &g.right_pull_to_m),
        ("assist_retreat_m", &g.assist_retreat_m),
    ] {
        c.point(key, p);
    }
    for (k, p) in g.tail_via_m.iter().enumerate() {
        c.point(&format!("tail_via_m[{k}]"), p);
    }
    if let Some(p) = &g.tail_brought_to_m {
        c.point("tail_brought_to_m", p);
    }
    c.direction("winding_towards", &g.winding_towards);
    if let Some(d) = &g.left_jaw_direction {
        c.direction("left_jaw_direction", d);
    }
    if let Some(d) = &g.assist_jaw_direction {
        c.direction("assist_jaw_direction", d);
    }
    for (key, v) in [
        ("winding_behind_m", g.winding_behind_m),
        ("winding_pitch_m", g.winding_pitch_m),
        ("tail_ahead_m", g.tail_ahead_m),
        ("loosen_m", g.loosen_m),
        ("coils_back_m", g.coils_back_m),
        ("tail_tension_m", g.tail_tension_m),
        ("tail_beyond_m", g.tail_beyond_m),
        ("tail_take_short_m", g.tail_take_short_m),
        ("draw_back_m", g.draw_back_m),
    ] {
        c.range(key, v, -0.1, 0.1);
    }
    c.range("winding_radius_m", g.winding_radius_m, 1e-3, 0.1);
    c.range("winding_lead_rad", g.winding_lead_rad, -std::f64::consts::TAU, std::f64::consts::TAU);
    c.range("winding_s", g.winding_s, 0.1, 60.0);
    c.range("run_down_s", g.run_down_s, 0.1, 60.0);
    c.range("winding_turns", g.winding_turns, 0.0, 5.0);
    c.range("take_tail_jaw_rad", g.take_tail_jaw_rad, 0.0, 1.6);
    c.range("winding_jaw_rad", g.winding_jaw_rad, 0.0, 1.6);
    if let Some(f) = g.winding_give_force_n {
        c.range("winding_give_force_n", f, 0.001, 5.0);
    }
    c.range("winding_give_rate_m_per_n_s", g.winding_give_rate_m_per_n_s, 1e-4, 1.0);
    c.range("winding_give_after_s", g.winding_give_after_s, 0.0, 10.0);
    c.range("speed_fraction", g.speed_fraction, 0.01, 1.0);
    c.range("pull_force_n", g.pull_force_n, 0.01, 10.0);
    if let Some(f) = g.tail_pull_force_n {
        c.range("tail_pull_force_n", f, 0.01, 10.0);
    }
    c.range("pull_force_sustain_s", g.pull_force_sustain_s, 0.0, 5.0);
    for (key, v) in [
        ("tail_give_fraction", g.tail_give_fraction),
        ("draw_relax", g.draw_relax),
        ("right_jaws_across_winding", g.right_jaws_across_winding),
    ] {
        c.range(key, v, 0.0, 1.0);
    }
    c.range("right_follows_draw", g.right_follows_draw, -1.0, 1.0);
    for (k, p) in g.right_before_draw_m.iter().enumerate() {
        c.point(&format!("right_before_draw_m[{k}]"), p);
    }
    for (k, p) in g.left_run_down_via_m.iter().enumerate() {
        c.point(&format!("left_run_down_via_m[{k}]"), p);
    }
    for (k, p) in g.right_run_down_via_m.iter().enumerate() {
        c.point(&format!("right_run_down_via_m[{k}]"), p);
    }
    if let Some(p) = &g.right_draws_to_m {
        c.point("right_draws_to_m", p);
    }
    c.range("draw_s", g.draw_s, 0.1, 60.0);
    c.range("pull_s", g.pull_s, 0.1, 60.0);
    c.range("pull_on_m", g.pull_on_m, 0.0, 0.2);
    if let Some(v) = g.tail_end_offered_m {
        c.range("tail_end_offered_m", v, 0.0, 0.05);
        if g.fetch().is_some() {
            c.0.push((
                "tail_end_offered_m".to_owned(),
                "cannot be set with left_fetches: the left fetches the tail, nothing is offered".to_owned(),
            ));
        }
    }
    if let Some(f) = g.run_down_force_n {
        c.range("run_down_force_n", f, 0.01, 10.0);
    }
    c.range("tail_swing_lean.x", g.tail_swing_lean[0], -10.0, 10.0);
    c.range("tail_swing_lean.y", g.tail_swing_lean[1], -10.0, 10.0);
    c.range("tail_swing_lean.z", g.tail_swing_lean[2], -10.0, 10.0);
    if let Some(f) = &g.left_fetches {
        c.fetch("left_fetches", f);
    }
    if let Some(s) = &g.second_throw {
        c.range("second_throw.tail_hold_along", s.tail_hold_along, 0.0, 1.0);
        if s.assist_presents && s.left_keeps_tail {
            c.0.push((
                "second_throw.assist_presents".to_owned(),
                "cannot be set with left_keeps_tail: the left holds the tail already".to_owned(),
            ));
        }
        if let Some(v) = s.tail_hold_from_end_m {
            c.range("second_throw.tail_hold_from_end_m", v, 0.0, 1.0);
        }
        if s.left_keeps_tail && s.left_lets_go_first {
            c.0.push((
                "second_throw.left_lets_go_first".to_owned(),
                "cannot be set with left_keeps_tail: the left cannot both let go of the tail and keep it"
                    .to_owned(),
            ));
        }
        if s.left_keeps_tail && s.tail_hold_from_end_m.is_some() {
            c.0.push((
                "second_throw.tail_hold_from_end_m".to_owned(),
                "cannot be set with left_keeps_tail: the assist takes no tail".to_owned(),
            ));
        }
        if let Some(v) = s.left_retakes_from_end_m {
            c.range("second_throw.left_retakes_from_end_m", v, 0.0, 0.1);
            if s.tail_hold_from_end_m.is_none() {
                c.0.push((
                    "second_throw.left_retakes_from_end_m".to_owned(),
                    "needs tail_hold_from_end_m: the left retakes the tail the assist holds by its end"
                        .to_owned(),
                ));
            } else if s.tail_hold_from_end_m.is_some_and(|held| v <= held) {
                c.0.push((
                    "second_throw.left_retakes_from_end_m".to_owned(),
                    "must be more than tail_hold_from_end_m: the left takes the tail between the assist's jaws and the knot"
                        .to_owned(),
                ));
            }
        }
        if let Some(p) = &s.tail_brought_to_m {
            c.point("second_throw.tail_brought_to_m", p);
        }
        if let Some(p) = &s.tail_held_to_m {
            c.point("second_throw.tail_held_to_m", p);
            if s.tail_hold_from_end_m.is_none() {
                c.0.push((
                    "second_throw.tail_held_to_m".to_owned(),
                    "needs tail_hold_from_end_m: the assist draws the tail by its end".to_owned(),
                ));
            }
        }
        if let Some(share) = s.tail_held_taut {
            c.range("second_throw.tail_held_taut", share, 0.1, 1.0);
            if s.tail_held_to_m.is_none() {
                c.0.push((
                    "second_throw.tail_held_taut".to_owned(),
                    "needs tail_held_to_m: it bounds how far the assist draws the tail there".to_owned(),
                ));
            }
        }
        if let Some(d) = &s.left_jaw_direction {
            c.direction("second_throw.left_jaw_direction", d);
        }
        if let Some(f) = &s.left_fetches {
            c.fetch("second_throw.left_fetches", f);
        }
        c.direction("second_throw.winding_towards", &s.winding_towards);
        if let Some(v) = s.winding_lead_rad {
            let tau = std::f64::consts::TAU;
            c.range("second_throw.winding_lead_rad", v, -tau, tau);
        }
        if let Some(v) = s.tail_end_offered_m {
            c.range("second_throw.tail_end_offered_m", v, 0.0, 0.05);
            // Offered only where the assist presents the tail: not when the left fetches it or keeps it.
            let fetched = !s.assist_presents && (s.left_fetches.is_some() || g.left_fetches.is_some());
            if s.left_keeps_tail || fetched {
                c.0.push((
                    "second_throw.tail_end_offered_m".to_owned(),
                    "needs the tail presented (assist_presents, or no left_fetches): nothing is offered otherwise"
                        .to_owned(),
                ));
            }
        }
        if let Some(v) = s.take_tail_jaw_rad {
            c.range("second_throw.take_tail_jaw_rad", v, 0.0, 1.6);
        }
        if let Some(v) = s.tail_ahead_m {
            c.range("second_throw.tail_ahead_m", v, -0.1, 0.1);
        }
        if let Some(v) = s.winding_radius_m {
            c.range("second_throw.winding_radius_m", v, 0.001, 0.1);
        }
        if let Some(v) = s.winding_behind_m {
            c.range("second_throw.winding_behind_m", v, -0.1, 0.1);
        }
        if let Some(v) = s.winding_pitch_m {
            c.range("second_throw.winding_pitch_m", v, -0.1, 0.1);
        }
        if let Some(v) = s.tail_take_short_m {
            c.range("second_throw.tail_take_short_m", v, -0.1, 0.1);
        }
        if let Some(v) = s.loosen_m {
            c.range("second_throw.loosen_m", v, -0.1, 0.1);
        }
        if let Some(v) = s.draw_back_m {
            c.range("second_throw.draw_back_m", v, -0.1, 0.1);
        }
        if let Some(v) = s.right_follows_draw {
            c.range("second_throw.right_follows_draw", v, -1.0, 1.0);
        }
        for (k, p) in s.right_before_draw_m.iter().enumerate() {
            c.point(&format!("second_throw.right_before_draw_m[{k}]"), p);
        }
        for (k, p) in s.left_run_down_via_m.iter().enumerate() {
            c.point(&format!("second_throw.left_run_down_via_m[{k}]"), p);
        }
        for (k, p) in s.right_run_down_via_m.iter().enumerate() {
            c.point(&format!("second_throw.right_run_down_via_m[{k}]"), p);
        }
        if let Some(p) = &s.right_draws_to_m {
            c.point("second_throw.right_draws_to_m", p);
        }
        if let Some(v) = s.draw_s {
            c.range("second_throw.draw_s", v, 0.1, 60.0);
        }
        if let Some(v) = s.pull_s {
            c.range("second_throw.pull_s", v, 0.1, 60.0);
        }
        for (key, force) in [
            ("second_throw.pull_force_n", s.pull_force_n),
            ("second_throw.tail_pull_force_n", s.tail_pull_force_n),
        ] {
            if let Some(v) = force {
                c.range(key, v, 0.01, 10.0);
            }
        }
        if let Some(v) = s.run_down_force_n {
            c.range("second_throw.run_down_force_n", v, 0.01, 10.0);
        }
        c.range("second_throw.winding_turns", s.winding_turns, 0.0, 5.0);
        for (key, p) in [
            ("second_throw.winding_point_m", &s.winding_point_m),
            ("second_throw.left_run_down_to_m", &s.left_run_down_to_m),
            ("second_throw.right_run_down_to_m", &s.right_run_down_to_m),
            ("second_throw.left_pull_to_m", &s.left_pull_to_m),
            ("second_throw.right_pull_to_m", &s.right_pull_to_m),
        ] {
            c.point(key, p);
        }
    }
    c.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `experts/base.toml` parses to exactly the base plan, so its listed values match the code's.
    #[test]
    fn the_base_file_is_the_base_plan() {
        let g = parse_tie_geometry(include_str!("../../experts/base.toml"), "base.toml")
            .expect("the base file parses");
        assert_eq!(g, TieGeometry::default());
    }

    /// A tie geometry file changes only the keys it gives; every other value stays the base plan's.
    #[test]
    fn only_the_keys_given_change() {
        let g = parse_tie_geometry("pull_force_n = 2.5\n[left_fetches]\nalong_tail = 0.4\njaw_direction = [0.0, 0.0, -1.0]\napproach_m = 0.01\nstop_short_m = 0.0\n", "x.toml").unwrap();
        let shipped = TieGeometry::default();
        assert_eq!(g.pull_force_n, 2.5);
        assert_eq!(g.left_fetches.as_ref().map(|f| f.along_tail), Some(0.4));
        assert_eq!(
            TieGeometry {
                pull_force_n: shipped.pull_force_n,
                left_fetches: shipped.left_fetches.clone(),
                ..g
            },
            shipped
        );
    }

    /// `tail_end_offered_m` is refused unless the assist presents the tail, and then the left fetches
    /// nothing; a second throw does not inherit the assist presenting.
    #[test]
    fn where_the_assist_presents_the_tail_the_left_fetches_nothing_and_the_tail_end_may_be_offered() {
        // Shipped, the left fetches: nothing is offered.
        assert!(TieGeometry::default().fetch().is_some());
        let refused = parse_tie_geometry("tail_end_offered_m = 0.004\n", "x.toml");
        assert!(
            matches!(&refused, Err(GeometryFileError::Invalid { problems, .. }) if problems[0].0 == "tail_end_offered_m"),
            "{refused:?}"
        );
        let g = parse_tie_geometry("assist_presents = true\ntail_end_offered_m = 0.004\n", "x.toml").unwrap();
        assert!(g.fetch().is_none());
        assert_eq!(g.tail_end_offered_m, Some(0.004));
        // The second throw does not inherit it: its own keys decide who brings the tail.
        let first = TieGeometry { assist_presents: true, ..TieGeometry::default() };
        let fetching = crate::expert::SecondThrow::default().applied_to(&first);
        assert!(fetching.fetch().is_some(), "{fetching:?}");
    }

    /// A `[second_throw]` table fills the keys it leaves out from the second throw's defaults and leaves the
    /// first throw as the base plan.
    #[test]
    fn a_second_throw_table_takes_its_own_defaults_for_keys_left_out() {
        let g = parse_tie_geometry("[second_throw]\nwinding_turns = 2.0\n", "x.toml").unwrap();
        let second = g.second_throw.expect("a second throw");
        assert_eq!(second.winding_turns, 2.0);
        assert_eq!(second.tail_hold_along, crate::expert::SecondThrow::default().tail_hold_along);
        // The first throw is the shipped one.
        assert_eq!(TieGeometry { second_throw: None, ..g }, TieGeometry::default());
    }

    /// A file with an unknown key, a wrong type or any value out of range is refused, naming the file, the
    /// key (and line) and why, for every problem, the second throw's included.
    #[test]
    fn bad_files_name_the_key_and_why() {
        let schema = |text: &str| match parse_tie_geometry(text, "bad.toml") {
            Err(GeometryFileError::Schema { file, line, key, .. }) => (file, line, key),
            other => panic!("{text}: {other:?}"),
        };
        assert_eq!(schema("pull_force = 2.0\n"), ("bad.toml".to_owned(), 1, "pull_force".to_owned()));
        assert_eq!(schema("\nwinding_turns = \"two\"\n").2, "winding_turns");
        assert_eq!(schema("[left_fetches]\nalong_tail = 0.4\n").2, "left_fetches");
        assert!(matches!(
            parse_tie_geometry("winding_s = ", "bad.toml"),
            Err(GeometryFileError::Schema { .. })
        ));
        let Err(GeometryFileError::Invalid { problems, .. }) = parse_tie_geometry(
            "pull_force_n = -1.0\nwinding_towards = [0.0, 0.0, 0.0]\nleft_pull_to_m = [0.0, 0.5, 0.0]\n",
            "bad.toml",
        ) else {
            panic!("out of range accepted");
        };
        let keys: Vec<&str> = problems.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(keys, ["left_pull_to_m.y", "winding_towards", "pull_force_n"], "{problems:?}");
        // The wind that keeps the tension: a force that is none and a rate that never gives.
        let Err(GeometryFileError::Invalid { problems, .. }) =
            parse_tie_geometry("winding_give_force_n = 0.0\nwinding_give_rate_m_per_n_s = 0.0\n", "bad.toml")
        else {
            panic!("a give of no force accepted");
        };
        let keys: Vec<&str> = problems.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(keys, ["winding_give_force_n", "winding_give_rate_m_per_n_s"], "{problems:?}");
        let Err(GeometryFileError::Invalid { problems, .. }) =
            parse_tie_geometry("[second_throw]\ntail_hold_along = 1.5\n", "bad.toml")
        else {
            panic!("out of range accepted");
        };
        assert_eq!(problems[0].0, "second_throw.tail_hold_along", "{problems:?}");
        let Err(GeometryFileError::Invalid { problems, .. }) = parse_tie_geometry(
            "tail_pull_force_n = 0.0\nright_jaws_across_winding = 1.5\nwinding_pitch_m = 0.5\ndraw_s = 0.0\ntail_end_offered_m = 0.01\n\
             run_down_force_n = -1.0\nright_draws_to_m = [0.0, 0.0, 0.3]\n\
             right_before_draw_m = [[0.0, 0.0, 0.0], [0.0, 0.3, 0.0]]\nright_run_down_via_m = [[0.4, 0.0, 0.0]]\n[second_throw]\n\
             left_jaw_direction = [0.0, 0.0, 0.0]\nwinding_lead_rad = 7.0\nloosen_m = 0.5\ntail_take_short_m = 0.5\ndraw_back_m = 0.5\n\
             right_follows_draw = -5.0\nright_draws_to_m = [0.3, 0.0, 0.0]\ndraw_s = 100.0\n\
             right_before_draw_m = [[0.3, 0.0, 0.0]]\nleft_run_down_via_m = [[0.0, 0.0, -0.3]]\n\
             right_run_down_via_m = [[0.0, 0.0, 0.0], [0.0, -0.3, 0.0]]\npull_force_n = 0.0\npull_s = 0.0\n\
             run_down_force_n = 0.0\nassist_presents = true\nleft_keeps_tail = true\nleft_lets_go_first = true\n\
             tail_hold_from_end_m = -0.01\ntail_held_to_m = [0.0, 0.5, 0.0]\ntail_held_taut = 2.0\n\
             tail_brought_to_m = [0.0, 0.0, -0.3]\n\
             winding_radius_m = 0.0\nwinding_behind_m = 0.5\nwinding_pitch_m = 0.2\ntake_tail_jaw_rad = 2.0\ntail_end_offered_m = 0.1\n\
             tail_ahead_m = 0.5\n\
             [second_throw.left_fetches]\nalong_tail = 2.0\n\
             jaw_direction = [0.0, 0.0, -1.0]\napproach_m = 0.01\nstop_short_m = 0.0\nright_follows = 3.0\n\
             right_beside_m = [0.0, 0.0, 0.3]\n",
            "bad.toml",
        ) else {
            panic!("out of range accepted");
        };
        let keys: Vec<&str> = problems.iter().map(|(k, _)| k.as_str()).collect();
        for key in [
            "tail_pull_force_n",
            "right_jaws_across_winding",
            "winding_pitch_m",
            "draw_s",
            "run_down_force_n",
            "right_draws_to_m.z",
            "right_before_draw_m[1].y",
            "second_throw.right_before_draw_m[0].x",
            "second_throw.left_run_down_via_m[0].z",
            "right_run_down_via_m[0].x",
            "second_throw.right_run_down_via_m[1].y",
            "second_throw.pull_force_n",
            "second_throw.pull_s",
            "second_throw.left_jaw_direction",
            "second_throw.assist_presents",
            "second_throw.winding_lead_rad",
            "second_throw.loosen_m",
            "second_throw.tail_take_short_m",
            "second_throw.draw_back_m",
            "second_throw.right_follows_draw",
            "second_throw.right_draws_to_m.x",
            "second_throw.draw_s",
            "second_throw.run_down_force_n",
            "second_throw.left_fetches.along_tail",
            "second_throw.tail_hold_from_end_m",
            "second_throw.tail_held_to_m.y",
            "second_throw.tail_brought_to_m.z",
            "second_throw.tail_held_taut",
            "second_throw.left_lets_go_first",
            "second_throw.left_fetches.right_follows",
            "second_throw.left_fetches.right_beside_m.z",
            "second_throw.winding_radius_m",
            "second_throw.winding_behind_m",
            "second_throw.winding_pitch_m",
            "second_throw.take_tail_jaw_rad",
            "second_throw.tail_end_offered_m",
            "second_throw.tail_ahead_m",
            "tail_end_offered_m",
        ] {
            assert!(keys.contains(&key), "{key} not named: {problems:?}");
        }
        // The left retakes the tail only where the assist holds it by its end, and nearer the knot.
        let retake_problems = |text: &str| match parse_tie_geometry(text, "bad.toml") {
            Err(GeometryFileError::Invalid { problems, .. }) => problems,
            other => panic!("{text}: {other:?}"),
        };
        let alone = retake_problems("[second_throw]\nleft_retakes_from_end_m = 0.017\n");
        assert_eq!(alone[0].0, "second_throw.left_retakes_from_end_m", "{alone:?}");
        assert!(alone[0].1.contains("needs tail_hold_from_end_m"), "{alone:?}");
        let inside = retake_problems(
            "[second_throw]\ntail_hold_from_end_m = 0.004\nleft_retakes_from_end_m = 0.004\n",
        );
        assert!(inside[0].1.contains("more than tail_hold_from_end_m"), "{inside:?}");
        let far =
            retake_problems("[second_throw]\ntail_hold_from_end_m = 0.004\nleft_retakes_from_end_m = 0.5\n");
        assert_eq!(far[0].0, "second_throw.left_retakes_from_end_m", "{far:?}");
        assert!(
            parse_tie_geometry(
                "[second_throw]\ntail_hold_from_end_m = 0.004\nleft_retakes_from_end_m = 0.017\n",
                "ok.toml"
            )
            .is_ok()
        );
        let missing = load_tie_geometry(Path::new("/nonexistent/expert.toml")).unwrap_err().to_string();
        assert!(missing.starts_with("/nonexistent/expert.toml: cannot read"), "{missing}");
    }
}

//! How far the left can carry the turns wound round its jaws: the long end runs from the stitch's
//! exit up to the jaws, round them and on to the needle in the right's jaws, and it has only so much
//! thread. Taken further, the turns are drawn tight and pulled off the jaws' tips. The second throw
//! leaves about 80 mm of long end; fetched 0.35 of the way to a tail drawn out to the assist (47-62
//! mm from the exit, the right 19-79 mm beyond), the turn came off on the way in every run, while a
//! take the thread reached kept it (`docs/notebook/knot-tying-notes.md`). The fetch therefore
//! takes the tail no further out than the long end reaches.

use nalgebra::Vector3;

/// The thread one turn round the left's open jaws takes, m (about their width's girth).
pub const TURN_THREAD_M: f64 = 0.015;

/// Thread the long end keeps to spare beyond the straight ways and the turns, m.
pub const SPARE_M: f64 = 0.01;

/// The least share of the way to the tail the fetch goes, whatever the long end.
pub const MIN_ALONG: f64 = 0.1;

/// The step by which the share is cut.
const STEP: f64 = 0.01;

/// The long end's thread the turns need with the left's jaws at `jaws_m` and the right's at
/// `right_m`: straight from the exit to the jaws, `turns` turns round them, straight on to the
/// right, m.
pub fn thread_needed_m(
    exit_m: &Vector3<f64>,
    jaws_m: &Vector3<f64>,
    right_m: &Vector3<f64>,
    turns: f64,
) -> f64 {
    (jaws_m - exit_m).norm() + turns.abs() * TURN_THREAD_M + (right_m - jaws_m).norm()
}

/// The largest share of the way from `entry_m` to `tail_hold_m`, no more than `along`, at which
/// the left's jaws with their turns are within the long end's `long_end_m` (less [`SPARE_M`]), the
/// right standing at `right_at(jaws)`; no less than [`MIN_ALONG`] (or `along`, if that is less).
pub fn along_within_long_end(
    along: f64,
    long_end_m: f64,
    turns: f64,
    exit_m: &Vector3<f64>,
    entry_m: &Vector3<f64>,
    tail_hold_m: &Vector3<f64>,
    right_at: impl Fn(&Vector3<f64>) -> Vector3<f64>,
) -> f64 {
    let fits = |share: f64| {
        let jaws = entry_m + (tail_hold_m - entry_m) * share;
        thread_needed_m(exit_m, &jaws, &right_at(&jaws), turns) <= long_end_m - SPARE_M
    };
    let least = MIN_ALONG.min(along);
    let mut share = along;
    while share > least && !fits(share) {
        share = (share - STEP).max(least);
    }
    share
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stitch (exit 9 mm from the entry), a tail held 150 mm out and 60 mm up.
    fn stitch() -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        (Vector3::new(0.0, -0.0045, 0.0), Vector3::new(0.0, 0.0045, 0.0), Vector3::new(0.0, 0.15, 0.06))
    }

    /// With long end to spare, the fetch takes the tail as far out as asked, not cut short.
    #[test]
    fn the_fetch_goes_as_far_as_asked_when_the_long_end_reaches() {
        let (exit, entry, hold) = stitch();
        let beside = |jaws: &Vector3<f64>| jaws + Vector3::new(-0.015, 0.0, 0.012);
        assert_eq!(along_within_long_end(0.35, 0.2, 1.0, &exit, &entry, &hold, beside), 0.35);
    }

    /// A long end too short for the asked fetch stops it at the furthest point its thread reaches, nearer
    /// still when the right stands far back, and never below the least share.
    #[test]
    fn a_short_long_end_keeps_the_fetch_near_the_stitch() {
        let (exit, entry, hold) = stitch();
        let beside = |jaws: &Vector3<f64>| jaws + Vector3::new(-0.015, 0.0, 0.012);
        let along = along_within_long_end(0.35, 0.08, 1.0, &exit, &entry, &hold, beside);
        assert!((MIN_ALONG..0.35).contains(&along), "{along}");
        let jaws = entry + (hold - entry) * along;
        assert!(thread_needed_m(&exit, &jaws, &beside(&jaws), 1.0) <= 0.08 - SPARE_M);
        // One step further would need more than the long end has.
        let further = entry + (hold - entry) * (along + STEP);
        assert!(thread_needed_m(&exit, &further, &beside(&further), 1.0) > 0.08 - SPARE_M);
        // A right left standing far back needs more: the fetch stays nearer still, down to its least.
        let stays = |_: &Vector3<f64>| Vector3::new(-0.003, -0.006, 0.045);
        let nearer = along_within_long_end(0.35, 0.08, 1.0, &exit, &entry, &hold, stays);
        assert!(nearer < along, "{nearer} against {along}");
        assert_eq!(along_within_long_end(0.35, 0.01, 1.0, &exit, &entry, &hold, stays), MIN_ALONG);
    }
}

//! Where the tail lies, as the expert sees it before it reaches for it (a surgeon looks at the
//! endoscope's picture): points on the thread between the stitch and its free end, world frame.

use knotlab_hw::rig::ArmName;
use knotlab_sim::tissue::Flap;
use knotlab_sim::world::SimWorld;
use nalgebra::Vector3;

/// How high over the tissue the tail must lie for jaws to close on it, m: a jaw (1.5 mm round)
/// under a tail lying on the tissue would press into it, and the grip pinning the tail there tore
/// (the left's grasp read 6 N within 4 ms of taking a tail that lay on the flap).
pub const TAKE_CLEARANCE_M: f64 = 0.003;

/// The tail's point nearest the line of jaws at `jaw_centre_m` pointing along `jaws` (world
/// frame), ahead of them (not behind the jaw centre), between the stitch and the assist's jaws
/// (the free end if the assist holds none), of those at least [`TAKE_CLEARANCE_M`] over the
/// tissue (any, if none is), and which way the tail runs there (towards its end); `None` if the
/// stitch holds no thread or no tail lies ahead.
pub fn tail_ahead_of_jaws(
    world: &SimWorld,
    jaw_centre_m: &Vector3<f64>,
    jaws: &Vector3<f64>,
) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let inside = world.thread_inside()?;
    let line = world.thread_centreline();
    let from = *inside.end() + 1;
    let to = world
        .arm(ArmName::Assist)
        .held_at()
        .unwrap_or(line.len().saturating_sub(1))
        .min(line.len().saturating_sub(1));
    let jaws = jaws.try_normalize(1e-12)?;
    let off_line = |p: &Vector3<f64>| {
        let ahead = (p - jaw_centre_m).dot(&jaws);
        (ahead >= 0.0).then(|| (p - jaw_centre_m - jaws * ahead).norm())
    };
    // The tissue's surface: the plane through the entry point, square to the stitch frame's z.
    let up = world.tissue().world_from_tissue.rotation * Vector3::z();
    let surface = world.tissue().hole_m(world.physics(), Flap::A);
    let clear = |p: &Vector3<f64>| (p - surface).dot(&up) >= TAKE_CLEARANCE_M;
    // (nearest of the clear points, nearest of all), each with the segment it lies on
    let mut best: [Option<(f64, Vector3<f64>, usize)>; 2] = [None, None];
    for at in from..to {
        // Each segment sampled finely enough for the nearest point to within a tenth of it.
        for k in 0..10 {
            let p = line[at] + (line[at + 1] - line[at]) * (k as f64 / 10.0);
            let Some(off) = off_line(&p) else { continue };
            for (slot, counts) in best.iter_mut().zip([clear(&p), true]) {
                if counts && slot.is_none_or(|(b, _, _)| off < b) {
                    *slot = Some((off, p, at));
                }
            }
        }
    }
    let [clear_best, any_best] = best;
    let (_, point, at) = clear_best.or(any_best)?;
    // The tail's way there over a few segments either side: one segment turns with its wiggles.
    let (before, after) = (at.saturating_sub(3).max(from), (at + 4).min(to));
    let direction = (line[after] - line[before]).try_normalize(1e-12)?;
    Some((point, direction))
}

/// Where the tail lies `along` of the way (by segments) from the knot to the left's jaws, and which
/// way it runs there (towards the left), world frame; `None` if the left holds no thread or the
/// stitch holds none.
pub fn tail_between_knot_and_left(world: &SimWorld, along: f64) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let held = world.arm(ArmName::Left).held_at()?;
    let inside = world.thread_inside()?;
    let line = world.thread_centreline();
    // The tail runs from the stitch towards the tail's end: the left holds it past the stitch.
    let (from, to) = (*inside.end() + 1, held);
    if to <= from || to + 1 >= line.len() {
        return None;
    }
    let at = from + ((to - from) as f64 * along).round() as usize;
    let at = at.clamp(from, to - 1);
    let point = 0.5 * (line[at] + line[at + 1]);
    let direction = (line[at + 1] - line[at]).try_normalize(1e-12)?;
    Some((point, direction))
}

/// Where the tail lies `from_end_m` of thread from its free end, and which way it runs there (towards
/// the end), world frame; `None` if the stitch holds no thread or the tail is shorter than that.
pub fn tail_from_its_end(world: &SimWorld, from_end_m: f64) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let inside = world.thread_inside()?;
    let line = world.thread_centreline();
    let mut left_m = from_end_m;
    for at in (*inside.end() + 1..line.len() - 1).rev() {
        let step = line[at + 1] - line[at];
        let length_m = step.norm();
        if left_m <= length_m {
            let direction = step.try_normalize(1e-12)?;
            return Some((line[at + 1] - direction * left_m, direction));
        }
        left_m -= length_m;
    }
    None
}

/// The thread between the stitch's entry and the tail's point `from_end_m` from its free end, m;
/// `None` if the stitch holds no thread or the tail is shorter than that.
pub fn tail_length_to(world: &SimWorld, from_end_m: f64) -> Option<f64> {
    let inside = world.thread_inside()?;
    let line = world.thread_centreline();
    let whole_m: f64 = (*inside.end()..line.len() - 1).map(|at| (line[at + 1] - line[at]).norm()).sum();
    (whole_m > from_end_m).then_some(whole_m - from_end_m)
}

//! An instrument takes the tail at a point, its jaws along its shaft and its hinge along the tail.

use nalgebra::{Unit, Vector3};

use super::{Setting, TAKE_APPROACH_M};
use crate::expert::motion::{Path, TrackBuilder};

/// `track` takes the tail at `tail_m`, its jaws along its shaft and its hinge along the tail
/// (`tail_dir`), so the tail runs between them.
pub(crate) fn take_tail(track: &mut TrackBuilder, s: &Setting, tail_m: Vector3<f64>, tail_dir: Vector3<f64>) {
    let jaws = (tail_m - s.trocar_m(track.arm())).normalize();
    let hinge = Unit::new_normalize(tail_dir - jaws * tail_dir.dot(&jaws));
    let frame = nalgebra::Rotation3::from_basis_unchecked(&[hinge.cross(&jaws), hinge.into_inner(), jaws]);
    track.go_framing(Path::To(tail_m - jaws * TAKE_APPROACH_M), s.d(1.5), frame);
    track.go(Path::To(tail_m), s.d(0.8));
    track.wait_until(track.time_s() + s.pause(3));
    track.jaw(0.0, s.d(0.3));
    track.wait_until(track.time_s() + s.d(0.3) + 0.1);
}

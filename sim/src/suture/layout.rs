//! Where the thread lies at the start of the knot-tying task: from the needle in the right jaws down to
//! the pad, along the pad to the exit point, down through the stitch under the wound and up to the
//! entry point, and up to the assist's jaws holding the tail. The point where the long end meets the
//! pad is placed so that the path is exactly as long as the thread.

use nalgebra::{Point3, Vector3};

use crate::physics::Physics;
use crate::scene::SceneConfig;
use crate::thread::ThreadModel;
use crate::tissue::{Flap, Tissue};

fn length(points: &[Vector3<f64>]) -> f64 {
    points.windows(2).map(|w| (w[1] - w[0]).norm()).sum()
}

/// The start path, needle end first, world frame, m.
pub fn start_layout(config: &SceneConfig, tissue: &Tissue, physics: &Physics) -> Vec<Vector3<f64>> {
    let frame = tissue.world_from_tissue;
    let to_world = |p: Vector3<f64>| (frame * Point3::from(p)).coords;
    let needle = to_world(Vector3::from(config.start.needle_m));
    let tail = to_world(Vector3::from(config.start.tail_m));
    let exit = tissue.hole_m(physics, Flap::B);
    let entry = tissue.hole_m(physics, Flap::A);
    let (deep_exit, deep_entry) = (tissue.deep_m(physics, Flap::B), tissue.deep_m(physics, Flap::A));
    // On the pad, outward from the exit point (towards -y), lifted by the thread's radius.
    let pad_z = -config.tissue.flap_size_m[2] + config.thread.radius_m;
    let on_pad = |reach: f64| {
        let y = match config.thread.model {
            // Outward from flap B's outer face.
            ThreadModel::Rope => -(0.5 * config.tissue.rest_gap_m + config.tissue.flap_size_m[1]) - reach,
            ThreadModel::Chain => -config.stitch.bite_m - reach,
        };
        to_world(Vector3::new(config.start.needle_m[0], y, pad_z))
    };
    // The rope (`thread.model = "rope"`) cannot start inside a flap, as the chain may (Rapier's
    // contacts push it out over a few steps): from the pad it rises past flap B's outer face and runs
    // over its top to the exit point.
    let r = config.thread.radius_m;
    let outer_y = -(0.5 * config.tissue.rest_gap_m + config.tissue.flap_size_m[1]) - r;
    let over_flap = match config.thread.model {
        ThreadModel::Chain => vec![],
        ThreadModel::Rope => {
            let at = |y: f64, z: f64| to_world(Vector3::new(config.start.needle_m[0], y, z));
            // Down into the exit point from over it.
            let exit_t = frame.inverse_transform_point(&Point3::from(exit)).coords;
            let over_exit = to_world(exit_t + Vector3::new(0.0, -r, 2.0 * r));
            vec![at(outer_y, pad_z), at(outer_y, r), over_exit]
        }
    };
    // The rope, inextensible, is laid with slack where it hangs free (a loop lifted at the middle of
    // each free span): laid taut between two held ends, the first push across it would pull them
    // with many times its force.
    let slack = |a: Vector3<f64>, b: Vector3<f64>| match config.thread.model {
        ThreadModel::Chain => vec![],
        ThreadModel::Rope => vec![0.5 * (a + b) + frame.rotation * Vector3::z() * (0.15 * (b - a).norm())],
    };
    let path = |reach: f64| {
        let mut path = vec![needle];
        path.extend(slack(needle, on_pad(reach)));
        path.push(on_pad(reach));
        path.extend(over_flap.iter().copied());
        path.extend([exit, deep_exit, deep_entry, entry]);
        path.extend(slack(entry, tail));
        path.push(tail);
        path
    };
    let total = config.thread.length_m;
    if length(&path(0.0)) >= total {
        return vec![needle, exit, deep_exit, deep_entry, entry, tail];
    }
    // The path's length grows with the reach on the pad: bisect for the thread's length.
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if length(&path(mid)) < total {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    path(0.5 * (lo + hi))
}
